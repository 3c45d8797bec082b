//! The bus as a driver sees it (spec 4, 5 address fields, 5.1 status, 5.24 swap, 5.42-5.45
//! init registers, 6.16 initEnable): chip and wrap fields, the triangle-register remap,
//! init write protection, reserved offsets and buffer swapping.

use firmware_tests::bits::fbz;
use firmware_tests::{
    fastfill, init_640x480, triangle_fixed, wait_idle, Buffer, Emulator, Port, Triangle,
    IDLE_READS, PCI_INIT_ENABLE,
};
use sst1_board::BufferKind;
use sst1_regs::addr;

const BASE: u32 = fbz::CLIP | fbz::RGB_WRITE | fbz::AUX_WRITE | fbz::DRAW_BACK;

/// Writes to `fbiInit0-3` are ignored while PCI `initEnable` bit 0 is clear, and take
/// effect once it is set.
///
/// Source: spec 6.16 and 5.42-5.45. A real board should read back the old `fbiInit3`
/// (0x77de4000) after the blocked write and the new value after the enabled one.
#[test]
fn init_registers_need_init_enable() {
    let mut p = Emulator::booted();
    assert_eq!(p.read(addr::FBI_INIT3), 0x77de_4000);
    p.pci_write(PCI_INIT_ENABLE, 0x2);
    p.write(addr::FBI_INIT3, 0x77de_4001);
    p.write(addr::FBI_INIT1, 0);
    assert_eq!(p.read(addr::FBI_INIT3), 0x77de_4000);
    assert_eq!(p.read(addr::FBI_INIT1), 0x0020_00a2);
    p.pci_write(PCI_INIT_ENABLE, 0x3);
    p.write(addr::FBI_INIT3, 0x77de_4001);
    assert_eq!(p.read(addr::FBI_INIT3), 0x77de_4001);
}

/// The triangle-register remap: with `fbiInit3` bit 0 set, addresses with bit 21 use the
/// alternate map, where 0x02c is `startG` (normally `startZ`) and 0x024 is `dRdX`;
/// addresses without bit 21 keep the normal map.
///
/// Source: spec 5 (alternate register table) and 5.45 bit 0. A real board should draw
/// green 0x40 (remapped) and then green 0x80 with depth 0x1234 (normal map).
#[test]
fn triangle_register_remap() {
    let mut p = Emulator::booted();
    p.write(addr::FBI_INIT3, 0x77de_4001);
    p.write(addr::FBZ_MODE, BASE | fbz::DEPTH | fbz::depth_function(7));
    let mut t = Triangle::corner(0xff00_0000);
    t.z = firmware_tests::Param::flat(0x1234 << 12);
    triangle_fixed(&mut p, &t); // normal map: green 0, depth 0x1234
    const REMAP: u32 = 1 << 21;
    p.write(REMAP | 0x02c, 0x40 << 12); // alternate map: startG
    p.write(REMAP | 0x030, 0); // dGdX
    p.write(REMAP | 0x034, 0); // dGdY
    p.write(REMAP | addr::TRIANGLE_CMD, 0);
    assert_eq!(p.read_pixel(Buffer::Back, 4, 4), 0x40 >> 2 << 5);
    assert_eq!(p.read_aux(4, 4), 0x1234, "startZ was not touched");
    // Without bit 21 the normal map applies even with the remap enabled.
    p.write(addr::START_G, 0x80 << 12);
    p.write(addr::START_Z, 0x0777 << 12);
    p.write(addr::TRIANGLE_CMD, 0);
    assert_eq!(
        (p.read_pixel(Buffer::Back, 4, 4), p.read_aux(4, 4)),
        (0x80 >> 2 << 5, 0x0777)
    );
    // With the remap disabled, bit 21 is only part of the wrap field: 0x02c is startZ.
    p.write(addr::FBI_INIT3, 0x77de_4000);
    p.write(REMAP | 0x02c, 0x0555 << 12);
    p.write(addr::TRIANGLE_CMD, 0);
    assert_eq!(p.read_aux(4, 4), 0x0555);
}

/// The wrap field (address bits 21:14) aliases the register map: a write through wrap
/// 0x2a is the same register as wrap 0.
///
/// Source: spec 5 ("SST-1 functionality is identical regardless of which wrap is
/// accessed"). A real board should read 0x00c0ffee back.
#[test]
fn wrap_field_aliases_registers() {
    let mut p = Emulator::booted();
    p.write(0x2a << 14 | addr::COLOR0, 0x00c0_ffee);
    assert_eq!(p.read(addr::COLOR0), 0x00c0_ffee);
    assert_eq!(p.read(0x13 << 14 | addr::COLOR0), 0x00c0_ffee);
}

/// The chip field (address bits 13:10) selects the chips a write reaches: a write with
/// chip field 0b0010 (TREX 0 only) does not reach the FBI's `color0`; 0b0001 and 0b0000
/// do. Reads ignore the chip field.
///
/// Source: spec 5 (chip field table; "for reads, the chip field is ignored, and read
/// data is always read from FBI"). A real board should read 0x11, 0x11, 0x22, 0x33.
#[test]
fn chip_field_selects_writes_not_reads() {
    let mut p = Emulator::booted();
    p.write(addr::COLOR0, 0x11);
    p.write(0b0010 << 10 | addr::COLOR0, 0x99);
    assert_eq!(p.read(addr::COLOR0), 0x11);
    assert_eq!(p.read(0b0100 << 10 | addr::COLOR0), 0x11);
    p.write(0b0001 << 10 | addr::COLOR0, 0x22);
    assert_eq!(p.read(addr::COLOR0), 0x22);
    p.write(0b1111 << 10 | addr::COLOR0, 0x33);
    assert_eq!(p.read(0b0010 << 10 | addr::COLOR0), 0x33);
}

/// Writes to reserved offsets (0x004, 0x084, 0x1e0-0x1fc, 0x234-0x2fc, 0x384-0x3fc) and
/// reads from them change nothing a driver can see: registers keep their values and a
/// FASTFILL still fills.
///
/// Source: spec 5 register table (no register at these offsets). A real board should
/// read back `color0` 0x0055aa55 and the filled colour 0x4208.
#[test]
fn reserved_offsets_are_harmless() {
    let mut p = Emulator::booted();
    p.write(addr::COLOR0, 0x0055_aa55);
    let reserved = [0x004u32, 0x084]
        .into_iter()
        .chain((0x1e0..0x200).step_by(4))
        .chain((0x234..0x300).step_by(4))
        .chain((0x384..0x400).step_by(4));
    for a in reserved {
        p.write(a, 0xffff_ffff);
        let _ = p.read(a);
    }
    assert_eq!(p.read(addr::COLOR0), 0x0055_aa55);
    assert_eq!(p.read(addr::FBZ_MODE), BASE | fbz::CLIP);
    fastfill(&mut p, 0x0040_4040, 0);
    assert_eq!(p.read_pixel(Buffer::Back, 320, 240), 0x4208);
}

/// After commands the status register reports idle (bits 9:7 clear) with an empty PCI
/// FIFO (bits 5:0 = 0x3f), and the idle wait of spec 9.3 succeeds.
///
/// Source: spec 5.1 and 9.3. The board reports busy while the triangle is drawn and
/// idle once the engine is done (`status_reads_busy_while_drawing`).
#[test]
fn status_reports_idle_after_commands() {
    let mut p = Emulator::booted();
    triangle_fixed(&mut p, &Triangle::corner(0xffff_ffff));
    assert!(wait_idle(&mut p, IDLE_READS));
    let s = p.read(addr::STATUS);
    assert_eq!(s & 0x3f, 0x3f);
    assert_eq!(s & 0x380, 0);
    assert_eq!(s >> 28 & 7, 0, "no swaps pending");
}

/// The status register follows the timing model: busy (bits 9 and 7) right after a
/// full-screen FASTFILL, with the writes issued behind it waiting in the PCI FIFO, and
/// idle after as many reads as the fill takes; the same on every run.
///
/// Source: spec 5.1 (busy bits, FIFO free space), spec 2 (3.45 ms for the clear).
#[test]
fn status_reads_busy_while_drawing() {
    let run = || {
        let mut p = Emulator::booted();
        assert!(wait_idle(&mut p, IDLE_READS));
        fastfill(&mut p, 0x00ff_0000, 0);
        let busy = p.read(addr::STATUS);
        for _ in 0..10 {
            p.write(addr::COLOR0, 0);
        }
        let queued = p.read(addr::STATUS) & 0x3f;
        let mut reads = 0;
        while p.read(addr::STATUS) & 0x200 != 0 {
            reads += 1;
        }
        (busy & 0x3bf, queued, reads)
    };
    let (busy, queued, reads) = run();
    assert_eq!(busy & 0x280, 0x280, "{busy:#x}");
    assert_eq!(queued, 0x3f - 9, "ten writes wait behind the fill");
    // 3.45 ms of fill at 4.5 clocks a read, less the writes and reads already made.
    assert!((38_000..38_400).contains(&reads), "{reads}");
    assert_eq!(run(), (busy, queued, reads));
}

/// SWAPBUFFER exchanges front and back: what was drawn into the back buffer becomes the
/// front buffer, and `status` bits 11:10 name the displayed buffer (0, then 1).
///
/// Source: spec 5.24 and 5.1. A real board should show the drawn colour in the front
/// buffer and displayed buffer 1 after the swap.
#[test]
fn swap_buffers_exchanges_front_and_back() {
    let mut p = Emulator::booted();
    assert_eq!(p.read(addr::STATUS) >> 10 & 3, 0);
    fastfill(&mut p, 0x00ff_0000, 0);
    assert_eq!(p.read_pixel(Buffer::Front, 5, 5), 0);
    p.write(addr::SWAPBUFFER_CMD, 0);
    assert!(wait_idle(&mut p, IDLE_READS));
    assert_eq!(p.read(addr::STATUS) >> 10 & 3, 1);
    assert_eq!(p.read_pixel(Buffer::Front, 5, 5), 0xf800);
    assert_eq!(p.read_pixel(Buffer::Back, 5, 5), 0);
}

/// Drawing into the front buffer (`fbzMode` bits 15:14 = 0) leaves the back buffer.
///
/// Source: spec 5.19 bits 15:14. A real board should show the fill in the front buffer.
#[test]
fn draw_buffer_front() {
    let mut p = Emulator::booted();
    p.write(addr::FBZ_MODE, BASE & !fbz::DRAW_BACK);
    fastfill(&mut p, 0x0000_00ff, 0);
    assert_eq!(p.read_pixel(Buffer::Front, 7, 7), 0x001f);
    assert_eq!(p.read_pixel(Buffer::Back, 7, 7), 0x1086);
}

/// Emulator self-check of the port layer: pixels read through the LFB equal the
/// emulator's buffer dump, for the back buffer and the aux buffer.
///
/// Source: spec 5.20.2 (LFB reads return the buffer's 16-bit values). Not a hardware
/// program (it inspects the emulator directly).
#[test]
fn lfb_reads_match_buffer_dump() {
    let mut p = Emulator::new();
    init_640x480(&mut p);
    p.write(
        addr::FBZ_MODE,
        BASE | fbz::DEPTH | fbz::depth_function(7) | fbz::DITHER,
    );
    let mut t = Triangle::flat([(3, 2), (60, 9), (20, 50)], 0xff12_3456);
    t.rgba[0].dx = 0x3000;
    t.z.dy = 0x40 << 12;
    triangle_fixed(&mut p, &t);
    let back = p.board().dump_buffer(BufferKind::Back);
    let aux = p.board().dump_buffer(BufferKind::Aux);
    for y in 0..60u32 {
        for x in 0..64u32 {
            let i = (y * 640 + x) as usize;
            assert_eq!(
                p.read_pixel(Buffer::Back, x, y),
                back[i],
                "colour ({x}, {y})"
            );
            assert_eq!(p.read_aux(x, y), aux[i], "aux ({x}, {y})");
        }
    }
}

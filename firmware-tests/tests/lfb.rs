//! Linear frame buffer writes and reads (spec 5.20, 5.20.1, 5.20.2, 7): every write
//! format and RGBA lane order, word swap, byte swizzle and the LFB Y origin, all read
//! back through LFB reads.
//!
//! Colour written through an LFB format reaches the 565 buffer by widening each field to
//! 8 bits and truncating again (dithering is off), so 5- and 6-bit fields come back
//! unchanged and a 5-bit green comes back as `g5 << 1 | g5 >> 4` (MAME and DOSBox Staging
//! widen by replicating the high bits).

use firmware_tests::bits::{fbz, lfb};
use firmware_tests::{fastfill, lfb16, lfb32, rgb565_truncated, set_clip, Buffer, Emulator, Port};
use sst1_regs::addr;

const BASE: u32 = fbz::CLIP | fbz::RGB_WRITE | fbz::AUX_WRITE | fbz::DRAW_BACK;

/// A board with a black back buffer, an aux buffer of 0x5555 and `lfbMode` = `mode`
/// writing to the back buffer.
fn board(mode: u32) -> Emulator {
    let mut p = Emulator::booted();
    fastfill(&mut p, 0, 0x5555);
    p.write(addr::LFB_MODE, mode | lfb::WRITE_BACK);
    p
}

fn back(p: &mut Emulator, x: u32, y: u32) -> u16 {
    p.read_pixel(Buffer::Back, x, y)
}

/// RGB565 from 5-bit red, 5-bit green (widened to 6 bits by replication), 5-bit blue.
fn from555(r: u32, g: u32, b: u32) -> u16 {
    (r << 11 | (g << 1 | g >> 4) << 5 | b) as u16
}

/// Fields (red, green, blue) of a 555 half-word in lane order `lane` (spec 5.20.1
/// format 1 table): lanes 0/1 use bits 14:10, 9:5, 4:0; lanes 2/3 use 15:11, 10:6, 5:1;
/// lanes 1/3 hold blue in the high field.
fn fields555(lane: u32, h: u32) -> (u32, u32, u32) {
    let h = if lane >= 2 { h >> 1 } else { h };
    let (hi, mid, lo) = ((h >> 10) & 0x1f, (h >> 5) & 0x1f, h & 0x1f);
    if lane & 1 == 0 {
        (hi, mid, lo)
    } else {
        (lo, mid, hi)
    }
}

/// Format 0 (RGB 565), two pixels per write, in all four lane orders: lanes 0 and 2
/// store the half-words as they are, lanes 1 and 3 exchange the red and blue fields.
///
/// Source: spec 5.20.1 format 0 table; MAME and DOSBox Staging agree. A real board
/// should read back the values below.
#[test]
fn format0_rgb565_lanes() {
    let (h0, h1) = (0xae6e_u32, 0x1234_u32);
    let swap_rb = |h: u32| ((h & 0x1f) << 11 | (h & 0x7e0) | h >> 11) as u16;
    for lane in 0..4 {
        let mut p = board(lfb::format(0) | lfb::lanes(lane));
        p.write(lfb16(10, 3), h1 << 16 | h0);
        let want = if lane & 1 == 0 {
            (h0 as u16, h1 as u16)
        } else {
            (swap_rb(h0), swap_rb(h1))
        };
        assert_eq!(
            (back(&mut p, 10, 3), back(&mut p, 11, 3)),
            want,
            "lane {lane}"
        );
        assert_eq!(
            p.read_aux(10, 3),
            0x5555,
            "format 0 leaves the aux buffer alone"
        );
    }
}

/// Format 1 (RGB x-5-5-5) in all four lane orders (bit 15 or bit 0 ignored).
///
/// Source: spec 5.20.1 format 1 table; widening as in the module docs. A real board
/// should read back the values below.
#[test]
fn format1_rgb555_lanes() {
    let (h0, h1) = (0xd6b5_u32, 0x2c63_u32);
    for lane in 0..4 {
        let mut p = board(lfb::format(1) | lfb::lanes(lane));
        p.write(lfb16(20, 5), h1 << 16 | h0);
        for (x, h) in [(20, h0), (21, h1)] {
            let (r, g, b) = fields555(lane, h);
            assert_eq!(
                back(&mut p, x, 5),
                from555(r, g, b),
                "lane {lane} pixel {x}"
            );
        }
    }
}

/// Format 2 (ARGB 1-5-5-5): the colour fields as in format 1; without alpha planes the
/// alpha bit goes nowhere.
///
/// Source: spec 5.20.1 format 2 table. A real board should read back the colours and
/// leave the aux buffer at 0x5555.
#[test]
fn format2_argb1555_lanes() {
    let (h0, h1) = (0xd6b5_u32, 0x2c62_u32);
    for lane in 0..4 {
        let mut p = board(lfb::format(2) | lfb::lanes(lane));
        p.write(lfb16(20, 5), h1 << 16 | h0);
        for (x, h) in [(20, h0), (21, h1)] {
            let (r, g, b) = fields555(lane, h);
            assert_eq!(
                back(&mut p, x, 5),
                from555(r, g, b),
                "lane {lane} pixel {x}"
            );
        }
        assert_eq!(p.read_aux(20, 5), 0x5555);
    }
}

/// Format 4 (RGB x-8-8-8), one pixel per 32-bit write at 4096 bytes per row, in all four
/// lane orders; the colour is truncated to 565.
///
/// Source: spec 5.20.1 format 4 table and 7.1 (4096 bytes per scan line). A real board
/// should read (0x9a, 0x5c, 0x3e) truncated, 0x9ae7, in every lane order.
#[test]
fn format4_rgb888_lanes() {
    let (r, g, b) = (0x9a, 0x5c, 0x3e);
    let words = [
        r << 16 | g << 8 | b,
        b << 16 | g << 8 | r,
        r << 24 | g << 16 | b << 8,
        b << 24 | g << 16 | r << 8,
    ];
    for (lane, &w) in words.iter().enumerate() {
        let mut p = board(lfb::format(4) | lfb::lanes(lane as u32));
        p.write(lfb32(33, 7), w | if lane < 2 { 0xff00_0000 } else { 0xff });
        assert_eq!(
            back(&mut p, 33, 7),
            rgb565_truncated(r, g, b),
            "lane {lane}"
        );
        assert_eq!(back(&mut p, 34, 7), 0, "one pixel per write");
    }
    assert_eq!(rgb565_truncated(r, g, b), 0x9ae7);
}

/// Format 5 (ARGB 8-8-8-8) in all four lane orders; with alpha planes enabled the alpha
/// byte goes to the aux buffer.
///
/// Source: spec 5.20.1 format 5 table and 5.20 ("the alpha component is written into
/// the alpha buffer" when it is enabled). A real board should read 0x9ae7 and alpha 0x6d.
#[test]
fn format5_argb8888_lanes_and_alpha_planes() {
    let (a, r, g, b) = (0x6d, 0x9a, 0x5c, 0x3e);
    let words = [
        a << 24 | r << 16 | g << 8 | b,
        a << 24 | b << 16 | g << 8 | r,
        r << 24 | g << 16 | b << 8 | a,
        b << 24 | g << 16 | r << 8 | a,
    ];
    for (lane, &w) in words.iter().enumerate() {
        let mut p = board(lfb::format(5) | lfb::lanes(lane as u32));
        p.write(addr::FBZ_MODE, BASE | fbz::ALPHA_PLANES);
        p.write(lfb32(40, 9), w);
        assert_eq!(back(&mut p, 40, 9), 0x9ae7, "lane {lane}");
        assert_eq!(p.read_aux(40, 9), a as u16, "lane {lane}");
    }
}

/// Formats 12, 13 and 14 carry a 16-bit depth in bits 31:16 and a 16-bit colour in bits
/// 15:0; with the pipeline bypassed both buffers are written.
///
/// Source: spec 5.20 (formats 12-14 update colour and depth "irrespective of the color
/// and Z mask bits") and the bit-11 table (Z in 31:16 without word swap). A real board
/// should read the colours below and depth 0xbeef.
#[test]
fn formats12_to_14_colour_and_depth() {
    let colour = 0xae6e_u32;
    let (r, g, b) = fields555(0, colour);
    for (format, want) in [
        (12, colour as u16),
        (13, from555(r, g, b)),
        (14, from555(r, g, b)),
    ] {
        let mut p = board(lfb::format(format));
        p.write(addr::FBZ_MODE, BASE & !fbz::AUX_WRITE & !fbz::RGB_WRITE);
        p.write(lfb32(50, 11), 0xbeef << 16 | colour);
        assert_eq!(back(&mut p, 50, 11), want, "format {format}");
        assert_eq!(p.read_aux(50, 11), 0xbeef, "format {format}");
    }
}

/// Format 14 with alpha planes enabled writes the replicated 1-bit alpha (0xff) into
/// the aux buffer and ignores the depth.
///
/// Source: spec 5.20 ("If the alpha buffer is enabled and LFB write format 14 is used
/// with bit(8)=0, then the depth component is ignored"; 5.20.1: the 1-bit alpha is
/// bit-replicated). A real board should read 0x00ff.
#[test]
fn format14_alpha_planes_take_alpha() {
    let mut p = board(lfb::format(14));
    p.write(addr::FBZ_MODE, BASE | fbz::ALPHA_PLANES);
    p.write(lfb32(50, 11), 0xbeef << 16 | 0x8000 | 0x1234);
    assert_eq!(p.read_aux(50, 11), 0x00ff);
}

/// Format 15 writes two 16-bit depths (left pixel in bits 15:0) and no colour.
///
/// Source: spec 5.20 ("If LFB mode 15 is used and bit(8)=0, then only the depth buffer
/// is updated") and the format-15 packing table. A real board should read 0x1111 and
/// 0x2222 from the aux buffer and black from the colour buffer.
#[test]
fn format15_two_depths() {
    let mut p = board(lfb::format(15));
    p.write(lfb16(60, 12), 0x2222_1111);
    assert_eq!((p.read_aux(60, 12), p.read_aux(61, 12)), (0x1111, 0x2222));
    assert_eq!((back(&mut p, 60, 12), back(&mut p, 61, 12)), (0, 0));
}

/// Word swap of writes (bit 11): for 16-bit formats the left pixel moves to bits 31:16.
///
/// Source: spec 5.20 bit-11 table. A real board should read 0x1234 left, 0xae6e right.
#[test]
fn word_swap_writes_exchange_pixels() {
    let mut p = board(lfb::format(0) | lfb::WORD_SWAP_WRITES);
    p.write(lfb16(70, 13), 0x1234_ae6e);
    assert_eq!(
        (back(&mut p, 70, 13), back(&mut p, 71, 13)),
        (0x1234, 0xae6e)
    );
}

/// Byte swizzle of writes (bit 12) happens before the word swap: 0x11223344 swizzled is
/// 0x44332211, then word-swapped 0x22114433: left pixel 0x4433, right 0x2211.
///
/// Source: spec 5.20 bit 12 and the "Very Important Note" on the order. A real board
/// should read 0x4433 and 0x2211.
#[test]
fn byte_swizzle_then_word_swap_on_writes() {
    let mut p = board(lfb::format(0) | lfb::BYTE_SWIZZLE_WRITES);
    p.write(lfb16(72, 13), 0x1122_3344);
    assert_eq!(
        (back(&mut p, 72, 13), back(&mut p, 73, 13)),
        (0x2211, 0x4433)
    );
    let mut p = board(lfb::format(0) | lfb::BYTE_SWIZZLE_WRITES | lfb::WORD_SWAP_WRITES);
    p.write(lfb16(72, 13), 0x1122_3344);
    assert_eq!(
        (back(&mut p, 72, 13), back(&mut p, 73, 13)),
        (0x4433, 0x2211)
    );
}

/// Reads return two pixels, left in bits 15:0; bit 15 swaps the words and bit 16 then
/// swizzles the bytes.
///
/// Source: spec 5.20.2 (table and "byte swizzling ... is performed after 16-bit word
/// swapping"). A real board should return the four words below.
#[test]
fn read_word_swap_and_byte_swizzle() {
    let mut p = board(lfb::format(0));
    p.write(lfb16(80, 14), 0x1234_ae6e);
    let sel = Buffer::Back.read_select();
    for (mode, want) in [
        (0, 0x1234_ae6e_u32),
        (lfb::WORD_SWAP_READS, 0xae6e_1234),
        (lfb::BYTE_SWIZZLE_READS, 0x6eae_3412),
        (lfb::WORD_SWAP_READS | lfb::BYTE_SWIZZLE_READS, 0x3412_6eae),
    ] {
        p.write(addr::LFB_MODE, sel | mode);
        assert_eq!(p.read(lfb16(80, 14)), want, "lfbMode {mode:#x}");
    }
}

/// The LFB Y origin (bit 13) puts y = 0 on screen row `fbiInit3[31:22]` (479) for raw
/// writes and for reads; `fbzMode` bit 17 does not affect raw writes.
///
/// Source: spec 5.20 bit 13 and 5.19 bit 17 ("bit(17) of fbzMode does not affect linear
/// frame buffer writes when the pixel pipeline is bypassed"). A real board should show
/// the pixel on row 479 and read it back at y = 0 with the origin bit set.
#[test]
fn lfb_y_origin() {
    let mut p = board(lfb::format(0) | lfb::Y_ORIGIN);
    p.write(addr::FBZ_MODE, BASE | fbz::Y_ORIGIN);
    p.write(lfb16(90, 0), 0x0000_f00f);
    assert_eq!(back(&mut p, 90, 479), 0xf00f);
    assert_eq!(back(&mut p, 90, 0), 0);
    p.write(addr::LFB_MODE, Buffer::Back.read_select() | lfb::Y_ORIGIN);
    assert_eq!(p.read(lfb16(90, 0)) & 0xffff, 0xf00f);
}

/// Writes through the pixel pipeline (bit 8) take depth and alpha from `zaColor` for
/// format 0 and are clipped: with the clip rectangle at columns 100..101, the left pixel
/// is drawn (and its depth 0x1234 written), the right one is not.
///
/// Source: spec 5.20 ("If lfbMode bit(8)=1 and a LFB write access format does not
/// include depth or alpha information ... taken from the zaColor register"; "subject to
/// ... clipping"). A real board should read 0xae6e / 0x1234 at x = 100 and nothing at 101.
#[test]
fn pipelined_write_uses_za_colour_and_clip() {
    let mut p = board(lfb::format(0) | lfb::PIPELINE);
    p.write(addr::FBZ_MODE, BASE | fbz::DEPTH | fbz::depth_function(7));
    set_clip(&mut p, 100, 101, 0, 480);
    p.write(addr::ZA_COLOR, 0x8000_1234);
    p.write(lfb16(100, 15), 0x1234_ae6e);
    assert_eq!(
        (back(&mut p, 100, 15), p.read_aux(100, 15)),
        (0xae6e, 0x1234)
    );
    assert_eq!((back(&mut p, 101, 15), p.read_aux(101, 15)), (0, 0x5555));
}

/// Word swap is never applied to formats 4 and 5: with bit 11 set a format-5 write of
/// 0xff9a5c3e still stores (0x9a, 0x5c, 0x3e).
///
/// Source: spec 5.20 ("Note that 16-bit word swapping is never performed on LFB data
/// when data formats 4 and 5 are used"; also "bit(11) of lfbMode is ignored for linear
/// frame buffer writes using formats 4 or 5"). MAME swaps regardless (`lfb_w`). A real
/// board should read 0x9ae7.
#[test]
fn word_swap_ignored_for_32_bit_colour_formats() {
    let mut p = board(lfb::format(5) | lfb::WORD_SWAP_WRITES);
    p.write(lfb32(40, 9), 0xff9a_5c3e);
    assert_eq!(back(&mut p, 40, 9), 0x9ae7);
}

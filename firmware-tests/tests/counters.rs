//! The statistics counters `fbiPixelsIn`, `fbiChromaFail`, `fbiZfuncFail`,
//! `fbiAfuncFail`, `fbiPixelsOut` (spec 5.31-5.35) read through the bus, and their reset
//! by `nopCMD` bit 0 (spec 5.22).
//!
//! The known triangle (0,0) (8,0) (0,8) covers 7 + 6 + ... + 1 = 28 pixels (centres
//! strictly inside; see `raster.rs` for the fill rule).

use firmware_tests::bits::{alpha, fbz, lfb};
use firmware_tests::{
    fastfill, lfb16, triangle_fixed, wait_idle, Emulator, Port, Triangle, IDLE_READS,
};
use sst1_regs::addr;

const BASE: u32 = fbz::CLIP | fbz::RGB_WRITE | fbz::AUX_WRITE | fbz::DRAW_BACK;
const PIXELS: u32 = 28;

/// The five counters in register order, read after the idle wait of spec 9.3.
fn counters(p: &mut Emulator) -> [u32; 5] {
    assert!(wait_idle(p, IDLE_READS));
    [
        addr::FBI_PIXELS_IN,
        addr::FBI_CHROMA_FAIL,
        addr::FBI_ZFUNC_FAIL,
        addr::FBI_AFUNC_FAIL,
        addr::FBI_PIXELS_OUT,
    ]
    .map(|a| p.read(a))
}

/// A booted board with cleared counters and `fbzMode` = `mode`.
fn board(mode: u32) -> Emulator {
    let mut p = Emulator::booted();
    p.write(addr::FBZ_MODE, mode);
    p.write(addr::NOP_CMD, 1);
    p
}

fn known_triangle(p: &mut Emulator, argb: u32) {
    triangle_fixed(p, &Triangle::flat([(0, 0), (8, 0), (0, 8)], argb));
}

/// Every pixel of an unobstructed triangle is counted in and out.
///
/// Source: spec 5.31 and 5.35. A real board should read 28, 0, 0, 0, 28.
#[test]
fn plain_triangle_counts_in_and_out() {
    let mut p = board(BASE);
    known_triangle(&mut p, 0xffff_ffff);
    assert_eq!(counters(&mut p), [PIXELS, 0, 0, 0, PIXELS]);
}

/// A colour equal to `chromaKey` fails every pixel on the chroma test.
///
/// Source: spec 5.27 and 5.32 (alpha ignored in the match). A real board should read
/// 28, 28, 0, 0, 0.
#[test]
fn chroma_key_failures() {
    let mut p = board(BASE | fbz::CHROMAKEY);
    p.write(addr::CHROMA_KEY, 0x0012_3456);
    known_triangle(&mut p, 0x7712_3456);
    assert_eq!(counters(&mut p), [PIXELS, PIXELS, 0, 0, 0]);
}

/// A depth test that fails everywhere ("never") counts Z failures.
///
/// Source: spec 5.33. A real board should read 28, 0, 28, 0, 0.
#[test]
fn depth_failures() {
    let mut p = board(BASE | fbz::DEPTH | fbz::depth_function(0));
    known_triangle(&mut p, 0xffff_ffff);
    assert_eq!(counters(&mut p), [PIXELS, 0, PIXELS, 0, 0]);
}

/// The alpha test and the alpha mask both count into `fbiAfuncFail`.
///
/// Source: spec 5.34 ("also incremented ... as a result of the alpha masking test").
/// A real board should read 28 alpha failures for each, 56 after both triangles.
#[test]
fn alpha_test_and_alpha_mask_failures() {
    let mut p = board(BASE);
    p.write(addr::ALPHA_MODE, alpha::test(1) | alpha::reference(0x10)); // alpha < 0x10
    known_triangle(&mut p, 0x80ff_ffff);
    assert_eq!(counters(&mut p), [PIXELS, 0, 0, PIXELS, 0]);
    p.write(addr::ALPHA_MODE, 0);
    p.write(addr::FBZ_MODE, BASE | fbz::ALPHA_MASK);
    known_triangle(&mut p, 0x80ff_ffff); // alpha bit 0 clear
    assert_eq!(counters(&mut p), [2 * PIXELS, 0, 0, 2 * PIXELS, 0]);
}

/// `fbiPixelsOut` ignores the RGB write mask.
///
/// Source: spec 5.35 ("the RGB mask (fbzMode bit(9)) is ignored"). A real board should
/// read 28 out with nothing written.
#[test]
fn pixels_out_ignores_rgb_mask() {
    let mut p = board(BASE & !fbz::RGB_WRITE);
    known_triangle(&mut p, 0xffff_ffff);
    assert_eq!(counters(&mut p)[4], PIXELS);
    assert_eq!(p.read_pixel(firmware_tests::Buffer::Back, 1, 1), 0x1086);
}

/// `nopCMD` with bit 0 set clears all five counters; with bit 0 clear it leaves them.
///
/// Source: spec 5.22. A real board should read the counts, the same counts, then zeros.
#[test]
fn nop_bit0_resets_counters() {
    let mut p = board(BASE | fbz::CHROMAKEY);
    p.write(addr::CHROMA_KEY, 0x00ff_ffff);
    known_triangle(&mut p, 0xffff_ffff);
    known_triangle(&mut p, 0xff00_0000);
    let c = counters(&mut p);
    assert_eq!(c, [2 * PIXELS, PIXELS, 0, 0, PIXELS]);
    p.write(addr::NOP_CMD, 0);
    assert_eq!(counters(&mut p), c);
    p.write(addr::NOP_CMD, 1);
    assert_eq!(counters(&mut p), [0; 5]);
}

/// FASTFILL and LFB writes count in `fbiPixelsOut` but not in `fbiPixelsIn`, which
/// counts only the triangle walker's pixels.
///
/// Source: spec 5.35 ("rendering operations include triangle commands, linear frame
/// buffer writes, and the FASTFILL command") and 5.31. A real board should read 0 in
/// and 6 * 5 + 2 out.
#[test]
fn fastfill_and_lfb_count_out_only() {
    let mut p = board(BASE);
    firmware_tests::set_clip(&mut p, 10, 16, 20, 25);
    fastfill(&mut p, 0x0040_4040, 0);
    p.write(addr::LFB_MODE, lfb::format(0) | lfb::WRITE_BACK);
    p.write(lfb16(0, 0), 0xffff_ffff);
    assert_eq!(counters(&mut p), [0, 0, 0, 0, 6 * 5 + 2]);
}

/// The counters are 24 bits wide: 55 full-screen FASTFILLs (55 * 307200 = 16 896 000
/// pixels) read back modulo 2^24 = 118 784.
///
/// Source: spec 5.35 (bits 23:0). A real board should read 118 784.
#[test]
fn counters_wrap_at_24_bits() {
    let mut p = board(BASE);
    for _ in 0..55 {
        p.write(addr::FASTFILL_CMD, 0);
    }
    assert_eq!(counters(&mut p)[4], 55 * 640 * 480 - (1 << 24));
}

/// The counters are read-only: a write to `fbiPixelsOut` does not change it.
///
/// Source: spec 5 register table (R only). A real board should still read 28.
#[test]
fn counters_ignore_writes() {
    let mut p = board(BASE);
    known_triangle(&mut p, 0xffff_ffff);
    p.write(addr::FBI_PIXELS_OUT, 0x1234);
    p.write(addr::FBI_PIXELS_IN, 0);
    assert_eq!(counters(&mut p), [PIXELS, 0, 0, 0, PIXELS]);
}

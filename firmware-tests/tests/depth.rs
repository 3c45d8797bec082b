//! Depth value, bias and test (spec 5.19 bits 3-7, 10, 16, 20; 5.19.1; 5.23; 5.26),
//! observed through LFB reads of the aux buffer.

use firmware_tests::bits::fbz;
use firmware_tests::expect::wfloat;
use firmware_tests::{fastfill, triangle_fixed, Buffer, Emulator, Param, Port, Triangle};
use sst1_regs::addr;

const BASE: u32 = fbz::CLIP | fbz::RGB_WRITE | fbz::AUX_WRITE | fbz::DRAW_BACK;
const ALWAYS: u32 = 7;

/// A board whose back buffer is black and aux buffer `aux`, with `fbzMode` = `mode`.
fn board(aux: u32, mode: u32) -> Emulator {
    let mut p = Emulator::booted();
    fastfill(&mut p, 0, aux);
    p.write(addr::FBZ_MODE, mode);
    p
}

/// Draw white with constant Z (16-bit) and W (2.30), read (4, 4): (colour, aux).
fn draw(p: &mut Emulator, z: i32, w: i32) -> (u16, u16) {
    let mut t = Triangle::corner(0xffff_ffff);
    t.z = Param::flat(z << 12);
    t.w = Param::flat(w);
    triangle_fixed(p, &t);
    (p.read_pixel(Buffer::Back, 4, 4), p.read_aux(4, 4))
}

/// FASTFILL writes `zaColor[15:0]` into the aux buffer through the aux mask, and with
/// the RGB mask clear leaves the colour buffer alone.
///
/// Source: spec 5.23 and 6.21. A real board should read 0x1234 in the aux buffer and
/// the init's 0x1086 in the colour buffer.
#[test]
fn fastfill_writes_depth_only() {
    let mut p = Emulator::booted();
    p.write(addr::FBZ_MODE, fbz::AUX_WRITE | fbz::DRAW_BACK);
    fastfill(&mut p, 0x00ff_ffff, 0x1234);
    assert_eq!(p.read_aux(100, 100), 0x1234);
    assert_eq!(p.read_pixel(Buffer::Back, 100, 100), 0x1086);
}

/// Depth bias adds the signed `zaColor[15:0]` and clamps: Z 0xfff0 + 0x0020 saturates
/// at 0xffff; Z 0x0010 + 0xffe0 (-32) stops at 0.
///
/// Source: spec 5.19 depth diagram ("sign extend 16-bit zaColor to 18 bits ... add ...
/// clamp to 0-FFFF"). A real board should read 0xffff and 0 from the aux buffer.
#[test]
fn depth_bias_clamps_at_both_ends() {
    let mode = BASE | fbz::DEPTH | fbz::depth_function(ALWAYS) | fbz::DEPTH_BIAS;
    let mut p = board(0x5555, mode);
    p.write(addr::ZA_COLOR, 0x0020);
    assert_eq!(draw(&mut p, 0xfff0, 0).1, 0xffff);
    p.write(addr::ZA_COLOR, 0xffe0);
    assert_eq!(draw(&mut p, 0x0010, 0).1, 0x0000);
    p.write(addr::ZA_COLOR, 0x0100);
    assert_eq!(draw(&mut p, 0x1000, 0).1, 0x1100);
}

/// Each depth function with the pixel's depth equal to the buffer's (0x8000): never,
/// less, greater and not-equal reject; equal, less-or-equal, greater-or-equal and
/// always accept. Rejected pixels leave colour and depth untouched.
///
/// Source: spec 5.19.1. A real board should draw for functions 2, 3, 6, 7 only.
#[test]
fn depth_functions_at_equality() {
    let mut drawn = Vec::new();
    for f in 0..8 {
        let mut p = board(0x8000, BASE | fbz::DEPTH | fbz::depth_function(f));
        let (colour, aux) = draw(&mut p, 0x8000, 0);
        assert_eq!(aux, 0x8000);
        drawn.push(colour == 0xffff);
    }
    assert_eq!(drawn, [false, false, true, true, false, false, true, true]);
}

/// Less and greater around the stored depth: with 0x8000 in the buffer, Z 0x7fff
/// passes "less" and is written; Z 0x8001 fails it and is not.
///
/// Source: spec 5.19.1. A real board should read 0x7fff, then 0x7fff again.
#[test]
fn depth_less_writes_only_nearer_pixels() {
    let mut p = board(0x8000, BASE | fbz::DEPTH | fbz::depth_function(1));
    assert_eq!(draw(&mut p, 0x7fff, 0), (0xffff, 0x7fff));
    p.write(addr::FBZ_MODE, BASE);
    fastfill(&mut p, 0, 0x8000);
    p.write(addr::FBZ_MODE, BASE | fbz::DEPTH | fbz::depth_function(1));
    assert_eq!(draw(&mut p, 0x8001, 0), (0, 0x8000));
}

/// With the aux write mask clear the depth test still runs but the buffer keeps its
/// value.
///
/// Source: spec 5.19 bit 10 ("writes to the depth-buffer are invalidated"). A real
/// board should draw the colour and keep 0x8000.
#[test]
fn depth_mask_clear_keeps_buffer() {
    let mode = (BASE & !fbz::AUX_WRITE) | fbz::DEPTH | fbz::depth_function(1);
    let mut p = board(0x8000, mode);
    assert_eq!(draw(&mut p, 0x1000, 0), (0xffff, 0x8000));
}

/// Depth source compare (`fbzMode` bit 20): the test compares `zaColor[15:0]` (0x7000,
/// passes "less" against 0x8000) while the buffer receives the iterated Z (0x9000,
/// which on its own would fail).
///
/// Source: spec 5.19 bit 20 ("Regardless of the state of fbzMode bit(20), the biased
/// iterated Z/W is written"). A real board (FBI revision > 1.0) should draw and read
/// 0x9000.
#[test]
fn depth_source_compare_uses_za_colour() {
    let mode = BASE | fbz::DEPTH | fbz::depth_function(1) | fbz::DEPTH_SOURCE_COMPARE;
    let mut p = board(0x8000, mode);
    p.write(addr::ZA_COLOR, 0x7000);
    assert_eq!(draw(&mut p, 0x9000, 0), (0xffff, 0x9000));
}

/// W-buffering (`fbzMode` bit 3) writes the 16-bit float of W: W = 0x02c00000 (2.30)
/// is 0x4a00; W = 0x00400000 (fraction 2^-8: exponent 7, mantissa 0) is 0x7fff + 1 = 0x8000.
///
/// Source: spec 5.19 (W-buffer diagram, "4-bit exponent and a 12-bit mantissa"); the
/// +1 from MAME and DOSBox Staging. A real board should read 0x4a00 and 0x8000.
#[test]
fn wbuffer_writes_float_depth() {
    let mode = BASE | fbz::DEPTH | fbz::depth_function(ALWAYS) | fbz::WBUFFER;
    let mut p = board(0, mode);
    assert_eq!(draw(&mut p, 0, 0x02c0_0000).1, 0x4a00);
    assert_eq!(wfloat(0x0040_0000 << 2), 0x8000);
    assert_eq!(draw(&mut p, 0, 0x0040_0000).1, 0x8000);
}

/// Iterated Z across a row: the buffer receives `startZ + dx * dZdX` (integer part)
/// at each pixel's offset from vertex A's pixel.
///
/// Source: spec 5.4, 5.8 (20.12 Z); MAME and DOSBox Staging step from A's pixel. A real
/// board should read 0x1000, 0x1180, 0x1300, ... along row 2 from column 0.
#[test]
fn iterated_z_along_a_row() {
    let mut p = board(0, BASE | fbz::DEPTH | fbz::depth_function(ALWAYS));
    let mut t = Triangle::corner(0xffff_ffff);
    t.z = Param {
        start: 0x1000 << 12,
        dx: 0x180 << 12,
        dy: 0,
    };
    triangle_fixed(&mut p, &t);
    let row: Vec<u16> = (0..8).map(|x| p.read_aux(x, 2)).collect();
    let want: Vec<u16> = (0..8).map(|x| 0x1000 + 0x180 * x).collect();
    assert_eq!(row, want);
}

//! Colour reduction to RGB565: ordered dither and truncation (spec 5.19 bits 8 and 11,
//! 5.20 LFB writes, 5.23 FASTFILL). The 2x2 matrix is disputed: see `disputes.rs`.

use firmware_tests::bits::{fbz, lfb};
use firmware_tests::expect::{dither565, MATRIX_4X4};
use firmware_tests::{
    fastfill, lfb32, rgb565_truncated, triangle_fixed, Buffer, Emulator, Port, Triangle,
};
use sst1_regs::addr;

const MODE: u32 = fbz::CLIP | fbz::RGB_WRITE | fbz::AUX_WRITE | fbz::DRAW_BACK;
/// A colour whose three channels round differently across the matrix.
const COLOUR: (u32, u32, u32) = (0x85, 0x41, 0x3c);

/// The 4x4 cell at (4..8, 4..8) of the back buffer, `[y][x]`.
fn cell(p: &mut Emulator) -> [[u16; 4]; 4] {
    std::array::from_fn(|y| {
        std::array::from_fn(|x| p.read_pixel(Buffer::Back, 4 + x as u32, 4 + y as u32))
    })
}

fn expected_cell(r: u32, g: u32, b: u32) -> [[u16; 4]; 4] {
    std::array::from_fn(|y| std::array::from_fn(|x| dither565(r, g, b, MATRIX_4X4[y][x])))
}

fn flat_triangle(p: &mut Emulator, (r, g, b): (u32, u32, u32)) {
    let argb = 0xff00_0000 | r << 16 | g << 8 | b;
    triangle_fixed(p, &Triangle::corner(argb));
}

/// A flat colour (0x85, 0x41, 0x3c) through the 4x4 ordered dither gives one exact
/// value per cell position. Red 0x85 rounds up to 17 where the matrix entry is 13 or
/// more, green 0x41 only at entry 15, blue 0x3c from entry 11.
///
/// Source: MAME (marked hardware-verified), DOSBox Staging and 86Box agree on the matrix
/// and the equations (spec 5.19 names only "4x4 ordered dither"). A real board should
/// read these 16 values at (4..8, 4..8).
#[test]
fn dither_4x4_cell_of_a_flat_triangle() {
    let mut p = Emulator::booted();
    p.write(addr::FBZ_MODE, MODE | fbz::DITHER);
    flat_triangle(&mut p, COLOUR);
    let want = expected_cell(COLOUR.0, COLOUR.1, COLOUR.2);
    assert_eq!(cell(&mut p), want);
    // Spot values written out: entry 0 at (4,4), entry 15 at (4,7).
    assert_eq!(want[0][0], 16 << 11 | 16 << 5 | 7);
    assert_eq!(want[3][0], 17 << 11 | 17 << 5 | 8);
}

/// FASTFILL dithers `color1` with the same matrix when `fbzMode` bit 8 is set.
///
/// Source: spec 5.23 ("dithering may be employed optionally as defined by bit(8)");
/// matrix as above. A real board should read the same 16 values as the triangle.
#[test]
fn dither_4x4_cell_of_a_fastfill() {
    let mut p = Emulator::booted();
    p.write(addr::FBZ_MODE, MODE | fbz::DITHER);
    let (r, g, b) = COLOUR;
    fastfill(&mut p, r << 16 | g << 8 | b, 0xffff);
    assert_eq!(cell(&mut p), expected_cell(r, g, b));
}

/// With dithering off the colour is truncated: (0x85, 0x41, 0x3c) is 0x8207 everywhere.
///
/// Source: spec 5.19 ("converted into 16-bit RGB color values by bit truncation").
/// A real board should read 0x8207 in all 16 positions.
#[test]
fn dithering_off_truncates() {
    let mut p = Emulator::booted();
    flat_triangle(&mut p, COLOUR);
    assert_eq!(rgb565_truncated(0x85, 0x41, 0x3c), 0x8207);
    assert_eq!(cell(&mut p), [[0x8207; 4]; 4]);
}

/// Black and white survive the dither unchanged at every matrix position (no entry
/// pushes 255 past 31/63 or 0 above 0).
///
/// Source: the equations of MAME, DOSBox Staging and 86Box. A real board should read
/// 0x0000 and 0xffff everywhere.
#[test]
fn dither_keeps_black_and_white() {
    let mut p = Emulator::booted();
    p.write(addr::FBZ_MODE, MODE | fbz::DITHER);
    flat_triangle(&mut p, (255, 255, 255));
    assert_eq!(cell(&mut p), [[0xffff; 4]; 4]);
    flat_triangle(&mut p, (0, 0, 0));
    assert_eq!(cell(&mut p), [[0; 4]; 4]);
}

/// LFB writes that bypass the pixel pipeline are still dithered when `fbzMode` bit 8
/// is set (format 4, x-8-8-8, one pixel per write).
///
/// Source: spec 5.20 ("written ... unconditionally ... except for optional color
/// dithering"); MAME and DOSBox Staging dither them with the 4x4 matrix at the
/// pixel's position. A real board should read the dithered cell.
#[test]
fn dither_applies_to_raw_lfb_writes() {
    let mut p = Emulator::booted();
    p.write(addr::FBZ_MODE, MODE | fbz::DITHER);
    p.write(addr::LFB_MODE, lfb::format(4) | lfb::WRITE_BACK);
    let (r, g, b) = COLOUR;
    for y in 4..8 {
        for x in 4..8 {
            p.write(lfb32(x, y), r << 16 | g << 8 | b);
        }
    }
    assert_eq!(cell(&mut p), expected_cell(r, g, b));
}

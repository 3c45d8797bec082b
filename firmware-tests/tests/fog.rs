//! The fog unit (spec 5.17 `fogMode`, 5.25 `fogColor`, 5.36 `fogTable`). Every program
//! keeps `fogColor` at or above the colour in each channel, where the three reference
//! emulators agree; the disputed cases (negative differences, fog from iterated alpha,
//! biased table index, both source bits) are in `disputes.rs`.

use firmware_tests::bits::fog;
use firmware_tests::expect::{fog_blend, fog_table_alpha, wfloat};
use firmware_tests::{rgb565_truncated, triangle_fixed, Buffer, Emulator, Param, Port, Triangle};
use sst1_regs::addr;

/// The colour-combine output: flat iterated (40, 100, 60), passed through unchanged
/// (`fbzColorPath` = 0).
const CIN: [i32; 3] = [40, 100, 60];
const FOG_COLOUR: [i32; 3] = [240, 200, 100];

fn fog_board(mode: u32, fog_colour: [i32; 3]) -> Emulator {
    let mut p = Emulator::booted();
    p.write(addr::FOG_MODE, mode);
    let [r, g, b] = fog_colour.map(|c| c as u32);
    p.write(addr::FOG_COLOR, r << 16 | g << 8 | b);
    p
}

/// Draw the flat colour with constant Z (16-bit integer) and W (2.30 register value) at
/// columns `x0..`, and read back pixel (x0 + 4, 4).
fn draw(p: &mut Emulator, x0: i32, z: i32, w: i32) -> u16 {
    let [r, g, b] = CIN.map(|c| c as u32);
    let mut t = Triangle::flat(
        [(x0, 0), (x0 + 40, 0), (x0, 40)],
        0xff00_0000 | r << 16 | g << 8 | b,
    );
    t.z = Param::flat(z << 12);
    t.w = Param::flat(w);
    triangle_fixed(p, &t);
    p.read_pixel(Buffer::Back, x0 as u32 + 4, 4)
}

fn fogged(afog: i32, fog_colour: [i32; 3]) -> u16 {
    let [r, g, b] = [0, 1, 2].map(|i| fog_blend(CIN[i], fog_colour[i], afog));
    rgb565_truncated(r, g, b)
}

/// Table fog interpolates between entries: W = 0x02c00000 (2.30) gives the 16-bit
/// float depth 0x4a00 (exponent 4, mantissa 0xa00), i.e. entry 18 at fraction 0x80,
/// so Afog = fog[18] + delta[18] * 0x80 / 1024 = 0x40 + 16 = 0x50; W = 0x02800000 gives
/// 0x4c00, exactly entry 19 (Afog = fog[19] = 0x60).
///
/// Source: spec 5.17 (table index and fraction from the float depth), 5.19 (float
/// depth of W), 5.36 (entry layout, 6.2 deltas); MAME, DOSBox Staging and 86Box agree.
/// A real board should read 0x6409 and 0x7449.
#[test]
fn fog_table_interpolation_step() {
    assert_eq!(
        (wfloat(0x02c0_0000 << 2), wfloat(0x0280_0000 << 2)),
        (0x4a00, 0x4c00)
    );
    let mut p = fog_board(fog::ENABLE, FOG_COLOUR);
    // fogTable[9]: entries 18 (delta 0x80 = 32.0, fog 0x40) and 19 (delta 0x10, fog 0x60).
    p.write(addr::FOG_TABLE + 9 * 4, 0x6010_4080);
    let a18 = fog_table_alpha(0x40, 0x80, 0x4a00);
    let a19 = fog_table_alpha(0x60, 0x10, 0x4c00);
    assert_eq!((a18, a19), (0x50, 0x60));
    assert_eq!(
        draw(&mut p, 0, 0, 0x02c0_0000),
        fogged(a18 as i32, FOG_COLOUR)
    );
    assert_eq!(
        draw(&mut p, 100, 0, 0x0280_0000),
        fogged(a19 as i32, FOG_COLOUR)
    );
    assert_eq!(
        (fogged(0x50, FOG_COLOUR), fogged(0x60, FOG_COLOUR)),
        (0x6409, 0x7449)
    );
}

/// Entries written through one `fogTable` word land in entries 2n and 2n+1 with the
/// documented byte layout: writing only word 0 fogs a depth in entry 1 (0x0600) with
/// fog[1] and leaves entry 2 (0x0800) at zero fog.
///
/// Source: spec 5.36. A real board should read the fogged and the unfogged colour.
#[test]
fn fog_table_word_layout() {
    let mut p = fog_board(fog::ENABLE, FOG_COLOUR);
    p.write(addr::FOG_TABLE, 0xc000_0000); // fog[1] = 0xc0, all else 0
                                           // W = 0.8125 (0x34000000 in 2.30) has float depth 0x0600 (entry 1, fraction 0x80);
                                           // W = 0.6875 (0x2c000000) has 0x0a00 (entry 2).
    let (w1, w2) = (0x3400_0000, 0x2c00_0000);
    assert_eq!((wfloat(w1 << 2), wfloat(w2 << 2)), (0x0600, 0x0a00));
    assert_eq!(draw(&mut p, 0, 0, w1 as i32), fogged(0xc0, FOG_COLOUR));
    assert_eq!(draw(&mut p, 100, 0, w2 as i32), fogged(0, FOG_COLOUR));
}

/// `fogMode` bit 4: the fog alpha is iterated Z bits 27:20, the high byte of the 16-bit
/// depth. Z = 0x8000 gives Afog 0x80; Z = 0x3fff gives 0x3f.
///
/// Source: spec 5.17 (bit 4: "iterated z(27:20)"); MAME, DOSBox Staging and 86Box
/// agree for in-range Z. A real board should read the two blends below.
#[test]
fn fog_from_iterated_z() {
    let mut p = fog_board(fog::ENABLE | fog::Z, FOG_COLOUR);
    assert_eq!(draw(&mut p, 0, 0x8000, 0), fogged(0x80, FOG_COLOUR));
    assert_eq!(draw(&mut p, 100, 0x3fff, 0), fogged(0x3f, FOG_COLOUR));
}

/// `fogMode` bit 5 adds `fogColor` as a constant, clamped, whatever bits 4:3 say:
/// (40, 100, 60) + (20, 30, 200) = (60, 130, 255).
///
/// Source: spec 5.17 (bit 5 "takes precedence over bits(4:3) and enables a constant
/// value(fogColor) to be added"). A real board should read 0x3c1f.
#[test]
fn fog_constant_adds_fog_colour() {
    let mut p = fog_board(fog::ENABLE | fog::CONSTANT | fog::Z, [20, 30, 200]);
    assert_eq!(draw(&mut p, 0, 0x8000, 0), rgb565_truncated(60, 130, 255));
    assert_eq!(rgb565_truncated(60, 130, 255), 0x3c1f);
}

/// `fogmult` (bit 2) drops the colour: `Cout = Afog * fogColor`; with `fogadd` (bit 1)
/// as well the output is zero.
///
/// Source: spec 5.17 equation table; the (Afog + 1) / 256 scale from MAME, DOSBox
/// Staging and 86Box. With Afog = 0x80 (Z = 0x8000) a real board should read
/// (120, 100, 50) and then black.
#[test]
fn fog_mult_and_fog_add() {
    let mut p = fog_board(fog::ENABLE | fog::MULT | fog::Z, FOG_COLOUR);
    let want = [0, 1, 2].map(|i| (FOG_COLOUR[i] as u32 * 0x81) >> 8);
    assert_eq!(want, [120, 100, 50]);
    assert_eq!(draw(&mut p, 0, 0x8000, 0), rgb565_truncated(120, 100, 50));
    p.write(addr::FOG_MODE, fog::ENABLE | fog::MULT | fog::ADD | fog::Z);
    assert_eq!(draw(&mut p, 100, 0x8000, 0), 0);
}

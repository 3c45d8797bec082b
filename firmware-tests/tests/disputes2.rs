//! The newer disputed behaviours, one register program per switch, run once per choice
//! (continuing `disputes.rs`): the dither/stipple row with a flipped Y origin
//! (`PatternRow`), float registers that overflow the fixed formats (`FloatOverflow`),
//! the width of the subpixel correction of Z (`SubpixelZ`),
//! the alpha-test input (`AlphaTestInput`), the LFB word swap of 32-bit formats
//! (`LfbWordSwap`), and the texel switches that a short program shows
//! (`TexelProfile::coord_rounding`, `decal_invert`, `trilinear`).
//!
//! Each program is what a driver could run on a real board: the doc comment of each
//! test says which value the board would read for that choice.
//!
//! The texel switches are run with both choices. The other choice's value is also given in
//! the doc comment (and `crates/board/tests/trilinear.rs` runs `Trilinear::Ignored`).

use firmware_tests::bits::{alpha, color_path, fbz, lfb};
use firmware_tests::expect::{dither565, MATRIX_4X4};
use firmware_tests::{
    fastfill, lfb16, lfb32, rgb565_truncated, triangle_fixed, Buffer, Emulator, Port, Triangle,
};
use pixelfx::profile::{AlphaTestInput, FloatOverflow, LfbWordSwap, PatternRow, SubpixelZ};
use pixelfx::PixelProfile;
use sst1_board::AccuracyProfile;
use sst1_regs::{addr, FbzColorPath, TLod, TcMselect, TextureMode};

const BASE: u32 = fbz::CLIP | fbz::RGB_WRITE | fbz::AUX_WRITE | fbz::DRAW_BACK;

fn board(pixel: PixelProfile) -> Emulator {
    Emulator::booted_with(AccuracyProfile {
        pixel,
        ..Default::default()
    })
}

// --- dither row with the Y origin at the bottom: PatternRow ---------------------------

/// A colour whose channels round differently across the dither matrix.
const DITHERED: (u32, u32, u32) = (0x85, 0x41, 0x3c);

/// The init's `fbiInit3` Y-origin swap value: raster row `y` lands on screen row
/// `479 - y` when `fbzMode` bit 17 is set (spec 5.19, 5.46).
const SWAP_Y: u32 = 479;

/// Pixels 4..8 of raster row 4 (screen row 475) after `draw` with dithering and the
/// Y origin at the bottom.
fn flipped_row(pixel: PixelProfile, draw: impl FnOnce(&mut Emulator)) -> [u16; 4] {
    let mut p = board(pixel);
    p.write(addr::FBZ_MODE, BASE | fbz::DITHER | fbz::Y_ORIGIN);
    draw(&mut p);
    std::array::from_fn(|i| p.read_pixel(Buffer::Back, 4 + i as u32, SWAP_Y - 4))
}

/// The dithered colour across x = 4..8 with matrix row `row`.
fn dithered_row(row: usize) -> [u16; 4] {
    let (r, g, b) = DITHERED;
    std::array::from_fn(|i| dither565(r, g, b, MATRIX_4X4[row][(4 + i) & 3]))
}

fn dithered_triangle(p: &mut Emulator) {
    let (r, g, b) = DITHERED;
    triangle_fixed(p, &Triangle::corner(0xff00_0000 | r << 16 | g << 8 | b));
}

/// `PatternRow::Screen` (MAME, 86Box; default): the triangle's dither row is the
/// frame-buffer row, 475 & 3 = 3. A board showing matrix row 3 at screen row 475
/// supports this choice.
#[test]
fn pattern_row_screen_triangle() {
    let pixel = PixelProfile {
        pattern_row: PatternRow::Screen,
        ..Default::default()
    };
    assert_eq!(flipped_row(pixel, dithered_triangle), dithered_row(3));
    assert_ne!(dithered_row(3), dithered_row(0));
}

/// `PatternRow::Raster` (DOSBox Staging): the dither row is the raster row before the
/// flip, 4 & 3 = 0. A board showing matrix row 0 there supports this choice.
#[test]
fn pattern_row_raster_triangle() {
    let pixel = PixelProfile {
        pattern_row: PatternRow::Raster,
        ..Default::default()
    };
    assert_eq!(flipped_row(pixel, dithered_triangle), dithered_row(0));
}

fn dithered_fill(p: &mut Emulator) {
    let (r, g, b) = DITHERED;
    fastfill(p, r << 16 | g << 8 | b, 0xffff);
}

/// FASTFILL indexes its dither cell with the raster row whatever `PatternRow` says
/// (crates/pixelfx/src/fastfill.rs: measured on the glide-sdk clears, which match all
/// three references that way): matrix row 0 at screen row 475 under both choices. A
/// board showing row 3 here would contradict the measurement.
#[test]
fn pattern_row_fastfill_uses_the_raster_row() {
    for pattern_row in [PatternRow::Screen, PatternRow::Raster] {
        let pixel = PixelProfile {
            pattern_row,
            ..Default::default()
        };
        assert_eq!(
            flipped_row(pixel, dithered_fill),
            dithered_row(0),
            "{pattern_row:?}"
        );
    }
}

// --- float registers out of range: FloatOverflow ----------------------------------------

/// 786752.0 = 0x1.805p19 (IEEE 0x49401400): as 12.12 its mantissa 0xc01400 is shifted
/// left by 8, giving 0xc0140000, past `i32::MAX`.
const OVERFLOWING: u32 = 0x4940_1400;

/// A flat black triangle with `fstartR` and `fdZdX` = [`OVERFLOWING`] (start Z 0); the
/// aux buffer gets Z (no depth test; `AuxWrite::MaskOnly`). Returns the pixel at (0, 0)
/// and the depth at x = 0, 1, 2 of row 0 (vertex A is (0, 0): Z = x * dZdX).
fn float_overflow_program(float_overflow: FloatOverflow) -> (u16, [u16; 3]) {
    let mut p = board(PixelProfile {
        float_overflow,
        ..Default::default()
    });
    let t = Triangle::corner(0xff00_0000);
    triangle_fixed(&mut p, &t);
    p.write(addr::F_START_R, OVERFLOWING);
    p.write(addr::F_D_Z_DX, OVERFLOWING);
    p.write(addr::TRIANGLE_CMD, t.area_sign());
    let depth = std::array::from_fn(|x| p.read_aux(x as u32, 0));
    (p.read_pixel(Buffer::Back, 0, 0), depth)
}

/// `FloatOverflow::Wrap` (MAME; default): the low 32 bits of the shifted mantissa,
/// 0xc0140000. Red keeps bits 23:12 (0x140, read as 0x40); Z steps by 0xc0140000 (its
/// bits 31:12 wrap): 0, 0x0140 (0xc0140), 0x0280 (0x80280 after the 32-bit wrap).
/// A board reading red 0x40 and depths 0x0140, 0x0280 supports this choice.
#[test]
fn float_overflow_wraps() {
    let (pixel, depth) = float_overflow_program(FloatOverflow::Wrap);
    assert_eq!(pixel, rgb565_truncated(0x40, 0, 0));
    assert_eq!(depth, [0, 0x0140, 0x0280]);
}

/// `FloatOverflow::Saturate` (DOSBox Staging): 0x7fffffff. Red's 24-bit register holds
/// 0xffffff = -1/4096, integer part 0xfff, which reads 0; Z: 0, 0x7ffff (reads 0xffff),
/// 0xfffff (2 * 0x7fffffff, reads 0).
#[test]
fn float_overflow_saturates() {
    let (pixel, depth) = float_overflow_program(FloatOverflow::Saturate);
    assert_eq!(pixel, 0);
    assert_eq!(depth, [0, 0xffff, 0]);
}

/// `FloatOverflow::Indefinite` (86Box: x86's "integer indefinite" from
/// `(int)(f * 4096.0f)`): 0x80000000. Red's low 24 bits are 0; Z: 0, 0x80000 (reads
/// 0), 0 (2 * 0x80000000 wraps to 0).
#[test]
fn float_overflow_indefinite() {
    let (pixel, depth) = float_overflow_program(FloatOverflow::Indefinite);
    assert_eq!(pixel, 0);
    assert_eq!(depth, [0, 0, 0]);
}

// --- subpixel correction of Z with a huge gradient: SubpixelZ ---------------------------

/// A flat triangle with vertex A on a pixel corner (the correction offsets are 8/16 in x
/// and y), subpixel correction on, `startZ` = 0xfffff000 (20.12: -1) and
/// `dZdX` = 0x20000000, so that `8 * dZdX` = 2^32 leaves 32 bits. Returns the depth at
/// x = 0, 1 of row 0. The depth is Z[31:12] with 0xfffff read as 0, 0x10000 as 0xffff and
/// anything else as its low 16 bits (spec 5.19's clamp as MAME, DOSBox and 86Box do it),
/// so a difference of 2^28 in Z shows only across that wrap.
fn subpixel_z_program(subpixel_z: SubpixelZ) -> [u16; 2] {
    let mut p = board(PixelProfile {
        subpixel_z,
        ..Default::default()
    });
    p.write(addr::FBZ_COLOR_PATH, color_path::PARAM_ADJUST);
    p.write(addr::FBZ_MODE, BASE);
    let t = Triangle::corner(0xff00_0000);
    for (reg, v) in [(addr::VERTEX_BX, 40 << 4), (addr::VERTEX_CY, 40 << 4)] {
        p.write(reg, v);
    }
    p.write(addr::START_Z, 0xffff_f000);
    p.write(addr::D_Z_DX, 0x2000_0000);
    p.write(addr::TRIANGLE_CMD, t.area_sign());
    std::array::from_fn(|x| p.read_aux(x as u32, 0))
}

/// `SubpixelZ::Wrap32` (MAME, 86Box; default): `(8 * 0 + 8 * 0x20000000) >> 4` wraps to
/// 0 in 32 bits, so Z(0) stays 0xfffff000 (Z[31:12] = 0xfffff, reads 0) and
/// Z(1) = 0x1ffff000 (0x1ffff, reads 0xffff). A board reading 0 at x = 0 supports it.
#[test]
fn subpixel_z_wraps_in_32_bits() {
    assert_eq!(subpixel_z_program(SubpixelZ::Wrap32), [0, 0xffff]);
}

/// `SubpixelZ::Wide64` (DOSBox Staging): the 64-bit product 2^32 >> 4 = 0x10000000 is
/// added, so Z(0) = 0x0ffff000 (0x0ffff, reads 0xffff) and Z(1) = 0x2ffff000 (0x2ffff,
/// reads 0xffff).
#[test]
fn subpixel_z_in_64_bits() {
    assert_eq!(subpixel_z_program(SubpixelZ::Wide64), [0xffff, 0xffff]);
}

// --- alpha test input: AlphaTestInput ---------------------------------------------------

/// Iterated alpha 0x80 as `a_other`; the alpha combine zeroes it (`cca_zero_other`,
/// `fbzColorPath` bit 17, no add), so the combined alpha is 0. The alpha test is
/// "greater than 0x40". Returns the pixel at (4, 4) and `fbiAfuncFail`.
fn alpha_test_program(alpha_test_input: AlphaTestInput) -> (u16, u32) {
    let mut p = board(PixelProfile {
        alpha_test_input,
        ..Default::default()
    });
    p.write(
        addr::FBZ_COLOR_PATH,
        FbzColorPath(0).with_cca_zero_other(true).0,
    );
    p.write(addr::ALPHA_MODE, alpha::test(4) | alpha::reference(0x40));
    p.write(addr::NOP_CMD, 1);
    triangle_fixed(&mut p, &Triangle::corner(0x80c8_6432));
    (
        p.read_pixel(Buffer::Back, 4, 4),
        p.read(addr::FBI_AFUNC_FAIL),
    )
}

/// `AlphaTestInput::Combined` (spec 5.18.1 diagram order; MAME, 86Box; default): the
/// test sees 0 and fails for every pixel: the back buffer keeps the init's fill
/// (0x101030) and `fbiAfuncFail` counts every pixel of the triangle. A board that draws
/// nothing here supports this choice.
#[test]
fn alpha_test_input_combined() {
    let (pixel, fails) = alpha_test_program(AlphaTestInput::Combined);
    assert_eq!(pixel, rgb565_truncated(0x10, 0x10, 0x30));
    // Row y covers x < 40 - (y + 0.5), rounded half down: 39 + 38 + ... + 1 pixels.
    assert_eq!(triangle_pixels(), 780);
    assert_eq!(fails, 780);
}

/// `AlphaTestInput::AOther` (DOSBox Staging): the test sees 0x80 and passes; the
/// triangle is drawn in its colour. A board drawing the triangle supports this choice.
#[test]
fn alpha_test_input_a_other() {
    let (pixel, fails) = alpha_test_program(AlphaTestInput::AOther);
    assert_eq!(pixel, rgb565_truncated(0xc8, 0x64, 0x32));
    assert_eq!(fails, 0);
}

/// Pixels of [`flat`]'s triangle: the same triangle drawn plainly, counted by
/// `fbiPixelsOut`.
fn triangle_pixels() -> u32 {
    let mut p = Emulator::booted();
    p.write(addr::NOP_CMD, 1);
    triangle_fixed(&mut p, &Triangle::corner(0xffff_ffff));
    p.read(addr::FBI_PIXELS_OUT)
}

// --- LFB word swap of 32-bit formats: LfbWordSwap ---------------------------------------

/// One ARGB8888 LFB write (format 5) of 0x00f88008 at (10, 10) with `lfbMode` bit 11
/// (word swap on writes), and, as a control, one RGB565 pair write (format 0) of
/// 0x001ff800 at (20, 10) with the same bit. Returns the pixels at (10, 10), (20, 10)
/// and (21, 10).
fn word_swap_program(lfb_word_swap: LfbWordSwap) -> [u16; 3] {
    let mut p = board(PixelProfile {
        lfb_word_swap,
        ..Default::default()
    });
    p.write(
        addr::LFB_MODE,
        lfb::format(5) | lfb::WRITE_BACK | lfb::WORD_SWAP_WRITES,
    );
    p.write(lfb32(10, 10), 0x00f8_8008);
    p.write(
        addr::LFB_MODE,
        lfb::format(0) | lfb::WRITE_BACK | lfb::WORD_SWAP_WRITES,
    );
    p.write(lfb16(20, 10), 0x001f_f800);
    [(10, 10), (20, 10), (21, 10)].map(|(x, y)| p.read_pixel(Buffer::Back, x, y))
}

/// `LfbWordSwap::SpecIgnoredFor32Bit` (spec 5.20, twice; default): the ARGB8888 word is taken as written, RGB (0xf8, 0x80, 0x08); the 565 pair
/// is swapped: blue (0x001f) at x = 20, red at 21. A board showing (0xf8, 0x80, 0x08)
/// at (10, 10) supports this choice.
#[test]
fn lfb_word_swap_ignored_for_32_bit() {
    assert_eq!(
        word_swap_program(LfbWordSwap::SpecIgnoredFor32Bit),
        [rgb565_truncated(0xf8, 0x80, 0x08), 0x001f, 0xf800]
    );
}

/// `LfbWordSwap::Always` (MAME, DOSBox Staging): the word becomes 0x800800f8, RGB
/// (0x08, 0x00, 0xf8). A board showing that at (10, 10) supports this choice.
#[test]
fn lfb_word_swap_always() {
    assert_eq!(
        word_swap_program(LfbWordSwap::Always),
        [rgb565_truncated(0x08, 0x00, 0xf8), 0x001f, 0xf800]
    );
}

/// `LfbWordSwap::Never` (86Box, which has no word swap): neither word is swapped, so the
/// 565 pair lands red at x = 20, blue at 21.
#[test]
fn lfb_word_swap_never() {
    assert_eq!(
        word_swap_program(LfbWordSwap::Never),
        [rgb565_truncated(0xf8, 0x80, 0x08), 0xf800, 0x001f]
    );
}

// --- texel switches -------------------------------------------------------------------

use firmware_tests::texture::{COLOR_PATH_TEXTURE, DECAL, TEX_565, TEX_BASE};

/// A board with the 2 x 2 level LOD 7 of a 256 x 256 RGB565 texture at base 0, texels
/// `[t][s]`, `tLOD` = `t_lod` and `textureMode` = `mode`, then a flat triangle with
/// `startS` = `s` (14.18), T 0 and no gradients. Returns the pixel at (4, 4).
fn texel_program(texels: [[u16; 2]; 2], t_lod: u32, mode: u32, s: u32) -> u16 {
    texel_program_with(texelfx::TexelProfile::default(), texels, t_lod, mode, s)
}

/// [`texel_program`] on a board with the texel switches `texel`.
fn texel_program_with(
    texel: texelfx::TexelProfile,
    texels: [[u16; 2]; 2],
    t_lod: u32,
    mode: u32,
    s: u32,
) -> u16 {
    let mut p = Emulator::booted_with(sst1_board::AccuracyProfile {
        texel,
        ..Default::default()
    });
    p.write(addr::TEXTURE_MODE, TEX_565);
    p.write(addr::T_LOD, t_lod);
    p.write(addr::TEX_BASE_ADDR, 0);
    for (t, row) in texels.iter().enumerate() {
        // Spec 8: LOD in address bits 20:17, T in 16:9, two 16-bit texels per write.
        let a = TEX_BASE | 7 << 17 | (t as u32) << 9;
        p.write(a, u32::from(row[0]) | u32::from(row[1]) << 16);
    }
    p.write(addr::TEXTURE_MODE, mode);
    p.write(addr::FBZ_COLOR_PATH, COLOR_PATH_TEXTURE);
    for (reg, v) in [
        (addr::START_S, s),
        (addr::D_S_DX, 0),
        (addr::D_S_DY, 0),
        (addr::START_T, 0),
        (addr::D_T_DX, 0),
        (addr::D_T_DY, 0),
    ] {
        p.write(reg, v);
    }
    triangle_fixed(&mut p, &Triangle::corner(0xff00_0000));
    p.read_pixel(Buffer::Back, 4, 4)
}

/// `tLOD` with `lodmin` = `lodmax` = `quarters` / 4 (4.2 fixed point, spec 5.51). With
/// zero gradients the computed LOD falls below `lodmin` and is clamped to it, so the
/// LOD is `quarters` / 4 whatever the LOD calculation.
const fn fixed_lod(quarters: u32) -> u32 {
    TLod(0).with_lodmin(quarters).with_lodmax(quarters).0
}

/// `CoordRounding::Floor` (DOSBox Staging, 86Box; default): S = -2^-18 texel (14.18
/// 0xffffffff) without perspective is S >> 24 = -1/256 in 24.8, which floors to texel
/// -1 and wraps to the last texel, s = 1 (green). With `CoordRounding::TowardZero`
/// (MAME's goldens) it truncates to texel 0 (red). A board drawing green supports
/// `Floor`, red `TowardZero`.
#[test]
fn coord_rounding_floor_wraps_to_the_last_texel() {
    let texels = [[0xf800, 0x07e0], [0xf800, 0x07e0]];
    let pixel = texel_program(texels, fixed_lod(7 << 2), TEX_565 | DECAL, 0xffff_ffff);
    assert_eq!(pixel, 0x07e0);
    // The same program at S = 0 reads texel 0.
    assert_eq!(
        texel_program(texels, fixed_lod(7 << 2), TEX_565 | DECAL, 0),
        0xf800
    );
    // `CoordRounding::TowardZero`: S = -2^-18 truncates to texel 0.
    let toward_zero = texelfx::TexelProfile {
        coord_rounding: texelfx::CoordRounding::TowardZero,
        ..Default::default()
    };
    let pixel = texel_program_with(
        toward_zero,
        texels,
        fixed_lod(7 << 2),
        TEX_565 | DECAL,
        0xffff_ffff,
    );
    assert_eq!(pixel, 0xf800);
}

/// `DecalInvert::Ignored` (MAME, 86Box; default): decal with `tc_invert_output` and
/// `tca_invert_output` (bits 20, 29) outputs the texel unchanged: red 0xf800. With
/// `DecalInvert::Applied` (DOSBox Staging; the spec's diagram) the combine inverts it to
/// (0x00, 0xff, 0xff), 0x07ff. A board drawing red supports `Ignored`, cyan `Applied`.
#[test]
fn decal_invert_ignored() {
    let red = [[0xf800; 2]; 2];
    let mode = TextureMode(TEX_565 | DECAL)
        .with_tc_invert_output(true)
        .with_tca_invert_output(true)
        .0;
    assert_eq!(texel_program(red, fixed_lod(7 << 2), mode, 0), 0xf800);
    let applied = texelfx::TexelProfile {
        decal_invert: texelfx::DecalInvert::Applied,
        ..Default::default()
    };
    assert_eq!(
        texel_program_with(applied, red, fixed_lod(7 << 2), mode, 0),
        0x07ff
    );
}

/// `Trilinear::Spec` (spec 5.50 diagram, 86Box; default): at LOD 7.25 (odd integer
/// part, fraction 0x40) a white texel through `local - local * (F + 1) / 256`
/// (`tc_zero_other`, `tc_sub_clocal`, `tc_mselect` = LOD fraction, `tc_reverse_blend`,
/// `tc_add_clocal`) with the `trilinear` bit: the odd LOD reverses the factor to
/// 0xbf, so 255 + ((-255 * 0xc0) >> 8) = 63 per channel. With `Trilinear::Ignored`
/// (MAME, DOSBox Staging) the factor stays 0x40: 255 + ((-255 * 0x41) >> 8) = 190.
/// A board reading (63, 63, 63) supports `Spec`, (190, 190, 190) `Ignored`.
#[test]
fn trilinear_reverses_the_blend_on_odd_lods() {
    let white = [[0xffff; 2]; 2];
    let mode = TextureMode(TEX_565)
        .with_tc_zero_other(true)
        .with_tc_sub_clocal(true)
        .with_tc_mselect(TcMselect::LodFrac)
        .with_tc_reverse_blend(true)
        .with_tc_add_clocal(true)
        .with_trilinear(true);
    // lodmin 7.25, lodmax 8.0 (4.2 fixed point).
    let lod = TLod(0).with_lodmin(7 << 2 | 1).with_lodmax(8 << 2).0;
    let pixel = texel_program(white, lod, mode.0, 0);
    assert_eq!(pixel, rgb565_truncated(63, 63, 63));
    // Without the trilinear bit the factor is the fraction itself on every LOD.
    let plain = texel_program(white, lod, mode.with_trilinear(false).0, 0);
    assert_eq!(plain, rgb565_truncated(190, 190, 190));
    // `Trilinear::Ignored`: the bit has no effect.
    let ignored = texelfx::TexelProfile {
        trilinear: texelfx::Trilinear::Ignored,
        ..Default::default()
    };
    let pixel = texel_program_with(ignored, white, lod, mode.0, 0);
    assert_eq!(pixel, rgb565_truncated(190, 190, 190));
}

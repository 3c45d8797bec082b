//! Disputed behaviours that the reference profiles (`sst1_board::Reference`) brought in,
//! one register program per switch, run once per choice (continuing `disputes2.rs`):
//! FASTFILL dithering (`FastfillDither`), the iterator origin and the lifetime of the
//! subpixel correction (`ParamOrigin`), the blue of RGB332 texels (`Rgb332Blue`),
//! how the filter bits choose point or bilinear sampling (`FilterSelect`), what the
//! local-select override reads when nothing else takes the texel (`OverrideTexel`),
//! which byte of Z is `a_local` (`ZAlphaByte`), the stipple rotation (`StippleRotate`),
//! the LFB ordering bits (`LfbOrdering`), the iterator clamp (`IteratorClamp`), what FBI
//! graphics reset does to the buffers (`GraphicsReset`) and the
//! combine shortcuts of 86Box (`ChainModel`).
//!
//! Each test's doc comment says which value a real board would show for each choice.

use firmware_tests::bits::{alpha, color_path, fbz, lfb};
use firmware_tests::expect::{dither565, MATRIX_4X4};
use firmware_tests::{
    fastfill, lfb32, rgb565_truncated, triangle_fixed, Buffer, Emulator, Port, Triangle,
};
use pixelfx::profile::{
    FastfillDither, GraphicsReset, IteratorClamp, LfbOrdering, OverrideTexel, ParamOrigin,
    StippleRotate, ZAlphaByte,
};
use pixelfx::PixelProfile;
use sst1_board::AccuracyProfile;
use sst1_regs::{addr, AlphaLocalSelect, FbzColorPath, RgbSelect, TLod, TextureMode};
use texelfx::{ChainModel, FilterSelect, Rgb332Blue, TexelProfile};

const BASE: u32 = fbz::CLIP | fbz::RGB_WRITE | fbz::AUX_WRITE | fbz::DRAW_BACK;

fn board(pixel: PixelProfile, texel: TexelProfile) -> Emulator {
    Emulator::booted_with(AccuracyProfile { pixel, texel })
}

// --- FASTFILL dithering: FastfillDither ------------------------------------------------

/// A colour whose channels round differently across the dither matrix.
const DITHERED: (u32, u32, u32) = (0x85, 0x41, 0x3c);

/// FASTFILL of [`DITHERED`] with 4x4 dithering on; pixels 0..4 of row 1.
fn fill_program(fastfill_dither: FastfillDither) -> [u16; 4] {
    let mut p = board(
        PixelProfile {
            fastfill_dither,
            ..Default::default()
        },
        TexelProfile::default(),
    );
    p.write(addr::FBZ_MODE, BASE | fbz::DITHER);
    let (r, g, b) = DITHERED;
    fastfill(&mut p, r << 16 | g << 8 | b, 0xffff);
    std::array::from_fn(|x| p.read_pixel(Buffer::Back, x as u32, 1))
}

/// `FastfillDither::Dithered` (spec 5.23; MAME, DOSBox Staging; default): the fill is
/// dithered like a triangle, matrix row 1 across the row.
#[test]
fn fastfill_dithered() {
    let (r, g, b) = DITHERED;
    let expected: [u16; 4] = std::array::from_fn(|x| dither565(r, g, b, MATRIX_4X4[1][x]));
    assert_eq!(fill_program(FastfillDither::Dithered), expected);
    // The matrix makes the row uneven, so the test tells the two choices apart.
    assert_ne!(expected[0], expected[1]);
}

/// `FastfillDither::Truncated` (86Box): `color1` truncated to RGB565 on every pixel.
#[test]
fn fastfill_truncated() {
    let (r, g, b) = DITHERED;
    assert_eq!(
        fill_program(FastfillDither::Truncated),
        [rgb565_truncated(r, g, b); 4]
    );
}

// --- iterator origin and subpixel correction: ParamOrigin -------------------------------

/// Red iterates by 8 per pixel (12.12 `dRdX` = 8.0) from `startR` = 64 at vertex A =
/// (10.75, 0); the triangle spans x 10..40 of rows 0..20. Dithering is off, so red 8-bit
/// `v` reads as `v >> 3`. Returns red (5 bits) at x = 12 of row 4 after `triangles`
/// triangles with the same start registers (the start values are written once).
fn origin_program(param_origin: ParamOrigin, adjust: bool, triangles: u32) -> u16 {
    let mut p = board(
        PixelProfile {
            param_origin,
            ..Default::default()
        },
        TexelProfile::default(),
    );
    let cp = if adjust { color_path::PARAM_ADJUST } else { 0 };
    p.write(addr::FBZ_COLOR_PATH, cp);
    p.write(addr::FBZ_MODE, BASE);
    let t = Triangle::flat([(10, 0), (40, 0), (10, 20)], 0xff00_0000);
    for (reg, v) in [
        (addr::VERTEX_AX, 10 << 4 | 12),
        (addr::VERTEX_AY, 0),
        (addr::VERTEX_BX, 40 << 4),
        (addr::VERTEX_BY, 0),
        (addr::VERTEX_CX, 10 << 4 | 12),
        (addr::VERTEX_CY, 20 << 4),
        (addr::START_R, 64 << 12),
        (addr::D_R_DX, 8 << 12),
        (addr::D_R_DY, 0),
    ] {
        p.write(reg, v);
    }
    for _ in 0..triangles {
        p.write(addr::TRIANGLE_CMD, t.area_sign());
    }
    p.read_pixel(Buffer::Back, 12, 4) >> 11
}

/// `ParamOrigin::VertexPixel` (MAME, DOSBox Staging; default): the iterators count from
/// A's pixel, 10: x = 12 reads 64 + 2 * 8 = 80 (red 10). Subpixel correction adds
/// (8 - 12) / 16 pixel * 8 = -2 to the start and writes it back, so x = 12 reads 78
/// (red 9) after one triangle and 80 - 5 * 2 = 70 (red 8) after five.
#[test]
fn param_origin_vertex_pixel() {
    assert_eq!(origin_program(ParamOrigin::VertexPixel, false, 1), 80 >> 3);
    assert_eq!(origin_program(ParamOrigin::VertexPixel, true, 1), 78 >> 3);
    assert_eq!(origin_program(ParamOrigin::VertexPixel, true, 5), 70 >> 3);
}

/// `ParamOrigin::RoundedVertex` (86Box): A = 10.75 rounds to pixel 11, so x = 12 reads
/// 64 + 8 = 72 (red 9). Subpixel correction moves the start by (24 - 12) / 16 pixel * 8 =
/// +6, for one triangle only: 78 (9) after one triangle and after five.
#[test]
fn param_origin_rounded_vertex() {
    assert_eq!(
        origin_program(ParamOrigin::RoundedVertex, false, 1),
        72 >> 3
    );
    assert_eq!(origin_program(ParamOrigin::RoundedVertex, true, 1), 78 >> 3);
    assert_eq!(origin_program(ParamOrigin::RoundedVertex, true, 5), 78 >> 3);
}

// --- RGB332 blue: Rgb332Blue ------------------------------------------------------------

use firmware_tests::texture::{COLOR_PATH_TEXTURE, DECAL as DECAL_RGB332, TEX_565, TEX_BASE};
/// `tLOD` with `lodmin` = `lodmax` = LOD 7 (28 in 4.2 fixed point, spec 5.51).
const LOD_7: u32 = TLod(0).with_lodmin(28).with_lodmax(28).0;

/// The 2 x 2 LOD 7 of a 256 x 256 RGB332 texture with texel (0, 0) = `texel`, drawn at
/// S = T = 0 by a flat triangle, undithered: the pixel at (4, 4).
fn rgb332_program(rgb332_blue: Rgb332Blue, texel: u8) -> u16 {
    let mut p = board(
        PixelProfile::default(),
        TexelProfile {
            rgb332_blue,
            ..Default::default()
        },
    );
    p.write(addr::FBZ_MODE, BASE);
    p.write(addr::TEXTURE_MODE, DECAL_RGB332);
    p.write(addr::T_LOD, LOD_7);
    p.write(addr::TEX_BASE_ADDR, 0);
    // Spec 8: LOD in address bits 20:17, T in 16:9; four 8-bit texels per write.
    p.write(TEX_BASE | 7 << 17, u32::from(texel));
    textured_pixel(&mut p, COLOR_PATH_TEXTURE, 0)
}

/// Draws a flat triangle (iterated colour `0xff203040`) with `fbzColorPath` = `cp`,
/// textured from S = T = 0 with `dS/dx` = `dsdx` (14.18) and no other gradient; returns
/// the pixel at (4, 4).
fn textured_pixel(p: &mut Emulator, cp: u32, dsdx: u32) -> u16 {
    p.write(addr::FBZ_COLOR_PATH, cp);
    for (reg, v) in [
        (addr::START_S, 0),
        (addr::D_S_DX, dsdx),
        (addr::D_S_DY, 0),
        (addr::START_T, 0),
        (addr::D_T_DX, 0),
        (addr::D_T_DY, 0),
    ] {
        p.write(reg, v);
    }
    triangle_fixed(p, &Triangle::corner(0xff20_3040));
    p.read_pixel(Buffer::Back, 4, 4)
}

/// `Rgb332Blue::Replicated` (spec, MAME, 86Box; default): texel 0xae = R 101, G 011,
/// B 10 expands to (0xb6, 0x6d, 0xaa).
#[test]
fn rgb332_blue_replicated() {
    assert_eq!(
        rgb332_program(Rgb332Blue::Replicated, 0xae),
        rgb565_truncated(0xb6, 0x6d, 0xaa)
    );
}

/// `Rgb332Blue::DosboxTable` (DOSBox Staging): blue 10 becomes 10 10 00 10 with the
/// texel's bits 5:4 (10) ORed into its top bits: 0xa2, one step darker in RGB565.
#[test]
fn rgb332_blue_dosbox_table() {
    assert_eq!(
        rgb332_program(Rgb332Blue::DosboxTable, 0xae),
        rgb565_truncated(0xb6, 0x6d, 0xa2)
    );
}

// --- point or bilinear: FilterSelect ----------------------------------------------------

/// `textureMode`: RGB565 decal with only `tmagfilter` (bit 2) set.
const DECAL_565_MAG_ONLY: u32 = TextureMode(TEX_565 | DECAL_RGB332).with_tmagfilter(true).0;

/// LOD 7 (2 x 2) of an RGB565 texture, texel column 0 red and column 1 green, with
/// `lodmin` 0 and `lodmax` 7, drawn with dS/dx = 256 texels per pixel: the LOD is
/// clamped to 7, above `lodmin`, so the pixels are minified. At (4, 4), S = 1024 texels
/// of LOD 0, texel 8.0 of LOD 7: on a texel edge.
fn filter_program(filter_select: FilterSelect) -> u16 {
    let mut p = board(
        PixelProfile::default(),
        TexelProfile {
            filter_select,
            ..Default::default()
        },
    );
    p.write(addr::FBZ_MODE, BASE);
    p.write(addr::TEXTURE_MODE, DECAL_565_MAG_ONLY);
    p.write(addr::T_LOD, TLod(0).with_lodmax(28).0);
    p.write(addr::TEX_BASE_ADDR, 0);
    for t in 0..2u32 {
        // Spec 8: LOD in address bits 20:17, T in 16:9, two 16-bit texels per write.
        p.write(TEX_BASE | 7 << 17 | t << 9, 0x07e0 << 16 | 0xf800);
    }
    textured_pixel(&mut p, COLOR_PATH_TEXTURE, 1 << 26)
}

/// `FilterSelect::ByLod` (spec 5.50; MAME, DOSBox Staging; default): minified, so
/// `tminfilter` (0) rules: point sampling reads texel 8 mod 2 = 0, red.
#[test]
fn filter_select_by_lod() {
    assert_eq!(filter_program(FilterSelect::ByLod), 0xf800);
}

/// `FilterSelect::EitherBit` (86Box): `tmagfilter` alone turns bilinear on at any LOD;
/// half a texel back from the edge, texels 1 and 0 weigh 8/16 each: (127, 127, 0).
#[test]
fn filter_select_either_bit() {
    assert_eq!(
        filter_program(FilterSelect::EitherBit),
        rgb565_truncated(127, 127, 0)
    );
}

// --- the local-select override without other texel use: OverrideTexel -------------------

/// `fbzColorPath`: texturing on, `c_other` = texture but zeroed (`cc_zero_other`), add
/// `c_local` (bit 14), `cc_localselect_override` (bit 7): the output is `c_local`, which
/// texture alpha bit 7 makes `color0` (set) or iterated RGB (clear). Nothing else reads the
/// texel.
const OVERRIDE_ONLY: u32 = FbzColorPath(0)
    .with_cc_rgbselect(RgbSelect::Texture)
    .with_cc_localselect_override(true)
    .with_cc_zero_other(true)
    .with_cc_add_clocal(true)
    .with_texture_enable(true)
    .0;

/// A board whose TMU holds a white, opaque RGB565 LOD 7 (2 x 2) at base 0, bound with
/// `textureMode` = `texture_mode`.
fn white_texture_board(pixel: PixelProfile, texel: TexelProfile, texture_mode: u32) -> Emulator {
    let mut p = board(pixel, texel);
    p.write(addr::FBZ_MODE, BASE);
    p.write(addr::TEXTURE_MODE, texture_mode);
    p.write(addr::T_LOD, LOD_7);
    p.write(addr::TEX_BASE_ADDR, 0);
    p.write(TEX_BASE | 7 << 17, 0xffff_ffff);
    p
}

/// The white texel (alpha 0xff) as an RGB565 decal under `fbzColorPath` = `cp`,
/// `color0` = 0x80a0c0e0.
fn override_program(override_texel: OverrideTexel, cp: u32) -> u16 {
    let pixel = PixelProfile {
        override_texel,
        ..Default::default()
    };
    let mut p = white_texture_board(pixel, TexelProfile::default(), TEX_565 | DECAL_RGB332);
    p.write(addr::COLOR0, 0x80a0_c0e0);
    textured_pixel(&mut p, cp, 0)
}

/// `OverrideTexel::Texel` (spec 5.16; DOSBox Staging, 86Box; default): texture alpha
/// 0xff has bit 7 set, so `c_local` is `color0`.
#[test]
fn override_reads_the_texel() {
    assert_eq!(
        override_program(OverrideTexel::Texel, OVERRIDE_ONLY),
        rgb565_truncated(0xa0, 0xc0, 0xe0)
    );
}

/// `OverrideTexel::ZeroWhenUnused` (MAME): no combine input takes the texel, so the TMUs
/// are off, alpha reads 0 and `c_local` is the iterated colour.
#[test]
fn override_reads_zero_when_the_texel_is_unused() {
    assert_eq!(
        override_program(OverrideTexel::ZeroWhenUnused, OVERRIDE_ONLY),
        rgb565_truncated(0x20, 0x30, 0x40)
    );
    // Once the colour comes from the texel as well, MAME fetches it: c_other = texel
    // (not zeroed) plus c_local = color0 saturates to white.
    assert_eq!(
        override_program(
            OverrideTexel::ZeroWhenUnused,
            FbzColorPath(OVERRIDE_ONLY).with_cc_zero_other(false).0
        ),
        0xffff
    );
}

// --- a_local from iterated Z: ZAlphaByte -----------------------------------------------

/// `cca_localselect` = iterated Z (bits 6:5 = 2), alpha output = `a_local`
/// (`cca_zero_other`, bit 17, and `cca_add_clocal`, bit 23); Z = 0x40c0 (start Z
/// 0x040c0000, 20.12, flat). The alpha test passes alpha above 0x80. Returns the pixel at
/// (4, 4), `fbiAfuncFail` and `fbiPixelsIn` of the triangle.
fn z_alpha_program(z_alpha: ZAlphaByte) -> (u16, u32, u32) {
    let mut p = board(
        PixelProfile {
            z_alpha,
            ..Default::default()
        },
        TexelProfile::default(),
    );
    p.write(addr::FBZ_MODE, BASE);
    let path = FbzColorPath(0)
        .with_cca_localselect(AlphaLocalSelect::IteratedZ)
        .with_cca_zero_other(true)
        .with_cca_add_clocal(true);
    p.write(addr::FBZ_COLOR_PATH, path.0);
    p.write(addr::ALPHA_MODE, alpha::test(4) | alpha::reference(0x80));
    let t = Triangle::corner(0xff20_3040);
    // triangle_fixed writes start Z 0: set Z afterwards and draw again, counting only that.
    triangle_fixed(&mut p, &t);
    p.write(addr::START_Z, 0x040c_0000);
    p.write(addr::NOP_CMD, 1);
    p.write(addr::TRIANGLE_CMD, t.area_sign());
    (
        p.read_pixel(Buffer::Back, 4, 4),
        p.read(addr::FBI_AFUNC_FAIL),
        p.read(addr::FBI_PIXELS_IN),
    )
}

/// `ZAlphaByte::High` (spec 5.16 Z[27:20]; MAME, 86Box; default): alpha 0x40 fails the
/// test on every pixel, so the pixel keeps the init's fill (0x101030).
#[test]
fn z_alpha_high_byte() {
    let (pixel, fails, pixels) = z_alpha_program(ZAlphaByte::High);
    assert_eq!(pixel, rgb565_truncated(0x10, 0x10, 0x30));
    assert_eq!(fails, pixels);
    assert_ne!(pixels, 0);
}

/// `ZAlphaByte::Low` (DOSBox Staging): alpha 0xc0 passes; nothing fails and the pixel is
/// the iterated colour.
#[test]
fn z_alpha_low_byte() {
    let (pixel, fails, _) = z_alpha_program(ZAlphaByte::Low);
    assert_eq!((pixel, fails), (rgb565_truncated(0x20, 0x30, 0x40), 0));
}

// --- the texture combine on a one-TMU board: ChainModel ---------------------------------

/// A white RGB565 texel under a `textureMode` whose combine zeroes everything
/// (`tc_zero_other`, `tca_zero_other`, nothing added) on the default one-TMU board.
fn chain_program(chain: ChainModel) -> u16 {
    let texel = TexelProfile {
        chain,
        ..Default::default()
    };
    let mode = TextureMode(TEX_565)
        .with_tc_zero_other(true)
        .with_tca_zero_other(true)
        .0;
    let mut p = white_texture_board(PixelProfile::default(), texel, mode);
    textured_pixel(&mut p, COLOR_PATH_TEXTURE, 0)
}

/// `ChainModel::Full` (spec 5.50; MAME, DOSBox Staging; default): the combine unit
/// outputs zero: black.
#[test]
fn chain_full_runs_the_combine() {
    assert_eq!(chain_program(ChainModel::Full), 0x0000);
}

/// `ChainModel::Box86` (86Box): a single TMU's texel passes with no combine: white.
#[test]
fn chain_box86_skips_the_combine_on_one_tmu() {
    assert_eq!(chain_program(ChainModel::Box86), 0xffff);
}

// --- stipple rotate mode: StippleRotate -------------------------------------------------

/// Rotate-mode stipple (`fbzMode` bit 2, bit 12 clear) with only bit 30 set, on a flat
/// triangle (0, 0), (40, 0), (0, 40) walked left to right. Returns pixels 0..4 of row 2
/// (drawn: the triangle's colour; not drawn: the init's fill) and `fbiPixelsOut`.
fn stipple_program(stipple_rotate: StippleRotate) -> ([u16; 4], u32) {
    let mut p = board(
        PixelProfile {
            stipple_rotate,
            ..Default::default()
        },
        TexelProfile::default(),
    );
    p.write(addr::FBZ_MODE, BASE | 1 << 2);
    p.write(addr::STIPPLE, 1 << 30);
    p.write(addr::NOP_CMD, 1);
    triangle_fixed(&mut p, &Triangle::corner(0xff20_3040));
    (
        std::array::from_fn(|x| p.read_pixel(Buffer::Back, x as u32, 2)),
        p.read(addr::FBI_PIXELS_OUT),
    )
}

const DRAWN: u16 = rgb565_truncated(0x20, 0x30, 0x40);
const FILL: u16 = rgb565_truncated(0x10, 0x10, 0x30);

/// `StippleRotate::PerScanline` (MAME, DOSBox Staging; default): each row starts from
/// the register, so bit 30 reaches bit 31 at the first pixel of every row and 32 pixels
/// later: row `y` is `39 - y` pixels wide (rows 0..=38), so 39 first pixels plus the 33rd
/// pixel of the 7 rows at least 33 wide.
#[test]
fn stipple_rotates_per_scanline() {
    let (row, out) = stipple_program(StippleRotate::PerScanline);
    assert_eq!(row, [DRAWN, FILL, FILL, FILL]);
    assert_eq!(out, 39 + 7);
}

/// `StippleRotate::PerTriangle` (86Box): the first pixel sets bit 31 and its
/// sign-extending shift fills the copy with ones: every pixel of the triangle is drawn.
#[test]
fn stipple_rotates_per_triangle() {
    let (row, out) = stipple_program(StippleRotate::PerTriangle);
    assert_eq!(row, [DRAWN; 4]);
    assert_eq!(out, (1..=39).sum::<u32>());
}

// --- LFB lanes, byte swizzle and Y origin: LfbOrdering ----------------------------------

/// Two LFB writes in ARGB8888 (format 4) straight to the back buffer: (0x10, 0x80, 0xf0)
/// at (4, 4) with the ABGR lane order (bits 10:9 = 1), then the same word at (6, 0) with
/// `lfbMode`'s Y origin at the bottom (bit 13). Returns the pixel at (4, 4), and rows 0
/// and 479 at x = 6.
fn lfb_ordering_program(lfb_ordering: LfbOrdering) -> [u16; 3] {
    let mut p = board(
        PixelProfile {
            lfb_ordering,
            ..Default::default()
        },
        TexelProfile::default(),
    );
    p.write(
        addr::LFB_MODE,
        lfb::format(4) | lfb::WRITE_BACK | lfb::lanes(1),
    );
    p.write(lfb32(4, 4), 0x0010_80f0);
    p.write(
        addr::LFB_MODE,
        lfb::format(4) | lfb::WRITE_BACK | lfb::Y_ORIGIN,
    );
    p.write(lfb32(6, 0), 0x0010_80f0);
    [(4, 4), (6, 0), (6, 479)].map(|(x, y)| p.read_pixel(Buffer::Back, x, y))
}

/// `LfbOrdering::Applied` (spec 5.20; MAME, DOSBox Staging; default): the ABGR word reads
/// blue 0x10, red 0xf0; the flipped write lands on row 479 (the init's swap value).
#[test]
fn lfb_ordering_applied() {
    assert_eq!(
        lfb_ordering_program(LfbOrdering::Applied),
        [
            rgb565_truncated(0xf0, 0x80, 0x10),
            rgb565_truncated(0x10, 0x10, 0x30),
            rgb565_truncated(0x10, 0x80, 0xf0)
        ]
    );
}

/// `LfbOrdering::Ignored` (86Box): the word is ARGB whatever the lanes say, and row 0 is
/// row 0.
#[test]
fn lfb_ordering_ignored() {
    assert_eq!(
        lfb_ordering_program(LfbOrdering::Ignored),
        [
            rgb565_truncated(0x10, 0x80, 0xf0),
            rgb565_truncated(0x10, 0x80, 0xf0),
            rgb565_truncated(0x10, 0x10, 0x30)
        ]
    );
}

// --- iterator clamping: IteratorClamp ---------------------------------------------------

/// Red starts at 250 and climbs 4 per pixel (12.12 `dRdX` = 4.0) from vertex A at
/// (0, 0); dithering is off. Returns red (5 bits) at x = 0, 2 and 4 of row 1: 250, 258
/// (one past 0x100) and 266.
fn clamp_program(iterator_clamp: IteratorClamp) -> [u16; 3] {
    let mut p = board(
        PixelProfile {
            iterator_clamp,
            ..Default::default()
        },
        TexelProfile::default(),
    );
    p.write(addr::FBZ_MODE, BASE);
    p.write(addr::FBZ_COLOR_PATH, 0);
    let t = Triangle::corner(0xff00_0000);
    triangle_fixed(&mut p, &t);
    p.write(addr::START_R, 250 << 12);
    p.write(addr::D_R_DX, 4 << 12);
    p.write(addr::TRIANGLE_CMD, t.area_sign());
    [0, 2, 4].map(|x| p.read_pixel(Buffer::Back, x, 1) >> 11)
}

/// `IteratorClamp::PseudoClamp` (spec 5.16; MAME, DOSBox Staging; default): 258 is
/// 0x102, neither 0x100 nor 0xfff, so it wraps to 2; 266 wraps to 10.
#[test]
fn iterator_pseudo_clamp_wraps() {
    assert_eq!(
        clamp_program(IteratorClamp::PseudoClamp),
        [250 >> 3, 2 >> 3, 10 >> 3]
    );
}

/// `IteratorClamp::Saturate` (86Box): both saturate at 255.
#[test]
fn iterator_saturates() {
    assert_eq!(clamp_program(IteratorClamp::Saturate), [250 >> 3, 31, 31]);
}

// --- FBI graphics reset and the buffers: GraphicsReset ----------------------------------

/// After the init (buffer 0 black, buffer 1 cleared to 0x101030 and back), a swap makes
/// buffer 1 the front. Then `fbiInit0` is written with bit 1 (graphics reset) set and
/// cleared again. Returns the front buffer's pixel at (8, 8) before and after.
fn graphics_reset_program(graphics_reset: GraphicsReset) -> [u16; 2] {
    let mut p = board(
        PixelProfile {
            graphics_reset,
            ..Default::default()
        },
        TexelProfile::default(),
    );
    p.write(addr::SWAPBUFFER_CMD, 0);
    let before = p.read_pixel(Buffer::Front, 8, 8);
    p.write(addr::FBI_INIT0, 0x3);
    p.write(addr::FBI_INIT0, 0x1);
    [before, p.read_pixel(Buffer::Front, 8, 8)]
}

/// `GraphicsReset::KeepsBuffers` (MAME, DOSBox Staging; default): buffer 1 stays the
/// front buffer.
#[test]
fn graphics_reset_keeps_buffers() {
    let fill = rgb565_truncated(0x10, 0x10, 0x30);
    assert_eq!(
        graphics_reset_program(GraphicsReset::KeepsBuffers),
        [fill, fill]
    );
}

/// `GraphicsReset::ResetsBuffers` (86Box): buffer 0, still black, is the front again.
#[test]
fn graphics_reset_resets_buffers() {
    let fill = rgb565_truncated(0x10, 0x10, 0x30);
    assert_eq!(
        graphics_reset_program(GraphicsReset::ResetsBuffers),
        [fill, 0]
    );
}

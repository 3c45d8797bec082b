//! The disputed behaviours: one register program per switch of the accuracy profile
//! (`sst1_board::AccuracyProfile`), run once per choice. Each test shows that the
//! emulator gives exactly what that choice documents. On a real board the same program
//! shows one of the outcomes and settles the dispute; the doc comments say which
//! outcome supports which choice.

use firmware_tests::bits::{alpha, fbz, fog};
use firmware_tests::expect::{blend, dither565, fog_blend, Blend};
use firmware_tests::{
    fastfill, rgb565_truncated, set_clip, triangle_fixed, Buffer, Emulator, Param, Port, Triangle,
};
use pixelfx::blend::{BlendArithmetic, BlendProfile, Dither2x2Blend, SaturateOperand};
use pixelfx::fog::{
    FogBothSources, FogConstantMult, FogDifference, FogIteratedAlpha, FogProfile, FogTableDepth,
};
use pixelfx::profile::{AuxWrite, ClipRightEdge, DitherMatrix2x2, EdgeRounding, WFloatEdges};
use pixelfx::PixelProfile;
use sst1_board::AccuracyProfile;
use sst1_regs::addr;

const BASE: u32 = fbz::CLIP | fbz::RGB_WRITE | fbz::AUX_WRITE | fbz::DRAW_BACK;

fn board(pixel: PixelProfile) -> Emulator {
    Emulator::booted_with(AccuracyProfile {
        pixel,
        ..Default::default()
    })
}

// --- scan conversion: EdgeRounding ----------------------------------------------------

/// A triangle whose left edge lies at x = -0.75: MAME rounds it to -1 (floor), DOSBox
/// Staging to 0 (toward zero). No visible pixel differs; `fbiPixelsIn`, which counts the
/// walked span before clipping, does: 23 against 19 over four rows.
fn edge_rounding_program(pixel: PixelProfile) -> u32 {
    let mut p = board(pixel);
    p.write(addr::NOP_CMD, 1);
    let t = Triangle {
        vertices: [(-12, 0), (160, 0), (-12, 64)],
        ..Triangle::corner(0xffff_ffff)
    };
    triangle_fixed(&mut p, &t);
    p.read(addr::FBI_PIXELS_IN)
}

/// `EdgeRounding::FloorHalfDown` (MAME, default): spans start at -1: 10 + 7 + 4 + 2.
/// A board reading 23 supports this choice.
#[test]
fn edge_rounding_floor() {
    let pixel = PixelProfile {
        edge_rounding: EdgeRounding::FloorHalfDown,
        ..Default::default()
    };
    assert_eq!(edge_rounding_program(pixel), 23);
}

/// `EdgeRounding::TruncHalfDown` (DOSBox Staging): spans start at 0: 9 + 6 + 3 + 1.
/// A board reading 19 supports this choice.
#[test]
fn edge_rounding_trunc() {
    let pixel = PixelProfile {
        edge_rounding: EdgeRounding::TruncHalfDown,
        ..Default::default()
    };
    assert_eq!(edge_rounding_program(pixel), 19);
}

// --- W float edge: WFloatEdges --------------------------------------------------------

/// W = 2^-16 (0x4000 in 2.30) has an all-ones mantissa: the float depth is 0xffff + 1.
/// Read through a W-buffered write of the aux buffer.
fn wfloat_program(pixel: PixelProfile) -> u16 {
    let mut p = board(pixel);
    p.write(
        addr::FBZ_MODE,
        BASE | fbz::DEPTH | fbz::depth_function(7) | fbz::WBUFFER,
    );
    let mut t = Triangle::corner(0xffff_ffff);
    t.w = Param::flat(0x4000);
    triangle_fixed(&mut p, &t);
    p.read_aux(4, 4)
}

/// `WFloatEdges::Dosbox` (default): the +1 saturates; a board reading 0xffff supports it.
#[test]
fn wfloat_edge_dosbox_saturates() {
    let pixel = PixelProfile {
        wfloat: WFloatEdges::Dosbox,
        ..Default::default()
    };
    assert_eq!(wfloat_program(pixel), 0xffff);
}

/// `WFloatEdges::Mame`: the +1 carries out; a board reading 0x0000 supports it.
#[test]
fn wfloat_edge_mame_carries() {
    let pixel = PixelProfile {
        wfloat: WFloatEdges::Mame,
        ..Default::default()
    };
    assert_eq!(wfloat_program(pixel), 0x0000);
}

// --- clip right edge: ClipRightEdge ----------------------------------------------------

/// Clip right = 20 over a triangle that covers columns 0-35 of row 4: is column 19 drawn?
fn clip_right_program(pixel: PixelProfile) -> (u16, u16) {
    let mut p = board(pixel);
    fastfill(&mut p, 0, 0xffff);
    set_clip(&mut p, 0, 20, 0, 480);
    triangle_fixed(&mut p, &Triangle::corner(0xffff_ffff));
    (
        p.read_pixel(Buffer::Back, 18, 4),
        p.read_pixel(Buffer::Back, 19, 4),
    )
}

/// `ClipRightEdge::Exclusive` (spec 5.21, MAME, 86Box; default): column 19 is drawn.
#[test]
fn clip_right_exclusive() {
    let pixel = PixelProfile {
        clip_right: ClipRightEdge::Exclusive,
        ..Default::default()
    };
    assert_eq!(clip_right_program(pixel), (0xffff, 0xffff));
}

/// `ClipRightEdge::DropLastColumn` (DOSBox Staging): column 19 stays empty.
#[test]
fn clip_right_drop_last_column() {
    let pixel = PixelProfile {
        clip_right: ClipRightEdge::DropLastColumn,
        ..Default::default()
    };
    assert_eq!(clip_right_program(pixel), (0xffff, 0));
}

// --- aux writes: AuxWrite --------------------------------------------------------------

/// The aux mask set, depth buffering and alpha planes off: does the pixel's Z (0x1234)
/// reach the aux buffer (0xffff after the init)?
fn aux_write_program(pixel: PixelProfile) -> u16 {
    let mut p = board(pixel);
    let mut t = Triangle::corner(0xffff_ffff);
    t.z = Param::flat(0x1234 << 12);
    triangle_fixed(&mut p, &t);
    p.read_aux(4, 4)
}

/// `AuxWrite::MaskOnly` (spec 5.19 bit 10, MAME, DOSBox Staging; default): written.
#[test]
fn aux_write_mask_only() {
    let pixel = PixelProfile {
        aux_write: AuxWrite::MaskOnly,
        ..Default::default()
    };
    assert_eq!(aux_write_program(pixel), 0x1234);
}

/// `AuxWrite::MaskAndDepthOrAlphaPlanes` (86Box): not written.
#[test]
fn aux_write_needs_depth_or_alpha_planes() {
    let pixel = PixelProfile {
        aux_write: AuxWrite::MaskAndDepthOrAlphaPlanes,
        ..Default::default()
    };
    assert_eq!(aux_write_program(pixel), 0xffff);
}

// --- 2x2 dither matrix: DitherMatrix2x2 -------------------------------------------------

/// A flat (0x85, 0x41, 0x3c) with the 2x2 dither: the 2x2 cell at (4..6, 4..6).
fn dither_2x2_program(pixel: PixelProfile) -> [[u16; 2]; 2] {
    let mut p = board(pixel);
    p.write(addr::FBZ_MODE, BASE | fbz::DITHER | fbz::DITHER_2X2);
    triangle_fixed(&mut p, &Triangle::corner(0xff85_413c));
    std::array::from_fn(|y| {
        std::array::from_fn(|x| p.read_pixel(Buffer::Back, 4 + x as u32, 4 + y as u32))
    })
}

fn cell_2x2(m: [[u32; 2]; 2]) -> [[u16; 2]; 2] {
    m.map(|row| row.map(|d| dither565(0x85, 0x41, 0x3c, d)))
}

/// `DitherMatrix2x2::Classic` (DOSBox Staging, 86Box; default): 2, 10 / 14, 6.
#[test]
fn dither_2x2_classic() {
    let pixel = PixelProfile {
        dither_2x2: DitherMatrix2x2::Classic,
        ..Default::default()
    };
    assert_eq!(dither_2x2_program(pixel), cell_2x2([[2, 10], [14, 6]]));
}

/// `DitherMatrix2x2::Mame` (MAME, from an arcade board's memory test): 8, 10 / 11, 9.
#[test]
fn dither_2x2_mame() {
    let pixel = PixelProfile {
        dither_2x2: DitherMatrix2x2::Mame,
        ..Default::default()
    };
    let got = dither_2x2_program(pixel);
    assert_eq!(got, cell_2x2([[8, 10], [11, 9]]));
    assert_ne!(got, cell_2x2([[2, 10], [14, 6]]));
}

// --- fog -------------------------------------------------------------------------------

/// Draw flat `cin` with `fogMode`, `fogColor`, Z, W (2.30) and `fbzMode` extra bits;
/// read (4, 4).
fn fog_program(
    profile: FogProfile,
    mode: u32,
    fog_colour: [i32; 3],
    argb: u32,
    z: i32,
    w: i32,
) -> u16 {
    let mut p = board(PixelProfile {
        fog: profile,
        ..Default::default()
    });
    p.write(addr::FOG_MODE, mode);
    let [r, g, b] = fog_colour.map(|c| c as u32);
    p.write(addr::FOG_COLOR, r << 16 | g << 8 | b);
    p.write(addr::FOG_TABLE + 9 * 4, 0x6010_4080); // entries 18 (0x40, +0x80), 19 (0x60)
    let mut t = Triangle::corner(argb);
    t.z = Param::flat(z << 12);
    t.w = Param::flat(w);
    triangle_fixed(&mut p, &t);
    p.read_pixel(Buffer::Back, 4, 4)
}

fn fogged(cin: [i32; 3], fog: [i32; 3], afog: i32) -> u16 {
    let [r, g, b] = [0, 1, 2].map(|i| fog_blend(cin[i], fog[i], afog));
    rgb565_truncated(r, g, b)
}

/// Fog darker than the colour: (200, 100, 60) towards (40, 20, 10) at Afog 0x80 (Z).
fn fog_difference_program(difference: FogDifference) -> u16 {
    let profile = FogProfile {
        difference,
        ..Default::default()
    };
    fog_program(
        profile,
        fog::ENABLE | fog::Z,
        [40, 20, 10],
        0xffc8_643c,
        0x8000,
        0,
    )
}

/// `FogDifference::Signed` (DOSBox Staging, 86Box, spec's signed 9-bit operand;
/// default): the colour darkens to (119, 59, 34).
#[test]
fn fog_difference_signed() {
    let want = fogged([200, 100, 60], [40, 20, 10], 0x80);
    assert_eq!(want, rgb565_truncated(119, 59, 34));
    assert_eq!(fog_difference_program(FogDifference::Signed), want);
}

/// `FogDifference::ClampedToByte` (MAME): the negative difference is dropped; the
/// colour stays (200, 100, 60).
#[test]
fn fog_difference_clamped() {
    assert_eq!(
        fog_difference_program(FogDifference::ClampedToByte),
        rgb565_truncated(200, 100, 60)
    );
}

/// Fog from iterated alpha (`fogMode` bit 3) with alpha 0xf1, fog brighter than colour.
fn fog_alpha_program(iterated_alpha: FogIteratedAlpha) -> u16 {
    let profile = FogProfile {
        iterated_alpha,
        ..Default::default()
    };
    fog_program(
        profile,
        fog::ENABLE | fog::ALPHA,
        [240, 200, 100],
        0xf128_643c,
        0,
        0,
    )
}

/// `FogIteratedAlpha::Clamped` (spec 5.17 "integer part of the iterated alpha",
/// DOSBox Staging, 86Box; default): Afog = 0xf1.
#[test]
fn fog_iterated_alpha_clamped() {
    let want = fogged([0x28, 0x64, 0x3c], [240, 200, 100], 0xf1);
    assert_eq!(fog_alpha_program(FogIteratedAlpha::Clamped), want);
}

/// `FogIteratedAlpha::MameLowByte` (MAME): Afog = 0, the colour is almost unchanged.
#[test]
fn fog_iterated_alpha_mame_low_byte() {
    let want = fogged([0x28, 0x64, 0x3c], [240, 200, 100], 0);
    assert_eq!(want, rgb565_truncated(0x28, 0x64, 0x3c));
    assert_eq!(fog_alpha_program(FogIteratedAlpha::MameLowByte), want);
}

/// Constant fog with `fogmult` (`fogMode` = 0x25): colour (40, 100, 60), fog (20, 30, 40).
fn fog_constant_mult_program(constant_mult: FogConstantMult) -> u16 {
    let profile = FogProfile {
        constant_mult,
        ..Default::default()
    };
    let mode = fog::ENABLE | fog::CONSTANT | fog::MULT;
    fog_program(profile, mode, [20, 30, 40], 0xff28_643c, 0, 0)
}

/// `FogConstantMult::FogColor` (MAME, DOSBox Staging; spec table `Cout = Afog*Cfog`;
/// default): the output is the fog colour.
#[test]
fn fog_constant_mult_gives_fog_colour() {
    assert_eq!(
        fog_constant_mult_program(FogConstantMult::FogColor),
        rgb565_truncated(20, 30, 40)
    );
}

/// `FogConstantMult::AddToColor` (86Box): the fog colour is added regardless.
#[test]
fn fog_constant_mult_adds() {
    assert_eq!(
        fog_constant_mult_program(FogConstantMult::AddToColor),
        rgb565_truncated(60, 130, 100)
    );
}

/// Table fog at W = 0x02c00000 (float depth 0x4a00) with depth bias 0x0200 enabled.
fn fog_table_depth_program(table_depth: FogTableDepth) -> u16 {
    let profile = FogProfile {
        table_depth,
        ..Default::default()
    };
    let mut p = board(PixelProfile {
        fog: profile,
        ..Default::default()
    });
    p.write(addr::FBZ_MODE, BASE | fbz::DEPTH_BIAS);
    p.write(addr::ZA_COLOR, 0x0200);
    p.write(addr::FOG_MODE, fog::ENABLE);
    p.write(addr::FOG_COLOR, 0x00f0_c864);
    p.write(addr::FOG_TABLE + 9 * 4, 0x6010_4080);
    let mut t = Triangle::corner(0xff28_643c);
    t.w = Param::flat(0x02c0_0000);
    triangle_fixed(&mut p, &t);
    p.read_pixel(Buffer::Back, 4, 4)
}

/// `FogTableDepth::Wfloat` (DOSBox Staging, 86Box; default): index 0x4a00, Afog 0x50.
#[test]
fn fog_table_depth_unbiased() {
    let want = fogged([40, 100, 60], [240, 200, 100], 0x50);
    assert_eq!(fog_table_depth_program(FogTableDepth::Wfloat), want);
}

/// `FogTableDepth::BiasedWfloat` (MAME): index 0x4a00 + 0x200 = 0x4c00, Afog 0x60.
#[test]
fn fog_table_depth_biased() {
    let want = fogged([40, 100, 60], [240, 200, 100], 0x60);
    assert_eq!(fog_table_depth_program(FogTableDepth::BiasedWfloat), want);
}

/// `fogMode` bits 4:3 both set, Z = 0x8000, W = 64.0 (through `fstartW`).
fn fog_both_program(both_sources: FogBothSources) -> u16 {
    let profile = FogProfile {
        both_sources,
        ..Default::default()
    };
    let mut p = board(PixelProfile {
        fog: profile,
        ..Default::default()
    });
    p.write(addr::FOG_MODE, fog::ENABLE | fog::ALPHA | fog::Z);
    p.write(addr::FOG_COLOR, 0x00f0_c864);
    let mut t = Triangle::corner(0xff28_643c);
    t.z = Param::flat(0x8000 << 12);
    triangle_fixed(&mut p, &t);
    p.write(addr::F_START_W, 64.0f32.to_bits());
    p.write(addr::TRIANGLE_CMD, t.area_sign());
    p.read_pixel(Buffer::Back, 4, 4)
}

/// `FogBothSources::IteratedW` (all three references; default): Afog = W's integer
/// byte, 0x40.
#[test]
fn fog_both_sources_iterated_w() {
    let want = fogged([40, 100, 60], [240, 200, 100], 0x40);
    assert_eq!(fog_both_program(FogBothSources::IteratedW), want);
}

/// `FogBothSources::IteratedZ` (spec 5.17: "bit(4) takes precedence"): Afog = 0x80.
/// A board showing this supports the spec against all three references.
#[test]
fn fog_both_sources_iterated_z() {
    let want = fogged([40, 100, 60], [240, 200, 100], 0x80);
    assert_eq!(fog_both_program(FogBothSources::IteratedZ), want);
}

// --- alpha blending: BlendArithmetic, SaturateOperand ----------------------------------

/// (200, 100, 50) at alpha `alpha` blended with ASRC_ALPHA / AOMSRC_ALPHA over 0x8410
/// with `fbzMode` bits `fbz_extra` added; pixel (4, 4).
fn blended_pixel(blend: BlendProfile, fbz_extra: u32, alpha: u32) -> u16 {
    let mut p = board(PixelProfile {
        blend,
        ..Default::default()
    });
    fastfill(&mut p, 0x0080_8080, 0xffff);
    p.write(addr::FBZ_MODE, BASE | fbz_extra);
    p.write(addr::ALPHA_MODE, alpha::BLEND | alpha::rgb_factors(1, 5));
    triangle_fixed(&mut p, &Triangle::corner(alpha << 24 | 0x00c8_6432));
    p.read_pixel(Buffer::Back, 4, 4)
}

/// [`blended_pixel`] at alpha 0x30, undithered: the three arithmetics give three different pixels
/// (0x93ee, 0x8bce, 0x93ce).
fn blend_program(arithmetic: BlendArithmetic) -> u16 {
    let blend = BlendProfile {
        arithmetic,
        ..Default::default()
    };
    blended_pixel(blend, 0, 0x30)
}

fn blend_expected(a: Blend) -> u16 {
    let [r, g, b] = blend(a, [200, 100, 50], 0x30, 0x8410, (1, 5));
    rgb565_truncated(r, g, b)
}

/// `BlendArithmetic::PerProduct` (the hardware model's): replicated destination,
/// `x+1` / `256-x`, each product `>> 8`.
#[test]
fn blend_arithmetic_per_product() {
    assert_eq!(blend_expected(Blend::PerProduct), 0x93ee);
    assert_eq!(blend_program(BlendArithmetic::PerProduct), 0x93ee);
    assert_eq!(blended_pixel(BlendProfile::default(), 0, 0x30), 0x93ee);
}

/// `BlendArithmetic::Mame`: as `PerProduct`, but the sum of the products `>> 8` once. At
/// alpha 0x30 both give 0x93ee; at 0x32 they differ in green: 0x93ee against
/// `PerProduct`'s 0x93ce.
#[test]
fn blend_arithmetic_mame() {
    assert_eq!(blend_expected(Blend::Mame), 0x93ee);
    assert_eq!(blend_program(BlendArithmetic::Mame), 0x93ee);
    let at_0x32 = |arithmetic| {
        let blend = BlendProfile {
            arithmetic,
            ..Default::default()
        };
        blended_pixel(blend, 0, 0x32)
    };
    assert_eq!(at_0x32(BlendArithmetic::Mame), 0x93ee);
    assert_eq!(at_0x32(BlendArithmetic::PerProduct), 0x93ce);
}

/// `BlendArithmetic::Dosbox`: zero-filled destination, otherwise as MAME.
#[test]
fn blend_arithmetic_dosbox() {
    assert_eq!(blend_expected(Blend::Dosbox), 0x8bce);
    assert_eq!(blend_program(BlendArithmetic::Dosbox), 0x8bce);
}

/// `BlendArithmetic::Exact255` (86Box): factors `x` / `255-x`, each product `/ 255`.
#[test]
fn blend_arithmetic_exact255() {
    assert_eq!(blend_expected(Blend::Box86), 0x93ce);
    assert_eq!(blend_program(BlendArithmetic::Exact255), 0x93ce);
}

/// `blend_program`'s blend with dithering on, pixel (4, 4): with the 2x2 dither (classic
/// entry 2) or the 4x4 dither (entry 0). MAME's arithmetic gives (145, 124, 116), DOSBox
/// Staging's (142, 123, 113): blue dithers to 14 and 13.
fn dither_2x2_blend_program(dither_2x2: Dither2x2Blend, fbz_dither: u32) -> u16 {
    let blend = BlendProfile {
        dither_2x2,
        ..Default::default()
    };
    blended_pixel(blend, fbz::DITHER | fbz_dither, 0x30)
}

fn dithered_blend(a: Blend, d: u32) -> u16 {
    let [r, g, b] = blend(a, [200, 100, 50], 0x30, 0x8410, (1, 5));
    dither565(r, g, b, d)
}

/// `Dither2x2Blend::ZeroFill` (default): 2x2-dithered destinations are widened by zero
/// fill, which with `PerProduct` is DOSBox Staging's arithmetic; 4x4-dithered ones keep
/// `arithmetic`'s widening.
#[test]
fn dither_2x2_blend_zero_fill() {
    assert_eq!(dithered_blend(Blend::Dosbox, 2), 0x8bcd);
    assert_eq!(
        dither_2x2_blend_program(Dither2x2Blend::ZeroFill, fbz::DITHER_2X2),
        0x8bcd
    );
    assert_eq!(dithered_blend(Blend::PerProduct, 0), 0x8bce);
    assert_eq!(
        dither_2x2_blend_program(Dither2x2Blend::ZeroFill, 0),
        0x8bce
    );
}

/// `Dither2x2Blend::SameAsArithmetic`: every pixel is widened as `arithmetic` widens it.
#[test]
fn dither_2x2_blend_same_as_arithmetic() {
    assert_eq!(dithered_blend(Blend::PerProduct, 2), 0x8bce);
    assert_eq!(
        dither_2x2_blend_program(Dither2x2Blend::SameAsArithmetic, fbz::DITHER_2X2),
        0x8bce
    );
}

/// ASATURATE / AZERO with alpha planes (destination alpha 0x30), source alpha 0x60:
/// factor min(0x60, 256 - 0x30) + 1 = 97 scales either the source or the destination.
fn saturate_program(saturate: SaturateOperand) -> u16 {
    let blend_profile = BlendProfile {
        saturate,
        ..Default::default()
    };
    let mut p = board(PixelProfile {
        blend: blend_profile,
        ..Default::default()
    });
    p.write(addr::FBZ_MODE, BASE | fbz::ALPHA_PLANES);
    fastfill(&mut p, 0x0080_8080, 0x30);
    p.write(addr::ALPHA_MODE, alpha::BLEND | alpha::rgb_factors(15, 0));
    triangle_fixed(&mut p, &Triangle::corner(0x60c8_6432));
    p.read_pixel(Buffer::Back, 4, 4)
}

/// `SaturateOperand::Source` (spec 5.18.2, MAME, DOSBox Staging; default): the source
/// is scaled: (200, 100, 50) * 97 >> 8 = (75, 37, 18).
#[test]
fn blend_saturate_scales_source() {
    assert_eq!(
        saturate_program(SaturateOperand::Source),
        rgb565_truncated(75, 37, 18)
    );
}

/// `SaturateOperand::Destination` (86Box): the destination (132, 130, 132 widened) is
/// scaled: (50, 49, 50).
#[test]
fn blend_saturate_scales_destination() {
    assert_eq!(
        saturate_program(SaturateOperand::Destination),
        rgb565_truncated(50, 49, 50)
    );
}

//! The three reference emulators as accuracy profiles, and the per-pixel two-of-three
//! vote over their outputs.
//!
//! Every behaviour on which MAME, DOSBox Staging and 86Box disagree is a switch of
//! [`AccuracyProfile`]. Setting every switch to one emulator's choice gives that
//! emulator's profile ([`Reference::profile`]); replaying a trace with it reproduces the
//! emulator's golden dumps (`crates/trace/tests/conformance.rs` checks this dump by dump,
//! and lists where it does not yet). The conformance pass rule of
//! `traces/conformance/README.md` asks for the two-of-three majority of the goldens on
//! every pixel, so replaying a trace once per reference and voting per pixel
//! ([`vote`]) meets it wherever the three profiles are faithful, including where the
//! references reach a pixel through different histories (an earlier pass blended
//! differently), which no single profile can follow.
//!
//! This is a model of the references, not of the chip: where they disagree nobody has
//! said which one the hardware matches. `AccuracyProfile::default()` remains the single
//! pipeline we believe closest to the hardware, for running programs.

use pixelfx::blend::{BlendArithmetic, BlendProfile, Dither2x2Blend, SaturateOperand};
use pixelfx::fog::{
    FogBothSources, FogConstantMult, FogDifference, FogIteratedAlpha, FogProfile, FogTableDepth,
};
use pixelfx::profile::{
    AlphaTestInput, AuxWrite, ClipRightEdge, DitherMatrix2x2, EdgeRounding, FastfillDither,
    FloatOverflow, GraphicsReset, IteratorClamp, LfbOrdering, LfbWordSwap, OverrideTexel,
    ParamOrigin, PatternRow, StippleRotate, SubpixelZ, WFloatEdges, ZAlphaByte,
};
use texelfx::{
    A8Expansion, BilinearPrecision, ChainModel, CoordRounding, DecalInvert, DetailRule,
    FilterSelect, LodCalc, LodDither, LodZeroFrac, NccQ2Write, NccUpdate, PerspDivide, Rgb332Blue,
    TextureCacheKey, Trilinear,
};

use crate::{AccuracyProfile, PixelProfile, TexelProfile};

/// One of the three reference emulators whose goldens define conformance.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Reference {
    /// MAME (`src/devices/video/voodoo*`).
    Mame,
    /// DOSBox Staging (`src/hardware/voodoo.cpp`).
    DosboxStaging,
    /// 86Box (`src/video/vid_voodoo_*.c`).
    Box86,
}

impl Reference {
    /// All three, in the order the goldens are named and the vote breaks ties (MAME
    /// first: the conformance README calls it the most hardware-checked).
    pub const ALL: [Reference; 3] = [Reference::Mame, Reference::DosboxStaging, Reference::Box86];

    /// The golden folder name under `traces/*/golden/`.
    pub fn golden_dir(self) -> &'static str {
        match self {
            Reference::Mame => "mame",
            Reference::DosboxStaging => "dosbox-staging",
            Reference::Box86 => "86box",
        }
    }

    /// The reference whose golden folder (and `--model` name) is `name`.
    pub fn from_name(name: &str) -> Option<Reference> {
        Reference::ALL.into_iter().find(|r| r.golden_dir() == name)
    }

    /// Every switch set to what this emulator does (each switch's documentation names
    /// who does what). One line per switch, in the order MAME, DOSBox Staging, 86Box; the
    /// literals name every field, so a new switch cannot be left out.
    pub const fn profile(self) -> AccuracyProfile {
        let r = self;
        AccuracyProfile {
            pixel: PixelProfile {
                edge_rounding: r.pick(
                    EdgeRounding::FloorHalfDown,
                    EdgeRounding::TruncHalfDown,
                    EdgeRounding::Box86Fixed,
                ),
                wfloat: r.pick(WFloatEdges::Mame, WFloatEdges::Dosbox, WFloatEdges::Box86),
                clip_right: r.pick(
                    ClipRightEdge::Exclusive,
                    ClipRightEdge::DropLastColumn,
                    ClipRightEdge::Exclusive,
                ),
                aux_write: r.pick(
                    AuxWrite::MaskOnly,
                    AuxWrite::MaskOnly,
                    AuxWrite::MaskAndDepthOrAlphaPlanes,
                ),
                pattern_row: r.pick(PatternRow::Screen, PatternRow::Raster, PatternRow::Screen),
                lfb_word_swap: r.pick(LfbWordSwap::Always, LfbWordSwap::Always, LfbWordSwap::Never),
                lfb_ordering: r.pick(
                    LfbOrdering::Applied,
                    LfbOrdering::Applied,
                    LfbOrdering::Ignored,
                ),
                float_overflow: r.pick(
                    FloatOverflow::Wrap,
                    FloatOverflow::Saturate,
                    FloatOverflow::Indefinite,
                ),
                subpixel_z: r.pick(SubpixelZ::Wrap32, SubpixelZ::Wide64, SubpixelZ::Wrap32),
                param_origin: r.pick(
                    ParamOrigin::VertexPixel,
                    ParamOrigin::VertexPixel,
                    ParamOrigin::RoundedVertex,
                ),
                alpha_test_input: r.pick(
                    AlphaTestInput::Combined,
                    AlphaTestInput::AOther,
                    AlphaTestInput::Combined,
                ),
                dither_2x2: r.pick(
                    DitherMatrix2x2::Mame,
                    DitherMatrix2x2::Classic,
                    DitherMatrix2x2::Classic,
                ),
                fastfill_dither: r.pick(
                    FastfillDither::Dithered,
                    FastfillDither::Dithered,
                    FastfillDither::Truncated,
                ),
                override_texel: r.pick(
                    OverrideTexel::ZeroWhenUnused,
                    OverrideTexel::Texel,
                    OverrideTexel::Texel,
                ),
                z_alpha: r.pick(ZAlphaByte::High, ZAlphaByte::Low, ZAlphaByte::High),
                stipple_rotate: r.pick(
                    StippleRotate::PerScanline,
                    StippleRotate::PerScanline,
                    StippleRotate::PerTriangle,
                ),
                iterator_clamp: r.pick(
                    IteratorClamp::PseudoClamp,
                    IteratorClamp::PseudoClamp,
                    IteratorClamp::Saturate,
                ),
                graphics_reset: r.pick(
                    GraphicsReset::KeepsBuffers,
                    GraphicsReset::KeepsBuffers,
                    GraphicsReset::ResetsBuffers,
                ),
                fog: FogProfile {
                    difference: r.pick(
                        FogDifference::ClampedToByte,
                        FogDifference::Signed,
                        FogDifference::Signed,
                    ),
                    iterated_alpha: r.pick(
                        FogIteratedAlpha::MameLowByte,
                        FogIteratedAlpha::Clamped,
                        FogIteratedAlpha::Clamped,
                    ),
                    constant_mult: r.pick(
                        FogConstantMult::FogColor,
                        FogConstantMult::FogColor,
                        FogConstantMult::AddToColor,
                    ),
                    table_depth: r.pick(
                        FogTableDepth::BiasedWfloat,
                        FogTableDepth::Wfloat,
                        FogTableDepth::Wfloat,
                    ),
                    both_sources: FogBothSources::IteratedW,
                },
                blend: BlendProfile {
                    arithmetic: r.pick(
                        BlendArithmetic::Mame,
                        BlendArithmetic::Dosbox,
                        BlendArithmetic::Exact255,
                    ),
                    saturate: r.pick(
                        SaturateOperand::Source,
                        SaturateOperand::Source,
                        SaturateOperand::Destination,
                    ),
                    // Each reference's own arithmetic for 2x2-dithered pixels too.
                    dither_2x2: Dither2x2Blend::SameAsArithmetic,
                },
            },
            texel: TexelProfile {
                lod: r.pick(LodCalc::Mame, LodCalc::Dosbox, LodCalc::Box86),
                lod_dither: r.pick(LodDither::Matrix4x4, LodDither::Matrix4x4, LodDither::Off),
                bilinear: BilinearPrecision::Bits4,
                a8: A8Expansion::AlphaInRgb,
                rgb332_blue: r.pick(
                    Rgb332Blue::Replicated,
                    Rgb332Blue::DosboxTable,
                    Rgb332Blue::Replicated,
                ),
                filter_select: r.pick(
                    FilterSelect::ByLod,
                    FilterSelect::ByLod,
                    FilterSelect::EitherBit,
                ),
                detail: r.pick(
                    DetailRule::WholeLodsCut8,
                    DetailRule::WholeLods,
                    DetailRule::IntegerLod,
                ),
                chain: r.pick(ChainModel::Full, ChainModel::Full, ChainModel::Box86),
                ncc_q2: r.pick(NccQ2Write::Q2, NccQ2Write::Q2, NccQ2Write::IntoI2),
                texture_cache: r.pick(
                    TextureCacheKey::Exact,
                    TextureCacheKey::Exact,
                    TextureCacheKey::Box86,
                ),
                ncc_update: r.pick(
                    NccUpdate::Immediate,
                    NccUpdate::OnTextureRegWrite,
                    NccUpdate::Immediate,
                ),
                trilinear: r.pick(Trilinear::Ignored, Trilinear::Ignored, Trilinear::Spec),
                lod_zerofrac: LodZeroFrac::Ignored,
                coord_rounding: r.pick(
                    CoordRounding::TowardZero,
                    CoordRounding::Floor,
                    CoordRounding::Floor,
                ),
                decal_invert: r.pick(
                    DecalInvert::Ignored,
                    DecalInvert::Applied,
                    DecalInvert::Ignored,
                ),
                persp_divide: r.pick(
                    PerspDivide::Double,
                    PerspDivide::DosboxReciprocal,
                    PerspDivide::Box86,
                ),
            },
        }
    }

    /// The argument that stands for this emulator.
    const fn pick<T: Copy>(self, mame: T, dosbox: T, box86: T) -> T {
        match self {
            Reference::Mame => mame,
            Reference::DosboxStaging => dosbox,
            Reference::Box86 => box86,
        }
    }
}

/// The conformance pass rule applied to three buffers of the same size, pixel by
/// pixel: the value two of them hold, or the first's (MAME's, in [`Reference::ALL`]
/// order) where all three differ. The result has the length of the shortest.
pub fn vote(first: &[u16], second: &[u16], third: &[u16]) -> Vec<u16> {
    first
        .iter()
        .zip(second)
        .zip(third)
        .map(|((&a, &b), &c)| if b == c { b } else { a })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vote_takes_two_of_three_and_the_first_when_all_differ() {
        let a = [1, 1, 1, 7, 5];
        let b = [1, 2, 3, 4, 5];
        let c = [1, 1, 3, 4, 6];
        // all agree; a = c; b = c; b = c against a; a = b; all differ (a).
        assert_eq!(vote(&a, &b, &c), vec![1, 1, 3, 4, 5]);
        assert_eq!(vote(&[9, 8], &[7, 6], &[5, 4]), vec![9, 8]);
        assert_eq!(vote(&[1, 2, 3], &[1], &[1, 2]), vec![1]);
    }

    #[test]
    fn profiles_differ_where_the_references_do() {
        let [m, d, b] = Reference::ALL.map(Reference::profile);
        assert_eq!(m.texel.persp_divide, PerspDivide::Double);
        assert_eq!(d.texel.persp_divide, PerspDivide::DosboxReciprocal);
        assert_eq!(b.texel.persp_divide, PerspDivide::Box86);
        assert_eq!(m.pixel.blend.arithmetic, BlendArithmetic::Mame);
        assert_eq!(d.pixel.pattern_row, PatternRow::Raster);
        assert_eq!(b.pixel.aux_write, AuxWrite::MaskAndDepthOrAlphaPlanes);
        // Each reference widens 2x2-dithered destinations as its own arithmetic does.
        for p in [m, d, b] {
            assert_eq!(p.pixel.blend.dither_2x2, Dither2x2Blend::SameAsArithmetic);
        }
    }
}

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

use pixelfx::blend::{BlendArithmetic, Dither2x2Blend, SaturateOperand};
use pixelfx::fog::{
    FogBothSources, FogConstantMult, FogDifference, FogIteratedAlpha, FogTableDepth,
};
use pixelfx::profile::{
    AlphaTestInput, AuxWrite, ClipRightEdge, DitherMatrix2x2, EdgeRounding, FastfillDither,
    FloatOverflow, LfbWordSwap, ParamOrigin, PatternRow, SubpixelZ, WFloatEdges,
};
use texelfx::{
    CoordRounding, DecalInvert, FilterSelect, LodCalc, LodDither, NccUpdate, PerspDivide,
    Rgb332Blue, Trilinear,
};

use crate::AccuracyProfile;

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

    /// Every switch set to what this emulator does (each switch's documentation names
    /// who does what). Switches no reference disagrees on keep their defaults.
    pub fn profile(self) -> AccuracyProfile {
        let mut p = AccuracyProfile::default();
        let (px, tx) = (&mut p.pixel, &mut p.texel);
        match self {
            Reference::Mame => {
                px.edge_rounding = EdgeRounding::FloorHalfDown;
                px.wfloat = WFloatEdges::Mame;
                px.clip_right = ClipRightEdge::Exclusive;
                px.aux_write = AuxWrite::MaskOnly;
                px.pattern_row = PatternRow::Screen;
                px.lfb_word_swap = LfbWordSwap::Always;
                px.float_overflow = FloatOverflow::Wrap;
                px.subpixel_z = SubpixelZ::Wrap32;
                px.param_origin = ParamOrigin::VertexPixel;
                px.alpha_test_input = AlphaTestInput::Combined;
                px.dither_2x2 = DitherMatrix2x2::Mame;
                px.fastfill_dither = FastfillDither::Dithered;
                px.fog.difference = FogDifference::ClampedToByte;
                px.fog.iterated_alpha = FogIteratedAlpha::MameLowByte;
                px.fog.constant_mult = FogConstantMult::FogColor;
                px.fog.table_depth = FogTableDepth::BiasedWfloat;
                px.fog.both_sources = FogBothSources::IteratedW;
                px.blend.arithmetic = BlendArithmetic::Mame;
                px.blend.saturate = SaturateOperand::Source;
                px.blend.dither_2x2 = Dither2x2Blend::SameAsArithmetic;
                tx.lod = LodCalc::Mame;
                tx.lod_dither = LodDither::Matrix4x4;
                tx.rgb332_blue = Rgb332Blue::Replicated;
                tx.filter_select = FilterSelect::ByLod;
                tx.ncc_update = NccUpdate::Immediate;
                tx.trilinear = Trilinear::Ignored;
                tx.coord_rounding = CoordRounding::TowardZero;
                tx.decal_invert = DecalInvert::Ignored;
                tx.persp_divide = PerspDivide::Double;
            }
            Reference::DosboxStaging => {
                px.edge_rounding = EdgeRounding::TruncHalfDown;
                px.wfloat = WFloatEdges::Dosbox;
                px.clip_right = ClipRightEdge::DropLastColumn;
                px.aux_write = AuxWrite::MaskOnly;
                px.pattern_row = PatternRow::Raster;
                px.lfb_word_swap = LfbWordSwap::Always;
                px.float_overflow = FloatOverflow::Saturate;
                px.subpixel_z = SubpixelZ::Wide64;
                px.param_origin = ParamOrigin::VertexPixel;
                px.alpha_test_input = AlphaTestInput::AOther;
                px.dither_2x2 = DitherMatrix2x2::Classic;
                px.fastfill_dither = FastfillDither::Dithered;
                px.fog.difference = FogDifference::Signed;
                px.fog.iterated_alpha = FogIteratedAlpha::Clamped;
                px.fog.constant_mult = FogConstantMult::FogColor;
                px.fog.table_depth = FogTableDepth::Wfloat;
                px.fog.both_sources = FogBothSources::IteratedW;
                px.blend.arithmetic = BlendArithmetic::Dosbox;
                px.blend.saturate = SaturateOperand::Source;
                px.blend.dither_2x2 = Dither2x2Blend::SameAsArithmetic;
                tx.lod = LodCalc::Dosbox;
                tx.lod_dither = LodDither::Matrix4x4;
                tx.rgb332_blue = Rgb332Blue::DosboxTable;
                tx.filter_select = FilterSelect::ByLod;
                tx.ncc_update = NccUpdate::OnTextureRegWrite;
                tx.trilinear = Trilinear::Ignored;
                tx.coord_rounding = CoordRounding::Floor;
                tx.decal_invert = DecalInvert::Applied;
                tx.persp_divide = PerspDivide::DosboxReciprocal;
            }
            Reference::Box86 => {
                // UNVERIFIED: 86Box's W-to-float edges are not modelled as their own
                // choice; the default stands in for it.
                px.edge_rounding = EdgeRounding::Box86Fixed;
                px.clip_right = ClipRightEdge::Exclusive;
                px.aux_write = AuxWrite::MaskAndDepthOrAlphaPlanes;
                px.pattern_row = PatternRow::Screen;
                px.lfb_word_swap = LfbWordSwap::SpecIgnoredFor32Bit;
                px.float_overflow = FloatOverflow::Indefinite;
                px.subpixel_z = SubpixelZ::Wrap32;
                px.param_origin = ParamOrigin::RoundedVertex;
                px.alpha_test_input = AlphaTestInput::Combined;
                px.dither_2x2 = DitherMatrix2x2::Classic;
                px.fastfill_dither = FastfillDither::Truncated;
                px.fog.difference = FogDifference::Signed;
                px.fog.iterated_alpha = FogIteratedAlpha::Clamped;
                px.fog.constant_mult = FogConstantMult::AddToColor;
                px.fog.table_depth = FogTableDepth::Wfloat;
                px.fog.both_sources = FogBothSources::IteratedW;
                px.blend.arithmetic = BlendArithmetic::Exact255;
                px.blend.saturate = SaturateOperand::Destination;
                px.blend.dither_2x2 = Dither2x2Blend::SameAsArithmetic;
                tx.lod = LodCalc::Box86;
                tx.lod_dither = LodDither::Off;
                tx.rgb332_blue = Rgb332Blue::Replicated;
                tx.filter_select = FilterSelect::EitherBit;
                tx.ncc_update = NccUpdate::Immediate;
                tx.trilinear = Trilinear::Spec;
                tx.coord_rounding = CoordRounding::Floor;
                tx.decal_invert = DecalInvert::Ignored;
                tx.persp_divide = PerspDivide::Box86;
            }
        }
        p
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
        // No reference votes: each profile is one emulator's arithmetic.
        for p in [m, d, b] {
            assert_ne!(p.pixel.blend.arithmetic, BlendArithmetic::Majority);
        }
    }
}

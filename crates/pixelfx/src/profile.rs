//! The accuracy profile: one named switch for every behaviour on which the reference
//! emulators (MAME, DOSBox Staging, 86Box) disagree. `Default` is the behaviour we
//! believe the hardware has; docs/accuracy.md lists the evidence for each default.

use serde::{Deserialize, Serialize};

pub use crate::iter::{IteratorClamp, WFloatEdges};
pub use crate::params::{FloatOverflow, ParamOrigin, SubpixelZ};
pub use crate::setup::EdgeRounding;
pub use sst1_dither::DitherMatrix2x2;

/// Where the right clip edge lies.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum ClipRightEdge {
    /// Pixels with `x < clipRight` are drawn (spec 5.21: exclusive of clipRight; MAME, 86Box).
    #[default]
    Exclusive,
    /// Also drop the column `clipRight - 1` (DOSBox Staging's off-by-one).
    DropLastColumn,
}

/// When a rendered pixel writes the aux (depth/alpha) buffer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum AuxWrite {
    /// Whenever `fbzMode.aux_buffer_mask` is set (spec 5.19 bit 10; MAME, DOSBox Staging).
    #[default]
    MaskOnly,
    /// Only if depth buffering or alpha planes are also enabled (86Box).
    MaskAndDepthOrAlphaPlanes,
}

/// Which row number the dither matrix and the stipple pattern are indexed with, for
/// triangles and LFB writes, when the Y origin is flipped (`fbzMode` bit 17).
/// (FASTFILL always uses the raster row: see `fastfill.rs`.)
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum PatternRow {
    /// The frame-buffer row the pixel lands on, after the flip (MAME `scry`, 86Box
    /// `real_y`). Measured on the glide-sdk traces (lower-left origin, dithering on):
    /// 5 consensus + 40.7 k majority failures, against 28 + 55.2 k with `Raster`.
    #[default]
    Screen,
    /// The raster row before the flip (DOSBox Staging).
    Raster,
}

impl PatternRow {
    /// The row the dither and stipple patterns use for raster row `y` landing on
    /// frame-buffer row `scry`.
    #[inline(always)]
    pub const fn row(self, y: i32, scry: i32) -> i32 {
        match self {
            PatternRow::Screen => scry,
            PatternRow::Raster => y,
        }
    }
}

/// Whether `lfbMode` bit 11 (word swap on writes) applies to the 32-bit colour formats.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum LfbWordSwap {
    /// Ignored for formats 4 and 5, as spec 5.20 says twice. No conformance trace
    /// exercises it.
    #[default]
    SpecIgnoredFor32Bit,
    /// Swapped for every format (MAME, DOSBox Staging).
    Always,
    /// Never swapped (86Box implements no word swap: `voodoo_fb_writel`).
    Never,
}

/// Whether LFB writes honour `lfbMode`'s lane order (bits 10:9), byte swizzle (bit 12)
/// and Y origin (bit 13, and `fbzMode`'s for pipelined writes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum LfbOrdering {
    /// As spec 5.20 says (MAME, DOSBox Staging).
    #[default]
    Applied,
    /// 86Box (`voodoo_fb_writel`, `voodoo_fb_writew`): none is implemented; data is
    /// always ARGB in host order and row 0 is the top of the buffer.
    Ignored,
}

/// Which alpha the alpha test (spec 5.18.1) compares for triangles.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum AlphaTestInput {
    /// The alpha combine unit's output (MAME: after `combine_color`; 86Box: `src_a`
    /// after the combine). `stress_random` depth: 2224 pixels where MAME and 86Box agree
    /// against DOSBox Staging on exactly this.
    #[default]
    Combined,
    /// `a_other`, before the alpha combine unit (DOSBox Staging).
    AOther,
}

/// Whether FASTFILL dithers `color1` when `fbzMode` enables dithering.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum FastfillDither {
    /// Dithered with the 4x4 or 2x2 matrix as `fbzMode` selects (spec 5.23; MAME, DOSBox
    /// Staging).
    #[default]
    Dithered,
    /// `color1` truncated to RGB565 whatever `fbzMode` says (86Box `voodoo_fastfill`).
    Truncated,
}

/// What `cc_localselect_override` (`fbzColorPath` bit 7) reads when the colour path
/// uses the texel for nothing else.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum OverrideTexel {
    /// The TMU chain's output, whatever else uses it (spec 5.16; DOSBox Staging, 86Box).
    #[default]
    Texel,
    /// MAME: its rasterizer set-up (`rasterizer_params::compute_equations`) turns the TMUs
    /// off when the colour equation takes nothing from the texel, and does not count the
    /// override as a use, so the override then reads texture alpha 0 (iterated RGB).
    /// UNVERIFIED: "takes nothing from the texel" is modelled from the register fields
    /// ([`crate::color_path::texel_feeds_equation`]); MAME decides on its simplified
    /// equation, which can drop more.
    ZeroWhenUnused,
}

/// Which byte of the clamped 16-bit Z `cca_localselect` = 2 (iterated Z) gives `a_local`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum ZAlphaByte {
    /// Z\[27:20\], the high byte (spec 5.16; MAME, 86Box).
    #[default]
    High,
    /// The low byte (DOSBox Staging casts the clamped Z to `uint8_t`).
    Low,
}

/// What the stipple register's rotate mode (`fbzMode` bit 12 clear) rotates across.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum StippleRotate {
    /// A copy of the register reloaded for every scanline (MAME, DOSBox Staging).
    #[default]
    PerScanline,
    /// 86Box (`voodoo_half_triangle`): one copy for the whole triangle, stepped for every
    /// pixel in walk order (right to left for a triangle whose `triangleCMD` bit 31 is
    /// set) by `(s << 1) | (s >> 31)` on a signed `int`, whose arithmetic shift fills the
    /// copy with ones once bit 31 has been set: every later pixel of the triangle passes.
    PerTriangle,
}

/// What `fbiInit0` bit 1 (FBI graphics reset) does besides clearing the statistics
/// counters.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum GraphicsReset {
    /// The colour buffers keep their front/back roles (MAME, DOSBox Staging).
    #[default]
    KeepsBuffers,
    /// Buffer 0 becomes the front buffer and buffer 1 the back one (86Box; its source
    /// doubts that the chip does this).
    ResetsBuffers,
}

/// Every disputed behaviour of the Pixelfx, chosen in one place.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(default)]
pub struct PixelProfile {
    pub edge_rounding: EdgeRounding,
    pub wfloat: WFloatEdges,
    pub clip_right: ClipRightEdge,
    pub aux_write: AuxWrite,
    pub pattern_row: PatternRow,
    pub lfb_word_swap: LfbWordSwap,
    pub lfb_ordering: LfbOrdering,
    pub float_overflow: FloatOverflow,
    pub subpixel_z: SubpixelZ,
    pub param_origin: ParamOrigin,
    pub alpha_test_input: AlphaTestInput,
    pub dither_2x2: DitherMatrix2x2,
    pub fastfill_dither: FastfillDither,
    pub override_texel: OverrideTexel,
    pub z_alpha: ZAlphaByte,
    pub stipple_rotate: StippleRotate,
    pub iterator_clamp: IteratorClamp,
    pub graphics_reset: GraphicsReset,
    pub fog: crate::fog::FogProfile,
    pub blend: crate::blend::BlendProfile,
}

impl PixelProfile {
    /// The hardware model: our reading of the SST-1 for every disputed behaviour (each
    /// switch's `#[default]` variant; docs/accuracy.md gives the evidence).
    pub const HARDWARE: PixelProfile = PixelProfile {
        edge_rounding: EdgeRounding::FloorHalfDown,
        wfloat: WFloatEdges::Dosbox,
        clip_right: ClipRightEdge::Exclusive,
        aux_write: AuxWrite::MaskOnly,
        pattern_row: PatternRow::Screen,
        lfb_word_swap: LfbWordSwap::SpecIgnoredFor32Bit,
        lfb_ordering: LfbOrdering::Applied,
        float_overflow: FloatOverflow::Wrap,
        subpixel_z: SubpixelZ::Wrap32,
        param_origin: ParamOrigin::VertexPixel,
        alpha_test_input: AlphaTestInput::Combined,
        dither_2x2: DitherMatrix2x2::Classic,
        fastfill_dither: FastfillDither::Dithered,
        override_texel: OverrideTexel::Texel,
        z_alpha: ZAlphaByte::High,
        stipple_rotate: StippleRotate::PerScanline,
        iterator_clamp: IteratorClamp::PseudoClamp,
        graphics_reset: GraphicsReset::KeepsBuffers,
        fog: crate::fog::FogProfile::HARDWARE,
        blend: crate::blend::BlendProfile::HARDWARE,
    };
}

impl Default for PixelProfile {
    fn default() -> Self {
        Self::HARDWARE
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hardware model's profile is every switch's `#[default]` variant, so that the
    /// enums' own documentation of the default and the model cannot disagree.
    #[test]
    fn hardware_is_every_switch_default() {
        let h = PixelProfile::HARDWARE;
        let d = PixelProfile {
            edge_rounding: Default::default(),
            wfloat: Default::default(),
            clip_right: Default::default(),
            aux_write: Default::default(),
            pattern_row: Default::default(),
            lfb_word_swap: Default::default(),
            lfb_ordering: Default::default(),
            float_overflow: Default::default(),
            subpixel_z: Default::default(),
            param_origin: Default::default(),
            alpha_test_input: Default::default(),
            dither_2x2: Default::default(),
            fastfill_dither: Default::default(),
            override_texel: Default::default(),
            z_alpha: Default::default(),
            stipple_rotate: Default::default(),
            iterator_clamp: Default::default(),
            graphics_reset: Default::default(),
            fog: crate::fog::FogProfile {
                difference: Default::default(),
                iterated_alpha: Default::default(),
                constant_mult: Default::default(),
                table_depth: Default::default(),
                both_sources: Default::default(),
            },
            blend: crate::blend::BlendProfile {
                arithmetic: Default::default(),
                saturate: Default::default(),
                dither_2x2: Default::default(),
            },
        };
        assert_eq!(h, d);
    }
}

//! The seam between the pixel stages and the models of the chip.
//!
//! Every stage is written once. Where MAME, DOSBox Staging and 86Box disagree, a stage
//! reads the switch of [`PixelProfile`] that names the disagreement, and it reads the
//! profile through a model type `M: PixelModel` that the caller chooses at compile time:
//! the board instantiates the pipeline once per model (`sst1_board::model`) and chooses
//! the instance once per register write. A model whose switches are constants (the
//! hardware model, and each reference emulator's) returns a constant profile, so every
//! test of a switch folds away and the instance holds only the behaviour it models; the
//! run-time-profile model returns the profile held at run time (`--profile FILE`, for
//! experiments), and may be slow.

use crate::profile::PixelProfile;

/// A model of the Pixelfx, chosen at compile time (see the module documentation).
pub trait PixelModel: 'static {
    /// The switches in force. `runtime` is the profile the FBI holds
    /// ([`crate::Fbi::set_profile`]); a model with fixed switches ignores it and returns a
    /// constant, which is what lets the compiler fold the switches.
    fn pixel(runtime: &PixelProfile) -> PixelProfile;

    /// Whether triangles run the span kernels ([`crate::span`]); otherwise the reference
    /// path, pixel by pixel. Each model that does gets its own copies of the kernels.
    const SPAN_KERNELS: bool = true;

    /// Whether the span kernels are compiled again with AVX2 and with AVX-512
    /// ([`crate::isa`]), the best the CPU has used. Two copies of every kernel more:
    /// the hardware model, which programs run, has them; the reference models,
    /// instruments for judging it, run the baseline copy.
    const SIMD: bool = false;
}

/// The run-time-profile model: the profile held at run time, every switch tested per pixel. For
/// experiments and for tests of one crate alone.
#[derive(Clone, Copy, Debug, Default)]
pub struct RuntimeProfile;

impl PixelModel for RuntimeProfile {
    #[inline(always)]
    fn pixel(runtime: &PixelProfile) -> PixelProfile {
        *runtime
    }
}

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
//!
//! The same seam selects the specialised walkers ([`PixelModel::specialised`]): a model
//! may offer walkers compiled for particular drawing states, each one the same pipeline
//! with both the model's switches and the state's mode bits folded in.

use crate::pipeline::DrawState;
use crate::profile::PixelProfile;
use crate::raster::TexelSource;
use crate::specialize::RasterKey;
use crate::Fbi;

/// A triangle walker: draws the triangle in `fbi.params` with the captured state.
pub type Walker<T> = fn(&mut Fbi, &DrawState, &mut T);

/// A model of the Pixelfx, chosen at compile time (see the module documentation).
pub trait PixelModel: 'static {
    /// The switches in force. `runtime` is the profile the FBI holds
    /// ([`Fbi::set_profile`]); a model with fixed switches ignores it and returns a
    /// constant, which is what lets the compiler fold the switches.
    fn pixel(runtime: &PixelProfile) -> PixelProfile;

    /// A walker specialised for the drawing state `key`, if the model has one; `None`
    /// runs the generic walker of this model. Every walker gives the pixels and counters
    /// the generic one gives.
    #[inline]
    fn specialised<T: TexelSource>(_key: RasterKey) -> Option<Walker<T>> {
        None
    }
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

//! The models of the chip, chosen at compile time, and the one place that turns the
//! model a board runs into a type.
//!
//! The pixel and texture stages are written once, against [`PixelModel`] and
//! [`TexelModel`] (`pixelfx::model`). Each model here is a type whose switches are
//! constants, so an instance of the pipeline for it holds only its own behaviour:
//!
//! * [`Hardware`]: the hardware model, our reading of the SST-1 ([`AccuracyProfile::HARDWARE`],
//!   docs/accuracy.md). What programs run, what `voodoo replay` shows.
//! * [`Mame`], [`DosboxStaging`], [`Box86`]: the three reference emulators
//!   ([`Reference::profile`]), instruments for judging the hardware model against their
//!   goldens; `--model vote` votes them.
//! * [`Custom`]: the profile held at run time (`--profile FILE`), every switch tested
//!   per pixel. For experiments; slow.
//!
//! The four fixed models run the span kernels (`pixelfx::span`), each instance compiled
//! with its own switches (the hardware model's again with AVX2 and with AVX-512,
//! `pixelfx::isa`); the custom model runs the reference path, as
//! `Board::set_generic_path` makes any model do.
//!
//! A [`Board`](crate::Board) holds a [`Model`] and instantiates its bus once per model
//! (`with_model!`): the match on the model runs once per bus access, never inside a
//! stage.

use pixelfx::{PixelModel, PixelProfile};
use texelfx::{TexelModel, TexelProfile};

use crate::reference::Reference;
use crate::AccuracyProfile;

/// A model of the whole chip set: the Pixelfx's switches and the Texelfx's.
pub trait ChipModel: PixelModel + TexelModel {}

impl<M: PixelModel + TexelModel> ChipModel for M {}

/// Defines a model type whose switches are the constant profile `$profile`.
macro_rules! fixed_model {
    ($(#[$doc:meta])* $name:ident = $profile:expr, simd = $simd:expr) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, Default)]
        pub struct $name;

        impl $name {
            /// The model's switches.
            pub const PROFILE: AccuracyProfile = $profile;
        }

        impl PixelModel for $name {
            const SIMD: bool = $simd;

            #[inline(always)]
            fn pixel(_runtime: &PixelProfile) -> PixelProfile {
                Self::PROFILE.pixel
            }
        }

        impl TexelModel for $name {
            #[inline(always)]
            fn texel(_runtime: &TexelProfile) -> TexelProfile {
                Self::PROFILE.texel
            }
        }
    };
}

fixed_model!(
    /// The hardware model: our reading of the SST-1.
    Hardware = AccuracyProfile::HARDWARE,
    simd = true
);
fixed_model!(
    /// MAME as a model.
    Mame = Reference::Mame.profile(),
    simd = false
);
fixed_model!(
    /// DOSBox Staging as a model.
    DosboxStaging = Reference::DosboxStaging.profile(),
    simd = false
);
fixed_model!(
    /// 86Box as a model.
    Box86 = Reference::Box86.profile(),
    simd = false
);

/// The model of `--profile FILE`: the profile the chips hold at run time, every switch
/// tested per pixel (`pixelfx::RuntimeProfile` and `texelfx::RuntimeProfile` for the
/// whole chip set). For experiments; slow.
#[derive(Clone, Copy, Debug, Default)]
pub struct Custom;

impl PixelModel for Custom {
    // The reference path only: slow by design, and no copy of the kernels to compile.
    const SPAN_KERNELS: bool = false;

    #[inline(always)]
    fn pixel(runtime: &PixelProfile) -> PixelProfile {
        *runtime
    }
}

impl TexelModel for Custom {
    #[inline(always)]
    fn texel(runtime: &TexelProfile) -> TexelProfile {
        *runtime
    }
}

/// The model a board runs, chosen at run time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Model {
    /// [`Hardware`].
    #[default]
    Hardware,
    /// The model of one reference emulator ([`Mame`], [`DosboxStaging`], [`Box86`]).
    Reference(Reference),
    /// [`Custom`] with this profile (what `--profile FILE` runs).
    Custom(AccuracyProfile),
}

impl Model {
    /// The model for `profile`: a fixed model if its profile is that one (the same
    /// pixels, compiled for them), otherwise [`Model::Custom`].
    pub fn from_profile(profile: AccuracyProfile) -> Model {
        if profile == AccuracyProfile::HARDWARE {
            return Model::Hardware;
        }
        Reference::ALL
            .into_iter()
            .find(|r| r.profile() == profile)
            .map_or(Model::Custom(profile), Model::Reference)
    }

    /// The switches this model has.
    pub fn profile(self) -> AccuracyProfile {
        match self {
            Model::Hardware => AccuracyProfile::HARDWARE,
            Model::Reference(r) => r.profile(),
            Model::Custom(p) => p,
        }
    }

    /// The model type a board instantiates for this model.
    pub(crate) fn kind(self) -> Kind {
        match self {
            Model::Hardware => Kind::Hardware,
            Model::Reference(Reference::Mame) => Kind::Mame,
            Model::Reference(Reference::DosboxStaging) => Kind::DosboxStaging,
            Model::Reference(Reference::Box86) => Kind::Box86,
            Model::Custom(_) => Kind::Custom,
        }
    }
}

/// Which model type runs: [`Model`] without the profile, for the dispatch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Hardware,
    Mame,
    DosboxStaging,
    Box86,
    Custom,
}

/// Evaluates `$body` with the type `$M` bound to the model type of `$kind` (a [`Kind`]).
macro_rules! with_model {
    ($kind:expr, $M:ident => $body:expr) => {
        match $kind {
            $crate::model::Kind::Hardware => {
                type $M = $crate::model::Hardware;
                $body
            }
            $crate::model::Kind::Mame => {
                type $M = $crate::model::Mame;
                $body
            }
            $crate::model::Kind::DosboxStaging => {
                type $M = $crate::model::DosboxStaging;
                $body
            }
            $crate::model::Kind::Box86 => {
                type $M = $crate::model::Box86;
                $body
            }
            $crate::model::Kind::Custom => {
                type $M = $crate::model::Custom;
                $body
            }
        }
    };
}
pub(crate) use with_model;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_profiles_are_found_from_their_profile() {
        assert_eq!(
            Model::from_profile(AccuracyProfile::default()),
            Model::Hardware
        );
        for r in Reference::ALL {
            assert_eq!(Model::from_profile(r.profile()), Model::Reference(r));
            assert_eq!(Model::Reference(r).profile(), r.profile());
        }
        let mut p = AccuracyProfile::HARDWARE;
        p.texel.trilinear = texelfx::Trilinear::Ignored;
        assert_eq!(Model::from_profile(p), Model::Custom(p));
        assert_eq!(Model::Custom(p).kind(), Kind::Custom);
        // The fixed models' switches are the profiles they stand for.
        assert_eq!(Hardware::pixel(&p.pixel), AccuracyProfile::HARDWARE.pixel);
        assert_eq!(
            <Mame as TexelModel>::texel(&p.texel),
            Reference::Mame.profile().texel
        );
        assert_eq!(Custom::texel(&p.texel), p.texel);
    }
}

//! Pixelfx: the SST-1 frame-buffer interface chip (FBI).
//!
//! One module per pipeline stage; [`pipeline`] calls them in hardware order and is the
//! only module that knows that order. [`fbi::Fbi`] owns the register file, the frame
//! buffer and the counters; the board crate decodes the PCI aperture and drives it.

pub mod alpha_test;
pub mod blend;
pub mod box86;
pub mod color_path;
pub mod deferred;
pub mod depth;
pub mod fastfill;
pub mod fb;
pub mod fbi;
pub mod fog;
mod helpers;
pub mod isa;
pub mod iter;
pub mod lfb;
pub mod model;
pub mod params;
pub mod pipeline;
pub mod profile;
pub mod raster;
pub mod setup;
pub mod span;
pub mod state;
pub mod stats;
pub mod stipple;
pub mod watch;

pub use deferred::{
    draw_untextured, DrawJob, RenderThread, RenderThreadFailed, TriangleJob, WalkCounts,
};
pub use fbi::{Command, Fbi, PathCounts};
pub use isa::VectorIsa;
pub use model::{PixelModel, RuntimeProfile};
pub use profile::PixelProfile;
pub use raster::{LanePlace, NoTexture, TexelSource};
pub use span::{Lanes, LANES};
pub use state::FbiState;
pub use stats::{Kill, Stats};
pub use watch::{PixelEvent, PixelStages, PixelWatch, TmuStage};

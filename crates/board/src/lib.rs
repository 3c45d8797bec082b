//! The SST-1 board: one Pixelfx (FBI), one to three Texelfx (TMU), and the PCI
//! aperture that feeds them (spec sections 4-6).
//!
//! ```text
//!   PCI aperture (16 MiB)
//!   0x000000-0x3fffff  registers  --chip select-->  FBI, TMU0, TMU1, TMU2
//!   0x400000-0x7fffff  LFB        -------------->   FBI
//!   0x800000-0xffffff  texture    --bits 22:21-->   TMU0..2
//! ```
//! Commands run to completion inside the write that starts them. [`timing`] counts the
//! graphics-clock cycles the real board would have taken (docs/timing.md) and answers
//! the `status` register from them.

mod box86;
mod bus;
mod deferred;
mod diagnostics;
pub mod method;
pub mod model;
pub mod presets;
pub mod reference;
pub mod state;
pub mod timing;
mod video;
mod write16;

use serde::{Deserialize, Serialize};

pub use bus::aperture_offset;
pub use deferred::Deferred;
pub use diagnostics::{Diagnostic, Diagnostics};
pub use method::Method;
pub use model::Model;
pub use pixelfx::watch;
pub use pixelfx::{Kill, PathCounts, PixelProfile, Stats, VectorIsa};
pub use reference::{vote, Reference};
pub use state::{StateError, StateInfo};
pub use texelfx::{TexelProfile, Tmu};
pub use timing::{Frame, FrameTime, Timing};

use pixelfx::Fbi;

/// What is on the board: memory sizes and TMU count (the trace's `config` lines).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct BoardConfig {
    /// Frame-buffer memory in MiB: 2 or 4.
    pub fbi_mb: u32,
    /// Number of TMUs: 1, 2 or 3.
    pub tmus: u32,
    /// Texture memory per TMU in MiB: 1, 2 or 4.
    pub tmu_mb: u32,
}

impl Default for BoardConfig {
    fn default() -> Self {
        Self {
            fbi_mb: 4,
            tmus: 1,
            tmu_mb: 4,
        }
    }
}

impl BoardConfig {
    /// The same configuration with every value forced into the range the hardware offers
    /// (2 or 4 MiB frame buffer, 1-3 TMUs, 1/2/4 MiB each).
    pub fn sanitized(self) -> Self {
        Self {
            fbi_mb: if self.fbi_mb <= 2 { 2 } else { 4 },
            tmus: self.tmus.clamp(1, 3),
            tmu_mb: match self.tmu_mb {
                0 | 1 => 1,
                2 | 3 => 2,
                _ => 4,
            },
        }
    }
}

/// Which buffer of the frame buffer to read out.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum BufferKind {
    /// The buffer being displayed.
    Front,
    /// The buffer being drawn (for double buffering).
    Back,
    /// The auxiliary buffer: depth or alpha.
    Aux,
}

/// The accuracy profile of the whole board: every disputed behaviour in one place.
/// `Default` is the hardware model's, [`AccuracyProfile::HARDWARE`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default)]
pub struct AccuracyProfile {
    /// Pixelfx switches.
    pub pixel: PixelProfile,
    /// Texelfx switches.
    pub texel: TexelProfile,
}

impl AccuracyProfile {
    /// The hardware model: our reading of the SST-1 (docs/accuracy.md).
    pub const HARDWARE: AccuracyProfile = AccuracyProfile {
        pixel: PixelProfile::HARDWARE,
        texel: TexelProfile::HARDWARE,
    };
}

/// The emulated board.
pub struct Board {
    config: BoardConfig,
    fbi: Fbi,
    tmus: Vec<Tmu>,
    /// PCI configuration register `initEnable` (0x40).
    init_enable: u32,
    diagnostics: Diagnostics,
    /// The model the chips run (their profiles are its profile).
    model: Model,
    /// `model.kind()`, which every bus access dispatches on (kept with `model`).
    kind: model::Kind,
    /// The modelled hardware time.
    timing: Timing,
    /// The DAC's PLL registers (the pixel clock), as `dacData` writes set them.
    dac: video::Dac,
    /// Whether the timing model runs ([`Board::set_timing`]).
    timing_on: bool,
    /// The render thread small triangles are shaded on during the writes of a
    /// [`Deferred`] run, with more than one render thread (started at the first); it
    /// holds the TMUs with the frame-buffer memory.
    render: Option<pixelfx::RenderThread<Vec<Tmu>, deferred::TmuJob>>,
    /// The TMUs' S, T, W register writes while the render thread holds the TMUs.
    lent_stw: deferred::LentStw,
    /// Whether a triangle command may go to the render thread: only inside the writes of
    /// a [`Deferred`] run.
    deferring: bool,
    /// The timing model's events while the render thread holds the memory, charged when
    /// it gives it back.
    timing_log: deferred::TimingLog,
}

impl Board {
    /// A board in its power-on state. Out-of-range configurations are sanitized.
    pub fn new(config: BoardConfig) -> Self {
        let config = config.sanitized();
        let tmu_bytes = (config.tmu_mb as usize) << 20;
        Self {
            config,
            fbi: Fbi::new(config.fbi_mb),
            tmus: (0..config.tmus as u8)
                .map(|i| Tmu::new(i, tmu_bytes))
                .collect(),
            init_enable: 0,
            diagnostics: Diagnostics::default(),
            model: Model::Hardware,
            kind: Model::Hardware.kind(),
            timing: Timing::default(),
            dac: video::Dac::default(),
            timing_on: true,
            render: None,
            lent_stw: deferred::LentStw::default(),
            deferring: false,
            timing_log: deferred::TimingLog::default(),
        }
    }

    /// How long the real board would have taken so far (graphics-clock cycles, per frame;
    /// see [`timing`]).
    pub fn timing(&self) -> &Timing {
        &self.timing
    }

    /// Run the timing model (the default) or not. Off, the board counts no cycles and
    /// plays nothing out in time: `status` reads the FBI's own bits (idle, FIFOs empty,
    /// never in vertical retrace, swaps never pending), `vRetrace` reads 0 and `wait` ops
    /// do nothing. Pixels, counters and diagnostics are the same either way; this is for
    /// measuring what the model costs (`voodoo replay --no-timing`, the `replay`
    /// bench). Choose before the first access.
    pub fn set_timing(&mut self, on: bool) {
        self.timing_on = on;
    }

    /// Whether the timing model runs.
    pub fn timing_enabled(&self) -> bool {
        self.timing_on
    }

    /// The board configuration.
    pub fn config(&self) -> BoardConfig {
        self.config
    }

    /// Choose the model the chips run (default: [`Model::Hardware`]).
    pub fn set_model(&mut self, model: Model) {
        let profile = model.profile();
        self.model = model;
        self.kind = model.kind();
        self.fbi.set_profile(profile.pixel);
        for t in &mut self.tmus {
            t.set_profile(profile.texel);
        }
    }

    /// The model the chips run.
    pub fn model(&self) -> Model {
        self.model
    }

    /// Choose the disputed behaviours: the model with this profile
    /// ([`Model::from_profile`]: a fixed model where the profile is one).
    pub fn set_profile(&mut self, profile: AccuracyProfile) {
        self.set_model(Model::from_profile(profile));
    }

    /// Force the generic path (the reference path): the pipeline runs pixel by pixel with
    /// every mode register read at run time for every pixel instead of the span kernels
    /// (`pixelfx::span`), and every texel is decoded from texture memory instead of
    /// read from the TMUs' decoded-texel caches. Output and counters are identical either
    /// way; this is for differential testing and debugging. Off by default.
    pub fn set_generic_path(&mut self, on: bool) {
        self.fbi.set_generic_path(on);
        for t in &mut self.tmus {
            t.set_generic_path(on);
        }
    }

    /// Choose how to draw ([`Method`]): the exact fast path (the default), the exact
    /// generic path ([`Board::set_generic_path`]), or an approximation of the fast path
    /// that trades exactness for speed. Replaces any earlier `set_generic_path` choice.
    pub fn set_method(&mut self, method: Method) {
        self.set_generic_path(method == Method::Reference);
        for t in &mut self.tmus {
            t.set_approx(method.approx());
        }
    }

    /// Shade large triangles on `threads` render threads (bands of rows; 1, the default,
    /// draws on the calling thread). Textured ones go to the threads where the TMU chain
    /// can be shared: the hardware model and the MAME and DOSBox models (not 86Box's
    /// texture cache, not the generic path). Pixels, counters, status reads and save
    /// states are the same for every count; only [`Board::path_counts`] says it.
    pub fn set_threads(&mut self, threads: usize) {
        self.fbi.set_threads(threads);
    }

    /// Run the copy of the span kernels compiled for `cap` (`pixelfx::isa`), or the best
    /// the CPU has below it; returns the copy that will run. Every copy gives the same
    /// pixels, counters and cycles; a board starts with the best the CPU has. Only the
    /// hardware model has the vector copies; the others run the baseline one whatever
    /// is set here.
    pub fn set_vector_isa(&mut self, cap: VectorIsa) -> VectorIsa {
        self.fbi.set_vector_isa(cap)
    }

    /// The copy of the span kernels set with [`Board::set_vector_isa`].
    pub fn vector_isa(&self) -> VectorIsa {
        self.fbi.vector_isa()
    }

    /// The copy of the span kernels this board's triangles run: [`Board::vector_isa`] for
    /// the hardware model, the baseline copy for the others (which have no other).
    pub fn kernel_isa(&self) -> VectorIsa {
        let simd = model::with_model!(self.kind, M => <M as pixelfx::PixelModel>::SIMD);
        if simd {
            self.vector_isa()
        } else {
            VectorIsa::Baseline
        }
    }

    /// The render threads in use ([`Board::set_threads`]).
    pub fn threads(&self) -> usize {
        self.fbi.threads()
    }

    /// Width and height of the video mode set by `videoDimensions`.
    pub fn display_size(&self) -> (u32, u32) {
        self.fbi.display_size()
    }

    /// The statistics counters and command counts.
    pub fn stats(&self) -> Stats {
        self.fbi.stats
    }

    /// How many triangle pixels each pixel path shaded (not a hardware counter).
    pub fn path_counts(&self) -> PathCounts {
        self.fbi.path_counts
    }

    /// What the board met that it does not model or that a driver should not do.
    pub fn diagnostics(&self) -> &Diagnostics {
        &self.diagnostics
    }

    /// The FBI, for inspection.
    pub fn fbi(&self) -> &Fbi {
        &self.fbi
    }

    /// TMU `index` (0 is the one next to the FBI), for inspection; `None` past the last.
    pub fn tmu(&self, index: usize) -> Option<&Tmu> {
        self.tmus.get(index)
    }

    /// Record the history of pixel `(x, row)` (`row`: the frame-buffer row, as
    /// [`Board::dump_buffer`] lays rows out) from now on: every operation that reaches
    /// it leaves a [`watch::PixelEvent`] ([`Board::take_pixel_events`]). Forces the
    /// generic path ([`Board::set_generic_path`]), whose stages record their values;
    /// pixels and counters are the same as without the watch. A later
    /// [`Board::set_method`] or `set_generic_path(false)` gives the span kernels back,
    /// which record nothing: choose those first.
    pub fn watch_pixel(&mut self, x: i32, row: i32) {
        self.set_generic_path(true);
        self.fbi.set_watch(Some(watch::PixelWatch::new(x, row)));
    }

    /// The events of the watched pixel ([`Board::watch_pixel`]) since the last call,
    /// oldest first (empty without a watch).
    pub fn take_pixel_events(&mut self) -> Vec<watch::PixelEvent> {
        self.fbi.watch_mut().map(|w| w.take()).unwrap_or_default()
    }

    /// Events of the watched pixel dropped because more than [`watch::MAX_EVENTS`] were
    /// waiting to be taken.
    pub fn pixel_events_dropped(&mut self) -> u64 {
        self.fbi.watch_mut().map_or(0, |w| w.dropped())
    }

    /// The frame-buffer word index of pixel `(x, row)` of buffer `which` (what
    /// [`watch::PixelEvent::wrote`] takes), or `None` where the buffer or the word does
    /// not exist.
    pub fn buffer_word(&self, which: BufferKind, x: i32, row: i32) -> Option<usize> {
        let fb = &self.fbi.fb;
        let base = match which {
            BufferKind::Front => fb.rgb_base(fb.front),
            BufferKind::Back => fb.rgb_base(fb.back),
            BufferKind::Aux => fb.aux_base(),
        }?;
        fb.index(base, x, row)
    }

    /// The buffer as `width * height` raw 16-bit values, row 0 = first row in memory.
    pub fn dump_buffer(&self, which: BufferKind) -> Vec<u16> {
        let (w, h) = self.display_size();
        let fb = &self.fbi.fb;
        let base = match which {
            BufferKind::Front => fb.rgb_base(fb.front),
            BufferKind::Back => fb.rgb_base(fb.back),
            BufferKind::Aux => fb.aux_base(),
        };
        fb.dump(base, w, h)
    }
}

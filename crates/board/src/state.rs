//! Save states: the whole board in a versioned binary form, restored bit for bit.
//!
//! ```text
//!   bytes 0..8    magic `SST1STAT`
//!   bytes 8..12   format version, u32 little-endian (FORMAT_VERSION)
//!   then          the header (StateInfo), postcard
//!   then          the payload, postcard: FBI, TMUs, PCI initEnable, diagnostics,
//!                 the timing model and the DAC
//! ```
//!
//! The header says which board the state is of: the crate version that wrote it, the
//! configuration (memory sizes, TMU count), the model, and the number of trace ops run
//! before it was taken when the front end knows it (`voodoo replay --save-at`), so that
//! `--resume` goes on from the next op. A reader refuses another format version, a state
//! of another configuration or model, a damaged or cut-short file and one larger than a
//! board of its configuration can hold, each with its own [`StateError`]; no length in
//! the file is trusted for an allocation before the whole file's size is checked
//! against the configuration, and every length is checked against the board after.
//!
//! What is saved is what a later access can observe: registers, frame-buffer and texture
//! memory, the NCC tables and palette, the fog table, the triangle parameters, the
//! counters, the PCI configuration, the diagnostics, the DAC, the timing model's FIFOs,
//! pending swaps and counts, and 86Box's texture cache (state of that model, see
//! `texelfx`). Caches are rebuilt instead (the TMUs' decoded-texel caches, decode
//! tables, layouts, dither tables, the video frame from the video registers and the DAC,
//! the span kernels' constants). The host's choices stay with the board that loads:
//! render threads and the generic-path switch, and the path counts that report what they
//! did ([`Board::path_counts`]), so that a state never depends on how many threads shaded
//! the frames before it.
//!
//! Format versions: 1 also held the path counts; 2 (this build) does not. A build reads
//! its own version only.

use serde::{Deserialize, Serialize};
use sst1_regs::addr;

use crate::diagnostics::Diagnostics;
use crate::model::Model;
use crate::reference::Reference;
use crate::timing::{
    FrameTime, HostView, MemoryFifo, HOST_CLOCK_MAX, MAX_FRAMES, MEMORY_FIFO_MAX_ENTRIES,
    PCI_FIFO_ENTRIES,
};
use crate::video::{Dac, VideoRegs};
use crate::{AccuracyProfile, Board, BoardConfig};

/// The first bytes of every save state.
pub const MAGIC: [u8; 8] = *b"SST1STAT";

/// The format version this build writes, and the only one it reads.
pub const FORMAT_VERSION: u32 = 2;

/// The crate version written into the header.
const CRATE_VERSION: &str = env!("CARGO_PKG_VERSION");

/// The longest crate version string a header may hold.
const MAX_VERSION_LEN: usize = 64;

/// What the header of a save state says.
#[derive(Clone, Debug, PartialEq)]
pub struct StateInfo {
    /// The format version ([`FORMAT_VERSION`] for the states this build writes).
    pub format_version: u32,
    /// The version of `sst1-board` that wrote it.
    pub crate_version: String,
    /// The board it is a state of.
    pub config: BoardConfig,
    /// The model that board ran.
    pub model: Model,
    /// How many trace ops had run when it was taken, if the writer said
    /// ([`Board::save_state_after`]).
    pub ops_done: Option<u64>,
}

/// Why a save state was refused.
#[derive(Debug, thiserror::Error)]
pub enum StateError {
    /// No magic: not a save state at all.
    #[error("not a save state (it does not start with `SST1STAT`)")]
    NotAState,
    /// Written by a newer build, in a format this one does not know.
    #[error("save state format version {found} is newer than this build reads (up to {supported}): use a newer voodoo-rs")]
    NewerVersion {
        /// The file's format version.
        found: u32,
        /// [`FORMAT_VERSION`].
        supported: u32,
    },
    /// Written by an older build, in a format this one no longer reads.
    #[error("save state format version {found} is older than this build reads ({supported}): replay the program or trace it came from to take it again")]
    OlderVersion {
        /// The file's format version.
        found: u32,
        /// [`FORMAT_VERSION`].
        supported: u32,
    },
    /// Cut short, or bytes that do not decode as a state.
    #[error("save state is damaged or cut short: {0}")]
    Corrupt(String),
    /// Larger than a state of its board can be.
    #[error("save state is {len} bytes, more than a state of its board can be ({limit})")]
    TooLarge {
        /// The file's length.
        len: usize,
        /// The most a state of its configuration takes.
        limit: usize,
    },
    /// A state of another board configuration.
    #[error("save state is of a board with {}, this board has {}", describe(.state), describe(.board))]
    OtherConfig {
        /// The state's configuration.
        state: BoardConfig,
        /// The loading board's.
        board: BoardConfig,
    },
    /// A state of another model.
    #[error("save state is of the {state} model, this board runs the {board} model")]
    OtherModel {
        /// The state's model, by name.
        state: String,
        /// The loading board's.
        board: String,
    },
}

/// A configuration in words.
fn describe(c: &BoardConfig) -> String {
    format!(
        "{} MiB of frame buffer and {} TMU(s) of {} MiB",
        c.fbi_mb, c.tmus, c.tmu_mb
    )
}

/// A model's name in messages (`voodoo replay --model`'s spelling).
pub fn model_name(model: Model) -> &'static str {
    match model {
        Model::Hardware => "hardware",
        Model::Reference(r) => r.golden_dir(),
        Model::Custom(_) => "custom-profile",
    }
}

/// [`Model`] as the header stores it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
enum StateModel {
    Hardware,
    Mame,
    DosboxStaging,
    Box86,
    Custom(AccuracyProfile),
}

impl From<Model> for StateModel {
    fn from(m: Model) -> Self {
        match m {
            Model::Hardware => StateModel::Hardware,
            Model::Reference(Reference::Mame) => StateModel::Mame,
            Model::Reference(Reference::DosboxStaging) => StateModel::DosboxStaging,
            Model::Reference(Reference::Box86) => StateModel::Box86,
            Model::Custom(p) => StateModel::Custom(p),
        }
    }
}

impl From<StateModel> for Model {
    fn from(m: StateModel) -> Self {
        match m {
            StateModel::Hardware => Model::Hardware,
            StateModel::Mame => Model::Reference(Reference::Mame),
            StateModel::DosboxStaging => Model::Reference(Reference::DosboxStaging),
            StateModel::Box86 => Model::Reference(Reference::Box86),
            StateModel::Custom(p) => Model::Custom(p),
        }
    }
}

/// The header after the magic and the version.
#[derive(Serialize, Deserialize)]
struct Header {
    crate_version: String,
    config: BoardConfig,
    model: StateModel,
    ops_done: Option<u64>,
}

/// The timing model's state (`timing::Timing` less the frame, which follows from the
/// video registers and the DAC).
#[derive(Serialize, Deserialize)]
struct TimingState {
    total: FrameTime,
    frames: Vec<FrameTime>,
    current: FrameTime,
    pending_bus: u64,
    pending_wait: u64,
    fraction: u64,
    last_swap: u64,
    host: HostView,
}

/// The payload.
#[derive(Serialize, Deserialize)]
struct Payload {
    fbi: pixelfx::FbiState,
    tmus: Vec<texelfx::TmuState>,
    init_enable: u32,
    diagnostics: Diagnostics,
    timing_on: bool,
    timing: TimingState,
    dac: Dac,
}

/// The largest state of a board of `config`: its memories, 86Box's texture cache full of
/// 256x256 mipmapped textures, the most frames the timing model keeps, both FIFOs full,
/// and room for the rest.
pub fn max_state_len(config: BoardConfig) -> usize {
    let config = config.sanitized();
    // Texels of a full 256x256 mip chain, 4 bytes each, in 64 entries.
    let box86_cache = 64 * 4 * (0..9).map(|lod| (256usize >> lod).pow(2)).sum::<usize>();
    let tmu = ((config.tmu_mb as usize) << 20) + box86_cache + (64 << 10);
    // Six counts of up to 10 bytes per frame; up to 10 bytes per queued write and swap.
    let timing = MAX_FRAMES * 60 + 2 * (PCI_FIFO_ENTRIES + MEMORY_FIFO_MAX_ENTRIES + 1) * 10;
    ((config.fbi_mb as usize) << 20) + config.tmus as usize * tmu + timing + (1 << 20)
}

/// Reads the magic, the version and the header; returns the header and the payload's
/// bytes.
fn split(bytes: &[u8]) -> Result<(StateInfo, &[u8]), StateError> {
    if bytes.len() < 12 || bytes[..8] != MAGIC {
        return Err(StateError::NotAState);
    }
    let version = u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]);
    if version > FORMAT_VERSION {
        return Err(StateError::NewerVersion {
            found: version,
            supported: FORMAT_VERSION,
        });
    }
    if version == 0 {
        return Err(StateError::Corrupt("format version 0".into()));
    }
    if version < FORMAT_VERSION {
        return Err(StateError::OlderVersion {
            found: version,
            supported: FORMAT_VERSION,
        });
    }
    let (header, payload): (Header, &[u8]) = postcard::take_from_bytes(&bytes[12..])
        .map_err(|e| StateError::Corrupt(format!("header: {e}")))?;
    if header.crate_version.len() > MAX_VERSION_LEN {
        return Err(StateError::Corrupt("header: crate version too long".into()));
    }
    if header.config.sanitized() != header.config {
        return Err(StateError::Corrupt(format!(
            "header: no SST-1 board has {}",
            describe(&header.config)
        )));
    }
    let limit = max_state_len(header.config);
    if bytes.len() > limit {
        return Err(StateError::TooLarge {
            len: bytes.len(),
            limit,
        });
    }
    let info = StateInfo {
        format_version: version,
        crate_version: header.crate_version,
        config: header.config,
        model: header.model.into(),
        ops_done: header.ops_done,
    };
    Ok((info, payload))
}

/// What the header of the save state `bytes` says, without decoding the rest.
pub fn read_info(bytes: &[u8]) -> Result<StateInfo, StateError> {
    split(bytes).map(|(info, _)| info)
}

fn corrupt(what: &str, e: impl std::fmt::Display) -> StateError {
    StateError::Corrupt(format!("{what}: {e}"))
}

/// Checks the timing model's state: every count and time in range (so that nothing
/// overflows later), the FIFOs no fuller than they can be.
fn check_timing(t: &TimingState, memory_fifo: MemoryFifo) -> Result<(), StateError> {
    let h = &t.host;
    // Host times stay below 2^61 (the view moves back by whole frames past 2^60).
    const TIME_MAX: u64 = 1 << 61;
    let times_ok = [h.now, h.engine_free, h.tmu_free, h.last_taken, h.last_swap]
        .into_iter()
        .chain(h.fifo.times())
        .chain(h.swaps.iter().copied())
        .all(|v| v <= TIME_MAX);
    let queued_max = PCI_FIFO_ENTRIES + memory_fifo.entries;
    let ok = t.frames.len() <= MAX_FRAMES
        && t.fraction < 16
        && t.pending_bus <= HOST_CLOCK_MAX
        && t.pending_wait <= HOST_CLOCK_MAX
        && t.last_swap <= HOST_CLOCK_MAX * 2
        && times_ok
        && h.fifo.len() <= queued_max
        && h.in_memory <= h.fifo.len().min(memory_fifo.entries)
        && h.swaps.len() <= PCI_FIFO_ENTRIES + MEMORY_FIFO_MAX_ENTRIES + 1
        && h.memory_fifo == memory_fifo;
    if ok {
        Ok(())
    } else {
        Err(StateError::Corrupt(
            "the timing model's state is out of range".into(),
        ))
    }
}

impl Board {
    /// The whole board as a save state (module [`crate::state`]).
    pub fn save_state(&self) -> Vec<u8> {
        self.encode_state(None)
    }

    /// [`Board::save_state`], recording that `ops_done` trace ops had run: what
    /// `voodoo replay --save-at` writes, so that `--resume` goes on from the next op.
    pub fn save_state_after(&self, ops_done: u64) -> Vec<u8> {
        self.encode_state(Some(ops_done))
    }

    fn encode_state(&self, ops_done: Option<u64>) -> Vec<u8> {
        let header = Header {
            crate_version: CRATE_VERSION.to_owned(),
            config: self.config,
            model: self.model.into(),
            ops_done,
        };
        let t = &self.timing;
        let payload = Payload {
            fbi: self.fbi.save_state(),
            tmus: self.tmus.iter().map(|t| t.save_state()).collect(),
            init_enable: self.init_enable,
            diagnostics: self.diagnostics.clone(),
            timing_on: self.timing_on,
            timing: TimingState {
                total: t.total,
                frames: t.frames.clone(),
                current: t.current,
                pending_bus: t.pending_bus,
                pending_wait: t.pending_wait,
                fraction: t.fraction,
                last_swap: t.last_swap,
                host: t.host.clone(),
            },
            dac: self.dac.clone(),
        };
        let mut out = MAGIC.to_vec();
        out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        // Serialising plain data into a Vec cannot fail.
        out = postcard::to_extend(&header, out).unwrap_or_default();
        postcard::to_extend(&payload, out).unwrap_or_default()
    }

    /// A board restored from the save state `bytes`: its configuration and model are the
    /// state's, its render threads and generic-path switch the defaults of
    /// [`Board::new`]. Also returns what the header says.
    pub fn from_state(bytes: &[u8]) -> Result<(Board, StateInfo), StateError> {
        let (info, payload) = split(bytes)?;
        let (payload, rest): (Payload, &[u8]) =
            postcard::take_from_bytes(payload).map_err(|e| corrupt("payload", e))?;
        if !rest.is_empty() {
            return Err(StateError::Corrupt(format!(
                "{} bytes after the end of the state",
                rest.len()
            )));
        }
        let mut board = Board::new(info.config);
        board.set_model(info.model);
        if payload.tmus.len() != board.tmus.len() {
            return Err(StateError::Corrupt(format!(
                "{} TMU states for a board with {} TMUs",
                payload.tmus.len(),
                board.tmus.len()
            )));
        }
        if payload.dac.address >= payload.dac.pll.len() {
            return Err(StateError::Corrupt(
                "the DAC's PLL address is out of range".into(),
            ));
        }
        board
            .fbi
            .load_state(payload.fbi)
            .map_err(|e| corrupt("FBI", e))?;
        for (tmu, state) in board.tmus.iter_mut().zip(payload.tmus) {
            let index = tmu.index();
            tmu.load_state(state)
                .map_err(|e| corrupt(&format!("TMU {index}"), e))?;
        }
        let memory_fifo = MemoryFifo::from_registers(
            board.fbi.reg(addr::FBI_INIT0),
            board.fbi.reg(addr::FBI_INIT4),
            board.config.fbi_mb,
        );
        check_timing(&payload.timing, memory_fifo)?;
        board.init_enable = payload.init_enable;
        board.diagnostics = payload.diagnostics;
        board.timing_on = payload.timing_on;
        board.dac = payload.dac;
        let t = payload.timing;
        let timing = &mut board.timing;
        timing.total = t.total;
        timing.frames = t.frames;
        timing.current = t.current;
        timing.pending_bus = t.pending_bus;
        timing.pending_wait = t.pending_wait;
        timing.fraction = t.fraction;
        timing.last_swap = t.last_swap;
        timing.host = t.host;
        // The video frame follows from the video registers and the DAC.
        let regs = VideoRegs {
            h_sync: board.fbi.reg(addr::H_SYNC),
            v_sync: board.fbi.reg(addr::V_SYNC),
            fbi_init1: board.fbi.reg(addr::FBI_INIT1),
        };
        board.timing.set_video(regs, &board.dac);
        Ok((board, info))
    }

    /// Replaces this board's state with the save state `bytes`, which must be of a board
    /// of the same configuration and model ([`StateError::OtherConfig`],
    /// [`StateError::OtherModel`]). How it draws stays as it is: the render threads, the
    /// generic-path switch, the approximations of [`Board::set_method`] and the copy of
    /// the span kernels. On an error the board is unchanged. Returns what the header says.
    pub fn load_state(&mut self, bytes: &[u8]) -> Result<StateInfo, StateError> {
        let info = read_info(bytes)?;
        if info.config != self.config {
            return Err(StateError::OtherConfig {
                state: info.config,
                board: self.config,
            });
        }
        if info.model != self.model {
            return Err(StateError::OtherModel {
                state: model_name(info.model).to_owned(),
                board: model_name(self.model).to_owned(),
            });
        }
        let (mut board, info) = Board::from_state(bytes)?;
        board.set_threads(self.threads());
        board.set_generic_path(self.fbi.generic_path());
        board.set_vector_isa(self.vector_isa());
        for (loaded, tmu) in board.tmus.iter_mut().zip(&self.tmus) {
            loaded.set_approx(tmu.approx());
        }
        *self = board;
        Ok(info)
    }
}

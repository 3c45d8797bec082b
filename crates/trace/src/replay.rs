//! Replaying a trace on a [`Board`], and counting what a trace does.
//!
//! Aperture decode facts used here (spec section 4, trace-text-format.md): offsets below
//! 0x400000 are registers; bits 2-9 select the register, bits 10-13 the chip (0 = broadcast,
//! bit 10 = FBI); bits 20-21 carry the wrap/remap variants and do not change the register
//! index of the command registers (triangleCMD and ftriangleCMD keep their offsets in the
//! remapped map, spec section 5 alias table).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use sst1_board::{vote, Board, BoardConfig, BufferKind, Reference};
use sst1_regs::{addr, RegisterBus};

use crate::{DumpBuffer, Trace, TraceOp};

/// First byte of the linear frame buffer in the aperture.
const LFB_BASE: u32 = 0x40_0000;
/// First byte of texture memory in the aperture.
const TEXTURE_BASE: u32 = 0x80_0000;

/// The register byte offset (`index * 4`, 0..0x400) that an aperture write selects, or
/// `None` outside the register space.
fn register_offset(addr: u32) -> Option<u32> {
    (addr < LFB_BASE).then_some(((addr >> 2) & 0xff) << 2)
}

/// Whether a register write reaches the FBI: chip field (bits 10-13) 0 or with bit 10 set.
fn reaches_fbi(addr: u32) -> bool {
    let chips = (addr >> 10) & 0xf;
    chips == 0 || chips & 1 != 0
}

/// The FBI register offset a write selects, if it reaches the FBI.
fn fbi_register(addr: u32) -> Option<u32> {
    register_offset(addr).filter(|_| reaches_fbi(addr))
}

/// Whether a write at `addr` is a `swapbufferCMD` that reaches the FBI.
pub(crate) fn is_swap(addr: u32) -> bool {
    fbi_register(addr) == Some(addr::SWAPBUFFER_CMD)
}

/// What a trace does, counted from its ops alone.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct OpCounts {
    /// `w` ops.
    pub writes: u64,
    /// `r` ops.
    pub reads: u64,
    /// `pci` ops.
    pub pci: u64,
    /// `dump` ops.
    pub dumps: u64,
    /// Writes to the register space (below 0x400000).
    pub register_writes: u64,
    /// Writes to the linear frame buffer (0x400000-0x7fffff).
    pub lfb_writes: u64,
    /// Writes to texture memory (0x800000 and up).
    pub texture_writes: u64,
    /// Writes of `triangleCMD` or `ftriangleCMD` that reach the FBI.
    pub triangles: u64,
    /// Writes of `fastfillCMD` that reach the FBI.
    pub fastfills: u64,
    /// Writes of `swapbufferCMD` that reach the FBI.
    pub swaps: u64,
    /// Register byte offset (0..0x400, wrap and chip bits removed) → writes to it.
    pub registers: BTreeMap<u32, u64>,
}

impl OpCounts {
    /// Counts the ops of `trace`.
    pub fn of(trace: &Trace) -> Self {
        let mut counts = OpCounts::default();
        for op in &trace.ops {
            match *op {
                TraceOp::Config { .. } => {}
                TraceOp::Pci { .. } => counts.pci += 1,
                TraceOp::Read { .. } => counts.reads += 1,
                TraceOp::Dump { .. } => counts.dumps += 1,
                TraceOp::Write { addr, .. } => counts.count_write(addr),
            }
        }
        counts
    }

    fn count_write(&mut self, addr: u32) {
        self.writes += 1;
        if addr >= TEXTURE_BASE {
            self.texture_writes += 1;
        } else if addr >= LFB_BASE {
            self.lfb_writes += 1;
        }
        let Some(offset) = register_offset(addr) else {
            return;
        };
        self.register_writes += 1;
        *self.registers.entry(offset).or_default() += 1;
        if !reaches_fbi(addr) {
            return;
        }
        match offset {
            addr::TRIANGLE_CMD | addr::F_TRIANGLE_CMD => self.triangles += 1,
            addr::FASTFILL_CMD => self.fastfills += 1,
            addr::SWAPBUFFER_CMD => self.swaps += 1,
            _ => {}
        }
    }
}

/// A buffer saved at a `dump` op.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Dump {
    /// The buffer the trace named.
    pub buffer: DumpBuffer,
    /// The file name the trace gave it.
    pub file: String,
    /// Width in pixels (the video mode's, at the time of the dump).
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` raw values, row 0 first: RGB565 or depth/alpha as stored.
    pub data: Vec<u16>,
}

impl Dump {
    /// The dump file's contents: the values as little-endian `u16`.
    pub fn to_le_bytes(&self) -> Vec<u8> {
        self.data.iter().flat_map(|v| v.to_le_bytes()).collect()
    }
}

/// Expands an RGB565 value to 8 bits a channel by replicating each channel's high bits
/// into its low bits (so 0x1f → 0xff and 0 → 0).
pub fn rgb565_to_rgb8(value: u16) -> [u8; 3] {
    let r = (value >> 11) as u8;
    let g = ((value >> 5) & 0x3f) as u8;
    let b = (value & 0x1f) as u8;
    [r << 3 | r >> 2, g << 2 | g >> 4, b << 3 | b >> 2]
}

/// How many ops run between calls of the progress callback of [`execute`].
pub const PROGRESS_STEP: usize = 1 << 16;

/// Runs `ops` on `board` in order and returns the buffers the `dump` ops saved.
///
/// `config` ops do nothing (the board is built from [`Trace::board_config`] beforehand);
/// a read's recorded value is not compared. `progress` is called with the number of ops
/// done every [`PROGRESS_STEP`] ops and once at the end.
pub fn execute(ops: &[TraceOp], board: &mut Board, mut progress: impl FnMut(usize)) -> Vec<Dump> {
    let mut dumps = Vec::new();
    for (index, op) in ops.iter().enumerate() {
        match op {
            TraceOp::Config { .. } => {}
            TraceOp::Pci { offset, value } => board.pci_write(*offset, *value),
            TraceOp::Write { addr, value } => board.write32(*addr, *value),
            TraceOp::Read { addr, .. } => {
                board.read32(*addr);
            }
            TraceOp::Dump { buffer, file } => {
                let (width, height) = board.display_size();
                let data = board.dump_buffer(buffer.kind());
                dumps.push(Dump {
                    buffer: *buffer,
                    file: file.clone(),
                    width,
                    height,
                    data,
                });
            }
        }
        if (index + 1) % PROGRESS_STEP == 0 {
            progress(index + 1);
        }
    }
    progress(ops.len());
    dumps
}

/// A trace replayed once per reference emulator ([`execute_references`]).
pub struct ReferenceReplay {
    /// Each reference's board after the last op, in [`Reference::ALL`] order.
    pub boards: [Board; 3],
    /// Each reference's dumps, in the same order.
    pub per_reference: [Vec<Dump>; 3],
    /// The dumps voted pixel by pixel ([`sst1_board::vote`]): two of three, MAME's
    /// where all differ.
    pub dumps: Vec<Dump>,
}

impl ReferenceReplay {
    /// A buffer of the boards' final state, voted pixel by pixel.
    pub fn vote_buffer(&self, which: BufferKind) -> Vec<u16> {
        let [a, b, c] = self.boards.each_ref().map(|board| board.dump_buffer(which));
        vote(&a, &b, &c)
    }
}

/// Runs `ops` three times, each on a board built from `config` with one reference
/// emulator's profile ([`Reference::profile`]), on three threads, and votes each dump.
///
/// This is the conformance pass rule as a model: where the three profiles reproduce
/// their emulators, the voted dumps are the goldens' two-of-three majority, whatever
/// history each reference took to its pixels. It costs three replays. `progress` follows
/// MAME's replay, as [`execute`]'s does.
pub fn execute_references(
    ops: &[TraceOp],
    config: BoardConfig,
    progress: impl FnMut(usize),
) -> ReferenceReplay {
    let replay = |reference: Reference, progress: &mut dyn FnMut(usize)| {
        let mut board = Board::new(config);
        board.set_profile(reference.profile());
        let dumps = execute(ops, &mut board, progress);
        (board, dumps)
    };
    let [mame, dosbox, box86] = Reference::ALL;
    let (first, second, third) = std::thread::scope(|scope| {
        let second = scope.spawn(|| replay(dosbox, &mut |_| {}));
        let third = scope.spawn(|| replay(box86, &mut |_| {}));
        let mut progress = progress;
        let first = replay(mame, &mut progress);
        let join = |handle: std::thread::ScopedJoinHandle<'_, (Board, Vec<Dump>)>| {
            handle
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
        };
        (first, join(second), join(third))
    });
    let dumps = first
        .1
        .iter()
        .zip(&second.1)
        .zip(&third.1)
        .map(|((a, b), c)| Dump {
            buffer: a.buffer,
            file: a.file.clone(),
            width: a.width,
            height: a.height,
            data: vote(&a.data, &b.data, &c.data),
        })
        .collect();
    ReferenceReplay {
        boards: [first.0, second.0, third.0],
        per_reference: [first.1, second.1, third.1],
        dumps,
    }
}

/// A replay's output could not be written.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {source}")]
pub struct ReplayError {
    /// The file that could not be written.
    pub path: PathBuf,
    /// What the OS said.
    pub source: std::io::Error,
}

/// Writes each dump to `out_dir`/its file name; returns the paths written.
pub fn write_dumps(dumps: &[Dump], out_dir: &Path) -> Result<Vec<PathBuf>, ReplayError> {
    dumps
        .iter()
        .map(|dump| {
            let path = out_dir.join(&dump.file);
            std::fs::write(&path, dump.to_le_bytes())
                .map(|()| path.clone())
                .map_err(|source| ReplayError { path, source })
        })
        .collect()
}

/// Runs `ops` on `board` and writes the dumps into `out_dir` (which must exist); returns
/// the dumps.
pub fn replay(
    ops: &[TraceOp],
    board: &mut Board,
    out_dir: &Path,
) -> Result<Vec<Dump>, ReplayError> {
    let dumps = execute(ops, board, |_| {});
    write_dumps(&dumps, out_dir)?;
    Ok(dumps)
}

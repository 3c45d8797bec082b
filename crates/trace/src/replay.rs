//! Replaying a trace on a [`Board`], and counting what a trace does.
//!
//! Aperture decode facts used here (spec section 4, trace-text-format.md): offsets below
//! 0x400000 are registers; bits 2-9 select the register, bits 10-13 the chip (0 = broadcast,
//! bit 10 = FBI); bits 20-21 carry the wrap/remap variants and do not change the register
//! index of the command registers (triangleCMD and ftriangleCMD keep their offsets in the
//! remapped map, spec section 5 alias table).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{mpsc, Arc};

use sst1_board::{vote, Board, BoardConfig, BufferKind, Deferred, Reference};
use sst1_regs::{addr, RegisterBus};

use crate::output::{DumpDir, OutputError};
use crate::{DumpBuffer, LoadError, Trace, TraceOp};

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
#[inline]
pub(crate) fn is_swap(addr: u32) -> bool {
    // `fbi_register(addr) == Some(SWAPBUFFER_CMD)`, its cheapest test first: this runs
    // for every write a binary trace replays.
    addr & 0x3fc == addr::SWAPBUFFER_CMD && fbi_register(addr).is_some()
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
    /// `wait` ops.
    pub waits: u64,
    /// Graphics-clock cycles the `wait` ops ask for in all (saturating).
    pub wait_cycles: u64,
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
            counts.add(op);
        }
        counts
    }

    /// Counts one more op (for counting a stream).
    pub fn add(&mut self, op: &TraceOp) {
        match *op {
            TraceOp::Config { .. } => {}
            TraceOp::Pci { .. } => self.pci += 1,
            TraceOp::Read { .. } => self.reads += 1,
            TraceOp::Dump { .. } => self.dumps += 1,
            TraceOp::Wait { cycles } => {
                self.waits += 1;
                self.wait_cycles = self.wait_cycles.saturating_add(cycles);
            }
            TraceOp::Write { addr, .. } => self.count_write(addr),
        }
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
        let mut out = Vec::with_capacity(self.data.len() * 2);
        for v in &self.data {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out
    }

    /// Writes the dump file's contents ([`Dump::to_le_bytes`]) to `out`, a piece at a time
    /// (no copy of the whole dump).
    pub fn write_le(&self, out: &mut dyn std::io::Write) -> std::io::Result<()> {
        let mut piece = [0u8; 8192];
        for values in self.data.chunks(piece.len() / 2) {
            for (bytes, v) in piece.chunks_exact_mut(2).zip(values) {
                bytes.copy_from_slice(&v.to_le_bytes());
            }
            out.write_all(&piece[..values.len() * 2])?;
        }
        Ok(())
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

/// Why a replay stopped.
#[derive(Debug, thiserror::Error)]
pub enum ReplayError {
    /// The trace is malformed or could not be read (the ops before the fault have run).
    #[error(transparent)]
    Load(#[from] LoadError),
    /// A dump could not be written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// A dump sink failed for a reason of its own.
    #[error("{0}")]
    Sink(String),
}

/// [`step`] in a run of writes that may queue small triangles for a render thread
/// ([`Board::deferred`]): a write is queued behind them, anything else waits for them.
fn step_in(run: &mut Deferred<&mut Board>, op: &TraceOp) -> Option<Dump> {
    match op {
        TraceOp::Write { addr, value } => {
            run.write32(*addr, *value);
            None
        }
        _ => step(run.board(), op),
    }
}

/// Runs one op on `board`; a `dump` op returns the buffer it saves.
#[inline]
fn step(board: &mut Board, op: &TraceOp) -> Option<Dump> {
    match op {
        TraceOp::Config { .. } => {}
        TraceOp::Pci { offset, value } => board.pci_write(*offset, *value),
        TraceOp::Write { addr, value } => board.write32(*addr, *value),
        TraceOp::Read { addr, .. } => {
            board.read32(*addr);
        }
        TraceOp::Wait { cycles } => board.host_wait(*cycles),
        TraceOp::Dump { buffer, file } => {
            let (width, height) = board.display_size();
            return Some(Dump {
                buffer: *buffer,
                file: file.clone(),
                width,
                height,
                data: board.dump_buffer(buffer.kind()),
            });
        }
    }
    None
}

/// Runs `ops` on `board` in order and returns the buffers the `dump` ops saved.
///
/// `config` ops do nothing (the board is built from [`Trace::board_config`] beforehand);
/// a read's recorded value is not compared. `progress` is called with the number of ops
/// done every [`PROGRESS_STEP`] ops and once at the end. The dumps are held in memory:
/// [`execute_stream`] hands each to a sink instead.
pub fn execute(ops: &[TraceOp], board: &mut Board, mut progress: impl FnMut(usize)) -> Vec<Dump> {
    let mut dumps = Vec::new();
    let mut run = board.deferred();
    for (index, op) in ops.iter().enumerate() {
        dumps.extend(step_in(&mut run, op));
        if (index + 1) % PROGRESS_STEP == 0 {
            progress(index + 1);
        }
    }
    progress(ops.len());
    dumps
}

/// Runs a stream of ops on `board` in order, as they are read, and hands each dump to
/// `sink` when it is reached: memory does not grow with the trace's length or its number
/// of dumps. Stops at the first bad op or failed dump (the ops before it have run).
/// Returns the number of ops run. `progress` as for [`execute`].
pub fn execute_stream(
    ops: impl IntoIterator<Item = Result<TraceOp, LoadError>>,
    board: &mut Board,
    mut progress: impl FnMut(usize),
    mut sink: impl FnMut(Dump) -> Result<(), ReplayError>,
) -> Result<usize, ReplayError> {
    let mut done = 0;
    let mut run = board.deferred();
    for op in ops {
        if let Some(dump) = step_in(&mut run, &op?) {
            sink(dump)?;
        }
        done += 1;
        if done % PROGRESS_STEP == 0 {
            progress(done);
        }
    }
    progress(done);
    Ok(done)
}

/// Plain writes [`execute_trace_stream`] takes from the reader at a time and hands the
/// board together ([`Board::write32_all`]).
const WRITE_RUN: usize = 64;

/// [`execute_stream`] for a trace file's stream: runs at most `limit` ops of `stream`
/// (all with `None`) on `board`, handing each dump to `sink`, and returns how many ran.
/// The same ops in the same order as `execute_stream(stream.by_ref().take(limit), ..)`,
/// with the same progress calls; plain writes, the replay's most common step, go from
/// the reader's buffer to the board without an op built for each, a run at a time
/// ([`crate::TraceStream::next_writes`], [`Board::write32_all`]).
pub fn execute_trace_stream(
    stream: &mut crate::TraceStream<'_>,
    limit: Option<usize>,
    board: &mut Board,
    mut progress: impl FnMut(usize),
    mut sink: impl FnMut(Dump) -> Result<(), ReplayError>,
) -> Result<usize, ReplayError> {
    let limit = limit.unwrap_or(usize::MAX);
    let mut done = 0;
    let mut next_progress = PROGRESS_STEP;
    let mut writes = [(0u32, 0u32); WRITE_RUN];
    let mut run = board.deferred();
    while done < limit {
        let writes_end = limit.min(next_progress);
        while done < writes_end {
            let room = (writes_end - done).min(WRITE_RUN);
            let n = stream.next_writes(&mut writes[..room]);
            if n == 0 {
                break;
            }
            run.write32_all(&writes[..n]);
            done += n;
        }
        if done < writes_end {
            let Some(op) = stream.next() else {
                break;
            };
            if let Some(dump) = step_in(&mut run, &op?) {
                sink(dump)?;
            }
            done += 1;
        }
        if done == next_progress {
            progress(done);
            next_progress = next_progress.saturating_add(PROGRESS_STEP);
        }
    }
    progress(done);
    Ok(done)
}

/// A dump of the reference vote: each reference's buffer and the vote of the three.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReferenceDump {
    /// The dump voted pixel by pixel ([`sst1_board::vote`]): two of three, MAME's where
    /// all differ.
    pub voted: Dump,
    /// Each reference's dump, in [`Reference::ALL`] order.
    pub references: [Dump; 3],
}

/// A trace replayed once per reference emulator ([`execute_references`]).
pub struct ReferenceReplay {
    /// Each reference's board after the last op, in [`Reference::ALL`] order.
    pub boards: [Board; 3],
    /// Each reference's dumps, in the same order.
    pub per_reference: [Vec<Dump>; 3],
    /// The dumps voted pixel by pixel ([`sst1_board::vote`]): two of three, MAME's where
    /// all differ.
    pub dumps: Vec<Dump>,
}

impl ReferenceReplay {
    /// A buffer of the boards' final state, voted pixel by pixel.
    pub fn vote_buffer(&self, which: BufferKind) -> Vec<u16> {
        vote_buffer(&self.boards, which)
    }
}

/// A buffer of three boards' state, voted pixel by pixel.
pub fn vote_buffer(boards: &[Board; 3], which: BufferKind) -> Vec<u16> {
    let [a, b, c] = boards.each_ref().map(|board| board.dump_buffer(which));
    vote(&a, &b, &c)
}

/// Runs `ops` three times, each on a board built from `config` with one reference
/// emulator's profile ([`Reference::profile`]), on three threads, and votes each dump.
///
/// This is the conformance pass rule as a model: where the three profiles reproduce
/// their emulators, the voted dumps are the goldens' two-of-three majority, whatever
/// history each reference took to its pixels. It costs three replays. The dumps are held
/// in memory ([`execute_references_stream`] hands each to a sink instead).
pub fn execute_references(
    ops: &[TraceOp],
    config: BoardConfig,
    progress: impl FnMut(usize),
) -> ReferenceReplay {
    let mut dumps = Vec::new();
    let mut per_reference: [Vec<Dump>; 3] = Default::default();
    let result = execute_references_stream(
        ops.iter().cloned().map(Ok),
        config,
        progress,
        |dump: ReferenceDump| {
            dumps.push(dump.voted);
            for (list, dump) in per_reference.iter_mut().zip(dump.references) {
                list.push(dump);
            }
            Ok(())
        },
    );
    // Neither the ops (all valid) nor the sink (infallible) can fail.
    let boards = match result {
        Ok(boards) => boards,
        Err(e) => unreachable!("in-memory reference replay failed: {e}"),
    };
    ReferenceReplay {
        boards,
        per_reference,
        dumps,
    }
}

/// Ops handed to the reference boards at a time.
const CHUNK_OPS: usize = 4096;
/// Chunks queued for each reference board (bounds the memory of the read-ahead).
const CHUNKS_QUEUED: usize = 2;

/// One reference board's thread: runs the chunks it receives and sends back each dump.
fn reference_worker(
    reference: Reference,
    config: BoardConfig,
    chunks: mpsc::Receiver<Arc<Vec<TraceOp>>>,
    dumps: mpsc::Sender<Dump>,
) -> Board {
    let mut board = Board::new(config);
    board.set_profile(reference.profile());
    for chunk in chunks {
        for op in chunk.iter() {
            if let Some(dump) = step(&mut board, op) {
                if dumps.send(dump).is_err() {
                    return board;
                }
            }
        }
    }
    board
}

/// Runs a stream of ops on three boards, one per reference emulator's profile
/// ([`Reference::profile`]), each on its own thread, reading the stream once; hands each
/// dump, voted ([`sst1_board::vote`]) and per reference, to `sink` when all three have
/// reached it. Memory is bounded: the ops are passed on in chunks of a few thousand, at
/// most a few chunks ahead of the slowest board, and only the dump in hand is held.
///
/// Returns the three boards after the last op, in [`Reference::ALL`] order. Stops at the
/// first bad op or failed dump. `progress` is called with the number of ops read every
/// [`PROGRESS_STEP`] ops and once at the end.
pub fn execute_references_stream(
    ops: impl IntoIterator<Item = Result<TraceOp, LoadError>>,
    config: BoardConfig,
    mut progress: impl FnMut(usize),
    mut sink: impl FnMut(ReferenceDump) -> Result<(), ReplayError>,
) -> Result<[Board; 3], ReplayError> {
    std::thread::scope(|scope| {
        let mut senders = Vec::new();
        let mut receivers = Vec::new();
        let mut handles = Vec::new();
        for reference in Reference::ALL {
            let (chunk_tx, chunk_rx) = mpsc::sync_channel(CHUNKS_QUEUED);
            let (dump_tx, dump_rx) = mpsc::channel();
            senders.push(chunk_tx);
            receivers.push(dump_rx);
            handles
                .push(scope.spawn(move || reference_worker(reference, config, chunk_rx, dump_tx)));
        }
        // Hands a chunk to every board; if its last op is a dump, waits for the three
        // dumps and passes them on. `Ok(false)`: a board thread has stopped (it panicked;
        // the join below reports it).
        let mut dispatch = |chunk: Vec<TraceOp>| -> Result<bool, ReplayError> {
            let ends_in_dump = matches!(chunk.last(), Some(TraceOp::Dump { .. }));
            let chunk = Arc::new(chunk);
            for tx in &senders {
                if tx.send(Arc::clone(&chunk)).is_err() {
                    return Ok(false);
                }
            }
            if ends_in_dump {
                let mut got = Vec::with_capacity(3);
                for rx in &receivers {
                    match rx.recv() {
                        Ok(dump) => got.push(dump),
                        Err(_) => return Ok(false),
                    }
                }
                let Ok::<[Dump; 3], _>(references) = got.try_into() else {
                    return Ok(false);
                };
                let [a, b, c] = &references;
                let voted = Dump {
                    buffer: a.buffer,
                    file: a.file.clone(),
                    width: a.width,
                    height: a.height,
                    data: vote(&a.data, &b.data, &c.data),
                };
                sink(ReferenceDump { voted, references })?;
            }
            Ok(true)
        };
        let mut outcome = Ok(());
        let mut chunk = Vec::with_capacity(CHUNK_OPS);
        let mut done = 0;
        for op in ops {
            let op = match op {
                Ok(op) => op,
                Err(e) => {
                    outcome = Err(ReplayError::from(e));
                    break;
                }
            };
            let is_dump = matches!(op, TraceOp::Dump { .. });
            chunk.push(op);
            done += 1;
            if done % PROGRESS_STEP == 0 {
                progress(done);
            }
            if is_dump || chunk.len() == CHUNK_OPS {
                let full = std::mem::replace(&mut chunk, Vec::with_capacity(CHUNK_OPS));
                match dispatch(full) {
                    Ok(true) => {}
                    Ok(false) => break,
                    Err(e) => {
                        outcome = Err(e);
                        break;
                    }
                }
            }
        }
        if outcome.is_ok() && !chunk.is_empty() {
            outcome = dispatch(chunk).map(|_| ());
        }
        progress(done);
        drop(senders);
        drop(receivers);
        let mut boards = Vec::with_capacity(3);
        for handle in handles {
            match handle.join() {
                Ok(board) => boards.push(board),
                Err(panic) => std::panic::resume_unwind(panic),
            }
        }
        outcome?;
        boards
            .try_into()
            .map_err(|_| ReplayError::Sink("a reference board was lost".to_owned()))
    })
}

/// Writes each dump to `out_dir`/its file name ([`DumpDir::write`]: never through a
/// link, never over anything but an earlier dump); returns the paths written.
pub fn write_dumps(dumps: &[Dump], out_dir: &Path) -> Result<Vec<PathBuf>, ReplayError> {
    let dir = DumpDir::existing(out_dir);
    dumps
        .iter()
        .map(|dump| Ok(dir.write_with(&dump.file, |out| dump.write_le(out))?))
        .collect()
}

/// Runs a stream of ops on `board` and writes each dump into `out_dir` (which must
/// exist) when it is reached ([`DumpDir::write`]); returns the number of dumps written.
pub fn replay(
    ops: impl IntoIterator<Item = Result<TraceOp, LoadError>>,
    board: &mut Board,
    out_dir: &Path,
) -> Result<usize, ReplayError> {
    let dir = DumpDir::existing(out_dir);
    let mut written = 0;
    execute_stream(
        ops,
        board,
        |_| {},
        |dump| {
            dir.write(&dump.file, &dump.to_le_bytes())?;
            written += 1;
            Ok(())
        },
    )?;
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quick swap test answers as the register decode does, for every register
    /// offset under every chip field and wrap bit, and past the register space.
    #[test]
    fn is_swap_is_the_decoded_register() {
        for high in [
            0u32,
            0x10_0000,
            0x20_0000,
            0x30_0000,
            0x40_0000,
            0x80_0000,
            0xff00_0000,
        ] {
            for chips in 0..16u32 {
                for offset in (0..0x400u32).step_by(4) {
                    for low in 0..4 {
                        let a = high | chips << 10 | offset | low;
                        let decoded = fbi_register(a) == Some(addr::SWAPBUFFER_CMD);
                        assert_eq!(is_swap(a), decoded, "{a:#x}");
                    }
                }
            }
        }
    }
}

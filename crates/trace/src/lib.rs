//! SST-1 register traces: the plain-text write-log, our binary format, a recording bus
//! wrapper and the replayer.
//!
//! A trace is what a driver does to the board through its PCI interface (spec sections 4
//! and 6): configuration-space writes, 32-bit writes and reads in the 16 MiB aperture,
//! plus `dump` points where a replayer saves a buffer, and `wait` ops where host time
//! passes between accesses. The plain-text form is defined in
//! `shared/docs/trace-text-format.md`; [`text`] reads and writes it, [`binary`] is our own
//! compact form for recording and fast replay, and both hold exactly the same [`TraceOp`]
//! stream, so conversion is lossless in both directions (text comments aside).
//!
//! * [`TraceReader`] / [`open_trace`] / [`stream_trace`]: read either form, gzip-compressed
//!   or not, op by op, in memory independent of the trace's length.
//! * [`read_trace`] / [`load_trace`]: read a whole trace into memory (bounded:
//!   [`MAX_TRACE_OPS`], [`MAX_DECOMPRESSED`]).
//! * [`Recorder`]: wraps any [`RegisterBus`](sst1_regs::RegisterBus) and logs every call
//!   as the board decodes it.
//! * [`execute_stream`] / [`execute_references_stream`]: drive one board, or the
//!   three-reference vote, with a stream of ops, handing each dump to a sink when it is
//!   reached; [`execute`] / [`execute_references`] / [`replay`] for ops in memory.
//! * [`DumpDir`]: writes dumps into a folder without following links or replacing
//!   anything but earlier dumps.
//! * [`OpCounts`]: what a trace does (writes, triangles, fills, swaps, registers touched).
//! * [`judge`]: the conformance pass rule for a dump against the reference goldens.
//! * [`scenes`]: generated scenes (small triangles, random drawing states) as seeded text
//!   traces.
//!
//! Error messages that show input quote it with [`quote`], cut to a few dozen characters.

pub mod binary;
pub mod judge;
pub mod output;
mod read;
mod recorder;
mod replay;
pub mod scenes;
pub mod text;
mod writer;

use std::io::Read;
use std::path::{Path, PathBuf};

use sst1_board::{BoardConfig, BufferKind};

pub use binary::{decode_binary, encode_binary, BinaryError, BinaryReader};
pub use output::{write_file_replacing, DumpDir, OutputError};
pub use read::{open_trace, stream_trace, TraceReader, TraceStream, MAX_PREFIX_OPS};
pub use recorder::{recorded_addr, recorded_pci_offset, OpLog, Recorder, PCI_UNDECODED};
pub use replay::{
    execute, execute_references, execute_references_stream, execute_stream, execute_trace_stream,
    replay, rgb565_to_rgb8, vote_buffer, write_dumps, Dump, OpCounts, ReferenceDump,
    ReferenceReplay, ReplayError, PROGRESS_STEP,
};
pub use text::{parse_text, write_text, ParseError, TextReader};
pub use writer::TraceWriter;

/// One `config` setting of the board a trace runs on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ConfigKey {
    /// `fbi_mb`: frame-buffer memory in MiB (2 or 4).
    FbiMb,
    /// `tmus`: number of TMUs (1, 2 or 3).
    Tmus,
    /// `tmu_mb`: texture memory per TMU in MiB (1, 2 or 4).
    TmuMb,
}

impl ConfigKey {
    /// Every key, in the order the text writer emits them.
    pub const ALL: [ConfigKey; 3] = [ConfigKey::FbiMb, ConfigKey::Tmus, ConfigKey::TmuMb];

    /// The key's name in the text format.
    pub fn name(self) -> &'static str {
        match self {
            ConfigKey::FbiMb => "fbi_mb",
            ConfigKey::Tmus => "tmus",
            ConfigKey::TmuMb => "tmu_mb",
        }
    }

    /// The key named `name` in the text format.
    pub fn from_name(name: &str) -> Option<ConfigKey> {
        ConfigKey::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The values the key accepts (trace-text-format.md, `config` lines).
    pub fn allowed(self) -> &'static [u32] {
        match self {
            ConfigKey::FbiMb => &[2, 4],
            ConfigKey::Tmus => &[1, 2, 3],
            ConfigKey::TmuMb => &[1, 2, 4],
        }
    }

    /// What the key accepts, in words, for error messages.
    pub fn expected(self) -> &'static str {
        match self {
            ConfigKey::FbiMb => "fbi_mb 2 or 4",
            ConfigKey::Tmus => "tmus 1, 2 or 3",
            ConfigKey::TmuMb => "tmu_mb 1, 2 or 4",
        }
    }
}

/// The buffer a `dump` line names. `Depth` and `Aux` read the same buffer; both are kept
/// so that a trace converts back to the exact text it came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DumpBuffer {
    /// `front`: the displayed colour buffer.
    Front,
    /// `back`: the colour buffer being drawn.
    Back,
    /// `depth`: the aux buffer (depth or alpha).
    Depth,
    /// `aux`: another name for `depth`.
    Aux,
}

impl DumpBuffer {
    /// Every buffer name.
    pub const ALL: [DumpBuffer; 4] = [
        DumpBuffer::Front,
        DumpBuffer::Back,
        DumpBuffer::Depth,
        DumpBuffer::Aux,
    ];

    /// The buffer's name in the text format.
    pub fn name(self) -> &'static str {
        match self {
            DumpBuffer::Front => "front",
            DumpBuffer::Back => "back",
            DumpBuffer::Depth => "depth",
            DumpBuffer::Aux => "aux",
        }
    }

    /// The buffer named `name` in the text format.
    pub fn from_name(name: &str) -> Option<DumpBuffer> {
        DumpBuffer::ALL.into_iter().find(|b| b.name() == name)
    }

    /// The board buffer this name reads.
    pub fn kind(self) -> BufferKind {
        match self {
            DumpBuffer::Front => BufferKind::Front,
            DumpBuffer::Back => BufferKind::Back,
            DumpBuffer::Depth | DumpBuffer::Aux => BufferKind::Aux,
        }
    }

    /// Whether the buffer holds depth/alpha values rather than RGB565 colours.
    pub fn is_aux(self) -> bool {
        self.kind() == BufferKind::Aux
    }
}

/// One step of a trace.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TraceOp {
    /// `config KEY VALUE`: a board setting; the last one of a key wins.
    Config {
        /// Which setting.
        key: ConfigKey,
        /// Its value, one of [`ConfigKey::allowed`].
        value: u32,
    },
    /// `pci OFFSET VALUE`: a PCI configuration-space write (spec section 6).
    Pci {
        /// Byte offset in configuration space, 4-aligned, below 0x100.
        offset: u32,
        /// The 32-bit value written.
        value: u32,
    },
    /// `w OFFSET VALUE`: one 32-bit write in the aperture (spec section 4).
    Write {
        /// Byte offset in the 16 MiB aperture, 4-aligned.
        addr: u32,
        /// The 32-bit value written.
        value: u32,
    },
    /// `r OFFSET [VALUE]`: one 32-bit read in the aperture, with the value the recording
    /// saw if it was recorded. An extension of the shared text format (which has no reads);
    /// the conformance traces contain none.
    Read {
        /// Byte offset in the 16 MiB aperture, 4-aligned.
        addr: u32,
        /// The value the recorded read returned, if known.
        value: Option<u32>,
    },
    /// `wait CYCLES`: host time passes with no bus access, `cycles` cycles of the
    /// replaying board's graphics clock (50 per microsecond at the default 50 MHz). The
    /// board's engine runs on meanwhile, so a `status` read after it sees less busy and
    /// more FIFO free space (docs/timing.md). Our extension of the shared text format; a
    /// trace without it replays as if no host time passed between accesses.
    Wait {
        /// Graphics-clock cycles of host time.
        cycles: u64,
    },
    /// `dump BUFFER FILE`: save a buffer as it is at this point.
    Dump {
        /// The buffer to save.
        buffer: DumpBuffer,
        /// A bare file name (see [`check_dump_name`]).
        file: String,
    },
}

/// Size of the PCI aperture in bytes (spec section 4: 16 MiB).
pub const APERTURE_SIZE: u32 = 0x100_0000;
/// Size of PCI configuration space in bytes (spec section 6).
pub const PCI_CONFIG_SIZE: u32 = 0x100;

/// What [`check_addr`] accepts, in words.
pub(crate) const ADDR_RULE: &str = "a 4-aligned aperture offset below 0x1000000";
/// What [`check_pci_offset`] accepts, in words.
pub(crate) const PCI_RULE: &str = "a 4-aligned PCI configuration offset below 0x100";
/// What [`check_dump_name`] accepts, in words.
pub(crate) const DUMP_NAME_RULE: &str =
    "a bare file name (no path separators, whitespace or `#`, at most 255 bytes)";

/// Checks an aperture offset: below [`APERTURE_SIZE`] and 4-aligned.
pub fn check_addr(addr: u32) -> Result<(), &'static str> {
    if addr < APERTURE_SIZE && addr.is_multiple_of(4) {
        Ok(())
    } else {
        Err(ADDR_RULE)
    }
}

/// Checks a configuration-space offset: below [`PCI_CONFIG_SIZE`] and 4-aligned.
pub fn check_pci_offset(offset: u32) -> Result<(), &'static str> {
    if offset < PCI_CONFIG_SIZE && offset.is_multiple_of(4) {
        Ok(())
    } else {
        Err(PCI_RULE)
    }
}

/// Checks a dump file name: a bare name, so a replayer can only write inside its output
/// folder, and one text token (no whitespace, no `#`).
pub fn check_dump_name(file: &str) -> Result<(), &'static str> {
    let bad_char = |c: char| c.is_whitespace() || c.is_control() || matches!(c, '/' | '\\' | '#');
    if file.is_empty() || file == "." || file == ".." || file.len() > 255 || file.contains(bad_char)
    {
        Err(DUMP_NAME_RULE)
    } else {
        Ok(())
    }
}

/// How much of a quoted piece of input an error message shows, in bytes.
pub const QUOTE_MAX: usize = 40;

/// Quotes a piece of input for an error message: in backticks, control characters
/// escaped, and cut to about [`QUOTE_MAX`] bytes with its full length said, so that a
/// hostile input cannot make a message long (or write terminal escapes to stderr). Every
/// error message of this crate that shows input uses it.
pub fn quote(input: &str) -> String {
    let mut shown = String::new();
    let mut cut = false;
    for (at, c) in input.char_indices() {
        if shown.len() >= QUOTE_MAX {
            cut = at < input.len();
            break;
        }
        if c.is_control() {
            shown.extend(c.escape_default());
        } else {
            shown.push(c);
        }
    }
    if cut {
        format!("`{shown}…` ({} bytes)", input.len())
    } else {
        format!("`{shown}`")
    }
}

/// A whole trace: the ops in order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Trace {
    /// The ops in the order they were recorded.
    pub ops: Vec<TraceOp>,
}

impl Trace {
    /// The board the trace runs on: defaults overridden by its `config` ops, the last one of
    /// a key winning.
    pub fn board_config(&self) -> BoardConfig {
        let mut config = BoardConfig::default();
        for op in &self.ops {
            apply_config(&mut config, op);
        }
        config
    }
}

/// Applies `op` to `config` if it is a `config` op.
pub(crate) fn apply_config(config: &mut BoardConfig, op: &TraceOp) {
    if let TraceOp::Config { key, value } = *op {
        match key {
            ConfigKey::FbiMb => config.fbi_mb = value,
            ConfigKey::Tmus => config.tmus = value,
            ConfigKey::TmuMb => config.tmu_mb = value,
        }
    }
}

/// Largest decompressed size a whole-trace read ([`read_trace`], [`load_trace`],
/// [`parse_text`]) or [`gunzip_if_needed`] accepts from a gzip stream (hostile-input
/// guard). Streaming readers ([`TraceReader`]) hold no decompressed bytes and have no cap.
pub const MAX_DECOMPRESSED: u64 = 1 << 30;

/// Most ops a whole-trace read ([`read_trace`], [`load_trace`], [`parse_text`],
/// [`decode_binary`]) holds in memory: 2^24 (about 16.8 million, 512 MiB), a hundred
/// times the longest trace in the repository. Replay streams traces of any length.
pub const MAX_TRACE_OPS: usize = 1 << 24;

/// Gzip's magic bytes.
pub(crate) const GZIP_MAGIC: [u8; 2] = [0x1f, 0x8b];

/// A reader that fails with [`std::io::ErrorKind::InvalidData`] once `inner` yields more
/// than `limit` bytes, reading nothing beyond the limit (a decompression cap in constant
/// memory).
pub(crate) struct Capped<R> {
    inner: R,
    left: u64,
    limit: u64,
}

impl<R> Capped<R> {
    pub(crate) fn new(inner: R, limit: u64) -> Self {
        Self {
            inner,
            left: limit,
            limit,
        }
    }
}

/// The error of a [`Capped`] reader past its limit.
fn too_large(limit: u64) -> std::io::Error {
    let size = if limit.is_multiple_of(1 << 30) {
        format!("{} GiB", limit >> 30)
    } else {
        format!("{limit} bytes")
    };
    std::io::Error::new(
        std::io::ErrorKind::InvalidData,
        format!("decompressed trace larger than {size}"),
    )
}

impl<R: Read> Read for Capped<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if buf.is_empty() {
            return Ok(0);
        }
        if self.left == 0 {
            // At the limit: one more byte means the input is too large.
            let mut probe = [0u8; 1];
            return match self.inner.read(&mut probe)? {
                0 => Ok(0),
                _ => Err(too_large(self.limit)),
            };
        }
        let want = buf
            .len()
            .min(usize::try_from(self.left).unwrap_or(usize::MAX));
        let n = self.inner.read(&mut buf[..want])?;
        self.left -= n as u64;
        Ok(n)
    }
}

/// Reads all of `input`, at most `limit` bytes: an [`std::io::ErrorKind::InvalidData`]
/// error if there is more. The buffer never grows past `limit + 1` bytes, so memory is
/// bounded by the limit (not by twice it, as with `read_to_end`).
pub fn read_bounded(input: impl Read, limit: u64) -> std::io::Result<Vec<u8>> {
    let limit_plus_one = usize::try_from(limit.saturating_add(1)).unwrap_or(usize::MAX);
    let mut input = input.take(limit.saturating_add(1));
    let mut out: Vec<u8> = Vec::new();
    let mut chunk = vec![0u8; 64 << 10];
    loop {
        let n = match input.read(&mut chunk) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        };
        let needed = out.len() + n;
        if needed > out.capacity() {
            // Double, but never past limit + 1 (the take above keeps `needed` within it).
            let capacity = out
                .capacity()
                .saturating_mul(2)
                .max(needed)
                .min(limit_plus_one);
            out.reserve_exact(capacity.max(needed) - out.len());
        }
        out.extend_from_slice(&chunk[..n]);
    }
    if out.len() as u64 > limit {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("larger than {limit} bytes"),
        ));
    }
    Ok(out)
}

/// Reads a whole file of at most `limit` bytes ([`read_bounded`]); the error names the
/// path.
pub fn read_file_bounded(path: &Path, limit: u64) -> Result<Vec<u8>, LoadError> {
    let io = |source| LoadError::Io {
        path: path.to_owned(),
        source,
    };
    let file = std::fs::File::open(path).map_err(io)?;
    read_bounded(file, limit).map_err(io)
}

/// Decompresses `bytes` if they start with gzip's magic bytes; returns them as they are
/// otherwise. At most [`MAX_DECOMPRESSED`] bytes, held once (the buffer never grows past
/// the cap).
pub fn gunzip_if_needed(bytes: &[u8]) -> std::io::Result<std::borrow::Cow<'_, [u8]>> {
    gunzip_with_limit(bytes, MAX_DECOMPRESSED)
}

/// [`gunzip_if_needed`] with a cap of `limit` decompressed bytes.
pub fn gunzip_with_limit(bytes: &[u8], limit: u64) -> std::io::Result<std::borrow::Cow<'_, [u8]>> {
    if !bytes.starts_with(&GZIP_MAGIC) {
        return Ok(std::borrow::Cow::Borrowed(bytes));
    }
    let decoder = flate2::bufread::MultiGzDecoder::new(bytes);
    let out = read_bounded(Capped::new(decoder, limit), limit)?;
    Ok(std::borrow::Cow::Owned(out))
}

/// Why a trace could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the OS said.
        source: std::io::Error,
    },
    /// The text form is malformed (or its gzip stream is).
    #[error(transparent)]
    Text(#[from] ParseError),
    /// The binary form is malformed.
    #[error("{file}: {source}")]
    Binary {
        /// The file's name.
        file: String,
        /// What is wrong.
        source: BinaryError,
    },
    /// A whole-trace read met more than [`MAX_TRACE_OPS`] ops.
    #[error("{file}: more than {limit} ops, the most a whole trace read into memory may hold (replay streams traces of any length)")]
    TooManyOps {
        /// The file's name.
        file: String,
        /// The limit.
        limit: usize,
    },
    /// A stream that cannot be read twice holds more than [`MAX_PREFIX_OPS`] ops before
    /// its first `w` or `r`, so its board (set by `config` ops, which may come anywhere
    /// before the first `w` or `r`) is not known within bounded memory.
    #[error("{file}: more than {limit} ops before the first write or read; cannot tell the board configuration from a stream without reading it twice (give a regular file)")]
    LongPrefix {
        /// The file's name.
        file: String,
        /// The limit.
        limit: usize,
    },
}

/// Reads a whole trace in either form from `bytes`: gzip is recognised by its magic bytes,
/// the binary form by [`binary::MAGIC`], anything else is parsed as text. `file` names
/// the source in error messages. At most [`MAX_TRACE_OPS`] ops and [`MAX_DECOMPRESSED`]
/// decompressed bytes; memory is the ops alone (no copy of the decompressed input).
pub fn read_trace(file: &str, bytes: &[u8]) -> Result<Trace, LoadError> {
    collect_ops(TraceReader::with_limit(
        file,
        bytes,
        Some(MAX_DECOMPRESSED),
    )?)
}

/// Reads a whole trace file in either form (see [`read_trace`]; the same limits).
pub fn load_trace(path: &Path) -> Result<Trace, LoadError> {
    let file = std::fs::File::open(path).map_err(|source| LoadError::Io {
        path: path.to_owned(),
        source,
    })?;
    let name = path.display().to_string();
    collect_ops(TraceReader::with_limit(
        &name,
        file,
        Some(MAX_DECOMPRESSED),
    )?)
}

/// Collects a reader's ops, at most [`MAX_TRACE_OPS`] of them.
fn collect_ops(reader: TraceReader<'_>) -> Result<Trace, LoadError> {
    let file = reader.file().to_owned();
    let mut ops = Vec::new();
    for op in reader {
        if ops.len() == MAX_TRACE_OPS {
            return Err(LoadError::TooManyOps {
                file,
                limit: MAX_TRACE_OPS,
            });
        }
        ops.push(op?);
    }
    Ok(Trace { ops })
}

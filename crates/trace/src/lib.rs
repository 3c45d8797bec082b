//! SST-1 register traces: the plain-text write-log, our binary format, a recording bus
//! wrapper and the replayer.
//!
//! A trace is what a driver does to the board through its PCI interface (spec sections 4
//! and 6): configuration-space writes, 32-bit writes and reads in the 16 MiB aperture,
//! plus `dump` points where a replayer saves a buffer. The plain-text form is defined in
//! `shared/docs/trace-text-format.md`; [`text`] reads and writes it, [`binary`] is our own
//! compact form for recording and fast replay, and both hold exactly the same [`TraceOp`]
//! stream, so conversion is lossless in both directions (text comments aside).
//!
//! * [`read_trace`] / [`load_trace`]: read either form, gzip-compressed or not.
//! * [`Recorder`]: wraps any [`RegisterBus`](sst1_regs::RegisterBus) and logs every call.
//! * [`replay`] / [`execute`]: drive a [`Board`](sst1_board::Board) with a trace.
//! * [`OpCounts`]: what a trace does (writes, triangles, fills, swaps, registers touched).
//! * [`judge`]: the conformance pass rule for a dump against the reference goldens.

pub mod binary;
pub mod judge;
mod recorder;
mod replay;
pub mod text;

use std::io::Read;
use std::path::{Path, PathBuf};

use sst1_board::{BoardConfig, BufferKind};

pub use binary::{decode_binary, encode_binary, BinaryError};
pub use recorder::Recorder;
pub use replay::{
    execute, execute_references, replay, rgb565_to_rgb8, write_dumps, Dump, OpCounts,
    ReferenceReplay, ReplayError, PROGRESS_STEP,
};
pub use text::{parse_text, write_text, ParseError};

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
    if addr < APERTURE_SIZE && addr % 4 == 0 {
        Ok(())
    } else {
        Err(ADDR_RULE)
    }
}

/// Checks a configuration-space offset: below [`PCI_CONFIG_SIZE`] and 4-aligned.
pub fn check_pci_offset(offset: u32) -> Result<(), &'static str> {
    if offset < PCI_CONFIG_SIZE && offset % 4 == 0 {
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
            if let TraceOp::Config { key, value } = *op {
                match key {
                    ConfigKey::FbiMb => config.fbi_mb = value,
                    ConfigKey::Tmus => config.tmus = value,
                    ConfigKey::TmuMb => config.tmu_mb = value,
                }
            }
        }
        config
    }
}

/// Largest decompressed size accepted from a gzip stream (hostile-input guard).
pub const MAX_DECOMPRESSED: u64 = 1 << 30;

/// Gzip's magic bytes.
const GZIP_MAGIC: [u8; 2] = [0x1f, 0x8b];

/// Decompresses `bytes` if they start with gzip's magic bytes; returns them as they are
/// otherwise.
pub fn gunzip_if_needed(bytes: &[u8]) -> std::io::Result<std::borrow::Cow<'_, [u8]>> {
    if !bytes.starts_with(&GZIP_MAGIC) {
        return Ok(std::borrow::Cow::Borrowed(bytes));
    }
    let mut out = Vec::new();
    flate2::read::MultiGzDecoder::new(bytes)
        .take(MAX_DECOMPRESSED + 1)
        .read_to_end(&mut out)?;
    if out.len() as u64 > MAX_DECOMPRESSED {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            "decompressed trace larger than 1 GiB",
        ));
    }
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
    /// The text form is malformed.
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
}

/// Reads a trace in either form from `bytes`: gzip is recognised by its magic bytes, the
/// binary form by [`binary::MAGIC`], anything else is parsed as text. `file` names the
/// source in error messages.
pub fn read_trace(file: &str, bytes: &[u8]) -> Result<Trace, LoadError> {
    let bytes = gunzip_if_needed(bytes).map_err(|source| ParseError::Gzip {
        file: file.to_owned(),
        message: source.to_string(),
    })?;
    if bytes.starts_with(&binary::MAGIC) {
        decode_binary(&bytes).map_err(|source| LoadError::Binary {
            file: file.to_owned(),
            source,
        })
    } else {
        Ok(text::parse_plain_text(file, &bytes)?)
    }
}

/// Reads a trace file in either form (see [`read_trace`]).
pub fn load_trace(path: &Path) -> Result<Trace, LoadError> {
    let bytes = std::fs::read(path).map_err(|source| LoadError::Io {
        path: path.to_owned(),
        source,
    })?;
    read_trace(&path.display().to_string(), &bytes)
}

//! Writing a trace op by op into a file, in memory that does not grow with the trace:
//! the form a [`Recorder`](crate::Recorder) streams a long recording in.
//!
//! The form follows the file's name, as for `voodoo convert`: `.vtrace` binary,
//! `.vtrace.gz` gzip binary, `.gz` gzip text, anything else text. The binary header holds
//! the op and frame counts and the board, known only at the end: a `.vtrace` file is
//! written with a provisional header that [`TraceWriter::finish`] rewrites in place; a
//! `.vtrace.gz` file's records go to a spool file beside it (`.NAME.spool`), which
//! `finish` compresses behind the header and removes.

use std::fs::File;
use std::io::{BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use sst1_board::BoardConfig;

use crate::binary::{encode_header, encode_op};
use crate::text::format_op;
use crate::{ConfigKey, TraceOp};

/// The file a trace is being written to.
enum Output {
    /// Text lines.
    Text(BufWriter<File>),
    /// Text lines, gzip-compressed.
    TextGz(flate2::write::GzEncoder<BufWriter<File>>),
    /// Binary records after a provisional header.
    Binary(BufWriter<File>),
    /// Binary records spooled uncompressed, compressed behind the header at the end.
    BinaryGz {
        spool: BufWriter<File>,
        spool_path: PathBuf,
        out: File,
    },
    /// Finished (or failed).
    Closed,
}

/// A trace being written op by op (see the module docs).
pub struct TraceWriter {
    output: Output,
    /// The board the config ops so far describe (the binary header's).
    board: BoardConfig,
    ops: u64,
    frame: u32,
    /// Whether a `wait` op was written (the binary header's version).
    waits: bool,
    /// One op's encoding.
    buf: Vec<u8>,
    /// The first error, kept for [`TraceWriter::finish`] once [`TraceWriter::record`] meets it.
    failed: Option<std::io::Error>,
}

/// Whether `path` names a gzip file, and whether (without `.gz`) a binary one.
fn form_of(path: &Path) -> (bool, bool) {
    let name = path.to_string_lossy();
    let (stem, gzip) = match name.strip_suffix(".gz") {
        Some(stem) => (stem, true),
        None => (&*name, false),
    };
    (stem.ends_with(".vtrace"), gzip)
}

impl TraceWriter {
    /// Creates (or truncates) `path` for a trace in the form its name says.
    pub fn create(path: &Path) -> std::io::Result<Self> {
        let gzip_encoder = |w: File| {
            flate2::write::GzEncoder::new(BufWriter::new(w), flate2::Compression::default())
        };
        let output = match form_of(path) {
            (false, false) => Output::Text(BufWriter::new(File::create(path)?)),
            (false, true) => Output::TextGz(gzip_encoder(File::create(path)?)),
            (true, false) => {
                let mut file = BufWriter::new(File::create(path)?);
                let mut header = Vec::new();
                encode_header(&mut header, BoardConfig::default(), 0, 0, false);
                file.write_all(&header)?;
                Output::Binary(file)
            }
            (true, true) => {
                let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
                let spool_path =
                    path.with_file_name(format!(".{}.spool", name.unwrap_or_default()));
                let out = File::create(path)?;
                // Read back at the end: opened for both.
                let spool = std::fs::OpenOptions::new()
                    .read(true)
                    .write(true)
                    .create(true)
                    .truncate(true)
                    .open(&spool_path)?;
                let spool = BufWriter::new(spool);
                Output::BinaryGz {
                    spool,
                    spool_path,
                    out,
                }
            }
        };
        Ok(Self {
            output,
            board: BoardConfig::default(),
            ops: 0,
            frame: 0,
            waits: false,
            buf: Vec::new(),
            failed: None,
        })
    }

    /// Writes one op.
    pub fn write_op(&mut self, op: &TraceOp) -> std::io::Result<()> {
        if let TraceOp::Config { key, value } = *op {
            match key {
                ConfigKey::FbiMb => self.board.fbi_mb = value,
                ConfigKey::Tmus => self.board.tmus = value,
                ConfigKey::TmuMb => self.board.tmu_mb = value,
            }
        }
        self.waits |= matches!(op, TraceOp::Wait { .. });
        self.buf.clear();
        match &mut self.output {
            Output::Text(w) => writeln!(w, "{}", format_op(op))?,
            Output::TextGz(w) => writeln!(w, "{}", format_op(op))?,
            Output::Binary(w) | Output::BinaryGz { spool: w, .. } => {
                encode_op(&mut self.buf, op, &mut self.frame);
                w.write_all(&self.buf)?;
            }
            Output::Closed => {
                return Err(std::io::Error::other("the trace is already finished"));
            }
        }
        self.ops += 1;
        Ok(())
    }

    /// The ops written so far (`config` ops included): a reader of the finished trace
    /// yields them first, in order.
    pub fn ops_written(&self) -> u64 {
        self.ops
    }

    /// Writes one op, or keeps the first error for [`TraceWriter::finish`] and writes
    /// nothing more (a recording cannot stop the bus it records).
    pub fn record(&mut self, op: &TraceOp) {
        if self.failed.is_none() {
            if let Err(e) = self.write_op(op) {
                self.failed = Some(e);
            }
        }
    }

    /// Completes the file (the binary header, the compression) and closes it; the first
    /// error met on the way, if any.
    pub fn finish(&mut self) -> std::io::Result<()> {
        let output = std::mem::replace(&mut self.output, Output::Closed);
        if let Some(e) = self.failed.take() {
            if let Output::BinaryGz { spool_path, .. } = &output {
                let _ = std::fs::remove_file(spool_path);
            }
            return Err(e);
        }
        let mut header = Vec::new();
        // Frames are numbered from 0: the number of the next one is how many there were.
        encode_header(
            &mut header,
            self.board,
            self.ops,
            u64::from(self.frame),
            self.waits,
        );
        match output {
            Output::Text(mut w) => w.flush(),
            Output::TextGz(w) => w.finish()?.flush(),
            Output::Binary(w) => {
                let mut file = w.into_inner().map_err(|e| e.into_error())?;
                file.seek(SeekFrom::Start(0))?;
                file.write_all(&header)?;
                file.flush()
            }
            Output::BinaryGz {
                spool,
                spool_path,
                out,
            } => {
                let result = (|| {
                    let mut spool = spool.into_inner().map_err(|e| e.into_error())?;
                    spool.seek(SeekFrom::Start(0))?;
                    let mut gz = flate2::write::GzEncoder::new(
                        BufWriter::new(out),
                        flate2::Compression::default(),
                    );
                    gz.write_all(&header)?;
                    std::io::copy(&mut spool, &mut gz)?;
                    gz.finish()?.flush()
                })();
                let _ = std::fs::remove_file(&spool_path);
                result
            }
            Output::Closed => Ok(()),
        }
    }
}

impl std::fmt::Debug for TraceWriter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TraceWriter")
            .field("ops", &self.ops)
            .field("board", &self.board)
            .finish_non_exhaustive()
    }
}

//! Reading a trace op by op, whatever its form, in memory independent of its length.
//!
//! [`TraceReader`] recognises gzip by its magic bytes (and decompresses as it reads), then
//! the binary form by [`MAGIC`](crate::binary::MAGIC); anything else is text. It yields
//! [`TraceOp`]s until the end of the input or the first error.
//!
//! A replay needs the board before the first op runs, and `config` ops may come anywhere
//! before the first `w` or `r` (trace-text-format.md), after `pci` or `dump` ops too.
//! [`stream_trace`] therefore reads ahead to the first `w` or `r`, holding at most
//! [`MAX_PREFIX_OPS`] ops; [`open_trace`] reads a regular file twice instead (the first
//! pass keeps only the `config` values) when the look-ahead would hold more.

use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

use sst1_board::BoardConfig;

use crate::binary::{BinaryError, BinaryReader, MAGIC};
use crate::text::{ParseError, TextReader};
use crate::{apply_config, Capped, LoadError, TraceOp, GZIP_MAGIC};

/// The input a reader decodes: buffered, possibly a decompressor.
type Input<'a> = Box<dyn BufRead + Send + 'a>;

/// What the input turned out to be.
enum Form<'a> {
    Text(TextReader<Input<'a>>),
    Binary(BinaryReader<Input<'a>>),
}

/// A trace read op by op from any byte source, text or binary, gzip-compressed or not: an
/// iterator of [`TraceOp`]s that ends after the first error. Memory is a read buffer and
/// one line (at most [`MAX_LINE`](crate::text::MAX_LINE)), whatever the trace's length.
pub struct TraceReader<'a> {
    file: String,
    form: Form<'a>,
    compressed: bool,
    done: bool,
}

/// Reads up to `n` bytes (fewer only at the end of the input).
fn read_head(input: &mut impl Read, n: usize) -> std::io::Result<Vec<u8>> {
    let mut head = Vec::with_capacity(n);
    input.by_ref().take(n as u64).read_to_end(&mut head)?;
    Ok(head)
}

impl<'a> TraceReader<'a> {
    /// A reader of `input`; `file` names it in error messages. Reads the first bytes to
    /// tell the form (and, for the binary form, the header). No decompression cap.
    pub fn new(file: &str, input: impl Read + Send + 'a) -> Result<Self, LoadError> {
        Self::with_limit(file, input, None)
    }

    /// As [`TraceReader::new`], failing once more than `max_decompressed` bytes come out of
    /// a gzip stream (if given).
    pub fn with_limit(
        file: &str,
        input: impl Read + Send + 'a,
        max_decompressed: Option<u64>,
    ) -> Result<Self, LoadError> {
        let mut raw = BufReader::new(input);
        let head = read_head(&mut raw, GZIP_MAGIC.len()).map_err(|source| LoadError::Io {
            path: PathBuf::from(file),
            source,
        })?;
        let compressed = head.starts_with(&GZIP_MAGIC);
        let raw = std::io::Cursor::new(head).chain(raw);
        let mut input: Input<'a> = if compressed {
            let decoder = flate2::bufread::MultiGzDecoder::new(raw);
            match max_decompressed {
                Some(limit) => Box::new(BufReader::new(Capped::new(decoder, limit))),
                None => Box::new(BufReader::new(decoder)),
            }
        } else {
            Box::new(raw)
        };
        let head = read_head(&mut input, MAGIC.len()).map_err(|e| {
            let message = e.to_string();
            let file = file.to_owned();
            if compressed {
                LoadError::Text(ParseError::Gzip { file, message })
            } else {
                LoadError::Text(ParseError::Io { file, message })
            }
        })?;
        let binary = head.starts_with(&MAGIC);
        let input: Input<'a> = Box::new(std::io::Cursor::new(head).chain(input));
        let form = if binary {
            let reader = BinaryReader::new(input)
                .map_err(|source| binary_error(file, compressed, source))?;
            Form::Binary(reader)
        } else {
            Form::Text(TextReader::new(file, input, compressed))
        };
        Ok(Self {
            file: file.to_owned(),
            form,
            compressed,
            done: false,
        })
    }

    /// A reader of the file at `path` (see [`TraceReader::new`]).
    pub fn open(path: &Path) -> Result<TraceReader<'static>, LoadError> {
        let file = std::fs::File::open(path).map_err(|source| LoadError::Io {
            path: path.to_owned(),
            source,
        })?;
        TraceReader::new(&path.display().to_string(), file)
    }

    /// The name the reader gives its input in error messages.
    pub fn file(&self) -> &str {
        &self.file
    }

    /// Whether the input is the binary form.
    pub fn is_binary(&self) -> bool {
        matches!(self.form, Form::Binary(_))
    }

    /// The next ops while they are writes that the binary form can hand out at once
    /// ([`BinaryReader::next_writes`]), into `out` until it is full: how many were
    /// taken, consumed as `next` would yield them. 0, with nothing consumed, otherwise
    /// (and always for the text form).
    #[inline(always)]
    pub fn next_writes(&mut self, out: &mut [(u32, u32)]) -> usize {
        match &mut self.form {
            Form::Binary(reader) if !self.done => reader.next_writes(out),
            _ => 0,
        }
    }
}

/// A binary-form error as a [`LoadError`]: a read error inside a gzip stream is a
/// decompression error, as for text.
fn binary_error(file: &str, compressed: bool, source: BinaryError) -> LoadError {
    match source {
        BinaryError::Io { message, .. } if compressed => LoadError::Text(ParseError::Gzip {
            file: file.to_owned(),
            message,
        }),
        source => LoadError::Binary {
            file: file.to_owned(),
            source,
        },
    }
}

impl Iterator for TraceReader<'_> {
    type Item = Result<TraceOp, LoadError>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        let item = match &mut self.form {
            Form::Text(reader) => reader.next().map(|r| r.map_err(LoadError::Text)),
            Form::Binary(reader) => reader
                .next()
                .map(|r| r.map_err(|e| binary_error(&self.file, self.compressed, e))),
        };
        if !matches!(item, Some(Ok(_))) {
            self.done = true;
        }
        item
    }
}

/// Most ops [`stream_trace`] holds while it looks for the board configuration (the ops
/// before the first `w` or `r`).
pub const MAX_PREFIX_OPS: usize = 4096;

/// A trace being read op by op, with the board it runs on: its `config` ops, read ahead.
/// Yields every op of the trace in order (the `config` ops too), then ends, or ends after
/// the first error.
pub struct TraceStream<'a> {
    config: BoardConfig,
    /// Ops read ahead to find the configuration, not yet yielded.
    ahead: VecDeque<TraceOp>,
    /// An error met while reading ahead, yielded after `ahead`.
    error: Option<LoadError>,
    rest: TraceReader<'a>,
}

impl TraceStream<'_> {
    /// The board the trace runs on (defaults overridden by its `config` ops).
    pub fn config(&self) -> BoardConfig {
        self.config
    }

    /// The name the stream gives its input in error messages.
    pub fn file(&self) -> &str {
        self.rest.file()
    }

    /// The next ops while they are writes that can be handed out without building a
    /// [`TraceOp`] ([`TraceReader::next_writes`]), into `out` until it is full: how many
    /// were taken, consumed as [`Iterator::next`] would yield them. 0, with nothing
    /// consumed, otherwise: `next` gives the next op.
    #[inline(always)]
    pub fn next_writes(&mut self, out: &mut [(u32, u32)]) -> usize {
        if self.ahead.is_empty() && self.error.is_none() {
            self.rest.next_writes(out)
        } else {
            0
        }
    }
}

impl Iterator for TraceStream<'_> {
    type Item = Result<TraceOp, LoadError>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        if let Some(op) = self.ahead.pop_front() {
            return Some(Ok(op));
        }
        if let Some(error) = self.error.take() {
            return Some(Err(error));
        }
        self.rest.next()
    }
}

/// Whether an op ends the part of a trace where `config` ops may appear.
fn is_access(op: &TraceOp) -> bool {
    matches!(op, TraceOp::Write { .. } | TraceOp::Read { .. })
}

/// Reads ahead to the first `w` or `r` (at most [`MAX_PREFIX_OPS`] ops).
fn read_ahead(mut reader: TraceReader<'_>) -> Result<TraceStream<'_>, LoadError> {
    let mut config = BoardConfig::default();
    let mut ahead = VecDeque::new();
    let mut error = None;
    let file = reader.file().to_owned();
    for item in reader.by_ref() {
        match item {
            Ok(op) => {
                apply_config(&mut config, &op);
                let access = is_access(&op);
                ahead.push_back(op);
                if access {
                    break;
                }
                if ahead.len() > MAX_PREFIX_OPS {
                    return Err(LoadError::LongPrefix {
                        file,
                        limit: MAX_PREFIX_OPS,
                    });
                }
            }
            Err(e) => {
                error = Some(e);
                break;
            }
        }
    }
    Ok(TraceStream {
        config,
        ahead,
        error,
        rest: reader,
    })
}

/// Streams a trace from `input` (any byte source, read once); `file` names it in error
/// messages. Fails if more than [`MAX_PREFIX_OPS`] ops come before the first `w` or `r`
/// ([`open_trace`] reads such a file twice instead).
pub fn stream_trace<'a>(
    file: &str,
    input: impl Read + Send + 'a,
) -> Result<TraceStream<'a>, LoadError> {
    read_ahead(TraceReader::new(file, input)?)
}

/// Streams the trace file at `path`. A regular file with more than [`MAX_PREFIX_OPS`] ops
/// before its first `w` or `r` is read twice: once for its `config` values, once for the
/// ops. Anything else (a pipe, a device) is read once, as by [`stream_trace`].
pub fn open_trace(path: &Path) -> Result<TraceStream<'static>, LoadError> {
    match read_ahead(TraceReader::open(path)?) {
        Err(LoadError::LongPrefix { .. }) if is_regular_file(path) => {
            let mut config = BoardConfig::default();
            // A first pass for the configuration; its errors show in the second.
            for op in TraceReader::open(path)?.map_while(Result::ok) {
                apply_config(&mut config, &op);
                if is_access(&op) {
                    break;
                }
            }
            Ok(TraceStream {
                config,
                ahead: VecDeque::new(),
                error: None,
                rest: TraceReader::open(path)?,
            })
        }
        other => other,
    }
}

fn is_regular_file(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| m.is_file())
}

//! The plain-text write-log (`shared/docs/trace-text-format.md`): parser and writer.
//!
//! One command a line, `#` comments, numbers in hex (`0x` prefix) or decimal:
//!
//! ```text
//! config fbi_mb 4
//! pci 0x40 0x00000003
//! w 0x000210 0x00000007
//! r 0x000000 0x0fffffff     # extension: a recorded read and what it returned
//! wait 500                  # extension: 500 graphics clocks (10 us) of host time
//! dump front scene_front.raw
//! ```
//!
//! `r OFFSET [VALUE]` is this project's extension for [`TraceOp::Read`] and `wait CYCLES`
//! for [`TraceOp::Wait`] (a 64-bit count); the shared format has neither. Besides the format's own rules the parser checks what a replayer relies
//! on: offsets 4-aligned and inside the aperture (or configuration space), `config` values
//! the board supports and before the first `w`/`r`, dump names that are bare file names.
//!
//! [`TextReader`] parses a line at a time from any [`BufRead`], so a trace of any length is
//! read in constant memory; a line is at most [`MAX_LINE`] bytes (comment included).
//! [`parse_text`] reads a whole trace into memory, at most
//! [`MAX_TRACE_OPS`] ops.

use std::fmt::Write as _;
use std::io::{BufRead, ErrorKind};

use crate::{
    check_addr, check_dump_name, check_pci_offset, quote, ConfigKey, DumpBuffer, Trace, TraceOp,
    ADDR_RULE, DUMP_NAME_RULE, MAX_TRACE_OPS, PCI_RULE,
};

/// The longest line a text trace may have, in bytes, comment and line end included
/// (1 MiB). The longest command is a `dump` with a 255-byte name; the limit keeps a
/// reader's memory bounded on input without line ends (`/dev/zero`).
pub const MAX_LINE: usize = 1 << 20;

/// A malformed text trace. Every variant names the file and, where there is one, the
/// 1-based line. Quoted input is cut to a few dozen characters ([`quote`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ParseError {
    /// The gzip stream is corrupt or too large.
    #[error("{file}: cannot decompress: {message}")]
    Gzip {
        /// The file's name.
        file: String,
        /// What the decompressor said.
        message: String,
    },
    /// The input could not be read.
    #[error("{file}: {message}")]
    Io {
        /// The file's name.
        file: String,
        /// What the OS said.
        message: String,
    },
    /// The line is not UTF-8.
    #[error("{file}:{line}: not UTF-8 text")]
    NotUtf8 {
        /// The file's name.
        file: String,
        /// 1-based line number.
        line: usize,
    },
    /// The line is longer than [`MAX_LINE`].
    #[error("{file}:{line}: line longer than {MAX_LINE} bytes")]
    LineTooLong {
        /// The file's name.
        file: String,
        /// 1-based line number.
        line: usize,
    },
    /// The line starts with a word that is not a command.
    #[error("{file}:{line}: unknown command {found}; expected config, pci, w, r, wait or dump")]
    UnknownCommand {
        /// The file's name.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The word found, quoted ([`quote`]).
        found: String,
    },
    /// A command's argument is missing or not what the command takes.
    #[error("{file}:{line}: expected {expected}, found {found}")]
    Expected {
        /// The file's name.
        file: String,
        /// 1-based line number.
        line: usize,
        /// What the command takes there.
        expected: &'static str,
        /// What the line holds there, quoted ([`quote`]), or `end of line`.
        found: String,
    },
    /// A `config` line after the first `w` or `r`.
    #[error("{file}:{line}: `config` after the first write; config lines must come first")]
    ConfigAfterAccess {
        /// The file's name.
        file: String,
        /// 1-based line number.
        line: usize,
    },
    /// A whole-trace read ([`parse_text`]) met more ops than it holds in memory.
    #[error("{file}: more than {limit} ops, the most a whole trace read into memory may hold (replay streams traces of any length)")]
    TooManyOps {
        /// The file's name.
        file: String,
        /// The limit, [`MAX_TRACE_OPS`].
        limit: usize,
    },
}

/// Parses a text trace, gzip-compressed or not (recognised by its magic bytes), into
/// memory: at most [`MAX_TRACE_OPS`] ops and [`MAX_DECOMPRESSED`](crate::MAX_DECOMPRESSED)
/// decompressed bytes. `file` names the source in error messages. Never panics, whatever
/// the bytes.
pub fn parse_text(file: &str, bytes: &[u8]) -> Result<Trace, ParseError> {
    if bytes.starts_with(&crate::GZIP_MAGIC) {
        let gz = flate2::bufread::MultiGzDecoder::new(bytes);
        let capped = crate::Capped::new(gz, crate::MAX_DECOMPRESSED);
        let input = std::io::BufReader::new(capped);
        collect_text(TextReader::new(file, input, true))
    } else {
        parse_plain_text(file, bytes)
    }
}

/// Parses text that is already decompressed (at most [`MAX_TRACE_OPS`] ops).
pub(crate) fn parse_plain_text(file: &str, bytes: &[u8]) -> Result<Trace, ParseError> {
    collect_text(TextReader::new(file, bytes, false))
}

fn collect_text<R: BufRead>(reader: TextReader<R>) -> Result<Trace, ParseError> {
    let file = reader.file.clone();
    let mut ops = Vec::new();
    for op in reader {
        if ops.len() == MAX_TRACE_OPS {
            return Err(ParseError::TooManyOps {
                file,
                limit: MAX_TRACE_OPS,
            });
        }
        ops.push(op?);
    }
    Ok(Trace { ops })
}

/// Reads a text trace op by op from `input` (already decompressed): an iterator of
/// [`TraceOp`]s that ends after the first error. Memory is one line, at most
/// [`MAX_LINE`] bytes, whatever the trace's length.
pub struct TextReader<R> {
    file: String,
    input: R,
    /// Whether `input` decompresses gzip (read errors are then decompression errors).
    compressed: bool,
    /// Lines read so far (the 1-based number of the last one).
    line: usize,
    /// Whether a `w` or `r` has been read (no `config` may follow).
    accessed: bool,
    buf: Vec<u8>,
    done: bool,
}

impl<R: BufRead> TextReader<R> {
    /// A reader of `input`; `file` names it in error messages; `compressed` says whether
    /// `input` is a decompressor (its read errors are then reported as such).
    pub fn new(file: &str, input: R, compressed: bool) -> Self {
        Self {
            file: file.to_owned(),
            input,
            compressed,
            line: 0,
            accessed: false,
            buf: Vec::new(),
            done: false,
        }
    }

    fn read_error(&self, error: std::io::Error) -> ParseError {
        let file = self.file.clone();
        let message = error.to_string();
        if self.compressed {
            ParseError::Gzip { file, message }
        } else {
            ParseError::Io { file, message }
        }
    }

    /// Reads the next line into `buf` (without the `\n`); `Ok(false)` at the end of input.
    fn read_line(&mut self) -> Result<bool, ParseError> {
        self.buf.clear();
        let mut any = false;
        loop {
            let chunk = match self.input.fill_buf() {
                Ok(chunk) => chunk,
                Err(e) if e.kind() == ErrorKind::Interrupted => continue,
                Err(e) => return Err(self.read_error(e)),
            };
            if chunk.is_empty() {
                return Ok(any);
            }
            any = true;
            let (take, end) = match chunk.iter().position(|&b| b == b'\n') {
                Some(i) => (i, true),
                None => (chunk.len(), false),
            };
            if self.buf.len() + take >= MAX_LINE {
                return Err(ParseError::LineTooLong {
                    file: self.file.clone(),
                    line: self.line + 1,
                });
            }
            self.buf.extend_from_slice(&chunk[..take]);
            self.input.consume(take + usize::from(end));
            if end {
                return Ok(true);
            }
        }
    }
}

impl<R: BufRead> Iterator for TextReader<R> {
    type Item = Result<TraceOp, ParseError>;

    fn next(&mut self) -> Option<Self::Item> {
        while !self.done {
            let result = match self.read_line() {
                Ok(false) => {
                    self.done = true;
                    return None;
                }
                Ok(true) => {
                    self.line += 1;
                    parse_line(&self.file, self.line, &self.buf, &mut self.accessed)
                }
                Err(e) => Err(e),
            };
            match result {
                Ok(None) => {}
                Ok(Some(op)) => return Some(Ok(op)),
                Err(e) => {
                    self.done = true;
                    return Some(Err(e));
                }
            }
        }
        None
    }
}

/// The words of one line, with their position for error messages.
struct Line<'a> {
    file: &'a str,
    number: usize,
    words: std::str::SplitAsciiWhitespace<'a>,
}

impl<'a> Line<'a> {
    fn error(&self, expected: &'static str, found: Option<&str>) -> ParseError {
        ParseError::Expected {
            file: self.file.to_owned(),
            line: self.number,
            expected,
            found: match found {
                Some(word) => quote(word),
                None => "end of line".to_owned(),
            },
        }
    }

    fn word(&mut self, expected: &'static str) -> Result<&'a str, ParseError> {
        self.words.next().ok_or_else(|| self.error(expected, None))
    }

    fn number(&mut self, expected: &'static str) -> Result<u32, ParseError> {
        let word = self.word(expected)?;
        parse_number(word).ok_or_else(|| self.error(expected, Some(word)))
    }

    /// A number that `check` accepts; `expected` says what that is.
    fn checked(
        &mut self,
        expected: &'static str,
        check: fn(u32) -> Result<(), &'static str>,
    ) -> Result<u32, ParseError> {
        let word = self.word(expected)?;
        parse_number(word)
            .filter(|&n| check(n).is_ok())
            .ok_or_else(|| self.error(expected, Some(word)))
    }

    fn end(&mut self) -> Result<(), ParseError> {
        match self.words.next() {
            Some(word) => Err(self.error("end of line", Some(word))),
            None => Ok(()),
        }
    }
}

/// A 32-bit number as the format writes them: `0x` + hex digits, or decimal digits.
pub fn parse_number(word: &str) -> Option<u32> {
    let (digits, radix) = match word.strip_prefix("0x").or_else(|| word.strip_prefix("0X")) {
        Some(hex) => (hex, 16),
        None => (word, 10),
    };
    // from_str_radix accepts a leading `+`; the format does not.
    if digits.is_empty() || !digits.chars().all(|c| c.is_digit(radix)) {
        return None;
    }
    u32::from_str_radix(digits, radix).ok()
}

const VALUE: &str = "a 32-bit value (0x hex or decimal)";
const CYCLES: &str = "a wait in graphics-clock cycles (0x hex or decimal, below 2^64)";

/// A 64-bit number as the format writes them (see [`parse_number`]).
pub fn parse_number_u64(word: &str) -> Option<u64> {
    let (digits, radix) = match word.strip_prefix("0x").or_else(|| word.strip_prefix("0X")) {
        Some(hex) => (hex, 16),
        None => (word, 10),
    };
    if digits.is_empty() || !digits.chars().all(|c| c.is_digit(radix)) {
        return None;
    }
    u64::from_str_radix(digits, radix).ok()
}

/// The value of up to eight hex digits, `None` for anything else (no digits, more than
/// eight, a byte that is not a hex digit).
#[inline]
fn hex_u32(digits: &[u8]) -> Option<u32> {
    if digits.is_empty() || digits.len() > 8 {
        return None;
    }
    let mut v = 0u32;
    for &b in digits {
        let d = match b {
            b'0'..=b'9' => b - b'0',
            b'a'..=b'f' => b - b'a' + 10,
            b'A'..=b'F' => b - b'A' + 10,
            _ => return None,
        };
        v = v << 4 | u32::from(d);
    }
    Some(v)
}

/// A write line exactly as the recorder writes it, `w 0xADDR 0xVALUE` (single spaces,
/// lower-case `0x`, at most eight digits each, nothing else), decoded without the word
/// splitting and UTF-8 checks of the general parser: most lines of a trace are such
/// writes. `None` for any other line, which the general parser then reads (and which
/// gives the same op or the error). The address must pass [`check_addr`].
#[inline]
fn canonical_write(raw: &[u8]) -> Option<(u32, u32)> {
    let rest = raw.strip_prefix(b"w 0x")?;
    let space = rest.iter().position(|&b| b == b' ')?;
    let addr = hex_u32(&rest[..space])?;
    let value = hex_u32(rest[space + 1..].strip_prefix(b"0x")?)?;
    check_addr(addr).ok()?;
    Some((addr, value))
}

/// Parses line `number` of `file` (without its `\n`): `None` for a blank or comment line.
/// `accessed` says whether a `w` or `r` came before, and is set by one.
fn parse_line(
    file: &str,
    number: usize,
    raw: &[u8],
    accessed: &mut bool,
) -> Result<Option<TraceOp>, ParseError> {
    if let Some((addr, value)) = canonical_write(raw) {
        *accessed = true;
        return Ok(Some(TraceOp::Write { addr, value }));
    }
    parse_line_general(file, number, raw, accessed)
}

/// [`parse_line`] for every line, word by word.
fn parse_line_general(
    file: &str,
    number: usize,
    raw: &[u8],
    accessed: &mut bool,
) -> Result<Option<TraceOp>, ParseError> {
    let text = std::str::from_utf8(raw).map_err(|_| ParseError::NotUtf8 {
        file: file.to_owned(),
        line: number,
    })?;
    let text = text.split('#').next().unwrap_or("");
    let mut line = Line {
        file,
        number,
        words: text.split_ascii_whitespace(),
    };
    let Some(command) = line.words.next() else {
        return Ok(None);
    };
    let op = match command {
        "config" => {
            if *accessed {
                return Err(ParseError::ConfigAfterAccess {
                    file: file.to_owned(),
                    line: number,
                });
            }
            const KEY: &str = "a config key (fbi_mb, tmus or tmu_mb)";
            let word = line.word(KEY)?;
            let key = ConfigKey::from_name(word).ok_or_else(|| line.error(KEY, Some(word)))?;
            let word = line.word(key.expected())?;
            let value = parse_number(word)
                .filter(|v| key.allowed().contains(v))
                .ok_or_else(|| line.error(key.expected(), Some(word)))?;
            TraceOp::Config { key, value }
        }
        "pci" => {
            let offset = line.checked(PCI_RULE, check_pci_offset)?;
            let value = line.number(VALUE)?;
            TraceOp::Pci { offset, value }
        }
        "w" => {
            *accessed = true;
            let addr = line.checked(ADDR_RULE, check_addr)?;
            let value = line.number(VALUE)?;
            TraceOp::Write { addr, value }
        }
        "r" => {
            *accessed = true;
            let addr = line.checked(ADDR_RULE, check_addr)?;
            let value = match line.words.next() {
                None => None,
                Some(word) => {
                    Some(parse_number(word).ok_or_else(|| line.error(VALUE, Some(word)))?)
                }
            };
            TraceOp::Read { addr, value }
        }
        "wait" => {
            let word = line.word(CYCLES)?;
            let cycles = parse_number_u64(word).ok_or_else(|| line.error(CYCLES, Some(word)))?;
            TraceOp::Wait { cycles }
        }
        "dump" => {
            const BUFFER: &str = "a buffer (front, back, depth or aux)";
            let word = line.word(BUFFER)?;
            let buffer =
                DumpBuffer::from_name(word).ok_or_else(|| line.error(BUFFER, Some(word)))?;
            let name = line.word(DUMP_NAME_RULE)?;
            check_dump_name(name).map_err(|e| line.error(e, Some(name)))?;
            TraceOp::Dump {
                buffer,
                file: name.to_owned(),
            }
        }
        other => {
            return Err(ParseError::UnknownCommand {
                file: file.to_owned(),
                line: number,
                found: quote(other),
            })
        }
    };
    line.end()?;
    Ok(Some(op))
}

/// Formats one op as a text line (without the newline).
pub fn format_op(op: &TraceOp) -> String {
    match op {
        TraceOp::Config { key, value } => format!("config {} {value}", key.name()),
        TraceOp::Pci { offset, value } => format!("pci {offset:#04x} {value:#010x}"),
        TraceOp::Write { addr, value } => format!("w {addr:#08x} {value:#010x}"),
        TraceOp::Read { addr, value: None } => format!("r {addr:#08x}"),
        TraceOp::Read {
            addr,
            value: Some(value),
        } => format!("r {addr:#08x} {value:#010x}"),
        TraceOp::Wait { cycles } => format!("wait {cycles}"),
        TraceOp::Dump { buffer, file } => format!("dump {} {file}", buffer.name()),
    }
}

/// Writes a trace as text, one op a line.
pub fn write_text(trace: &Trace) -> String {
    let mut out = String::with_capacity(trace.ops.len() * 24);
    for op in &trace.ops {
        // Writing to a String cannot fail.
        let _ = writeln!(out, "{}", format_op(op));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn canonical_writes_parse_as_the_general_parser_does() {
        let lines: &[&[u8]] = &[
            b"w 0x000120 0x00000000",
            b"w 0x400000 0xdeadBEEF",
            b"w 0xfffffc 0xffffffff",
            b"w 0x0 0x0",
            b"w 0x1000000 0x1",
            b"w 0x000122 0x1",
            b"w 0x000120 0x123456789",
            b"w 0x0000000120 0x1",
            b"w 0x120 0x",
            b"w 0x 0x5",
            b"w 0x120  0x5",
            b"w 0x120 0x5 ",
            b"w 0x120 0x5\r",
            b"w 0x120 0x5 # comment",
            b"w 0x120 5",
            b"w 0X120 0x5",
            b"w 0x12g 0x5",
            b"w 0x120 0x5 0x6",
            b"w 0x120 0x+5",
        ];
        for raw in lines {
            let mut fast_accessed = false;
            let fast = parse_line("t", 1, raw, &mut fast_accessed);
            let mut general_accessed = false;
            let general = parse_line_general("t", 1, raw, &mut general_accessed);
            assert_eq!(fast, general, "{}", String::from_utf8_lossy(raw));
            assert_eq!(fast_accessed, general_accessed);
            if let Some((addr, value)) = canonical_write(raw) {
                assert_eq!(general, Ok(Some(TraceOp::Write { addr, value })));
            }
        }
        assert_eq!(
            canonical_write(b"w 0x000120 0x0000abcd"),
            Some((0x120, 0xabcd))
        );
        assert_eq!(canonical_write(b"w 0x000122 0x1"), None);
    }
}

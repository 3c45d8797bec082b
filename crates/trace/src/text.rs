//! The plain-text write-log (`shared/docs/trace-text-format.md`): parser and writer.
//!
//! One command a line, `#` comments, numbers in hex (`0x` prefix) or decimal:
//!
//! ```text
//! config fbi_mb 4
//! pci 0x40 0x00000003
//! w 0x000210 0x00000007
//! r 0x000000 0x0fffffff     # extension: a recorded read and what it returned
//! dump front scene_front.raw
//! ```
//!
//! `r OFFSET [VALUE]` is this project's extension for [`TraceOp::Read`]; the shared format
//! has no reads. Besides the format's own rules the parser checks what a replayer relies
//! on: offsets 4-aligned and inside the aperture (or configuration space), `config` values
//! the board supports and before the first `w`/`r`, dump names that are bare file names.

use std::fmt::Write as _;

use crate::{
    check_addr, check_dump_name, check_pci_offset, ConfigKey, DumpBuffer, Trace, TraceOp,
    ADDR_RULE, DUMP_NAME_RULE, PCI_RULE,
};

/// A malformed text trace. Every variant names the file and, where there is one, the
/// 1-based line.
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
    /// The line is not UTF-8.
    #[error("{file}:{line}: not UTF-8 text")]
    NotUtf8 {
        /// The file's name.
        file: String,
        /// 1-based line number.
        line: usize,
    },
    /// The line starts with a word that is not a command.
    #[error("{file}:{line}: unknown command `{found}`; expected config, pci, w, r or dump")]
    UnknownCommand {
        /// The file's name.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The word found.
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
        /// What the line holds there, quoted, or `end of line`.
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
}

/// Parses a text trace, gzip-compressed or not (recognised by its magic bytes). `file`
/// names the source in error messages. Never panics, whatever the bytes.
pub fn parse_text(file: &str, bytes: &[u8]) -> Result<Trace, ParseError> {
    let bytes = crate::gunzip_if_needed(bytes).map_err(|e| ParseError::Gzip {
        file: file.to_owned(),
        message: e.to_string(),
    })?;
    parse_plain_text(file, &bytes)
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
                Some(word) => format!("`{word}`"),
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

/// Parses text that is already decompressed.
pub(crate) fn parse_plain_text(file: &str, bytes: &[u8]) -> Result<Trace, ParseError> {
    let mut ops = Vec::new();
    let mut accessed = false;
    for (index, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let number = index + 1;
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
            continue;
        };
        let op = match command {
            "config" => {
                if accessed {
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
                accessed = true;
                let addr = line.checked(ADDR_RULE, check_addr)?;
                let value = line.number(VALUE)?;
                TraceOp::Write { addr, value }
            }
            "r" => {
                accessed = true;
                let addr = line.checked(ADDR_RULE, check_addr)?;
                let value = match line.words.next() {
                    None => None,
                    Some(word) => {
                        Some(parse_number(word).ok_or_else(|| line.error(VALUE, Some(word)))?)
                    }
                };
                TraceOp::Read { addr, value }
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
                    found: other.to_owned(),
                })
            }
        };
        line.end()?;
        ops.push(op);
    }
    Ok(Trace { ops })
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

//! Our binary trace format: compact, versioned, quick to read, lossless with the text form.
//!
//! Layout (all integers little-endian):
//!
//! ```text
//! header   magic "SST1TRCB" (8 bytes)
//!          version u16, min_reader_version u16, header_len u32 (bytes before the records)
//!          fbi_mb u8, tmus u8, tmu_mb u8, reserved u8 (= 0)   the board the ops configure
//!          op_count u64, frame_count u64
//! records  tag u8 then its fields:
//!          0x01 config      key u8 (0 fbi_mb, 1 tmus, 2 tmu_mb), value u32
//!          0x02 pci         offset u32, value u32
//!          0x03 write       addr u32, value u32
//!          0x04 read        addr u32
//!          0x05 read+value  addr u32, value u32
//!          0x06 dump        buffer u8 (0 front, 1 back, 2 depth, 3 aux), len u8, name (UTF-8)
//!          0x07 frame       frame number u32: follows every write of swapbufferCMD that
//!                           reaches the FBI; frame N+1 starts after it
//! ```
//!
//! A reader accepts a file whose `min_reader_version` is at most [`READER_VERSION`] and skips
//! header bytes it does not know (up to `header_len`). Frame records carry no op of their
//! own: decoding yields exactly the ops that were encoded, and the decoder checks that each
//! swap is followed by its frame record. The same rules as the text parser apply (offsets,
//! config values and order, dump names), so any decoded trace writes back as valid text.

use crate::{
    check_addr, check_dump_name, check_pci_offset, ConfigKey, DumpBuffer, OpCounts, Trace, TraceOp,
    ADDR_RULE, DUMP_NAME_RULE, PCI_RULE,
};

/// The magic bytes that open a binary trace.
pub const MAGIC: [u8; 8] = *b"SST1TRCB";
/// The version this code writes.
pub const VERSION: u16 = 1;
/// The newest `min_reader_version` this code can read.
pub const READER_VERSION: u16 = 1;
/// Length of the version-1 header.
const HEADER_LEN: u32 = 36;

const TAG_CONFIG: u8 = 0x01;
const TAG_PCI: u8 = 0x02;
const TAG_WRITE: u8 = 0x03;
const TAG_READ: u8 = 0x04;
const TAG_READ_VALUE: u8 = 0x05;
const TAG_DUMP: u8 = 0x06;
const TAG_FRAME: u8 = 0x07;

/// A malformed binary trace. `offset` is the byte offset of the record at fault.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum BinaryError {
    /// The file does not start with [`MAGIC`].
    #[error("not a binary SST-1 trace (bad magic bytes)")]
    BadMagic,
    /// The file needs a newer reader.
    #[error("needs reader version {min_reader_version} (file version {version}); this reader is version {READER_VERSION}")]
    TooNew {
        /// The file's format version.
        version: u16,
        /// The oldest reader that can read it.
        min_reader_version: u16,
    },
    /// The file ends inside the header or a record.
    #[error("byte {offset}: file ends inside {what}")]
    Truncated {
        /// Where the incomplete item starts.
        offset: usize,
        /// What was being read.
        what: &'static str,
    },
    /// A header field is out of range.
    #[error("header: expected {expected}")]
    BadHeader {
        /// What the field must hold.
        expected: &'static str,
    },
    /// A record starts with an unknown tag.
    #[error("byte {offset}: unknown record tag {tag:#04x}")]
    UnknownTag {
        /// Where the record starts.
        offset: usize,
        /// The tag found.
        tag: u8,
    },
    /// A record's field is out of range.
    #[error("byte {offset}: expected {expected}")]
    BadField {
        /// Where the record starts.
        offset: usize,
        /// What the field must hold.
        expected: &'static str,
    },
    /// The header's counts or board do not match the records.
    #[error("header says {expected}, records hold {found}")]
    HeaderMismatch {
        /// What the header says, in words.
        expected: String,
        /// What the records hold, in words.
        found: String,
    },
}

fn config_code(key: ConfigKey) -> u8 {
    match key {
        ConfigKey::FbiMb => 0,
        ConfigKey::Tmus => 1,
        ConfigKey::TmuMb => 2,
    }
}

fn buffer_code(buffer: DumpBuffer) -> u8 {
    match buffer {
        DumpBuffer::Front => 0,
        DumpBuffer::Back => 1,
        DumpBuffer::Depth => 2,
        DumpBuffer::Aux => 3,
    }
}

/// Encodes a trace. The trace must satisfy the text parser's rules (any trace read by
/// [`parse_text`](crate::parse_text) or [`decode_binary`] does); the board configuration in
/// the header is narrowed to a byte per field.
pub fn encode_binary(trace: &Trace) -> Vec<u8> {
    let config = trace.board_config();
    let counts = OpCounts::of(trace);
    let mut out = Vec::with_capacity(HEADER_LEN as usize + trace.ops.len() * 9);
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&READER_VERSION.to_le_bytes());
    out.extend_from_slice(&HEADER_LEN.to_le_bytes());
    for field in [config.fbi_mb, config.tmus, config.tmu_mb] {
        out.push(field.min(255) as u8);
    }
    out.push(0);
    out.extend_from_slice(&(trace.ops.len() as u64).to_le_bytes());
    out.extend_from_slice(&counts.swaps.to_le_bytes());

    let mut frame = 0u32;
    for op in &trace.ops {
        match op {
            TraceOp::Config { key, value } => {
                out.push(TAG_CONFIG);
                out.push(config_code(*key));
                out.extend_from_slice(&value.to_le_bytes());
            }
            TraceOp::Pci { offset, value } => {
                out.push(TAG_PCI);
                out.extend_from_slice(&offset.to_le_bytes());
                out.extend_from_slice(&value.to_le_bytes());
            }
            TraceOp::Write { addr, value } => {
                out.push(TAG_WRITE);
                out.extend_from_slice(&addr.to_le_bytes());
                out.extend_from_slice(&value.to_le_bytes());
                if crate::replay::is_swap(*addr) {
                    out.push(TAG_FRAME);
                    out.extend_from_slice(&frame.to_le_bytes());
                    frame = frame.wrapping_add(1);
                }
            }
            TraceOp::Read { addr, value: None } => {
                out.push(TAG_READ);
                out.extend_from_slice(&addr.to_le_bytes());
            }
            TraceOp::Read {
                addr,
                value: Some(value),
            } => {
                out.push(TAG_READ_VALUE);
                out.extend_from_slice(&addr.to_le_bytes());
                out.extend_from_slice(&value.to_le_bytes());
            }
            TraceOp::Dump { buffer, file } => {
                out.push(TAG_DUMP);
                out.push(buffer_code(*buffer));
                let name = &file.as_bytes()[..file.len().min(255)];
                out.push(name.len() as u8);
                out.extend_from_slice(name);
            }
        }
    }
    out
}

/// A cursor over the input that reports truncation instead of panicking.
struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Cursor<'a> {
    fn take(
        &mut self,
        n: usize,
        start: usize,
        what: &'static str,
    ) -> Result<&'a [u8], BinaryError> {
        let end = self
            .pos
            .checked_add(n)
            .filter(|&end| end <= self.bytes.len());
        let end = end.ok_or(BinaryError::Truncated {
            offset: start,
            what,
        })?;
        let slice = &self.bytes[self.pos..end];
        self.pos = end;
        Ok(slice)
    }

    fn u8(&mut self, start: usize, what: &'static str) -> Result<u8, BinaryError> {
        Ok(self.take(1, start, what)?[0])
    }

    fn u16(&mut self, start: usize, what: &'static str) -> Result<u16, BinaryError> {
        let b = self.take(2, start, what)?;
        Ok(u16::from_le_bytes([b[0], b[1]]))
    }

    fn u32(&mut self, start: usize, what: &'static str) -> Result<u32, BinaryError> {
        let b = self.take(4, start, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn u64(&mut self, start: usize, what: &'static str) -> Result<u64, BinaryError> {
        let lo = u64::from(self.u32(start, what)?);
        let hi = u64::from(self.u32(start, what)?);
        Ok(lo | hi << 32)
    }
}

/// Decodes a binary trace (not gzip-compressed; [`read_trace`](crate::read_trace) handles
/// that). Never panics, whatever the bytes.
pub fn decode_binary(bytes: &[u8]) -> Result<Trace, BinaryError> {
    if !bytes.starts_with(&MAGIC) {
        return Err(BinaryError::BadMagic);
    }
    let mut cur = Cursor {
        bytes,
        pos: MAGIC.len(),
    };
    const HEADER: &str = "the header";
    let version = cur.u16(0, HEADER)?;
    let min_reader_version = cur.u16(0, HEADER)?;
    if min_reader_version > READER_VERSION {
        return Err(BinaryError::TooNew {
            version,
            min_reader_version,
        });
    }
    let header_len = cur.u32(0, HEADER)?;
    if header_len < HEADER_LEN {
        return Err(BinaryError::BadHeader {
            expected: "header_len of at least 36",
        });
    }
    let board: Vec<u32> = cur.take(4, 0, HEADER)?[..3]
        .iter()
        .map(|&b| u32::from(b))
        .collect();
    let op_count = cur.u64(0, HEADER)?;
    let frame_count = cur.u64(0, HEADER)?;
    cur.take(header_len as usize - HEADER_LEN as usize, 0, HEADER)?;

    // Each op takes at least 5 bytes, so a hostile count cannot make us over-allocate.
    let capacity = (op_count as usize).min(bytes.len() / 5);
    let mut ops = Vec::with_capacity(capacity);
    let mut accessed = false;
    let mut frames = 0u64;
    let mut frame_due = false;
    while cur.pos < bytes.len() {
        let start = cur.pos;
        const RECORD: &str = "a record";
        let tag = cur.u8(start, RECORD)?;
        if frame_due && tag != TAG_FRAME {
            return Err(BinaryError::BadField {
                offset: start,
                expected: "a frame record after a swap",
            });
        }
        let bad = |expected| BinaryError::BadField {
            offset: start,
            expected,
        };
        let op = match tag {
            TAG_CONFIG => {
                if accessed {
                    return Err(bad("config records before the first write or read"));
                }
                let key = match cur.u8(start, RECORD)? {
                    0 => ConfigKey::FbiMb,
                    1 => ConfigKey::Tmus,
                    2 => ConfigKey::TmuMb,
                    _ => return Err(bad("a config key code 0-2")),
                };
                let value = cur.u32(start, RECORD)?;
                if !key.allowed().contains(&value) {
                    return Err(bad(key.expected()));
                }
                TraceOp::Config { key, value }
            }
            TAG_PCI => {
                let offset = cur.u32(start, RECORD)?;
                check_pci_offset(offset).map_err(|_| bad(PCI_RULE))?;
                TraceOp::Pci {
                    offset,
                    value: cur.u32(start, RECORD)?,
                }
            }
            TAG_WRITE => {
                accessed = true;
                let addr = cur.u32(start, RECORD)?;
                check_addr(addr).map_err(|_| bad(ADDR_RULE))?;
                frame_due = crate::replay::is_swap(addr);
                TraceOp::Write {
                    addr,
                    value: cur.u32(start, RECORD)?,
                }
            }
            TAG_READ | TAG_READ_VALUE => {
                accessed = true;
                let addr = cur.u32(start, RECORD)?;
                check_addr(addr).map_err(|_| bad(ADDR_RULE))?;
                let value = if tag == TAG_READ_VALUE {
                    Some(cur.u32(start, RECORD)?)
                } else {
                    None
                };
                TraceOp::Read { addr, value }
            }
            TAG_DUMP => {
                let buffer = match cur.u8(start, RECORD)? {
                    0 => DumpBuffer::Front,
                    1 => DumpBuffer::Back,
                    2 => DumpBuffer::Depth,
                    3 => DumpBuffer::Aux,
                    _ => return Err(bad("a dump buffer code 0-3")),
                };
                let len = cur.u8(start, RECORD)?;
                let name = cur.take(usize::from(len), start, RECORD)?;
                let file = std::str::from_utf8(name).map_err(|_| bad(DUMP_NAME_RULE))?;
                check_dump_name(file).map_err(|_| bad(DUMP_NAME_RULE))?;
                TraceOp::Dump {
                    buffer,
                    file: file.to_owned(),
                }
            }
            TAG_FRAME => {
                let number = cur.u32(start, RECORD)?;
                if !frame_due || u64::from(number) != frames {
                    return Err(bad("frame records only after a swap, numbered from 0"));
                }
                frame_due = false;
                frames += 1;
                continue;
            }
            tag => return Err(BinaryError::UnknownTag { offset: start, tag }),
        };
        ops.push(op);
    }
    if frame_due {
        return Err(BinaryError::Truncated {
            offset: bytes.len(),
            what: "the frame record after the last swap",
        });
    }
    let trace = Trace { ops };
    let config = trace.board_config();
    let found = [config.fbi_mb, config.tmus, config.tmu_mb];
    if (op_count, frame_count, &board[..]) != (trace.ops.len() as u64, frames, &found[..]) {
        return Err(BinaryError::HeaderMismatch {
            expected: format!("{op_count} ops, {frame_count} frames, board {board:?}"),
            found: format!("{} ops, {frames} frames, board {found:?}", trace.ops.len()),
        });
    }
    Ok(trace)
}

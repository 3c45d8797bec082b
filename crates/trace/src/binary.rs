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
//!          0x08 wait        cycles u64: host time with no bus access (version 2)
//! ```
//!
//! A reader accepts a file whose `min_reader_version` is at most [`READER_VERSION`] and skips
//! header bytes it does not know (up to `header_len`). A trace with `wait` records is
//! written as version 2 with `min_reader_version` 2 (a version-1 reader refuses it rather
//! than dropping the waits); one without is written exactly as version 1 wrote it.
//! [`BinaryReader`] reads the records one at a time and trusts no count for an
//! allocation; the header's counts are only checked against the records, at the end.
//! Frame records carry no op of their own: decoding yields exactly the ops that were encoded, and the decoder checks that each
//! swap is followed by its frame record. The same rules as the text parser apply (offsets,
//! config values and order, dump names), so any decoded trace writes back as valid text.

use crate::{
    check_addr, check_dump_name, check_pci_offset, ConfigKey, DumpBuffer, OpCounts, Trace, TraceOp,
    ADDR_RULE, DUMP_NAME_RULE, PCI_RULE,
};

/// The magic bytes that open a binary trace.
pub const MAGIC: [u8; 8] = *b"SST1TRCB";
/// The version this code writes for a trace with `wait` records (one without is
/// written as version 1, which it is).
pub const VERSION: u16 = 2;
/// The newest `min_reader_version` this code can read.
pub const READER_VERSION: u16 = 2;
/// The version of a trace without `wait` records.
const VERSION_WITHOUT_WAITS: u16 = 1;
/// Length of the version-1 header.
const HEADER_LEN: u32 = 36;

const TAG_CONFIG: u8 = 0x01;
const TAG_PCI: u8 = 0x02;
const TAG_WRITE: u8 = 0x03;
const TAG_READ: u8 = 0x04;
const TAG_READ_VALUE: u8 = 0x05;
const TAG_DUMP: u8 = 0x06;
const TAG_FRAME: u8 = 0x07;
const TAG_WAIT: u8 = 0x08;

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
    /// The input could not be read.
    #[error("byte {offset}: {message}")]
    Io {
        /// Where the item being read starts.
        offset: usize,
        /// What the OS said.
        message: String,
    },
    /// A whole-trace decode ([`decode_binary`]) met more ops than it holds in memory.
    #[error("more than {limit} ops, the most a whole trace read into memory may hold (replay streams traces of any length)")]
    TooManyOps {
        /// The limit, [`MAX_TRACE_OPS`](crate::MAX_TRACE_OPS).
        limit: usize,
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
    let counts = OpCounts::of(trace);
    let mut out = Vec::with_capacity(HEADER_LEN as usize + trace.ops.len() * 9);
    encode_header(
        &mut out,
        trace.board_config(),
        trace.ops.len() as u64,
        counts.swaps,
        counts.waits > 0,
    );
    let mut frame = 0u32;
    for op in &trace.ops {
        encode_op(&mut out, op, &mut frame);
    }
    out
}

/// Appends the header of a trace on `board` with `op_count` ops and `frame_count` frames;
/// `waits` says whether it holds `wait` records (version 2) or not (version 1).
pub(crate) fn encode_header(
    out: &mut Vec<u8>,
    board: sst1_board::BoardConfig,
    op_count: u64,
    frame_count: u64,
    waits: bool,
) {
    let version = if waits {
        VERSION
    } else {
        VERSION_WITHOUT_WAITS
    };
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(&HEADER_LEN.to_le_bytes());
    for field in [board.fbi_mb, board.tmus, board.tmu_mb] {
        out.push(field.min(255) as u8);
    }
    out.push(0);
    out.extend_from_slice(&op_count.to_le_bytes());
    out.extend_from_slice(&frame_count.to_le_bytes());
}

/// Appends the record of `op` (and, after a swap, the frame record numbered `frame`,
/// which then counts on).
pub(crate) fn encode_op(out: &mut Vec<u8>, op: &TraceOp, frame: &mut u32) {
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
                *frame = frame.wrapping_add(1);
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
        TraceOp::Wait { cycles } => {
            out.push(TAG_WAIT);
            out.extend_from_slice(&cycles.to_le_bytes());
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

/// The header fields a reader checks the records against.
#[derive(Clone, Copy, Debug)]
struct Header {
    board: [u32; 3],
    op_count: u64,
    frame_count: u64,
}

/// Reads a binary trace op by op from `input` (not gzip-compressed;
/// [`TraceReader`](crate::TraceReader) handles that): an iterator of [`TraceOp`]s that
/// ends after the first error. Memory is constant: no count from the header is trusted
/// for an allocation. The header's counts and board are checked against the records at the
/// end of the input, so the last item of a trace that disagrees with its header is a
/// [`BinaryError::HeaderMismatch`].
pub struct BinaryReader<R> {
    input: Buffered<R>,
    /// Byte offset of the next unread byte.
    pos: u64,
    header: Header,
    /// The board the `config` records set so far.
    config: sst1_board::BoardConfig,
    ops: u64,
    frames: u64,
    accessed: bool,
    frame_due: bool,
    done: bool,
}

/// What is being read, for [`BinaryError::Truncated`].
const RECORD: &str = "a record";

impl<R: std::io::Read> BinaryReader<R> {
    /// Reads and checks the header.
    pub fn new(mut input: R) -> Result<Self, BinaryError> {
        const HEADER: &str = "the header";
        let mut fixed = [0u8; HEADER_LEN as usize];
        // The magic first: an input that does not start with it is not ours, short or not.
        let mut magic = Vec::with_capacity(MAGIC.len());
        std::io::Read::read_to_end(
            &mut <&mut R as std::io::Read>::take(&mut input, MAGIC.len() as u64),
            &mut magic,
        )
        .map_err(|e| io_error(0, &e))?;
        if magic != MAGIC {
            return Err(BinaryError::BadMagic);
        }
        fixed[..MAGIC.len()].copy_from_slice(&magic);
        read_full(&mut input, &mut fixed[MAGIC.len()..], 0, HEADER)?;
        let u16_at = |at: usize| u16::from_le_bytes([fixed[at], fixed[at + 1]]);
        let u32_at = |at: usize| {
            u32::from_le_bytes([fixed[at], fixed[at + 1], fixed[at + 2], fixed[at + 3]])
        };
        let u64_at = |at: usize| u64::from(u32_at(at)) | u64::from(u32_at(at + 4)) << 32;
        let version = u16_at(8);
        let min_reader_version = u16_at(10);
        if min_reader_version > READER_VERSION {
            return Err(BinaryError::TooNew {
                version,
                min_reader_version,
            });
        }
        let header_len = u32_at(12);
        if header_len < HEADER_LEN {
            return Err(BinaryError::BadHeader {
                expected: "header_len of at least 36",
            });
        }
        let header = Header {
            board: [fixed[16], fixed[17], fixed[18]].map(u32::from),
            op_count: u64_at(20),
            frame_count: u64_at(28),
        };
        // Skip header fields this reader does not know, in constant memory.
        let extra = u64::from(header_len - HEADER_LEN);
        let skipped = std::io::copy(
            &mut <&mut R as std::io::Read>::take(&mut input, extra),
            &mut std::io::sink(),
        )
        .map_err(|e| io_error(0, &e))?;
        if skipped < extra {
            return Err(BinaryError::Truncated {
                offset: 0,
                what: HEADER,
            });
        }
        Ok(Self {
            input: Buffered::new(input),
            pos: u64::from(header_len),
            header,
            config: sst1_board::BoardConfig::default(),
            ops: 0,
            frames: 0,
            accessed: false,
            frame_due: false,
            done: false,
        })
    }

    /// The board configuration the header announces (checked against the `config`
    /// records at the end).
    pub fn header_board(&self) -> [u32; 3] {
        self.header.board
    }

    /// Reads `buf.len()` bytes of the record that starts at `start`.
    #[inline]
    fn read(&mut self, buf: &mut [u8], start: u64) -> Result<(), BinaryError> {
        let got = self.input.take(buf).map_err(|e| io_error(start, &e))?;
        if got < buf.len() {
            return Err(BinaryError::Truncated {
                offset: offset(start),
                what: RECORD,
            });
        }
        self.pos += buf.len() as u64;
        Ok(())
    }

    fn u8(&mut self, start: u64) -> Result<u8, BinaryError> {
        let mut b = [0u8; 1];
        self.read(&mut b, start)?;
        Ok(b[0])
    }

    fn u32(&mut self, start: u64) -> Result<u32, BinaryError> {
        let mut b = [0u8; 4];
        self.read(&mut b, start)?;
        Ok(u32::from_le_bytes(b))
    }

    /// The next record's first byte, or `None` at the end of the input.
    #[inline]
    fn tag(&mut self) -> Result<Option<u8>, BinaryError> {
        let mut b = [0u8; 1];
        match self
            .input
            .take(&mut b)
            .map_err(|e| io_error(self.pos, &e))?
        {
            0 => Ok(None),
            _ => {
                self.pos += 1;
                Ok(Some(b[0]))
            }
        }
    }

    /// The checks at the end of the input: the last swap's frame record, and the header.
    fn finish(&self) -> Result<(), BinaryError> {
        if self.frame_due {
            return Err(BinaryError::Truncated {
                offset: offset(self.pos),
                what: "the frame record after the last swap",
            });
        }
        let c = self.config;
        let found = [c.fbi_mb, c.tmus, c.tmu_mb];
        let h = self.header;
        if (h.op_count, h.frame_count, h.board) != (self.ops, self.frames, found) {
            return Err(BinaryError::HeaderMismatch {
                expected: format!(
                    "{} ops, {} frames, board {:?}",
                    h.op_count, h.frame_count, h.board
                ),
                found: format!("{} ops, {} frames, board {found:?}", self.ops, self.frames),
            });
        }
        Ok(())
    }

    /// The next op, `Ok(None)` at a valid end.
    fn record(&mut self) -> Result<Option<TraceOp>, BinaryError> {
        loop {
            let start = self.pos;
            let Some(tag) = self.tag()? else {
                self.finish()?;
                return Ok(None);
            };
            let bad = |expected| BinaryError::BadField {
                offset: offset(start),
                expected,
            };
            if self.frame_due && tag != TAG_FRAME {
                return Err(bad("a frame record after a swap"));
            }
            let op = match tag {
                TAG_CONFIG => {
                    if self.accessed {
                        return Err(bad("config records before the first write or read"));
                    }
                    let key = match self.u8(start)? {
                        0 => ConfigKey::FbiMb,
                        1 => ConfigKey::Tmus,
                        2 => ConfigKey::TmuMb,
                        _ => return Err(bad("a config key code 0-2")),
                    };
                    let value = self.u32(start)?;
                    if !key.allowed().contains(&value) {
                        return Err(bad(key.expected()));
                    }
                    TraceOp::Config { key, value }
                }
                TAG_PCI => {
                    let offset = self.u32(start)?;
                    check_pci_offset(offset).map_err(|_| bad(PCI_RULE))?;
                    TraceOp::Pci {
                        offset,
                        value: self.u32(start)?,
                    }
                }
                TAG_WRITE => {
                    self.accessed = true;
                    let addr = self.u32(start)?;
                    check_addr(addr).map_err(|_| bad(ADDR_RULE))?;
                    let value = self.u32(start)?;
                    self.frame_due = crate::replay::is_swap(addr);
                    TraceOp::Write { addr, value }
                }
                TAG_READ | TAG_READ_VALUE => {
                    self.accessed = true;
                    let addr = self.u32(start)?;
                    check_addr(addr).map_err(|_| bad(ADDR_RULE))?;
                    let value = if tag == TAG_READ_VALUE {
                        Some(self.u32(start)?)
                    } else {
                        None
                    };
                    TraceOp::Read { addr, value }
                }
                TAG_DUMP => {
                    let buffer = match self.u8(start)? {
                        0 => DumpBuffer::Front,
                        1 => DumpBuffer::Back,
                        2 => DumpBuffer::Depth,
                        3 => DumpBuffer::Aux,
                        _ => return Err(bad("a dump buffer code 0-3")),
                    };
                    let len = usize::from(self.u8(start)?);
                    let mut name = [0u8; 255];
                    self.read(&mut name[..len], start)?;
                    let file =
                        std::str::from_utf8(&name[..len]).map_err(|_| bad(DUMP_NAME_RULE))?;
                    check_dump_name(file).map_err(|_| bad(DUMP_NAME_RULE))?;
                    TraceOp::Dump {
                        buffer,
                        file: file.to_owned(),
                    }
                }
                TAG_WAIT => {
                    let mut b = [0u8; 8];
                    self.read(&mut b, start)?;
                    TraceOp::Wait {
                        cycles: u64::from_le_bytes(b),
                    }
                }
                TAG_FRAME => {
                    let number = self.u32(start)?;
                    if !self.frame_due || u64::from(number) != self.frames {
                        return Err(bad("frame records only after a swap, numbered from 0"));
                    }
                    self.frame_due = false;
                    self.frames += 1;
                    continue;
                }
                tag => {
                    return Err(BinaryError::UnknownTag {
                        offset: offset(start),
                        tag,
                    })
                }
            };
            crate::apply_config(&mut self.config, &op);
            self.ops += 1;
            return Ok(Some(op));
        }
    }
}

impl<R: std::io::Read> Iterator for BinaryReader<R> {
    type Item = Result<TraceOp, BinaryError>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        // Most records are writes: one whose bytes are all in the buffer is decoded by
        // `next_write`, small enough to inline into the replay loop; the rest (and every
        // error) take `record`.
        if let Some((addr, value)) = self.next_write() {
            return Some(Ok(TraceOp::Write { addr, value }));
        }
        self.next_record()
    }
}

impl<R: std::io::Read> BinaryReader<R> {
    /// The next op if it is a write whose record is all in the buffer and whose address
    /// is valid: its address and value, consumed, as [`Iterator::next`] would yield it.
    /// `None`, with nothing consumed, for anything else (another record, a record that
    /// crosses the buffer's end, an error, the end, a frame record due): `next` reads it.
    #[inline(always)]
    pub fn next_write(&mut self) -> Option<(u32, u32)> {
        let mut one = [(0, 0)];
        (self.next_writes(&mut one) == 1).then_some(one[0])
    }

    /// The next ops while they are writes as [`BinaryReader::next_write`] takes them,
    /// into `out` until it is full: how many were taken, consumed as that many
    /// `next_write` calls would consume them (a run ends after a swap: its frame record
    /// comes next).
    #[inline(always)]
    pub fn next_writes(&mut self, out: &mut [(u32, u32)]) -> usize {
        if self.done || self.frame_due {
            return 0;
        }
        // The whole write records in the buffer, decoded in one loop; the reader's
        // position and counts move once for them all.
        let n = self.input.take_writes(out);
        if n > 0 {
            self.pos += (n * WRITE_RECORD_LEN) as u64;
            self.ops += n as u64;
            self.accessed = true;
            self.frame_due = crate::replay::is_swap(out[n - 1].0);
        }
        n
    }

    /// [`Iterator::next`] through [`BinaryReader::record`].
    #[inline(never)]
    fn next_record(&mut self) -> Option<Result<TraceOp, BinaryError>> {
        if self.done {
            return None;
        }
        let item = self.record().transpose();
        if !matches!(item, Some(Ok(_))) {
            self.done = true;
        }
        item
    }
}

/// A byte offset as the error types hold it.
fn offset(pos: u64) -> usize {
    usize::try_from(pos).unwrap_or(usize::MAX)
}

fn io_error(pos: u64, e: &std::io::Error) -> BinaryError {
    BinaryError::Io {
        offset: offset(pos),
        message: e.to_string(),
    }
}

/// The records' input behind a buffer of its own: a record's fields are copied out of
/// the buffer, and the input is read only when the buffer runs dry (a read per field
/// through a generic `Read` cost more than the replay of the write it carries).
struct Buffered<R> {
    input: R,
    buf: Box<[u8]>,
    /// Unread bytes are `buf[at..len]`.
    at: usize,
    len: usize,
}

/// Bytes of a write record: the tag, the address and the value.
const WRITE_RECORD_LEN: usize = 9;

impl<R: std::io::Read> Buffered<R> {
    /// The buffer's size.
    const SIZE: usize = 64 << 10;

    /// Consumes the write records at the front of the buffer into `out`, as many as are
    /// whole in it and fit: up to the first record that is not a write, has an invalid
    /// address or crosses the buffer's end, and up to and including a swap (the frame it
    /// ends is the reader's to count). Returns how many.
    #[inline(always)]
    fn take_writes(&mut self, out: &mut [(u32, u32)]) -> usize {
        let whole = (self.len - self.at) / WRITE_RECORD_LEN;
        let records = self.buf[self.at..self.at + whole * WRITE_RECORD_LEN]
            .chunks_exact(WRITE_RECORD_LEN)
            .take(out.len());
        let mut n = 0;
        for (record, slot) in records.zip(out.iter_mut()) {
            let Ok(&[tag, a0, a1, a2, a3, v0, v1, v2, v3]) =
                <&[u8; WRITE_RECORD_LEN]>::try_from(record)
            else {
                break;
            };
            let addr = u32::from_le_bytes([a0, a1, a2, a3]);
            if tag != TAG_WRITE || check_addr(addr).is_err() {
                break;
            }
            *slot = (addr, u32::from_le_bytes([v0, v1, v2, v3]));
            n += 1;
            if crate::replay::is_swap(addr) {
                break;
            }
        }
        self.at += n * WRITE_RECORD_LEN;
        n
    }

    fn new(input: R) -> Self {
        Self {
            input,
            buf: vec![0; Self::SIZE].into_boxed_slice(),
            at: 0,
            len: 0,
        }
    }

    /// Copies up to `out.len()` bytes into `out`; fewer only at the end of the input.
    #[inline]
    fn take(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        if let Some(src) = self.buf.get(self.at..self.at + out.len()) {
            if self.at + out.len() <= self.len {
                out.copy_from_slice(src);
                self.at += out.len();
                return Ok(out.len());
            }
        }
        self.take_slow(out)
    }

    /// [`Buffered::take`] across a refill.
    #[cold]
    fn take_slow(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        let mut filled = 0;
        while filled < out.len() {
            if self.at == self.len {
                self.at = 0;
                self.len = 0;
                loop {
                    match self.input.read(&mut self.buf) {
                        Ok(n) => {
                            self.len = n;
                            break;
                        }
                        Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                        Err(e) => return Err(e),
                    }
                }
                if self.len == 0 {
                    break;
                }
            }
            let n = (out.len() - filled).min(self.len - self.at);
            out[filled..filled + n].copy_from_slice(&self.buf[self.at..self.at + n]);
            self.at += n;
            filled += n;
        }
        Ok(filled)
    }
}

/// Fills `buf`, or reports what was being read (at `start`) as truncated.
fn read_full(
    input: &mut impl std::io::Read,
    buf: &mut [u8],
    start: u64,
    what: &'static str,
) -> Result<(), BinaryError> {
    let mut filled = 0;
    while filled < buf.len() {
        match input.read(&mut buf[filled..]) {
            Ok(0) => {
                return Err(BinaryError::Truncated {
                    offset: offset(start),
                    what,
                })
            }
            Ok(n) => filled += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(io_error(start, &e)),
        }
    }
    Ok(())
}

/// Decodes a whole binary trace (not gzip-compressed; [`read_trace`](crate::read_trace)
/// handles that): at most [`MAX_TRACE_OPS`](crate::MAX_TRACE_OPS) ops. Never panics, and
/// allocates nothing from the header's counts, whatever the bytes.
pub fn decode_binary(bytes: &[u8]) -> Result<Trace, BinaryError> {
    let mut ops = Vec::new();
    for op in BinaryReader::new(bytes)? {
        if ops.len() == crate::MAX_TRACE_OPS {
            return Err(BinaryError::TooManyOps {
                limit: crate::MAX_TRACE_OPS,
            });
        }
        ops.push(op?);
    }
    Ok(Trace { ops })
}

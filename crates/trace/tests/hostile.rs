//! Hostile input to the trace readers, the recorder and the replayer (issue 11, items
//! 11-16): what a recording holds, memory that must not grow with what a trace says, and
//! error messages that must stay short.
//!
//! The memory tests run their body again in a child process (this test binary, with the
//! test's name and an environment variable) whose address space is limited with
//! `setrlimit(RLIMIT_AS)`: an allocation past the limit fails there, so a body that
//! allocates with the input's size aborts the child, and the test fails with its output.

#[cfg(unix)]
#[path = "support/address_space.rs"]
mod address_space;

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::Command;

use sst1_board::{Board, BoardConfig, BufferKind, Reference};
use sst1_regs::RegisterBus;
use sst1_trace::{
    decode_binary, encode_binary, execute, execute_references_stream, parse_text, read_trace,
    stream_trace, write_text, BinaryReader, DumpBuffer, LoadError, Recorder, ReferenceDump, Trace,
    TraceOp, TraceReader, TraceWriter,
};

// ---------------------------------------------------------------------------------------
// Helpers.

/// The environment variable that tells a child which test body to run.
const CHILD: &str = "SST1_TRACE_MEMORY_CHILD";

/// Runs `body` in a child process whose address space is limited to `limit` bytes, or,
/// in that child, runs it. `name` is the test's name (the child runs only that test).
fn in_memory_limit(name: &str, limit: u64, body: impl FnOnce()) {
    if std::env::var(CHILD).as_deref() == Ok(name) {
        body();
        return;
    }
    let exe = std::env::current_exe().expect("test binary path");
    let mut command = Command::new(exe);
    command
        .args([name, "--exact", "--nocapture", "--test-threads=1"])
        .env(CHILD, name);
    #[cfg(unix)]
    address_space::limit_address_space(&mut command, limit);
    let output = command.output().expect("run the test in a child");
    let text = String::from_utf8_lossy(&output.stdout).into_owned()
        + &String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success() && text.contains("1 passed"),
        "{name} under an address-space limit of {} MiB: {}\n{text}",
        limit >> 20,
        output.status
    );
}

/// xorshift64* (Vigna 2016): small, deterministic, good enough for random streams.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn u32(&mut self) -> u32 {
        (self.next() >> 32) as u32
    }

    fn below(&mut self, n: u32) -> u32 {
        (self.next() % u64::from(n.max(1))) as u32
    }
}

/// A unique scratch path under the temporary folder.
fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("sst1-trace-hostile-{name}-{}", std::process::id()))
}

/// Gzip-compresses `bytes`.
fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    enc.write_all(bytes).unwrap();
    enc.finish().unwrap()
}

// ---------------------------------------------------------------------------------------
// Item 11: recorded traces read back and replay as the recording ran.

/// Everything observable of a board: its three buffers, display size, counters,
/// diagnostics, FBI registers and texture memory.
#[derive(PartialEq)]
struct BoardState {
    buffers: Vec<Vec<u16>>,
    display: (u32, u32),
    stats: sst1_board::Stats,
    diagnostics: sst1_board::Diagnostics,
    registers: Vec<u32>,
    textures: Vec<Vec<u8>>,
}

fn board_state(board: &Board) -> BoardState {
    BoardState {
        buffers: [BufferKind::Front, BufferKind::Back, BufferKind::Aux]
            .map(|kind| board.dump_buffer(kind))
            .to_vec(),
        display: board.display_size(),
        stats: board.stats(),
        diagnostics: board.diagnostics().clone(),
        registers: (0..0x400).step_by(4).map(|o| board.fbi().reg(o)).collect(),
        textures: (0..3)
            .filter_map(|i| board.tmu(i).map(|t| t.memory().to_vec()))
            .collect(),
    }
}

/// A random bus address in `region` (0 registers, 1 LFB, 2 texture), with random bits
/// above the 16 MiB window and random low (unaligned) bits.
fn random_addr(rng: &mut Rng, region: u32) -> u32 {
    let low = match region {
        // Registers: any register, chip field and remap/wrap bits.
        0 => rng.u32() & 0x3f_ffff,
        1 => 0x40_0000 | (rng.u32() & 0x3f_ffff),
        _ => 0x80_0000 | (rng.u32() & 0x7f_ffff),
    };
    let high = if rng.below(2) == 0 {
        rng.u32() & 0xff00_0000
    } else {
        0
    };
    low | high | (rng.u32() & 3)
}

#[test]
fn recorded_random_streams_read_back_and_replay_identically() {
    let mut rng = Rng(0x11_5eed_c0de);
    let config = BoardConfig {
        fbi_mb: 4,
        tmus: 2,
        tmu_mb: 2,
    };
    let mut odd = [0usize; 3];
    for stream in 0..20 {
        let mut rec = Recorder::new(Board::new(config), config);
        rec.pci_write(0x40, 3);
        let mut live_dumps = Vec::new();
        for _ in 0..1500 {
            match rng.below(100) {
                0..=39 => {
                    let addr = random_addr(&mut rng, 0);
                    // Keep triangle commands rare: a random triangle may cover the screen.
                    let reg = (addr >> 2) & 0xff;
                    if matches!(reg, 0x20 | 0x40) && rng.below(4) != 0 {
                        continue;
                    }
                    rec.write32(addr, rng.u32());
                }
                40..=59 => rec.write32(random_addr(&mut rng, 1), rng.u32()),
                60..=74 => rec.write32(random_addr(&mut rng, 2), rng.u32()),
                75..=87 => {
                    let region = rng.below(3);
                    rec.read32(random_addr(&mut rng, region));
                }
                88..=95 => {
                    let offset = match rng.below(5) {
                        0 => 0x40,
                        1 => 0x41,
                        2 => 0x140,
                        3 => 0x100 | (rng.u32() & 0xfc),
                        _ => rng.u32(),
                    };
                    rec.pci_write(offset, if rng.below(2) == 0 { 3 } else { rng.u32() });
                }
                _ => {
                    let buffer = DumpBuffer::ALL[rng.below(4) as usize];
                    let file = format!("s{stream}_{}.raw", live_dumps.len());
                    rec.dump(buffer, &file);
                    live_dumps.push(rec.inner().dump_buffer(buffer.kind()));
                }
            }
        }
        let (live, trace) = rec.finish();
        for op in &trace.ops {
            match *op {
                TraceOp::Write { addr, .. } | TraceOp::Read { addr, .. } => {
                    odd[0] += usize::from(addr % 4 != 0);
                    odd[1] += usize::from(addr >= 0x100_0000);
                }
                TraceOp::Pci { offset, .. } => odd[2] += usize::from(offset == 0xfc),
                _ => {}
            }
        }

        // Text and binary read back to the same ops.
        let text = write_text(&trace);
        let from_text = parse_text("recorded", text.as_bytes())
            .unwrap_or_else(|e| panic!("stream {stream}: {e}"));
        assert_eq!(from_text, trace, "stream {stream}");
        let from_binary = decode_binary(&encode_binary(&trace))
            .unwrap_or_else(|e| panic!("stream {stream}: {e}"));
        assert_eq!(from_binary, trace, "stream {stream}");

        // Both replay to the live board's dumps and final state.
        let expected = board_state(&live);
        for replayed in [from_text, from_binary] {
            let mut board = Board::new(replayed.board_config());
            let dumps = execute(&replayed.ops, &mut board, |_| {});
            let data: Vec<&Vec<u16>> = dumps.iter().map(|d| &d.data).collect();
            assert_eq!(
                data,
                live_dumps.iter().collect::<Vec<_>>(),
                "stream {stream}"
            );
            assert!(
                board_state(&board) == expected,
                "stream {stream}: final state"
            );
        }
    }
    // The recorder saw nothing but aligned offsets inside the window, and logged the
    // undecodable PCI offsets as PCI_UNDECODED.
    assert_eq!(odd[..2], [0, 0]);
    assert!(odd[2] > 100, "{odd:?}");
}

#[test]
fn recorder_logs_what_the_board_decodes() {
    let mut rec = Recorder::new(Board::new(BoardConfig::default()), BoardConfig::default());
    rec.write32(0x0100_0124, 0); // above the window: fastfillCMD
    rec.write32(0x0040_0003, 0x1234_5678); // unaligned LFB write
    rec.read32(0xffff_ffff);
    rec.pci_write(0x141, 3);
    rec.pci_write(0x40, 3);
    let (_, trace) = rec.finish();
    assert_eq!(
        write_text(&trace),
        "config fbi_mb 4\nconfig tmus 1\nconfig tmu_mb 4\n\
         w 0x000124 0x00000000\nw 0x400000 0x12345678\nr 0xfffffc 0xffffffff\n\
         pci 0xfc 0x00000003\npci 0x40 0x00000003\n"
    );
}

// ---------------------------------------------------------------------------------------
// Item 12: replay streams; memory does not depend on the trace's length.

/// An endless text trace: `r 0` lines, with a `dump` line every `dump_every` lines if
/// given; ends after `lines` lines.
struct Generated {
    lines: u64,
    dump_every: Option<u64>,
    line: u64,
    pending: Vec<u8>,
    at: usize,
}

impl Generated {
    fn new(lines: u64, dump_every: Option<u64>) -> Self {
        Self {
            lines,
            dump_every,
            line: 0,
            pending: Vec::new(),
            at: 0,
        }
    }
}

impl Read for Generated {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if self.at == self.pending.len() {
            self.pending.clear();
            self.at = 0;
            while self.pending.len() < 4096 && self.line < self.lines {
                self.line += 1;
                match self.dump_every {
                    Some(n) if self.line.is_multiple_of(n) => {
                        self.pending.extend_from_slice(b"dump front d.raw\n")
                    }
                    _ => self.pending.extend_from_slice(b"r 0\n"),
                }
            }
        }
        let n = buf.len().min(self.pending.len() - self.at);
        buf[..n].copy_from_slice(&self.pending[self.at..self.at + n]);
        self.at += n;
        Ok(n)
    }
}

#[test]
fn trace_reader_streams_an_endless_input() {
    // No end: the reader must hand out ops as it reads them.
    let mut reader = TraceReader::new("endless", Generated::new(u64::MAX, None)).unwrap();
    for _ in 0..1_000_000 {
        assert_eq!(
            reader.next().unwrap().unwrap(),
            TraceOp::Read {
                addr: 0,
                value: None
            }
        );
    }
}

#[test]
fn vote_streams_millions_of_reads_and_thousands_of_dumps_in_bounded_memory() {
    // 3 million ops and 1500 dumps of 640x480: 96 MB of ops and 3.7 GB of dumps (four
    // copies under the vote) if they were held.
    in_memory_limit(
        "vote_streams_millions_of_reads_and_thousands_of_dumps_in_bounded_memory",
        384 << 20,
        || {
            let lines = 3_000_000;
            let stream = stream_trace("generated", Generated::new(lines, Some(2000))).unwrap();
            let config = stream.config();
            let mut dumps = 0;
            let boards = execute_references_stream(
                stream,
                config,
                |_| {},
                |d: ReferenceDump| {
                    assert_eq!(d.voted.data.len(), 640 * 480);
                    dumps += 1;
                    Ok(())
                },
            )
            .unwrap();
            assert_eq!(dumps, 1500);
            assert_eq!(boards.len(), Reference::ALL.len());
        },
    );
}

// ---------------------------------------------------------------------------------------
// Item 13: a forged op count allocates nothing.

/// A binary trace header with `extra` unknown header bytes (zeros) and no records, whose
/// op count says `op_count`.
fn binary_header(op_count: u64, extra: u32) -> Vec<u8> {
    let mut bytes = b"SST1TRCB".to_vec();
    bytes.extend_from_slice(&1u16.to_le_bytes());
    bytes.extend_from_slice(&1u16.to_le_bytes());
    bytes.extend_from_slice(&(36 + extra).to_le_bytes());
    bytes.extend_from_slice(&[4, 1, 4, 0]);
    bytes.extend_from_slice(&op_count.to_le_bytes());
    bytes.extend_from_slice(&0u64.to_le_bytes());
    bytes
}

#[test]
fn forged_op_count_allocates_nothing() {
    // 128 MiB of input: a reader that sizes its op list from the count (capped by the
    // input's length / 5) reserves 850 MB.
    in_memory_limit("forged_op_count_allocates_nothing", 512 << 20, || {
        let extra = 128 << 20;
        let mut bytes = binary_header(u64::MAX, extra);
        bytes.resize(bytes.len() + extra as usize, 0);
        let expected = "header says 18446744073709551615 ops, 0 frames, board [4, 1, 4], \
                        records hold 0 ops, 0 frames, board [4, 1, 4]";
        assert_eq!(decode_binary(&bytes).unwrap_err().to_string(), expected);
        assert_eq!(
            read_trace("forged", &bytes).unwrap_err().to_string(),
            format!("forged: {expected}")
        );
    });
}

#[test]
fn binary_reader_checks_the_count_only_at_the_end() {
    let mut bytes = binary_header(u64::MAX, 0);
    bytes.extend_from_slice(&[0x04, 0, 0, 0, 0]); // r 0
    let mut reader = BinaryReader::new(&bytes[..]).unwrap();
    assert_eq!(
        reader.next().unwrap().unwrap(),
        TraceOp::Read {
            addr: 0,
            value: None
        }
    );
    assert_eq!(
        reader.next().unwrap().unwrap_err().to_string(),
        "header says 18446744073709551615 ops, 0 frames, board [4, 1, 4], \
         records hold 1 ops, 0 frames, board [4, 1, 4]"
    );
    assert!(reader.next().is_none());
}

// ---------------------------------------------------------------------------------------
// Item 14: the decompression cap is met in bounded memory.

/// A gzip stream of a binary trace header announcing `zeros` header bytes, then those
/// zeros: `parts` gzip members of `part` zeros each after the header's own member
/// (MultiGzDecoder reads them as one stream).
fn gzip_bomb(part: usize, parts: usize) -> Vec<u8> {
    let zeros = (part * parts) as u32;
    let mut bomb = gzip(&binary_header(0, zeros));
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    enc.write_all(&vec![0u8; part]).unwrap();
    let member = enc.finish().unwrap();
    for _ in 0..parts {
        bomb.extend_from_slice(&member);
    }
    bomb
}

#[test]
fn gzip_bomb_stops_at_the_cap_in_bounded_memory() {
    // 1.06 GiB decompressed from 1 MB: a reader that holds the decompressed bytes grows a
    // 2 GiB buffer before it sees the cap.
    in_memory_limit(
        "gzip_bomb_stops_at_the_cap_in_bounded_memory",
        256 << 20,
        || {
            let bomb = gzip_bomb(64 << 20, 17);
            assert!(bomb.len() < 2 << 20, "{}", bomb.len());
            assert_eq!(
                read_trace("bomb.vtrace.gz", &bomb).unwrap_err().to_string(),
                "bomb.vtrace.gz: cannot decompress: decompressed trace larger than 1 GiB"
            );
            let path = scratch("bomb.vtrace.gz");
            std::fs::write(&path, &bomb).unwrap();
            let err = sst1_trace::load_trace(&path).unwrap_err().to_string();
            std::fs::remove_file(&path).unwrap();
            assert!(
                err.ends_with(": cannot decompress: decompressed trace larger than 1 GiB"),
                "{err}"
            );
        },
    );
}

#[test]
fn bounded_reads_never_hold_more_than_the_limit() {
    let data = vec![7u8; 100_000];
    let read = sst1_trace::read_bounded(&data[..], 100_000).unwrap();
    assert_eq!(read, data);
    assert!(read.capacity() <= 100_001, "{}", read.capacity());
    let err = sst1_trace::read_bounded(&data[..], 99_999).unwrap_err();
    assert_eq!(err.to_string(), "larger than 99999 bytes");
    let bomb = gzip(&vec![0u8; 1 << 20]);
    let err = sst1_trace::gunzip_with_limit(&bomb, 1000).unwrap_err();
    assert_eq!(err.to_string(), "decompressed trace larger than 1000 bytes");
    assert_eq!(
        sst1_trace::gunzip_with_limit(&bomb, 1 << 20).unwrap().len(),
        1 << 20
    );
}

// ---------------------------------------------------------------------------------------
// Item 15: dumps go to a sink when reached (see the vote test above); a single board too.

#[test]
fn single_board_streams_dumps_in_bounded_memory() {
    // 2000 dumps of 640x480 (1.2 GB if held).
    in_memory_limit(
        "single_board_streams_dumps_in_bounded_memory",
        256 << 20,
        || {
            let stream = stream_trace("dumps", Generated::new(2000, Some(1))).unwrap();
            let mut board = Board::new(stream.config());
            let mut dumps = 0;
            let ops = sst1_trace::execute_stream(
                stream,
                &mut board,
                |_| {},
                |d| {
                    assert_eq!(d.file, "d.raw");
                    dumps += 1;
                    Ok(())
                },
            )
            .unwrap();
            assert_eq!((ops, dumps), (2000, 2000));
        },
    );
}

// ---------------------------------------------------------------------------------------
// Item 16: error messages quote at most a few dozen characters of input.

#[test]
fn error_messages_cut_quoted_input() {
    let long = "1".repeat(260_000);
    let cases: Vec<(Vec<u8>, String)> = vec![
        (
            format!("w 0x10 {long}\n").into_bytes(),
            format!(
                "t.trace:1: expected a 32-bit value (0x hex or decimal), found `{}…` (260000 bytes)",
                &long[..40]
            ),
        ),
        (
            format!("{long}x\n").into_bytes(),
            format!(
                "t.trace:1: unknown command `{}…` (260001 bytes); expected config, pci, w, r, wait or dump",
                &long[..40]
            ),
        ),
        (
            format!("dump front {}\n", "é".repeat(100_000)).into_bytes(),
            format!(
                "t.trace:1: expected a bare file name (no path separators, whitespace or `#`, at most 255 bytes), found `{}…` (200000 bytes)",
                "é".repeat(20)
            ),
        ),
        // Control characters are escaped, not written to the terminal.
        (
            b"w 0x10 \x1b[2J\n".to_vec(),
            "t.trace:1: expected a 32-bit value (0x hex or decimal), found `\\u{1b}[2J`".to_owned(),
        ),
        // A line without end is cut at MAX_LINE.
        (
            vec![b'x'; 3 << 20],
            "t.trace:1: line longer than 1048576 bytes".to_owned(),
        ),
    ];
    for (input, expected) in cases {
        let message = parse_text("t.trace", &input).unwrap_err().to_string();
        assert_eq!(message, expected);
        assert!(message.len() < 200, "{}", message.len());
        let message = read_trace("t.trace", &gzip(&input))
            .unwrap_err()
            .to_string();
        assert_eq!(message, expected);
    }
}

// ---------------------------------------------------------------------------------------
// Streaming and whole reads agree, and config lines may come after pci/dump lines.

#[test]
fn streams_find_the_board_after_pci_and_dump_lines() {
    let text = "pci 0x40 3\ndump front a.raw\nconfig tmus 3\nconfig fbi_mb 2\nw 0 0\nr 4\n";
    let stream = stream_trace("t", text.as_bytes()).unwrap();
    assert_eq!(
        stream.config(),
        BoardConfig {
            fbi_mb: 2,
            tmus: 3,
            tmu_mb: 4
        }
    );
    let ops: Vec<TraceOp> = stream.map(Result::unwrap).collect();
    assert_eq!(ops, parse_text("t", text.as_bytes()).unwrap().ops);

    // More ops before the first write than a stream may hold: a pipe cannot be read
    // twice, a regular file can.
    let mut long = "pci 0x40 3\n".repeat(5000);
    long.push_str("config tmus 2\nw 0 0\n");
    let err = match stream_trace("pipe", long.as_bytes()) {
        Err(e) => e,
        Ok(_) => panic!("a long prefix streams from a pipe"),
    };
    assert!(matches!(err, LoadError::LongPrefix { .. }), "{err}");
    let path = scratch("long-prefix.trace");
    std::fs::write(&path, &long).unwrap();
    let stream = sst1_trace::open_trace(&path).unwrap();
    assert_eq!(stream.config().tmus, 2);
    let ops: Vec<TraceOp> = stream.map(Result::unwrap).collect();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(ops.len(), 5002);
    assert_eq!(ops, parse_text("t", long.as_bytes()).unwrap().ops);
}

#[test]
fn streams_equal_whole_reads_for_every_repository_trace() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../traces/conformance/traces");
    let mut names: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    names.sort();
    for path in names.iter().take(8) {
        let whole: Trace = sst1_trace::load_trace(path).unwrap();
        let stream = sst1_trace::open_trace(path).unwrap();
        assert_eq!(stream.config(), whole.board_config());
        let ops: Vec<TraceOp> = stream.map(Result::unwrap).collect();
        assert_eq!(ops, whole.ops, "{}", path.display());
        let binary = encode_binary(&whole);
        let stream = stream_trace("b", &binary[..]).unwrap();
        let ops: Vec<TraceOp> = stream.map(Result::unwrap).collect();
        assert_eq!(ops, whole.ops, "{}", path.display());
    }
}

// ---------------------------------------------------------------------------------------
// The recorder streams into a file: every form, and memory that does not grow.

#[test]
fn streaming_recorder_writes_every_form_as_the_memory_recorder_records() {
    let dir = scratch("writer");
    std::fs::create_dir_all(&dir).unwrap();
    let config = BoardConfig {
        fbi_mb: 2,
        tmus: 3,
        tmu_mb: 1,
    };
    for name in ["t.trace", "t.trace.gz", "t.vtrace", "t.vtrace.gz"] {
        let path = dir.join(name);
        let mut rng = Rng(0x5712_ea11);
        let mut memory = Recorder::new(Board::new(config), config);
        let writer = TraceWriter::create(&path).unwrap();
        let mut streaming = Recorder::streaming(Board::new(config), config, writer);
        for i in 0..3000 {
            let region = rng.below(3);
            let addr = random_addr(&mut rng, region);
            let value = rng.u32();
            match i % 7 {
                0 => {
                    memory.read32(addr);
                    streaming.read32(addr);
                }
                1 => {
                    memory.pci_write(addr & 0x1fc, value);
                    streaming.pci_write(addr & 0x1fc, value);
                }
                2 if i % 300 == 2 => {
                    memory.dump(DumpBuffer::Front, "f.raw");
                    streaming.dump(DumpBuffer::Front, "f.raw");
                }
                _ => {
                    // Swaps included (register 0x128), so binary frame records are written.
                    let addr = if i % 50 == 0 { 0x128 } else { addr };
                    memory.write32(addr, value);
                    streaming.write32(addr, value);
                }
            }
        }
        streaming.log_mut().finish().unwrap();
        let (_, expected) = memory.finish();
        let read = sst1_trace::load_trace(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(read, expected, "{name}");
        assert_eq!(read.board_config(), config, "{name}");
        // The binary-gzip spool is gone.
        let left: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".spool"))
            .collect();
        assert!(left.is_empty(), "{left:?}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn streaming_recorder_keeps_its_first_error() {
    let mut writer = TraceWriter::create(Path::new("/dev/full")).unwrap();
    for _ in 0..10_000 {
        writer.record(&TraceOp::Write { addr: 0, value: 0 });
    }
    let err = writer.finish().unwrap_err();
    assert_eq!(err.raw_os_error(), Some(libc::ENOSPC), "{err}");
    // Finished: nothing more is written.
    assert!(writer
        .write_op(&TraceOp::Write { addr: 0, value: 0 })
        .is_err());
}

/// 8 million writes streamed into a binary trace under a 128 MiB address-space limit
/// (held in memory, as the recorder once did, they would take 256 MiB of ops).
#[test]
fn streaming_recorder_memory_does_not_grow_with_the_recording() {
    let dir = scratch("long-recording");
    in_memory_limit(
        "streaming_recorder_memory_does_not_grow_with_the_recording",
        128 << 20,
        || {
            std::fs::create_dir_all(&dir).unwrap();
            let path = dir.join("long.vtrace");
            let config = BoardConfig::default();
            let writer = TraceWriter::create(&path).unwrap();
            let mut rec = Recorder::streaming(Board::new(config), config, writer);
            for i in 0..8_000_000u32 {
                // color0: a plain register write, no drawing.
                rec.write32(0x144, i);
            }
            rec.log_mut().finish().unwrap();
            let mut ops = 0u64;
            for op in sst1_trace::open_trace(&path).unwrap() {
                op.unwrap();
                ops += 1;
            }
            assert_eq!(ops, 3 + 8_000_000);
            std::fs::remove_dir_all(&dir).unwrap();
        },
    );
}

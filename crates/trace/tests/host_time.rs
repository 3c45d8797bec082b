//! Host time in traces: the `wait` line (text) and record (binary), its replay on the
//! board's timing model, the recorder's host-time option, and hostile wait values.

use sst1_board::{Board, BoardConfig};
use sst1_regs::RegisterBus;
use sst1_trace::{
    decode_binary, encode_binary, parse_text, read_trace, write_text, BinaryError, ParseError,
    Recorder, Trace, TraceOp,
};

/// Replays `trace` on a fresh board and returns what each `r` op read.
fn replay_reads(trace: &Trace) -> (Board, Vec<u32>) {
    let mut board = Board::new(trace.board_config());
    let mut reads = Vec::new();
    for op in &trace.ops {
        match *op {
            TraceOp::Pci { offset, value } => board.pci_write(offset, value),
            TraceOp::Write { addr, value } => board.write32(addr, value),
            TraceOp::Read { addr, .. } => reads.push(board.read32(addr)),
            TraceOp::Wait { cycles } => board.host_wait(cycles),
            TraceOp::Config { .. } | TraceOp::Dump { .. } => {}
        }
    }
    (board, reads)
}

/// A full-screen FASTFILL (172,500 clocks: 640x480 at two pixels a clock plus 480 rows
/// of 39.375, docs/timing.md) with ten writes queued behind it in the PCI FIFO.
const FILL: &str = "\
pci 0x40 0x3
w 0x118 0x00000280  # clipLeftRight: x 0..640
w 0x11c 0x000001e0  # clipLowYHighY: y 0..480
w 0x110 0x00000200  # fbzMode: RGB writes
w 0x124 0           # fastfillCMD
";

fn fill_then(rest: &str) -> Trace {
    let mut text = FILL.to_owned();
    for _ in 0..10 {
        text.push_str("w 0x144 0\n"); // color0, queued behind the fill
    }
    text.push_str(rest);
    parse_text("fill.trace", text.as_bytes()).unwrap_or_else(|e| panic!("{e}"))
}

/// status (spec 5.1) as the fill leaves it: memory FIFO empty (bits 27:12 = 0xffff),
/// outside vertical retrace (bit 6), with this PCI FIFO free space and busy bits.
fn status(free: u32, busy: bool) -> u32 {
    0x0fff_f000 | free | 1 << 6 | if busy { 0x280 } else { 0 }
}

/// A `wait` line lets the engine drain: the status read after it sees the FIFO empty and
/// the engine idle, where without it (or with a shorter wait) the fill is still running
/// with the ten writes queued behind it.
///
/// Timeline (1/16 clock): the 15 writes take 24 each, the fill is taken at 96 and runs
/// to 96 + 2,760,000; the ten writes behind it are taken when it ends; a read takes 72.
#[test]
fn a_wait_changes_the_status_read_after_it() {
    let (_, reads) = replay_reads(&fill_then("r 0x0\n"));
    assert_eq!(reads, [status(64 - 10, true)]);
    // 172,400 clocks: the host's clock at the read is 168 + 360 + 2,758,400 = 2,758,928
    // (1/16 clock), still before the fill ends (2,760,096).
    let (_, reads) = replay_reads(&fill_then("r 0x0\nwait 172400\nr 0x0\n"));
    assert_eq!(reads, [status(54, true), status(54, true)]);
    // 172,500 clocks: past the end; the queued writes are taken and the board is idle.
    let (_, reads) = replay_reads(&fill_then("r 0x0\nwait 172500\nr 0x0\n"));
    assert_eq!(reads, [status(54, true), status(0x3f, false)]);
    assert_eq!(reads[1], 0x0fff_f07f);
    // The same reads on every run.
    let trace = fill_then("r 0x0\nwait 100000\nr 0x0\nwait 0x20000\nr 0x0\n");
    let first = replay_reads(&trace).1;
    for _ in 0..3 {
        assert_eq!(replay_reads(&trace).1, first);
    }
    assert_eq!(
        first,
        [status(54, true), status(54, true), status(0x3f, false)]
    );
}

/// The count charges a wait as feed time of the command after it (docs/timing.md): a
/// FASTFILL 100,000 clocks after the host's last write starts that much later.
#[test]
fn a_wait_is_host_time_in_the_count() {
    let text = "pci 0x40 0x3\nw 0x118 0x280\nw 0x11c 0x1e0\nw 0x110 0x200\nwait 200000\nw 0x124 0\nw 0x128 0\n";
    let (board, _) = replay_reads(&parse_text("t", text.as_bytes()).unwrap());
    let t = board.timing();
    assert_eq!(t.frames.len(), 1);
    // Four writes (6 clocks) and the wait (200,000) feed the fill (172,500 clocks of
    // engine), so it costs the feed, 200,006 clocks: 27,506 more than the engine, all
    // charged to the host's wait. The swap after it costs its write, 1.5 clocks.
    assert_eq!(t.frames[0].fills, 200_006);
    assert_eq!(t.frames[0].host_wait, 27_506);
    assert_eq!(t.frames[0].bus_bound, 0);
    assert_eq!(t.frames[0].cycles, 200_007);
}

/// Without `wait` lines nothing changes: a trace replays exactly as it did before the
/// line existed (the status reads of the fill above, and the count).
#[test]
fn traces_without_waits_replay_as_before() {
    let (board, reads) = replay_reads(&fill_then("r 0x0\nr 0x0\n"));
    assert_eq!(reads, [status(54, true), status(54, true)]);
    assert_eq!(board.timing().cycles(), 172_500);
    assert_eq!(board.timing().total.host_wait, 0);
}

/// Text and binary hold the same waits, and convert both ways without loss; a binary
/// trace with waits is version 2 (a version-1 reader refuses it), one without is
/// version 1 byte for byte as before.
#[test]
fn waits_round_trip_text_and_binary() {
    let text = "config tmus 2\nwait 0\nw 0x000000 0x00000001\nwait 123456789\nr 0x000000\nwait 18446744073709551615\nwait 0x10\n";
    let trace = parse_text("t.trace", text.as_bytes()).unwrap();
    let waits: Vec<u64> = trace
        .ops
        .iter()
        .filter_map(|op| match *op {
            TraceOp::Wait { cycles } => Some(cycles),
            _ => None,
        })
        .collect();
    assert_eq!(waits, [0, 123_456_789, u64::MAX, 16]);
    let rewritten = write_text(&trace);
    assert!(rewritten.contains("\nwait 18446744073709551615\nwait 16\n"));
    assert_eq!(parse_text("again", rewritten.as_bytes()).unwrap(), trace);
    let binary = encode_binary(&trace);
    assert_eq!(
        &binary[8..12],
        &[2, 0, 2, 0],
        "version 2, min_reader_version 2"
    );
    assert_eq!(decode_binary(&binary).unwrap(), trace);
    assert_eq!(read_trace("b", &binary).unwrap(), trace);
    // The wait record: tag 0x08, then the cycles as a little-endian u64.
    let record = [&[0x08u8][..], &123_456_789u64.to_le_bytes()].concat();
    assert!(binary.windows(9).any(|w| w == record.as_slice()));
    // Without waits: version 1, as every earlier writer wrote it.
    let plain = Trace {
        ops: trace
            .ops
            .iter()
            .filter(|op| !matches!(op, TraceOp::Wait { .. }))
            .cloned()
            .collect(),
    };
    assert_eq!(&encode_binary(&plain)[8..12], &[1, 0, 1, 0]);
    // A wait record cut short is an error at its offset.
    let cut = &binary[..binary.len() - 3];
    let err = decode_binary(cut).unwrap_err();
    assert!(matches!(err, BinaryError::Truncated { .. }), "{err}");
}

/// Malformed wait lines stop the parse with the file, the line and what was expected.
#[test]
fn malformed_wait_lines_name_file_and_line() {
    let expected = "a wait in graphics-clock cycles (0x hex or decimal, below 2^64)";
    for (line, found) in [
        ("wait", "end of line".to_owned()),
        ("wait -1", "`-1`".to_owned()),
        ("wait +5", "`+5`".to_owned()),
        ("wait 0x", "`0x`".to_owned()),
        ("wait 1.5", "`1.5`".to_owned()),
        (
            "wait 18446744073709551616",
            "`18446744073709551616`".to_owned(),
        ),
        (
            "wait 0x10000000000000000",
            "`0x10000000000000000`".to_owned(),
        ),
    ] {
        let text = format!("w 0x0 0x1\n{line}  # host time\n");
        let err = parse_text("t.trace", text.as_bytes()).unwrap_err();
        assert_eq!(
            err,
            ParseError::Expected {
                file: "t.trace".to_owned(),
                line: 2,
                expected,
                found,
            },
            "{line}"
        );
        assert_eq!(
            err.to_string(),
            format!(
                "t.trace:2: expected {expected}, found {}",
                match &err {
                    ParseError::Expected { found, .. } => found.clone(),
                    _ => unreachable!(),
                }
            )
        );
    }
    let err = parse_text("t.trace", b"wait 5 6\n").unwrap_err();
    assert_eq!(
        err.to_string(),
        "t.trace:1: expected end of line, found `6`"
    );
    let err = parse_text("t.trace", b"idle 5\n").unwrap_err();
    assert_eq!(
        err.to_string(),
        "t.trace:1: unknown command `idle`; expected config, pci, w, r, wait or dump"
    );
}

/// A huge wait neither hangs nor overflows: the host's clock saturates, the board is
/// idle after it and goes on working; a million of the largest waits replay at once.
#[test]
fn huge_waits_saturate() {
    let mut text = fill_then("wait 18446744073709551615\nr 0x0\n")
        .ops
        .iter()
        .map(sst1_trace::text::format_op)
        .collect::<Vec<_>>()
        .join("\n");
    text.push('\n');
    for _ in 0..1_000_000 {
        text.push_str("wait 0xffffffffffffffff\n");
    }
    // Another fill after the waits: busy again, then idle after a long wait.
    text.push_str("w 0x124 0\nr 0x0\nwait 1000000\nr 0x0\nw 0x128 1\n");
    let trace = parse_text("huge.trace", text.as_bytes()).unwrap();
    let (board, reads) = replay_reads(&trace);
    assert_eq!(reads[0] & 0x3bf, 0x3f, "idle, FIFO empty");
    assert_eq!(reads[1] & 0x280, 0x280, "the fill after the waits runs");
    assert_eq!(reads[2] & 0x3bf, 0x3f);
    let t = board.timing();
    assert_eq!(t.frames.len(), 1);
    assert!(t.cycles() >= 1 << 58, "{}", t.cycles());
    assert!(t.cycles() < u64::MAX);
}

/// The recorder logs a driver's own waits (`RegisterBus::host_wait`, deterministic) and
/// passes them to the board, so the recorded reads are what a replay reads.
#[test]
fn recorder_logs_and_forwards_waits() {
    let config = BoardConfig::default();
    let mut rec = Recorder::new(Board::new(config), config);
    for op in &fill_then("").ops {
        match *op {
            TraceOp::Pci { offset, value } => rec.pci_write(offset, value),
            TraceOp::Write { addr, value } => rec.write32(addr, value),
            _ => {}
        }
    }
    let busy = rec.read32(0);
    rec.host_wait(0); // logs nothing
    rec.host_wait(172_500);
    let idle = rec.read32(0);
    assert_eq!((busy, idle), (status(54, true), status(0x3f, false)));
    let (_, trace) = rec.finish();
    let waits: Vec<&TraceOp> = trace
        .ops
        .iter()
        .filter(|op| matches!(op, TraceOp::Wait { .. }))
        .collect();
    assert_eq!(waits, [&TraceOp::Wait { cycles: 172_500 }]);
    let recorded: Vec<u32> = trace
        .ops
        .iter()
        .filter_map(|op| match *op {
            TraceOp::Read { value, .. } => value,
            _ => None,
        })
        .collect();
    assert_eq!(replay_reads(&trace).1, recorded);
}

/// With the host clock on, the recorder logs the time spent between accesses (here at
/// least the millisecond slept: 50,000 clocks at 50 MHz) and passes it to the board, so
/// the replay reads what the recording read, whatever the host's speed was.
#[test]
fn recorder_measures_host_time_when_asked() {
    let config = BoardConfig::default();
    let mut rec = Recorder::new(Board::new(config), config);
    rec.record_host_time(50);
    for op in &fill_then("").ops {
        match *op {
            TraceOp::Pci { offset, value } => rec.pci_write(offset, value),
            TraceOp::Write { addr, value } => rec.write32(addr, value),
            _ => {}
        }
    }
    rec.read32(0);
    std::thread::sleep(std::time::Duration::from_millis(1));
    rec.read32(0);
    let (_, trace) = rec.finish();
    let mut waited = 0u64;
    for op in &trace.ops {
        if let TraceOp::Wait { cycles } = *op {
            assert!(cycles >= 50, "short waits carry over: {cycles}");
            waited += cycles;
        }
    }
    assert!(waited >= 50_000, "{waited}");
    let recorded: Vec<u32> = trace
        .ops
        .iter()
        .filter_map(|op| match *op {
            TraceOp::Read { value, .. } => value,
            _ => None,
        })
        .collect();
    assert_eq!(replay_reads(&trace).1, recorded);
}

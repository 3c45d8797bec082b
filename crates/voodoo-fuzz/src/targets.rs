//! The fuzz targets, all in one list: [`TARGETS`]. To add one, write a `fn(&[u8])` that
//! panics when an invariant breaks (and only then: hostile input must be handled, not
//! panicked on), a seed function, and an entry below.

use sst1_board::{Board, BufferKind};
use sst1_regs::RegisterBus;
use sst1_trace::{
    decode_binary, encode_binary, execute, execute_references_stream, execute_stream, parse_text,
    read_trace, stream_trace, write_text, BinaryReader, Dump, DumpBuffer, Recorder, Trace, TraceOp,
    TraceReader,
};

use crate::corpus::{self, Repository};
use crate::mutate::ByteSource;

/// One fuzz target.
pub struct Target {
    /// Its name (for `VOODOO_FUZZ_TARGETS` and failure files).
    pub name: &'static str,
    /// What it exercises, in a line.
    pub about: &'static str,
    /// Its seed inputs, built once per run.
    pub seeds: fn(&Repository) -> Vec<Vec<u8>>,
    /// Runs one input; panics if an invariant breaks.
    pub run: fn(&[u8]),
    /// Its share of a run's cases, relative to the other targets' (costly targets run
    /// fewer cases).
    pub weight: u32,
}

/// Every target.
pub const TARGETS: &[Target] = &[
    Target {
        name: "text",
        about: "the text parser: never panics, short errors, round trips through both forms",
        seeds: corpus::text_seeds,
        run: text,
        weight: 8,
    },
    Target {
        name: "binary",
        about: "the binary decoder: whole and streaming agree, round trips, short errors",
        seeds: corpus::binary_seeds,
        run: binary,
        weight: 8,
    },
    Target {
        name: "read",
        about: "form detection, gzip and streaming (TraceReader, stream_trace) against whole reads",
        seeds: corpus::any_form_seeds,
        run: read,
        weight: 6,
    },
    Target {
        name: "replay",
        about: "streamed replay on two render threads equals replay from memory on one; the vote never panics",
        seeds: corpus::any_form_seeds,
        run: replay,
        weight: 2,
    },
    Target {
        name: "glide",
        about: "a program of calls to every C entry point of libglide3 with hostile values: no internal error, crash or hang",
        seeds: crate::glide::seeds,
        run: crate::glide::run,
        weight: 1,
    },
    Target {
        name: "recorder",
        about:
            "bus accesses of any address through Recorder<Board> read back and replay identically",
        seeds: recorder_seeds,
        run: recorder,
        weight: 2,
    },
    Target {
        name: "state",
        about: "save states (Board::from_state): a damaged one is refused or loads and runs; a loaded one saves and reloads to the same bytes",
        seeds: state_seeds,
        run: state,
        weight: 1,
    },
];

/// The longest error message any input may cause (item 16: quotes are cut short).
const MAX_MESSAGE: usize = 400;

fn assert_short(message: &str) {
    assert!(
        message.len() <= MAX_MESSAGE,
        "error message of {} bytes: {:.200}",
        message.len(),
        message
    );
}

/// A parsed trace survives both round trips unchanged.
fn assert_round_trips(trace: &Trace) {
    let text = write_text(trace);
    match parse_text("rewritten", text.as_bytes()) {
        Ok(back) => assert!(&back == trace, "text round trip changed the trace"),
        Err(e) => panic!("written text does not parse: {e}"),
    }
    let encoded = encode_binary(trace);
    match decode_binary(&encoded) {
        Ok(back) => {
            assert!(&back == trace, "binary round trip changed the trace");
            assert!(
                encode_binary(&back) == encoded,
                "binary re-encoding differs"
            );
        }
        Err(e) => panic!("encoded binary does not decode: {e}"),
    }
}

fn text(input: &[u8]) {
    match parse_text("fuzz", input) {
        Ok(trace) => assert_round_trips(&trace),
        Err(e) => assert_short(&e.to_string()),
    }
}

fn binary(input: &[u8]) {
    let whole = decode_binary(input);
    let streamed: Result<Vec<TraceOp>, _> =
        BinaryReader::new(input).and_then(|reader| reader.collect());
    match (&whole, &streamed) {
        (Ok(trace), Ok(ops)) => {
            assert!(&trace.ops == ops, "streaming decode differs");
            assert_round_trips(trace);
        }
        (Err(a), Err(b)) => {
            assert!(a == b, "errors differ: {a} / {b}");
            assert_short(&a.to_string());
        }
        _ => panic!("whole and streaming decodes disagree on success"),
    }
}

/// The outcome of a read, comparable across readers: the ops, or the error's message.
fn outcome<E: std::fmt::Display>(result: Result<Vec<TraceOp>, E>) -> Result<Vec<TraceOp>, String> {
    result.map_err(|e| e.to_string())
}

fn read(input: &[u8]) {
    let whole = outcome(read_trace("fuzz", input).map(|t| t.ops));
    let streamed = outcome(TraceReader::new("fuzz", input).and_then(|r| r.collect()));
    assert!(whole == streamed, "whole and streaming reads differ");
    if let Err(e) = &whole {
        assert_short(e);
    }
    match stream_trace("fuzz", input) {
        Ok(stream) => {
            let config = stream.config();
            let ops = outcome(stream.collect::<Result<Vec<TraceOp>, _>>());
            assert!(ops == whole, "stream_trace differs from a whole read");
            if let Ok(ops) = &whole {
                let expected = Trace { ops: ops.clone() }.board_config();
                assert!(config == expected, "stream_trace found another board");
            }
        }
        Err(e) => {
            // Only an error before any op, or a long prefix, stops a stream early.
            let message = e.to_string();
            assert_short(&message);
            assert!(whole.is_err() || message.contains("before the first write"));
        }
    }
}

/// Most ops a replay case runs (a mutated triangle can be large).
const REPLAY_OPS: usize = 2000;

fn replay(input: &[u8]) {
    let Ok(trace) = read_trace("fuzz", input) else {
        return;
    };
    if trace.ops.len() > REPLAY_OPS {
        return;
    }
    let config = trace.board_config();
    let mut whole = Board::new(config);
    let dumps = execute(&trace.ops, &mut whole, |_| {});
    let Ok(stream) = stream_trace("fuzz", input) else {
        panic!("a trace that reads whole does not stream");
    };
    // The streamed replay on two render threads: its small triangles go to a render
    // thread behind the writes (`sst1_board::Deferred`), with the TMUs' writes after
    // them, and must give what one thread gives.
    let mut streamed = Board::new(stream.config());
    streamed.set_threads(2);
    let mut streamed_dumps: Vec<Dump> = Vec::new();
    let result = execute_stream(
        stream,
        &mut streamed,
        |_| {},
        |d| {
            streamed_dumps.push(d);
            Ok(())
        },
    );
    assert!(result.is_ok(), "streamed replay failed");
    assert!(
        dumps == streamed_dumps,
        "streamed dumps differ (two threads)"
    );
    assert!(
        whole.stats() == streamed.stats(),
        "streamed counters differ"
    );
    assert!(
        whole.dump_buffer(BufferKind::Front) == streamed.dump_buffer(BufferKind::Front),
        "streamed front buffer differs"
    );
    // The vote (three boards on three threads) for one case in eight: it must finish and
    // yield a voted dump per dump op.
    if input.len().is_multiple_of(8) {
        let mut voted = 0;
        let ops = trace.ops.iter().cloned().map(Ok);
        let result = execute_references_stream(
            ops,
            config,
            |_| {},
            |_| {
                voted += 1;
                Ok(())
            },
        );
        assert!(result.is_ok(), "vote failed");
        assert_eq!(voted, dumps.len(), "vote lost dumps");
    }
}

/// Bus accesses a recorder case makes at most.
const RECORDER_OPS: usize = 400;

/// Drives a recorded board from `input`: each access is a kind byte and its fields.
fn recorder(input: &[u8]) {
    let mut source = ByteSource::new(input);
    let config = match source.below(3) {
        0 => sst1_board::BoardConfig::default(),
        1 => sst1_board::BoardConfig {
            fbi_mb: 2,
            tmus: 2,
            tmu_mb: 1,
        },
        _ => sst1_board::BoardConfig {
            fbi_mb: 4,
            tmus: 3,
            tmu_mb: 2,
        },
    };
    let mut rec = Recorder::new(Board::new(config), config);
    let mut live_dumps = Vec::new();
    for _ in 0..RECORDER_OPS {
        if source.is_empty() {
            break;
        }
        match source.below(8) {
            0..=3 => {
                let addr = source.u32();
                rec.write32(addr, source.u32());
            }
            4 | 5 => {
                rec.read32(source.u32());
            }
            6 => {
                let offset = source.u32();
                rec.pci_write(offset, source.u32());
            }
            _ => {
                let buffer = DumpBuffer::ALL[usize::from(source.below(4))];
                rec.dump(buffer, "d.raw");
                live_dumps.push(rec.inner().dump_buffer(buffer.kind()));
            }
        }
    }
    let (live, trace) = rec.finish();
    let text = write_text(&trace);
    let from_text = match parse_text("recorded", text.as_bytes()) {
        Ok(t) => t,
        Err(e) => panic!("a recorded trace does not read back: {e}"),
    };
    assert!(from_text == trace, "recorded text reads back changed");
    assert_round_trips(&trace);
    let mut board = Board::new(from_text.board_config());
    let dumps = execute(&from_text.ops, &mut board, |_| {});
    let replayed: Vec<&Vec<u16>> = dumps.iter().map(|d| &d.data).collect();
    assert!(
        replayed == live_dumps.iter().collect::<Vec<_>>(),
        "replayed dumps differ"
    );
    assert!(board.stats() == live.stats(), "replayed counters differ");
    assert!(
        board.diagnostics() == live.diagnostics(),
        "replayed diagnostics differ"
    );
    for kind in [BufferKind::Front, BufferKind::Back, BufferKind::Aux] {
        assert!(
            board.dump_buffer(kind) == live.dump_buffer(kind),
            "replayed {kind:?} buffer differs"
        );
    }
}

/// Recorder inputs from the repository's pieces: each op as the recorder target reads
/// it (a kind byte, then its fields).
fn recorder_seeds(repo: &Repository) -> Vec<Vec<u8>> {
    repo.pieces()
        .iter()
        .map(|piece| {
            let mut bytes = vec![0u8];
            for op in &piece.ops {
                match *op {
                    TraceOp::Write { addr, value } => {
                        bytes.push(0);
                        bytes.extend_from_slice(&addr.to_le_bytes());
                        bytes.extend_from_slice(&value.to_le_bytes());
                    }
                    TraceOp::Read { addr, .. } => {
                        bytes.push(4);
                        bytes.extend_from_slice(&addr.to_le_bytes());
                    }
                    TraceOp::Pci { offset, value } => {
                        bytes.push(6);
                        bytes.extend_from_slice(&offset.to_le_bytes());
                        bytes.extend_from_slice(&value.to_le_bytes());
                    }
                    TraceOp::Dump { .. } => bytes.push(7),
                    TraceOp::Config { .. } | TraceOp::Wait { .. } => {}
                }
            }
            bytes
        })
        .collect()
}

/// A save state: refused with an error, or a board that saves to bytes that load back
/// to the same bytes and that takes accesses afterwards.
fn state(input: &[u8]) {
    let Ok((mut board, _)) = Board::from_state(input) else {
        return;
    };
    let saved = board.save_state();
    let again = match Board::from_state(&saved) {
        Ok((b, _)) => b.save_state(),
        Err(e) => panic!("a loaded state saves bytes that do not load: {e}"),
    };
    assert!(again == saved, "a state reloaded saves other bytes");
    for (addr, value) in [(0x124, 0), (0x080, 0), (0x400000, 0x1234_5678), (0x128, 1)] {
        board.write32(addr, value);
    }
    board.read32(0);
}

/// States of a small board (2 MiB, one 1 MiB TMU, so that a case copies little): fresh,
/// and after the start of each textured repository trace on the hardware and the 86Box
/// model (whose texture cache the state holds).
fn state_seeds(repo: &Repository) -> Vec<Vec<u8>> {
    let config = sst1_board::BoardConfig {
        fbi_mb: 2,
        tmus: 1,
        tmu_mb: 1,
    };
    let mut seeds = vec![Board::new(config).save_state()];
    let textured = repo.traces().iter().filter(|(_, t)| {
        t.ops
            .iter()
            .any(|op| matches!(op, TraceOp::Write { addr, .. } if *addr >= 0x80_0000))
    });
    for (_, trace) in textured.take(2) {
        for model in [
            sst1_board::Model::Hardware,
            sst1_board::Model::Reference(sst1_board::Reference::Box86),
        ] {
            let mut board = Board::new(config);
            board.set_model(model);
            execute(&trace.ops[..trace.ops.len().min(4000)], &mut board, |_| {});
            seeds.push(board.save_state_after(4000));
        }
    }
    seeds
}

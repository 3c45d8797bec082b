//! `execute_trace_stream`, which hands a binary trace's writes from the reader's buffer
//! to the board, replays a trace exactly as `execute_stream` over the same stream's ops:
//! the same board state (save-state bytes, the timing model's included), the same
//! dumps, the same progress calls and the same error, whether it runs a trace whole or
//! in pieces (`--save-at`), from the binary form or the text form.

use sst1_board::Board;
use sst1_trace::scenes::{random_states, small_triangles, RandomStates};
use sst1_trace::{
    encode_binary, execute_stream, execute_trace_stream, parse_text, stream_trace, Dump,
    PROGRESS_STEP,
};

/// What a replay leaves: the board's state, the dumps, the progress calls, the ops run
/// by each piece, and the error if one ended it.
type Outcome = (Vec<u8>, Vec<Dump>, Vec<usize>, Vec<usize>, Option<String>);

/// Replays `bytes` in pieces of `pieces` ops (then the rest) with `execute_trace_stream`
/// (`fast`) or `execute_stream` over `take`.
fn replay(bytes: &[u8], pieces: &[usize], fast: bool) -> Outcome {
    let mut stream = stream_trace("t", bytes).unwrap();
    let mut board = Board::new(stream.config());
    let (mut dumps, mut calls, mut done) = (Vec::new(), Vec::new(), Vec::new());
    let mut error = None;
    let limits = pieces.iter().map(|&k| Some(k)).chain([None]);
    for limit in limits {
        let result = {
            let progress = |n: usize| calls.push(n);
            let sink = |d: Dump| {
                dumps.push(d);
                Ok(())
            };
            if fast {
                execute_trace_stream(&mut stream, limit, &mut board, progress, sink)
            } else {
                let ops = stream.by_ref().take(limit.unwrap_or(usize::MAX));
                execute_stream(ops, &mut board, progress, sink)
            }
        };
        match result {
            Ok(n) => done.push(n),
            Err(e) => {
                error = Some(e.to_string());
                break;
            }
        }
    }
    (board.save_state(), dumps, calls, done, error)
}

fn scenes() -> Vec<(String, Vec<u8>)> {
    let tris = small_triangles(7, 6000, true);
    let states = random_states(RandomStates {
        seed: 5,
        states: 40,
        dump_every: 10,
        ..RandomStates::default()
    });
    let mut out = Vec::new();
    for (name, text) in [("small_triangles", tris), ("random_states", states)] {
        let trace = parse_text(name, text.as_bytes()).unwrap();
        out.push((format!("{name}.vtrace"), encode_binary(&trace)));
        out.push((format!("{name}.trace"), text.into_bytes()));
    }
    out
}

#[test]
fn trace_streams_replay_as_their_ops_whole_and_in_pieces() {
    let step = PROGRESS_STEP;
    let piecings: [&[usize]; 5] = [
        &[],
        &[0, 1, 17],
        &[step - 1, 1, step],
        &[step, step + 1],
        &[5000, 0, 123_456],
    ];
    for (name, bytes) in scenes() {
        for pieces in piecings {
            let fast = replay(&bytes, pieces, true);
            let reference = replay(&bytes, pieces, false);
            assert!(fast.4.is_none(), "{name}: {:?}", fast.4);
            assert!(!fast.1.is_empty(), "{name}: the scene dumps");
            if pieces.is_empty() && name.starts_with("small") {
                assert!(fast.2.contains(&step), "{name}: progress was reported");
            }
            assert!(fast == reference, "{name}, pieces {pieces:?}");
        }
    }
}

#[test]
fn a_trace_stream_stops_at_the_same_bad_record() {
    // The last record cut short, and a record of an unknown tag after the last.
    let (_, bytes) = scenes().remove(0);
    let cut = bytes[..bytes.len() - 3].to_vec();
    let mut unknown = bytes.clone();
    unknown.extend([0xee, 1, 2, 3]);
    for broken in [cut, unknown] {
        let fast = replay(&broken, &[1000], true);
        let reference = replay(&broken, &[1000], false);
        assert!(fast.4.is_some(), "the trace is bad");
        assert!(fast == reference);
    }
}

#[test]
fn a_run_of_writes_stops_at_a_bad_address_and_after_a_swap() {
    // A write of a misaligned address in the middle of a run of writes (the replay
    // takes runs of whole write records from the buffer at once), and swaps inside runs
    // (each ends a frame): the same ops, dumps and error as op by op.
    use sst1_trace::TraceOp;
    let text = small_triangles(3, 3000, true);
    let mut trace = parse_text("t", text.as_bytes()).unwrap();
    let writes: Vec<usize> = (0..trace.ops.len())
        .filter(|&i| matches!(trace.ops[i], TraceOp::Write { .. }))
        .collect();
    // Swaps among plain writes, away from any other op.
    for k in [writes.len() / 5, writes.len() / 3] {
        trace.ops[writes[k]] = TraceOp::Write {
            addr: 0x128,
            value: 0,
        };
    }
    let swapped = encode_binary(&trace);
    let fast = replay(&swapped, &[], true);
    assert!(fast.4.is_none(), "{:?}", fast.4);
    assert!(fast == replay(&swapped, &[], false));
    trace.ops[writes[writes.len() / 2]] = TraceOp::Write {
        addr: 0x102,
        value: 7,
    };
    let bad = encode_binary(&trace);
    let fast = replay(&bad, &[], true);
    assert!(fast.4.is_some(), "the address is refused");
    assert!(fast == replay(&bad, &[], false));
}

#[test]
fn a_swap_without_its_frame_record_stops_a_run_of_writes() {
    // A hostile binary trace: the frame record after a swap taken out, so that the swap
    // is followed by more writes. A run of writes taken from the buffer must end at the
    // swap, as op by op, and both refuse the write after it. (Record layout: the
    // `binary` module's docs: a write is 0x03, addr u32, value u32; a frame is 0x07,
    // number u32.)
    let text = small_triangles(4, 2000, true);
    let mut trace = parse_text("t", text.as_bytes()).unwrap();
    let middle = trace.ops.len() / 2;
    trace.ops.insert(
        middle,
        sst1_trace::TraceOp::Write {
            addr: 0x128,
            value: 0,
        },
    );
    let bytes = encode_binary(&trace);
    // The swap, its frame record, and a write after it.
    let swap = [0x03, 0x28, 0x01, 0, 0, 0, 0, 0, 0, 0x07];
    let at = bytes
        .windows(swap.len())
        .position(|w| w == swap)
        .expect("the swap and its frame record");
    let frame = at + 9;
    assert_eq!(bytes[frame + 5], 0x03, "a write follows the frame record");
    let mut hostile = bytes[..frame].to_vec();
    hostile.extend_from_slice(&bytes[frame + 5..]);
    let fast = replay(&hostile, &[], true);
    assert!(fast.4.is_some(), "the write after the swap is refused");
    assert!(fast == replay(&hostile, &[], false));
}

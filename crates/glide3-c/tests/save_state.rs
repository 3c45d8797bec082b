//! Save states from libglide3: `VOODOO_SAVE_STATE` (at `grGlideShutdown`, or after the
//! swap `VOODOO_SAVE_STATE_SWAP` names) and `VOODOO_LOAD_STATE` (at `grSstWinOpen`),
//! with `tests/frames.c`, three textured, fogged frames from one texture download.
//!
//! * A state saved after swap 1 while recording (`VOODOO_TRACE`) says how many trace
//!   ops had been written; the trace's remaining ops replayed on the restored board give
//!   the dumps and buffers of the whole trace replayed from the start.
//! * A state saved at shutdown is the board the whole trace leaves.
//! * A program that loads a state goes on from it (its counters add to the state's); a
//!   state of another board is refused on stderr and the run goes on from a fresh board.

use sst1_board::{Board, BufferKind};
use sst1_trace::{execute, load_trace, TraceOp};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    exe.parent().expect("target deps dir").to_path_buf()
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn build(out: &Path) -> PathBuf {
    let exe = out.join("frames");
    let status = Command::new("cc")
        .args(["-std=gnu17", "-Wall", "-Wextra", "-Werror"])
        .arg("-I")
        .arg(repo().join("crates/glide3-c/include"))
        .arg(repo().join("crates/glide3-c/tests/frames.c"))
        .arg("-L")
        .arg(lib_dir())
        .args(["-lglide3", "-lm", "-lpthread", "-o"])
        .arg(&exe)
        .status()
        .expect("run cc");
    assert!(status.success(), "compiling frames.c failed");
    exe
}

fn run(exe: &Path, env: &[(&str, &Path)]) -> Output {
    let mut command = Command::new(exe);
    command.env("LD_LIBRARY_PATH", lib_dir());
    for (k, v) in env {
        command.env(k, v);
    }
    let out = command.output().expect("run frames");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn state(path: &Path) -> Board {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    Board::from_state(&bytes)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .0
}

#[test]
fn glide_programs_save_and_load_states() {
    let dir = std::env::temp_dir().join(format!("glide3-c-state-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let exe = build(&dir);
    let p = |name: &str| dir.join(name);

    // Recorded, with a state after the first swap; and a run saving at shutdown.
    run(
        &exe,
        &[
            ("VOODOO_TRACE", &p("frames.trace")),
            ("VOODOO_SAVE_STATE", &p("swap1.state")),
            ("VOODOO_SAVE_STATE_SWAP", Path::new("1")),
        ],
    );
    run(
        &exe,
        &[
            ("VOODOO_TRACE", &p("end.trace")),
            ("VOODOO_SAVE_STATE", &p("end.state")),
        ],
    );

    let trace = load_trace(&p("frames.trace")).unwrap();
    let mut whole = Board::new(trace.board_config());
    let dumps = execute(&trace.ops, &mut whole, |_| {});
    assert_eq!(dumps.len(), 3, "a dump after each swap");

    // Resumed after swap 1: the ops written so far are done, the dump of swap 1 last.
    let bytes = std::fs::read(p("swap1.state")).unwrap();
    let (mut resumed, info) = Board::from_state(&bytes).unwrap();
    let done = info
        .ops_done
        .expect("the state says how many ops were written") as usize;
    assert!(
        matches!(&trace.ops[done - 1], TraceOp::Dump { file, .. } if file == "frames_swap1_front.raw"),
        "{:?}",
        trace.ops[done - 1]
    );
    assert_eq!(resumed.dump_buffer(BufferKind::Front), dumps[0].data);
    let rest = execute(&trace.ops[done..], &mut resumed, |_| {});
    assert_eq!(rest, dumps[1..]);
    for kind in [BufferKind::Front, BufferKind::Back, BufferKind::Aux] {
        assert_eq!(
            resumed.dump_buffer(kind),
            whole.dump_buffer(kind),
            "{kind:?}"
        );
    }
    assert_eq!(resumed.stats(), whole.stats());
    assert_eq!(resumed.timing().cycles(), whole.timing().cycles());

    // At shutdown: the board as the program left it, before grGlideShutdown's close
    // sequence (the 27 writes of grSstWinClose, which the trace records after it).
    let bytes = std::fs::read(p("end.state")).unwrap();
    let (end, info) = Board::from_state(&bytes).unwrap();
    let end_trace = load_trace(&p("end.trace")).unwrap();
    let before_close = info.ops_done.expect("recorded: an op count") as usize;
    assert_eq!(end_trace.ops.len() - before_close, 27, "the close sequence");
    assert_eq!(
        end_trace.ops.last(),
        Some(&TraceOp::Write {
            addr: 0x120,
            value: 0
        })
    );
    let mut open = Board::new(end_trace.board_config());
    execute(&end_trace.ops[..before_close], &mut open, |_| {});
    assert!(
        end.save_state() == open.save_state(),
        "the state at shutdown"
    );

    // Loaded at grSstWinOpen: the program's frames come on top of the state's.
    run(
        &exe,
        &[
            ("VOODOO_LOAD_STATE", &p("end.state")),
            ("VOODOO_SAVE_STATE", &p("twice.state")),
        ],
    );
    let twice = state(&p("twice.state"));
    let (one, two) = (end.stats(), twice.stats());
    // Swaps and pixels double; of the triangle commands, the state's and the three
    // the frames draw after grSstWinOpen (those Glide's initialisation sends before the
    // load are replaced by the state's).
    assert_eq!(
        (two.swaps, two.triangles, two.pixels_out),
        (2 * one.swaps, one.triangles + 3, 2 * one.pixels_out)
    );
    assert_eq!(
        twice.dump_buffer(BufferKind::Front),
        end.dump_buffer(BufferKind::Front)
    );

    // A state of another board: said on stderr, not loaded.
    let out = run(
        &exe,
        &[
            ("VOODOO_TMUS", Path::new("2")),
            ("VOODOO_LOAD_STATE", &p("end.state")),
            ("VOODOO_SAVE_STATE", &p("fresh.state")),
        ],
    );
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!(
            "glide3: VOODOO_LOAD_STATE={}: save state is of a board with 4 MiB of frame \
             buffer and 1 TMU(s) of 4 MiB, this board has 4 MiB of frame buffer and 2 TMU(s) \
             of 4 MiB; not loaded\n",
            p("end.state").display()
        )
    );
    run(
        &exe,
        &[
            ("VOODOO_TMUS", Path::new("2")),
            ("VOODOO_SAVE_STATE", &p("plain.state")),
        ],
    );
    assert!(
        state(&p("fresh.state")).save_state() == state(&p("plain.state")).save_state(),
        "the refused state changed the run"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

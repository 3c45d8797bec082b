//! Save states restore the board bit for bit: every conformance, glide-sdk, example and
//! generated trace is cut at three points (a third of the way in, right after a triangle
//! command in the middle of the trace, so inside a frame, and right after the middle
//! texture download), the board saved there and restored into a fresh board that replays
//! the rest; every dump, the final front, back and aux buffers, the counters, the
//! modelled time frame by frame, the diagnostics and a final `status` and `vRetrace` read
//! must equal those of the run that was never interrupted. A restored board saves the
//! same bytes it was restored from, and a state does not depend on how many render
//! threads shaded the frames before it.
//!
//! The uninterrupted run saves at each cut as it passes it, so a trace costs about three
//! replays. The benchmark traces (`perf_tex_heavy`, `perf_gouraud_heavy`) are cut short
//! to their first [`PERF_OPS`] ops. The 86Box model's texture cache is state (module
//! `texelfx::state`): the textured traces run again on that model, and the generated
//! ones on every reference model.

use std::path::{Path, PathBuf};

use sst1_board::state::{read_info, StateError, FORMAT_VERSION, MAGIC};
use sst1_board::{Board, BoardConfig, BufferKind, Method, Model, Reference, VectorIsa};
use sst1_regs::{addr, RegisterBus};
use sst1_trace::{execute, load_trace, Dump, TraceOp};

/// Ops of a benchmark trace the test replays.
const PERF_OPS: usize = 20_000;

/// What a replay leaves that a later access could see.
#[derive(Debug, PartialEq)]
struct Outcome {
    dumps: Vec<Dump>,
    finals: Vec<Vec<u16>>,
    stats: sst1_board::Stats,
    cycles: u64,
    frames: Vec<sst1_board::FrameTime>,
    total: sst1_board::FrameTime,
    diagnostics: Vec<(sst1_board::Diagnostic, u64)>,
    status: u32,
    v_retrace: u32,
}

fn finish(mut board: Board, dumps: Vec<Dump>) -> Outcome {
    let finals = [BufferKind::Front, BufferKind::Back, BufferKind::Aux]
        .map(|k| board.dump_buffer(k))
        .to_vec();
    let t = board.timing().clone();
    let diagnostics = board.diagnostics().iter().collect();
    let status = board.read32(addr::STATUS);
    let v_retrace = board.read32(addr::V_RETRACE);
    Outcome {
        dumps,
        finals,
        stats: board.stats(),
        cycles: t.cycles(),
        frames: t.frames,
        total: t.total,
        diagnostics,
        status,
        v_retrace,
    }
}

/// Whether `op` is a triangle command (`triangleCMD` or `ftriangleCMD`, any chip mask).
fn is_triangle(op: &TraceOp) -> bool {
    matches!(op, TraceOp::Write { addr: a, .. }
        if *a < 0x40_0000 && matches!(a & 0x3fc, addr::TRIANGLE_CMD | addr::F_TRIANGLE_CMD))
}

fn is_texture_write(op: &TraceOp) -> bool {
    matches!(op, TraceOp::Write { addr, .. } if *addr >= 0x80_0000)
}

/// The cut points of `ops`: after this many ops, sorted, without repeats (`all` false:
/// only the one after the middle texture download).
fn cuts(ops: &[TraceOp], all: bool) -> Vec<usize> {
    let middle = |pick: fn(&TraceOp) -> bool| {
        let at: Vec<usize> = (0..ops.len()).filter(|&i| pick(&ops[i])).collect();
        at.get(at.len() / 2).map(|&i| i + 1)
    };
    let mut cuts = Vec::new();
    if all {
        cuts.push(ops.len() / 3);
        cuts.extend(middle(is_triangle));
    }
    cuts.extend(middle(is_texture_write));
    cuts.sort_unstable();
    cuts.dedup();
    cuts
}

/// Replays `ops` on a board of `config` running `model`, uninterrupted and resumed from a
/// state saved at each cut; returns the differences in words.
fn check(
    name: &str,
    config: BoardConfig,
    model: Model,
    ops: &[TraceOp],
    all_cuts: bool,
) -> Vec<String> {
    let new_board = || {
        let mut b = Board::new(config);
        b.set_model(model);
        b
    };
    let mut board = new_board();
    let mut dumps = Vec::new();
    let mut saved = Vec::new();
    let mut done = 0;
    for &cut in &cuts(ops, all_cuts) {
        dumps.extend(execute(&ops[done..cut], &mut board, |_| {}));
        done = cut;
        saved.push((cut, dumps.clone(), board.save_state_after(cut as u64)));
    }
    dumps.extend(execute(&ops[done..], &mut board, |_| {}));
    let whole = finish(board, dumps);
    let mut problems = Vec::new();
    for (cut, mut dumps, state) in saved {
        let what = format!("{name} ({model:?}) resumed after op {cut}");
        let info = read_info(&state).expect("header");
        assert_eq!(info.ops_done, Some(cut as u64));
        assert_eq!((info.config, info.model), (config, model));
        // Restored both ways: into a fresh board, and over a board that has run.
        let (mut resumed, _) = Board::from_state(&state).unwrap_or_else(|e| panic!("{what}: {e}"));
        if resumed.save_state_after(cut as u64) != state {
            problems.push(format!("{what}: the restored board saves other bytes"));
        }
        let mut over = new_board();
        execute(&ops[..ops.len().min(200)], &mut over, |_| {});
        over.load_state(&state)
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        if over.save_state_after(cut as u64) != state {
            problems.push(format!(
                "{what}: loading over a used board saves other bytes"
            ));
        }
        dumps.extend(execute(&ops[cut..], &mut resumed, |_| {}));
        let outcome = finish(resumed, dumps);
        if outcome != whole {
            problems.push(describe_difference(&what, &whole, &outcome));
        }
    }
    problems
}

fn describe_difference(what: &str, whole: &Outcome, resumed: &Outcome) -> String {
    if whole.dumps.len() != resumed.dumps.len() {
        return format!(
            "{what}: {} dumps, not {}",
            resumed.dumps.len(),
            whole.dumps.len()
        );
    }
    for (a, b) in whole.dumps.iter().zip(&resumed.dumps) {
        if a != b {
            let n = a.data.iter().zip(&b.data).filter(|(x, y)| x != y).count();
            return format!("{what}: dump {} differs ({n} values)", a.file);
        }
    }
    if whole.finals != resumed.finals {
        return format!("{what}: the final buffers differ");
    }
    format!(
        "{what}: counters differ\n  uninterrupted {:?} cycles {} status {:#x} vRetrace {} {:?}\n  resumed       {:?} cycles {} status {:#x} vRetrace {} {:?}",
        whole.stats, whole.cycles, whole.status, whole.v_retrace, whole.diagnostics,
        resumed.stats, resumed.cycles, resumed.status, resumed.v_retrace, resumed.diagnostics,
    )
}

/// The traces in `dir` (relative to the repository's `traces/`), sorted.
fn traces(dir: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../traces")
        .join(dir);
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .filter(|p| p.to_string_lossy().contains(".trace"))
        .collect();
    paths.sort();
    paths
}

/// Checks every trace of `dir` with each of `models` (`textured_only`: only the traces
/// that download a texture, cut only after the middle download).
fn check_dir(dir: &str, models: &[Model], textured_only: bool) -> usize {
    let paths = traces(dir);
    let mut problems = Vec::new();
    for path in &paths {
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        let trace = load_trace(path).unwrap_or_else(|e| panic!("{e}"));
        let mut ops = trace.ops.as_slice();
        if name.starts_with("perf_") {
            ops = &ops[..ops.len().min(PERF_OPS)];
        }
        if textured_only && !ops.iter().any(is_texture_write) {
            continue;
        }
        for &model in models {
            problems.extend(check(
                &name,
                trace.board_config(),
                model,
                ops,
                !textured_only,
            ));
        }
    }
    assert!(
        problems.is_empty(),
        "{} difference(s) after a restore:\n{}",
        problems.len(),
        problems.join("\n")
    );
    paths.len()
}

#[test]
fn conformance_traces_resume_identically() {
    assert_eq!(
        check_dir("conformance/traces", &[Model::Hardware], false),
        41
    );
}

/// Loading a state keeps how the board draws: its render threads, copy of the span
/// kernels and method (none of them is saved state).
#[test]
fn loading_keeps_how_the_board_draws() {
    let saved = used_board(BoardConfig::default()).save_state();
    let mut board = Board::new(BoardConfig::default());
    board.set_threads(3);
    board.set_vector_isa(VectorIsa::Baseline);
    board.set_method(Method::Nearest);
    board.load_state(&saved).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(board.threads(), 3);
    assert_eq!(board.vector_isa(), VectorIsa::Baseline);
    let tmu = board.tmu(0).expect("one TMU");
    assert_eq!(tmu.approx(), Method::Nearest.approx());
}

/// The host's choice of render threads is not state: the same trace on one thread and on
/// four saves the same bytes, though the bands on four threads really ran (the path
/// counts, which are not saved, say how many pixels they shaded).
#[test]
fn states_do_not_depend_on_render_threads() {
    for name in ["tmu2_combine", "tex_rgb565_bilinear", "gouraud_dither4"] {
        let path = traces("conformance/traces")
            .into_iter()
            .find(|p| {
                p.file_name()
                    .is_some_and(|s| s.to_string_lossy().starts_with(&format!("{name}.")))
            })
            .unwrap_or_else(|| panic!("no trace {name}"));
        let trace = load_trace(&path).unwrap_or_else(|e| panic!("{e}"));
        let run = |threads: usize| {
            let mut board = Board::new(trace.board_config());
            board.set_threads(threads);
            execute(&trace.ops, &mut board, |_| {});
            (board.save_state(), board.path_counts().in_bands)
        };
        let (one, in_bands_one) = run(1);
        let (four, in_bands_four) = run(4);
        assert_eq!(in_bands_one, 0, "{name}");
        assert!(
            in_bands_four > 0,
            "{name}: no band ran on the render threads"
        );
        assert!(
            one == four,
            "{name}: the state depends on the render threads"
        );
    }
}

#[test]
fn glide_sdk_traces_resume_identically() {
    assert_eq!(check_dir("glide-sdk/traces", &[Model::Hardware], false), 18);
}

#[test]
fn example_traces_resume_identically() {
    assert!(check_dir("examples", &[Model::Hardware], false) > 0);
}

#[test]
fn generated_traces_resume_identically() {
    let mut models = vec![Model::Hardware];
    models.extend(Reference::ALL.map(Model::Reference));
    assert_eq!(check_dir("generated", &models, false), 2);
}

/// 86Box's texture cache is state of its model: the textured traces resume on it too,
/// cut after a download. (Without its entries, `tex_p8_palette` resumes with 3,500
/// other pixels: the entry keyed by an earlier palette's checksum.)
#[test]
fn textured_traces_resume_identically_on_the_86box_model() {
    let model = [Model::Reference(Reference::Box86)];
    check_dir("conformance/traces", &model, true);
    check_dir("glide-sdk/traces", &model, true);
}

/// A board with some of everything: two TMUs, a texture, triangles, a swap.
fn used_board(config: BoardConfig) -> Board {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../traces/conformance/traces/tex_2tmu_modulate.trace.gz");
    let trace = load_trace(&path).unwrap_or_else(|e| panic!("{e}"));
    let mut board = Board::new(config);
    execute(&trace.ops, &mut board, |_| {});
    board
}

/// Why `bytes` is refused (panics if it loads).
fn refusal(bytes: &[u8]) -> StateError {
    match Board::from_state(bytes) {
        Ok(_) => panic!("a state of {} bytes loaded", bytes.len()),
        Err(e) => e,
    }
}

#[test]
fn states_of_other_boards_and_versions_are_refused() {
    let config = BoardConfig {
        fbi_mb: 4,
        tmus: 2,
        tmu_mb: 2,
    };
    let board = used_board(config);
    let state = board.save_state();
    assert_eq!(state[..8], MAGIC);

    // Another configuration, another model.
    let mut other = Board::new(BoardConfig { tmus: 1, ..config });
    let e = other.load_state(&state).unwrap_err();
    assert!(matches!(e, StateError::OtherConfig { .. }), "{e}");
    assert_eq!(
        e.to_string(),
        "save state is of a board with 4 MiB of frame buffer and 2 TMU(s) of 2 MiB, \
         this board has 4 MiB of frame buffer and 1 TMU(s) of 2 MiB"
    );
    let mut mame = Board::new(config);
    mame.set_model(Model::Reference(Reference::Mame));
    let e = mame.load_state(&state).unwrap_err();
    assert_eq!(
        e.to_string(),
        "save state is of the hardware model, this board runs the mame model"
    );

    // A newer version.
    let mut newer = state.clone();
    newer[8..12].copy_from_slice(&(FORMAT_VERSION + 1).to_le_bytes());
    let e = refusal(&newer);
    assert!(matches!(e, StateError::NewerVersion { found, .. } if found == FORMAT_VERSION + 1));
    assert_eq!(
        e.to_string(),
        format!(
            "save state format version {} is newer than this build reads (up to {}): use a newer voodoo-rs",
            FORMAT_VERSION + 1,
            FORMAT_VERSION
        )
    );

    // An older version (1 also held the path counts).
    let mut older = state.clone();
    older[8..12].copy_from_slice(&(FORMAT_VERSION - 1).to_le_bytes());
    let e = refusal(&older);
    assert!(matches!(e, StateError::OlderVersion { found, .. } if found == FORMAT_VERSION - 1));

    // Not a state; cut short at many lengths; trailing bytes.
    assert!(matches!(refusal(b"SST1TRCB...."), StateError::NotAState));
    assert!(matches!(refusal(&[]), StateError::NotAState));
    for len in [12, 13, 20, 100, 1000, state.len() / 2, state.len() - 1] {
        let e = refusal(&state[..len]);
        assert!(matches!(e, StateError::Corrupt(_)), "{len}: {e}");
    }
    let mut long = state.clone();
    long.push(0);
    assert!(matches!(refusal(&long), StateError::Corrupt(_)));

    // Too large for its board: refused before decoding.
    let mut huge = state.clone();
    huge.resize(sst1_board::state::max_state_len(config) + 1, 0);
    assert!(matches!(refusal(&huge), StateError::TooLarge { .. }));

    // On every error the loading board is unchanged.
    let before = other.save_state();
    let _ = other.load_state(&state[..state.len() / 2]);
    assert_eq!(other.save_state(), before);
}

/// Damaged states never panic: every byte of the header and a sample of the payload's
/// flipped, and forged lengths, give an error or a state that loads.
#[test]
fn damaged_states_never_panic() {
    let config = BoardConfig {
        fbi_mb: 2,
        tmus: 2,
        tmu_mb: 1,
    };
    let state = used_board(config).save_state();
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut loaded = 0;
    let positions: Vec<usize> = (0..64)
        .chain((0..300).map(|_| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % state.len() as u64) as usize
        }))
        .collect();
    for at in positions {
        for value in [0x00, 0xff, 0x80, state[at] ^ 1] {
            let mut bad = state.clone();
            bad[at] = value;
            if let Ok((mut board, _)) = Board::from_state(&bad) {
                // A state that decodes runs on.
                board.write32(addr::FASTFILL_CMD, 0);
                board.read32(addr::STATUS);
                loaded += 1;
            }
        }
    }
    // Most single-byte changes inside the memories decode: the test did load states.
    assert!(loaded > 0);
}

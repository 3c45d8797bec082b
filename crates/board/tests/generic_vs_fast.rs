//! Differential test of the span kernels (`pixelfx::span`, the fast path) against the
//! generic path (the reference path, pixel by pixel: `Board::set_generic_path(true)`):
//! every conformance, glide-sdk, example, generated and stability trace is replayed both
//! ways with the default profile, and the conformance, glide-sdk, generated and stability
//! ones again with each
//! reference emulator's profile; every dump the trace takes, the final
//! front, back and aux buffers and the statistics counters must be bit-identical.
//!
//! Every fast replay of the hardware model runs on 1, 2 and 4 render threads
//! (`Board::set_threads`) with the best copy of the span kernels the CPU has, and on one
//! thread with each lesser copy (`Board::set_vector_isa`: baseline, AVX2, AVX-512); each
//! of the reference models' on 1 and 2.
//!
//! `perf_tex_heavy` (about 40 s for two replays in release, texture-sampling bound)
//! runs only in the ignored test: `cargo test -p sst1-board --release --test
//! generic_vs_fast -- --ignored`.

use std::path::{Path, PathBuf};

use sst1_board::{AccuracyProfile, Board, BufferKind, Reference, Stats, VectorIsa};
use sst1_trace::{execute, load_trace};

/// Traces too slow for every CI run; [`slow_traces_identical`] covers them.
const SLOW: &[&str] = &["perf_tex_heavy"];

/// One buffer read out of the board: its name, row width and values.
struct Buffer {
    name: String,
    width: u32,
    data: Vec<u16>,
}

/// What one replay produced: the dumps, the final buffers and the counters.
struct Outcome {
    buffers: Vec<Buffer>,
    stats: Stats,
    /// The timing model's record (`Debug` of the total and of every frame): a triangle
    /// shaded on the render thread is timed on the calling thread from its walk's counts.
    timing: String,
}

/// How a replay draws: the reference path, or the fast path on this many render threads
/// with this copy of the span kernels.
#[derive(Clone, Copy, Debug)]
enum Run {
    Reference,
    Fast { threads: usize, isa: VectorIsa },
}

/// The fast replays of the hardware model: 1, 2 and 4 threads with the best copy of the
/// kernels, one thread with each lesser copy the CPU has.
fn hardware_runs() -> Vec<Run> {
    let best = VectorIsa::best();
    let threads = [1, 2, 4].map(|threads| Run::Fast { threads, isa: best });
    let lesser = VectorIsa::available()
        .filter(|&isa| isa < best)
        .map(|isa| Run::Fast { threads: 1, isa });
    threads.into_iter().chain(lesser).collect()
}

/// The fast replays of a reference model (which has the baseline copy only): 1 and 2
/// threads.
const REFERENCE_RUNS: [Run; 2] = [
    Run::Fast {
        threads: 1,
        isa: VectorIsa::Baseline,
    },
    Run::Fast {
        threads: 2,
        isa: VectorIsa::Baseline,
    },
];

fn replay(path: &Path, profile: AccuracyProfile, run: Run) -> Outcome {
    let trace = load_trace(path).unwrap_or_else(|e| panic!("{e}"));
    let mut board = Board::new(trace.board_config());
    board.set_profile(profile);
    match run {
        Run::Reference => board.set_generic_path(true),
        Run::Fast { threads, isa } => {
            board.set_threads(threads);
            board.set_vector_isa(isa);
        }
    }
    let mut buffers: Vec<Buffer> = execute(&trace.ops, &mut board, |_| {})
        .into_iter()
        .map(|d| Buffer {
            name: d.file,
            width: d.width,
            data: d.data,
        })
        .collect();
    for (name, kind) in [
        ("final front", BufferKind::Front),
        ("final back", BufferKind::Back),
        ("final aux", BufferKind::Aux),
    ] {
        buffers.push(Buffer {
            name: name.to_owned(),
            width: board.display_size().0,
            data: board.dump_buffer(kind),
        });
    }
    let timing = board.timing();
    Outcome {
        buffers,
        stats: board.stats(),
        timing: format!("{:?} {:?}", timing.total, timing.frames),
    }
}

/// Differences between the reference replay of `path` with `profile` and each of the
/// fast replays `runs`, in words.
fn compare(path: &Path, profile: AccuracyProfile, runs: &[Run]) -> Vec<String> {
    let reference = replay(path, profile, Run::Reference);
    runs.iter()
        .flat_map(|&run| {
            differences(path, &reference, &replay(path, profile, run))
                .into_iter()
                .map(move |d| format!("{run:?}: {d}"))
        })
        .collect()
}

/// Differences between two replays of `path`, in words.
fn differences(path: &Path, reference: &Outcome, fast: &Outcome) -> Vec<String> {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let mut problems = Vec::new();
    if reference.stats != fast.stats {
        problems.push(format!(
            "{name}: counters differ\n  reference {:?}\n  fast      {:?}",
            reference.stats, fast.stats
        ));
    }
    if reference.timing != fast.timing {
        problems.push(format!(
            "{name}: modelled time differs\n  reference {}\n  fast      {}",
            reference.timing, fast.timing
        ));
    }
    if reference.buffers.len() != fast.buffers.len() {
        problems.push(format!("{name}: dump count differs"));
    }
    for (r, f) in reference.buffers.iter().zip(&fast.buffers) {
        let diffs: Vec<usize> = (0..r.data.len().max(f.data.len()))
            .filter(|&i| r.data.get(i) != f.data.get(i))
            .collect();
        if let Some(&first) = diffs.first() {
            let w = r.width.max(1) as usize;
            problems.push(format!(
                "{name} {}: {} values differ; first at (x {}, y {}): reference {:04x?} fast {:04x?}",
                r.name,
                diffs.len(),
                first % w,
                first / w,
                r.data.get(first),
                f.data.get(first)
            ));
        }
    }
    problems
}

/// The traces in `dir` (relative to the repository's `traces/`), sorted, whose names
/// pass `keep`.
fn traces(dir: &str, keep: impl Fn(&str) -> bool) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../traces")
        .join(dir);
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .filter(|p| {
            let file = p.file_name().unwrap_or_default().to_string_lossy();
            file.contains(".trace") && keep(file.split('.').next().unwrap_or_default())
        })
        .collect();
    paths.sort();
    paths
}

/// The hardware model: the reference path against the fast path ([`hardware_runs`]).
fn check_all(paths: &[PathBuf]) {
    check_all_with(paths, AccuracyProfile::default(), &hardware_runs());
}

fn check_all_with(paths: &[PathBuf], profile: AccuracyProfile, runs: &[Run]) {
    let problems: Vec<String> = paths
        .iter()
        .flat_map(|p| compare(p, profile, runs))
        .collect();
    assert!(
        problems.is_empty(),
        "{} difference(s) between the reference and fast paths:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[test]
fn conformance_traces_identical() {
    let paths = traces("conformance/traces", |name| !SLOW.contains(&name));
    // 41 traces less the slow one.
    assert_eq!(paths.len(), 40);
    check_all(&paths);
}

#[test]
fn glide_sdk_traces_identical() {
    let paths = traces("glide-sdk/traces", |_| true);
    assert_eq!(paths.len(), 18);
    check_all(&paths);
}

#[test]
fn example_traces_identical() {
    let paths = traces("examples", |_| true);
    assert!(!paths.is_empty());
    check_all(&paths);
}

/// The generated scenes (`traces/generated`: 10-pixel triangles, random drawing states),
/// with the default profile and each reference emulator's.
#[test]
fn generated_traces_identical() {
    let paths = traces("generated", |_| true);
    assert_eq!(paths.len(), 2);
    check_all(&paths);
    for reference in Reference::ALL {
        check_all_with(&paths, reference.profile(), &REFERENCE_RUNS);
    }
}

/// The stability scenes (`traces/stability`, `sst1_trace::scenes::stability`): ten
/// families, each sweeping one number (width, size, W, depth, gradient, LOD, run length)
/// to where arithmetic breaks. The approximate methods break on them; the exact fast path
/// must not, for the hardware model and each reference model.
#[test]
fn stability_traces_identical() {
    let paths = traces("stability", |_| true);
    assert_eq!(paths.len(), 10);
    check_all(&paths);
    for reference in Reference::ALL {
        check_all_with(&paths, reference.profile(), &REFERENCE_RUNS);
    }
}

/// The reference emulators' profiles (the conformance vote replays every trace with
/// them) run the same span kernels, compiled with their switches: both paths agree for
/// each of them too, on one render thread and two.
#[test]
fn reference_profiles_identical() {
    let mut paths = traces("conformance/traces", |name| !SLOW.contains(&name));
    paths.extend(traces("glide-sdk/traces", |_| true));
    for reference in Reference::ALL {
        check_all_with(&paths, reference.profile(), &REFERENCE_RUNS);
    }
}

/// The bands of the threaded walk do run on the traces above (so that the thread counts
/// of [`check_all`] are not a no-op): a large untextured triangle goes to them.
#[test]
fn render_threads_take_large_untextured_triangles() {
    let path = traces("conformance/traces", |name| name == "gouraud_dither4");
    let trace = load_trace(&path[0]).unwrap_or_else(|e| panic!("{e}"));
    let mut board = Board::new(trace.board_config());
    board.set_threads(2);
    execute(&trace.ops, &mut board, |_| {});
    let counts = board.path_counts();
    assert!(counts.in_bands > 50_000, "{counts:?}");
    assert_eq!(counts.aliased_layout + counts.reference, 0, "{counts:?}");
}

/// Small triangles are shaded on the render thread behind the writes
/// (`pixelfx::deferred`) on the traces above, so that [`check_all`]'s two- and
/// four-thread runs prove them: most of the small-triangle scene's pixels, and some of
/// the random-state scene's (where fills, LFB accesses, table writes and large
/// triangles call them back between).
#[test]
fn render_thread_takes_small_triangles() {
    for (name, least) in [("small_tris", 15_000), ("random_states", 300)] {
        let path = traces("generated", |n| n == name);
        let trace = load_trace(&path[0]).unwrap_or_else(|e| panic!("{e}"));
        let mut board = Board::new(trace.board_config());
        board.set_threads(2);
        execute(&trace.ops, &mut board, |_| {});
        let counts = board.path_counts();
        assert!(counts.behind_writes > least, "{name}: {counts:?}");
        // One thread never defers.
        let mut board = Board::new(trace.board_config());
        board.set_threads(1);
        execute(&trace.ops, &mut board, |_| {});
        assert_eq!(board.path_counts().behind_writes, 0, "{name}");
    }
}

#[test]
fn render_threads_take_large_textured_triangles() {
    // Two TMUs chained (each TMU's levels shared, `Tmu::share_levels`), and one.
    for (name, least) in [("tmu2_combine", 500_000), ("tex_rgb565_bilinear", 50_000)] {
        let path = traces("conformance/traces", |n| n == name);
        let trace = load_trace(&path[0]).unwrap_or_else(|e| panic!("{e}"));
        let mut board = Board::new(trace.board_config());
        board.set_threads(2);
        execute(&trace.ops, &mut board, |_| {});
        let counts = board.path_counts();
        assert!(counts.in_bands > least, "{name}: {counts:?}");
        assert_eq!(
            counts.aliased_layout + counts.reference,
            0,
            "{name}: {counts:?}"
        );
    }
}

#[test]
#[ignore = "about 80 s in release: the texture-heavy benchmark trace, replayed four times"]
fn slow_traces_identical() {
    let paths = traces("conformance/traces", |name| SLOW.contains(&name));
    assert_eq!(paths.len(), SLOW.len());
    check_all(&paths);
}

//! Differential test of the span kernels (`pixelfx::span`, the fast path) against the
//! generic path (the reference path, pixel by pixel, (`Board::set_generic_path(true)`): every conformance, glide-sdk, example
//! and generated trace is replayed both ways with the default profile, and the conformance,
//! glide-sdk and generated ones again with each reference emulator's profile; every dump the trace takes, the final
//! front, back and aux buffers and the statistics counters must be bit-identical.
//!
//! `perf_tex_heavy` (about 40 s for both replays in release, texture-sampling bound)
//! runs only in the ignored test: `cargo test -p sst1-board --release --test
//! generic_vs_fast -- --ignored`.

use std::path::{Path, PathBuf};

use sst1_board::{AccuracyProfile, Board, BufferKind, Reference, Stats};
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
}

fn replay(path: &Path, profile: AccuracyProfile, reference: bool) -> Outcome {
    let trace = load_trace(path).unwrap_or_else(|e| panic!("{e}"));
    let mut board = Board::new(trace.board_config());
    board.set_profile(profile);
    board.set_generic_path(reference);
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
    Outcome {
        buffers,
        stats: board.stats(),
    }
}

/// Differences between the two replays of `path` with `profile`, in words.
fn compare(path: &Path, profile: AccuracyProfile) -> Vec<String> {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let reference = replay(path, profile, true);
    let fast = replay(path, profile, false);
    let mut problems = Vec::new();
    if reference.stats != fast.stats {
        problems.push(format!(
            "{name}: counters differ\n  reference {:?}\n  fast      {:?}",
            reference.stats, fast.stats
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

fn check_all(paths: &[PathBuf]) {
    check_all_with(paths, AccuracyProfile::default());
}

fn check_all_with(paths: &[PathBuf], profile: AccuracyProfile) {
    let problems: Vec<String> = paths.iter().flat_map(|p| compare(p, profile)).collect();
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
        check_all_with(&paths, reference.profile());
    }
}

/// The reference emulators' profiles (the conformance vote replays every trace with
/// them) run the same span kernels, compiled with their switches: both paths agree for
/// each of them too.
#[test]
fn reference_profiles_identical() {
    let mut paths = traces("conformance/traces", |name| !SLOW.contains(&name));
    paths.extend(traces("glide-sdk/traces", |_| true));
    for reference in Reference::ALL {
        check_all_with(&paths, reference.profile());
    }
}

#[test]
#[ignore = "about 40 s in release: the texture-heavy benchmark trace, replayed twice"]
fn slow_traces_identical() {
    let paths = traces("conformance/traces", |name| SLOW.contains(&name));
    assert_eq!(paths.len(), SLOW.len());
    check_all(&paths);
}

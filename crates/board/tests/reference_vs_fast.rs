//! Differential test of the specialised pixel path (`pixelfx::specialize`) against the
//! reference path (`Board::set_reference(true)`): every conformance and glide-sdk trace is
//! replayed both ways, and every dump the trace takes, the final front, back and aux
//! buffers and the statistics counters must be bit-identical.
//!
//! `perf_tex_heavy` (about a minute per replay on the reference path, texture sampling
//! bound) runs only in the ignored test: `cargo test -p sst1-board --release --test
//! reference_vs_fast -- --ignored`.

use std::path::{Path, PathBuf};

use sst1_board::{Board, BufferKind, Stats};
use sst1_trace::{execute, load_trace};

/// Traces too slow for every CI run; [`slow_traces_identical`] covers them.
const SLOW: &[&str] = &["perf_tex_heavy"];

/// What one replay produced: the dumps (file name, values), final buffers and counters.
struct Outcome {
    dumps: Vec<(String, Vec<u16>)>,
    stats: Stats,
}

fn replay(path: &Path, reference: bool) -> Outcome {
    let trace = load_trace(path).unwrap_or_else(|e| panic!("{e}"));
    let mut board = Board::new(trace.board_config());
    board.set_reference(reference);
    let mut dumps: Vec<(String, Vec<u16>)> = execute(&trace.ops, &mut board, |_| {})
        .into_iter()
        .map(|d| (d.file, d.data))
        .collect();
    for (name, kind) in [
        ("final front", BufferKind::Front),
        ("final back", BufferKind::Back),
        ("final aux", BufferKind::Aux),
    ] {
        dumps.push((name.to_owned(), board.dump_buffer(kind)));
    }
    Outcome {
        dumps,
        stats: board.stats(),
    }
}

/// Differences between the two replays of `path`, in words.
fn compare(path: &Path) -> Vec<String> {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let reference = replay(path, true);
    let fast = replay(path, false);
    let mut problems = Vec::new();
    if reference.stats != fast.stats {
        problems.push(format!(
            "{name}: counters differ\n  reference {:?}\n  fast      {:?}",
            reference.stats, fast.stats
        ));
    }
    if reference.dumps.len() != fast.dumps.len() {
        problems.push(format!("{name}: dump count differs"));
    }
    for ((file, r), (_, f)) in reference.dumps.iter().zip(&fast.dumps) {
        let diffs: Vec<usize> = (0..r.len().max(f.len()))
            .filter(|&i| r.get(i) != f.get(i))
            .collect();
        if let Some(&first) = diffs.first() {
            problems.push(format!(
                "{name} {file}: {} values differ; first at index {first}: reference {:04x?} fast {:04x?}",
                diffs.len(),
                r.get(first),
                f.get(first)
            ));
        }
    }
    problems
}

/// The traces of trace set `set` (`conformance` or `glide-sdk`), sorted, whose names
/// pass `keep`.
fn traces(set: &str, keep: impl Fn(&str) -> bool) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../traces")
        .join(set)
        .join("traces");
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
    let problems: Vec<String> = paths.iter().flat_map(|p| compare(p)).collect();
    assert!(
        problems.is_empty(),
        "{} difference(s) between the reference and fast paths:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[test]
fn conformance_traces_identical() {
    let paths = traces("conformance", |name| !SLOW.contains(&name));
    // 41 traces less the slow one.
    assert_eq!(paths.len(), 40);
    check_all(&paths);
}

#[test]
fn glide_sdk_traces_identical() {
    let paths = traces("glide-sdk", |_| true);
    assert!(!paths.is_empty());
    check_all(&paths);
}

#[test]
#[ignore = "about two minutes: the texture-heavy benchmark trace, replayed twice"]
fn slow_traces_identical() {
    let paths = traces("conformance", |name| SLOW.contains(&name));
    assert_eq!(paths.len(), SLOW.len());
    check_all(&paths);
}

//! Replay throughput: runs the two heavy conformance traces (or any trace whose name
//! contains a command-line filter) on the hardware model's span kernels, on its
//! generic path, and on the custom model (the switches read at run time, here set to the
//! hardware model's: what the compile-time model saves) and prints Mpixels/s
//! (`fbiPixelsIn` per second), triangles/s and the speedups; and the fast path with the
//! timing model off (`Board::set_timing(false)`), for what the model costs.
//!
//! ```text
//! cargo bench -p sst1-board --bench replay                  # perf_gouraud_heavy, perf_tex_heavy
//! cargo bench -p sst1-board --bench replay -- gouraud       # traces whose name contains "gouraud"
//! BENCH_ITERS=5 cargo bench -p sst1-board --bench replay    # best of 5 runs per path
//! ```
//!
//! Each run builds a fresh board and replays the whole trace (`sst1_trace::execute`);
//! trace loading is not timed. The run kept is the best of `BENCH_ITERS` runs (default
//! 3). Throughput is computed from the CPU time of the replaying thread (Linux
//! schedstat; wall time elsewhere), because other load on a shared machine inflates
//! wall time far more; both are printed.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use sst1_board::{AccuracyProfile, Board, Model, Stats};
use sst1_trace::{execute, load_trace, Trace};

/// The traces run when no filter is given.
const DEFAULT_TRACES: [&str; 2] = ["perf_gouraud_heavy", "perf_tex_heavy"];

/// One replay's cost: wall-clock time and the time this thread spent on a CPU.
#[derive(Clone, Copy)]
struct Timing {
    wall: Duration,
    /// `None` where the OS does not tell (only Linux's schedstat is read).
    cpu: Option<Duration>,
}

/// Time this thread has spent running, from Linux's `/proc/thread-self/schedstat`
/// (first field, nanoseconds). On a shared machine this is much steadier than wall time.
fn thread_cpu_time() -> Option<Duration> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns = s.split_whitespace().next()?.parse().ok()?;
    Some(Duration::from_nanos(ns))
}

/// Replay `trace` once on a fresh board; returns the time taken and the counters.
/// How a run drives the board.
#[derive(Clone, Copy)]
enum RunPath {
    /// The hardware model, span kernels and texel caches.
    Fast,
    /// The hardware model's generic path.
    Generic,
    /// The custom model with the hardware model's switches, fast path.
    Custom,
    /// The fast path with the timing model off.
    NoTiming,
}

fn run_once(trace: &Trace, path: RunPath) -> (Timing, Stats) {
    let mut board = Board::new(trace.board_config());
    match path {
        RunPath::Fast => {}
        RunPath::Generic => board.set_generic_path(true),
        RunPath::Custom => board.set_model(Model::Custom(AccuracyProfile::HARDWARE)),
        RunPath::NoTiming => board.set_timing(false),
    }
    let cpu0 = thread_cpu_time();
    let start = Instant::now();
    let dumps = execute(&trace.ops, &mut board, |_| {});
    let wall = start.elapsed();
    let cpu = thread_cpu_time()
        .zip(cpu0)
        .map(|(b, a)| b.saturating_sub(a));
    std::hint::black_box(dumps);
    (Timing { wall, cpu }, board.stats())
}

/// The run with the least CPU time (wall time without schedstat) of `iters` runs.
fn best_of(trace: &Trace, path: RunPath, iters: u32) -> (Timing, Stats) {
    let mut best: Option<(Timing, Stats)> = None;
    for _ in 0..iters {
        let (t, s) = run_once(trace, path);
        let better = best.is_none_or(|(b, _)| t.key() < b.key());
        if better {
            best = Some((t, s));
        }
    }
    best.expect("at least one run")
}

impl Timing {
    /// The time throughput is computed from: CPU time where known.
    fn key(&self) -> Duration {
        self.cpu.unwrap_or(self.wall)
    }
}

fn report(label: &str, t: Timing, s: &Stats) {
    let secs = t.key().as_secs_f64();
    let cpu = t
        .cpu
        .map_or(String::from("n/a"), |c| format!("{:.3} s", c.as_secs_f64()));
    println!(
        "  {label:<9} cpu {cpu:>9}  wall {:8.3} s  {:8.2} Mpix/s  {:8.0} tri/s  ({} pixels in, {} triangles)",
        t.wall.as_secs_f64(),
        s.pixels_in as f64 / secs / 1e6,
        s.triangles as f64 / secs,
        s.pixels_in,
        s.triangles
    );
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../traces");
    let args: Vec<String> = std::env::args().skip(1).collect();
    let filters: Vec<String> = args.into_iter().filter(|a| !a.starts_with("--")).collect();
    let iters = std::env::var("BENCH_ITERS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(3u32)
        .max(1);
    let mut paths: Vec<PathBuf> = ["conformance/traces", "glide-sdk/traces"]
        .iter()
        .filter_map(|d| std::fs::read_dir(root.join(d)).ok())
        .flatten()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let name = trace_name(p);
            if filters.is_empty() {
                DEFAULT_TRACES.contains(&name.as_str())
            } else {
                filters.iter().any(|f| name.contains(f.as_str()))
            }
        })
        .collect();
    paths.sort();
    println!("best of {iters} run(s) per path");
    for path in paths {
        let trace = match load_trace(&path) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("{e}");
                continue;
            }
        };
        println!("{}", trace_name(&path));
        let (tf, sf) = best_of(&trace, RunPath::Fast, iters);
        report("fast", tf, &sf);
        let (tr, sr) = best_of(&trace, RunPath::Generic, iters);
        report("generic", tr, &sr);
        let (tc, sc) = best_of(&trace, RunPath::Custom, iters);
        report("custom", tc, &sc);
        let (tn, sn) = best_of(&trace, RunPath::NoTiming, iters);
        report("no timing", tn, &sn);
        println!(
            "  fast is {:.2}x the generic path, {:.2}x the custom model; the timing model costs {:+.2} %{}",
            tr.key().as_secs_f64() / tf.key().as_secs_f64(),
            tc.key().as_secs_f64() / tf.key().as_secs_f64(),
            (tf.key().as_secs_f64() / tn.key().as_secs_f64() - 1.0) * 100.0,
            if sf == sr && sf == sc && sf == sn {
                ""
            } else {
                "  (COUNTERS DIFFER)"
            }
        );
    }
}

/// `name` of `.../name.trace[.gz]`.
fn trace_name(p: &Path) -> String {
    let file = p
        .file_name()
        .map_or(String::new(), |f| f.to_string_lossy().into_owned());
    file.split('.').next().unwrap_or_default().to_owned()
}

//! `voodoo bench`: replay throughput of the fast path (the span kernels) and the
//! reference path (`Board::set_generic_path(true)`) in the same run.
//!
//! Each scene is loaded (or generated and parsed) first, and encoded in the binary form;
//! only the replay is timed (the `binary` row's replay decodes that form as it runs), from
//! the replaying thread's CPU time (`CLOCK_THREAD_CPUTIME_ID`; wall time where there is
//! none), because other load on a shared machine inflates wall time far more. Each
//! path runs `iters` times on a fresh board and the fastest run is kept. Pixels are the
//! board's `fbiPixelsIn` count (spec 5.31: every pixel the triangle walker processes).
//! Cycles per pixel use the CPU's clock rate where Linux tells it (`cpufreq`'s maximum,
//! else `cpu MHz` of `/proc/cpuinfo`) and are left out otherwise.
//!
//! This is `crates/board/benches/replay.rs` as a command, with the generated scenes of
//! `sst1_trace::scenes` beside the perf traces.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use sst1_board::{Board, Method, Stats, VectorIsa};
use sst1_trace::scenes::{self, RandomStates};
use sst1_trace::{
    encode_binary, execute, execute_trace_stream, load_trace, read_trace, stream_trace, Trace,
};

/// The recorded traces `voodoo bench` runs by default (in `traces/conformance/traces`).
pub const PERF_TRACES: [&str; 2] = ["perf_gouraud_heavy", "perf_tex_heavy"];

/// Drawing states of the default heavy-states scene ([`scenes::heavy_states`]).
const HEAVY_STATES: u32 = 12;

/// The repository's conformance traces, where this binary was built.
fn default_trace_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../traces/conformance/traces")
}

/// What to run.
pub struct Options {
    /// Trace files to run instead of the default set.
    pub traces: Vec<PathBuf>,
    /// Runs per path; the fastest is kept.
    pub iters: u32,
    /// Print JSON instead of a table.
    pub json: bool,
    /// Triangles in each small-triangle scene.
    pub small: u32,
    /// States in the random-state scene.
    pub states: u32,
    /// Where the perf traces are (default: the repository's `traces/conformance/traces`).
    pub trace_dir: Option<PathBuf>,
    /// Render threads of the extra fast-path row (none when 1).
    pub threads: usize,
    /// Also run every approximate method (`sst1_board::Method`) on one thread, a row each
    /// with its speed-up over the fast path.
    pub methods: bool,
    /// Also run the fast path with each copy of the span kernels below the best the CPU
    /// has (`pixelfx::isa`), one thread, a row each with its speed-up over the fast path.
    pub isas: bool,
    /// Write the chart of every method on every trace into this folder instead
    /// (module `chart`).
    pub chart: Option<PathBuf>,
}

/// One scene to run: its name and ops, and the ops in the binary trace form.
struct Scene {
    name: String,
    trace: Trace,
    binary: Vec<u8>,
}

impl Scene {
    fn new(name: String, trace: Trace) -> Self {
        let binary = encode_binary(&trace);
        Self {
            name,
            trace,
            binary,
        }
    }
}

/// One replay's cost.
#[derive(Clone, Copy)]
struct Timing {
    wall: Duration,
    /// `None` where the OS does not tell (only Linux's schedstat is read).
    cpu: Option<Duration>,
    /// Timed by the wall clock (a run on several threads: the replaying thread's CPU
    /// time leaves out the others').
    by_wall: bool,
}

impl Timing {
    /// The time throughput is computed from: CPU time where known, wall time for a run
    /// on several threads.
    fn key(&self) -> Duration {
        if self.by_wall {
            self.wall
        } else {
            self.cpu.unwrap_or(self.wall)
        }
    }
}

/// Time this thread has spent running: `CLOCK_THREAD_CPUTIME_ID` (precise to the
/// nanosecond on Linux), else the first field of `/proc/thread-self/schedstat` (what
/// `crates/board/benches/replay.rs` reads; it advances only at scheduler ticks, a few
/// milliseconds, so it suits long replays only).
pub(crate) fn thread_cpu_time() -> Option<Duration> {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec for the duration of the call.
    if unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) } == 0 {
        return Some(Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32));
    }
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns = s.split_whitespace().next()?.parse().ok()?;
    Some(Duration::from_nanos(ns))
}

/// The CPU's clock rate in Hz and where it came from, if Linux tells it.
fn clock_hz() -> Option<(f64, &'static str)> {
    if let Ok(s) = std::fs::read_to_string("/sys/devices/system/cpu/cpu0/cpufreq/cpuinfo_max_freq")
    {
        if let Ok(khz) = s.trim().parse::<f64>() {
            return Some((khz * 1e3, "cpufreq cpuinfo_max_freq"));
        }
    }
    let info = std::fs::read_to_string("/proc/cpuinfo").ok()?;
    let mhz = info
        .lines()
        .find(|l| l.starts_with("cpu MHz"))?
        .split(':')
        .nth(1)?
        .trim()
        .parse::<f64>()
        .ok()?;
    Some((mhz * 1e6, "/proc/cpuinfo cpu MHz"))
}

/// How a run draws.
#[derive(Clone, Copy)]
enum Run {
    /// The reference path, one thread.
    Reference,
    /// The fast path on this many render threads.
    Fast(usize),
    /// An approximate method, one thread.
    Approx(Method),
    /// The fast path, one thread, with this copy of the span kernels.
    Isa(VectorIsa),
    /// The fast path, one thread, reading the scene's binary form as it runs (what
    /// `voodoo replay FILE.vtrace` does, from memory rather than a file).
    FromBinary,
}

/// The fastest of `iters` runs of each of `runs`, in rounds with the fast path, so that
/// a change in the machine's load falls on all of them alike; `fast` becomes the
/// fastest of its runs here and before. No runs, no rounds.
fn interleaved<K: Copy>(
    scene: &Scene,
    runs: Vec<K>,
    run: impl Fn(K) -> Run,
    iters: u32,
    fast: &mut PathResult,
) -> Vec<(K, PathResult)> {
    if runs.is_empty() {
        return Vec::new();
    }
    let mut best: Vec<Option<(Timing, Stats)>> = vec![None; runs.len()];
    for _ in 0..iters.max(1) {
        let (t, s) = run_once(scene, Run::Fast(1));
        if t.key() < fast.timing.key() {
            *fast = PathResult {
                timing: t,
                stats: s,
            };
        }
        for (slot, &k) in best.iter_mut().zip(&runs) {
            let (t, s) = run_once(scene, run(k));
            if slot.is_none_or(|(b, _)| t.key() < b.key()) {
                *slot = Some((t, s));
            }
        }
    }
    runs.into_iter()
        .zip(best)
        .filter_map(|(k, b)| b.map(|(timing, stats)| (k, PathResult { timing, stats })))
        .collect()
}

/// Replays `scene` once on a fresh board.
fn run_once(scene: &Scene, run: Run) -> (Timing, Stats) {
    let trace = &scene.trace;
    let mut board = Board::new(trace.board_config());
    match run {
        Run::Reference => board.set_generic_path(true),
        Run::Fast(threads) => board.set_threads(threads),
        Run::Approx(method) => {
            board.set_method(method);
            board.set_threads(1);
        }
        Run::Isa(isa) => {
            board.set_vector_isa(isa);
            board.set_threads(1);
        }
        Run::FromBinary => board.set_threads(1),
    }
    let cpu0 = thread_cpu_time();
    let start = Instant::now();
    if let Run::FromBinary = run {
        // An encoded trace always decodes; were it not to, the counters would differ
        // from the fast path's and the bench would say so.
        if let Ok(mut stream) = stream_trace(&scene.name, &scene.binary[..]) {
            let sink = |dump| {
                std::hint::black_box(dump);
                Ok(())
            };
            let _ = execute_trace_stream(&mut stream, None, &mut board, |_| {}, sink);
        }
    } else {
        std::hint::black_box(execute(&trace.ops, &mut board, |_| {}));
    }
    let wall = start.elapsed();
    let cpu = thread_cpu_time()
        .zip(cpu0)
        .map(|(b, a)| b.saturating_sub(a));
    let by_wall = matches!(run, Run::Fast(n) if n > 1);
    (Timing { wall, cpu, by_wall }, board.stats())
}

/// The fastest of `iters` runs.
fn best_of(scene: &Scene, run: Run, iters: u32) -> (Timing, Stats) {
    let mut best: Option<(Timing, Stats)> = None;
    for _ in 0..iters.max(1) {
        let (t, s) = run_once(scene, run);
        if best.is_none_or(|(b, _)| t.key() < b.key()) {
            best = Some((t, s));
        }
    }
    best.expect("at least one run")
}

/// The figures of one path on one scene.
struct PathResult {
    timing: Timing,
    stats: Stats,
}

impl PathResult {
    fn secs(&self) -> f64 {
        self.timing.key().as_secs_f64().max(1e-9)
    }

    fn mpix(&self) -> f64 {
        self.stats.pixels_in as f64 / self.secs() / 1e6
    }

    fn mtri(&self) -> f64 {
        self.stats.triangles as f64 / self.secs() / 1e6
    }

    fn ns_per_pixel(&self) -> Option<f64> {
        (self.stats.pixels_in > 0).then(|| self.secs() * 1e9 / self.stats.pixels_in as f64)
    }

    fn cycles_per_pixel(&self, clock: Option<f64>) -> Option<f64> {
        Some(self.ns_per_pixel()? * clock? / 1e9)
    }

    fn json(&self, clock: Option<f64>) -> serde_json::Value {
        serde_json::json!({
            "cpu_s": self.timing.cpu.map(|c| c.as_secs_f64()),
            "wall_s": self.timing.wall.as_secs_f64(),
            "mpix_per_s": self.mpix(),
            "mtri_per_s": self.mtri(),
            "ns_per_pixel": self.ns_per_pixel(),
            "cycles_per_pixel": self.cycles_per_pixel(clock),
        })
    }
}

/// The default scenes: the perf traces (where found), then the generated ones.
fn default_scenes(o: &Options) -> Result<Vec<Scene>, String> {
    let dir = o.trace_dir.clone().unwrap_or_else(default_trace_dir);
    let mut out = Vec::new();
    for name in PERF_TRACES {
        let path = dir.join(format!("{name}.trace.gz"));
        if path.exists() {
            let trace = load_trace(&path).map_err(|e| e.to_string())?;
            out.push(Scene::new(name.to_owned(), trace));
        } else if !o.json {
            eprintln!("voodoo bench: {} not found, skipped", path.display());
        }
    }
    let generated = [
        (
            format!("small_tris_gouraud ({} tris)", o.small),
            scenes::small_triangles(1, o.small, false),
        ),
        (
            format!("small_tris_textured ({} tris)", o.small),
            scenes::small_triangles(1, o.small, true),
        ),
        (
            format!("random_states ({} states, 2 TMUs)", o.states),
            scenes::random_states(RandomStates {
                seed: 1,
                tmus: 2,
                states: o.states,
                triangles_per_state: 2,
                dump_every: 0,
                layout: false,
                large: false,
            }),
        ),
        (
            format!("heavy_states ({HEAVY_STATES} states, 2 TMUs)"),
            scenes::heavy_states(1, HEAVY_STATES),
        ),
    ];
    for (name, text) in generated {
        let trace = read_trace(&name, text.as_bytes()).map_err(|e| e.to_string())?;
        out.push(Scene::new(name, trace));
    }
    Ok(out)
}

/// The name of a trace file without its folder and `.trace[.gz]`/`.vtrace[.gz]`.
fn stem(path: &Path) -> String {
    let file = path
        .file_name()
        .map_or(String::new(), |f| f.to_string_lossy().into_owned());
    file.split('.').next().unwrap_or_default().to_owned()
}

/// Runs `voodoo bench`.
pub fn bench(o: &Options) -> Result<(), String> {
    if let Some(dir) = &o.chart {
        return crate::chart::chart(&crate::chart::ChartOptions {
            dir,
            root: Path::new(env!("CARGO_MANIFEST_DIR")).join("../../traces"),
            given: &o.traces,
            iters: o.iters,
        });
    }
    let scenes = if o.traces.is_empty() {
        default_scenes(o)?
    } else {
        o.traces
            .iter()
            .map(|p| {
                Ok(Scene::new(
                    stem(p),
                    load_trace(p).map_err(|e| e.to_string())?,
                ))
            })
            .collect::<Result<_, String>>()?
    };
    let clock = clock_hz();
    let timer = if thread_cpu_time().is_some() {
        "thread CPU time"
    } else {
        "wall time"
    };
    if !o.json {
        println!(
            "best of {} run(s) per path, {timer} of the replay (parsing excluded but on the binary row, which decodes the binary form as it runs; the threaded row by wall time); the fast path's kernels compiled for {}{}",
            o.iters.max(1),
            VectorIsa::best(),
            clock.map_or(String::new(), |(hz, from)| format!(
                "; clock {:.2} GHz ({from})",
                hz / 1e9
            ))
        );
        println!(
            "{:<34} {:<13} {:>9} {:>9} {:>8} {:>8} {:>9} {:>11} {:>9}",
            "scene",
            "path",
            "Mpix/s",
            "Mtri/s",
            "ns/pix",
            "cyc/pix",
            "speed-up",
            "pixels in",
            "triangles"
        );
    }
    let mut json_scenes = Vec::new();
    let mut all_match = true;
    for scene in &scenes {
        let (t, s) = best_of(scene, Run::Fast(1), o.iters);
        let mut fast = PathResult {
            timing: t,
            stats: s,
        };
        let (t, s) = best_of(scene, Run::Reference, o.iters);
        let reference = PathResult {
            timing: t,
            stats: s,
        };
        let (t, s) = best_of(scene, Run::FromBinary, o.iters);
        let from_binary = PathResult {
            timing: t,
            stats: s,
        };
        let threaded = (o.threads > 1).then(|| {
            let (t, s) = best_of(scene, Run::Fast(o.threads), o.iters);
            PathResult {
                timing: t,
                stats: s,
            }
        });
        let methods: Vec<Method> = if o.methods {
            Method::ALL.into_iter().filter(|m| !m.is_exact()).collect()
        } else {
            Vec::new()
        };
        let lesser: Vec<VectorIsa> = if o.isas {
            VectorIsa::available()
                .filter(|&isa| isa < VectorIsa::best())
                .collect()
        } else {
            Vec::new()
        };
        let approx = interleaved(scene, methods, Run::Approx, o.iters, &mut fast);
        let isa_rows = interleaved(scene, lesser, Run::Isa, o.iters, &mut fast);
        let speedup = reference.secs() / fast.secs();
        // Threads against one thread, both by the wall clock.
        let thread_speedup = threaded
            .as_ref()
            .map(|t| fast.timing.wall.as_secs_f64() / t.secs());
        let same = fast.stats == reference.stats
            && from_binary.stats == fast.stats
            && threaded.as_ref().is_none_or(|t| t.stats == fast.stats)
            && isa_rows.iter().all(|(_, r)| r.stats == fast.stats);
        all_match &= same;
        let hz = clock.map(|(hz, _)| hz);
        if o.json {
            json_scenes.push(serde_json::json!({
                "name": scene.name,
                "pixels_in": fast.stats.pixels_in,
                "pixels_out": fast.stats.pixels_out,
                "triangles": fast.stats.triangles,
                "fast": fast.json(hz),
                "reference": reference.json(hz),
                "from_binary": from_binary.json(hz),
                "speedup": speedup,
                "threads": o.threads,
                "threaded": threaded.as_ref().map(|t| t.json(hz)),
                "thread_speedup_wall": thread_speedup,
                "methods": approx.iter().map(|(m, r)| serde_json::json!({
                    "method": m.name(),
                    "result": r.json(hz),
                    "speedup_over_fast": fast.secs() / r.secs(),
                })).collect::<Vec<_>>(),
                "isa": VectorIsa::best().name(),
                "isas": isa_rows.iter().map(|(isa, r)| serde_json::json!({
                    "isa": isa.name(),
                    "result": r.json(hz),
                    "speedup_over_fast": fast.secs() / r.secs(),
                })).collect::<Vec<_>>(),
                "counters_match": same,
            }));
        } else {
            let opt =
                |v: Option<f64>, prec: usize| v.map_or("-".to_owned(), |v| format!("{v:.prec$}"));
            let threads_label = format!("{} thr", o.threads);
            let mut rows = vec![
                ("fast", &fast, format!("{speedup:.2}x")),
                ("reference", &reference, String::new()),
                (
                    "binary",
                    &from_binary,
                    format!("{:.2}x/f", fast.secs() / from_binary.secs()),
                ),
            ];
            if let (Some(t), Some(up)) = (&threaded, thread_speedup) {
                rows.push((threads_label.as_str(), t, format!("{up:.2}x/1")));
            }
            for (m, r) in &approx {
                rows.push((m.name(), r, format!("{:.2}x/f", fast.secs() / r.secs())));
            }
            for (isa, r) in &isa_rows {
                rows.push((isa.name(), r, format!("{:.2}x/f", fast.secs() / r.secs())));
            }
            for (label, r, up) in rows {
                let name = if label == "fast" {
                    scene.name.as_str()
                } else {
                    ""
                };
                println!(
                    "{:<34} {:<13} {:>9.2} {:>9.4} {:>8.2} {:>8} {:>9} {:>11} {:>9}",
                    name,
                    label,
                    r.mpix(),
                    r.mtri(),
                    r.ns_per_pixel().unwrap_or(0.0),
                    opt(r.cycles_per_pixel(hz), 1),
                    up,
                    r.stats.pixels_in,
                    r.stats.triangles
                );
            }
            if !same {
                println!("  COUNTERS DIFFER between the fast and the reference path");
            }
        }
    }
    if o.json {
        let doc = serde_json::json!({
            "iters": o.iters.max(1),
            "timer": timer,
            "clock_hz": clock.map(|(hz, _)| hz),
            "clock_source": clock.map(|(_, from)| from),
            "scenes": json_scenes,
        });
        println!(
            "{}",
            serde_json::to_string_pretty(&doc).map_err(|e| e.to_string())?
        );
    }
    if all_match {
        Ok(())
    } else {
        Err("the fast and the reference path counted differently".to_owned())
    }
}

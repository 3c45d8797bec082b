//! `voodoo bench --chart DIR`: every trace of the repository replayed with every method
//! (`sst1_board::Method`) in one run, and what each method costs and gives up against the
//! exact fast path:
//!
//! - `table.md`, `table.csv`, `table.json`: per trace and method, Mpix/s (`fbiPixelsIn`
//!   per second of the replaying thread's CPU time, one render thread, best of `iters`
//!   rounds that run every method in turn),
//!   the speed-up over `exact`, the share of pixels identical to `exact`, PSNR and the
//!   largest per-channel error (8-bit channels, RGB565 expanded by bit replication);
//! - `stability.md` / `stability.csv`: the same errors per step of each stability family
//!   (`traces/stability`), with the swept value;
//! - `speed_vs_accuracy.png`: one point per approximate method and trace of at least a
//!   million pixels, speed-up against PSNR; `error_histogram.png`: per method, the share of pixels at each size of
//!   error; `error_map.png`: where the worst method's errors fall on the worst trace;
//!   `stability.png`: per family, each method's share of differing pixels per step.
//!
//! Pixels compared are those of every colour dump the trace takes (front or back; depth
//! dumps are not colours), or the final front buffer when it takes none.

use std::path::{Path, PathBuf};

use sst1_board::{Board, BufferKind, Method};
use sst1_trace::scenes::stability;
use sst1_trace::{execute, load_trace, rgb565_to_rgb8, write_file_replacing, DumpBuffer, Trace};

use crate::bench::thread_cpu_time;
use crate::plot::{Area, Canvas, METHOD_COLOURS};

/// The folders of `traces/` whose traces the chart replays, with the group name used in
/// the table.
pub const TRACE_DIRS: [(&str, &str); 5] = [
    ("conformance", "conformance/traces"),
    ("glide-sdk", "glide-sdk/traces"),
    ("examples", "examples"),
    ("generated", "generated"),
    ("stability", "stability"),
];

/// Error buckets of the histogram: the largest channel error of a differing pixel is at
/// most `HIST_EDGES[k]` (and above the previous edge).
pub const HIST_EDGES: [u8; 8] = [2, 4, 8, 16, 32, 64, 128, 255];

/// How one method's pixels compare with the exact path's.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Accuracy {
    /// Pixels compared.
    pub pixels: u64,
    /// Pixels identical in all three channels.
    pub identical: u64,
    /// Sum of squared channel errors (8-bit channels).
    pub sq_err: f64,
    /// Largest channel error.
    pub max_err: u8,
    /// Differing pixels by their largest channel error ([`HIST_EDGES`]).
    pub hist: [u64; 8],
}

impl Accuracy {
    /// Adds the comparison of `got` with `exact` (RGB565 values; extra values of the
    /// longer one count as differing by their full value against black).
    pub fn add(&mut self, exact: &[u16], got: &[u16]) {
        for i in 0..exact.len().max(got.len()) {
            let a = rgb565_to_rgb8(exact.get(i).copied().unwrap_or(0));
            let b = rgb565_to_rgb8(got.get(i).copied().unwrap_or(0));
            let mut worst = 0u8;
            for ch in 0..3 {
                let e = a[ch].abs_diff(b[ch]);
                worst = worst.max(e);
                self.sq_err += f64::from(e) * f64::from(e);
            }
            let same = exact.get(i) == got.get(i);
            self.pixels += 1;
            if same {
                self.identical += 1;
            } else {
                let bucket = HIST_EDGES.iter().position(|&e| worst <= e).unwrap_or(7);
                self.hist[bucket] += 1;
            }
            self.max_err = self.max_err.max(worst);
        }
    }

    /// The sum of two comparisons.
    pub fn merge(&mut self, other: &Accuracy) {
        self.pixels += other.pixels;
        self.identical += other.identical;
        self.sq_err += other.sq_err;
        self.max_err = self.max_err.max(other.max_err);
        for (a, b) in self.hist.iter_mut().zip(&other.hist) {
            *a += b;
        }
    }

    /// Share of identical pixels, 0..=1 (1 with no pixels).
    pub fn identical_share(&self) -> f64 {
        if self.pixels == 0 {
            1.0
        } else {
            self.identical as f64 / self.pixels as f64
        }
    }

    /// PSNR in dB over the RGB channels (peak 255); `None` where every pixel is identical.
    pub fn psnr(&self) -> Option<f64> {
        if self.sq_err == 0.0 || self.pixels == 0 {
            return None;
        }
        let mse = self.sq_err / (3.0 * self.pixels as f64);
        Some(10.0 * (255.0 * 255.0 / mse).log10())
    }
}

/// One row of the table: a method on a trace.
#[derive(Clone, Debug)]
pub struct Row {
    /// The group of [`TRACE_DIRS`] (or `given`).
    pub group: String,
    pub trace: String,
    pub method: Method,
    /// `fbiPixelsIn` of the replay.
    pub pixels_in: u64,
    /// CPU seconds of the best replay.
    pub secs: f64,
    /// Speed-up over `exact` on the same trace (its seconds over these).
    pub speedup: f64,
    pub accuracy: Accuracy,
}

impl Row {
    /// Mpix/s.
    pub fn mpix(&self) -> f64 {
        self.pixels_in as f64 / self.secs.max(1e-9) / 1e6
    }
}

/// One step of a stability family for one method.
#[derive(Clone, Debug)]
pub struct StabilityRow {
    pub family: String,
    pub step: usize,
    /// The swept value of the step.
    pub value: f64,
    pub method: Method,
    pub accuracy: Accuracy,
}

/// The table as markdown.
pub fn table_markdown(rows: &[Row]) -> String {
    let mut s = String::from(
        "| group | trace | method | Mpix/s | speed-up | identical | PSNR dB | max error |\n\
         |---|---|---|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        s.push_str(&format!(
            "| {} | `{}` | {} | {:.2} | {:.2}x | {:.4} % | {} | {} |\n",
            r.group,
            r.trace,
            r.method,
            r.mpix(),
            r.speedup,
            100.0 * r.accuracy.identical_share(),
            r.accuracy
                .psnr()
                .map_or("identical".to_owned(), |p| format!("{p:.1}")),
            r.accuracy.max_err
        ));
    }
    s
}

/// The table as CSV (PSNR empty where identical).
pub fn table_csv(rows: &[Row]) -> String {
    let mut s = String::from(
        "group,trace,method,pixels_in,cpu_s,mpix_per_s,speedup,pixels,identical,psnr_db,max_error\n",
    );
    for r in rows {
        s.push_str(&format!(
            "{},{},{},{},{:.6},{:.3},{:.4},{},{},{},{}\n",
            r.group,
            r.trace,
            r.method,
            r.pixels_in,
            r.secs,
            r.mpix(),
            r.speedup,
            r.accuracy.pixels,
            r.accuracy.identical,
            r.accuracy
                .psnr()
                .map_or(String::new(), |p| format!("{p:.3}")),
            r.accuracy.max_err
        ));
    }
    s
}

/// The table as JSON.
pub fn table_json(rows: &[Row], stab: &[StabilityRow]) -> serde_json::Value {
    let acc = |a: &Accuracy| {
        serde_json::json!({
            "pixels": a.pixels,
            "identical": a.identical,
            "identical_share": a.identical_share(),
            "psnr_db": a.psnr(),
            "max_error": a.max_err,
            "histogram": a.hist,
        })
    };
    serde_json::json!({
        "histogram_edges": HIST_EDGES,
        "rows": rows.iter().map(|r| serde_json::json!({
            "group": r.group,
            "trace": r.trace,
            "method": r.method.name(),
            "pixels_in": r.pixels_in,
            "cpu_s": r.secs,
            "mpix_per_s": r.mpix(),
            "speedup": r.speedup,
            "accuracy": acc(&r.accuracy),
        })).collect::<Vec<_>>(),
        "stability": stab.iter().map(|r| serde_json::json!({
            "family": r.family,
            "step": r.step,
            "value": r.value,
            "method": r.method.name(),
            "accuracy": acc(&r.accuracy),
        })).collect::<Vec<_>>(),
    })
}

/// The stability table as markdown: per family and step, each approximate method's share
/// of differing pixels and largest channel error.
pub fn stability_markdown(rows: &[StabilityRow]) -> String {
    let methods: Vec<Method> = Method::ALL
        .into_iter()
        .filter(|m| *m != Method::Exact)
        .collect();
    let mut s = String::from("| family | step | value |");
    for m in &methods {
        s.push_str(&format!(" {m} differ / max |"));
    }
    s.push_str("\n|---|---:|---:|");
    for _ in &methods {
        s.push_str("---:|");
    }
    s.push('\n');
    let mut keys: Vec<(String, usize, f64)> = Vec::new();
    for r in rows {
        if !keys.iter().any(|k| k.0 == r.family && k.1 == r.step) {
            keys.push((r.family.clone(), r.step, r.value));
        }
    }
    for (family, step, value) in keys {
        s.push_str(&format!("| {family} | {step} | {value} |"));
        for m in &methods {
            match rows
                .iter()
                .find(|r| r.family == family && r.step == step && r.method == *m)
            {
                Some(r) => s.push_str(&format!(
                    " {:.2} % / {} |",
                    100.0 * (1.0 - r.accuracy.identical_share()),
                    r.accuracy.max_err
                )),
                None => s.push_str(" - |"),
            }
        }
        s.push('\n');
    }
    s
}

/// The stability table as CSV.
pub fn stability_csv(rows: &[StabilityRow]) -> String {
    let mut s = String::from("family,step,value,method,pixels,identical,psnr_db,max_error\n");
    for r in rows {
        s.push_str(&format!(
            "{},{},{},{},{},{},{},{}\n",
            r.family,
            r.step,
            r.value,
            r.method,
            r.accuracy.pixels,
            r.accuracy.identical,
            r.accuracy
                .psnr()
                .map_or(String::new(), |p| format!("{p:.3}")),
            r.accuracy.max_err
        ));
    }
    s
}

/// The colour dumps of one replay (name, width, values) and its cost.
struct Replay {
    dumps: Vec<(String, u32, Vec<u16>)>,
    secs: f64,
    pixels_in: u64,
}

/// Replays `trace` once with `method` on one render thread; the colour dumps are kept
/// only with `keep` (the pixels are the same on every run).
fn replay(trace: &Trace, method: Method, keep: bool) -> Replay {
    let mut board = Board::new(trace.board_config());
    board.set_method(method);
    board.set_threads(1);
    let cpu0 = thread_cpu_time();
    let wall0 = std::time::Instant::now();
    let dumps = execute(&trace.ops, &mut board, |_| {});
    let secs = match (thread_cpu_time(), cpu0) {
        (Some(b), Some(a)) => b.saturating_sub(a).as_secs_f64(),
        _ => wall0.elapsed().as_secs_f64(),
    };
    let mut colour: Vec<(String, u32, Vec<u16>)> = Vec::new();
    if keep {
        colour = dumps
            .into_iter()
            .filter(|d| matches!(d.buffer, DumpBuffer::Front | DumpBuffer::Back))
            .map(|d| (d.file, d.width, d.data))
            .collect();
        if colour.is_empty() {
            let (w, _) = board.display_size();
            colour.push((
                "final front".to_owned(),
                w,
                board.dump_buffer(BufferKind::Front),
            ));
        }
    }
    Replay {
        dumps: colour,
        secs,
        pixels_in: board.stats().pixels_in,
    }
}

/// Every method on `trace`, `iters` rounds of one replay per method in turn (so that a
/// change in the machine's load falls on every method alike), keeping each method's
/// fastest CPU time: in [`Method::ALL`] order.
fn replay_all(trace: &Trace, iters: u32) -> Vec<Replay> {
    let mut best: Vec<Replay> = Method::ALL
        .iter()
        .map(|&m| replay(trace, m, true))
        .collect();
    for _ in 1..iters.max(1) {
        for (slot, &m) in best.iter_mut().zip(Method::ALL.iter()) {
            let again = replay(trace, m, false);
            slot.secs = slot.secs.min(again.secs);
        }
    }
    best
}

/// The traces to chart: `given` (each in the group of its folder's name), or every trace of [`TRACE_DIRS`] under `root`, sorted
/// within each group.
fn chart_traces(root: &Path, given: &[PathBuf]) -> Vec<(String, PathBuf)> {
    if !given.is_empty() {
        // A given trace's group is its folder's name (`stability` for the families).
        return given
            .iter()
            .map(|p| {
                let group = p
                    .parent()
                    .and_then(|d| d.file_name())
                    .map_or("given".to_owned(), |d| d.to_string_lossy().into_owned());
                (group, p.clone())
            })
            .collect();
    }
    let mut out = Vec::new();
    for (group, dir) in TRACE_DIRS {
        let Ok(entries) = std::fs::read_dir(root.join(dir)) else {
            continue;
        };
        let mut paths: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.file_name()
                    .is_some_and(|f| f.to_string_lossy().contains(".trace"))
            })
            .collect();
        paths.sort();
        out.extend(paths.into_iter().map(|p| (group.to_owned(), p)));
    }
    out
}

/// The trace's name: its file name up to the first dot.
fn stem(path: &Path) -> String {
    path.file_name()
        .map_or(String::new(), |f| f.to_string_lossy().into_owned())
        .split('.')
        .next()
        .unwrap_or_default()
        .to_owned()
}

/// The worst (method, trace, dump) so far and its error picture.
struct Worst {
    psnr: f64,
    label: String,
    map: Option<Canvas>,
}

/// A picture of where `got` differs from `exact`: the exact frame dimmed to grey, each
/// differing pixel coloured from yellow (1) to red (128 and more) by the bit length of
/// its largest channel error.
pub fn error_map(exact: &[u16], got: &[u16], width: u32) -> Canvas {
    let width = width.max(1);
    let height = (exact.len() as u32).div_ceil(width).max(1);
    let mut c = Canvas::new(width, height);
    for (i, &e) in exact.iter().enumerate() {
        let (x, y) = ((i as u32 % width) as i64, (i as u32 / width) as i64);
        let a = rgb565_to_rgb8(e);
        let b = rgb565_to_rgb8(got.get(i).copied().unwrap_or(0));
        let err = (0..3).map(|ch| a[ch].abs_diff(b[ch])).max().unwrap_or(0);
        let colour = if err == 0 {
            let g = ((u32::from(a[0]) + u32::from(a[1]) + u32::from(a[2])) / 6 + 40) as u8;
            [g, g, g]
        } else {
            // By the error's bit length: 1 -> yellow, 128 and more -> red.
            let k = ((8 - err.leading_zeros()) * 255 / 8) as u8;
            [255, 255 - k, 0]
        };
        c.put(x, y, colour);
    }
    c
}

/// What `--chart` does.
pub struct ChartOptions<'a> {
    pub dir: &'a Path,
    /// The repository's `traces` folder.
    pub root: PathBuf,
    /// Traces to chart instead of the repository's.
    pub given: &'a [PathBuf],
    pub iters: u32,
}

/// Runs the chart and writes its files into `o.dir`.
pub fn chart(o: &ChartOptions<'_>) -> Result<(), String> {
    std::fs::create_dir_all(o.dir).map_err(|e| format!("{}: {e}", o.dir.display()))?;
    let traces = chart_traces(&o.root, o.given);
    if traces.is_empty() {
        return Err(format!("no traces found under {}", o.root.display()));
    }
    let mut rows = Vec::new();
    let mut stab = Vec::new();
    let mut worst = Worst {
        psnr: f64::INFINITY,
        label: String::new(),
        map: None,
    };
    for (group, path) in &traces {
        let trace = load_trace(path).map_err(|e| e.to_string())?;
        let name = stem(path);
        let runs = replay_all(&trace, o.iters);
        let exact = &runs[0];
        let family = (group == "stability")
            .then(|| stability::family(&name))
            .flatten();
        for (method, got) in Method::ALL.into_iter().zip(&runs) {
            let mut total = Accuracy::default();
            for (k, ((file, width, e), (_, _, g))) in exact.dumps.iter().zip(&got.dumps).enumerate()
            {
                let mut a = Accuracy::default();
                a.add(e, g);
                // The stability scenes break methods on purpose (their own chart shows
                // them): the error picture is of the worst other trace.
                let candidate = !method.is_exact() && family.is_none();
                if let (Some(p), true) = (a.psnr(), candidate) {
                    if p < worst.psnr {
                        worst = Worst {
                            psnr: p,
                            label: format!("{method} on {name}, {file}"),
                            map: Some(error_map(e, g, *width)),
                        };
                    }
                }
                if let Some(f) = family {
                    stab.push(StabilityRow {
                        family: f.name.to_owned(),
                        step: k,
                        value: f.values.get(k).copied().unwrap_or(f64::NAN),
                        method,
                        accuracy: a.clone(),
                    });
                }
                total.merge(&a);
            }
            rows.push(Row {
                group: group.clone(),
                trace: name.clone(),
                method,
                pixels_in: got.pixels_in,
                secs: got.secs,
                speedup: exact.secs / got.secs.max(1e-9),
                accuracy: total,
            });
        }
        eprintln!("charted {name}");
    }
    let write = |file: &str, bytes: &[u8]| {
        write_file_replacing(&o.dir.join(file), bytes).map_err(|e| e.to_string())
    };
    write("table.md", table_markdown(&rows).as_bytes())?;
    write("table.csv", table_csv(&rows).as_bytes())?;
    let json =
        serde_json::to_string_pretty(&table_json(&rows, &stab)).map_err(|e| e.to_string())?;
    write("table.json", (json + "\n").as_bytes())?;
    write("stability.md", stability_markdown(&stab).as_bytes())?;
    write("stability.csv", stability_csv(&stab).as_bytes())?;
    write("speed_vs_accuracy.png", &speed_chart(&rows).png()?)?;
    write("error_histogram.png", &histogram_chart(&rows).png()?)?;
    write("stability.png", &stability_chart(&stab).png()?)?;
    if let Some(map) = &worst.map {
        write("error_map.png", &map.png()?)?;
        write(
            "error_map.txt",
            format!("{}: PSNR {:.2} dB\n", worst.label, worst.psnr).as_bytes(),
        )?;
    }
    println!(
        "wrote table.md, table.csv, table.json, stability.md, stability.csv and the charts to {} ({} traces, {} methods)",
        o.dir.display(),
        traces.len(),
        Method::ALL.len()
    );
    Ok(())
}

/// The legend: a colour swatch and name per method, from `(x, y)` down.
fn legend(c: &mut Canvas, x: i64, y: i64, methods: &[Method]) {
    for (i, m) in methods.iter().enumerate() {
        let colour = METHOD_COLOURS[Method::ALL.iter().position(|a| a == m).unwrap_or(0)];
        let yy = y + 16 * i as i64;
        c.rect(x, yy, x + 10, yy + 9, colour);
        c.text(x + 16, yy, m.name(), [40, 40, 40]);
    }
}

/// The approximate methods and the reference path: what the charts plot against `exact`.
fn plotted() -> Vec<Method> {
    Method::ALL
        .into_iter()
        .filter(|m| *m != Method::Exact)
        .collect()
}

/// The fewest pixels a trace draws for its point in [`speed_chart`]: shorter replays
/// take milliseconds, too short to time on a shared machine.
pub const SPEED_CHART_MIN_PIXELS: u64 = 1_000_000;

/// Speed-up over `exact` (log2 axis, 1/4x to 4x) against PSNR (10 to 70 dB; identical
/// at the top line), one point per method and trace of at least
/// [`SPEED_CHART_MIN_PIXELS`].
pub fn speed_chart(rows: &[Row]) -> Canvas {
    let mut c = Canvas::new(900, 560);
    let a = Area {
        x0: 70,
        y0: 40,
        x1: 680,
        y1: 500,
        xr: (-2.0, 2.0),
        yr: (10.0, 75.0),
    };
    let xt: Vec<(f64, String)> = [
        (-2.0, "1/4X"),
        (-1.0, "1/2X"),
        (0.0, "1X"),
        (1.0, "2X"),
        (2.0, "4X"),
    ]
    .iter()
    .map(|(v, s)| (*v, (*s).to_owned()))
    .collect();
    let mut yt: Vec<(f64, String)> = (1..=7)
        .map(|k| (f64::from(k) * 10.0, format!("{}", k * 10)))
        .collect();
    yt.push((75.0, "=".to_owned()));
    a.frame(
        &mut c,
        &xt,
        &yt,
        "SPEED-UP OVER EXACT (X) AGAINST PSNR DB (= IDENTICAL)",
    );
    for r in rows
        .iter()
        .filter(|r| r.method != Method::Exact && r.pixels_in >= SPEED_CHART_MIN_PIXELS)
    {
        let colour = METHOD_COLOURS[Method::ALL.iter().position(|m| *m == r.method).unwrap_or(0)];
        let y = r.accuracy.psnr().unwrap_or(75.0);
        let (px, py) = a.at(r.speedup.max(1e-6).log2(), y);
        c.marker(px, py, 2, colour);
    }
    legend(&mut c, 700, 60, &plotted());
    c
}

/// Per method, the share of all its pixels at each size of error (log10 axis, 10^-7 to
/// 1): the bars are the buckets of [`HIST_EDGES`], left to right.
pub fn histogram_chart(rows: &[Row]) -> Canvas {
    let methods = plotted();
    let panel = 170;
    let mut c = Canvas::new(70 + panel * methods.len() as u32 + 20, 420);
    for (i, m) in methods.iter().enumerate() {
        let mut total = Accuracy::default();
        for r in rows.iter().filter(|r| r.method == *m) {
            total.merge(&r.accuracy);
        }
        let x0 = 70 + (panel as i64) * i as i64;
        let a = Area {
            x0,
            y0: 40,
            x1: x0 + panel as i64 - 20,
            y1: 360,
            xr: (0.0, 8.0),
            yr: (-7.0, 0.0),
        };
        let yt: Vec<(f64, String)> = if i == 0 {
            (0..=7)
                .map(|k| (-f64::from(k), format!("1E-{k}")))
                .collect()
        } else {
            Vec::new()
        };
        let xt = [
            (0.5, "2".to_owned()),
            (3.5, "16".to_owned()),
            (7.5, "255".to_owned()),
        ];
        a.frame(&mut c, &xt, &yt, m.name());
        let colour = METHOD_COLOURS[Method::ALL.iter().position(|a| a == m).unwrap_or(0)];
        for (k, &n) in total.hist.iter().enumerate() {
            if n == 0 || total.pixels == 0 {
                continue;
            }
            let share = (n as f64 / total.pixels as f64).log10();
            let (l, top) = a.at(k as f64 + 0.1, share);
            let (r, bottom) = a.at(k as f64 + 0.9, -7.0);
            c.rect(l, top, r, bottom, colour);
        }
    }
    c.text(
        70,
        390,
        "SHARE OF PIXELS BY LARGEST CHANNEL ERROR: <=2 <=4 <=8 <=16 <=32 <=64 <=128 <=255",
        [40, 40, 40],
    );
    c
}

/// Per stability family, each plotted method's share of differing pixels (0 to 100 %)
/// at each step of the sweep (easy on the left).
pub fn stability_chart(rows: &[StabilityRow]) -> Canvas {
    let mut families: Vec<String> = Vec::new();
    for r in rows {
        if !families.contains(&r.family) {
            families.push(r.family.clone());
        }
    }
    let (cols, pw, ph) = (5i64, 230i64, 200i64);
    let nrows = (families.len() as i64 + cols - 1) / cols;
    let mut c = Canvas::new(
        (60 + cols * pw + 160) as u32,
        (30 + nrows.max(1) * (ph + 50)) as u32,
    );
    for (i, family) in families.iter().enumerate() {
        let (col, row) = (i as i64 % cols, i as i64 / cols);
        let steps = rows
            .iter()
            .filter(|r| &r.family == family)
            .map(|r| r.step)
            .max()
            .unwrap_or(0);
        let x0 = 60 + col * pw;
        let y0 = 40 + row * (ph + 50);
        let a = Area {
            x0,
            y0,
            x1: x0 + pw - 30,
            y1: y0 + ph - 20,
            xr: (0.0, steps.max(1) as f64),
            yr: (0.0, 100.0),
        };
        let yt: Vec<(f64, String)> = if col == 0 {
            [0.0, 50.0, 100.0]
                .iter()
                .map(|v| (*v, format!("{v}%")))
                .collect()
        } else {
            Vec::new()
        };
        let xt: Vec<(f64, String)> = (0..=steps).map(|k| (k as f64, k.to_string())).collect();
        a.frame(&mut c, &xt, &yt, family);
        for m in plotted() {
            let colour = METHOD_COLOURS[Method::ALL.iter().position(|a| *a == m).unwrap_or(0)];
            let mut pts: Vec<(usize, f64)> = rows
                .iter()
                .filter(|r| &r.family == family && r.method == m)
                .map(|r| (r.step, 100.0 * (1.0 - r.accuracy.identical_share())))
                .collect();
            pts.sort_by_key(|p| p.0);
            let mut last: Option<(i64, i64)> = None;
            for (step, v) in pts {
                let p = a.at(step as f64, v);
                if let Some(q) = last {
                    c.line(q, p, colour);
                }
                c.marker(p.0, p.1, 2, colour);
                last = Some(p);
            }
        }
    }
    legend(&mut c, 60 + cols * pw, 40, &plotted());
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rgb(r: u16, g: u16, b: u16) -> u16 {
        (r << 11) | (g << 5) | b
    }

    #[test]
    fn accuracy_counts_identical_pixels_errors_and_psnr() {
        let exact = [rgb(0, 0, 0), rgb(31, 63, 31), rgb(16, 32, 16), rgb(1, 0, 0)];
        let got = [rgb(0, 0, 0), rgb(31, 63, 31), rgb(16, 33, 16), rgb(0, 0, 0)];
        let mut a = Accuracy::default();
        a.add(&exact, &got);
        assert_eq!((a.pixels, a.identical), (4, 2));
        // Green 32 -> 130, 33 -> 134: 4; red 1 -> 8 against 0: 8.
        assert_eq!(a.max_err, 8);
        assert_eq!(a.hist, [0, 1, 1, 0, 0, 0, 0, 0]);
        assert_eq!(a.sq_err, 16.0 + 64.0);
        let mse = 80.0 / 12.0;
        let psnr = a.psnr().unwrap();
        assert!(
            (psnr - 10.0 * (65025.0f64 / mse).log10()).abs() < 1e-9,
            "{psnr}"
        );
        assert_eq!(a.identical_share(), 0.5);
        // A missing pixel differs from its value against black; identical has no PSNR.
        let mut b = Accuracy::default();
        b.add(&[rgb(0, 0, 0)], &[rgb(0, 0, 0)]);
        assert_eq!(b.psnr(), None);
        b.add(&[rgb(0, 0, 0)], &[]);
        assert_eq!((b.pixels, b.identical), (2, 1));
        b.merge(&a);
        assert_eq!((b.pixels, b.identical, b.max_err), (6, 3, 8));
    }

    #[test]
    fn tables_name_every_row_in_each_form() {
        let mut acc = Accuracy::default();
        acc.add(&[rgb(1, 0, 0), 0], &[0, 0]);
        let rows = vec![
            Row {
                group: "stability".into(),
                trace: "persp".into(),
                method: Method::Exact,
                pixels_in: 2_000_000,
                secs: 2.0,
                speedup: 1.0,
                accuracy: Accuracy {
                    pixels: 2,
                    identical: 2,
                    ..Accuracy::default()
                },
            },
            Row {
                group: "stability".into(),
                trace: "persp".into(),
                method: Method::Nearest,
                pixels_in: 2_000_000,
                secs: 1.0,
                speedup: 2.0,
                accuracy: acc.clone(),
            },
        ];
        let md = table_markdown(&rows);
        assert_eq!(
            md.lines().nth(2),
            Some("| stability | `persp` | exact | 1.00 | 1.00x | 100.0000 % | identical | 0 |")
        );
        assert_eq!(
            md.lines().nth(3),
            Some("| stability | `persp` | nearest | 2.00 | 2.00x | 50.0000 % | 37.9 | 8 |")
        );
        let csv = table_csv(&rows);
        assert_eq!(
            csv.lines().nth(2),
            Some("stability,persp,nearest,2000000,1.000000,2.000,2.0000,2,1,37.851,8")
        );
        let json = table_json(&rows, &[]);
        assert_eq!(json["rows"][1]["method"], "nearest");
        assert_eq!(
            json["rows"][0]["accuracy"]["psnr_db"],
            serde_json::Value::Null
        );
        let stab = vec![StabilityRow {
            family: "lod".into(),
            step: 3,
            value: 8.0,
            method: Method::FloatDivide,
            accuracy: acc,
        }];
        let md = stability_markdown(&stab);
        assert_eq!(
            md.lines().nth(2),
            Some("| lod | 3 | 8 | - | - | - | 50.00 % / 8 | - |")
        );
        assert_eq!(
            stability_csv(&stab).lines().nth(1),
            Some("lod,3,8,float-divide,2,1,37.851,8")
        );
        // The charts draw on small inputs without panicking, at their fixed sizes.
        assert_eq!(speed_chart(&rows).img.dimensions(), (900, 560));
        assert_eq!(stability_chart(&stab).img.width(), 60 + 5 * 230 + 160);
        assert_eq!(histogram_chart(&rows).img.height(), 420);
        let map = error_map(&[rgb(1, 0, 0), 0], &[0, 0], 2);
        // An error of 8 is 4 bits long: half-way from yellow to red.
        assert_eq!(map.img.get_pixel(0, 0).0, [255, 128, 0]);
    }
}

//! `voodoo`: replay SST-1 register traces, inspect and convert them, decode registers.
//!
//! Trace formats are those of the `sst1-trace` crate: the plain-text write-log
//! (`shared/docs/trace-text-format.md`) and our binary form, either gzip-compressed.
//!
//! Hostile input is expected: `replay`, `check` and `info` stream the trace (memory does not
//! grow with its length or its number of dumps), every file read whole is read with a
//! limit, and every file written goes through a temporary file renamed into place (see
//! `sst1_trace::output`); dumps go to a fresh folder unless `--out` names one.

mod bench;
mod chart;
mod demo;
mod play;
mod plot;
mod why;

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use sst1_board::{AccuracyProfile, Board, BufferKind, Method, Reference, VectorIsa};
use sst1_regs::map;
use sst1_trace::judge;
use sst1_trace::text::parse_number;
use sst1_trace::{
    encode_binary, execute_references_stream, execute_trace_stream, load_trace, open_trace, quote,
    read_file_bounded, rgb565_to_rgb8, vote_buffer, write_file_replacing, write_text, Dump,
    DumpDir, OpCounts, ReplayError, TraceOp, TraceStream,
};

#[derive(Parser)]
#[command(
    name = "voodoo",
    version,
    about = "3dfx Voodoo Graphics (SST-1) emulator tools"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Replay a trace: write its dumps and, optionally, the displayed buffer as PNG.
    Replay {
        /// Trace file: text or binary, optionally gzip-compressed.
        trace: PathBuf,
        /// Folder for the trace's dump files (created if missing). A dump replaces only
        /// an earlier dump there (a regular file with no other link), never follows a
        /// link and never opens a FIFO. Default: a new folder in the current one, named
        /// after the trace (`NAME-dumps`, or `NAME-dumps-2`, … if taken), made at the
        /// first dump.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Write the front (displayed) buffer at the end as a PNG.
        #[arg(long)]
        png: Option<PathBuf>,
        /// The model of the board: `hardware` (the default) is our reading of the SST-1;
        /// `mame`, `dosbox-staging` and `86box` are one board each with that reference
        /// emulator's behaviour; `vote` replays the trace once per reference emulator and
        /// keeps, per pixel, the value two of them write (the conformance pass rule; three
        /// times the work, on three threads).
        #[arg(long, value_enum)]
        model: Option<Model>,
        /// Print the pixel and command counters at the end, and the modelled hardware
        /// time in graphics-clock cycles, in all and per frame (docs/timing.md; with
        /// `--model vote`: those of the MAME-model board).
        #[arg(long)]
        stats: bool,
        /// Write the counters as JSON to this file, with `clock_hz`, `cycles` and
        /// `frames` (one object per swap with its `cycles`).
        #[arg(long, value_name = "FILE")]
        stats_json: Option<PathBuf>,
        /// Accuracy profile as JSON (at most 1 MiB) for experiments on a one-board model:
        /// the switches to change from that model's, e.g.
        /// `{"pixel": {"blend": {"arithmetic": "Mame"}}}` (see docs/accuracy.md).
        #[arg(long, value_name = "FILE")]
        profile: Option<PathBuf>,
        /// Render threads for large triangles (bands of rows; the output is the
        /// same for every count). Default: the machine's cores.
        #[arg(long, value_name = "N")]
        threads: Option<usize>,
        /// Run without the timing model (one-board models only): the same pixels and
        /// counters, no cycles counted, `status` always idle (docs/timing.md: what the
        /// model costs).
        #[arg(long)]
        no_timing: bool,
        /// Save the whole board's state to FILE once the first OP ops of the trace have
        /// run (docs/save-states.md); the replay goes on to the end. One-board models only.
        #[arg(long, num_args = 2, value_names = ["OP", "FILE"])]
        save_at: Option<Vec<String>>,
        /// Start from the board state in FILE (written by `--save-at`) instead of a fresh
        /// board, and replay the trace from the op after the one the state was saved at.
        /// The model, the profile and the timing switch are the state's: `--model`,
        /// `--profile` and `--no-timing` are refused with it.
        #[arg(long, value_name = "FILE")]
        resume: Option<PathBuf>,
        /// How to draw (one-board models only): `exact`, the default, and `reference` are
        /// the exact paths (span kernels; pixel by pixel); the others approximate the
        /// texture stages for speed, each giving up what its line says (docs/methods.md).
        #[arg(long, value_enum, value_name = "NAME")]
        method: Option<MethodArg>,
        /// The copy of the span kernels to run (one-board models; only the hardware model
        /// has the vector copies): `baseline`, `avx2` or `avx512`, capped by what the CPU
        /// has. Every copy gives the same output. Default: the best the CPU has.
        #[arg(long, value_name = "ISA")]
        isa: Option<VectorIsa>,
    },
    /// Replay a trace on a model (default: the hardware model) and judge each of its dumps
    /// against reference emulators' goldens with the conformance pass rule: every pixel
    /// where all goldens agree must match (consensus), and every pixel where two of three
    /// agree (majority). Prints both counts per dump; exits with status 1 if a pixel
    /// fails, if the goldens folder is missing, or if a dump has fewer than two goldens.
    Check {
        /// Trace file: text or binary, optionally gzip-compressed.
        trace: PathBuf,
        /// Folder with one folder of golden dumps per reference emulator (`mame`,
        /// `dosbox-staging`, `86box`), each dump named as the trace names it, as `.raw`
        /// or `.raw.gz` (the layout of `traces/conformance/golden`).
        #[arg(long, value_name = "DIR")]
        goldens: PathBuf,
        /// As for `replay`.
        #[arg(long, value_enum)]
        model: Option<Model>,
        /// As for `replay`.
        #[arg(long, value_name = "FILE")]
        profile: Option<PathBuf>,
    },
    /// Draw the demo scene through the Glide 3 front-end (mipmapped textures, a light
    /// map, fog, transparency) and write the picture as a PNG.
    Demo {
        /// Where to write the picture.
        #[arg(long, default_value = "voodoo-demo.png")]
        png: PathBuf,
        /// Only write the PNG: no window, even where a display exists.
        #[arg(long)]
        no_window: bool,
    },
    /// Play a trace in a window: step by frame or by drawing command, show the front,
    /// back or depth buffer of each model, mark where it breaks golden dumps (keys in the
    /// title bar).
    Play {
        /// Trace file: text or binary, optionally gzip-compressed.
        trace: PathBuf,
        /// Golden dumps to mark differences to: `check`'s folder (one folder per
        /// reference), or a folder of the dumps themselves.
        #[arg(long, value_name = "DIR")]
        goldens: Option<PathBuf>,
        /// The model shown first (M cycles through them).
        #[arg(long, value_enum, default_value = "hardware")]
        model: Model,
    },
    /// Summarise a trace: board, writes, triangles, fills, swaps, registers touched.
    Info {
        /// Trace file: text or binary, optionally gzip-compressed.
        trace: PathBuf,
    },
    /// Decode a register value by name (`fbzMode`) or byte offset (`0x110`).
    Reg {
        /// Register name or byte offset (hex with 0x, or decimal).
        register: String,
        /// The 32-bit value (hex with 0x, or decimal).
        value: String,
    },
    /// Write a generated scene (`sst1_trace::scenes`), seeded and deterministic, as a
    /// text trace: to stdout, or to `--out FILE` (gzip if the name ends in `.gz`).
    Gen {
        /// Which scene.
        #[arg(value_enum)]
        scene: SceneKind,
        /// Seed of the generator: the same seed and options give the same trace.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Triangles (small-tris, small-tex-tris; default 20000) or drawing states
        /// (random-states, default 200; heavy-states, default 12).
        #[arg(long)]
        count: Option<u32>,
        /// TMUs on the board (random-states, heavy-states), 1 to 3.
        #[arg(long, default_value_t = 2)]
        tmus: u32,
        /// A random frame-buffer layout (random-states, heavy-states): row pitch and buffer offset
        /// drawn at random, so buffers may overlap.
        #[arg(long)]
        layout: bool,
        /// The family of a stability scene (stability): thin, large, w_near_zero,
        /// w_near_two, persp, depth_z, depth_w, gradients, lod or long_runs
        /// (`sst1_trace::scenes::stability`).
        #[arg(long, value_name = "NAME")]
        family: Option<String>,
        /// Output file (replaced through a temporary file); default stdout.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Measure replay throughput of the fast path and the reference path in the same run:
    /// Mpix/s (`fbiPixelsIn` per second of the replaying thread's CPU time, parsing
    /// excluded), Mtri/s, ns and cycles per pixel, and the fast path's speed-up; a
    /// `binary` row replays the fast path from the binary trace form, decoding included.
    /// Default scenes: perf_gouraud_heavy, perf_tex_heavy, 10-pixel Gouraud and textured
    /// triangles, a random-state scene and a heavy-states scene (large triangles in random
    /// states).
    Bench {
        /// Trace files to measure instead of the default scenes.
        traces: Vec<PathBuf>,
        /// Runs per path; the fastest is kept.
        #[arg(long, default_value_t = 3)]
        iters: u32,
        /// Print JSON (for tools) instead of a table.
        #[arg(long)]
        json: bool,
        /// Triangles in each generated small-triangle scene.
        #[arg(long, default_value_t = 20000)]
        small: u32,
        /// Drawing states in the generated random-state scene.
        #[arg(long, default_value_t = 200)]
        states: u32,
        /// Folder holding perf_gouraud_heavy.trace.gz and perf_tex_heavy.trace.gz
        /// (default: the repository's traces/conformance/traces).
        #[arg(long, value_name = "DIR")]
        trace_dir: Option<PathBuf>,
        /// Also run the fast path on this many render threads, timed by the wall clock
        /// (the speed-up column then compares it with one thread's wall time). Default:
        /// the machine's cores; 1 leaves the row out.
        #[arg(long, value_name = "N")]
        threads: Option<usize>,
        /// Also run each approximate method (`--method` of `replay`) on one thread, a row
        /// each, with its speed-up over the fast path (`x/f`).
        #[arg(long)]
        methods: bool,
        /// Also run the fast path with each copy of the span kernels below the best the
        /// CPU has (`replay --isa`), one thread, a row each with its speed-up over the
        /// fast path (`x/f`).
        #[arg(long)]
        isas: bool,
        /// Instead: replay every trace of the repository (or the TRACES given) with every
        /// method and write into DIR the table (table.md, .csv, .json: Mpix/s, speed-up,
        /// share of pixels identical to `exact`, PSNR, largest channel error), the
        /// stability families' errors per step (stability.md, .csv) and PNG charts
        /// (speed_vs_accuracy, error_histogram, error_map, stability). `--iters` runs
        /// per method (1 for a quick chart).
        #[arg(long, value_name = "DIR")]
        chart: Option<PathBuf>,
    },
    /// The history of one pixel: every operation that touched it up to a dump (triangles
    /// with the register writes that set their state, fast fills, LFB writes), and for
    /// each shaded pixel the value of every pipeline stage and why it was killed, if it
    /// was (docs/pixel-history.md). The pixel is shaded on the reference path.
    Why {
        /// Trace file: text or binary, optionally gzip-compressed.
        trace: PathBuf,
        /// Column.
        x: i32,
        /// Row of the dump (frame-buffer row: row 0 is the first in memory).
        y: i32,
        /// Stop at this dump (1 is the trace's first). Default: the last dump, or the
        /// end of a trace without one.
        #[arg(long, value_name = "N")]
        dump: Option<u64>,
        /// The model (as for `replay`); `vote` takes the history on each reference
        /// model's board and shows at which stage they part ways.
        #[arg(long, value_enum)]
        model: Option<Model>,
        /// Print JSON (for tools) instead of text.
        #[arg(long)]
        json: bool,
        /// Follow a pixel outside the dump (a row past its last, a column past its
        /// width) as the buffer's word at that column and row: rows past a buffer's last
        /// are the next buffer's first, which triangles drawn with clipping off reach.
        #[arg(long)]
        beyond_dump: bool,
    },
    /// Convert a trace between the text and binary forms, chosen by OUT's extension:
    /// `.vtrace` binary, `.vtrace.gz` gzip binary, `.gz` gzip text, anything else text.
    Convert {
        /// Input trace, either form.
        input: PathBuf,
        /// Output file.
        output: PathBuf,
    },
}

/// A generated scene of `voodoo gen`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum SceneKind {
    /// Gouraud triangles of about 10 pixels.
    SmallTris,
    /// Textured triangles of about 10 pixels (bilinear, perspective, mipmapped).
    SmallTexTris,
    /// Triangles of random size in random drawing states.
    RandomStates,
    /// Large triangles in random drawing states (`--count` states, default 12): the
    /// pixels of states no trace in the repository uses, with little set-up between.
    HeavyStates,
    /// A family of stability scenes (`--family`): one parameter swept towards where
    /// arithmetic breaks, one dump per step.
    Stability,
}

/// How a replay draws: `sst1_board::Method`, spelled as its `name()`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum MethodArg {
    /// Exact fast path: the span kernels (the default).
    Exact,
    /// Exact generic path: pixel by pixel, every register read per pixel.
    Reference,
    /// Approximate: point sampling instead of bilinear (loses the 4-bit filter fractions).
    Nearest,
    /// Approximate: the LOD once per chunk of up to 64 pixels of a span (loses the LOD's
    /// change along it).
    LodPerChunk,
    /// Approximate: the perspective divide in single precision (24-bit mantissa: texel
    /// coordinates move where S/W is large).
    FloatDivide,
    /// Approximate: nearest, lod-per-chunk and float-divide together.
    Fastest,
}

impl From<MethodArg> for Method {
    fn from(m: MethodArg) -> Method {
        match m {
            MethodArg::Exact => Method::Exact,
            MethodArg::Reference => Method::Reference,
            MethodArg::Nearest => Method::Nearest,
            MethodArg::LodPerChunk => Method::LodPerChunk,
            MethodArg::FloatDivide => Method::FloatDivide,
            MethodArg::Fastest => Method::Fastest,
        }
    }
}

/// The model of the board a replay runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Model {
    /// The hardware model: one board, our reading of the SST-1 (the default accuracy
    /// profile, docs/accuracy.md).
    Hardware,
    /// One board per reference emulator, voted pixel by pixel.
    Vote,
    /// One board that behaves as MAME does.
    Mame,
    /// One board that behaves as DOSBox Staging does.
    #[value(name = "dosbox-staging")]
    DosboxStaging,
    /// One board that behaves as 86Box does.
    #[value(name = "86box")]
    Box86,
    /// The former name of `hardware`.
    #[value(hide = true)]
    Single,
}

impl Model {
    /// What `voodoo play` shows of the model.
    fn view(self) -> play::View {
        match self {
            Model::Hardware | Model::Single => play::View::Hardware,
            Model::Vote => play::View::Vote,
            Model::Mame => play::View::Reference(Reference::Mame),
            Model::DosboxStaging => play::View::Reference(Reference::DosboxStaging),
            Model::Box86 => play::View::Reference(Reference::Box86),
        }
    }

    /// The accuracy profile of a one-board model; `None` for the vote.
    fn profile(self) -> Option<AccuracyProfile> {
        match self {
            Model::Hardware | Model::Single => Some(AccuracyProfile::default()),
            Model::Vote => None,
            Model::Mame => Some(Reference::Mame.profile()),
            Model::DosboxStaging => Some(Reference::DosboxStaging.profile()),
            Model::Box86 => Some(Reference::Box86.profile()),
        }
    }
}

/// Let a closed output pipe (`voodoo info t.trace | head`) end the process quietly, as
/// other command-line tools do, instead of panicking in `println!`.
fn restore_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called once at start-up, before any thread exists; SIG_DFL is a valid
    // disposition for SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn main() -> ExitCode {
    restore_sigpipe();
    let result = match Cli::parse().command {
        Command::Replay {
            trace,
            out,
            png,
            model,
            stats,
            stats_json,
            profile,
            threads,
            no_timing,
            save_at,
            resume,
            method,
            isa,
        } => resolve_model(model, profile.as_deref()).and_then(|resolved| {
            if no_timing && resolved.is_none() {
                return Err("--no-timing needs a one-board model (not --model vote)".into());
            }
            if method.is_some() && resolved.is_none() {
                return Err("--method needs a one-board model (not --model vote)".into());
            }
            if isa.is_some() && resolved.is_none() {
                return Err("--isa needs a one-board model (not --model vote)".into());
            }
            if (save_at.is_some() || resume.is_some()) && resolved.is_none() {
                return Err(
                    "--save-at and --resume need a one-board model (not --model vote)".into(),
                );
            }
            let mut session = Session::default();
            if let Some(path) = &resume {
                if model.is_some() || profile.is_some() || no_timing {
                    return Err(
                        "--resume takes the model, the profile and the timing switch \
                                from the state: leave out --model, --profile and --no-timing"
                            .into(),
                    );
                }
                session.from = Some(load_state(path)?);
            }
            if let Some(args) = &save_at {
                let op = args[0].parse::<u64>().ok().ok_or_else(|| {
                    format!("--save-at: expected an op count, found {}", quote(&args[0]))
                })?;
                session.save_at = Some((op, Path::new(&args[1])));
            }
            replay(
                &trace,
                out.as_deref(),
                png.as_deref(),
                stats,
                stats_json.as_deref(),
                resolved.map(|p| OneBoard {
                    profile: p,
                    timing: !no_timing,
                    method: method.map_or(Method::Exact, Method::from),
                    isa: isa.unwrap_or_else(VectorIsa::best),
                }),
                threads.unwrap_or_else(default_threads),
                session,
            )
        }),
        Command::Check {
            trace,
            goldens,
            model,
            profile,
        } => resolve_model(model, profile.as_deref())
            .and_then(|profile| check(&trace, &goldens, profile)),
        Command::Demo { png, no_window } => demo(&png, !no_window),
        Command::Play {
            trace,
            goldens,
            model,
        } => play::run(&trace, model.view(), goldens),
        Command::Info { trace } => info(&trace),
        Command::Reg { register, value } => reg(&register, &value),
        Command::Convert { input, output } => convert(&input, &output),
        Command::Why {
            trace,
            x,
            y,
            dump,
            model,
            json,
            beyond_dump,
        } => {
            let req = why::Request {
                trace: &trace,
                x,
                y,
                dump,
                beyond_dump,
            };
            why_command(&req, model.unwrap_or(Model::Hardware), json)
        }
        Command::Gen {
            scene,
            seed,
            count,
            tmus,
            layout,
            family,
            out,
        } => gen(
            scene,
            seed,
            count,
            tmus,
            layout,
            family.as_deref(),
            out.as_deref(),
        ),
        Command::Bench {
            traces,
            iters,
            json,
            small,
            states,
            trace_dir,
            threads,
            methods,
            isas,
            chart,
        } => bench::bench(&bench::Options {
            threads: threads.unwrap_or_else(default_threads),
            methods,
            isas,
            chart,
            traces,
            iters,
            json,
            small,
            states,
            trace_dir,
        }),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("voodoo: {message}");
            ExitCode::FAILURE
        }
    }
}

/// The one board's profile (the model's, changed by `--profile`), or `None` for the
/// reference vote.
fn resolve_model(
    model: Option<Model>,
    profile: Option<&Path>,
) -> Result<Option<AccuracyProfile>, String> {
    let model = model.unwrap_or(Model::Hardware);
    match (model.profile(), profile) {
        (None, Some(_)) => Err(
            "--profile sets up one board: use it with a one-board model \
             (--model hardware, mame, dosbox-staging or 86box)"
                .to_string(),
        ),
        (None, None) => Ok(None),
        (Some(base), None) => Ok(Some(base)),
        (Some(base), Some(path)) => load_profile(base, path).map(Some),
    }
}

/// The largest accuracy profile read (a full profile is a few KiB of JSON).
const MAX_PROFILE: u64 = 1 << 20;

/// `base` changed by the accuracy profile in a JSON file of at most [`MAX_PROFILE`]
/// bytes: members left out keep `base`'s value.
fn load_profile(base: AccuracyProfile, path: &Path) -> Result<AccuracyProfile, String> {
    let bytes = read_file_bounded(path, MAX_PROFILE).map_err(|e| e.to_string())?;
    let text =
        std::str::from_utf8(&bytes).map_err(|_| format!("{}: not UTF-8 text", path.display()))?;
    let changes: serde_json::Value =
        serde_json::from_str(text).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut merged = serde_json::to_value(base).map_err(|e| e.to_string())?;
    merge_json(&mut merged, changes);
    serde_json::from_value(merged).map_err(|e| format!("{}: {e}", path.display()))
}

/// Writes `changes` over `base`: objects member by member, anything else whole.
fn merge_json(base: &mut serde_json::Value, changes: serde_json::Value) {
    match (base, changes) {
        (serde_json::Value::Object(base), serde_json::Value::Object(changes)) => {
            for (key, value) in changes {
                match base.get_mut(&key) {
                    Some(slot) => merge_json(slot, value),
                    None => {
                        base.insert(key, value);
                    }
                }
            }
        }
        (slot, value) => *slot = value,
    }
}

/// Where a one-board replay starts, and whether it saves the board on the way
/// (`--resume`, `--save-at`).
#[derive(Default)]
struct Session<'a> {
    /// A board restored from a save state, and the ops of the trace it had run.
    from: Option<(Board, u64)>,
    /// Save the board once this many ops of the trace have run, to this file.
    save_at: Option<(u64, &'a Path)>,
}

/// The largest save state read: that of the largest board.
fn max_state_file() -> u64 {
    sst1_board::state::max_state_len(sst1_board::BoardConfig {
        fbi_mb: 4,
        tmus: 3,
        tmu_mb: 4,
    }) as u64
}

/// A board restored from the save state at `path`, and the ops it had run.
fn load_state(path: &Path) -> Result<(Board, u64), String> {
    let bytes = read_file_bounded(path, max_state_file()).map_err(|e| e.to_string())?;
    let (board, info) =
        Board::from_state(&bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    let done = info.ops_done.ok_or_else(|| {
        format!(
            "{}: the state does not say after which trace op it was taken (it was not \
             written by `voodoo replay --save-at`), so there is no op to resume from",
            path.display()
        )
    })?;
    Ok((board, done))
}

/// How one board of a replay is set up.
#[derive(Clone, Copy)]
struct OneBoard {
    profile: AccuracyProfile,
    /// The timing model on.
    timing: bool,
    method: Method,
    /// The copy of the span kernels (capped by the CPU's).
    isa: VectorIsa,
}

impl OneBoard {
    /// `profile` with the timing model and the exact fast path.
    fn exact(profile: AccuracyProfile) -> Self {
        Self {
            profile,
            timing: true,
            method: Method::Exact,
            isa: VectorIsa::best(),
        }
    }
}

/// What a replay leaves: a board to report on and the front buffer.
struct Replayed {
    /// The board (with the reference vote: the MAME-profile board).
    board: Board,
    /// The front buffer after the last op (voted, with the reference vote).
    front: Vec<u16>,
}

/// Runs a streamed trace on one board with `profile` (and the timing model on or off),
/// or on one board per reference emulator and votes (`None`), handing each dump (voted)
/// to `sink` when it is reached, with a progress counter when stderr is a terminal.
fn run(
    stream: TraceStream<'_>,
    profile: Option<OneBoard>,
    threads: usize,
    session: Session<'_>,
    mut sink: impl FnMut(Dump) -> Result<(), ReplayError>,
) -> Result<Replayed, String> {
    let bar = if std::io::stderr().is_terminal() {
        let bar = ProgressBar::new_spinner();
        if let Ok(style) = ProgressStyle::with_template("{spinner} {pos} ops {elapsed}") {
            bar.set_style(style);
        }
        bar
    } else {
        ProgressBar::hidden()
    };
    let progress = |done: usize| bar.set_position(done as u64);
    let config = stream.config();
    let replayed = match profile {
        Some(one) => {
            let mut stream = stream;
            let (mut board, skip) = match session.from {
                Some((board, done)) => {
                    if board.config() != config {
                        return Err(format!(
                            "the state is of a board with {}, the trace's has {}",
                            describe_config(board.config()),
                            describe_config(config)
                        ));
                    }
                    (board, done)
                }
                None => {
                    let mut board = Board::new(config);
                    board.set_profile(one.profile);
                    board.set_timing(one.timing);
                    (board, 0)
                }
            };
            board.set_threads(threads);
            // The method is how this replay draws, not board state: a resumed board
            // takes this replay's.
            board.set_method(one.method);
            board.set_vector_isa(one.isa);
            // The ops the state had run.
            let mut skipped = 0;
            for op in stream
                .by_ref()
                .take(usize::try_from(skip).unwrap_or(usize::MAX))
            {
                op.map_err(|e| e.to_string())?;
                skipped += 1;
            }
            if skipped < skip {
                return Err(format!(
                    "the state was saved after op {skip}, but the trace has only {skipped} ops"
                ));
            }
            // Progress counts the trace's ops from its first.
            let from = |base: u64| move |done: usize| progress(done + base as usize);
            let mut base = skipped;
            if let Some((at, file)) = session.save_at {
                if at < skip {
                    return Err(format!(
                        "--save-at {at}: the state resumed from was saved after op {skip}, later"
                    ));
                }
                let ahead = usize::try_from(at - skip).unwrap_or(usize::MAX);
                let done = execute_trace_stream(
                    &mut stream,
                    Some(ahead),
                    &mut board,
                    from(base),
                    &mut sink,
                )
                .map_err(|e| e.to_string())?;
                if done < ahead {
                    return Err(format!(
                        "--save-at {at}: the trace has only {} ops; no state saved",
                        skip as usize + done
                    ));
                }
                write_file_replacing(file, &board.save_state_after(at))
                    .map_err(|e| e.to_string())?;
                println!("saved the board after op {at} to {}", file.display());
                base = at;
            }
            execute_trace_stream(&mut stream, None, &mut board, from(base), sink)
                .map(|_| {
                    let front = board.dump_buffer(BufferKind::Front);
                    Replayed { board, front }
                })
                .map_err(|e| e.to_string())
        }
        None => execute_references_stream(stream, config, progress, |dump| sink(dump.voted))
            .map(|boards| {
                let front = vote_buffer(&boards, BufferKind::Front);
                let [board, _, _] = boards;
                Replayed { board, front }
            })
            .map_err(|e| e.to_string()),
    };
    bar.finish_and_clear();
    replayed
}

/// A board configuration in words.
fn describe_config(c: sst1_board::BoardConfig) -> String {
    format!(
        "{} MiB of frame buffer and {} TMU(s) of {} MiB",
        c.fbi_mb, c.tmus, c.tmu_mb
    )
}

/// Writes the front buffer as an RGB PNG (RGB565 expanded by bit replication), through a
/// temporary file renamed over `path`.
fn write_front_png(replayed: &Replayed, path: &Path) -> Result<(u32, u32), String> {
    let (width, height) = replayed.board.display_size();
    write_png(width, height, &replayed.front, path)
}

/// Writes `width * height` RGB565 pixels as an RGB PNG (expanded by bit replication),
/// through a temporary file renamed over `path`.
fn write_png(width: u32, height: u32, pixels: &[u16], path: &Path) -> Result<(u32, u32), String> {
    let rgb: Vec<u8> = pixels.iter().flat_map(|&p| rgb565_to_rgb8(p)).collect();
    let image = image::RgbImage::from_raw(width, height, rgb)
        .ok_or_else(|| format!("front buffer is not {width}x{height}"))?;
    let mut png = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut png, image::ImageFormat::Png)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    write_file_replacing(path, png.get_ref()).map_err(|e| e.to_string())?;
    Ok((width, height))
}

/// The counters `--stats` prints: the board's own statistics (spec 5.31-5.35, kept
/// without the hardware registers' 24-bit wrap), command counts, and the modelled
/// hardware time (`sst1_board::timing`).
struct Stats(
    sst1_board::Stats,
    sst1_board::Timing,
    sst1_board::PathCounts,
);

impl Stats {
    fn to_json(&self) -> serde_json::Value {
        let s = &self.0;
        let t = &self.1;
        let frame = |f: &sst1_board::FrameTime| {
            serde_json::json!({
                "cycles": f.cycles,
                "triangles": f.triangles,
                "fills": f.fills,
                "bus_bound": f.bus_bound,
                "retrace_wait": f.retrace_wait,
                "host_wait": f.host_wait,
            })
        };
        serde_json::json!({
            "clock_hz": t.clock_hz,
            "cycles": t.cycles(),
            "frames": t.frames.iter().map(frame).collect::<Vec<_>>(),
            "pixels_in": s.pixels_in,
            "chroma_fail": s.chroma_fail,
            "zfunc_fail": s.zfunc_fail,
            "afunc_fail": s.afunc_fail,
            "pixels_out": s.pixels_out,
            "triangles": s.triangles,
            "fastfills": s.fastfills,
            "swaps": s.swaps,
            "shaded_by": {
                "span_kernels": self.2.span_kernels,
                "in_bands": self.2.in_bands,
                "packed": self.2.packed,
                "aliased_layout": self.2.aliased_layout,
                "short_rows": self.2.short_rows,
                "reference": self.2.reference,
                "behind_writes": self.2.behind_writes,
            },
        })
    }
}

/// The name of the default dump folder's trace: the file name without `.gz`, `.trace` or
/// `.vtrace`.
fn trace_stem(path: &Path) -> String {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = name.strip_suffix(".gz").unwrap_or(&name);
    let name = name
        .strip_suffix(".trace")
        .or_else(|| name.strip_suffix(".vtrace"))
        .unwrap_or(name);
    if name.is_empty() || name == "." || name == ".." {
        "trace".to_owned()
    } else {
        name.to_owned()
    }
}

/// Where `voodoo replay` writes dumps: the folder `--out` names (made before the replay),
/// or a fresh folder named after the trace, made at the first dump.
struct DumpTarget<'a> {
    trace: &'a Path,
    dir: Option<DumpDir>,
}

impl<'a> DumpTarget<'a> {
    fn new(trace: &'a Path, out: Option<&Path>) -> Result<Self, String> {
        let dir = match out {
            Some(out) => {
                std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
                let mut dir = DumpDir::existing(out);
                dir.protect(trace);
                Some(dir)
            }
            None => None,
        };
        Ok(Self { trace, dir })
    }

    fn write(&mut self, dump: &Dump) -> Result<PathBuf, ReplayError> {
        let dir = match &mut self.dir {
            Some(dir) => dir,
            empty => {
                let mut dir = DumpDir::create_fresh(Path::new(""), &trace_stem(self.trace))?;
                dir.protect(self.trace);
                println!("writing dumps to {}", dir.path().display());
                empty.insert(dir)
            }
        };
        Ok(dir.write_with(&dump.file, |out| dump.write_le(out))?)
    }
}

/// The render threads when `--threads` is not given: the machine's cores.
fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

fn replay(
    path: &Path,
    out: Option<&Path>,
    png: Option<&Path>,
    stats: bool,
    stats_json: Option<&Path>,
    profile: Option<OneBoard>,
    threads: usize,
    session: Session<'_>,
) -> Result<(), String> {
    let stream = open_trace(path).map_err(|e| e.to_string())?;
    let mut target = DumpTarget::new(path, out)?;
    let replayed = run(stream, profile, threads, session, |dump| {
        let written = target.write(&dump)?;
        println!("wrote {}", written.display());
        Ok(())
    })?;
    let board = &replayed.board;
    if let Some(png) = png {
        let (w, h) = write_front_png(&replayed, png)?;
        println!("wrote {} ({w}x{h})", png.display());
    }
    if stats || stats_json.is_some() {
        let s = Stats(board.stats(), board.timing().clone(), board.path_counts());
        if stats {
            let c = &s.0;
            let t = &s.1;
            let ms = |cycles: u64| cycles as f64 * 1000.0 / t.clock_hz as f64;
            println!(
                "hardware     {} cycles at {} MHz ({:.3} ms)",
                t.cycles(),
                t.clock_hz / 1_000_000,
                ms(t.cycles())
            );
            for (i, f) in t.frames.iter().enumerate() {
                println!(
                    "frame {i:<6} {:.3} ms: triangles {:.3}, fills {:.3}, retrace wait {:.3}, bus-bound {:.3}, host-bound {:.3}",
                    ms(f.cycles),
                    ms(f.triangles),
                    ms(f.fills),
                    ms(f.retrace_wait),
                    ms(f.bus_bound),
                    ms(f.host_wait)
                );
            }
            println!("pixels in    {}", c.pixels_in);
            println!("chroma fail  {}", c.chroma_fail);
            println!("zfunc fail   {}", c.zfunc_fail);
            println!("afunc fail   {}", c.afunc_fail);
            println!("pixels out   {}", c.pixels_out);
            println!("triangles    {}", c.triangles);
            println!("fastfills    {}", c.fastfills);
            println!("swaps        {}", c.swaps);
            let paths = board.path_counts();
            println!(
                "shaded by    span kernels {} ({} on render threads, {} in chunks packed from short rows; compiled for {}), pixel by pixel {} (rows of at most 2 pixels {}, aliased buffers {}, reference path {}); of all, {} of small triangles on the render thread behind the writes",
                paths.span_kernels,
                paths.in_bands,
                paths.packed,
                board.kernel_isa(),
                paths.short_rows + paths.aliased_layout + paths.reference,
                paths.short_rows,
                paths.aliased_layout,
                paths.reference,
                paths.behind_writes
            );
            for (what, n) in board.diagnostics().iter() {
                println!("ignored      {n} x {what:?}");
            }
        }
        if let Some(file) = stats_json {
            let text = serde_json::to_string_pretty(&s.to_json()).map_err(|e| e.to_string())?;
            write_file_replacing(file, (text + "\n").as_bytes()).map_err(|e| e.to_string())?;
        }
    }
    Ok(())
}

/// Checks that `goldens` is a folder holding at least one reference's golden folder.
fn check_goldens_folder(goldens: &Path) -> Result<(), String> {
    let meta = std::fs::metadata(goldens)
        .map_err(|e| format!("goldens folder {}: {e}", goldens.display()))?;
    if !meta.is_dir() {
        return Err(format!(
            "goldens folder {}: not a folder",
            goldens.display()
        ));
    }
    if !Reference::ALL
        .iter()
        .any(|r| goldens.join(r.golden_dir()).is_dir())
    {
        let names: Vec<&str> = Reference::ALL.iter().map(|r| r.golden_dir()).collect();
        return Err(format!(
            "goldens folder {}: holds none of the folders {}",
            goldens.display(),
            names.join(", ")
        ));
    }
    Ok(())
}

/// `voodoo check`: one line per dump, then the totals; an error if any pixel fails or any
/// dump has fewer than two goldens (or the goldens folder is missing).
fn check(path: &Path, goldens: &Path, profile: Option<AccuracyProfile>) -> Result<(), String> {
    check_goldens_folder(goldens)?;
    let stream = open_trace(path).map_err(|e| e.to_string())?;
    let (mut consensus, mut majority, mut judged, mut unjudged) = (0, 0, 0, 0);
    run(
        stream,
        profile.map(OneBoard::exact),
        default_threads(),
        Session::default(),
        |dump| {
            let stem = dump.file.strip_suffix(".raw").unwrap_or(&dump.file);
            let found: Vec<(&str, Vec<u16>)> = Reference::ALL
                .iter()
                .filter_map(|r| {
                    let dir = goldens.join(r.golden_dir());
                    [format!("{stem}.raw.gz"), format!("{stem}.raw")]
                        .iter()
                        .find_map(|f| judge::load_golden(&dir.join(f)))
                        .map(|g| (r.golden_dir(), g))
                })
                .collect();
            if found.len() < 2 {
                println!("{stem}: fewer than two goldens, not judged");
                unjudged += 1;
                return Ok(());
            }
            let buffers: Vec<&[u16]> = found.iter().map(|(_, g)| g.as_slice()).collect();
            let j = judge::judge(&buffers, &dump.data);
            let names: Vec<&str> = found.iter().map(|(n, _)| *n).collect();
            println!(
            "{stem}: {} consensus and {} majority pixels fail ({} pixels where all differ; {}){}",
            j.consensus_fail,
            j.majority_fail,
            j.free,
            names.join(", "),
            if j.same_size { "" } else { "; size differs" }
        );
            consensus += j.consensus_fail;
            majority += j.majority_fail;
            judged += 1;
            Ok(())
        },
    )?;
    println!("{judged} dumps judged: {consensus} consensus and {majority} majority pixels fail");
    if consensus + majority > 0 {
        return Err(format!(
            "{} pixels break the pass rule",
            consensus + majority
        ));
    }
    if unjudged > 0 {
        return Err(format!(
            "{unjudged} dumps have fewer than two goldens in {}",
            goldens.display()
        ));
    }
    if judged == 0 {
        return Err("the trace has no dumps to judge".to_owned());
    }
    Ok(())
}

fn demo(png: &Path, window: bool) -> Result<(), String> {
    let picture = demo::render_on(Board::new(demo::config()))?;
    let (w, h) = write_png(picture.width, picture.height, &picture.pixels, png)?;
    println!("wrote {} ({w}x{h}), drawn through Glide 3:", png.display());
    for line in glide::demo::DESCRIPTION {
        println!("  {line}");
    }
    if window {
        demo::show(&picture, png)?;
    }
    Ok(())
}

/// How many dump lines `voodoo info` lists (the rest are counted).
const INFO_DUMPS_LISTED: usize = 1000;

fn info(path: &Path) -> Result<(), String> {
    let stream = open_trace(path).map_err(|e| e.to_string())?;
    let config = stream.config();
    let mut c = OpCounts::default();
    let mut ops = 0u64;
    let mut dumps = Vec::new();
    for op in stream {
        let op = op.map_err(|e| e.to_string())?;
        c.add(&op);
        ops += 1;
        if let TraceOp::Dump { buffer, file } = op {
            if dumps.len() < INFO_DUMPS_LISTED {
                dumps.push(format!("dump {} {file}", buffer.name()));
            }
        }
    }
    println!(
        "board: fbi_mb {}, tmus {}, tmu_mb {}",
        config.fbi_mb, config.tmus, config.tmu_mb
    );
    println!(
        "ops: {ops} ({} writes, {} reads, {} pci, {} dumps)",
        c.writes, c.reads, c.pci, c.dumps
    );
    if c.waits > 0 {
        println!(
            "waits: {} ({} graphics-clock cycles of host time)",
            c.waits, c.wait_cycles
        );
    }
    println!(
        "writes: {} register, {} frame buffer, {} texture",
        c.register_writes, c.lfb_writes, c.texture_writes
    );
    println!(
        "triangles: {}, fastfills: {}, swaps: {}",
        c.triangles, c.fastfills, c.swaps
    );
    for line in &dumps {
        println!("{line}");
    }
    if c.dumps > dumps.len() as u64 {
        println!("... and {} more dumps", c.dumps - dumps.len() as u64);
    }
    println!("registers written:");
    for (offset, n) in &c.registers {
        println!("  {offset:#05x} {:<16} {n}", map::name_of(*offset));
    }
    Ok(())
}

fn reg(register: &str, value: &str) -> Result<(), String> {
    let offset = match parse_number(register) {
        Some(offset) if offset < 0x40_0000 => offset,
        Some(offset) => return Err(format!("{offset:#x} is not in the register space")),
        None => map::find(register)
            .map(|desc| desc.offset)
            .ok_or_else(|| format!("no register named {}", quote(register)))?,
    };
    let value =
        parse_number(value).ok_or_else(|| format!("{} is not a 32-bit number", quote(value)))?;
    println!(
        "{:#05x} {}",
        offset & 0x3fc,
        map::decode_pretty(offset, value)
    );
    Ok(())
}

/// `voodoo why`: the pixel's history on one model, or the references compared.
fn why_command(req: &why::Request<'_>, model: Model, json: bool) -> Result<(), String> {
    let text = match model.profile() {
        Some(profile) => {
            let name = match model {
                Model::Mame => "mame",
                Model::DosboxStaging => "dosbox-staging",
                Model::Box86 => "86box",
                _ => "hardware",
            };
            let h = why::history(req, name, profile)?;
            if json {
                serde_json::to_string_pretty(&h).map_err(|e| e.to_string())?
            } else {
                why::render(&h)
            }
        }
        None => {
            let histories = why::references()
                .into_iter()
                .map(|(name, profile)| why::history(req, name, profile))
                .collect::<Result<Vec<_>, String>>()?;
            let c = why::compare(histories);
            if json {
                serde_json::to_string_pretty(&c).map_err(|e| e.to_string())?
            } else {
                why::render_comparison(&c)
            }
        }
    };
    println!("{}", text.trim_end());
    Ok(())
}

fn convert(input: &Path, output: &Path) -> Result<(), String> {
    let trace = load_trace(input).map_err(|e| e.to_string())?;
    let name = output.to_string_lossy();
    let (stem, gzip) = match name.strip_suffix(".gz") {
        Some(stem) => (stem, true),
        None => (&*name, false),
    };
    let mut bytes = if stem.ends_with(".vtrace") {
        encode_binary(&trace)
    } else {
        write_text(&trace).into_bytes()
    };
    if gzip {
        bytes = gzip_bytes(&bytes).map_err(|e| format!("{}: {e}", output.display()))?;
    }
    write_file_replacing(output, &bytes).map_err(|e| e.to_string())?;
    println!("wrote {} ({} ops)", output.display(), trace.ops.len());
    Ok(())
}

fn gen(
    scene: SceneKind,
    seed: u64,
    count: Option<u32>,
    tmus: u32,
    layout: bool,
    family: Option<&str>,
    out: Option<&Path>,
) -> Result<(), String> {
    use sst1_trace::scenes;
    let text = match scene {
        SceneKind::Stability => {
            let names = || {
                scenes::stability::FAMILIES
                    .iter()
                    .map(|f| f.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            let name =
                family.ok_or_else(|| format!("stability needs --family: one of {}", names()))?;
            let f = scenes::stability::family(name).ok_or_else(|| {
                format!(
                    "--family {}: not a stability family ({})",
                    quote(name),
                    names()
                )
            })?;
            scenes::stability::scene(f)
        }
        SceneKind::SmallTris => scenes::small_triangles(seed, count.unwrap_or(20000), false),
        SceneKind::SmallTexTris => scenes::small_triangles(seed, count.unwrap_or(20000), true),
        SceneKind::RandomStates | SceneKind::HeavyStates => {
            if !(1..=3).contains(&tmus) {
                return Err(format!("--tmus {tmus}: a board has 1 to 3 TMUs"));
            }
            let base = if scene == SceneKind::HeavyStates {
                scenes::RandomStates::heavy(seed, count.unwrap_or(12))
            } else {
                scenes::RandomStates {
                    seed,
                    states: count.unwrap_or(200),
                    ..scenes::RandomStates::default()
                }
            };
            scenes::random_states(scenes::RandomStates {
                tmus,
                layout,
                ..base
            })
        }
    };
    match out {
        None => {
            use std::io::Write;
            std::io::stdout()
                .write_all(text.as_bytes())
                .map_err(|e| format!("stdout: {e}"))
        }
        Some(path) => {
            let bytes = if path.extension().is_some_and(|e| e == "gz") {
                gzip_bytes(text.as_bytes()).map_err(|e| format!("{}: {e}", path.display()))?
            } else {
                text.into_bytes()
            };
            write_file_replacing(path, &bytes).map_err(|e| e.to_string())
        }
    }
}

fn gzip_bytes(bytes: &[u8]) -> std::io::Result<Vec<u8>> {
    use std::io::Write;
    let mut encoder = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    encoder.write_all(bytes)?;
    encoder.finish()
}

//! The fuzz harness of voodoo-rs: seeded mutation of hostile inputs, on the stable
//! toolchain, with no coverage instrumentation.
//!
//! Each [`Target`] of [`TARGETS`] is a function of an
//! input's bytes that panics only when an invariant breaks (a reader panicked, a round
//! trip changed a trace, a streamed replay differs from one from memory, an error message
//! is too long). [`run`] takes each target's seeds (pieces of the repository's traces
//! and inputs written here), mutates them ([`mutate`]) with a seeded random generator
//! ([`rng::Rng`]), runs every case under `catch_unwind`, keeps the inputs that reach a
//! target's success path as further seeds, and writes every failing input to a file.
//! A run is reproduced exactly by its seed.
//!
//! * `cargo test --release -p voodoo-fuzz` runs a bounded run (a few seconds; CI).
//! * `VOODOO_FUZZ_SECS=3600 cargo test --release -p voodoo-fuzz -- --ignored` runs for an
//!   hour (or `cargo run --release -p voodoo-fuzz -- --secs 3600`).
//! * Environment: `VOODOO_FUZZ_SECS` (run this long), `VOODOO_FUZZ_CASES` (cases of the
//!   bounded run), `VOODOO_FUZZ_SEED` (a run's seed, decimal or 0x hex),
//!   `VOODOO_FUZZ_TARGETS` (comma-separated names), `VOODOO_FUZZ_FAILURES` (folder for
//!   failing inputs; default the temporary folder's `voodoo-fuzz-failures`).
//! * `cargo run --release -p voodoo-fuzz -- --repro TARGET FILE` runs one saved input.

pub mod corpus;
pub mod glide;
pub mod mutate;
pub mod rng;
pub mod targets;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::time::{Duration, Instant};

use corpus::Repository;
use rng::Rng;
use targets::{Target, TARGETS};

/// How long or how many cases a run lasts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Budget {
    /// This many cases in all, shared among the targets by weight.
    Cases(u64),
    /// Until this much time has passed.
    Time(Duration),
}

/// What a run does.
#[derive(Clone, Debug)]
pub struct Config {
    /// The seed of the run's random generator.
    pub seed: u64,
    /// How long it lasts.
    pub budget: Budget,
    /// The targets, by name (`None`: all).
    pub targets: Option<Vec<String>>,
    /// Where failing inputs are written.
    pub failures: PathBuf,
}

/// The seed of a run that names none.
pub const DEFAULT_SEED: u64 = 0x5eed_f0e5_5571;

fn parse_u64(text: &str) -> Option<u64> {
    match text.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16).ok(),
        None => text.parse().ok(),
    }
}

impl Config {
    /// A run of `cases` cases with the default seed, changed by the `VOODOO_FUZZ_*`
    /// environment variables (see the crate docs).
    pub fn from_env(cases: u64) -> Self {
        let var = |name: &str| std::env::var(name).ok();
        let budget = match var("VOODOO_FUZZ_SECS").as_deref().and_then(parse_u64) {
            Some(secs) => Budget::Time(Duration::from_secs(secs)),
            None => Budget::Cases(
                var("VOODOO_FUZZ_CASES")
                    .as_deref()
                    .and_then(parse_u64)
                    .unwrap_or(cases),
            ),
        };
        Self {
            seed: var("VOODOO_FUZZ_SEED")
                .as_deref()
                .and_then(parse_u64)
                .unwrap_or(DEFAULT_SEED),
            budget,
            targets: var("VOODOO_FUZZ_TARGETS")
                .map(|list| list.split(',').map(|s| s.trim().to_owned()).collect()),
            failures: var("VOODOO_FUZZ_FAILURES")
                .map(PathBuf::from)
                .unwrap_or_else(|| std::env::temp_dir().join("voodoo-fuzz-failures")),
        }
    }
}

/// A case that broke an invariant.
#[derive(Clone, Debug)]
pub struct Failure {
    /// The target.
    pub target: &'static str,
    /// The case number in the run.
    pub case: u64,
    /// The panic message.
    pub message: String,
    /// Where the input was saved (if it could be).
    pub input: Option<PathBuf>,
}

/// What a run did.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Cases run, per target name.
    pub cases: Vec<(&'static str, u64)>,
    /// Inputs kept as seeds because they reached a target's success path, per target.
    pub kept: Vec<(&'static str, usize)>,
    /// The cases that failed.
    pub failures: Vec<Failure>,
}

/// Most inputs a target keeps as further seeds during a run.
const MAX_KEPT: usize = 512;

/// The message of a caught panic.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_owned()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "a panic without a message".to_owned()
    }
}

/// Runs `target` on one input; the panic message if it broke an invariant.
pub fn run_one(target: &Target, input: &[u8]) -> Result<(), String> {
    catch_unwind(AssertUnwindSafe(|| (target.run)(input))).map_err(|p| panic_message(&*p))
}

/// The target named `name`.
pub fn target(name: &str) -> Option<&'static Target> {
    TARGETS.iter().find(|t| t.name == name)
}

/// One target's state during a run.
struct Lane {
    target: &'static Target,
    seeds: Vec<Vec<u8>>,
    kept: usize,
    cases: u64,
}

/// Runs the fuzz targets as `config` says. Panics inside targets are caught (and
/// silenced while the run lasts); failing inputs are written to `config.failures`.
pub fn run(config: &Config) -> Report {
    let repo = Repository::load();
    let mut lanes: Vec<Lane> = TARGETS
        .iter()
        .filter(|t| {
            config
                .targets
                .as_ref()
                .is_none_or(|names| names.iter().any(|n| n == t.name))
        })
        .map(|target| {
            let mut seeds = (target.seeds)(&repo);
            if seeds.is_empty() {
                seeds.push(Vec::new());
            }
            Lane {
                target,
                seeds,
                kept: 0,
                cases: 0,
            }
        })
        .collect();
    let mut rng = Rng::new(config.seed);
    let mut report = Report::default();
    if lanes.is_empty() {
        return report;
    }
    let start = Instant::now();
    // Silence the panic messages of caught cases; they are reported once, at the end.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut case = 0u64;
    'run: loop {
        for lane in &mut lanes {
            for _ in 0..lane.target.weight.max(1) {
                let done = match config.budget {
                    Budget::Cases(n) => case >= n,
                    Budget::Time(limit) => case.is_multiple_of(64) && start.elapsed() >= limit,
                };
                if done {
                    break 'run;
                }
                let input = make_input(&mut rng, &lane.seeds);
                match run_one(lane.target, &input) {
                    Ok(()) => {
                        // Keep now and then an input that got through, to mutate further.
                        if lane.kept < MAX_KEPT && rng.one_in(16) {
                            lane.seeds.push(input);
                            lane.kept += 1;
                        }
                    }
                    Err(message) => {
                        let path = config
                            .failures
                            .join(format!("{}-{:x}-{case}.bin", lane.target.name, config.seed));
                        let saved = std::fs::create_dir_all(&config.failures)
                            .and_then(|()| std::fs::write(&path, &input))
                            .is_ok();
                        report.failures.push(Failure {
                            target: lane.target.name,
                            case,
                            message,
                            input: saved.then_some(path),
                        });
                    }
                }
                lane.cases += 1;
                case += 1;
            }
        }
    }
    std::panic::set_hook(hook);
    report.cases = lanes.iter().map(|l| (l.target.name, l.cases)).collect();
    report.kept = lanes.iter().map(|l| (l.target.name, l.kept)).collect();
    report
}

/// One case's input: a seed, mutated (now and then random bytes instead).
fn make_input(rng: &mut Rng, seeds: &[Vec<u8>]) -> Vec<u8> {
    if rng.one_in(32) {
        return (0..rng.below(256)).map(|_| rng.next_u32() as u8).collect();
    }
    let mut input = rng.pick(seeds).cloned().unwrap_or_default();
    let other = rng.pick(seeds).map(Vec::as_slice).unwrap_or(&[]);
    mutate::mutate(rng, &mut input, other);
    input
}

/// A report in words: cases per target, then each failure.
pub fn describe(report: &Report, config: &Config) -> String {
    let mut text = format!("seed {:#x}:", config.seed);
    for (name, cases) in &report.cases {
        text.push_str(&format!(" {name} {cases}"));
    }
    text.push_str(" cases\n");
    for f in &report.failures {
        text.push_str(&format!(
            "FAILED {} case {}: {}\n  input: {}\n  reproduce: cargo run --release -p voodoo-fuzz -- --repro {} {}\n",
            f.target,
            f.case,
            f.message,
            f.input
                .as_ref()
                .map_or("(not saved)".to_owned(), |p| p.display().to_string()),
            f.target,
            f.input
                .as_ref()
                .map_or("FILE".to_owned(), |p| p.display().to_string()),
        ));
    }
    text
}

//! Conformance: one test per trace dump, judged by the pass rule of
//! `traces/conformance/README.md` against the three reference emulators' goldens.
//!
//! Each trace is replayed once per reference emulator's profile
//! ([`sst1_board::Reference::profile`]), the three outputs voted pixel by pixel
//! ([`sst1_trace::execute_references`]), and once with the hardware model (one board,
//! [`sst1_board::AccuracyProfile::default`], [`sst1_trace::execute`]). A dump's test
//! checks three things:
//! - each reference profile's dump equals that emulator's golden exactly, except for the
//!   gaps listed in `traces/reference-gaps.toml` (`"reference/trace/buffer"` tables, with
//!   a `reason` and `max_pixels`): this pins every accuracy switch to what its emulator
//!   does;
//! - the voted dump meets the pass rule, except for `traces/known-failures.toml`;
//! - the hardware model's consensus and majority misses equal its entry in
//!   `traces/hardware-budget.toml` (`"suite/trace/buffer"` tables with `consensus`,
//!   `majority` and a `reason`; no entry means no miss). More fails, an unlisted miss
//!   fails, and fewer fails too, until `UPDATE_HARDWARE_BUDGET=1` records it (the budget
//!   only shrinks); that variable rewrites the file from the results, keeping the reasons.
//!
//! Per pixel: where all goldens agree (consensus) ours must equal them; where two of three
//! agree (majority) ours must equal the majority; where all differ nothing is required.
//! `mode_800x600` has goldens from two emulators only: a pixel counts only where both agree.
//! `mode_512x384`'s MAME golden is already the 512×384 top-left crop of its 640×480-pitch
//! output, so it compares directly with the others.
//!
//! `traces/known-failures.toml` lists dumps that do not pass yet (`"trace/buffer"` tables
//! with a `reason` and optional `max_pixels`). A listed dump that passes fails its test (the
//! list only shrinks), an unlisted failure fails, and a listed one failing on more than
//! `max_pixels` pixels fails. `UPDATE_KNOWN_FAILURES=1` rewrites the list from the results
//! instead of failing; `TRACE_RESULTS=all` writes PNGs for known failures too.
//!
//! Failing dumps leave `expected.png`, `actual.png` and `diff.png` (red: pixel breaks the
//! rule, yellow: all goldens differ, grey: ours matches) under
//! `<target>/trace-results/fail/<suite>/` (the hardware model's under
//! `<target>/trace-results/fail/hardware/<suite>/`).

use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

use sst1_board::{AccuracyProfile, Board, Reference};
use sst1_regs::RegisterBus;
use sst1_trace::judge::Rule;
use sst1_trace::{execute, execute_references, load_trace, rgb565_to_rgb8, Dump};

/// The reference emulators' golden folders, in [`Reference::ALL`] order.
const ORACLES: [&str; 3] = ["mame", "dosbox-staging", "86box"];

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn known_failures_path() -> PathBuf {
    repo().join("traces/known-failures.toml")
}

fn reference_gaps_path() -> PathBuf {
    repo().join("traces/reference-gaps.toml")
}

/// `target/` of this build: `CARGO_TARGET_DIR`, else three levels above the test binary
/// (`target/<profile>/deps/<binary>`).
fn target_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("CARGO_TARGET_DIR") {
        return PathBuf::from(dir);
    }
    let exe = std::env::current_exe().expect("test binary path");
    exe.ancestors()
        .nth(3)
        .map(Path::to_path_buf)
        .unwrap_or_else(|| repo().join("target"))
}

// ---------------------------------------------------------------------------------------
// Replays, once per trace and model per test process.

/// One trace replayed with every model the test judges.
struct Replayed {
    /// The reference vote's dumps ([`execute_references`]).
    voted: Vec<Dump>,
    /// Each reference profile's dumps, in [`Reference::ALL`] order.
    per_reference: [Vec<Dump>; 3],
    /// The hardware model's dumps: one board, [`AccuracyProfile::default`].
    hardware: Vec<Dump>,
}

/// A trace's replays, or why the trace could not be loaded.
type Replay = Result<Replayed, String>;

/// Replays the trace with the reference vote (three boards, three threads) and, on a
/// fourth thread at the same time, with the hardware model.
fn replay_trace(suite: &str, trace: &str) -> Replay {
    let path = repo().join(format!("traces/{suite}/traces/{trace}.trace.gz"));
    let trace = load_trace(&path).map_err(|e| e.to_string())?;
    let config = trace.board_config();
    std::thread::scope(|scope| {
        let hardware = scope.spawn(|| {
            let mut board = Board::new(config);
            board.set_profile(AccuracyProfile::default());
            execute(&trace.ops, &mut board, |_| {})
        });
        let references = execute_references(&trace.ops, config, |_| {});
        Ok(Replayed {
            voted: references.dumps,
            per_reference: references.per_reference,
            hardware: hardware
                .join()
                .map_err(|_| "the hardware model's replay panicked".to_owned())?,
        })
    })
}

fn cached_replay(suite: &'static str, trace: &'static str) -> Arc<Replay> {
    type Cache = Mutex<HashMap<(&'static str, &'static str), Arc<OnceLock<Arc<Replay>>>>>;
    static CACHE: OnceLock<Cache> = OnceLock::new();
    let slot = {
        let mut cache = CACHE
            .get_or_init(Default::default)
            .lock()
            .unwrap_or_else(|e| e.into_inner());
        cache.entry((suite, trace)).or_default().clone()
    };
    slot.get_or_init(|| Arc::new(replay_trace(suite, trace)))
        .clone()
}

// ---------------------------------------------------------------------------------------
// Goldens and the pass rule.

fn load_golden(suite: &str, oracle: &str, name: &str) -> Option<Vec<u16>> {
    sst1_trace::judge::load_golden(
        &repo().join(format!("traces/{suite}/golden/{oracle}/{name}.raw.gz")),
    )
}

/// The display sizes the goldens come in (README: 640×480, 512×384, 800×600).
fn golden_dims(len: usize) -> (usize, usize) {
    match len {
        196_608 => (512, 384),
        480_000 => (800, 600),
        _ => (640, 480),
    }
}

/// How a dump fares against the pass rule.
struct Outcome {
    width: usize,
    height: usize,
    rules: Vec<Rule>,
    /// Ours, if it has the goldens' size.
    actual: Option<Vec<u16>>,
    consensus_fail: u64,
    majority_fail: u64,
    free: u64,
}

impl Outcome {
    fn failing(&self) -> u64 {
        self.consensus_fail + self.majority_fail
    }

    fn fails(&self, i: usize) -> bool {
        match (self.rules[i], &self.actual) {
            (Rule::Free, _) => false,
            (_, None) => true,
            (Rule::Consensus(v) | Rule::Majority(v), Some(actual)) => actual[i] != v,
        }
    }
}

fn judge(goldens: &[(&str, Vec<u16>)], ours: &Dump) -> Outcome {
    let len = goldens[0].1.len();
    let (width, height) = golden_dims(len);
    let buffers: Vec<&[u16]> = goldens.iter().map(|(_, g)| g.as_slice()).collect();
    let j = sst1_trace::judge::judge(&buffers, &ours.data);
    Outcome {
        width,
        height,
        rules: j.rules,
        actual: j.same_size.then(|| ours.data.clone()),
        consensus_fail: j.consensus_fail,
        majority_fail: j.majority_fail,
        free: j.free,
    }
}

fn describe(value: u16, aux: bool) -> String {
    if aux {
        format!("{value:#06x} (depth/alpha {value})")
    } else {
        let (r, g, b) = (value >> 11, (value >> 5) & 0x3f, value & 0x1f);
        let [r8, g8, b8] = rgb565_to_rgb8(value);
        format!("{value:#06x} (R {r}/31 G {g}/63 B {b}/31 = #{r8:02x}{g8:02x}{b8:02x})")
    }
}

fn report(
    suite: &str,
    name: &str,
    ours: &Dump,
    goldens: &[(&str, Vec<u16>)],
    outcome: &Outcome,
) -> String {
    let aux = ours.buffer.is_aux();
    let mut text = format!(
        "{suite}/{name}: {} pixels break the pass rule ({} consensus, {} majority; {} pixels \
         where all goldens differ)\n",
        outcome.failing(),
        outcome.consensus_fail,
        outcome.majority_fail,
        outcome.free
    );
    if outcome.actual.is_none() {
        let _ = writeln!(
            text,
            "  size mismatch: ours {}x{} ({} values), goldens {}x{}",
            ours.width,
            ours.height,
            ours.data.len(),
            outcome.width,
            outcome.height
        );
        return text;
    }
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    let mut first = None;
    for i in (0..outcome.rules.len()).filter(|&i| outcome.fails(i)) {
        let (x, y) = (i % outcome.width, i / outcome.width);
        (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
        first.get_or_insert(i);
    }
    if let (Some(i), Some(actual)) = (first, &outcome.actual) {
        let (x, y) = (i % outcome.width, i / outcome.width);
        let (kind, expected) = match outcome.rules[i] {
            Rule::Consensus(v) => ("consensus", v),
            Rule::Majority(v) => ("majority", v),
            Rule::Free => unreachable!("free pixels never fail"),
        };
        let _ = writeln!(text, "  bounding box: x {x0}..={x1}, y {y0}..={y1}");
        let _ = writeln!(text, "  first differing pixel ({x}, {y}), {kind}:");
        let _ = writeln!(text, "    expected {}", describe(expected, aux));
        let _ = writeln!(text, "    actual   {}", describe(actual[i], aux));
        for (oracle, golden) in goldens {
            let _ = writeln!(text, "    {oracle:<14} {:#06x}", golden[i]);
        }
    }
    text
}

fn to_rgb(value: u16, aux: bool) -> [u8; 3] {
    if aux {
        let v = (value >> 8) as u8;
        [v, v, v]
    } else {
        rgb565_to_rgb8(value)
    }
}

/// Writes expected/actual/diff PNGs; returns their folder.
fn write_pngs(
    suite: &str,
    name: &str,
    ours: &Dump,
    first_golden: &[u16],
    outcome: &Outcome,
) -> PathBuf {
    let dir = target_dir().join("trace-results/fail").join(suite);
    std::fs::create_dir_all(&dir).expect("create trace-results folder");
    let aux = ours.buffer.is_aux();
    let (w, h) = (outcome.width as u32, outcome.height as u32);
    let image = |pixel: &dyn Fn(usize) -> [u8; 3]| {
        image::RgbImage::from_fn(w, h, |x, y| image::Rgb(pixel((y * w + x) as usize)))
    };
    let expected = image(&|i| match outcome.rules[i] {
        Rule::Consensus(v) | Rule::Majority(v) => to_rgb(v, aux),
        Rule::Free => to_rgb(first_golden[i], aux),
    });
    let actual = outcome
        .actual
        .as_ref()
        .map(|a| image(&|i| to_rgb(a[i], aux)));
    let diff = image(&|i| {
        if outcome.fails(i) {
            [255, 0, 0]
        } else if outcome.rules[i] == Rule::Free {
            [255, 255, 0]
        } else {
            let [r, g, b] = to_rgb(first_golden[i], aux);
            let grey = ((u32::from(r) + u32::from(g) + u32::from(b)) / 12) as u8;
            [grey, grey, grey]
        }
    });
    let save = |img: &image::RgbImage, what: &str| {
        img.save(dir.join(format!("{name}_{what}.png")))
            .expect("write PNG");
    };
    save(&expected, "expected");
    if let Some(actual) = &actual {
        save(actual, "actual");
    }
    save(&diff, "diff");
    dir
}

// ---------------------------------------------------------------------------------------
// The known-failures list.

/// One entry of `traces/known-failures.toml`.
#[derive(Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct KnownFailure {
    /// Why the dump does not pass (spec text, evidence, or "not yet implemented").
    reason: String,
    /// The documented number of pixels that break the rule; more fails the test.
    max_pixels: Option<u64>,
}

fn read_list(path: &Path) -> BTreeMap<String, KnownFailure> {
    match std::fs::read_to_string(path) {
        Ok(text) => {
            toml::from_str(&text).unwrap_or_else(|e| panic!("{} is malformed: {e}", path.display()))
        }
        Err(_) => BTreeMap::new(),
    }
}

fn known_failures() -> &'static BTreeMap<String, KnownFailure> {
    static KNOWN: OnceLock<BTreeMap<String, KnownFailure>> = OnceLock::new();
    KNOWN.get_or_init(|| read_list(&known_failures_path()))
}

fn reference_gaps() -> &'static BTreeMap<String, KnownFailure> {
    static GAPS: OnceLock<BTreeMap<String, KnownFailure>> = OnceLock::new();
    GAPS.get_or_init(|| read_list(&reference_gaps_path()))
}

const KNOWN_FAILURES_HEADER: &str = "\
# Dumps that do not meet the conformance pass rule (traces/conformance/README.md).
# One table per dump, named \"trace/buffer\" after its golden file:
#   reason     why: spec text or hardware evidence for a deliberate deviation from the
#              majority, or \"not yet implemented\"
#   max_pixels optional: the documented number of pixels that break the rule
# crates/trace/tests/conformance.rs fails when a listed dump passes (remove it), when an
# unlisted dump fails, and when a listed one breaks more than max_pixels pixels.
# `UPDATE_KNOWN_FAILURES=1 cargo test -p sst1-trace --test conformance` rewrites this file
# from the results, keeping the reasons already written.
# The dumps are the per-pixel vote of the three reference profiles
# (sst1_trace::execute_references); traces/hardware-budget.toml pins the hardware model.
";

const REFERENCE_GAPS_HEADER: &str = "\
# Where a reference emulator's profile (sst1_board::Reference::profile) does not yet
# reproduce that emulator's golden dump exactly. One table per dump and reference, named
# \"reference/trace/buffer\" (reference: the golden folder, mame, dosbox-staging or 86box):
#   reason     what the profile does not model
#   max_pixels the number of pixels that differ from that golden
# crates/trace/tests/conformance.rs fails when a listed dump matches (remove it), when an
# unlisted one differs, and when a listed one differs on more than max_pixels pixels.
# `UPDATE_KNOWN_FAILURES=1 cargo test -p sst1-trace --test conformance` rewrites this file.
";

/// Records `failing` for `key` in the list at `path` (update mode).
fn update_list(path: &Path, header: &str, key: &str, failing: u64) {
    static LOCK: Mutex<()> = Mutex::new(());
    let _guard = LOCK.lock().unwrap_or_else(|e| e.into_inner());
    let mut entries = read_list(path);
    if failing == 0 {
        entries.remove(key);
    } else {
        let reason = entries
            .get(key)
            .map_or("not yet implemented".to_owned(), |e| e.reason.clone());
        entries.insert(
            key.to_owned(),
            KnownFailure {
                reason,
                max_pixels: Some(failing),
            },
        );
    }
    let mut text = header.to_owned();
    for (key, entry) in &entries {
        let _ = write!(text, "\n[{key:?}]\nreason = {:?}\n", entry.reason);
        if let Some(max) = entry.max_pixels {
            let _ = writeln!(text, "max_pixels = {max}");
        }
    }
    std::fs::write(path, text).unwrap_or_else(|e| panic!("write {}: {e}", path.display()));
}

fn updating() -> bool {
    std::env::var_os("UPDATE_KNOWN_FAILURES").is_some_and(|v| v == "1")
}

/// Each reference profile's dump against its own emulator's golden: `None` if it
/// matches or its listed gap covers it, else why not.
fn check_reference_fidelity(
    suite: &str,
    name: &str,
    key: &str,
    per_reference: &[Vec<Dump>; 3],
) -> Option<String> {
    let file = format!("{name}.raw");
    let mut problems = String::new();
    for (reference, dumps) in Reference::ALL.iter().zip(per_reference) {
        let Some(golden) = load_golden(suite, reference.golden_dir(), name) else {
            continue;
        };
        let Some(ours) = dumps.iter().find(|d| d.file == file) else {
            continue;
        };
        let differing = if ours.data.len() == golden.len() {
            ours.data
                .iter()
                .zip(&golden)
                .filter(|(a, b)| a != b)
                .count() as u64
        } else {
            golden.len() as u64
        };
        let gap_key = format!("{}/{key}", reference.golden_dir());
        if updating() {
            update_list(
                &reference_gaps_path(),
                REFERENCE_GAPS_HEADER,
                &gap_key,
                differing,
            );
            continue;
        }
        let listed = reference_gaps().get(&gap_key);
        match (differing, listed) {
            (0, None) => {}
            (0, Some(_)) => {
                let _ = writeln!(
                    problems,
                    "{suite}/{name}: the {reference:?} profile now reproduces its golden: \
                     remove [\"{gap_key}\"] from traces/reference-gaps.toml"
                );
            }
            (n, Some(gap)) if gap.max_pixels.is_some_and(|max| n <= max) => {}
            (n, _) => {
                let _ = writeln!(
                    problems,
                    "{suite}/{name}: the {reference:?} profile differs from its golden on {n} \
                     pixels (traces/reference-gaps.toml allows {})",
                    listed.and_then(|g| g.max_pixels).unwrap_or(0)
                );
            }
        }
    }
    (!problems.is_empty()).then_some(problems)
}

// ---------------------------------------------------------------------------------------
// The hardware model's budget.

fn hardware_budget_path() -> PathBuf {
    repo().join("traces/hardware-budget.toml")
}

/// One entry of `traces/hardware-budget.toml`: what the hardware model misses on a dump.
#[derive(Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct Budget {
    /// Consensus pixels (all goldens agree) the hardware model misses.
    consensus: u64,
    /// Majority pixels (two goldens agree) the hardware model misses.
    majority: u64,
    /// Why: the documented deviation or the behaviour that explains the misses, or
    /// "Not yet explained: " and what was observed.
    reason: String,
}

/// The reason [`update_budget`] gives a new entry; [`hardware_budget_is_explained`] fails
/// while one is left.
const UNEXPLAINED: &str = "TODO: explain these misses";

fn read_budget() -> BTreeMap<String, Budget> {
    let path = hardware_budget_path();
    match std::fs::read_to_string(&path) {
        Ok(text) => {
            toml::from_str(&text).unwrap_or_else(|e| panic!("{} is malformed: {e}", path.display()))
        }
        Err(_) => BTreeMap::new(),
    }
}

fn hardware_budget() -> &'static BTreeMap<String, Budget> {
    static BUDGET: OnceLock<BTreeMap<String, Budget>> = OnceLock::new();
    BUDGET.get_or_init(read_budget)
}

const HARDWARE_BUDGET_HEADER: &str = "\
# The hardware model's misses: one board running sst1_board::model::Hardware
# (AccuracyProfile::HARDWARE, the default; what sst1_trace::execute replays and
# `voodoo replay` runs), judged with the pass rule of
# traces/conformance/README.md on every dump of traces/conformance and traces/glide-sdk.
# One table per dump that misses any pixel, named \"suite/trace/buffer\" (suite:
# conformance or glide-sdk; trace/buffer after the golden file):
#   consensus  pixels where all goldens agree and the hardware model differs
#   majority   pixels where two goldens agree and the hardware model differs
#   reason     why: the documented deviation (docs/accuracy.md, \"Where the hardware model
#              departs from the majority\") or \"Not yet explained: \" and what was seen
# crates/trace/tests/conformance.rs fails when a dump's consensus or majority count grows
# above its entry, when a dump without an entry misses a pixel, and when a listed dump
# misses fewer pixels than its entry says (the list only shrinks: record the gain).
# `UPDATE_HARDWARE_BUDGET=1 cargo test --release -p sst1-trace --test conformance`
# rewrites this file from the results, keeping the reasons already written; a new entry
# gets a placeholder reason that the test rejects until it is replaced.
";

/// Records the hardware model's misses on `key` in `traces/hardware-budget.toml`.
fn update_budget(key: &str, consensus: u64, majority: u64) {
    static LOCK: Mutex<()> = Mutex::new(());
    let _guard = LOCK.lock().unwrap_or_else(|e| e.into_inner());
    let mut entries = read_budget();
    if consensus + majority == 0 {
        entries.remove(key);
    } else {
        let reason = entries
            .get(key)
            .map_or(UNEXPLAINED.to_owned(), |e| e.reason.clone());
        entries.insert(
            key.to_owned(),
            Budget {
                consensus,
                majority,
                reason,
            },
        );
    }
    let mut text = HARDWARE_BUDGET_HEADER.to_owned();
    for (key, entry) in &entries {
        let _ = write!(
            text,
            "\n[{key:?}]\nconsensus = {}\nmajority = {}\nreason = {:?}\n",
            entry.consensus, entry.majority, entry.reason
        );
    }
    let path = hardware_budget_path();
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("write {}: {e}", path.display()));
}

fn updating_budget() -> bool {
    std::env::var_os("UPDATE_HARDWARE_BUDGET").is_some_and(|v| v == "1")
}

/// The hardware model's dump against the goldens and its budget: `None` if it keeps to
/// its entry exactly, else why not (with PNGs of the misses).
fn check_hardware_budget(
    suite: &str,
    name: &str,
    key: &str,
    ours: &Dump,
    goldens: &[(&str, Vec<u16>)],
) -> Option<String> {
    let outcome = judge(goldens, ours);
    let (consensus, majority) = (outcome.consensus_fail, outcome.majority_fail);
    if updating_budget() {
        update_budget(key, consensus, majority);
        return None;
    }
    const UPDATE: &str = "UPDATE_HARDWARE_BUDGET=1 cargo test --release -p sst1-trace --test \
                          conformance";
    let verdict = match hardware_budget().get(key) {
        None if consensus + majority == 0 => return None,
        None => format!("no entry [\"{key}\"] in traces/hardware-budget.toml"),
        Some(b) if consensus == b.consensus && majority == b.majority => return None,
        Some(b) if consensus <= b.consensus && majority <= b.majority => {
            return Some(format!(
                "hardware model: {suite}/{name} now misses {consensus} consensus and {majority} \
                 majority pixels, fewer than its budget [\"{key}\"] ({} and {}): the list only \
                 shrinks, run `{UPDATE}` to record it\n",
                b.consensus, b.majority
            ));
        }
        Some(b) => format!(
            "over its budget [\"{key}\"] in traces/hardware-budget.toml ({} consensus, {} \
             majority: {})",
            b.consensus, b.majority, b.reason
        ),
    };
    let text = report(suite, name, ours, goldens, &outcome);
    let dir = write_pngs(
        &format!("hardware/{suite}"),
        name,
        ours,
        &goldens[0].1,
        &outcome,
    );
    Some(format!(
        "hardware model: {text}  images: {}/{name}_{{expected,actual,diff}}.png\n{verdict}\n",
        dir.display()
    ))
}

// ---------------------------------------------------------------------------------------
// One dump's test.

fn check_dump(suite: &'static str, trace: &'static str, buffer: &str) {
    let name = format!("{trace}_{buffer}");
    let key = format!("{trace}/{buffer}");
    let replay = cached_replay(suite, trace);
    let replayed = match replay.as_ref() {
        Ok(replayed) => replayed,
        Err(e) => panic!("{suite}/{trace}: cannot load the trace: {e}"),
    };
    let file = format!("{name}.raw");
    let find = |dumps: &'static str, list: &[Dump]| {
        list.iter()
            .position(|d| d.file == file)
            .unwrap_or_else(|| panic!("{suite}/{trace}: the {dumps} made no dump named {file}"))
    };
    let voted = &replayed.voted[find("reference vote", &replayed.voted)];
    let hardware = &replayed.hardware[find("hardware model", &replayed.hardware)];
    let goldens: Vec<(&str, Vec<u16>)> = ORACLES
        .iter()
        .filter_map(|&oracle| load_golden(suite, oracle, &name).map(|g| (oracle, g)))
        .collect();
    assert!(goldens.len() >= 2, "{suite}/{name}: fewer than two goldens");
    assert!(
        goldens.iter().all(|(_, g)| g.len() == goldens[0].1.len()),
        "{name}: golden sizes differ"
    );

    let budget = check_hardware_budget(suite, &name, &format!("{suite}/{key}"), hardware, &goldens);
    let fidelity = check_reference_fidelity(suite, &name, &key, &replayed.per_reference);
    let vote = check_vote(suite, &name, &key, voted, &goldens);
    let problems: String = [vote, fidelity, budget].into_iter().flatten().collect();
    assert!(problems.is_empty(), "{problems}");
}

/// The reference vote's dump against the pass rule and `traces/known-failures.toml`:
/// `None` if it passes or keeps to its listed failure, else why not (with PNGs).
fn check_vote(
    suite: &str,
    name: &str,
    key: &str,
    ours: &Dump,
    goldens: &[(&str, Vec<u16>)],
) -> Option<String> {
    let outcome = judge(goldens, ours);
    let failing = outcome.failing();
    if updating() {
        update_list(&known_failures_path(), KNOWN_FAILURES_HEADER, key, failing);
        return None;
    }
    let known = known_failures().get(key);
    let verdict = match (failing, known) {
        (0, None) => return None,
        (0, Some(_)) => {
            return Some(format!(
                "{suite}/{name} now passes: remove [\"{key}\"] from traces/known-failures.toml\n"
            ))
        }
        (_, None) => "not listed in traces/known-failures.toml".to_owned(),
        (
            n,
            Some(KnownFailure {
                max_pixels: Some(max),
                reason,
            }),
        ) if n > *max => format!(
            "listed in traces/known-failures.toml ({reason}) with max_pixels = {max}, but \
             {n} pixels now break the rule"
        ),
        (_, Some(KnownFailure { reason, .. })) => {
            if std::env::var_os("TRACE_RESULTS").is_some_and(|v| v == "all") {
                write_pngs(suite, name, ours, &goldens[0].1, &outcome);
            }
            eprintln!(
                "known failure ({reason}): {}",
                report(suite, name, ours, goldens, &outcome)
            );
            return None;
        }
    };
    let text = report(suite, name, ours, goldens, &outcome);
    let dir = write_pngs(suite, name, ours, &goldens[0].1, &outcome);
    Some(format!(
        "{text}  images: {}/{name}_{{expected,actual,diff}}.png\n{verdict}\n",
        dir.display()
    ))
}

// ---------------------------------------------------------------------------------------
// The test list: one module per trace, one #[test] per golden dump.

macro_rules! dump_tests {
    ($suite_mod:ident, $suite:literal, { $($trace:ident: [$($buffer:ident),+],)* }) => {
        mod $suite_mod {
            $(
                #[allow(non_snake_case)]
                mod $trace {
                    $(
                        #[test]
                        fn $buffer() {
                            crate::check_dump($suite, stringify!($trace), stringify!($buffer));
                        }
                    )+
                }
            )*
            /// Every (trace, buffer) listed here.
            pub const LISTED: &[(&str, &[&str])] =
                &[$((stringify!($trace), &[$(stringify!($buffer)),+]),)*];
        }
    };
}

dump_tests!(conformance, "conformance", {
    alpha_blend: [front, aux],
    alpha_blend_dither: [front, aux],
    alpha_test: [front, depth],
    board_2mb: [front, back, depth],
    chroma_key: [front, depth],
    clip_yorigin: [front, depth],
    color_combine: [front, depth],
    depth_w_bias: [front, depth],
    depth_z: [front, depth],
    fastfill_depth: [front, back, depth],
    flat_dither4: [front, depth],
    flat_nodither: [front, depth],
    fog_alpha_z_const: [front, depth],
    fog_table: [front, depth],
    gouraud_dither2: [front, depth],
    gouraud_dither4: [front, depth],
    gouraud_float_subpix: [front, depth],
    gouraud_nodither: [front, depth],
    lfb_writes: [front, back, depth],
    mode_512x384: [front, back, depth],
    mode_800x600: [front, back, depth],
    perf_gouraud_heavy: [front, depth],
    perf_tex_heavy: [front, depth],
    stipple: [front, depth],
    stress_random: [front, depth],
    tex_2tmu_modulate: [front, depth],
    tex_8bit_formats: [front, depth],
    tex_argb1555_4444: [front, depth],
    tex_clamp_wrap: [front, depth],
    tex_filter_clamp: [front, depth],
    tex_mipmap_lodbias: [front, depth],
    tex_p8_palette: [front, depth],
    tex_perspective: [front, depth],
    tex_rgb565_bilinear: [front, depth],
    tex_rgb565_point: [front, depth],
    tex_yiq_ncc: [front, depth],
    tmu2_combine: [front, depth],
    tmu2_detail: [front, depth],
    tmu2_projected: [front, depth],
    tmu2_trilinear: [front, depth],
    tmu_combine: [front, depth],
});

dump_tests!(glide_sdk, "glide-sdk", {
    test00: [front, depth],
    test02: [front, depth],
    test04: [front, depth],
    test06: [front, depth],
    test08: [front, depth],
    test10: [front, depth],
    test12: [front, back, depth],
    test14: [front, depth],
    test16: [front, depth],
    test18: [front, depth],
    test20: [front, depth],
    test22: [front, depth],
    test24: [front, depth],
    test26: [front, depth],
    test28: [front, depth],
    test30: [front, depth],
    test32: [front, depth],
    test38: [front, depth],
});

/// The lists above name every golden dump in the repository, and nothing else.
#[test]
fn every_golden_dump_has_a_test() {
    for (suite, listed) in [
        ("conformance", conformance::LISTED),
        ("glide-sdk", glide_sdk::LISTED),
    ] {
        let mut on_disk = std::collections::BTreeSet::new();
        for oracle in ORACLES {
            let dir = repo().join(format!("traces/{suite}/golden/{oracle}"));
            for entry in std::fs::read_dir(dir).unwrap() {
                let file = entry.unwrap().file_name().into_string().unwrap();
                if let Some(stem) = file.strip_suffix(".raw.gz") {
                    on_disk.insert(stem.to_owned());
                }
            }
        }
        let mut tests = std::collections::BTreeSet::new();
        for (trace, buffers) in listed {
            for buffer in *buffers {
                tests.insert(format!("{trace}_{buffer}"));
            }
            let path = repo().join(format!("traces/{suite}/traces/{trace}.trace.gz"));
            assert!(path.exists(), "{} missing", path.display());
        }
        assert_eq!(tests, on_disk, "{suite}: test list and golden files differ");
        let traces = std::fs::read_dir(repo().join(format!("traces/{suite}/traces")))
            .unwrap()
            .count();
        assert_eq!(traces, listed.len(), "{suite}: a trace has no test");
    }
    // Known-failure keys are "trace/buffer": trace names must be unique across suites.
    for (trace, _) in conformance::LISTED {
        assert!(
            glide_sdk::LISTED.iter().all(|(t, _)| t != trace),
            "{trace} in both suites"
        );
    }
}

/// Every known-failures, reference-gaps and hardware-budget entry names a dump that has
/// a test.
#[test]
fn known_failures_name_existing_dumps() {
    for key in known_failures().keys() {
        let found = [conformance::LISTED, glide_sdk::LISTED]
            .iter()
            .any(|listed| {
                listed.iter().any(|(trace, buffers)| {
                    buffers
                        .iter()
                        .any(|buffer| *key == format!("{trace}/{buffer}"))
                })
            });
        assert!(found, "traces/known-failures.toml: no dump named {key}");
    }
    for key in hardware_budget().keys() {
        let found = [
            ("conformance", conformance::LISTED),
            ("glide-sdk", glide_sdk::LISTED),
        ]
        .iter()
        .any(|(suite, listed)| {
            listed.iter().any(|(trace, buffers)| {
                buffers
                    .iter()
                    .any(|buffer| *key == format!("{suite}/{trace}/{buffer}"))
            })
        });
        assert!(found, "traces/hardware-budget.toml: no dump named {key}");
    }
    for key in reference_gaps().keys() {
        let dump = ORACLES
            .iter()
            .find_map(|oracle| key.strip_prefix(&format!("{oracle}/")));
        let found = dump.is_some_and(|dump| {
            [conformance::LISTED, glide_sdk::LISTED]
                .iter()
                .any(|listed| {
                    listed.iter().any(|(trace, buffers)| {
                        buffers
                            .iter()
                            .any(|buffer| dump == format!("{trace}/{buffer}"))
                    })
                })
        });
        assert!(
            found,
            "traces/reference-gaps.toml: no reference dump named {key}"
        );
    }
}

/// Every hardware-budget entry says why: none keeps the placeholder that
/// `UPDATE_HARDWARE_BUDGET=1` gives a new entry, and every count is a miss.
#[test]
fn hardware_budget_is_explained() {
    for (key, entry) in hardware_budget() {
        assert!(
            !entry.reason.trim().is_empty() && !entry.reason.starts_with(UNEXPLAINED),
            "traces/hardware-budget.toml: [\"{key}\"] needs a reason (what explains its \
             misses, or \"Not yet explained: \" and what was observed)"
        );
        assert!(
            entry.consensus + entry.majority > 0,
            "traces/hardware-budget.toml: [\"{key}\"] misses nothing: remove it"
        );
    }
}

// ---------------------------------------------------------------------------------------
// Determinism.

/// The statistics registers (spec 5.31-5.35), read after a replay.
const STAT_REGISTERS: [u32; 5] = [0x14c, 0x150, 0x154, 0x158, 0x15c];

fn replay_with_stats(suite: &str, trace: &str) -> (Vec<Dump>, Vec<u32>) {
    let path = repo().join(format!("traces/{suite}/traces/{trace}.trace.gz"));
    let trace = load_trace(&path).unwrap();
    let mut board = Board::new(trace.board_config());
    let dumps = execute(&trace.ops, &mut board, |_| {});
    let stats = STAT_REGISTERS.iter().map(|&r| board.read32(r)).collect();
    (dumps, stats)
}

/// Two replays of the same trace on fresh boards give identical dumps and counters.
#[test]
fn replays_are_deterministic() {
    for (suite, trace) in [
        ("conformance", "gouraud_dither4"),
        ("conformance", "tmu2_combine"),
        ("glide-sdk", "test12"),
    ] {
        let first = replay_with_stats(suite, trace);
        let second = replay_with_stats(suite, trace);
        assert!(!first.0.is_empty(), "{trace}: no dumps");
        assert!(first == second, "{suite}/{trace}: two replays differ");
    }
}

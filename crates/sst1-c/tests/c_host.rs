//! C host programs against libsst1, built with `cc` from `include/sst1.h` and run:
//!
//! * `examples/replay.c` replays every trace of `traces/conformance/traces`,
//!   `traces/glide-sdk/traces` and `traces/examples` (as plain text in a temporary
//!   folder) on the hardware model, and one on each reference model: every
//!   buffer it dumps must be, byte for byte, what `sst1_trace::execute` dumps for the same
//!   trace on the same model, every front-buffer dump's RGBA8 must be that buffer
//!   widened with `sst1_trace::rgb565_to_rgb8`, and the swaps its callback saw must be
//!   the board's count;
//! * `tests/errors.c`, linked to the shared and to the static library, checks every
//!   error code and the features no trace shows;
//! * `tests/state.c` saves a board and loads it into another, and checks every refusal.
//!
//! It also checks the header: every function it declares is documented there and
//! exported by the library, and its result codes are the library's.

use sst1_board::{Board, Model, Reference};
use sst1_trace::{execute, load_trace, rgb565_to_rgb8, write_text, Dump, DumpBuffer};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The folder holding libsst1.so: `<target>/<profile>/deps`, where the test binary
/// lives and cargo builds this package's cdylib before its tests.
fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    exe.parent().expect("target deps dir").to_path_buf()
}

fn crate_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn repo() -> PathBuf {
    crate_dir().join("../..")
}

/// A fresh temporary folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sst1-c-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// Compiles `source` against sst1.h and libsst1 into `out/exe`: linked to libsst1.so,
/// or with `static_lib` to libsst1.a (and the system libraries Rust's std needs).
fn compile_with(source: &Path, out: &Path, exe: &str, static_lib: bool) -> PathBuf {
    let lib = lib_dir();
    let file = if static_lib {
        "libsst1.a"
    } else {
        "libsst1.so"
    };
    assert!(
        lib.join(file).exists(),
        "{file} not found in {}",
        lib.display()
    );
    let exe = out.join(exe);
    let mut cc = Command::new("cc");
    cc.args(["-std=gnu17", "-Wall", "-Wextra", "-Werror", "-pedantic"])
        .arg("-I")
        .arg(crate_dir().join("include"))
        .arg(source);
    if static_lib {
        cc.arg(lib.join(file)).args(["-lpthread", "-ldl", "-lm"]);
    } else {
        cc.arg("-L").arg(&lib).arg("-lsst1");
    }
    let status = cc.arg("-o").arg(&exe).status().expect("run cc");
    assert!(status.success(), "compiling {} failed", source.display());
    exe
}

/// [`compile_with`], linked to libsst1.so.
fn compile(source: &Path, out: &Path, exe: &str) -> PathBuf {
    compile_with(source, out, exe, false)
}

fn run(exe: &Path, args: &[PathBuf]) -> std::process::Output {
    Command::new(exe)
        .args(args)
        .env("LD_LIBRARY_PATH", lib_dir())
        .output()
        .expect("run the C program")
}

/// Every trace in the repository: the conformance suite, 3dfx's Glide test programs,
/// the example programs.
fn all_traces() -> Vec<PathBuf> {
    let mut traces = Vec::new();
    for dir in [
        "traces/conformance/traces",
        "traces/glide-sdk/traces",
        "traces/examples",
    ] {
        for entry in std::fs::read_dir(repo().join(dir)).expect("trace folder") {
            let path = entry.expect("folder entry").path();
            let name = path.file_name().unwrap().to_string_lossy();
            if name.ends_with(".trace.gz") || name.contains(".vtrace") {
                traces.push(path);
            }
        }
    }
    traces.sort();
    traces
}

/// The trace as plain text for the C host: a text trace uncompressed as it is (comments
/// and all), a binary one written out as text.
fn plain_text(path: &Path) -> Vec<u8> {
    let name = path.file_name().unwrap().to_string_lossy();
    if name.ends_with(".trace.gz") {
        let mut text = Vec::new();
        flate2::read::GzDecoder::new(std::fs::File::open(path).expect("trace file"))
            .read_to_end(&mut text)
            .expect("gunzip the trace");
        text
    } else {
        write_text(&load_trace(path).expect("trace loads")).into_bytes()
    }
}

/// Replays `path` with the C host on `model` and with `sst1_trace::execute` on a Rust
/// board, requires the same dumps, RGBA8 frames and swap count, and returns the dumps.
fn replay_matches(exe: &Path, path: &Path, model: Option<Reference>) -> Vec<Dump> {
    let trace = path
        .strip_prefix(repo())
        .unwrap_or(path)
        .display()
        .to_string();
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let tag = model.map_or("hardware", |r| r.golden_dir());
    let dir = scratch(&format!("{name}-{tag}"));
    let plain = dir.join("trace.txt");
    std::fs::write(&plain, plain_text(path)).expect("write the plain trace");
    let out = dir.join("dumps");
    std::fs::create_dir_all(&out).unwrap();
    let mut args = vec![plain.clone(), out.clone()];
    if let Some(r) = model {
        args.push(PathBuf::from(r.golden_dir()));
    }
    let ran = run(exe, &args);
    assert!(
        ran.status.success(),
        "{trace} ({tag}): the C host failed: {}",
        String::from_utf8_lossy(&ran.stderr)
    );

    // The Rust replay.
    let loaded = load_trace(path).expect("trace loads");
    let mut board = Board::new(loaded.board_config());
    if let Some(r) = model {
        board.set_model(Model::Reference(r));
    }
    let dumps = execute(&loaded.ops, &mut board, |_| {});
    assert!(!dumps.is_empty(), "{trace} has no dumps");
    let swaps = board.stats().swaps;
    assert_eq!(
        String::from_utf8_lossy(&ran.stdout),
        format!("swaps {swaps} dumps {}\n", dumps.len()),
        "{trace} ({tag}): swaps or dump count differ"
    );
    for d in &dumps {
        let c = std::fs::read(out.join(&d.file)).expect("the C host's dump");
        assert!(
            c == d.to_le_bytes(),
            "{trace} ({tag}): {} differs from the Rust replay's ({}x{})",
            d.file,
            d.width,
            d.height
        );
        if d.buffer == DumpBuffer::Front {
            let rgba = std::fs::read(out.join(format!("{}.rgba", d.file))).expect("RGBA dump");
            let want: Vec<u8> = d
                .data
                .iter()
                .flat_map(|&p| {
                    let [r, g, b] = rgb565_to_rgb8(p);
                    [r, g, b, 0xff]
                })
                .collect();
            assert!(
                rgba == want,
                "{trace} ({tag}): {}.rgba differs from the front buffer widened",
                d.file
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    dumps
}

/// The one trace that takes most of the time (20 s of a 30 s total), in a test of its
/// own so that it runs beside the others.
const SLOWEST: &str = "perf_tex_heavy.trace.gz";

fn build_replay(tag: &str) -> PathBuf {
    let dir = scratch(&format!("replay-build-{tag}"));
    compile(&crate_dir().join("examples/replay.c"), &dir, "replay")
}

#[test]
fn c_host_replays_every_trace_as_the_rust_replay() {
    let exe = build_replay("all");
    let traces: Vec<PathBuf> = all_traces()
        .into_iter()
        .filter(|p| !p.ends_with(SLOWEST))
        .collect();
    assert!(traces.len() > 60, "found only {} traces", traces.len());
    for trace in &traces {
        replay_matches(&exe, trace, None);
    }
}

#[test]
fn c_host_replays_the_slowest_trace_as_the_rust_replay() {
    let exe = build_replay("slowest");
    let path = repo().join("traces/conformance/traces").join(SLOWEST);
    replay_matches(&exe, &path, None);
}

/// Each reference model, on a trace where the hardware model and the references part
/// ways (docs/accuracy.md): the C host's model is the one the board runs.
#[test]
fn c_host_runs_the_reference_models() {
    let exe = build_replay("models");
    let path = repo().join("traces/conformance/traces/tmu2_combine.trace.gz");
    let hardware = replay_matches(&exe, &path, None);
    let mut departs = false;
    for r in Reference::ALL {
        let dumps = replay_matches(&exe, &path, Some(r));
        departs |= dumps.iter().zip(&hardware).any(|(a, b)| a.data != b.data);
    }
    assert!(
        departs,
        "no reference model departs from the hardware model here"
    );
}

/// `tests/errors.c`, linked to the shared and to the static library.
#[test]
fn every_error_is_a_code() {
    let dir = scratch("errors");
    let source = crate_dir().join("tests/errors.c");
    for (exe, static_lib) in [("errors", false), ("errors_static", true)] {
        let exe = compile_with(&source, &dir, exe, static_lib);
        let ran = run(&exe, &[]);
        assert_eq!(
            String::from_utf8_lossy(&ran.stdout),
            "ok\n",
            "{}: {}",
            exe.display(),
            String::from_utf8_lossy(&ran.stderr)
        );
        assert!(ran.status.success());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `tests/state.c`: save states from C (a board saved and loaded goes on alike; every
/// refusal is its code).
#[test]
fn save_states_from_c() {
    let dir = scratch("state");
    let exe = compile(&crate_dir().join("tests/state.c"), &dir, "state");
    let ran = run(&exe, &[]);
    assert_eq!(
        String::from_utf8_lossy(&ran.stdout),
        "ok\n",
        "{}",
        String::from_utf8_lossy(&ran.stderr)
    );
    assert!(ran.status.success());
    let _ = std::fs::remove_dir_all(&dir);
}

/// The header compiles as C++ too (its `extern "C"` block), where a C++ compiler is.
#[test]
fn header_compiles_as_cpp() {
    let header = crate_dir().join("include/sst1.h");
    match Command::new("c++")
        .args(["-fsyntax-only", "-Wall", "-Wextra", "-Werror", "-x", "c++"])
        .arg(&header)
        .status()
    {
        Ok(status) => assert!(status.success(), "sst1.h does not compile as C++"),
        Err(e) => eprintln!("SKIPPED: no C++ compiler ({e}); sst1.h not checked as C++"),
    }
}

/// The functions the header declares (`TYPE sst1_NAME(` at the start of a line), and
/// whether a comment ends on the line before each.
fn declared() -> Vec<(String, bool)> {
    let header = std::fs::read_to_string(crate_dir().join("include/sst1.h")).unwrap();
    let lines: Vec<&str> = header.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let skip = [" ", "#", "/*", "typedef"];
        if skip.iter().any(|p| line.starts_with(p)) {
            continue;
        }
        // The identifier just before the first `(`, if it is sst1_*.
        let Some(paren) = line.find('(') else {
            continue;
        };
        let name = line[..paren].rsplit([' ', '*']).next().unwrap_or_default();
        if !name.starts_with("sst1_") {
            continue;
        }
        // Documented: the line before is the end of a comment.
        let documented = i > 0 && lines[i - 1].trim_end().ends_with("*/");
        out.push((name.to_string(), documented));
    }
    out
}

#[test]
fn header_matches_the_library() {
    let functions = declared();
    assert!(functions.len() >= 25, "found only {functions:?}");
    let undocumented: Vec<_> = functions.iter().filter(|(_, d)| !d).collect();
    assert!(
        undocumented.is_empty(),
        "undocumented in sst1.h: {undocumented:?}"
    );
    // Result codes: the header's enum values are the library's.
    let header = std::fs::read_to_string(crate_dir().join("include/sst1.h")).unwrap();
    for e in sst1::Error::ALL {
        let name = format!("{e:?}");
        let c_name: String = name
            .chars()
            .enumerate()
            .flat_map(|(i, c)| {
                let sep = (i > 0 && c.is_ascii_uppercase()).then_some('_');
                sep.into_iter()
                    .chain(std::iter::once(c.to_ascii_uppercase()))
            })
            .collect();
        let line = format!("SST1_ERR_{c_name} = {}", e as i32);
        assert!(header.contains(&line), "sst1.h lacks `{line}`");
    }
    // Exports: every declared function, nothing else named sst1_*.
    let lib = lib_dir().join("libsst1.so");
    let out = match Command::new("nm")
        .args(["-D", "--defined-only"])
        .arg(&lib)
        .output()
    {
        Ok(out) if out.status.success() => out,
        _ => {
            eprintln!("SKIPPED: nm (binutils) cannot run; exported symbols not checked");
            return;
        }
    };
    let mut exported: Vec<String> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| {
            let mut w = l.split_whitespace();
            let (kind, name) = (w.nth(1)?, w.next()?);
            (kind == "T" && name.starts_with("sst1_")).then(|| name.to_string())
        })
        .collect();
    exported.sort();
    let mut want: Vec<String> = functions.into_iter().map(|(n, _)| n).collect();
    want.sort();
    assert_eq!(exported, want, "libsst1.so's exports differ from sst1.h");
}

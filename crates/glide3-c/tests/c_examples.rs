//! Build the C example programs in `examples/` against `include/` and libglide3, run
//! them headless with `VOODOO_PNG` and `VOODOO_TRACE`, then:
//!
//! * replay the recorded trace with `sst1_trace::execute` on a fresh board: every
//!   displayed frame it dumps must equal our golden (`traces/examples/golden/`), and
//!   the last one must equal the PNG the run wrote, pixel for pixel;
//! * the committed trace `traces/examples/NAME.trace.gz` must be the op stream this run
//!   recorded (a change of the front-end's register stream shows up here).
//!
//! The goldens are our own regression references (traces/examples/README.md). After an
//! intended change, `VOODOO_BLESS=1 cargo test -p glide3-c --test c_examples` rewrites
//! the committed trace and goldens of the C examples.

#[path = "../../trace/tests/support/address_space.rs"]
mod address_space;

use sst1_board::{Board, Reference};
use sst1_trace::{execute, load_trace, rgb565_to_rgb8, Dump, Trace};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The directory holding libglide3.so: `<target>/<profile>/deps`, where the test
/// binary lives and where cargo builds this package's cdylib before the tests (it
/// copies it up to `<profile>/` only for `cargo build`, so that copy may be stale
/// or missing).
fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    exe.parent().expect("target deps dir").to_path_buf()
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn examples_dir() -> PathBuf {
    repo().join("traces/examples")
}

fn blessing() -> bool {
    std::env::var_os("VOODOO_BLESS").is_some()
}

/// What one run of an example left behind.
struct Run {
    png: PathBuf,
    trace: PathBuf,
    stderr: String,
}

/// Compiles `examples/NAME.c` (or `crates/glide3-c/tests/NAME.c` for `tests/NAME`).
fn build(name: &str, out: &Path) -> PathBuf {
    compile(name, out, &[]).unwrap_or_else(|| panic!("compiling {name}.c failed"))
}

/// Compiles `examples/NAME.c` (or `crates/glide3-c/tests/NAME.c` for `tests/NAME`) with
/// extra compiler flags; `None` if the compiler refuses.
fn compile(name: &str, out: &Path, flags: &[&str]) -> Option<PathBuf> {
    let source = match name.strip_prefix("tests/") {
        Some(test) => repo().join(format!("crates/glide3-c/tests/{test}.c")),
        None => repo().join(format!("examples/{name}.c")),
    };
    let suffix: String = flags.iter().map(|f| f.replace(['-', '='], "_")).collect();
    let exe = out.join(format!("{}{suffix}", name.replace('/', "_")));
    let lib = lib_dir();
    assert!(
        lib.join("libglide3.so").exists(),
        "libglide3.so not found in {}",
        lib.display()
    );
    let status = Command::new("cc")
        .args(["-std=gnu17", "-Wall", "-Wextra", "-Werror"])
        .args(flags)
        .arg("-I")
        .arg(repo().join("crates/glide3-c/include"))
        .arg(&source)
        .arg("-L")
        .arg(&lib)
        .arg("-lglide3")
        .arg("-lm")
        .arg("-lpthread")
        .arg("-o")
        .arg(&exe)
        .status()
        .expect("run cc");
    status.success().then_some(exe)
}

/// A test program printed exactly "ok" and exited with status 0.
fn assert_prints_ok(run: &std::process::Output) {
    assert_eq!(
        String::from_utf8_lossy(&run.stdout),
        "ok\n",
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(run.status.success());
}

fn build_and_run(name: &str) -> Run {
    build_and_run_with(name, None)
}

/// [`build_and_run`] with `VOODOO_MODEL` set to `model`.
fn build_and_run_with(name: &str, model: Option<&str>) -> Run {
    let tag = model.map(|m| format!("-{m}")).unwrap_or_default();
    let out =
        std::env::temp_dir().join(format!("glide3-c-test-{}-{name}{tag}", std::process::id()));
    std::fs::create_dir_all(&out).expect("temp dir");
    let exe = build(name, &out);
    let png = out.join(format!("{name}.png"));
    let trace = out.join(format!("{name}.trace.gz"));
    let mut command = Command::new(&exe);
    if let Some(model) = model {
        command.env("VOODOO_MODEL", model);
    }
    let run = command
        .env("LD_LIBRARY_PATH", lib_dir())
        .env("VOODOO_PNG", &png)
        .env("VOODOO_TRACE", &trace)
        .output()
        .expect("run example");
    assert!(
        run.status.success(),
        "{name} exited with {:?}: {}",
        run.status,
        String::from_utf8_lossy(&run.stderr)
    );
    Run {
        png,
        trace,
        stderr: String::from_utf8_lossy(&run.stdout).into_owned()
            + &String::from_utf8_lossy(&run.stderr),
    }
}

fn replay(trace: &Trace) -> Vec<Dump> {
    let mut board = Board::new(trace.board_config());
    execute(&trace.ops, &mut board, |_| {})
}

fn gunzip(path: &Path) -> Vec<u8> {
    let mut out = Vec::new();
    flate2::read::GzDecoder::new(std::fs::File::open(path).expect("golden file"))
        .read_to_end(&mut out)
        .expect("gzip");
    out
}

fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    enc.write_all(bytes).expect("gzip");
    enc.finish().expect("gzip")
}

/// Every dump equals its golden; the last one equals the PNG. Returns the dumps.
fn check(name: &str) -> Vec<Dump> {
    let run = build_and_run(name);
    let trace = load_trace(&run.trace).expect("recorded trace loads");
    let dumps = replay(&trace);
    assert!(!dumps.is_empty(), "{name}: the trace has no dump points");

    // Step 1: the replay reproduces what the run displayed.
    let img = image::open(&run.png).expect("decode PNG").to_rgb8();
    let last = dumps.last().expect("a dump");
    assert_eq!((img.width(), img.height()), (last.width, last.height));
    let replayed: Vec<u8> = last.data.iter().flat_map(|&p| rgb565_to_rgb8(p)).collect();
    assert!(
        replayed == img.as_raw().as_slice(),
        "{name}: replayed front buffer differs from the PNG the run wrote"
    );

    let committed = examples_dir().join(format!("{name}.trace.gz"));
    if blessing() {
        std::fs::copy(&run.trace, &committed).expect("bless trace");
        for d in &dumps {
            let golden = examples_dir().join(format!("golden/{}.gz", d.file));
            std::fs::write(golden, gzip(&d.to_le_bytes())).expect("bless golden");
        }
        return dumps;
    }
    // Step 2: exact pixels against our goldens, and the same register stream.
    for d in &dumps {
        let golden = gunzip(&examples_dir().join(format!("golden/{}.gz", d.file)));
        assert!(
            d.to_le_bytes() == golden,
            "{name}: {} differs from its golden",
            d.file
        );
    }
    let ours = load_trace(&committed).expect("committed trace");
    assert!(
        ours == trace,
        "{name}: the recorded register stream differs from traces/examples/{name}.trace.gz"
    );
    assert!(
        run.stderr.is_empty(),
        "{name} printed errors: {}",
        run.stderr
    );
    dumps
}

#[test]
fn gouraud_triangle() {
    let dumps = check("gouraud");
    // Two frames, identical; a swap dump each.
    assert_eq!(dumps.len(), 2);
    assert_eq!(dumps[0].file, "gouraud_swap1_front.raw");
    assert_eq!(dumps[0].data, dumps[1].data);
}

#[test]
fn textured_fog() {
    check("textured_fog");
}

#[test]
fn decal_blend() {
    check("decal_blend");
}

#[test]
fn lightmap_multipass() {
    check("lightmap");
}

#[test]
fn lfb_overlay() {
    check("lfb_overlay");
}

/// grGet, grQueryResolutions, grGetProcAddress, grReset, state save/restore through
/// copied buffers, table downloads and .3df files from C (tests/api.c prints "ok").
#[test]
fn api_queries_and_3df_files() {
    let out = std::env::temp_dir().join(format!("glide3-c-test-{}-api", std::process::id()));
    std::fs::create_dir_all(&out).expect("temp dir");
    let exe = build("tests/api", &out);
    let run = Command::new(&exe)
        .arg(&out)
        .env("LD_LIBRARY_PATH", lib_dir())
        .output()
        .expect("run api");
    assert_prints_ok(&run);
}

/// Null vertex pointers, an out-of-range enum and a texture that does not fit reach the
/// error callback with the call's name and leave the counters untouched.
#[test]
fn hostile_arguments_reach_the_error_callback() {
    let out = std::env::temp_dir().join(format!("glide3-c-test-{}-hostile", std::process::id()));
    std::fs::create_dir_all(&out).expect("temp dir");
    let exe = build("tests/hostile", &out);
    let run = Command::new(&exe)
        .env("LD_LIBRARY_PATH", lib_dir())
        .output()
        .expect("run hostile");
    assert_prints_ok(&run);
}

/// A hostile Glide program (tests/abuse.c: every item of the C-library part of the
/// hostile-input review) prints "ok": no crash, no access outside its memory, no
/// memory growing with a count, errors reported. Run plain under a 4 GiB address-space
/// limit (so an unbounded read fails fast), and built with AddressSanitizer, which must
/// report nothing.
#[test]
fn a_hostile_program_is_harmless() {
    let out = std::env::temp_dir().join(format!("glide3-c-test-{}-abuse", std::process::id()));
    std::fs::create_dir_all(&out).expect("temp dir");
    let exe = build("tests/abuse", &out);
    let mut plain = Command::new(&exe);
    plain.arg("plain").env("LD_LIBRARY_PATH", lib_dir());
    address_space::limit_address_space(&mut plain, 4 << 30);
    let run = plain.output().expect("run abuse");
    assert_prints_ok(&run);

    let asan = ["-fsanitize=address", "-fno-omit-frame-pointer", "-g"];
    let Some(exe) = compile("tests/abuse", &out, &asan) else {
        eprintln!("cc cannot build with AddressSanitizer here: the ASan run is skipped");
        return;
    };
    let run = Command::new(&exe)
        .arg("asan")
        .env("LD_LIBRARY_PATH", lib_dir())
        .env("ASAN_OPTIONS", "detect_leaks=1:exitcode=99")
        .output()
        .expect("run abuse under AddressSanitizer");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!stderr.contains("AddressSanitizer"), "{stderr}");
    assert_eq!(String::from_utf8_lossy(&run.stdout), "ok\n", "{stderr}");
    assert!(run.status.success(), "{stderr}");
}

/// `VOODOO_MODEL` chooses the model the library runs: each reference emulator's model
/// draws what replaying the recorded trace on that model draws, at least one of them
/// differs from the hardware model on this scene, and an unknown name runs the hardware
/// model with one line on stderr.
#[test]
fn voodoo_model_chooses_the_board_model() {
    let front = |run: &Run| {
        image::open(&run.png)
            .expect("decode PNG")
            .to_rgb8()
            .into_raw()
    };
    let hardware = build_and_run_with("decal_blend", Some("hardware"));
    let mut differs = false;
    for r in Reference::ALL {
        let run = build_and_run_with("decal_blend", Some(r.golden_dir()));
        assert!(run.stderr.is_empty(), "{}", run.stderr);
        let trace = load_trace(&run.trace).expect("recorded trace loads");
        let mut board = Board::new(trace.board_config());
        board.set_profile(r.profile());
        let last = execute(&trace.ops, &mut board, |_| {})
            .pop()
            .expect("a dump");
        let replayed: Vec<u8> = last.data.iter().flat_map(|&p| rgb565_to_rgb8(p)).collect();
        assert!(
            replayed == front(&run),
            "{}: PNG differs from its replay",
            r.golden_dir()
        );
        differs |= front(&run) != front(&hardware);
    }
    assert!(
        differs,
        "every reference model drew what the hardware model drew"
    );
    let bogus = build_and_run_with("decal_blend", Some("vote"));
    assert!(
        bogus
            .stderr
            .starts_with("glide3: VOODOO_MODEL=vote is not hardware"),
        "{}",
        bogus.stderr
    );
    assert!(front(&bogus) == front(&hardware));
}

/// The entry points 3dfx's SST-1 Glide 3 exports without declaring them (tests/
/// sst1_extras.c declares them itself, `grSstVidMode` with its own
/// `FxVideoTimingInfo`): each one's outcome, checked from C, prints "ok".
#[test]
fn undeclared_3dfx_entry_points_link_and_work() {
    let out = std::env::temp_dir().join(format!("glide3-c-test-{}-extras", std::process::id()));
    std::fs::create_dir_all(&out).expect("temp dir");
    let exe = build("tests/sst1_extras", &out);
    let run = Command::new(&exe)
        .env("LD_LIBRARY_PATH", lib_dir())
        .env_remove("VOODOO_EXTRAS_TEST")
        .output()
        .expect("run sst1_extras");
    assert_prints_ok(&run);
}

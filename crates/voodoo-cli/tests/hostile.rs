//! The `voodoo` command against hostile traces and paths (issue 11, items 12 and 15-19):
//! memory that must not grow with the trace, files that must not be written, inputs that
//! must be read with a limit, missing goldens that must fail.
//!
//! Each run has a watchdog (a run that blocks, e.g. on a FIFO, is killed and fails the
//! test) and may have an address-space limit (`setrlimit(RLIMIT_AS)` in the child); its
//! peak resident memory comes from `wait4`.

#[path = "../../trace/tests/support/address_space.rs"]
mod address_space;

use std::io::Write;
use std::os::unix::fs::{FileTypeExt, MetadataExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What a run of `voodoo` did.
struct Run {
    /// The exit status, or `None` if a signal ended it.
    code: Option<i32>,
    stdout: String,
    stderr: String,
    /// Peak resident memory in KiB.
    max_rss_kib: i64,
}

/// How long a run may take before the watchdog kills it (it is then a failure: a run
/// that blocks, not a slow one; the slowest run here takes seconds).
const WATCHDOG: Duration = Duration::from_secs(300);

/// Runs `voodoo args` in `dir`, with its address space limited to `limit` bytes if given.
// The child is reaped with wait4 (for its peak memory), not Child::wait.
#[allow(clippy::zombie_processes)]
fn voodoo_limited(dir: &Path, args: &[&str], limit: Option<u64>) -> Run {
    let out_path = dir.join(format!(".run-{}.out", std::process::id()));
    let err_path = dir.join(format!(".run-{}.err", std::process::id()));
    let mut command = Command::new(env!("CARGO_BIN_EXE_voodoo"));
    command
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::fs::File::create(&err_path).unwrap());
    if let Some(limit) = limit {
        address_space::limit_address_space(&mut command, limit);
    }
    let child = command.spawn().unwrap();
    let pid = child.id() as libc::pid_t;
    let start = Instant::now();
    let mut status = 0;
    // SAFETY: an all-zero rusage is a valid value for wait4 to fill.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    loop {
        // SAFETY: pid is our child's; status and usage are valid for writing.
        let done = unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) };
        assert!(done >= 0, "wait4: {}", std::io::Error::last_os_error());
        if done == pid {
            break;
        }
        if start.elapsed() > WATCHDOG {
            // SAFETY: kills our own child, which has not been reaped.
            unsafe { libc::kill(pid, libc::SIGKILL) };
            // SAFETY: as above.
            unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
            panic!("voodoo {args:?} did not finish in {WATCHDOG:?}: it blocks");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let read = |p: &Path| {
        let text = String::from_utf8_lossy(&std::fs::read(p).unwrap()).into_owned();
        std::fs::remove_file(p).unwrap();
        text
    };
    Run {
        code: libc::WIFEXITED(status).then(|| libc::WEXITSTATUS(status)),
        stdout: read(&out_path),
        stderr: read(&err_path),
        max_rss_kib: usage.ru_maxrss,
    }
}

fn voodoo(dir: &Path, args: &[&str]) -> Run {
    voodoo_limited(dir, args, None)
}

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("voodoo-hostile-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The names in a folder, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with(".run-"))
        .collect();
    names.sort();
    names
}

const DUMP_BYTES: usize = 640 * 480 * 2;

// ---------------------------------------------------------------------------------------
// Items 12 and 15: replay streams, and writes each dump when it is reached.

#[test]
fn replay_of_ten_million_reads_and_4000_dumps_runs_in_bounded_memory() {
    let dir = scratch("big");
    // 10^7 `r 0` lines with a `dump` after every 2500th: 40 MB of text, 48 KB gzip. Held
    // in memory that is 320 MB of ops and 4 x 4000 x 600 KB = 9.8 GB of dumps under the
    // vote.
    let mut gz = flate2::write::GzEncoder::new(
        std::fs::File::create(dir.join("big.trace.gz")).unwrap(),
        flate2::Compression::fast(),
    );
    let mut block = b"r 0\n".repeat(2500);
    block.extend_from_slice(b"dump front d.raw\n");
    for _ in 0..4000 {
        gz.write_all(&block).unwrap();
    }
    gz.finish().unwrap();

    let run = voodoo_limited(
        &dir,
        // The vote: four boards' buffers, the most a replay holds.
        &["replay", "big.trace.gz", "--model", "vote", "--out", "out"],
        Some(512 << 20),
    );
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert_eq!(run.stdout, "wrote out/d.raw\n".repeat(4000));
    assert_eq!(names(&dir.join("out")), ["d.raw"]);
    assert_eq!(
        std::fs::metadata(dir.join("out/d.raw")).unwrap().len(),
        DUMP_BYTES as u64
    );
    // Measured: about 9 MB. The bound leaves room for allocator and thread overheads.
    eprintln!("peak resident memory: {} KiB", run.max_rss_kib);
    assert!(run.max_rss_kib < 100 << 10, "{} KiB", run.max_rss_kib);
    std::fs::remove_dir_all(dir).unwrap();
}

// ---------------------------------------------------------------------------------------
// Item 17: no file written where it should not be.

/// A trace that clears the screen and dumps the front buffer to each of `names`.
fn dumping_trace(names: &[&str]) -> String {
    let mut text = "pci 0x40 3\nw 0x124 0\n".to_owned();
    for name in names {
        text.push_str(&format!("dump front {name}\n"));
    }
    text
}

#[test]
fn default_output_is_a_fresh_folder_named_after_the_trace() {
    let dir = scratch("default-out");
    let trace = dumping_trace(&["victim.txt", ".bashrc", "evil.trace", "a.raw"]);
    std::fs::write(dir.join("evil.trace"), &trace).unwrap();
    std::fs::write(dir.join("victim.txt"), "keep me").unwrap();
    std::fs::write(dir.join(".bashrc"), "keep me too").unwrap();
    for (n, folder) in ["evil-dumps", "evil-dumps-2"].iter().enumerate() {
        let run = voodoo(&dir, &["replay", "evil.trace"]);
        assert_eq!(run.code, Some(0), "run {n}: {}", run.stderr);
        assert_eq!(
            run.stdout,
            format!(
                "writing dumps to {folder}\nwrote {folder}/victim.txt\nwrote {folder}/.bashrc\n\
                 wrote {folder}/evil.trace\nwrote {folder}/a.raw\n"
            )
        );
        assert_eq!(
            names(&dir.join(folder)),
            [".bashrc", "a.raw", "evil.trace", "victim.txt"]
        );
    }
    assert_eq!(
        std::fs::read_to_string(dir.join("victim.txt")).unwrap(),
        "keep me"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join(".bashrc")).unwrap(),
        "keep me too"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("evil.trace")).unwrap(),
        trace
    );
    assert_eq!(
        names(&dir),
        [
            ".bashrc",
            "evil-dumps",
            "evil-dumps-2",
            "evil.trace",
            "victim.txt"
        ]
    );
    // A trace without dumps makes no folder.
    std::fs::write(dir.join("quiet.trace"), "w 0x124 0\n").unwrap();
    let run = voodoo(&dir, &["replay", "quiet.trace"]);
    assert_eq!((run.code, run.stdout.as_str()), (Some(0), ""));
    assert!(!dir.join("quiet-dumps").exists());
    std::fs::remove_dir_all(dir).unwrap();
}

/// Replays a trace that dumps to `name` into `out/`; returns the run.
fn dump_into(dir: &Path, name: &str) -> Run {
    std::fs::write(dir.join("t.trace"), dumping_trace(&[name])).unwrap();
    voodoo(dir, &["replay", "t.trace", "--out", "out"])
}

#[test]
fn dumps_replace_only_earlier_dumps() {
    let dir = scratch("no-follow");
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(dir.join("outside.txt"), "outside").unwrap();
    std::os::unix::fs::symlink("../outside.txt", out.join("link.raw")).unwrap();
    std::os::unix::fs::symlink("../nowhere.txt", out.join("dangling.raw")).unwrap();
    std::fs::hard_link(dir.join("outside.txt"), out.join("hard.raw")).unwrap();
    std::fs::create_dir(out.join("dir.raw")).unwrap();
    let fifo = std::ffi::CString::new(out.join("fifo.raw").to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o644) }, 0);

    for (name, reason) in [
        ("link.raw", "is a symbolic link"),
        ("dangling.raw", "is a symbolic link"),
        (
            "hard.raw",
            "is a file with other hard links, not an earlier dump",
        ),
        ("dir.raw", "is a directory"),
        (
            "fifo.raw",
            "is not a regular file (a FIFO, socket or device)",
        ),
    ] {
        let run = dump_into(&dir, name);
        assert_eq!(run.code, Some(1), "{name}");
        assert_eq!(
            run.stderr,
            format!("voodoo: out/{name}: {reason}; not replaced\n"),
            "{name}"
        );
    }
    assert_eq!(
        std::fs::read_to_string(dir.join("outside.txt")).unwrap(),
        "outside"
    );
    assert!(!dir.join("nowhere.txt").exists());
    let kind = |n: &str| std::fs::symlink_metadata(out.join(n)).unwrap().file_type();
    assert!(kind("link.raw").is_symlink() && kind("dangling.raw").is_symlink());
    assert!(kind("fifo.raw").is_fifo() && kind("dir.raw").is_dir());
    assert_eq!(std::fs::metadata(out.join("hard.raw")).unwrap().nlink(), 2);

    // An earlier dump (a regular file with one link) is replaced, twice.
    std::fs::write(out.join("ok.raw"), "earlier").unwrap();
    for _ in 0..2 {
        let run = dump_into(&dir, "ok.raw");
        assert_eq!(
            (run.code, run.stdout.as_str()),
            (Some(0), "wrote out/ok.raw\n")
        );
        assert_eq!(
            std::fs::read(out.join("ok.raw")).unwrap(),
            vec![0; DUMP_BYTES]
        );
    }
    // The trace being replayed is never replaced, even where `--out` holds it.
    std::fs::write(dir.join("self.trace"), dumping_trace(&["self.trace"])).unwrap();
    let run = voodoo(&dir, &["replay", "self.trace", "--out", "."]);
    assert_eq!(run.code, Some(1));
    assert_eq!(
        run.stderr,
        "voodoo: ./self.trace: is an input of this run; not replaced\n"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("self.trace")).unwrap(),
        dumping_trace(&["self.trace"])
    );
    // No temporary file is left behind.
    assert_eq!(
        names(&out),
        [
            "dangling.raw",
            "dir.raw",
            "fifo.raw",
            "hard.raw",
            "link.raw",
            "ok.raw"
        ]
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn png_and_stats_files_never_block_or_write_through_links() {
    let dir = scratch("user-files");
    std::fs::write(dir.join("t.trace"), "w 0x124 0\n").unwrap();
    std::fs::write(dir.join("target.txt"), "target").unwrap();
    std::os::unix::fs::symlink("target.txt", dir.join("s.json")).unwrap();
    let fifo = std::ffi::CString::new(dir.join("f.png").to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o644) }, 0);

    let run = voodoo(&dir, &["replay", "t.trace", "--png", "f.png"]);
    assert_eq!(run.code, Some(1));
    assert_eq!(
        run.stderr,
        "voodoo: f.png: is not a regular file (a FIFO, socket or device); not replaced\n"
    );
    let run = voodoo(&dir, &["replay", "t.trace", "--stats-json", "s.json"]);
    assert_eq!(run.code, Some(1));
    assert_eq!(
        run.stderr,
        "voodoo: s.json: is a symbolic link; not replaced\n"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("target.txt")).unwrap(),
        "target"
    );
    // A regular file is replaced.
    std::fs::write(dir.join("p.png"), "old").unwrap();
    let run = voodoo(&dir, &["replay", "t.trace", "--png", "p.png"]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert_eq!(&std::fs::read(dir.join("p.png")).unwrap()[1..4], b"PNG");
    assert_eq!(
        names(&dir),
        ["f.png", "p.png", "s.json", "t.trace", "target.txt"]
    );
    std::fs::remove_dir_all(dir).unwrap();
}

// ---------------------------------------------------------------------------------------
// Item 18: missing goldens are an error.

#[test]
fn check_without_goldens_fails() {
    let dir = scratch("goldens");
    std::fs::write(dir.join("t.trace"), dumping_trace(&["t_front.raw"])).unwrap();
    let run = voodoo(&dir, &["check", "t.trace", "--goldens", "/nonexistent"]);
    assert_eq!(run.code, Some(1));
    assert_eq!(
        run.stderr,
        "voodoo: goldens folder /nonexistent: No such file or directory (os error 2)\n"
    );
    std::fs::create_dir(dir.join("empty")).unwrap();
    let run = voodoo(&dir, &["check", "t.trace", "--goldens", "empty"]);
    assert_eq!(run.code, Some(1));
    assert_eq!(
        run.stderr,
        "voodoo: goldens folder empty: holds none of the folders mame, dosbox-staging, 86box\n"
    );
    std::fs::write(dir.join("file"), "").unwrap();
    let run = voodoo(&dir, &["check", "t.trace", "--goldens", "file"]);
    assert_eq!(run.code, Some(1));
    assert_eq!(run.stderr, "voodoo: goldens folder file: not a folder\n");
    // One golden of three: the dump is not judged, and that fails.
    std::fs::create_dir_all(dir.join("one/mame")).unwrap();
    std::fs::write(dir.join("one/mame/t_front.raw"), vec![0; DUMP_BYTES]).unwrap();
    let run = voodoo(&dir, &["check", "t.trace", "--goldens", "one"]);
    assert_eq!(run.code, Some(1));
    assert_eq!(
        run.stdout,
        "t_front: fewer than two goldens, not judged\n\
         0 dumps judged: 0 consensus and 0 majority pixels fail\n"
    );
    assert_eq!(
        run.stderr,
        "voodoo: 1 dumps have fewer than two goldens in one\n"
    );
    // Two goldens: judged, and it passes.
    std::fs::create_dir_all(dir.join("one/86box")).unwrap();
    std::fs::write(dir.join("one/86box/t_front.raw"), vec![0; DUMP_BYTES]).unwrap();
    let run = voodoo(&dir, &["check", "t.trace", "--goldens", "one"]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    std::fs::remove_dir_all(dir).unwrap();
}

// ---------------------------------------------------------------------------------------
// Item 19: every input read whole is read with a limit.

#[test]
fn endless_inputs_are_bounded() {
    let dir = scratch("endless");
    std::fs::write(dir.join("t.trace"), "w 0x124 0\n").unwrap();
    let line = "voodoo: /dev/zero:1: line longer than 1048576 bytes\n";
    std::fs::create_dir_all(dir.join("mame")).unwrap();
    for args in [
        &["replay", "/dev/zero"][..],
        &["replay", "/dev/zero", "--model", "single"],
        &["info", "/dev/zero"],
        &["convert", "/dev/zero", "z.trace"],
        &["check", "/dev/zero", "--goldens", "."],
    ] {
        let run = voodoo_limited(&dir, args, Some(256 << 20));
        assert_eq!((run.code, run.stderr.as_str()), (Some(1), line), "{args:?}");
    }
    let run = voodoo_limited(
        &dir,
        &["replay", "t.trace", "--profile", "/dev/zero"],
        Some(256 << 20),
    );
    assert_eq!(run.code, Some(1));
    assert_eq!(run.stderr, "voodoo: /dev/zero: larger than 1048576 bytes\n");
    assert!(!dir.join("z.trace").exists());
    std::fs::remove_dir_all(dir).unwrap();
}

// ---------------------------------------------------------------------------------------
// Item 16: error messages stay short.

#[test]
fn errors_quote_a_few_dozen_characters() {
    let dir = scratch("quotes");
    let token = "A".repeat(260_000);
    std::fs::write(dir.join("t.trace"), format!("w 0x10 {token}\n")).unwrap();
    let run = voodoo(&dir, &["replay", "t.trace"]);
    assert_eq!(run.code, Some(1));
    assert_eq!(
        run.stderr,
        format!(
            "voodoo: t.trace:1: expected a 32-bit value (0x hex or decimal), found `{}…` (260000 bytes)\n",
            &token[..40]
        )
    );
    // Command-line arguments are at most 128 KiB each (Linux MAX_ARG_STRLEN).
    let arg = &token[..100_000];
    let run = voodoo(&dir, &["reg", arg, "1"]);
    assert_eq!(
        run.stderr,
        format!(
            "voodoo: no register named `{}…` (100000 bytes)\n",
            &token[..40]
        )
    );
    let run = voodoo(&dir, &["reg", "fbzMode", arg]);
    assert_eq!(
        run.stderr,
        format!(
            "voodoo: `{}…` (100000 bytes) is not a 32-bit number\n",
            &token[..40]
        )
    );
    std::fs::remove_dir_all(dir).unwrap();
}

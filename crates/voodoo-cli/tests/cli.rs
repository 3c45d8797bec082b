//! The `voodoo` command, run as a user would.

mod support;
use support::{scratch, stdout, voodoo};

use std::path::Path;
use std::process::Command;

const SMALL: &str = "# a comment\n\
                     config tmus 2\n\
                     pci 0x40 0x3\n\
                     w 0x000124 0\n\
                     w 0x000080 0\n\
                     w 0x000500 0\n\
                     w 0x000128 1\n\
                     w 0x400000 0x12345678\n\
                     w 0x400000 0x12345678\n\
                     dump front small_front.raw\n";

/// The demo's blessed front buffer (traces/demo/demo_front.raw.gz).
fn demo_golden() -> Vec<u16> {
    use std::io::Read;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../traces/demo/demo_front.raw.gz");
    let mut bytes = Vec::new();
    flate2::read::GzDecoder::new(std::fs::File::open(path).unwrap())
        .read_to_end(&mut bytes)
        .unwrap();
    bytes
        .chunks_exact(2)
        .map(|b| u16::from_le_bytes([b[0], b[1]]))
        .collect()
}

#[test]
fn demo_writes_a_png() {
    let dir = scratch("demo");
    let out = stdout(&voodoo(&dir, &["demo", "--no-window"]));
    let mut want = "wrote voodoo-demo.png (640x480), drawn through Glide 3:\n".to_string();
    for line in glide::demo::DESCRIPTION {
        want += &format!("  {line}\n");
    }
    assert_eq!(out, want);
    // The PNG is the demo's front buffer, blessed in traces/demo (glide3's demo_scene
    // test), each RGB565 pixel widened by bit replication.
    let image = image::open(dir.join("voodoo-demo.png")).unwrap().to_rgb8();
    assert_eq!((image.width(), image.height()), (640, 480));
    let golden = demo_golden();
    let want: Vec<u8> = golden
        .iter()
        .flat_map(|&p| sst1_trace::rgb565_to_rgb8(p))
        .collect();
    assert!(
        image.as_raw() == &want,
        "the PNG is not the blessed demo frame"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn demo_without_a_display_says_so_and_writes_the_png() {
    let dir = scratch("demo-headless");
    let output = Command::new(env!("CARGO_BIN_EXE_voodoo"))
        .args(["demo", "--png", "d.png"])
        .current_dir(&dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .unwrap();
    assert!(output.status.success());
    let why = if cfg!(feature = "window") {
        "no display is available (DISPLAY and WAYLAND_DISPLAY are unset)"
    } else {
        "this build has no window (it was built without the `window` feature)"
    };
    assert_eq!(
        String::from_utf8_lossy(&output.stderr),
        format!("voodoo: no window: {why}; the picture is in d.png\n")
    );
    let image = image::open(dir.join("d.png")).unwrap();
    assert_eq!((image.width(), image.height()), (640, 480));
    std::fs::remove_dir_all(dir).unwrap();
}

/// `voodoo ARGS` in `dir` with no display; its exit status and stderr.
fn headless(dir: &Path, args: &[&str]) -> (bool, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_voodoo"))
        .args(args)
        .current_dir(dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .unwrap();
    (
        output.status.success(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[test]
fn play_checks_its_inputs_then_needs_a_window() {
    let dir = scratch("play");
    std::fs::write(dir.join("bad.trace"), "w 0x000124 0\nbogus line\n").unwrap();
    std::fs::write(dir.join("ok.trace"), "w 0x000124 0\n").unwrap();
    assert_eq!(
        headless(&dir, &["play", "bad.trace"]),
        (
            false,
            "voodoo: bad.trace:2: unknown command `bogus`; expected config, pci, w, r, wait or dump\n"
                .into()
        )
    );
    let (ok, err) = headless(&dir, &["play", "missing.trace"]);
    assert!(!ok);
    assert!(err.starts_with("voodoo: missing.trace: "), "{err}");
    let (ok, err) = headless(&dir, &["play", "ok.trace", "--goldens", "nowhere"]);
    assert!(!ok);
    assert!(err.starts_with("voodoo: goldens folder nowhere: "), "{err}");
    assert_eq!(
        headless(&dir, &["play", "ok.trace", "--goldens", "ok.trace"]),
        (
            false,
            "voodoo: goldens folder ok.trace: not a folder\n".into()
        )
    );
    let why = if cfg!(feature = "window") {
        "no display is available (DISPLAY and WAYLAND_DISPLAY are unset)"
    } else {
        "this build has no window (it was built without the `window` feature)"
    };
    assert_eq!(
        headless(&dir, &["play", "ok.trace"]),
        (false, format!("voodoo: play needs a window: {why}\n"))
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn info_summarises() {
    let dir = scratch("info");
    std::fs::write(dir.join("small.trace"), SMALL).unwrap();
    let out = stdout(&voodoo(&dir, &["info", "small.trace"]));
    assert_eq!(
        out,
        "board: fbi_mb 4, tmus 2, tmu_mb 4\n\
         ops: 9 (6 writes, 0 reads, 1 pci, 1 dumps)\n\
         writes: 4 register, 2 frame buffer, 0 texture\n\
         triangles: 2, fastfills: 1, swaps: 1\n\
         dump front small_front.raw\n\
         registers written:\n  \
         0x080 triangleCMD      1\n  \
         0x100 ftriangleCMD     1\n  \
         0x124 fastfillCMD      1\n  \
         0x128 swapbufferCMD    1\n"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn replay_writes_dumps_png_and_stats() {
    let dir = scratch("replay");
    std::fs::write(dir.join("small.trace"), SMALL).unwrap();
    let out = stdout(&voodoo(
        &dir,
        &[
            "replay",
            "small.trace",
            "--out",
            "dumps",
            "--png",
            "f.png",
            "--stats-json",
            "s.json",
        ],
    ));
    assert_eq!(out, "wrote dumps/small_front.raw\nwrote f.png (640x480)\n");
    assert_eq!(
        std::fs::read(dir.join("dumps/small_front.raw"))
            .unwrap()
            .len(),
        640 * 480 * 2
    );
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("s.json")).unwrap()).unwrap();
    assert_eq!(stats["triangles"], 2);
    assert_eq!(stats["fastfills"], 1);
    assert_eq!(stats["swaps"], 1);
    for counter in [
        "pixels_in",
        "chroma_fail",
        "zfunc_fail",
        "afunc_fail",
        "pixels_out",
    ] {
        assert!(stats[counter].is_u64(), "{counter}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// `--no-timing` replays the same pixels and counters without counting cycles; a
/// `wait` line is host time in the count (`host_wait`); the vote refuses the switch.
#[test]
fn replay_without_timing_and_with_waits() {
    let dir = scratch("no-timing");
    let waited = SMALL.replace("w 0x000128 1\n", "wait 1000000\nw 0x000128 1\n");
    std::fs::write(dir.join("small.trace"), &waited).unwrap();
    let json = |args: &[&str], file: &str| {
        let mut all = vec!["replay", "small.trace", "--stats-json", file];
        all.extend_from_slice(args);
        stdout(&voodoo(&dir, &all));
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        serde_json::from_str::<serde_json::Value>(&text).unwrap()
    };
    let on = json(&["--out", "on"], "on.json");
    let off = json(&["--out", "off", "--no-timing"], "off.json");
    assert_eq!(
        std::fs::read(dir.join("on/small_front.raw")).unwrap(),
        std::fs::read(dir.join("off/small_front.raw")).unwrap()
    );
    for counter in ["pixels_in", "pixels_out", "triangles", "fastfills", "swaps"] {
        assert_eq!(on[counter], off[counter], "{counter}");
    }
    assert!(on["cycles"].as_u64().unwrap() >= 1_000_000);
    assert!(on["frames"][0]["host_wait"].as_u64().unwrap() > 0);
    assert_eq!(off["cycles"], 0);
    assert_eq!(off["frames"].as_array().unwrap().len(), 0);
    let info = stdout(&voodoo(&dir, &["info", "small.trace"]));
    assert!(info.contains("\nwaits: 1 (1000000 graphics-clock cycles of host time)\n"));
    let vote = voodoo(
        &dir,
        &["replay", "small.trace", "--model", "vote", "--no-timing"],
    );
    assert!(!vote.status.success());
    assert_eq!(
        String::from_utf8_lossy(&vote.stderr),
        "voodoo: --no-timing needs a one-board model (not --model vote)\n"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn convert_round_trips() {
    let dir = scratch("convert");
    std::fs::write(dir.join("small.trace"), SMALL).unwrap();
    stdout(&voodoo(&dir, &["convert", "small.trace", "b.vtrace"]));
    stdout(&voodoo(&dir, &["convert", "b.vtrace", "c.vtrace.gz"]));
    stdout(&voodoo(&dir, &["convert", "c.vtrace.gz", "d.trace.gz"]));
    let out = stdout(&voodoo(&dir, &["convert", "d.trace.gz", "e.trace"]));
    assert_eq!(out, "wrote e.trace (9 ops)\n");
    assert_eq!(
        &std::fs::read(dir.join("b.vtrace")).unwrap()[..8],
        b"SST1TRCB"
    );
    assert_eq!(
        &std::fs::read(dir.join("c.vtrace.gz")).unwrap()[..2],
        [0x1f, 0x8b]
    );
    let text = std::fs::read_to_string(dir.join("e.trace")).unwrap();
    assert_eq!(
        text,
        "config tmus 2\npci 0x40 0x00000003\nw 0x000124 0x00000000\nw 0x000080 0x00000000\n\
         w 0x000500 0x00000000\nw 0x000128 0x00000001\nw 0x400000 0x12345678\n\
         w 0x400000 0x12345678\ndump front small_front.raw\n"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn reg_decodes_by_name_or_offset() {
    let dir = std::env::temp_dir();
    let by_name = stdout(&voodoo(&dir, &["reg", "fbzMode", "0x4701"]));
    let by_offset = stdout(&voodoo(&dir, &["reg", "0x110", "18177"]));
    assert_eq!(by_name, by_offset);
    assert!(by_name.starts_with("0x110 fbzMode = "), "{by_name}");

    let unknown = voodoo(&dir, &["reg", "noSuchReg", "1"]);
    assert!(!unknown.status.success());
    assert_eq!(
        String::from_utf8_lossy(&unknown.stderr),
        "voodoo: no register named `noSuchReg`\n"
    );
}

#[test]
fn bad_trace_reports_file_and_line() {
    let dir = scratch("bad");
    std::fs::write(dir.join("bad.trace"), "w 0 0\nw 0x2 0\n").unwrap();
    let out = voodoo(&dir, &["info", "bad.trace"]);
    assert!(!out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "voodoo: bad.trace:2: expected a 4-aligned aperture offset below 0x1000000, found `0x2`\n"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

/// A 16x16 FASTFILL of colour (0x85, 0x85, 0x85) with the 2x2 dither: row 1 gets matrix
/// entries 14, 6 (classic) or 11, 9 (MAME's matrix), so red at (0, 1) is 17 or 16.
const DITHERED_FILL: &str = "pci 0x40 0x3\n\
                             w 0x000118 0x00000010\n\
                             w 0x00011c 0x00000010\n\
                             w 0x000148 0x00858585\n\
                             w 0x000110 0x00000b01\n\
                             w 0x000124 0\n\
                             dump front fill_front.raw\n";

#[test]
fn replay_takes_a_partial_profile() {
    let dir = scratch("profile");
    std::fs::write(dir.join("fill.trace"), DITHERED_FILL).unwrap();
    std::fs::write(
        dir.join("mame.json"),
        r#"{"pixel": {"dither_2x2": "Mame"}}"#,
    )
    .unwrap();
    // `--out .` each time: each replay replaces the earlier dump of the same name.
    let red_at_0_1 = |args: &[&str]| {
        let args = [args, &["--out", "."]].concat();
        stdout(&voodoo(&dir, &args));
        let raw = std::fs::read(dir.join("fill_front.raw")).unwrap();
        let i = 2 * 640;
        u16::from_le_bytes([raw[i], raw[i + 1]]) >> 11
    };
    // The hardware model (the default; the classic 2x2 matrix), and with MAME's matrix
    // set by a profile.
    assert_eq!(red_at_0_1(&["replay", "fill.trace"]), 17);
    assert_eq!(
        red_at_0_1(&["replay", "fill.trace", "--model", "hardware"]),
        17
    );
    assert_eq!(
        red_at_0_1(&["replay", "fill.trace", "--model", "single"]),
        17
    );
    assert_eq!(
        red_at_0_1(&["replay", "fill.trace", "--profile", "mame.json"]),
        16
    );
    // Each reference emulator's model: MAME's matrix gives 16, DOSBox Staging's 17, and
    // 86Box's undithered fill 0x85 >> 3 = 16; so the vote of the three writes 16.
    for (model, red) in [
        ("mame", 16),
        ("dosbox-staging", 17),
        ("86box", 16),
        ("vote", 16),
    ] {
        assert_eq!(
            red_at_0_1(&["replay", "fill.trace", "--model", model]),
            red,
            "{model}"
        );
    }
    // A profile changes the chosen model's switches only: DOSBox Staging's model with
    // MAME's 2x2 matrix.
    assert_eq!(
        red_at_0_1(&[
            "replay",
            "fill.trace",
            "--model",
            "dosbox-staging",
            "--profile",
            "mame.json"
        ]),
        16
    );
    let out = voodoo(
        &dir,
        &[
            "replay",
            "fill.trace",
            "--model",
            "vote",
            "--profile",
            "mame.json",
        ],
    );
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("one-board model"));
    std::fs::write(dir.join("bad.json"), r#"{"pixel": {"dither_2x2": "Nope"}}"#).unwrap();
    let out = voodoo(&dir, &["replay", "fill.trace", "--profile", "bad.json"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with("voodoo: bad.json: unknown variant `Nope`"),
        "{err}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn check_judges_dumps_against_goldens() {
    let dir = scratch("check");
    std::fs::write(dir.join("fill.trace"), DITHERED_FILL).unwrap();
    stdout(&voodoo(&dir, &["replay", "fill.trace", "--out", "ours"]));
    let ours = std::fs::read(dir.join("ours/fill_front.raw")).unwrap();
    // All three goldens equal to our dump: every pixel is consensus and passes.
    for name in ["mame", "dosbox-staging", "86box"] {
        std::fs::create_dir_all(dir.join("gold").join(name)).unwrap();
        std::fs::write(dir.join("gold").join(name).join("fill_front.raw"), &ours).unwrap();
    }
    let out = stdout(&voodoo(&dir, &["check", "fill.trace", "--goldens", "gold"]));
    assert!(
        out.starts_with(
            "fill_front: 0 consensus and 0 majority pixels fail (0 pixels where all differ;"
        ),
        "{out}"
    );
    // Two goldens move pixel 0 and a third disagrees with both: one majority failure;
    // pixel 1 changed in one golden only stays a majority that we meet.
    let mut changed = ours.clone();
    changed[0] ^= 0xff;
    changed[2] ^= 0x01;
    let mut other = ours.clone();
    other[0] ^= 0x0f;
    std::fs::write(dir.join("gold/mame/fill_front.raw"), &changed).unwrap();
    let mut dosbox = ours.clone();
    dosbox[0] ^= 0xff;
    std::fs::write(dir.join("gold/dosbox-staging/fill_front.raw"), &dosbox).unwrap();
    std::fs::write(dir.join("gold/86box/fill_front.raw"), &other).unwrap();
    let out = voodoo(&dir, &["check", "fill.trace", "--goldens", "gold"]);
    assert!(!out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.starts_with(
            "fill_front: 0 consensus and 1 majority pixels fail (0 pixels where all differ;"
        ),
        "{text}"
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("1 pixels break the pass rule"));
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn gen_writes_the_same_scene_for_a_seed() {
    let dir = scratch("gen");
    let a = stdout(&voodoo(
        &dir,
        &["gen", "small-tris", "--seed", "7", "--count", "30"],
    ));
    let b = stdout(&voodoo(
        &dir,
        &["gen", "small-tris", "--seed", "7", "--count", "30"],
    ));
    assert_eq!(a, b);
    assert!(
        a.starts_with("# small triangles: 30 Gouraud triangles"),
        "{a}"
    );
    assert_eq!(
        a.lines().filter(|l| l.starts_with("w 0x000080 ")).count(),
        30
    );
    let out = voodoo(
        &dir,
        &[
            "gen",
            "random-states",
            "--seed",
            "7",
            "--count",
            "3",
            "--tmus",
            "3",
            "--out",
            "rs.trace.gz",
        ],
    );
    stdout(&out);
    let info = stdout(&voodoo(&dir, &["info", "rs.trace.gz"]));
    assert!(
        info.starts_with("board: fbi_mb 4, tmus 3, tmu_mb 4\n"),
        "{info}"
    );
    assert!(info.contains("triangles: 6,"), "{info}");
    let bad = voodoo(&dir, &["gen", "random-states", "--tmus", "4"]);
    assert!(!bad.status.success());
    std::fs::remove_dir_all(dir).unwrap();
}

/// The layout of `voodoo bench`'s table and JSON on a tiny scene (no timing is checked).
#[test]
fn bench_reports_both_paths() {
    let dir = scratch("bench");
    stdout(&voodoo(
        &dir,
        &[
            "gen",
            "small-tex-tris",
            "--count",
            "20",
            "--out",
            "tiny.trace",
        ],
    ));
    let out = stdout(&voodoo(
        &dir,
        &["bench", "--iters", "1", "--threads", "2", "tiny.trace"],
    ));
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 6, "{out}");
    assert!(lines[0].starts_with("best of 1 run(s) per path, "), "{out}");
    let header: Vec<&str> = lines[1].split_whitespace().collect();
    assert_eq!(
        header,
        [
            "scene",
            "path",
            "Mpix/s",
            "Mtri/s",
            "ns/pix",
            "cyc/pix",
            "speed-up",
            "pixels",
            "in",
            "triangles"
        ]
    );
    let fast: Vec<&str> = lines[2].split_whitespace().collect();
    assert_eq!((fast[0], fast[1]), ("tiny", "fast"), "{out}");
    assert!(fast[6].ends_with('x'), "{out}");
    assert_eq!(fast[8], "20", "{out}");
    let reference: Vec<&str> = lines[3].split_whitespace().collect();
    assert_eq!(reference[0], "reference", "{out}");
    assert_eq!(reference[reference.len() - 1], "20", "{out}");
    let binary: Vec<&str> = lines[4].split_whitespace().collect();
    assert_eq!(binary[0], "binary", "{out}");
    assert!(binary[5].ends_with("x/f"), "{out}");
    assert_eq!(binary[binary.len() - 1], "20", "{out}");
    let threaded: Vec<&str> = lines[5].split_whitespace().collect();
    assert_eq!((threaded[0], threaded[1]), ("2", "thr"), "{out}");
    assert!(threaded[6].ends_with("x/1"), "{out}");
    assert_eq!(threaded[threaded.len() - 1], "20", "{out}");

    let json = stdout(&voodoo(
        &dir,
        &[
            "bench",
            "--iters",
            "1",
            "--threads",
            "1",
            "--json",
            "tiny.trace",
        ],
    ));
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["iters"], 1);
    let scene = &v["scenes"][0];
    assert_eq!(scene["name"], "tiny");
    assert_eq!(scene["triangles"], 20);
    assert_eq!(scene["counters_match"], true);
    assert!(scene["pixels_in"].as_u64().unwrap() > 0);
    for path in ["fast", "reference", "from_binary"] {
        for key in [
            "cpu_s",
            "wall_s",
            "mpix_per_s",
            "mtri_per_s",
            "ns_per_pixel",
        ] {
            assert!(scene[path][key].is_number(), "{path}.{key}: {json}");
        }
        assert!(scene[path].get("cycles_per_pixel").is_some(), "{json}");
    }
    assert!(scene["speedup"].as_f64().unwrap() > 0.0);
    assert_eq!(scene["threads"], 1);
    assert!(scene["threaded"].is_null(), "{json}");
    std::fs::remove_dir_all(dir).unwrap();
}

/// `--isa`: every copy of the span kernels draws the same pixels and `--stats` names the
/// copy that ran (capped by the CPU's); a wrong name and the vote are refused.
#[test]
fn every_copy_of_the_kernels_draws_the_same() {
    let dir = scratch("isa");
    stdout(&voodoo(
        &dir,
        &[
            "gen",
            "small-tex-tris",
            "--count",
            "300",
            "--out",
            "tex.trace",
        ],
    ));
    let mut fronts = Vec::new();
    for isa in ["baseline", "avx2", "avx512"] {
        let out = stdout(&voodoo(
            &dir,
            &["replay", "tex.trace", "--isa", isa, "--out", isa, "--stats"],
        ));
        let shaded = out
            .lines()
            .find(|l| l.starts_with("shaded by"))
            .unwrap_or("");
        assert!(shaded.contains("compiled for "), "{out}");
        if isa == "baseline" {
            assert!(shaded.contains("compiled for baseline"), "{out}");
        }
        fronts.push(std::fs::read(dir.join(isa).join("small_triangles_front.raw")).unwrap());
    }
    assert_eq!(fronts[0], fronts[1]);
    assert_eq!(fronts[0], fronts[2]);
    let bad = voodoo(&dir, &["replay", "tex.trace", "--isa", "sse4"]);
    assert!(!bad.status.success());
    assert!(
        String::from_utf8_lossy(&bad.stderr).contains("not baseline, avx2 or avx512"),
        "{}",
        String::from_utf8_lossy(&bad.stderr)
    );
    let vote = voodoo(
        &dir,
        &["replay", "tex.trace", "--isa", "avx2", "--model", "vote"],
    );
    assert!(!vote.status.success());
    std::fs::remove_dir_all(dir).unwrap();
}

/// `--method`: the exact methods draw the same pixels, an approximation on a textured
/// scene does not, and a wrong name or the vote is refused; `gen stability` writes a
/// family or names them; `bench --methods` and `--chart` on a tiny scene.
#[test]
fn methods_stability_scenes_and_chart() {
    let dir = scratch("methods");
    stdout(&voodoo(
        &dir,
        &[
            "gen",
            "small-tex-tris",
            "--count",
            "40",
            "--out",
            "tex.trace",
        ],
    ));
    let mut fronts = Vec::new();
    for method in ["exact", "reference", "nearest"] {
        stdout(&voodoo(
            &dir,
            &[
                "replay",
                "tex.trace",
                "--method",
                method,
                "--out",
                method,
                "--threads",
                "1",
            ],
        ));
        fronts.push(std::fs::read(dir.join(method).join("small_triangles_front.raw")).unwrap());
    }
    assert_eq!(fronts[0], fronts[1]);
    assert_ne!(fronts[0], fronts[2]);
    let bad = voodoo(&dir, &["replay", "tex.trace", "--method", "bilinear"]);
    assert!(!bad.status.success());
    let vote = voodoo(
        &dir,
        &[
            "replay",
            "tex.trace",
            "--method",
            "nearest",
            "--model",
            "vote",
        ],
    );
    assert!(!vote.status.success());
    assert!(
        String::from_utf8_lossy(&vote.stderr).contains("--method needs a one-board model"),
        "{}",
        String::from_utf8_lossy(&vote.stderr)
    );
    let help = stdout(&voodoo(&dir, &["replay", "--help"]));
    for name in ["lod-per-chunk", "float-divide", "fastest"] {
        assert!(help.contains(name), "{help}");
    }

    let missing = voodoo(&dir, &["gen", "stability"]);
    assert!(!missing.status.success());
    assert!(String::from_utf8_lossy(&missing.stderr).contains("thin, large, w_near_zero"));
    let wrong = voodoo(&dir, &["gen", "stability", "--family", "nope"]);
    assert!(!wrong.status.success());
    let text = stdout(&voodoo(&dir, &["gen", "stability", "--family", "thin"]));
    assert!(text.starts_with("# stability family thin: "), "{text}");
    assert_eq!(
        text.lines()
            .filter(|l| l.starts_with("dump front thin_"))
            .count(),
        6
    );

    let out = stdout(&voodoo(
        &dir,
        &[
            "bench",
            "--iters",
            "1",
            "--threads",
            "1",
            "--methods",
            "tex.trace",
        ],
    ));
    let paths: Vec<&str> = out
        .lines()
        .skip(2)
        .map(|l| {
            l.split_whitespace()
                .nth(usize::from(l.starts_with("tex")))
                .unwrap_or("")
        })
        .collect();
    assert_eq!(
        paths,
        [
            "fast",
            "reference",
            "binary",
            "nearest",
            "lod-per-chunk",
            "float-divide",
            "fastest"
        ],
        "{out}"
    );

    let out = stdout(&voodoo(
        &dir,
        &["bench", "--iters", "1", "--chart", "chart", "tex.trace"],
    ));
    assert!(out.contains("(1 traces, 6 methods)"), "{out}");
    let table = std::fs::read_to_string(dir.join("chart/table.md")).unwrap();
    assert_eq!(table.lines().count(), 2 + 6, "{table}");
    assert!(table.contains("| given | `tex` | reference |"), "{table}");
    for png in [
        "speed_vs_accuracy.png",
        "error_histogram.png",
        "stability.png",
        "error_map.png",
    ] {
        let image = image::open(dir.join("chart").join(png)).unwrap();
        assert!(image.width() > 100, "{png}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

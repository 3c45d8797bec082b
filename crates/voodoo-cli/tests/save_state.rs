//! `voodoo replay --save-at OP FILE` and `--resume FILE`: a replay resumed from a state
//! writes the dumps and the counters of the replay that was never interrupted.

mod support;
use support::{scratch, voodoo};

use std::path::Path;
use std::process::Output;

fn ok(output: Output) -> String {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).unwrap()
}

fn refused(output: Output) -> String {
    assert!(!output.status.success());
    String::from_utf8(output.stderr).unwrap()
}

fn trace(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../traces/conformance/traces")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

/// A texture download, triangles and two dumps: saved after op 1998 (past the
/// downloads, before the dumps), resumed, on the 86Box model (whose texture cache is
/// state) and on the hardware model.
#[test]
fn a_resumed_replay_writes_the_same_dumps_and_counters() {
    let dir = scratch("resume");
    let t = trace("tex_p8_palette.trace.gz");
    for model in ["86box", "hardware"] {
        let whole = ok(voodoo(
            &dir,
            &[
                "replay",
                &t,
                "--model",
                model,
                "--out",
                "whole",
                "--stats-json",
                "whole.json",
            ],
        ));
        let first = ok(voodoo(
            &dir,
            &[
                "replay",
                &t,
                "--model",
                model,
                "--save-at",
                "1998",
                "s.state",
                "--out",
                "first",
            ],
        ));
        assert!(
            first.starts_with("saved the board after op 1998 to s.state\n"),
            "{first}"
        );
        let resumed = ok(voodoo(
            &dir,
            &[
                "replay",
                &t,
                "--resume",
                "s.state",
                "--out",
                "resumed",
                "--stats-json",
                "resumed.json",
            ],
        ));
        assert_eq!(
            resumed.replace("resumed/", "whole/"),
            whole,
            "the same dumps, written in the same order"
        );
        for dump in ["tex_p8_palette_front.raw", "tex_p8_palette_depth.raw"] {
            let a = std::fs::read(dir.join("whole").join(dump)).unwrap();
            let b = std::fs::read(dir.join("resumed").join(dump)).unwrap();
            assert!(a == b, "{model}: {dump} differs");
        }
        // The counters and the modelled time, the same; the path counts ("shaded_by")
        // are the host's and not in the state, so the resumed run counts only its part.
        let counters = |name: &str| {
            let text = std::fs::read_to_string(dir.join(name)).unwrap();
            let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
            let paths = json
                .as_object_mut()
                .and_then(|o| o.remove("shaded_by"))
                .expect("shaded_by");
            (json, paths["span_kernels"].as_u64().expect("span_kernels"))
        };
        let (a, shaded_whole) = counters("whole.json");
        let (b, shaded_resumed) = counters("resumed.json");
        assert_eq!(a, b, "{model}: the counters and the modelled time");
        assert!(
            shaded_resumed < shaded_whole,
            "{model}: the resumed run shaded {shaded_resumed} of {shaded_whole} pixels"
        );
        // Saving again from a resumed replay.
        ok(voodoo(
            &dir,
            &[
                "replay",
                &t,
                "--resume",
                "s.state",
                "--save-at",
                "2000",
                "t.state",
                "--out",
                "again",
            ],
        ));
        let e = refused(voodoo(
            &dir,
            &[
                "replay",
                &t,
                "--resume",
                "t.state",
                "--save-at",
                "1999",
                "u.state",
            ],
        ));
        assert_eq!(
            e,
            "voodoo: --save-at 1999: the state resumed from was saved after op 2000, later\n"
        );
        for d in ["whole", "first", "resumed", "again"] {
            std::fs::remove_dir_all(dir.join(d)).unwrap();
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn bad_states_and_arguments_are_refused_with_a_message() {
    let dir = scratch("refused");
    let t = trace("tex_p8_palette.trace.gz");
    ok(voodoo(
        &dir,
        &["replay", &t, "--save-at", "100", "s.state", "--out", "d"],
    ));
    let cases: &[(&[&str], &str)] = &[
        (
            &["replay", &t, "--resume", "s.state", "--model", "mame"],
            "voodoo: --resume takes the model, the profile and the timing switch from the \
             state: leave out --model, --profile and --no-timing\n",
        ),
        (
            &[
                "replay",
                &trace("board_2mb.trace.gz"),
                "--resume",
                "s.state",
            ],
            "voodoo: the state is of a board with 4 MiB of frame buffer and 1 TMU(s) of 4 MiB, \
             the trace's has 2 MiB of frame buffer and 1 TMU(s) of 2 MiB\n",
        ),
        (
            &["replay", &t, "--save-at", "99999", "x.state", "--out", "e"],
            "voodoo: --save-at 99999: the trace has only 2163 ops; no state saved\n",
        ),
        (
            &[
                "replay",
                &t,
                "--save-at",
                "10",
                "x.state",
                "--model",
                "vote",
            ],
            "voodoo: --save-at and --resume need a one-board model (not --model vote)\n",
        ),
        (
            &["replay", &t, "--save-at", "ten", "x.state"],
            "voodoo: --save-at: expected an op count, found `ten`\n",
        ),
        (
            &["replay", &t, "--resume", &t],
            &format!("voodoo: {t}: not a save state (it does not start with `SST1STAT`)\n"),
        ),
    ];
    for (args, message) in cases {
        assert_eq!(refused(voodoo(&dir, args)), *message, "{args:?}");
    }
    assert!(!dir.join("x.state").exists());
    // A state cut short.
    let state = std::fs::read(dir.join("s.state")).unwrap();
    std::fs::write(dir.join("cut.state"), &state[..5000]).unwrap();
    let e = refused(voodoo(&dir, &["replay", &t, "--resume", "cut.state"]));
    assert!(
        e.starts_with("voodoo: cut.state: save state is damaged or cut short: "),
        "{e}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

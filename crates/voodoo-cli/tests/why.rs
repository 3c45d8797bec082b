//! `voodoo why`, run as a user would: the history's values against the pipeline's own
//! result (the dump a plain replay writes), against values worked out by hand from the
//! spec for a hand-built triangle, and bad input.

mod support;
use support::{scratch, stdout, voodoo};

use std::path::Path;

use serde_json::Value;

fn conformance(name: &str) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    root.join("traces/conformance/traces")
        .join(format!("{name}.trace.gz"))
        .display()
        .to_string()
}

/// The history as JSON.
fn why_json(dir: &Path, trace: &str, x: u32, y: u32, extra: &[&str]) -> Value {
    let (x, y) = (x.to_string(), y.to_string());
    let mut args = vec!["why", trace, &x, &y, "--json"];
    args.extend_from_slice(extra);
    serde_json::from_str(&stdout(&voodoo(dir, &args))).unwrap()
}

/// The value at `(x, y)` of dump `file` written by a plain `voodoo replay` (the fast
/// path, one thread) of `trace`.
fn replayed_value(dir: &Path, trace: &str, file: &str, x: u32, y: u32) -> u16 {
    let out = dir.join("dumps");
    let _ = std::fs::remove_dir_all(&out);
    let out_arg = out.display().to_string();
    stdout(&voodoo(
        dir,
        &["replay", trace, "--out", &out_arg, "--threads", "1"],
    ));
    let bytes = std::fs::read(out.join(file)).unwrap();
    let i = 2 * (y as usize * 640 + x as usize);
    u16::from_le_bytes([bytes[i], bytes[i + 1]])
}

/// The counter each kill reason moves (spec 5.31-5.35), as the history names both.
fn counter_of(kill: &Value) -> &'static str {
    match kill.as_str() {
        None => "PixelsOut",
        Some("DepthFunc") => "ZfuncFail",
        Some("Chroma") => "ChromaFail",
        Some("AlphaMask" | "AlphaFunc") => "AfuncFail",
        Some(_) => "Nothing",
    }
}

/// Checks a history against the dump of a plain replay: the dump's value is the
/// replay's, the last event that wrote the pixel wrote it, and every shaded event's kill
/// reason moved its counter. Returns the shaded events.
fn check_history(dir: &Path, trace: &str, x: u32, y: u32) -> Vec<Value> {
    let h = why_json(dir, trace, x, y, &["--dump", "1"]);
    let dump = &h["dump"];
    let file = dump["file"].as_str().unwrap();
    let expected = replayed_value(dir, trace, file, x, y);
    assert_eq!(dump["value"], u64::from(expected), "{trace} ({x}, {y})");
    assert_eq!(h["last_write"]["value"], u64::from(expected), "{trace}");
    let events = h["events"].as_array().unwrap();
    let last = &events[h["last_write"]["event"].as_u64().unwrap() as usize];
    assert_eq!(last["op"], h["last_write"]["op"]);
    let shaded: Vec<Value> = events
        .iter()
        .filter_map(|e| e["event"].get("Shaded").cloned())
        .collect();
    for s in &shaded {
        assert_eq!(s["counted"], counter_of(&s["kill"]), "{trace}: {s}");
        assert_eq!(
            (s["x"].as_u64(), s["row"].as_u64()),
            (Some(x.into()), Some(y.into()))
        );
    }
    // The final written colour the history reports is the dump's.
    let word = dump["word"].as_u64().unwrap();
    let written = match last["event"].get("Shaded") {
        Some(s) => &s["write"]["colour_word"],
        None => &last["event"]["Fastfill"]["colour_word"],
    };
    assert_eq!(written["index"], word, "{trace}");
    assert_eq!(written["value"], u64::from(expected), "{trace}");
    shaded
}

#[test]
fn untextured_gouraud_pixel_matches_the_replay() {
    let dir = scratch("gouraud");
    let shaded = check_history(&dir, &conformance("gouraud_dither4"), 300, 200);
    let s = shaded.last().unwrap();
    assert!(s["tmus"].as_array().unwrap().is_empty());
    assert_eq!(s["write"]["dither"], "Dither4x4");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn textured_two_tmu_pixel_matches_the_replay() {
    let dir = scratch("tex2");
    let shaded = check_history(&dir, &conformance("tex_2tmu_modulate"), 100, 100);
    let s = shaded.last().unwrap();
    let tmus = s["tmus"].as_array().unwrap();
    // Upstream first: TMU 1's output is what TMU 0 combines with; TMU 0's is the texel.
    assert_eq!(tmus.len(), 2);
    assert_eq!(
        (tmus[0]["tmu"].as_u64(), tmus[1]["tmu"].as_u64()),
        (Some(1), Some(0))
    );
    assert_eq!(tmus[1]["output"], s["texel"]);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn fog_and_blend_pixels_match_the_replay() {
    let dir = scratch("fogblend");
    let fog = check_history(&dir, &conformance("fog_table"), 60, 60);
    let f = fog.last().unwrap();
    assert_eq!(f["fog"]["enabled"], true);
    // Without blending, the fog's output is what is dithered and written.
    assert!(f["blend"].is_null());
    assert_eq!(f["fog"]["output"], f["write"]["colour"]);
    let blend = check_history(&dir, &conformance("alpha_blend"), 60, 20);
    let b = blend.last().unwrap();
    assert_eq!(b["blend"]["src"], b["fog"]["output"]);
    assert_eq!(b["blend"]["output"], b["write"]["colour"]);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn depth_killed_pixel_names_the_depth_test() {
    let dir = scratch("depth");
    let shaded = check_history(&dir, &conformance("depth_z"), 60, 60);
    let killed: Vec<&Value> = shaded.iter().filter(|s| !s["kill"].is_null()).collect();
    assert_eq!(killed.len(), 1);
    let k = killed[0];
    assert_eq!(k["kill"], "DepthFunc");
    assert_eq!(k["counted"], "ZfuncFail");
    assert_eq!(k["depth"]["pass"], false);
    // Killed at the depth test: no later stage ran.
    assert!(k["colour"].is_null() && k["write"].is_null());
    std::fs::remove_dir_all(dir).unwrap();
}

/// A one-TMU board set up as the conformance traces do (640x480, two colour buffers and
/// an aux buffer): the start of the hand-built traces below.
macro_rules! glide_init {
    () => {
        "config tmus 1\n\
pci 0x40 0x3\n\
w 0x000210 0x7\nw 0x000214 0x1a2\nw 0x000210 0x1\nw 0x000220 0x02c00060\n\
w 0x000224 0x020b0002\nw 0x000208 0x00120032\nw 0x00020c 0x01e0027f\n\
w 0x000218 0x1874b040\nw 0x00021c 0x77de4000\nw 0x000200 0x1\nw 0x000214 0x002000a2\n\
"
    };
}

/// [`glide_init!`]'s board, a fast fill, then the same flat triangle twice: first at
/// Z 0x1234, then at Z 0x2000, which the "less" depth test kills.
const HAND_BUILT: &str = concat!(
    glide_init!(),
    "w 0x000118 0x280\nw 0x00011c 0x1e0\n\
w 0x000104 0x0\nw 0x000108 0x0\nw 0x00010c 0x0\n\
w 0x000148 0x0\nw 0x000130 0xffff\nw 0x000110 0x631\nw 0x000124 0x0\n\
w 0x000008 0x140\nw 0x00000c 0xa0\nw 0x000010 0x640\nw 0x000014 0x140\n\
w 0x000018 0x280\nw 0x00001c 0x640\n\
w 0x000020 0x64000\nw 0x000024 0x32000\nw 0x000028 0xc8000\nw 0x00002c 0x1234000\n\
w 0x000030 0xff000\n\
w 0x000040 0x0\nw 0x000044 0x0\nw 0x000048 0x0\nw 0x00004c 0x0\nw 0x000050 0x0\n\
w 0x000060 0x0\nw 0x000064 0x0\nw 0x000068 0x0\nw 0x00006c 0x0\nw 0x000070 0x0\n\
w 0x000080 0x0\n\
w 0x00002c 0x2000000\nw 0x000080 0x0\n\
dump front hand_front.raw\n\
dump depth hand_depth.raw\n"
);

#[test]
fn hand_built_triangle_stages_are_the_spec_values() {
    let dir = scratch("hand");
    std::fs::write(dir.join("hand.trace"), HAND_BUILT).unwrap();
    let h = why_json(&dir, "hand.trace", 40, 40, &["--dump", "1"]);
    let events = h["events"].as_array().unwrap();
    assert_eq!(events.len(), 3);
    // The fill: color1 (black) to the front buffer, zaColor[15:0] to the aux buffer.
    assert_eq!(events[0]["operation"]["Fastfill"]["number"], 1);
    let fill = &events[0]["event"]["Fastfill"];
    assert_eq!(fill["colour_word"]["value"], 0);
    assert_eq!(fill["aux_word"]["value"], 0xffff);
    // Triangle 1. Iterated colour: startR/G/B/A 100.0, 50.0, 200.0, 255.0 in 12.12 with
    // zero gradients; fbzColorPath 0 selects and passes it on unchanged (spec 5.16).
    assert_eq!(events[1]["operation"]["Triangle"]["number"], 1);
    let t = &events[1]["event"]["Shaded"];
    let rgba = |r: u8, g: u8, b: u8, a: u8| serde_json::json!({"r": r, "g": g, "b": b, "a": a});
    assert_eq!(
        t["iterated"]["rgba_12_12"],
        serde_json::json!([0x64000, 0x32000, 0xc8000, 0xff000])
    );
    assert_eq!(t["iterated"]["colour"], rgba(100, 50, 200, 255));
    // startZ 0x1234000 (20.12): the 16-bit depth is 0x1234, compared "less" (fbzMode
    // 0x631: bits 7:5 = 1) against the cleared 0xffff.
    assert_eq!(t["iterated"]["z16"], 0x1234);
    assert_eq!(t["depth"]["function"], "Less");
    assert_eq!(t["depth"]["source"], 0x1234);
    assert_eq!(t["depth"]["dest"], 0xffff);
    assert_eq!(t["depth"]["pass"], true);
    assert_eq!(t["colour"]["other"], rgba(100, 50, 200, 255));
    assert_eq!(t["colour"]["combined"], rgba(100, 50, 200, 255));
    assert_eq!(t["fog"]["enabled"], false);
    assert!(t["blend"].is_null());
    // No dither (bit 8 clear): RGB565 by truncation, (100 >> 3) << 11 | (50 >> 2) << 5 |
    // (200 >> 3) = 0x6199; the aux write stores the depth.
    assert_eq!(t["write"]["dither"], "Off");
    assert_eq!(t["write"]["colour_word"]["value"], 0x6199);
    assert_eq!(t["write"]["aux_word"]["value"], 0x1234);
    assert!(t["kill"].is_null());
    assert_eq!(t["counted"], "PixelsOut");
    // Triangle 2: Z 0x2000 is not less than 0x1234.
    let k = &events[2]["event"]["Shaded"];
    assert_eq!(k["depth"]["source"], 0x2000);
    assert_eq!(k["depth"]["dest"], 0x1234);
    assert_eq!(k["kill"], "DepthFunc");
    assert_eq!(k["counted"], "ZfuncFail");
    // Triangle 2's setup is the one write since triangle 1.
    let written = events[2]["written"].as_array().unwrap();
    assert_eq!(written.len(), 1);
    assert_eq!(written[0]["name"], "startZ");
    assert_eq!(written[0]["value"], 0x2000000);
    assert_eq!(h["dump"]["value"], 0x6199);
    assert_eq!(h["last_write"]["op"], events[1]["op"]);
    // Dump 2 is the aux buffer: the history ends with triangle 1's depth.
    let h = why_json(&dir, "hand.trace", 40, 40, &[]);
    assert_eq!(h["dump"]["number"], 2);
    assert_eq!(h["dump"]["value"], 0x1234);
    assert_eq!(h["last_write"]["value"], 0x1234);
    // The text form: one block per operation.
    let text = stdout(&voodoo(
        &dir,
        &["why", "hand.trace", "40", "40", "--dump", "1"],
    ));
    assert!(
        text.contains("op 46: triangle 2 (Triangle through the pipeline)\n"),
        "{text}"
    );
    assert!(
        text.contains("  depth      Less: source 0x2000 against 0x1234: fail\n"),
        "{text}"
    );
    assert!(
        text.contains("  fate       killed: DepthFunc (counted: ZfuncFail)\n"),
        "{text}"
    );
    assert!(
        text.ends_with("dump 1 holds 0x6199 at (40, 40), written by op 44 (the history agrees)\n"),
        "{text}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn vote_shows_where_the_references_part() {
    let dir = scratch("vote");
    let trace = conformance("tex_2tmu_modulate");
    let c = why_json(&dir, &trace, 100, 100, &["--model", "vote"]);
    let histories = c["histories"].as_array().unwrap();
    let models: Vec<&str> = histories
        .iter()
        .map(|h| h["model"].as_str().unwrap())
        .collect();
    assert_eq!(models, ["mame", "dosbox-staging", "86box"]);
    // 86Box leaves the aux buffer alone when the depth buffer is off and aux writes
    // are on; MAME and DOSBox Staging write the depth (docs/accuracy.md, aux_write).
    let d = &c["divergences"].as_array().unwrap()[0];
    assert_eq!(d["stage"], "aux");
    assert_eq!(d["values"][2][1], "aux none");
    assert_eq!(d["values"][0][1], d["values"][1][1]);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn bad_input_is_refused_with_a_message() {
    let dir = scratch("bad");
    std::fs::write(dir.join("hand.trace"), HAND_BUILT).unwrap();
    std::fs::write(dir.join("broken.trace"), "w 0x000110 0x1\nfrobnicate 1 2\n").unwrap();
    let fails = |args: &[&str], message: &str| {
        let out = voodoo(&dir, args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(message), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    };
    fails(
        &["why", "hand.trace", "1024", "0"],
        "outside the frame buffer's addresses",
    );
    fails(&["why", "hand.trace", "700", "10"], "outside the last dump");
    fails(
        &["why", "hand.trace", "1", "1", "--dump", "3"],
        "--dump 3: hand.trace has 2 dump(s)",
    );
    fails(
        &["why", "hand.trace", "1", "1", "--dump", "0"],
        "--dump counts from 1",
    );
    fails(&["why", "broken.trace", "1", "1"], "broken.trace:2");
    fails(&["why", "missing.trace", "1", "1"], "missing.trace");
    let out = voodoo(&dir, &["why", "hand.trace", "-3", "1"]);
    assert_eq!(out.status.code(), Some(2));
    std::fs::remove_dir_all(dir).unwrap();
}

/// [`glide_init!`]'s board, then a triangle drawn with clipping off over rows
/// 470 to 500 of the front buffer (`fbzMode` 0x200: RGB writes only), whose rows 480 and
/// up are the first rows of the back buffer (the buffers are 150 pages, 480 rows, apart).
const PAST_THE_LAST_ROW: &str = concat!(
    glide_init!(),
    "w 0x000104 0x0\nw 0x000108 0x0\nw 0x00010c 0x0\nw 0x000110 0x200\n\
w 0x000008 0x640\nw 0x00000c 0x1d60\nw 0x000010 0xc80\nw 0x000014 0x1d60\n\
w 0x000018 0x960\nw 0x00001c 0x1f40\n\
w 0x000020 0x64000\nw 0x000024 0x32000\nw 0x000028 0xc8000\nw 0x000030 0xff000\n\
w 0x000080 0x0\n\
dump front past_front.raw\n\
dump back past_back.raw\n"
);

#[test]
fn beyond_dump_follows_rows_past_the_last() {
    let dir = scratch("beyond");
    std::fs::write(dir.join("past.trace"), PAST_THE_LAST_ROW).unwrap();
    // Row 485 of the front buffer is row 5 of the back buffer.
    let h = why_json(
        &dir,
        "past.trace",
        150,
        485,
        &["--dump", "1", "--beyond-dump"],
    );
    let dump = &h["dump"];
    assert_eq!(dump["inside"], false);
    let back = replayed_value(&dir, "past.trace", "past_back.raw", 150, 5);
    // startR/G/B 100, 50, 200 with the 4x4 dither off: 565 truncation.
    assert_eq!(back, (100 >> 3) << 11 | (50 >> 2) << 5 | (200 >> 3));
    assert_eq!(dump["value"], u64::from(back));
    assert_eq!(h["last_write"]["value"], u64::from(back));
    let events = h["events"].as_array().unwrap();
    assert_eq!(events.len(), 1);
    assert_eq!(events[0]["operation"]["Triangle"]["number"], 1);
    // The text says the dump does not show the pixel, and what the word held.
    let text = stdout(&voodoo(
        &dir,
        &[
            "why",
            "past.trace",
            "150",
            "485",
            "--dump",
            "1",
            "--beyond-dump",
        ],
    ));
    assert!(
        text.contains(&format!(
            "dump 1 (640x480) does not show (150, 485); the buffer's word there held {back:#06x}"
        )),
        "{text}"
    );
    // Without the flag the pixel is refused as before.
    let out = voodoo(&dir, &["why", "past.trace", "150", "485", "--dump", "1"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("is outside dump 1"));
}

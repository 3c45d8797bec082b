//! The example scenes and their regression goldens (traces/examples/README.md).
//!
//! * Each Rust scene (crates/glide3/examples) is recorded again and must produce
//!   exactly the committed trace `traces/examples/NAME.trace.gz`.
//! * Every committed trace in traces/examples (Rust and C examples) is replayed on a
//!   fresh board and each dump must equal its golden `golden/FILE.gz` pixel for pixel.
//!
//! `VOODOO_BLESS=1 cargo test -p glide3 --test example_scenes` rewrites the Rust scenes'
//! traces and every golden after an intended change.

// Each scene file brings its own copy of examples/support (as the example binaries do).
#![allow(clippy::duplicate_mod)]

#[allow(dead_code)]
#[path = "../examples/aa_shapes.rs"]
mod aa_shapes;
#[allow(dead_code)]
#[path = "../examples/detail_texture.rs"]
mod detail_texture;
#[allow(dead_code)]
#[path = "../examples/fog_transparency.rs"]
mod fog_transparency;

use sst1_board::Board;
use sst1_trace::{execute, load_trace, Trace};
use std::io::{Read, Write};
use std::path::PathBuf;

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../traces/examples")
}

fn blessing() -> bool {
    std::env::var_os("VOODOO_BLESS").is_some()
}

fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    enc.write_all(bytes).expect("gzip");
    enc.finish().expect("gzip")
}

fn gunzip(bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    flate2::read::GzDecoder::new(bytes)
        .read_to_end(&mut out)
        .expect("gzip");
    out
}

fn check_scene(name: &str, trace: Trace) {
    let path = dir().join(format!("{name}.trace.gz"));
    if blessing() {
        let text = sst1_trace::write_text(&trace);
        std::fs::write(&path, gzip(text.as_bytes())).expect("write trace");
    }
    let committed = load_trace(&path).expect("committed trace");
    assert!(
        committed == trace,
        "{name}: the scene's register stream differs from {}",
        path.display()
    );
}

#[test]
fn rust_scenes_record_their_committed_traces() {
    check_scene("aa_shapes", aa_shapes::trace());
    check_scene("detail_texture", detail_texture::trace());
    check_scene("fog_transparency", fog_transparency::trace());
}

#[test]
fn every_example_trace_replays_to_its_goldens() {
    let mut traces: Vec<PathBuf> = std::fs::read_dir(dir())
        .expect("traces/examples")
        .map(|e| e.expect("dir entry").path())
        .filter(|p| p.to_string_lossy().ends_with(".trace.gz"))
        .collect();
    traces.sort();
    // Five C examples and three Rust scenes.
    assert_eq!(traces.len(), 8, "{traces:?}");
    let mut dumps_checked = 0;
    for path in traces {
        let trace = load_trace(&path).expect("trace loads");
        let mut board = Board::new(trace.board_config());
        for dump in execute(&trace.ops, &mut board, |_| {}) {
            let golden = dir().join(format!("golden/{}.gz", dump.file));
            let ours = dump.to_le_bytes();
            if blessing() {
                std::fs::write(&golden, gzip(&ours)).expect("write golden");
            }
            let want = gunzip(&std::fs::read(&golden).expect("golden file"));
            assert!(
                ours == want,
                "{}: dump {} differs from its golden",
                path.display(),
                dump.file
            );
            dumps_checked += 1;
        }
    }
    assert_eq!(dumps_checked, 9, "one dump per swap (gouraud swaps twice)");
}

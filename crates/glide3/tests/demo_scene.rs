//! The demo scene (`glide::demo`, what `voodoo demo` shows): its front buffer after the
//! swap must equal the blessed `traces/demo/demo_front.raw.gz` pixel for pixel, on the
//! fast path and on the reference path (`Board::set_generic_path`) alike.
//!
//! `VOODOO_BLESS=1 cargo test --release -p glide3 --test demo_scene` rewrites the golden
//! after an intended change to the scene or the board.

use glide::BoardInfo;
use sst1_board::{Board, BoardConfig, BufferKind};
use std::cell::RefCell;
use std::io::{Read, Write};
use std::path::PathBuf;
use std::rc::Rc;

/// The front buffer after drawing the demo and swapping, on the generic path or not.
fn front(generic: bool) -> Vec<u16> {
    let config = BoardConfig {
        tmus: glide::demo::TMUS,
        ..BoardConfig::default()
    };
    let mut board = Board::new(config);
    board.set_generic_path(generic);
    let shared = Rc::new(RefCell::new(board));
    let info = BoardInfo::new(config.fbi_mb, config.tmus, config.tmu_mb);
    glide::demo::render(Box::new(shared.clone()), info).expect("the demo draws");
    let board = shared.borrow();
    assert_eq!(
        board.display_size(),
        (glide::demo::WIDTH, glide::demo::HEIGHT)
    );
    board.dump_buffer(BufferKind::Front)
}

fn golden_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../traces/demo/demo_front.raw.gz")
}

fn to_bytes(pixels: &[u16]) -> Vec<u8> {
    pixels.iter().flat_map(|p| p.to_le_bytes()).collect()
}

/// Panics with the number of differing pixels and the first one, in words.
fn assert_same(what: &str, want: &[u16], got: &[u16]) {
    assert_eq!(want.len(), got.len(), "{what}: pixel count");
    let differ: Vec<usize> = (0..want.len()).filter(|&i| want[i] != got[i]).collect();
    if let Some(&i) = differ.first() {
        let w = glide::demo::WIDTH as usize;
        panic!(
            "{what}: {} pixels differ; the first at ({}, {}): expected {:#06x}, got {:#06x}",
            differ.len(),
            i % w,
            i / w,
            want[i],
            got[i]
        );
    }
}

#[test]
fn demo_front_buffer_is_the_blessed_one_on_both_paths() {
    let fast = front(false);
    let path = golden_path();
    if std::env::var_os("VOODOO_BLESS").is_some() {
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
        enc.write_all(&to_bytes(&fast)).expect("gzip");
        std::fs::write(&path, enc.finish().expect("gzip")).expect("write golden");
    }
    let mut bytes = Vec::new();
    flate2::read::GzDecoder::new(std::fs::File::open(&path).expect("golden file"))
        .read_to_end(&mut bytes)
        .expect("gunzip golden");
    let golden: Vec<u16> = bytes
        .chunks_exact(2)
        .map(|b| u16::from_le_bytes([b[0], b[1]]))
        .collect();
    assert_same("fast path vs golden", &golden, &fast);
    // The picture is not one colour: the scene drew (a blank frame cannot be blessed
    // by accident into passing).
    let mut colours = fast.clone();
    colours.sort_unstable();
    colours.dedup();
    assert!(colours.len() > 1000, "{} colours", colours.len());
    assert_same("reference path vs fast path", &fast, &front(true));
}

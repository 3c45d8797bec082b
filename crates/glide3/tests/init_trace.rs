//! The init sequence (`grGlideInit` + `grSstWinOpen(640x480)` + Glide's default state)
//! must be the exact register stream 3dfx's SST-1 Glide 3 wrote in the glide-sdk
//! traces, and the first frame's buffer clear must follow it.

mod common;
use common::{assert_prefix, trace, Op};
use glide::consts::*;

/// Our writes for init + window open (the part every glide-sdk test shares).
fn open_640x480() -> (glide::Glide, common::Rec) {
    let (rec, g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    (g, rec)
}

#[test]
fn init_matches_test00_exactly() {
    let (_g, rec) = open_640x480();
    let ours = rec.0.borrow().clone();
    let theirs = trace("test00");
    assert_prefix(&ours, &theirs, "init vs test00");
    // The shared init part of every glide-sdk trace ends with grGlideSetState's
    // trailing packer write; nothing may be missing.
    assert_eq!(ours.len(), 5412, "init length");
    assert_eq!(ours.last(), Some(&Op::W(0xe2_0000, 0)));
}

#[test]
fn init_is_identical_across_traces() {
    let (_g, rec) = open_640x480();
    let ours = rec.0.borrow().clone();
    for t in ["test02", "test04", "test10", "test28"] {
        assert_prefix(&ours, &trace(t), t);
    }
}

#[test]
fn first_clear_of_test00() {
    let (mut g, rec) = open_640x480();
    let mut w = [0i32; 2];
    assert_eq!(g.get(GR_WDEPTH_MIN_MAX, 8, &mut w), 8);
    g.buffer_clear(0xff0000, 0, w[1] as u32);
    let ours = rec.0.borrow().clone();
    assert_prefix(&ours, &trace("test00"), "test00 first clear");
}

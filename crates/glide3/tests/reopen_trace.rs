//! Issue "Glide 3 as 3dfx shipped it", item 4: closing a window and opening one again
//! writes 3dfx's close sequence (idle, `sst1InitShutdown`: video reset and blank, a
//! graphics-engine reset, the VGA pass-through, the graphics clock at 30 MHz) and its
//! full re-initialisation of the board (`sst1InitRegisters` and the video set-up), so
//! what follows runs on the board 3dfx's library leaves. glide-sdk test30 opens
//! 640x480, closes, and opens 640x480 again: its stream is ours, write for write.

mod common;
use common::{assert_prefix, trace, Op};
use glide::consts::*;

/// Operations of glide-sdk test30: `grGlideInit` + the first `grSstWinOpen`, then
/// `grSstWinClose`, then the re-initialisation and the second `grSstWinOpen`.
const OPEN: usize = 5412;
const CLOSE: usize = 27;
/// The first open less two PCI writes: the command register (written only when the
/// board is first mapped) and the video clock enable of the first gamma load.
const REOPEN: usize = OPEN - 2;

#[test]
fn close_and_reopen_match_test30() {
    let (rec, mut g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    let theirs = trace("test30");
    assert_eq!(rec.0.borrow().len(), OPEN, "first open");

    assert!(g.win_close());
    {
        let ours = rec.0.borrow();
        assert_prefix(&ours, &theirs, "test30 close");
        assert_eq!(ours.len(), OPEN + CLOSE, "close length");
        // The close ends with sst1InitShutdown's idle; the trace then maps the board again.
        assert_eq!(ours.last(), Some(&Op::W(0x120, 0)));
        assert_eq!(theirs[OPEN + CLOSE], Op::Pci(0xe0, 0));
    }
    // Closing what is closed writes nothing.
    assert!(!g.win_close());
    assert_eq!(rec.0.borrow().len(), OPEN + CLOSE);

    assert!(g.win_open(
        GR_RESOLUTION_640x480,
        GR_REFRESH_60Hz,
        GR_COLORFORMAT_ABGR,
        GR_ORIGIN_UPPER_LEFT,
        2,
        1
    ));
    let ours = rec.0.borrow();
    assert_prefix(&ours, &theirs, "test30 reopen");
    assert_eq!(ours.len(), OPEN + CLOSE + REOPEN, "reopen length");
    // The re-initialisation resets the graphics engine as the first one did, starting
    // from the init registers the close left.
    let reinit = &ours[OPEN + CLOSE..];
    assert!(reinit.contains(&Op::W(0x210, 0x6c40_3b56)));
    assert!(!reinit.contains(&Op::Pci(0x04, 2)));
}

/// A refused reopen (a mode the board cannot show) still re-initialises the board
/// first, as 3dfx's grSstWinOpen does, and the next reopen does not do it again.
#[test]
fn a_refused_reopen_reinitialises_once() {
    let (rec, mut g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    assert!(g.win_close());
    let before = rec.0.borrow().len();
    assert!(!g.win_open(
        0x7f,
        GR_REFRESH_60Hz,
        GR_COLORFORMAT_ABGR,
        GR_ORIGIN_UPPER_LEFT,
        2,
        1
    ));
    let reinit = rec.0.borrow().len() - before;
    let theirs = trace("test30");
    // The board's re-initialisation is the reopen's stream up to the video set-up,
    // which starts by putting the video unit in reset and enabling the video clock.
    let video = theirs[OPEN + CLOSE..]
        .iter()
        .position(|op| *op == Op::Pci(0xc0, 0))
        .expect("video clock enable in test30's reopen");
    assert_eq!(reinit, video - 1, "writes of the refused reopen");
    assert_eq!(
        rec.0.borrow()[before..],
        theirs[OPEN + CLOSE..OPEN + CLOSE + reinit]
    );
    let before = rec.0.borrow().len();
    assert!(g.win_open(
        GR_RESOLUTION_640x480,
        GR_REFRESH_60Hz,
        GR_COLORFORMAT_ABGR,
        GR_ORIGIN_UPPER_LEFT,
        2,
        1
    ));
    let ours = rec.0.borrow();
    assert_eq!(
        ours[before..],
        theirs[OPEN + CLOSE + reinit..OPEN + CLOSE + REOPEN]
    );
}

/// `grGlideShutdown` with a window open closes it first, as 3dfx's SST-1 library does
/// (its `grGlideShutdown` calls `grSstWinClose` for every board): the same 27 writes
/// of test30's close, ending with the idle; with no window open it writes nothing.
#[test]
fn shutdown_closes_an_open_window() {
    let (rec, g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    let theirs = trace("test30");
    drop(g.shutdown());
    let ours = rec.0.borrow();
    assert_eq!(ours.len(), OPEN + CLOSE, "shutdown length");
    assert_prefix(&ours, &theirs, "test30 close at shutdown");
    assert_eq!(ours.last(), Some(&Op::W(0x120, 0)));

    let (rec, mut g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    assert!(g.win_close());
    let closed = rec.0.borrow().len();
    drop(g.shutdown());
    assert_eq!(rec.0.borrow().len(), closed, "shutdown after close");
}

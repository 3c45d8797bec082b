//! Shared by the example scenes: a 640x480 Glide window on an emulated SST-1 behind an
//! `sst1_trace::Recorder`, one frame, and the trace written to `traces/examples/`.

use glide::consts::*;
use glide::{BoardInfo, Glide};
use sst1_board::{Board, BoardConfig};
use sst1_trace::{write_text, DumpBuffer, Recorder, Trace};
use std::cell::RefCell;
use std::io::Write;
use std::path::PathBuf;
use std::rc::Rc;

/// Runs `draw` for one frame on a board configured as `config` and returns the trace:
/// `grGlideInit`, `grSstWinOpen(640x480)`, the scene, `grBufferSwap(1)`, then a dump of
/// the front buffer named `NAME_swap1_front.raw`. Panics if Glide reports an error.
pub fn record(name: &str, config: BoardConfig, draw: fn(&mut Glide)) -> Trace {
    // The recorder, shared between Glide (which writes through it) and this driver.
    let rec = Rc::new(RefCell::new(Recorder::new(Board::new(config), config)));
    let info = BoardInfo::new(config.fbi_mb, config.tmus, config.tmu_mb);
    let mut g = Glide::init(Box::new(rec.clone()), info);
    g.set_error_callback(Box::new(|msg, _| panic!("Glide error: {msg}")));
    g.sst_select(0);
    assert!(g.win_open(
        GR_RESOLUTION_640x480,
        GR_REFRESH_60Hz,
        GR_COLORFORMAT_ARGB,
        GR_ORIGIN_UPPER_LEFT,
        2,
        1
    ));
    draw(&mut g);
    g.buffer_swap(1);
    rec.borrow_mut()
        .dump(DumpBuffer::Front, &format!("{name}_swap1_front.raw"));
    drop(g.shutdown());
    let trace = rec.borrow().trace().clone();
    trace
}

/// Writes `trace` gzip-compressed to the path given as the first argument, or to
/// `traces/examples/NAME.trace.gz` in the repository.
pub fn save(name: &str, trace: &Trace) -> std::io::Result<PathBuf> {
    let path = std::env::args_os().nth(1).map_or_else(
        || {
            PathBuf::from(env!("CARGO_MANIFEST_DIR"))
                .join(format!("../../traces/examples/{name}.trace.gz"))
        },
        PathBuf::from,
    );
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    enc.write_all(write_text(trace).as_bytes())?;
    std::fs::write(&path, enc.finish()?)?;
    Ok(path)
}

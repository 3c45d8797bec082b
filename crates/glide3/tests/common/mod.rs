//! Shared helpers: a recording bus and a reader for the glide-sdk text traces.
#![allow(dead_code)]

use glide::consts::*;
use glide::{BoardInfo, Glide, RegisterBus};
use std::cell::RefCell;
use std::rc::Rc;

/// One bus operation as the text trace format writes it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    /// `w OFFSET VALUE`
    W(u32, u32),
    /// `pci OFFSET VALUE`
    Pci(u32, u32),
}

impl std::fmt::Display for Op {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Op::W(a, v) => write!(f, "w {a:#08x} {v:#010x} ({})", name(*a)),
            Op::Pci(a, v) => write!(f, "pci {a:#04x} {v:#010x}"),
        }
    }
}

/// Register name for failure messages.
fn name(a: u32) -> String {
    if a >= 0x80_0000 {
        return "texture memory".into();
    }
    if a >= 0x40_0000 {
        return "LFB".into();
    }
    format!("reg {:#05x} chip {:#x}", a & 0x3fc, (a >> 10) & 0xf)
}

/// A bus that records writes and answers reads with 0 (a stub board).
#[derive(Clone, Default)]
pub struct Rec(pub Rc<RefCell<Vec<Op>>>);

impl RegisterBus for Rec {
    fn write32(&mut self, addr: u32, value: u32) {
        self.0.borrow_mut().push(Op::W(addr, value));
    }
    fn read32(&mut self, _addr: u32) -> u32 {
        0
    }
    fn pci_write(&mut self, offset: u32, value: u32) {
        self.0.borrow_mut().push(Op::Pci(offset, value));
    }
}

/// All `w`/`pci` operations of a glide-sdk trace, in order (read with the project's
/// own trace parser).
pub fn trace(name: &str) -> Vec<Op> {
    let path = format!(
        "{}/../../traces/glide-sdk/traces/{name}.trace.gz",
        env!("CARGO_MANIFEST_DIR")
    );
    let trace = sst1_trace::load_trace(std::path::Path::new(&path)).expect("glide-sdk trace");
    trace
        .ops
        .iter()
        .filter_map(|op| match *op {
            sst1_trace::TraceOp::Write { addr, value } => Some(Op::W(addr, value)),
            sst1_trace::TraceOp::Pci { offset, value } => Some(Op::Pci(offset, value)),
            _ => None,
        })
        .collect()
}

/// A Glide context on a recording bus (4 MiB FBI, one 4 MiB TMU), with
/// `grSstWinOpen(640x480, 60 Hz, ABGR, origin, 2 colour buffers, 1 aux)` done.
pub fn open_640x480(origin: u32) -> (Rec, Glide) {
    open_640x480_on(BoardInfo::new(4, 1, 4), origin)
}

/// [`open_640x480`] on the board `info`.
pub fn open_640x480_on(info: BoardInfo, origin: u32) -> (Rec, Glide) {
    let rec = Rec::default();
    let mut g = Glide::init(Box::new(rec.clone()), info);
    g.sst_select(0);
    assert!(g.win_open(
        GR_RESOLUTION_640x480,
        GR_REFRESH_60Hz,
        GR_COLORFORMAT_ABGR,
        origin,
        2,
        1
    ));
    (rec, g)
}

/// Compare `ours` with the start of `theirs`; on mismatch, list the first
/// differences with their index and panic.
pub fn assert_prefix(ours: &[Op], theirs: &[Op], what: &str) {
    let n = ours.len().min(theirs.len());
    let diffs: Vec<usize> = (0..n).filter(|&i| ours[i] != theirs[i]).collect();
    if let Some(&first) = diffs.first() {
        let mut msg = format!(
            "{what}: {} of {n} operations differ; first at #{first}\n",
            diffs.len()
        );
        for i in first.saturating_sub(3)..(first + 8).min(n) {
            let mark = if ours[i] != theirs[i] { "!" } else { " " };
            msg += &format!("{mark} #{i}: ours {}  trace {}\n", ours[i], theirs[i]);
        }
        panic!("{msg}");
    }
    assert!(
        ours.len() <= theirs.len(),
        "{what}: we wrote {} ops, the trace has {}",
        ours.len(),
        theirs.len()
    );
}

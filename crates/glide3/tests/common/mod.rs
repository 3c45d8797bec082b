//! Shared helpers: a recording bus and a reader for the glide-sdk text traces.
#![allow(dead_code)]

use flate2::read::GzDecoder;
use glide::RegisterBus;
use std::cell::RefCell;
use std::io::Read;
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

fn num(s: &str) -> u32 {
    if let Some(h) = s.strip_prefix("0x") {
        u32::from_str_radix(h, 16).expect("hex number")
    } else {
        s.parse().expect("decimal number")
    }
}

/// All `w`/`pci` operations of a glide-sdk trace, in order.
pub fn trace(name: &str) -> Vec<Op> {
    let path = format!(
        "{}/../../traces/glide-sdk/traces/{name}.trace.gz",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut text = String::new();
    GzDecoder::new(std::fs::File::open(&path).expect("trace file"))
        .read_to_string(&mut text)
        .expect("gzip text");
    text.lines()
        .filter_map(|l| {
            let l = l.split('#').next().unwrap_or("");
            let mut p = l.split_whitespace();
            match p.next() {
                Some("w") => Some(Op::W(num(p.next()?), num(p.next()?))),
                Some("pci") => Some(Op::Pci(num(p.next()?), num(p.next()?))),
                _ => None,
            }
        })
        .collect()
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

//! The SST-1 (Voodoo Graphics) register map.
//!
//! Source: SST-1 Graphics Engine specification rev 1.61, sections 4 and 5
//! (`shared/reference/sst-1-spec-rev1.61.md`).
//!
//! * [`addr`]: the byte offset of every register in the (non-remapped) register map.
//! * [`color`]: the 8-bit-per-channel colour value passed between pipeline stages.
//! * [`lanes`]: the lanes of a span-kernel chunk, which both chips' kernels share.
//! * [`map`]: the register table in spec order ([`map::REGISTERS`]), name lookup,
//!   the triangle-register remap and [`map::decode`] for dumps and logs.
//! * [`types`] (re-exported here): one typed, self-describing view per mode register
//!   (`FbzMode`, `TextureMode`, ...).
//! * [`RegisterBus`]: what a driver sees of the board: 32-bit reads and writes in the
//!   16 MiB PCI aperture plus PCI configuration writes.

pub mod addr;
pub mod color;
pub mod float;
pub mod lanes;
pub mod map;
pub mod types;

pub use color::Rgba;
pub use lanes::{LanePlace, Lanes, LANES};
pub use types::*;

/// The 16 MiB PCI memory aperture of an SST-1 board, as a driver (or a trace) sees it.
///
/// Everything that drives the emulated chip goes through this trait: the trace
/// replayer, the Glide 3 front-end and the hardware-behaviour tests. A recorder can
/// therefore wrap any implementation and log what was written.
pub trait RegisterBus {
    /// One 32-bit write at byte offset `addr` of the aperture (spec section 4).
    fn write32(&mut self, addr: u32, value: u32);
    /// One 32-bit read at byte offset `addr` of the aperture.
    fn read32(&mut self, addr: u32) -> u32;
    /// A write to PCI configuration space (spec section 6); `offset` is the byte offset.
    fn pci_write(&mut self, offset: u32, value: u32);
    /// Host time passes without a bus access: `cycles` cycles of the board's graphics
    /// clock (a trace's `wait` line). A board that models time lets its engine run on
    /// meanwhile; a bus that does not model time ignores it (the default). A wrapper that
    /// forwards the other calls forwards this one too.
    fn host_wait(&mut self, cycles: u64) {
        let _ = cycles;
    }
}

/// A bus shared by several owners, such as a Glide context that writes the board and the
/// caller that reads its picture back: each call borrows it for its own duration (and
/// panics, as `RefCell` does, if it is already borrowed).
impl<B: RegisterBus + ?Sized> RegisterBus for std::rc::Rc<std::cell::RefCell<B>> {
    fn write32(&mut self, addr: u32, value: u32) {
        self.borrow_mut().write32(addr, value);
    }
    fn read32(&mut self, addr: u32) -> u32 {
        self.borrow_mut().read32(addr)
    }
    fn pci_write(&mut self, offset: u32, value: u32) {
        self.borrow_mut().pci_write(offset, value);
    }
    fn host_wait(&mut self, cycles: u64) {
        self.borrow_mut().host_wait(cycles);
    }
}

//! The register path: every chip access the front-end makes goes through [`Hw`].
//!
//! Glide never draws pixels itself: it only writes the SST-1 aperture (spec section 4)
//! and PCI configuration space (spec section 6) through a [`RegisterBus`]. The trace
//! recorder of `sst1-trace` wraps any bus, so the same writes can drive the emulated
//! board and be recorded.
//!
//! Register values are composed with the typed views of `sst1_regs` (`FbzMode`,
//! `TextureMode`, ...) and their `with_*` setters; no register bit is spelled out here.

use sst1_regs::RegisterBus;

/// Byte offset of the first texture-memory download address (spec section 8).
pub(crate) const TEX_BASE: u32 = 0x80_0000;
/// Byte offset of the linear frame buffer (spec section 4).
pub(crate) const LFB_BASE: u32 = 0x40_0000;
/// The address 3dfx's SST-1 Glide writes a zero to around writes aimed at TMU registers
/// ("packer bug" workaround): texture space, TMU field 3, bit 17 set.
/// Source: the Glide 3 SST-1 traces (`w 0xe20000 0`), derived in disst.c as
/// texture base + (3 << 21) + (1 << 17).
pub(crate) const PACKER_FIX: u32 = TEX_BASE + (3 << 21) + (1 << 17);

/// Chip-select offset of TMU `n` in the register space (spec 4: bit 11 + n).
pub(crate) const fn tmu_chip(n: usize) -> u32 {
    0x800 << n
}

/// The bus plus the helpers Glide uses to talk to the chip.
pub(crate) struct Hw {
    bus: Box<dyn RegisterBus>,
}

impl Hw {
    pub(crate) fn new(bus: Box<dyn RegisterBus>) -> Self {
        Self { bus }
    }

    /// One 32-bit register or memory write.
    pub(crate) fn w(&mut self, addr: u32, value: u32) {
        self.bus.write32(addr, value);
    }

    /// A float written to a floating-point register (its IEEE-754 bits).
    pub(crate) fn wf(&mut self, addr: u32, value: f32) {
        self.bus.write32(addr, value.to_bits());
    }

    /// A 32-bit read.
    pub(crate) fn r(&mut self, addr: u32) -> u32 {
        self.bus.read32(addr)
    }

    /// A PCI configuration write.
    pub(crate) fn pci(&mut self, offset: u32, value: u32) {
        self.bus.pci_write(offset, value);
    }

    /// The packer workaround write.
    pub(crate) fn packer(&mut self) {
        self.w(PACKER_FIX, 0);
    }

    /// A lone 16-bit frame-buffer write at byte address `addr`. The bus carries 32-bit
    /// writes only, so the neighbouring pixel is read back and written unchanged (the
    /// glide-sdk traces record lone 16-bit writes the same way).
    pub(crate) fn w16(&mut self, addr: u32, value: u16) {
        let word = addr & !3;
        let old = self.r(word);
        let merged = if addr & 2 != 0 {
            (old & 0xffff) | (u32::from(value) << 16)
        } else {
            (old & 0xffff_0000) | u32::from(value)
        };
        self.w(word, merged);
    }

    /// Take the bus back (used when the context is torn down).
    pub(crate) fn into_bus(self) -> Box<dyn RegisterBus> {
        self.bus
    }
}

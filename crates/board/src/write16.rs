//! 16-bit bus writes: what a host whose guest stores a halfword into the aperture sends.
//!
//! Spec 9: "Linear frame buffer accesses may be 32-bit or 16-bit accesses, depending
//! upon the linear frame buffer access format specified in lfbMode. Texture memory
//! accesses must be 32-bit word accesses", and spec 4: "All accesses to the memory
//! mapped registers must be 32-bit accesses. No byte (8-bit) or halfword (16-bit)
//! accesses are allowed". So a 16-bit write reaches the LFB as a write of one half of
//! the 32-bit word (`pixelfx::Fbi::lfb_write_lanes`), and a register or texture one
//! is ignored and counted (`Diagnostic::NarrowWrite`).

use crate::diagnostics::Diagnostic;
use crate::model::{with_model, ChipModel};
use crate::{aperture_offset, Board};

/// Start of the linear frame buffer region.
const LFB_BASE: u32 = 0x40_0000;
/// Start of the texture region.
const TEX_BASE: u32 = 0x80_0000;

impl Board {
    /// A 16-bit write of `value` at aperture offset `bus_addr` (the low 24 bits; bit 1
    /// selects the half of the 32-bit word, bit 0 is ignored). In the LFB region it
    /// writes that half: a pixel of the 16-bit formats, changing no other pixel (see
    /// `Fbi::lfb_write_lanes` for the lane swaps and the 32-bit formats). A register or
    /// texture-memory write, which the SST-1 takes only 32 bits wide, is ignored and
    /// counted as [`Diagnostic::NarrowWrite`]. Either is one bus write in time.
    pub fn write16(&mut self, bus_addr: u32, value: u16) {
        with_model!(self.kind, M => self.write16_as::<M>(bus_addr, value))
    }

    fn write16_as<M: ChipModel>(&mut self, bus_addr: u32, value: u16) {
        if self.timing_on {
            self.timing.write();
        }
        let half = (bus_addr >> 1) & 1;
        let word = aperture_offset(bus_addr);
        if (LFB_BASE..TEX_BASE).contains(&word) {
            let shift = 16 * half;
            self.fbi.lfb_write_lanes::<M>(
                word - LFB_BASE,
                u32::from(value) << shift,
                0xffff << shift,
            );
        } else {
            self.diagnostics.note(Diagnostic::NarrowWrite);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BoardConfig;
    use sst1_regs::{addr, RegisterBus};

    #[test]
    fn lfb_halves_are_pixels_and_other_regions_ignore_halfwords() {
        let mut board = Board::new(BoardConfig::default());
        board.pci_write(0x40, 1);
        board.write32(addr::FBI_INIT1, 10 << 4);
        board.write32(addr::FBI_INIT2, 0x96 << 11);
        board.write32(LFB_BASE + 8, 0x1111_2222);
        board.write16(LFB_BASE + 10, 0x3333);
        board.write16(LFB_BASE + 8 + 1, 0x4444); // bit 0 is ignored
        assert_eq!(board.read32(LFB_BASE + 8), 0x3333_4444);
        assert_eq!(board.fbi().fb.ram[..6], [0, 0, 0, 0, 0x4444, 0x3333]);
        let zero_writes = board.stats();
        board.write16(addr::COLOR1, 0x1234);
        board.write16(TEX_BASE + 2, 0x1234);
        assert_eq!(board.read32(addr::COLOR1), 0);
        assert_eq!(board.tmu(0).unwrap().memory()[..4], [0; 4]);
        assert_eq!(board.diagnostics().count(Diagnostic::NarrowWrite), 2);
        assert_eq!(board.stats(), zero_writes);
    }
}

//! The SST-1 Glide 3 calls that talk to the chip directly, outside the lazy state:
//! busy, retrace and video-line queries, the raw pipeline write, the delta-0 colour
//! mode. Facts from 3dfx's SST-1 Glide 3 (glide3x/sst1/glide3/src, file named at each).

use crate::consts::*;
use crate::hw::tmu_chip;
use sst1_regs::addr::{
    D_B_DX, D_B_DY, D_G_DX, D_G_DY, D_R_DX, D_R_DY, F_START_B, F_START_G, F_START_R, NOP_CMD,
    STATUS, V_RETRACE,
};

/// status bit 6, vertical retrace (sst.h `SST_VRETRACE`).
const STATUS_VRETRACE: u32 = 1 << 6;
/// status bit 9, SST-1 busy (sst.h `SST_BUSY`).
const STATUS_BUSY: u32 = 1 << 9;
/// Word registers in one chip's register space (0x000-0x3fc).
const CHIP_REGISTERS: u32 = 0x100;

impl crate::Glide {
    /// `grSstVideoLine`: the whole `vRetrace` register, unmasked (gsst.c): the scan
    /// line of the board's video timing model (docs/timing.md).
    pub fn video_line(&mut self) -> u32 {
        self.hw.r(V_RETRACE)
    }

    /// `grSstVRetraceOn`: true when the status register's retrace bit is clear
    /// (gsst.c tests `SST_VRETRACE` and answers the opposite); the board's timing model
    /// sets the bit from its frame clock (`sst1_board::timing`).
    pub fn vretrace_on(&mut self) -> bool {
        self.hw.r(STATUS) & STATUS_VRETRACE == 0
    }

    /// `grSstIsBusy` (gsst.c): unless one is outstanding, write `nopCMD` = 1 (which
    /// also clears the pixel counters, spec 5.22); then read the busy bit, and once
    /// the chip is seen idle the next call writes `nopCMD` again. The board's timing
    /// model answers busy while the queued commands would still be drawing
    /// (`sst1_board::timing`).
    pub fn is_busy(&mut self) -> bool {
        if !self.nop_cmd_sent {
            self.hw.w(NOP_CMD, 1);
            self.nop_cmd_sent = true;
        }
        let busy = self.hw.r(STATUS) & STATUS_BUSY != 0;
        if !busy {
            self.nop_cmd_sent = false;
        }
        busy
    }

    /// `grSstConfigPipeline` (gsst.c, compiled out in later trees): write `value` to
    /// word register `reg` of the FBI (`GR_FBI`, which is `GR_TMU0`'s value, so TMU 0's
    /// chip select) or of TMU `chip`, between two packer workarounds. An unknown chip
    /// or a register past the chip's space (3dfx checks neither) is an error and
    /// writes nothing.
    pub fn config_pipeline(&mut self, chip: u32, reg: u32, value: u32) {
        if self.check(
            chip > GR_TMU2,
            "grSstConfigPipeline",
            "invalid chip ID specified",
        ) || self.check(
            reg >= CHIP_REGISTERS,
            "grSstConfigPipeline",
            "register out of range",
        ) {
            return;
        }
        self.hw.packer();
        self.hw.w(tmu_chip(chip as usize) | reg << 2, value);
        self.hw.packer();
    }

    /// `_grColorCombineDelta0Mode` (gdraw.c), as `guColorCombineFunction` uses it:
    /// entering delta-0 mode writes the constant colour 3dfx keeps in
    /// `gc->state.r/g/b` to the start registers and zeroes the six RGB slopes;
    /// in the mode triangles carry no iterated RGB (gglide.c `_grUpdateParamIndex`).
    /// Only `grConstantColorValue4`, which neither 3dfx's Glide 3 headers nor our
    /// library offers, sets that colour, so it is 0.0 here.
    pub fn color_combine_delta0(&mut self, on: bool) {
        if on {
            for reg in [F_START_R, F_START_G, F_START_B] {
                self.hw.wf(reg, 0.0);
            }
            for reg in [D_R_DX, D_R_DY, D_G_DX, D_G_DY, D_B_DX, D_B_DY] {
                self.hw.w(reg, 0);
            }
        }
        self.cc_delta0 = on;
    }

    /// Whether delta-0 colour mode is on.
    pub fn in_delta0_mode(&self) -> bool {
        self.cc_delta0
    }
}

//! The SST-1 board: one Pixelfx (FBI), one to three Texelfx (TMU), and the PCI
//! aperture that feeds them (spec sections 4-6).

use serde::{Deserialize, Serialize};
use sst1_regs::RegisterBus;

/// What is on the board: memory sizes and TMU count (the trace's `config` lines).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct BoardConfig {
    /// Frame-buffer memory in MiB: 2 or 4.
    pub fbi_mb: u32,
    /// Number of TMUs: 1, 2 or 3.
    pub tmus: u32,
    /// Texture memory per TMU in MiB: 1, 2 or 4.
    pub tmu_mb: u32,
}

impl Default for BoardConfig {
    fn default() -> Self {
        Self { fbi_mb: 4, tmus: 1, tmu_mb: 4 }
    }
}

/// Which buffer of the frame buffer to read out.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum BufferKind {
    /// The buffer being displayed.
    Front,
    /// The buffer being drawn (for double buffering).
    Back,
    /// The auxiliary buffer: depth or alpha.
    Aux,
}

/// The emulated board.
pub struct Board {
    config: BoardConfig,
}

impl Board {
    pub fn new(config: BoardConfig) -> Self {
        Self { config }
    }

    pub fn config(&self) -> BoardConfig {
        self.config
    }

    /// Width and height of the video mode set by `videoDimensions`.
    pub fn display_size(&self) -> (u32, u32) {
        (640, 480)
    }

    /// The buffer as `width * height` raw 16-bit values, row 0 = first row in memory.
    pub fn dump_buffer(&self, _which: BufferKind) -> Vec<u16> {
        let (w, h) = self.display_size();
        vec![0; (w * h) as usize]
    }
}

impl RegisterBus for Board {
    fn write32(&mut self, _addr: u32, _value: u32) {}
    fn read32(&mut self, _addr: u32) -> u32 {
        0
    }
    fn pci_write(&mut self, _offset: u32, _value: u32) {}
}

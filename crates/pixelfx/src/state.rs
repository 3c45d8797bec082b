//! The FBI's part of a save state (`sst1_board::state`): what a register write, a
//! command or an LFB write can change and a later one can read back, and nothing that is
//! rebuilt from it.
//!
//! Saved: the register file, the triangle parameter registers, the frame-buffer memory
//! (as little-endian bytes), its layout and front/back buffer indices, the fog table (as
//! the 32 `fogTable` words that load it) and the counters. Not saved: the profile and its
//! dither tables (the board's model sets them), the render threads, the generic-path
//! switch and the path counts (the host's choices and what they did: a state must not
//! depend on how many threads shaded it), and the span kernels' per-triangle constants
//! (built for each triangle).

use serde::{Deserialize, Serialize};

use crate::fb::Layout;
use crate::fbi::Fbi;
use crate::params::TriangleParams;
use crate::stats::Stats;

/// The FBI's state, as [`Fbi::save_state`] takes it and [`Fbi::load_state`] puts it back.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct FbiState {
    /// The register file by normal-map register number: 256 words.
    regs: Vec<u32>,
    /// The triangle parameter registers.
    params: TriangleParams,
    /// Frame-buffer memory, its 16-bit words little-endian.
    #[serde(with = "serde_bytes")]
    ram: Vec<u8>,
    /// The layout in force.
    layout: Layout,
    /// Displayed and drawn colour buffers (0..3).
    front: u8,
    back: u8,
    /// The fog table as the 32 `fogTable` words that load it (spec 5.36).
    fog_table: [u32; 32],
    /// Statistics counters and command counts.
    stats: Stats,
}

/// Why an [`FbiState`] does not fit an FBI: a damaged or forged state.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StateMismatch(pub &'static str);

impl std::fmt::Display for StateMismatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.0)
    }
}

/// The layout of a frame buffer no init register has been written to (as
/// `FrameBuffer::new` sets it).
const POWER_ON_LAYOUT: Layout = Layout {
    row_pixels: 0,
    rgb_offset: [Some(0), Some(0), None],
    aux_offset: None,
};

impl Fbi {
    /// The FBI's state, for a save state.
    pub fn save_state(&self) -> FbiState {
        let fog_table = std::array::from_fn(|word| {
            let (f0, d0) = self.fog_table.entry(2 * word);
            let (f1, d1) = self.fog_table.entry(2 * word + 1);
            u32::from_le_bytes([d0, f0, d1, f1])
        });
        FbiState {
            regs: self.regs.to_vec(),
            params: self.params,
            ram: self.fb.ram.iter().flat_map(|w| w.to_le_bytes()).collect(),
            layout: self.fb.layout,
            front: self.fb.front as u8,
            back: self.fb.back as u8,
            fog_table,
            stats: self.stats,
        }
    }

    /// Puts back a state [`Fbi::save_state`] took, on an FBI with the same memory size.
    /// Checks every length and index first: on an error the FBI is unchanged.
    pub fn load_state(&mut self, state: FbiState) -> Result<(), StateMismatch> {
        if state.regs.len() != self.regs.len() {
            return Err(StateMismatch("the FBI's register file is not 256 words"));
        }
        if state.ram.len() != self.fb.ram.len() * 2 {
            return Err(StateMismatch(
                "the frame buffer is not the size of the board's",
            ));
        }
        if state.front > 2 || state.back > 2 {
            return Err(StateMismatch("a colour buffer index is out of range"));
        }
        let old_regs = self.regs;
        let old_layout = self.fb.layout;
        let (old_front, old_back) = (self.fb.front, self.fb.back);
        self.regs.copy_from_slice(&state.regs);
        // The layout follows from the init registers once one of them has been written,
        // and is the power-on layout before: any other is forged.
        self.recompute_layout();
        if state.layout != self.fb.layout && state.layout != POWER_ON_LAYOUT {
            self.regs = old_regs;
            self.fb.layout = old_layout;
            (self.fb.front, self.fb.back) = (old_front, old_back);
            return Err(StateMismatch(
                "the frame-buffer layout does not follow from the init registers",
            ));
        }
        self.fb.layout = state.layout;
        self.fb.front = usize::from(state.front);
        self.fb.back = usize::from(state.back);
        for (word, bytes) in self.fb.ram.iter_mut().zip(state.ram.chunks_exact(2)) {
            *word = u16::from_le_bytes([bytes[0], bytes[1]]);
        }
        self.params = state.params;
        for (word, &value) in state.fog_table.iter().enumerate() {
            self.fog_table.write(word, value);
        }
        self.stats = state.stats;
        Ok(())
    }

    /// The raw register file (normal-map register number), e.g. to compare two FBIs.
    pub fn registers(&self) -> &[u32; 256] {
        &self.regs
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::RuntimeProfile;
    use sst1_regs::addr;

    #[test]
    fn a_state_round_trips_and_forged_ones_are_refused() {
        let mut fbi = Fbi::new(2);
        fbi.write_reg::<RuntimeProfile>(addr::FBI_INIT1, 10 << 4);
        fbi.write_reg::<RuntimeProfile>(addr::FBI_INIT2, 0x96 << 11);
        fbi.write_reg::<RuntimeProfile>(addr::FOG_TABLE + 8, 0x4433_2211);
        fbi.write_reg::<RuntimeProfile>(addr::COLOR0, 0x1234_5678);
        fbi.fb.ram[12345] = 0xbeef;
        fbi.swap();
        let state = fbi.save_state();
        let mut other = Fbi::new(2);
        other.load_state(state.clone()).unwrap();
        assert_eq!(other.save_state(), state);
        assert_eq!(other.fog_table, fbi.fog_table);
        assert_eq!(other.fb.ram, fbi.fb.ram);
        assert_eq!((other.fb.front, other.fb.back), (1, 0));
        assert_eq!(other.fb.layout, fbi.fb.layout);

        // Another memory size, a short register file, a bad index, a forged layout: each
        // refused, the FBI unchanged.
        let fresh = Fbi::new(4).save_state();
        let mut four = Fbi::new(4);
        assert!(four.load_state(state.clone()).is_err());
        let mut bad = state.clone();
        bad.regs.pop();
        assert!(other.load_state(bad).is_err());
        let mut bad = state.clone();
        bad.back = 3;
        assert!(other.load_state(bad).is_err());
        let mut bad = state.clone();
        bad.layout.row_pixels = u32::MAX;
        assert!(other.load_state(bad).is_err());
        assert_eq!(other.save_state(), state);
        assert_eq!(four.save_state(), fresh);
    }
}

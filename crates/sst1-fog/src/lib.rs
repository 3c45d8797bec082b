//! The SST-1 fog table (spec 5.36 `fogTable`, used by the fog unit of spec 5.17).
//!
//! 64 entries, each an 8-bit fog blending factor (8.0) and an 8-bit delta to the next
//! entry (6.2 fixed point). The table is indexed by the 16-bit floating-point depth
//! `wfloat` (4-bit exponent in bits 15:12, 12-bit mantissa in 11:0):
//!
//! ```text
//! index = wfloat[15:10]          (exponent and the two mantissa MSBs)
//! frac  = wfloat[9:2]            (the next 8 mantissa bits)
//! blend = fog[index] + ((delta[index] & mask) * frac) >> 10
//! ```
//!
//! The `>> 10` is the 6.2 delta (`>> 2`) times an 8-bit fraction (`>> 8`).
//! Source: spec 5.17 block diagram (6-bit index from exponent and mantissa\[11:10\],
//! mantissa\[9:2\] into the 8x8 multiply); MAME `apply_fogging`, DOSBox Staging
//! `APPLY_FOGGING` and 86Box `APPLY_FOG` agree (MAME and DOSBox shift by 6 and then 4,
//! which is the same for these non-negative products).

/// Delta mask of the SST-1: all 8 delta bits take part. Source: MAME `m_fogdelta_mask`
/// and DOSBox Staging `fogdelta_mask` (0xff below Voodoo 2); 86Box uses the whole byte.
pub const DELTA_MASK_SST1: u8 = 0xff;

/// Delta mask of the Voodoo 2, whose delta bits 1:0 are flags (bit 1: fog zones).
/// Source: MAME and DOSBox Staging (0xfc for Voodoo 2).
pub const DELTA_MASK_VOODOO2: u8 = 0xfc;

/// The 64-entry fog table as loaded through the 32 `fogTable` registers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FogTable {
    /// Each entry as one word: the fog blending factor (8.0) in bits 7:0, the delta to
    /// the next factor (6.2, as written: the mask applies on use) in bits 23:16. One
    /// 32-bit load per lane in [`FogTable::blend`], which a vector gather does (there is
    /// no gather of bytes).
    entries: [u32; 64],
    /// [`DELTA_MASK_SST1`] or [`DELTA_MASK_VOODOO2`].
    delta_mask: u8,
}

impl Default for FogTable {
    fn default() -> Self {
        Self::new()
    }
}

impl FogTable {
    /// An all-zero SST-1 table ([`DELTA_MASK_SST1`]).
    pub const fn new() -> Self {
        Self::with_delta_mask(DELTA_MASK_SST1)
    }

    /// An all-zero table whose deltas are masked with `delta_mask` on use.
    pub const fn with_delta_mask(delta_mask: u8) -> Self {
        Self {
            entries: [0; 64],
            delta_mask,
        }
    }

    /// A write to `fogTable[word]` (register offset `0x160 + 4 * word`, `word` 0..32).
    /// Each word holds two entries, 2n and 2n+1:
    ///
    /// ```text
    /// bits  7:0   delta[2n]     bits 23:16  delta[2n+1]
    /// bits 15:8   fog[2n]       bits 31:24  fog[2n+1]
    /// ```
    /// Source: spec 5.36; MAME `write_fog`, DOSBox Staging and 86Box agree.
    /// A `word` beyond 31 addresses no fog table register and is ignored.
    pub fn write(&mut self, word: usize, value: u32) {
        if word >= 32 {
            return;
        }
        let [d0, f0, d1, f1] = value.to_le_bytes();
        let n = 2 * word;
        self.entries[n] = u32::from(f0) | u32::from(d0) << 16;
        self.entries[n + 1] = u32::from(f1) | u32::from(d1) << 16;
    }

    /// Entry `i` (taken modulo 64) as `(fog blending factor, delta)`, unmasked.
    pub fn entry(&self, i: usize) -> (u8, u8) {
        let entry = self.entries[i & 63];
        (entry as u8, (entry >> 16) as u8)
    }

    /// The fog blending factor for the floating-point depth `wfloat`.
    ///
    /// The result can exceed 255 (up to 255 + 63) when the table breaks the spec's rule
    /// that an entry plus its delta must not exceed 255; the references keep the sum
    /// unclamped and so does this. UNVERIFIED: what the hardware's adder does then.
    #[inline]
    pub fn blend(&self, wfloat: u16) -> u16 {
        let index = (wfloat >> 10) as usize; // 0..64
        let frac = (wfloat >> 2) & 0xff;
        let entry = self.entries[index & 63];
        let fog = entry & 0xff;
        let delta = (entry >> 16) & u32::from(self.delta_mask);
        (fog + ((delta * u32::from(frac)) >> 10)) as u16
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A table with every entry and delta different: fog[i] = 3i + 7, delta[i] = 255 - 4i
    /// (so deltas use all bits, including bits 1:0).
    fn patterned(mask: u8) -> (FogTable, [u32; 64], [u32; 64]) {
        let mut fog = [0u32; 64];
        let mut delta = [0u32; 64];
        for i in 0..64 {
            fog[i] = (3 * i as u32 + 7) & 0xff;
            delta[i] = 255 - 4 * i as u32 - (i as u32 & 3);
        }
        let mut t = FogTable::with_delta_mask(mask);
        for n in 0..32 {
            let w = delta[2 * n] | fog[2 * n] << 8 | delta[2 * n + 1] << 16 | fog[2 * n + 1] << 24;
            t.write(n, w);
        }
        (t, fog, delta)
    }

    #[test]
    fn write_layout() {
        let mut t = FogTable::new();
        t.write(5, 0x4433_2211);
        assert_eq!(t.entry(10), (0x22, 0x11));
        assert_eq!(t.entry(11), (0x44, 0x33));
        assert_eq!(t.entry(9), (0, 0));
        assert_eq!(t.entry(12), (0, 0));
        t.write(32, 0xffff_ffff); // ignored
        t.write(usize::MAX, 0xffff_ffff); // ignored
        assert_eq!(t, {
            let mut u = FogTable::new();
            u.write(5, 0x4433_2211);
            u
        });
        t.write(31, 0x8070_6050);
        assert_eq!(t.entry(62), (0x60, 0x50));
        assert_eq!(t.entry(63), (0x80, 0x70));
    }

    #[test]
    fn every_index_and_fraction_sst1_and_voodoo2() {
        for mask in [DELTA_MASK_SST1, DELTA_MASK_VOODOO2] {
            let (t, fog, delta) = patterned(mask);
            for index in 0..64u32 {
                for frac in 0..256u32 {
                    for low in 0..4u32 {
                        let w = (index << 10 | frac << 2 | low) as u16;
                        let d = delta[index as usize] & mask as u32;
                        // 6.2 delta times an 8-bit fraction, truncated.
                        let want = fog[index as usize] + (d * frac) / 1024;
                        assert_eq!(
                            t.blend(w) as u32,
                            want,
                            "mask {mask:#x} index {index} frac {frac}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn known_values() {
        let mut t = FogTable::new();
        // fog[0] = 0x10, delta[0] = 0x40 (16.0 in 6.2); fog[1] = 0x50.
        t.write(0, 0x5000_1040);
        assert_eq!(t.blend(0x0000), 0x10);
        // Half way (frac 0x80): 0x10 + 0x40 * 0x80 / 1024 = 0x10 + 8.
        assert_eq!(t.blend(0x0200), 0x18);
        assert_eq!(t.blend(0x03ff), 0x10 + (0x40 * 0xff) / 1024);
        assert_eq!(t.blend(0x0400), 0x50);
        // Out-of-spec table: 255 plus the largest delta.
        t.write(31, 0xffff_0000);
        assert_eq!(t.blend(0xffff), 255 + 63);
        // The Voodoo 2 mask drops delta bits 1:0: 0xff -> 0xfc.
        let mut v2 = FogTable::with_delta_mask(DELTA_MASK_VOODOO2);
        v2.write(31, 0xffff_0000);
        assert_eq!(v2.blend(0xffff), 255 + (0xfc * 0xff) / 1024);
        assert_eq!(FogTable::default(), FogTable::new());
    }
}

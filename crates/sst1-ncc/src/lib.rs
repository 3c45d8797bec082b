//! Narrow-channel compression (NCC, "YIQ") tables and the 8-bit palette of the SST-1 TMU.
//!
//! Spec section 5.56 (`nccTable0`, `nccTable1`, 8-bit palette) and the `tformat` table of
//! section 5.50 (formats 1 = YIQ 4-2-2 and 9 = AYIQ 8-4-2-2).
//!
//! An NCC table is twelve 32-bit register words:
//!
//! ```text
//! word 0..=3   {Y(4n+3), Y(4n+2), Y(4n+1), Y(4n)}   16 unsigned 8-bit intensities
//! word 4..=7   {I_r[8:0], I_g[8:0], I_b[8:0]}        bits 26:18, 17:9, 8:0, each 9-bit signed
//! word 8..=11  {Q_r[8:0], Q_g[8:0], Q_b[8:0]}        same packing
//! ```
//!
//! A compressed texel `{y[3:0], i[1:0], q[1:0]}` (bits 7:4, 3:2, 1:0) decodes to
//! `clamp(Y[y] + I[i] + Q[q], 0, 255)` per channel. Source: spec 5.56.1; MAME
//! `rasterizer_palette::compute_ncc` and DOSBox Staging agree on the bit positions and the
//! clamp.
//!
//! The same register space carries palette writes: a write to one of the I or Q words of
//! table 0 with bit 31 set stores `{R, G, B}` (bits 23:0) into palette entry
//! `{data[30:24], word[0]}` instead, and the NCC table write is inhibited (spec 5.56.2; MAME
//! `tmu_state::ncc_w` agrees, including that only table 0 is affected).

/// Number of 32-bit register words in one NCC table.
pub const NCC_WORDS: usize = 12;

/// The raw register words of one NCC table, in register order (spec 5.56.1).
pub type NccRegs = [u32; NCC_WORDS];

/// An RGB triple, 8 bits per channel, `[r, g, b]`.
pub type Rgb8 = [u8; 3];

/// What a write to an `nccTable` register word does (spec 5.56).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NccWrite {
    /// Store `value` into word `word` (0..12) of NCC table `table` (0 or 1).
    Table {
        /// NCC table, 0 or 1.
        table: usize,
        /// Register word within the table, 0..12.
        word: usize,
        /// The 32-bit value written.
        value: u32,
    },
    /// Store `rgb` into 8-bit palette entry `index` (the NCC write is inhibited).
    Palette {
        /// Palette index `{data[30:24], word[0]}`.
        index: u8,
        /// The colour, from data bits 23:16 (R), 15:8 (G), 7:0 (B).
        rgb: Rgb8,
    },
}

/// Classifies a write of `value` to word `word` (0..12) of NCC table `table` (0 or 1).
///
/// Source: spec 5.56.2 ("written through the NCC table 0 I and Q register space when the
/// MSB of the register write data is set"); the palette index LSB is the word's LSB
/// (even words I0, I2, Q0, Q2 give `P[0]` = 0). MAME `tmu_state::ncc_w` agrees.
pub fn classify_write(table: usize, word: usize, value: u32) -> NccWrite {
    if table == 0 && (4..NCC_WORDS).contains(&word) && value & 0x8000_0000 != 0 {
        let index = (((value >> 24) & 0x7f) << 1) as u8 | (word & 1) as u8;
        let rgb = [(value >> 16) as u8, (value >> 8) as u8, value as u8];
        NccWrite::Palette { index, rgb }
    } else {
        NccWrite::Table { table, word, value }
    }
}

/// Intensity `Y[n]` (n = 0..16) of a table: byte `n % 4` of word `n / 4` (spec 5.56.1).
pub fn y_entry(regs: &NccRegs, n: usize) -> u8 {
    let n = n & 15;
    (regs[n / 4] >> (8 * (n % 4))) as u8
}

/// Sign-extends a 9-bit two's complement field.
fn sext9(v: u32) -> i32 {
    ((v << 23) as i32) >> 23
}

/// The three 9-bit signed components `[r, g, b]` of an I or Q word (bits 26:18, 17:9, 8:0).
///
/// Bits 31:27 are ignored, so a table-1 word written with bit 31 set still decodes.
/// Source: spec 5.56.1; MAME `compute_ncc` sign-extends the same three fields.
pub fn iq_entry(word: u32) -> [i32; 3] {
    [sext9(word >> 18), sext9(word >> 9), sext9(word)]
}

/// Decodes one compressed 8-bit texel `{y[3:0], i[1:0], q[1:0]}` with the given table.
pub fn decode(regs: &NccRegs, texel: u8) -> Rgb8 {
    let y = i32::from(y_entry(regs, usize::from(texel >> 4)));
    let i = iq_entry(regs[4 + usize::from((texel >> 2) & 3)]);
    let q = iq_entry(regs[8 + usize::from(texel & 3)]);
    let ch = |c: usize| (y + i[c] + q[c]).clamp(0, 255) as u8;
    [ch(0), ch(1), ch(2)]
}

/// Decodes all 256 compressed texels of a table (index = the 8-bit texel).
///
/// The same values as [`decode`] of each texel, with each field read once: the sixteen
/// `I + Q` sums first, then each intensity added to each (the TMU expands a table on
/// every write of one of its words).
pub fn expand(regs: &NccRegs) -> [Rgb8; 256] {
    let mut iq = [[0i32; 3]; 16];
    for (k, sum) in iq.iter_mut().enumerate() {
        let (i, q) = (iq_entry(regs[4 + (k >> 2)]), iq_entry(regs[8 + (k & 3)]));
        *sum = [i[0] + q[0], i[1] + q[1], i[2] + q[2]];
    }
    let mut out = [[0; 3]; 256];
    // Texel `{y, i, q}` is entry `16 * y + (4 * i + q)`.
    for (y, row) in out.chunks_exact_mut(16).enumerate() {
        let y = i32::from(y_entry(regs, y));
        for (slot, sum) in row.iter_mut().zip(&iq) {
            *slot = sum.map(|c| (y + c).clamp(0, 255) as u8);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Packs three 9-bit signed components into an I/Q word.
    fn pack_iq(r: i32, g: i32, b: i32) -> u32 {
        ((r as u32 & 0x1ff) << 18) | ((g as u32 & 0x1ff) << 9) | (b as u32 & 0x1ff)
    }

    #[test]
    fn expand_decodes_every_texel() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..2000 {
            let mut regs = [0u32; NCC_WORDS];
            for r in &mut regs {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                *r = x as u32;
            }
            let table = expand(&regs);
            for texel in 0..=255u8 {
                assert_eq!(table[usize::from(texel)], decode(&regs, texel), "{regs:x?}");
            }
        }
    }

    #[test]
    fn y_entries_are_bytes_lsb_first() {
        let mut regs = [0u32; 12];
        regs[0] = 0x0302_0100;
        regs[1] = 0x0706_0504;
        regs[2] = 0x0b0a_0908;
        regs[3] = 0xff0e_0d0c;
        for n in 0..15 {
            assert_eq!(y_entry(&regs, n), n as u8);
        }
        assert_eq!(y_entry(&regs, 15), 0xff);
    }

    #[test]
    fn iq_fields_sign_extend() {
        assert_eq!(iq_entry(pack_iq(-256, 255, -1)), [-256, 255, -1]);
        assert_eq!(iq_entry(pack_iq(0, -2, 100)), [0, -2, 100]);
        // Bits 31:27 do not leak into the R field.
        assert_eq!(iq_entry(0xf800_0000 | pack_iq(5, 6, 7)), [5, 6, 7]);
    }

    #[test]
    fn decode_adds_and_clamps_each_channel() {
        let mut regs = [0u32; 12];
        regs[0] = 0x0000_8000; // Y1 = 0x80
        regs[3] = 0xf000_0000; // Y15 = 0xf0
        regs[4 + 2] = pack_iq(10, -20, 30); // I2
        regs[8 + 1] = pack_iq(-5, 7, 100); // Q1
                                           // y = 1, i = 2, q = 1: blue (0x80 + 130) saturates
        assert_eq!(decode(&regs, 0x19), [0x80 + 5, 0x80 - 13, 0xff]);
        // y = 15 (0xf0), i = 2, q = 1
        assert_eq!(decode(&regs, 0xf9), [0xf5, 0xe3, 0xff]);
        regs[8] = pack_iq(-256, -256, -256); // Q0
                                             // y = 1, i = 0, q = 0: all clamp at zero
        assert_eq!(decode(&regs, 0x10), [0, 0, 0]);
        let table = expand(&regs);
        assert_eq!(table[0x19], decode(&regs, 0x19));
        assert_eq!(table[0xf9], [0xf5, 0xe3, 0xff]);
    }

    #[test]
    fn palette_writes_only_via_table0_iq_with_msb() {
        // I0 (word 4): P[0] = 0
        assert_eq!(
            classify_write(0, 4, 0x8512_3456),
            NccWrite::Palette {
                index: 0x0a,
                rgb: [0x12, 0x34, 0x56]
            }
        );
        // Q3 (word 11): P[0] = 1
        assert_eq!(
            classify_write(0, 11, 0xff00_00ff),
            NccWrite::Palette {
                index: 0xff,
                rgb: [0, 0, 0xff]
            }
        );
        // I1 (word 5), index 1
        assert_eq!(
            classify_write(0, 5, 0x8000_0001),
            NccWrite::Palette {
                index: 1,
                rgb: [0, 0, 1]
            }
        );
        // MSB clear: NCC write
        assert_eq!(
            classify_write(0, 4, 0x0512_3456),
            NccWrite::Table {
                table: 0,
                word: 4,
                value: 0x0512_3456
            }
        );
        // Y words never alias the palette
        assert_eq!(
            classify_write(0, 3, 0x8000_0000),
            NccWrite::Table {
                table: 0,
                word: 3,
                value: 0x8000_0000
            }
        );
        // Table 1 never aliases the palette
        assert_eq!(
            classify_write(1, 4, 0x8512_3456),
            NccWrite::Table {
                table: 1,
                word: 4,
                value: 0x8512_3456
            }
        );
    }
}

//! The SST-1's ordered dither from 24-bit colour to the 16-bit RGB565 frame buffer
//! (spec 5.19, `fbzMode` bit 8 "enable dithering" and bit 11 "dither algorithm":
//! 0 = 4x4, 1 = 2x2; with dithering off the colour is truncated).
//!
//! Each channel is dithered with one matrix entry `d` (0..=15) chosen by the pixel's
//! screen position, `(x & 3, y & 3)` for the 4x4 matrix and `(x & 1, y & 1)` for 2x2:
//!
//! ```text
//! red, blue (8 -> 5 bits):  (2v - (v >> 4) + (v >> 7) + d) >> 4
//! green     (8 -> 6 bits):  (4v - (v >> 4) + (v >> 6) + d) >> 4
//! ```
//!
//! Source: MAME `dither_helper::dither_rb`/`dither_g` (marked hardware-verified) and
//! DOSBox Staging `dither_rb`/`dither_g` give these equations; 86Box ships precomputed
//! tables (`vid_voodoo_dither.h`) that equal them for every value and position of both
//! matrices (checked entry by entry when this crate was written). The 4x4 matrix is the
//! same in all three. The 2x2 matrix is disputed: see [`DitherMatrix2x2`].
//!
//! [`Dither`] precomputes one 256-entry table per channel width and matrix position,
//! so converting a pixel is three table lookups; [`Dither::rgb565_row_into`] computes the
//! equations over lanes instead, which vectorises.

/// The 4x4 ordered-dither matrix, `[y & 3][x & 3]`.
/// Source: MAME, DOSBox Staging and 86Box agree.
pub const MATRIX_4X4: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

/// The older 2x2 matrix, `[y & 1][x & 1]` (DOSBox Staging, 86Box).
pub const MATRIX_2X2_CLASSIC: [[u8; 2]; 2] = [[2, 10], [14, 6]];

/// MAME's 2x2 matrix, `[y & 1][x & 1]`.
pub const MATRIX_2X2_MAME: [[u8; 2]; 2] = [[8, 10], [11, 9]];

/// Which 2x2 dither matrix to use (`fbzMode` bit 11 = 1).
///
/// The references disagree. DOSBox Staging and 86Box use the older matrix
/// [`MATRIX_2X2_CLASSIC`] (2, 10 / 14, 6), which is also the 4x4 matrix's pattern scaled
/// to 2x2. MAME replaced it with [`MATRIX_2X2_MAME`] (8, 10 / 11, 9), citing the
/// iteagle arcade board's video-memory power-on test, which passes only with it. No
/// capture from an SST-1 settles it. The default is the matrix two of the three
/// references use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum DitherMatrix2x2 {
    /// 2, 10 / 14, 6 (DOSBox Staging, 86Box).
    #[default]
    Classic,
    /// 8, 10 / 11, 9 (MAME; justified there by an arcade board's memory test).
    Mame,
}

impl DitherMatrix2x2 {
    /// The matrix, `[y & 1][x & 1]`.
    pub const fn matrix(self) -> [[u8; 2]; 2] {
        match self {
            Self::Classic => MATRIX_2X2_CLASSIC,
            Self::Mame => MATRIX_2X2_MAME,
        }
    }
}

/// How a pixel's colour is reduced to RGB565: `fbzMode` bits 8 and 11 (spec 5.19).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DitherKind {
    /// Dithering disabled: plain truncation (`r >> 3`, `g >> 2`, `b >> 3`).
    #[default]
    Off,
    /// 4x4 ordered dither (bit 8 = 1, bit 11 = 0).
    Dither4x4,
    /// 2x2 ordered dither (bit 8 = 1, bit 11 = 1).
    Dither2x2,
}

/// The entry (0..=15) of the matrix `kind` selects at `(x, y)`, with `matrix_2x2` as the
/// 2x2 matrix; 0 when dithering is off. [`Dither::matrix_value`] without the tables, for
/// callers that need another 2x2 matrix than the one a [`Dither`] was built with.
pub const fn matrix_entry(kind: DitherKind, matrix_2x2: DitherMatrix2x2, x: u32, y: u32) -> u8 {
    match kind {
        DitherKind::Off => 0,
        DitherKind::Dither4x4 => MATRIX_4X4[(y & 3) as usize][(x & 3) as usize],
        DitherKind::Dither2x2 => matrix_2x2.matrix()[(y & 1) as usize][(x & 1) as usize],
    }
}

/// Red/blue: 8 bits to 5 with matrix entry `d`. Source: see the module documentation.
pub const fn dither_rb(v: u8, d: u8) -> u8 {
    let v = v as u32;
    ((2 * v - (v >> 4) + (v >> 7) + d as u32) >> 4) as u8
}

/// Green: 8 bits to 6 with matrix entry `d`. Source: see the module documentation.
pub const fn dither_g(v: u8, d: u8) -> u8 {
    let v = v as u32;
    ((4 * v - (v >> 4) + (v >> 6) + d as u32) >> 4) as u8
}

/// Lanes of one step of [`Dither::rgb565_row_into`]: a multiple of the 4-column pattern.
const ROW_LANES: usize = 16;

/// One pixel of [`Dither::rgb565_row_into`] with dithering on: [`dither_rb`] and [`dither_g`]
/// on the low 8 bits of each channel, packed to RGB565, in lane-friendly `i32`
/// arithmetic (every intermediate is below 2^11).
#[inline(always)]
fn dither_lane(r: i32, g: i32, b: i32, d: i32) -> u16 {
    let rb = |v: i32| {
        let v = v & 0xff;
        (2 * v - (v >> 4) + (v >> 7) + d) >> 4
    };
    let v = g & 0xff;
    let g6 = (4 * v - (v >> 4) + (v >> 6) + d) >> 4;
    (rb(r) << 11 | g6 << 5 | rb(b)) as u16
}

/// Dithering off: one pixel's channels truncated and packed to RGB565.
#[inline(always)]
fn truncate_lane(r: i32, g: i32, b: i32) -> u16 {
    ((r as u16 & 0xf8) << 8) | ((g as u16 & 0xfc) << 3) | ((b as u16 & 0xff) >> 3)
}

/// Dithering off: each channel truncated and packed to RGB565.
#[inline(always)]
fn truncate_lanes([r, g, b]: [&[i32]; 3], out: &mut [u16]) {
    for (o, ((r, g), b)) in out.iter_mut().zip(r.iter().zip(g).zip(b)) {
        *o = truncate_lane(*r, *g, *b);
    }
}

/// Tables for one matrix position: `[0]` red/blue (5-bit results), `[1]` green (6-bit).
type Cell = [[u8; 256]; 2];

/// Precomputed dither tables for both matrices (the 2x2 one chosen at construction).
#[derive(Clone)]
pub struct Dither {
    matrix_2x2: DitherMatrix2x2,
    /// Cells 0..16: 4x4 matrix at `y * 4 + x`; cells 16..32: 2x2 matrix at
    /// `16 + y * 4 + x` (the 2x2 matrix repeated to 4x4, so both index the same way).
    cells: Box<[Cell; 32]>,
}

impl core::fmt::Debug for Dither {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Dither")
            .field("matrix_2x2", &self.matrix_2x2)
            .finish_non_exhaustive()
    }
}

impl Dither {
    /// Builds the tables, using matrix `m` for 2x2 dithering.
    pub fn new(m: DitherMatrix2x2) -> Self {
        let m2 = m.matrix();
        let mut cells = Box::new([[[0u8; 256]; 2]; 32]);
        for (i, cell) in cells.iter_mut().enumerate() {
            let (x, y) = (i & 3, (i >> 2) & 3);
            let d = if i < 16 {
                MATRIX_4X4[y][x]
            } else {
                m2[y & 1][x & 1]
            };
            for v in 0..=255u8 {
                cell[0][v as usize] = dither_rb(v, d);
                cell[1][v as usize] = dither_g(v, d);
            }
        }
        Self {
            matrix_2x2: m,
            cells,
        }
    }

    /// The 2x2 matrix these tables were built for.
    pub fn matrix_2x2(&self) -> DitherMatrix2x2 {
        self.matrix_2x2
    }

    /// The tables for `kind` at screen position `(x, y)`; `None` when dithering is off.
    #[inline]
    fn cell(&self, kind: DitherKind, x: u32, y: u32) -> Option<&Cell> {
        let pos = ((y & 3) * 4 + (x & 3)) as usize;
        match kind {
            DitherKind::Off => None,
            DitherKind::Dither4x4 => self.cells.get(pos),
            DitherKind::Dither2x2 => self.cells.get(16 + pos),
        }
    }

    /// Converts one 8-bit-per-channel colour at screen position `(x, y)` to RGB565
    /// (red in bits 15:11, green 10:5, blue 4:0). Only the low two bits of `x` and `y`
    /// matter.
    #[inline]
    pub fn rgb565(&self, kind: DitherKind, x: u32, y: u32, r: u8, g: u8, b: u8) -> u16 {
        let (r5, g6, b5) = match self.cell(kind, x, y) {
            None => (r >> 3, g >> 2, b >> 3),
            Some(c) => (c[0][r as usize], c[1][g as usize], c[0][b as usize]),
        };
        (r5 as u16) << 11 | (g6 as u16) << 5 | b5 as u16
    }

    /// [`Dither::rgb565`] for a run of pixels on one row, written straight into the
    /// frame buffer: pixel `i` (at `(x0 + i, y)`, colour `(r[i], g[i], b[i])`, the low 8
    /// bits of each counting) replaces `dst[i]` where `write[i]` holds, and `dst[i]` keeps
    /// its word elsewhere. The same values as one call per pixel: with dithering on, the
    /// equations of the module documentation (from which the tables are built) over
    /// [`ROW_LANES`] lanes at a time, the row's matrix entries repeated every four
    /// pixels, so that the loop is plain lane arithmetic the compiler vectorises instead
    /// of three table lookups per pixel. One pass with no array of packed values in
    /// between: a packed array written at one vector width and read back at another
    /// stalled the store that followed it (measured on perf_gouraud_heavy).
    #[inline(always)]
    pub fn rgb565_row_into(
        &self,
        kind: DitherKind,
        x0: u32,
        y: u32,
        [r, g, b]: [&[i32]; 3],
        write: &[bool],
        dst: &mut [u16],
    ) {
        let n = dst
            .len()
            .min(r.len())
            .min(g.len())
            .min(b.len())
            .min(write.len());
        let (dst, r, g, b, write) = (&mut dst[..n], &r[..n], &g[..n], &b[..n], &write[..n]);
        // A bit mask rather than a choice, so that the loops vectorise.
        let put = |d: &mut u16, v: u16, w: bool| {
            let keep = (w as u16).wrapping_sub(1);
            *d = (v & !keep) | (*d & keep);
        };
        if kind == DitherKind::Off {
            for i in 0..n {
                put(&mut dst[i], truncate_lane(r[i], g[i], b[i]), write[i]);
            }
            return;
        }
        // In steps of a fixed width with the entries spread over it (indexed `i & 3`
        // instead, the loop stayed scalar).
        let d: [i32; ROW_LANES] = core::array::from_fn(|i| {
            i32::from(matrix_entry(
                kind,
                self.matrix_2x2,
                x0.wrapping_add(i as u32),
                y,
            ))
        });
        let mut dst_steps = dst.chunks_exact_mut(ROW_LANES);
        let mut src_steps = r
            .chunks_exact(ROW_LANES)
            .zip(g.chunks_exact(ROW_LANES))
            .zip(b.chunks_exact(ROW_LANES))
            .zip(write.chunks_exact(ROW_LANES));
        for (o, (((r, g), b), w)) in (&mut dst_steps).zip(&mut src_steps) {
            for i in 0..ROW_LANES {
                put(&mut o[i], dither_lane(r[i], g[i], b[i], d[i]), w[i]);
            }
        }
        let done = n - n % ROW_LANES;
        for (i, o) in dst_steps.into_remainder().iter_mut().enumerate() {
            let j = done + i;
            put(o, dither_lane(r[j], g[j], b[j], d[i]), write[j]);
        }
    }

    /// [`Dither::rgb565_row_into`] for pixels that need not share a row: pixel `i` is
    /// dithered with matrix entry `entries[i]` (what [`Dither::matrix_value`] gives at its
    /// position; ignored when dithering is off).
    #[inline(always)]
    pub fn rgb565_lanes(
        &self,
        kind: DitherKind,
        entries: &[i32],
        [r, g, b]: [&[i32]; 3],
        out: &mut [u16],
    ) {
        let n = out
            .len()
            .min(r.len())
            .min(g.len())
            .min(b.len())
            .min(entries.len());
        let (out, r, g, b, d) = (&mut out[..n], &r[..n], &g[..n], &b[..n], &entries[..n]);
        if kind == DitherKind::Off {
            truncate_lanes([r, g, b], out);
            return;
        }
        for i in 0..n {
            out[i] = dither_lane(r[i], g[i], b[i], d[i]);
        }
    }

    /// The matrix entry (0..=15) that `kind` uses at `(x, y)`; 0 when dithering is off.
    /// The alpha-blend dither subtraction (`fbzMode` bit 19) works from this value.
    #[inline]
    pub fn matrix_value(&self, kind: DitherKind, x: u32, y: u32) -> u8 {
        matrix_entry(kind, self.matrix_2x2, x, y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The matrix entry, written out independently of the crate's tables.
    fn entry(kind: DitherKind, m2: DitherMatrix2x2, x: u32, y: u32) -> u32 {
        const M4: [u32; 16] = [0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5];
        let (x, y) = (x % 4, y % 4);
        match (kind, m2) {
            (DitherKind::Off, _) => 0,
            (DitherKind::Dither4x4, _) => M4[(y * 4 + x) as usize],
            (DitherKind::Dither2x2, DitherMatrix2x2::Classic) => {
                [2, 10, 14, 6][((y % 2) * 2 + x % 2) as usize]
            }
            (DitherKind::Dither2x2, DitherMatrix2x2::Mame) => {
                [8, 10, 11, 9][((y % 2) * 2 + x % 2) as usize]
            }
        }
    }

    /// The straightforward per-pixel formula, from the reference equations.
    fn expected(kind: DitherKind, m2: DitherMatrix2x2, x: u32, y: u32, v: u32, bits: u32) -> u32 {
        if kind == DitherKind::Off {
            return v >> (8 - bits);
        }
        let d = entry(kind, m2, x, y);
        if bits == 5 {
            (v * 2 - v / 16 + v / 128 + d) / 16
        } else {
            (v * 4 - v / 16 + v / 64 + d) / 16
        }
    }

    /// Each 2x2 matrix's tables, with each dither kind.
    fn each_table_and_kind(mut check: impl FnMut(DitherMatrix2x2, &Dither, DitherKind)) {
        for m2 in [DitherMatrix2x2::Classic, DitherMatrix2x2::Mame] {
            let t = Dither::new(m2);
            for kind in [
                DitherKind::Off,
                DitherKind::Dither4x4,
                DitherKind::Dither2x2,
            ] {
                check(m2, &t, kind);
            }
        }
    }

    #[test]
    fn every_value_position_channel_and_matrix() {
        each_table_and_kind(|m2, t, kind| {
            // x and y up to 8 also checks that only their low bits matter.
            for y in 0..8 {
                for x in 0..8 {
                    for v in 0..=255u8 {
                        let vv = v as u32;
                        let want_r = expected(kind, m2, x, y, vv, 5);
                        let want_g = expected(kind, m2, x, y, vv, 6);
                        let want = (want_r << 11 | want_g << 5 | want_r) as u16;
                        assert_eq!(
                            t.rgb565(kind, x, y, v, v, v),
                            want,
                            "{m2:?} {kind:?} x{x} y{y} v{v}"
                        );
                        // Channels are independent: vary each alone.
                        assert_eq!(t.rgb565(kind, x, y, v, 0, 0), (want_r as u16) << 11);
                        assert_eq!(t.rgb565(kind, x, y, 0, v, 0), (want_g as u16) << 5);
                        assert_eq!(t.rgb565(kind, x, y, 0, 0, v), want_r as u16);
                    }
                    assert_eq!(t.matrix_value(kind, x, y) as u32, entry(kind, m2, x, y));
                }
            }
        });
    }

    /// A row written into a buffer equals the per-pixel tables where its pixels are
    /// written and keeps the buffer's words where not, for every kind and matrix and
    /// many a column, row and length (whole steps of lanes, a remainder, both), on
    /// channel values that run through 0..=255 and past it (only the low 8 bits count).
    #[test]
    fn rows_into_a_buffer_equal_pixels() {
        each_table_and_kind(|m2, t, kind| {
            for seed in 0..64i32 {
                let len = 1 + (seed as usize * 7) % 70;
                let (x0, y) = (seed as u32 * 5 % 11, seed as u32 % 6);
                let ch = |k: i32| -> Vec<i32> {
                    (0..len as i32)
                        .map(|i| (i * 37 + seed * 101 + k * 59) % 300)
                        .collect()
                };
                let (r, g, b) = (ch(0), ch(1), ch(2));
                let write: Vec<bool> = (0..len)
                    .map(|i| !(i * 13 + seed as usize).is_multiple_of(5))
                    .collect();
                let before: Vec<u16> = (0..len).map(|i| (i as u16).wrapping_mul(40503)).collect();
                let mut dst = before.clone();
                t.rgb565_row_into(kind, x0, y, [&r, &g, &b], &write, &mut dst);
                for i in 0..len {
                    let pixel =
                        t.rgb565(kind, x0 + i as u32, y, r[i] as u8, g[i] as u8, b[i] as u8);
                    let want = if write[i] { pixel } else { before[i] };
                    assert_eq!(dst[i], want, "{m2:?} {kind:?} x0 {x0} y {y} lane {i}");
                }
            }
        });
    }

    /// The conversion with an entry per pixel equals the per-pixel tables at scattered
    /// positions, for every kind and matrix.
    #[test]
    fn lanes_equal_pixels() {
        each_table_and_kind(|m2, t, kind| {
            for seed in 0..64u32 {
                let len = 1 + (seed as usize * 5) % 20;
                let pos: Vec<(u32, u32)> = (0..len as u32)
                    .map(|i| ((i * 7 + seed) % 13, (i * 3 + seed * 5) % 9))
                    .collect();
                let ch = |k: u32| -> Vec<i32> {
                    (0..len as u32)
                        .map(|i| ((i * 41 + seed * 97 + k * 61) % 300) as i32)
                        .collect()
                };
                let (r, g, b) = (ch(0), ch(1), ch(2));
                let entries: Vec<i32> = pos
                    .iter()
                    .map(|&(x, y)| i32::from(t.matrix_value(kind, x, y)))
                    .collect();
                let mut out = vec![0u16; len];
                t.rgb565_lanes(kind, &entries, [&r, &g, &b], &mut out);
                for (i, &(x, y)) in pos.iter().enumerate() {
                    let want = t.rgb565(kind, x, y, r[i] as u8, g[i] as u8, b[i] as u8);
                    assert_eq!(out[i], want, "{m2:?} {kind:?} ({x}, {y}) lane {i}");
                }
            }
        });
    }

    #[test]
    fn extremes_and_known_values() {
        let t = Dither::new(DitherMatrix2x2::Classic);
        for kind in [
            DitherKind::Off,
            DitherKind::Dither4x4,
            DitherKind::Dither2x2,
        ] {
            for p in 0..16 {
                assert_eq!(t.rgb565(kind, p % 4, p / 4, 0, 0, 0), 0);
                assert_eq!(t.rgb565(kind, p % 4, p / 4, 255, 255, 255), 0xffff);
            }
        }
        // v = 0x80 at the 4x4 matrix's 0 and 15 entries: (256 - 8 + 1 + d) >> 4.
        assert_eq!(t.rgb565(DitherKind::Dither4x4, 0, 0, 0x80, 0, 0), 15 << 11);
        assert_eq!(t.rgb565(DitherKind::Dither4x4, 0, 3, 0x80, 0, 0), 16 << 11);
        // Green 0x41 at entry 14 ((1, 2) is row 1, column 2): (260 - 4 + 1 + 14) >> 4 = 16.
        assert_eq!(t.rgb565(DitherKind::Dither4x4, 2, 1, 0, 0x41, 0), 16 << 5);
        assert_eq!(
            t.rgb565(DitherKind::Off, 7, 7, 0x87, 0x47, 0x0f),
            (0x10 << 11) | (0x11 << 5) | 0x01
        );
    }

    #[test]
    fn the_two_2x2_matrices_differ_where_expected() {
        let classic = Dither::new(DitherMatrix2x2::Classic);
        let mame = Dither::new(DitherMatrix2x2::Mame);
        assert_eq!(classic.matrix_2x2(), DitherMatrix2x2::Classic);
        // Red 0x84 = 132: (264 - 8 + 1 + d) >> 4 is 16 for d <= 14, 17 for d = 15;
        // with v = 0x85 (266 - 8 + 1 = 259) the split is at d = 13.
        assert_eq!(
            classic.rgb565(DitherKind::Dither2x2, 0, 1, 0x85, 0, 0),
            17 << 11
        ); // d = 14
        assert_eq!(
            mame.rgb565(DitherKind::Dither2x2, 0, 1, 0x85, 0, 0),
            16 << 11
        ); // d = 11
        assert_eq!(classic.matrix_value(DitherKind::Dither2x2, 3, 2), 10);
        assert_eq!(mame.matrix_value(DitherKind::Dither2x2, 3, 2), 10);
        assert_eq!(mame.matrix_value(DitherKind::Dither2x2, 2, 3), 11);
        assert_eq!(classic.matrix_value(DitherKind::Off, 1, 1), 0);
    }
}

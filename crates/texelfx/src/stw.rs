//! The S, T and W parameter registers of a TMU (spec 5.3.x, `startS` to `dWdY` and their
//! floating-point aliases `fstartS` to `fdWdY`): the start values at vertex A and the
//! gradients along X and Y, held as .32 fixed point.
//!
//! A write is decoded in two steps, where it goes ([`StwParams::decode`], a few bit
//! operations) and its conversion ([`StwParams::apply`]), so that a board whose TMUs are
//! lent to a render thread (`crates/board/src/deferred.rs`) can note the writes on the
//! calling thread ([`StwPending`]) and send them with each textured triangle's job,
//! rather than queue every write behind the triangles.

use crate::Fx32;

/// A TMU's S, T, W start values and gradients (.32 fixed point).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StwParams {
    /// Rows [`START`] (S, T, W at vertex A), [`DX`] (dS/dX, dT/dX, dW/dX) and [`DY`]
    /// (dS/dY, dT/dY, dW/dY); register `3 * row + component` (component 0 S, 1 T, 2 W)
    /// is word `3 * row + component` of the rows flattened.
    pub(crate) rows: [[Fx32; 3]; 3],
}

/// The start values' row of [`StwParams`].
pub(crate) const START: usize = 0;
/// The X gradients' row of [`StwParams`].
pub(crate) const DX: usize = 1;
/// The Y gradients' row of [`StwParams`].
pub(crate) const DY: usize = 2;

/// Converts an IEEE single to fixed point with 32 fraction bits, truncating towards zero
/// ([`sst1_regs::float::float_to_fixed64`], the FBI's converter).
fn float_to_fx32(data: u32) -> Fx32 {
    sst1_regs::float::float_to_fixed64(data, 32)
}

/// A write to one of the nine S, T, W registers ([`StwParams::decode`]), as written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StwWrite {
    /// `3 * row + component`: row 0 the start values, 1 d/dX, 2 d/dY; component 0 S,
    /// 1 T, 2 W.
    register: usize,
    /// Written through the floating-point alias.
    float: bool,
    value: u32,
}

impl StwWrite {
    /// The value as .32 fixed point: the fixed-point forms are S and T 14.18 and W 2.30
    /// (spec 5.3.x); the floats are converted.
    #[inline(always)]
    fn fixed(self) -> Fx32 {
        if self.float {
            float_to_fx32(self.value)
        } else {
            Fx32::from(self.value as i32) << fixed_shift(self.register)
        }
    }
}

/// How far register `register`'s fixed-point form shifts to .32: 14 for S and T (14.18),
/// 2 for W (2.30).
#[inline(always)]
fn fixed_shift(register: usize) -> u32 {
    if register % 3 == 2 {
        2
    } else {
        14
    }
}

/// Per register-map word below 0x100 (offset bits 7:2): the S, T, W register it is
/// (`3 * row + component`, plus [`FLOAT`] for a floating-point alias), or [`NONE`].
/// Built from the map's rule ([`StwParams::decode`]).
const WORDS: [u8; 64] = {
    let mut t = [NONE; 64];
    let mut word = 0;
    while word < 64 {
        let o = (word as u32) << 2;
        let component = ((o >> 2) & 7).wrapping_sub(5);
        let row = ((o >> 5) & 3).wrapping_sub(1);
        if component <= 2 && row <= 2 {
            let float = if o & 0x80 != 0 { FLOAT } else { 0 };
            t[word] = (3 * row + component) as u8 | float;
        }
        word += 1;
    }
    t
};
const FLOAT: u8 = 0x10;
const NONE: u8 = 0xff;

impl StwParams {
    /// The write of `value` to the register at normal-map `offset`, if it is one of these
    /// (`None` for any other register).
    ///
    /// The map (spec 5): `startS`, `startT`, `startW` at 0x034, 0x038, 0x03c; the X
    /// gradients 0x20 above, the Y gradients 0x40 above; the floating-point aliases 0x80
    /// above each. So bits 4:2 are 5, 6, 7 for S, T, W, and bits 6:5 are 1, 2, 3 for the
    /// start, d/dX and d/dY (one lookup in a table built from that rule).
    #[inline(always)]
    pub fn decode(offset: u32, value: u32) -> Option<StwWrite> {
        let word = ((offset & 0x3fc) >> 2) as usize;
        let entry = *WORDS.get(word)?;
        if entry == NONE {
            return None;
        }
        Some(StwWrite {
            register: usize::from(entry & !FLOAT),
            float: entry & FLOAT != 0,
            value,
        })
    }

    /// A write [`StwParams::decode`] gave.
    #[inline(always)]
    pub fn apply(&mut self, w: StwWrite) {
        self.rows.as_flattened_mut()[w.register] = w.fixed();
    }

    /// The write of `value` to the register at normal-map `offset`; `false` (nothing
    /// written) where it is not one of these ([`StwParams::decode`]).
    #[inline]
    pub fn write(&mut self, offset: u32, value: u32) -> bool {
        match Self::decode(offset, value) {
            Some(w) => {
                self.apply(w);
                true
            }
            None => false,
        }
    }

    /// Subpixel correction of the start values (`fbzColorPath` bit 26):
    /// `start += (dx * d/dx + dy * d/dy) >> 4`, with the FBI's 12.4 offsets. The corrected
    /// values replace the start registers, so a triangle that does not resend them is
    /// corrected again (spec 9.4). Source: MAME and 86Box apply it at 32 fraction bits.
    pub fn subpixel_adjust(&mut self, dx_12_4: i32, dy_12_4: i32) {
        let [start, ddx, ddy] = &mut self.rows;
        for i in 0..3 {
            let delta = i64::from(dx_12_4)
                .wrapping_mul(ddx[i])
                .wrapping_add(i64::from(dy_12_4).wrapping_mul(ddy[i]));
            start[i] = start[i].wrapping_add(delta >> 4);
        }
    }

    /// Iterator `i` (0 S, 1 T, 2 W) at pixel offset `(dx, dy)` from vertex A:
    /// `start + dx * d/dx + dy * d/dy`, wrapping as the 64-bit references do.
    #[inline(always)]
    pub(crate) fn iterated(&self, i: usize, dx: i32, dy: i32) -> Fx32 {
        let [start, ddx, ddy] = &self.rows;
        start[i]
            .wrapping_add(i64::from(dx).wrapping_mul(ddx[i]))
            .wrapping_add(i64::from(dy).wrapping_mul(ddy[i]))
    }
}

/// S, T, W register writes not yet applied to a TMU: the last value written to each of
/// the nine registers, as written. Applying them ([`crate::Tmu::apply_stw`]) gives what
/// the writes one by one give: each register's last write wins, and nothing in the
/// conversion depends on another register.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StwPending {
    values: [u32; 9],
    /// Bit `r`: register `r` was written.
    written: u16,
    /// Bit `r`: register `r`'s last write went through the floating-point alias.
    float: u16,
}

impl StwPending {
    /// Note a write ([`StwParams::decode`]).
    #[inline(always)]
    pub fn note(&mut self, w: StwWrite) {
        let bit = 1 << w.register;
        self.values[w.register] = w.value;
        self.written |= bit;
        self.float = (self.float & !bit) | if w.float { bit } else { 0 };
    }

    /// The writes noted so far, leaving none (the values stay, unwritten).
    #[inline(always)]
    pub fn take(&mut self) -> Self {
        let taken = *self;
        self.written = 0;
        taken
    }

    /// Whether no write is pending.
    pub fn is_empty(&self) -> bool {
        self.written == 0
    }

    /// Apply the pending writes to `p` (each register's last).
    pub(crate) fn apply_to(&self, p: &mut StwParams) {
        let regs = p.rows.as_flattened_mut();
        if self.written == ALL && self.float == 0 {
            // All nine in their fixed-point forms: no branch per register. (Writes
            // through the float aliases, which this project's Glide front-end uses, take
            // the loop below.)
            for (r, (reg, &v)) in regs.iter_mut().zip(&self.values).enumerate() {
                *reg = Fx32::from(v as i32) << fixed_shift(r);
            }
            return;
        }
        for (r, reg) in regs.iter_mut().enumerate() {
            if self.written & (1 << r) != 0 {
                *reg = StwWrite {
                    register: r,
                    float: self.float & (1 << r) != 0,
                    value: self.values[r],
                }
                .fixed();
            }
        }
    }
}

/// [`StwPending::written`] with all nine registers.
const ALL: u16 = 0x1ff;

#[cfg(test)]
mod tests {
    use super::*;
    use sst1_regs::addr;

    /// The decode by bits against the register map's names, for every offset of the map.
    #[test]
    fn decode_follows_the_register_map() {
        let named = [
            (addr::START_S, 0, 0),
            (addr::START_T, 0, 1),
            (addr::START_W, 0, 2),
            (addr::D_S_DX, 1, 0),
            (addr::D_T_DX, 1, 1),
            (addr::D_W_DX, 1, 2),
            (addr::D_S_DY, 2, 0),
            (addr::D_T_DY, 2, 1),
            (addr::D_W_DY, 2, 2),
        ];
        let value = 0x8765_4321;
        let mut found = 0;
        for offset in (0..0x400).step_by(4) {
            let fixed = named.iter().find(|n| n.0 == offset);
            let float = named.iter().find(|n| n.0 + 0x80 == offset);
            let want = match (fixed, float) {
                (Some(&(_, row, component)), _) => Some((
                    row,
                    component,
                    if component == 2 {
                        Fx32::from(value as i32) << 2
                    } else {
                        Fx32::from(value as i32) << 14
                    },
                )),
                (_, Some(&(_, row, component))) => Some((
                    row,
                    component,
                    sst1_regs::float::float_to_fixed64(value, 32),
                )),
                _ => None,
            };
            found += usize::from(want.is_some());
            let got = StwParams::decode(offset, value)
                .map(|w| (w.register / 3, w.register % 3, w.fixed()));
            assert_eq!(got, want, "{offset:#x}");
        }
        assert_eq!(found, 18);
        assert_eq!(addr::F_START_S, addr::START_S + 0x80);
        assert_eq!(addr::F_D_W_DY, addr::D_W_DY + 0x80);
    }

    /// Pending writes applied at once give what the writes one by one give.
    #[test]
    fn pending_writes_apply_as_written() {
        let writes = [
            (addr::START_S, 0x1234),
            (addr::F_D_W_DY, 0x3f80_0000),
            (addr::START_S + 0x80, 0xc000_0000),
            (addr::D_T_DX, 0xffff_fff0),
            (addr::D_W_DY, 7),
            (addr::START_W, 0x4000_0000),
        ];
        for n in 0..=writes.len() {
            let mut one_by_one = StwParams {
                rows: [[0; 3], [1, 2, 3], [0; 3]],
            };
            let mut pending = StwPending::default();
            for &(offset, value) in &writes[..n] {
                assert!(one_by_one.write(offset, value));
                pending.note(StwParams::decode(offset, value).unwrap());
            }
            let mut at_once = StwParams {
                rows: [[0; 3], [1, 2, 3], [0; 3]],
            };
            pending.apply_to(&mut at_once);
            assert_eq!(at_once, one_by_one, "{n} writes");
            assert_eq!(pending.is_empty(), n == 0);
        }
    }

    /// All nine written in fixed point (the path without a branch per register), then
    /// one of them again through its float alias.
    #[test]
    fn pending_all_nine_apply_as_written() {
        let offsets = [
            addr::START_S,
            addr::START_T,
            addr::START_W,
            addr::D_S_DX,
            addr::D_T_DX,
            addr::D_W_DX,
            addr::D_S_DY,
            addr::D_T_DY,
            addr::D_W_DY,
        ];
        let mut one_by_one = StwParams::default();
        let mut pending = StwPending::default();
        for (i, &offset) in offsets.iter().enumerate() {
            let value = 0x9e37_79b9u32.wrapping_mul(i as u32 + 1);
            assert!(one_by_one.write(offset, value));
            pending.note(StwParams::decode(offset, value).unwrap());
        }
        assert_eq!(pending.written, ALL);
        let mut at_once = StwParams::default();
        pending.apply_to(&mut at_once);
        assert_eq!(at_once, one_by_one);
        assert_eq!(
            at_once.rows[DX][2],
            Fx32::from(0x9e37_79b9u32.wrapping_mul(6) as i32) << 2
        );
        assert_eq!(
            at_once.rows[DY][0],
            Fx32::from(0x9e37_79b9u32.wrapping_mul(7) as i32) << 14
        );
        // The float alias of dTdX replaces the fixed write.
        assert!(one_by_one.write(addr::F_D_T_DX, 0xbf80_0000));
        pending.note(StwParams::decode(addr::F_D_T_DX, 0xbf80_0000).unwrap());
        let mut at_once = StwParams::default();
        pending.apply_to(&mut at_once);
        assert_eq!(at_once, one_by_one);
        assert_eq!(at_once.rows[DX][1], -1 << 32);
    }

    #[test]
    fn write_sets_one_register() {
        let mut p = StwParams::default();
        assert!(p.write(addr::D_T_DY, 3));
        assert!(!p.write(addr::START_R, 3));
        assert_eq!(
            p,
            StwParams {
                rows: [[0; 3], [0; 3], [0, 3 << 14, 0]],
            }
        );
    }
}

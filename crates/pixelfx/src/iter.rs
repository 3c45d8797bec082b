//! Iterated parameters at one pixel, and their conversion to the 8-bit colour and 16-bit
//! depth values the pipeline uses (spec 5.3-5.14, 5.16, 5.19).
//!
//! Every parameter is `start + dy * d/dy + dx * d/dx`, where `(dx, dy)` is the pixel's
//! integer offset from vertex A's pixel. The SST-1 has no RGBZW clamp bit (a Voodoo 2
//! addition), so out-of-range values take the "pseudo-clamp" of the spec: the 12-bit
//! integer part wraps, except that 0xfff (-1) reads as 0 and 0x100 (256) reads as 255.
//! Source: MAME `clamped_argb`/`clamped_z`, DOSBox Staging `CLAMPED_ARGB`/`CLAMPED_Z`
//! (they agree).

use crate::params::{Fx12_12, Fx20_12, Fx32_32, TriangleParams};

/// The raw iterator values at one pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Iterated {
    /// R, G, B, A (12.12).
    pub argb: [Fx12_12; 4],
    /// Z (20.12).
    pub z: Fx20_12,
    /// W (32.32).
    pub w: Fx32_32,
}

impl Iterated {
    /// The iterators at pixel offset `(dx, dy)` from vertex A.
    #[inline]
    pub fn at(p: &TriangleParams, dx: i32, dy: i32) -> Self {
        let lin = |s: i32, gx: i32, gy: i32| {
            s.wrapping_add(dy.wrapping_mul(gy))
                .wrapping_add(dx.wrapping_mul(gx))
        };
        Self {
            argb: [
                lin(p.start[0], p.dx[0], p.dy[0]),
                lin(p.start[1], p.dx[1], p.dy[1]),
                lin(p.start[2], p.dx[2], p.dy[2]),
                lin(p.start[3], p.dx[3], p.dy[3]),
            ],
            z: lin(p.start_z, p.dzdx, p.dzdy),
            w: p.start_w
                .wrapping_add((dy as i64).wrapping_mul(p.dwdy))
                .wrapping_add((dx as i64).wrapping_mul(p.dwdx)),
        }
    }

    /// Step one pixel to the right.
    #[inline]
    pub fn step_x(&mut self, p: &TriangleParams) {
        for i in 0..4 {
            self.argb[i] = self.argb[i].wrapping_add(p.dx[i]);
        }
        self.z = self.z.wrapping_add(p.dzdx);
        self.w = self.w.wrapping_add(p.dwdx);
    }
}

/// One 12.12 colour iterator to 8 bits with the SST-1 pseudo-clamp.
#[inline]
pub fn clamp_colour(v: Fx12_12) -> u8 {
    // Bit masks rather than a `match`, so that a loop over lanes vectorises: 0x100 has
    // a zero low byte, so or-ing 0xff gives 0xff; 0xfff is cleared.
    let c = (v >> 12) & 0xfff;
    let max = -((c == 0x100) as i32);
    let negative = -((c == 0xfff) as i32);
    (((c & 0xff) | (max & 0xff)) & !negative) as u8
}

/// The 20.12 Z iterator to a 16-bit depth value with the SST-1 pseudo-clamp.
#[inline]
pub fn clamp_z(z: Fx20_12) -> u16 {
    // Bit masks rather than a `match`, as in `clamp_colour`: 0x10000 has a zero low
    // half, so or-ing 0xffff gives 0xffff; 0xfffff is cleared.
    let v = ((z as u32) >> 12) & 0xfffff;
    let max = ((v == 0x10000) as u32).wrapping_neg();
    let negative = ((v == 0xfffff) as u32).wrapping_neg();
    (((v & 0xffff) | (max & 0xffff)) & !negative) as u16
}

/// How the colour and Z iterators are clamped into 8-bit colours and the 16-bit depth.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum IteratorClamp {
    /// The SST-1 pseudo-clamp of [`clamp_colour`] and [`clamp_z`]: only the values just
    /// outside the range are caught, the rest wrap (spec 5.16; MAME, DOSBox Staging).
    #[default]
    PseudoClamp,
    /// Saturation to 0..=255 and 0..=0xffff (86Box `CLAMP`, `CLAMP16`).
    Saturate,
}

impl IteratorClamp {
    /// One 12.12 colour iterator to 8 bits.
    #[inline(always)]
    pub fn colour(self, v: Fx12_12) -> u8 {
        match self {
            IteratorClamp::PseudoClamp => clamp_colour(v),
            IteratorClamp::Saturate => (v >> 12).clamp(0, 0xff) as u8,
        }
    }

    /// The 20.12 Z iterator to 16 bits.
    #[inline(always)]
    pub fn z(self, z: Fx20_12) -> u16 {
        match self {
            IteratorClamp::PseudoClamp => clamp_z(z),
            IteratorClamp::Saturate => (z >> 12).clamp(0, 0xffff) as u16,
        }
    }
}

/// Which formula turns iterated W into the 16-bit floating-point depth ("wfloat":
/// 4-bit exponent = leading zeros, 12-bit inverted mantissa, plus one).
///
/// The references agree for ordinary values and differ only at the edges.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum WFloatEdges {
    /// DOSBox Staging: W with any of bits 47:32 set gives 0; W below 1.0 >> 16 (bits 31:16
    /// clear) gives 0xffff; the final +1 saturates at 0xffff.
    #[default]
    Dosbox,
    /// MAME: exponent from the leading zeros of the 64-bit value; the +1 may carry.
    Mame,
    /// 86Box (`voodoo_half_triangle`'s `w_depth`): as DOSBox Staging, except that W below
    /// 1.0 >> 16 gives 0xf001.
    Box86,
}

/// The 16-bit floating-point form of iterated W used for W-buffering and table fog
/// (spec 5.19: "the W value ... is converted to a 16-bit floating point format").
#[inline]
pub fn wfloat(w: Fx32_32, edges: WFloatEdges) -> u16 {
    match edges {
        WFloatEdges::Dosbox | WFloatEdges::Box86 => {
            if w & 0xffff_0000_0000 != 0 {
                return 0;
            }
            let t = w as u32;
            if t & 0xffff_0000 == 0 {
                return if edges == WFloatEdges::Box86 {
                    0xf001
                } else {
                    0xffff
                };
            }
            let exp = t.leading_zeros();
            let v = (exp << 12) | ((!t >> (19 - exp)) & 0xfff);
            (v + u32::from(v < 0xffff)) as u16
        }
        WFloatEdges::Mame => {
            // MAME keeps W with 48 fraction bits; with our 32 the exponent is the count of
            // leading zeros beyond the 32 integer bits.
            let exp = w.leading_zeros() as i32 - 32;
            if exp < 0 {
                return 0;
            }
            if exp >= 16 {
                return 0xffff;
            }
            (((exp << 12) as i64 | ((w >> (19 - exp)) ^ 0x1fff)) + 1) as u16
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_pseudo_clamp() {
        assert_eq!(clamp_colour(0x7f_f00), 0x7f);
        assert_eq!(clamp_colour(-1 << 12), 0);
        assert_eq!(clamp_colour(0x100 << 12), 0xff);
        assert_eq!(clamp_colour(0x101 << 12), 0x01);
        assert_eq!(clamp_colour(-2 << 12), 0xfe);
    }

    #[test]
    fn pseudo_clamps_are_the_spec_cases_for_every_integer_part() {
        // The bit-mask forms against the spec's three cases, for every value the
        // integer bits can take (the fraction bits below them do not matter).
        for c in 0..0x1000 {
            let expected = match c {
                0xfff => 0,
                0x100 => 0xff,
                c => c as u8,
            };
            assert_eq!(clamp_colour(c << 12 | 0xabc), expected, "colour {c:#x}");
        }
        for v in 0..0x10_0000u32 {
            let expected = match v {
                0xfffff => 0,
                0x10000 => 0xffff,
                v => v as u16,
            };
            assert_eq!(clamp_z((v << 12 | 0x123) as i32), expected, "z {v:#x}");
        }
    }

    #[test]
    fn z_pseudo_clamp() {
        assert_eq!(clamp_z(0x1234_5678), 0x2345);
        assert_eq!(clamp_z(-0x1000), 0);
        assert_eq!(clamp_z(0x1000_0000), 0xffff);
        // 86Box saturates: 0x101 -> 0xff, -2 -> 0; Z 0x12345 -> 0xffff.
        let sat = IteratorClamp::Saturate;
        assert_eq!((sat.colour(0x101 << 12), sat.colour(-2 << 12)), (0xff, 0));
        assert_eq!((sat.z(0x1234_5678), sat.z(-0x1000)), (0xffff, 0));
    }

    #[test]
    fn wfloat_values() {
        for e in [WFloatEdges::Dosbox, WFloatEdges::Mame] {
            // W = 1.0 (0x1_0000_0000) has bit 32 set: both give 0.
            assert_eq!(wfloat(1 << 32, e), 0);
            // W = 0.5: no leading zeros in the low word.
            assert_eq!(wfloat(1 << 31, e), 0x0fff + 1);
        }
        // W = 2^-16: the mantissa is all ones; DOSBox saturates the +1, MAME carries.
        assert_eq!(wfloat(0x1_0000, WFloatEdges::Dosbox), 0xffff);
        assert_eq!(wfloat(0x1_0000, WFloatEdges::Mame), 0x0000);
        assert_eq!(wfloat(0x8000, WFloatEdges::Dosbox), 0xffff);
        assert_eq!(wfloat(0x8000, WFloatEdges::Mame), 0xffff);
        // 86Box: 0xf001 below 2^-16, DOSBox's values elsewhere.
        assert_eq!(wfloat(0x8000, WFloatEdges::Box86), 0xf001);
        assert_eq!(wfloat(1 << 31, WFloatEdges::Box86), 0x1000);
        assert_eq!(wfloat(1 << 32, WFloatEdges::Box86), 0);
    }

    #[test]
    fn iterate_matches_stepping() {
        let p = TriangleParams {
            start: [1, 2, 3, 4],
            dx: [5, -6, 7, 8],
            dy: [9, 10, -11, 12],
            start_z: 100,
            dzdx: -3,
            dzdy: 4,
            start_w: 1 << 32,
            dwdx: -(1 << 20),
            dwdy: 1 << 21,
            ..Default::default()
        };
        let mut it = Iterated::at(&p, -3, 7);
        for dx in -2..5 {
            it.step_x(&p);
            assert_eq!(it, Iterated::at(&p, dx, 7));
        }
    }
}

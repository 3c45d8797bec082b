//! x87 extended-precision arithmetic (64-bit significand) for the `gu` fog-table
//! utilities and the triangle setup (`draw.rs`).
//!
//! 3dfx's `guFogGenerate*` (gu.c) keep `1 - exp(-dp)`, the product with `scale` and
//! the `* 255` in x87 registers, so they are rounded to a 64-bit significand, not to
//! `float`. Example: test24's `guFogGenerateExp(0.9)` has 254 at entry 22, where
//! `1 - 2.1e-17` is below 1.0 in extended precision but rounds to 1.0 (255) in
//! single or double precision. Source: the glide-sdk traces test08/test22/test24
//! (tests/fog_trace.rs), which single- and double-precision models both miss.
//!
//! Only finite values are represented (zeros keep their sign, as the FPU's do);
//! callers handle infinities and NaN.

/// A finite x87 extended value: `(-1)^neg * m * 2^e`, `m` normalised (bit 63 set)
/// or zero (`m == 0`, `e == 0`, `neg` its sign).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Ext {
    neg: bool,
    m: u64,
    e: i32,
}

impl Ext {
    const ZERO: Ext = Ext {
        neg: false,
        m: 0,
        e: 0,
    };

    /// Round `m * 2^e` (plus a non-zero remainder below `m` when `sticky`) to a
    /// 64-bit significand, ties to even. A zero keeps the sign `neg`.
    fn round(neg: bool, m: u128, e: i32, sticky: bool) -> Ext {
        if m == 0 {
            return Ext { neg, ..Ext::ZERO };
        }
        let bits = 128 - m.leading_zeros() as i32;
        if bits <= 64 {
            let sh = 64 - bits;
            return Ext {
                neg,
                m: (m << sh) as u64,
                e: e - sh,
            };
        }
        let sh = bits - 64;
        let mut kept = m >> sh;
        let rem = m & ((1u128 << sh) - 1);
        let half = 1u128 << (sh - 1);
        if rem > half || (rem == half && (sticky || kept & 1 == 1)) {
            kept += 1;
        }
        let mut e = e + sh;
        if kept >> 64 != 0 {
            kept >>= 1;
            e += 1;
        }
        Ext {
            neg,
            m: kept as u64,
            e,
        }
    }

    /// The exact value of a finite `f64` (every `f32` converts exactly too); a
    /// non-finite value gives +0.
    pub(crate) fn from_f64(v: f64) -> Ext {
        if !v.is_finite() {
            return Ext::ZERO;
        }
        if v == 0.0 {
            return Ext {
                neg: v.is_sign_negative(),
                ..Ext::ZERO
            };
        }
        let bits = v.to_bits();
        let exp = ((bits >> 52) & 0x7ff) as i32;
        let frac = bits & ((1 << 52) - 1);
        let (m, e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1 << 52), exp - 1075)
        };
        Ext::round(v < 0.0, u128::from(m), e, false)
    }

    /// `self + other`, rounded (round to nearest: an exact zero sum is +0 unless
    /// both terms are -0).
    pub(crate) fn add(self, other: Ext) -> Ext {
        if self.m == 0 && other.m == 0 {
            return Ext {
                neg: self.neg && other.neg,
                ..Ext::ZERO
            };
        }
        let (a, b) = if (self.m == 0) || (other.m != 0 && self.mag_lt(other)) {
            (other, self)
        } else {
            (self, other)
        };
        if b.m == 0 {
            return a;
        }
        // a's significand at bits 125..62; b aligned below it.
        let ua = u128::from(a.m) << 62;
        let d = (a.e - b.e) as u32;
        let (ub, sticky) = if d >= 126 {
            (0, true)
        } else {
            let full = u128::from(b.m) << 62;
            (full >> d, full & ((1u128 << d) - 1) != 0)
        };
        let e = a.e - 62;
        if a.neg == b.neg {
            Ext::round(a.neg, ua + ub, e, sticky)
        } else if ua == ub && !sticky {
            Ext::ZERO
        } else if sticky {
            // True value is (ua - ub - delta), 0 < delta < 1 unit: one extra bit below.
            Ext::round(a.neg, ((ua - ub) << 1) - 1, e - 1, true)
        } else {
            Ext::round(a.neg, ua - ub, e, false)
        }
    }

    /// `self - other`, rounded.
    pub(crate) fn sub(self, other: Ext) -> Ext {
        self.add(Ext {
            neg: !other.neg,
            ..other
        })
    }

    /// `self * other`, rounded.
    pub(crate) fn mul(self, other: Ext) -> Ext {
        Ext::round(
            self.neg != other.neg,
            u128::from(self.m) * u128::from(other.m),
            self.e + other.e,
            false,
        )
    }

    /// `self / other`, rounded; `None` when `other` is zero.
    pub(crate) fn div(self, other: Ext) -> Option<Ext> {
        if other.m == 0 {
            return None;
        }
        let n = u128::from(self.m) << 64;
        let d = u128::from(other.m);
        Some(Ext::round(
            self.neg != other.neg,
            n / d,
            self.e - 64 - other.e,
            n % d != 0,
        ))
    }

    /// `self == 0.0` (either sign).
    pub(crate) fn is_zero(self) -> bool {
        self.m == 0
    }

    fn mag_lt(self, other: Ext) -> bool {
        (self.e, self.m) < (other.e, other.m)
    }

    /// `self > 1.0`.
    pub(crate) fn gt_one(self) -> bool {
        !self.neg && self.m != 0 && (self.e > -63 || (self.e == -63 && self.m > 1 << 63))
    }

    /// `self < 0.0`.
    pub(crate) fn lt_zero(self) -> bool {
        self.neg && self.m != 0
    }

    /// Rounded to `f32` (a `float` variable's store), ties to even; beyond the
    /// `f32` range it gives the infinity of its sign.
    /// UNVERIFIED: results in the `f32` subnormal range are rounded twice (to 24
    /// bits, then to the subnormal's precision); no setup or fog value gets there.
    pub(crate) fn to_f32(self) -> f32 {
        if self.m == 0 {
            return if self.neg { -0.0 } else { 0.0 };
        }
        // 24 bits are exact in an f64; the power of two scales it exactly for the
        // magnitudes the fog utilities produce.
        let top = self.m >> 40;
        let low = self.m & ((1 << 40) - 1);
        let half = 1u64 << 39;
        let mut q = top;
        if low > half || (low == half && top & 1 == 1) {
            q += 1;
        }
        let v = q as f64 * 2f64.powi(self.e + 40);
        (if self.neg { -v } else { v }) as f32
    }

    /// Integer part (truncation toward zero) of a value in `0..=255`.
    pub(crate) fn trunc_u8(self) -> u8 {
        if self.neg || self.m == 0 || self.e <= -64 {
            return 0;
        }
        if self.e >= 0 {
            return u8::MAX;
        }
        (self.m >> (-self.e) as u32).min(255) as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_minus_tiny() {
        let one = Ext::from_f64(1.0);
        // 2^-65 is half an ulp below 1.0: ties to even gives 1.0.
        assert_eq!(one.sub(Ext::from_f64(2f64.powi(-65))), one);
        // Just above half an ulp: 1 - 2^-64.
        let r = one.sub(Ext::from_f64(2.1e-17));
        assert!(!r.gt_one() && r != one);
        assert_eq!(r.mul(Ext::from_f64(255.0)).trunc_u8(), 254);
        assert_eq!(one.sub(Ext::from_f64(1e-20)), one);
    }

    #[test]
    fn signed_zeros_and_range() {
        let (z, nz) = (Ext::from_f64(0.0), Ext::from_f64(-0.0));
        let bits = |e: Ext| e.to_f32().to_bits();
        assert_eq!(bits(nz), 0x8000_0000);
        assert_eq!(bits(z.mul(Ext::from_f64(-2.0))), 0x8000_0000);
        assert_eq!(bits(nz.sub(z)), 0x8000_0000);
        assert_eq!(bits(nz.add(z)), 0);
        let one = Ext::from_f64(-1.5);
        assert_eq!(bits(one.sub(one)), 0);
        assert!(nz.is_zero() && !one.is_zero());
        assert_eq!(Ext::from_f64(1e39).to_f32(), f32::INFINITY);
        assert_eq!(Ext::from_f64(-1e39).to_f32(), f32::NEG_INFINITY);
    }

    #[test]
    fn arithmetic() {
        let x = Ext::from_f64(3.0).div(Ext::from_f64(4.0)).unwrap();
        assert_eq!(x.to_f32(), 0.75);
        assert_eq!(Ext::from_f64(-2.5).mul(Ext::from_f64(2.0)).to_f32(), -5.0);
        assert!(Ext::from_f64(1.0).sub(Ext::from_f64(2.0)).lt_zero());
        assert_eq!(Ext::from_f64(1.0).div(Ext::ZERO), None);
        assert_eq!(Ext::from_f64(1.0 / 3.0).to_f32(), 1.0f32 / 3.0);
        assert_eq!(Ext::from_f64(254.75).trunc_u8(), 254);
    }
}

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

/// `2^k` outside the normal `f64` exponents. Out of line: inline, the compiler computes
/// `powi` before the test of [`Ext::to_f32`] that almost never needs it.
#[cold]
#[inline(never)]
fn far_power_of_two(k: i32) -> f64 {
    2f64.powi(k)
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
        if a.e == b.e {
            // Equal exponents (the differences of snapped coordinates): a sum of 65 bits
            // at most, or a difference exact in 64.
            if a.neg == b.neg {
                return Ext::round(a.neg, u128::from(a.m) + u128::from(b.m), a.e, false);
            }
            // |a| >= |b|: the difference is exact; shifted up to normal.
            let d = a.m - b.m;
            if d == 0 {
                return Ext::ZERO;
            }
            let z = d.leading_zeros();
            return Ext {
                neg: a.neg,
                m: d << z,
                e: a.e - z as i32,
            };
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

    /// `c + 3 * 2^18` (Glide's snap bias), rounded: as `from_f64(c).add(from_f64(3 *
    /// 2^18))`. For a multiple of 2^-44 below 2^18 in magnitude (every window coordinate
    /// from 2^-21 up, and 0) the sum is exact: its significand is `3 * 2^62 + c * 2^44`, in
    /// `2^63..2^64`, at exponent -44, found without the general addition.
    pub(crate) fn plus_snap_bias(c: f32) -> Ext {
        // c * 2^44, exact (a power of two).
        let t = f64::from(c) * 17_592_186_044_416.0;
        if t.abs() < 4_611_686_018_427_387_904.0 && t == t.trunc() {
            Ext {
                neg: false,
                m: ((3u64 << 62) as i64 + t as i64) as u64,
                e: -44,
            }
        } else {
            Ext::from_f64(f64::from(c)).add(Ext::from_f64(f64::from(3u32 << 18)))
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
        let k = self.e + 40;
        // 2^k built from its bits where it is a normal f64 (as powi gives it, without
        // the call).
        let scale = if (-1022..=1023).contains(&k) {
            f64::from_bits(((k + 1023) as u64) << 52)
        } else {
            far_power_of_two(k)
        };
        let v = q as f64 * scale;
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

/// `1.0f / area` computed on the x87 and stored to a `float`.
///
/// Fast path: the `f32` quotient. An extended (64-bit) quotient of two `float`s rounded
/// again to 24 bits is the correctly rounded one, because 64 >= 2 * 24 + 2 (double
/// rounding is innocuous for +, -, *, / when the first precision p' >= 2p + 2: S. A.
/// Figueroa, "When is double rounding innocuous?", SIGNUM Newsletter 30(3), 1995).
/// Where the quotient is not a normal `f32` the extended model answers
/// ([`reciprocal_ext`]: its subnormal rounding is [`Ext::to_f32`]'s).
#[inline]
pub(crate) fn reciprocal(area: f32) -> f32 {
    let q = 1.0 / area;
    if q.is_normal() {
        q
    } else {
        reciprocal_ext(area)
    }
}

/// [`reciprocal`] in the extended model (ties rounded twice, as the FPU does).
fn reciprocal_ext(area: f32) -> f32 {
    match Ext::from_f64(1.0).div(Ext::from_f64(f64::from(area))) {
        Some(q) if area.is_finite() => q.to_f32(),
        _ => 1.0 / area,
    }
}

/// `a - b` computed on the x87 and stored to a `float` variable: the `f32` difference.
/// For finite inputs the extended difference rounded to 24 bits is the correctly rounded
/// one (Figueroa, see [`reciprocal`]), and a difference in the subnormal range is exact;
/// for infinities and NaN both are IEEE arithmetic. Test
/// `difference_is_the_extended_model` checks it against [`difference_ext`].
#[inline]
pub(crate) fn difference(a: f32, b: f32) -> f32 {
    a - b
}

/// [`difference`] in the extended model (IEEE `f64` for non-finite inputs).
fn difference_ext(a: f32, b: f32) -> f32 {
    if a.is_finite() && b.is_finite() {
        Ext::from_f64(f64::from(a))
            .sub(Ext::from_f64(f64::from(b)))
            .to_f32()
    } else {
        (f64::from(a) - f64::from(b)) as f32
    }
}

/// `(u0 - u1) * su - (w0 - w1) * sw` as 3dfx's build computes one setup gradient:
/// the parameter differences `dpAB`, `dpBC` are `float` variables in `_trisetup`
/// (gxdraw.c), so each is rounded to a `float` (from the x87 difference); the two
/// products and their difference stay in x87 extended precision and the result is
/// rounded once more, when stored to its register. Infinities and NaN in the
/// inputs follow IEEE arithmetic instead.
/// Source of the rounding of the differences: the glide-sdk trace test08 (table fog
/// on W, `1/20 - 1/2000` needs more than 24 bits), pinned by tests/fog_trace.rs.
///
/// Fast path, in `f64`: each product of two `float`s is exact (48 bits), so the
/// extended difference is `x = p - q` rounded to 64 bits, and the `f64` difference `s`
/// is `x` rounded to 53 bits. Rounding to 24 bits is constant between two neighbouring
/// midpoints of the `float` grid (25-bit numbers, so on `s`'s 53-bit grid). Unless `s` is
/// one, the nearest midpoint is at least one `f64` ulp from `s`, while `x` is within half
/// an ulp of `s` and its 64-bit rounding within 2^-11 ulp of `x`: all three round to the
/// same `float`. A midpoint `s`, or a result outside the normal `float` range, takes the
/// extended model ([`gradient_ext`]); test `gradient_is_the_extended_model` builds such
/// midpoints on purpose.
#[inline]
pub(crate) fn gradient(u: (f32, f32), su: f32, w: (f32, f32), sw: f32) -> f32 {
    let (du, dw) = (difference(u.0, u.1), difference(w.0, w.1));
    let s = f64::from(du) * f64::from(su) - f64::from(dw) * f64::from(sw);
    let bits = s.to_bits();
    // The biased f64 exponent of a normal f32 magnitude below 2^127: 1023 - 126 ..= 1023 + 126.
    let exp = (bits >> 52) & 0x7ff;
    // The 29 bits below a float's 24: exactly half is a midpoint of the float grid.
    let below = bits & ((1 << 29) - 1);
    if (897..=1149).contains(&exp) && below != 1 << 28 {
        s as f32
    } else {
        gradient_ext(u, su, w, sw)
    }
}

/// [`gradient`] in the extended model.
fn gradient_ext(u: (f32, f32), su: f32, w: (f32, f32), sw: f32) -> f32 {
    let all = [u.0, u.1, su, w.0, w.1, sw];
    if all.iter().all(|v| v.is_finite()) {
        let e = |v: f32| Ext::from_f64(f64::from(v));
        let du = e(difference_ext(u.0, u.1));
        let dw = e(difference_ext(w.0, w.1));
        du.mul(e(su)).sub(dw.mul(e(sw))).to_f32()
    } else {
        let f = f64::from;
        let (du, dw) = (difference_ext(u.0, u.1), difference_ext(w.0, w.1));
        (f(du) * f(su) - f(dw) * f(sw)) as f32
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

    /// xorshift64*: inputs for the fast paths' checks.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
        }

        /// Any f32 bit pattern (NaN and infinities included) one time in four; a value
        /// of a random sign, 24 random bits and an exponent near 0 otherwise.
        fn float(&mut self) -> f32 {
            let r = self.next();
            if r & 3 == 0 {
                f32::from_bits((r >> 32) as u32)
            } else {
                let m = 1.0 + ((r >> 8) & 0x7f_ffff) as f32 / (1 << 23) as f32;
                let e = ((r >> 40) % 48) as i32 - 24;
                let v = m * 2f32.powi(e);
                if r & 4 != 0 {
                    -v
                } else {
                    v
                }
            }
        }
    }

    fn same(a: f32, b: f32) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    #[test]
    fn difference_is_the_extended_model() {
        let mut rng = Rng(0x1234_5678_9abc_def1);
        for _ in 0..200_000 {
            let (a, b) = (rng.float(), rng.float());
            // Near neighbours too: differences that cancel.
            let c = f32::from_bits(a.to_bits().wrapping_add((rng.next() % 5) as u32));
            for (x, y) in [(a, b), (a, c), (c, a)] {
                assert!(
                    same(difference(x, y), difference_ext(x, y)),
                    "{x:e} - {y:e}"
                );
            }
        }
        for (x, y) in [
            (0.0f32, -0.0f32),
            (-0.0, 0.0),
            (-0.0, -0.0),
            (f32::MAX, -f32::MAX),
        ] {
            assert!(
                same(difference(x, y), difference_ext(x, y)),
                "{x:e} - {y:e}"
            );
        }
    }

    #[test]
    fn reciprocal_is_the_extended_model() {
        let mut rng = Rng(0x0fed_cba9_8765_4321);
        for i in 0..200_000u32 {
            let a = rng.float();
            // Every exponent, subnormal areas and quotients included.
            let b = f32::from_bits((rng.next() >> 33) as u32 | (i & 1) << 31);
            for x in [a, b] {
                assert!(same(reciprocal(x), reciprocal_ext(x)), "1 / {x:e}");
            }
        }
    }

    #[test]
    fn gradient_is_the_extended_model() {
        let mut rng = Rng(0x5555_aaaa_3333_cccc);
        let mut took_model = 0;
        for _ in 0..200_000 {
            let u = (rng.float(), rng.float());
            let w = (rng.float(), rng.float());
            let (su, sw) = (rng.float(), rng.float());
            assert!(
                same(gradient(u, su, w, sw), gradient_ext(u, su, w, sw)),
                "{u:?} {su:e} {w:?} {sw:e}"
            );
        }
        // du * su exactly on a midpoint of the float grid (an odd 25-bit product), minus
        // a second product from far below the f64 precision to just inside it.
        for _ in 0..20_000 {
            let m = ((1u32 << 23) + (rng.next() % 2_796_202) as u32) | 1;
            let e = (rng.next() % 60) as i32 - 30;
            let du = m as f32 * 2f32.powi(e - 23);
            let p = f64::from(du) * 1.5;
            let below = (rng.next() % 80) as i32 + 10;
            let dw = (p * 2f64.powi(-below)) as f32;
            let sign: f32 = if rng.next() & 1 == 0 { 1.0 } else { -1.0 };
            let (u, w) = ((du, 0.0), (dw, 0.0));
            let fast = gradient(u, 1.5, w, sign);
            assert!(
                same(fast, gradient_ext(u, 1.5, w, sign)),
                "{du:e} * 1.5 - {dw:e} * {sign}"
            );
            let s = p - f64::from(dw) * f64::from(sign);
            took_model += usize::from(s.to_bits() & ((1 << 29) - 1) == 1 << 28);
        }
        // Both sides of the check are reached.
        assert!((1_000..19_000).contains(&took_model), "{took_model}");
    }

    /// The general addition without its equal-exponent branch, as it was.
    fn add_general(x: Ext, y: Ext) -> Ext {
        if x.m == 0 || y.m == 0 || x.e != y.e {
            return x.add(y);
        }
        // Move one exponent apart by scaling both significands' exponents through u128.
        let (a, b) = if x.mag_lt(y) { (y, x) } else { (x, y) };
        let (ua, ub) = (u128::from(a.m) << 62, u128::from(b.m) << 62);
        let e = a.e - 62;
        if a.neg == b.neg {
            Ext::round(a.neg, ua + ub, e, false)
        } else if ua == ub {
            Ext::ZERO
        } else {
            Ext::round(a.neg, ua - ub, e, false)
        }
    }

    #[test]
    fn equal_exponents_add_as_the_general_addition() {
        let mut rng = Rng(0x7777_1111_9999_2222);
        for _ in 0..200_000 {
            let e = (rng.next() % 200) as i32 - 100;
            let mut x = Ext::from_f64(rng.float() as f64);
            let mut y = Ext::from_f64(rng.float() as f64);
            if x.m == 0 || y.m == 0 {
                continue;
            }
            (x.e, y.e) = (e, e);
            if rng.next() & 1 == 0 {
                y.m = x.m.wrapping_add(rng.next() % 7) | 1 << 63;
            }
            assert_eq!(x.add(y), add_general(x, y), "{x:?} + {y:?}");
            assert_eq!(x.sub(y), add_general(x, Ext { neg: !y.neg, ..y }));
        }
    }

    #[test]
    fn snap_bias_as_the_general_addition() {
        let mut rng = Rng(0x2468_ace0_1357_9bdf);
        let bias = Ext::from_f64(f64::from(3u32 << 18));
        for i in 0..200_000u32 {
            let c = match i % 3 {
                0 => rng.float(),
                1 => (rng.next() % 2_000_000) as f32 / 1024.0 - 900.0,
                _ => f32::from_bits((rng.next() >> 32) as u32),
            };
            // A non-finite c counts as +0 in both.
            let want = Ext::from_f64(f64::from(c)).add(bias);
            assert_eq!(Ext::plus_snap_bias(c), want, "{c:e}");
        }
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

//! Deliberate approximations of the TMU's span kernels: what `voodoo replay --method`
//! chooses besides the exact paths (docs/methods.md).
//!
//! The hardware model stays exact and is the default. An approximation is a run-time
//! choice held by the TMU ([`Tmu::set_approx`](crate::Tmu::set_approx)) and read once per
//! chunk by [`Tmu::texels`](crate::Tmu::texels): no kernel is compiled twice for it, and
//! the exact path pays one test of a flag per chunk. The per-pixel path (the reference,
//! and the FBI's pixel-by-pixel layouts) ignores it: approximations exist only where the
//! span kernels run.
//!
//! Each one gives something up:
//!
//! - [`Approx::point_sampling`]: the filter bits of `textureMode` read as point sampling
//!   for magnification and minification, so one texel is fetched instead of four and
//!   nothing is blended. Loses the bilinear fractions (4 bits in S and T).
//! - [`Approx::lod_per_chunk`]: the LOD (its `log2(1/W)` term, the dither and the clamp)
//!   computed for the chunk's first live lane and used for all its lanes (up to 64
//!   pixels of one span), instead of per pixel, so that the chunk samples one level with
//!   one filter. Loses the LOD's change along the chunk: where W changes fast along a
//!   span (steep perspective), the level is chosen late or early, and the LOD dither's
//!   4x4 pattern becomes one value per chunk.
//! - [`Approx::float_divide`]: what the TMU computes from 1/W in single precision: the
//!   perspective divide `S * 256 / W`, `T * 256 / W` (eight lanes to a vector instead of
//!   four doubles), and, for the hardware model's LOD arithmetic (DOSBox Staging's), the
//!   LOD's `log2(1/W)` from the float's exponent and mantissa bits instead of a table.
//!   Loses what a 24-bit mantissa cannot hold (S, T and W rounded to 24 significant bits,
//!   so texel coordinates move by a few 1/256 of a texel where S/W is large, and S/W
//!   beyond 2^24 in 24.8 is rounded to even coarser steps) and up to 0.086 of a LOD
//!   between powers of two of W.

use crate::span::LANES;

/// The approximations in force for a TMU's span kernels. `Default` (all off) is exact.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Approx {
    /// Point sampling instead of bilinear filtering, at every LOD.
    pub point_sampling: bool,
    /// The LOD once per chunk (its first live lane) instead of per pixel.
    pub lod_per_chunk: bool,
    /// The perspective divide in `f32` instead of `f64`.
    pub float_divide: bool,
}

impl Approx {
    /// No approximation: the exact span kernels.
    pub const EXACT: Approx = Approx {
        point_sampling: false,
        lod_per_chunk: false,
        float_divide: false,
    };

    /// Whether every approximation is off.
    pub fn is_exact(self) -> bool {
        self == Self::EXACT
    }
}

/// `v as f32` in arithmetic that vectorises (AVX2 converts 32-bit integers only): the
/// high half times 2^32 plus the unsigned low half, each converted, then added. Rounds
/// twice (each half, then the sum), so it can differ from `v as f32` in the last bit:
/// part of what [`Approx::float_divide`] gives up.
#[inline(always)]
fn i64_to_f32(v: i64) -> f32 {
    let hi = (v >> 32) as i32;
    let lo = (v as u32 ^ 0x8000_0000) as i32;
    hi as f32 * 4_294_967_296.0 + (lo as f32 + 2_147_483_648.0)
}

/// [`Approx::float_divide`]: the 24.8 texture coordinates of `n` lanes from S, T and W
/// (.32), as `floor(S * (256 / W))` in single precision (or truncated towards zero without
/// `floor`, as the exact path's [`crate::CoordRounding`] says). Out of range, NaN and
/// infinite quotients (W = 0) give `i32::MIN`, as the exact path's conversion does.
#[inline(always)]
pub(crate) fn coords_f32(
    (s, t, w): (&[i64; LANES], &[i64; LANES], &[i64; LANES]),
    n: usize,
    floor: bool,
    cs: &mut [i32; LANES],
    ct: &mut [i32; LANES],
) {
    for i in 0..n.min(LANES) {
        let recip = 256.0 / i64_to_f32(w[i]);
        cs[i] = f32_to_i32(i64_to_f32(s[i]) * recip, floor);
        ct[i] = f32_to_i32(i64_to_f32(t[i]) * recip, floor);
    }
}

/// [`Approx::float_divide`]: the LOD's W term, `log2(1 / W)` as 8.8 for a .32 W, read
/// from the bits of `|W|` in single precision: the exponent is the integer part and the
/// top 8 mantissa bits are taken as the fraction (`log2(1 + m) ~ m`, off by up to 0.086
/// between powers of two), where the exact path interpolates DOSBox Staging's 512-entry
/// table. W = 0 gives 159.0, which every `lodmax` clamps as the exact path's 1000.0.
#[inline(always)]
pub(crate) fn w_log_f32(w: i64) -> i32 {
    // `bits >> 15` is `(exponent + 127) << 8 | mantissa >> 15`: log2 |W * 2^32| + 127.
    let bits = i64_to_f32(w).to_bits() & 0x7fff_ffff;
    ((127 + 32) << 8) - (bits >> 15) as i32
}

/// `q` truncated (or floored) to an integer; `i32::MIN` where it is out of range or NaN.
/// Branch-free, so that a loop of it vectorises (Rust's saturating `as` does not here).
#[inline(always)]
fn f32_to_i32(q: f32, floor: bool) -> i32 {
    // The largest f32 below 2^31; the clamp makes the conversion exact and NaN gives
    // the low end (`max` returns the number when one side is NaN).
    const HI: f32 = 2_147_483_520.0;
    const LO: f32 = -2_147_483_648.0;
    let in_range = (LO..2_147_483_648.0).contains(&q);
    // Not `clamp`: it passes NaN through, which `to_int_unchecked` must not see.
    #[allow(clippy::manual_clamp)]
    let c = q.max(LO).min(HI);
    // SAFETY: `c` is a number (not NaN) in `LO..=HI`, whose truncation fits an i32. (The
    // saturating `c as i32` does not vectorise: its NaN and range tests stay scalar.)
    let i: i32 = unsafe { c.to_int_unchecked() };
    // Truncation went up for a negative non-integer: one down for the floor.
    let i = i.wrapping_sub(i32::from(floor && (i as f32) > c));
    if in_range {
        i
    } else {
        i32::MIN
    }
}

#[cfg(test)]
mod tests {
    use super::{coords_f32, f32_to_i32, i64_to_f32, w_log_f32};
    use crate::span::LANES;

    fn lanes(v: i64) -> [i64; LANES] {
        [v; LANES]
    }

    #[test]
    fn conversion_floors_truncates_and_saturates_as_the_exact_one() {
        for (q, trunc, floor) in [
            (1.5f32, 1, 1),
            (-1.5, -1, -2),
            (-2.0, -2, -2),
            (2_147_483_520.0, 2_147_483_520, 2_147_483_520),
            (2_147_483_648.0, i32::MIN, i32::MIN),
            (-2_147_483_648.0, i32::MIN, i32::MIN),
            (-3.0e9, i32::MIN, i32::MIN),
            (f32::NAN, i32::MIN, i32::MIN),
            (f32::INFINITY, i32::MIN, i32::MIN),
        ] {
            assert_eq!(
                (f32_to_i32(q, false), f32_to_i32(q, true)),
                (trunc, floor),
                "{q}"
            );
        }
    }

    #[test]
    fn float_divide_matches_the_double_divide_where_single_precision_suffices() {
        // S = 3.5 texels (.32 of 14.18 S at LOD 0: texels * 2^32), W = 1.0 (.32).
        let (s, t, w) = (lanes(15 << 31), lanes(-(5 << 30)), lanes(1 << 32));
        let (mut cs, mut ct) = ([0; LANES], [0; LANES]);
        coords_f32((&s, &t, &w), 1, true, &mut cs, &mut ct);
        // 7.5 texels -> 7.5 * 256 = 1920; -1.25 -> -320.
        assert_eq!((cs[0], ct[0]), (1920, -320));
        // W = 0: the quotient is infinite, out of range.
        let w0 = lanes(0);
        coords_f32((&s, &t, &w0), 1, true, &mut cs, &mut ct);
        assert_eq!((cs[0], ct[0]), (i32::MIN, i32::MIN));
    }

    #[test]
    fn float_log_is_exact_at_powers_of_two_and_linear_between() {
        // W = 1.0, 0.5, 4.0 (.32): log2(1/W) = 0, 1, -2.
        assert_eq!(w_log_f32(1 << 32), 0);
        assert_eq!(w_log_f32(1 << 31), 256);
        assert_eq!(w_log_f32(-(1 << 31)), 256);
        assert_eq!(w_log_f32(1 << 34), -512);
        // W = 1.5: log2(1/1.5) = -0.585; the linear mantissa gives -0.5.
        assert_eq!(w_log_f32(3 << 31), -128);
        assert_eq!(w_log_f32(0), 159 << 8);
    }

    #[test]
    fn float_divide_loses_low_bits_of_large_coordinates() {
        // 2^25 + 1 in 24.8 does not fit a 24-bit mantissa: single precision rounds it.
        let s = lanes(((1 << 25) + 1) << 24);
        let w = lanes(1 << 32);
        let (mut cs, mut ct) = ([0; LANES], [0; LANES]);
        coords_f32((&s, &s, &w), 1, true, &mut cs, &mut ct);
        assert_eq!(cs[0], 1 << 25);
        assert_eq!(i64_to_f32(i64::MIN), -9.223_372e18);
    }
}

//! Level-of-detail computation (spec 5.51 `tLOD`, 5.50 `tloddither`).
//!
//! LOD values are 8.8 fixed point (integer LOD in the high bits). The base LOD of a triangle
//! is `log2` of the larger texture-space gradient (in LOD-0 texels per pixel); with
//! perspective correction `log2(W)` of the pixel's iterated W is subtracted per pixel.
//! `lodbias` is then added, optionally the LOD dither, and the result clamped to
//! `[lodmin, min(lodmax, 8.0)]`.

use crate::{LodCalc, LodDither};
use sst1_regs::lanes::LANES;
use sst1_regs::TLod;

/// `floor(256 * log2(1 + i / 128))`: fraction of a base-2 log from the 7 mantissa bits below
/// the leading one. Source: the table in MAME `fast_log2` (voodoo_render.cpp) equals this
/// formula, checked by a test.
const LOG2_FRAC_128: [u8; 128] = [
    0, 2, 5, 8, 11, 14, 16, 19, 22, 25, 27, 30, 33, 35, 38, 40, //
    43, 46, 48, 51, 53, 56, 58, 61, 63, 65, 68, 70, 73, 75, 77, 80, //
    82, 84, 87, 89, 91, 93, 96, 98, 100, 102, 104, 106, 109, 111, 113, 115, //
    117, 119, 121, 123, 125, 127, 129, 132, 134, 136, 138, 140, 141, 143, 145, 147, //
    149, 151, 153, 155, 157, 159, 161, 162, 164, 166, 168, 170, 172, 173, 175, 177, //
    179, 181, 182, 184, 186, 188, 189, 191, 193, 194, 196, 198, 200, 201, 203, 205, //
    206, 208, 209, 211, 213, 214, 216, 218, 219, 221, 222, 224, 225, 227, 229, 230, //
    232, 233, 235, 236, 238, 239, 241, 242, 244, 245, 247, 248, 250, 251, 253, 254, //
];

/// `floor(256 * log2(1 + i / 256))`. Source: the `logtable` of 86Box vid_voodoo_render.c
/// equals this formula, checked by a test.
const LOG2_FRAC_256: [u8; 256] = [
    0, 1, 2, 4, 5, 7, 8, 9, 11, 12, 14, 15, 16, 18, 19, 21, //
    22, 23, 25, 26, 27, 29, 30, 31, 33, 34, 35, 37, 38, 39, 40, 42, //
    43, 44, 46, 47, 48, 49, 51, 52, 53, 54, 56, 57, 58, 59, 61, 62, //
    63, 64, 65, 67, 68, 69, 70, 71, 73, 74, 75, 76, 77, 78, 80, 81, //
    82, 83, 84, 85, 87, 88, 89, 90, 91, 92, 93, 94, 96, 97, 98, 99, //
    100, 101, 102, 103, 104, 105, 106, 108, 109, 110, 111, 112, 113, 114, 115, 116, //
    117, 118, 119, 120, 121, 122, 123, 124, 125, 126, 127, 128, 129, 131, 132, 133, //
    134, 135, 136, 137, 138, 139, 140, 140, 141, 142, 143, 144, 145, 146, 147, 148, //
    149, 150, 151, 152, 153, 154, 155, 156, 157, 158, 159, 160, 161, 162, 162, 163, //
    164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 173, 174, 175, 176, 177, 178, //
    179, 180, 181, 181, 182, 183, 184, 185, 186, 187, 188, 188, 189, 190, 191, 192, //
    193, 194, 194, 195, 196, 197, 198, 199, 200, 200, 201, 202, 203, 204, 205, 205, //
    206, 207, 208, 209, 209, 210, 211, 212, 213, 214, 214, 215, 216, 217, 218, 218, //
    219, 220, 221, 222, 222, 223, 224, 225, 225, 226, 227, 228, 229, 229, 230, 231, //
    232, 232, 233, 234, 235, 235, 236, 237, 238, 239, 239, 240, 241, 242, 242, 243, //
    244, 245, 245, 246, 247, 247, 248, 249, 250, 250, 251, 252, 253, 253, 254, 255, //
];

/// The 4x4 ordered-dither matrix, indexed `[y & 3][x & 3]`. Source: MAME and DOSBox
/// `dither_matrix_4x4` (the same matrix the FBI uses for colour dither).
pub(crate) const DITHER_4X4: [[u8; 4]; 4] =
    [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

/// log2 of a non-negative value with `frac_bits` fractional bits, as 24.8, from the double's
/// exponent and its top 7 mantissa bits (MAME `fast_log2`). Negative values give 0.
#[inline]
fn log2_mame(value: f64, frac_bits: i32) -> i32 {
    if value < 0.0 {
        return 0;
    }
    let ival = (value.to_bits() >> 45) as u32;
    let exp = (ival >> 7) as i32 - 1023 - frac_bits;
    (exp << 8) | i32::from(LOG2_FRAC_128[(ival & 127) as usize])
}

/// log2 of an integer as 24.8 from its top 9 significant bits (86Box `fastlog`); zero and
/// values with bit 63 set give `i32::MIN`.
#[inline]
fn log2_86box(val: u64) -> i32 {
    if val == 0 || val & (1 << 63) != 0 {
        return i32::MIN;
    }
    let exp = 63 - val.leading_zeros() as i32;
    let frac = if exp >= 8 {
        val >> (exp - 8)
    } else {
        val << (8 - exp)
    } & 0xff;
    (exp << 8) | i32::from(LOG2_FRAC_256[frac as usize])
}

/// Entries of the reciprocal/log table: 512 steps of the mantissa range 1.0..=2.0.
pub(crate) const RECIPLOG_STEPS: usize = 512;

/// The reciprocal/log table DOSBox builds at start-up: for `n = 1 + i / 512`
/// (`i = 0..=512`), `[2^22 / n, 2^22 * log2 n]`, each truncated to an integer.
/// Source: DOSBox Staging `voodoo_reciplog` (lookup bits 9, lookup precision 22).
pub(crate) fn reciplog_table() -> &'static [[u32; 2]; RECIPLOG_STEPS + 1] {
    static TABLE: std::sync::OnceLock<[[u32; 2]; RECIPLOG_STEPS + 1]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut t = [[0u32; 2]; RECIPLOG_STEPS + 1];
        let width = f64::from(1u32 << 22);
        let steps = RECIPLOG_STEPS as f64;
        for (i, e) in t.iter_mut().enumerate() {
            let n = steps + i as f64;
            *e = [
                (steps * width / n) as u32,
                ((n / steps).log2() * width) as u32,
            ];
        }
        t
    })
}

/// DOSBox Staging's `fast_reciplog`: `1 / value` for a .32 value, as .15 (sign kept), and
/// `log2(1 / value)` as 24.8, both interpolated linearly between the two nearest entries of
/// [`reciplog_table`] with the 8 mantissa bits below the table index. Only bits 47:0 of
/// the magnitude count (bits 47:32 set: bits 47:16 are used). Zero gives the largest
/// reciprocal and a log of 1000.0.
#[inline]
pub(crate) fn reciplog_dosbox(value: i64) -> (i64, i32) {
    reciplog_in(reciplog_table(), value)
}

/// [`reciplog_dosbox`] with the table already at hand (the span kernels fetch it once per
/// chunk).
#[inline(always)]
pub(crate) fn reciplog_in(table: &[[u32; 2]; RECIPLOG_STEPS + 1], value: i64) -> (i64, i32) {
    let neg = value < 0;
    let mag = value.wrapping_abs() as u64;
    let (mut temp, mut exponent) = if mag & 0xffff_0000_0000 != 0 {
        ((mag >> 16) as u32, -16i32)
    } else {
        (mag as u32, 0)
    };
    if temp == 0 {
        return (if neg { 0x8000_0000 } else { 0x7fff_ffff }, 1000 << 8);
    }
    let lz = temp.leading_zeros();
    temp <<= lz;
    exponent += lz as i32;
    let index = ((temp >> 22) & 0x1ff) as usize;
    let interp = (temp >> 14) & 0xff;
    let (lo, hi) = (table[index], table[index + 1]);
    let mut recip = u64::from((lo[0] * (0x100 - interp) + hi[0] * interp) >> 8);
    // Round the 22-bit log fraction to 8 bits; log(1/v) = exponent - log(mantissa).
    let rlog = log_fraction(table, index, interp);
    let log = ((exponent + 1) << 8) - rlog as i32;
    // 22 fraction bits in the table, 15 wanted, input .32 normalised at bit 31.
    let shift = exponent - 6;
    if shift < 0 {
        recip >>= -shift;
    } else {
        recip <<= shift;
    }
    let recip = recip as i64;
    (if neg { recip.wrapping_neg() } else { recip }, log)
}

/// `log2` of a mantissa as [`reciplog_in`] reads it: the table's two log entries at
/// `index` and `index + 1` interpolated with the 8-bit weight `interp`, the 22-bit
/// fraction rounded to 8 bits (0..=256).
#[inline(always)]
fn log_fraction(table: &[[u32; 2]; RECIPLOG_STEPS + 1], index: usize, interp: u32) -> u32 {
    let rlog = (table[index][1] * (0x100 - interp) + table[index + 1][1] * interp) >> 8;
    (rlog + (1 << 13)) >> 14
}

/// Bits 30:14 of a mantissa normalised to bit 31, as [`reciplog_in`] reads it: the
/// table index (bits 30:22) and the interpolation weight (bits 21:14) together.
const MANTISSA_KEYS: usize = 1 << 17;

/// For every mantissa key ([`MANTISSA_KEYS`]), the log fraction [`reciplog_in`] takes
/// from the reciprocal/log table: the two entries interpolated and rounded to 8 bits
/// (0..=256), computed once from [`reciplog_table`], so that the span kernels' lanes
/// find it with one load instead of two loads, two multiplies and a rounding. Held as
/// 32-bit words, which a vector gather loads (there is no 16-bit gather).
pub(crate) fn reciplog_log_fractions() -> &'static [u32; MANTISSA_KEYS] {
    static FRACTIONS: std::sync::OnceLock<Box<[u32; MANTISSA_KEYS]>> = std::sync::OnceLock::new();
    FRACTIONS.get_or_init(|| {
        let table = reciplog_table();
        let mut fractions: Box<[u32; MANTISSA_KEYS]> = vec![0u32; MANTISSA_KEYS]
            .into_boxed_slice()
            .try_into()
            .expect("MANTISSA_KEYS words");
        for (key, f) in fractions.iter_mut().enumerate() {
            *f = log_fraction(table, key >> 8, key as u32 & 0xff);
        }
        fractions
    })
}

/// The log of [`reciplog_in`] alone, without branches, for the span kernels' lane
/// loops, its fraction from [`reciplog_log_fractions`]: the same integer for every
/// value (test `branch_free_reciplog_log`).
#[inline(always)]
pub(crate) fn reciplog_log_keyed(fractions: &[u32; MANTISSA_KEYS], value: i64) -> i32 {
    let (key, whole, zero) = reciplog_log_key(value);
    if zero {
        1000 << 8
    } else {
        whole - fractions[key as usize] as i32
    }
}

/// What [`reciplog_in`]'s log takes from `value` besides the table: the mantissa key
/// (bits 30:14 of the magnitude normalised to bit 31), the whole part (`exponent + 1`,
/// 8.8) the key's fraction is taken from, and whether the value is 0 (whose log is
/// `1000 << 8`).
#[inline(always)]
fn reciplog_log_key(value: i64) -> (u32, i32, bool) {
    let mag = value.wrapping_abs() as u64;
    let high = mag & 0xffff_0000_0000 != 0;
    let temp = if high { (mag >> 16) as u32 } else { mag as u32 };
    let lz = temp.leading_zeros();
    let exponent = if high { -16 } else { 0 } + lz as i32;
    let norm = temp.wrapping_shl(lz);
    let key = (norm >> 14) & (MANTISSA_KEYS as u32 - 1);
    (key, (exponent + 1) << 8, temp == 0)
}

/// [`reciplog_log_keyed`] of the first `n` of `w`, into `out`, in three passes that
/// each vectorise (the mantissa keys and exponents, the table gather, the sum), which
/// the one loop of the keyed form does not: the same integers (test
/// `reciplog_log_lanes_equal_the_keyed_form`).
#[inline(always)]
pub(crate) fn reciplog_log_lanes(
    fractions: &[u32; MANTISSA_KEYS],
    w: &[i64; LANES],
    n: usize,
    out: &mut [i32; LANES],
) {
    let n = n.min(LANES);
    let mut keys = [0u32; LANES];
    let mut zero = [false; LANES];
    for i in 0..n {
        let (key, whole, is_zero) = reciplog_log_key(w[i]);
        keys[i] = key;
        out[i] = whole;
        zero[i] = is_zero;
    }
    let mut fraction = [0u32; LANES];
    for i in 0..n {
        fraction[i] = fractions[keys[i] as usize];
    }
    for i in 0..n {
        out[i] = if zero[i] {
            1000 << 8
        } else {
            out[i] - fraction[i] as i32
        };
    }
}

/// Converts a double to i32 as x86 `cvttsd2si` does (truncation; NaN and out-of-range give
/// `i32::MIN`), which is what the C++ references compiled to.
#[inline]
pub(crate) fn f64_to_i32_x86(v: f64) -> i32 {
    if !(-2_147_483_648.0..2_147_483_648.0).contains(&v) {
        i32::MIN
    } else {
        v as i32
    }
}

/// Per-triangle base LOD (8.8) from the S/T gradients (all .32 fixed point, in LOD-0 texels).
///
/// For [`LodCalc::Box86`] the result already includes `lodbias` (86Box adds it at setup).
pub(crate) fn lod_base(calc: LodCalc, g: [i64; 4], t_lod: u32) -> i32 {
    let [dsdx, dsdy, dtdx, dtdy] = g;
    match calc {
        LodCalc::Mame => {
            // Source: MAME `compute_lodbase`: log2 of the larger squared gradient, halved.
            let (a, b, c, d) = (dsdx as f64, dsdy as f64, dtdx as f64, dtdy as f64);
            let texdx = a * a + c * c;
            let texdy = b * b + d * d;
            let max = if texdx < texdy { texdy } else { texdx };
            log2_mame(max, 64) / 2
        }
        LodCalc::Dosbox => {
            // Source: DOSBox Staging `prepare_tmu`: gradients reduced to .18, squared as
            // 64-bit integers (28.36), the larger shifted to 28.20; log2 from
            // `fast_reciplog` (of the reciprocal, hence negated), + 12 for the shift,
            // halved towards zero.
            let sq = |v: i64| (v >> 14).wrapping_mul(v >> 14);
            let tdx = sq(dsdx).wrapping_add(sq(dtdx));
            let tdy = sq(dsdy).wrapping_add(sq(dtdy));
            let max = if tdx < tdy { tdy } else { tdx };
            let (_, log) = reciplog_dosbox(max >> 16);
            (-log + (12 << 8)) / 2
        }
        LodCalc::Box86 => {
            // Source: 86Box `voodoo_triangle`: gradients reduced to .18, squared as
            // 64-bit integers, log2 in doubles, then scaled by 1/4 (so half the MAME value).
            let sq = |v: i64| (v >> 14).wrapping_mul(v >> 14);
            let tdx = sq(dsdx).wrapping_add(sq(dtdx)) as u64;
            let tdy = sq(dsdy).wrapping_add(sq(dtdy)) as u64;
            let max = tdx.max(tdy);
            let lod = f64_to_i32_x86((max as f64 / (1u64 << 36) as f64).log2() * 256.0) >> 2;
            lod.wrapping_add(TLod(t_lod).lodbias() << 6)
        }
    }
}

/// Inputs of the per-pixel LOD.
pub(crate) struct PixelLod {
    /// Base LOD from [`lod_base`].
    pub base: i32,
    /// With perspective correction on, the pixel's LOD change from its W ([`w_term`]).
    pub persp_term: Option<i32>,
    /// Screen position, for the dither.
    pub x: i32,
    /// Screen position, for the dither.
    pub y: i32,
}

/// The per-pixel LOD change (8.8) of perspective texturing: `log2(1 / W)` of the pixel's
/// iterated W (.32), at the precision of `calc`.
#[inline]
pub(crate) fn w_term(calc: LodCalc, w: i64) -> i32 {
    match calc {
        LodCalc::Mame => log2_mame(w as f64, 32).wrapping_neg(),
        // Source: DOSBox Staging `TEXTURE_PIPELINE`: log2(1/W) from `fast_reciplog`.
        LodCalc::Dosbox => reciplog_dosbox(w).1,
        LodCalc::Box86 => {
            // 1/W as 16.16 from a 64-bit divide; a negative W is a huge unsigned value.
            let recip = crate::sample::box86_oow(w) as u64;
            log2_86box(recip).wrapping_sub(19 << 8)
        }
    }
}

/// Final 8.8 LOD of one pixel, clamped to `[lodmin, min(lodmax, 8.0)]`.
#[inline]
pub(crate) fn pixel_lod(
    calc: LodCalc,
    dither: LodDither,
    p: &PixelLod,
    t_lod: u32,
    lod_dither_on: bool,
) -> i32 {
    let tl = TLod(t_lod);
    let mut lod = p.base;
    if let Some(term) = p.persp_term {
        lod = lod.wrapping_add(term);
    }
    // 86Box adds the bias at setup (see `lod_base`).
    if calc != LodCalc::Box86 {
        lod = lod.wrapping_add(tl.lodbias() << 6);
    }
    if lod_dither_on && dither == LodDither::Matrix4x4 {
        // Source: MAME `fetch_texel` and DOSBox `TEXTURE_PIPELINE`: matrix value << 4 (0..15/16).
        lod += i32::from(DITHER_4X4[(p.y & 3) as usize][(p.x & 3) as usize]) << 4;
    }
    // UNVERIFIED: the range is capped at LOD 8.0, the smallest level (spec 5.51: LODs 0
    // to 8), lodmin too: a `lodmin` field above 8.0 (4.2 fixed point, up to 15.75) gives
    // LOD 8.0, whose level, parity (trilinear) and zero fraction are those of the level
    // read. MAME does not cap lodmax at 8.0. For a lodmin above 8.0, 86Box's
    // `voodoo_tmu_fetch` indexes its nine-level table with the clamped LOD as it is
    // (as far as we read): not a behaviour a chip has.
    let min = lod_min(tl);
    let max = ((tl.lodmax() << 6) as i32).min(0x800);
    // A lodmin above lodmax: MAME's std::clamp is then undefined; take lodmin like 86Box.
    lod.min(max).max(min)
}

/// `tLOD`'s `lodmin` as 8.8, capped at LOD 8.0 as [`pixel_lod`]'s clamp is.
#[inline]
pub(crate) fn lod_min(tl: TLod) -> i32 {
    ((tl.lodmin() << 6) as i32).min(0x800)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_tables_follow_their_formulas() {
        for (i, &v) in LOG2_FRAC_128.iter().enumerate() {
            assert_eq!(
                v,
                (256.0 * (1.0 + i as f64 / 128.0).log2()).floor() as u8,
                "{i}"
            );
        }
        for (i, &v) in LOG2_FRAC_256.iter().enumerate() {
            assert_eq!(
                v,
                (256.0 * (1.0 + i as f64 / 256.0).log2()).floor() as u8,
                "{i}"
            );
        }
    }

    #[test]
    fn mame_log2() {
        // 1.0 in .32
        assert_eq!(log2_mame((1u64 << 32) as f64, 32), 0);
        assert_eq!(log2_mame((1u64 << 34) as f64, 32), 0x200);
        // 0.5 -> -1.0
        assert_eq!(log2_mame((1u64 << 31) as f64, 32), -0x100);
        // 1.5 -> 0x95 (floor(256 * log2 1.5) = 149)
        assert_eq!(log2_mame((3u64 << 31) as f64, 32), 149);
        assert_eq!(log2_mame(-5.0, 32), 0);
    }

    #[test]
    fn box86_log2() {
        assert_eq!(log2_86box(1 << 16), 16 << 8);
        assert_eq!(log2_86box(3 << 15), (16 << 8) | 149);
        assert_eq!(log2_86box(3), (1 << 8) | 149);
        assert_eq!(log2_86box(0), i32::MIN);
    }

    #[test]
    fn mame_base_lod_from_gradients() {
        let one = 1i64 << 32;
        // 1 texel per pixel: LOD 0
        assert_eq!(lod_base(LodCalc::Mame, [one, 0, 0, one], 0), 0);
        // 4 texels per pixel in X: LOD 2
        assert_eq!(lod_base(LodCalc::Mame, [4 * one, 0, 0, one], 0), 0x200);
        // the larger of the X and Y gradients wins; sqrt(3^2 + 4^2) = 5 -> log2 5 = 2.32
        // squared 25 -> 4.64 as 4.8: 4 << 8 | table[(25/16 - 1) * 128 = 72] = 0x4a4, halved
        assert_eq!(
            lod_base(LodCalc::Mame, [3 * one, one, 4 * one, 0], 0),
            0x4a4 / 2
        );
    }

    #[test]
    fn box86_base_lod_is_half_scale_plus_bias() {
        let one = 1i64 << 32;
        // 4 texels per pixel: log2(16) * 256 >> 2 = 0x100
        assert_eq!(lod_base(LodCalc::Box86, [4 * one, 0, 0, one], 0), 0x100);
        // bias +1.5 (4.2: 6) -> + 0x180
        assert_eq!(
            lod_base(LodCalc::Box86, [4 * one, 0, 0, one], 6 << 12),
            0x280
        );
    }

    #[test]
    fn pixel_lod_bias_dither_clamp() {
        let tl = (8 << 6 | 1) | (0x3e << 12); // lodmin 0.25, lodmax 2.0, bias -0.5
        let p = PixelLod {
            base: 0x180,
            persp_term: None,
            x: 1,
            y: 2,
        };
        assert_eq!(
            pixel_lod(LodCalc::Mame, LodDither::Matrix4x4, &p, tl, false),
            0x100
        );
        // dither at (1, 2): 11 << 4 = 0xb0
        assert_eq!(
            pixel_lod(LodCalc::Mame, LodDither::Matrix4x4, &p, tl, true),
            0x1b0
        );
        assert_eq!(
            pixel_lod(LodCalc::Mame, LodDither::Off, &p, tl, true),
            0x100
        );
        // clamp high and low
        let p = PixelLod { base: 0x900, ..p };
        assert_eq!(
            pixel_lod(LodCalc::Mame, LodDither::Off, &p, tl, false),
            0x200
        );
        let p = PixelLod { base: -0x900, ..p };
        assert_eq!(
            pixel_lod(LodCalc::Mame, LodDither::Off, &p, tl, false),
            0x40
        );
        // lodmax above 8.0 is capped
        let p = PixelLod { base: 0x1000, ..p };
        assert_eq!(
            pixel_lod(LodCalc::Mame, LodDither::Off, &p, 0x3f << 6, false),
            0x800
        );
    }

    #[test]
    fn perspective_subtracts_log_w() {
        let tl = 0x20 << 6; // lodmax 8.0
                            // W = 0.25 (2.30 << 2 = .32): log2 = -2 -> LOD + 2
        let at = |calc| PixelLod {
            base: 0x100,
            persp_term: Some(w_term(calc, 1 << 30)),
            x: 0,
            y: 0,
        };
        assert_eq!(w_term(LodCalc::Mame, 1 << 30), 0x200);
        assert_eq!(
            pixel_lod(LodCalc::Mame, LodDither::Off, &at(LodCalc::Mame), tl, false),
            0x300
        );
        // 86Box: 2^48 / 2^30 = 2^18 -> 18 - 19 = -1.0
        assert_eq!(w_term(LodCalc::Box86, 1 << 30), -0x100);
        assert_eq!(
            pixel_lod(
                LodCalc::Box86,
                LodDither::Off,
                &at(LodCalc::Box86),
                tl,
                false
            ),
            0
        );
    }

    #[test]
    fn dosbox_reciplog() {
        let one = 1i64 << 32;
        // 1.0: 1/1 = 1.0 as .15, log 0
        assert_eq!(reciplog_dosbox(one), (1 << 15, 0));
        // 4.0 -> 0.25, log -2; 0.5 -> 2.0, log +1; signs carry to the reciprocal only
        assert_eq!(reciplog_dosbox(4 * one), (1 << 13, -0x200));
        assert_eq!(reciplog_dosbox(-(one / 2)), (-(1 << 16), 0x100));
        // 1.5: table entry 256 exactly: 2^22 / 1.5 = 2796202 (.22) -> >> 7 = 21845;
        // log2 1.5 * 2^22 = 2453426 -> rounded to 8 bits: (2453426 + 8192) >> 14 = 150
        assert_eq!(reciplog_dosbox(3 * one / 2), (21845, -150));
        // interpolation: 1 + 1/1024 lies halfway between entries 0 and 1
        let t = reciplog_table();
        let half = u64::from((t[0][0] + t[1][0]) >> 1) >> 7;
        assert_eq!(reciplog_dosbox(one + (one >> 10)).0, half as i64);
        // zero: the largest reciprocal, log 1000.0
        assert_eq!(reciplog_dosbox(0), (0x7fff_ffff, 1000 << 8));
        // above 32 integer bits only bits 47:16 are looked at
        assert_eq!(reciplog_dosbox(1 << 47).1, -(15 << 8));
    }

    #[test]
    fn dosbox_base_lod_from_gradients() {
        let one = 1i64 << 32;
        assert_eq!(lod_base(LodCalc::Dosbox, [one, 0, 0, one], 0), 0);
        assert_eq!(lod_base(LodCalc::Dosbox, [4 * one, 0, 0, one], 0), 0x200);
        // |(3, 4)| = 5: 25 = 16 * (1 + 288 / 512): log2 = 4 + 165 (entry 288, rounded) / 256
        assert_eq!(
            lod_base(LodCalc::Dosbox, [3 * one, one, 4 * one, 0], 0),
            (0x400 + 165) / 2
        );
        // per pixel: log2(1 / 0.25) = +2; bias is added after
        let p = PixelLod {
            base: 0x100,
            persp_term: Some(w_term(LodCalc::Dosbox, 1 << 30)),
            x: 0,
            y: 0,
        };
        let tl = (0x20 << 6) | (0x3e << 12); // lodmax 8.0, bias -0.5
        assert_eq!(
            pixel_lod(LodCalc::Dosbox, LodDither::Off, &p, tl, false),
            0x300 - 0x80
        );
    }

    #[test]
    fn branch_free_reciplog_log() {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut values = vec![
            0,
            1,
            -1,
            i64::MIN,
            i64::MAX,
            1 << 32,
            1 << 47,
            1 << 48,
            -(1 << 48),
        ];
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            values.push((x as i64) >> (x % 64));
        }
        // Every mantissa key at a few exponents, both signs.
        for key in 0..MANTISSA_KEYS as i64 {
            let norm = 1 << 31 | key << 14 | ((key * 7) & 0x3fff);
            for shift in [0, 5, 17, 31] {
                values.push(norm >> shift);
                values.push(-(norm << 16 >> shift));
            }
        }
        let fractions = reciplog_log_fractions();
        for v in &values {
            let log = reciplog_dosbox(*v).1;
            assert_eq!(reciplog_log_keyed(fractions, *v), log, "{v:#x}");
        }
        reciplog_log_lanes_equal_the_keyed_form(&values);
    }

    /// `reciplog_log_lanes` against `reciplog_log_keyed`, a chunk of lanes at a time,
    /// with every count of live lanes (the lanes past it left alone).
    fn reciplog_log_lanes_equal_the_keyed_form(values: &[i64]) {
        let fractions = reciplog_log_fractions();
        for (k, chunk) in values.chunks(LANES).enumerate() {
            let n = chunk.len().saturating_sub(k % 3);
            let mut w = [0i64; LANES];
            w[..chunk.len()].copy_from_slice(chunk);
            let mut out = [7i32; LANES];
            reciplog_log_lanes(fractions, &w, n, &mut out);
            for i in 0..LANES {
                let want = if i < n {
                    reciplog_log_keyed(fractions, w[i])
                } else {
                    7
                };
                assert_eq!(out[i], want, "lane {i} of {n}: {:#x}", w[i]);
            }
        }
    }

    #[test]
    fn x86_conversion() {
        assert_eq!(f64_to_i32_x86(-1.9), -1);
        assert_eq!(f64_to_i32_x86(3e10), i32::MIN);
        assert_eq!(f64_to_i32_x86(f64::NAN), i32::MIN);
        assert_eq!(f64_to_i32_x86(f64::NEG_INFINITY), i32::MIN);
    }
}

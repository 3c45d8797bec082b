//! Alpha blending (spec 5.18.2 `alphaMode` bits 23:8; `fbzMode` bit 18 alpha planes and
//! bit 19 alpha-blend dither subtraction, spec 5.19).
//!
//! ```text
//! RGB:    Dnew = S * alpha + Dold * beta      (alphaMode bits 11:8 and 15:12)
//! alpha:  Anew = As * alpha_d + Aold * beta_d (bits 19:16 and 23:20)
//! ```
//! `Dold` is the RGB565 destination widened to 8 bits; `Aold` is the aux-buffer word when
//! alpha planes are enabled, else 0xff. Factors: `AZERO`, `ASRC_ALPHA`, `A_COLOR` (the
//! other operand's colour), `ADST_ALPHA`, `AONE`, `AOMSRC_ALPHA`, `AOM_COLOR`,
//! `AOMDST_ALPHA`, and 0xf: `ASATURATE` = min(As, 1 - Ad) as a source factor,
//! `A_COLORBEFOREFOG` (the source colour before fog) as a destination factor. Reserved
//! factors 8..=14 act as zero (MAME, DOSBox Staging; 86Box leaves the source term
//! unscaled for them). The alpha channel implements only `AZERO` and `AONE` (spec 5.18.2:
//! "the first silicon spin of SST-1 only supports AZERO and AONE for the alpha channel";
//! all three references treat every other alpha factor as zero). Results clamp to
//! 0..=255.
//!
//! The references agree on all of that and differ on the arithmetic; see
//! [`BlendArithmetic`].

use serde::{Deserialize, Serialize};
use sst1_regs::{AlphaMode, BlendFactor, FbzMode, Rgba};

/// How the blend is computed: destination widening, dither subtraction, factor scale and
/// rounding. `Mame`, `Dosbox` and `Exact255` each reproduce one reference's arithmetic as
/// a whole; `PerProduct` (the hardware model's) takes each of the three choices as two
/// of the three references make it.
///
/// | | widening of 565 | dither subtraction (bit 19) | factors, rounding |
/// |---|---|---|---|
/// | `PerProduct` | replicate high bits | only with dithering on: `+(15-d)>>1` R/B, `+(15-d)>>2` G | `x+1` and `256-x` (0..=256), each product `>> 8`, then add |
/// | `Mame` | as `PerProduct` | as `PerProduct` | as `PerProduct`, but the two products are added and the sum shifted `>> 8` once |
/// | `Dosbox` | zero-fill low bits | as MAME | as `PerProduct` |
/// | `Exact255` | replicate high bits | also with dithering off: 86Box's tables, see below | `x` and `255-x`, each product `/ 255` (truncating), then add |
///
/// MAME's rounding is that of `Mame`: its `alpha_blend` ends in
/// `rgbaint_t::scale2_add_and_clamp`, which in both the SSE2 build (`rgbsse.h`: the two
/// 16-bit products summed by one `_mm_madd_epi16`, then `>> 8`) and the portable one
/// (`rgbgen.h`: `mul`, `add`, then `sra_imm(8)`) rounds the sum once. The MAME goldens
/// confirm it: with `Mame` ours equal MAME's dump on every pixel of `alpha_blend`
/// (307200 of 307200, against 300709 with `PerProduct`) and `tex_8bit_formats` (307200,
/// against 270159).
///
/// 86Box's dither-subtraction tables (`dithersub_rb`, `dithersub_g` and their 2x2 forms)
/// equal, for every entry: red/blue `0` if the widened value is below 4, else
/// `min(255, v + ((10 - d) >> 1))`; green `0` below 2, else `min(255, v + ((12 - d) >> 2))`,
/// `d` being the entry of the dither matrix at the pixel (fitted to the tables when this
/// module was written). It also uses only the low byte of the aux word as destination
/// alpha, where MAME and DOSBox Staging use the whole word, and it stores the blended
/// alpha unclamped (up to 510) in the aux buffer; here it is clamped to 255 in every
/// variant (INACCURATE for 86Box's `AONE`/`AONE` alpha above 255).
///
/// Default (the hardware model): `PerProduct`. The spec gives only
/// `Dnew = S*alpha + Dold*beta`, no capture from a board exists, and no two references
/// share one arithmetic; but on each of its three parts two of them agree: the 565
/// destination is widened by replicating its high bits (MAME, 86Box), factors are
/// `x + 1` and `256 - x` (MAME, DOSBox Staging), and each product is rounded on its own
/// (DOSBox Staging's `>> 8`, 86Box's `/ 255`). A chip with two 8x9-bit multipliers, each
/// truncated, and one adder computes it. Measured over every dump of both suites
/// (conformance + glide-sdk, consensus + majority misses, every other switch at the
/// hardware model's): `PerProduct` 36 + 184,161 and 5 + 34,597; `Mame` 52 + 298,512 and
/// 5 + 49,415 (185 + 299,034 on the conformance suite with MAME's own widening of
/// 2x2-dithered destinations too). (The per-pixel vote of the
/// three arithmetics that this project used before, which no chip computes, left
/// 33 + 121,807 and 5 + 3,197; `--model vote` still votes whole boards.)
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum BlendArithmetic {
    /// Each part as two of the three references have it (see above).
    #[default]
    PerProduct,
    /// MAME, as its source and its goldens show: the sum of the two products rounded once.
    Mame,
    /// DOSBox Staging.
    Dosbox,
    /// 86Box: exact division by 255.
    Exact255,
}

/// Which colour the `ASATURATE` source factor scales.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum SaturateOperand {
    /// The source colour, as for every source factor (spec 5.18.2; MAME, DOSBox Staging).
    #[default]
    Source,
    /// The destination colour (86Box).
    Destination,
}

/// How the destination is widened for pixels written with the 2x2 dither (`fbzMode`
/// bit 8 and bit 11 set).
///
/// Every reference widens these destinations as it widens any other
/// ([`Dither2x2Blend::SameAsArithmetic`]), and so does the hardware model: one widening
/// for every pixel, as one blend unit would compute it. Zero fill for 2x2-dithered
/// destinations only was the hardware model's default until 2026-12-02. It had been
/// chosen for one dump, `stress_random/front`, where the three references agree on 109
/// pixels that replicated widening misses and zero fill gives; but they reach them each
/// by its own path (DOSBox Staging zero-fills every pixel, MAME dithers with its own 2x2
/// matrix, 86Box divides by 255), a coincidence rather than evidence. On 31 generated
/// scenes of random states (`voodoo gen random-states`, seeds 11 to 14, 21 to 23, 31 to
/// 42 and 51 to 62, judged against the three reference models' output; docs/accuracy.md,
/// "Unseen scenes") zero fill missed 2,715 more pixels on which the three agree than
/// replicated widening (1,028, 1,560 and 127 more in three scenes, the same elsewhere),
/// and no scene did better with it; on `stress_random` replicated widening misses the
/// 109 again (listed in `traces/hardware-budget.toml`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Dither2x2Blend {
    /// [`BlendProfile::arithmetic`]'s widening, as for every other pixel (the hardware
    /// model, and what each reference emulator does).
    #[default]
    SameAsArithmetic,
    /// The 565 destination is widened by zero fill, whatever [`BlendProfile::arithmetic`]
    /// widens other pixels by (an experiment; the hardware model's default before
    /// 2026-12-02).
    ZeroFill,
}

/// The alpha-blend unit's disputed behaviours.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(default)]
pub struct BlendProfile {
    pub arithmetic: BlendArithmetic,
    pub saturate: SaturateOperand,
    pub dither_2x2: Dither2x2Blend,
}

impl BlendProfile {
    /// The hardware model's blend unit.
    pub const HARDWARE: BlendProfile = BlendProfile {
        arithmetic: BlendArithmetic::PerProduct,
        saturate: SaturateOperand::Source,
        dither_2x2: Dither2x2Blend::SameAsArithmetic,
    };
}

impl Default for BlendProfile {
    fn default() -> Self {
        Self::HARDWARE
    }
}

/// The per-pixel inputs of the blend unit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BlendInput {
    /// The source pixel: the fog unit's output colour and the combined alpha.
    pub src: Rgba,
    /// The colour before the fog unit (for `A_COLORBEFOREFOG`); its alpha is unused.
    pub prefog: Rgba,
    /// The destination pixel in the colour buffer.
    pub dst_rgb565: u16,
    /// The aux-buffer word at the pixel, if the frame buffer has an aux buffer. It is the
    /// destination alpha when `fbzMode` bit 18 enables alpha planes.
    pub dst_aux: Option<u16>,
    /// The entry at the pixel of the dither matrix that `fbzMode` bit 11 selects (4x4 or
    /// 2x2), whether or not bit 8 enables dithering: `Dither::matrix_value` with
    /// `Dither4x4` or `Dither2x2`. Used only for dither subtraction (bit 19).
    pub dither_value: u8,
}

/// Scale of the blend factors: `(one, plus)`: a factor `x` is `x + plus`, `1 - x` is
/// `one - x`.
#[inline(always)]
fn scale(arithmetic: BlendArithmetic) -> (i32, i32) {
    match arithmetic {
        BlendArithmetic::PerProduct | BlendArithmetic::Mame | BlendArithmetic::Dosbox => (256, 1),
        BlendArithmetic::Exact255 => (255, 0),
    }
}

/// One channel's blend factor. `other` is the colour `A_COLOR` refers to (the destination
/// for a source factor, the source for a destination factor); `fifteen` is the value of
/// code 0xf (ASATURATE's min, or the pre-fog colour), before `plus` is added.
#[inline(always)]
fn factor(
    code: BlendFactor,
    sa: i32,
    da: i32,
    other: i32,
    fifteen: i32,
    (one, plus): (i32, i32),
) -> i32 {
    match code {
        BlendFactor::Zero => 0,
        BlendFactor::SrcAlpha => sa + plus,
        BlendFactor::Color => other + plus,
        BlendFactor::DstAlpha => da + plus,
        BlendFactor::One => one,
        BlendFactor::OneMinusSrcAlpha => one - sa,
        BlendFactor::OneMinusColor => one - other,
        BlendFactor::OneMinusDstAlpha => one - da,
        BlendFactor::SaturateOrColorBeforeFog => fifteen + plus,
        _ => 0, // reserved 8..=14
    }
}

/// What the blend of one colour channel needs besides the channel's own values.
struct Channel {
    sa: i32,
    da: i32,
    saturate: i32,
    src_code: BlendFactor,
    dst_code: BlendFactor,
    sc: (i32, i32),
    arith: BlendArithmetic,
    /// The source factor scales the destination (86Box's ASATURATE operand).
    saturate_dst: bool,
}

impl Channel {
    /// `src * fs + dst * fd` for one channel, clamped to 0..=255; `pf` is the channel's
    /// pre-fog colour. Inlined into the walker so that the blend codes are folded where they
    /// are constants (a closure here was not inlined).
    #[inline(always)]
    fn blend(&self, s: i32, d: i32, pf: i32) -> i32 {
        let fs = factor(self.src_code, self.sa, self.da, d, self.saturate, self.sc);
        let fd = factor(self.dst_code, self.sa, self.da, s, pf, self.sc);
        let sv = if self.saturate_dst { d } else { s };
        let (ts, td) = match self.arith {
            // Arithmetic shift: floor, as the references' signed shifts.
            BlendArithmetic::PerProduct | BlendArithmetic::Dosbox => {
                ((sv * fs) >> 8, (d * fd) >> 8)
            }
            // Source: MAME `scale2_add_and_clamp` (rgbsse.h, rgbgen.h).
            BlendArithmetic::Mame => ((sv * fs + d * fd) >> 8, 0),
            // C division: truncation toward zero (negative only for aux words above 255).
            BlendArithmetic::Exact255 => (sv * fs / 255, d * fd / 255),
        };
        (ts + td).clamp(0, 255)
    }
}

/// The destination colour widened to 8 bits per channel.
#[inline(always)]
fn widen(p: u16, replicate: bool) -> [i32; 3] {
    let p = p as i32;
    let (r, g, b) = ((p >> 8) & 0xf8, (p >> 3) & 0xfc, (p << 3) & 0xf8);
    if replicate {
        [r | r >> 5, g | g >> 6, b | b >> 5]
    } else {
        [r, g, b]
    }
}

/// 86Box's dither subtraction for one widened channel (see [`BlendArithmetic`]).
#[inline(always)]
fn dither_sub_86box(v: i32, offset: i32, floor: i32) -> i32 {
    if v < floor {
        0
    } else {
        (v + offset).clamp(0, 255)
    }
}

/// Blends `input.src` into the destination as `alpha_mode` says. With blending disabled
/// (`alphaMode` bit 4 clear) the source is returned unchanged. `fbz_mode` supplies alpha
/// planes (bit 18), dithering (bit 8) and dither subtraction (bit 19).
#[inline(always)]
pub fn alpha_blend(
    alpha_mode: AlphaMode,
    fbz_mode: FbzMode,
    input: &BlendInput,
    profile: BlendProfile,
) -> Rgba {
    let src = input.src;
    if !alpha_mode.alpha_blend_enable() {
        return src;
    }
    let zero_fill = fbz_mode.enable_dithering()
        && fbz_mode.dither_2x2()
        && profile.dither_2x2 == Dither2x2Blend::ZeroFill;
    let (rgb, da) = blend_rgb(
        profile.arithmetic,
        zero_fill,
        alpha_mode,
        fbz_mode,
        input,
        profile,
    );
    finish(rgb, da, alpha_mode, input)
}

/// The blended pixel from its RGB and the destination alpha: the alpha channel has only
/// `AONE` or nothing (spec 5.18.2; all three references).
#[inline(always)]
fn finish(rgb: [i32; 3], da: i32, alpha_mode: AlphaMode, input: &BlendInput) -> Rgba {
    let sa = input.src.a as i32;
    let a_src = if alpha_mode.src_alpha_blend() == BlendFactor::One {
        sa
    } else {
        0
    };
    let a_dst = if alpha_mode.dst_alpha_blend() == BlendFactor::One {
        da
    } else {
        0
    };
    Rgba {
        r: rgb[0] as u8,
        g: rgb[1] as u8,
        b: rgb[2] as u8,
        a: (a_src + a_dst).clamp(0, 255) as u8,
    }
}

/// The RGB blend under one arithmetic, and the destination alpha it used. `zero_fill`:
/// widen the destination by zero fill whatever the arithmetic says
/// ([`Dither2x2Blend::ZeroFill`]).
#[inline(always)]
fn blend_rgb(
    arith: BlendArithmetic,
    zero_fill: bool,
    alpha_mode: AlphaMode,
    fbz_mode: FbzMode,
    input: &BlendInput,
    profile: BlendProfile,
) -> ([i32; 3], i32) {
    let src = input.src;
    let sc = scale(arith);

    // Destination colour and alpha.
    let replicate = arith != BlendArithmetic::Dosbox && !zero_fill;
    let mut d = widen(input.dst_rgb565, replicate);
    let da = match (fbz_mode.enable_alpha_planes(), input.dst_aux) {
        (true, Some(aux)) if arith == BlendArithmetic::Exact255 => (aux & 0xff) as i32,
        (true, Some(aux)) => aux as i32,
        _ => 0xff,
    };

    // Dither subtraction: despite the name, MAME and DOSBox Staging raise the widened
    // destination by the part of the dither offset its truncation lost.
    if fbz_mode.dither_subtract() {
        let dv = input.dither_value as i32;
        match arith {
            BlendArithmetic::PerProduct | BlendArithmetic::Mame | BlendArithmetic::Dosbox
                if fbz_mode.enable_dithering() =>
            {
                let k = 15 - dv;
                d = [d[0] + (k >> 1), d[1] + (k >> 2), d[2] + (k >> 1)];
            }
            BlendArithmetic::Exact255 => {
                d = [
                    dither_sub_86box(d[0], (10 - dv) >> 1, 4),
                    dither_sub_86box(d[1], (12 - dv) >> 2, 2),
                    dither_sub_86box(d[2], (10 - dv) >> 1, 4),
                ];
            }
            _ => {}
        }
    }

    let s = [src.r as i32, src.g as i32, src.b as i32];
    let pf = [
        input.prefog.r as i32,
        input.prefog.g as i32,
        input.prefog.b as i32,
    ];
    let sa = src.a as i32;
    let (one, _) = sc;
    let saturate = sa.min(one - da);
    let src_code = alpha_mode.src_rgb_blend();
    let dst_code = alpha_mode.dst_rgb_blend();

    let channel = Channel {
        sa,
        da,
        saturate,
        src_code,
        dst_code,
        sc,
        arith,
        saturate_dst: src_code == BlendFactor::SaturateOrColorBeforeFog
            && profile.saturate == SaturateOperand::Destination,
    };
    let rgb = [
        channel.blend(s[0], d[0], pf[0]),
        channel.blend(s[1], d[1], pf[1]),
        channel.blend(s[2], d[2], pf[2]),
    ];
    (rgb, da)
}

/// [`alpha_blend`]'s inputs for every lane of a chunk of a span ([`crate::span`]).
pub struct BlendLanes<'a, const L: usize> {
    /// The fogged colour, R, G, B, A.
    pub src: &'a [[i32; L]; 4],
    /// The colour before fog, R, G, B (A unused).
    pub prefog: &'a [[i32; L]; 4],
    /// The destination RGB565 word (0 where the lane has none).
    pub dst_rgb565: &'a [i32; L],
    /// The aux word, where `has_aux`.
    pub dst_aux: &'a [i32; L],
    /// Whether the lane has an aux word.
    pub has_aux: &'a [bool; L],
    /// The dither matrix entry at the lane's pixel.
    pub dither_value: &'a [i32; L],
}

/// [`factor`] for every lane, `code` chosen once.
#[inline(always)]
fn factor_lanes<const L: usize>(
    code: BlendFactor,
    sa: &[i32; L],
    da: &[i32; L],
    other: &[i32; L],
    fifteen: &[i32; L],
    (one, plus): (i32, i32),
) -> [i32; L] {
    use crate::span::lanes;
    match code {
        BlendFactor::Zero => [0; L],
        BlendFactor::SrcAlpha => lanes(|i| sa[i] + plus),
        BlendFactor::Color => lanes(|i| other[i] + plus),
        BlendFactor::DstAlpha => lanes(|i| da[i] + plus),
        BlendFactor::One => [one; L],
        BlendFactor::OneMinusSrcAlpha => lanes(|i| one - sa[i]),
        BlendFactor::OneMinusColor => lanes(|i| one - other[i]),
        BlendFactor::OneMinusDstAlpha => lanes(|i| one - da[i]),
        BlendFactor::SaturateOrColorBeforeFog => lanes(|i| fifteen[i] + plus),
        _ => [0; L], // reserved 8..=14
    }
}

/// [`alpha_blend`] (with blending enabled) for every lane at once: the same arithmetic,
/// its choices made once, into `out` (R, G, B, A). Lanes without a pixel compute
/// harmless garbage.
#[inline(always)]
pub fn alpha_blend_lanes<const L: usize>(
    alpha_mode: AlphaMode,
    fbz_mode: FbzMode,
    input: &BlendLanes<'_, L>,
    profile: BlendProfile,
    out: &mut [[i32; L]; 4],
) {
    use crate::span::lanes;
    let arith = profile.arithmetic;
    let zero_fill = fbz_mode.enable_dithering()
        && fbz_mode.dither_2x2()
        && profile.dither_2x2 == Dither2x2Blend::ZeroFill;
    let sc = scale(arith);
    let (one, _) = sc;
    let replicate = arith != BlendArithmetic::Dosbox && !zero_fill;

    // Destination colour and alpha (see `widen`).
    let p = input.dst_rgb565;
    let rep = |v: i32, shift: i32| if replicate { v | v >> shift } else { v };
    let mut d: [[i32; L]; 3] = [
        lanes(|i| rep((p[i] >> 8) & 0xf8, 5)),
        lanes(|i| rep((p[i] >> 3) & 0xfc, 6)),
        lanes(|i| rep((p[i] << 3) & 0xf8, 5)),
    ];
    let planes = fbz_mode.enable_alpha_planes();
    let da: [i32; L] = lanes(|i| match (planes, input.has_aux[i]) {
        (true, true) if arith == BlendArithmetic::Exact255 => input.dst_aux[i] & 0xff,
        (true, true) => input.dst_aux[i],
        _ => 0xff,
    });

    if fbz_mode.dither_subtract() {
        let dv = input.dither_value;
        match arith {
            BlendArithmetic::PerProduct | BlendArithmetic::Mame | BlendArithmetic::Dosbox
                if fbz_mode.enable_dithering() =>
            {
                for i in 0..L {
                    let k = 15 - dv[i];
                    d[0][i] += k >> 1;
                    d[1][i] += k >> 2;
                    d[2][i] += k >> 1;
                }
            }
            BlendArithmetic::Exact255 => {
                for i in 0..L {
                    d[0][i] = dither_sub_86box(d[0][i], (10 - dv[i]) >> 1, 4);
                    d[1][i] = dither_sub_86box(d[1][i], (12 - dv[i]) >> 2, 2);
                    d[2][i] = dither_sub_86box(d[2][i], (10 - dv[i]) >> 1, 4);
                }
            }
            _ => {}
        }
    }

    let s = input.src;
    let sa = &s[3];
    let saturate: [i32; L] = lanes(|i| sa[i].min(one - da[i]));
    let src_code = alpha_mode.src_rgb_blend();
    let dst_code = alpha_mode.dst_rgb_blend();
    let saturate_dst = src_code == BlendFactor::SaturateOrColorBeforeFog
        && profile.saturate == SaturateOperand::Destination;
    for c in 0..3 {
        let fs = factor_lanes(src_code, sa, &da, &d[c], &saturate, sc);
        let fd = factor_lanes(dst_code, sa, &da, &s[c], &input.prefog[c], sc);
        let sv = if saturate_dst { &d[c] } else { &s[c] };
        let dc = &d[c];
        out[c] = match arith {
            // Arithmetic shift: floor, as the references' signed shifts.
            BlendArithmetic::PerProduct | BlendArithmetic::Dosbox => {
                lanes(|i| (((sv[i] * fs[i]) >> 8) + ((dc[i] * fd[i]) >> 8)).clamp(0, 255))
            }
            BlendArithmetic::Mame => {
                lanes(|i| ((sv[i] * fs[i] + dc[i] * fd[i]) >> 8).clamp(0, 255))
            }
            BlendArithmetic::Exact255 => {
                lanes(|i| (sv[i] * fs[i] / 255 + dc[i] * fd[i] / 255).clamp(0, 255))
            }
        };
    }
    let a_src = alpha_mode.src_alpha_blend() == BlendFactor::One;
    let a_dst = alpha_mode.dst_alpha_blend() == BlendFactor::One;
    out[3] = lanes(|i| {
        let a = if a_src { sa[i] } else { 0 } + if a_dst { da[i] } else { 0 };
        a.clamp(0, 255)
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use BlendArithmetic::{Dosbox, Exact255, Mame, PerProduct};

    const SRC: Rgba = Rgba {
        r: 200,
        g: 100,
        b: 50,
        a: 96,
    };
    const PREFOG: Rgba = Rgba {
        r: 10,
        g: 20,
        b: 30,
        a: 0,
    };
    /// r5 = 20, g6 = 40, b5 = 10: widened (165, 162, 82) by replication, (160, 160, 80)
    /// by zero fill.
    const DST: u16 = 20 << 11 | 40 << 5 | 10;
    const ALPHA_PLANES: u32 = 1 << 18;
    const DITHER: u32 = 1 << 8;
    const DITHER_SUB: u32 = 1 << 19;

    /// (source factor, destination factor, MAME, DOSBox Staging, 86Box results).
    type Case = (u32, u32, [u8; 3], [u8; 3], [u8; 3]);

    fn input() -> BlendInput {
        BlendInput {
            src: SRC,
            prefog: PREFOG,
            dst_rgb565: DST,
            dst_aux: Some(0x30),
            dither_value: 3,
        }
    }

    /// `alphaMode` with blending on and the given RGB / alpha factors.
    fn am(src: u32, dst: u32, src_a: u32, dst_a: u32) -> AlphaMode {
        AlphaMode(0x10 | src << 8 | dst << 12 | src_a << 16 | dst_a << 20)
    }

    fn blend(arith: BlendArithmetic, src: u32, dst: u32, fbz: u32, input: &BlendInput) -> [u8; 3] {
        let p = BlendProfile {
            arithmetic: arith,
            ..Default::default()
        };
        let c = alpha_blend(am(src, dst, 0, 0), FbzMode(fbz), input, p);
        [c.r, c.g, c.b]
    }

    /// Each factor pair under the three arithmetics: (src, dst, MAME, DOSBox, 86Box).
    /// The expected values follow the references' formulas (see the module docs), e.g.
    /// ASRC_ALPHA/AOMSRC_ALPHA red: MAME (200*97 >> 8) + (165*160 >> 8) = 75 + 103;
    /// DOSBox 75 + (160*160 >> 8 = 100); 86Box 200*96/255 + 165*159/255 = 75 + 102.
    #[test]
    fn every_rgb_factor_and_arithmetic() {
        #[rustfmt::skip]
        let cases: [Case; 14] = [
            (0, 0, [0, 0, 0], [0, 0, 0], [0, 0, 0]),
            (1, 5, [178, 138, 69], [175, 137, 68], [177, 138, 69]),
            (5, 1, [187, 123, 62], [185, 122, 61], [186, 122, 61]),
            (2, 0, [129, 63, 16], [125, 62, 15], [129, 63, 16]),
            (0, 2, [129, 63, 16], [125, 63, 15], [129, 63, 16]),
            (3, 7, [200, 100, 50], [200, 100, 50], [200, 100, 50]),
            (7, 3, [165, 162, 82], [160, 160, 80], [165, 162, 82]),
            (4, 4, [255, 255, 132], [255, 255, 130], [255, 255, 132]),
            (6, 4, [236, 198, 115], [235, 197, 114], [235, 198, 115]),
            (4, 6, [236, 198, 115], [235, 197, 114], [235, 198, 115]),
            // ASATURATE with Ad = 0xff: MAME/DOSBox min(96, 1) + 1 = 2; 86Box min(96, 0).
            (15, 4, [166, 162, 82], [161, 160, 80], [165, 162, 82]),
            // A_COLORBEFOREFOG.
            (4, 15, [207, 113, 59], [206, 113, 59], [206, 112, 59]),
            // Reserved factors act as zero.
            (8, 4, [165, 162, 82], [160, 160, 80], [165, 162, 82]),
            (1, 14, [75, 37, 18], [75, 37, 18], [75, 37, 18]),
        ];
        for (s, d, mame, dosbox, exact) in cases {
            assert_eq!(
                blend(PerProduct, s, d, 0, &input()),
                mame,
                "per product {s} {d}"
            );
            assert_eq!(blend(Dosbox, s, d, 0, &input()), dosbox, "DOSBox {s} {d}");
            assert_eq!(blend(Exact255, s, d, 0, &input()), exact, "86Box {s} {d}");
        }
    }

    /// `Mame` adds the two products before the shift; `PerProduct` shifts each.
    #[test]
    fn mame_sum_once() {
        // ASRC_ALPHA / AOMSRC_ALPHA: (200*97 + 165*160) >> 8 = 178, (100*97 + 162*160) >> 8
        // = 139 (per product 37 + 101 = 138), (50*97 + 82*160) >> 8 = 70 (18 + 51 = 69).
        assert_eq!(blend(Mame, 1, 5, 0, &input()), [178, 139, 70]);
        assert_eq!(blend(PerProduct, 1, 5, 0, &input()), [178, 138, 69]);
        // tmu2_combine (603, 430): source 60 with alpha 104 over 565 (31, 1, 23), widened
        // (255, 4, 189): red (60*105 + 255*152) >> 8 = 176 (per product 24 + 151 = 175).
        let i = BlendInput {
            src: Rgba {
                r: 60,
                g: 60,
                b: 60,
                a: 104,
            },
            dst_rgb565: 31 << 11 | 1 << 5 | 23,
            ..input()
        };
        assert_eq!(blend(Mame, 1, 5, 0, &i), [176, 26, 136]);
        assert_eq!(blend(PerProduct, 1, 5, 0, &i), [175, 26, 136]);
        // Widening, factors and dither subtraction are MAME's: with dithering and dither
        // subtraction on (d = 3: +6 R/B, +3 G) the destination is (171, 165, 88):
        // (200*97 + 171*160) >> 8 = 182, (100*97 + 165*160) >> 8 = 141, (50*97 + 88*160)
        // >> 8 = 73 (per product 75 + 106, 37 + 103, 18 + 55).
        assert_eq!(
            blend(Mame, 1, 5, DITHER | DITHER_SUB, &input()),
            [182, 141, 73]
        );
        assert_eq!(
            blend(PerProduct, 1, 5, DITHER | DITHER_SUB, &input()),
            [181, 140, 73]
        );
    }

    #[test]
    fn destination_alpha_from_alpha_planes() {
        let i = input(); // aux 0x30
        #[rustfmt::skip]
        let cases: [Case; 3] = [
            (3, 7, [172, 150, 75], [168, 149, 74], [170, 149, 75]),
            (7, 3, [193, 112, 55], [192, 111, 55], [193, 111, 55]),
            // ASATURATE: min(96, 256 - 48) = 96 -> factor 97; 86Box min(96, 207) = 96.
            (15, 0, [75, 37, 18], [75, 37, 18], [75, 37, 18]),
        ];
        for (s, d, mame, dosbox, exact) in cases {
            assert_eq!(blend(PerProduct, s, d, ALPHA_PLANES, &i), mame);
            assert_eq!(blend(Dosbox, s, d, ALPHA_PLANES, &i), dosbox);
            assert_eq!(blend(Exact255, s, d, ALPHA_PLANES, &i), exact);
        }
        // Without alpha planes, or without an aux buffer, Ad = 0xff.
        assert_eq!(blend(PerProduct, 3, 0, 0, &i), [200, 100, 50]);
        let no_aux = BlendInput { dst_aux: None, ..i };
        assert_eq!(
            blend(PerProduct, 3, 0, ALPHA_PLANES, &no_aux),
            [200, 100, 50]
        );
        // A whole aux word above 255: MAME/DOSBox use it (factor 0x131), 86Box its low byte.
        let big = BlendInput {
            dst_aux: Some(0x130),
            ..i
        };
        assert_eq!(blend(PerProduct, 3, 0, ALPHA_PLANES, &big), [238, 119, 59]);
        assert_eq!(blend(Dosbox, 3, 0, ALPHA_PLANES, &big), [238, 119, 59]);
        assert_eq!(blend(Exact255, 3, 0, ALPHA_PLANES, &big), [37, 18, 9]);
    }

    #[test]
    fn saturate_switch() {
        let p = BlendProfile {
            arithmetic: Exact255,
            saturate: SaturateOperand::Destination,
            ..Default::default()
        };
        let c = alpha_blend(am(15, 4, 0, 0), FbzMode(ALPHA_PLANES), &input(), p);
        // 86Box: dst * min(96, 207) / 255 + dst = 62 + 165, 60 + 162, 30 + 82.
        assert_eq!([c.r, c.g, c.b], [227, 222, 112]);
    }

    #[test]
    fn dither_subtraction() {
        let i = input(); // matrix entry 3
        let on = DITHER | DITHER_SUB;
        // AZERO/AONE shows the adjusted destination. MAME: (165, 162, 82) + (6, 3, 6);
        // DOSBox: (160, 160, 80) + (6, 3, 6); 86Box: + ((10-3)>>1, (12-3)>>2) = (3, 2, 3).
        assert_eq!(blend(PerProduct, 0, 4, on, &i), [171, 165, 88]);
        assert_eq!(blend(Dosbox, 0, 4, on, &i), [166, 163, 86]);
        assert_eq!(blend(Exact255, 0, 4, on, &i), [168, 164, 85]);
        assert_eq!(blend(PerProduct, 1, 5, on, &i), [181, 140, 73]);
        assert_eq!(blend(Dosbox, 1, 5, on, &i), [178, 138, 71]);
        assert_eq!(blend(Exact255, 1, 5, on, &i), [179, 139, 71]);
        // With dithering off only 86Box subtracts.
        assert_eq!(blend(PerProduct, 0, 4, DITHER_SUB, &i), [165, 162, 82]);
        assert_eq!(blend(Dosbox, 0, 4, DITHER_SUB, &i), [160, 160, 80]);
        assert_eq!(blend(Exact255, 0, 4, DITHER_SUB, &i), [168, 164, 85]);
        // Bit 19 clear: no adjustment.
        assert_eq!(blend(PerProduct, 0, 4, DITHER, &i), [165, 162, 82]);
        // 86Box's edges: black stays black, white saturates, negative offsets apply.
        let white = BlendInput {
            dst_rgb565: 0xffff,
            dither_value: 15,
            ..i
        };
        assert_eq!(blend(Exact255, 0, 4, on, &white), [252, 254, 252]);
        let black = BlendInput {
            dst_rgb565: 0,
            dither_value: 0,
            ..i
        };
        assert_eq!(blend(Exact255, 0, 4, on, &black), [0, 0, 0]);
        // MAME lets the destination exceed 255: AOM_COLOR on white with entry 0:
        // (255 + 7) * (256 - 200) >> 8 = 57.
        let white0 = BlendInput {
            dither_value: 0,
            ..white
        };
        assert_eq!(blend(PerProduct, 0, 6, on, &white0), [57, 157, 210]);
    }

    #[test]
    fn dither_2x2_pairing() {
        let i = input();
        let d2 = DITHER | 1 << 11;
        // Default: a 2x2-dithered destination is widened as any other.
        assert_eq!(blend(PerProduct, 1, 5, d2, &i), [178, 138, 69]);
        assert_eq!(blend(PerProduct, 1, 5, 1 << 11, &i), [178, 138, 69]);
        // `ZeroFill`: zero fill for 2x2-dithered destinations only; with `PerProduct`
        // that is DOSBox Staging's arithmetic.
        let zero_fill = BlendProfile {
            arithmetic: PerProduct,
            dither_2x2: Dither2x2Blend::ZeroFill,
            ..Default::default()
        };
        let c = alpha_blend(am(1, 5, 0, 0), FbzMode(d2), &i, zero_fill);
        assert_eq!([c.r, c.g, c.b], [175, 137, 68]);
        assert_eq!(blend(Dosbox, 1, 5, d2, &i), [175, 137, 68]);
        // Bit 11 without dithering (bit 8) is not 2x2 dithering.
        let c = alpha_blend(am(1, 5, 0, 0), FbzMode(1 << 11), &i, zero_fill);
        assert_eq!([c.r, c.g, c.b], [178, 138, 69]);
    }

    #[test]
    fn alpha_channel_and_disable() {
        let i = input();
        let planes = FbzMode(ALPHA_PLANES);
        let p = BlendProfile::default();
        // AONE + AONE: 96 + 0x30 = 144; AONE + AZERO: 96; AZERO + AONE: 48.
        assert_eq!(alpha_blend(am(4, 0, 4, 4), planes, &i, p).a, 144);
        assert_eq!(alpha_blend(am(4, 0, 4, 0), planes, &i, p).a, 96);
        assert_eq!(alpha_blend(am(4, 0, 0, 4), planes, &i, p).a, 48);
        // Other alpha factors act as zero; without alpha planes Ad = 0xff and the sum clamps.
        assert_eq!(alpha_blend(am(4, 0, 1, 5), planes, &i, p).a, 0);
        assert_eq!(alpha_blend(am(4, 0, 4, 4), FbzMode(0), &i, p).a, 255);
        // Blending disabled (bit 4 clear): the source is returned unchanged.
        assert_eq!(alpha_blend(AlphaMode(0x0000_4400), planes, &i, p), SRC);
    }
}

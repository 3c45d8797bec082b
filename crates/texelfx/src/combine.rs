//! The texture combine unit of each TMU: how a TMU merges its own texel (`c_local`) with the
//! upstream TMU's output (`c_other`), as controlled by the `tc_*` / `tca_*` fields of
//! `textureMode` (spec section 5.50 and its "Blend with Incoming Color" diagram), plus the
//! detail factor of `tDetail` (spec 5.52).
//!
//! Per channel (R, G, B use the `tc_*` fields, A the `tca_*` fields):
//!
//! ```text
//! blend  = (zero_other ? 0 : c_other) - (sub_clocal ? c_local : 0)      9-bit signed
//! factor = mselect(zero, c_local, a_other, a_local, detail, LOD frac)   0.8 unsigned
//! factor = reverse_blend' ? factor : factor ^ 0xff                        then + 1
//! out    = clamp((blend * factor) >> 8 + add, 0, 255)                  truncating multiply
//! out    = invert_output ? out ^ 0xff : out
//! ```
//!
//! `reverse_blend'` is `reverse_blend` inverted on odd LODs when `textureMode` bit 30
//! (trilinear) is set (the diagram's "for trilinear: 0 odd TREX, 1 even TREX" term).
//! Source for the arithmetic: spec 5.50 diagram (9x9 multiply, LSBs truncated, `+1` on the
//! factor, clamp 0..FF); MAME `combine_texture` and DOSBox Staging `TEXTURE_PIPELINE` agree on
//! every step. 86Box also agrees for a single TMU.
//!
//! The register fields are read through `sst1_regs`' [`TextureMode`] and [`TDetail`]
//! views; colours are `[r, g, b, a]` arrays.

use sst1_regs::{TDetail, TextureMode};

/// Index of the alpha channel in a `[r, g, b, a]` colour.
const A: usize = 3;

/// The multiplier source of one combine unit (`tc_mselect` / `tca_mselect`, spec 5.50).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MSelect {
    /// 0: zero.
    Zero,
    /// 1: `c_local` (for the alpha unit: the local alpha).
    CLocal,
    /// 2: `a_other`, the upstream alpha.
    AOther,
    /// 3: `a_local`, the local alpha.
    ALocal,
    /// 4: the detail factor computed from `tDetail` and the LOD.
    DetailFactor,
    /// 5: the fractional part of the LOD.
    LodFraction,
    /// 6, 7: reserved; MAME and DOSBox use zero.
    Reserved,
}

impl MSelect {
    /// Decodes a 3-bit `mselect` field.
    pub const fn from_bits(v: u32) -> Self {
        match v & 7 {
            0 => Self::Zero,
            1 => Self::CLocal,
            2 => Self::AOther,
            3 => Self::ALocal,
            4 => Self::DetailFactor,
            5 => Self::LodFraction,
            _ => Self::Reserved,
        }
    }
}

/// What is added after the multiply (`tc_add_clocal`, `tc_add_alocal`; `tca_add_*`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AddLocal {
    /// Nothing is added.
    None,
    /// `c_local` (its own channel).
    CLocal,
    /// `a_local`, the local alpha.
    ALocal,
}

/// The decoded controls of one combine unit (the RGB units or the alpha unit).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnitControl {
    /// `*_zero_other`: use zero instead of `c_other`.
    pub zero_other: bool,
    /// `*_sub_clocal`: subtract `c_local` before the multiply.
    pub sub_clocal: bool,
    /// `*_mselect`: multiplier source.
    pub mselect: MSelect,
    /// `*_reverse_blend`: use the factor as is (1) or its ones' complement (0).
    pub reverse_blend: bool,
    /// `*_add_clocal` / `*_add_alocal`.
    pub add: AddLocal,
    /// `*_invert_output`: ones' complement of the clamped result.
    pub invert_output: bool,
}

impl UnitControl {
    /// Whether the unit reads `c_other`: unless it zeroes it, and as the factor
    /// `a_other`.
    const fn reads_other(&self) -> bool {
        !self.zero_other || matches!(self.mselect, MSelect::AOther)
    }

    /// Combines the decoded `*_add_clocal` / `*_add_alocal` bits of one unit.
    ///
    /// For the RGB unit both add bits set add nothing (MAME and DOSBox treat the 2-bit field
    /// value 3 as reserved; 86Box adds `c_local`). For the alpha unit either bit adds the
    /// local alpha (MAME and DOSBox: any non-zero value).
    const fn add(add_clocal: bool, add_alocal: bool, alpha: bool) -> AddLocal {
        match (add_clocal, add_alocal) {
            (false, false) => AddLocal::None,
            _ if alpha => AddLocal::ALocal,
            (true, false) => AddLocal::CLocal,
            (false, true) => AddLocal::ALocal,
            (true, true) => AddLocal::None,
        }
    }

    /// The colour units' controls (`tc_*`, `textureMode` bits 20:12).
    const fn rgb(m: TextureMode) -> Self {
        Self {
            zero_other: m.tc_zero_other(),
            sub_clocal: m.tc_sub_clocal(),
            mselect: MSelect::from_bits(m.tc_mselect() as u32),
            reverse_blend: m.tc_reverse_blend(),
            add: Self::add(m.tc_add_clocal(), m.tc_add_alocal(), false),
            invert_output: m.tc_invert_output(),
        }
    }

    /// The alpha unit's controls (`tca_*`, `textureMode` bits 29:21).
    const fn alpha(m: TextureMode) -> Self {
        Self {
            zero_other: m.tca_zero_other(),
            sub_clocal: m.tca_sub_clocal(),
            mselect: MSelect::from_bits(m.tca_mselect() as u32),
            reverse_blend: m.tca_reverse_blend(),
            add: Self::add(m.tca_add_clocal(), m.tca_add_alocal(), true),
            invert_output: m.tca_invert_output(),
        }
    }
}

/// The texture combine configuration of one TMU, decoded from `textureMode`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[doc(alias = "textureMode")]
pub struct TextureCombine {
    /// The three colour units (`tc_*`, bits 20:12).
    pub rgb: UnitControl,
    /// The alpha unit (`tca_*`, bits 29:21).
    pub alpha: UnitControl,
    /// `trilinear` (bit 30): reverse the blend on odd LODs.
    pub trilinear: bool,
}

/// Per-pixel values the combine unit uses besides the two colours.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Factors {
    /// Detail factor (0.8), see [`detail_factor`].
    pub detail: u8,
    /// Fractional part of the LOD (0.8).
    pub lod_fraction: u8,
    /// The integer LOD is odd (only used when `trilinear` is set).
    pub odd_lod: bool,
}

impl TextureCombine {
    /// Decodes the combine fields of a `textureMode` value.
    pub const fn from_texture_mode(mode: u32) -> Self {
        let m = TextureMode(mode);
        Self {
            rgb: UnitControl::rgb(m),
            alpha: UnitControl::alpha(m),
            trilinear: m.trilinear(),
        }
    }

    /// Whether both units output this TMU's own texel unchanged, before `invert_output`:
    /// `zero_other` without `sub_clocal`, adding `c_local` (RGB) and `a_local` (alpha).
    /// The multiply then has nothing to scale, whatever `mselect` and `reverse_blend` say.
    ///
    /// MAME reduces such a mode to a plain texel fetch and so drops `invert_output`;
    /// 86Box fetches the texel alone for the same register pattern (its `TEXTUREMODE_LOCAL`).
    pub const fn is_local_identity(&self) -> bool {
        let rgb = &self.rgb;
        let alpha = &self.alpha;
        rgb.zero_other
            && !rgb.sub_clocal
            && matches!(rgb.add, AddLocal::CLocal)
            && alpha.zero_other
            && !alpha.sub_clocal
            && matches!(alpha.add, AddLocal::ALocal)
    }

    /// Whether either unit reads `c_other`, the upstream TMU's output: unless it zeroes
    /// it, and as the factor `a_other`.
    pub const fn reads_other(&self) -> bool {
        self.rgb.reads_other() || self.alpha.reads_other()
    }

    /// 86Box's combine for the upstream TMU of two (`voodoo_tmu_fetch_and_blend`, TMU 1):
    /// a unit runs only if its `sub_clocal` bit is set, as `(-c_local * factor) >> 8`
    /// plus the add (other taken as zero, `a_other` as a zero factor); otherwise the
    /// texel's channels pass unchanged. `invert_output` is never applied. The
    /// `reverse_blend` bits are `downstream`'s (TMU 0's: 86Box reads them through TMU 0's
    /// macros), and the alpha unit tests them the other way round from the colour unit.
    pub fn combine_box86_upstream(
        &self,
        local: [u8; 4],
        f: &Factors,
        downstream: &TextureCombine,
    ) -> [u8; 4] {
        let odd = self.trilinear && f.odd_lod;
        let mut out = local;
        for (ch, slot) in out.iter_mut().enumerate() {
            let alpha = ch == A;
            let u = if alpha { &self.alpha } else { &self.rgb };
            if !u.sub_clocal {
                continue;
            }
            let c_local = i32::from(local[ch]);
            let a_local = i32::from(local[A]);
            let factor = match u.mselect {
                MSelect::Zero | MSelect::Reserved | MSelect::AOther => 0,
                MSelect::CLocal if alpha => a_local,
                MSelect::CLocal => c_local,
                MSelect::ALocal => a_local,
                MSelect::DetailFactor => i32::from(f.detail),
                MSelect::LodFraction => i32::from(f.lod_fraction),
            };
            let plain = if alpha {
                downstream.alpha.reverse_blend == odd
            } else {
                downstream.rgb.reverse_blend != odd
            };
            let factor = if plain { factor } else { factor ^ 0xff };
            let mut v = (-c_local * (factor + 1)) >> 8;
            v += match (alpha, u.add) {
                (_, AddLocal::None) => 0,
                (true, _) | (false, AddLocal::ALocal) => a_local,
                (false, AddLocal::CLocal) => c_local,
            };
            *slot = v.clamp(0, 255) as u8;
        }
        out
    }

    /// Combines `local` (this TMU's texel) with `other` (the upstream TMU's output).
    pub fn combine(&self, local: [u8; 4], other: [u8; 4], f: &Factors) -> [u8; 4] {
        let odd = self.trilinear && f.odd_lod;
        let mut out = [0u8; 4];
        for (ch, slot) in out.iter_mut().enumerate() {
            let unit = if ch == A { &self.alpha } else { &self.rgb };
            *slot = channel(unit, ch, local, other, f, odd);
        }
        out
    }
}

/// One channel of the combine unit.
#[inline]
fn channel(
    u: &UnitControl,
    ch: usize,
    local: [u8; 4],
    other: [u8; 4],
    f: &Factors,
    odd: bool,
) -> u8 {
    let c_local = i32::from(local[ch]);
    let a_local = i32::from(local[A]);
    let mut blend = if u.zero_other {
        0
    } else {
        i32::from(other[ch])
    };
    if u.sub_clocal {
        blend -= c_local;
    }
    let factor = match u.mselect {
        MSelect::Zero | MSelect::Reserved => 0,
        MSelect::CLocal => c_local,
        MSelect::AOther => i32::from(other[A]),
        MSelect::ALocal => a_local,
        MSelect::DetailFactor => i32::from(f.detail),
        MSelect::LodFraction => i32::from(f.lod_fraction),
    };
    let factor = if u.reverse_blend != odd {
        factor
    } else {
        factor ^ 0xff
    };
    // Arithmetic shift: the product of a negative blend truncates towards -infinity,
    // as in MAME and DOSBox.
    let mut v = (blend * (factor + 1)) >> 8;
    v += match u.add {
        AddLocal::None => 0,
        AddLocal::CLocal => c_local,
        AddLocal::ALocal => a_local,
    };
    let v = v.clamp(0, 255) as u8;
    if u.invert_output {
        v ^ 0xff
    } else {
        v
    }
}

/// How the detail factor reads `tDetail`'s bias and the LOD (spec 5.52 leaves the units
/// of `detail_bias` unstated).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum DetailRule {
    /// DOSBox Staging (`TEXTURE_PIPELINE`): `detail_bias` (bits 13:8, 6-bit signed) in
    /// whole LODs against the 8.8 LOD; the shifted value clamps to `detail_max`.
    #[default]
    WholeLods,
    /// MAME (`rasterizer_texture::recompute`, `combine_texture`): as `WholeLods`, but the
    /// shifted value is cut to 8 bits (`u8`) before the clamp.
    WholeLodsCut8,
    /// 86Box (`voodoo_tmu_fetch_and_blend`): `detail_bias` unsigned, in whole LODs,
    /// against the integer LOD: `((bias - LOD) << scale)` clamped to `detail_max`.
    /// INACCURATE: 86Box multiplies by a negative factor when the LOD exceeds the bias;
    /// here that gives 0.
    IntegerLod,
}

/// The detail factor of spec 5.52 for a LOD in 8.8 fixed point (`tDetail` raw value).
///
/// `detail_factor = min(detail_max, ((detail_bias - LOD) << detail_scale))` in 0.8, zero when
/// `detail_bias <= LOD`. The spec writes `max`, but a clamp is meant (the field is called
/// "LOD clamp"). `detail_scale` (bits 16:14) is a left shift, `detail_max` (bits 7:0) 0.8;
/// [`DetailRule`] says what the bias and the LOD are.
#[doc(alias = "tDetail")]
#[inline]
pub fn detail_factor(t_detail: u32, lod: i32, rule: DetailRule) -> u8 {
    let d = TDetail(t_detail);
    let detail_max = d.detail_max() as i32;
    let signed = d.detail_bias();
    let scale = d.detail_scale();
    let (bias, lod) = match rule {
        DetailRule::WholeLods | DetailRule::WholeLodsCut8 => (signed << 8, lod),
        // The 6-bit field read unsigned: its two's complement bits.
        DetailRule::IntegerLod => (signed & 0x3f, lod >> 8),
    };
    if bias <= lod {
        return 0;
    }
    let v = match rule {
        DetailRule::WholeLods => ((bias - lod) << scale) >> 8,
        DetailRule::WholeLodsCut8 => (((bias - lod) << scale) >> 8) & 0xff,
        DetailRule::IntegerLod => (bias - lod) << scale,
    };
    v.min(detail_max) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    const LOCAL: [u8; 4] = [0x40, 0x80, 0xc0, 0x60];
    const OTHER: [u8; 4] = [0x20, 0xff, 0x10, 0xa0];
    const F0: Factors = Factors {
        detail: 0,
        lod_fraction: 0,
        odd_lod: false,
    };

    /// textureMode with the same 9-bit control value in the RGB and alpha fields.
    fn both(ctrl: u32) -> u32 {
        (ctrl << 12) | (ctrl << 21)
    }
    const ZERO_OTHER: u32 = 1;
    const SUB_CLOCAL: u32 = 2;
    const fn msel(m: u32) -> u32 {
        m << 2
    }
    const REVERSE: u32 = 0x20;
    const ADD_CLOCAL: u32 = 0x40;
    const ADD_ALOCAL: u32 = 0x80;
    const INVERT: u32 = 0x100;

    fn run(mode: u32, f: Factors) -> [u8; 4] {
        TextureCombine::from_texture_mode(mode).combine(LOCAL, OTHER, &f)
    }

    #[test]
    fn zero_is_pass_nothing() {
        // zero_other, mselect zero, no add: 0 * anything = 0
        assert_eq!(run(both(ZERO_OTHER), F0), [0, 0, 0, 0]);
    }

    #[test]
    fn other_passthrough() {
        // mselect zero, reverse 0 -> factor 0xff + 1 = 256: c_other unchanged
        assert_eq!(run(0, F0), OTHER);
    }

    #[test]
    fn local_passthrough_via_add() {
        // zero_other + add c_local (RGB) / add a_local (alpha)
        assert_eq!(run(both(ZERO_OTHER | ADD_CLOCAL), F0), LOCAL);
    }

    #[test]
    fn add_alocal_and_reserved_add() {
        // RGB add a_local: 0 + 0x60 each
        let m = ((ZERO_OTHER | ADD_ALOCAL) << 12) | ((ZERO_OTHER | ADD_CLOCAL) << 21);
        assert_eq!(run(m, F0), [0x60, 0x60, 0x60, 0x60]);
        // both RGB add bits: reserved, adds nothing; alpha with both bits adds a_local
        let m = both(ZERO_OTHER | ADD_CLOCAL | ADD_ALOCAL);
        assert_eq!(run(m, F0), [0, 0, 0, 0x60]);
    }

    #[test]
    fn subtract_local_and_clamp() {
        // (other - local) * 256 >> 8, clamped at zero
        assert_eq!(run(both(SUB_CLOCAL), F0), [0, 0x7f, 0, 0x40]);
    }

    #[test]
    fn mselect_local_modulate() {
        // reverse blend: other * (local + 1) >> 8 = modulate
        let m = both(msel(1) | REVERSE);
        assert_eq!(
            run(m, F0),
            [
                ((0x20 * 0x41) >> 8) as u8,
                ((0xff * 0x81) >> 8) as u8,
                ((0x10 * 0xc1) >> 8) as u8,
                ((0xa0 * 0x61) >> 8) as u8
            ]
        );
        // normal blend: other * ((local ^ 0xff) + 1) >> 8
        let m = both(msel(1));
        assert_eq!(
            run(m, F0),
            [
                ((0x20 * 0xc0) >> 8) as u8,
                ((0xff * 0x80) >> 8) as u8,
                ((0x10 * 0x40) >> 8) as u8,
                ((0xa0 * 0xa0) >> 8) as u8
            ]
        );
    }

    #[test]
    fn mselect_alphas() {
        // a_other (0xa0) and a_local (0x60) as factors, reversed
        let m = both(msel(2) | REVERSE);
        let e = |c: u32| ((c * 0xa1) >> 8) as u8;
        assert_eq!(run(m, F0), [e(0x20), e(0xff), e(0x10), e(0xa0)]);
        let m = both(msel(3) | REVERSE);
        let e = |c: u32| ((c * 0x61) >> 8) as u8;
        assert_eq!(run(m, F0), [e(0x20), e(0xff), e(0x10), e(0xa0)]);
    }

    #[test]
    fn mselect_detail_and_lod_fraction() {
        let f = Factors {
            detail: 0x40,
            lod_fraction: 0xc0,
            odd_lod: false,
        };
        let e = |c: u32, k: u32| ((c * (k + 1)) >> 8) as u8;
        let m = both(msel(4) | REVERSE);
        assert_eq!(
            run(m, f),
            [e(0x20, 0x40), e(0xff, 0x40), e(0x10, 0x40), e(0xa0, 0x40)]
        );
        let m = both(msel(5) | REVERSE);
        assert_eq!(
            run(m, f),
            [e(0x20, 0xc0), e(0xff, 0xc0), e(0x10, 0xc0), e(0xa0, 0xc0)]
        );
        // reserved selects are zero: with reverse, other * 1 >> 8 = 0
        assert_eq!(run(both(msel(6) | REVERSE), f), [0, 0, 0, 0]);
        assert_eq!(run(both(msel(7) | REVERSE), f), [0, 0, 0, 0]);
    }

    #[test]
    fn negative_blend_truncates_down() {
        // (other - local) with reverse lod-frac 0x7f: factor 0x80
        // R: (0x20 - 0x40) * 0x80 >> 8 = -16; plus add c_local 0x40 = 0x30
        let f = Factors {
            detail: 0,
            lod_fraction: 0x7f,
            odd_lod: false,
        };
        let m = both(SUB_CLOCAL | msel(5) | REVERSE | ADD_CLOCAL);
        // G: (0xff-0x80)*0x80>>8 = 0x3f + 0x80 = 0xbf; B: (0x10-0xc0)=-176*128>>8=-88+0xc0=0x68
        // A: (0xa0-0x60)=64*128>>8=32 + 0x60 = 0x80
        assert_eq!(run(m, f), [0x30, 0xbf, 0x68, 0x80]);
        // -1 * 1 >> 8 = -1 (floor), so 0 + ... check with odd product
        let local = [1, 0, 0, 0];
        let other = [0, 0, 0, 0];
        let tc = TextureCombine::from_texture_mode(both(SUB_CLOCAL | REVERSE | msel(0)));
        // factor 0 -> +1: -1 * 1 >> 8 = -1, clamps to 0
        assert_eq!(tc.combine(local, other, &F0), [0, 0, 0, 0]);
        let tc = TextureCombine::from_texture_mode(both(SUB_CLOCAL | REVERSE | ADD_CLOCAL));
        // -1 + 1 = 0 (a truncation towards zero would give 1)
        assert_eq!(tc.combine(local, other, &F0), [0, 0, 0, 0]);
    }

    #[test]
    fn invert_output() {
        assert_eq!(run(both(INVERT), F0), OTHER.map(|c| c ^ 0xff));
        // RGB invert only
        assert_eq!(run(INVERT << 12, F0), [0xdf, 0x00, 0xef, 0xa0]);
    }

    #[test]
    fn separate_rgb_and_alpha_fields() {
        // RGB: zero; alpha: pass other
        assert_eq!(run(ZERO_OTHER << 12, F0), [0, 0, 0, 0xa0]);
        // RGB: pass other; alpha: zero
        assert_eq!(run(ZERO_OTHER << 21, F0), [0x20, 0xff, 0x10, 0]);
    }

    #[test]
    fn trilinear_reverses_on_odd_lod_only() {
        // Blend other by LOD fraction 0x40, normal (non-reversed) blend: factor 0xbf + 1
        let base = both(msel(5));
        let even = Factors {
            detail: 0,
            lod_fraction: 0x40,
            odd_lod: false,
        };
        let odd = Factors {
            odd_lod: true,
            ..even
        };
        let e = |c: u32, k: u32| ((c * (k + 1)) >> 8) as u8;
        let normal = [e(0x20, 0xbf), e(0xff, 0xbf), e(0x10, 0xbf), e(0xa0, 0xbf)];
        let reversed = [e(0x20, 0x40), e(0xff, 0x40), e(0x10, 0x40), e(0xa0, 0x40)];
        assert_eq!(run(base, even), normal);
        // without the trilinear bit odd LODs change nothing
        assert_eq!(run(base, odd), normal);
        let tri = base | (1 << 30);
        assert_eq!(run(tri, even), normal);
        assert_eq!(run(tri, odd), reversed);
    }

    #[test]
    fn detail_factor_formula() {
        let detail_factor = |td, lod| detail_factor(td, lod, DetailRule::WholeLods);
        // max 0xff, bias 4, scale 0: (4.0 - 1.5) << 0 = 2.5 -> 0x280 >> 8 = 2
        let td = 0xff | (4 << 8);
        assert_eq!(detail_factor(td, 0x180), 2);
        // scale 6: 2.5 * 64 = 160
        assert_eq!(detail_factor(td | (6 << 14), 0x180), 160);
        // clamped by detail_max
        assert_eq!(detail_factor(0x80 | (4 << 8) | (6 << 14), 0x180), 0x80);
        // bias <= LOD: zero
        assert_eq!(detail_factor(td | (6 << 14), 0x400), 0);
        assert_eq!(detail_factor(td | (6 << 14), 0x500), 0);
        // negative bias (-1 = 0x3f)
        assert_eq!(detail_factor(0xff | (0x3f << 8) | (7 << 14), -0x200), 0x80);
        // large value beyond 8 bits is clamped, not wrapped (DOSBox behaviour)
        assert_eq!(detail_factor(0xff | (31 << 8) | (7 << 14), 0), 0xff);
    }

    #[test]
    fn box86_upstream_combine() {
        let f = F0;
        let local = [0x40, 0x80, 0xc0, 0x60];
        let plain = TextureCombine::from_texture_mode(0);
        // Without sub_clocal a unit passes the texel, whatever else it says (here zero
        // other, add a_local, invert).
        let tmu1 = TextureCombine::from_texture_mode(both(ZERO_OTHER | ADD_ALOCAL | INVERT));
        assert_eq!(tmu1.combine_box86_upstream(local, &f, &plain), local);
        // sub_clocal, factor a_local (0x60), add c_local; TMU 0 without reverse_blend:
        // colour complements the factor, alpha (tested the other way) does not.
        let mode = both(SUB_CLOCAL | msel(3) | ADD_CLOCAL);
        let tmu1 = TextureCombine::from_texture_mode(mode);
        let e = |c: i32, k: i32| (((-c * (k + 1)) >> 8) + c) as u8;
        assert_eq!(
            tmu1.combine_box86_upstream(local, &f, &plain),
            [e(0x40, 0x9f), e(0x80, 0x9f), e(0xc0, 0x9f), e(0x60, 0x60)]
        );
        // TMU 0 with both reverse_blend bits set swaps them.
        let reversed = TextureCombine::from_texture_mode(both(REVERSE));
        assert_eq!(
            tmu1.combine_box86_upstream(local, &f, &reversed),
            [e(0x40, 0x60), e(0x80, 0x60), e(0xc0, 0x60), e(0x60, 0x9f)]
        );
    }

    #[test]
    fn detail_factor_rules() {
        // bias 8, scale 6, max 0xc0 (tmu2_detail's tDetail 0x188c0) at LOD 1.5.
        let td = 0xc0 | (8 << 8) | (6 << 14);
        // Whole LODs: (8.0 - 1.5) * 64 = 416, clamped to 0xc0.
        assert_eq!(detail_factor(td, 0x180, DetailRule::WholeLods), 0xc0);
        // MAME's cut to 8 bits: 416 & 0xff = 160, under the clamp.
        assert_eq!(detail_factor(td, 0x180, DetailRule::WholeLodsCut8), 160);
        // Both zero from LOD 8.0 up.
        assert_eq!(detail_factor(td, 0x800, DetailRule::WholeLodsCut8), 0);
        assert_eq!(detail_factor(td, 0x800, DetailRule::WholeLods), 0);
        // Integer LOD: (8 - 1) << 6 = 448, clamped to 0xc0; at LOD 7.9, (8 - 7) << 6 = 64.
        assert_eq!(detail_factor(td, 0x180, DetailRule::IntegerLod), 0xc0);
        assert_eq!(detail_factor(td, 0x7e6, DetailRule::IntegerLod), 64);
        // Bias 31, scale 7, LOD 0: (31 << 8 << 7) >> 8 = 3968, cut to 0x80 by MAME, clamped
        // to 0xff by DOSBox Staging.
        let big = 0xff | (31 << 8) | (7 << 14);
        assert_eq!(detail_factor(big, 0, DetailRule::WholeLodsCut8), 0x80);
        assert_eq!(detail_factor(big, 0, DetailRule::WholeLods), 0xff);
    }

    #[test]
    fn local_identity_detection() {
        let decal = both(ZERO_OTHER | ADD_CLOCAL);
        assert!(TextureCombine::from_texture_mode(decal).is_local_identity());
        // mselect, reverse and invert do not matter; alpha may use either add bit
        let m = both(ZERO_OTHER | ADD_CLOCAL | msel(3) | REVERSE | INVERT);
        assert!(TextureCombine::from_texture_mode(m).is_local_identity());
        let m = (ZERO_OTHER | ADD_CLOCAL) << 12 | (ZERO_OTHER | ADD_ALOCAL) << 21;
        assert!(TextureCombine::from_texture_mode(m).is_local_identity());
        // the other colour, a subtraction, a missing add or RGB adding a_local break it
        for m in [
            both(ADD_CLOCAL),
            both(ZERO_OTHER | SUB_CLOCAL | ADD_CLOCAL),
            (ZERO_OTHER | ADD_CLOCAL) << 12 | ZERO_OTHER << 21,
            (ZERO_OTHER | ADD_ALOCAL) << 12 | (ZERO_OTHER | ADD_CLOCAL) << 21,
        ] {
            assert!(
                !TextureCombine::from_texture_mode(m).is_local_identity(),
                "{m:#x}"
            );
        }
    }
}

//! The colour and alpha combine units with their input selection, chroma key and alpha
//! mask (spec 5.16 `fbzColorPath`, 5.27 `chromaKey`, 5.19 `fbzMode` bits 1 and 13).
//!
//! ```text
//!  c_other = rgbselect(iterated | texture | color1)      a_other = aselect(...)
//!  c_local = localselect(iterated | color0)              a_local = cca_localselect(...)
//!  out = clamp(((zero_other ? 0 : other) - (sub_clocal ? local : 0)) * (factor + 1) >> 8
//!              + add) ^ (invert ? 0xff : 0)
//!  factor = mselect(0 | c_local | a_other | a_local | texture alpha) ^ (reverse ? 0 : 0xff)
//! ```
//! Source: spec 5.16 block diagrams; arithmetic (9-bit signed difference times
//! `factor + 1`, shift by 8, clamp to 0..=255) from MAME and DOSBox Staging, which agree.

use sst1_regs::{
    AlphaLocalSelect, AlphaMode, AlphaSelect, CcMselect, FbzColorPath, FbzMode, RgbSelect, Rgba,
};

/// The candidate inputs of the combine units for one pixel.
#[derive(Clone, Copy, Debug, Default)]
pub struct Inputs {
    /// Clamped iterated ARGB.
    pub iterated: Rgba,
    /// The TMU chain's output (zero when texturing is off).
    pub texel: Rgba,
    /// `color0` register.
    pub color0: Rgba,
    /// `color1` register.
    pub color1: Rgba,
    /// The clamped iterated Z as an alpha source (`cca_localselect` = iterated Z).
    pub z_alpha: u8,
}

/// `c_other` / `a_other` (spec 5.16 bits 1:0 and 3:2). Reserved selections give zero.
#[inline(always)]
pub fn select_other(cp: FbzColorPath, i: &Inputs) -> Rgba {
    let rgb = match cp.cc_rgbselect() {
        RgbSelect::IteratedRgb => i.iterated,
        RgbSelect::Texture => i.texel,
        RgbSelect::Color1 => i.color1,
        _ => Rgba::default(),
    };
    let a = match cp.cc_aselect() {
        AlphaSelect::IteratedAlpha => i.iterated.a,
        AlphaSelect::Texture => i.texel.a,
        AlphaSelect::Color1 => i.color1.a,
        _ => 0,
    };
    Rgba { a, ..rgb }
}

/// Whether the combine units take anything from the texel besides the local-select
/// override: as `c_other` or `a_other` (not zeroed), or as a blend factor (texture alpha,
/// or `a_other` when that is the texture's).
pub fn texel_feeds_equation(cp: FbzColorPath) -> bool {
    let other_rgb = cp.cc_rgbselect() == RgbSelect::Texture;
    let other_alpha = cp.cc_aselect() == AlphaSelect::Texture;
    (other_rgb && !cp.cc_zero_other())
        || (other_alpha && !cp.cca_zero_other())
        || cp.cc_mselect() == CcMselect::TextureAlpha
        || (cp.cc_mselect() == CcMselect::AOther && other_alpha)
        || cp.cca_mselect() == CcMselect::TextureAlpha
        || (cp.cca_mselect() == CcMselect::AOther && other_alpha)
}

/// Whether anything a pixel computes reads the texel in this state: chroma key on
/// `c_other`, the alpha mask and (unless the combined alpha is tested) the alpha test on
/// `a_other`; the colour combine unit (`c_other` and `a_other` unless zeroed, `a_other`
/// or texture alpha as a factor, the local-select override's texture alpha bit 7) where
/// RGB is written (`rgb_written`); the alpha unit (`a_other` unless zeroed or as a
/// factor, texture alpha as a factor) where its output is used: RGB written (the blend
/// factors), alpha planes written (`alpha_written`), or the combined alpha tested. (Fog
/// and the alpha blend pass alpha on without reading RGB: the alpha channel blends with
/// `AZERO` or `AONE` alone.)
///
/// Where it is `false`, the texel changes neither a pixel's value nor whether it is
/// written, and a chunk need not sample it (the span kernels' shortcut; the reference
/// path samples every textured pixel).
pub fn texel_read(
    cp: FbzColorPath,
    mode: FbzMode,
    alpha_mode: AlphaMode,
    alpha_test_on_combined: bool,
    rgb_written: bool,
    alpha_written: bool,
) -> bool {
    let rgb_texel = cp.cc_rgbselect() == RgbSelect::Texture;
    let alpha_texel = cp.cc_aselect() == AlphaSelect::Texture;
    let alpha_test = alpha_mode.alpha_test_enable();
    let tests = (rgb_texel && mode.enable_chromakey())
        || (alpha_texel && (mode.enable_alpha_mask() || (alpha_test && !alpha_test_on_combined)));
    let rgb_unit = (rgb_texel && !cp.cc_zero_other())
        || (alpha_texel && cp.cc_mselect() == CcMselect::AOther)
        || cp.cc_mselect() == CcMselect::TextureAlpha
        || cp.cc_localselect_override();
    let alpha_unit = (alpha_texel
        && (!cp.cca_zero_other() || cp.cca_mselect() == CcMselect::AOther))
        || cp.cca_mselect() == CcMselect::TextureAlpha;
    let alpha_used = rgb_written || alpha_written || (alpha_test && alpha_test_on_combined);
    tests || (rgb_written && rgb_unit) || (alpha_used && alpha_unit)
}

/// `c_local` / `a_local` (spec 5.16 bits 4, 6:5, 7).
#[inline(always)]
pub fn select_local(cp: FbzColorPath, i: &Inputs) -> Rgba {
    // localselect_override: texture alpha bit 7 chooses color0 instead of iterated.
    let use_color0 = if cp.cc_localselect_override() {
        i.texel.a & 0x80 != 0
    } else {
        cp.cc_localselect()
    };
    let rgb = if use_color0 { i.color0 } else { i.iterated };
    let a = match cp.cca_localselect() {
        AlphaLocalSelect::IteratedAlpha => i.iterated.a,
        AlphaLocalSelect::Color0 => i.color0.a,
        AlphaLocalSelect::IteratedZ => i.z_alpha,
        // UNVERIFIED: reserved on the SST-1 (iterated W on Voodoo 2); zero here.
        _ => 0,
    };
    Rgba { a, ..rgb }
}

/// Chroma-key test on the selected `c_other` (spec 5.27): `true` if the pixel is killed.
#[inline(always)]
pub fn chroma_killed(other: Rgba, chroma_key: u32) -> bool {
    (other.to_argb() ^ chroma_key) & 0x00ff_ffff == 0
}

/// The colour and alpha combine arithmetic. Returns the combined ARGB, each 0..=255.
#[inline(always)]
pub fn combine(cp: FbzColorPath, other: Rgba, local: Rgba, texel_alpha: u8) -> Rgba {
    let o = [other.r as i32, other.g as i32, other.b as i32];
    let l = [local.r as i32, local.g as i32, local.b as i32];

    // --- colour ---
    let factor: [i32; 3] = match cp.cc_mselect() {
        CcMselect::Zero => [0; 3],
        CcMselect::CLocal => l,
        CcMselect::AOther => [other.a as i32; 3],
        CcMselect::ALocal => [local.a as i32; 3],
        CcMselect::TextureAlpha => [texel_alpha as i32; 3],
        _ => [0; 3],
    };
    let mut rgb = [0i32; 3];
    for c in 0..3 {
        let mut v = if cp.cc_zero_other() { 0 } else { o[c] };
        if cp.cc_sub_clocal() {
            v -= l[c];
        }
        let f = if cp.cc_reverse_blend() {
            factor[c]
        } else {
            factor[c] ^ 0xff
        };
        v = (v * (f + 1)) >> 8;
        // Bits 15:14 as one field: 1 adds c_local, 2 adds a_local, 3 is reserved (adds
        // nothing). Source: DOSBox Staging and MAME treat it as a 2-bit field.
        v += match (cp.cc_add_clocal(), cp.cc_add_alocal()) {
            (true, false) => l[c],
            (false, true) => local.a as i32,
            _ => 0,
        };
        let v = v.clamp(0, 255);
        rgb[c] = if cp.cc_invert_output() { v ^ 0xff } else { v };
    }

    // --- alpha ---
    let factor = match cp.cca_mselect() {
        // In the alpha unit both 1 and 3 select a_local (spec 5.16).
        CcMselect::Zero => 0,
        CcMselect::CLocal | CcMselect::ALocal => local.a as i32,
        CcMselect::AOther => other.a as i32,
        CcMselect::TextureAlpha => texel_alpha as i32,
        _ => 0,
    };
    let mut a = if cp.cca_zero_other() {
        0
    } else {
        other.a as i32
    };
    if cp.cca_sub_clocal() {
        a -= local.a as i32;
    }
    let f = if cp.cca_reverse_blend() {
        factor
    } else {
        factor ^ 0xff
    };
    a = (a * (f + 1)) >> 8;
    // cca_add_clocal and cca_add_alocal both add a_local (spec 5.16 bits 23-24).
    if cp.cca_add_clocal() || cp.cca_add_alocal() {
        a += local.a as i32;
    }
    let a = a.clamp(0, 255);
    let a = if cp.cca_invert_output() { a ^ 0xff } else { a };

    Rgba {
        r: rgb[0] as u8,
        g: rgb[1] as u8,
        b: rgb[2] as u8,
        a: a as u8,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const RED: Rgba = Rgba {
        r: 200,
        g: 100,
        b: 50,
        a: 128,
    };
    const LOCAL: Rgba = Rgba {
        r: 10,
        g: 20,
        b: 30,
        a: 64,
    };

    #[test]
    fn texel_read_follows_each_reader() {
        let (mode, am) = (FbzMode(0), AlphaMode(0));
        let read = |cp: u32, mode: FbzMode, am: AlphaMode| {
            texel_read(FbzColorPath(cp), mode, am, false, true, false)
        };
        // rgbselect = texture (1), the other passed through: read.
        assert!(read(1, mode, am));
        // ... zeroed (bit 8): not read, unless the chroma key compares it (fbzMode bit 1).
        assert!(!read(1 | 1 << 8 | 1 << 17, mode, am));
        assert!(read(1 | 1 << 8 | 1 << 17, FbzMode(1 << 1), am));
        // aselect = texture (1 << 2), both units' other zeroed: read only by the alpha
        // mask (fbzMode bit 13), the alpha test of a_other, or a_other as a factor.
        let zeroed = 1 << 2 | 1 << 8 | 1 << 17;
        assert!(!read(zeroed, mode, am));
        assert!(read(zeroed, FbzMode(1 << 13), am));
        assert!(read(zeroed, mode, AlphaMode(1)));
        assert!(!texel_read(
            FbzColorPath(zeroed),
            mode,
            AlphaMode(1),
            true,
            true,
            false
        ));
        assert!(read(zeroed | 2 << 10, mode, am));
        assert!(read(zeroed | 2 << 19, mode, am));
        // Iterated colour, other zeroed: read only through texture alpha (as a factor of
        // either unit, or by the local-select override).
        let iterated = 1 << 8 | 1 << 17;
        assert!(!read(iterated, mode, am));
        assert!(read(iterated | 4 << 10, mode, am));
        assert!(read(iterated | 4 << 19, mode, am));
        assert!(read(iterated | 1 << 7, mode, am));
        // Nothing written: only the tests read it; the alpha unit's output also where
        // alpha planes are written or the combined alpha is tested.
        let modulate = 1 | 1 << 2 | 4 << 10 | 4 << 19;
        assert!(!texel_read(
            FbzColorPath(modulate),
            mode,
            am,
            false,
            false,
            false
        ));
        assert!(texel_read(
            FbzColorPath(modulate),
            mode,
            am,
            false,
            false,
            true
        ));
        assert!(texel_read(
            FbzColorPath(modulate),
            mode,
            AlphaMode(1),
            true,
            false,
            false
        ));
        assert!(texel_read(
            FbzColorPath(modulate),
            FbzMode(1 << 1),
            am,
            false,
            false,
            false
        ));
        // RGB alone written: the alpha unit's output still sets the blend factors.
        let alpha_only = 1 << 2 | 1 << 8;
        assert!(texel_read(
            FbzColorPath(alpha_only),
            mode,
            am,
            false,
            true,
            false
        ));
    }

    #[test]
    fn pass_through_other() {
        // mselect zero, not reversed: factor = 0xff -> (v * 256) >> 8 = v.
        let out = combine(FbzColorPath(0), RED, LOCAL, 0);
        assert_eq!(out, RED);
    }

    #[test]
    fn modulate_by_local_with_add_and_invert() {
        // cc_mselect = c_local (1 << 10), reverse blend (bit 13): other * (local + 1) >> 8
        let cp = FbzColorPath(1 << 10 | 1 << 13);
        let out = combine(cp, RED, LOCAL, 0);
        assert_eq!(
            (out.r, out.g, out.b),
            (
                ((200 * 11) >> 8) as u8,
                ((100 * 21) >> 8) as u8,
                ((50 * 31) >> 8) as u8
            )
        );
        // sub c_local then add c_local, invert
        let cp = FbzColorPath(1 << 9 | 1 << 14 | 1 << 16);
        let out = combine(cp, RED, LOCAL, 0);
        assert_eq!((out.r, out.g, out.b), (200 ^ 0xff, 100 ^ 0xff, 50 ^ 0xff));
    }

    #[test]
    fn negative_results_clamp_to_zero() {
        // zero_other, sub_clocal: -local, factor 0xff -> clamps to 0.
        let cp = FbzColorPath(1 << 8 | 1 << 9 | 1 << 17 | 1 << 18);
        assert_eq!(
            combine(cp, RED, LOCAL, 0),
            Rgba {
                r: 0,
                g: 0,
                b: 0,
                a: 0
            }
        );
    }

    #[test]
    fn chroma_ignores_alpha() {
        assert!(chroma_killed(
            Rgba {
                r: 1,
                g: 2,
                b: 3,
                a: 9
            },
            0xff01_0203
        ));
        assert!(!chroma_killed(
            Rgba {
                r: 1,
                g: 2,
                b: 4,
                a: 9
            },
            0x0001_0203
        ));
    }

    #[test]
    fn local_override_uses_texture_alpha_bit7() {
        let i = Inputs {
            iterated: RED,
            color0: LOCAL,
            texel: Rgba {
                a: 0x80,
                ..Default::default()
            },
            ..Default::default()
        };
        let cp = FbzColorPath(1 << 7);
        assert_eq!(select_local(cp, &i).r, LOCAL.r);
        let i = Inputs {
            texel: Rgba::default(),
            ..i
        };
        assert_eq!(select_local(cp, &i).r, RED.r);
    }
}

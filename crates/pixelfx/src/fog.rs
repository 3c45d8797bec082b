//! The fog unit (spec 5.17 `fogMode`, 5.25 `fogColor`, 5.36 `fogTable`, and the fog
//! block diagram of 5.17).
//!
//! The unit blends the colour-combine output `Cin` with `fogColor` by a fog alpha `Afog`:
//!
//! ```text
//! fogconstant (bit 5):  Cout = Cin + fogColor            (fogmult = 0)
//!                       Cout = fogColor                  (fogmult = 1)
//! otherwise:            F    = (fogadd ? 0 : fogColor) - (fogmult ? 0 : Cin)   9-bit signed
//!                       Cout = (fogmult ? 0 : Cin) + (F * (Afog + 1)) >> 8
//! Afog (bits 4:3):      0 table[wfloat], 1 iterated alpha, 2 iterated Z[27:20],
//!                       3 see FogBothSources
//! ```
//! and clamps each channel to 0..=255. Alpha passes through unchanged.
//!
//! Source: spec 5.17 (equations, diagram: 2's complement of Cin, "9 signed x 8 unsigned"
//! multiply, clamp); the `+ 1` and the `>> 8` from MAME `apply_fogging`, DOSBox Staging
//! `APPLY_FOGGING` and 86Box `APPLY_FOG`, which agree on them. Where they disagree,
//! [`FogProfile`] has a switch. The Voodoo 2 bits 7:6 (fog zones, fog dither) do not
//! exist on the SST-1 and are ignored.

use serde::{Deserialize, Serialize};
use sst1_fog::FogTable;
use sst1_regs::{FogMode, FogZa, Rgba};

/// What happens to the scaled fog difference `(F * (Afog + 1)) >> 8` before it is added
/// back to the colour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum FogDifference {
    /// It stays signed, so fog darker than the pixel darkens it (DOSBox Staging, 86Box;
    /// the spec's diagram shows a signed 9-bit operand).
    #[default]
    Signed,
    /// It is clamped to 0..=255 first, so fog darker than the pixel has no effect (MAME:
    /// `scale_imm_and_clamp` before the add).
    ClampedToByte,
}

/// The fog alpha for fog from iterated alpha (`fogMode` bits 4:3 = 1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum FogIteratedAlpha {
    /// The iterated alpha's integer part after the pseudo-clamp, as the colour path uses
    /// it (DOSBox Staging; 86Box clamps to 0..=255, which agrees for in-range values).
    #[default]
    Clamped,
    /// Always 0, so the blend factor is 1/256 (MAME: it reads the low byte of its alpha
    /// iterator, which it keeps shifted left by 8 bits, so that byte is always 0; the
    /// MAME golden of `fog_alpha_z_const` indeed shows no fog in that region).
    MameLowByte,
}

/// Constant fog (`fogMode` bit 5) with `fogmult` (bit 2) set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum FogConstantMult {
    /// The output is `fogColor` alone (MAME, DOSBox Staging; the spec's table gives
    /// `Cout = Afog * Cfog` for fogmult = 1).
    #[default]
    FogColor,
    /// `fogColor` is added to the colour whatever `fogmult` says (86Box).
    AddToColor,
}

/// The depth that indexes the fog table.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum FogTableDepth {
    /// `wfloat` as computed from W (DOSBox Staging, 86Box).
    #[default]
    Wfloat,
    /// `wfloat` plus the depth bias (`zaColor[15:0]`, clamped to 0..=0xffff) when
    /// `fbzMode` bit 16 enables biasing (MAME).
    BiasedWfloat,
}

/// The fog alpha when `fogMode` bits 4:3 are both set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum FogBothSources {
    /// Iterated W's integer part (bits 39:32 of 32.32 W) after the pseudo-clamp: the
    /// Voodoo 2 meaning, which MAME, DOSBox Staging and 86Box all apply to the SST-1 too.
    /// The pass rule requires matching their consensus.
    #[default]
    IteratedW,
    /// Iterated Z: spec 5.17 says bit 4 (`fogz`) takes precedence over bit 3.
    IteratedZ,
}

/// The fog unit's disputed behaviours. `Default` follows two of the three references
/// (or all three, against the spec, for [`FogBothSources`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(default)]
pub struct FogProfile {
    pub difference: FogDifference,
    pub iterated_alpha: FogIteratedAlpha,
    pub constant_mult: FogConstantMult,
    pub table_depth: FogTableDepth,
    pub both_sources: FogBothSources,
}

impl FogProfile {
    /// The hardware model's fog unit (each switch's `#[default]` variant).
    pub const HARDWARE: FogProfile = FogProfile {
        difference: FogDifference::Signed,
        iterated_alpha: FogIteratedAlpha::Clamped,
        constant_mult: FogConstantMult::FogColor,
        table_depth: FogTableDepth::Wfloat,
        both_sources: FogBothSources::IteratedW,
    };
}

impl Default for FogProfile {
    fn default() -> Self {
        Self::HARDWARE
    }
}

/// The per-pixel inputs of the fog unit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FogInput {
    /// The colour-combine output `Cin`; its alpha passes through.
    pub color: Rgba,
    /// Iterated alpha, integer part after the pseudo-clamp (the colour path's value).
    pub alpha: u8,
    /// Iterated Z, 16-bit integer part after the pseudo-clamp (Z bits 27:20 are its
    /// high byte).
    pub z: u16,
    /// Iterated W, raw 32.32 (only for `fogMode` bits 4:3 = 3).
    pub w: i64,
    /// The 16-bit floating-point depth from W (spec 5.19) that indexes the fog table.
    pub wfloat: u16,
    /// `zaColor[15:0]` when `fbzMode` bit 16 enables depth biasing, else `None`. Only
    /// [`FogTableDepth::BiasedWfloat`] uses it.
    pub depth_bias: Option<i16>,
}

/// Iterated W's integer byte with the SST-1 pseudo-clamp (no RGBZW clamp bit): the
/// 16-bit integer part wraps to its low byte, except 0xffff (-1) reads 0 and 0x100
/// reads 0xff. Source: MAME `clamped_w`, DOSBox Staging `CLAMPED_W` (non-clamp branch).
/// 86Box takes the low byte without the two exceptions.
#[inline(always)]
fn pseudo_clamped_w(w: i64) -> i32 {
    match (w >> 32) & 0xffff {
        0xffff => 0,
        0x100 => 0xff,
        v => (v & 0xff) as i32,
    }
}

/// The fog alpha `Afog` (0..=318; above 255 only with an out-of-spec fog table).
#[inline(always)]
fn fog_alpha(mode: FogMode, table: &FogTable, input: &FogInput, profile: FogProfile) -> i32 {
    match mode.fog_za() {
        FogZa::FogTable => {
            let depth = match (profile.table_depth, input.depth_bias) {
                (FogTableDepth::BiasedWfloat, Some(bias)) => {
                    (input.wfloat as i32 + bias as i32).clamp(0, 0xffff) as u16
                }
                _ => input.wfloat,
            };
            table.blend(depth) as i32
        }
        FogZa::IteratedAlpha => match profile.iterated_alpha {
            FogIteratedAlpha::Clamped => input.alpha as i32,
            FogIteratedAlpha::MameLowByte => 0,
        },
        // Z[27:20] is the high byte of the 16-bit integer part.
        // Source: spec 5.17; MAME, DOSBox Staging (86Box skips the pseudo-clamp).
        FogZa::IteratedZ => (input.z >> 8) as i32,
        FogZa::IteratedZAndAlpha => match profile.both_sources {
            FogBothSources::IteratedW => pseudo_clamped_w(input.w),
            FogBothSources::IteratedZ => (input.z >> 8) as i32,
        },
    }
}

/// Applies `fogMode` to one pixel. With fog disabled (bit 0 clear) the colour is
/// returned unchanged. `fog_color` is the `fogColor` register (its alpha is unused).
#[inline(always)]
pub fn apply_fog(
    mode: FogMode,
    fog_color: Rgba,
    table: &FogTable,
    input: &FogInput,
    profile: FogProfile,
) -> Rgba {
    let c = input.color;
    if !mode.enable_fog() {
        return c;
    }
    let cin = [c.r as i32, c.g as i32, c.b as i32];
    let fog = [fog_color.r as i32, fog_color.g as i32, fog_color.b as i32];
    let add_back = !mode.fog_mult();

    let out: [i32; 3] = if mode.fog_constant() {
        // Constant fog bypasses the multiplier (spec 5.17: bit 5 overrides bits 4:3).
        let add = add_back || profile.constant_mult == FogConstantMult::AddToColor;
        per_channel(|i| if add { cin[i] + fog[i] } else { fog[i] })
    } else {
        let factor = fog_alpha(mode, table, input, profile) + 1;
        per_channel(|i| {
            let f = if mode.fog_add() { 0 } else { fog[i] };
            let f = if add_back { f - cin[i] } else { f };
            // Arithmetic shift: floor, as in all three references.
            let scaled = (f * factor) >> 8;
            let scaled = match profile.difference {
                FogDifference::Signed => scaled,
                FogDifference::ClampedToByte => scaled.clamp(0, 255),
            };
            if add_back {
                cin[i] + scaled
            } else {
                scaled
            }
        })
    };
    Rgba {
        r: out[0].clamp(0, 255) as u8,
        g: out[1].clamp(0, 255) as u8,
        b: out[2].clamp(0, 255) as u8,
        a: c.a,
    }
}

/// [`apply_fog`]'s per-pixel inputs for every lane of a chunk of a span ([`crate::span`]).
pub struct FogLanes<'a, const L: usize> {
    /// The colour-combine output, R, G, B, A.
    pub color: &'a [[i32; L]; 4],
    /// The clamped iterated alpha.
    pub alpha: &'a [i32; L],
    /// The clamped 16-bit iterated Z.
    pub z: &'a [i32; L],
    /// The iterated W of lane `i`.
    pub w: &'a dyn Fn(usize) -> i64,
    /// The 16-bit floating-point W.
    pub wfloat: &'a [i32; L],
    /// The depth bias (`zaColor`), when enabled.
    pub depth_bias: Option<i16>,
}

/// [`apply_fog`] (with fog enabled) for every lane at once: the same arithmetic, its
/// choices made once, into `out` (R, G, B, A).
#[inline(always)]
pub fn apply_fog_lanes<const L: usize>(
    mode: FogMode,
    fog_color: Rgba,
    table: &FogTable,
    input: &FogLanes<'_, L>,
    profile: FogProfile,
    out: &mut [[i32; L]; 4],
) {
    use crate::span::lanes;
    let cin = input.color;
    let fog = [fog_color.r as i32, fog_color.g as i32, fog_color.b as i32];
    let add_back = !mode.fog_mult();
    out[3] = cin[3];
    if mode.fog_constant() {
        // Constant fog bypasses the multiplier (spec 5.17: bit 5 overrides bits 4:3).
        let add = add_back || profile.constant_mult == FogConstantMult::AddToColor;
        for c in 0..3 {
            let (f, base) = (fog[c], &cin[c]);
            out[c] = if add {
                lanes(|i| (base[i] + f).clamp(0, 255))
            } else {
                [f.clamp(0, 255); L]
            };
        }
        return;
    }
    // Afog + 1 per lane (see `fog_alpha`).
    let factor: [i32; L] = match mode.fog_za() {
        FogZa::FogTable => {
            let biased = profile.table_depth == FogTableDepth::BiasedWfloat;
            lanes(|i| {
                let depth = match (biased, input.depth_bias) {
                    (true, Some(bias)) => (input.wfloat[i] + bias as i32).clamp(0, 0xffff) as u16,
                    _ => input.wfloat[i] as u16,
                };
                table.blend(depth) as i32 + 1
            })
        }
        FogZa::IteratedAlpha => match profile.iterated_alpha {
            FogIteratedAlpha::Clamped => lanes(|i| input.alpha[i] + 1),
            FogIteratedAlpha::MameLowByte => [1; L],
        },
        FogZa::IteratedZ => lanes(|i| (input.z[i] >> 8) + 1),
        FogZa::IteratedZAndAlpha => match profile.both_sources {
            FogBothSources::IteratedW => lanes(|i| pseudo_clamped_w((input.w)(i)) + 1),
            FogBothSources::IteratedZ => lanes(|i| (input.z[i] >> 8) + 1),
        },
    };
    let clamp_difference = profile.difference == FogDifference::ClampedToByte;
    for c in 0..3 {
        let fc = if mode.fog_add() { 0 } else { fog[c] };
        let base = &cin[c];
        out[c] = lanes(|i| {
            let f = if add_back { fc - base[i] } else { fc };
            // Arithmetic shift: floor, as in all three references.
            let scaled = (f * factor[i]) >> 8;
            let scaled = if clamp_difference {
                scaled.clamp(0, 255)
            } else {
                scaled
            };
            let v = if add_back { base[i] + scaled } else { scaled };
            v.clamp(0, 255)
        });
    }
}

/// `[f(0), f(1), f(2)]`: one value per colour channel, written out so that the compiler
/// inlines the channel arithmetic instead of calling it three times.
#[inline(always)]
fn per_channel(mut f: impl FnMut(usize) -> i32) -> [i32; 3] {
    [f(0), f(1), f(2)]
}

#[cfg(test)]
mod tests {
    use super::*;

    const FOG: Rgba = Rgba {
        r: 240,
        g: 120,
        b: 40,
        a: 0x99,
    };
    const CIN: Rgba = Rgba {
        r: 40,
        g: 100,
        b: 230,
        a: 0x5a,
    };

    fn input() -> FogInput {
        FogInput {
            color: CIN,
            alpha: 241,
            z: 0x80ff,
            w: 0,
            wfloat: 0,
            depth_bias: None,
        }
    }

    fn rgb(c: Rgba) -> [u8; 3] {
        [c.r, c.g, c.b]
    }

    fn run(mode: u32, input: &FogInput, table: &FogTable, profile: FogProfile) -> Rgba {
        apply_fog(FogMode(mode), FOG, table, input, profile)
    }

    #[test]
    fn disabled_is_identity() {
        let t = FogTable::new();
        assert_eq!(run(0x3e, &input(), &t, FogProfile::default()), CIN);
    }

    #[test]
    fn iterated_alpha_blend() {
        // fogMode 0x09: fog from iterated alpha, Cout = Cin + ((fog - Cin) * 242) >> 8.
        // r: 40 + (200 * 242 >> 8 = 189) = 229; g: 100 + (20 * 242 >> 8 = 18) = 118;
        // b: 230 + (-190 * 242 >> 8 = -180, floor) = 50.
        // These are the values DOSBox Staging and 86Box draw for fog_alpha_z_const.
        let t = FogTable::new();
        let out = run(0x09, &input(), &t, FogProfile::default());
        assert_eq!(
            out,
            Rgba {
                r: 229,
                g: 118,
                b: 50,
                a: CIN.a
            }
        );
    }

    #[test]
    fn difference_switch() {
        let t = FogTable::new();
        let p = FogProfile {
            difference: FogDifference::ClampedToByte,
            ..Default::default()
        };
        // MAME: the negative blue difference is dropped, blue stays 230.
        assert_eq!(rgb(run(0x09, &input(), &t, p)), [229, 118, 230]);
    }

    #[test]
    fn iterated_alpha_switch() {
        let t = FogTable::new();
        let p = FogProfile {
            iterated_alpha: FogIteratedAlpha::MameLowByte,
            ..Default::default()
        };
        // Factor 1: r 40 + (200 >> 8) = 40, g 100 + 0, b 230 + (-190 >> 8 = -1) = 229.
        assert_eq!(rgb(run(0x09, &input(), &t, p)), [40, 100, 229]);
        // With MAME's clamp as well the colour is unchanged, as the MAME golden shows.
        let p = FogProfile {
            difference: FogDifference::ClampedToByte,
            ..p
        };
        assert_eq!(rgb(run(0x09, &input(), &t, p)), [40, 100, 230]);
    }

    #[test]
    fn iterated_z() {
        // fogMode 0x11: Afog = Z[27:20] = 0x80, factor 129.
        // r 40 + (200 * 129 >> 8 = 100) = 140; g 100 + (20 * 129 >> 8 = 10) = 110;
        // b 230 + (-190 * 129 >> 8 = -96) = 134.
        let t = FogTable::new();
        assert_eq!(
            rgb(run(0x11, &input(), &t, FogProfile::default())),
            [140, 110, 134]
        );
    }

    #[test]
    fn table_fog_and_bias_switch() {
        let mut t = FogTable::new();
        // Entries 8 (fog 0x40, delta 0x80) and 9 (fog 0xff).
        t.write(4, 0xff00_4080);
        // wfloat 0x2200: index 8, frac 0x80: 0x40 + (0x80 * 0x80 >> 10 = 16) = 80.
        let mut i = input();
        i.wfloat = 0x2200;
        i.depth_bias = Some(0x0200);
        // factor 81: r 40 + (200 * 81 >> 8 = 63) = 103; g 100 + (20 * 81 >> 8 = 6) = 106;
        // b 230 + (-190 * 81 >> 8 = -61) = 169.
        assert_eq!(
            rgb(run(0x01, &i, &t, FogProfile::default())),
            [103, 106, 169]
        );
        // MAME indexes with wfloat + bias = 0x2400: index 9, frac 0: Afog 255, factor 256.
        let p = FogProfile {
            table_depth: FogTableDepth::BiasedWfloat,
            ..Default::default()
        };
        assert_eq!(rgb(run(0x01, &i, &t, p)), [240, 120, 40]);
        // Bias clamps at 0: 0x2200 - 0x4000 -> 0, index 0 (fog 0): factor 1.
        i.depth_bias = Some(-0x4000);
        assert_eq!(rgb(run(0x01, &i, &t, p)), [40, 100, 229]);
    }

    #[test]
    fn fog_add_and_fog_mult() {
        let t = FogTable::new();
        let i = input(); // Afog = 241 from iterated alpha, factor 242
                         // fogadd (0x0b): F = -Cin: Cout = Cin - (Cin * 242 >> 8), floor.
                         // r 40 - 38 (floor(-37.8)) = 2; g 100 - 95 = 5; b 230 - 218 = 12.
        assert_eq!(rgb(run(0x0b, &i, &t, FogProfile::default())), [2, 5, 12]);
        // MAME drops the negative differences: colour unchanged.
        let m = FogProfile {
            difference: FogDifference::ClampedToByte,
            ..Default::default()
        };
        assert_eq!(rgb(run(0x0b, &i, &t, m)), [40, 100, 230]);
        // fogmult (0x0d): Cout = fog * 242 >> 8: 226, 113, 37.
        assert_eq!(
            rgb(run(0x0d, &i, &t, FogProfile::default())),
            [226, 113, 37]
        );
        // fogadd + fogmult (0x0f): Cout = 0.
        assert_eq!(rgb(run(0x0f, &i, &t, FogProfile::default())), [0, 0, 0]);
    }

    #[test]
    fn constant_fog() {
        let t = FogTable::new();
        let i = input();
        // 0x21: Cin + fog, clamped: 255, 220, 255.
        assert_eq!(
            run(0x21, &i, &t, FogProfile::default()),
            Rgba {
                r: 255,
                g: 220,
                b: 255,
                a: CIN.a
            }
        );
        // fogadd is ignored by constant fog (0x23).
        assert_eq!(
            rgb(run(0x23, &i, &t, FogProfile::default())),
            [255, 220, 255]
        );
        // 0x25 (constant + fogmult): fogColor alone by default, Cin + fog for 86Box.
        assert_eq!(
            rgb(run(0x25, &i, &t, FogProfile::default())),
            [240, 120, 40]
        );
        let p = FogProfile {
            constant_mult: FogConstantMult::AddToColor,
            ..Default::default()
        };
        assert_eq!(rgb(run(0x25, &i, &t, p)), [255, 220, 255]);
        // Constant fog overrides the alpha/Z source bits (0x39).
        assert_eq!(
            rgb(run(0x39, &i, &t, FogProfile::default())),
            [255, 220, 255]
        );
    }

    #[test]
    fn both_source_bits() {
        let t = FogTable::new();
        let mut i = input();
        // W integer part 0x40 -> Afog 0x40, factor 65:
        // r 40 + (200 * 65 >> 8 = 50) = 90; g 100 + 5 = 105; b 230 + (-190 * 65 >> 8 = -49) = 181.
        i.w = 0x40 << 32;
        assert_eq!(
            rgb(run(0x19, &i, &t, FogProfile::default())),
            [90, 105, 181]
        );
        // Pseudo-clamp: W = -1.x reads 0 (factor 1), W = 256.x reads 255 (factor 256).
        i.w = -0x8000_0000;
        assert_eq!(
            rgb(run(0x19, &i, &t, FogProfile::default())),
            [40, 100, 229]
        );
        i.w = 0x100 << 32 | 0x1234;
        assert_eq!(
            rgb(run(0x19, &i, &t, FogProfile::default())),
            [240, 120, 40]
        );
        // Spec precedence: iterated Z (0x80, factor 129) as in `iterated_z`.
        let p = FogProfile {
            both_sources: FogBothSources::IteratedZ,
            ..Default::default()
        };
        assert_eq!(rgb(run(0x19, &i, &t, p)), [140, 110, 134]);
    }
}

//! Texel formats: expansion of the 8- and 16-bit texels read from memory to 8-bit ARGB
//! (spec 5.50, `tformat` table).
//!
//! | tformat | format    | A          | R, G, B                              |
//! |---------|-----------|------------|--------------------------------------|
//! | 0       | RGB332    | 0xff       | bit replication                      |
//! | 1       | YIQ422    | 0xff       | NCC table (`tnccselect`)             |
//! | 2       | A8        | a          | a (see [`crate::A8Expansion`])       |
//! | 3       | I8        | 0xff       | i                                    |
//! | 4       | AI44      | a4 * 0x11  | i4 * 0x11                            |
//! | 5       | P8        | 0xff       | palette                              |
//! | 8       | ARGB8332  | high byte  | RGB332 of the low byte               |
//! | 9       | AYIQ8422  | high byte  | NCC of the low byte                  |
//! | 10      | RGB565    | 0xff       | bit replication                      |
//! | 11      | ARGB1555  | a ? ff : 0 | bit replication                      |
//! | 12      | ARGB4444  | a4 * 0x11  | nibble * 0x11                        |
//! | 13      | AI88      | high byte  | low byte                             |
//! | 14      | AP88      | high byte  | palette of the low byte              |
//!
//! Reserved formats decode as MAME does: 6 as a palette entry read as ARGB 6-6-6-6 (the
//! Voodoo 2 format), 7 as P8 and 15 as AP88.
//!
//! Source: spec 5.50 table; MAME `shared_tables` and `lookup_single_texel`, DOSBox Staging
//! `init_tmu_shared` and 86Box `voodoo_use_texture` agree on every format as read. (The
//! spec's RGB565 green column `{g[5:0], r[5:4]}` is a typo for `{g[5:0], g[5:4]}`.)

use crate::{A8Expansion, Rgb332Blue};
use sst1_ncc::Rgb8;

/// Tables a texel decode may need.
pub(crate) struct Lookups<'a> {
    /// The selected NCC table, expanded.
    pub ncc: &'a [Rgb8; 256],
    /// The 8-bit palette.
    pub palette: &'a [Rgb8; 256],
    /// How A8 fills RGB.
    pub a8: A8Expansion,
    /// How RGB332 expands blue.
    pub rgb332_blue: Rgb332Blue,
}

/// Replicates a `bits`-wide value to 8 bits.
fn expand(v: u32, bits: u32) -> u8 {
    let v = v & ((1 << bits) - 1);
    let mut out = v << (8 - bits);
    let mut filled = bits;
    while filled < 8 {
        out |= out >> filled;
        filled *= 2;
    }
    out as u8
}

/// Packs `[r, g, b, a]` as `0xAARRGGBB`.
#[inline]
pub(crate) fn to_argb([r, g, b, a]: [u8; 4]) -> u32 {
    u32::from_be_bytes([a, r, g, b])
}

/// Unpacks `0xAARRGGBB` to `[r, g, b, a]`.
#[inline]
pub(crate) fn to_rgba(argb: u32) -> [u8; 4] {
    let [a, r, g, b] = argb.to_be_bytes();
    [r, g, b, a]
}

/// RGB565 (format 10) as `0xAARRGGBB`, each field widened by replicating its top bits.
#[inline(always)]
pub(crate) fn rgb565(raw: u32) -> u32 {
    let (r, g, b) = ((raw >> 11) & 0x1f, (raw >> 5) & 0x3f, raw & 0x1f);
    0xff00_0000 | ((r << 3) | (r >> 2)) << 16 | ((g << 2) | (g >> 4)) << 8 | (b << 3) | (b >> 2)
}

/// ARGB1555 (format 11) as `0xAARRGGBB`.
#[inline(always)]
pub(crate) fn argb1555(raw: u32) -> u32 {
    let (r, g, b) = ((raw >> 10) & 0x1f, (raw >> 5) & 0x1f, raw & 0x1f);
    let a = if raw & 0x8000 != 0 { 0xff00_0000 } else { 0 };
    a | ((r << 3) | (r >> 2)) << 16 | ((g << 3) | (g >> 2)) << 8 | (b << 3) | (b >> 2)
}

/// ARGB4444 (format 12) as `0xAARRGGBB`: each nibble times 0x11.
#[inline(always)]
pub(crate) fn argb4444(raw: u32) -> u32 {
    let n = |shift: u32| (raw >> shift) & 0xf;
    (n(12) << 24 | n(8) << 16 | n(4) << 8 | n(0)) * 0x11
}

/// How the texels of a format are turned into ARGB on the sampling path, chosen when the
/// texture state changes so that no texel decodes by a `match` on `tformat`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Decode {
    /// 8-bit formats (0..7): the texel indexes a 256-entry table of decoded texels.
    Lut8,
    /// 16-bit formats with an 8-bit colour and an 8-bit alpha (8, 9, 13, 14, 15): the low
    /// byte indexes the table for RGB, the high byte is alpha.
    LutLo16,
    /// Format 10.
    Rgb565,
    /// Format 11.
    Argb1555,
    /// Format 12.
    Argb4444,
}

impl Decode {
    /// [`Decode::Lut8`] as a const generic argument.
    pub const LUT8: u8 = 0;
    /// [`Decode::LutLo16`] as a const generic argument.
    pub const LUT_LO16: u8 = 1;
    /// [`Decode::Rgb565`] as a const generic argument.
    pub const RGB565: u8 = 2;
    /// [`Decode::Argb1555`] as a const generic argument.
    pub const ARGB1555: u8 = 3;
    /// [`Decode::Argb4444`] as a const generic argument.
    pub const ARGB4444: u8 = 4;
    /// Not a format: texels come already decoded from the texel cache (`crate::cache`).
    pub const CACHED: u8 = 5;

    /// The decode of `tformat`.
    pub fn of(tformat: u32) -> Self {
        match tformat & 0xf {
            0..=7 => Self::Lut8,
            10 => Self::Rgb565,
            11 => Self::Argb1555,
            12 => Self::Argb4444,
            _ => Self::LutLo16,
        }
    }
}

/// The 256-entry table of decoded texels (`0xAARRGGBB`) for `tformat`: every 8-bit texel,
/// or, for the 16-bit formats, every low byte (the alpha there is replaced by the high
/// byte at fetch time).
pub(crate) fn lut(tformat: u32, l: &Lookups<'_>) -> [u32; 256] {
    let mut out = [0; 256];
    for (raw, slot) in out.iter_mut().enumerate() {
        *slot = to_argb(decode(tformat, raw as u32, l));
    }
    out
}

/// `[r, g, b]` of an RGB 3-3-2 byte.
fn rgb332(v: u32, blue: Rgb332Blue) -> [u8; 3] {
    let b = match blue {
        Rgb332Blue::Replicated => expand(v, 2),
        // Source: DOSBox Staging EXTRACT_332_TO_888 (see Rgb332Blue).
        Rgb332Blue::DosboxTable => {
            ((v << 6) & 0xc0 | (v << 4) & 0x30 | (v << 2) & 0xc0 | v & 0x03) as u8
        }
    };
    [expand(v >> 5, 3), expand(v >> 2, 3), b]
}

/// `[r, g, b, a]` from an RGB triple and alpha.
fn rgba(rgb: Rgb8, a: u8) -> [u8; 4] {
    [rgb[0], rgb[1], rgb[2], a]
}

/// Decodes a raw texel (8 or 16 bits, zero-extended) of format `tformat` to `[r, g, b, a]`.
pub(crate) fn decode(tformat: u32, raw: u32, l: &Lookups<'_>) -> [u8; 4] {
    let lo = (raw & 0xff) as u8;
    let hi = (raw >> 8) as u8;
    match tformat & 0xf {
        0 => rgba(rgb332(raw, l.rgb332_blue), 0xff),
        1 => rgba(l.ncc[usize::from(lo)], 0xff),
        2 => match l.a8 {
            A8Expansion::AlphaInRgb => [lo, lo, lo, lo],
            A8Expansion::WhiteRgb => [0xff, 0xff, 0xff, lo],
        },
        3 => [lo, lo, lo, 0xff],
        4 => {
            let i = expand(raw, 4);
            [i, i, i, expand(raw >> 4, 4)]
        }
        5 | 7 => rgba(l.palette[usize::from(lo)], 0xff),
        6 => {
            // Palette entry read as A6 R6 G6 B6 (MAME `argbexpand<6,6,6,6>`).
            let [r, g, b] = l.palette[usize::from(lo)];
            let p = u32::from(r) << 16 | u32::from(g) << 8 | u32::from(b);
            [
                expand(p >> 12, 6),
                expand(p >> 6, 6),
                expand(p, 6),
                expand(p >> 18, 6),
            ]
        }
        8 => rgba(rgb332(raw, l.rgb332_blue), hi),
        9 => rgba(l.ncc[usize::from(lo)], hi),
        10 => to_rgba(rgb565(raw)),
        11 => to_rgba(argb1555(raw)),
        12 => to_rgba(argb4444(raw)),
        13 => [lo, lo, lo, hi],
        _ => rgba(l.palette[usize::from(lo)], hi),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lookups<'a>(ncc: &'a [Rgb8; 256], pal: &'a [Rgb8; 256]) -> Lookups<'a> {
        Lookups {
            ncc,
            palette: pal,
            a8: A8Expansion::AlphaInRgb,
            rgb332_blue: Rgb332Blue::Replicated,
        }
    }

    fn tables() -> ([Rgb8; 256], [Rgb8; 256]) {
        let mut ncc = [[0u8; 3]; 256];
        let mut pal = [[0u8; 3]; 256];
        ncc[0x5a] = [1, 2, 3];
        pal[0x5a] = [0x10, 0x20, 0x30];
        pal[0x77] = [0xfe, 0xdc, 0xba];
        (ncc, pal)
    }

    #[test]
    fn eight_bit_formats() {
        let (ncc, pal) = tables();
        let l = lookups(&ncc, &pal);
        // RGB332 0b101_011_10: r 5 -> 10110110, g 3 -> 01101101, b 2 -> 10101010
        assert_eq!(decode(0, 0xae, &l), [0xb6, 0x6d, 0xaa, 0xff]);
        assert_eq!(decode(0, 0xff, &l), [0xff, 0xff, 0xff, 0xff]);
        assert_eq!(decode(1, 0x5a, &l), [1, 2, 3, 0xff]);
        assert_eq!(decode(2, 0x5a, &l), [0x5a, 0x5a, 0x5a, 0x5a]);
        assert_eq!(decode(3, 0x5a, &l), [0x5a, 0x5a, 0x5a, 0xff]);
        // AI44: alpha high nibble, intensity low nibble
        assert_eq!(decode(4, 0x5a, &l), [0xaa, 0xaa, 0xaa, 0x55]);
        assert_eq!(decode(5, 0x5a, &l), [0x10, 0x20, 0x30, 0xff]);
        assert_eq!(decode(7, 0x5a, &l), [0x10, 0x20, 0x30, 0xff]);
    }

    #[test]
    fn rgb332_dosbox_blue() {
        let (ncc, pal) = tables();
        let l = Lookups {
            rgb332_blue: Rgb332Blue::DosboxTable,
            ..lookups(&ncc, &pal)
        };
        // 0b101_011_10: blue 10 -> 10 10 00 10, bits 5:4 (10) ORed into the top: 0xa2.
        assert_eq!(decode(0, 0xae, &l), [0xb6, 0x6d, 0xa2, 0xff]);
        // Blue 0 with bits 5:4 = 11 reads 0xc0; blue 3 with them 00 reads 0xf3.
        assert_eq!(decode(0, 0b0011_0000, &l)[2], 0xc0);
        assert_eq!(decode(0, 0b0000_0011, &l)[2], 0xf3);
        // ARGB8332 takes the same table for its low byte.
        assert_eq!(decode(8, 0x7fae, &l), [0xb6, 0x6d, 0xa2, 0x7f]);
    }

    #[test]
    fn a8_white_variant() {
        let (ncc, pal) = tables();
        let l = Lookups {
            a8: A8Expansion::WhiteRgb,
            rgb332_blue: Rgb332Blue::Replicated,
            ..lookups(&ncc, &pal)
        };
        assert_eq!(decode(2, 0x5a, &l), [0xff, 0xff, 0xff, 0x5a]);
    }

    #[test]
    fn sixteen_bit_formats() {
        let (ncc, pal) = tables();
        let l = lookups(&ncc, &pal);
        assert_eq!(decode(8, 0x80ae, &l), [0xb6, 0x6d, 0xaa, 0x80]);
        assert_eq!(decode(9, 0x335a, &l), [1, 2, 3, 0x33]);
        // RGB565 r=0b10110 g=0b011011 b=0b00101
        assert_eq!(
            decode(10, (0b10110 << 11) | (0b011011 << 5) | 0b00101, &l),
            [0xb5, 0x6d, 0x29, 0xff]
        );
        assert_eq!(decode(10, 0xffff, &l), [0xff; 4]);
        // ARGB1555
        assert_eq!(
            decode(11, 0x8000 | (0b10110 << 10) | (0b01101 << 5) | 0b00101, &l),
            [0xb5, 0x6b, 0x29, 0xff]
        );
        assert_eq!(decode(11, 0x7fff, &l), [0xff, 0xff, 0xff, 0]);
        assert_eq!(decode(12, 0x49e2, &l), [0x99, 0xee, 0x22, 0x44]);
        assert_eq!(decode(13, 0x805a, &l), [0x5a, 0x5a, 0x5a, 0x80]);
        assert_eq!(decode(14, 0x8077, &l), [0xfe, 0xdc, 0xba, 0x80]);
        assert_eq!(decode(15, 0x8077, &l), [0xfe, 0xdc, 0xba, 0x80]);
    }

    #[test]
    fn direct_16bit_decoders_replicate_top_bits() {
        for raw in 0..=0xffff_u32 {
            let a1 = if raw & 0x8000 != 0 { 0xff } else { 0 };
            let e = |v: u32, bits: u32| expand(v, bits);
            assert_eq!(
                to_rgba(rgb565(raw)),
                [e(raw >> 11, 5), e(raw >> 5, 6), e(raw, 5), 0xff]
            );
            assert_eq!(
                to_rgba(argb1555(raw)),
                [e(raw >> 10, 5), e(raw >> 5, 5), e(raw, 5), a1]
            );
            assert_eq!(
                to_rgba(argb4444(raw)),
                [e(raw >> 8, 4), e(raw >> 4, 4), e(raw, 4), e(raw >> 12, 4)]
            );
        }
    }

    #[test]
    fn lut_holds_each_decoded_byte() {
        let (ncc, pal) = tables();
        let l = lookups(&ncc, &pal);
        for f in [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 13, 14, 15] {
            let t = lut(f, &l);
            for raw in 0..256u32 {
                assert_eq!(to_rgba(t[raw as usize]), decode(f, raw, &l), "{f} {raw}");
            }
        }
        assert_eq!(Decode::of(0x5), Decode::Lut8);
        assert_eq!(Decode::of(0x9), Decode::LutLo16);
        assert_eq!(Decode::of(0xe), Decode::LutLo16);
        assert_eq!(Decode::of(0xa), Decode::Rgb565);
        assert_eq!(Decode::of(0xb), Decode::Argb1555);
        assert_eq!(Decode::of(0xc), Decode::Argb4444);
    }

    #[test]
    fn reserved_format_6_is_argb6666_palette() {
        let (ncc, mut pal) = tables();
        // a=0x3f r=0 g=0x2a b=0x15
        pal[1] = [0xfc, 0x0a, 0x95];
        let l = lookups(&ncc, &pal);
        assert_eq!(decode(6, 1, &l), [0x00, 0xaa, 0x55, 0xff]);
    }
}

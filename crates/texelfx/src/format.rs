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

use crate::A8Expansion;
use sst1_ncc::Rgb8;

/// Tables a texel decode may need.
pub(crate) struct Lookups<'a> {
    /// The selected NCC table, expanded.
    pub ncc: &'a [Rgb8; 256],
    /// The 8-bit palette.
    pub palette: &'a [Rgb8; 256],
    /// How A8 fills RGB.
    pub a8: A8Expansion,
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

/// `[r, g, b]` of an RGB 3-3-2 byte.
fn rgb332(v: u32) -> [u8; 3] {
    [expand(v >> 5, 3), expand(v >> 2, 3), expand(v, 2)]
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
        0 => rgba(rgb332(raw), 0xff),
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
        8 => rgba(rgb332(raw), hi),
        9 => rgba(l.ncc[usize::from(lo)], hi),
        10 => [
            expand(raw >> 11, 5),
            expand(raw >> 5, 6),
            expand(raw, 5),
            0xff,
        ],
        11 => [
            expand(raw >> 10, 5),
            expand(raw >> 5, 5),
            expand(raw, 5),
            if raw & 0x8000 != 0 { 0xff } else { 0 },
        ],
        12 => [
            expand(raw >> 8, 4),
            expand(raw >> 4, 4),
            expand(raw, 4),
            expand(raw >> 12, 4),
        ],
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
    fn a8_white_variant() {
        let (ncc, pal) = tables();
        let l = Lookups {
            a8: A8Expansion::WhiteRgb,
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
    fn reserved_format_6_is_argb6666_palette() {
        let (ncc, mut pal) = tables();
        // a=0x3f r=0 g=0x2a b=0x15
        pal[1] = [0xfc, 0x0a, 0x95];
        let l = lookups(&ncc, &pal);
        assert_eq!(decode(6, 1, &l), [0x00, 0xaa, 0x55, 0xff]);
    }
}

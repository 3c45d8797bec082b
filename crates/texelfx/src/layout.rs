//! Where each LOD of a texture lies in texture memory (spec section 8, "Texture Memory
//! Access", and 5.53 `texBaseAddr*`).
//!
//! Textures are stored as if mipmapped: `texBaseAddr` points where LOD 0 (256 texels on the
//! wider side) would start, and the levels follow one another, largest first. With
//! `lod_tsplit` only the even or only the odd levels are stored. Every level occupies at least
//! 4 texels (8 bytes for 16-bit texels, 4 for 8-bit), as in the spec's examples 2 and 3. The
//! base may wrap below zero and every address wraps at the end of the TMU's memory.
//!
//! With `tmultibaseaddr`, LOD 0, 1 and 2 start at `texBaseAddr`, `texBaseAddr1` and
//! `texBaseAddr2`, and LOD 3 at `texBaseAddr38` with LODs 4..8 packed after it.
//!
//! Source: spec section 8 examples 1-3; MAME `rasterizer_texture::recompute` (DOSBox Staging
//! has the same arithmetic). 86Box differs: it has no 4-texel minimum, sizes narrow levels as
//! 0 bytes, and offsets the multibase levels by the packed size of the earlier levels.

use sst1_regs::{TLod, TextureMode};

/// Byte address of a `texBaseAddr*` value: bits 18:0 in units of 8 bytes (spec 5.53).
const fn tex_base_bytes(v: u32) -> u32 {
    (v & 0x7ffff) << 3
}

/// The address layout of the current texture, derived from `textureMode`, `tLOD` and the
/// four `texBaseAddr` registers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Layout {
    /// Byte address of each LOD 0..=8, already wrapped to the memory size.
    pub lod_base: [u32; 9],
    /// Width minus 1 of LOD 0 (255 >> aspect or 255).
    pub wmask: u32,
    /// Height minus 1 of LOD 0.
    pub hmask: u32,
    /// Bit n set when LOD n is stored (all of them unless `lod_tsplit`).
    pub lodmask: u32,
    /// log2 of the bytes per texel (0 for formats 0..7, 1 for 8..15).
    pub bpp_shift: u32,
}

impl Layout {
    /// Computes the layout; `mem_mask` is the memory size minus 1.
    pub fn new(texture_mode: u32, t_lod: u32, tex_base: &[u32; 4], mem_mask: u32) -> Self {
        let lod = TLod(t_lod);
        let lodmask = if lod.lod_tsplit() {
            if lod.lod_odd() {
                0x0aa
            } else {
                0x155
            }
        } else {
            0x1ff
        };
        let (mut wmask, mut hmask) = (0xffu32, 0xffu32);
        if lod.lod_s_is_wider() {
            hmask >>= lod.lod_aspect();
        } else {
            wmask >>= lod.lod_aspect();
        }
        let bpp_shift = TextureMode(texture_mode).format() as u32 >> 3;
        let texels = |lod: usize| ((wmask >> lod) + 1) * ((hmask >> lod) + 1);

        let mut lod_base = [0u32; 9];
        let mut base = tex_base_bytes(tex_base[0]);
        lod_base[0] = base & mem_mask;
        if lod.tmultibaseaddr() {
            for lod in 1..=3 {
                base = tex_base_bytes(tex_base[lod]);
                lod_base[lod] = base & mem_mask;
            }
        } else {
            for lod in 0..3 {
                if lodmask & (1 << lod) != 0 {
                    base = base.wrapping_add(texels(lod) << bpp_shift);
                }
                lod_base[lod + 1] = base & mem_mask;
            }
        }
        for (lod, slot) in lod_base.iter_mut().enumerate().skip(4) {
            if lodmask & (1 << (lod - 1)) != 0 {
                base = base.wrapping_add(texels(lod - 1).max(4) << bpp_shift);
            }
            *slot = base & mem_mask;
        }
        Self {
            lod_base,
            wmask,
            hmask,
            lodmask,
            bpp_shift,
        }
    }

    /// Width minus 1 of a LOD.
    pub fn smax(&self, lod: usize) -> u32 {
        self.wmask >> lod
    }

    /// Height minus 1 of a LOD.
    pub fn tmax(&self, lod: usize) -> u32 {
        self.hmask >> lod
    }

    /// Byte address (not yet wrapped) of texel `(s, t)` of a LOD; `s`, `t` already in range.
    pub fn texel_addr(&self, lod: usize, s: u32, t: u32) -> u32 {
        let index = t * (self.smax(lod) + 1) + s;
        self.lod_base[lod].wrapping_add(index << self.bpp_shift)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MEM: u32 = (4 << 20) - 1;
    const FMT16: u32 = 10 << 8;
    const FMT8: u32 = 0;
    const S_WIDER: u32 = 1 << 20;
    const fn aspect(a: u32) -> u32 {
        a << 21
    }
    const TSPLIT: u32 = 1 << 19;
    const ODD: u32 = 1 << 18;
    const MULTI: u32 = 1 << 24;

    fn bases(tm: u32, tl: u32, base: u32) -> [u32; 9] {
        Layout::new(tm, tl, &[base, 0, 0, 0], MEM).lod_base
    }

    #[test]
    fn square_16bit_chain() {
        // 256x256, 128x128, ... 1x1 at 2 bytes: sizes 0x20000, 0x8000, 0x2000, 0x800, 0x200,
        // 0x80, 0x20, 8 (2x2), 8 (1x1 rounded up to 4 texels)
        let b = bases(FMT16, 0, 0);
        assert_eq!(
            b,
            [0, 0x20000, 0x28000, 0x2a000, 0x2a800, 0x2aa00, 0x2aa80, 0x2aaa0, 0x2aaa8]
        );
    }

    #[test]
    fn square_8bit_chain_with_base() {
        let b = bases(FMT8, 0, 0x100 >> 3);
        assert_eq!(
            b,
            [0x100, 0x10100, 0x14100, 0x15100, 0x15500, 0x15600, 0x15640, 0x15650, 0x15654]
        );
    }

    #[test]
    fn spec_example_1_base_wraps_below_zero() {
        // 16-bit, 1:1, LODs 1 and 2 loaded at 0x00010 (units of 8 bytes);
        // texbaseaddr = 0x00010 - 0x04000 = 0xfc010 (19-bit field: 0x7c010).
        let b = bases(FMT16, 0, 0xfc010);
        assert_eq!(b[1], 0x10 << 3);
        assert_eq!(b[3] - b[1], 0x1400 << 3);
    }

    #[test]
    fn spec_example_2_8bit_8to1_s_wider() {
        // LOD 4..8 loaded at 0x10000; texbaseaddr = 0x0fab0; next free = 0x10007
        let b = bases(FMT8, S_WIDER | aspect(3), 0x0fab0);
        assert_eq!(b[4], 0x10000 << 3);
        // levels 16x2, 8x1, 4x1, 2x1 (4), 1x1 (4) = 32, 8, 4, 4, 4 bytes
        assert_eq!([b[5], b[6], b[7], b[8]].map(|a| a - b[4]), [32, 40, 44, 48]);
        // 52 bytes = 6.5 units -> next start 0x10007
        assert_eq!((b[8] + 4 + 7) >> 3, 0x10007);
    }

    #[test]
    fn spec_example_3_split_even() {
        // 8-bit, 8:1, tsplit, even; LOD 4, 6, 8 loaded at 0x10000, texbaseaddr 0x0fbc0
        let b = bases(FMT8, S_WIDER | aspect(3) | TSPLIT, 0x0fbc0);
        assert_eq!(b[4], 0x10000 << 3);
        // odd levels take no room: LOD 5 shares LOD 6's address
        assert_eq!([b[5], b[6], b[7], b[8]].map(|a| a - b[4]), [32, 32, 36, 36]);
        assert_eq!((b[8] + 4 + 7) >> 3, 0x10005);
    }

    #[test]
    fn split_odd_skips_even_levels() {
        let b = bases(FMT16, TSPLIT | ODD, 0);
        // LOD 0 not stored: LOD 1 at the base
        assert_eq!(&b[..4], &[0, 0, 0x8000, 0x8000]);
        assert_eq!(b[4], 0x8800);
    }

    #[test]
    fn t_wider_aspect_2_16bit() {
        // 64x256: LOD 0 64*256*2 = 0x8000; LOD 1 32x128 = 0x2000; LOD 6 1x4 = 8 bytes,
        // LOD 7 1x2 -> 4 texels = 8, LOD 8 1x1
        let l = Layout::new(FMT16, aspect(2), &[0; 4], MEM);
        assert_eq!((l.wmask, l.hmask), (63, 255));
        assert_eq!(
            l.lod_base,
            [0, 0x8000, 0xa000, 0xa800, 0xaa00, 0xaa80, 0xaaa0, 0xaaa8, 0xaab0]
        );
        assert_eq!(l.texel_addr(1, 3, 2), 0x8000 + (2 * 32 + 3) * 2);
    }

    #[test]
    fn s_wider_aspect_1_8bit() {
        // 256x128 8-bit
        let l = Layout::new(FMT8, S_WIDER | aspect(1), &[0; 4], MEM);
        assert_eq!((l.wmask, l.hmask), (255, 127));
        assert_eq!(l.lod_base[1], 0x8000);
        assert_eq!(l.lod_base[2], 0xa000);
        assert_eq!(l.texel_addr(2, 5, 1), 0xa000 + 64 + 5);
    }

    #[test]
    fn multibase() {
        let l = Layout::new(FMT16, MULTI, &[0x100, 0x2000, 0x3000, 0x4000], MEM);
        assert_eq!(&l.lod_base[..4], &[0x800, 0x10000, 0x18000, 0x20000]);
        // LOD 4 follows LOD 3 (32x32x2 = 0x800)
        assert_eq!(l.lod_base[4], 0x20800);
    }

    #[test]
    fn addresses_wrap_at_memory_size() {
        // 1 MiB: base 0xff000 (units) = 0x7f8000 bytes wraps to 0xf8000
        let l = Layout::new(FMT16, 0, &[0xff000, 0, 0, 0], (1 << 20) - 1);
        assert_eq!(l.lod_base[0], 0xf8000);
        assert_eq!(l.lod_base[1], 0x18000);
    }
}

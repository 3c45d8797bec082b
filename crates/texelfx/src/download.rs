//! Texture downloads through the 8 MiB texture aperture (spec section 8, "Texture Load").
//!
//! ```text
//! seq_8_downld = 0, or 16-bit texels:   addr[20:17] LOD  addr[16:9] T  addr[8:2] S[7:1]
//! seq_8_downld = 1 and 8-bit texels:    addr[20:17] LOD  addr[16:9] T  addr[7:2] S[7:2]
//! ```
//!
//! (bits 22:21 select the TMU and are ignored here.) A 32-bit write carries two 16-bit
//! texels (S, S+1) or four 8-bit texels (S..S+3), low bits first; for 8-bit texels with
//! `seq_8_downld = 0`, S\[1\] is forced to 0. Texels that fall beyond the width of a narrow
//! map (1xN for 16-bit; 1xN, 2xN for 8-bit) are not written. `tLOD` `tdata_swizzle` reverses
//! the bytes of the word and `tdata_swap` then swaps its halves (spec 5.51). LODs above 8
//! are ignored.
//!
//! Source: spec section 8 and 5.51; MAME `voodoo_1_device::texture_w` and 86Box
//! `voodoo_tex_writel` decode the same fields. They differ only on narrow maps (MAME aligns
//! the destination down to 4 bytes and writes all four bytes; 86Box writes all four bytes
//! unaligned); this follows the spec's write inhibit.

use crate::Tmu;
use sst1_regs::{TLod, TextureMode};

impl Tmu {
    /// Implements [`Tmu::write_texture`].
    pub(crate) fn download(&mut self, addr: u32, value: u32) {
        let mut data = value;
        let lod_reg = TLod(self.t_lod);
        if lod_reg.tdata_swizzle() {
            data = data.swap_bytes();
        }
        if lod_reg.tdata_swap() {
            data = data.rotate_left(16);
        }
        let lod = ((addr >> 17) & 0xf) as usize;
        if lod > 8 {
            return;
        }
        let t = (addr >> 9) & 0xff;
        let width = self.layout.smax(lod) + 1;
        let row = self.layout.lod_base[lod].wrapping_add((t * width) << self.layout.bpp_shift);
        // UNVERIFIED: MAME takes seq_8_downld from TMU 0 for every TMU; this uses the
        // TMU's own textureMode.
        if self.layout.bpp_shift == 1 {
            let s = (addr >> 1) & 0xfe;
            let texels = if width > 1 { 2 } else { 1 };
            self.cache
                .written(row.wrapping_add(s * 2), texels * 2, self.ram_mask);
            self.box86.written(row.wrapping_add(s * 2) & self.ram_mask);
            for k in 0..texels {
                let a = row.wrapping_add((s + k) * 2);
                let texel = (data >> (16 * k)) as u16;
                self.store(a, texel as u8);
                self.store(a.wrapping_add(1), (texel >> 8) as u8);
            }
        } else {
            let s = if TextureMode(self.texture_mode).seq_8_downld() {
                addr & 0xfc
            } else {
                (addr >> 1) & 0xfc
            };
            self.cache
                .written(row.wrapping_add(s), width.min(4), self.ram_mask);
            self.box86.written(row.wrapping_add(s) & self.ram_mask);
            for k in 0..width.min(4) {
                self.store(row.wrapping_add(s + k), (data >> (8 * k)) as u8);
            }
        }
    }

    /// Stores one byte of texture memory, wrapping at its end.
    fn store(&mut self, addr: u32, byte: u8) {
        self.ram[(addr & self.ram_mask) as usize] = byte;
    }
}

//! Texture state, memory layout and downloads.
//!
//! Spec sections 5 (`textureMode`, `tLOD`, `tDetail`, `texBaseAddr*`, `nccTable0/1`)
//! and 8 (texture memory download addressing: TMU in bits 22:21, LOD in 20:17, T in
//! 16:9, S in 8:1 of the aperture offset).
//!
//! Memory sizes, base-address arithmetic and register encodings follow 3dfx's SST-1
//! Glide 3 (ditex.c, gtex.c, gtexdl.c); every register write to a TMU is bracketed by
//! the packer workaround write, as 3dfx's library does.

use crate::consts::*;
use crate::hw::{tmu_chip, TEX_BASE};
use sst1_regs::addr::*;
use sst1_regs::{TDetail, TLod, TcMselect, TextureFormat, TextureMode};

/// A texture description (`GrTexInfo`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexInfo {
    /// `GR_LOD_LOG2_*` of the smallest level.
    pub small_lod: u32,
    /// `GR_LOD_LOG2_*` of the largest level.
    pub large_lod: u32,
    /// `GR_ASPECT_LOG2_*` (-3..=3).
    pub aspect: i32,
    /// `GR_TEXFMT_*`.
    pub format: u32,
}

/// Texels the hardware allocates for each LOD (0 = 256) of each aspect class
/// (8:1, 4:1, 2:1, 1:1). Source: ditex.c `_grMipMapSize`.
const MIPMAP_SIZE: [[u32; 9]; 4] = [
    [0x2000, 0x800, 0x200, 0x80, 0x20, 0x10, 0x8, 0x4, 0x4],
    [0x4000, 0x1000, 0x400, 0x100, 0x40, 0x10, 0x8, 0x4, 0x4],
    [0x8000, 0x2000, 0x800, 0x200, 0x80, 0x20, 0x8, 0x4, 0x4],
    [0x10000, 0x4000, 0x1000, 0x400, 0x100, 0x40, 0x10, 0x4, 0x4],
];

/// `tLOD` `lod_aspect` and `lod_s_is_wider` for aspect index 0 (8:1) .. 6 (1:8).
/// Source: ditex.c.
const ASPECT_XLATE: [(u32, bool); 7] = [
    (3, true),
    (2, true),
    (1, true),
    (0, false),
    (1, false),
    (2, false),
    (3, false),
];

/// `l` with the aspect fields of a `GR_ASPECT_LOG2_*`.
fn with_aspect(l: TLod, aspect: i32) -> TLod {
    let (log2, s_is_wider) = ASPECT_XLATE[aspect_index(aspect)];
    l.with_lod_aspect(log2).with_lod_s_is_wider(s_is_wider)
}

/// `l` with the odd/even split bits of a `GR_MIPMAPLEVELMASK_*` (1 even, 2 odd, 3
/// both) set; bits already set stay set, as in ditex.c's `|=`.
fn with_even_odd(l: TLod, mask: u32) -> TLod {
    match mask {
        GR_MIPMAPLEVELMASK_EVEN => l.with_lod_tsplit(true),
        GR_MIPMAPLEVELMASK_ODD => l.with_lod_tsplit(true).with_lod_odd(true),
        _ => l,
    }
}

/// Hardware LOD number (0 = 256x256 .. 8 = 1x1) of a `GR_LOD_LOG2_*`.
pub(crate) fn hw_lod(lod: u32) -> u32 {
    8u32.saturating_sub(lod.min(8))
}

/// Aspect index (0 = 8:1 .. 6 = 1:8) of a `GR_ASPECT_LOG2_*`.
fn aspect_index(aspect: i32) -> usize {
    (3 - aspect.clamp(-3, 3)) as usize
}

/// The aspect class used for memory sizes (1:n mirrors n:1).
fn aspect_class(aspect: i32) -> usize {
    let a = aspect_index(aspect);
    if a > 3 {
        6 - a
    } else {
        a
    }
}

/// `l` with the lodmin/lodmax fields (4.2 fixed point) set to whole LODs `min`, `max`.
fn with_lod_minmax(l: TLod, min: u32, max: u32) -> TLod {
    l.with_lodmin(min << 2).with_lodmax(max << 2)
}

/// Whether a `textureMode` is the odd pass of two-pass trilinear: trilinear on, zero
/// other, blend by the LOD fraction, no reverse blend (then `tLOD` selects odd LODs).
fn odd_trilinear_pass(m: TextureMode) -> bool {
    m.trilinear()
        && m.tc_zero_other()
        && matches!(m.tc_mselect(), TcMselect::LodFrac)
        && !m.tc_reverse_blend()
}

/// Offset of each LOD from the start of a full mipmap, and with odd/even split.
fn mip_offset(class: usize, lod: u32, split: bool) -> u32 {
    let sizes = &MIPMAP_SIZE[class];
    let lod = lod.min(9) as usize;
    if split {
        let mut sum = 0;
        let mut l = lod;
        while l >= 2 {
            l -= 2;
            sum += sizes[l];
        }
        sum
    } else {
        sizes[..lod].iter().sum()
    }
}

/// Bytes of texture memory a mipmap needs, rounded up to 8 (`_grTexTextureMemRequired`).
pub(crate) fn mem_required(small: u32, large: u32, aspect: i32, format: u32, even_odd: u32) -> u32 {
    let class = aspect_class(aspect);
    let (small, large) = (hw_lod(small), hw_lod(large));
    let mut m = if even_odd == GR_MIPMAPLEVELMASK_BOTH {
        mip_offset(class, small + 1, false).saturating_sub(mip_offset(class, large, false))
    } else {
        let want_odd = even_odd == GR_MIPMAPLEVELMASK_ODD;
        (large..=small.min(8))
            .filter(|l| (l & 1 == 1) == want_odd)
            .map(|l| MIPMAP_SIZE[class][l as usize])
            .sum()
    };
    if format >= GR_TEXFMT_16BIT {
        m <<= 1;
    }
    (m + 7) & !7
}

/// Texture base address for `start` given the largest LOD (`_grTexCalcBaseAddress`):
/// the hardware addresses LOD 0 (256) even if the texture starts smaller.
fn base_address(start: u32, large_hw_lod: u32, aspect: i32, format: u32, even_odd: u32) -> u32 {
    let class = aspect_class(aspect);
    let sum = if even_odd == GR_MIPMAPLEVELMASK_BOTH {
        mip_offset(class, large_hw_lod, false)
    } else {
        let mut l = large_hw_lod;
        if (even_odd == GR_MIPMAPLEVELMASK_EVEN && l & 1 == 1)
            || (even_odd == GR_MIPMAPLEVELMASK_ODD && l & 1 == 0)
        {
            l += 1;
        }
        mip_offset(class, l, true)
    };
    let sum = if format >= GR_TEXFMT_16BIT {
        sum << 1
    } else {
        sum
    };
    start.wrapping_sub(sum)
}

/// Host-side width and height of one LOD level.
pub fn level_wh(lod: u32, aspect: i32) -> (u32, u32) {
    let side = 1u32 << lod.min(8);
    if aspect >= 0 {
        (side, (side >> aspect.min(3)).max(1))
    } else {
        ((side >> (-aspect).min(3)).max(1), side)
    }
}

/// Whether rows `t..=max_t` lie inside level `lod` (`GR_LOD_LOG2_*`) of aspect
/// `aspect`: what `grTexDownloadMipMapLevelPartial` may read of the caller's data.
pub fn rows_ok(lod: u32, aspect: i32, t: i32, max_t: i32) -> bool {
    let (_, height) = level_wh(lod, aspect);
    0 <= t && t <= max_t && i64::from(max_t) < i64::from(height)
}

impl crate::Glide {
    fn tmu_write(&mut self, tmu: usize, regs: &[(u32, u32)]) {
        self.hw.packer();
        for &(a, v) in regs {
            self.hw.w(tmu_chip(tmu) | a, v);
        }
        self.hw.packer();
    }

    /// `grTexClampMode`.
    pub(crate) fn tex_clamp(&mut self, tmu: usize, s: u32, t: u32) {
        let m = TextureMode(self.st.tmu[tmu].texture_mode)
            .with_tclamps(s == GR_TEXTURECLAMP_CLAMP)
            .with_tclampt(t == GR_TEXTURECLAMP_CLAMP)
            .0;
        self.tmu_write(tmu, &[(TEXTURE_MODE, m)]);
        self.st.tmu[tmu].texture_mode = m;
    }

    /// `grTexFilterMode`.
    pub(crate) fn tex_filter(&mut self, tmu: usize, min: u32, mag: u32) {
        let m = TextureMode(self.st.tmu[tmu].texture_mode)
            .with_tminfilter(min == GR_TEXTUREFILTER_BILINEAR)
            .with_tmagfilter(mag == GR_TEXTUREFILTER_BILINEAR)
            .0;
        self.tmu_write(tmu, &[(TEXTURE_MODE, m)]);
        self.st.tmu[tmu].texture_mode = m;
    }

    /// `grTexLodBiasValue`: bias in quarter LODs, 6-bit two's complement.
    pub(crate) fn tex_lod_bias(&mut self, tmu: usize, bias: f32) {
        let quarters = ((bias + 0.125) / 0.25) as i32;
        let l = TLod(self.st.tmu[tmu].t_lod).with_lodbias(quarters).0;
        self.tmu_write(tmu, &[(T_LOD, l)]);
        self.st.tmu[tmu].t_lod = l;
    }

    /// `grTexDetailControl`.
    pub(crate) fn tex_detail(&mut self, tmu: usize, lod_bias: i32, scale: u8, max: f32) {
        let dmax = (max * 255.0) as u32;
        let d = TDetail::default()
            .with_detail_max(dmax)
            .with_detail_bias(lod_bias)
            .with_detail_scale(u32::from(scale))
            .0;
        self.tmu_write(tmu, &[(T_DETAIL, d)]);
        self.st.tmu[tmu].t_detail = d;
    }

    /// `grTexMipMapMode`.
    pub(crate) fn tex_mipmap(&mut self, tmu: usize, mode: u32, lod_blend: bool) {
        let c = self.st.tmu[tmu];
        let small = if mode == GR_MIPMAP_DISABLE {
            c.large_lod
        } else {
            c.small_lod
        };
        let dither = mode == GR_MIPMAP_NEAREST_DITHER && self.st.allow_lod_dither;
        let m = TextureMode(c.texture_mode)
            .with_tloddither(dither)
            .with_trilinear(lod_blend);
        let l =
            with_lod_minmax(TLod(c.t_lod), c.large_lod, small).with_lod_odd(odd_trilinear_pass(m));
        let l = with_even_odd(l, c.even_odd);
        self.tmu_write(tmu, &[(T_LOD, l.0), (TEXTURE_MODE, m.0)]);
        self.st.tmu[tmu].mm_mode = mode;
        self.st.tmu[tmu].t_lod = l.0;
        self.st.tmu[tmu].texture_mode = m.0;
    }

    /// `grTexCombine`.
    pub(crate) fn tex_combine_hw(
        &mut self,
        tmu: usize,
        rgb_fn: u32,
        rgb_factor: u32,
        a_fn: u32,
        a_factor: u32,
        rgb_invert: bool,
        a_invert: bool,
    ) {
        let c = self.st.tmu[tmu];
        let bit = 1u32 << tmu;
        self.st.tmu_mask &= !bit;
        let is_local = |f: u32| {
            matches!(
                f & 7,
                GR_COMBINE_FACTOR_LOCAL | GR_COMBINE_FACTOR_LOCAL_ALPHA
            )
        };
        let ([zero, sub, add_c, add_a], rgb_local) = combine_bits(rgb_fn);
        let ([a_zero, a_sub, a_add_c, a_add_a], a_local) = combine_bits(a_fn);
        // Every tc_* and tca_* field (bits 29:12) is set here.
        let m = TextureMode(c.texture_mode)
            .with_tc_zero_other(zero)
            .with_tc_sub_clocal(sub)
            .with_tc_mselect(TcMselect::from_bits(rgb_factor))
            .with_tc_reverse_blend(rgb_factor & 8 == 0)
            .with_tc_add_clocal(add_c)
            .with_tc_add_alocal(add_a)
            .with_tc_invert_output(rgb_invert)
            .with_tca_zero_other(a_zero)
            .with_tca_sub_clocal(a_sub)
            .with_tca_mselect(TcMselect::from_bits(a_factor))
            .with_tca_reverse_blend(a_factor & 8 == 0)
            .with_tca_add_clocal(a_add_c)
            .with_tca_add_alocal(a_add_a)
            .with_tca_invert_output(a_invert);
        if is_local(rgb_factor) || is_local(a_factor) || rgb_local || a_local {
            self.st.tmu_mask |= bit;
        }
        let l = TLod(c.t_lod).with_lod_odd(odd_trilinear_pass(m));
        let l = with_even_odd(l, c.even_odd);
        self.tmu_write(tmu, &[(TEXTURE_MODE, m.0), (T_LOD, l.0)]);
        self.st.tmu[tmu].texture_mode = m.0;
        self.st.tmu[tmu].t_lod = l.0;
        self.update_param_index();
    }

    /// `grTexSource`.
    pub(crate) fn tex_source_hw(&mut self, tmu: usize, start: u32, even_odd: u32, info: &TexInfo) {
        let large = hw_lod(info.large_lod);
        let small = hw_lod(info.small_lod);
        let c = &mut self.st.tmu[tmu];
        c.small_lod = small;
        c.large_lod = large;
        c.even_odd = even_odd;
        let base = base_address(start, large, info.aspect, info.format, even_odd) >> 3;
        let m = TextureMode(c.texture_mode)
            .with_format(TextureFormat::from_bits(info.format))
            .with_tpersp_st(true)
            .with_tclampw(true)
            .0;
        let smallest = if c.mm_mode == GR_MIPMAP_DISABLE {
            large
        } else {
            small
        };
        let l = with_lod_minmax(TLod(c.t_lod), large, smallest)
            .with_lod_tsplit(false)
            .with_lod_odd(false);
        let l = with_aspect(with_even_odd(l, even_odd), info.aspect).0;
        c.st_scale = match info.aspect {
            3 => [256.0, 32.0],
            2 => [256.0, 64.0],
            1 => [256.0, 128.0],
            -1 => [128.0, 256.0],
            -2 => [64.0, 256.0],
            -3 => [32.0, 256.0],
            _ => [256.0, 256.0],
        };
        c.tex_base_addr[0] = base;
        c.texture_mode = m;
        c.t_lod = l;
        self.tmu_write(tmu, &[(TEX_BASE_ADDR, base), (TEXTURE_MODE, m), (T_LOD, l)]);
    }

    /// `grTexMultibase`.
    pub(crate) fn tex_multibase_hw(&mut self, tmu: usize, enable: bool) {
        let l = TLod(self.st.tmu[tmu].t_lod).with_tmultibaseaddr(enable).0;
        self.tmu_write(tmu, &[(T_LOD, l)]);
        self.st.tmu[tmu].t_lod = l;
    }

    /// `grTexMultibaseAddress`: `range` is `GR_TEXBASE_*`.
    pub(crate) fn tex_multibase_address_hw(
        &mut self,
        tmu: usize,
        range: u32,
        start: u32,
        even_odd: u32,
        info: &TexInfo,
    ) {
        let (slot, lod, reg) = match range {
            GR_TEXBASE_256 => (0, GR_LOD_LOG2_256, TEX_BASE_ADDR),
            GR_TEXBASE_128 => (1, GR_LOD_LOG2_128, TEX_BASE_ADDR_1),
            GR_TEXBASE_64 => (2, GR_LOD_LOG2_64, TEX_BASE_ADDR_2),
            _ => (3, GR_LOD_LOG2_32, TEX_BASE_ADDR_3_8),
        };
        let base = base_address(start, hw_lod(lod), info.aspect, info.format, even_odd) >> 3;
        self.tmu_write(tmu, &[(reg, base)]);
        self.st.tmu[tmu].tex_base_addr[slot] = base;
    }

    /// `grTexNCCTable`: select NCC table 0 or 1 on every TMU.
    pub(crate) fn tex_ncc_table(&mut self, table: u32) {
        for t in 0..self.st.tmu.len() {
            let m = TextureMode(self.st.tmu[t].texture_mode)
                .with_tnccselect(table != 0)
                .0;
            self.tmu_write(t, &[(TEXTURE_MODE, m)]);
            self.st.tmu[t].texture_mode = m;
        }
    }

    /// `grTexDownloadMipMapLevelPartial`: rows `t..=max_t` of one level.
    /// `data` holds the level's texels (1 or 2 bytes each, row-major).
    pub(crate) fn tex_download_level_partial(
        &mut self,
        tmu: usize,
        start: u32,
        this_lod: u32,
        large_lod: u32,
        aspect: i32,
        format: u32,
        even_odd: u32,
        data: &[u8],
        t: u32,
        max_t: u32,
    ) {
        let this_hw = hw_lod(this_lod);
        let large_hw = hw_lod(large_lod);
        let level_mask = if this_hw & 1 == 1 {
            GR_MIPMAPLEVELMASK_ODD
        } else {
            GR_MIPMAPLEVELMASK_EVEN
        };
        if even_odd & level_mask == 0 {
            return;
        }
        let (width, _) = level_wh(this_lod, aspect);
        let wide = format >= GR_TEXFMT_16BIT;
        let base = base_address(start, large_hw, aspect, format, even_odd) >> 3;
        let lod_base = TEX_BASE + ((tmu as u32) << 21) + (this_hw << 17);
        let l = with_lod_minmax(TLod::default(), large_hw, 8);
        let l = with_aspect(with_even_odd(l, even_odd), aspect).0;
        let seq8 = TextureMode(self.st.tmu[tmu].texture_mode).seq_8_downld();
        let m = TextureMode::default()
            .with_format(TextureFormat::from_bits(format))
            .with_seq_8_downld(seq8)
            .0;
        self.tmu_write(tmu, &[(TEX_BASE_ADDR, base), (TEXTURE_MODE, m), (T_LOD, l)]);

        let word = |i: usize| -> u32 {
            let mut b = [0u8; 4];
            for (k, x) in b.iter_mut().enumerate() {
                *x = data.get(i + k).copied().unwrap_or(0);
            }
            u32::from_le_bytes(b)
        };
        let bytes_per_row = (width as usize) * if wide { 2 } else { 1 };
        let mut src = 0usize;
        for row in t..=max_t.min(255) {
            let row_addr = lod_base + (row << 9);
            match (wide, width) {
                (false, 1) => self
                    .hw
                    .w(row_addr, u32::from(data.get(src).copied().unwrap_or(0))),
                (false, 2) | (true, 1) => self.hw.w(row_addr, word(src) & 0xffff),
                (false, 4) | (true, 2) => self.hw.w(row_addr, word(src)),
                _ => {
                    // Old TMUs (no sequential 8-bit download) space 8-bit pairs 8 bytes apart.
                    let stride = if !wide && !seq8 { 16 } else { 8 };
                    let second = if !wide && !seq8 { 8 } else { 4 };
                    let mut addr = row_addr;
                    let mut s = 0;
                    while s + 8 <= bytes_per_row {
                        self.hw.w(addr, word(src + s));
                        self.hw.w(addr + second, word(src + s + 4));
                        addr += stride;
                        s += 8;
                    }
                }
            }
            src += bytes_per_row;
        }
        let c = self.st.tmu[tmu];
        self.tmu_write(
            tmu,
            &[
                (TEX_BASE_ADDR, c.tex_base_addr[0]),
                (TEXTURE_MODE, c.texture_mode),
                (T_LOD, c.t_lod),
            ],
        );
    }

    /// `grTexDownloadMipMap`: every level from large to small; `data` holds all
    /// levels back to back.
    pub(crate) fn tex_download_mipmap_hw(
        &mut self,
        tmu: usize,
        start: u32,
        even_odd: u32,
        info: &TexInfo,
        data: &[u8],
    ) {
        let texel = if info.format >= GR_TEXFMT_16BIT { 2 } else { 1 };
        let mut off = 0usize;
        let mut lod = info.large_lod.min(8);
        loop {
            if lod < info.small_lod {
                break;
            }
            let (w, h) = level_wh(lod, info.aspect);
            let size = (w * h) as usize * texel;
            let level = data.get(off..).unwrap_or(&[]);
            self.tex_download_level_partial(
                tmu,
                start,
                lod,
                info.large_lod,
                info.aspect,
                info.format,
                even_odd,
                level,
                0,
                h - 1,
            );
            off += size;
            if lod == 0 {
                break;
            }
            lod -= 1;
        }
    }

    /// `_grTexDownloadNccTable`: 12 packed words into `nccTable0` or `nccTable1`.
    pub(crate) fn tex_download_ncc(&mut self, tmu: usize, which: u32, packed: &[u32; 12]) {
        let base = if which == 0 { NCC_TABLE0 } else { NCC_TABLE1 };
        let regs: Vec<(u32, u32)> = (0..12).map(|i| (base + 4 * i as u32, packed[i])).collect();
        self.tmu_write(tmu, &regs);
    }

    /// `_grTexDownloadPalette`: entries `start..=end` through the NCC table 0
    /// I/Q registers (bit 31 set selects palette writes).
    pub(crate) fn tex_download_palette(
        &mut self,
        tmu: usize,
        pal: &[u32; 256],
        start: usize,
        end: usize,
    ) {
        let regs: Vec<(u32, u32)> = (start..=end.min(255))
            .map(|i| {
                let reg = NCC_TABLE0 + 4 * (4 + (i as u32 & 7));
                (
                    reg,
                    0x8000_0000 | (((i as u32) & 0xfe) << 23) | (pal[i] & 0xff_ffff),
                )
            })
            .collect();
        self.tmu_write(tmu, &regs);
    }
}

/// The combine-unit bits `[zero_other, sub_clocal, add_clocal, add_alocal]` of a
/// `GR_COMBINE_FUNCTION_*`, and whether it uses the local colour (it subtracts or adds it).
fn combine_bits(f: u32) -> ([bool; 4], bool) {
    let bits = crate::state::combine_function_bits(f);
    (bits, !matches!(bits, [_, false, false, false]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn memory_sizes_match_glide() {
        // 256x256 16-bit, all levels: (0x10000+0x4000+...+4+4) texels * 2, rounded.
        let full = mem_required(
            GR_LOD_LOG2_1,
            GR_LOD_LOG2_256,
            0,
            GR_TEXFMT_RGB_565,
            GR_MIPMAPLEVELMASK_BOTH,
        );
        assert_eq!(full, 0x15558 * 2);
        // One 8x8 8-bit level: 0x40 texels.
        assert_eq!(
            mem_required(
                GR_LOD_LOG2_8,
                GR_LOD_LOG2_8,
                0,
                GR_TEXFMT_ALPHA_8,
                GR_MIPMAPLEVELMASK_BOTH
            ),
            0x40
        );
        assert_eq!(level_wh(GR_LOD_LOG2_256, -3), (32, 256));
        assert_eq!(level_wh(GR_LOD_LOG2_2, 3), (2, 1));
    }

    #[test]
    fn base_address_backs_up_to_lod0() {
        // A 128x128 16-bit texture at 0: base = 0 - 0x10000*2 (wrapping), as Glide.
        assert_eq!(
            base_address(0x20000, 1, 0, GR_TEXFMT_RGB_565, GR_MIPMAPLEVELMASK_BOTH),
            0
        );
    }
}

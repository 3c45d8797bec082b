//! Glide rendering state and its translation into FBI registers.
//!
//! Spec section 5 (`fbzColorPath`, `fbzMode`, `alphaMode`, `fogMode`, `zaColor`,
//! `chromaKey`, `clipLeftRight`, `clipLowYHighY`, `color0/1`, `fogColor`, `lfbMode`).
//!
//! Like 3dfx's SST-1 Glide 3, state calls only record their arguments and mark a
//! register group dirty; the group is recomputed and written, in a fixed order, the
//! next time a primitive, buffer clear or state save needs it. The bit composition of
//! each call and the validation order follow 3dfx's SST-1 Glide 3 (gglide.c,
//! distate.c), so the register stream matches the glide-sdk traces.

use crate::consts::*;
use sst1_regs::addr::*;
use sst1_regs::{
    AlphaLocalSelect, AlphaMode, AlphaSelect, BlendFactor, CcMselect, ClipLeftRight, ClipLowYHighY,
    ColorBuffer, CompareFunction, FbzColorPath, FbzMode, FogMode, FogZa, LfbMode, RgbSelect,
    RgbaLanes, ZaColor,
};

/// Register groups that can be dirty.
pub(crate) mod dirty {
    pub const ALPHA_MODE: u32 = 1 << 0;
    pub const FBZ_COLOR_PATH: u32 = 1 << 1;
    pub const FBZ_MODE: u32 = 1 << 2;
    pub const CHROMA_KEY: u32 = 1 << 3;
    pub const CLIP: u32 = 1 << 4;
    pub const ZA_COLOR: u32 = 1 << 5;
    pub const FOG_MODE: u32 = 1 << 6;
    pub const FOG_COLOR: u32 = 1 << 7;
    pub const LFB_MODE: u32 = 1 << 8;
    pub const C0C1: u32 = 1 << 9;
}

/// The shadow of the FBI rendering registers Glide owns.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FbiConfig {
    /// `fbzColorPath`.
    pub fbz_color_path: u32,
    /// `fogMode`.
    pub fog_mode: u32,
    /// `alphaMode`.
    pub alpha_mode: u32,
    /// `fbzMode`.
    pub fbz_mode: u32,
    /// `lfbMode`.
    pub lfb_mode: u32,
    /// `clipLeftRight`.
    pub clip_left_right: u32,
    /// `clipLowYHighY`.
    pub clip_bottom_top: u32,
    /// `fogColor`.
    pub fog_color: u32,
    /// `zaColor`.
    pub za_color: u32,
    /// `chromaKey`.
    pub chroma_key: u32,
    /// `stipple`.
    pub stipple: u32,
    /// `color0`.
    pub color0: u32,
    /// `color1`.
    pub color1: u32,
}

/// The shadow of one TMU's registers plus the texture it samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TmuConfig {
    /// `textureMode`.
    pub texture_mode: u32,
    /// `tLOD`.
    pub t_lod: u32,
    /// `tDetail`.
    pub t_detail: u32,
    /// `texBaseAddr`, `texBaseAddr1`, `texBaseAddr2`, `texBaseAddr38`.
    pub tex_base_addr: [u32; 4],
    /// Current `GR_MIPMAP_*` mode.
    pub mm_mode: u32,
    /// Smallest LOD of the current texture, hardware numbering (0 = 256).
    pub small_lod: u32,
    /// Largest LOD of the current texture, hardware numbering (0 = 256).
    pub large_lod: u32,
    /// `GR_MIPMAPLEVELMASK_*` of the current texture.
    pub even_odd: u32,
    /// S and T scale for clip-coordinate texture coordinates.
    pub st_scale: [f32; 2],
}

impl TmuConfig {
    pub(crate) fn new(texture_mode: u32) -> Self {
        Self {
            texture_mode,
            t_lod: 0,
            t_detail: 0,
            tex_base_addr: [0; 4],
            mm_mode: GR_MIPMAP_NEAREST,
            small_lod: 8,
            large_lod: 8,
            even_odd: GR_MIPMAPLEVELMASK_BOTH,
            st_scale: [256.0, 256.0],
        }
    }
}

/// Arguments of one combine-unit call (`grColorCombine` / `grAlphaCombine`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Combine {
    pub function: u32,
    pub factor: u32,
    pub local: u32,
    pub other: u32,
    pub invert: bool,
}

/// The recorded arguments of the lazily applied state calls.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Args {
    pub blend: [u32; 4],
    pub alpha_test_fn: u32,
    pub alpha_ref: u8,
    pub alpha_combine: Combine,
    pub alpha_controls_itrgb: bool,
    pub color_combine: Combine,
    pub chromakey_mode: u32,
    pub depth_mask: bool,
    pub depth_fn: u32,
    pub depth_mode: u32,
    pub dither: u32,
    pub render_buffer: u32,
    pub color_mask: (bool, bool),
    pub origin: u32,
    pub chroma_color: u32,
    pub chroma_range: u32,
    pub chroma_range_mode: u32,
    pub clip: [u32; 4],
    pub depth_bias: i32,
    pub fog_mode: u32,
    pub fog_color: u32,
    pub lfb_format: u32,
    pub lfb_swizzle: (bool, bool),
    pub constant_color: u32,
}

/// Everything `grGlideGetState` saves.
#[derive(Clone, Debug, PartialEq)]
pub struct GlideState {
    /// FBI register shadow.
    pub fbi: FbiConfig,
    /// Per-TMU shadow.
    pub tmu: Vec<TmuConfig>,
    pub(crate) args: Args,
    pub(crate) invalid: u32,
    pub(crate) cull_mode: u32,
    pub(crate) cc_requires_it_rgb: bool,
    pub(crate) cc_requires_texture: bool,
    pub(crate) ac_requires_it_alpha: bool,
    pub(crate) ac_requires_texture: bool,
    pub(crate) tmu_mask: u32,
    pub(crate) color_format: u32,
    pub(crate) num_buffers: u32,
    pub(crate) allow_lod_dither: bool,
    pub(crate) smooth_mode: u32,
    pub(crate) coordinate_space: u32,
    pub(crate) viewport: Viewport,
    pub(crate) lfb_constant_alpha: u8,
    pub(crate) lfb_constant_depth: u32,
    pub(crate) screen_width: u32,
    pub(crate) screen_height: u32,
}

/// `grViewport` / `grDepthRange` derived values.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Viewport {
    pub ox: f32,
    pub oy: f32,
    pub oz: f32,
    pub hwidth: f32,
    pub hheight: f32,
    pub hdepth: f32,
}

/// Swap channels of a `GrColor_t` from the application's `GR_COLORFORMAT_*` into the
/// chip's ARGB.
pub(crate) fn swizzle(color: u32, format: u32) -> u32 {
    match format {
        GR_COLORFORMAT_ABGR => {
            (color & 0xff00_ff00) | ((color & 0xff) << 16) | ((color >> 16) & 0xff)
        }
        GR_COLORFORMAT_RGBA | GR_COLORFORMAT_BGRA => {
            let (a, x, y, z) = (
                color & 0xff,
                (color >> 8) & 0xff,
                (color >> 16) & 0xff,
                color >> 24,
            );
            if format == GR_COLORFORMAT_RGBA {
                // RGBA: R in 31:24, G 23:16, B 15:8.
                (a << 24) | (z << 16) | (y << 8) | x
            } else {
                // BGRA: B in 31:24, G 23:16, R 15:8.
                (a << 24) | (x << 16) | (y << 8) | z
            }
        }
        _ => color,
    }
}

impl GlideState {
    pub(crate) fn new(tmus: usize, tex_mode: u32) -> Self {
        Self {
            fbi: FbiConfig::default(),
            tmu: vec![TmuConfig::new(tex_mode); tmus],
            args: Args::default(),
            invalid: 0,
            cull_mode: GR_CULL_DISABLE,
            cc_requires_it_rgb: false,
            cc_requires_texture: false,
            ac_requires_it_alpha: false,
            ac_requires_texture: false,
            tmu_mask: 0,
            color_format: GR_COLORFORMAT_ARGB,
            num_buffers: 2,
            allow_lod_dither: false,
            smooth_mode: 0,
            coordinate_space: GR_WINDOW_COORDS,
            viewport: Viewport::default(),
            lfb_constant_alpha: 0xff,
            lfb_constant_depth: 0,
            screen_width: 640,
            screen_height: 480,
        }
    }

    fn blend(&mut self) {
        let [rgb_sf, rgb_df, mut a_sf, mut a_df] = self.args.blend;
        if a_sf != GR_BLEND_ONE && a_sf != GR_BLEND_ZERO {
            a_sf = GR_BLEND_ONE;
        }
        if a_df != GR_BLEND_ONE && a_df != GR_BLEND_ZERO {
            a_df = GR_BLEND_ZERO;
        }
        let blend = !(rgb_sf == GR_BLEND_ONE
            && rgb_df == GR_BLEND_ZERO
            && a_sf == GR_BLEND_ONE
            && a_df == GR_BLEND_ZERO);
        let f = self.args.alpha_test_fn;
        let test = f != GR_CMP_ALWAYS;
        // GR_BLEND_* and GR_CMP_* are the hardware encodings.
        let m = AlphaMode(self.fbi.alpha_mode)
            .with_alpha_blend_enable(blend)
            .with_src_rgb_blend(BlendFactor::from_bits(rgb_sf))
            .with_dst_rgb_blend(BlendFactor::from_bits(rgb_df))
            .with_src_alpha_blend(BlendFactor::from_bits(a_sf))
            .with_dst_alpha_blend(BlendFactor::from_bits(a_df))
            .with_alpha_test_enable(test)
            .with_alpha_function(if test {
                CompareFunction::from_bits(f)
            } else {
                CompareFunction::Never
            })
            .with_alpha_ref(self.args.alpha_ref);
        self.fbi.alpha_mode = m.0;
    }

    /// Returns whether texture mapping was switched on or off (Glide then issues a NOP).
    fn alpha_combine(&mut self) -> bool {
        let c = self.args.alpha_combine;
        let old = FbzColorPath(self.fbi.fbz_color_path);
        let factor = c.factor & 0x7;
        self.ac_requires_texture =
            factor == GR_COMBINE_FACTOR_TEXTURE_ALPHA || c.other == GR_COMBINE_OTHER_TEXTURE;
        self.ac_requires_it_alpha =
            c.local == GR_COMBINE_LOCAL_ITERATED || c.other == GR_COMBINE_OTHER_ITERATED;
        // The alpha unit adds its local alpha for both "add local" kinds.
        let [zero, sub, add_c, add_a] = combine_function_bits(c.function);
        // Every alpha-combine field and the texture enable is set here.
        let p = old
            .with_cc_aselect(AlphaSelect::from_bits(c.other))
            .with_cca_localselect(AlphaLocalSelect::from_bits(c.local))
            .with_cca_zero_other(zero)
            .with_cca_sub_clocal(sub)
            .with_cca_mselect(CcMselect::from_bits(factor))
            .with_cca_reverse_blend(c.factor & 0x8 == 0)
            .with_cca_add_clocal(false)
            .with_cca_add_alocal(add_c || add_a)
            .with_cca_invert_output(c.invert)
            .with_texture_enable(self.cc_requires_texture || self.ac_requires_texture);
        self.fbi.fbz_color_path = p.0;
        old.texture_enable() != p.texture_enable()
    }

    fn color_combine(&mut self) -> bool {
        let c = self.args.color_combine;
        let old = FbzColorPath(self.fbi.fbz_color_path);
        let factor = c.factor & 0x7;
        self.cc_requires_texture =
            factor == GR_COMBINE_FACTOR_TEXTURE_ALPHA || c.other == GR_COMBINE_OTHER_TEXTURE;
        self.cc_requires_it_rgb =
            c.local == GR_COMBINE_LOCAL_ITERATED || c.other == GR_COMBINE_OTHER_ITERATED;
        let [zero, sub, add_c, add_a] = combine_function_bits(c.function);
        // Every colour-combine field and the texture enable is set here.
        let p = old
            .with_cc_rgbselect(RgbSelect::from_bits(c.other))
            .with_cc_localselect(c.local & 1 != 0)
            .with_cc_zero_other(zero)
            .with_cc_sub_clocal(sub)
            .with_cc_mselect(CcMselect::from_bits(factor))
            .with_cc_reverse_blend(c.factor & 0x8 == 0)
            .with_cc_add_clocal(add_c)
            .with_cc_add_alocal(add_a)
            .with_cc_invert_output(c.invert)
            .with_param_adjust(true)
            .with_texture_enable(self.cc_requires_texture || self.ac_requires_texture);
        self.fbi.fbz_color_path = p.0;
        old.texture_enable() != p.texture_enable()
    }

    fn fbz_mode(&mut self) {
        let a = self.args;
        // [enable_depthbuffer, wbuffer_select, enable_depth_bias, depth_source_compare]
        let [depth, w, bias, compare] = match a.depth_mode {
            GR_DEPTHBUFFER_ZBUFFER => [true, false, true, false],
            GR_DEPTHBUFFER_WBUFFER => [true, true, true, false],
            GR_DEPTHBUFFER_ZBUFFER_COMPARE_TO_BIAS => [true, false, false, true],
            GR_DEPTHBUFFER_WBUFFER_COMPARE_TO_BIAS => [true, true, false, true],
            _ => [false; 4],
        };
        // [enable_dithering, dither_2x2, dither_subtract]
        let [dither, dither_2x2, subtract] = match a.dither {
            GR_DITHER_2x2 => [true, true, false],
            GR_DITHER_4x4 => [true, false, true],
            _ => [false; 3],
        };
        let (rgb, alpha) = a.color_mask;
        let mut m = FbzMode(self.fbi.fbz_mode)
            .with_enable_chromakey(a.chromakey_mode == GR_CHROMAKEY_ENABLE)
            .with_aux_buffer_mask(a.depth_mask)
            .with_depth_function(CompareFunction::from_bits(a.depth_fn))
            .with_enable_depthbuffer(depth)
            .with_wbuffer_select(w)
            .with_enable_depth_bias(bias)
            .with_depth_source_compare(compare)
            .with_enable_dithering(dither)
            .with_dither_2x2(dither_2x2)
            .with_dither_subtract(subtract)
            .with_draw_buffer(if a.render_buffer != GR_BUFFER_FRONTBUFFER {
                ColorBuffer::Back
            } else {
                ColorBuffer::Front
            })
            .with_rgb_buffer_mask(rgb);
        if !m.enable_depthbuffer() && self.num_buffers != 3 {
            m = m
                .with_enable_alpha_planes(alpha)
                .with_aux_buffer_mask(alpha);
        }
        self.fbi.fbz_mode = m.with_y_origin(a.origin == GR_ORIGIN_LOWER_LEFT).0;
    }

    /// The `clipLeftRight` / `clipLowYHighY` values for a window, clamped to the screen.
    pub(crate) fn clip_regs(&self, minx: u32, miny: u32, maxx: u32, maxy: u32) -> (u32, u32) {
        let maxx = maxx.min(self.screen_width);
        let maxy = maxy.min(self.screen_height);
        let minx = minx.min(maxx);
        let miny = miny.min(maxy);
        // Screen sizes stay below 1024, inside the 10-bit fields.
        let lr = ClipLeftRight::default()
            .with_clip_left(minx)
            .with_clip_right(maxx);
        let bt = ClipLowYHighY::default()
            .with_clip_lowy(miny)
            .with_clip_highy(maxy);
        (lr.0, bt.0)
    }
}

impl crate::Glide {
    /// `_grValidateState`: recompute and write every dirty register group.
    pub(crate) fn validate(&mut self) {
        let inv = self.st.invalid;
        if inv & dirty::ALPHA_MODE != 0 {
            self.st.blend();
            self.hw.w(ALPHA_MODE, self.st.fbi.alpha_mode);
        }
        if inv & dirty::FBZ_COLOR_PATH != 0 {
            if self.st.alpha_combine() {
                self.hw.w(NOP_CMD, 0);
            }
            self.st.fbi.fbz_color_path = FbzColorPath(self.st.fbi.fbz_color_path)
                .with_cc_localselect_override(self.st.args.alpha_controls_itrgb)
                .0;
            if self.st.color_combine() {
                self.hw.w(NOP_CMD, 0);
            }
            self.hw.w(FBZ_COLOR_PATH, self.st.fbi.fbz_color_path);
        }
        if inv & dirty::FBZ_MODE != 0 {
            self.st.fbz_mode();
            self.hw.w(FBZ_MODE, self.st.fbi.fbz_mode);
        }
        if inv & dirty::CHROMA_KEY != 0 {
            self.st.fbi.chroma_key = swizzle(self.st.args.chroma_color, self.st.color_format);
            self.hw.w(CHROMA_KEY, self.st.fbi.chroma_key);
        }
        if inv & dirty::CLIP != 0 {
            let [a, b, c, d] = self.st.args.clip;
            let (lr, bt) = self.st.clip_regs(a, b, c, d);
            self.st.fbi.clip_left_right = lr;
            self.st.fbi.clip_bottom_top = bt;
            self.hw.w(CLIP_LEFT_RIGHT, lr);
            self.hw.w(CLIP_LOW_Y_HIGH_Y, bt);
        }
        if inv & dirty::ZA_COLOR != 0 {
            let level = (self.st.args.depth_bias as i16) as u16;
            self.st.fbi.za_color = ZaColor(self.st.fbi.za_color).with_constant_depth(level).0;
            self.hw.w(ZA_COLOR, self.st.fbi.za_color);
        }
        if inv & dirty::FOG_MODE != 0 {
            let mode = self.st.args.fog_mode;
            let (enable, za) = match mode & 0xff {
                GR_FOG_WITH_ITERATED_ALPHA_EXT => (true, FogZa::IteratedAlpha),
                GR_FOG_WITH_ITERATED_Z => (true, FogZa::IteratedZ),
                GR_FOG_WITH_TABLE_ON_W => (true, FogZa::FogTable),
                _ => (false, FogZa::FogTable),
            };
            let f = FogMode(self.st.fbi.fog_mode)
                .with_enable_fog(enable)
                .with_fog_za(za)
                .with_fog_constant(false)
                .with_fog_mult(mode & GR_FOG_MULT2 != 0)
                .with_fog_add(mode & GR_FOG_ADD2 != 0)
                .0;
            self.st.fbi.fog_mode = f;
            self.hw.w(FOG_MODE, f);
        }
        if inv & dirty::FOG_COLOR != 0 {
            self.st.fbi.fog_color = swizzle(self.st.args.fog_color, self.st.color_format);
            self.hw.w(FOG_COLOR, self.st.fbi.fog_color);
        }
        if inv & dirty::LFB_MODE != 0 {
            // grLfbWriteColorFormat's GR_COLORFORMAT_* is the RGBA lane order.
            let l = LfbMode(self.st.fbi.lfb_mode)
                .with_rgba_lanes(RgbaLanes::from_bits(self.st.args.lfb_format));
            self.hw.w(LFB_MODE, l.0);
            let (bytes, words) = self.st.args.lfb_swizzle;
            let l = l
                .with_byte_swizzle_writes(bytes)
                .with_word_swap_writes(words);
            self.hw.w(LFB_MODE, l.0);
            self.st.fbi.lfb_mode = l.0;
        }
        if inv & dirty::C0C1 != 0 {
            let c = swizzle(self.st.args.constant_color, self.st.color_format);
            self.st.fbi.color0 = c;
            self.st.fbi.color1 = c;
            self.hw.w(COLOR0, c);
            self.hw.w(COLOR1, c);
        }
        self.update_param_index();
        self.st.invalid = 0;
    }

    /// Validate if anything is dirty (`GR_FLUSH_STATE`).
    pub(crate) fn flush_state(&mut self) {
        if self.st.invalid != 0 {
            self.validate();
        }
    }

    /// `grGlideSetState`'s register reload: every FBI state register, then each TMU's.
    pub(crate) fn write_all_state(&mut self) {
        let f = self.st.fbi;
        for (a, v) in [
            (FBZ_COLOR_PATH, f.fbz_color_path),
            (FOG_MODE, f.fog_mode),
            (ALPHA_MODE, f.alpha_mode),
            (FBZ_MODE, f.fbz_mode),
            (LFB_MODE, f.lfb_mode),
            (CLIP_LEFT_RIGHT, f.clip_left_right),
            (CLIP_LOW_Y_HIGH_Y, f.clip_bottom_top),
            (FOG_COLOR, f.fog_color),
            (ZA_COLOR, f.za_color),
            (CHROMA_KEY, f.chroma_key),
            (STIPPLE, f.stipple),
            (COLOR0, f.color0),
            (COLOR1, f.color1),
        ] {
            self.hw.w(a, v);
        }
        for t in 0..self.st.tmu.len() {
            let c = self.st.tmu[t];
            let chip = crate::hw::tmu_chip(t);
            self.hw.packer();
            for (a, v) in [
                (TEXTURE_MODE, c.texture_mode),
                (T_LOD, c.t_lod),
                (T_DETAIL, c.t_detail),
                (TEX_BASE_ADDR, c.tex_base_addr[0]),
                (TEX_BASE_ADDR_1, c.tex_base_addr[1]),
                (TEX_BASE_ADDR_2, c.tex_base_addr[2]),
                (TEX_BASE_ADDR_3_8, c.tex_base_addr[3]),
            ] {
                self.hw.w(chip | a, v);
            }
        }
        self.hw.packer();
        self.update_param_index();
    }
}

/// The `*_zero_other`, `*_sub_clocal`, `*_add_clocal` and `*_add_alocal` bits of a
/// `GR_COMBINE_FUNCTION_*`, in that order (gglide.c; the texture combine of gtex.c
/// uses the same table).
pub(crate) fn combine_function_bits(f: u32) -> [bool; 4] {
    const F: bool = false;
    const T: bool = true;
    match f {
        GR_COMBINE_FUNCTION_ZERO => [T, F, F, F],
        GR_COMBINE_FUNCTION_LOCAL => [T, F, T, F],
        GR_COMBINE_FUNCTION_LOCAL_ALPHA => [T, F, F, T],
        GR_COMBINE_FUNCTION_SCALE_OTHER_ADD_LOCAL => [F, F, T, F],
        GR_COMBINE_FUNCTION_SCALE_OTHER_ADD_LOCAL_ALPHA => [F, F, F, T],
        GR_COMBINE_FUNCTION_SCALE_OTHER_MINUS_LOCAL => [F, T, F, F],
        GR_COMBINE_FUNCTION_SCALE_OTHER_MINUS_LOCAL_ADD_LOCAL => [F, T, T, F],
        GR_COMBINE_FUNCTION_SCALE_OTHER_MINUS_LOCAL_ADD_LOCAL_ALPHA => [F, T, F, T],
        GR_COMBINE_FUNCTION_SCALE_MINUS_LOCAL_ADD_LOCAL => [T, T, T, F],
        GR_COMBINE_FUNCTION_SCALE_MINUS_LOCAL_ADD_LOCAL_ALPHA => [T, T, F, T],
        _ => [F; 4],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn swizzle_formats() {
        assert_eq!(swizzle(0x11223344, GR_COLORFORMAT_ARGB), 0x11223344);
        assert_eq!(swizzle(0x11223344, GR_COLORFORMAT_ABGR), 0x11443322);
        // RGBA 0xRRGGBBAA -> ARGB
        assert_eq!(swizzle(0x11223344, GR_COLORFORMAT_RGBA), 0x44112233);
        // BGRA 0xBBGGRRAA -> ARGB
        assert_eq!(swizzle(0x11223344, GR_COLORFORMAT_BGRA), 0x44332211);
    }
}

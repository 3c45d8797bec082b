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
use crate::hw::bits::*;
use sst1_regs::addr::*;

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
        let mut m = self.fbi.alpha_mode;
        if rgb_sf == GR_BLEND_ONE
            && rgb_df == GR_BLEND_ZERO
            && a_sf == GR_BLEND_ONE
            && a_df == GR_BLEND_ZERO
        {
            m &= !ENALPHABLEND;
        } else {
            m |= ENALPHABLEND;
        }
        m &= !BLEND_FACTORS;
        m |= (rgb_sf << RGBSRCFACT_SHIFT)
            | (rgb_df << RGBDSTFACT_SHIFT)
            | (a_sf << ASRCFACT_SHIFT)
            | (a_df << ADSTFACT_SHIFT);
        let f = self.args.alpha_test_fn;
        m &= !(ALPHAFUNC | ENALPHAFUNC);
        if f != GR_CMP_ALWAYS {
            m |= (f << ALPHAFUNC_SHIFT) | ENALPHAFUNC;
        }
        m = (m & !ALPHAREF) | (u32::from(self.args.alpha_ref) << ALPHAREF_SHIFT);
        self.fbi.alpha_mode = m;
    }

    /// Returns whether texture mapping was switched on or off (Glide then issues a NOP).
    fn alpha_combine(&mut self) -> bool {
        let c = self.args.alpha_combine;
        let mut p = self.fbi.fbz_color_path;
        let old_tex = p & ENTEXTUREMAP;
        p &= !CCA_FIELDS;
        if c.factor & 0x8 == 0 {
            p |= CCA_REVERSE_BLEND;
        }
        let factor = c.factor & 0x7;
        self.ac_requires_texture =
            factor == GR_COMBINE_FACTOR_TEXTURE_ALPHA || c.other == GR_COMBINE_OTHER_TEXTURE;
        self.ac_requires_it_alpha =
            c.local == GR_COMBINE_LOCAL_ITERATED || c.other == GR_COMBINE_OTHER_ITERATED;
        p |= factor << CCA_MSELECT_SHIFT;
        p |= (c.local & 3) << CC_ALOCALSELECT_SHIFT;
        p |= (c.other & 3) << 2;
        if c.invert {
            p |= CCA_INVERT_OUTPUT;
        }
        p |= match c.function {
            GR_COMBINE_FUNCTION_ZERO => CCA_ZERO_OTHER,
            GR_COMBINE_FUNCTION_LOCAL | GR_COMBINE_FUNCTION_LOCAL_ALPHA => {
                CCA_ZERO_OTHER | CCA_ADD_ALOCAL
            }
            GR_COMBINE_FUNCTION_SCALE_OTHER_ADD_LOCAL
            | GR_COMBINE_FUNCTION_SCALE_OTHER_ADD_LOCAL_ALPHA => CCA_ADD_ALOCAL,
            GR_COMBINE_FUNCTION_SCALE_OTHER_MINUS_LOCAL => CCA_SUB_CLOCAL,
            GR_COMBINE_FUNCTION_SCALE_OTHER_MINUS_LOCAL_ADD_LOCAL
            | GR_COMBINE_FUNCTION_SCALE_OTHER_MINUS_LOCAL_ADD_LOCAL_ALPHA => {
                CCA_SUB_CLOCAL | CCA_ADD_ALOCAL
            }
            GR_COMBINE_FUNCTION_SCALE_MINUS_LOCAL_ADD_LOCAL
            | GR_COMBINE_FUNCTION_SCALE_MINUS_LOCAL_ADD_LOCAL_ALPHA => {
                CCA_ZERO_OTHER | CCA_SUB_CLOCAL | CCA_ADD_ALOCAL
            }
            _ => 0,
        };
        if self.cc_requires_texture || self.ac_requires_texture {
            p |= ENTEXTUREMAP;
        }
        self.fbi.fbz_color_path = p;
        old_tex != p & ENTEXTUREMAP
    }

    fn color_combine(&mut self) -> bool {
        let c = self.args.color_combine;
        let mut p = self.fbi.fbz_color_path;
        let old_tex = p & ENTEXTUREMAP;
        p &= !CC_FIELDS;
        p |= PARMADJUST;
        if c.factor & 0x8 == 0 {
            p |= CC_REVERSE_BLEND;
        }
        let factor = c.factor & 0x7;
        self.cc_requires_texture =
            factor == GR_COMBINE_FACTOR_TEXTURE_ALPHA || c.other == GR_COMBINE_OTHER_TEXTURE;
        self.cc_requires_it_rgb =
            c.local == GR_COMBINE_LOCAL_ITERATED || c.other == GR_COMBINE_OTHER_ITERATED;
        p |= factor << CC_MSELECT_SHIFT;
        p |= (c.local & 1) << CC_LOCALSELECT_SHIFT;
        p |= c.other & 3;
        if c.invert {
            p |= CC_INVERT_OUTPUT;
        }
        p |= match c.function {
            GR_COMBINE_FUNCTION_ZERO => CC_ZERO_OTHER,
            GR_COMBINE_FUNCTION_LOCAL => CC_ZERO_OTHER | CC_ADD_CLOCAL,
            GR_COMBINE_FUNCTION_LOCAL_ALPHA => CC_ZERO_OTHER | CC_ADD_ALOCAL,
            GR_COMBINE_FUNCTION_SCALE_OTHER_ADD_LOCAL => CC_ADD_CLOCAL,
            GR_COMBINE_FUNCTION_SCALE_OTHER_ADD_LOCAL_ALPHA => CC_ADD_ALOCAL,
            GR_COMBINE_FUNCTION_SCALE_OTHER_MINUS_LOCAL => CC_SUB_CLOCAL,
            GR_COMBINE_FUNCTION_SCALE_OTHER_MINUS_LOCAL_ADD_LOCAL => CC_SUB_CLOCAL | CC_ADD_CLOCAL,
            GR_COMBINE_FUNCTION_SCALE_OTHER_MINUS_LOCAL_ADD_LOCAL_ALPHA => {
                CC_SUB_CLOCAL | CC_ADD_ALOCAL
            }
            GR_COMBINE_FUNCTION_SCALE_MINUS_LOCAL_ADD_LOCAL => {
                CC_ZERO_OTHER | CC_SUB_CLOCAL | CC_ADD_CLOCAL
            }
            GR_COMBINE_FUNCTION_SCALE_MINUS_LOCAL_ADD_LOCAL_ALPHA => {
                CC_ZERO_OTHER | CC_SUB_CLOCAL | CC_ADD_ALOCAL
            }
            _ => 0,
        };
        if self.cc_requires_texture || self.ac_requires_texture {
            p |= ENTEXTUREMAP;
        }
        self.fbi.fbz_color_path = p;
        old_tex != p & ENTEXTUREMAP
    }

    fn fbz_mode(&mut self) {
        let a = self.args;
        let mut m = self.fbi.fbz_mode;
        // chroma key
        if a.chromakey_mode == GR_CHROMAKEY_ENABLE {
            m |= ENCHROMAKEY;
        } else {
            m &= !ENCHROMAKEY;
        }
        // depth mask
        if a.depth_mask {
            m |= ZAWRMASK;
        } else {
            m &= !ZAWRMASK;
        }
        m = (m & !ZFUNC) | ((a.depth_fn << ZFUNC_SHIFT) & ZFUNC);
        m &= !(ENDEPTHBUFFER | WBUFFER | ENZBIAS | ZCOMPARE_TO_ZACOLOR);
        m |= match a.depth_mode {
            GR_DEPTHBUFFER_ZBUFFER => ENDEPTHBUFFER | ENZBIAS,
            GR_DEPTHBUFFER_WBUFFER => ENDEPTHBUFFER | WBUFFER | ENZBIAS,
            GR_DEPTHBUFFER_ZBUFFER_COMPARE_TO_BIAS => ENDEPTHBUFFER | ZCOMPARE_TO_ZACOLOR,
            GR_DEPTHBUFFER_WBUFFER_COMPARE_TO_BIAS => ENDEPTHBUFFER | WBUFFER | ZCOMPARE_TO_ZACOLOR,
            _ => 0,
        };
        m &= !(ENDITHER | DITHER2X2 | ENDITHERSUBTRACT);
        m |= match a.dither {
            GR_DITHER_2x2 => ENDITHER | DITHER2X2,
            GR_DITHER_4x4 => ENDITHER | ENDITHERSUBTRACT,
            _ => 0,
        };
        m &= !DRAWBUFFER;
        if a.render_buffer != GR_BUFFER_FRONTBUFFER {
            m |= DRAWBUFFER_BACK;
        }
        let (rgb, alpha) = a.color_mask;
        if rgb {
            m |= RGBWRMASK;
        } else {
            m &= !RGBWRMASK;
        }
        if m & ENDEPTHBUFFER == 0 && self.num_buffers != 3 {
            if alpha {
                m |= ENALPHABUFFER | ZAWRMASK;
            } else {
                m &= !(ENALPHABUFFER | ZAWRMASK);
            }
        }
        if a.origin == GR_ORIGIN_LOWER_LEFT {
            m |= YORIGIN;
        } else {
            m &= !YORIGIN;
        }
        self.fbi.fbz_mode = m;
    }

    /// The `clipLeftRight` / `clipLowYHighY` values for a window, clamped to the screen.
    pub(crate) fn clip_regs(&self, minx: u32, miny: u32, maxx: u32, maxy: u32) -> (u32, u32) {
        let maxx = maxx.min(self.screen_width);
        let maxy = maxy.min(self.screen_height);
        let minx = minx.min(maxx);
        let miny = miny.min(maxy);
        ((minx << 16) | maxx, (miny << 16) | maxy)
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
            let p = self.st.fbi.fbz_color_path;
            self.st.fbi.fbz_color_path = if self.st.args.alpha_controls_itrgb {
                p | LOCALSELECT_OVERRIDE_WITH_ATEX
            } else {
                p & !LOCALSELECT_OVERRIDE_WITH_ATEX
            };
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
            let level = (self.st.args.depth_bias as i16) as u16 as u32;
            self.st.fbi.za_color = (self.st.fbi.za_color & !0xffff) | level;
            self.hw.w(ZA_COLOR, self.st.fbi.za_color);
        }
        if inv & dirty::FOG_MODE != 0 {
            let mode = self.st.args.fog_mode;
            let mut f = self.st.fbi.fog_mode
                & !(ENFOGGING | FOGADD | FOGMULT | FOG_ALPHA | FOG_Z | FOG_CONSTANT);
            f |= match mode & 0xff {
                GR_FOG_WITH_ITERATED_ALPHA_EXT => ENFOGGING | FOG_ALPHA,
                GR_FOG_WITH_ITERATED_Z => ENFOGGING | FOG_Z,
                GR_FOG_WITH_TABLE_ON_W => ENFOGGING,
                _ => 0,
            };
            if mode & GR_FOG_MULT2 != 0 {
                f |= FOGMULT;
            }
            if mode & GR_FOG_ADD2 != 0 {
                f |= FOGADD;
            }
            self.st.fbi.fog_mode = f;
            self.hw.w(FOG_MODE, f);
        }
        if inv & dirty::FOG_COLOR != 0 {
            self.st.fbi.fog_color = swizzle(self.st.args.fog_color, self.st.color_format);
            self.hw.w(FOG_COLOR, self.st.fbi.fog_color);
        }
        if inv & dirty::LFB_MODE != 0 {
            let mut l = self.st.fbi.lfb_mode & !(3 << 9);
            l |= (self.st.args.lfb_format & 3) << 9;
            self.hw.w(LFB_MODE, l);
            l &= !(LFB_WRITE_SWAP16 | LFB_WRITE_BYTESWAP);
            let (bytes, words) = self.st.args.lfb_swizzle;
            if bytes {
                l |= LFB_WRITE_BYTESWAP;
            }
            if words {
                l |= LFB_WRITE_SWAP16;
            }
            self.hw.w(LFB_MODE, l);
            self.st.fbi.lfb_mode = l;
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

//! Glide 3 for the emulated SST-1 (Voodoo Graphics): API calls become register writes.
//!
//! The front-end implements the Glide 3.0 API (Glide 3.0 Programming Guide,
//! shared/seeds/001) on top of a [`RegisterBus`]: it never draws pixels, it writes the
//! SST-1 registers (spec sections 4-6) exactly as 3dfx's own Glide 3 for the SST-1
//! does, so a trace recorded from it can be compared write for write with the
//! glide-sdk traces. See the module docs for what each part reproduces:
//!
//! * [`init`]: board bring-up (`grGlideInit`, `grSstWinOpen` video set-up, gamma).
//! * [`state`]: lazily validated rendering state (combine, blend, depth, fog, ...).
//! * [`draw`]: vertex layout and triangle/line/point setup.
//! * [`tex`]: texture state, memory layout and downloads.
//! * [`lfb`]: frame-buffer locks and region copies.
//! * [`get`]: `grGet`/`grGetString` and the fog-table utilities.
//!
//! Bad arguments are reported through the error callback ([`Glide::set_error_callback`])
//! with a message naming the call, and leave the state unchanged.

// The Glide SDK spells some constants in mixed case (`GR_RESOLUTION_640x480`,
// `GR_REFRESH_60Hz`); we keep its spelling so they match the C headers and the guide.
#![allow(non_upper_case_globals)]

mod aa;
pub mod consts;
pub mod demo;
pub mod draw;
pub mod g3df;
pub mod get;
mod hw;
pub mod init;
pub mod lfb;
pub mod saved;
pub mod sst;
pub mod state;
pub mod tex;
pub mod video;
mod x87;

use consts::*;
pub use draw::VertexLayout;
pub use init::BoardInfo;
pub use lfb::LfbInfo;
pub use sst1_regs::RegisterBus;
pub use state::GlideState;
pub use tex::TexInfo;

use std::borrow::Cow;

use hw::Hw;
use init::{Init, InitState};
use sst1_regs::addr::*;
use sst1_regs::{ColorBuffer, FbzColorPath, FbzMode, TextureMode, ZaColor};
use state::{dirty, Combine};

/// Error callback: message and whether Glide considers it fatal.
pub type ErrorCallback = Box<dyn FnMut(&str, bool)>;

/// Primitive counters (`grGet(GR_STATS_*)`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Triangles submitted.
    pub triangles_in: u32,
    /// Triangles that reached the chip.
    pub triangles_drawn: u32,
    /// Lines drawn.
    pub lines: u32,
    /// Points drawn.
    pub points: u32,
}

/// What `grSstQueryHardware` reports for the one board.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HwConfig {
    /// Number of boards (always 1).
    pub num_sst: u32,
    /// FBI revision.
    pub fbi_rev: u32,
    /// Number of TMUs.
    pub num_tmu: u32,
    /// Frame-buffer memory in MiB.
    pub fb_ram: u32,
    /// TMU revision.
    pub tmu_rev: u32,
    /// Texture memory per TMU in MiB.
    pub tmu_ram: u32,
}

/// A Glide 3 context driving one SST-1 board through a [`RegisterBus`].
pub struct Glide {
    hw: Hw,
    board: BoardInfo,
    init: InitState,
    st: GlideState,
    layout: VertexLayout,
    param_index: u32,
    data_list: Vec<draw::Entry>,
    open: bool,
    /// 3dfx's `gc->closedP`: `grSstWinClose` shut the board down, so the next
    /// `grSstWinOpen` re-initialises it first.
    closed: bool,
    stats: Stats,
    swaps: u32,
    lfb_locks: [Option<u32>; 2],
    list_tail: draw::ListTail,
    error_cb: Option<ErrorCallback>,
    last_error: Option<String>,
    /// 3dfx's `gc->nopCMD`: `grSstIsBusy` has written a `nopCMD` not yet seen idle.
    nop_cmd_sent: bool,
    /// 3dfx's `gc->state.cc_delta0mode` (`guColorCombineFunction`'s `*_DELTA0` modes).
    cc_delta0: bool,
}

impl std::fmt::Debug for Glide {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Glide")
            .field("board", &self.board)
            .field("open", &self.open)
            .finish_non_exhaustive()
    }
}

fn tmu_index(tmu: u32) -> usize {
    tmu as usize
}

impl Glide {
    /// `grGlideInit`: map, reset and probe the board (writes the whole power-on
    /// sequence to `bus`).
    pub fn init(bus: Box<dyn RegisterBus>, board: BoardInfo) -> Self {
        let mut g = Self {
            hw: Hw::new(bus),
            board,
            init: InitState::new(),
            st: GlideState::new(board.tmus as usize, 0),
            layout: VertexLayout::default(),
            param_index: 0,
            data_list: Vec::new(),
            open: false,
            closed: false,
            stats: Stats::default(),
            swaps: 0,
            lfb_locks: [None; 2],
            list_tail: draw::ListTail::default(),
            nop_cmd_sent: false,
            cc_delta0: false,
            error_cb: None,
            last_error: None,
        };
        Init {
            hw: &mut g.hw,
            st: &mut g.init,
            board: &g.board,
        }
        .power_on();
        g
    }

    /// `grGlideShutdown`: close the window and give the bus back. An open context is
    /// closed as `grSstWinClose` closes it, close sequence and all: 3dfx's SST-1
    /// `grGlideShutdown` (glide3x/sst1/glide3/src/gglide.c) calls `grSstWinClose` for
    /// every board before `initClose`. (The glide-sdk captures end where
    /// `grGlideShutdown` is entered, so they show none of it.)
    pub fn shutdown(mut self) -> Box<dyn RegisterBus> {
        self.win_close();
        self.hw.into_bus()
    }

    /// `grErrorSetCallback`.
    pub fn set_error_callback(&mut self, cb: ErrorCallback) {
        self.error_cb = Some(cb);
    }

    /// The last error message reported (also given to the callback).
    pub fn last_error(&self) -> Option<&str> {
        self.last_error.as_deref()
    }

    /// Report an error through the callback (for front-end layers such as the C ABI).
    pub fn report_error(&mut self, msg: &str) {
        self.report(msg.to_string(), false);
    }

    pub(crate) fn report(&mut self, msg: String, fatal: bool) {
        if let Some(cb) = self.error_cb.as_mut() {
            cb(&msg, fatal);
        }
        self.last_error = Some(msg);
    }

    /// Report a bad argument; returns `true` when `bad`.
    fn check(&mut self, bad: bool, call: &str, what: &str) -> bool {
        if bad {
            self.report(format!("{call}: {what}"), false);
        }
        bad
    }

    fn check_tmu(&mut self, call: &str, tmu: u32) -> bool {
        let bad = tmu >= self.board.tmus;
        self.check(
            bad,
            call,
            &format!("invalid TMU {tmu} (board has {})", self.board.tmus),
        )
    }

    /// The probe results Glide is using.
    pub fn board(&self) -> BoardInfo {
        self.board
    }

    /// Primitive counters.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Number of `grBufferSwap` calls made.
    pub fn swap_count(&self) -> u32 {
        self.swaps
    }

    /// Screen size of the open window.
    pub fn screen_size(&self) -> (u32, u32) {
        (self.st.screen_width, self.st.screen_height)
    }

    /// Whether a window is open.
    pub fn is_open(&self) -> bool {
        self.open
    }

    /// `grSstQueryHardware` / `grSstQueryBoards`.
    pub fn query_hardware(&self) -> HwConfig {
        HwConfig {
            num_sst: 1,
            fbi_rev: self.board.fbi_revision,
            num_tmu: self.board.tmus,
            fb_ram: self.board.fbi_mb,
            tmu_rev: self.board.tmu_revision,
            tmu_ram: self.board.tmu_mb,
        }
    }

    /// `grQueryResolutions` for this board (see [`video::query_resolutions`]).
    pub fn query_resolutions(
        &self,
        resolution: Option<u32>,
        refresh: Option<u32>,
        color_buffers: Option<u32>,
        aux_buffers: Option<u32>,
    ) -> Vec<video::Resolution> {
        video::query_resolutions(
            self.board.fbi_mb,
            resolution,
            refresh,
            color_buffers,
            aux_buffers,
        )
    }

    /// `grReset`: clear counters or the vertex layout; false for other selectors.
    /// Source: diget.c. `GR_STATS_TRIANGLES` also clears the line count (3dfx's
    /// `_grResetTriStats`); `GR_STATS_PIXELS` writes `nopCMD` = 1, which clears the
    /// chip's pixel counters (spec 5.22); `GR_VERTEX_PARAMETER` disables
    /// every vertex parameter. UNVERIFIED: 3dfx also leaves its parameter list stale
    /// until the next `grVertexLayout`; we rebuild it at once.
    pub fn reset(&mut self, what: u32) -> bool {
        match what {
            GR_STATS_POINTS => self.stats.points = 0,
            GR_STATS_LINES => self.stats.lines = 0,
            GR_STATS_PIXELS => self.hw.w(NOP_CMD, 1),
            GR_STATS_TRIANGLES => {
                self.stats.lines = 0;
                self.stats.triangles_in = 0;
                self.stats.triangles_drawn = 0;
            }
            GR_VERTEX_PARAMETER => {
                self.layout = VertexLayout::default();
                self.update_param_index();
            }
            _ => return false,
        }
        true
    }

    /// `grSstSelect`: only board 0 exists.
    pub fn sst_select(&mut self, which: i32) {
        self.check(which != 0, "grSstSelect", "only board 0 exists");
    }

    /// `grSstWinOpen`: set the video mode, reset the rendering state to Glide's
    /// defaults and load them into the chip. False for modes the board cannot show.
    pub fn win_open(
        &mut self,
        resolution: u32,
        refresh: u32,
        color_format: u32,
        origin: u32,
        color_buffers: i32,
        aux_buffers: i32,
    ) -> bool {
        if self.open {
            self.report("grSstWinOpen: gc opened twice!".into(), false);
            return false;
        }
        // After grSstWinClose the board is mapped and initialised again, as
        // grGlideInit did, before the arguments are looked at (Source: sezero/glide
        // gsst.c grSstWinOpen, `closedP`; init.c initMapBoard).
        if self.closed {
            Init {
                hw: &mut self.hw,
                st: &mut self.init,
                board: &self.board,
            }
            .registers();
            self.closed = false;
        }
        let Some(mode) = video::find_mode(resolution, refresh) else {
            self.report(
                format!(
                    "grSstWinOpen: unsupported resolution {resolution:#x} / refresh {refresh:#x}"
                ),
                false,
            );
            return false;
        };
        if color_format > GR_COLORFORMAT_BGRA
            || !(2..=3).contains(&color_buffers)
            || !(0..=1).contains(&aux_buffers)
        {
            self.report(
                "grSstWinOpen: invalid color format or buffer count".into(),
                false,
            );
            return false;
        }
        let small = self.board.fbi_mb <= 2;
        if small
            && ((matches!(resolution, GR_RESOLUTION_800x600 | GR_RESOLUTION_856x480)
                && color_buffers + aux_buffers >= 3)
                || resolution == GR_RESOLUTION_960x720)
        {
            self.report(
                "grSstWinOpen: insufficient frame-buffer memory for this mode".into(),
                false,
            );
            return false;
        }
        Init {
            hw: &mut self.hw,
            st: &mut self.init,
            board: &self.board,
        }
        .video(&mode);
        self.open = true;

        // Texture download sequencing exists from TMU revision 1 on.
        let tex_mode = TextureMode::default()
            .with_seq_8_downld(self.board.tmu_revision != 0)
            .0;
        let mut st = GlideState::new(self.board.tmus as usize, tex_mode);
        st.screen_width = mode.timing.x_dimension;
        st.screen_height = mode.timing.y_dimension;
        st.num_buffers = color_buffers as u32;
        st.color_format = color_format;
        st.fbi.fbz_mode = FbzMode::default()
            .with_enable_clipping(true)
            .with_enable_depth_bias(true)
            .with_draw_buffer(ColorBuffer::Back)
            .0;
        self.st = st;
        self.lfb_locks = [None; 2];
        let (w, h) = (mode.timing.x_dimension, mode.timing.y_dimension);

        // The default state, in the order 3dfx's grSstWinOpen sets it.
        self.disable(GR_ALLOW_MIPMAP_DITHER);
        self.sst_origin(origin);
        self.alpha_blend_function(GR_BLEND_ONE, GR_BLEND_ZERO, GR_BLEND_ONE, GR_BLEND_ZERO);
        self.alpha_test_function(GR_CMP_ALWAYS);
        self.alpha_test_reference_value(0);
        self.chromakey_mode(GR_CHROMAKEY_DISABLE);
        self.constant_color_value(!0);
        self.clip_window(0, 0, w, h);
        self.color_combine(
            GR_COMBINE_FUNCTION_SCALE_OTHER,
            GR_COMBINE_FACTOR_ONE,
            GR_COMBINE_LOCAL_ITERATED,
            GR_COMBINE_OTHER_ITERATED,
            false,
        );
        self.alpha_combine(
            GR_COMBINE_FUNCTION_SCALE_OTHER,
            GR_COMBINE_FACTOR_ONE,
            GR_COMBINE_LOCAL_NONE,
            GR_COMBINE_OTHER_CONSTANT,
            false,
        );
        self.color_mask(true, false);
        self.cull_mode(GR_CULL_DISABLE);
        self.depth_bias_level(0);
        self.depth_mask(false);
        self.depth_buffer_mode(GR_DEPTHBUFFER_DISABLE);
        self.depth_buffer_function(GR_CMP_LESS);
        self.dither_mode(GR_DITHER_4x4);
        self.fog_mode(GR_FOG_DISABLE);
        self.fog_color_value(0);
        self.gamma_correction_rgb(1.7, 1.7, 1.7);
        self.coordinate_space(GR_WINDOW_COORDS);
        self.viewport(0, 0, w as i32, h as i32);
        self.render_buffer(GR_BUFFER_BACKBUFFER);
        for tmu in (0..self.board.tmus).rev() {
            self.tex_clamp_mode(tmu, GR_TEXTURECLAMP_CLAMP, GR_TEXTURECLAMP_CLAMP);
            self.tex_detail_control(tmu, 0, 1, 1.0);
            self.tex_filter_mode(
                tmu,
                GR_TEXTUREFILTER_POINT_SAMPLED,
                GR_TEXTUREFILTER_POINT_SAMPLED,
            );
            self.tex_lod_bias_value(tmu, 0.0);
            self.tex_mipmap_mode(tmu, GR_MIPMAP_DISABLE, false);
            self.tex_combine(
                tmu,
                GR_COMBINE_FUNCTION_ZERO,
                GR_COMBINE_FACTOR_NONE,
                GR_COMBINE_FUNCTION_ZERO,
                GR_COMBINE_FACTOR_NONE,
                false,
                false,
            );
        }
        self.lfb_constant_alpha(0xff);
        self.lfb_constant_depth(0);
        // grGlideGetState (validates) + grGlideSetState (reloads everything).
        let saved = self.get_state();
        self.set_state(&saved);
        // gsst.c grSstWinOpen: gc->nopCMD = FXFALSE.
        self.nop_cmd_sent = false;
        true
    }

    /// `grSstWinClose`: idle and shut the board down (video reset and blanked, a
    /// graphics-engine reset, the monitor back to the VGA, the graphics clock at
    /// 30 MHz); the next `grSstWinOpen` re-initialises it. False (and no writes) when
    /// no window is open. Source: sezero/glide gsst.c grSstWinClose.
    pub fn win_close(&mut self) -> bool {
        let was = self.open;
        if was {
            Init {
                hw: &mut self.hw,
                st: &mut self.init,
                board: &self.board,
            }
            .close();
            self.open = false;
            self.closed = true;
        }
        was
    }

    /// `grGlideGetState`: validate and copy the state.
    pub fn get_state(&mut self) -> GlideState {
        self.validate();
        self.st.clone()
    }

    /// `grGlideSetState`: restore a saved state and reload every state register.
    pub fn set_state(&mut self, state: &GlideState) {
        if state.tmu.len() != self.st.tmu.len() {
            self.report(
                "grGlideSetState: state saved for a different TMU count".into(),
                false,
            );
            return;
        }
        if FbzColorPath(self.st.fbi.fbz_color_path).texture_enable()
            != FbzColorPath(state.fbi.fbz_color_path).texture_enable()
        {
            self.hw.w(NOP_CMD, 0);
        }
        self.st = state.clone();
        self.write_all_state();
    }

    /// `grGlideGetVertexLayout`.
    pub fn get_vertex_layout(&self) -> VertexLayout {
        self.layout
    }

    /// `grGlideSetVertexLayout`.
    pub fn set_vertex_layout(&mut self, layout: &VertexLayout) {
        self.layout = *layout;
        self.update_param_index();
    }

    // ----- state calls (lazy) ---------------------------------------------------

    fn dirty(&mut self, bits: u32) {
        self.st.invalid |= bits;
    }

    /// `grAlphaBlendFunction`.
    pub fn alpha_blend_function(&mut self, rgb_sf: u32, rgb_df: u32, alpha_sf: u32, alpha_df: u32) {
        if self.check(
            [rgb_sf, rgb_df, alpha_sf, alpha_df]
                .iter()
                .any(|&f| f > GR_BLEND_ALPHA_SATURATE),
            "grAlphaBlendFunction",
            "blend factor out of range",
        ) {
            return;
        }
        self.dirty(dirty::ALPHA_MODE);
        self.st.args.blend = [rgb_sf, rgb_df, alpha_sf, alpha_df];
    }

    /// `grAlphaTestFunction`.
    pub fn alpha_test_function(&mut self, f: u32) {
        if self.check(
            f > GR_CMP_ALWAYS,
            "grAlphaTestFunction",
            "invalid compare function",
        ) {
            return;
        }
        self.dirty(dirty::ALPHA_MODE);
        self.st.args.alpha_test_fn = f;
    }

    /// `grAlphaTestReferenceValue`.
    pub fn alpha_test_reference_value(&mut self, v: u8) {
        self.dirty(dirty::ALPHA_MODE);
        self.st.args.alpha_ref = v;
    }

    fn combine_ok(&mut self, call: &str, c: &Combine, local_max: u32) -> bool {
        let bad = c.function > GR_COMBINE_FUNCTION_SCALE_MINUS_LOCAL_ADD_LOCAL_ALPHA
            || (c.function > GR_COMBINE_FUNCTION_SCALE_MINUS_LOCAL_ADD_LOCAL
                && c.function < GR_COMBINE_FUNCTION_SCALE_MINUS_LOCAL_ADD_LOCAL_ALPHA)
            || (c.factor & 7) > GR_COMBINE_FACTOR_TEXTURE_ALPHA
            || c.factor > GR_COMBINE_FACTOR_ONE_MINUS_TEXTURE_ALPHA
            || c.local > local_max
            || c.other > GR_COMBINE_OTHER_CONSTANT;
        !self.check(
            bad,
            call,
            "unsupported combine function, factor, local or other",
        )
    }

    /// `grColorCombine`.
    pub fn color_combine(
        &mut self,
        function: u32,
        factor: u32,
        local: u32,
        other: u32,
        invert: bool,
    ) {
        let c = Combine {
            function,
            factor,
            local,
            other,
            invert,
        };
        if self.combine_ok("grColorCombine", &c, GR_COMBINE_LOCAL_CONSTANT) {
            self.dirty(dirty::FBZ_COLOR_PATH);
            self.st.args.color_combine = c;
        }
    }

    /// `grAlphaCombine`.
    pub fn alpha_combine(
        &mut self,
        function: u32,
        factor: u32,
        local: u32,
        other: u32,
        invert: bool,
    ) {
        let c = Combine {
            function,
            factor,
            local,
            other,
            invert,
        };
        if self.combine_ok("grAlphaCombine", &c, GR_COMBINE_LOCAL_DEPTH) {
            self.dirty(dirty::FBZ_COLOR_PATH);
            self.st.args.alpha_combine = c;
        }
    }

    /// `grAlphaControlsITRGBLighting`.
    pub fn alpha_controls_itrgb_lighting(&mut self, enable: bool) {
        self.dirty(dirty::FBZ_COLOR_PATH);
        self.st.args.alpha_controls_itrgb = enable;
    }

    /// `grChromakeyMode`.
    pub fn chromakey_mode(&mut self, mode: u32) {
        if self.check(
            mode > GR_CHROMAKEY_ENABLE,
            "grChromakeyMode",
            "invalid mode",
        ) {
            return;
        }
        self.dirty(dirty::FBZ_MODE);
        self.st.args.chromakey_mode = mode;
    }

    /// `grChromakeyValue`.
    pub fn chromakey_value(&mut self, color: u32) {
        self.dirty(dirty::CHROMA_KEY);
        self.st.args.chroma_color = color;
    }

    /// `grChromaRangeExt` (the SST-1 has no range hardware; only the key colour is used).
    pub fn chroma_range(&mut self, color: u32, range: u32, mode: u32) {
        self.dirty(dirty::CHROMA_KEY);
        self.st.args.chroma_color = color;
        self.st.args.chroma_range = range;
        self.st.args.chroma_range_mode = mode;
    }

    /// `grDepthMask`.
    pub fn depth_mask(&mut self, enable: bool) {
        self.dirty(dirty::FBZ_MODE);
        self.st.args.depth_mask = enable;
    }

    /// `grDepthBufferFunction`.
    pub fn depth_buffer_function(&mut self, f: u32) {
        if self.check(
            f > GR_CMP_ALWAYS,
            "grDepthBufferFunction",
            "invalid compare function",
        ) {
            return;
        }
        self.dirty(dirty::FBZ_MODE);
        self.st.args.depth_fn = f;
    }

    /// `grDepthBufferMode`.
    pub fn depth_buffer_mode(&mut self, mode: u32) {
        if self.check(
            mode > GR_DEPTHBUFFER_WBUFFER_COMPARE_TO_BIAS,
            "grDepthBufferMode",
            "invalid depth buffer mode",
        ) {
            return;
        }
        self.dirty(dirty::FBZ_MODE);
        self.st.args.depth_mode = mode;
    }

    /// `grDitherMode`.
    pub fn dither_mode(&mut self, mode: u32) {
        if self.check(mode > GR_DITHER_4x4, "grDitherMode", "invalid dither mode") {
            return;
        }
        self.dirty(dirty::FBZ_MODE);
        self.st.args.dither = mode;
    }

    /// `grRenderBuffer`.
    pub fn render_buffer(&mut self, buffer: u32) {
        if self.check(
            buffer >= GR_BUFFER_AUXBUFFER,
            "grRenderBuffer",
            "invalid buffer",
        ) {
            return;
        }
        self.dirty(dirty::FBZ_MODE);
        self.st.args.render_buffer = buffer;
    }

    /// `grColorMask`.
    pub fn color_mask(&mut self, rgb: bool, alpha: bool) {
        self.dirty(dirty::FBZ_MODE);
        self.st.args.color_mask = (rgb, alpha);
    }

    /// `grSstOrigin`.
    pub fn sst_origin(&mut self, origin: u32) {
        if self.check(
            origin > GR_ORIGIN_LOWER_LEFT,
            "grSstOrigin",
            "invalid origin",
        ) {
            return;
        }
        self.dirty(dirty::FBZ_MODE);
        self.st.args.origin = origin;
    }

    /// `grClipWindow`.
    pub fn clip_window(&mut self, minx: u32, miny: u32, maxx: u32, maxy: u32) {
        self.dirty(dirty::CLIP);
        self.st.args.clip = [minx, miny, maxx, maxy];
    }

    /// `grDepthBiasLevel`.
    pub fn depth_bias_level(&mut self, level: i32) {
        self.dirty(dirty::ZA_COLOR);
        self.st.args.depth_bias = level;
    }

    /// `grFogMode`.
    pub fn fog_mode(&mut self, mode: u32) {
        if self.check(
            (mode & 0xff) > GR_FOG_WITH_ITERATED_ALPHA_EXT || mode & !0x3ff != 0,
            "grFogMode",
            "invalid fog mode",
        ) {
            return;
        }
        self.dirty(dirty::FOG_MODE);
        self.st.args.fog_mode = mode;
    }

    /// `grFogColorValue`.
    pub fn fog_color_value(&mut self, color: u32) {
        self.dirty(dirty::FOG_COLOR);
        self.st.args.fog_color = color;
    }

    /// `grFogTable`: 64 entries into the 32 `fogTable` registers, each holding two
    /// entries and their deltas (".2" fixed point, 8 bits).
    pub fn fog_table(&mut self, table: &[u8; 64]) {
        for i in 0..32usize {
            let e0 = table[2 * i];
            let e1 = table[2 * i + 1];
            let next = if i == 31 { e1 } else { table[2 * i + 2] };
            let d0 = e1.wrapping_sub(e0).wrapping_shl(2);
            let d1 = next.wrapping_sub(e1).wrapping_shl(2);
            let v = (u32::from(e1) << 24)
                | (u32::from(d1) << 16)
                | (u32::from(e0) << 8)
                | u32::from(d0);
            self.hw.w(FOG_TABLE + 4 * i as u32, v);
        }
    }

    /// `grLfbWriteColorFormat`.
    pub fn lfb_write_color_format(&mut self, format: u32) {
        if self.check(
            format > GR_COLORFORMAT_BGRA,
            "grLfbWriteColorFormat",
            "invalid color format",
        ) {
            return;
        }
        self.dirty(dirty::LFB_MODE);
        self.st.args.lfb_format = format;
    }

    /// `grLfbWriteColorSwizzle`.
    pub fn lfb_write_color_swizzle(&mut self, swizzle_bytes: bool, swap_words: bool) {
        self.dirty(dirty::LFB_MODE);
        self.st.args.lfb_swizzle = (swizzle_bytes, swap_words);
    }

    /// `grConstantColorValue`.
    pub fn constant_color_value(&mut self, color: u32) {
        self.dirty(dirty::C0C1);
        self.st.args.constant_color = color;
    }

    /// `grCullMode`.
    pub fn cull_mode(&mut self, mode: u32) {
        if self.check(mode > GR_CULL_POSITIVE, "grCullMode", "invalid cull mode") {
            return;
        }
        self.st.cull_mode = mode;
    }

    /// `grDisableAllEffects`.
    pub fn disable_all_effects(&mut self) {
        self.alpha_blend_function(GR_BLEND_ONE, GR_BLEND_ZERO, GR_BLEND_ONE, GR_BLEND_ZERO);
        self.alpha_test_function(GR_CMP_ALWAYS);
        self.chromakey_mode(GR_CHROMAKEY_DISABLE);
        self.depth_bias_level(0);
        self.depth_buffer_mode(GR_DEPTHBUFFER_DISABLE);
        self.fog_mode(GR_FOG_DISABLE);
    }

    /// `grEnable`.
    pub fn enable(&mut self, mode: u32) {
        match mode {
            GR_AA_ORDERED => self.st.smooth_mode = 7,
            GR_ALLOW_MIPMAP_DITHER => self.st.allow_lod_dither = true,
            GR_PASSTHRU | GR_SHAMELESS_PLUG | GR_VIDEO_SMOOTHING => {}
            _ => {
                self.report(format!("grEnable: unknown mode {mode:#x}"), false);
            }
        }
    }

    /// `grDisable`.
    pub fn disable(&mut self, mode: u32) {
        match mode {
            GR_AA_ORDERED => self.st.smooth_mode = 0,
            GR_ALLOW_MIPMAP_DITHER => self.st.allow_lod_dither = false,
            GR_PASSTHRU | GR_SHAMELESS_PLUG | GR_VIDEO_SMOOTHING => {}
            _ => {
                self.report(format!("grDisable: unknown mode {mode:#x}"), false);
            }
        }
    }

    /// `grCoordinateSpace`.
    pub fn coordinate_space(&mut self, mode: u32) {
        if self.check(
            mode > GR_CLIP_COORDS,
            "grCoordinateSpace",
            "invalid coordinate space",
        ) {
            return;
        }
        self.st.coordinate_space = mode;
        self.update_param_index();
    }

    /// `grViewport`.
    pub fn viewport(&mut self, x: i32, y: i32, width: i32, height: i32) {
        let vp = &mut self.st.viewport;
        vp.ox = x as f32 + width as f32 * 0.5;
        vp.oy = y as f32 + height as f32 * 0.5;
        vp.hwidth = width as f32 * 0.5;
        vp.hheight = height as f32 * 0.5;
    }

    /// `grDepthRange`.
    pub fn depth_range(&mut self, near: f32, far: f32) {
        self.st.viewport.hdepth = (far - near) * 0.5 * 65535.0;
        self.st.viewport.oz = (far + near) * 0.5 * 65535.0;
    }

    /// `grLfbConstantAlpha`.
    pub fn lfb_constant_alpha(&mut self, alpha: u8) {
        self.st.lfb_constant_alpha = alpha;
    }

    /// `grLfbConstantDepth`.
    pub fn lfb_constant_depth(&mut self, depth: u32) {
        self.st.lfb_constant_depth = depth;
    }

    // ----- vertices and primitives ----------------------------------------------

    /// `grVertexLayout`: `param` is a `GR_PARAM_*`, `offset` in bytes.
    pub fn vertex_layout(&mut self, param: u32, offset: i32, mode: u32) {
        if self.check(
            !draw::offset_ok(offset),
            "grVertexLayout",
            "offset must be a multiple of 4 from 0 to 1024",
        ) || self.check(
            mode > GR_PARAM_ENABLE,
            "grVertexLayout",
            "mode must be GR_PARAM_ENABLE or GR_PARAM_DISABLE",
        ) {
            return;
        }
        let p = draw::Param {
            offset,
            enabled: mode == GR_PARAM_ENABLE,
        };
        let l = &mut self.layout;
        match param {
            GR_PARAM_XY => l.xy = p,
            GR_PARAM_Z => l.z = p,
            GR_PARAM_W => l.w = p,
            GR_PARAM_Q => l.q = p,
            GR_PARAM_FOG_EXT => l.fog = p,
            GR_PARAM_A => {
                l.a = p;
                if p.enabled {
                    l.packed_color = false;
                }
            }
            GR_PARAM_RGB => {
                l.rgb = p;
                if p.enabled {
                    l.packed_color = false;
                }
            }
            GR_PARAM_PARGB => {
                l.pargb = p;
                if p.enabled {
                    l.packed_color = true;
                }
            }
            GR_PARAM_ST0..=GR_PARAM_ST2 => l.st[(param - GR_PARAM_ST0) as usize] = p,
            GR_PARAM_Q0..=GR_PARAM_Q2 => l.qn[(param - GR_PARAM_Q0) as usize] = p,
            _ => {
                self.report(
                    format!("grVertexLayout: unknown parameter {param:#x}"),
                    false,
                );
                return;
            }
        }
        self.update_param_index();
    }

    /// `grDrawTriangle`. Vertices are the raw vertex words (byte offsets of the layout
    /// index into them; packed colours are read from the word's little-endian bytes).
    pub fn draw_triangle(&mut self, a: &[f32], b: &[f32], c: &[f32]) {
        self.triangle(a, b, c);
    }

    /// `grDrawLine`.
    pub fn draw_line(&mut self, a: &[f32], b: &[f32]) {
        self.line(a, b);
    }

    /// `grDrawPoint`.
    pub fn draw_point(&mut self, p: &[f32]) {
        self.point(p);
    }

    /// `grDrawVertexArray`: `mode` is `GR_POINTS` .. `GR_TRIANGLE_FAN_CONTINUE`.
    pub fn draw_vertex_array(&mut self, mode: u32, vertices: &[&[f32]]) {
        self.draw_vertex_array_with(mode, vertices.len(), |i| Cow::Borrowed(vertices[i]));
    }

    /// `grDrawVertexArray` over `count` vertices that `vertex(i)` gives, each asked for
    /// once and in order (the C ABI reads them from the program's memory one at a time,
    /// so drawing needs no memory in proportion to `count`).
    pub fn draw_vertex_array_with<'v>(
        &mut self,
        mode: u32,
        count: usize,
        vertex: impl FnMut(usize) -> Cow<'v, [f32]>,
    ) {
        if self.check(
            mode > GR_TRIANGLE_FAN_CONTINUE,
            "grDrawVertexArray",
            "invalid primitive mode",
        ) {
            return;
        }
        self.draw_list(mode, count, vertex);
    }

    /// `grDrawVertexArrayContiguous`: `count` vertices `stride` bytes apart in `data`;
    /// a vertex that starts past the end of `data` reads as zeros.
    pub fn draw_vertex_array_contiguous(
        &mut self,
        mode: u32,
        data: &[f32],
        count: usize,
        stride: usize,
    ) {
        if self.check(
            !stride.is_multiple_of(4),
            "grDrawVertexArrayContiguous",
            "stride must be a positive multiple of 4",
        ) {
            return;
        }
        let words = stride / 4;
        self.draw_vertex_array_contiguous_with(mode, count, stride, |i| {
            let start = i.saturating_mul(words);
            Cow::Borrowed(data.get(start..).unwrap_or(&[]))
        });
    }

    /// `grDrawVertexArrayContiguous` over `count` vertices `stride` bytes apart that
    /// `vertex(i)` gives (see [`Glide::draw_vertex_array_with`]).
    pub fn draw_vertex_array_contiguous_with<'v>(
        &mut self,
        mode: u32,
        count: usize,
        stride: usize,
        vertex: impl FnMut(usize) -> Cow<'v, [f32]>,
    ) {
        if self.check(
            stride == 0,
            "grDrawVertexArrayContiguous",
            "stride must be a positive multiple of 4",
        ) || self.check(
            mode > GR_TRIANGLE_FAN_CONTINUE,
            "grDrawVertexArrayContiguous",
            "invalid primitive mode",
        ) {
            return;
        }
        // 3dfx's grDrawVertexArrayContiguous starts a new fan for
        // GR_TRIANGLE_FAN_CONTINUE (only grDrawVertexArray continues one).
        // Source: sezero/glide distrip.c grDrawVertexArrayContiguous.
        let mode = match mode {
            GR_TRIANGLE_FAN_CONTINUE => GR_TRIANGLE_FAN,
            m => m,
        };
        self.draw_list(mode, count, vertex);
    }

    /// `grAADrawTriangle`: the triangle plus alpha-ramped edge triangles outside the
    /// edges whose flag is set (a-b, b-c, c-a); see the `aa` module. Needs an
    /// iterated-alpha combine and source-alpha blending to look antialiased.
    pub fn aa_draw_triangle(
        &mut self,
        a: &[f32],
        b: &[f32],
        c: &[f32],
        ab_antialias: bool,
        bc_antialias: bool,
        ca_antialias: bool,
    ) {
        self.aa_triangle(a, b, c, [ab_antialias, bc_antialias, ca_antialias]);
    }

    // ----- buffers ------------------------------------------------------------------

    /// `grBufferClear`: fast-fill the draw buffer (and depth/alpha when enabled).
    pub fn buffer_clear(&mut self, color: u32, alpha: u8, depth: u32) {
        self.flush_state();
        let fbz = FbzMode(self.st.fbi.fbz_mode);
        let old_c1 = self.st.fbi.color1;
        let old_za = self.st.fbi.za_color;
        let mut za = ZaColor(old_za);
        if fbz.rgb_buffer_mask() {
            self.hw
                .w(COLOR1, state::swizzle(color, self.st.color_format));
        }
        if fbz.enable_alpha_planes() && fbz.aux_buffer_mask() {
            za = za.with_constant_alpha(alpha);
            self.hw.w(ZA_COLOR, za.0);
        }
        if fbz.enable_depthbuffer() && fbz.aux_buffer_mask() {
            za = za.with_constant_depth(depth as u16);
            self.hw.w(ZA_COLOR, za.0);
        }
        self.hw.w(FASTFILL_CMD, 1);
        self.hw.w(COLOR1, old_c1);
        self.hw.w(ZA_COLOR, old_za);
    }

    /// `grBufferSwap`: `swapbufferCMD` with vsync when `interval > 0` (the SST-1
    /// counts interval - 1 extra vertical retraces on revision-2 FBIs).
    pub fn buffer_swap(&mut self, interval: u32) {
        if self.check(interval > 255, "grBufferSwap", "swap interval out of range") {
            return;
        }
        let vsync = u32::from(interval > 0);
        let mut iv = interval;
        if interval > 0 && self.board.fbi_revision == 1 {
            iv = match interval {
                1 => 1,
                2 => 3,
                n => n << 1,
            };
        } else {
            iv = iv.saturating_sub(1);
        }
        self.hw.w(SWAPBUFFER_CMD, (iv << 1) | vsync);
        self.swaps += 1;
    }

    /// `grBufferNumPending`: swaps queued, from the status register.
    pub fn buffer_num_pending(&mut self) -> u32 {
        (self.hw.r(STATUS) >> 28) & 7
    }

    /// `grFinish`: a NOP command, then wait for idle (status reads).
    pub fn finish(&mut self) {
        self.hw.w(NOP_CMD, 0);
    }

    /// `guGammaCorrectionRGB`.
    pub fn gamma_correction_rgb(&mut self, r: f32, g: f32, b: f32) {
        Init {
            hw: &mut self.hw,
            st: &mut self.init,
            board: &self.board,
        }
        .gamma(f64::from(r), f64::from(g), f64::from(b));
    }

    /// `grLoadGammaTable`.
    pub fn load_gamma_table(&mut self, red: &[u32], green: &[u32], blue: &[u32]) {
        Init {
            hw: &mut self.hw,
            st: &mut self.init,
            board: &self.board,
        }
        .gamma_table(red, green, blue);
    }

    // ----- textures -----------------------------------------------------------------

    /// `grTexMinAddress`.
    pub fn tex_min_address(&self, _tmu: u32) -> u32 {
        0
    }

    /// `grTexMaxAddress`.
    pub fn tex_max_address(&self, _tmu: u32) -> u32 {
        (self.board.tmu_mb << 20) - 8
    }

    /// `grTexTextureMemRequired`.
    pub fn tex_texture_mem_required(&self, even_odd: u32, info: &TexInfo) -> u32 {
        tex::mem_required(
            info.small_lod,
            info.large_lod,
            info.aspect,
            info.format,
            even_odd,
        )
    }

    /// `grTexCalcMemRequired`.
    pub fn tex_calc_mem_required(&self, small: u32, large: u32, aspect: i32, format: u32) -> u32 {
        tex::mem_required(small, large, aspect, format, GR_MIPMAPLEVELMASK_BOTH)
    }

    fn tex_info_ok(&mut self, call: &str, info: &TexInfo, even_odd: u32) -> bool {
        let bad = info.small_lod > 8
            || info.large_lod > 8
            || info.small_lod > info.large_lod
            || !(-3..=3).contains(&info.aspect)
            || info.format > GR_TEXFMT_RSVD2
            || !(1..=3).contains(&even_odd);
        !self.check(
            bad,
            call,
            "invalid texture description (LODs, aspect, format or even/odd mask)",
        )
    }

    /// `grTexSource`.
    pub fn tex_source(&mut self, tmu: u32, start: u32, even_odd: u32, info: &TexInfo) {
        if self.check_tmu("grTexSource", tmu) || !self.tex_info_ok("grTexSource", info, even_odd) {
            return;
        }
        let need = tex::mem_required(
            info.small_lod,
            info.large_lod,
            info.aspect,
            info.format,
            even_odd,
        );
        if self.check(
            start.saturating_add(need) > self.board.tmu_mb << 20,
            "grTexSource",
            "insufficient texture ram at startAddress",
        ) {
            return;
        }
        self.tex_source_hw(tmu_index(tmu), start, even_odd, info);
    }

    /// `grTexDownloadMipMap`: `data` holds every level, largest first.
    pub fn tex_download_mipmap(
        &mut self,
        tmu: u32,
        start: u32,
        even_odd: u32,
        info: &TexInfo,
        data: &[u8],
    ) {
        if self.check_tmu("grTexDownloadMipMap", tmu)
            || !self.tex_info_ok("grTexDownloadMipMap", info, even_odd)
        {
            return;
        }
        let size = tex::mem_required(
            info.small_lod,
            info.large_lod,
            info.aspect,
            info.format,
            even_odd,
        );
        if self.check(
            start.saturating_add(size) > self.board.tmu_mb << 20,
            "grTexDownloadMipMap",
            "insufficient texture ram at startAddress",
        ) || self.check(
            start < 0x20_0000 && start + size > 0x20_0000,
            "grTexDownloadMipMap",
            "mipmap cannot span 2 Mbyte boundary",
        ) {
            return;
        }
        self.tex_download_mipmap_hw(tmu_index(tmu), start, even_odd, info, data);
    }

    /// `grTexDownloadMipMapLevel`.
    pub fn tex_download_mipmap_level(
        &mut self,
        tmu: u32,
        start: u32,
        this_lod: u32,
        large_lod: u32,
        aspect: i32,
        format: u32,
        even_odd: u32,
        data: &[u8],
    ) {
        let (_, h) = tex::level_wh(this_lod, aspect);
        self.tex_download_mipmap_level_partial(
            tmu,
            start,
            this_lod,
            large_lod,
            aspect,
            format,
            even_odd,
            data,
            0,
            h as i32 - 1,
        );
    }

    /// `grTexDownloadMipMapLevelPartial`: rows `t..=max_t`.
    pub fn tex_download_mipmap_level_partial(
        &mut self,
        tmu: u32,
        start: u32,
        this_lod: u32,
        large_lod: u32,
        aspect: i32,
        format: u32,
        even_odd: u32,
        data: &[u8],
        t: i32,
        max_t: i32,
    ) -> bool {
        let info = TexInfo {
            small_lod: this_lod,
            large_lod,
            aspect,
            format,
        };
        if self.check_tmu("grTexDownloadMipMapLevelPartial", tmu)
            || !self.tex_info_ok("grTexDownloadMipMapLevelPartial", &info, even_odd)
            || self.check(
                !tex::rows_ok(this_lod, aspect, t, max_t),
                "grTexDownloadMipMapLevelPartial",
                "invalid row range (t..=maxT must lie inside the level)",
            )
        {
            return false;
        }
        self.tex_download_level_partial(
            tmu_index(tmu),
            start,
            this_lod,
            large_lod,
            aspect,
            format,
            even_odd,
            data,
            t as u32,
            max_t as u32,
        );
        true
    }

    /// `grTexDownloadTable` / `grTexDownloadTableExt` for NCC tables: 12 packed words.
    pub fn tex_download_ncc_table(&mut self, tmu: u32, which: u32, packed: &[u32; 12]) {
        if self.check_tmu("grTexDownloadTable", tmu)
            || self.check(
                which > GR_TEXTABLE_NCC1,
                "grTexDownloadTable",
                "invalid NCC table",
            )
        {
            return;
        }
        self.tex_download_ncc(tmu_index(tmu), which, packed);
    }

    /// `grTexDownloadTable(GR_TEXTABLE_PALETTE)` / `grTexDownloadTablePartial`.
    pub fn tex_download_palette_range(
        &mut self,
        tmu: u32,
        palette: &[u32; 256],
        start: usize,
        end: usize,
    ) {
        if self.check_tmu("grTexDownloadTable", tmu)
            || self.check(
                start > end || end > 255,
                "grTexDownloadTablePartial",
                "invalid palette range",
            )
        {
            return;
        }
        self.tex_download_palette(tmu_index(tmu), palette, start, end);
    }

    /// `grTexNCCTable`.
    pub fn tex_ncc_table_select(&mut self, table: u32) {
        if self.check(
            table > GR_NCCTABLE_NCC1,
            "grTexNCCTable",
            "invalid NCC table",
        ) {
            return;
        }
        self.tex_ncc_table(table);
    }

    /// `grTexClampMode`.
    pub fn tex_clamp_mode(&mut self, tmu: u32, s: u32, t: u32) {
        if self.check_tmu("grTexClampMode", tmu)
            || self.check(
                s > GR_TEXTURECLAMP_MIRROR_EXT || t > GR_TEXTURECLAMP_MIRROR_EXT,
                "grTexClampMode",
                "invalid clamp mode",
            )
        {
            return;
        }
        self.tex_clamp(tmu_index(tmu), s, t);
    }

    /// `grTexFilterMode`.
    pub fn tex_filter_mode(&mut self, tmu: u32, min: u32, mag: u32) {
        if self.check_tmu("grTexFilterMode", tmu)
            || self.check(min > 1 || mag > 1, "grTexFilterMode", "invalid filter mode")
        {
            return;
        }
        self.tex_filter(tmu_index(tmu), min, mag);
    }

    /// `grTexLodBiasValue`.
    pub fn tex_lod_bias_value(&mut self, tmu: u32, bias: f32) {
        if self.check_tmu("grTexLodBiasValue", tmu)
            || self.check(
                !bias.is_finite(),
                "grTexLodBiasValue",
                "bias must be finite",
            )
        {
            return;
        }
        self.tex_lod_bias(tmu_index(tmu), bias);
    }

    /// `grTexDetailControl`.
    pub fn tex_detail_control(&mut self, tmu: u32, lod_bias: i32, scale: u8, max: f32) {
        if self.check_tmu("grTexDetailControl", tmu)
            || self.check(
                !(-32..=31).contains(&lod_bias) || scale > 7 || !(0.0..=1.0).contains(&max),
                "grTexDetailControl",
                "invalid detail parameters",
            )
        {
            return;
        }
        self.tex_detail(tmu_index(tmu), lod_bias, scale, max);
    }

    /// `grTexMipMapMode`.
    pub fn tex_mipmap_mode(&mut self, tmu: u32, mode: u32, lod_blend: bool) {
        if self.check_tmu("grTexMipMapMode", tmu)
            || self.check(
                mode > GR_MIPMAP_NEAREST_DITHER,
                "grTexMipMapMode",
                "invalid mode passed",
            )
        {
            return;
        }
        self.tex_mipmap(tmu_index(tmu), mode, lod_blend);
    }

    /// `grTexCombine`.
    pub fn tex_combine(
        &mut self,
        tmu: u32,
        rgb_fn: u32,
        rgb_factor: u32,
        a_fn: u32,
        a_factor: u32,
        rgb_invert: bool,
        a_invert: bool,
    ) {
        let bad_fn = |f: u32| {
            f > GR_COMBINE_FUNCTION_SCALE_MINUS_LOCAL_ADD_LOCAL_ALPHA || (f > 9 && f < 0x10)
        };
        let bad_factor = |f: u32| {
            (f & 7) > GR_COMBINE_FACTOR_LOD_FRACTION || f > GR_COMBINE_FACTOR_ONE_MINUS_LOD_FRACTION
        };
        if self.check_tmu("grTexCombine", tmu)
            || self.check(
                bad_fn(rgb_fn) || bad_fn(a_fn) || bad_factor(rgb_factor) || bad_factor(a_factor),
                "grTexCombine",
                "unsupported texture combine function or factor",
            )
        {
            return;
        }
        self.tex_combine_hw(
            tmu_index(tmu),
            rgb_fn,
            rgb_factor,
            a_fn,
            a_factor,
            rgb_invert,
            a_invert,
        );
    }

    /// `grTexMultibase`.
    pub fn tex_multibase(&mut self, tmu: u32, enable: bool) {
        if self.check_tmu("grTexMultibase", tmu) {
            return;
        }
        self.tex_multibase_hw(tmu_index(tmu), enable);
    }

    /// `grTexMultibaseAddress`.
    pub fn tex_multibase_address(
        &mut self,
        tmu: u32,
        range: u32,
        start: u32,
        even_odd: u32,
        info: &TexInfo,
    ) {
        if self.check_tmu("grTexMultibaseAddress", tmu)
            || self.check(
                range > GR_TEXBASE_256,
                "grTexMultibaseAddress",
                "invalid range",
            )
        {
            return;
        }
        self.tex_multibase_address_hw(tmu_index(tmu), range, start, even_odd, info);
    }

    // ----- LFB ----------------------------------------------------------------------

    /// `grLfbLock`.
    pub fn lfb_lock(
        &mut self,
        ty: u32,
        buffer: u32,
        write_mode: u32,
        origin: u32,
        pixel_pipeline: bool,
    ) -> Option<LfbInfo> {
        let r = if lfb::lock_slot(ty).is_none() {
            self.report(format!("grLfbLock: invalid lock type {ty:#x}"), false);
            None
        } else {
            let r = self.lfb_lock_hw(ty, buffer, write_mode, origin, pixel_pipeline);
            if r.is_none() {
                self.report(
                    format!(
                        "grLfbLock: lock refused (type {ty:#x}, buffer {buffer}, mode {write_mode:#x})"
                    ),
                    false,
                );
            }
            r
        };
        // 3dfx's grLfbLock ends with grFinish (a `nopCMD` write) unless the type carries
        // GR_LFB_NOIDLE, whether or not the lock was granted (glfb.c).
        if ty & GR_LFB_NOIDLE == 0 {
            self.finish();
        }
        r
    }

    /// `grLfbUnlock`.
    pub fn lfb_unlock(&mut self, ty: u32, buffer: u32) -> bool {
        if lfb::lock_slot(ty).is_none() {
            self.report(format!("grLfbUnlock: invalid lock type {ty:#x}"), false);
            return false;
        }
        self.lfb_unlock_hw(ty, buffer)
    }

    /// The buffer a lock of type `ty` (`GR_LFB_READ_ONLY` or `GR_LFB_WRITE_ONLY`, with
    /// or without `GR_LFB_NOIDLE`) holds, if one does: `grLfbUnlock(ty, buffer)`
    /// succeeds exactly when this is `Some(buffer)`.
    pub fn lfb_locked_buffer(&self, ty: u32) -> Option<u32> {
        self.lfb_locks[lfb::lock_slot(ty)?]
    }

    /// `grLfbWriteRegion`.
    pub fn lfb_write_region(
        &mut self,
        buffer: u32,
        x: u32,
        y: u32,
        format: u32,
        width: u32,
        height: u32,
        pipeline: bool,
        stride: usize,
        data: &[u8],
    ) -> bool {
        self.lfb_write_region_hw(buffer, x, y, format, width, height, pipeline, stride, data)
    }

    /// `grLfbReadRegion`: 16-bit pixels.
    pub fn lfb_read_region(
        &mut self,
        buffer: u32,
        x: u32,
        y: u32,
        width: u32,
        height: u32,
        stride: usize,
        out: &mut [u8],
    ) -> bool {
        self.lfb_read_region_hw(buffer, x, y, width, height, stride, out)
    }
}

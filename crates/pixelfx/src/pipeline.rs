//! The pixel pipeline: the one place that knows the order of the stages
//! (spec 3.3 and the `fbzColorPath`/`fbzMode` diagrams of section 5).
//!
//! ```text
//! clip -> stipple -> depth value -> depth test -> [texture] -> colour select
//!      -> chroma key -> alpha mask -> alpha test -> combine -> fog -> alpha blend
//!      -> dither -> RGB write / aux write
//! ```
//! Each stage either passes the pixel on or names why it was killed ([`Kill`]); the
//! counters are updated here and nowhere else. Source for the order: spec 5.27 (chroma
//! key after texture lookup, before lighting, fog and blending), 5.18, 5.19; MAME and
//! DOSBox Staging run the depth test before the colour path, which gives the same
//! pixels and counters as the spec's order because the depth test has no side effects.

use sst1_dither::DitherKind;
use sst1_regs::{AlphaMode, FbzColorPath, FbzMode, FogMode, Rgba};

use crate::color_path::{self, Inputs};
use crate::fbi::Fbi;
use crate::iter::{wfloat, Iterated};
use crate::model::PixelModel;
use crate::profile::{ClipRightEdge, OverrideTexel, PixelProfile, ZAlphaByte};
use crate::stats::Kill;
use crate::watch::StageSink;
use crate::{alpha_test, blend, depth, fog, stipple};

/// The mode registers and constants of one drawing operation, decoded once.
#[derive(Clone, Copy, Debug)]
pub struct DrawState {
    pub color_path: FbzColorPath,
    pub mode: FbzMode,
    pub alpha_mode: AlphaMode,
    pub fog_mode: FogMode,
    pub color0: Rgba,
    pub color1: Rgba,
    pub chroma_key: u32,
    pub za_color: u32,
    pub fog_color: Rgba,
    pub stipple: u32,
    /// Clip rectangle `[left, right) x [low_y, high_y)` in screen coordinates.
    pub clip: (i32, i32, i32, i32),
    /// The Y origin subtraction value (`fbiInit3[31:22]`, [`Fbi::y_origin`]).
    pub y_origin: i32,
    /// Word index of the colour buffer drawn into.
    pub dest: usize,
    /// Word index of the aux buffer, if the memory layout has one.
    pub aux: Option<usize>,
    /// Dither applied to the RGB write (`Off` when `fbzMode` disables dithering).
    pub dither: DitherKind,
    /// The matrix `fbzMode` bit 11 selects, whether or not dithering is on (the
    /// alpha-blend dither subtraction reads it).
    pub dither_matrix: DitherKind,
    /// Whether the TMU chain is read for a textured pixel: `false` with
    /// `OverrideTexel::ZeroWhenUnused` when the combine units take nothing from it, and
    /// on the span kernels' walk where no pixel reads the texel and the source samples
    /// purely ([`DrawState::for_span_kernels`]).
    pub fetch_texel: bool,
}

impl DrawState {
    /// Snapshot the registers of `fbi` for drawing into colour buffer `dest`, as model
    /// `M` reads them.
    pub fn capture<M: PixelModel>(fbi: &Fbi, dest: usize) -> Self {
        use sst1_regs::addr;
        let profile = M::pixel(&fbi.profile());
        let mode = fbi.fbz_mode();
        let (left, mut right, low, high) = fbi.clip_rect();
        if profile.clip_right == ClipRightEdge::DropLastColumn {
            right -= 1;
        }
        let dither_matrix = if mode.dither_2x2() {
            DitherKind::Dither2x2
        } else {
            DitherKind::Dither4x4
        };
        let dither = if mode.enable_dithering() {
            dither_matrix
        } else {
            DitherKind::Off
        };
        let color_path = FbzColorPath(fbi.reg(addr::FBZ_COLOR_PATH));
        let fetch_texel = match profile.override_texel {
            OverrideTexel::Texel => true,
            OverrideTexel::ZeroWhenUnused => color_path::texel_feeds_equation(color_path),
        };
        Self {
            color_path,
            mode,
            alpha_mode: AlphaMode(fbi.reg(addr::ALPHA_MODE)),
            fog_mode: FogMode(fbi.reg(addr::FOG_MODE)),
            color0: Rgba::from_argb(fbi.reg(addr::COLOR0)),
            color1: Rgba::from_argb(fbi.reg(addr::COLOR1)),
            chroma_key: fbi.reg(addr::CHROMA_KEY),
            za_color: fbi.reg(addr::ZA_COLOR),
            fog_color: Rgba::from_argb(fbi.reg(addr::FOG_COLOR)),
            stipple: fbi.reg(addr::STIPPLE),
            clip: (left, right, low, high),
            y_origin: fbi.y_origin(),
            dest,
            aux: fbi.fb.aux_base(),
            dither,
            dither_matrix,
            fetch_texel,
        }
    }
}

impl DrawState {
    /// The state for the span kernels' walk from a texel source, as `profile` (the
    /// model's) draws, without the work whose output no pixel reads (the reference path
    /// does it all): a source that samples purely
    /// ([`crate::TexelSource::samples_purely`]) is not asked where no pixel reads the
    /// texel ([`color_path::texel_read`]), and fog and the alpha blend, which feed the
    /// colour writes alone, are off where no colour is written (neither RGB nor alpha
    /// planes).
    #[inline]
    pub fn for_span_kernels(mut self, profile: &PixelProfile, source_samples_purely: bool) -> Self {
        let mode = self.mode;
        let rgb_written = mode.rgb_buffer_mask();
        let alpha_written =
            crate::span::aux_enabled(mode, profile.aux_write) && mode.enable_alpha_planes();
        if source_samples_purely {
            self.fetch_texel &= color_path::texel_read(
                self.color_path,
                mode,
                self.alpha_mode,
                profile.alpha_test_input == crate::profile::AlphaTestInput::Combined,
                rgb_written,
                alpha_written,
            );
        }
        if !rgb_written && !alpha_written {
            self.fog_mode = self.fog_mode.with_enable_fog(false);
            self.alpha_mode = self.alpha_mode.with_alpha_blend_enable(false);
        }
        self
    }

    /// Screen row of raster row `y`, after the Y origin flip when `flip` is set (as
    /// [`Fbi::screen_y`] with the registers captured).
    #[inline]
    pub fn screen_y(&self, y: i32, flip: bool) -> i32 {
        screen_row(self.y_origin, y, flip)
    }
}

/// Screen row of raster row `y` with Y origin subtraction value `y_origin`
/// (`fbiInit3[31:22]`), flipped when `flip` is set (spec 5.19, `fbzMode` bit 17).
#[inline]
pub(crate) fn screen_row(y_origin: i32, y: i32, flip: bool) -> i32 {
    if flip {
        (y_origin - y) & 0x3ff
    } else {
        y
    }
}

/// Where the colour entering the pipeline comes from.
#[derive(Clone, Copy, Debug)]
pub enum Source {
    /// A triangle: the iterators and the TMU chain.
    Triangle,
    /// A linear-frame-buffer write through the pipeline: the written colour replaces
    /// `c_other` and the iterated colour (spec 5.20, `lfbMode` bit 8).
    Lfb(Rgba),
}

impl Fbi {
    /// Run one pixel through the pipeline. `x` is the screen column, `y` the raster row
    /// (used for dithering), `scry` the frame-buffer row after the Y-origin flip.
    /// `texel` is called only if the pixel survives the depth test and texturing is on.
    /// `prow` is the row the dither and stipple patterns are indexed with (see
    /// [`crate::profile::PatternRow`]).
    ///
    /// `M` is the model of the chip ([`crate::model`]). This is the reference path: every
    /// mode bit is tested for every pixel. The span kernels ([`crate::span`]) run the same
    /// stages a chunk of pixels at a time.
    ///
    /// `stages` is told the value of every stage ([`crate::watch`]): [`NoStages`]
    /// (nothing, at no cost) for every pixel but a watched one.
    ///
    /// [`NoStages`]: crate::watch::NoStages
    #[inline(always)]
    pub(crate) fn shade_pixel<M: PixelModel, S: StageSink>(
        &mut self,
        st: &DrawState,
        x: i32,
        prow: i32,
        scry: i32,
        it: &Iterated,
        source: Source,
        stipple_state: &mut u32,
        texel: impl FnOnce() -> Rgba,
        stages: &mut S,
    ) -> Result<(), Kill> {
        let mode = st.mode;
        let color_path = st.color_path;
        let am = st.alpha_mode;
        let fog_mode = st.fog_mode;
        let profile = M::pixel(&self.profile());

        // --- stipple ---
        if mode.enable_stipple()
            && !stipple::test(
                mode.enable_stipple_pattern(),
                stipple_state,
                st.stipple,
                x,
                prow,
            )
        {
            return Err(Kill::Stipple);
        }

        // --- depth value and test ---
        let wf = wfloat(it.w, profile.wfloat);
        let clamp = profile.iterator_clamp;
        let z16 = clamp.z(it.z);
        let bias = mode.enable_depth_bias().then_some(st.za_color as u16);
        let depth_value = depth::value(mode.wbuffer_select(), z16, wf, bias);
        let aux_index = st.aux.and_then(|a| self.fb.index(a, x, scry));
        stages.iterated(it, &source, clamp, z16, wf, depth_value);
        if mode.enable_depthbuffer() {
            let source_depth = if mode.depth_source_compare() {
                (st.za_color & 0xffff) as i32
            } else {
                depth_value
            };
            // Without an aux buffer only "never" can fail (MAME, DOSBox Staging).
            let dest = aux_index.map(|i| self.fb.ram[i]);
            let pass = match dest {
                Some(d) => depth::test(mode.depth_function(), source_depth, d),
                None => mode.depth_function() != sst1_regs::DepthFunction::Never,
            };
            stages.depth(mode.depth_function(), source_depth, dest, pass);
            if !pass {
                return Err(Kill::DepthFunc);
            }
        }

        // --- colour selection ---
        let texel = if color_path.texture_enable() && st.fetch_texel {
            stages.texel(texel())
        } else {
            Rgba::default()
        };
        let iterated = match source {
            Source::Triangle => Rgba {
                r: clamp.colour(it.argb[0]),
                g: clamp.colour(it.argb[1]),
                b: clamp.colour(it.argb[2]),
                a: clamp.colour(it.argb[3]),
            },
            Source::Lfb(c) => c,
        };
        let inputs = Inputs {
            iterated,
            texel,
            color0: st.color0,
            color1: st.color1,
            // Z[27:20], the high byte of the clamped 16-bit Z (spec 5.16; MAME, 86Box).
            // DOSBox Staging takes the low byte; `color_combine` shows MAME and 86Box agree
            // against it.
            z_alpha: match profile.z_alpha {
                ZAlphaByte::High => (z16 >> 8) as u8,
                ZAlphaByte::Low => z16 as u8,
            },
        };
        let other = match source {
            Source::Triangle => color_path::select_other(color_path, &inputs),
            Source::Lfb(c) => c,
        };

        stages.colour_path(color_path, &inputs, other);

        // --- chroma key, alpha mask ---
        if mode.enable_chromakey() && color_path::chroma_killed(other, st.chroma_key) {
            return Err(Kill::Chroma);
        }
        if mode.enable_alpha_mask() && other.a & 1 == 0 {
            return Err(Kill::AlphaMask);
        }
        let test_alpha = |a: u8| {
            !am.alpha_test_enable() || alpha_test::test(am.alpha_function(), a, am.alpha_ref())
        };
        let test_combined = matches!(source, Source::Triangle)
            && profile.alpha_test_input == crate::profile::AlphaTestInput::Combined;
        if !test_combined && !test_alpha(other.a) {
            return Err(Kill::AlphaFunc);
        }

        // --- combine, alpha test ---
        let local = color_path::select_local(color_path, &inputs);
        let combined = stages.combined(color_path::combine(color_path, other, local, texel.a));
        if test_combined && !test_alpha(combined.a) {
            return Err(Kill::AlphaFunc);
        }

        // --- fog ---
        let fog_input = fog::FogInput {
            color: combined,
            alpha: iterated.a,
            z: z16,
            w: it.w,
            wfloat: wf,
            depth_bias: bias.map(|b| b as i16),
        };
        let fogged = fog::apply_fog(
            fog_mode,
            st.fog_color,
            &self.fog_table,
            &fog_input,
            profile.fog,
        );
        stages.fog(fog_mode.enable_fog(), fogged);

        // --- alpha blend ---
        let dest_index = self.fb.index(st.dest, x, scry);
        let out = if am.alpha_blend_enable() {
            let input = blend::BlendInput {
                src: fogged,
                prefog: combined,
                dst_rgb565: dest_index.map_or(0, |i| self.fb.ram[i]),
                dst_aux: aux_index.map(|i| self.fb.ram[i]),
                dither_value: self
                    .dither
                    .matrix_value(st.dither_matrix, x as u32, prow as u32),
            };
            stages.blend(&input, blend::alpha_blend(am, mode, &input, profile.blend))
        } else {
            fogged
        };

        // --- write ---
        if mode.rgb_buffer_mask() {
            if let Some(i) = dest_index {
                self.fb.ram[i] =
                    self.dither
                        .rgb565(st.dither, x as u32, prow as u32, out.r, out.g, out.b);
            }
        }
        if crate::span::aux_enabled(mode, profile.aux_write) {
            if let Some(i) = aux_index {
                self.fb.ram[i] = if mode.enable_alpha_planes() {
                    out.a as u16
                } else {
                    depth_value as u16
                };
            }
        }
        if S::RECORDS {
            let rgb = dest_index.filter(|_| mode.rgb_buffer_mask());
            let aux = aux_index.filter(|_| crate::span::aux_enabled(mode, profile.aux_write));
            let dither_value = self.dither.matrix_value(st.dither, x as u32, prow as u32);
            stages.write(out, st.dither, dither_value, &self.fb.ram, rgb, aux);
        }
        Ok(())
    }

    /// Account for a pixel's fate in the statistics counters (spec 5.31-5.35).
    #[inline]
    pub(crate) fn count(&mut self, result: Result<(), Kill>) {
        match result {
            Ok(()) => self.stats.pixels_out += 1,
            Err(k) => self.stats.kill(k),
        }
    }
}

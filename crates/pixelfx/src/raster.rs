//! Triangle rasterization: spans from [`crate::setup`], clipping, and the per-pixel walk
//! with the iterators (spec 5.15 `triangleCMD`, 5.21 clip registers, 5.19 Y origin).

use sst1_regs::Rgba;

use crate::fbi::Fbi;
use crate::iter::Iterated;
use crate::model::PixelModel;
use crate::pipeline::{DrawState, Source};
use crate::profile::StippleRotate;
use crate::span::{ChunkAt, Lanes, TriangleLanes, LANES};
use crate::{box86, setup};

/// What the TMU chain gives the FBI for one pixel.
pub trait TexelSource {
    /// The texel for the pixel at offset `(dx, dy)` from vertex A's pixel, at screen
    /// position `(x, y)`.
    fn texel(&mut self, dx: i32, dy: i32, x: i32, y: i32) -> Rgba;

    /// A span of `len` pixels from offset `(dx, dy)` rightwards is about to be shaded: a
    /// source may compute per-pixel values for all of them at once here. Optional; the
    /// texels must not depend on whether it was called.
    #[inline]
    fn begin_span(&mut self, _dx: i32, _dy: i32, _len: usize) {}

    /// The texels of the live lanes of one chunk of a span ([`crate::span`]): lane `i`
    /// is the pixel at offset `(dx0 + i, dy)`, screen position `(x0 + i, y)`; for each
    /// `i < n` with `alive[i]`, its texel's R, G, B, A go to `out[0..4][i]`. Other lanes
    /// of `out` are left as they are. Texels are asked for in lane order, exactly those
    /// [`TexelSource::texel`] would be asked for one at a time, so a source with state
    /// (a texture cache) sees the same sequence; this default does just that.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn texels(
        &mut self,
        dx0: i32,
        dy: i32,
        x0: i32,
        y: i32,
        alive: &[bool; LANES],
        n: usize,
        out: &mut [Lanes; 4],
    ) {
        for i in 0..n.min(LANES) {
            if alive[i] {
                let t = self.texel(dx0 + i as i32, dy, x0 + i as i32, y);
                out[0][i] = t.r as i32;
                out[1][i] = t.g as i32;
                out[2][i] = t.b as i32;
                out[3][i] = t.a as i32;
            }
        }
    }
}

/// The source for untextured drawing: always zero.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoTexture;

impl TexelSource for NoTexture {
    #[inline]
    fn texel(&mut self, _dx: i32, _dy: i32, _x: i32, _y: i32) -> Rgba {
        Rgba::default()
    }
}

impl Fbi {
    /// Draw the triangle held in the parameter registers (the `triangleCMD` command).
    /// The caller has applied subpixel correction if `fbzColorPath` asks for it.
    ///
    /// Runs the span kernels ([`crate::span`]) unless [`Fbi::set_generic_path`] forced
    /// the reference path (the pipeline pixel by pixel, every mode bit tested per pixel).
    ///
    /// `M` is the model of the chip ([`crate::model`]); the caller guarantees that the
    /// profile this FBI holds is `M`'s.
    pub fn draw_triangle<M: PixelModel, T: TexelSource>(&mut self, tex: &mut T) {
        self.stats.triangles += 1;
        let mode = self.fbz_mode();
        let Some(dest) = self.colour_buffer(mode.draw_buffer()) else {
            return;
        };
        let st = DrawState::capture::<M>(self, dest);
        if self.generic_path {
            self.walk::<M, T, false>(&st, tex);
        } else {
            self.walk_spans::<M, T>(&st, tex);
        }
    }

    /// The span kernels, compiled for the best vector instructions the CPU has: with AVX2
    /// where the CPU has it (found at run time), for the baseline target otherwise. Both
    /// compute the same integers; the choice changes only the speed.
    fn walk_spans<M: PixelModel, T: TexelSource>(&mut self, st: &DrawState, tex: &mut T) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2 (checked just above).
            unsafe { self.walk_spans_avx2::<M, T>(st, tex) };
            return;
        }
        self.walk::<M, T, true>(st, tex);
    }

    /// [`Fbi::walk`] with the span kernels, compiled with AVX2 enabled.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn walk_spans_avx2<M: PixelModel, T: TexelSource>(&mut self, st: &DrawState, tex: &mut T) {
        self.walk::<M, T, true>(st, tex);
    }

    /// Force the reference path (every mode register read at run time for every pixel)
    /// instead of the span kernels. Both give identical pixels and counters; the switch
    /// exists to prove that (`crates/board/tests/generic_vs_fast.rs`) and to debug the
    /// kernels.
    pub fn set_generic_path(&mut self, on: bool) {
        self.generic_path = on;
    }

    /// Whether the generic path is forced.
    pub fn generic_path(&self) -> bool {
        self.generic_path
    }

    /// Walk the triangle's spans and shade their pixels: a chunk of up to
    /// [`crate::span::LANES`] pixels at a time with the span kernels (`SPANS`), or one
    /// pixel at a time with the reference path.
    #[inline(always)]
    fn walk<M: PixelModel, T: TexelSource, const SPANS: bool>(
        &mut self,
        st: &DrawState,
        tex: &mut T,
    ) {
        let mode = st.mode;
        let flip = mode.y_origin();
        let profile = M::pixel(&self.profile());
        let origin = profile.param_origin;
        let (ax, ay) = (origin.pixel(self.params.ax), origin.pixel(self.params.ay));
        let params = self.params;
        // Only rotate-mode stipple reads the per-triangle copy.
        let per_triangle = profile.stipple_rotate == StippleRotate::PerTriangle
            && mode.enable_stipple()
            && !mode.enable_stipple_pattern();
        let mut copy = per_triangle.then(|| box86::StippleCopy::new(st.stipple));
        let consts = SPANS.then(|| TriangleLanes::new(st));
        for span in setup::spans(&params, profile.edge_rounding) {
            let (mut start, mut stop) = (span.start, span.stop);
            // Every pixel the walker visits counts as "in" (spec 5.31), clipped or not.
            self.stats.pixels_in += (stop - start) as u64;
            self.stats.spans += 1;
            let scry = self.screen_y(span.y, flip);
            if mode.enable_clipping() {
                let (left, right, low, high) = st.clip;
                if scry < low || scry >= high {
                    continue;
                }
                start = start.max(left);
                stop = stop.min(right);
            }
            if start >= stop {
                continue;
            }
            let dy = span.y - ay;
            let mut stipple = st.stipple;
            let prow = profile.pattern_row.row(span.y, scry);
            tex.begin_span(start - ax, dy, (stop - start) as usize);
            if let Some(c) = &mut copy {
                c.step_row(start, stop, params.right_to_left);
            }
            if let Some(consts) = &consts {
                let mut x0 = start;
                while x0 < stop {
                    let n = ((stop - x0) as usize).min(LANES);
                    let at = ChunkAt {
                        x0,
                        n,
                        y: span.y,
                        scry,
                        prow,
                        span_start: start,
                        ax,
                        dy,
                    };
                    let it = Iterated::at(&params, x0 - ax, dy);
                    self.shade_chunk::<M, T>(
                        st,
                        &at,
                        &it,
                        &mut stipple,
                        copy.as_ref(),
                        tex,
                        consts,
                    );
                    x0 += n as i32;
                }
                continue;
            }
            self.path_counts.reference += (stop - start) as u64;
            let mut it = Iterated::at(&params, start - ax, dy);
            for x in start..stop {
                if let Some(c) = &copy {
                    stipple = c.at((x - start) as usize);
                }
                let r = self.shade_pixel::<M>(
                    st,
                    x,
                    prow,
                    scry,
                    &it,
                    Source::Triangle,
                    &mut stipple,
                    || tex.texel(x - ax, dy, x, span.y),
                );
                self.count(r);
                it.step_x(&params);
            }
        }
    }
}

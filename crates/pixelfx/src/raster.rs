//! Triangle rasterization: spans from [`crate::setup`], clipping, and the per-pixel walk
//! with the iterators (spec 5.15 `triangleCMD`, 5.21 clip registers, 5.19 Y origin).

use sst1_regs::{FbzMode, Rgba};

use crate::fbi::Fbi;
use crate::iter::Iterated;
use crate::model::PixelModel;
use crate::pipeline::{DrawState, Source};
use crate::profile::StippleRotate;
use crate::specialize::{value, Known, RasterKey, LIVE};
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
    /// Unless [`Fbi::set_generic_path`] forced the generic path, a walker specialised for
    /// the triangle's mode registers is used when [`crate::specialize`] has one.
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
        let specialised = if self.generic_path {
            None
        } else {
            M::specialised::<T>(RasterKey::of_state(&st))
        };
        let walk = specialised.unwrap_or(Fbi::walk::<M, T, LIVE, LIVE, LIVE, LIVE>);
        walk(self, &st, tex);
    }

    /// Force the generic path (every mode register read at run time for every pixel)
    /// instead of the specialised walkers. Both give identical pixels and counters; the
    /// switch exists to prove that (`crates/board/tests/generic_vs_fast.rs`) and to
    /// debug the specialisation.
    pub fn set_generic_path(&mut self, on: bool) {
        self.generic_path = on;
    }

    /// Whether the generic path is forced.
    pub fn generic_path(&self) -> bool {
        self.generic_path
    }

    /// Walk the triangle's spans and shade its pixels with the bits of `fbzColorPath`
    /// (`CP`), `alphaMode` (`AM`), `fogMode` (`FM`) and `fbzMode` (`ZM`) that are known
    /// at compile time folded in (see [`crate::specialize::Known`]); the rest is read
    /// from `st`. The caller guarantees that the known bits equal `st`'s.
    pub(crate) fn walk<
        M: PixelModel,
        T: TexelSource,
        const CP: Known,
        const AM: Known,
        const FM: Known,
        const ZM: Known,
    >(
        &mut self,
        st: &DrawState,
        tex: &mut T,
    ) {
        debug_assert!(
            value(CP, st.color_path.0) == st.color_path.0
                && value(AM, st.alpha_mode.0) == st.alpha_mode.0
                && value(FM, st.fog_mode.0) == st.fog_mode.0
                && value(ZM, st.mode.0) == st.mode.0,
            "walker specialised for other modes"
        );
        let mode = FbzMode(value(ZM, st.mode.0));
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
            let mut it = Iterated::at(&params, start - ax, dy);
            let mut stipple = st.stipple;
            let prow = profile.pattern_row.row(span.y, scry);
            tex.begin_span(start - ax, dy, (stop - start) as usize);
            if let Some(c) = &mut copy {
                c.step_row(start, stop, params.right_to_left);
            }
            for x in start..stop {
                if let Some(c) = &copy {
                    stipple = c.at((x - start) as usize);
                }
                let r = self.shade::<M, CP, AM, FM, ZM>(
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

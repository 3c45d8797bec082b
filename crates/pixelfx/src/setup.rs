//! Scan conversion: from the three 12.4 vertices to one pixel span per scanline
//! (spec 7, triangle rendering).
//!
//! The FBI walks the triangle top to bottom. A scanline `y` is sampled at its centre
//! `y + 0.5`; the left and right edge crossings there are rounded to pixel boundaries
//! and the span covers `[start, stop)`. Vertices are sorted by Y; the long edge runs from
//! the top vertex to the bottom one.
//!
//! Source: MAME (`poly_manager::render_triangle`) and DOSBox Staging
//! (`triangle_worker_work`) agree on this evaluation in single-precision floating point:
//! the same operations in the same order, so the same spans. 86Box walks edges in fixed
//! point instead and differs by a few edge pixels per scene; the README of the
//! conformance set lists this as a known disagreement, and the majority is followed.
//! [`EdgeRounding::Box86Fixed`] selects 86Box's walk (`voodoo_triangle`,
//! `voodoo_half_triangle`) for its model; it lives with 86Box's other structural
//! behaviours in [`crate::box86`].

use crate::params::TriangleParams;

/// How a coordinate is rounded to a pixel boundary.
///
/// Both round half down (`x.5` goes to `x`) for positive values; they differ for
/// negative coordinates, which only occur for partly off-screen triangles.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum EdgeRounding {
    /// `floor(v)`, plus one if the remaining fraction exceeds 0.5 (MAME `round_coordinate`).
    #[default]
    FloorHalfDown,
    /// Truncate toward zero, plus one if `v - trunc(v) > 0.5` (DOSBox Staging
    /// `round_coordinate`): negative values round toward zero.
    TruncHalfDown,
    /// 86Box: no floating point. Edge slopes are 16.16 integers, `((x1 - x0) << 16) /
    /// (y1 - y0)` truncated; an edge crosses row `y` at `x0 + slope * (y + 0.5 - y0)` in
    /// 32-bit arithmetic, and a crossing becomes a pixel boundary by `(x + 7/16) >> 16`
    /// (fractions from 9/16 round up). Rows run from `(Ay + 7) >> 4` to `(Cy + 7) >> 4`
    /// in register order (the vertices are not sorted), and a row whose edges cross
    /// against the triangle's direction (`triangleCMD` bit 31) is empty.
    Box86Fixed,
}

impl EdgeRounding {
    /// Round one coordinate ([`EdgeRounding::Box86Fixed`] rounds as `FloorHalfDown`
    /// here; its spans come from [`spans`] without floating point).
    ///
    /// Written with selects and no saturating conversion where a value may have a
    /// fraction (on the baseline target `as i32` is a dozen instructions, and it keeps a
    /// loop of roundings from vectorising); equal to `base as i32 + i32::from(v - base >
    /// 0.5)` with `base` the floor or the truncation of `v` from libm (tested on every
    /// 12.4 coordinate and on bit patterns of every exponent).
    #[inline(always)]
    pub fn round(self, v: f32) -> i32 {
        // Below 2^23 a value may have a fraction, and its integer part fits in i32; at
        // and above it (and for infinities and NaN) a value is its own floor and
        // truncation, and `v - base` is 0 or NaN, never above 0.5.
        let fractional = v.abs() < F32_FRACTION_LIMIT;
        let vf = if fractional { v } else { 0.0 };
        // SAFETY: |vf| < 2^23, within i32's range.
        let mut base = unsafe { vf.to_int_unchecked::<i32>() };
        let mut base_f = base as f32;
        if !matches!(self, EdgeRounding::TruncHalfDown) {
            // From the truncation to the floor: one less where the truncation is above.
            let above = i32::from(base_f > vf);
            base -= above;
            base_f -= above as f32;
        }
        let rounded = base + i32::from(vf - base_f > 0.5);
        if fractional {
            rounded
        } else {
            saturate(v)
        }
    }
}

/// Below this magnitude an `f32` may have a fraction; at and above it (and for
/// infinities and NaN) a value is its own floor and truncation.
const F32_FRACTION_LIMIT: f32 = 8_388_608.0; // 2^23

/// `v as i32` (NaN to 0, out-of-range values to the nearest bound: hostile coordinates
/// never overflow) with selects in place of the saturating conversion, which the
/// baseline target cannot vectorise.
#[inline(always)]
fn saturate(v: f32) -> i32 {
    /// The largest `f32` below 2^31.
    const BELOW_2_31: f32 = 2_147_483_520.0;
    let v_or_0 = if v.is_nan() { 0.0 } else { v };
    let low = if v_or_0 < i32::MIN as f32 {
        i32::MIN as f32
    } else {
        v_or_0
    };
    let clamped = if low > BELOW_2_31 { BELOW_2_31 } else { low };
    // SAFETY: `clamped` is a number within [-2^31, 2^31 - 128], within i32's range.
    let i = unsafe { clamped.to_int_unchecked::<i32>() };
    if v >= 2_147_483_648.0 {
        i32::MAX
    } else {
        i
    }
}

/// One scanline's span: pixels `start..stop` of row `y` (before clipping).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Span {
    pub y: i32,
    pub start: i32,
    pub stop: i32,
}

/// The spans of the triangle given by the vertex registers, top to bottom.
#[inline]
pub fn spans(p: &TriangleParams, rounding: EdgeRounding) -> impl Iterator<Item = Span> {
    match rounding {
        EdgeRounding::Box86Fixed => Walk::Fixed(crate::box86::spans(p)),
        _ => Walk::Float(spans_float(p, rounding)),
    }
}

/// One of the two edge walks (an enum rather than a boxed iterator: no allocation per
/// triangle, and a model with a fixed [`EdgeRounding`] keeps only its own walk).
enum Walk<F, X> {
    Float(F),
    Fixed(X),
}

impl<F: Iterator<Item = Span>, X: Iterator<Item = Span>> Iterator for Walk<F, X> {
    type Item = Span;

    #[inline(always)]
    fn next(&mut self) -> Option<Span> {
        match self {
            Walk::Float(f) => f.next(),
            Walk::Fixed(x) => x.next(),
        }
    }
}

/// The MAME / DOSBox Staging walk in single-precision floating point.
fn spans_float(p: &TriangleParams, rounding: EdgeRounding) -> FloatSpans {
    let mut v = [
        (p.ax as f32 * (1.0 / 16.0), p.ay as f32 * (1.0 / 16.0)),
        (p.bx as f32 * (1.0 / 16.0), p.by as f32 * (1.0 / 16.0)),
        (p.cx as f32 * (1.0 / 16.0), p.cy as f32 * (1.0 / 16.0)),
    ];
    // Sort by Y with the same compare-and-swap sequence as the references (stable for ties).
    if v[1].1 < v[0].1 {
        v.swap(0, 1);
    }
    if v[2].1 < v[1].1 {
        v.swap(1, 2);
        if v[1].1 < v[0].1 {
            v.swap(0, 1);
        }
    }
    let [(x1, y1), (x2, y2), (x3, y3)] = v;
    let top = rounding.round(y1);
    let bottom = rounding.round(y3);
    let slope =
        |xa: f32, ya: f32, xb: f32, yb: f32| if yb == ya { 0.0 } else { (xb - xa) / (yb - ya) };
    FloatSpans {
        edges: FloatEdges {
            x1,
            y1,
            x2,
            y2,
            d13: slope(x1, y1, x3, y3),
            d12: slope(x1, y1, x2, y2),
            d23: slope(x2, y2, x3, y3),
            rounding,
        },
        y: top,
        bottom: bottom.max(top),
        block: [(0, 0); BLOCK_ROWS],
        at: 0,
        len: 0,
    }
}

/// A triangle's edges as the float walk samples them: vertices sorted by Y and the
/// slopes of the long edge (1 to 3) and of the two short ones.
#[derive(Clone, Copy)]
struct FloatEdges {
    x1: f32,
    y1: f32,
    x2: f32,
    y2: f32,
    d13: f32,
    d12: f32,
    d23: f32,
    rounding: EdgeRounding,
}

impl FloatEdges {
    /// Row `y`'s span: where the long edge and the short edge it meets cross the row's
    /// centre, rounded to pixel boundaries; `None` where both round to the same one. The
    /// statement of the walk, row by row, that [`FloatEdges::block`] computes eight rows
    /// at a time (the test compares them).
    #[cfg(test)]
    fn span(&self, y: i32) -> Option<Span> {
        let fy = y as f32 + 0.5;
        let a = self.x1 + (fy - self.y1) * self.d13;
        let b = if fy < self.y2 {
            self.x1 + (fy - self.y1) * self.d12
        } else {
            self.x2 + (fy - self.y2) * self.d23
        };
        let (mut start, mut stop) = (self.rounding.round(a), self.rounding.round(b));
        if start == stop {
            return None;
        }
        if start > stop {
            std::mem::swap(&mut start, &mut stop);
        }
        Some(Span { y, start, stop })
    }
}

/// Rows the float walk computes at a time: their edge crossings are computed together,
/// with no branch (each row's crossings are independent of the others'), and then handed
/// out one span at a time.
const BLOCK_ROWS: usize = 8;

/// The spans of the float walk, top to bottom: rows' crossings computed
/// [`BLOCK_ROWS`] at a time ([`FloatEdges::block`]), equal to [`FloatEdges::span`] row by
/// row (a struct rather than a closure over the rows, so that the walk's loop inlines a
/// row's work).
pub struct FloatSpans {
    edges: FloatEdges,
    /// The next row to compute, and the row after the last.
    y: i32,
    bottom: i32,
    /// The computed rows' `(start, stop)` (equal where a row is empty): rows
    /// `y - len..y`, of which `at..len` are still to be handed out.
    block: [(i32, i32); BLOCK_ROWS],
    at: usize,
    len: usize,
}

impl FloatEdges {
    /// The crossings of rows `y..y + BLOCK_ROWS` as [`FloatEdges::span`] rounds them,
    /// ordered, `(start, start)` where a row is empty: the same arithmetic, with selects
    /// in place of the branches, so that the rows' rounding chains run side by side.
    #[inline(always)]
    fn block(&self, y: i32) -> [(i32, i32); BLOCK_ROWS] {
        let mut out = [(0, 0); BLOCK_ROWS];
        for (i, o) in out.iter_mut().enumerate() {
            let fy = (y + i as i32) as f32 + 0.5;
            let a = self.x1 + (fy - self.y1) * self.d13;
            let upper = fy < self.y2;
            let (x0, y0, d) = if upper {
                (self.x1, self.y1, self.d12)
            } else {
                (self.x2, self.y2, self.d23)
            };
            let b = x0 + (fy - y0) * d;
            let (start, stop) = (self.rounding.round(a), self.rounding.round(b));
            *o = (start.min(stop), start.max(stop));
        }
        out
    }
}

impl Iterator for FloatSpans {
    type Item = Span;

    #[inline(always)]
    fn next(&mut self) -> Option<Span> {
        loop {
            while self.at < self.len {
                let i = self.at;
                self.at += 1;
                let (start, stop) = self.block[i];
                if start != stop {
                    return Some(Span {
                        y: self.y - (self.len - i) as i32,
                        start,
                        stop,
                    });
                }
            }
            if self.y >= self.bottom {
                return None;
            }
            self.block = self.edges.block(self.y);
            self.at = 0;
            self.len = (self.bottom - self.y).min(BLOCK_ROWS as i32) as usize;
            self.y += self.len as i32;
        }
    }
}

/// `count` pseudo-random triangles from `seed` (xorshift), the `k`-th with vertex
/// coordinates within `ranges[k % ranges.len()]` sixteenths of a pixel around 0 and
/// every other one right to left: slivers to the whole 12.4 range, for the walks' tests.
#[cfg(test)]
pub(crate) fn random_triangles(
    mut seed: u64,
    count: usize,
    ranges: &[i32],
) -> impl Iterator<Item = TriangleParams> + '_ {
    let mut next = move |range: i32| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 33) as i32 % range - range / 2
    };
    (0..count).map(move |k| {
        let range = ranges[k % ranges.len()];
        let v: [i16; 6] = core::array::from_fn(|_| next(range) as i16);
        TriangleParams {
            ax: v[0],
            ay: v[1],
            bx: v[2],
            by: v[3],
            cx: v[4],
            cy: v[5],
            right_to_left: k % 2 == 0,
            ..Default::default()
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_walk_in_blocks_of_rows_is_the_walk_row_by_row() {
        // Random triangles from slivers to the whole 12.4 range, both float roundings:
        // the spans handed out from blocks of rows are those of the rows one at a time.
        let mut rows = 0;
        for p in random_triangles(0x9e37_79b9_7f4a_7c15, 20_000, &[16, 64, 300, 1024, 65536]) {
            for rounding in [EdgeRounding::FloorHalfDown, EdgeRounding::TruncHalfDown] {
                let walk = spans_float(&p, rounding);
                let (edges, top, bottom) = (walk.edges, walk.y, walk.bottom);
                let by_row: Vec<Span> = (top..bottom).filter_map(|y| edges.span(y)).collect();
                let blocks: Vec<Span> = walk.collect();
                assert_eq!(blocks, by_row, "{p:?} {rounding:?}");
                rows += by_row.len();
            }
        }
        assert!(rows > 100_000, "{rows}");
    }

    #[test]
    fn rounding_without_libm_equals_rounding_with_it() {
        let reference = |rounding: EdgeRounding, v: f32| {
            let base = match rounding {
                EdgeRounding::TruncHalfDown => v.trunc(),
                _ => v.floor(),
            };
            base as i32 + i32::from(v - base > 0.5)
        };
        // Every value that matters for 12.4 coordinates and their slopes, the edges of
        // the fast range, and bit patterns spread over every exponent (NaN, infinities).
        let mut values: Vec<f32> = (-70_000..70_000).map(|i| i as f32 / 16.0).collect();
        for e in [
            8_388_607.5f32,
            8_388_608.0,
            8_388_609.0,
            16_777_217.0,
            0.5,
            0.49999997,
        ] {
            values.extend([
                e,
                -e,
                f32::from_bits(e.to_bits() + 1),
                -f32::from_bits(e.to_bits() - 1),
            ]);
        }
        values.extend([
            0.0,
            -0.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            f32::MIN,
            f32::MAX,
        ]);
        let mut bits = 0x1234_5678u32;
        for _ in 0..200_000 {
            bits ^= bits << 13;
            bits ^= bits >> 17;
            bits ^= bits << 5;
            values.push(f32::from_bits(bits));
        }
        for rounding in [EdgeRounding::FloorHalfDown, EdgeRounding::TruncHalfDown] {
            for &v in &values {
                assert_eq!(
                    rounding.round(v),
                    reference(rounding, v),
                    "{rounding:?} {v:e}"
                );
            }
        }
    }

    fn tri(a: (f32, f32), b: (f32, f32), c: (f32, f32)) -> TriangleParams {
        let f = |v: f32| (v * 16.0) as i16;
        TriangleParams {
            ax: f(a.0),
            ay: f(a.1),
            bx: f(b.0),
            by: f(b.1),
            cx: f(c.0),
            cy: f(c.1),
            ..Default::default()
        }
    }

    #[test]
    fn rounding_modes() {
        let r = EdgeRounding::FloorHalfDown;
        assert_eq!(
            (r.round(2.5), r.round(2.5625), r.round(-0.75), r.round(-0.5)),
            (2, 3, -1, -1)
        );
        let t = EdgeRounding::TruncHalfDown;
        assert_eq!(
            (t.round(2.5), t.round(2.5625), t.round(-0.75), t.round(-0.5)),
            (2, 3, 0, 0)
        );
    }

    #[test]
    fn right_triangle_spans() {
        // (0,0) (8,0) (0,8): row y covers x in [0, 8 - (y + 0.5)) rounded.
        let s: Vec<Span> = spans(
            &tri((0.0, 0.0), (8.0, 0.0), (0.0, 8.0)),
            EdgeRounding::default(),
        )
        .collect();
        // Row 7 samples x = 0.5, which rounds to an empty span.
        assert_eq!(s.len(), 7);
        assert_eq!(
            s[0],
            Span {
                y: 0,
                start: 0,
                stop: 7
            }
        );
        assert_eq!(
            s[6],
            Span {
                y: 6,
                start: 0,
                stop: 1
            }
        );
        let total: i32 = s.iter().map(|s| s.stop - s.start).sum();
        assert_eq!(total, 7 + 6 + 5 + 4 + 3 + 2 + 1);
    }

    /// A = (75, 27), B = (196, 80), C = (30, 85) in 1/16 pixel, walked left to right:
    /// rows 2 and 4 have edge crossings that the float walk and 86Box's 16.16 walk
    /// round to different pixels.
    #[test]
    fn box86_fixed_walk_differs_at_the_edges() {
        let p = TriangleParams {
            ax: 75,
            ay: 27,
            bx: 196,
            by: 80,
            cx: 30,
            cy: 85,
            ..Default::default()
        };
        let rows = |r: EdgeRounding| -> Vec<(i32, i32, i32)> {
            spans(&p, r).map(|s| (s.y, s.start, s.stop)).collect()
        };
        assert_eq!(
            rows(EdgeRounding::FloorHalfDown),
            [(2, 4, 7), (3, 3, 9), (4, 3, 11)]
        );
        assert_eq!(
            rows(EdgeRounding::Box86Fixed),
            [(2, 4, 6), (3, 3, 9), (4, 2, 11)]
        );
        // Walked right to left, the same edges cross the wrong way round: no rows.
        let mirrored = TriangleParams {
            right_to_left: true,
            ..p
        };
        assert_eq!(spans(&mirrored, EdgeRounding::Box86Fixed).count(), 0);
    }

    #[test]
    fn degenerate_and_hostile_triangles() {
        assert_eq!(
            spans(
                &tri((0.0, 5.0), (9.0, 5.0), (3.0, 5.0)),
                EdgeRounding::default()
            )
            .count(),
            0
        );
        let p = TriangleParams {
            ax: i16::MIN,
            ay: i16::MIN,
            bx: i16::MAX,
            by: i16::MAX,
            cx: 0,
            cy: i16::MAX,
            ..Default::default()
        };
        // Must not panic. 4096 rows are walked; the rows at the two sharp ends sample
        // spans narrower than half a pixel, which round to empty.
        assert_eq!(spans(&p, EdgeRounding::default()).count(), 4094);
        // The fixed-point walk wraps in 32 bits as 86Box's does, without panicking.
        let _ = spans(&p, EdgeRounding::Box86Fixed).count();
    }
}

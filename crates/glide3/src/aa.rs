//! Anti-aliased points, lines, triangles and polygons (`grEnable(GR_AA_ORDERED)`,
//! `grAADrawTriangle`).
//!
//! The SST-1 has no coverage hardware: Glide draws each primitive and then thin "edge
//! triangles" one pixel wide along its edges, with the same colour parameters but an
//! alpha that ramps from the vertex alpha to 0 across that pixel (spec 5: the `Fa`,
//! `FdAdX`, `FdAdY` iterators), so alpha blending (`GR_BLEND_SRC_ALPHA`,
//! `GR_BLEND_ONE_MINUS_SRC_ALPHA`) fades the edge into the background. The program must
//! enable that blend and an iterated-alpha combine, as with 3dfx's library.
//!
//! Source for the geometry, the order of the register writes and the alpha gradient
//! expressions: 3dfx Glide 3 for the SST-1, `gaa.c` (`_grAADrawPoint`,
//! `_grAADrawLine`, `grAADrawTriEdgeSense`, `grAADrawTriangle`), read for facts only.
//! Points become four triangles around the pixel, lines four triangles along both
//! sides, and each antialiased triangle edge two triangles on its outer side. Edge
//! triangles take the vertex coordinates with the snap bias added but unsorted; the
//! main triangle of `grAADrawTriangle` goes through the normal setup. While edges
//! are drawn, depth writes are off (`fbzMode` without `zaWrMask`), so edges never
//! occlude.
//!
//! The edge triangles write the start values of every parameter (not their
//! gradients: those stay as the main primitive set them) and then the alpha start and
//! gradients. Arithmetic: 3dfx's code ran on the x87; values held in `float`
//! variables are rounded to `f32` here (each statement that assigns one stores it), the
//! expression on its right evaluated in x87 extended precision, as the triangle setup's
//! parameter differences are (draw.rs). The glide-sdk test24 trace (lines,
//! tests/aa_trace.rs) is matched bit for bit; it is matched too with `dp` kept in
//! extended precision, so the rounding of `dp` rests on gaa.c's `float dp` and on
//! test08's triangles, not on a line trace.

use crate::draw::{fetch, fetch_byte, SNAP_BIAS};
use crate::x87::Ext;
use sst1_regs::addr::*;
use sst1_regs::FbzMode;

/// `GR_AA_ORDERED` sets these bits of the smoothing mode (3dfx `fxglide.h`:
/// `GR_AA_ORDERED_{POINTS,LINES,TRIANGLES}_MASK`).
pub(crate) const AA_POINTS: u32 = 1;
/// Lines are antialiased.
pub(crate) const AA_LINES: u32 = 2;
/// Triangles (and polygons) are antialiased.
pub(crate) const AA_TRIANGLES: u32 = 4;

/// Which side of an edge is outside the triangle (3dfx `aaEdgeSense`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Sense {
    Top,
    Left,
    Bottom,
    Right,
}

/// `f32` product rounded once (x87 product stored to a `float`).
fn mul(a: f32, b: f32) -> f32 {
    (f64::from(a) * f64::from(b)) as f32
}

/// `a - b + c` evaluated on the x87 (extended) and stored to a `float` variable.
/// Non-finite inputs follow IEEE arithmetic in `f64`.
fn x87_sum(a: f32, b: f32, c: f32) -> f32 {
    if [a, b, c].iter().all(|v| v.is_finite()) {
        let e = |v: f32| Ext::from_f64(f64::from(v));
        e(a).sub(e(b)).add(e(c)).to_f32()
    } else {
        (f64::from(a) - f64::from(b) + f64::from(c)) as f32
    }
}

impl crate::Glide {
    /// Vertex `v`'s x and y (the layout's `GR_PARAM_XY`) plus the 3 * 2^18 snap bias,
    /// which leaves 4 fraction bits (12.4). The glide-sdk test24 trace shows the bias
    /// on every antialiased-line coordinate (the gaa.c revision we read does not add
    /// it; the traced library did, as for aliased lines in test02).
    fn xy(&self, v: &[f32]) -> (f32, f32) {
        let o = self.layout.xy.offset;
        (fetch(v, o) + SNAP_BIAS, fetch(v, o + 4) + SNAP_BIAS)
    }

    /// Vertex `v`'s alpha: the float at `GR_PARAM_A`, or the alpha byte of
    /// `GR_PARAM_PARGB` for packed colours.
    fn alpha(&self, v: &[f32]) -> f32 {
        let l = &self.layout;
        if l.packed_color {
            fetch_byte(v, l.pargb.offset + 3)
        } else {
            fetch(v, l.a.offset)
        }
    }

    /// The start value of every parameter of the data list at vertex `v`, no gradients
    /// (3dfx `grSetVertexParameter`).
    fn start_values(&mut self, v: &[f32]) {
        for i in 0..self.data_list.len() {
            let e = self.data_list[i];
            let val = crate::draw::value(v, e);
            self.send_start(e, val);
        }
    }

    /// Start values and zero gradients of every parameter (the flat first triangle of an
    /// antialiased point).
    fn flat_values(&mut self, v: &[f32]) {
        for i in 0..self.data_list.len() {
            let e = self.data_list[i];
            let val = crate::draw::value(v, e);
            if let Some(reg) = self.send_start(e, val) {
                self.hw.wf(reg + 0x20, 0.0);
                self.hw.wf(reg + 0x40, 0.0);
            }
        }
    }

    /// Start values and gradients along one axis for a line from `a` to `b`, `m` being
    /// 1 / (the coordinate difference a - b along that axis, or its negation for Y).
    fn line_gradients(&mut self, a: &[f32], b: &[f32], m: f32, x_major: bool) {
        for i in 0..self.data_list.len() {
            let e = self.data_list[i];
            let pa = crate::draw::value(a, e);
            let Some(reg) = self.send_start(e, pa) else {
                continue;
            };
            // `dp` is a `float` variable: the difference is rounded before the product
            // (gaa.c `_grAADrawLineStrip`).
            let dp = mul(x87_sum(pa, crate::draw::value(b, e), 0.0), m);
            if x_major {
                self.hw.wf(reg + 0x20, dp);
                self.hw.wf(reg + 0x40, 0.0);
            } else {
                self.hw.wf(reg + 0x20, 0.0);
                self.hw.wf(reg + 0x40, dp);
            }
        }
    }

    /// `_grAADrawPoint`: four triangles meeting at the point, alpha falling to 0 one
    /// pixel away.
    pub(crate) fn aa_point(&mut self, v: &[f32]) {
        self.flush_state();
        let (px, py) = self.xy(v);
        // The gradient is -alpha per pixel (sign bit flipped), then +alpha.
        let j = self.alpha(v).to_bits() ^ 0x8000_0000;
        // E-D-A: the triangle below the point.
        self.hw.wf(F_VERTEX_AX, px);
        self.hw.wf(F_VERTEX_BX, px - 1.0);
        self.hw.wf(F_VERTEX_CX, px + 1.0);
        self.hw.wf(F_VERTEX_AY, py);
        self.hw.wf(F_VERTEX_BY, py + 1.0);
        self.hw.wf(F_VERTEX_CY, py + 1.0);
        self.flat_values(v);
        self.hw.w(F_D_A_DY, j);
        self.hw.w(TRIANGLE_CMD, 0xffff_ffff);
        // B-E-C: the right quarter.
        self.hw.wf(F_VERTEX_AX, px + 1.0);
        self.hw.wf(F_VERTEX_BX, px);
        self.hw.wf(F_VERTEX_AY, py - 1.0);
        self.hw.wf(F_VERTEX_BY, py);
        self.hw.w(F_START_A, 0);
        self.hw.w(F_D_A_DX, j);
        self.hw.w(F_D_A_DY, 0);
        self.hw.w(TRIANGLE_CMD, 0xffff_ffff);
        // A-E-D: the left quarter.
        self.hw.wf(F_VERTEX_AX, px - 1.0);
        self.hw.wf(F_VERTEX_CX, px - 1.0);
        let j = j ^ 0x8000_0000;
        self.hw.w(F_START_A, 0);
        self.hw.w(F_D_A_DX, j);
        self.hw.w(TRIANGLE_CMD, 1);
        // A-B-E: the triangle above.
        self.hw.wf(F_VERTEX_BX, px + 1.0);
        self.hw.wf(F_VERTEX_CX, px);
        self.hw.wf(F_VERTEX_BY, py - 1.0);
        self.hw.wf(F_VERTEX_CY, py);
        self.hw.w(F_START_A, 0);
        self.hw.w(F_D_A_DX, 0);
        self.hw.w(F_D_A_DY, j);
        self.hw.w(TRIANGLE_CMD, 1);
        self.stats.points += 1;
    }

    /// `_grAADrawLine`: the line as four triangles, two on each side, alpha falling from
    /// the vertex alpha on the line to 0 one pixel away.
    pub(crate) fn aa_line(&mut self, a: &[f32], b: &[f32]) {
        self.flush_state();
        let (mut v1, mut v2) = (a, b);
        if self.xy(v2).1 < self.xy(v1).1 {
            std::mem::swap(&mut v1, &mut v2);
        }
        let ((x1, y1), (x2, y2)) = (self.xy(v1), self.xy(v2));
        let (a1, a2) = (self.alpha(v1), self.alpha(v2));
        let dx = x1 - x2;
        let dy = y2 - y1;
        self.stats.lines += 1;
        let w = |g: &mut Self, reg: u32, v: f32| g.hw.wf(reg, v);
        if dx.abs() >= dy {
            if dx == 0.0 {
                return;
            }
            // X major: A(x1, y1-1) B(x2, y2-1) V2, then V1-V2 below.
            w(self, F_VERTEX_AX, x1);
            let m = 1.0f32 / dx;
            w(self, F_VERTEX_AY, y1 - 1.0);
            let tmp1 = -mul(a1, dy);
            w(self, F_VERTEX_BX, x2);
            w(self, F_VERTEX_BY, y2 - 1.0);
            let tmp2 = -mul(a2, dy);
            w(self, F_VERTEX_CX, x2);
            w(self, F_VERTEX_CY, y2);
            self.line_gradients(v1, v2, m, true);
            self.hw.w(F_START_A, 0);
            w(self, F_D_A_DX, mul(-tmp2, m));
            w(self, F_D_A_DY, a2);
            w(self, F_TRIANGLE_CMD, -m);
            // A-V1-V2.
            w(self, F_VERTEX_BX, x1);
            self.start_values(v1);
            self.hw.w(F_START_A, 0);
            w(self, F_VERTEX_BY, y1);
            w(self, F_D_A_DY, a1);
            // `dp = a1 - a2; dp -= tmp1; dp *= m`, each step stored to the float `dp`.
            let dp = mul(x87_sum(x87_sum(a1, a2, 0.0), tmp1, 0.0), m);
            w(self, F_D_A_DX, dp);
            w(self, F_TRIANGLE_CMD, m);
            // V1-E-F below the line.
            w(self, F_VERTEX_AY, y1);
            w(self, F_VERTEX_BY, y1 + 1.0);
            w(self, F_VERTEX_CY, y2 + 1.0);
            self.start_values(v1);
            w(self, F_D_A_DY, -a1);
            w(self, F_D_A_DX, mul(tmp1, m));
            w(self, F_TRIANGLE_CMD, m);
            // V1-V2-F.
            w(self, F_VERTEX_BX, x2);
            let dp = mul(x87_sum(a1, a2, tmp2), m);
            w(self, F_VERTEX_BY, y2);
            self.start_values(v1);
            w(self, F_D_A_DX, dp);
            w(self, F_D_A_DY, -a2);
            w(self, F_TRIANGLE_CMD, -m);
        } else {
            if dy == 0.0 {
                return;
            }
            // Y major: V1-V2-(x2-1, y2), then the other side.
            w(self, F_VERTEX_AX, x1);
            let tmp1 = mul(a1, dx);
            w(self, F_VERTEX_AY, y1);
            let tmp2 = mul(a2, dx);
            w(self, F_VERTEX_BX, x2);
            let m = -1.0f32 / dy;
            w(self, F_VERTEX_BY, y2);
            w(self, F_VERTEX_CX, x2 - 1.0);
            w(self, F_VERTEX_CY, y2);
            self.line_gradients(v1, v2, m, false);
            let dp = mul(x87_sum(a1, tmp2, -a2), m);
            w(self, F_D_A_DX, a2);
            w(self, F_D_A_DY, dp);
            w(self, F_TRIANGLE_CMD, -m);
            // V1-A-B.
            w(self, F_VERTEX_BX, x1 - 1.0);
            w(self, F_VERTEX_BY, y1);
            self.start_values(v1);
            w(self, F_D_A_DX, a1);
            w(self, F_D_A_DY, mul(-tmp1, m));
            w(self, F_TRIANGLE_CMD, m);
            // E-V1-V2 on the right.
            w(self, F_VERTEX_AX, x1 + 1.0);
            let dp = mul(x87_sum(a1, a2, tmp1), m);
            w(self, F_VERTEX_BX, x1);
            w(self, F_VERTEX_CX, x2);
            self.start_values(v1);
            self.hw.w(F_START_A, 0);
            w(self, F_D_A_DX, -a1);
            w(self, F_D_A_DY, dp);
            w(self, F_TRIANGLE_CMD, m);
            // E-F-V2.
            w(self, F_VERTEX_BX, x2 + 1.0);
            w(self, F_VERTEX_BY, y2);
            self.start_values(v1);
            self.hw.w(F_START_A, 0);
            w(self, F_D_A_DX, -a2);
            w(self, F_D_A_DY, mul(tmp2, m));
            w(self, F_TRIANGLE_CMD, -m);
        }
    }

    /// `grAADrawTriangle` in window coordinates: the triangle, then two edge triangles
    /// outside each edge whose flag is set, with depth writes off meanwhile.
    pub(crate) fn aa_triangle_window(&mut self, a: &[f32], b: &[f32], c: &[f32], edges: [bool; 3]) {
        if self.trisetup(a, b, c) <= 0 {
            return;
        }
        let fbz = self.st.fbi.fbz_mode;
        self.hw
            .w(FBZ_MODE, FbzMode(fbz).with_aux_buffer_mask(false).0);
        if edges[0] {
            self.aa_edge(a, b, c);
        }
        if edges[1] {
            self.aa_edge(b, c, a);
        }
        if edges[2] {
            self.aa_edge(c, a, b);
        }
        self.hw.w(FBZ_MODE, fbz);
    }

    /// `grAADrawTriEdgeSense`: the edge a-b of a triangle whose third vertex is `c`.
    fn aa_edge(&mut self, a: &[f32], b: &[f32], c: &[f32]) {
        let (mut a, mut b) = (a, b);
        if self.xy(a).1 >= self.xy(b).1 {
            std::mem::swap(&mut a, &mut b);
        }
        let ((ax, ay), (bx, by), (cx, cy)) = (self.xy(a), self.xy(b), self.xy(c));
        let dx = ax - bx;
        let dy = ay - by;
        let (aa, ba) = (self.alpha(a), self.alpha(b));
        let sense = if dx == 0.0 {
            if cx > ax {
                Sense::Left
            } else {
                Sense::Right
            }
        } else if dy == 0.0 {
            if cy > ay {
                Sense::Bottom
            } else {
                Sense::Top
            }
        } else {
            // Which side c lies on: the cross product of (a - c) and (b - c).
            let cp =
                f64::from(ax - cx) * f64::from(by - cy) - f64::from(ay - cy) * f64::from(bx - cx);
            match (dx > 0.0, dx >= -dy, dx <= dy) {
                (true, true, _) if cp > 0.0 => Sense::Top,
                (true, true, _) => Sense::Bottom,
                (true, false, _) if cp > 0.0 => Sense::Right,
                (true, false, _) => Sense::Left,
                (false, _, true) if cp < 0.0 => Sense::Top,
                (false, _, true) => Sense::Bottom,
                (false, _, false) if cp < 0.0 => Sense::Left,
                (false, _, false) => Sense::Right,
            }
        };
        let w = |g: &mut Self, reg: u32, v: f32| g.hw.wf(reg, v);
        // `dp = p - q + r; dp *= m`: each statement stores the float `dp`.
        let lin = |p: f32, q: f32, r: f32, m: f32| mul(x87_sum(p, q, r), m);
        match sense {
            Sense::Top => {
                w(self, F_VERTEX_AX, ax);
                w(self, F_VERTEX_AY, ay);
                w(self, F_VERTEX_BX, ax);
                w(self, F_VERTEX_CX, bx);
                let m = 1.0f32 / dx;
                w(self, F_VERTEX_BY, ay + 1.0);
                let dp = mul(aa, dy);
                w(self, F_VERTEX_CY, by + 1.0);
                self.start_values(a);
                w(self, F_D_A_DY, -aa);
                w(self, F_D_A_DX, mul(dp, m));
                w(self, TRIANGLE_CMD, dx);
                let dp = mul(ba, dy);
                w(self, F_VERTEX_BX, bx);
                let dp = lin(aa, ba, dp, m);
                w(self, F_VERTEX_BY, by);
                self.start_values(a);
                w(self, F_D_A_DY, -ba);
                w(self, F_D_A_DX, dp);
                w(self, TRIANGLE_CMD, -dx);
            }
            Sense::Left | Sense::Right => {
                let side = if sense == Sense::Left { -1.0 } else { 1.0 };
                w(self, F_VERTEX_AY, ay);
                w(self, F_VERTEX_BX, ax);
                w(self, F_VERTEX_BY, ay);
                w(self, F_VERTEX_CY, by);
                let m = 1.0f32 / dy;
                w(self, F_VERTEX_AX, ax + side);
                w(self, F_VERTEX_CX, bx + side);
                self.start_values(a);
                self.hw.w(F_START_A, 0);
                // Left: alpha rises to the right; right: it falls.
                let cmd = if sense == Sense::Left { -dy } else { dy };
                w(self, F_D_A_DX, -side * aa);
                w(self, F_D_A_DY, mul(mul(side * aa, dx), m));
                w(self, TRIANGLE_CMD, cmd);
                w(self, F_VERTEX_AX, ax);
                let dp = mul(ba, dx);
                w(self, F_VERTEX_BX, bx);
                let dp = if sense == Sense::Left {
                    lin(aa, dp, -ba, m)
                } else {
                    lin(dp, -aa, -ba, m)
                };
                w(self, F_VERTEX_BY, by);
                self.start_values(a);
                w(self, F_D_A_DX, -side * ba);
                w(self, F_D_A_DY, dp);
                w(self, TRIANGLE_CMD, cmd);
            }
            Sense::Bottom if dy < -1.0 => {
                w(self, F_VERTEX_AX, ax);
                w(self, F_VERTEX_BX, ax);
                w(self, F_VERTEX_BY, ay);
                w(self, F_VERTEX_CX, bx);
                let m = 1.0f32 / dx;
                w(self, F_VERTEX_AY, ay - 1.0);
                w(self, F_VERTEX_CY, by - 1.0);
                self.start_values(a);
                self.hw.w(F_START_A, 0);
                let dp = mul(mul(aa, dy), m);
                w(self, F_D_A_DX, -dp);
                w(self, F_D_A_DY, aa);
                w(self, TRIANGLE_CMD, dx);
                w(self, F_VERTEX_AY, ay);
                let dp = mul(ba, dy);
                w(self, F_VERTEX_BX, bx);
                w(self, F_VERTEX_BY, by - 1.0);
                let dp = lin(aa, ba, -dp, m);
                w(self, F_VERTEX_CY, by);
                self.start_values(a);
                w(self, F_D_A_DY, ba);
                w(self, F_D_A_DX, dp);
                w(self, TRIANGLE_CMD, -dx);
            }
            Sense::Bottom if dy == 0.0 => {
                w(self, F_VERTEX_AX, ax);
                w(self, F_VERTEX_CX, bx);
                w(self, F_VERTEX_CY, by);
                w(self, F_VERTEX_BX, bx);
                let m = 1.0f32 / dx;
                w(self, F_VERTEX_AY, ay - 1.0);
                w(self, F_VERTEX_BY, by - 1.0);
                self.start_values(a);
                self.hw.w(F_START_A, 0);
                self.hw.w(F_D_A_DX, 0);
                w(self, F_D_A_DY, ba);
                w(self, TRIANGLE_CMD, -dx);
                w(self, F_VERTEX_BX, ax);
                w(self, F_VERTEX_BY, ay);
                self.start_values(a);
                self.hw.w(F_START_A, 0);
                w(self, F_D_A_DY, aa);
                w(self, F_D_A_DX, lin(aa, ba, 0.0, m));
                w(self, TRIANGLE_CMD, dx);
            }
            Sense::Bottom => {
                w(self, F_VERTEX_AX, ax);
                w(self, F_VERTEX_BX, bx);
                w(self, F_VERTEX_CX, ax);
                w(self, F_VERTEX_CY, ay);
                let m = 1.0f32 / dx;
                w(self, F_VERTEX_AY, ay - 1.0);
                w(self, F_VERTEX_BY, by - 1.0);
                self.start_values(a);
                self.hw.w(F_START_A, 0);
                w(self, F_D_A_DX, mul(mul(-aa, dy), m));
                w(self, F_D_A_DY, aa);
                w(self, TRIANGLE_CMD, -dx);
                w(self, F_VERTEX_AX, bx);
                w(self, F_VERTEX_AY, by - 1.0);
                w(self, F_VERTEX_BX, ax);
                w(self, F_VERTEX_BY, ay);
                let dp = mul(ba, dy);
                w(self, F_VERTEX_CX, bx);
                w(self, F_VERTEX_CY, by);
                self.start_values(b);
                self.hw.w(F_START_A, 0);
                w(self, F_D_A_DY, ba);
                w(self, F_D_A_DX, lin(aa, dp, -ba, m));
                w(self, TRIANGLE_CMD, dx);
            }
        }
    }
}

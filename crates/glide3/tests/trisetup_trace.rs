//! Triangle setup must reproduce 3dfx's SST-1 Glide 3 start and gradient values bit
//! for bit. test04 (glide3x/sst1/glide3/tests/test04.c) draws one Gouraud triangle:
//! A = (0.3, 0.3) red, B = (0.8, 0.4) green, C = (0.5, 0.8) blue, scaled to 640x480,
//! after `grColorCombine(LOCAL, NONE, ITERATED, NONE)` and a black clear.

mod common;
use common::{assert_prefix, trace, Op, Rec};
use glide::consts::*;
use glide::{BoardInfo, Glide};

/// A tlib `GrVertex`: x, y, ooz, oow, r, g, b, a, z, then TMU s/t/w triples.
fn vertex(x: f32, y: f32, r: f32, g: f32, b: f32) -> [f32; 15] {
    let mut v = [0.0; 15];
    v[0] = x;
    v[1] = y;
    v[4] = r;
    v[5] = g;
    v[6] = b;
    v
}

#[test]
fn test04_gouraud_triangle_registers() {
    let (rec, mut g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    let mut w = [0i32; 2];
    g.get(GR_WDEPTH_MIN_MAX, 8, &mut w);
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_RGB, 4 << 2, GR_PARAM_ENABLE);
    g.color_combine(
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_LOCAL_ITERATED,
        GR_COMBINE_OTHER_NONE,
        false,
    );
    g.buffer_clear(0, 0, w[1] as u32);
    let (sx, sy) = (640.0f32, 480.0f32);
    let a = vertex(0.3 * sx, 0.3 * sy, 255.0, 0.0, 0.0);
    let b = vertex(0.8 * sx, 0.4 * sy, 0.0, 255.0, 0.0);
    let c = vertex(0.5 * sx, 0.8 * sy, 0.0, 0.0, 255.0);
    let before = rec.0.borrow().len();
    g.draw_triangle(&a, &b, &c);
    let ours = rec.0.borrow().clone();
    // 6 vertex coordinates, 3 x (start, d/dx, d/dy), the area.
    assert_eq!(ours.len() - before, 16);
    assert_prefix(&ours, &trace("test04"), "test04 triangle");
    assert_eq!(g.stats().triangles_drawn, 1);
}

#[test]
fn culling_and_zero_area() {
    let rec = Rec::default();
    let mut g = Glide::init(Box::new(rec.clone()), BoardInfo::new(4, 1, 4));
    assert!(g.win_open(
        GR_RESOLUTION_640x480,
        GR_REFRESH_60Hz,
        GR_COLORFORMAT_ARGB,
        GR_ORIGIN_UPPER_LEFT,
        2,
        1
    ));
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    let a = vertex(10.0, 10.0, 0.0, 0.0, 0.0);
    let b = vertex(100.0, 10.0, 0.0, 0.0, 0.0);
    let c = vertex(10.0, 100.0, 0.0, 0.0, 0.0);
    // Screen-space area of (a, b, c) with y down: the sign the chip sees.
    g.cull_mode(GR_CULL_NEGATIVE);
    g.draw_triangle(&a, &b, &c);
    g.draw_triangle(&a, &c, &b);
    g.cull_mode(GR_CULL_POSITIVE);
    g.draw_triangle(&a, &b, &c);
    g.draw_triangle(&a, &c, &b);
    g.cull_mode(GR_CULL_DISABLE);
    g.draw_triangle(&a, &a, &c);
    let s = g.stats();
    assert_eq!((s.triangles_in, s.triangles_drawn), (5, 2));
    // A vertex at infinity or NaN: nothing reaches the chip.
    let before = rec.0.borrow().len();
    g.draw_triangle(&vertex(f32::NAN, 10.0, 0.0, 0.0, 0.0), &b, &c);
    g.draw_triangle(&a, &vertex(100.0, f32::INFINITY, 0.0, 0.0, 0.0), &c);
    assert_eq!(rec.0.borrow().len(), before);
    assert_eq!(g.stats().triangles_drawn, 2);
}

/// test02 (glide3x/sst1/glide3/tests/test02.c): 100 lines from (i/100, 0) to
/// (1, i/100), flat white. Every line's two half-triangles must match the trace.
#[test]
fn test02_lines_registers() {
    let (rec, mut g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    let mut w = [0i32; 2];
    g.get(GR_WDEPTH_MIN_MAX, 8, &mut w);
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    g.color_combine(
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_LOCAL_CONSTANT,
        GR_COMBINE_OTHER_NONE,
        false,
    );
    g.constant_color_value(0xffffff);
    g.buffer_clear(0, 0, w[1] as u16 as u32);
    for i in 0..100 {
        let pos = i as f32 / 100.0;
        let a = vertex(pos * 640.0, 0.0, 0.0, 0.0, 0.0);
        let b = vertex(640.0, pos * 480.0, 0.0, 0.0, 0.0);
        g.draw_line(&a, &b);
    }
    let ours = rec.0.borrow().clone();
    assert_prefix(&ours, &trace("test02"), "test02 lines");
    assert_eq!(g.stats().lines, 100);
}

/// The setup writes (`fvertexAx` .. `ftriangleCMD`) of the first `n` triangles of a
/// trace.
fn first_triangles(name: &str, n: usize) -> Vec<Vec<Op>> {
    let mut out = Vec::new();
    let mut cur: Option<Vec<Op>> = None;
    for op in trace(name) {
        let Op::W(a, _) = op else { continue };
        if a == 0x88 {
            cur = Some(Vec::new());
        }
        if let Some(c) = cur.as_mut() {
            c.push(op);
            if a == 0x100 && out.len() < n {
                out.push(cur.take().unwrap_or_default());
            }
        }
    }
    out
}

/// Our setup writes for `draw_triangle(a, b, c)`.
fn setup_writes(g: &mut Glide, rec: &Rec, a: &[f32], b: &[f32], c: &[f32]) -> Vec<Op> {
    let before = rec.0.borrow().len();
    g.draw_triangle(a, b, c);
    let ops = rec.0.borrow()[before..].to_vec();
    ops.into_iter()
        .skip_while(|op| !matches!(op, Op::W(0x88, _)))
        .collect()
}

/// A tlib `GrVertex` with a position and one more float at index `k`.
fn vertex_with(x: f32, y: f32, k: usize, p: f32) -> [f32; 15] {
    let mut v = [0.0; 15];
    v[0] = x;
    v[1] = y;
    v[k] = p;
    v
}

/// test06 (W buffer, oow) and test14 (Z buffer, ooz) draw the same two flat
/// triangles, the second one off the 1/16 grid: A = (0.86, 0.21), B = (0.86, 0.79),
/// C = (0.14, 0.5) times 640x480. 3dfx's area and gradients come from the unsnapped
/// positions.
#[test]
fn test06_test14_unsnapped_positions() {
    let cases: [(&str, usize, f32, [f32; 3]); 2] = [
        ("test06", 3, 1.0, [10.0, 12.5, 7.5]),
        ("test14", 2, 65535.0, [10.0, 12.5, 7.5]),
    ];
    for (name, k, num, dist) in cases {
        let rec = Rec::default();
        let mut g = Glide::init(Box::new(rec.clone()), BoardInfo::new(4, 1, 4));
        assert!(g.win_open(
            GR_RESOLUTION_640x480,
            GR_REFRESH_60Hz,
            GR_COLORFORMAT_ABGR,
            GR_ORIGIN_UPPER_LEFT,
            2,
            1
        ));
        g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
        if k == 3 {
            g.vertex_layout(GR_PARAM_Q, 3 << 2, GR_PARAM_ENABLE);
            g.depth_buffer_mode(GR_DEPTHBUFFER_WBUFFER);
        } else {
            g.vertex_layout(GR_PARAM_Z, 2 << 2, GR_PARAM_ENABLE);
            g.depth_buffer_mode(GR_DEPTHBUFFER_ZBUFFER);
        }
        g.color_combine(
            GR_COMBINE_FUNCTION_LOCAL,
            GR_COMBINE_FACTOR_NONE,
            GR_COMBINE_LOCAL_CONSTANT,
            GR_COMBINE_OTHER_NONE,
            false,
        );
        let (sx, sy) = (640.0f32, 480.0f32);
        let p = |d: f32| num / d;
        let first = [
            vertex_with(0.25 * sx, 0.21 * sy, k, p(dist[0])),
            vertex_with(0.75 * sx, 0.21 * sy, k, p(dist[0])),
            vertex_with(0.5 * sx, 0.79 * sy, k, p(dist[0])),
        ];
        let second = [
            vertex_with(0.86 * sx, 0.21 * sy, k, p(dist[1])),
            vertex_with(0.86 * sx, 0.79 * sy, k, p(dist[1])),
            vertex_with(0.14 * sx, 0.5 * sy, k, p(dist[2])),
        ];
        let theirs = first_triangles(name, 2);
        let ours = [
            setup_writes(&mut g, &rec, &first[0], &first[1], &first[2]),
            setup_writes(&mut g, &rec, &second[0], &second[1], &second[2]),
        ];
        assert_eq!(ours[0], theirs[0], "{name} first triangle");
        assert_eq!(ours[1], theirs[1], "{name} second triangle");
        // ftriangleCMD of the second triangle (the snapped positions would give
        // -128261.28, 0xc7fa82a4).
        assert_eq!(theirs[1].last(), Some(&Op::W(0x100, 0xc7fa_8f5e)));
    }
}

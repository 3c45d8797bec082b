//! Where 3dfx's SST-1 Glide 3 rounds an intermediate value to a `float`: replays of
//! glide-sdk programs (glide3x/sst1/glide3/tests/testNN.c) whose register writes depend
//! on it, each required to equal 3dfx's trace bit for bit.
//!
//! - The parameter differences of the triangle setup (`dpAB`, `dpBC` in gxdraw.c
//!   `_trisetup`) are `float` variables: test08's W goes from 1/20 to 1/2000, whose
//!   difference needs more than 24 bits; kept in extended precision, the W gradients
//!   come out one unit in the last place high. test28's polygon (colours with
//!   fractional differences, `GR_POLYGON`) shows the same in dRdX and dGdX.
//! - test38's gamma tables: the program's gamma values are `float` sums (1.3f + 0.1f),
//!   and its three frames need three key presses, which is why it never ends on an
//!   empty stdin.

mod common;
use common::{assert_prefix, trace};
use glide::consts::*;
use glide::get::{fog_generate_exp, FOG_TABLE_SIZE};

/// A tlib `GrVertex`: x, y, ooz, oow, r, g, b, a, z, then TMU s/t/w triples.
fn vertex(x: f32, y: f32, oow: f32, b: f32) -> [f32; 15] {
    let mut v = [0.0; 15];
    v[0] = x;
    v[1] = y;
    v[3] = oow;
    v[6] = b;
    v
}

/// test08 (table fog on W): the calls up to and including the first frame's triangle.
#[test]
fn test08_fogged_triangle_w_gradients() {
    let (rec, mut g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    let mut entries = [0i32; 1];
    g.get(GR_FOG_TABLE_ENTRIES, 4, &mut entries);
    assert_eq!(entries[0] as usize, FOG_TABLE_SIZE);
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_RGB, 4 << 2, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_Q, 3 << 2, GR_PARAM_ENABLE);
    g.color_combine(
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_LOCAL_ITERATED,
        GR_COMBINE_OTHER_NONE,
        false,
    );
    g.fog_mode(GR_FOG_WITH_TABLE_ON_W);
    g.fog_color_value(0xff00_ff00);
    let mut table = [0u8; FOG_TABLE_SIZE];
    fog_generate_exp(&mut table, 0.01);
    g.fog_table(&table);
    g.buffer_clear(0, 0, 0);
    let (sx, sy) = (640.0f32, 480.0f32);
    let a = vertex(0.0 * sx, 0.0 * sy, 1.0 / 20.0, 64.0);
    let b = vertex(0.016 * sx, 1.0 * sy, 1.0 / 2000.0, 128.0);
    let c = vertex(1.0 * sx, 0.0208 * sy, 1.0 / 20.0, 64.0);
    let before = rec.0.borrow().len();
    g.draw_triangle(&a, &b, &c);
    let ours = rec.0.borrow().clone();
    // 6 coordinates, R G B and W (start, d/dx, d/dy), the area.
    assert_eq!(ours.len() - before, 19);
    // 3dfx's FdWdX, FdWdY (0x0dc, 0x0fc) are where the rounding of dpBC shows.
    let tail: Vec<_> = ours[ours.len() - 3..].to_vec();
    assert_eq!(
        tail,
        [
            common::Op::W(0x0dc, 0x35d7_fea1),
            common::Op::W(0x0fc, 0xb8d8_573f),
            common::Op::W(0x100, 0x4895_f338),
        ]
    );
    assert_prefix(&ours, &trace("test08"), "test08 fogged triangle");
}

/// test38 (`guGammaCorrectionRGB`), run with the keys `w`, `e`, `r` (3dfx's three
/// frames): the `clutData` (0x228) writes of the gamma load `grSstWinOpen` does (1.7)
/// and of the three the keys make, each channel starting at 1.3 and raised by `0.1f`
/// (a `float` sum) in turn.
#[test]
fn test38_gamma_tables() {
    const CLUT_DATA: u32 = 0x228;
    let clut = |ops: &[common::Op]| -> Vec<u32> {
        ops.iter()
            .filter_map(|op| match *op {
                common::Op::W(CLUT_DATA, v) => Some(v),
                _ => None,
            })
            .collect()
    };
    let (rec, mut g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    let (start, up) = (1.3f32, 1.3f32 + 0.1f32);
    g.gamma_correction_rgb(up, start, start);
    g.gamma_correction_rgb(up, up, start);
    g.gamma_correction_rgb(up, up, up);
    let ours = clut(&rec.0.borrow());
    let theirs = clut(&trace("test38"));
    // Four loads of 33 entries each.
    assert_eq!(theirs.len(), 4 * 33);
    assert_eq!(ours, theirs);
}

/// test28's `hlsToRGB` channel (its `value`): `n1 + (n2 - n1) * hue / 60`, the ramp
/// towards `n2 - 1` above 180 degrees (the program's own formula), clamped to 0..1,
/// times 255. The x87 build keeps the expression extended and rounds once, on the
/// store to the colour.
fn hls_value(n1: f32, n2: f32, hue: f32) -> f32 {
    let mut hue = hue;
    if hue > 360.0 {
        hue -= 360.0;
    }
    if hue < 0.0 {
        hue += 360.0;
    }
    let (n1, n2, h) = (f64::from(n1), f64::from(n2), f64::from(hue));
    let v = if hue < 60.0 {
        n1 + (n2 - n1) * h / 60.0
    } else if hue < 180.0 {
        n2
    } else if hue < 240.0 {
        n1 + (n2 - 1.0) * (240.0 - h) / 60.0
    } else {
        n1
    };
    (v.clamp(0.0, 1.0) * 255.0) as f32
}

/// test28 (planar polygon): five vertices on a circle, `GR_POLYGON` through
/// `grDrawVertexArrayContiguous`, Gouraud colours with fractional differences. The
/// three fan triangles' writes, from the first vertex register on, must equal 3dfx's
/// first polygon; its dRdX and dGdX (0x0c0, 0x0c4) need the `float` parameter
/// differences.
#[test]
fn test28_polygon_colour_gradients() {
    let (rec, mut g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_RGB, 4 << 2, GR_PARAM_ENABLE);
    g.color_combine(
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_LOCAL_ITERATED,
        GR_COMBINE_OTHER_NONE,
        false,
    );
    // hlsToRGB(theta, l = 0.4, s = 0.5): p2 = l * (1 + s), p1 = 2 l - p2 (floats).
    let (l, s) = (0.4f32, 0.5f32);
    let p2 = l * (1.0 + s);
    let p1 = 2.0 * l - p2;
    let mut vtx = [[0.0f32; 15]; 5];
    for (i, v) in vtx.iter_mut().enumerate() {
        let theta = 2.0 * std::f64::consts::PI * i as f64 / 5.0;
        v[0] = ((theta.cos() / 4.0 + 0.5) as f32) * 640.0;
        v[1] = ((theta.sin() / 4.0 + 0.5) as f32) * 480.0;
        // Vertex i takes hue i * 72 degrees.
        let h = (i * 72) as f32;
        v[4] = hls_value(p1, p2, h + 120.0);
        v[5] = hls_value(p1, p2, h);
        v[6] = hls_value(p1, p2, h - 120.0);
    }
    // The program's deliberate overflowing colours.
    vtx[3][4..7].copy_from_slice(&[235.519, 51.001, 115.721]);
    vtx[4][4..7].copy_from_slice(&[298.559, -12.039, 91.0]);
    let data: Vec<f32> = vtx.iter().flatten().copied().collect();
    let before = rec.0.borrow().len();
    g.draw_vertex_array_contiguous(GR_POLYGON, &data, 5, 15 * 4);
    let ops = rec.0.borrow()[before..].to_vec();
    let first_vertex = |ops: &[common::Op]| {
        ops.iter()
            .position(|op| matches!(op, common::Op::W(0x088, _)))
            .expect("a triangle")
    };
    let ours = &ops[first_vertex(&ops)..];
    // 3 triangles of 6 coordinates, R G B (start, d/dx, d/dy) and the area.
    assert_eq!(ours.len(), 3 * 16);
    let theirs = trace("test28");
    assert_prefix(ours, &theirs[first_vertex(&theirs)..], "test28 polygon");
}

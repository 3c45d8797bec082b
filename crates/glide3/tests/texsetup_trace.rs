//! Textured triangle setup must reproduce 3dfx's SST-1 Glide 3 bit for bit. Every
//! glide-sdk trace draws its console text with tlib's `drawChar`
//! (glide3x/sst1/glide3/tests/tlib.c): a quad a-b (top) c-d (bottom) as the
//! triangles (a, d, c) and (a, b, d), window coordinates, oow = 1, and S/T the
//! character's cell in the 256x128 font texture: (s0, t0) at a, + 18 in S to the
//! right, + 24 in T down.
//!
//! For each textured triangle of a trace we rebuild those vertices: the positions
//! from the snapped vertex registers (the setup works on snapped coordinates only,
//! gxdraw.c `_trisetup`), the role of each vertex (left/right, top/bottom) from
//! them, and the character cell from vertex A's S/T start. The cell must be a font
//! cell (S a multiple of 18 below 252, T a multiple of 24 below 96); then every write
//! of our setup (vertices, fstartS/T/W, fdSdX/Y, fdTdX/Y, fdWdX/Y, ftriangleCMD) must
//! equal the trace's.
//!
//! KNOWN FAILURE (ignored): 3dfx's traces were made by an x87 build of Glide. Its
//! `_trisetup` keeps `x + SNAP_BIAS` unrounded in x87 registers, so the area and the
//! gradients come from the UNSNAPPED vertex positions (only the vertex registers get
//! the 1/16-snapped floats), `area` is rounded to float (`_GlideRoot.pool.temp1`),
//! and the gradient products use `1/area` or the scaled deltas rounded to float. With
//! that model (explored outside the tree) test00's 90 console triangles match bit for
//! bit wherever the vertex position is right (72 of 90 when tlib's positions are
//! modelled as `f32(k * (1/60 as f32) * 640)`); the other 18 differ in the area only,
//! i.e. in tlib's own x87 rounding of `charX`, which the trace cannot pin down. Our
//! setup (draw.rs) works on the snapped floats, hence fdSdX 1.6842105 where the trace
//! has 1.6875. Fixing it needs the unsnapped positions carried into `triangle()`.

mod common;
use common::{trace, Op, Rec};
use glide3::consts::*;
use glide3::{BoardInfo, Glide};

/// `SNAP_BIAS` of 3dfx's VG trisetup: 3 << 18.
const SNAP: f32 = 786432.0;
const FV_AX: u32 = 0x88;
const F_TRIANGLE_CMD: u32 = 0x100;
const F_START_S: u32 = 0xb4;
const F_START_T: u32 = 0xb8;

/// The setup writes of each triangle: `fvertexAx` .. `ftriangleCMD`.
fn triangles(ops: &[Op]) -> Vec<Vec<(u32, u32)>> {
    let mut out = Vec::new();
    let mut cur: Option<Vec<(u32, u32)>> = None;
    for op in ops {
        let Op::W(a, v) = *op else { continue };
        if a == FV_AX {
            cur = Some(Vec::new());
        }
        if let Some(c) = cur.as_mut() {
            c.push((a, v));
            if a == F_TRIANGLE_CMD {
                out.push(cur.take().unwrap_or_default());
            }
        }
    }
    out
}

fn reg(t: &[(u32, u32)], a: u32) -> Option<f32> {
    t.iter().find(|w| w.0 == a).map(|w| f32::from_bits(w.1))
}

/// A tlib `GrVertex` in window coordinates: x, y, oow and TMU0 sow/tow.
fn vertex(x: f32, y: f32, s: f32, t: f32) -> [f32; 15] {
    let mut v = [0.0; 15];
    v[0] = x;
    v[1] = y;
    v[3] = 1.0;
    v[9] = s;
    v[10] = t;
    v
}

/// The drawChar vertices behind one traced triangle, in the order drawChar passed
/// them; `None` if the triangle is not a console character.
fn rebuild(t: &[(u32, u32)]) -> Option<[[f32; 15]; 3]> {
    let p: Vec<(f32, f32)> = (0..3)
        .map(|i| {
            let x = reg(t, FV_AX + 8 * i)? - SNAP;
            let y = reg(t, FV_AX + 8 * i + 4)? - SNAP;
            Some((x, y))
        })
        .collect::<Option<_>>()?;
    let (sa, ta) = (reg(t, F_START_S)?, reg(t, F_START_T)?);
    let minx = p.iter().map(|v| v.0).fold(f32::INFINITY, f32::min);
    let maxx = p.iter().map(|v| v.0).fold(f32::NEG_INFINITY, f32::max);
    let miny = p.iter().map(|v| v.1).fold(f32::INFINITY, f32::min);
    let maxy = p.iter().map(|v| v.1).fold(f32::NEG_INFINITY, f32::max);
    let right = |v: (f32, f32)| v.0 == maxx;
    let bottom = |v: (f32, f32)| v.1 == maxy;
    let s0 = sa - if right(p[0]) { 18.0 } else { 0.0 };
    let t0 = ta - if bottom(p[0]) { 24.0 } else { 0.0 };
    let cell_ok = (0.0..252.0).contains(&s0)
        && s0 % 18.0 == 0.0
        && (0.0..96.0).contains(&t0)
        && t0 % 24.0 == 0.0;
    if !cell_ok {
        return None;
    }
    let a = vertex(minx, miny, s0, t0);
    let b = vertex(maxx, miny, s0 + 18.0, t0);
    let c = vertex(minx, maxy, s0, t0 + 24.0);
    let d = vertex(maxx, maxy, s0 + 18.0, t0 + 24.0);
    let has_b = p.iter().any(|&v| right(v) && !bottom(v));
    Some(if has_b { [a, b, d] } else { [a, d, c] })
}

/// Glide in tlConRender's state: window coordinates, XY/Q/ST0 layout, texture
/// combine on TMU0.
fn console_glide() -> (Glide, Rec) {
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
    g.vertex_layout(GR_PARAM_Q, 3 << 2, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_ST0, 9 << 2, GR_PARAM_ENABLE);
    g.coordinate_space(GR_WINDOW_COORDS);
    g.color_combine(
        GR_COMBINE_FUNCTION_SCALE_OTHER,
        GR_COMBINE_FACTOR_LOCAL,
        GR_COMBINE_LOCAL_CONSTANT,
        GR_COMBINE_OTHER_TEXTURE,
        false,
    );
    g.alpha_combine(
        GR_COMBINE_FUNCTION_SCALE_OTHER,
        GR_COMBINE_FACTOR_ONE,
        GR_COMBINE_LOCAL_NONE,
        GR_COMBINE_OTHER_TEXTURE,
        false,
    );
    g.tex_combine(
        0,
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        false,
        false,
    );
    (g, rec)
}

#[test]
#[ignore = "x87 setup model not reproduced yet: see the module doc"]
fn console_text_setup_matches_every_trace() {
    let names = [
        "test00", "test02", "test04", "test06", "test08", "test10", "test12", "test14", "test16",
        "test18", "test20", "test22", "test24", "test26", "test28", "test30", "test32", "test38",
    ];
    let (mut g, rec) = console_glide();
    let mut checked = 0;
    let mut failures = Vec::new();
    for name in names {
        for (k, t) in triangles(&trace(name)).iter().enumerate() {
            if reg(t, F_START_S).is_none() {
                continue;
            }
            let Some([a, b, c]) = rebuild(t) else {
                continue;
            };
            let before = rec.0.borrow().len();
            g.draw_triangle(&a, &b, &c);
            let ours: Vec<(u32, u32)> = rec.0.borrow()[before..]
                .iter()
                .filter_map(|op| match *op {
                    Op::W(a, v) => Some((a, v)),
                    Op::Pci(..) => None,
                })
                .skip_while(|w| w.0 != FV_AX)
                .collect();
            checked += 1;
            if ours != *t && failures.len() < 5 {
                let diff: Vec<String> = t
                    .iter()
                    .zip(ours.iter().chain(std::iter::repeat(&(0, 0))))
                    .filter(|(x, y)| x != y)
                    .map(|(x, y)| {
                        format!(
                            "reg {:#x}: trace {:#010x} ({}) ours {:#x}={:#010x} ({})",
                            x.0,
                            x.1,
                            f32::from_bits(x.1),
                            y.0,
                            y.1,
                            f32::from_bits(y.1)
                        )
                    })
                    .collect();
                failures.push(format!("{name} triangle #{k}: {diff:#?}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // Every trace prints at least its title line.
    assert!(checked > 200, "only {checked} console triangles found");
}

//! Textured triangle setup must reproduce 3dfx's SST-1 Glide 3 bit for bit. Every
//! glide-sdk trace draws its console text with tlib's `tlConRender`/`drawChar`
//! (glide3x/sst1/glide3/tests/tlib.c): a quad a-b (top) c-d (bottom) as the
//! triangles (a, d, c) and (a, b, d), window coordinates, oow = 1, and S/T the
//! character's cell in the 256x128 font texture: (s0, t0) at a, + 18 in S to the
//! right, + 24 in T down.
//!
//! 3dfx's setup works from the UNSNAPPED positions (see draw.rs), so the vertices
//! must be rebuilt exactly as tlib computed them, not from the snapped registers.
//! tlib's console is 60 columns of `w = 1.0f / 60` and rows of `h = 1.0f / 30`
//! (`tlConSet(0, 0, 1, 1, 60, 30)` or `(0, 0, 1, 0.5, 60, 15)`), scaled by the
//! screen size (`tlScaleX`/`tlScaleY`). Its x87 build rounds as follows, which the
//! traces pin down: `charX` accumulates `+= w` in `float`; `charY = h * row` is a
//! `float`; a.x = `(float)(charX * width)`; b.x = `(float)((charX + w) * width)` with
//! the sum NOT rounded to float first (drawChar and tlScaleX inlined), and likewise
//! for c.y. With those sums rounded to float first, 3456 of the 7434 triangles checked
//! below differ.
//!
//! For each textured triangle of a trace we take the character's cell from vertex
//! A's S/T start (it must be a font cell: S a multiple of 18 below 252, T a multiple
//! of 24 below 96), its column and row from the snapped vertex registers, and the
//! screen size from the clip window tlConRender set; the triangle is a console
//! character when the rebuilt vertices snap to the traced vertex registers. Then
//! every write of our setup (vertices, fstartS/T/W, fdSdX/Y, fdTdX/Y, fdWdX/Y,
//! ftriangleCMD) must equal the trace's: 7434 triangles, all of them bit for bit.
//! Skipped: 819 textured triangles that send more than S, T and W (test14 keeps Z
//! enabled, so its console also sends drawChar's uninitialised `ooz`, which no trace
//! records; and textured scene geometry), and 3 scene triangles whose S/T look like
//! a font cell but which are not console characters.

mod common;
use common::{trace, Op, Rec};
use glide::consts::*;
use glide::{BoardInfo, Glide};

/// `SNAP_BIAS` of 3dfx's VG trisetup: 3 << 18.
const SNAP: f32 = 786432.0;
const FV_AX: u32 = 0x88;
const F_TRIANGLE_CMD: u32 = 0x100;
const F_START_S: u32 = 0xb4;
const F_START_T: u32 = 0xb8;
/// Six vertex coordinates, S, T and W (start, d/dX, d/dY), the area.
const CONSOLE_WRITES: usize = 16;
const CLIP_LEFT_RIGHT: u32 = 0x118;
const CLIP_LOW_Y_HIGH_Y: u32 = 0x11c;

/// One triangle's setup writes (`fvertexAx` .. `ftriangleCMD`) and the screen size
/// (width, height) of the last clip window written before it.
type Traced = (Vec<(u32, u32)>, f32, f32);

/// Every triangle of a trace.
fn triangles(ops: &[Op]) -> Vec<Traced> {
    let mut out = Vec::new();
    let mut cur: Option<Vec<(u32, u32)>> = None;
    let (mut width, mut height) = (0.0, 0.0);
    for op in ops {
        let Op::W(a, v) = *op else { continue };
        match a {
            CLIP_LEFT_RIGHT => width = (v & 0xffff) as f32,
            CLIP_LOW_Y_HIGH_Y => height = (v & 0xffff) as f32,
            FV_AX => cur = Some(Vec::new()),
            _ => {}
        }
        if let Some(c) = cur.as_mut() {
            c.push((a, v));
            if a == F_TRIANGLE_CMD {
                out.push((cur.take().unwrap_or_default(), width, height));
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

/// `(float)((p + d) * scale)` with `p + d` kept in extended precision: exact in f64
/// for these magnitudes (at most 33 significant bits), so one rounding to f32.
fn far_edge(p: f32, d: f32, scale: f32) -> f32 {
    ((f64::from(p) + f64::from(d)) * f64::from(scale)) as f32
}

/// The drawChar vertices behind one traced triangle, in the order drawChar passed
/// them; `None` if the triangle is not a console character.
fn rebuild(t: &[(u32, u32)], width: f32, height: f32) -> Option<[[f32; 15]; 3]> {
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
    let (w, h) = (1.0f32 / 60.0, 1.0f32 / 30.0);
    let column = (minx / (width * w)).round() as usize;
    let row = (miny / (height * h)).round() as u16;
    let mut char_x = 0.0f32;
    for _ in 0..column {
        char_x += w;
    }
    let char_y = h * f32::from(row);
    let (x0, x1) = (char_x * width, far_edge(char_x, w, width));
    let (y0, y1) = (char_y * height, far_edge(char_y, h, height));
    let a = vertex(x0, y0, s0, t0);
    let b = vertex(x1, y0, s0 + 18.0, t0);
    let c = vertex(x0, y1, s0, t0 + 24.0);
    let d = vertex(x1, y1, s0 + 18.0, t0 + 24.0);
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
fn console_text_setup_matches_every_trace() {
    let names = [
        "test00", "test02", "test04", "test06", "test08", "test10", "test12", "test14", "test16",
        "test18", "test20", "test22", "test24", "test26", "test28", "test30", "test32", "test38",
    ];
    let (mut g, rec) = console_glide();
    let (mut checked, mut other, mut with_z) = (0, 0, 0);
    let mut failures = Vec::new();
    for name in names {
        for (k, (t, width, height)) in triangles(&trace(name)).iter().enumerate() {
            if reg(t, F_START_S).is_none() {
                continue;
            }
            // More parameters than the console's S, T, W (see the module doc).
            if t.len() != CONSOLE_WRITES {
                with_z += 1;
                continue;
            }
            let Some([a, b, c]) = rebuild(t, *width, *height) else {
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
            // Not a console character: the rebuilt quad is not where the trace's is.
            if ours.get(..6) != t.get(..6) {
                other += 1;
                continue;
            }
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
    assert_eq!((checked, other, with_z), (7434, 3, 819));
}

//! Antialiased lines must reproduce 3dfx's SST-1 Glide 3 register writes: test24
//! (glide3x/sst1/glide3/tests/test24.c) draws 50 antialiased lines a frame with table
//! fog on W. The line end points (x, y, 1/w) are read back from the trace's own writes
//! (the vertices come from tlib transforms we do not reproduce), then our whole
//! register stream up to the end of the first frame's lines must equal the trace.

mod common;
use common::{assert_prefix, trace, Op};
use glide::consts::*;
use glide::Glide;

const BIAS: f32 = (3 << 18) as f32;

fn f(op: Op) -> f32 {
    match op {
        Op::W(_, v) => f32::from_bits(v),
        Op::Pci(..) => panic!("pci op inside a line"),
    }
}

fn addr(op: Op) -> u32 {
    match op {
        Op::W(a, _) => a,
        Op::Pci(..) => u32::MAX,
    }
}

/// tlib `GrVertex`: x, y, ooz, oow, r, g, b, a.
fn vtx(x: f32, y: f32, oow: f32) -> [f32; 8] {
    [x, y, 0.0, oow, 0.0, 0.0, 0.0, 255.0]
}

/// The two end points of the line whose writes start at `ops[0]` (`FvA.x`).
fn line_at(ops: &[Op]) -> ([f32; 8], [f32; 8]) {
    let x1 = f(ops[0]);
    let x2 = f(ops[2]);
    let y_major = f(ops[4]) != x2;
    let (y1, y2) = if y_major {
        (f(ops[1]), f(ops[3]))
    } else {
        (f(ops[1]) + 1.0, f(ops[3]) + 1.0)
    };
    // Data list: Fa, FdAdX, FdAdY, Fw, FdWdX, FdWdY.
    assert_eq!(addr(ops[9]), 0x0bc, "Fw start");
    let w1 = f(ops[9]);
    let (grad, m) = if y_major {
        (f(ops[11]), -1.0f32 / (y2 - y1))
    } else {
        (f(ops[10]), 1.0f32 / (x1 - x2))
    };
    // The far end's 1/w: the f32 whose gradient is the traced one.
    let guess = w1 - (f64::from(grad) / f64::from(m)) as f32;
    let w2 = (-256i32..=256)
        .map(|d| f32::from_bits(guess.to_bits().wrapping_add_signed(d)))
        .find(|&w2| ((f64::from(w1) - f64::from(w2)) * f64::from(m)) as f32 == grad)
        .expect("a 1/w reproducing the gradient");
    (vtx(x1 - BIAS, y1 - BIAS, w1), vtx(x2 - BIAS, y2 - BIAS, w2))
}

#[test]
fn test24_antialiased_lines_registers() {
    let (rec, mut g) = common::open_640x480(GR_ORIGIN_LOWER_LEFT);
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_A, 7 << 2, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_Q, 3 << 2, GR_PARAM_ENABLE);
    let mut w = [0i32; 2];
    g.get(GR_WDEPTH_MIN_MAX, 8, &mut w);
    g.color_combine(
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_LOCAL_CONSTANT,
        GR_COMBINE_OTHER_NONE,
        false,
    );
    let iterated_alpha = |g: &mut Glide| {
        g.alpha_combine(
            GR_COMBINE_FUNCTION_LOCAL,
            GR_COMBINE_FACTOR_NONE,
            GR_COMBINE_LOCAL_ITERATED,
            GR_COMBINE_OTHER_NONE,
            false,
        );
    };
    iterated_alpha(&mut g);
    g.fog_mode(GR_FOG_WITH_TABLE_ON_W);
    g.fog_color_value(0);
    // The fog table as the trace loaded it (guFogGenerateExp is tested elsewhere):
    // each fogTable register holds entries 2i (bits 8-15) and 2i+1 (bits 24-31).
    let theirs = trace("test24");
    let mut table = [0u8; 64];
    for op in &theirs {
        if let Op::W(a @ 0x160..=0x1dc, v) = *op {
            let i = ((a - 0x160) / 4) as usize;
            table[2 * i] = (v >> 8) as u8;
            table[2 * i + 1] = (v >> 24) as u8;
        }
    }
    g.fog_table(&table);
    let blend = |g: &mut Glide| {
        g.alpha_blend_function(
            GR_BLEND_SRC_ALPHA,
            GR_BLEND_ONE_MINUS_SRC_ALPHA,
            GR_BLEND_ZERO,
            GR_BLEND_ZERO,
        );
    };
    blend(&mut g);
    // Frame 1.
    g.buffer_clear(0, 0, w[1] as u32);
    g.constant_color_value(0xffff_ffff);
    iterated_alpha(&mut g);
    blend(&mut g);
    g.enable(GR_AA_ORDERED);
    g.vertex_layout(GR_PARAM_A, 7 << 2, GR_PARAM_ENABLE);

    for n in 0..50 {
        let pos = rec.0.borrow().len();
        let start = (pos..theirs.len())
            .find(|&i| addr(theirs[i]) == 0x088)
            .expect("next line in the trace");
        let (a, b) = line_at(&theirs[start..]);
        g.draw_line(&a, &b);
        assert_prefix(&rec.0.borrow(), &theirs, &format!("test24 line {n}"));
    }
    assert_eq!(g.stats().lines, 50);
}

//! `grDrawVertexArray` reads each vertex once and holds at most three: the register
//! stream of every list mode equals the triangles, lines and points it stands for,
//! drawn one by one, `*_CONTINUE` modes included.

mod common;
use common::{Op, Rec};
use glide::consts::*;
use glide::Glide;

fn open() -> (Glide, Rec) {
    let (rec, mut g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_RGB, 8, GR_PARAM_ENABLE);
    g.color_combine(
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_LOCAL_ITERATED,
        GR_COMBINE_OTHER_NONE,
        false,
    );
    rec.0.borrow_mut().clear();
    (g, rec)
}

/// The triangles of a strip of eight vertices (every other one turned).
const STRIP: [[usize; 3]; 6] = [
    [0, 1, 2],
    [2, 1, 3],
    [2, 3, 4],
    [4, 3, 5],
    [4, 5, 6],
    [6, 5, 7],
];

/// Eight vertices on a rough circle, each with its own colour.
fn vertices() -> Vec<[f32; 5]> {
    (0..8)
        .map(|i| {
            let a = i as f32 * 0.7;
            [
                320.0 + 100.0 * a.cos(),
                240.0 + 80.0 * a.sin(),
                30.0 * i as f32,
                255.0 - 30.0 * i as f32,
                17.0 * i as f32,
            ]
        })
        .collect()
}

/// What drawing `mode` over `v` (after `first`, when continuing) writes.
fn list(first: Option<(u32, &[[f32; 5]])>, mode: u32, v: &[[f32; 5]]) -> Vec<Op> {
    let (mut g, rec) = open();
    if let Some((m, f)) = first {
        let refs: Vec<&[f32]> = f.iter().map(|v| &v[..]).collect();
        g.draw_vertex_array(m, &refs);
    }
    let refs: Vec<&[f32]> = v.iter().map(|v| &v[..]).collect();
    g.draw_vertex_array(mode, &refs);
    let ops = rec.0.borrow().clone();
    ops
}

/// What drawing the triangles `tris` (indices into `v`) one by one writes.
fn triangles(v: &[[f32; 5]], tris: &[[usize; 3]]) -> Vec<Op> {
    let (mut g, rec) = open();
    for t in tris {
        g.draw_triangle(&v[t[0]], &v[t[1]], &v[t[2]]);
    }
    let ops = rec.0.borrow().clone();
    ops
}

#[test]
fn strips_fans_and_polygons_are_their_triangles() {
    let v = vertices();
    assert_eq!(list(None, GR_TRIANGLE_STRIP, &v), triangles(&v, &STRIP));
    let fan: Vec<[usize; 3]> = (1..7).map(|i| [0, i, i + 1]).collect();
    assert_eq!(list(None, GR_TRIANGLE_FAN, &v), triangles(&v, &fan));
    assert_eq!(list(None, GR_POLYGON, &v), triangles(&v, &fan));
    let tris = [[0, 1, 2], [3, 4, 5]];
    assert_eq!(list(None, GR_TRIANGLES, &v), triangles(&v, &tris));
    // Continuing a strip or fan: one list split in two draws the same triangles (a
    // first part of one vertex leaves nothing to continue, as before).
    for split in (0..=v.len()).filter(|&s| s != 1) {
        let (a, b) = v.split_at(split);
        assert_eq!(
            list(Some((GR_TRIANGLE_STRIP, a)), GR_TRIANGLE_STRIP_CONTINUE, b),
            triangles(&v, &STRIP),
            "strip split at {split}"
        );
        assert_eq!(
            list(Some((GR_TRIANGLE_FAN, a)), GR_TRIANGLE_FAN_CONTINUE, b),
            triangles(&v, &fan),
            "fan split at {split}"
        );
    }
}

#[test]
fn lines_and_points_are_drawn_one_by_one() {
    let v = vertices();
    let by_hand = |f: &dyn Fn(&mut Glide)| {
        let (mut g, rec) = open();
        f(&mut g);
        let ops = rec.0.borrow().clone();
        ops
    };
    assert_eq!(
        list(None, GR_LINE_STRIP, &v),
        by_hand(&|g| (1..8).for_each(|i| g.draw_line(&v[i - 1], &v[i])))
    );
    assert_eq!(
        list(None, GR_LINES, &v),
        by_hand(&|g| (0..4).for_each(|i| g.draw_line(&v[2 * i], &v[2 * i + 1])))
    );
    assert_eq!(
        list(None, GR_POINTS, &v),
        by_hand(&|g| v.iter().for_each(|p| g.draw_point(p)))
    );
}

#[test]
fn contiguous_arrays_are_read_by_stride() {
    let v = vertices();
    // Six floats per vertex: the five used and one of padding.
    let data: Vec<f32> = v
        .iter()
        .flat_map(|p| p.iter().copied().chain([9.0]))
        .collect();
    let (mut g, rec) = open();
    g.draw_vertex_array_contiguous(GR_TRIANGLE_STRIP, &data, 8, 24);
    let ops = rec.0.borrow().clone();
    assert_eq!(ops, triangles(&v, &STRIP));
    // A zero stride is refused and draws nothing.
    let (mut g, rec) = open();
    g.draw_vertex_array_contiguous(GR_TRIANGLE_STRIP, &data, 8, 0);
    assert_eq!(
        g.last_error(),
        Some("grDrawVertexArrayContiguous: stride must be a positive multiple of 4")
    );
    assert!(rec.0.borrow().is_empty());
}

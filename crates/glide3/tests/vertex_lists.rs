//! `grDrawVertexArray` reads each vertex once and holds at most three: the register
//! stream of every list mode equals the triangles, lines and points it stands for,
//! drawn one by one, `*_CONTINUE` modes included, with the vertices 3dfx's library
//! keeps between calls (issue "Glide 3 as 3dfx shipped it", item 5).

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
    // Continuing a strip or fan: one list split in two draws the same triangles, a
    // first part of one vertex included (3dfx keeps it, and the continuation's first
    // vertex completes the pair). A first part of none is not a split: 3dfx's
    // continuation then starts from the vertex it kept before (see below).
    for split in 1..=v.len() {
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

/// What drawing each `(mode, vertices)` call in turn writes, and the statistics after.
fn calls(calls: &[(u32, &[[f32; 5]])]) -> (Vec<Op>, glide::Stats) {
    let (mut g, rec) = open();
    for (mode, v) in calls {
        let refs: Vec<&[f32]> = v.iter().map(|v| &v[..]).collect();
        g.draw_vertex_array(*mode, &refs);
    }
    let ops = rec.0.borrow().clone();
    (ops, g.stats())
}

/// A strip or fan started with one vertex and continued one vertex a call draws the
/// whole strip or fan, as 3dfx's library does: it keeps the previous vertices across
/// calls (gstrip.c `gc->vert1`, `gc->vert2`). Each continuation's triangle goes
/// through 3dfx's mixed-layout setup, which counts it twice as drawn.
#[test]
fn lists_started_with_one_vertex_continue_one_vertex_a_call() {
    let v = vertices();
    let fan: Vec<[usize; 3]> = (1..7).map(|i| [0, i, i + 1]).collect();
    for (first, cont, tris) in [
        (GR_TRIANGLE_STRIP, GR_TRIANGLE_STRIP_CONTINUE, &STRIP[..]),
        (GR_TRIANGLE_FAN, GR_TRIANGLE_FAN_CONTINUE, &fan[..]),
    ] {
        let mut list: Vec<(u32, &[[f32; 5]])> = vec![(first, &v[..1])];
        list.extend((1..8).map(|i| (cont, &v[i..=i])));
        let (ops, stats) = calls(&list);
        assert_eq!(ops, triangles(&v, tris), "mode {first}");
        assert_eq!(stats.triangles_in, 6, "mode {first}");
        assert_eq!(stats.triangles_drawn, 12, "mode {first}");
    }
    // A strip continued in pairs: each call draws two mixed-setup triangles.
    let (ops, stats) = calls(&[
        (GR_TRIANGLE_STRIP, &v[..1]),
        (GR_TRIANGLE_STRIP_CONTINUE, &v[1..3]),
        (GR_TRIANGLE_STRIP_CONTINUE, &v[3..5]),
        (GR_TRIANGLE_STRIP_CONTINUE, &v[5..8]),
    ]);
    assert_eq!(ops, triangles(&v, &STRIP));
    assert_eq!((stats.triangles_in, stats.triangles_drawn), (6, 11));
}

/// 3dfx's continuation quirks (gstrip.c _grDrawVertexListContinue): a continuation
/// that draws three triangles or more does not update the strip's turn, so the next
/// one starts turned as this one did; strips and fans keep the same two vertices, so
/// a fan can continue a strip; and before any list the kept first vertex is zeros.
#[test]
fn continuations_keep_3dfx_state() {
    let v = vertices();
    // STRIP 0,1 then 2..7: five triangles, the turn stays unturned; 7 then continues
    // from 5, 6 unturned instead of [6, 5, 7].
    let (ops, _) = calls(&[
        (GR_TRIANGLE_STRIP, &v[..2]),
        (GR_TRIANGLE_STRIP_CONTINUE, &v[2..7]),
        (GR_TRIANGLE_STRIP_CONTINUE, &v[7..8]),
    ]);
    let mut tris = STRIP[..5].to_vec();
    tris.push([5, 6, 7]);
    assert_eq!(ops, triangles(&v, &tris));
    // A fan continuing a strip turns around the strip's second-newest vertex.
    let (ops, _) = calls(&[
        (GR_TRIANGLE_STRIP, &v[..4]),
        (GR_TRIANGLE_FAN_CONTINUE, &v[4..6]),
    ]);
    assert_eq!(
        ops,
        triangles(&v, &[[0, 1, 2], [2, 1, 3], [2, 3, 4], [2, 4, 5]])
    );
    // Continuing before any list: the first kept vertex is a vertex of zeros.
    let mut z = v.clone();
    z.insert(0, [0.0; 5]);
    let (ops, _) = calls(&[(GR_TRIANGLE_FAN_CONTINUE, &v[..3])]);
    assert_eq!(ops, triangles(&z, &[[0, 1, 2], [0, 2, 3]]));
}

/// grDrawVertexArrayContiguous draws GR_TRIANGLE_FAN_CONTINUE as a new fan (3dfx's
/// distrip.c calls `_grDrawVertexList` for it), and GR_TRIANGLE_STRIP_CONTINUE as a
/// continuation.
#[test]
fn contiguous_fan_continue_starts_a_new_fan() {
    let v = vertices();
    let data: Vec<f32> = v.iter().flat_map(|p| p.iter().copied()).collect();
    let (mut g, rec) = open();
    g.draw_vertex_array_contiguous(GR_TRIANGLE_FAN, &data[..15], 3, 20);
    g.draw_vertex_array_contiguous(GR_TRIANGLE_FAN_CONTINUE, &data[15..], 5, 20);
    let ops = rec.0.borrow().clone();
    assert_eq!(
        ops,
        triangles(&v, &[[0, 1, 2], [3, 4, 5], [3, 5, 6], [3, 6, 7]])
    );
    let (mut g, rec) = open();
    g.draw_vertex_array_contiguous(GR_TRIANGLE_STRIP, &data[..5], 1, 20);
    g.draw_vertex_array_contiguous(GR_TRIANGLE_STRIP_CONTINUE, &data[5..], 7, 20);
    let ops = rec.0.borrow().clone();
    assert_eq!(ops, triangles(&v, &STRIP));
}

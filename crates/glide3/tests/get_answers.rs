//! `grGet` / `grGetString` / `grQueryResolutions` / `grReset` must answer as 3dfx's
//! SST-1 Glide 3 does (glide3x/sst1/glide3/src/diget.c, read for the values) for
//! every selector of the Glide 3.0 Programming Guide's Table 12.1/12.2, on boards of
//! 1 and 2 TMUs with 2 and 4 MiB. The bus is a stub that reads 0 (an idle chip with
//! an empty status register and zeroed counters).

mod common;
use common::{Op, Rec};
use glide::consts::*;
use glide::get::get_string;
use glide::{BoardInfo, Glide};

fn open(fbi_mb: u32, tmus: u32, tmu_mb: u32) -> (Glide, Rec) {
    let rec = Rec::default();
    let mut g = Glide::init(Box::new(rec.clone()), BoardInfo::new(fbi_mb, tmus, tmu_mb));
    assert!(g.win_open(
        GR_RESOLUTION_640x480,
        GR_REFRESH_60Hz,
        GR_COLORFORMAT_ARGB,
        GR_ORIGIN_UPPER_LEFT,
        2,
        1
    ));
    (g, rec)
}

/// (selector, plength, values) as 3dfx answers them on an idle board.
fn expected(fbi_mb: u32, tmus: u32, tmu_mb: u32) -> Vec<(u32, u32, Vec<i32>)> {
    vec![
        (GR_BITS_DEPTH, 4, vec![16]),
        (GR_BITS_RGBA, 16, vec![5, 6, 5, 0]),
        (GR_BITS_GAMMA, 4, vec![8]),
        // status 0: 0xffff - 0 free entries, then (s << 8) + (s >> 8).
        (GR_FIFO_FULLNESS, 8, vec![0xff_ffff, 0xffff]),
        (GR_FOG_TABLE_ENTRIES, 4, vec![64]),
        (GR_GAMMA_TABLE_ENTRIES, 4, vec![32]),
        (GR_GLIDE_STATE_SIZE, 4, vec![588]),
        (GR_GLIDE_VERTEXLAYOUT_SIZE, 4, vec![100]),
        (GR_IS_BUSY, 4, vec![0]),
        (GR_LFB_PIXEL_PIPE, 4, vec![1]),
        (GR_MAX_TEXTURE_SIZE, 4, vec![256]),
        (GR_MAX_TEXTURE_ASPECT_RATIO, 4, vec![3]),
        (GR_MEMORY_FB, 4, vec![(fbi_mb << 20) as i32]),
        (GR_MEMORY_TMU, 4, vec![(tmu_mb << 20) as i32]),
        (GR_MEMORY_UMA, 4, vec![0]),
        (GR_NON_POWER_OF_TWO_TEXTURES, 4, vec![0]),
        (GR_NUM_BOARDS, 4, vec![1]),
        (GR_NUM_FB, 4, vec![1]),
        (GR_NUM_SWAP_HISTORY_BUFFER, 4, vec![0]),
        (GR_NUM_TMU, 4, vec![tmus as i32]),
        (GR_PENDING_BUFFERSWAPS, 4, vec![0]),
        (GR_REVISION_FB, 4, vec![2]),
        (GR_REVISION_TMU, 4, vec![1]),
        (GR_STATS_LINES, 4, vec![0]),
        (GR_STATS_PIXELS_AFUNC_FAIL, 4, vec![0]),
        (GR_STATS_PIXELS_CHROMA_FAIL, 4, vec![0]),
        (GR_STATS_PIXELS_DEPTHFUNC_FAIL, 4, vec![0]),
        (GR_STATS_PIXELS_IN, 4, vec![0]),
        (GR_STATS_PIXELS_OUT, 4, vec![0]),
        (GR_STATS_POINTS, 4, vec![0]),
        (GR_STATS_TRIANGLES_IN, 4, vec![0]),
        (GR_STATS_TRIANGLES_OUT, 4, vec![0]),
        // Not implemented on the SST-1: "succeeds" only with plength 0, writing nothing.
        (GR_SWAP_HISTORY, 0, vec![]),
        (GR_SUPPORTS_PASSTHRU, 4, vec![1]),
        (GR_TEXTURE_ALIGN, 4, vec![8]),
        (GR_VIDEO_POSITION, 8, vec![0, 0]),
        (GR_VIEWPORT, 16, vec![0, 0, 640, 480]),
        (GR_WDEPTH_MIN_MAX, 8, vec![0, 0xffff]),
        (GR_ZDEPTH_MIN_MAX, 8, vec![0xffff, 0]),
    ]
}

#[test]
fn every_selector_on_every_board() {
    for (fbi_mb, tmus, tmu_mb) in [(2, 1, 2), (2, 2, 2), (4, 1, 4), (4, 2, 4), (4, 2, 2)] {
        let (mut g, _) = open(fbi_mb, tmus, tmu_mb);
        for (pname, plength, values) in expected(fbi_mb, tmus, tmu_mb) {
            let board = format!("{fbi_mb} MiB, {tmus} TMU(s), {tmu_mb} MiB/TMU");
            let mut out = [0x5a5a_5a5a_i32; 4];
            assert_eq!(
                g.get(pname, plength, &mut out),
                plength,
                "selector {pname:#x} on {board}"
            );
            assert_eq!(&out[..values.len()], &values[..], "{pname:#x} on {board}");
            assert!(
                out[values.len()..].iter().all(|&w| w == 0x5a5a_5a5a),
                "{pname:#x} wrote past its values"
            );
            // A known selector with the wrong plength: FXTRUE, params untouched.
            let mut out = [0x5a5a_5a5a_i32; 4];
            assert_eq!(
                g.get(pname, plength + 4, &mut out),
                1,
                "{pname:#x} wrong length"
            );
            assert_eq!(out, [0x5a5a_5a5a; 4]);
        }
        // Unknown selectors: FXFALSE.
        let mut out = [0i32; 4];
        assert_eq!(g.get(0x7777, 4, &mut out), 0);
        assert_eq!(g.get(GR_EXTENSION, 4, &mut out), 0);
    }
}

#[test]
fn strings() {
    assert_eq!(get_string(GR_EXTENSION), "FOGALPHA ");
    assert_eq!(get_string(GR_HARDWARE), "Voodoo Graphics");
    assert_eq!(get_string(GR_RENDERER), "Glide");
    assert_eq!(get_string(GR_VENDOR), "3Dfx Interactive");
    assert_eq!(get_string(GR_VERSION), "3.01.0001");
    assert_eq!(get_string(GR_NUM_TMU), "ERROR");
}

#[test]
fn counters_follow_drawing_and_reset() {
    let (mut g, rec) = open(4, 1, 4);
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    let v = |x: f32, y: f32| [x, y];
    g.draw_triangle(&v(10.0, 10.0), &v(100.0, 10.0), &v(10.0, 100.0));
    g.draw_line(&v(0.0, 0.0), &v(50.0, 20.0));
    g.draw_point(&v(5.0, 5.0));
    let get1 = |g: &mut Glide, s: u32| {
        let mut o = [0i32; 1];
        assert_eq!(g.get(s, 4, &mut o), 4);
        o[0]
    };
    assert_eq!(get1(&mut g, GR_STATS_TRIANGLES_IN), 1);
    assert_eq!(get1(&mut g, GR_STATS_TRIANGLES_OUT), 1);
    assert_eq!(get1(&mut g, GR_STATS_LINES), 1);
    assert_eq!(get1(&mut g, GR_STATS_POINTS), 1);
    // GR_STATS_TRIANGLES clears lines too (3dfx _grResetTriStats), not points.
    assert!(g.reset(GR_STATS_TRIANGLES));
    assert_eq!(get1(&mut g, GR_STATS_TRIANGLES_IN), 0);
    assert_eq!(get1(&mut g, GR_STATS_TRIANGLES_OUT), 0);
    assert_eq!(get1(&mut g, GR_STATS_LINES), 0);
    assert_eq!(get1(&mut g, GR_STATS_POINTS), 1);
    assert!(g.reset(GR_STATS_POINTS));
    assert_eq!(get1(&mut g, GR_STATS_POINTS), 0);
    // GR_STATS_PIXELS: nopCMD with bit 0 set clears the chip counters.
    let before = rec.0.borrow().len();
    assert!(g.reset(GR_STATS_PIXELS));
    assert_eq!(rec.0.borrow()[before..], [Op::W(0x120, 1)]);
    assert!(g.reset(GR_VERTEX_PARAMETER));
    assert_eq!(g.get_vertex_layout(), glide::VertexLayout::default());
    assert!(!g.reset(GR_STATS_PIXELS_IN));
}

#[test]
fn query_resolutions_as_diget() {
    let (g4, _) = open(4, 1, 4);
    let all4 = g4.query_resolutions(None, None, None, None);
    // 512x384 at 5 refreshes, 640x400 and 640x480 at 4, 800x600 at 3; 4 buffer
    // combinations each fit in 4 MiB.
    assert_eq!(all4.len(), (5 + 4 + 4 + 3) * 4);
    let first = all4[0];
    assert_eq!(
        (
            first.resolution,
            first.refresh,
            first.color_buffers,
            first.aux_buffers
        ),
        (GR_RESOLUTION_512x384, GR_REFRESH_60Hz, 2, 0)
    );
    let last = all4[all4.len() - 1];
    assert_eq!(
        (
            last.resolution,
            last.refresh,
            last.color_buffers,
            last.aux_buffers
        ),
        (GR_RESOLUTION_800x600, GR_REFRESH_85Hz, 3, 1)
    );
    let (g2, _) = open(2, 1, 2);
    // 2 MiB: 640x400 and 640x480 drop 3 colour + 1 aux; 800x600 keeps only 2 + 0.
    assert_eq!(
        g2.query_resolutions(None, None, None, None).len(),
        20 + 12 + 12 + 3
    );
    let m = g2.query_resolutions(Some(GR_RESOLUTION_800x600), None, None, None);
    assert_eq!(m.len(), 3);
    assert!(m.iter().all(|r| (r.color_buffers, r.aux_buffers) == (2, 0)));
    // Out-of-range template values mean "any".
    assert_eq!(
        g2.query_resolutions(Some(99), Some(42), Some(7), Some(9))
            .len(),
        47
    );
    assert!(g2
        .query_resolutions(Some(GR_RESOLUTION_960x720), None, None, None)
        .is_empty());
}

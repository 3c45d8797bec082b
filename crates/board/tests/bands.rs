//! The render threads' bands (`Fbi::shade_rows_threaded`) where their words are hardest
//! to keep apart: large triangles drawn with clipping off whose rows run past the row
//! pitch into the next frame-buffer row (as the single walk lets them), some above the
//! first row, under the Y-origin flip or not, with random `fbzMode`, `alphaMode`,
//! `fbzColorPath` and `fogMode` (depth test, blending and dither read what an earlier
//! row wrote), in Glide's buffer layout and with colour and aux buffers a few pages apart.
//! On 2 and 4 render threads every frame-buffer word and every counter must be those of
//! the reference path, and the bands must have taken most of the pixels (rows past the
//! pitch are cut there into pieces, so that even triangles wider than the pitch band;
//! rotate-mode stipple starts each piece where the row had stepped it to).

use sst1_board::{Board, BoardConfig};
use sst1_regs::{addr, FbiInit2, RegisterBus};
use sst1_trace::scenes::Rng;

/// A value in `lo..hi`.
fn within(rng: &mut Rng, lo: i32, hi: i32) -> i32 {
    lo + rng.below((hi - lo) as u32) as i32
}

/// The write stream of one seed: the Glide mode set, then states and large triangles.
fn stream(seed: u64) -> Vec<(u32, u32)> {
    let mut rng = Rng::new(seed);
    let mut w: Vec<(u32, u32)> = sst1_board::presets::GLIDE_640X480.to_vec();
    // Glide's layout (buffers 150 pages apart) on most seeds; buffers a few pages apart
    // on every third, where one triangle's colour and aux words can meet.
    let pages = if seed % 3 == 2 { 1 + rng.below(8) } else { 150 };
    w.push((
        addr::FBI_INIT2,
        FbiInit2(0x1874_b040).with_video_buffer_offset(pages).0,
    ));
    w.push((addr::STIPPLE, rng.u32()));
    for _ in 0..6 {
        // Any mode with a real draw buffer (bits 15:14 = 0 or 1) and clipping off.
        w.push((addr::FBZ_MODE, rng.u32() & !0x8000 & !1));
        w.push((addr::ALPHA_MODE, rng.u32()));
        // Untextured: the texture-enable bit of fbzColorPath off.
        w.push((addr::FBZ_COLOR_PATH, rng.u32() & !(1 << 27)));
        w.push((addr::FOG_MODE, rng.u32() & 0x3f));
        w.push((addr::ZA_COLOR, rng.u32()));
        w.push((addr::COLOR0, rng.u32()));
        w.push((addr::COLOR1, rng.u32()));
        for _ in 0..6 {
            // Columns from 0 to 1250 (rows of 640 words): most rows reach past the pitch,
            // in triangles wider than 640 pixels by more than the next row starts right
            // of column 0 (those rows must share a band), in narrower ones by less (bands
            // can be cut between them); rows from above the first to below the screen.
            let (x0, y0) = (within(&mut rng, 0, 450), within(&mut rng, -60, 400));
            let vertices = [
                (x0, y0),
                (
                    x0 + within(&mut rng, 300, 800),
                    y0 + within(&mut rng, 0, 80),
                ),
                (
                    x0 + within(&mut rng, 0, 400),
                    y0 + within(&mut rng, 120, 300),
                ),
            ];
            let regs = [addr::VERTEX_AX, addr::VERTEX_BX, addr::VERTEX_CX];
            for (reg, (x, y)) in regs.into_iter().zip(vertices) {
                w.push((reg, (x * 16 + within(&mut rng, 0, 16)) as u32));
                w.push((reg + 4, (y * 16 + within(&mut rng, 0, 16)) as u32));
            }
            // Every iterated parameter's start and gradients (S and T unused: untextured).
            for reg in (addr::START_R..=addr::START_W).step_by(4) {
                // Starts anywhere in range, small steps either way.
                w.push((reg, rng.u32() & 0x00ff_ffff));
                w.push((reg + 0x20, within(&mut rng, -0x800, 0x800) as u32));
                w.push((reg + 0x40, within(&mut rng, -0x800, 0x800) as u32));
            }
            // Either sign of the area.
            w.push((addr::TRIANGLE_CMD, rng.u32() & 0x8000_0000));
        }
    }
    w
}

/// The frame buffer's words, the counters, and the pixels the span kernels shaded and of
/// those the bands, after `writes` on `threads` render threads (`None`: the reference
/// path).
fn replay(writes: &[(u32, u32)], threads: Option<usize>) -> (Vec<u16>, String, (u64, u64)) {
    let mut board = Board::new(BoardConfig::default());
    match threads {
        Some(threads) => board.set_threads(threads),
        None => {
            board.set_generic_path(true);
            board.set_threads(1);
        }
    }
    board.pci_write(0x40, 3);
    for &(a, v) in writes {
        board.write32(a, v);
    }
    let paths = board.path_counts();
    (
        board.fbi().fb.ram.clone(),
        format!("{:?}", board.stats()),
        (paths.span_kernels, paths.in_bands),
    )
}

#[test]
fn bands_of_rows_past_the_pitch_equal_the_reference_path() {
    let (mut shaded, mut banded) = (0, 0);
    for seed in 0..6 {
        let writes = stream(seed);
        let (ram, stats, _) = replay(&writes, None);
        for threads in [2, 4] {
            let (fast_ram, fast_stats, (kernels, bands)) = replay(&writes, Some(threads));
            assert_eq!(
                stats, fast_stats,
                "seed {seed}, {threads} threads: counters"
            );
            if let Some(i) = (0..ram.len()).find(|&i| ram[i] != fast_ram[i]) {
                panic!(
                    "seed {seed}, {threads} threads: word {i:#x} is {:#06x}, {:#06x} on the reference path",
                    fast_ram[i], ram[i]
                );
            }
            if seed % 3 != 2 {
                shaded += kernels;
                banded += bands;
            }
        }
    }
    // Before bands could hold rows past the pitch, none of these triangles was banded.
    assert!(
        banded * 5 > shaded * 4,
        "{banded} of {shaded} pixels shaded in bands"
    );
}

//! Chunks packed from several short rows of a triangle (`pixelfx::span::Packed`) against
//! the reference path, where packing is most likely to go wrong: small triangles drawn
//! with clipping off across the edges of the screen and of memory (rows above the first,
//! columns past the row pitch, rows past the end of the frame buffer), under the Y-origin
//! flip, with colour and aux buffers placed a few pages apart so that their words meet,
//! and with every mode bit of `fbzMode`, `alphaMode`, `fbzColorPath` and `fogMode` random
//! (depth test against the rows the chunk itself writes, blending, rotating stipple,
//! dither). Every frame-buffer word and every counter must be identical, and the packed
//! chunks must have taken pixels (and left some rows to the row path).

use sst1_board::{Board, BoardConfig, VectorIsa};
use sst1_regs::{addr, FbiInit2, RegisterBus};

mod common;
use common::Rng;

/// The write stream of one seed: the Glide mode set, then states and small triangles.
fn stream(seed: u64) -> Vec<(u32, u32)> {
    let mut rng = Rng::new(seed);
    let mut w: Vec<(u32, u32)> = sst1_board::presets::GLIDE_640X480.to_vec();
    // Buffers 150 pages apart (Glide's), or a few pages: then a buffer's rows run into
    // the next buffer's, and colour and aux words of one triangle can meet.
    // Glide's layout (rows of 640 words, buffers 150 pages apart), or buffers a few
    // pages apart, or rows of 256 words (4 in `video_tiles_in_x`) with buffers one or two
    // pages (8 or 16 rows) apart: then a lane's colour word can be another lane's aux
    // word in one tall triangle.
    let (pages, narrow_rows) = match seed % 4 {
        0 => (150, false),
        1 => (1 + rng.below(8), false),
        _ => (1 + rng.below(2), true),
    };
    let init2 = FbiInit2(0x1874_b040).with_video_buffer_offset(pages);
    w.push((addr::FBI_INIT2, init2.0));
    if narrow_rows {
        w.push((addr::FBI_INIT1, 0x0020_0042));
    }
    w.push((addr::STIPPLE, rng.u32()));
    for state in 0..40 {
        // Any mode, but a real draw buffer (bits 15:14 = 0 or 1) and mostly no clipping;
        // one state in four clips to one to three rows under the Y-origin flip.
        let wrapping = state % 4 == 3;
        let mut fbz = rng.u32() & !0x8000;
        let mut alpha_mode = rng.u32();
        if wrapping {
            // Clipping and the flip, RGB writes, nothing that kills a pixel (chroma key,
            // stipple, depth test, alpha mask, alpha test), and additive blending (both
            // factors one): a lane that reads a word another lane of its chunk wrote
            // shows.
            fbz = (fbz | 1 | 1 << 17 | 1 << 9) & !(1 << 1 | 1 << 2 | 1 << 4 | 1 << 13);
            alpha_mode = 1 << 4 | 4 << 8 | 4 << 12;
        } else if rng.below(4) != 0 {
            fbz &= !1;
        }
        w.push((addr::FBZ_MODE, fbz));
        w.push((addr::ALPHA_MODE, alpha_mode));
        // Untextured: the texture-enable bit of fbzColorPath off.
        w.push((addr::FBZ_COLOR_PATH, rng.u32() & !(1 << 27)));
        w.push((addr::FOG_MODE, rng.u32() & 0x3f));
        let clip_columns = if wrapping {
            0x3ff
        } else {
            rng.u32() & 0x03ff_03ff
        };
        w.push((addr::CLIP_LEFT_RIGHT, clip_columns));
        let clip_rows = if wrapping {
            let low = rng.below(1000);
            low << 16 | (low + 1 + rng.below(3))
        } else {
            rng.u32() & 0x03ff_03ff
        };
        w.push((addr::CLIP_LOW_Y_HIGH_Y, clip_rows));
        w.push((addr::ZA_COLOR, rng.u32()));
        w.push((addr::COLOR0, rng.u32()));
        w.push((addr::COLOR1, rng.u32()));
        for _ in 0..60 {
            // Anywhere from above the screen to below the frame buffer's last row, and
            // past both sides of the row pitch. Mostly up to 12 pixels across; some
            // columns about a pixel wide and up to 40 rows tall (rows of one or two
            // pixels, many to a chunk); in the clipped states, triangles over 1100 rows,
            // whose rows 1024 apart land on one frame-buffer row (10 bits) under the
            // flip, and are the only ones inside the clip rectangle.
            let (x0, y0) = (rng.within(-24, 1060) * 16, rng.within(-24, 1060) * 16);
            let vertices: [(i32, i32); 3] = if wrapping {
                // A flat top of 15 pixels narrowing over 1100 rows to the bottom vertex:
                // a row near the top and the row 1024 below it, a pixel or two wide,
                // fit in one chunk.
                let (x, y) = (x0 % (200 * 16), -100 * 16);
                [(x, y), (x + 15 * 16, y), (x + 7 * 16, y + 1100 * 16)]
            } else {
                let (wide, tall) = if rng.below(4) == 0 {
                    (20, 40 * 16)
                } else {
                    (12 * 16, 12 * 16)
                };
                core::array::from_fn(|_| (x0 + rng.within(0, wide), y0 + rng.within(0, tall)))
            };
            let regs = [addr::VERTEX_AX, addr::VERTEX_BX, addr::VERTEX_CX];
            for (reg, (x, y)) in regs.into_iter().zip(vertices) {
                w.push((reg, x as u32));
                w.push((reg + 4, y as u32));
            }
            for reg in [
                addr::START_R,
                addr::START_G,
                addr::START_B,
                addr::START_A,
                addr::START_Z,
                addr::START_W,
            ] {
                // Starts anywhere in range, steps of up to 32 units of 1.0 either way.
                w.push((reg, rng.u32() & 0x00ff_ffff));
                w.push((reg + 0x20, (rng.within(-0x2_0000, 0x2_0000)) as u32));
                w.push((reg + 0x40, (rng.within(-0x2_0000, 0x2_0000)) as u32));
            }
            w.push((addr::TRIANGLE_CMD, rng.u32()));
        }
    }
    w
}

/// The frame buffer's words and the counters after `writes`, on the reference path or
/// the fast one, with the fast path's pixels in packed chunks and by the row path.
/// `isa`: the copy of the span kernels (`None`: the reference path).
fn replay(writes: &[(u32, u32)], isa: Option<VectorIsa>) -> (Vec<u16>, String, (u64, u64)) {
    let mut board = Board::new(BoardConfig::default());
    match isa {
        Some(isa) => {
            board.set_vector_isa(isa);
        }
        None => board.set_generic_path(true),
    }
    board.set_threads(1);
    board.pci_write(0x40, 3);
    for &(a, v) in writes {
        board.write32(a, v);
    }
    let paths = board.path_counts();
    let packed = (
        paths.packed,
        paths.span_kernels - paths.packed + paths.short_rows,
    );
    (
        board.fbi().fb.ram.clone(),
        format!("{:?}", board.stats()),
        packed,
    )
}

#[test]
fn packed_chunks_equal_the_reference_path() {
    let (mut packed, mut by_rows) = (0, 0);
    for seed in 0..24 {
        let writes = stream(seed);
        let (ram, stats, _) = replay(&writes, None);
        // Every copy of the kernels the CPU has, the best last (whose counts are kept).
        for isa in VectorIsa::available() {
            let (fast_ram, fast_stats, (p, r)) = replay(&writes, Some(isa));
            assert_eq!(stats, fast_stats, "seed {seed}, {isa}: counters");
            if let Some(i) = (0..ram.len()).find(|&i| ram[i] != fast_ram[i]) {
                panic!(
                    "seed {seed}, {isa}: word {i:#x} is {:#06x} on the fast path, {:#06x} on the reference path",
                    fast_ram[i], ram[i]
                );
            }
            if isa == VectorIsa::best() {
                packed += p;
                by_rows += r;
            }
        }
    }
    assert!(packed > 10_000, "{packed} pixels in packed chunks");
    assert!(by_rows > 1_000, "{by_rows} pixels left to the row path");
}

//! Small triangles shaded on the render thread behind the writes (`pixelfx::deferred`,
//! `Board::deferred`) against the same writes on one thread, where the order is most
//! likely to break: every kind of access that reads or writes what the render thread
//! holds comes right after blended triangles it is still shading (an LFB write under the
//! next triangles and an LFB read of the last one, a FASTFILL, a new vertical timing and a
//! swap on the retrace, host time passing and a new horizontal timing, a fog-table write
//! with fog on, `nopCMD` clearing the counters, a counter read, a new buffer layout, a
//! large triangle on the bands), and textured rounds on two TMUs change the TMUs between
//! their triangles (random `textureMode`, `tLOD` and base per TMU, texture-memory and
//! NCC-table writes into the bound texture, subpixel correction of S, T and W, which are
//! written to both TMUs, to each on its own or through the floating-point aliases). Every
//! frame-buffer word, every value read, the counters and the modelled time must be
//! identical, and the render thread must have taken most of the triangles.

use sst1_board::{Board, BoardConfig};
use sst1_regs::{addr, FbiInit2, RegisterBus};

mod common;
use common::Rng;

const LFB: u32 = 0x40_0000;
const TEX: u32 = 0x80_0000;

/// One access of the stream: a write, a read whose value is kept, or host time
/// passing (graphics clocks).
#[derive(Clone, Copy)]
enum Access {
    Write(u32, u32),
    Read(u32),
    Wait(u64),
}

/// A triangle with its three vertices `size` pixels around `(x, y)` (12.4), random
/// Gouraud colour, Z and alpha, S, T and W, drawn with `command`.
fn triangle(rng: &mut Rng, out: &mut Vec<Access>, (x, y): (u32, u32), size: u32, command: u32) {
    let regs = [addr::VERTEX_AX, addr::VERTEX_BX, addr::VERTEX_CX];
    for reg in regs {
        out.push(Access::Write(
            reg,
            (x + rng.below(size)) * 16 + rng.below(16),
        ));
        out.push(Access::Write(
            reg + 4,
            (y + rng.below(size)) * 16 + rng.below(16),
        ));
    }
    for reg in [
        addr::START_R,
        addr::START_G,
        addr::START_B,
        addr::START_A,
        addr::START_Z,
    ] {
        out.push(Access::Write(reg, rng.u32() & 0x00ff_ffff));
        out.push(Access::Write(reg + 0x20, rng.u32() & 0x1fff));
        out.push(Access::Write(reg + 0x40, rng.u32() & 0x1fff));
    }
    // S, T and W (which the calling thread keeps while the render thread holds the
    // TMUs, `deferred::LentStw`): to every chip, or to each TMU on its own (chip bits 1
    // and 2), or through the floating-point aliases (0x80 above), and some written
    // twice, the second write the one that counts.
    let form = rng.below(4);
    for reg in [addr::START_S, addr::START_T, addr::START_W] {
        for d in [0, 0x20, 0x40] {
            let fixed = |rng: &mut Rng| {
                if d == 0 {
                    rng.u32() & 0x00ff_ffff
                } else {
                    rng.u32() & 0x1fff
                }
            };
            match form {
                0 => out.push(Access::Write(reg + d, fixed(rng))),
                1 => {
                    for chip in [2 << 10, 4 << 10] {
                        out.push(Access::Write(chip | (reg + d), fixed(rng)));
                    }
                }
                2 => {
                    let v = rng.below(1 << 16) as f32 / if d == 0 { 64.0 } else { 4096.0 };
                    out.push(Access::Write(reg + d + 0x80, v.to_bits()));
                }
                _ => {
                    out.push(Access::Write(
                        reg + d + 0x80,
                        (rng.below(256) as f32).to_bits(),
                    ));
                    out.push(Access::Write(reg + d, fixed(rng)));
                }
            }
        }
    }
    out.push(Access::Write(command, rng.u32() & 1 << 31));
}

/// The stream of `seed`: rounds of small blended triangles, each round ended by one
/// access of every kind in turn that the render thread must be called back for.
fn stream(seed: u64) -> Vec<Access> {
    let mut rng = Rng::new(seed);
    let mut out: Vec<Access> = sst1_board::presets::GLIDE_640X480
        .iter()
        .map(|&(a, v)| Access::Write(a, v))
        .collect();
    // LFB writes and reads of the back buffer, RGB565.
    out.push(Access::Write(addr::LFB_MODE, 1 << 4 | 1 << 6));
    out.push(Access::Write(addr::CLIP_LEFT_RIGHT, 640));
    out.push(Access::Write(addr::CLIP_LOW_Y_HIGH_Y, 480));
    for round in 0..60u32 {
        // Back buffer, RGB and depth writes, a random depth function, 4x4 dither; fog
        // on in some rounds; blending source alpha over the destination.
        let fbz = 1 << 14 | 1 << 9 | 1 << 10 | 1 << 4 | (rng.below(8) << 5) | 1 << 8 | 1;
        out.push(Access::Write(addr::FBZ_MODE, fbz));
        out.push(Access::Write(addr::ALPHA_MODE, 1 << 4 | 1 << 8 | 5 << 12));
        // Odd rounds textured, on both TMUs (TMU 0 at chip bit 1, TMU 1 at bit 2): one
        // in two with random modes and any colour path, the other with the texel as the
        // colour and TMU 0 on a 16x16 RGB565 bilinear level (tex_rgb565_bilinear's
        // textureMode; LOD 4 alone) that the downloads below fill, so that a texel
        // written or an S, T or W out of place shows. Subpixel correction or not.
        let textured = round % 2 == 1;
        let known = round % 4 == 1;
        let adjust = rng.below(2) << 26;
        let color_path = match (textured, known) {
            (false, _) => 0,
            (true, false) => rng.u32() | 1 << 27,
            (true, true) => 0x0800_0005 | adjust,
        };
        out.push(Access::Write(addr::FBZ_COLOR_PATH, color_path));
        if textured {
            for chip in [2 << 10, 4 << 10] {
                let (mode, lod, base) = if known && chip == 2 << 10 {
                    (0x0824_1a00, 16 | 16 << 6, 0)
                } else {
                    (rng.u32(), rng.u32(), rng.below(64))
                };
                out.push(Access::Write(chip | addr::TEXTURE_MODE, mode));
                out.push(Access::Write(chip | addr::T_LOD, lod));
                out.push(Access::Write(chip | addr::TEX_BASE_ADDR, base));
            }
        }
        if round == 1 {
            // The whole 16x16 level, two texels a word.
            for t in 0..16 {
                for pair in 0..8 {
                    out.push(Access::Write(
                        TEX + (4 << 17) + (t << 9) + (pair << 2),
                        rng.u32(),
                    ));
                }
            }
        }
        out.push(Access::Write(addr::FOG_MODE, rng.below(2)));
        out.push(Access::Write(addr::FOG_COLOR, rng.u32()));
        // All triangles of a round within 40 pixels of one place, so that they
        // overlap each other and what the round's hazard touches.
        let at = (20 + rng.below(560), 20 + rng.below(400));
        for k in 0..12 {
            let corner = (at.0 + rng.below(24), at.1 + rng.below(24));
            triangle(&mut rng, &mut out, corner, 10, addr::TRIANGLE_CMD);
            if textured && k % 3 == 0 {
                // Texture words into the first levels of either TMU, and an NCC
                // register, between triangles still queued.
                for _ in 0..8 {
                    let texel = if known {
                        TEX + (4 << 17) + (rng.below(16) << 9) + (rng.below(8) << 2)
                    } else {
                        TEX + (rng.below(2) << 21) + (rng.below(0x8000) << 2)
                    };
                    out.push(Access::Write(texel, rng.u32()));
                }
                let ncc = addr::NCC_TABLE0 + rng.below(24) * 4;
                out.push(Access::Write(2 << 10 | ncc, rng.u32()));
            }
        }
        let (x, y) = (at.0 + 12, at.1 + 12);
        let lfb = LFB + (y << 11) + (x << 1);
        match round % 9 {
            0 => {
                // An LFB write under the next triangles.
                out.push(Access::Write(lfb, rng.u32()));
                out.push(Access::Write(lfb + 2048, rng.u32()));
            }
            1 => out.push(Access::Read(lfb)),
            2 => {
                out.push(Access::Write(addr::COLOR1, rng.u32()));
                out.push(Access::Write(
                    addr::CLIP_LEFT_RIGHT,
                    x << 16 | (x + 1 + rng.below(8)),
                ));
                out.push(Access::Write(
                    addr::CLIP_LOW_Y_HIGH_Y,
                    y << 16 | (y + 1 + rng.below(8)),
                ));
                out.push(Access::Write(addr::FASTFILL_CMD, 0));
                out.push(Access::Write(addr::CLIP_LEFT_RIGHT, 640));
                out.push(Access::Write(addr::CLIP_LOW_Y_HIGH_Y, 480));
            }
            3 => {
                // A new vertical timing (the frame's length), then a swap that waits
                // for the retrace.
                let lines = 0x020b + rng.below(64);
                out.push(Access::Write(addr::V_SYNC, lines << 16 | 2));
                triangle(&mut rng, &mut out, at, 10, addr::TRIANGLE_CMD);
                out.push(Access::Write(addr::SWAPBUFFER_CMD, 1));
            }
            4 => {
                let entry = rng.below(32) * 4;
                out.push(Access::Write(addr::FOG_TABLE + entry, rng.u32()));
            }
            5 => {
                // The counters cleared after triangles still to shade, then read.
                out.push(Access::Read(addr::FBI_PIXELS_IN));
                triangle(&mut rng, &mut out, at, 10, addr::TRIANGLE_CMD);
                out.push(Access::Write(addr::NOP_CMD, 1));
                triangle(&mut rng, &mut out, at, 10, addr::TRIANGLE_CMD);
                out.push(Access::Read(addr::FBI_PIXELS_OUT));
            }
            6 => {
                // Rows of 256 words (4 tiles across in fbiInit1) with buffers a page
                // further on, or Glide's layout again.
                let (init1, pages) = if (round / 9) % 2 == 0 {
                    (0x0020_0042, 151)
                } else {
                    (0x0020_00a2, 150)
                };
                let init2 = FbiInit2(0x1874_b040).with_video_buffer_offset(pages);
                out.push(Access::Write(addr::FBI_INIT1, init1));
                triangle(&mut rng, &mut out, at, 10, addr::TRIANGLE_CMD);
                out.push(Access::Write(addr::FBI_INIT2, init2.0));
            }
            7 => {
                // The float triangle command; host time passing while triangles are
                // queued, a new horizontal timing, then the status and the scan line.
                triangle(&mut rng, &mut out, at, 10, addr::F_TRIANGLE_CMD);
                out.push(Access::Wait(u64::from(rng.below(20_000))));
                triangle(&mut rng, &mut out, at, 10, addr::TRIANGLE_CMD);
                out.push(Access::Write(
                    addr::H_SYNC,
                    (0x0320 + rng.below(64)) << 16 | 0x60,
                ));
                triangle(&mut rng, &mut out, at, 10, addr::TRIANGLE_CMD);
                out.push(Access::Read(addr::STATUS));
                out.push(Access::Read(addr::V_RETRACE));
            }
            _ => triangle(
                &mut rng,
                &mut out,
                (at.0 / 2, at.1 / 2),
                200,
                addr::TRIANGLE_CMD,
            ),
        }
        // More triangles over what the hazard touched before the round ends.
        for _ in 0..4 {
            triangle(&mut rng, &mut out, (x - 6, y - 6), 12, addr::TRIANGLE_CMD);
        }
    }
    out.push(Access::Read(addr::FBI_PIXELS_IN));
    out
}

/// What one replay of `stream` left and read, on `threads` render threads: the
/// frame-buffer words, the values read, the counters, the modelled time and the pixels
/// shaded behind the writes.
fn replay(stream: &[Access], threads: usize) -> (Vec<u16>, Vec<u32>, String, u64) {
    let mut board = Board::new(BoardConfig {
        tmus: 2,
        ..BoardConfig::default()
    });
    board.set_threads(threads);
    board.pci_write(0x40, 3);
    let mut reads = Vec::new();
    {
        let mut run = board.deferred();
        for &access in stream {
            match access {
                Access::Write(a, v) => run.write32(a, v),
                Access::Read(a) => reads.push(run.board().read32(a)),
                Access::Wait(cycles) => run.host_wait(cycles),
            }
        }
    }
    let timing = board.timing();
    let record = format!("{:?} {:?} {:?}", board.stats(), timing.total, timing.frames);
    (
        board.fbi().fb.ram.clone(),
        reads,
        record,
        board.path_counts().behind_writes,
    )
}

#[test]
fn triangles_behind_the_writes_equal_one_thread() {
    let mut behind = 0;
    for seed in 0..4 {
        let writes = stream(seed);
        let (ram, reads, record, none) = replay(&writes, 1);
        assert_eq!(none, 0, "one thread defers nothing");
        let (ram2, reads2, record2, b) = replay(&writes, 2);
        assert_eq!(record, record2, "seed {seed}: counters or time");
        assert_eq!(reads, reads2, "seed {seed}: values read");
        if let Some(i) = (0..ram.len()).find(|&i| ram[i] != ram2[i]) {
            panic!(
                "seed {seed}: word {i:#x} is {:#06x} behind the writes, {:#06x} on one thread",
                ram2[i], ram[i]
            );
        }
        behind += b;
    }
    assert!(behind > 30_000, "{behind} pixels behind the writes");
}

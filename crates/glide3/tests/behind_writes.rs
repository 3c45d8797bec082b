//! Glide on a board that shades its small triangles behind the writes
//! (`sst1_board::Deferred`, owned, as libglide3 holds its board for a whole session):
//! the same buffers, values read and counters as one thread writing the board directly,
//! whatever Glide calls come between the triangles.

use glide::consts::*;
use glide::{BoardInfo, Glide, TexInfo};
use sst1_board::{Board, BoardConfig, BufferKind, Deferred};
use sst1_regs::addr::{
    FBI_AFUNC_FAIL, FBI_CHROMA_FAIL, FBI_PIXELS_IN, FBI_PIXELS_OUT, FBI_ZFUNC_FAIL,
};
use sst1_regs::RegisterBus;
use std::cell::RefCell;
use std::rc::Rc;

/// xorshift64* (Vigna): picks the scene's inputs.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 32) as u32
    }

    fn below(&mut self, n: u32) -> u32 {
        self.next() % n
    }

    fn pick(&mut self, items: &[u32]) -> u32 {
        items[self.below(items.len() as u32) as usize]
    }

    fn unit(&mut self) -> f32 {
        self.below(1 << 16) as f32 / 65536.0
    }
}

const CONFIG: BoardConfig = BoardConfig {
    fbi_mb: 4,
    tmus: 2,
    tmu_mb: 2,
};

/// One 16x16 RGB565 level.
const TEX: TexInfo = TexInfo {
    small_lod: GR_LOD_LOG2_16,
    large_lod: GR_LOD_LOG2_16,
    aspect: GR_ASPECT_LOG2_1x1,
    format: GR_TEXFMT_RGB_565,
};

/// `GR_COMBINE_FUNCTION_*`.
const FUNCTIONS: [u32; 11] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 0x10];
/// `GR_COMBINE_FACTOR_*` of the colour combine.
const COLOUR_FACTORS: [u32; 10] = [0, 1, 2, 3, 4, 8, 9, 10, 11, 12];
/// `GR_COMBINE_FACTOR_*` of the texture combine.
const FACTORS: [u32; 12] = [0, 1, 2, 3, 4, 5, 8, 9, 10, 11, 12, 13];

/// What a run saw and left: the values its LFB reads and status polls returned, then
/// the front, back and aux buffers and the pixel counters.
#[derive(PartialEq, Debug)]
struct Outcome {
    read: Vec<u32>,
    buffers: [Vec<u16>; 3],
    counters: [u32; 5],
}

fn open(bus: Box<dyn RegisterBus>) -> Glide {
    let mut g = Glide::init(
        bus,
        BoardInfo::new(CONFIG.fbi_mb, CONFIG.tmus, CONFIG.tmu_mb),
    );
    assert!(g.win_open(
        GR_RESOLUTION_640x480,
        GR_REFRESH_60Hz,
        GR_COLORFORMAT_ARGB,
        GR_ORIGIN_UPPER_LEFT,
        2,
        1,
    ));
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_Q, 8, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_RGB, 12, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_A, 24, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_ST0, 28, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_ST1, 36, GR_PARAM_ENABLE);
    g.cull_mode(GR_CULL_DISABLE);
    g
}

/// A texture of random texels into `tmu` at `start`.
fn download(g: &mut Glide, rng: &mut Rng, tmu: u32, start: u32) {
    let texels: Vec<u8> = (0..512).map(|_| rng.below(256) as u8).collect();
    g.tex_download_mipmap(tmu, start, GR_MIPMAPLEVELMASK_BOTH, &TEX, &texels);
}

/// A random vertex near `(cx, cy)`: a triangle of three is a few pixels.
fn vertex(rng: &mut Rng, cx: f32, cy: f32) -> [f32; 11] {
    let oow = 0.2 + rng.unit();
    [
        cx + rng.unit() * 6.0,
        cy + rng.unit() * 6.0,
        oow,
        rng.unit() * 255.0,
        rng.unit() * 255.0,
        rng.unit() * 255.0,
        rng.unit() * 255.0,
        rng.unit() * 16.0 * oow,
        rng.unit() * 16.0 * oow,
        rng.unit() * 16.0 * oow,
        rng.unit() * 16.0 * oow,
    ]
}

/// Many small triangles in random states, with texture downloads, LFB reads and
/// writes, clears, status polls and swaps between them.
fn scene(g: &mut Glide, seed: u64) -> Vec<u32> {
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let mut read = Vec::new();
    let starts = [g.tex_min_address(GR_TMU0), g.tex_min_address(GR_TMU1)];
    for tmu in [GR_TMU0, GR_TMU1] {
        download(g, &mut rng, tmu, starts[tmu as usize]);
        g.tex_source(tmu, starts[tmu as usize], GR_MIPMAPLEVELMASK_BOTH, &TEX);
    }
    g.depth_buffer_mode(GR_DEPTHBUFFER_WBUFFER);
    g.depth_mask(true);
    g.buffer_clear(0x0020_4060, 0, 0xffff);
    for i in 0..3000u32 {
        match rng.below(100) {
            0..=5 => {
                let which = rng.below(2);
                download(g, &mut rng, which, starts[which as usize]);
            }
            6..=8 => {
                let mut out = vec![0u8; 2 * 8 * 4];
                let (x, y) = (rng.below(600), rng.below(440));
                g.lfb_read_region(GR_BUFFER_BACKBUFFER, x, y, 8, 4, 16, &mut out);
                read.extend(
                    out.chunks(4)
                        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])),
                );
            }
            9 => {
                let data: Vec<u8> = (0..2 * 4 * 4).map(|_| rng.below(256) as u8).collect();
                let (x, y) = (rng.below(600), rng.below(440));
                g.lfb_write_region(
                    GR_BUFFER_BACKBUFFER,
                    x,
                    y,
                    GR_LFB_SRC_FMT_565,
                    4,
                    4,
                    false,
                    8,
                    &data,
                );
            }
            10 => read.push(g.is_busy() as u32),
            11 if i % 7 == 0 => g.buffer_swap(0),
            12..=25 => {
                g.color_combine(
                    rng.pick(&FUNCTIONS),
                    rng.pick(&COLOUR_FACTORS),
                    rng.below(2),
                    rng.below(3),
                    rng.below(2) != 0,
                );
                g.alpha_blend_function(
                    rng.pick(&[GR_BLEND_ONE, GR_BLEND_SRC_ALPHA, GR_BLEND_DST_COLOR]),
                    rng.pick(&[GR_BLEND_ZERO, GR_BLEND_ONE_MINUS_SRC_ALPHA, GR_BLEND_ONE]),
                    GR_BLEND_ONE,
                    GR_BLEND_ZERO,
                );
                g.depth_buffer_function(rng.below(8));
                g.dither_mode(rng.below(3));
                g.fog_mode(rng.pick(&[GR_FOG_DISABLE, GR_FOG_WITH_TABLE_ON_Q]));
                g.fog_color_value(rng.next());
                for tmu in [GR_TMU0, GR_TMU1] {
                    g.tex_filter_mode(tmu, rng.below(2), rng.below(2));
                    g.tex_clamp_mode(tmu, rng.below(2), rng.below(2));
                    g.tex_combine(
                        tmu,
                        rng.pick(&FUNCTIONS),
                        rng.pick(&FACTORS),
                        rng.pick(&FUNCTIONS),
                        rng.pick(&FACTORS),
                        rng.below(2) != 0,
                        rng.below(2) != 0,
                    );
                }
            }
            _ => {
                let (cx, cy) = (rng.unit() * 630.0, rng.unit() * 470.0);
                let [a, b, c] = [0; 3].map(|_| vertex(&mut rng, cx, cy));
                g.draw_triangle(&a, &b, &c);
            }
        }
    }
    g.buffer_swap(0);
    read
}

fn outcome(board: &mut Board, read: Vec<u32>) -> Outcome {
    Outcome {
        read,
        buffers: [BufferKind::Front, BufferKind::Back, BufferKind::Aux]
            .map(|b| board.dump_buffer(b)),
        counters: [
            FBI_PIXELS_IN,
            FBI_CHROMA_FAIL,
            FBI_ZFUNC_FAIL,
            FBI_AFUNC_FAIL,
            FBI_PIXELS_OUT,
        ]
        .map(|r| board.read32(r)),
    }
}

#[test]
fn glide_behind_the_writes_equals_one_thread() {
    for seed in 1..=3 {
        // One thread, writing the board directly.
        let direct = Rc::new(RefCell::new(Board::new(CONFIG)));
        let mut g = open(Box::new(direct.clone()));
        let read = scene(&mut g, seed);
        assert_eq!(g.last_error(), None);
        drop(g);
        let want = outcome(&mut direct.borrow_mut(), read);

        // Two threads, the board held behind the writes as libglide3 holds it.
        let mut board = Board::new(CONFIG);
        board.set_threads(2);
        let behind = Rc::new(RefCell::new(Deferred::new(board)));
        let mut g = open(Box::new(behind.clone()));
        let read = scene(&mut g, seed);
        drop(g);
        let mut held = behind.borrow_mut();
        let board = held.board();
        let behind_writes = board.path_counts().behind_writes;
        let got = outcome(board, read);
        assert!(got == want, "seed {seed}: the runs differ");
        assert!(
            behind_writes > 10_000,
            "seed {seed}: only {behind_writes} pixels were shaded behind the writes"
        );
    }
}

//! Hostile input on the whole PCI aperture (spec 4: registers, LFB and texture regions;
//! spec 5: chip select, the wrap field and the triangle-register remap of `fbiInit3`).
//!
//! Two kinds of test:
//!
//! * Random bus traffic from a seeded xorshift generator: tens of thousands of writes and
//!   reads at random addresses, mixed with the operations most likely to break
//!   arithmetic (triangles with extreme, degenerate and sliver vertices and huge
//!   gradients, float registers holding NaN, infinities, denormals and huge exponents,
//!   FASTFILL with inverted clip rectangles, swaps, LFB writes in every `lfbMode`,
//!   texture downloads under random `textureMode`/`tLOD`, reads of every register).
//!   Each stream must run without a panic, give the same buffers, counters, diagnostics
//!   and read values when replayed, and give the same again on the reference pixel path
//!   (`Board::set_generic_path(true)`).
//! * Iterators that leave their fixed-point range (spec 5.3-5.14: colour 12.12, Z 20.12,
//!   W 2.30): exact pixels derived by hand from the SST-1 pseudo-clamp, on both paths.
//!
//! Run the stress tests in a debug build too (`cargo test -p sst1-board --test stress`):
//! there integer overflow panics, so any unchecked arithmetic on hostile values shows.

use sst1_board::{Board, BoardConfig, BufferKind, Diagnostics, Stats, VectorIsa};
use sst1_regs::{addr, RegisterBus};

mod common;
use common::Rng;

/// Start of the LFB region of the aperture (spec 4).
const LFB_BASE: u32 = 0x40_0000;
/// Start of the texture region of the aperture (spec 4).
const TEX_BASE: u32 = 0x80_0000;
/// `initEnable` in PCI configuration space (spec 6).
const PCI_INIT_ENABLE: u32 = 0x40;
/// `fbzMode` bit 0: clip to the clip rectangle.
const FBZ_CLIP: u32 = 1;

/// After the Glide 640x480 mode set: clip on, RGB and aux writes on, drawing into the
/// back buffer; stipple all ones.
const INIT_TAIL: &[(u32, u32)] = &[(addr::FBZ_MODE, 0x0000_4601), (addr::STIPPLE, 0xffff_ffff)];

fn init(board: &mut Board) {
    sst1_board::presets::init_glide_640x480(board);
    for &(a, v) in INIT_TAIL {
        board.write32(a, v);
    }
}

// --- the generator -----------------------------------------------------------------

/// One bus operation.
#[derive(Clone, Copy, Debug)]
enum Op {
    Write(u32, u32),
    Read(u32),
    Pci(u32, u32),
}

/// IEEE singles that break float-to-fixed conversions: NaNs, infinities, denormals,
/// the largest finite values, powers of two at and past the 32-bit boundaries, -0.
const NASTY_FLOATS: &[u32] = &[
    0x7fc0_0000, // quiet NaN
    0xffc0_0000, // negative quiet NaN
    0x7f80_0001, // signalling NaN
    0xffff_ffff, // NaN, all bits set
    0x7f80_0000, // +inf
    0xff80_0000, // -inf
    0x0000_0001, // smallest denormal
    0x807f_ffff, // largest negative denormal
    0x0080_0000, // smallest normal
    0x7f7f_ffff, // largest finite
    0xff7f_ffff, // most negative finite
    0x4f00_0000, // 2^31
    0xcf00_0000, // -2^31
    0x5380_0000, // 2^40
    0x54ad_c3f7, // ~5.97e12, overflows 32 bits after a shift of 31
    0x8000_0000, // -0.0
    0x0000_0000, // +0.0
    0x3f80_0000, // 1.0
    0xbf80_0000, // -1.0
    0x457f_fff0, // 4095.996
    0x477f_ff00, // 65535.0
    0x4580_0000, // 4096.0
];

/// Fixed-point values at the edges of the register formats (12.4, 12.12 in 24 bits,
/// 20.12, 14.18, 2.30).
const NASTY_FIXED: &[u32] = &[
    0x0000_0000,
    0x0000_0001,
    0xffff_ffff,
    0x7fff_ffff,
    0x8000_0000,
    0x0000_7fff,
    0x0000_8000,
    0x0000_ffff,
    0x007f_ffff,
    0x0080_0000,
    0x00ff_ffff,
    0x00ff_f000,
    0x0010_0000,
    0x0fff_f000,
    0x1000_0000,
    0x4000_0000,
    0xc000_0000,
    0x0000_0100,
];

/// 12.4 vertex coordinates at the ends of the 16-bit register and around zero.
const NASTY_VERTICES: &[i32] = &[
    0x7fff, -0x8000, 0x7ff0, -0x7ff0, 0x7fef, -0x8001, 0, 1, -1, 8, -8, 0x10, 0x1000,
];

/// Registers the generator writes more often than a uniform pick would.
const HOT_REGISTERS: &[u32] = &[
    addr::FBZ_COLOR_PATH,
    addr::FOG_MODE,
    addr::ALPHA_MODE,
    addr::FBZ_MODE,
    addr::LFB_MODE,
    addr::CLIP_LEFT_RIGHT,
    addr::CLIP_LOW_Y_HIGH_Y,
    addr::NOP_CMD,
    addr::FASTFILL_CMD,
    addr::SWAPBUFFER_CMD,
    addr::FOG_COLOR,
    addr::ZA_COLOR,
    addr::CHROMA_KEY,
    addr::STIPPLE,
    addr::COLOR0,
    addr::COLOR1,
    addr::FOG_TABLE,
    addr::FOG_TABLE_LAST,
    addr::FBI_INIT0,
    addr::FBI_INIT1,
    addr::FBI_INIT2,
    addr::FBI_INIT3,
    addr::FBI_INIT4,
    addr::VIDEO_DIMENSIONS,
    addr::TEXTURE_MODE,
    addr::T_LOD,
    addr::T_DETAIL,
    addr::TEX_BASE_ADDR,
    addr::TEX_BASE_ADDR_1,
    addr::TEX_BASE_ADDR_2,
    addr::TEX_BASE_ADDR_3_8,
    addr::TREX_INIT0,
    addr::TREX_INIT1,
    addr::NCC_TABLE0,
    addr::NCC_TABLE0 + 0x20,
    addr::NCC_TABLE1 + 0x2c,
];

/// The start, d/dX and d/dY registers of every iterated parameter (fixed-point map).
const PARAMS: &[[u32; 3]] = &[
    [addr::START_R, addr::D_R_DX, addr::D_R_DY],
    [addr::START_G, addr::D_G_DX, addr::D_G_DY],
    [addr::START_B, addr::D_B_DX, addr::D_B_DY],
    [addr::START_Z, addr::D_Z_DX, addr::D_Z_DY],
    [addr::START_A, addr::D_A_DX, addr::D_A_DY],
    [addr::START_S, addr::D_S_DX, addr::D_S_DY],
    [addr::START_T, addr::D_T_DX, addr::D_T_DY],
    [addr::START_W, addr::D_W_DX, addr::D_W_DY],
];

/// Builds the operation stream for one seed.
struct Generator {
    rng: Rng,
    ops: Vec<Op>,
}

impl Generator {
    fn write(&mut self, a: u32, v: u32) {
        self.ops.push(Op::Write(a, v));
    }

    /// A register-region address for normal-map `offset`: random chip-select field
    /// (bits 13:10) and wrap field (bits 21:14; bit 21 selects the remap when
    /// `fbiInit3` bit 0 is set), and sometimes stray low bits.
    fn reg_addr(&mut self, offset: u32) -> u32 {
        let chips = if self.rng.chance(50) {
            0
        } else {
            self.rng.below(16)
        };
        let wrap = if self.rng.chance(70) {
            0
        } else {
            self.rng.below(256)
        };
        let stray = if self.rng.chance(5) {
            self.rng.below(4)
        } else {
            0
        };
        (wrap << 14) | (chips << 10) | (offset & 0x3fc) | stray
    }

    /// A random `fbzMode` that mostly draws something: usually a real draw buffer
    /// (bits 15:14 = 0 or 1, 2 and 3 are reserved) and the RGB write mask on (bit 9).
    fn fbz_mode(&mut self) -> u32 {
        let v = self.rng.u32();
        if self.rng.chance(80) {
            v & !0x8000 | 0x200
        } else {
            v
        }
    }

    /// A register value: an edge of a fixed-point format, a nasty float, a 24-bit value
    /// or anything.
    fn value(&mut self) -> u32 {
        match self.rng.below(4) {
            0 => self.rng.pick(NASTY_FIXED),
            1 => self.rng.pick(NASTY_FLOATS),
            2 => self.rng.u32() & 0xff_ffff,
            _ => self.rng.u32(),
        }
    }

    /// One generator step: one or more bus operations of a randomly chosen kind.
    fn op(&mut self) {
        match self.rng.below(100) {
            // Anything anywhere in the 16 MiB aperture (and beyond: bits 31:24 set).
            0..=19 => {
                let a = self.rng.u32();
                let v = self.value();
                self.write(a, v);
            }
            20..=34 => {
                let offset = if self.rng.chance(50) {
                    self.rng.pick(HOT_REGISTERS)
                } else {
                    self.rng.below(0x100) << 2
                };
                let a = self.reg_addr(offset);
                let v = self.value();
                self.write(a, v);
            }
            35..=54 => self.triangle(),
            55..=59 => self.float_registers(),
            60..=64 => self.fastfill(),
            65..=66 => {
                let a = self.reg_addr(addr::SWAPBUFFER_CMD);
                let v = self.rng.u32();
                self.write(a, v);
            }
            67..=79 => self.lfb(),
            80..=89 => self.texture(),
            90..=94 => self.read_all(),
            // Back to the Glide init now and then: random fbiInit, videoDimensions and
            // fbzMode writes leave a layout where little can be drawn.
            95 => {
                self.ops.push(Op::Pci(PCI_INIT_ENABLE, 3));
                for &(a, v) in sst1_board::presets::GLIDE_640X480.iter().chain(INIT_TAIL) {
                    self.write(a, v);
                }
            }
            96 => {
                // initEnable, sometimes closing the fbiInit gate, or some other offset.
                let offset = if self.rng.chance(70) {
                    PCI_INIT_ENABLE
                } else {
                    self.rng.below(64) << 2
                };
                let v = if self.rng.chance(80) {
                    3
                } else {
                    self.rng.u32()
                };
                self.ops.push(Op::Pci(offset, v));
            }
            _ => {
                let a = self.rng.u32();
                self.ops.push(Op::Read(a));
            }
        }
    }

    /// Vertices: extreme, degenerate, sliver or ordinary, in the fixed or float registers.
    fn vertices(&mut self) {
        let r = &mut self.rng;
        let v: [(i32, i32); 3] = match r.below(5) {
            // Extremes of the 12.4 registers.
            0 => std::array::from_fn(|_| (r.pick(NASTY_VERTICES), r.pick(NASTY_VERTICES))),
            // Zero area: C on the line through A and B.
            1 => {
                let a = (
                    r.below(0x4000) as i32 - 0x1000,
                    r.below(0x4000) as i32 - 0x1000,
                );
                let d = (r.below(0x200) as i32 - 0x100, r.below(0x200) as i32 - 0x100);
                let k = r.below(8) as i32 - 3;
                [a, (a.0 + d.0, a.1 + d.1), (a.0 + k * d.0, a.1 + k * d.1)]
            }
            // Sliver: two vertices 1/16 pixel apart, the third far away.
            2 => {
                let a = (r.below(0x2000) as i32, r.below(0x2000) as i32);
                let far = (
                    r.below(0x10000) as i32 - 0x8000,
                    r.below(0x10000) as i32 - 0x8000,
                );
                [a, (a.0 + 1, a.1 + r.below(3) as i32 - 1), far]
            }
            // Random 16-bit registers.
            3 => std::array::from_fn(|_| (r.u32() as i16 as i32, r.u32() as i16 as i32)),
            // Ordinary: on screen, up to 64 pixels.
            _ => {
                let (x0, y0) = (r.below(600 * 16) as i32, r.below(440 * 16) as i32);
                std::array::from_fn(|_| {
                    (x0 + r.below(64 * 16) as i32, y0 + r.below(64 * 16) as i32)
                })
            }
        };
        let float = self.rng.chance(30);
        let regs = [
            addr::VERTEX_AX,
            addr::VERTEX_AY,
            addr::VERTEX_BX,
            addr::VERTEX_BY,
            addr::VERTEX_CX,
            addr::VERTEX_CY,
        ];
        let coords = [v[0].0, v[0].1, v[1].0, v[1].1, v[2].0, v[2].1];
        for (reg, c) in regs.into_iter().zip(coords) {
            if float {
                let bits = if self.rng.chance(10) {
                    self.rng.pick(NASTY_FLOATS)
                } else {
                    (c as f32 / 16.0).to_bits()
                };
                self.write(reg + 0x80, bits);
            } else {
                self.write(reg, c as u32);
            }
        }
    }

    /// A triangle command with random modes and random or extreme parameters.
    fn triangle(&mut self) {
        self.vertices();
        for &[start, dx, dy] in PARAMS {
            if self.rng.chance(25) {
                continue; // keep the previous triangle's value
            }
            for reg in [start, dx, dy] {
                let v = match self.rng.below(5) {
                    0 => 0,
                    // Huge gradients: the largest 12.12 / 20.12 / 14.18 / 2.30 steps.
                    1 => self
                        .rng
                        .pick(&[0x007f_ffff, 0x0080_0000, 0x7fff_ffff, 0x8000_0000]),
                    2 => self.rng.pick(NASTY_FIXED),
                    _ => self.rng.u32(),
                };
                // Some go to a TMU alone (chip select bits 11..13) and some to all.
                let chips = self.rng.pick(&[0, 0, 0, 1, 2, 4, 8, 6]);
                self.write(chips << 10 | reg, v);
            }
        }
        if self.rng.chance(70) {
            for reg in [addr::FBZ_COLOR_PATH, addr::ALPHA_MODE, addr::FOG_MODE] {
                if self.rng.chance(60) {
                    let v = self.rng.u32();
                    self.write(reg, v);
                }
            }
            if self.rng.chance(60) {
                let v = self.fbz_mode();
                self.write(addr::FBZ_MODE, v);
            }
        }
        self.clip();
        let cmd = if self.rng.chance(50) {
            addr::TRIANGLE_CMD
        } else {
            addr::F_TRIANGLE_CMD
        };
        let sign = self.rng.u32();
        let a = self.reg_addr(cmd);
        self.write(a, sign);
    }

    /// Float parameter registers (0x088..=0x0fc) with NaN, infinities and friends.
    fn float_registers(&mut self) {
        for _ in 0..1 + self.rng.below(8) {
            let reg = addr::F_VERTEX_AX + (self.rng.below(30) << 2);
            let v = if self.rng.chance(70) {
                self.rng.pick(NASTY_FLOATS)
            } else {
                self.rng.u32()
            };
            let a = self.reg_addr(reg);
            self.write(a, v);
        }
    }

    /// A random clip rectangle, mostly small (up to 64x64, sometimes inverted or empty),
    /// sometimes with edges at 0, the screen size or 1023. Bits above the 10-bit fields
    /// are set too: they must be ignored.
    fn clip(&mut self) {
        let edges = [0, 1, 479, 480, 639, 640, 1023];
        let range = |g: &mut Self| {
            if g.rng.chance(90) {
                let a = g.rng.below(1024);
                let b = (a + g.rng.below(80)).saturating_sub(16).min(1023);
                (a, b)
            } else {
                (g.rng.pick(&edges), g.rng.pick(&edges))
            }
        };
        let ((l, r), (lo, hi)) = (range(self), range(self));
        let junk = self.rng.u32() & 0xfc00_fc00;
        self.write(addr::CLIP_LEFT_RIGHT, junk | l << 16 | r);
        self.write(addr::CLIP_LOW_Y_HIGH_Y, junk | lo << 16 | hi);
    }

    /// FASTFILL of a random clip rectangle with random colour, depth and `fbzMode`.
    fn fastfill(&mut self) {
        self.clip();
        if self.rng.chance(50) {
            let v = self.fbz_mode();
            self.write(addr::FBZ_MODE, v);
        }
        let (c1, za) = (self.rng.u32(), self.rng.u32());
        self.write(addr::COLOR1, c1);
        self.write(addr::ZA_COLOR, za);
        let a = self.reg_addr(addr::FASTFILL_CMD);
        self.write(a, 0);
    }

    /// An `lfbMode` (any format, lanes, swaps, buffers, pipeline bit) and a burst of LFB
    /// writes and reads.
    fn lfb(&mut self) {
        let mode = self.rng.u32();
        let a = self.reg_addr(addr::LFB_MODE);
        self.write(a, mode);
        for _ in 0..1 + self.rng.below(16) {
            let offset = if self.rng.chance(70) {
                // On screen, 16- or 32-bit pixel addressing.
                let (x, y) = (self.rng.below(640), self.rng.below(480));
                if self.rng.chance(50) {
                    y << 11 | x << 1
                } else {
                    y << 12 | x << 2
                }
            } else {
                self.rng.u32() & 0x3f_ffff
            };
            if self.rng.chance(80) {
                let v = self.rng.u32();
                self.write(LFB_BASE + offset, v);
            } else {
                self.ops.push(Op::Read(LFB_BASE + offset));
            }
        }
    }

    /// Random texture state for one or all TMUs, then texture-memory writes.
    fn texture(&mut self) {
        let chips = self.rng.pick(&[0, 2, 4, 8, 0xe]);
        for reg in [
            addr::TEXTURE_MODE,
            addr::T_LOD,
            addr::T_DETAIL,
            addr::TEX_BASE_ADDR,
            addr::TEX_BASE_ADDR_1,
            addr::TEX_BASE_ADDR_2,
            addr::TEX_BASE_ADDR_3_8,
        ] {
            if self.rng.chance(60) {
                let v = self.rng.u32();
                self.write(chips << 10 | reg, v);
            }
        }
        for _ in 0..self.rng.below(32) {
            let a = TEX_BASE | (self.rng.u32() & 0x7f_ffff);
            let v = self.rng.u32();
            self.write(a, v);
        }
    }

    /// Every register offset, through a random chip field and wrap field.
    fn read_all(&mut self) {
        for i in 0..0x100 {
            let a = self.reg_addr(i << 2);
            self.ops.push(Op::Read(a));
        }
    }
}

/// The operation stream for `seed`: `n` generator steps (each one or more bus operations).
fn ops(seed: u64, n: usize) -> Vec<Op> {
    let mut g = Generator {
        rng: Rng::new(seed),
        ops: Vec::new(),
    };
    for _ in 0..n {
        g.op();
    }
    g.ops
}

/// Everything observable after a run.
#[derive(Debug, PartialEq)]
struct Outcome {
    front: Vec<u16>,
    back: Vec<u16>,
    aux: Vec<u16>,
    stats: Stats,
    diagnostics: Diagnostics,
    /// FNV-1a over every value the reads returned, in order.
    reads: u64,
    /// `pixels_out` and the three fail counters summed over the run (the hardware
    /// counters are cleared by `nopCMD` bit 0 and `fbiInit0` bit 1 along the way).
    totals: [u64; 2],
}

/// `pixels_out` and the sum of the fail counters.
fn counters(s: &Stats) -> [u64; 2] {
    [s.pixels_out, s.zfunc_fail + s.afunc_fail + s.chroma_fail]
}

/// Replays `ops` on a fresh board after the Glide init.
///
/// Writes to `fbzMode` always get the clip bit (bit 0): without it a triangle with
/// vertices at the ends of the 12.4 range walks up to 4096 x 4096 pixels, which is
/// correct but too slow for a test of this size. Unclipped drawing still happens through
/// the init value of the clip rectangle being overwritten with random ones, and through
/// LFB writes, which ignore clipping unless they use the pipeline.
fn run(
    config: BoardConfig,
    ops: &[Op],
    reference: bool,
    threads: usize,
    isa: VectorIsa,
) -> Outcome {
    let mut board = Board::new(config);
    board.set_generic_path(reference);
    board.set_threads(threads);
    board.set_vector_isa(isa);
    init(&mut board);
    let mut reads: u64 = 0xcbf2_9ce4_8422_2325;
    let mut totals = [0u64; 2];
    let mut last = counters(&board.stats());
    for &op in ops {
        match op {
            Op::Write(a, v) => {
                let is_fbz_mode = a & 0xff_ffff < LFB_BASE && a & 0x3fc == addr::FBZ_MODE;
                board.write32(a, if is_fbz_mode { v | FBZ_CLIP } else { v });
            }
            Op::Read(a) => {
                let v = board.read32(a);
                for byte in v.to_le_bytes() {
                    reads = (reads ^ u64::from(byte)).wrapping_mul(0x100_0000_01b3);
                }
            }
            Op::Pci(o, v) => board.pci_write(o, v),
        }
        let now = counters(&board.stats());
        for i in 0..2 {
            // A counter below its last value was cleared, then counted up from zero.
            totals[i] += now[i] - if now[i] >= last[i] { last[i] } else { 0 };
        }
        last = now;
    }
    Outcome {
        front: board.dump_buffer(BufferKind::Front),
        back: board.dump_buffer(BufferKind::Back),
        aux: board.dump_buffer(BufferKind::Aux),
        stats: board.stats(),
        diagnostics: board.diagnostics().clone(),
        reads,
        totals,
    }
}

/// The first difference between two outcomes, in words.
fn describe(a: &Outcome, b: &Outcome) -> String {
    if a.stats != b.stats {
        return format!("counters: {:?} vs {:?}", a.stats, b.stats);
    }
    if a.diagnostics != b.diagnostics {
        return format!("diagnostics: {:?} vs {:?}", a.diagnostics, b.diagnostics);
    }
    if a.reads != b.reads {
        return "read values differ".to_owned();
    }
    for (name, x, y) in [
        ("front", &a.front, &b.front),
        ("back", &a.back, &b.back),
        ("aux", &a.aux, &b.aux),
    ] {
        if x.len() != y.len() {
            return format!("{name}: sizes {} vs {}", x.len(), y.len());
        }
        let diff = x.iter().zip(y.iter()).filter(|(p, q)| p != q).count();
        if let Some(i) = x.iter().zip(y.iter()).position(|(p, q)| p != q) {
            return format!(
                "{name}: {diff} words differ, first at index {i}: {:04x} vs {:04x}",
                x[i], y[i]
            );
        }
    }
    "no difference".to_owned()
}

/// Runs the stream of `seed` three times: fast path twice (determinism; the second time
/// on three render threads with the baseline copy of the span kernels, the first with the
/// best the CPU has), generic path once (the span kernels must not change anything).
/// Returns the outcome.
/// 25 000 steps are about 560 000 bus operations (half of them the register sweeps of
/// `read_all`); a run takes about 0.2 s in release.
fn check_seed(seed: u64, config: BoardConfig, steps: usize) -> Outcome {
    let ops = ops(seed, steps);
    let first = run(config, &ops, false, 1, VectorIsa::best());
    let again = run(config, &ops, false, 3, VectorIsa::Baseline);
    assert!(
        first == again,
        "seed {seed}: replay differs: {}",
        describe(&first, &again)
    );
    let reference = run(config, &ops, true, 1, VectorIsa::best());
    assert!(
        first == reference,
        "seed {seed}: generic path differs from fast path: {}",
        describe(&first, &reference)
    );
    first
}

/// Shows that a stream did something: triangles, fills and swaps ran and pixels were
/// drawn, so that a generator bug cannot turn the test into a no-op.
fn assert_busy(o: &Outcome) {
    assert!(o.stats.triangles > 3000, "{:?}", o.stats);
    assert!(o.stats.fastfills > 600, "{:?}", o.stats);
    assert!(o.stats.swaps > 200, "{:?}", o.stats);
    assert!(o.totals[0] > 1_000_000, "{:?}", o.totals);
    assert!(o.totals[1] > 50_000, "{:?}", o.totals);
    assert!(!o.diagnostics.is_empty());
}

#[test]
fn random_bus_default_board() {
    let o = check_seed(1, BoardConfig::default(), 25_000);
    assert_busy(&o);
}

#[test]
fn random_bus_three_tmus_2mb() {
    let config = BoardConfig {
        fbi_mb: 2,
        tmus: 3,
        tmu_mb: 1,
    };
    let o = check_seed(2, config, 25_000);
    assert_busy(&o);
}

#[test]
fn random_bus_two_tmus_hostile_config() {
    // Out-of-range sizes are sanitised to 4 MiB / 3 TMUs / 2 MiB.
    let config = BoardConfig {
        fbi_mb: 1000,
        tmus: 2,
        tmu_mb: 3,
    };
    let o = check_seed(3, config, 25_000);
    assert_busy(&o);
}

// --- minimal reproducers of panics the random streams found -------------------------
//
// Both are integer overflows, so they panic only where overflow checks are on (debug
// builds, `cargo test` without `--release`); a release build wraps, which is the
// behaviour the surrounding code intends.

/// Subpixel correction (`fbzColorPath` bit 26) with `fdWdY` = +inf: the float converts to
/// `i64::MAX` in the 32.32 W iterator, and the correction multiplies it by the 12.4 offset
/// of vertex A from its pixel centre (8 here).
/// Found: crates/pixelfx/src/params.rs, `TriangleParams::subpixel_adjust`, the W line
/// (`dy as i64 * self.dwdy`, `dx as i64 * self.dwdx`: plain multiplies).
#[test]
fn subpixel_correction_of_an_infinite_w_gradient() {
    let mut b = Board::new(BoardConfig::default());
    b.write32(addr::FBZ_COLOR_PATH, 1 << 26);
    b.write32(addr::F_D_W_DY, 0x7f80_0000);
    b.write32(addr::TRIANGLE_CMD, 0);
    assert_eq!(b.stats().triangles, 1);
}

/// Perspective-corrected bilinear texturing with W = 0 (the power-on value): S / W is
/// NaN, which converts to `i32::MIN` (x86 `cvttsd2si`), and the bilinear fetch subtracts
/// half a texel from it.
/// Found: crates/texelfx/src/sample.rs, `Tmu::sample`, `(s >> ilod) - 0x80` (and the
/// same for t).
#[test]
fn bilinear_fetch_at_w_zero() {
    let mut b = Board::new(BoardConfig::default());
    b.write32(addr::FBZ_COLOR_PATH, 1 << 27);
    // tpersp_st, tminfilter, tmagfilter.
    b.write32(addr::TEXTURE_MODE, 0x7);
    b.write32(addr::VERTEX_BX, 16 << 4);
    b.write32(addr::VERTEX_CY, 16 << 4);
    b.write32(addr::TRIANGLE_CMD, 0);
    assert!(b.stats().pixels_in > 0);
}

// --- iterator overflow -------------------------------------------------------------

/// `fbzMode` for the edge programs: clip, RGB and aux writes, back buffer, no dithering,
/// no depth test (so the aux buffer receives every pixel's depth value).
const EDGE_FBZ: u32 = 0x4601;
/// `fbzMode` bit 3: the depth value is the floating-point form of W.
const FBZ_WBUFFER: u32 = 1 << 3;

/// Draws the triangle (0, 0), (`width`, 0), (0, 8) (whole pixels) with `fbzMode` = `fbz`
/// and the iterated colour straight through the colour path. `params` are
/// `(start register, start, d/dX)` in the fixed-point map; every d/dY is zero. Vertex A
/// is (0, 0) and there is no subpixel correction, so pixel `x` of row 0 sees exactly
/// `start + x * d/dX` (spec 5.15). Row 0 covers `0..width * 15 / 16`, clipped to 640.
fn edge_program(reference: bool, fbz: u32, width: u32, params: &[(u32, u32, u32)]) -> Board {
    let mut b = Board::new(BoardConfig::default());
    b.set_generic_path(reference);
    init(&mut b);
    b.write32(addr::FBZ_MODE, fbz);
    b.write32(addr::FBZ_COLOR_PATH, 0);
    for &(start, value, dx) in params {
        // d/dX sits 0x20 above its start register, d/dY 0x40 (spec 5, register table).
        b.write32(start, value);
        b.write32(start + 0x20, dx);
        b.write32(start + 0x40, 0);
    }
    for (reg, v) in [
        (addr::VERTEX_AX, 0),
        (addr::VERTEX_AY, 0),
        (addr::VERTEX_BX, width << 4),
        (addr::VERTEX_BY, 0),
        (addr::VERTEX_CX, 0),
        (addr::VERTEX_CY, 8 << 4),
        (addr::TRIANGLE_CMD, 0),
    ] {
        b.write32(reg, v);
    }
    b
}

/// Runs `edge_program` on both pixel paths, checks that they agree on every buffer and
/// counter, and returns row 0 of the back buffer and of the aux buffer.
fn edge_row(fbz: u32, width: u32, params: &[(u32, u32, u32)]) -> (Vec<u16>, Vec<u16>) {
    let fast = edge_program(false, fbz, width, params);
    let reference = edge_program(true, fbz, width, params);
    for kind in [BufferKind::Front, BufferKind::Back, BufferKind::Aux] {
        assert!(
            fast.dump_buffer(kind) == reference.dump_buffer(kind),
            "{kind:?} differs between the paths"
        );
    }
    assert_eq!(fast.stats(), reference.stats());
    let row = |kind| fast.dump_buffer(kind)[..640].to_vec();
    (row(BufferKind::Back), row(BufferKind::Aux))
}

/// RGB565 with the channels truncated (dithering off, spec 5.19 bit 8).
const fn rgb565(r: u32, g: u32, b: u32) -> u16 {
    ((r >> 3) << 11 | (g >> 2) << 5 | (b >> 3)) as u16
}

/// Colour and Z iterators stepping past the edges of their formats. The SST-1 has no
/// clamp: the 12-bit integer part of a colour wraps, except that 0xfff (-1) reads 0 and
/// 0x100 (256) reads 255; Z's 20-bit integer part likewise, 0xfffff reading 0 and
/// 0x10000 reading 0xffff (crates/pixelfx/src/iter.rs; MAME and DOSBox Staging agree).
#[test]
fn colour_and_z_iterators_wrap_with_the_pseudo_clamp() {
    let (rgb, aux) = edge_row(
        EDGE_FBZ,
        64,
        &[
            // R: 240.0 + 8.0 x: 0xf0, 0xf8, 0x100 (reads 255), 0x108, 0x110, 0x118.
            (addr::START_R, 0x0f_0000, 0x00_8000),
            // G: 2.0 - 1.0 x: 2, 1, 0, 0xfff (reads 0), 0xffe, 0xffd.
            (addr::START_G, 0x00_2000, 0xff_f000),
            // B: 2032.0 + 8.0 x: 0x7f0, 0x7f8, then past the largest positive 24-bit
            // 12.12 value: 0x800, 0x808, 0x810, 0x818.
            (addr::START_B, 0x7f_0000, 0x00_8000),
            // Z (20.12): 65520.0 + 8.0 x: 0xfff0, 0xfff8, 0x10000 (reads 0xffff),
            // 0x10008, 0x10010, 0x10018.
            (addr::START_Z, 0x0fff_0000, 0x0000_8000),
        ],
    );
    // Each channel keeps the low 8 bits of its integer part, but for the two specials.
    let r = [0xf0, 0xf8, 0xff, 0x08, 0x10, 0x18];
    let g = [2, 1, 0, 0, 0xfe, 0xfd];
    let b = [0xf0, 0xf8, 0x00, 0x08, 0x10, 0x18];
    let want: Vec<u16> = (0..6).map(|x| rgb565(r[x], g[x], b[x])).collect();
    assert_eq!(rgb[..6], want);
    // Spelled out for the two specials: x = 2 is red 255, x = 3 is green 0.
    assert_eq!(rgb[2] >> 11, 0x1f);
    assert_eq!((rgb[3] >> 5) & 0x3f, 0);
    assert_eq!(aux[..6], [0xfff0, 0xfff8, 0xffff, 0x0008, 0x0010, 0x0018]);
}

/// The largest 12.12 gradient (0x7fffff = 2048 - 1/4096 per pixel) over a 640-pixel row:
/// `x * d/dX` wraps the 32-bit iterator many times. Bits 23:12 of `x * (2^23 - 1)` are
/// 0xfff for even x > 0 (reads 0) and 0x7ff for odd x (reads 0xff), so red alternates
/// 0, 255 across the whole row, including where the 32-bit sum has wrapped (x >= 256).
#[test]
fn huge_colour_gradient_alternates_across_the_row() {
    let (rgb, _) = edge_row(EDGE_FBZ, 1024, &[(addr::START_R, 0, 0x7f_ffff)]);
    for (x, &p) in rgb.iter().enumerate() {
        let want = if x % 2 == 1 { rgb565(255, 0, 0) } else { 0 };
        assert_eq!(p, want, "x = {x}");
    }
}

/// W-buffering (the aux buffer gets the 16-bit float form of W) while W steps from 1.0
/// through zero to negative values (2.30: start 1.0, d/dX -0.25).
///
/// * 1.0: an integer bit is set: 0 (the nearest depth).
/// * 0.75, 0.5, 0.25: exponent = leading zeros of the 32 fraction bits, mantissa = the
///   12 bits after the leading one, inverted, plus one: 0x0800, 0x1000, 0x2000.
/// * 0: no bit in 31:16: 0xffff (the farthest depth).
/// * -0.25, -0.5: negative W has its high bits set, as 1.0 does: 0.
///
/// Source: spec 5.19 W-buffer diagram; the edge cases as DOSBox Staging (the default
/// `WFloatEdges`, which MAME matches for these values).
#[test]
fn w_through_zero_and_negative() {
    let (_, aux) = edge_row(
        EDGE_FBZ | FBZ_WBUFFER,
        64,
        &[(addr::START_W, 0x4000_0000, 0xf000_0000)],
    );
    assert_eq!(aux[..7], [0, 0x0800, 0x1000, 0x2000, 0xffff, 0, 0]);
}

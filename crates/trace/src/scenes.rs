//! Generated scenes: seeded, deterministic traces in the text form of docs/traces.md, for
//! benchmarks (`voodoo bench`) and for the proof that the fast path and the reference path
//! agree on drawing states no recorded trace uses (`crates/board/tests/random_states.rs`).
//!
//! * [`small_triangles`]: N triangles of about 10 pixels each, Gouraud-shaded, or
//!   textured (bilinear, perspective-correct, mipmapped RGB565 modulated by the iterated
//!   colour).
//! * [`stability`]: families of textured scenes that sweep one number towards where
//!   arithmetic breaks (thin, huge, extreme W, depth and gradient limits, LOD extremes,
//!   long iterator runs), one dump per step.
//! * [`random_states`]: triangles of random size, each group in a random drawing state:
//!   every bit of `fbzColorPath`, `alphaMode`, `fogMode` and `fbzMode` the FBI stores
//!   (`sst1_regs::map::mask_of`) drawn at random, and per TMU every bit of
//!   `textureMode` and `tLOD` the TMU uses, `tDetail` and the base addresses, with random texture contents downloaded through
//!   the texture aperture for the layout in force, random NCC tables and palette, fog
//!   table, chroma key, `zaColor`, stipple, constant colours and clip rectangle, over
//!   colour and aux buffers filled with random rectangles and noise; a fifth of the
//!   triangles through the float registers, and now and then LFB writes through the
//!   pixel pipeline in the state in force. Reserved values
//!   are kept: the emulator must handle them.
//!
//! A scene is a function of its parameters alone (an xorshift generator seeded from
//! them), so a seed names a scene for good. The register sequences follow the
//! conformance traces (`traces/conformance/traces/*.trace.gz`): PCI `initEnable`, Glide's
//! 640x480 mode set (`sst1_board::presets::GLIDE_640X480`), Glide's default state, then
//! texture downloads (spec section 8: bits 22:21 the TMU, 20:17 the LOD, 16:9 T, S below)
//! and triangles through the fixed-point registers (vertices sorted by Y, start values at
//! vertex A, gradients from the plane equation, `triangleCMD` bit 31 the area's sign).

pub mod stability;

use std::fmt::Write as _;

use sst1_board::presets::GLIDE_640X480;
use sst1_regs::{addr, map};

/// xorshift64* (Vigna): small, fast, and enough to pick scene contents. Public so that
/// tests draw their own choices the same way.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator whose sequence depends on `seed` only (small seeds differ at once).
    pub fn new(seed: u64) -> Self {
        Self(seed.wrapping_add(1).wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// 32 random bits.
    pub fn u32(&mut self) -> u32 {
        (self.next_u64() >> 32) as u32
    }

    /// Uniform in `0..n` (`n > 0`; the modulo bias does not matter here).
    pub fn below(&mut self, n: u32) -> u32 {
        self.u32() % n.max(1)
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// True with probability `percent` / 100.
    pub fn chance(&mut self, percent: u32) -> bool {
        self.below(100) < percent
    }
}

/// Start of the linear frame buffer in the aperture (spec section 4).
const LFB_BASE: u32 = 0x40_0000;
/// Start of texture memory in the aperture (spec section 4).
const TEXTURE_BASE: u32 = 0x80_0000;
/// `initEnable` in PCI configuration space (spec section 6).
const PCI_INIT_ENABLE: u32 = 0x40;
/// Chip-select field of a register address (bits 13:10, spec section 5): the FBI.
const CHIP_FBI: u32 = 0x400;
/// Chip-select field: TMU `n` is `CHIP_TMU0 << n`.
const CHIP_TMU0: u32 = 0x800;
/// Screen size of the mode the scenes set.
const WIDTH: f64 = 640.0;
const HEIGHT: f64 = 480.0;

/// A trace being written as text.
struct Scene {
    text: String,
}

impl Scene {
    /// The header every scene starts with: a comment naming it, the board, PCI
    /// `initEnable`, Glide's 640x480 mode set and Glide's default state (as the
    /// conformance traces write them).
    fn new(title: &str, tmus: u32) -> Self {
        let mut s = Self {
            text: String::new(),
        };
        s.comment(title);
        s.line("config fbi_mb 4");
        let _ = writeln!(s.text, "config tmus {tmus}");
        s.line("config tmu_mb 4");
        s.comment("PCI config space: initEnable (0x40) = enable fbiInit writes + PCI FIFO");
        let _ = writeln!(s.text, "pci {PCI_INIT_ENABLE:#04x} 0x00000003");
        s.comment("Glide-style SST-1 init for 640x480, 2 colour buffers + 1 aux buffer, 4 MB FBI");
        for &(a, v) in GLIDE_640X480 {
            s.w(a, v);
        }
        s.comment("Glide grSstWinOpen-like default state");
        for (a, v) in [
            (addr::FBZ_COLOR_PATH, 0),
            (addr::FOG_MODE, 0),
            (addr::ALPHA_MODE, 0),
            (addr::FBZ_MODE, 0x0000_4601),
            (addr::LFB_MODE, 0),
            (addr::STIPPLE, 0xffff_ffff),
            (addr::TEXTURE_MODE, 0x0824_1a00),
            (addr::T_LOD, 0),
            (addr::T_DETAIL, 0),
            (addr::NOP_CMD, 0),
            (addr::COLOR1, 0),
            (addr::ZA_COLOR, 0x0000_ffff),
            (addr::FBZ_MODE, 0x0000_4600),
            (addr::FASTFILL_CMD, 0),
        ] {
            s.w(a, v);
        }
        s
    }

    fn line(&mut self, line: &str) {
        self.text.push_str(line);
        self.text.push('\n');
    }

    fn comment(&mut self, text: &str) {
        let _ = writeln!(self.text, "# {text}");
    }

    /// `w ADDR VALUE`.
    fn w(&mut self, addr: u32, value: u32) {
        let _ = writeln!(self.text, "w {addr:#08x} {value:#010x}");
    }

    fn dump(&mut self, buffer: &str, file: &str) {
        let _ = writeln!(self.text, "dump {buffer} {file}");
    }

    /// One texture download for TMU `tmu`: every LOD in `lods` that the texture
    /// `texture_mode`/`t_lod` describe stores (all, or the even or odd ones with
    /// `lod_tsplit`), at most `max_rows` rows of each, one write per two 16-bit or four
    /// 8-bit texels; `word` gives the data (called with LOD, S, T and the texel size in
    /// bytes).
    fn download(
        &mut self,
        tmu: u32,
        texture_mode: u32,
        t_lod: u32,
        lods: std::ops::RangeInclusive<u32>,
        max_rows: u32,
        mut word: impl FnMut(u32, u32, u32, u32) -> u32,
    ) {
        let bytes = if (texture_mode >> 8) & 0xf >= 8 { 2 } else { 1 };
        let aspect = (t_lod >> 21) & 3;
        let s_is_wider = t_lod & (1 << 20) != 0;
        let tsplit = t_lod & (1 << 19) != 0;
        let odd = t_lod & (1 << 18) != 0;
        let seq8 = texture_mode & (1 << 31) != 0;
        let (w0, h0) = if s_is_wider {
            (256u32, 256 >> aspect)
        } else {
            (256 >> aspect, 256u32)
        };
        let base = TEXTURE_BASE | (tmu << 21);
        for lod in lods {
            if lod > 8 || (tsplit && (lod & 1 == 1) != odd) {
                continue;
            }
            let (w, h) = ((w0 >> lod).max(1), (h0 >> lod).max(1));
            let per_word = 4 / bytes;
            for t in 0..h.min(max_rows) {
                for s in (0..w).step_by(per_word as usize) {
                    let low = if bytes == 2 || !seq8 { s << 1 } else { s };
                    let a = base | (lod << 17) | (t << 9) | (low & 0x1fc);
                    let v = word(lod, s, t, bytes);
                    self.w(a, v);
                }
            }
        }
    }

    fn finish(self) -> String {
        self.text
    }
}

/// Fixed point: `v * 2^frac`, rounded, as the register's two's complement bits.
fn fixed(v: f64, frac: u32) -> u32 {
    let scaled = (v * f64::from(1u32 << frac)).round();
    // Saturating conversion: out-of-range values are what a hostile driver writes.
    (scaled.clamp(i64::MIN as f64, i64::MAX as f64) as i64) as u32
}

/// One vertex of a triangle: position in pixels and the parameters in their natural
/// units (colour 0-255, Z 0-65535, `oow` = 1/W, S/W and T/W in texels of LOD 0 per TMU).
#[derive(Clone, Copy, Debug, Default)]
struct Vertex {
    x: f64,
    y: f64,
    rgba: [f64; 4],
    z: f64,
    /// 1/W as the FBI iterates it (W buffer, fog), 2.30.
    oow: f64,
    /// Per TMU: S/W, T/W (texels), 1/W.
    st: [[f64; 3]; 3],
}

/// The gradients of a parameter over the plane through three vertices.
fn plane(v: &[Vertex; 3], p: impl Fn(&Vertex) -> f64) -> (f64, f64, f64) {
    let [a, b, c] = v;
    let area = (a.x - b.x) * (b.y - c.y) - (b.x - c.x) * (a.y - b.y);
    if area == 0.0 {
        return (p(a), 0.0, 0.0);
    }
    let (pa, pb, pc) = (p(a), p(b), p(c));
    let dx = ((pa - pb) * (b.y - c.y) - (pb - pc) * (a.y - b.y)) / area;
    let dy = ((pb - pc) * (a.x - b.x) - (pa - pb) * (b.x - c.x)) / area;
    (pa, dx, dy)
}

/// Which parameters a triangle sends.
#[derive(Clone, Copy)]
struct Sends {
    /// Z and alpha as well as RGB.
    za: bool,
    /// The FBI's W (W buffer, fog).
    w: bool,
    /// S, T, W for this many TMUs (0: none).
    tmus: u32,
    /// Through the floating-point registers and `ftriangleCMD` (spec 5.2: converted to
    /// the fixed formats on write) instead of the fixed-point ones.
    float: bool,
}

/// Writes one triangle: vertices snapped to 12.4 and sorted by Y, start values at vertex
/// A, gradients from the plane equation (the way Glide's `grDrawTriangle` does), then
/// `triangleCMD` with the area's sign in bit 31.
fn triangle(scene: &mut Scene, mut v: [Vertex; 3], sends: Sends) {
    for p in &mut v {
        p.x = (p.x * 16.0).round() / 16.0;
        p.y = (p.y * 16.0).round() / 16.0;
    }
    v.sort_by(|a, b| a.y.total_cmp(&b.y));
    let [a, b, c] = &v;
    let area = (a.x - b.x) * (b.y - c.y) - (b.x - c.x) * (a.y - b.y);
    // The float registers lie 0x80 above their fixed twins (spec 5, register table).
    let float = if sends.float { 0x80 } else { 0 };
    let value = |v: f64, frac: u32| {
        if sends.float {
            (v as f32).to_bits()
        } else {
            fixed(v, frac)
        }
    };
    for (reg, v) in [
        (addr::VERTEX_AX, a.x),
        (addr::VERTEX_AY, a.y),
        (addr::VERTEX_BX, b.x),
        (addr::VERTEX_BY, b.y),
        (addr::VERTEX_CX, c.x),
        (addr::VERTEX_CY, c.y),
    ] {
        let bits = if sends.float {
            value(v, 4)
        } else {
            fixed(v, 4) & 0xffff
        };
        scene.w(reg + float, bits);
    }
    let param =
        |scene: &mut Scene, regs: [u32; 3], chip: u32, frac: u32, p: &dyn Fn(&Vertex) -> f64| {
            let (start, dx, dy) = plane(&v, p);
            scene.w((regs[0] + float) | chip, value(start, frac));
            scene.w((regs[1] + float) | chip, value(dx, frac));
            scene.w((regs[2] + float) | chip, value(dy, frac));
        };
    let colour = [
        [addr::START_R, addr::D_R_DX, addr::D_R_DY],
        [addr::START_G, addr::D_G_DX, addr::D_G_DY],
        [addr::START_B, addr::D_B_DX, addr::D_B_DY],
        [addr::START_A, addr::D_A_DX, addr::D_A_DY],
    ];
    let channels = if sends.za { 4 } else { 3 };
    for (i, regs) in colour.iter().enumerate().take(channels) {
        param(scene, *regs, 0, 12, &|p| p.rgba[i]);
    }
    if sends.za {
        param(
            scene,
            [addr::START_Z, addr::D_Z_DX, addr::D_Z_DY],
            0,
            12,
            &|p| p.z,
        );
    }
    if sends.w {
        let chip = if sends.tmus > 0 { CHIP_FBI } else { 0 };
        param(
            scene,
            [addr::START_W, addr::D_W_DX, addr::D_W_DY],
            chip,
            30,
            &|p| p.oow,
        );
    }
    for tmu in 0..sends.tmus.min(3) as usize {
        let chip = CHIP_TMU0 << tmu;
        param(
            scene,
            [addr::START_S, addr::D_S_DX, addr::D_S_DY],
            chip,
            18,
            &|p| p.st[tmu][0],
        );
        param(
            scene,
            [addr::START_T, addr::D_T_DX, addr::D_T_DY],
            chip,
            18,
            &|p| p.st[tmu][1],
        );
        param(
            scene,
            [addr::START_W, addr::D_W_DX, addr::D_W_DY],
            chip,
            30,
            &|p| p.st[tmu][2],
        );
    }
    if sends.float {
        scene.w(addr::F_TRIANGLE_CMD, (area as f32).to_bits());
    } else {
        let sign = if area < 0.0 { 0x8000_0000 } else { 0 };
        scene.w(addr::TRIANGLE_CMD, sign);
    }
}

/// Three vertices around a random point of the screen enclosing about `area` pixels:
/// a random first edge of 3-7 pixels and a second one at 40-140 degrees to it, so that the
/// triangle is neither a sliver nor always the same shape.
fn small_triangle_at(rng: &mut Rng, area: f64) -> [Vertex; 3] {
    let cx = rng.range(8.0, WIDTH - 8.0);
    let cy = rng.range(8.0, HEIGHT - 8.0);
    let theta = rng.range(0.0, std::f64::consts::TAU);
    let r1 = rng.range(3.0, 7.0);
    let phi = rng.range(40f64.to_radians(), 140f64.to_radians());
    let r2 = 2.0 * area / (r1 * phi.sin());
    let a = (cx, cy);
    let b = (cx + r1 * theta.cos(), cy + r1 * theta.sin());
    let c = (cx + r2 * (theta + phi).cos(), cy + r2 * (theta + phi).sin());
    [a, b, c].map(|(x, y)| Vertex {
        x,
        y,
        ..Vertex::default()
    })
}

/// `count` triangles of about 10 pixels each at random places (`seed`), then a swap.
///
/// Gouraud (`textured = false`): the state of `perf_gouraud_heavy`, iterated RGB straight
/// to a 565 back buffer (`fbzColorPath` 0, `fbzMode` 0x4201: clip, RGB writes, back
/// buffer). Textured: a mipmapped 256x256 RGB565 texture (LODs 0-8), bilinear,
/// perspective-correct (`textureMode` 0x08241a07), modulated by the iterated colour as in
/// `perf_tex_heavy` (`fbzColorPath` 0x08482405), 1/W per vertex between 0.3 and 1.9 and
/// 0.5 to 3 texels per pixel.
pub fn small_triangles(seed: u64, count: u32, textured: bool) -> String {
    let mut rng = Rng::new(seed ^ if textured { 0x7e70 } else { 0x6a00 });
    let kind = if textured {
        "textured (RGB565 256x256 mipmapped, bilinear, perspective)"
    } else {
        "Gouraud"
    };
    let mut scene = Scene::new(
        &format!("small triangles: {count} {kind} triangles of about 10 pixels, seed {seed}"),
        1,
    );
    if textured {
        scene.comment("texture download: RGB565 256x256, LODs 0..8, at texBaseAddr 0x8000 tmu0");
        let texture_mode = 0x0824_1a07;
        let t_lod = 0x0010_0800; // lodmin 0, lodmax 8, S wider
        scene.w(addr::TEXTURE_MODE | CHIP_TMU0, texture_mode);
        scene.w(addr::T_LOD | CHIP_TMU0, t_lod);
        scene.w(addr::TEX_BASE_ADDR | CHIP_TMU0, 0x8000);
        // A smooth pattern (each LOD a checker over a gradient), so bilinear filtering
        // has something to blend and the file compresses.
        scene.download(0, texture_mode, t_lod, 0..=8, 256, |lod, s, t, _| {
            let texel = |s: u32| {
                let check = ((s >> 3) ^ (t >> 3)) & 1;
                let r = (s * 31 / 255) & 0x1f;
                let g = ((t * 63 / 255) ^ (lod * 7)) & 0x3f;
                let b = if check == 1 { 0x1f } else { (lod * 3) & 0x1f };
                (r << 11) | (g << 5) | b
            };
            let (s0, s1) = (s << lod, (s + 1) << lod);
            texel(s0 & 0xff) | (texel(s1 & 0xff) << 16)
        });
        scene.w(addr::T_DETAIL | CHIP_TMU0, 0);
        scene.w(addr::FBZ_COLOR_PATH, 0x0848_2405);
    } else {
        scene.w(addr::FBZ_COLOR_PATH, 0);
    }
    scene.w(addr::ALPHA_MODE, 0);
    scene.w(addr::FOG_MODE, 0);
    scene.w(addr::FBZ_MODE, 0x0000_4201);
    let sends = Sends {
        za: false,
        w: false,
        tmus: u32::from(textured),
        float: false,
    };
    for _ in 0..count {
        let mut v = small_triangle_at(&mut rng, 10.0);
        let texels_per_pixel = rng.range(0.5, 3.0);
        let (s0, t0) = (rng.range(0.0, 256.0), rng.range(0.0, 256.0));
        let (ox, oy) = (v[0].x, v[0].y);
        for p in &mut v {
            for c in &mut p.rgba[..3] {
                *c = rng.range(0.0, 255.0);
            }
            let oow = rng.range(0.3, 1.9);
            let s = s0 + (p.x - ox) * texels_per_pixel;
            let t = t0 + (p.y - oy) * texels_per_pixel;
            p.st[0] = [s * oow, t * oow, oow];
        }
        triangle(&mut scene, v, sends);
    }
    scene.w(addr::SWAPBUFFER_CMD, 0);
    scene.dump("front", "small_triangles_front.raw");
    scene.finish()
}

/// Parameters of a [`random_states`] scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RandomStates {
    /// Seed of the generator.
    pub seed: u64,
    /// TMUs on the board, 1 to 3.
    pub tmus: u32,
    /// Drawing states (each one random mode-register set with its own textures).
    pub states: u32,
    /// Triangles drawn in each state (at least one).
    pub triangles_per_state: u32,
    /// A dump of every buffer after this many states (0: only at the end).
    pub dump_every: u32,
    /// A random frame-buffer layout after Glide's mode set: `fbiInit1` tiles in X
    /// (the row pitch) and `fbiInit2` buffer offset at random, so that buffers may
    /// overlap (one buffer's colour word another's aux word) and rows wrap.
    pub layout: bool,
    /// Large triangles only (10,000 to 60,000 pixels of area, before clipping), so that
    /// the scene's time goes to the pixels of its states rather than to their set-up and
    /// texture downloads (`voodoo gen heavy-states`).
    pub large: bool,
}

impl Default for RandomStates {
    fn default() -> Self {
        Self {
            seed: 1,
            tmus: 2,
            states: 200,
            triangles_per_state: 2,
            dump_every: 50,
            layout: false,
            large: false,
        }
    }
}

impl RandomStates {
    /// A heavy-states scene: `states` random drawing states on 2 TMUs, each drawing 96
    /// large triangles, one dump at the end: kernel-bound work in states that no trace
    /// in the repository uses (`voodoo bench`'s `heavy_states`).
    pub fn heavy(seed: u64, states: u32) -> Self {
        Self {
            seed,
            tmus: 2,
            states,
            triangles_per_state: 96,
            dump_every: 0,
            layout: false,
            large: true,
        }
    }
}

/// [`random_states`] of [`RandomStates::heavy`].
pub fn heavy_states(seed: u64, states: u32) -> String {
    random_states(RandomStates::heavy(seed, states))
}

/// The register bits the FBI stores for a mode register: a random value within them.
fn random_bits(rng: &mut Rng, offset: u32) -> u32 {
    rng.u32() & map::mask_of(offset)
}

/// A random-state scene (see the module documentation).
pub fn random_states(p: RandomStates) -> String {
    let tmus = p.tmus.clamp(1, 3);
    let mut rng = Rng::new(p.seed.wrapping_mul(31).wrapping_add(u64::from(tmus)));
    let mut scene = Scene::new(
        &format!(
            "random states: seed {}, {} TMUs, {} states of {} triangles",
            p.seed, tmus, p.states, p.triangles_per_state
        ),
        tmus,
    );
    if p.layout {
        let tiles = rng.below(16);
        let offset = rng.below(512);
        let _ = writeln!(
            scene.text,
            "# frame buffer layout: {tiles} tiles in X, buffer offset {offset} pages"
        );
        scene.w(addr::FBI_INIT1, (0x0020_00a2 & !0xf0) | (tiles << 4));
        scene.w(
            addr::FBI_INIT2,
            (0x1874_b040 & !(0x1ff << 11)) | (offset << 11),
        );
    }
    palette_and_ncc(&mut scene, &mut rng, tmus, true);
    fog_table(&mut scene, &mut rng);
    for state in 0..p.states {
        if state % 8 == 0 {
            background(&mut scene, &mut rng);
        }
        let _ = writeln!(scene.text, "# state {state}");
        if rng.chance(20) {
            fog_table(&mut scene, &mut rng);
        }
        if rng.chance(15) {
            palette_and_ncc(&mut scene, &mut rng, tmus, false);
        }
        let mut tmu_modes = [(0u32, 0u32); 3];
        for (tmu, mode) in tmu_modes.iter_mut().enumerate().take(tmus as usize) {
            *mode = tmu_state(&mut scene, &mut rng, tmu as u32);
        }
        fbi_state(&mut scene, &mut rng, &tmu_modes[..tmus as usize]);
        for _ in 0..p.triangles_per_state.max(1) {
            let v = random_triangle(&mut rng, p.large);
            let sends = Sends {
                za: true,
                w: true,
                tmus,
                float: rng.chance(20),
            };
            triangle(&mut scene, v, sends);
        }
        if rng.chance(10) {
            lfb_through_pipeline(&mut scene, &mut rng);
        }
        if rng.chance(3) {
            scene.w(addr::SWAPBUFFER_CMD, 0);
        }
        if p.dump_every > 0 && (state + 1) % p.dump_every == 0 {
            for buffer in ["front", "back", "aux"] {
                scene.dump(buffer, &format!("state{}_{buffer}.raw", state + 1));
            }
        }
    }
    scene.finish()
}

/// Random NCC tables 0 and 1 and (at the start, or by chance) the whole 8-bit palette
/// for every TMU; palette entries go through table 0's I/Q words with bit 31 set (spec
/// 5.56.2).
fn palette_and_ncc(scene: &mut Scene, rng: &mut Rng, tmus: u32, all: bool) {
    for tmu in 0..tmus {
        let chip = CHIP_TMU0 << tmu;
        for word in 0..24 {
            let a = addr::NCC_TABLE0 + 4 * word;
            let value = rng.u32() & map::mask_of(a);
            scene.w(a | chip, value);
        }
        if all || rng.chance(50) {
            let entries = if all { 256 } else { rng.below(64) + 1 };
            let first = rng.below(256);
            for k in 0..entries {
                let index = (first + k) & 0xff;
                let word = 4 + (index & 1) + 2 * rng.below(4);
                let value = 0x8000_0000 | ((index >> 1) << 24) | (rng.u32() & 0x00ff_ffff);
                scene.w((addr::NCC_TABLE0 + 4 * word) | chip, value);
            }
        }
    }
}

/// A random fog table (64 entries and their deltas, every bit random).
fn fog_table(scene: &mut Scene, rng: &mut Rng) {
    let monotone = rng.chance(50);
    let mut level = 0u32;
    for word in 0..32 {
        let value = if monotone {
            // Increasing entries with their true deltas, as Glide writes them.
            let e0 = level.min(255);
            let e1 = (level + rng.below(12)).min(255);
            let e2 = (e1 + rng.below(12)).min(255);
            level = e2;
            let d0 = e1 - e0;
            let d1 = e2 - e1;
            (e1 << 24) | (d1 << 16) | (e0 << 8) | d0
        } else {
            rng.u32()
        };
        scene.w(addr::FOG_TABLE + 4 * word, value);
    }
}

/// Random contents for the colour and aux buffers: fast fills of random rectangles in
/// random colours and depths, and blocks of noise written through the LFB (565 colour or
/// 16-bit depth, pipeline off) into the front or back buffer.
fn background(scene: &mut Scene, rng: &mut Rng) {
    scene.comment("background: random fills and LFB noise");
    for _ in 0..1 + rng.below(3) {
        let (x0, x1) = sorted(rng.below(640), rng.below(641));
        let (y0, y1) = sorted(rng.below(480), rng.below(481));
        scene.w(addr::CLIP_LEFT_RIGHT, (x0 << 16) | x1);
        scene.w(addr::CLIP_LOW_Y_HIGH_Y, (y0 << 16) | y1);
        scene.w(addr::COLOR1, rng.u32());
        scene.w(addr::ZA_COLOR, rng.u32());
        // Clip on, RGB and aux writes at random, dither at random, front or back buffer.
        let fbz = 1
            | (rng.below(2) << 8)
            | (rng.below(2) << 9)
            | (rng.below(2) << 10)
            | (rng.below(2) << 11)
            | (rng.below(2) << 14);
        scene.w(addr::FBZ_MODE, fbz);
        scene.w(addr::FASTFILL_CMD, 0);
    }
    for _ in 0..rng.below(3) {
        let depth = rng.chance(50);
        // Format 0 (RGB565) or 15 (16-bit depth); front or back buffer.
        let format = if depth { 15 } else { 0 };
        let buffer = rng.below(2);
        scene.w(addr::LFB_MODE, format | (buffer << 4));
        let (w, h) = (2 * (1 + rng.below(32)), 1 + rng.below(32));
        let (x0, y0) = (2 * rng.below(320 - w / 2), rng.below(480 - h));
        for y in y0..y0 + h {
            for x in (x0..x0 + w).step_by(2) {
                scene.w(LFB_BASE | (y << 11) | (x << 1), rng.u32());
            }
        }
    }
    scene.w(addr::LFB_MODE, 0);
}

/// A few rows of LFB writes through the pixel pipeline in the state in force (spec
/// 5.20: `lfbMode` bit 8), every other `lfbMode` bit at random (format, buffer, lanes,
/// swaps, Y origin, W select) but the read bits, random data.
fn lfb_through_pipeline(scene: &mut Scene, rng: &mut Rng) {
    let mode = (random_bits(rng, addr::LFB_MODE) | (1 << 8)) & !(3 << 6);
    let _ = writeln!(
        scene.text,
        "# LFB writes through the pipeline, lfbMode {mode:#07x}"
    );
    scene.w(addr::LFB_MODE, mode);
    let (w, h) = (1 + rng.below(32), 1 + rng.below(8));
    // 32-bit formats carry one pixel a write, 16-bit ones two (spec 5.20.1).
    let wide = matches!(mode & 0xf, 4 | 5 | 12..=14);
    let x0 = rng.below(640 - w) & if wide { !0 } else { !1 };
    let y0 = rng.below(480 - h);
    for y in y0..y0 + h {
        let step = if wide { 1 } else { 2 };
        for x in (x0..x0 + w).step_by(step) {
            let offset = if wide {
                (y << 12) | (x << 2)
            } else {
                (y << 11) | (x << 1)
            };
            scene.w(LFB_BASE | offset, rng.u32());
        }
    }
    scene.w(addr::LFB_MODE, 0);
}

fn sorted(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// One TMU's random state: `textureMode`, `tLOD`, `tDetail`, the four base addresses,
/// and texture data for the layout they describe. Returns (`textureMode`, `tLOD`).
fn tmu_state(scene: &mut Scene, rng: &mut Rng, tmu: u32) -> (u32, u32) {
    let chip = CHIP_TMU0 << tmu;
    // The TMU keeps every bit written to these two, and uses some outside the register
    // table's ranges (spec 5.50 bit 31 `seq_8_downld`; 5.51 bits 27:24 `tmultibaseaddr`,
    // the download swaps, `tdirect_write`): all of those are drawn too.
    let texture_mode = rng.u32();
    let t_lod = rng.u32() & 0x0fff_ffff;
    let _ = writeln!(
        scene.text,
        "# tmu{tmu}: textureMode {texture_mode:#010x} (format {}), tLOD {t_lod:#08x}",
        (texture_mode >> 8) & 0xf
    );
    scene.w(addr::TEXTURE_MODE | chip, texture_mode);
    scene.w(addr::T_LOD | chip, t_lod);
    scene.w(addr::T_DETAIL | chip, random_bits(rng, addr::T_DETAIL));
    for reg in [
        addr::TEX_BASE_ADDR,
        addr::TEX_BASE_ADDR_1,
        addr::TEX_BASE_ADDR_2,
        addr::TEX_BASE_ADDR_3_8,
    ] {
        // Mostly in the first MiB (so textures of different states overlap and leave
        // each other's texels behind), sometimes anywhere in the 19 bits.
        let base = if rng.chance(80) {
            rng.below(0x2_0000)
        } else {
            random_bits(rng, reg)
        };
        scene.w(reg | chip, base);
    }
    if rng.chance(85) {
        let lodmin = (t_lod & 0x3f) >> 2;
        let lodmax = ((t_lod >> 6) & 0x3f) >> 2;
        let (lo, hi) = sorted(lodmin, lodmax);
        let smooth = rng.chance(40);
        let seed = rng.u32();
        let mut noise = Rng::new(u64::from(seed));
        // Large LODs get a band of rows (the rest holds earlier states' texels).
        let max_rows = 8 + rng.below(24);
        scene.download(
            tmu,
            texture_mode,
            t_lod,
            lo..=hi.min(8),
            max_rows,
            |lod, s, t, bytes| {
                if smooth {
                    // Slowly varying texels: bilinear blends of near values.
                    let v = (s * 3 + t * 5 + lod * 40 + seed) & 0xff;
                    if bytes == 2 {
                        let texel = (v << 8) | (v ^ 0x5a);
                        texel | (texel.wrapping_add(0x0101) << 16)
                    } else {
                        u32::from_le_bytes([v as u8, (v + 1) as u8, (v + 2) as u8, (v + 3) as u8])
                    }
                } else {
                    noise.u32()
                }
            },
        );
    }
    (texture_mode, t_lod)
}

/// The FBI's random state: every stored bit of `fbzColorPath`, `fogMode`, `alphaMode`
/// and `fbzMode`, the constant colours, `zaColor`, chroma key, stipple, fog colour and the
/// clip rectangle. The chroma key often equals a constant colour or 0 so that chroma
/// tests fail for some pixels.
fn fbi_state(scene: &mut Scene, rng: &mut Rng, _tmus: &[(u32, u32)]) {
    let mut color_path = random_bits(rng, addr::FBZ_COLOR_PATH);
    // Texture on for most states, so the TMUs are reached often.
    if rng.chance(60) {
        color_path |= 1 << 27;
    }
    let fog_mode = random_bits(rng, addr::FOG_MODE);
    let alpha_mode = random_bits(rng, addr::ALPHA_MODE);
    let fbz_mode = random_bits(rng, addr::FBZ_MODE);
    let color0 = rng.u32();
    let color1 = rng.u32();
    let chroma = match rng.below(4) {
        0 => color0,
        1 => color1,
        2 => 0,
        _ => rng.u32(),
    } & map::mask_of(addr::CHROMA_KEY);
    let clip = if rng.chance(70) {
        let (x0, x1) = sorted(rng.below(640), rng.below(641));
        let (y0, y1) = sorted(rng.below(480), rng.below(481));
        [(x0 << 16) | x1, (y0 << 16) | y1]
    } else if rng.chance(50) {
        [640, 480]
    } else {
        [rng.u32(), rng.u32()]
    };
    let _ = writeln!(
        scene.text,
        "# fbi: fbzColorPath {color_path:#010x} fogMode {fog_mode:#04x} alphaMode {alpha_mode:#010x} fbzMode {fbz_mode:#08x}"
    );
    for (a, v) in [
        (addr::FBZ_COLOR_PATH, color_path),
        (addr::FOG_MODE, fog_mode),
        (addr::ALPHA_MODE, alpha_mode),
        (addr::FBZ_MODE, fbz_mode),
        (addr::CLIP_LEFT_RIGHT, clip[0]),
        (addr::CLIP_LOW_Y_HIGH_Y, clip[1]),
        (addr::FOG_COLOR, rng.u32() & map::mask_of(addr::FOG_COLOR)),
        (addr::ZA_COLOR, rng.u32()),
        (addr::CHROMA_KEY, chroma),
        (
            addr::STIPPLE,
            if rng.chance(30) {
                0xffff_ffff
            } else {
                rng.u32()
            },
        ),
        (addr::COLOR0, color0),
        (addr::COLOR1, color1),
    ] {
        scene.w(a, v);
    }
}

/// A triangle of random size (from slivers of under a pixel to most of the screen, area
/// log-uniform), partly off-screen now and then, with random parameters: colours mostly
/// in 0-255 and sometimes beyond (the iterators clamp), Z over the 16-bit range and
/// sometimes beyond, 1/W between 0.02 and 1.99, S/W and T/W per TMU over a few texture
/// widths.
fn random_triangle(rng: &mut Rng, large: bool) -> [Vertex; 3] {
    let smallest = if large { 20_000f64 } else { 1.0 };
    let area = (rng.range(smallest.ln(), (120_000f64).ln())).exp() * 0.5;
    let cx = rng.range(-40.0, WIDTH + 40.0);
    let cy = rng.range(-40.0, HEIGHT + 40.0);
    let theta = rng.range(0.0, std::f64::consts::TAU);
    let elong = rng.range(0.0, 3.0f64).exp(); // 1 to 20: squat to thin
    let r1 = (2.0 * area * elong).sqrt();
    let phi = rng.range(10f64.to_radians(), 170f64.to_radians());
    let r2 = 2.0 * area / (r1 * phi.sin());
    let pts = [
        (cx, cy),
        (cx + r1 * theta.cos(), cy + r1 * theta.sin()),
        (cx + r2 * (theta + phi).cos(), cy + r2 * (theta + phi).sin()),
    ];
    let wide = rng.chance(10);
    let persp = rng.chance(70);
    let mut st0 = [[0.0f64; 2]; 3];
    let mut scale = [1.0f64; 3];
    for tmu in 0..3 {
        st0[tmu] = [rng.range(-300.0, 600.0), rng.range(-300.0, 600.0)];
        scale[tmu] = (rng.range(-3.0, 3.0f64)).exp2();
    }
    pts.map(|(x, y)| {
        let mut v = Vertex {
            x,
            y,
            ..Vertex::default()
        };
        for c in &mut v.rgba {
            *c = if wide {
                rng.range(-64.0, 320.0)
            } else {
                rng.range(0.0, 256.0)
            };
        }
        v.z = if wide {
            rng.range(-8192.0, 73728.0)
        } else {
            rng.range(0.0, 65536.0)
        };
        v.oow = if persp { rng.range(0.02, 1.99) } else { 1.0 };
        for tmu in 0..3 {
            let oow = if persp { rng.range(0.02, 1.99) } else { 1.0 };
            let s = st0[tmu][0] + (x - cx) * scale[tmu];
            let t = st0[tmu][1] + (y - cy) * scale[tmu] * rng.range(0.5, 2.0);
            v.st[tmu] = [s * oow, t * oow, oow];
        }
        v
    })
}

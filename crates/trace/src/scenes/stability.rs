//! Stability scenes: families of textured scenes that push one number towards where
//! arithmetic breaks, from easy to hard, one parameter swept (docs/methods.md).
//!
//! Each family is one trace (`traces/stability/NAME.trace.gz`, written by `voodoo gen
//! stability --family NAME`). Every step of the sweep is drawn over a cleared back
//! buffer, swapped and dumped as `NAME_KK_front.raw` (`KK` the step, 00 the easiest;
//! the depth families dump the aux buffer too), so that a replay judges each step on
//! its own. All steps draw in the state of `perf_tex_heavy`: a 64x64 RGB565 mipmapped
//! texture (levels 2-8 of the SST-1's 256x256 LOD 0, `lodmin` 2), bilinear, perspective
//! corrected, modulated by the iterated colour, alpha blended, dithered, W- or Z-buffered
//! (module docs of [`crate::scenes`] for the register sequences).
//!
//! The families and what runs out:
//!
//! | family | swept | limit pushed |
//! |---|---|---|
//! | `thin` | triangle width, 2 to 1/16 px, 1000 px long | sub-pixel coverage, 12.4 vertices |
//! | `large` | half-size 256 to 2047.9 px around (0, 0) | 12.4 range (+-2048), triangles far larger than the screen |
//! | `w_near_zero` | 1/W scale, 1 to 2^-20 | 2.30 W and 14.18 S/W, T/W precision |
//! | `w_near_two` | 1/W, 1 to 1.9999 | the largest 2.30 holds |
//! | `persp` | 1/W ratio across a wall, left to right, 1 to 2^16 | steep perspective along spans: LOD and divide per pixel |
//! | `depth_z` | Z distance from the ends of 20.12, 256 to 1/4096 | Z-buffer resolution at 0 and 65535 |
//! | `depth_w` | 1/W of the W buffer, 1.9 to 2^-29 | W-float depth exponent range |
//! | `gradients` | colour and S/T slope, 1 to 2047 per pixel | 12.12 colour and 14.18 S/T ranges |
//! | `lod` | texels per pixel, 1/64 to 4096 | magnification past the largest level, minification past LOD 8 |
//! | `long_runs` | distance of vertex A off screen, 0 to 2000 px | iterators run over 1000+ pixels |

use super::{triangle, Scene, Sends, Vertex, CHIP_TMU0};
use sst1_regs::addr;

/// One family of stability scenes.
#[derive(Clone, Copy, Debug)]
pub struct Family {
    /// File stem and `voodoo gen stability --family` name.
    pub name: &'static str,
    /// What the sweep changes, in words (chart axis).
    pub parameter: &'static str,
    /// The swept values, easiest first: step `k` of the trace is `values[k]`.
    pub values: &'static [f64],
    /// Z-buffered instead of W-buffered (and the aux buffer dumped too).
    z_buffer: bool,
    /// A clip rectangle `(left, right, low y, high y)` instead of the whole screen.
    clip: Option<(u32, u32, u32, u32)>,
    /// The triangles of one step.
    triangles: fn(f64) -> Vec<[Vertex; 3]>,
}

/// Every family, in the order of the module's table.
pub const FAMILIES: [Family; 10] = [
    Family {
        name: "thin",
        parameter: "triangle width (pixels)",
        values: &[2.0, 1.0, 0.5, 0.25, 0.125, 0.0625],
        z_buffer: false,
        clip: None,
        triangles: thin,
    },
    Family {
        name: "large",
        parameter: "half-size (pixels) around (0, 0)",
        values: &[256.0, 512.0, 1024.0, 1536.0, 2000.0, 2047.9375],
        z_buffer: false,
        clip: Some((0, 320, 0, 240)),
        triangles: large,
    },
    Family {
        name: "w_near_zero",
        parameter: "1/W scale",
        values: &[
            1.0,
            0.0625,
            0.003_906_25,
            2.441_406_25e-4,
            1.525_878_906_25e-5,
            9.536_743_164_062_5e-7,
        ],
        z_buffer: false,
        clip: None,
        triangles: w_near_zero,
    },
    Family {
        name: "w_near_two",
        parameter: "largest 1/W",
        values: &[1.0, 1.5, 1.9, 1.99, 1.999, 1.9999],
        z_buffer: false,
        clip: None,
        triangles: w_near_two,
    },
    Family {
        name: "persp",
        parameter: "1/W ratio across the triangle",
        values: &[1.0, 4.0, 16.0, 256.0, 4096.0, 65536.0],
        z_buffer: false,
        clip: None,
        triangles: persp,
    },
    Family {
        name: "depth_z",
        parameter: "Z distance from 0 and 65535",
        values: &[256.0, 16.0, 1.0, 0.0625, 0.003_906_25, 2.441_406_25e-4],
        z_buffer: true,
        clip: None,
        triangles: depth_z,
    },
    Family {
        name: "depth_w",
        parameter: "1/W of the W buffer",
        values: &[
            1.9,
            1.0,
            0.003_906_25,
            1.525_878_906_25e-5,
            5.960_464_477_539_063e-8,
            1.862_645_149_230_957e-9,
        ],
        z_buffer: false,
        clip: None,
        triangles: depth_w,
    },
    Family {
        name: "gradients",
        parameter: "colour and S/T slope per pixel",
        values: &[1.0, 16.0, 128.0, 512.0, 1024.0, 2047.0],
        z_buffer: false,
        clip: None,
        triangles: gradients,
    },
    Family {
        name: "lod",
        parameter: "texels per pixel",
        values: &[0.015_625, 0.125, 1.0, 8.0, 64.0, 512.0, 4096.0],
        z_buffer: false,
        clip: None,
        triangles: lod,
    },
    Family {
        name: "long_runs",
        parameter: "vertex A off screen (pixels)",
        values: &[0.0, 256.0, 512.0, 1024.0, 1536.0, 2000.0],
        z_buffer: false,
        clip: None,
        triangles: long_runs,
    },
];

/// The family named `name`.
pub fn family(name: &str) -> Option<&'static Family> {
    FAMILIES.iter().find(|f| f.name == name)
}

/// The dump of step `step` of `family`'s front buffer (as the trace names it).
pub fn front_dump(family: &str, step: usize) -> String {
    format!("{family}_{step:02}_front.raw")
}

/// The texture: levels 2-8 (64x64 down to 1x1), RGB565, bilinear, perspective.
const TEXTURE_MODE: u32 = 0x0824_1a07;
/// `lodmin` 2.0, `lodmax` 8.0, S wider (`tLOD`).
const T_LOD: u32 = 0x0010_0808;
/// Blend (src alpha, 1 - src alpha) as `perf_tex_heavy`.
const ALPHA_MODE: u32 = 0x0000_5110;
/// Clip, W buffer, depth less, dither, RGB and aux writes, back buffer (`perf_tex_heavy`).
const FBZ_MODE_W: u32 = 0x0000_4739;
/// The same with a Z buffer.
const FBZ_MODE_Z: u32 = 0x0000_4731;
/// RGB and aux writes to the back buffer, for the clear.
const FBZ_MODE_CLEAR: u32 = 0x0000_4600;

/// The trace of one family.
pub fn scene(f: &Family) -> String {
    let mut scene = Scene::new(
        &format!(
            "stability family {}: {} swept over {:?}, one dump per step",
            f.name, f.parameter, f.values
        ),
        1,
    );
    scene.comment("texture download: RGB565 64x64 (LODs 2..8), at texBaseAddr 0x8000 tmu0");
    scene.w(addr::TEXTURE_MODE | CHIP_TMU0, TEXTURE_MODE);
    scene.w(addr::T_LOD | CHIP_TMU0, T_LOD);
    scene.w(addr::TEX_BASE_ADDR | CHIP_TMU0, 0x8000);
    scene.download(0, TEXTURE_MODE, T_LOD, 2..=8, 64, |lod, s, t, _| {
        // A checker over gradients, different on every level, so that a wrong level,
        // a lost fraction or a moved coordinate changes the picture.
        let texel = |s: u32| {
            let size = 256 >> lod;
            let check = ((s * 8 / size.max(1)) ^ (t * 8 / size.max(1))) & 1;
            let r = (s * 31 / size.max(1)) & 0x1f;
            let g = ((t * 63 / size.max(1)) ^ (lod * 9)) & 0x3f;
            let b = if check == 1 { 0x1f } else { (lod * 3) & 0x1f };
            (r << 11) | (g << 5) | b
        };
        texel(s) | (texel(s + 1) << 16)
    });
    scene.w(addr::T_DETAIL | CHIP_TMU0, 0);
    scene.w(addr::FBZ_COLOR_PATH, 0x0848_2405);
    scene.w(addr::FOG_MODE, 0);
    if let Some((l, r, lo, hi)) = f.clip {
        scene.w(addr::CLIP_LEFT_RIGHT, (l << 16) | r);
        scene.w(addr::CLIP_LOW_Y_HIGH_Y, (lo << 16) | hi);
    }
    let sends = Sends {
        za: true,
        w: true,
        tmus: 1,
        float: false,
    };
    for (step, &value) in f.values.iter().enumerate() {
        scene.comment(&format!("step {step}: {} = {value}", f.parameter));
        scene.w(addr::ALPHA_MODE, 0);
        scene.w(addr::FBZ_MODE, FBZ_MODE_CLEAR);
        scene.w(addr::COLOR1, 0x0040_3020);
        scene.w(addr::ZA_COLOR, 0x0000_ffff);
        scene.w(addr::FASTFILL_CMD, 0);
        scene.w(addr::ALPHA_MODE, ALPHA_MODE);
        scene.w(
            addr::FBZ_MODE,
            if f.z_buffer { FBZ_MODE_Z } else { FBZ_MODE_W },
        );
        for v in (f.triangles)(value) {
            triangle(&mut scene, v, sends);
        }
        scene.w(addr::SWAPBUFFER_CMD, 0);
        scene.dump("front", &front_dump(f.name, step));
        if f.z_buffer {
            scene.dump("depth", &format!("{}_{step:02}_depth.raw", f.name));
        }
    }
    scene.finish()
}

/// A textured vertex: position, texture coordinates in texels of LOD 0 (256 across the
/// texture), 1/W (the TMU's and the FBI's), Z (0-65535) and a colour.
fn vtx(x: f64, y: f64, st: (f64, f64), oow: f64, z: f64, rgba: [f64; 4]) -> Vertex {
    Vertex {
        x,
        y,
        rgba,
        z,
        oow,
        st: [[st.0 * oow, st.1 * oow, oow], [0.0; 3], [0.0; 3]],
    }
}

/// Light grey, three quarters opaque.
const GREY: [f64; 4] = [230.0, 220.0, 210.0, 192.0];

/// 12 triangles 1000 px long at different slopes, `width` px wide at their widest.
fn thin(width: f64) -> Vec<[Vertex; 3]> {
    (0..12)
        .map(|i| {
            let y0 = 20.0 + 36.0 * f64::from(i);
            let (ax, ay) = (-180.0, y0);
            let (bx, by) = (820.0, y0 + 30.0 - 5.0 * f64::from(i));
            // Perpendicular offset of the third vertex at the middle of the long edge.
            let (dx, dy) = (bx - ax, by - ay);
            let len = (dx * dx + dy * dy).sqrt();
            let (cx, cy) = (
                (ax + bx) / 2.0 - dy / len * width,
                (ay + by) / 2.0 + dx / len * width,
            );
            [
                vtx(ax, ay, (0.0, 0.0), 1.0, 0.0, GREY),
                vtx(bx, by, (1000.0, 60.0), 0.25, 0.0, GREY),
                vtx(cx, cy, (500.0, 30.0 + width), 0.6, 0.0, GREY),
            ]
        })
        .collect()
}

/// One triangle with corners up to `r` px from (0, 0) (the 12.4 format ends at +-2048),
/// seen through a 320x240 clip window.
fn large(r: f64) -> Vec<[Vertex; 3]> {
    vec![[
        vtx(-r, -r, (-r * 0.5, -r * 0.5), 1.0, 0.0, GREY),
        vtx(r, -r * 0.5, (r * 0.5, -r * 0.25), 0.5, 0.0, GREY),
        vtx(-r / 3.0, r, (-r / 6.0, r * 0.5), 0.25, 0.0, GREY),
    ]]
}

/// A quad of two triangles over most of the screen: corners `(x, y)`, texture
/// coordinates and 1/W from `corner(i)` for corners 0-3 (top left, top right, bottom
/// right, bottom left).
fn quad(corner: impl Fn(usize) -> ((f64, f64), (f64, f64), f64)) -> Vec<[Vertex; 3]> {
    let v: Vec<Vertex> = (0..4)
        .map(|i| {
            let ((x, y), st, oow) = corner(i);
            vtx(x, y, st, oow, 0.0, GREY)
        })
        .collect();
    vec![[v[0], v[1], v[2]], [v[0], v[2], v[3]]]
}

/// Screen corners of [`quad`]s (a 400x300 rectangle) and their texture coordinates
/// (two repeats of the texture).
const CORNERS: [(f64, f64); 4] = [(120.0, 90.0), (520.0, 90.0), (520.0, 390.0), (120.0, 390.0)];
const CORNER_ST: [(f64, f64); 4] = [(0.0, 0.0), (512.0, 0.0), (512.0, 512.0), (0.0, 512.0)];

/// A gently tilted quad whose 1/W are all scaled by `scale`: S/W, T/W and 1/W shrink
/// towards the low bits of 14.18 and 2.30.
fn w_near_zero(scale: f64) -> Vec<[Vertex; 3]> {
    let oow = [1.0, 0.8, 0.6, 0.9];
    quad(|i| (CORNERS[i], CORNER_ST[i], oow[i] * scale))
}

/// A quad whose nearest corner has 1/W `max` (below 2.0, the end of 2.30).
fn w_near_two(max: f64) -> Vec<[Vertex; 3]> {
    let oow = [max, max * 0.75, max * 0.5, max * 0.9];
    quad(|i| (CORNERS[i], CORNER_ST[i], oow[i]))
}

/// A wall receding from 1/W 1 at the left to `1 / ratio` at the right: W changes along
/// every span, the hard case for a LOD or divide taken once per chunk.
fn persp(ratio: f64) -> Vec<[Vertex; 3]> {
    let far = 1.0 / ratio;
    let oow = [1.0, far, far, 1.0];
    let st = [(0.0, 0.0), (2048.0, 0.0), (2048.0, 2048.0), (0.0, 2048.0)];
    let corners = [(0.0, 40.0), (640.0, 40.0), (640.0, 480.0), (0.0, 480.0)];
    quad(|i| (corners[i], st[i], oow[i]))
}

/// Pairs of overlapping triangles at Z `d` from 0 and from 65535, the second of each
/// pair `d / 2` nearer: the Z buffer must resolve `d / 2` (20.12 holds 1/4096).
fn depth_z(d: f64) -> Vec<[Vertex; 3]> {
    let mut out = Vec::new();
    for (i, base) in [d, 65535.0 - d].into_iter().enumerate() {
        let x0 = 40.0 + 300.0 * i as f64;
        for (j, z) in [base, base - d / 2.0].into_iter().enumerate() {
            let o = 30.0 * j as f64;
            let colour = if j == 0 {
                GREY
            } else {
                [60.0, 200.0, 90.0, 192.0]
            };
            let tri = [
                vtx(x0 + o, 60.0 + o, (0.0, 0.0), 0.8, z, colour),
                vtx(x0 + 260.0 + o, 80.0 + o, (256.0, 0.0), 0.6, z, colour),
                vtx(x0 + 40.0 + o, 420.0 + o, (0.0, 256.0), 0.4, z, colour),
            ];
            out.push(tri);
        }
    }
    out
}

/// Pairs of overlapping triangles at 1/W `w` (the W buffer's float depth), the second
/// 1/1024 nearer.
fn depth_w(w: f64) -> Vec<[Vertex; 3]> {
    let mut out = Vec::new();
    for j in 0..2 {
        let o = 40.0 * j as f64;
        let oow = w * (1.0 + f64::from(j) / 1024.0);
        let colour = if j == 0 {
            GREY
        } else {
            [60.0, 200.0, 90.0, 192.0]
        };
        out.push([
            vtx(60.0 + o, 60.0 + o, (0.0, 0.0), oow, 0.0, colour),
            vtx(560.0 + o, 90.0 + o, (256.0, 0.0), oow, 0.0, colour),
            vtx(100.0 + o, 420.0 + o, (0.0, 256.0), oow, 0.0, colour),
        ]);
    }
    out
}

/// A 100x100 triangle whose red rises by `g` per pixel (12.12 holds up to 2048) and whose
/// S runs `4 * g` texels per pixel (14.18 holds up to 8192), affine in W.
fn gradients(g: f64) -> Vec<[Vertex; 3]> {
    let c = |x: f64| [x * g, 128.0, 255.0 - x, 192.0];
    vec![[
        vtx(270.0, 190.0, (0.0, 0.0), 1.0, 0.0, c(0.0)),
        vtx(370.0, 190.0, (400.0 * g, 0.0), 1.0, 0.0, c(100.0)),
        vtx(270.0, 290.0, (0.0, 100.0), 1.0, 0.0, c(0.0)),
    ]]
}

/// A quad mapped at `k` texels of LOD 0 per pixel in S and `k / 4` in T (anisotropic),
/// with 1/W from 1 to 1/2.
fn lod(k: f64) -> Vec<[Vertex; 3]> {
    let oow = [1.0, 0.7, 0.5, 0.8];
    quad(|i| {
        let (x, y) = CORNERS[i];
        let st = ((x - 120.0) * k, (y - 90.0) * k / 4.0);
        (CORNERS[i], st, oow[i])
    })
}

/// A thin wedge from vertex A `d` px left of the screen to the right edge: every span
/// iterates from A over `d` to `d + 640` pixels.
fn long_runs(d: f64) -> Vec<[Vertex; 3]> {
    (0..4)
        .map(|i| {
            let y = 60.0 + 110.0 * f64::from(i);
            let len = d + 640.0;
            [
                vtx(-d, y, (0.0, 0.0), 1.0, 0.0, GREY),
                vtx(640.0, y - 50.0, (len, 0.0), 0.3, 0.0, GREY),
                vtx(640.0, y + 50.0, (len, 100.0), 0.3, 0.0, GREY),
            ]
        })
        .collect()
}

//! The demo scene of `voodoo demo`: one 640x480 frame that shows what the board does,
//! drawn through this crate's Glide 3 calls on a two-TMU board.
//!
//! * A stone-tiled floor receding to the horizon: a 256x256 RGB565 texture with its
//!   full mipmap chain (256 down to 1, each level the 2x2 box average of the one above),
//!   bilinear within a level, the level chosen per pixel (`GR_MIPMAP_NEAREST`), so the
//!   tiles soften into their average colour with distance instead of shimmering.
//! * A light map on the second TMU: TMU1 holds a 64x64 map of warm pools of light at
//!   the foot of each pillar and a cyan glow under the crystal; TMU0 multiplies its
//!   floor texel by it (`GR_COMBINE_FUNCTION_SCALE_OTHER` by `GR_COMBINE_FACTOR_LOCAL`).
//! * Two rows of textured, Gouraud-lit pillars and the floor, depth-buffered on W,
//!   fading into linear table fog (`GR_FOG_WITH_TABLE_ON_W`) the colour of the horizon.
//! * An alpha-blended crystal floating between the pillars (its far faces drawn first,
//!   then its near ones, without writing depth), the pillars and floor showing through,
//!   and behind it two panes of tinted glass between pillars, drawn before it.
//! * A sky gradient behind, unfogged, with stars (`grDrawPoint`); the whole frame
//!   16-bit with 4x4 dithering.
//!
//! Where the Glide facts come from (Glide 3.0 Programming Guide, shared/seeds/001):
//! texture coordinates are s/w and t/w with 0..256 one repeat of the texture across
//! its longer side (the vertex-parameter table, GR_PARAM_STn; chapter 9), and the
//! hardware takes -2^16..2^16-1 (glossary, "texture coordinates"): the floor's reach
//! at most 5760. The upstream TMU1's texel is TMU0's `other`, and `SCALE_OTHER` by
//! `LOCAL` multiplies the two (chapter 9, Example 9.2, a spotlight map times a source
//! texture; here the light map is upstream).
//!
//! [`draw`] draws it on an open 640x480 context; the caller swaps. Everything is
//! computed from fixed numbers with plain arithmetic (no libm calls), so the frame is
//! the same on every run and host.

use crate::consts::*;
use crate::{Glide, TexInfo};

/// Screen size the scene is laid out for.
pub const WIDTH: u32 = 640;
/// Screen size the scene is laid out for.
pub const HEIGHT: u32 = 480;
/// TMUs the scene needs: the light map is on the second.
pub const TMUS: u32 = 2;

/// What the picture shows, in one line per feature (for `voodoo demo` to print).
pub const DESCRIPTION: &[&str] = &[
    "a stone floor with a 256x256 mipmapped texture (9 levels, bilinear) receding to the horizon",
    "a light map on the second TMU modulating the floor texture (warm pools, a cyan glow)",
    "textured Gouraud-lit pillars, depth-buffered on W, fading into linear table fog",
    "an alpha-blended crystal floating between the pillars, and two panes of tinted glass",
    "an unfogged sky gradient with stars; 16-bit colour with 4x4 dithering",
];

/// Camera: the eye is `EYE_Y` above the floor at x = z = 0, looking down +z; the
/// horizon is at screen row `HORIZON` (an off-centre projection, no pitch).
const EYE_Y: f32 = 2.0;
const FOCAL: f32 = 360.0;
const CENTRE_X: f32 = 320.0;
const HORIZON: f32 = 200.0;
/// The floor ends here (world units); the fog is complete before it.
const FAR_Z: f32 = 90.0;

/// The fog's colour and the sky's at the horizon (0x00RRGGBB).
const HAZE: [f32; 3] = [150.0, 128.0, 150.0];
/// The sky's colour at the top of the screen.
const ZENITH: [f32; 3] = [16.0, 18.0, 60.0];

/// Pillars: world x of the two rows, z of each pair, half width, height.
const PILLAR_X: f32 = 4.0;
const PILLAR_Z: [f32; 7] = [7.0, 12.0, 17.0, 22.0, 27.0, 32.0, 37.0];
const PILLAR_HALF: f32 = 0.45;
const PILLAR_HEIGHT: f32 = 5.5;

/// The crystal: centre, half width, half height.
const CRYSTAL: [f32; 3] = [0.0, 2.3, 10.5];
const CRYSTAL_HALF_W: f32 = 1.3;
const CRYSTAL_HALF_H: f32 = 1.9;

/// The light map covers the floor for x in `LIGHT_X` and z in `LIGHT_Z`; clamped
/// outside, where its edge texels hold the ambient level.
const LIGHT_X: [f32; 2] = [-12.0, 12.0];
const LIGHT_Z: [f32; 2] = [0.0, 40.0];
const AMBIENT: f32 = 0.34;

/// Floor texture repeats every this many world units.
const FLOOR_TILE: f32 = 4.0;

/// One vertex as the scene's layout has it: x, y, 1/w, r, g, b, a, s0/w, t0/w,
/// s1/w, t1/w (texture coordinates in Glide's 0..256 across a texture).
type Vertex = [f32; 11];

/// A point of the world seen from the eye: screen x, y and 1/w (w = depth z).
fn project(p: [f32; 3]) -> [f32; 3] {
    let oow = 1.0 / p[2];
    [
        CENTRE_X + FOCAL * p[0] * oow,
        HORIZON - FOCAL * (p[1] - EYE_Y) * oow,
        oow,
    ]
}

/// The vertex at world point `p` with colour `rgb`, alpha `a` and texture
/// coordinates `st0` (TMU0) and `st1` (TMU1).
fn vertex(p: [f32; 3], rgb: [f32; 3], a: f32, st0: [f32; 2], st1: [f32; 2]) -> Vertex {
    let [x, y, oow] = project(p);
    [
        x,
        y,
        oow,
        rgb[0],
        rgb[1],
        rgb[2],
        a,
        st0[0] * oow,
        st0[1] * oow,
        st1[0] * oow,
        st1[1] * oow,
    ]
}

fn quad(g: &mut Glide, q: &[Vertex; 4]) {
    g.draw_triangle(&q[0], &q[1], &q[2]);
    g.draw_triangle(&q[0], &q[2], &q[3]);
}

/// A small integer hash (for texture noise): the same on every host.
fn hash(x: u32, y: u32, seed: u32) -> u32 {
    let mut h = x.wrapping_mul(0x27d4_eb2d) ^ y.wrapping_mul(0x1656_67b1) ^ seed;
    h ^= h >> 15;
    h = h.wrapping_mul(0x2c1b_3c6d);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297a_2d39);
    h ^ (h >> 15)
}

/// Noise in 0..1 from the hash.
fn noise(x: u32, y: u32, seed: u32) -> f32 {
    (hash(x, y, seed) & 0xffff) as f32 / 65535.0
}

/// Smooth value noise over cells of `cell` texels, wrapping every `size` texels.
fn smooth_noise(x: u32, y: u32, cell: u32, size: u32, seed: u32) -> f32 {
    let cells = size / cell;
    let (cx, cy) = (x / cell, y / cell);
    let (fx, fy) = (
        (x % cell) as f32 / cell as f32,
        (y % cell) as f32 / cell as f32,
    );
    let at = |i: u32, j: u32| noise(i % cells, j % cells, seed);
    let (sx, sy) = (fx * fx * (3.0 - 2.0 * fx), fy * fy * (3.0 - 2.0 * fy));
    let top = at(cx, cy) + (at(cx + 1, cy) - at(cx, cy)) * sx;
    let bottom = at(cx, cy + 1) + (at(cx + 1, cy + 1) - at(cx, cy + 1)) * sx;
    top + (bottom - top) * sy
}

/// A square image of linear 0..255 RGB texels.
struct Image {
    size: usize,
    texels: Vec<[f32; 3]>,
}

impl Image {
    fn new(size: usize, texel: impl Fn(u32, u32) -> [f32; 3]) -> Self {
        let texels = (0..size * size)
            .map(|i| texel((i % size) as u32, (i / size) as u32))
            .collect();
        Self { size, texels }
    }

    /// The next smaller mipmap level: each texel the average of a 2x2 block.
    fn half(&self) -> Self {
        let size = self.size / 2;
        let at = |x: usize, y: usize| self.texels[y * self.size + x];
        let texels = (0..size * size)
            .map(|i| {
                let (x, y) = (2 * (i % size), 2 * (i / size));
                let q = [at(x, y), at(x + 1, y), at(x, y + 1), at(x + 1, y + 1)];
                std::array::from_fn(|c| (q[0][c] + q[1][c] + q[2][c] + q[3][c]) / 4.0)
            })
            .collect();
        Self { size, texels }
    }

    /// The texels as little-endian RGB565, rounded to nearest.
    fn rgb565(&self, out: &mut Vec<u8>) {
        for t in &self.texels {
            let c = |v: f32, max: f32| (v.clamp(0.0, 255.0) * max / 255.0 + 0.5) as u16;
            let p = (c(t[0], 31.0) << 11) | (c(t[1], 63.0) << 5) | c(t[2], 31.0);
            out.extend_from_slice(&p.to_le_bytes());
        }
    }

    /// The full mipmap chain down to 1x1, largest first, as RGB565.
    fn mipmaps(self) -> Vec<u8> {
        let mut out = Vec::new();
        let mut level = self;
        loop {
            level.rgb565(&mut out);
            if level.size == 1 {
                return out;
            }
            level = level.half();
        }
    }
}

/// A sine wave of period 1 made of two parabolas (within 6% of `sin(2 pi t)`):
/// plain arithmetic, so the same on every host, unlike libm's `sin`.
fn sine(t: f32) -> f32 {
    let p = t - t.floor();
    if p < 0.5 {
        16.0 * p * (0.5 - p)
    } else {
        -16.0 * (p - 0.5) * (1.0 - p)
    }
}

fn lerp3(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    std::array::from_fn(|c| a[c] + (b[c] - a[c]) * t)
}

/// The floor: 4x4 stone tiles of 64 texels, alternating sandstone and slate, each
/// tinted, mottled, bevelled and set in dark grout.
fn floor_texture() -> Image {
    Image::new(256, |x, y| {
        let (tx, ty) = (x / 64, y / 64);
        let (u, v) = (x % 64, y % 64);
        let sand = [196.0, 170.0, 128.0];
        let slate = [92.0, 104.0, 116.0];
        let base = if (tx + ty) % 2 == 0 { sand } else { slate };
        let tint = 0.85 + 0.3 * noise(tx, ty, 7);
        let mottle = 0.75
            + 0.35 * smooth_noise(x, y, 16, 256, 11)
            + 0.15 * smooth_noise(x, y, 4, 256, 12)
            + 0.08 * noise(x, y, 13);
        let mut c: [f32; 3] = std::array::from_fn(|i| base[i] * tint * mottle);
        // Bevel: lit on the top and left edges, shaded on the bottom and right.
        let edge = |d: u32| (1.0 - d as f32 / 4.0).max(0.0);
        let light = edge(u.saturating_sub(2)) * 0.25 + edge(v.saturating_sub(2)) * 0.25
            - edge(61u32.saturating_sub(u)) * 0.3
            - edge(61u32.saturating_sub(v)) * 0.3;
        c = c.map(|ch| ch * (1.0 + light));
        if u < 2 || v < 2 {
            let grout = 40.0 + 20.0 * noise(x, y, 14);
            c = [grout, grout * 0.95, grout * 0.9];
        }
        c
    })
}

/// The pillars: pale fluted marble, veined, the flutes running along t.
fn pillar_texture() -> Image {
    Image::new(128, |x, y| {
        let flute = sine(x as f32 / 32.0 + 0.25);
        let shade = 0.82 + 0.18 * flute;
        let vein = sine(smooth_noise(x, y, 16, 128, 21) * 2.0 + (x + y) as f32 / 64.0);
        let sharp = 1.0 - vein.abs();
        let sharp = sharp * sharp * sharp * sharp;
        let vein = 1.0 - 0.22 * sharp * sharp;
        let grain = 0.93 + 0.07 * noise(x, y, 22);
        let k = shade * vein * grain;
        [230.0 * k, 222.0 * k, 210.0 * k]
    })
}

/// A pool of light: `colour` (0..1 a channel) at strength 1 on `at`, falling to 0 at
/// `radius`.
struct Pool {
    at: [f32; 2],
    radius: f32,
    colour: [f32; 3],
}

/// The lights of the floor, in world x, z.
fn pools() -> Vec<Pool> {
    let mut pools = Vec::new();
    for (i, &z) in PILLAR_Z.iter().enumerate() {
        for side in [-1.0f32, 1.0] {
            let warm = if (i + usize::from(side > 0.0)) % 2 == 0 {
                [1.0, 0.62, 0.28]
            } else {
                [1.0, 0.45, 0.35]
            };
            pools.push(Pool {
                at: [side * (PILLAR_X - 1.0), z - 0.8],
                radius: 3.2,
                colour: warm.map(|c| c * 0.95),
            });
        }
    }
    pools.push(Pool {
        at: [CRYSTAL[0], CRYSTAL[2]],
        radius: 5.0,
        colour: [0.2, 0.75, 1.0],
    });
    pools
}

/// The light map: ambient plus the pools, over `LIGHT_X` x `LIGHT_Z`; the border
/// texels are ambient so the clamped floor beyond is evenly lit.
fn light_map() -> Image {
    let pools = pools();
    let size = 64;
    Image::new(size, |x, y| {
        if x == 0 || y == 0 || x == size as u32 - 1 || y == size as u32 - 1 {
            return [AMBIENT * 255.0; 3];
        }
        let wx = LIGHT_X[0] + (x as f32 + 0.5) / size as f32 * (LIGHT_X[1] - LIGHT_X[0]);
        let wz = LIGHT_Z[0] + (y as f32 + 0.5) / size as f32 * (LIGHT_Z[1] - LIGHT_Z[0]);
        let mut light = [AMBIENT; 3];
        for p in &pools {
            let d = ((wx - p.at[0]).powi(2) + (wz - p.at[1]).powi(2)).sqrt() / p.radius;
            let f = (1.0 - d * d).max(0.0);
            let f = f * f;
            for (l, c) in light.iter_mut().zip(p.colour) {
                *l += c * f;
            }
        }
        light.map(|l| l.min(1.0) * 255.0)
    })
}

fn tex_info(size_log2: u32) -> TexInfo {
    TexInfo {
        small_lod: GR_LOD_LOG2_1,
        large_lod: size_log2,
        aspect: GR_ASPECT_LOG2_1x1,
        format: GR_TEXFMT_RGB_565,
    }
}

/// The light map's texture coordinates at world x, z.
fn light_st(x: f32, z: f32) -> [f32; 2] {
    [
        (x - LIGHT_X[0]) / (LIGHT_X[1] - LIGHT_X[0]) * 256.0,
        (z - LIGHT_Z[0]) / (LIGHT_Z[1] - LIGHT_Z[0]) * 256.0,
    ]
}

/// Draws the demo's frame on the board behind `bus` (of [`TMUS`] TMUs, the rest as
/// [`crate::BoardInfo`]'s defaults say) and swaps it to the front: `grGlideInit`,
/// `grSstWinOpen` at [`WIDTH`]x[`HEIGHT`], [`draw`], `grBufferSwap(1)`,
/// `grGlideShutdown`. A Glide error (there should be none) is returned as text.
pub fn render(bus: Box<dyn crate::RegisterBus>, info: crate::BoardInfo) -> Result<(), String> {
    let mut g = Glide::init(bus, info);
    g.sst_select(0);
    if !g.win_open(
        GR_RESOLUTION_640x480,
        GR_REFRESH_60Hz,
        GR_COLORFORMAT_ARGB,
        GR_ORIGIN_UPPER_LEFT,
        2,
        1,
    ) {
        return Err(format!(
            "the demo cannot open Glide at 640x480: {}",
            g.last_error().unwrap_or("grSstWinOpen failed")
        ));
    }
    draw(&mut g);
    g.buffer_swap(1);
    if let Some(e) = g.last_error() {
        return Err(format!("the demo scene made a Glide error: {e}"));
    }
    drop(g.shutdown());
    Ok(())
}

/// Draws the scene on `g`, a context open at 640x480 on a board with two TMUs, into
/// the back buffer (the caller swaps). Sets the vertex layout and every state it uses.
pub fn draw(g: &mut Glide) {
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_Q, 8, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_RGB, 12, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_A, 24, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_ST0, 28, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_ST1, 36, GR_PARAM_ENABLE);
    g.dither_mode(GR_DITHER_4x4);
    g.cull_mode(GR_CULL_DISABLE);
    g.depth_buffer_mode(GR_DEPTHBUFFER_WBUFFER);
    g.depth_buffer_function(GR_CMP_LESS);
    g.depth_mask(true);
    let haze = u32::from_be_bytes([0, HAZE[0] as u8, HAZE[1] as u8, HAZE[2] as u8]);
    g.buffer_clear(haze, 0, 0xffff);

    // Textures: floor and pillars on TMU0 one after the other, the light map on TMU1.
    let floor_info = tex_info(GR_LOD_LOG2_256);
    let pillar_info = tex_info(GR_LOD_LOG2_128);
    let floor_at = g.tex_min_address(GR_TMU0);
    let pillar_at = floor_at + g.tex_texture_mem_required(GR_MIPMAPLEVELMASK_BOTH, &floor_info);
    g.tex_download_mipmap(
        GR_TMU0,
        floor_at,
        GR_MIPMAPLEVELMASK_BOTH,
        &floor_info,
        &floor_texture().mipmaps(),
    );
    g.tex_download_mipmap(
        GR_TMU0,
        pillar_at,
        GR_MIPMAPLEVELMASK_BOTH,
        &pillar_info,
        &pillar_texture().mipmaps(),
    );
    let light_info = TexInfo {
        small_lod: GR_LOD_LOG2_64,
        large_lod: GR_LOD_LOG2_64,
        aspect: GR_ASPECT_LOG2_1x1,
        format: GR_TEXFMT_RGB_565,
    };
    let light_at = g.tex_min_address(GR_TMU1);
    let mut light = Vec::new();
    light_map().rgb565(&mut light);
    g.tex_download_mipmap(
        GR_TMU1,
        light_at,
        GR_MIPMAPLEVELMASK_BOTH,
        &light_info,
        &light,
    );
    g.tex_source(GR_TMU1, light_at, GR_MIPMAPLEVELMASK_BOTH, &light_info);
    g.tex_clamp_mode(GR_TMU1, GR_TEXTURECLAMP_CLAMP, GR_TEXTURECLAMP_CLAMP);
    g.tex_filter_mode(
        GR_TMU1,
        GR_TEXTUREFILTER_BILINEAR,
        GR_TEXTUREFILTER_BILINEAR,
    );
    g.tex_mipmap_mode(GR_TMU1, GR_MIPMAP_DISABLE, false);
    g.tex_combine(
        GR_TMU1,
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        false,
        false,
    );
    g.tex_clamp_mode(GR_TMU0, GR_TEXTURECLAMP_WRAP, GR_TEXTURECLAMP_WRAP);
    g.tex_filter_mode(
        GR_TMU0,
        GR_TEXTUREFILTER_BILINEAR,
        GR_TEXTUREFILTER_BILINEAR,
    );
    g.tex_mipmap_mode(GR_TMU0, GR_MIPMAP_NEAREST, false);

    // Sky: a gradient from the zenith to the haze, behind everything, unfogged.
    g.fog_mode(GR_FOG_DISABLE);
    g.color_combine(
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_LOCAL_ITERATED,
        GR_COMBINE_OTHER_NONE,
        false,
    );
    g.alpha_combine(
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_LOCAL_ITERATED,
        GR_COMBINE_OTHER_NONE,
        false,
    );
    let sky_oow = 1.0 / (2.0 * FAR_Z);
    let sky = |x: f32, y: f32, c: [f32; 3]| -> Vertex {
        [x, y, sky_oow, c[0], c[1], c[2], 255.0, 0.0, 0.0, 0.0, 0.0]
    };
    let floor_top = project([0.0, 0.0, FAR_Z])[1] + 1.0;
    quad(
        g,
        &[
            sky(0.0, 0.0, ZENITH),
            sky(640.0, 0.0, ZENITH),
            sky(640.0, floor_top, HAZE),
            sky(0.0, floor_top, HAZE),
        ],
    );

    // Stars in the dark top of the sky, fainter towards the haze.
    for i in 0..90u32 {
        let x = (hash(i, 1, 31) % 640) as f32;
        let y = (hash(i, 2, 31) % 130) as f32;
        let k = (1.0 - y / 150.0) * (0.5 + 0.5 * noise(i, 3, 31));
        let star = [255.0 * k, 240.0 * k, 210.0 * k];
        g.draw_point(&[
            x + 0.5,
            y + 0.5,
            sky_oow * 1.5,
            star[0],
            star[1],
            star[2],
            255.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ]);
    }

    // Fog from here on: linear in w from near the eye to the end of the floor.
    let mut fog = [0u8; 64];
    crate::get::fog_generate_linear(&mut fog, 3.0, FAR_Z * 0.85);
    g.fog_table(&fog);
    g.fog_color_value(haze);
    g.fog_mode(GR_FOG_WITH_TABLE_ON_W);

    // Floor: base texture (TMU0) times the light map (TMU1).
    g.tex_source(GR_TMU0, floor_at, GR_MIPMAPLEVELMASK_BOTH, &floor_info);
    g.tex_combine(
        GR_TMU0,
        GR_COMBINE_FUNCTION_SCALE_OTHER,
        GR_COMBINE_FACTOR_LOCAL,
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        false,
        false,
    );
    g.color_combine(
        GR_COMBINE_FUNCTION_SCALE_OTHER,
        GR_COMBINE_FACTOR_ONE,
        GR_COMBINE_LOCAL_NONE,
        GR_COMBINE_OTHER_TEXTURE,
        false,
    );
    let floor = |x: f32, z: f32| {
        let st = [x / FLOOR_TILE * 256.0, z / FLOOR_TILE * 256.0];
        vertex([x, 0.0, z], [255.0; 3], 255.0, st, light_st(x, z))
    };
    // The near edge just below the screen; x wide enough to reach both sides.
    let near_z = FOCAL * EYE_Y / (HEIGHT as f32 - HORIZON) * 0.95;
    let reach = |z: f32| z * (CENTRE_X + 40.0) / FOCAL;
    // Bands in z keep each triangle's texture iteration short.
    let bands = [near_z, 6.0, 12.0, 24.0, 48.0, FAR_Z];
    for z in bands.windows(2) {
        let (z0, z1) = (z[0], z[1]);
        quad(
            g,
            &[
                floor(-reach(z0), z0),
                floor(reach(z0), z0),
                floor(reach(z1), z1),
                floor(-reach(z1), z1),
            ],
        );
    }

    // Pillars: marble times the iterated light (faces lit by their direction).
    g.tex_source(GR_TMU0, pillar_at, GR_MIPMAPLEVELMASK_BOTH, &pillar_info);
    g.tex_combine(
        GR_TMU0,
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        false,
        false,
    );
    g.color_combine(
        GR_COMBINE_FUNCTION_SCALE_OTHER,
        GR_COMBINE_FACTOR_LOCAL,
        GR_COMBINE_LOCAL_ITERATED,
        GR_COMBINE_OTHER_TEXTURE,
        false,
    );
    for &z in PILLAR_Z.iter().rev() {
        for side in [-1.0f32, 1.0] {
            pillar(g, side * PILLAR_X, z, side);
        }
    }

    // The crystal: iterated colour and alpha, blended over what is behind it.
    g.color_combine(
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_LOCAL_ITERATED,
        GR_COMBINE_OTHER_NONE,
        false,
    );
    g.alpha_blend_function(
        GR_BLEND_SRC_ALPHA,
        GR_BLEND_ONE_MINUS_SRC_ALPHA,
        GR_BLEND_ZERO,
        GR_BLEND_ZERO,
    );
    g.depth_mask(false);
    panes(g);
    crystal(g);
    g.depth_mask(true);
    g.alpha_blend_function(GR_BLEND_ONE, GR_BLEND_ZERO, GR_BLEND_ONE, GR_BLEND_ZERO);
}

/// One pillar at floor point (`x`, `z`) (`side` is -1 on the left, +1 on the right): a
/// fluted shaft on a wider plinth under a wider capital, marble-textured, brighter at
/// the foot where the pool of light is and darker towards the top.
fn pillar(g: &mut Glide, x: f32, z: f32, side: f32) {
    let warm = |k: f32| [255.0 * k, 214.0 * k, 170.0 * k];
    let h = PILLAR_HEIGHT;
    let (plinth, capital) = (0.35, 0.3);
    let wide = PILLAR_HALF + 0.12;
    let block = |g: &mut Glide, half: f32, y0: f32, y1: f32, foot: f32, head: f32| {
        let b = Block {
            x: [x - half, x + half],
            y: [y0, y1],
            z: [z - half, z + half],
            // The texture once across a face, twice up the shaft's height.
            t: 512.0 * (y1 - y0) / h,
        };
        b.draw(g, side, warm(foot), warm(head));
    };
    block(g, PILLAR_HALF, plinth, h - capital, 0.95, 0.45);
    block(g, wide, 0.0, plinth, 1.0, 0.95);
    block(g, wide, h - capital, h, 0.5, 0.45);
}

/// An upright box of the hall, textured on the faces the eye sees.
struct Block {
    x: [f32; 2],
    y: [f32; 2],
    z: [f32; 2],
    /// Texture t across its height.
    t: f32,
}

impl Block {
    /// Draws the front face (towards the eye), the face towards the middle of the hall
    /// (darker, turned from the light), the top where it is below the eye (lit) and the
    /// underside where it is above (in shadow), coloured `foot` at the bottom and `head`
    /// at the top.
    fn draw(&self, g: &mut Glide, side: f32, foot: [f32; 3], head: [f32; 3]) {
        let ([x0, x1], [y0, y1], [z0, z1]) = (self.x, self.y, self.z);
        let none = [0.0, 0.0];
        let v = |p: [f32; 3], c: [f32; 3], st: [f32; 2]| vertex(p, c, 255.0, st, none);
        let t = self.t;
        quad(
            g,
            &[
                v([x0, y1, z0], head, [0.0, 0.0]),
                v([x1, y1, z0], head, [256.0, 0.0]),
                v([x1, y0, z0], foot, [256.0, t]),
                v([x0, y0, z0], foot, [0.0, t]),
            ],
        );
        let xi = if side < 0.0 { x1 } else { x0 };
        let dim = |c: [f32; 3]| c.map(|v| v * 0.6);
        quad(
            g,
            &[
                v([xi, y1, z0], dim(head), [0.0, 0.0]),
                v([xi, y1, z1], dim(head), [256.0, 0.0]),
                v([xi, y0, z1], dim(foot), [256.0, t]),
                v([xi, y0, z0], dim(foot), [0.0, t]),
            ],
        );
        if y1 < EYE_Y {
            let lit = head.map(|c| (c * 1.15).min(255.0));
            quad(
                g,
                &[
                    v([x0, y1, z1], lit, [0.0, 0.0]),
                    v([x1, y1, z1], lit, [256.0, 0.0]),
                    v([x1, y1, z0], lit, [256.0, 64.0]),
                    v([x0, y1, z0], lit, [0.0, 64.0]),
                ],
            );
        }
        if y0 > EYE_Y {
            let shade = dim(dim(foot));
            quad(
                g,
                &[
                    v([x0, y0, z0], shade, [0.0, 0.0]),
                    v([x1, y0, z0], shade, [256.0, 0.0]),
                    v([x1, y0, z1], shade, [256.0, 64.0]),
                    v([x0, y0, z1], shade, [0.0, 64.0]),
                ],
            );
        }
    }
}

/// Two panes of tinted glass between the second and third pillar of each row (behind
/// the crystal, so drawn before it), clearer at the foot than at the top.
fn panes(g: &mut Glide) {
    let (z0, z1) = (PILLAR_Z[1] + PILLAR_HALF, PILLAR_Z[2] - PILLAR_HALF);
    let (y0, y1) = (0.0, PILLAR_HEIGHT * 0.8);
    for (side, tint) in [(-1.0f32, [255.0, 170.0, 60.0]), (1.0, [90.0, 200.0, 120.0])] {
        let x = side * (PILLAR_X - PILLAR_HALF);
        let v = |y: f32, z: f32, a: f32| vertex([x, y, z], tint, a, [0.0; 2], [0.0; 2]);
        quad(
            g,
            &[
                v(y1, z0, 170.0),
                v(y1, z1, 170.0),
                v(y0, z1, 60.0),
                v(y0, z0, 60.0),
            ],
        );
    }
}

/// The crystal: an octahedron turned 30 degrees about its vertical axis, each face
/// shaded by how it faces a light above and to the left, far faces drawn first.
fn crystal(g: &mut Glide) {
    let [cx, cy, cz] = CRYSTAL;
    // cos and sin of 30 degrees, then quarter turns: no libm calls, whose last bits
    // may differ between hosts.
    let (c, s) = (0.866_025_4f32, 0.5f32);
    let ring: Vec<[f32; 3]> = [(c, s), (-s, c), (-c, -s), (s, -c)]
        .iter()
        .map(|&(cos, sin)| [cx + CRYSTAL_HALF_W * cos, cy, cz + CRYSTAL_HALF_W * sin])
        .collect();
    let top = [cx, cy + CRYSTAL_HALF_H, cz];
    let bottom = [cx, cy - CRYSTAL_HALF_H, cz];
    let mut faces: Vec<[[f32; 3]; 3]> = Vec::new();
    for i in 0..4 {
        let (a, b) = (ring[i], ring[(i + 1) % 4]);
        faces.push([top, a, b]);
        faces.push([bottom, b, a]);
    }
    let light = normalize([-0.9, 0.6, -0.6]);
    let sub = |a: [f32; 3], b: [f32; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let shaded: Vec<(bool, [[f32; 3]; 3], f32)> = faces
        .iter()
        .map(|f| {
            let n = normalize(cross(sub(f[1], f[0]), sub(f[2], f[0])));
            let centre: [f32; 3] = std::array::from_fn(|c| (f[0][c] + f[1][c] + f[2][c]) / 3.0);
            // Faces whose normal points at the eye (the origin, at EYE_Y) are near.
            let to_eye = sub([0.0, EYE_Y, 0.0], centre);
            let near = dot(n, to_eye) > 0.0;
            (near, *f, dot(n, light).max(0.0))
        })
        .collect();
    for pass_near in [false, true] {
        for (near, f, lit) in &shaded {
            if *near != pass_near {
                continue;
            }
            let (alpha, k) = if *near { (96.0, 0.5) } else { (140.0, 0.25) };
            let colour = |p: [f32; 3]| {
                // Cyan at the top, violet below, lit by the face's light.
                let up = ((p[1] - (cy - CRYSTAL_HALF_H)) / (2.0 * CRYSTAL_HALF_H)).clamp(0.0, 1.0);
                let hue = lerp3([150.0, 60.0, 255.0], [90.0, 240.0, 255.0], up);
                let glint = if *near { 90.0 * lit * lit * up } else { 0.0 };
                hue.map(|c| (c * (k + (1.0 - k) * lit) + glint).min(255.0))
            };
            let v: Vec<Vertex> = f
                .iter()
                .map(|&p| vertex(p, colour(p), alpha, [0.0; 2], [0.0; 2]))
                .collect();
            g.draw_triangle(&v[0], &v[1], &v[2]);
        }
    }
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn normalize(a: [f32; 3]) -> [f32; 3] {
    let l = dot(a, a).sqrt();
    a.map(|c| c / l)
}

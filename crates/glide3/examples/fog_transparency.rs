//! Depth-buffered Gouraud pillars receding into linear table fog, a chroma-keyed
//! texture decal (magenta texels removed by the chroma key) and an alpha-blended
//! transparent pane in front, alpha-tested so its fully clear texels are skipped.
//!
//! Run: `cargo run -p glide3 --example fog_transparency [OUT.trace.gz]`.

#[path = "support/mod.rs"]
mod support;

use glide::consts::*;
use glide::{Glide, TexInfo};
use sst1_board::BoardConfig;

/// A vertex: x, y, 1/w, r, g, b, a, s/w, t/w.
fn v(x: f32, y: f32, oow: f32, rgb: [f32; 3], a: f32, st: [f32; 2]) -> [f32; 9] {
    [
        x,
        y,
        oow,
        rgb[0],
        rgb[1],
        rgb[2],
        a,
        st[0] * oow,
        st[1] * oow,
    ]
}

fn quad(g: &mut Glide, q: &[[f32; 9]; 4]) {
    g.draw_triangle(&q[0], &q[1], &q[2]);
    g.draw_triangle(&q[0], &q[2], &q[3]);
}

/// The scene.
pub fn draw(g: &mut Glide) {
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_Q, 8, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_RGB, 12, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_A, 24, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_ST0, 28, GR_PARAM_ENABLE);
    g.color_combine(
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_LOCAL_ITERATED,
        GR_COMBINE_OTHER_NONE,
        false,
    );
    g.depth_buffer_mode(GR_DEPTHBUFFER_WBUFFER);
    g.depth_buffer_function(GR_CMP_LESS);
    g.depth_mask(true);
    let mut fog = [0u8; 64];
    glide::get::fog_generate_linear(&mut fog, 1.0, 12.0);
    g.fog_table(&fog);
    g.fog_color_value(0x00a0a0b0);
    g.fog_mode(GR_FOG_WITH_TABLE_ON_W);
    g.buffer_clear(0x00a0a0b0, 0, 0xffff);

    // Two rows of pillars from w = 1 to w = 12.
    for k in 0..6 {
        let w = 1.0 + 2.0 * k as f32;
        let oow = 1.0 / w;
        let h = 300.0 * oow;
        for side in [-1.0f32, 1.0] {
            let cx = 320.0 + side * 220.0 * oow;
            let half = 30.0 * oow;
            let c = if side < 0.0 {
                [200.0, 60.0, 40.0]
            } else {
                [40.0, 90.0, 200.0]
            };
            let dark = [c[0] * 0.4, c[1] * 0.4, c[2] * 0.4];
            quad(
                g,
                &[
                    v(cx - half, 240.0 - h, oow, c, 255.0, [0.0; 2]),
                    v(cx + half, 240.0 - h, oow, c, 255.0, [0.0; 2]),
                    v(cx + half, 240.0 + h, oow, dark, 255.0, [0.0; 2]),
                    v(cx - half, 240.0 + h, oow, dark, 255.0, [0.0; 2]),
                ],
            );
        }
    }

    // A chroma-keyed decal: a 32x32 RGB565 texture, magenta around a yellow ring.
    let mut texels = Vec::with_capacity(32 * 32 * 2);
    for y in 0..32i32 {
        for x in 0..32i32 {
            let r2 = (x - 16) * (x - 16) + (y - 16) * (y - 16);
            let t: u16 = if (64..196).contains(&r2) {
                0xffe0
            } else {
                0xf81f
            };
            texels.extend_from_slice(&t.to_le_bytes());
        }
    }
    let info = TexInfo {
        small_lod: GR_LOD_LOG2_32,
        large_lod: GR_LOD_LOG2_32,
        aspect: GR_ASPECT_LOG2_1x1,
        format: GR_TEXFMT_RGB_565,
    };
    let at = g.tex_min_address(GR_TMU0);
    g.tex_download_mipmap(GR_TMU0, at, GR_MIPMAPLEVELMASK_BOTH, &info, &texels);
    g.tex_source(GR_TMU0, at, GR_MIPMAPLEVELMASK_BOTH, &info);
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
        GR_COMBINE_FACTOR_ONE,
        GR_COMBINE_LOCAL_NONE,
        GR_COMBINE_OTHER_TEXTURE,
        false,
    );
    g.chromakey_value(0x00ff00ff);
    g.chromakey_mode(GR_CHROMAKEY_ENABLE);
    let s = 32.0 * 8.0;
    quad(
        g,
        &[
            v(250.0, 150.0, 0.5, [0.0; 3], 255.0, [0.0, 0.0]),
            v(390.0, 150.0, 0.5, [0.0; 3], 255.0, [s, 0.0]),
            v(390.0, 290.0, 0.5, [0.0; 3], 255.0, [s, s]),
            v(250.0, 290.0, 0.5, [0.0; 3], 255.0, [0.0, s]),
        ],
    );
    g.chromakey_mode(GR_CHROMAKEY_DISABLE);

    // A transparent pane in front, alpha falling from left to right; texels whose alpha
    // is below 16 are rejected by the alpha test.
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
    g.alpha_blend_function(
        GR_BLEND_SRC_ALPHA,
        GR_BLEND_ONE_MINUS_SRC_ALPHA,
        GR_BLEND_ZERO,
        GR_BLEND_ZERO,
    );
    g.alpha_test_function(GR_CMP_GREATER);
    g.alpha_test_reference_value(16);
    g.depth_mask(false);
    let glass = [120.0, 255.0, 160.0];
    quad(
        g,
        &[
            v(100.0, 320.0, 0.9, glass, 200.0, [0.0; 2]),
            v(540.0, 320.0, 0.9, glass, 0.0, [0.0; 2]),
            v(540.0, 460.0, 0.9, glass, 0.0, [0.0; 2]),
            v(100.0, 460.0, 0.9, glass, 200.0, [0.0; 2]),
        ],
    );
}

/// The recorded trace of the scene (one 1-TMU board).
pub fn trace() -> sst1_trace::Trace {
    support::record("fog_transparency", BoardConfig::default(), draw)
}

fn main() -> std::io::Result<()> {
    let path = support::save("fog_transparency", &trace())?;
    println!("wrote {}", path.display());
    Ok(())
}

//! Detail texturing on a two-TMU board: a ground plane in perspective whose coarse
//! base texture (TMU1, 16x16 checker) is blended with a fine noise detail texture
//! (TMU0) by the detail factor, which grows as the texture is magnified
//! (`grTexDetailControl`): near texels get the detail, far ones the plain base.
//!
//! Run: `cargo run -p glide3 --example detail_texture [OUT.trace.gz]`.

#[path = "support/mod.rs"]
mod support;

use glide::consts::*;
use glide::{Glide, TexInfo};
use sst1_board::BoardConfig;

/// A vertex: x, y, 1/w, s0/w, t0/w, s1/w, t1/w.
fn v(x: f32, y: f32, oow: f32, s: f32, t: f32) -> [f32; 7] {
    // Detail (TMU0) repeats 8 times as often as the base (TMU1).
    [x, y, oow, 8.0 * s * oow, 8.0 * t * oow, s * oow, t * oow]
}

fn texture(g: &mut Glide, tmu: u32, texel: impl Fn(u32, u32) -> u16) {
    let mut data = Vec::with_capacity(64 * 64 * 2);
    for y in 0..64 {
        for x in 0..64 {
            data.extend_from_slice(&texel(x, y).to_le_bytes());
        }
    }
    let info = TexInfo {
        small_lod: GR_LOD_LOG2_64,
        large_lod: GR_LOD_LOG2_64,
        aspect: GR_ASPECT_LOG2_1x1,
        format: GR_TEXFMT_RGB_565,
    };
    let at = g.tex_min_address(tmu);
    g.tex_download_mipmap(tmu, at, GR_MIPMAPLEVELMASK_BOTH, &info, &data);
    g.tex_source(tmu, at, GR_MIPMAPLEVELMASK_BOTH, &info);
    g.tex_clamp_mode(tmu, GR_TEXTURECLAMP_WRAP, GR_TEXTURECLAMP_WRAP);
    g.tex_filter_mode(tmu, GR_TEXTUREFILTER_BILINEAR, GR_TEXTUREFILTER_BILINEAR);
}

/// The scene.
pub fn draw(g: &mut Glide) {
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_Q, 8, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_ST0, 12, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_ST1, 20, GR_PARAM_ENABLE);
    // Base: a green/brown 16-texel checker.
    texture(g, GR_TMU1, |x, y| {
        if ((x / 16) ^ (y / 16)) & 1 != 0 {
            0x4c43
        } else {
            0x8b06
        }
    });
    // Detail: hashed grey noise.
    texture(g, GR_TMU0, |x, y| {
        let h = (x.wrapping_mul(73_856_093) ^ y.wrapping_mul(19_349_663)) >> 7;
        let l = 8 + (h % 16) as u16;
        (l << 11) | ((2 * l) << 5) | l
    });
    g.tex_combine(
        GR_TMU1,
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        false,
        false,
    );
    g.tex_combine(
        GR_TMU0,
        GR_COMBINE_FUNCTION_BLEND,
        GR_COMBINE_FACTOR_DETAIL_FACTOR,
        GR_COMBINE_FUNCTION_BLEND,
        GR_COMBINE_FACTOR_DETAIL_FACTOR,
        false,
        false,
    );
    g.tex_detail_control(GR_TMU0, 4, 4, 0.75);
    g.color_combine(
        GR_COMBINE_FUNCTION_SCALE_OTHER,
        GR_COMBINE_FACTOR_ONE,
        GR_COMBINE_LOCAL_NONE,
        GR_COMBINE_OTHER_TEXTURE,
        false,
    );
    g.buffer_clear(0x0070a0d0, 0, 0);
    // Ground from w = 1 at the bottom edge to w = 16 at the horizon.
    let s = 255.0 * 4.0;
    let q = [
        v(-200.0, 479.0, 1.0, 0.0, 0.0),
        v(840.0, 479.0, 1.0, s, 0.0),
        v(380.0, 200.0, 1.0 / 16.0, s, s * 4.0),
        v(260.0, 200.0, 1.0 / 16.0, 0.0, s * 4.0),
    ];
    g.draw_triangle(&q[0], &q[1], &q[2]);
    g.draw_triangle(&q[0], &q[2], &q[3]);
}

/// The recorded trace of the scene on a two-TMU board.
pub fn trace() -> sst1_trace::Trace {
    let config = BoardConfig {
        tmus: 2,
        ..BoardConfig::default()
    };
    support::record("detail_texture", config, draw)
}

fn main() -> std::io::Result<()> {
    let path = support::save("detail_texture", &trace())?;
    println!("wrote {}", path.display());
    Ok(())
}

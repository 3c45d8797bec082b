//! Anti-aliased primitives: a fan of AA lines, AA points, `grAADrawTriangle` and an AA
//! polygon, each blended over a Gouraud background with source alpha, next to their
//! aliased versions for comparison.
//!
//! Run: `cargo run -p glide3 --example aa_shapes [OUT.trace.gz]`.

#[path = "support/mod.rs"]
mod support;

use glide::consts::*;
use glide::Glide;
use sst1_board::BoardConfig;

/// A vertex: x, y, r, g, b, a (window coordinates, colours 0..255).
fn v(x: f32, y: f32, rgb: [f32; 3], a: f32) -> [f32; 6] {
    [x, y, rgb[0], rgb[1], rgb[2], a]
}

/// The scene.
pub fn draw(g: &mut Glide) {
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_RGB, 8, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_A, 20, GR_PARAM_ENABLE);
    g.color_combine(
        GR_COMBINE_FUNCTION_LOCAL,
        GR_COMBINE_FACTOR_NONE,
        GR_COMBINE_LOCAL_ITERATED,
        GR_COMBINE_OTHER_NONE,
        false,
    );
    g.buffer_clear(0x000000, 0, 0);
    // Background: a dark blue-to-purple quad.
    let dark = [
        v(0.0, 0.0, [0.0, 0.0, 40.0], 255.0),
        v(640.0, 0.0, [40.0, 0.0, 60.0], 255.0),
    ];
    let bottom = [
        v(640.0, 480.0, [10.0, 10.0, 90.0], 255.0),
        v(0.0, 480.0, [0.0, 20.0, 30.0], 255.0),
    ];
    let bg = [&dark[0][..], &dark[1][..], &bottom[0][..], &bottom[1][..]];
    g.draw_vertex_array(GR_TRIANGLE_FAN, &bg);

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
    // Left half aliased, right half antialiased: the same shapes shifted by 320.
    for (shift, aa) in [(0.0f32, false), (320.0, true)] {
        if aa {
            g.enable(GR_AA_ORDERED);
        } else {
            g.disable(GR_AA_ORDERED);
        }
        // A fan of lines, x-major and y-major, in several colours.
        let centre = v(shift + 80.0, 120.0, [255.0, 255.0, 255.0], 255.0);
        for k in 0..12 {
            let ang = k as f32 * std::f32::consts::PI / 6.0 + 0.1;
            let end = v(
                shift + 80.0 + 70.0 * ang.cos(),
                120.0 + 70.0 * ang.sin(),
                [255.0, 128.0 + 10.0 * k as f32, 40.0],
                255.0,
            );
            g.draw_line(&centre, &end);
        }
        // A row of points of falling alpha.
        for k in 0..10 {
            let p = v(
                shift + 180.0 + 12.5 * k as f32,
                60.25 + 3.5 * k as f32,
                [255.0, 255.0, 0.0],
                255.0 - 20.0 * k as f32,
            );
            g.draw_point(&p);
        }
        // A thin sliver triangle: its long edges show the stair steps.
        let a = v(shift + 20.0, 420.0, [255.0, 40.0, 40.0], 255.0);
        let b = v(shift + 300.0, 250.0, [40.0, 255.0, 40.0], 255.0);
        let c = v(shift + 160.0, 460.0, [40.0, 40.0, 255.0], 255.0);
        if aa {
            g.aa_draw_triangle(&a, &b, &c, true, true, true);
        } else {
            g.draw_triangle(&a, &b, &c);
        }
        // A hexagon through grDrawVertexArray(GR_POLYGON).
        let hex: Vec<[f32; 6]> = (0..6)
            .map(|k| {
                let ang = k as f32 * std::f32::consts::PI / 3.0 + 0.2;
                v(
                    shift + 230.0 + 60.0 * ang.cos(),
                    170.0 + 60.0 * ang.sin(),
                    [80.0 + 30.0 * k as f32, 200.0, 255.0 - 30.0 * k as f32],
                    255.0,
                )
            })
            .collect();
        let refs: Vec<&[f32]> = hex.iter().map(|p| &p[..]).collect();
        g.draw_vertex_array(GR_POLYGON, &refs);
    }
    g.disable(GR_AA_ORDERED);
}

/// The recorded trace of the scene (one 1-TMU board).
pub fn trace() -> sst1_trace::Trace {
    support::record("aa_shapes", BoardConfig::default(), draw)
}

fn main() -> std::io::Result<()> {
    let path = support::save("aa_shapes", &trace())?;
    println!("wrote {}", path.display());
    Ok(())
}

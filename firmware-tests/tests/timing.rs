//! Calibration of the timing model (`sst1_board::timing`) against the spec's performance
//! table (section 2): the spec's scenes built through the register interface, run on
//! the model, and the modelled rate compared with the spec's, row by row.
//!
//! `cargo test --release -p firmware-tests --test timing -- --nocapture` prints the
//! table that docs/timing.md shows.

use firmware_tests::bits::{alpha, color_path, fbz, fog};
use firmware_tests::texture::COLOR_PATH_TEXTURE;
use firmware_tests::{init_640x480, set_clip, Emulator, Port};
use sst1_regs::addr;

/// The spec's triangle rows: (scene, pixels, Ktriangles/s).
const SPEC_TRIANGLES: [(Scene, u32, f64); 16] = [
    (Scene::Flat, 10, 1911.0),
    (Scene::Flat, 25, 1096.0),
    (Scene::Flat, 50, 644.0),
    (Scene::Flat, 1000, 42.0),
    (Scene::Gouraud, 10, 1231.0),
    (Scene::Gouraud, 25, 968.0),
    (Scene::Gouraud, 50, 550.0),
    (Scene::Gouraud, 1000, 37.0),
    (Scene::Textured, 10, 828.0),
    (Scene::Textured, 25, 823.0),
    (Scene::Textured, 50, 655.0),
    (Scene::Textured, 1000, 43.0),
    (Scene::TexturedBlendZ, 10, 826.0),
    (Scene::TexturedBlendZ, 25, 807.0),
    (Scene::TexturedBlendZ, 50, 549.0),
    (Scene::TexturedBlendZ, 1000, 37.0),
];

/// The spec's screen clears at 640x480: (what, milliseconds).
const SPEC_CLEARS: [(Clear, f64); 3] = [
    (Clear::Rgb, 3.45),
    (Clear::Depth, 3.45),
    (Clear::Both, 3.45),
];

/// The four triangle scenes of spec section 2.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scene {
    /// Flat shaded: no fog, blending, Z or subpixel correction; right-angled,
    /// horizontally oriented.
    Flat,
    /// Gouraud shaded, subpixel corrected, fogged, blended, Z-buffered; right-angled,
    /// randomly oriented.
    Gouraud,
    /// Bilinear, mipmapped, fogged, textured, Gouraud shaded, subpixel corrected; no
    /// blending or Z; randomly oriented.
    Textured,
    /// The same with blending and Z.
    TexturedBlendZ,
}

impl Scene {
    fn name(self) -> &'static str {
        match self {
            Scene::Flat => "flat",
            Scene::Gouraud => "Gouraud, fog, blend, Z",
            Scene::Textured => "textured, fog",
            Scene::TexturedBlendZ => "textured, fog, blend, Z",
        }
    }

    fn textured(self) -> bool {
        matches!(self, Scene::Textured | Scene::TexturedBlendZ)
    }

    fn blend_z(self) -> bool {
        matches!(self, Scene::Gouraud | Scene::TexturedBlendZ)
    }

    /// The mode registers of the scene.
    fn set_up(self, port: &mut impl Port) {
        let shaded = self != Scene::Flat;
        // Iterated RGB (cc_rgbselect 0), or the texture.
        let mut cp = if self.textured() {
            COLOR_PATH_TEXTURE
        } else {
            0
        };
        if shaded {
            cp |= color_path::PARAM_ADJUST;
        }
        port.write(addr::FBZ_COLOR_PATH, cp);
        port.write(addr::FOG_MODE, if shaded { fog::ENABLE } else { 0 });
        let blend = if self.blend_z() {
            // ASRC_ALPHA, AOMSRC_ALPHA.
            alpha::BLEND | alpha::rgb_factors(1, 5)
        } else {
            0
        };
        port.write(addr::ALPHA_MODE, blend);
        let mut zm = fbz::CLIP | fbz::RGB_WRITE | fbz::DRAW_BACK;
        if self.blend_z() {
            // Depth test "less or equal".
            zm |= fbz::DEPTH | fbz::depth_function(3) | fbz::AUX_WRITE;
        }
        port.write(addr::FBZ_MODE, zm);
        if self.textured() {
            // Bilinear (min and mag filter), perspective, RGB565; LOD 0..8 mipmapped.
            port.write(addr::TEXTURE_MODE, 0x0000_0a07);
            port.write(addr::T_LOD, 0x0000_0800);
        }
    }
}

/// The spec's clears.
#[derive(Clone, Copy, Debug)]
enum Clear {
    Rgb,
    Depth,
    Both,
}

/// A small deterministic generator (64-bit LCG) for the random orientations.
struct Lcg(u64);

impl Lcg {
    fn next_unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Writes one right-angled triangle of about `pixels` pixels (legs `sqrt(2 * pixels)`)
/// with the right angle at `(x, y)`, turned by `angle`, and the parameters the scene
/// iterates; returns nothing (the board counts the writes and the time).
fn triangle(port: &mut impl Port, scene: Scene, pixels: u32, (x, y): (f64, f64), angle: f64) {
    let leg = (2.0 * pixels as f64).sqrt();
    let (s, c) = angle.sin_cos();
    let mut v = [
        (x, y),
        (x + leg * c, y + leg * s),
        (x - leg * s, y + leg * c),
    ];
    v.sort_by(|a, b| a.1.total_cmp(&b.1));
    let fixed = |f: f64| ((f * 16.0).round() as i32) as u32 & 0xffff;
    for (i, (vx, vy)) in v.iter().enumerate() {
        port.write(addr::VERTEX_AX + 8 * i as u32, fixed(*vx));
        port.write(addr::VERTEX_AY + 8 * i as u32, fixed(*vy));
    }
    if scene == Scene::Flat {
        // A constant colour: the three start values (the gradients stay zero).
        for reg in [addr::START_R, addr::START_G, addr::START_B] {
            port.write(reg, 0x80 << 12);
        }
    } else {
        // R, G, B, A: start and both gradients.
        for i in 0..4 {
            let start = [addr::START_R, addr::START_G, addr::START_B, addr::START_A][i];
            let dx = [addr::D_R_DX, addr::D_G_DX, addr::D_B_DX, addr::D_A_DX][i];
            let dy = [addr::D_R_DY, addr::D_G_DY, addr::D_B_DY, addr::D_A_DY][i];
            port.write(start, 0x40 << 12);
            port.write(dx, 1 << 10);
            port.write(dy, 1 << 10);
        }
        if scene.blend_z() {
            port.write(addr::START_Z, 0x1000 << 12);
            port.write(addr::D_Z_DX, 1 << 12);
            port.write(addr::D_Z_DY, 1 << 12);
        }
        // W: the fog unit's depth, and (broadcast to the TMU) the texture's.
        port.write(addr::START_W, 1 << 30);
        port.write(addr::D_W_DX, 0);
        port.write(addr::D_W_DY, 0);
        if scene.textured() {
            for (s, dx, dy) in [
                (addr::START_S, addr::D_S_DX, addr::D_S_DY),
                (addr::START_T, addr::D_T_DX, addr::D_T_DY),
            ] {
                port.write(s, 0);
                port.write(dx, 1 << 18);
                port.write(dy, 1 << 18);
            }
        }
    }
    let [a, b, c] = v;
    let area = (a.0 - b.0) * (b.1 - c.1) - (b.0 - c.0) * (a.1 - b.1);
    port.write(addr::TRIANGLE_CMD, if area < 0.0 { 0x8000_0000 } else { 0 });
}

/// The modelled Ktriangles/s of `count` triangles of the scene, and the mean pixels,
/// spans and writes per triangle (for the fit).
fn measure(scene: Scene, pixels: u32, count: u32, seed: u64) -> (f64, [f64; 2]) {
    let mut port = Emulator::new();
    init_640x480(&mut port);
    set_clip(&mut port, 0, 640, 0, 480);
    scene.set_up(&mut port);
    let mut rng = Lcg(seed ^ u64::from(pixels));
    // The first triangle pays for the set-up writes; time the rest.
    triangle(&mut port, scene, pixels, (320.0, 240.0), 0.0);
    let before = port.board().timing().cycles();
    let stats0 = port.board().stats();
    for _ in 0..count {
        let angle = if scene == Scene::Flat {
            0.0
        } else {
            rng.next_unit() * std::f64::consts::TAU
        };
        let at = (
            100.0 + rng.next_unit() * 440.0,
            100.0 + rng.next_unit() * 280.0,
        );
        triangle(&mut port, scene, pixels, at, angle);
    }
    let cycles = port.board().timing().cycles() - before;
    let stats = port.board().stats();
    let n = f64::from(count);
    let seconds = cycles as f64 / port.board().timing().clock_hz as f64;
    let spans = (stats.spans - stats0.spans) as f64 / n;
    let px = (stats.pixels_in - stats0.pixels_in) as f64 / n;
    (n / seconds / 1000.0, [px, spans])
}

/// The modelled milliseconds of one 640x480 clear.
fn clear_ms(what: Clear) -> f64 {
    let mut port = Emulator::new();
    init_640x480(&mut port);
    set_clip(&mut port, 0, 640, 0, 480);
    let mask = match what {
        Clear::Rgb => fbz::RGB_WRITE,
        Clear::Depth => fbz::AUX_WRITE,
        Clear::Both => fbz::RGB_WRITE | fbz::AUX_WRITE,
    };
    port.write(addr::FBZ_MODE, mask | fbz::DRAW_BACK);
    let before = port.board().timing().cycles();
    port.write(addr::FASTFILL_CMD, 0);
    let cycles = port.board().timing().cycles() - before;
    cycles as f64 * 1000.0 / port.board().timing().clock_hz as f64
}

#[test]
fn every_row_of_the_spec_table_within_tolerance() {
    println!(
        "| scene | pixels | spec Ktri/s | model Ktri/s | model / spec | pixels drawn | spans |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let mut worst: f64 = 0.0;
    let mut misses = Vec::new();
    for (scene, pixels, spec) in SPEC_TRIANGLES {
        let (model, [px, spans]) = measure(scene, pixels, 400, 0x5eed);
        let ratio = model / spec;
        println!(
            "| {} | {pixels} | {spec} | {model:.0} | {ratio:.3} | {px:.1} | {spans:.1} |",
            scene.name()
        );
        worst = worst.max((ratio - 1.0).abs());
        if (ratio - 1.0).abs() > 0.10 {
            misses.push(format!("{} {pixels}: {ratio:.3}", scene.name()));
        }
    }
    println!();
    println!("| clear (640x480) | spec ms | model ms | model / spec |");
    println!("|---|---:|---:|---:|");
    for (what, spec) in SPEC_CLEARS {
        let model = clear_ms(what);
        let ratio = model / spec;
        println!("| {what:?} | {spec} | {model:.3} | {ratio:.3} |");
        if (ratio - 1.0).abs() > 0.05 {
            misses.push(format!("clear {what:?}: {ratio:.3}"));
        }
    }
    println!("worst triangle row: {:.1} %", worst * 100.0);
    assert!(misses.is_empty(), "outside the tolerance: {misses:?}");
}

/// Other triangle counts and other random orientations of the same scenes stay within
/// the tolerance too: the fit is of the scenes, not of one sample of them.
#[test]
fn other_counts_and_orientations_within_tolerance() {
    for (count, seed) in [(97, 1), (1000, 0xdead_beef), (250, 42)] {
        for (scene, pixels, spec) in SPEC_TRIANGLES {
            let ratio = measure(scene, pixels, count, seed).0 / spec;
            assert!(
                (ratio - 1.0).abs() <= 0.10,
                "{} {pixels} px, {count} triangles, seed {seed}: {ratio:.3}",
                scene.name()
            );
        }
    }
}

/// The same trace gives the same cycle count on every run: the model never reads the
/// host's clock.
#[test]
fn cycles_are_the_same_on_every_run() {
    let a = measure(Scene::Gouraud, 50, 50, 7).0;
    let b = measure(Scene::Gouraud, 50, 50, 7).0;
    assert_eq!(a.to_bits(), b.to_bits());
}

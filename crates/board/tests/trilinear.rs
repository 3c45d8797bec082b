//! Trilinear mipmapping two ways (spec 5.50 `textureMode` trilinear bit and texture
//! combine, 5.51 `tLOD` split/odd bits; Glide 3.0 Programming Guide, "Trilinear
//! Filtering" and Example 9.3): with two TMUs in one pass, with one TMU in two passes.
//!
//! The scene: a 128 x 251 quad whose W runs from 5/256 at the top to 1.0 at the bottom,
//! with S/W and T/W stepping 4 LOD-0 texels per pixel, so that the LOD (spec 5.51:
//! `log2` of the texel step, less `log2(W)` per pixel) runs from about 7.7 at the top to
//! 2.0 (`lodmin`) at the bottom. The texture is a 64 x 64 mipmap (LODs 2..=8, 16-bit
//! RGB565), each level a checkerboard of two colours of its own (or one flat colour).
//!
//! * One pass, two TMUs: TMU0 holds the even LODs and TMU1 the odd ones (`tLOD`
//!   `lod_tsplit`, `lod_odd`). TMU1 passes its texel on (decal); TMU0 blends
//!   `local + (other - local) * (lodfrac + 1)` (`tc_sub_clocal`, `tc_mselect` = LOD
//!   fraction, `tc_reverse_blend`, `tc_add_clocal`, the same for alpha) with the
//!   `trilinear` bit, which reverses the blend where the integer LOD is odd. This is the
//!   set-up of traces/conformance/traces/tmu2_trilinear.trace.gz (`textureMode`
//!   0x4ec76a0f on TMU0, 0x48241a0f on TMU1).
//! * Two passes, one TMU: pass 1 draws the even LODs opaque; pass 2 draws the odd LODs
//!   alpha-blended (`ASRC_ALPHA`, `AOMSRC_ALPHA`) with the odd level's weight in alpha,
//!   which the TMU's alpha combine computes from the LOD fraction (with the `trilinear`
//!   bit, so that the weight is the fraction on even LODs and one minus it on odd ones).

use sst1_board::{AccuracyProfile, Board, BoardConfig, BufferKind, TexelProfile};
use sst1_regs::{addr, RegisterBus};
use texelfx::{LodCalc, Trilinear};

/// Start of the texture region of the aperture (spec 4).
const TEX_BASE: u32 = 0x80_0000;
/// Register-address chip-select bits (spec 5: address bits 13:10).
const TMU0: u32 = 0x800;
const TMU1: u32 = 0x1000;

// --- register values -----------------------------------------------------------------

/// `textureMode` bits 0-2 and 11:8: perspective, bilinear min and mag filters, RGB565.
const TEX_BASIC: u32 = 1 | 2 | 4 | 10 << 8;
/// `textureMode` bit 30: reverse the combine factor where the integer LOD is odd.
const TRILINEAR: u32 = 1 << 30;
/// Combine-unit control bits, relative to the unit's first bit (12 for `tc_*`, 21 for
/// `tca_*`): zero_other, sub_clocal, mselect, reverse_blend, add_clocal, add_alocal.
const ZERO_OTHER: u32 = 1;
const SUB_CLOCAL: u32 = 2;
/// `mselect` 5: the LOD fraction.
const MSEL_LODFRAC: u32 = 5 << 2;
const REVERSE: u32 = 0x20;
const ADD_CLOCAL: u32 = 0x40;
const ADD_ALOCAL: u32 = 0x80;
const fn tc(bits: u32) -> u32 {
    bits << 12
}
const fn tca(bits: u32) -> u32 {
    bits << 21
}
/// Decal: the TMU's own texel, colour and alpha.
const DECAL: u32 = tc(ZERO_OTHER | ADD_CLOCAL) | tca(ZERO_OTHER | ADD_ALOCAL);
/// `local + (other - local) * (lodfrac + 1) >> 8` for colour and alpha: Glide's
/// `GR_COMBINE_FUNCTION_BLEND` with `GR_COMBINE_FACTOR_LOD_FRACTION` (the even TMU of
/// Example 9.3 in the trace's form).
const BLEND_BY_LODFRAC: u32 = tc(SUB_CLOCAL | MSEL_LODFRAC | REVERSE | ADD_CLOCAL)
    | tca(SUB_CLOCAL | MSEL_LODFRAC | REVERSE | ADD_CLOCAL);

/// `tLOD`: `lodmin` 2.0 (64 x 64 is the largest level), `lodmax` 8.0 (4.2 fixed point).
const LOD_RANGE: u32 = 2 << 2 | (8 << 2) << 6;
/// `tLOD` bit 19: only the even or only the odd LODs are stored; bit 18: the odd ones.
const TSPLIT: u32 = 1 << 19;
const ODD: u32 = 1 << 18;

/// `fbzColorPath`: colour and alpha from the texture, straight through; texturing on.
const COLOR_PATH_TEXTURE: u32 = 1 | 1 << 2 | 1 << 27;
/// `fbzMode`: clip, RGB writes, draw into the front buffer, no dithering.
const FBZ: u32 = 1 | 1 << 9;
/// `alphaMode`: blend on, source factor `ASRC_ALPHA` (1), destination `AOMSRC_ALPHA` (5).
const BLEND_SRC_ALPHA: u32 = 1 << 4 | 1 << 8 | 5 << 12;

/// The quad: columns 0..128, rows 0..251.
const WIDTH: u32 = 128;
const HEIGHT: u32 = 251;

// --- the texture ---------------------------------------------------------------------

/// The two RGB565 colours of each LOD 2..=8; a level's texel `(s, t)` is colour
/// `(s + t) & 1`.
const CHECKER: [[u16; 2]; 7] = [
    [0xf800, 0xc618],
    [0x07e0, 0x4208],
    [0x001f, 0xffe0],
    [0xf81f, 0x07ff],
    [0x8410, 0xfc00],
    [0x03e0, 0xa145],
    [0x5aeb, 0x5aeb],
];

/// One flat RGB565 colour per LOD 2..=8.
const FLAT: [[u16; 2]; 7] = [
    [0xf800, 0xf800],
    [0x07e0, 0x07e0],
    [0x001f, 0x001f],
    [0xffe0, 0xffe0],
    [0xf81f, 0xf81f],
    [0x07ff, 0x07ff],
    [0x8410, 0x8410],
];

/// Sets RGB565 `textureMode`, `tLOD` = `t_lod` and `texBaseAddr` = `base` / 8 on TMU
/// `tmu`, then downloads the LODs 2..=8 of `levels` that `t_lod` stores (all, or the even
/// or odd ones with `lod_tsplit`). Spec 8, texture load: address bits 20:17 LOD, 16:9 T,
/// 8:1 S; two 16-bit texels per write.
fn download(b: &mut Board, tmu: u32, t_lod: u32, base: u32, levels: &[[u16; 2]; 7]) {
    let chip = [TMU0, TMU1][tmu as usize];
    b.write32(chip | addr::TEXTURE_MODE, TEX_BASIC);
    b.write32(chip | addr::T_LOD, t_lod);
    b.write32(chip | addr::TEX_BASE_ADDR, base >> 3);
    for lod in 2..=8u32 {
        let stored = t_lod & TSPLIT == 0 || (lod & 1 == 1) == (t_lod & ODD != 0);
        if !stored {
            continue;
        }
        let size = 256 >> lod;
        let colours = levels[(lod - 2) as usize];
        let texel = |s: u32, t: u32| u32::from(colours[((s + t) & 1) as usize]);
        for t in 0..size {
            for s in (0..size).step_by(2) {
                let a = TEX_BASE | tmu << 21 | lod << 17 | t << 9 | s << 1;
                b.write32(a, texel(s, t) | texel(s + 1, t) << 16);
            }
        }
    }
}

/// A board with `tmus` TMUs and the texel switches `texel`, after the Glide init, drawing
/// the texture into the front buffer.
fn board(tmus: u32, texel: TexelProfile) -> Board {
    let mut b = Board::new(BoardConfig {
        fbi_mb: 4,
        tmus,
        tmu_mb: 4,
    });
    b.set_profile(AccuracyProfile {
        texel,
        ..Default::default()
    });
    sst1_board::presets::init_glide_640x480(&mut b);
    b.write32(addr::STIPPLE, 0xffff_ffff);
    b.write32(addr::FBZ_MODE, FBZ);
    b.write32(addr::FBZ_COLOR_PATH, COLOR_PATH_TEXTURE);
    b
}

/// Draws the quad as two triangles, both with vertex A on the top row. The iterators
/// (broadcast to every TMU; the FBI keeps W too):
/// S = 4.0 x, T = 4.0 y (14.18: 4.0 = 0x100000), W = (5 + y) / 256 (2.30: 5/256 =
/// 0x1400000, 1/256 = 0x400000), so S/W and T/W step 4 / W LOD-0 texels per pixel.
fn quad(b: &mut Board) {
    for (ax, [bv, cv]) in [
        (0, [(WIDTH, 0), (0, HEIGHT)]),
        (WIDTH, [(WIDTH, HEIGHT), (0, HEIGHT)]),
    ] {
        for (reg, v) in [
            (addr::VERTEX_AX, ax << 4),
            (addr::VERTEX_AY, 0),
            (addr::VERTEX_BX, bv.0 << 4),
            (addr::VERTEX_BY, bv.1 << 4),
            (addr::VERTEX_CX, cv.0 << 4),
            (addr::VERTEX_CY, cv.1 << 4),
            (addr::START_S, (4 * ax) << 18),
            (addr::D_S_DX, 0x10_0000),
            (addr::D_S_DY, 0),
            (addr::START_T, 0),
            (addr::D_T_DX, 0),
            (addr::D_T_DY, 0x10_0000),
            (addr::START_W, 0x140_0000),
            (addr::D_W_DX, 0),
            (addr::D_W_DY, 0x40_0000),
        ] {
            b.write32(reg, v);
        }
        // Bit 31 is the sign of the area (spec 5.15): positive for both.
        b.write32(addr::TRIANGLE_CMD, 0);
    }
}

/// The quad's pixels of the front buffer, row by row.
fn pixels(b: &Board) -> Vec<u16> {
    let front = b.dump_buffer(BufferKind::Front);
    (0..HEIGHT)
        .flat_map(|y| {
            let row = (y * 640) as usize;
            front[row..row + WIDTH as usize].to_vec()
        })
        .collect()
}

/// One pass on two TMUs: TMU0 even LODs blending, TMU1 odd LODs decal.
fn one_pass(levels: &[[u16; 2]; 7], texel: TexelProfile) -> Vec<u16> {
    let mut b = board(2, texel);
    download(&mut b, 0, LOD_RANGE | TSPLIT, 0, levels);
    download(&mut b, 1, LOD_RANGE | TSPLIT | ODD, 0, levels);
    b.write32(
        TMU0 | addr::TEXTURE_MODE,
        TEX_BASIC | TRILINEAR | BLEND_BY_LODFRAC,
    );
    b.write32(TMU1 | addr::TEXTURE_MODE, TEX_BASIC | TRILINEAR | DECAL);
    quad(&mut b);
    // Every pixel drawn once: the two triangles share their diagonal without overlap.
    assert_eq!(b.stats().pixels_out, u64::from(WIDTH * HEIGHT));
    pixels(&b)
}

/// Two passes on one TMU holding the even LODs at 0 and the odd ones at 0x40000.
///
/// Pass 2's alpha: the TMU's alpha unit computes `((0 - a_local) * (G + 1) >> 8) + a_local`
/// (`tca_zero_other`, `tca_sub_clocal`, LOD-fraction factor, no reverse, `tca_add_alocal`)
/// with `a_local` = 255 (RGB565 texels are opaque) and `G` the factor: `255 - lodfrac`
/// on even LODs, `lodfrac` on odd ones (the trilinear bit reverses it). Writing `F` for
/// the odd level's factor in the one-pass blend (`lodfrac` on even LODs, `255 - lodfrac`
/// on odd ones), `G = 255 - F`, and `(-255 * (256 - F)) >> 8 + 255 = F - 1` for `F >= 1`
/// (0 for `F = 0`): the alpha is `max(F - 1, 0)`, the closest this unit comes to `F`.
fn two_pass(levels: &[[u16; 2]; 7]) -> Vec<u16> {
    let mut b = board(1, TexelProfile::default());
    download(&mut b, 0, LOD_RANGE | TSPLIT | ODD, 0x4_0000, levels);
    download(&mut b, 0, LOD_RANGE | TSPLIT, 0, levels);
    // Pass 1: the even LODs, opaque.
    b.write32(addr::TEXTURE_MODE, TEX_BASIC | DECAL);
    quad(&mut b);
    // Pass 2: the odd LODs, weighted by alpha.
    b.write32(addr::T_LOD, LOD_RANGE | TSPLIT | ODD);
    b.write32(addr::TEX_BASE_ADDR, 0x4_0000 >> 3);
    b.write32(
        addr::TEXTURE_MODE,
        TEX_BASIC
            | TRILINEAR
            | tc(ZERO_OTHER | ADD_CLOCAL)
            | tca(ZERO_OTHER | SUB_CLOCAL | MSEL_LODFRAC | ADD_ALOCAL),
    );
    b.write32(addr::ALPHA_MODE, BLEND_SRC_ALPHA);
    quad(&mut b);
    pixels(&b)
}

/// Plain mipmapping: one TMU with every LOD, decal, no blend between levels.
fn plain(levels: &[[u16; 2]; 7]) -> Vec<u16> {
    let mut b = board(1, TexelProfile::default());
    download(&mut b, 0, LOD_RANGE, 0, levels);
    b.write32(addr::TEXTURE_MODE, TEX_BASIC | DECAL);
    quad(&mut b);
    pixels(&b)
}

/// Per-channel differences of two RGB565 pixels, in units of each field (5, 6, 5 bits).
fn channel_diff(a: u16, b: u16) -> [u16; 3] {
    let f = |p: u16| [p >> 11, (p >> 5) & 0x3f, p & 0x1f];
    let (x, y) = (f(a), f(b));
    [0, 1, 2].map(|i| x[i].abs_diff(y[i]))
}

/// The largest per-channel difference of each pixel pair, and how many pixels differ
/// by more than `threshold` in some channel.
fn compare(a: &[u16], b: &[u16], threshold: u16) -> (u16, usize) {
    let d: Vec<u16> = a
        .iter()
        .zip(b)
        .map(|(&p, &q)| channel_diff(p, q).into_iter().max().unwrap_or(0))
        .collect();
    let max = d.iter().copied().max().unwrap_or(0);
    (max, d.iter().filter(|&&v| v > threshold).count())
}

/// The two-pass result against the one-pass one.
///
/// Per channel, with `E` the even level's and `O` the odd level's filtered texel (8
/// bits), `F` the odd level's factor (see [`two_pass`]), the one-pass TMU0 output is
/// `P1 = E + floor((O - E) * (F + 1) / 256)`. Pass 1 stores `E` truncated to 5 (6) bits;
/// the blend widens it back by replicating its high bits (the default `BlendArithmetic`)
/// to `d`, with `|d - E| <= 7` for red and blue and `<= 3` for green: this is the
/// quantisation of the intermediate pass. Pass 2 blends with `a = F - 1` as
/// `P2 = floor(O * (a + 1) / 256) + floor(d * (256 - a) / 256)`. Exactly:
///
/// ```text
/// O*F/256 + d*(257-F)/256 - (E + (O-E)*(F+1)/256) = ((d - E)*(257 - F) + 2E - O) / 256
/// ```
///
/// which for `1 <= F` lies in `[-7.996, 8.99]` (red, blue) or `[-3.996, 4.99]` (green);
/// the two floors of `P2` take up to 2 away and the floor of `P1` up to 1, so
/// `|P2 - P1| <= 9` (red, blue) and `<= 5` (green). (`F = 0`: `P2 = d`,
/// `P1` is `E` or `E - 1`: within the same.) Truncating both to the 5-bit (6-bit) field
/// turns a difference of up to 9 (5) into at most 2 units: `ceil(9 / 8) = ceil(5 / 4)
/// = 2`. With flat levels of RGB565 colours `d = E` (replicating the high bits of a
/// truncated RGB565 expansion gives it back), the difference is `(2E - O) / 256` in
/// `(-1, 2)` before the floors, `|P2 - P1| <= 2`, and at most 1 unit.
fn two_pass_against_one_pass(levels: &[[u16; 2]; 7], bound: u16) {
    let one = one_pass(levels, TexelProfile::default());
    let two = two_pass(levels);
    let (max, _) = compare(&one, &two, bound);
    assert!(max <= bound, "two-pass differs by {max} > {bound}");
    // Not plain mipmapping: the blend between levels shows (by more than the bound)
    // across much of the quad, in both renderings.
    let flat = plain(levels);
    for image in [&one, &two] {
        let (max, count) = compare(image, &flat, bound);
        assert!(max > 8, "{max}");
        assert!(count > (WIDTH * HEIGHT / 4) as usize, "{count}");
    }
}

#[test]
fn two_pass_matches_one_pass_checker_levels() {
    two_pass_against_one_pass(&CHECKER, 2);
}

#[test]
fn two_pass_matches_one_pass_flat_levels() {
    two_pass_against_one_pass(&FLAT, 1);
}

/// `floor(256 * log2(v))` for the W of a row, in .32 fixed point, as the TMU takes it:
/// the exponent and the 7 mantissa bits after the leading one (spec 5.51 gives only
/// `log2`; the 7-bit table is MAME's `fast_log2`, which DOSBox Staging shares).
fn log2_8_8(v: u64) -> i32 {
    let k = 63 - v.leading_zeros() as i32;
    let m = ((v << (63 - k)) >> 56) & 0x7f;
    (k - 32) * 256 + (256.0 * (1.0 + m as f64 / 128.0).log2()).floor() as i32
}

/// With flat levels the one-pass image is exact and can be written down per row. The
/// base LOD is `log2` of the texel step, 4.0: 2.0. Row y has W = (5 + y) / 256, so
/// LOD = 2.0 - log2(W), clamped to `lodmin` 2.0, as 8.8: integer `n`, fraction `f`.
/// TMU0 holds the even level `E` (`n` if even, else `n + 1`), TMU1 the odd `O`; the
/// pixel is `E + ((O - E) * (F + 1) >> 8)` per channel, truncated to RGB565, with `F`
/// the factor of TMU0's combine: `f` on even `n`; on odd `n`, `255 - f` where the
/// trilinear bit reverses it (`Trilinear::Spec`), `f` where it is ignored.
///
/// The LOD is MAME's (`LodCalc::Mame`): its 7-bit log table is the one written out in
/// [`log2_8_8`]; the other calculations round the fraction differently on some rows.
fn one_pass_against_the_lod_blend(trilinear: Trilinear) {
    let image = one_pass(
        &FLAT,
        TexelProfile {
            lod: LodCalc::Mame,
            trilinear,
            ..Default::default()
        },
    );
    let expand = |p: u16| {
        let (r, g, b) = (
            u32::from(p >> 11),
            u32::from((p >> 5) & 0x3f),
            u32::from(p & 0x1f),
        );
        [r << 3 | r >> 2, g << 2 | g >> 4, b << 3 | b >> 2].map(|v| v as i32)
    };
    let mut odd_rows = 0;
    for y in 0..HEIGHT {
        let w = u64::from(5 + y) << 24;
        let lod = (0x200 - log2_8_8(w)).clamp(0x200, 0x800);
        let (n, f) = (lod >> 8, lod & 0xff);
        let (even, odd, factor) = if n % 2 == 0 {
            (n, n + 1, f)
        } else {
            odd_rows += 1;
            let factor = match trilinear {
                Trilinear::Spec => 255 - f,
                Trilinear::Ignored => f,
            };
            (n + 1, n, factor)
        };
        let e = expand(FLAT[(even - 2) as usize][0]);
        let o = expand(FLAT[(odd - 2) as usize][0]);
        let c = [0, 1, 2].map(|i| (e[i] + (((o[i] - e[i]) * (factor + 1)) >> 8)) as u32);
        let want = ((c[0] >> 3) << 11 | (c[1] >> 2) << 5 | (c[2] >> 3)) as u16;
        let row = &image[(y * WIDTH) as usize..((y + 1) * WIDTH) as usize];
        assert!(
            row.iter().all(|&p| p == want),
            "row {y}: lod {lod:#x}: {row:04x?}"
        );
    }
    // Rows 0..=3 (LOD 7.x), 12..=27 (5.x) and 60..=123 (3.x) have an odd integer LOD:
    // there the two choices differ.
    assert_eq!(odd_rows, 4 + 16 + 64);
}

/// `Trilinear::Spec` (spec 5.50 diagram, 86Box; default): the blend is continuous across
/// the quad, each level fading into the next.
#[test]
fn one_pass_is_the_lod_fraction_blend() {
    one_pass_against_the_lod_blend(Trilinear::Spec);
}

/// `Trilinear::Ignored` (MAME, DOSBox Staging): on odd LODs the even level gets the
/// fraction's weight, so the image jumps at every integer LOD (one-pass trilinear as
/// Glide sets it up is wrong there).
#[test]
fn one_pass_without_the_trilinear_reverse() {
    one_pass_against_the_lod_blend(Trilinear::Ignored);
}

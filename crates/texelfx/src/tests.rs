//! End-to-end tests through the public `Tmu` interface.

use super::*;
/// These tests set profiles at run time: the run-time-profile model reads them.
use crate::RuntimeProfile as R;

/// textureMode combine fields that output the local texel unchanged (Glide's "decal").
const DECAL: u32 = (1 << 12) | (1 << 18) | (1 << 21) | (1 << 27);
const BILINEAR: u32 = 6;
const PERSP: u32 = 1;
const CLAMPW: u32 = 8;
const CLAMPS: u32 = 0x40;
const CLAMPT: u32 = 0x80;
const fn fmt(f: u32) -> u32 {
    f << 8
}
/// tLOD with lodmin = lodmax = `lod` (whole LODs).
const fn fixed_lod(lod: u32) -> u32 {
    (lod * 4) | (lod * 4) << 6
}
const BLACK: Rgba = Rgba {
    r: 0,
    g: 0,
    b: 0,
    a: 0,
};
const WHITE: Rgba = Rgba {
    r: 255,
    g: 255,
    b: 255,
    a: 255,
};

fn rgba(v: [u8; 4]) -> Rgba {
    Rgba {
        r: v[0],
        g: v[1],
        b: v[2],
        a: v[3],
    }
}

/// Download address of 16-bit texels (s, s+1) of a LOD.
fn addr16(lod: u32, s: u32, t: u32) -> u32 {
    (lod << 17) | (t << 9) | ((s >> 1) << 2)
}

/// Sets S/T iterators (in LOD-0 texels, 14.18) and W (2.30).
fn set_iter(tmu: &mut Tmu, s: i32, t: i32, dsdx: i32, dtdy: i32, w: i32) {
    tmu.write_reg(addr::START_S, s as u32);
    tmu.write_reg(addr::START_T, t as u32);
    tmu.write_reg(addr::START_W, w as u32);
    tmu.write_reg(addr::D_S_DX, dsdx as u32);
    tmu.write_reg(addr::D_T_DX, 0);
    tmu.write_reg(addr::D_W_DX, 0);
    tmu.write_reg(addr::D_S_DY, 0);
    tmu.write_reg(addr::D_T_DY, dtdy as u32);
    tmu.write_reg(addr::D_W_DY, 0);
}

const ONE_W: i32 = 1 << 30;
const fn tex(v: i32) -> i32 {
    v << 18
}

/// An 8x8 RGB565 texture stored as LOD 5 of a square chain at address 0, with
/// (2,2) blue, (3,2) red, (4,2) green, (0,2) green, (6,2)/(7,2) white.
fn rgb565_8x8(mode_extra: u32) -> Tmu {
    let mut tmu = Tmu::new(0, 2 << 20);
    tmu.write_reg(addr::TEXTURE_MODE, fmt(10) | DECAL | mode_extra);
    tmu.write_reg(addr::T_LOD, fixed_lod(5));
    tmu.write_reg(addr::TEX_BASE_ADDR, 0);
    tmu.write_texture(addr16(5, 2, 2), 0xf800_001f);
    tmu.write_texture(addr16(5, 4, 2), 0x0000_07e0);
    tmu.write_texture(addr16(5, 0, 2), 0x0000_07e0);
    tmu.write_texture(addr16(5, 6, 2), 0xffff_ffff);
    // centre of texel (3, 2) of LOD 5 (32 LOD-0 texels each), one texel per pixel in X
    set_iter(
        &mut tmu,
        tex(3 * 32 + 16),
        tex(2 * 32 + 16),
        tex(32),
        tex(32),
        ONE_W,
    );
    tmu.begin_triangle::<R>();
    tmu
}

const RED: Rgba = Rgba {
    r: 255,
    g: 0,
    b: 0,
    a: 255,
};
const GREEN: Rgba = Rgba {
    r: 0,
    g: 255,
    b: 0,
    a: 255,
};
const BLUE: Rgba = Rgba {
    r: 0,
    g: 0,
    b: 255,
    a: 255,
};
const OPAQUE_BLACK: Rgba = Rgba {
    r: 0,
    g: 0,
    b: 0,
    a: 255,
};

#[test]
fn point_sampling_and_wrap() {
    let mut tmu = rgb565_8x8(0);
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), RED);
    assert_eq!(tmu.texel::<R>(-1, 0, 0, 0, BLACK), BLUE);
    assert_eq!(tmu.texel::<R>(1, 0, 0, 0, BLACK), GREEN);
    assert_eq!(tmu.texel::<R>(2, 0, 0, 0, BLACK), OPAQUE_BLACK);
    // s = 8 wraps to 0
    assert_eq!(tmu.texel::<R>(5, 0, 0, 0, BLACK), GREEN);
    // t = 10 wraps to 2
    assert_eq!(tmu.texel::<R>(0, 8, 0, 0, BLACK), RED);
}

#[test]
fn point_sampling_clamp() {
    let mut tmu = rgb565_8x8(CLAMPS | CLAMPT);
    assert_eq!(tmu.texel::<R>(5, 0, 0, 0, BLACK), WHITE);
    assert_eq!(tmu.texel::<R>(-9, 0, 0, 0, BLACK), GREEN);
    // t clamps to 7: an empty row
    assert_eq!(tmu.texel::<R>(0, 8, 0, 0, BLACK), OPAQUE_BLACK);
}

#[test]
fn bilinear_four_bit_weights() {
    let mut tmu = rgb565_8x8(BILINEAR);
    // S = texel 3 centre + 9/32 of a LOD-5 texel: s fraction 0x48 -> 4-bit weight 4/16
    tmu.write_reg(addr::START_S, tex(3 * 32 + 16 + 9) as u32);
    tmu.begin_triangle::<R>();
    let c = tmu.texel::<R>(0, 0, 0, 0, BLACK);
    assert_eq!(
        c,
        Rgba {
            r: (255 * 12 * 16 / 256) as u8,
            g: (255 * 4 * 16 / 256) as u8,
            b: 0,
            a: 255
        }
    );
    // 8-bit weights (Voodoo 2 precision) see the full 0x48
    tmu.set_profile(TexelProfile {
        bilinear: BilinearPrecision::Bits8,
        ..Default::default()
    });
    assert_eq!(
        tmu.texel::<R>(0, 0, 0, 0, BLACK),
        Rgba {
            r: 183,
            g: 71,
            b: 0,
            a: 255
        }
    );
}

#[test]
fn bilinear_blends_in_t_and_clamps() {
    let mut tmu = rgb565_8x8(BILINEAR | CLAMPS);
    // half-way between rows 2 and 3 at texel 7's centre: (7, 2) is white and row 3 is
    // zero memory (RGB565 black, alpha ff)
    tmu.write_reg(addr::START_S, tex(7 * 32 + 16) as u32);
    tmu.write_reg(addr::START_T, tex(3 * 32) as u32);
    tmu.begin_triangle::<R>();
    assert_eq!(
        tmu.texel::<R>(0, 0, 0, 0, BLACK),
        Rgba {
            r: 127,
            g: 127,
            b: 127,
            a: 255
        }
    );
    // beyond the right edge both neighbours clamp to texel 7
    assert_eq!(
        tmu.texel::<R>(3, 0, 0, 0, BLACK),
        Rgba {
            r: 127,
            g: 127,
            b: 127,
            a: 255
        }
    );
}

#[test]
fn perspective_divide_and_tclampw() {
    let mut tmu = rgb565_8x8(PERSP);
    // S/W and T/W with W = 0.5
    set_iter(
        &mut tmu,
        tex((3 * 32 + 16) / 2),
        tex((2 * 32 + 16) / 2),
        tex(16),
        tex(16),
        1 << 29,
    );
    tmu.begin_triangle::<R>();
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), RED);
    assert_eq!(tmu.texel::<R>(-1, 0, 0, 0, BLACK), BLUE);
    // negative W: coordinates flip sign (wrap) unless tclampw forces them to 0
    tmu.write_reg(addr::START_W, (-(1i32 << 29)) as u32);
    tmu.write_reg(addr::START_S, tex(-(2 * 32 + 16) / 2) as u32);
    tmu.write_reg(addr::START_T, tex(-(2 * 32 + 16) / 2) as u32);
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), BLUE);
    tmu.write_reg(addr::TEXTURE_MODE, fmt(10) | DECAL | PERSP | CLAMPW);
    tmu.write_texture(addr16(5, 0, 0), 0x0000_f800);
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), RED);
}

#[test]
fn download_8bit_both_address_forms() {
    let mut tmu = Tmu::new(0, 4 << 20);
    tmu.write_reg(addr::TEXTURE_MODE, fmt(3));
    tmu.write_reg(addr::T_LOD, fixed_lod(5));
    // LOD 5 of an 8-bit square chain at 0: 0x10000 + 0x4000 + 0x1000 + 0x400 + 0x100
    let lod5 = 0x15500;
    // seq_8_downld = 0: S[7:2] at address bits 8:3 (bit 2 ignored)
    tmu.write_texture((5 << 17) | (3 << 9) | (4 << 1) | 4, 0x4433_2211);
    assert_eq!(
        &tmu.memory()[lod5 + 24..lod5 + 32],
        &[0, 0, 0, 0, 0x11, 0x22, 0x33, 0x44]
    );
    // seq_8_downld = 1: S[7:2] at address bits 7:2
    tmu.write_reg(addr::TEXTURE_MODE, fmt(3) | 0x8000_0000);
    tmu.write_texture((5 << 17) | (4 << 9) | 4, 0x8877_6655);
    assert_eq!(
        &tmu.memory()[lod5 + 32..lod5 + 40],
        &[0, 0, 0, 0, 0x55, 0x66, 0x77, 0x88]
    );
}

#[test]
fn download_narrow_maps_inhibit_upper_texels() {
    let mut tmu = Tmu::new(0, 4 << 20);
    tmu.write_reg(addr::TEXTURE_MODE, fmt(10));
    // 16-bit 1x1 (LOD 8) at 0x2aaa8: only the low half is written
    tmu.write_texture(8 << 17, 0xbbbb_aaaa);
    assert_eq!(&tmu.memory()[0x2aaa8..0x2aaac], &[0xaa, 0xaa, 0, 0]);
    // 8-bit 2x2 (LOD 7) at 0x15550: row 1 gets two bytes only
    tmu.write_reg(addr::TEXTURE_MODE, fmt(3));
    tmu.write_texture((7 << 17) | (1 << 9), 0x4433_2211);
    assert_eq!(&tmu.memory()[0x15550..0x15555], &[0, 0, 0x11, 0x22, 0]);
}

#[test]
fn download_swizzle_and_swap() {
    let mut tmu = Tmu::new(0, 1 << 20);
    tmu.write_reg(addr::TEXTURE_MODE, fmt(10));
    tmu.write_reg(addr::T_LOD, 1 << 25);
    tmu.write_texture(0, 0x1122_3344);
    assert_eq!(&tmu.memory()[0..4], &[0x11, 0x22, 0x33, 0x44]);
    tmu.write_reg(addr::T_LOD, 1 << 26);
    tmu.write_texture(0, 0x1122_3344);
    assert_eq!(&tmu.memory()[0..4], &[0x22, 0x11, 0x44, 0x33]);
    tmu.write_reg(addr::T_LOD, 3 << 25);
    tmu.write_texture(0, 0x1122_3344);
    assert_eq!(&tmu.memory()[0..4], &[0x33, 0x44, 0x11, 0x22]);
    // LOD above 8 is ignored
    tmu.write_texture(9 << 17, 0xffff_ffff);
    assert!(tmu.memory().iter().skip(4).all(|&b| b == 0));
}

#[test]
fn download_multibase_lod1() {
    let mut tmu = Tmu::new(0, 4 << 20);
    tmu.write_reg(addr::TEXTURE_MODE, fmt(10));
    tmu.write_reg(addr::T_LOD, 1 << 24);
    tmu.write_reg(addr::TEX_BASE_ADDR_1, 0x8000);
    tmu.write_texture(addr16(1, 2, 1), 0x1234_5678);
    // LOD 1 is 128 wide: texel (2, 1) at 0x40000 + (128 + 2) * 2
    assert_eq!(&tmu.memory()[0x40104..0x40108], &[0x78, 0x56, 0x34, 0x12]);
}

/// A square AI88 mipmap chain whose texel (0, 0) of LOD n has intensity n * 20.
fn mip_chain(t_lod: u32) -> Tmu {
    let mut tmu = Tmu::new(0, 4 << 20);
    tmu.write_reg(addr::TEXTURE_MODE, fmt(13) | DECAL);
    tmu.write_reg(addr::T_LOD, t_lod);
    for lod in 0..=8 {
        tmu.write_texture(addr16(lod, 0, 0), 0xff00 | (lod * 20));
    }
    tmu
}

fn at_gradient(tmu: &mut Tmu, log2: u32) -> u8 {
    set_iter(tmu, 0, 0, tex(1 << log2), tex(1 << log2), ONE_W);
    tmu.begin_triangle::<R>();
    tmu.texel::<R>(0, 0, 0, 0, BLACK).r
}

#[test]
fn lod_from_gradients_bias_and_clamp() {
    let mut tmu = mip_chain(0x20 << 6);
    for k in 0..=8 {
        assert_eq!(at_gradient(&mut tmu, k), (k * 20) as u8, "LOD {k}");
    }
    // bias +1.0 (4.2 signed: 4), capped at 8
    tmu.write_reg(addr::T_LOD, (0x20 << 6) | (4 << 12));
    assert_eq!(at_gradient(&mut tmu, 2), 60);
    assert_eq!(at_gradient(&mut tmu, 8), 160);
    // lodmin 3, lodmax 5
    tmu.write_reg(addr::T_LOD, 12 | (20 << 6));
    assert_eq!(at_gradient(&mut tmu, 0), 60);
    assert_eq!(at_gradient(&mut tmu, 7), 100);
}

#[test]
fn lod_dither_adds_matrix_sixteenths() {
    // LOD 1.5 via bias 0.5: dither at (0, 0) adds 0, at (1, 0) adds 8/16 -> LOD 2
    let mut tmu = mip_chain((0x20 << 6) | (2 << 12));
    tmu.write_reg(addr::TEXTURE_MODE, fmt(13) | DECAL | 0x10);
    set_iter(&mut tmu, 0, 0, tex(2), tex(2), ONE_W);
    tmu.begin_triangle::<R>();
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK).r, 20);
    assert_eq!(tmu.texel::<R>(0, 0, 1, 0, BLACK).r, 40);
    tmu.set_profile(TexelProfile {
        lod_dither: LodDither::Off,
        ..Default::default()
    });
    assert_eq!(tmu.texel::<R>(0, 0, 1, 0, BLACK).r, 20);
}

#[test]
fn split_odd_texture_takes_next_level() {
    // odd levels only: LOD 2.0 reads LOD 3
    let mut tmu = mip_chain((0x20 << 6) | (1 << 19) | (1 << 18));
    assert_eq!(at_gradient(&mut tmu, 2), 60);
    assert_eq!(at_gradient(&mut tmu, 3), 60);
    assert_eq!(at_gradient(&mut tmu, 0), 20);
}

#[test]
fn trilinear_reverses_blend_on_odd_lods() {
    // combine: c_other * (~lodfrac + 1) >> 8; the local texel is unused
    let mode = fmt(13) | (5 << 14) | (5 << 23) | (1 << 30);
    let mut tmu = mip_chain((0x20 << 6) | (2 << 12));
    tmu.write_reg(addr::TEXTURE_MODE, mode);
    set_iter(&mut tmu, 0, 0, tex(2), tex(2), ONE_W); // LOD 1.5, odd
    tmu.begin_triangle::<R>();
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, WHITE).r, 128);
    set_iter(&mut tmu, 0, 0, tex(4), tex(4), ONE_W); // LOD 2.5, even
    tmu.begin_triangle::<R>();
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, WHITE).r, 127);
    // without the trilinear bit, or with the MAME/DOSBox profile, odd LODs blend normally
    set_iter(&mut tmu, 0, 0, tex(2), tex(2), ONE_W);
    tmu.begin_triangle::<R>();
    tmu.set_profile(TexelProfile {
        trilinear: Trilinear::Ignored,
        ..Default::default()
    });
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, WHITE).r, 127);
    tmu.set_profile(TexelProfile::default());
    tmu.write_reg(addr::TEXTURE_MODE, mode & !(1 << 30));
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, WHITE).r, 127);
}

/// A `lodmin` field above 8.0 (here 13.5, field 54, with `lodmax` 7.25) gives LOD 8.0:
/// level 8, an even LOD for trilinear and a zero fraction, whatever the gradients.
#[test]
fn lodmin_above_eight_is_lod_eight() {
    // combine: c_other * (~lodfrac + 1) >> 8, reversed on odd LODs; the local texel unused
    let mode = fmt(13) | (5 << 14) | (5 << 23) | (1 << 30);
    let mut tmu = mip_chain(54 | (29 << 6));
    tmu.write_reg(addr::TEXTURE_MODE, fmt(13) | DECAL);
    assert_eq!(at_gradient(&mut tmu, 0), 160, "level 8");
    tmu.write_reg(addr::TEXTURE_MODE, mode);
    set_iter(&mut tmu, 0, 0, tex(1), tex(1), ONE_W);
    tmu.begin_triangle::<R>();
    // LOD 8.0, fraction 0, even: 255 * (0 ^ 0xff) + 1 >> 8 = 255. Taken as 13.5 it would
    // be odd with fraction 0x80: 255 * (0x80 + 1) >> 8 = 128.
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, WHITE).r, 255);
}

#[test]
fn lod_zerofrac_profile() {
    let mode = fmt(13) | (5 << 14) | (5 << 23) | (1 << 17) | (1 << 26);
    // LOD 1.5, reversed blend by the LOD fraction: 255 * 0x81 >> 8
    let mut tmu = mip_chain((0x20 << 6) | (2 << 12) | (1 << 23));
    tmu.write_reg(addr::TEXTURE_MODE, mode);
    set_iter(&mut tmu, 0, 0, tex(2), tex(2), ONE_W);
    tmu.begin_triangle::<R>();
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, WHITE).r, 128);
    tmu.set_profile(TexelProfile {
        lod_zerofrac: LodZeroFrac::Spec,
        ..Default::default()
    });
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, WHITE).r, 0);
}

/// An 8-bit texture of one texel at LOD 8 with raw value `raw`, format `f`.
fn one_texel(f: u32, raw: u8) -> Tmu {
    let mut tmu = Tmu::new(0, 1 << 20);
    tmu.write_reg(addr::TEXTURE_MODE, fmt(f) | DECAL);
    tmu.write_reg(addr::T_LOD, fixed_lod(8));
    tmu.write_texture(8 << 17, u32::from(raw));
    set_iter(&mut tmu, 0, 0, tex(1), tex(1), ONE_W);
    tmu.begin_triangle::<R>();
    tmu
}

#[test]
fn ncc_tables_through_registers() {
    let mut tmu = one_texel(1, 0x12); // y = 1, i = 0, q = 2
    tmu.write_reg(addr::NCC_TABLE1, 0x0000_5000); // Y1 = 0x50
    tmu.write_reg(addr::NCC_TABLE1 + 4 * 4, (10 << 18) | (20 << 9) | 30); // I0
    tmu.write_reg(addr::NCC_TABLE1 + 10 * 4, (0x1ff << 18) | (0x1fe << 9) | 1); // Q2 -1,-2,+1
                                                                                // table 0 is still selected and empty
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), OPAQUE_BLACK);
    tmu.write_reg(addr::TEXTURE_MODE, fmt(1) | DECAL | 0x20);
    assert_eq!(
        tmu.texel::<R>(0, 0, 0, 0, BLACK),
        Rgba {
            r: 0x59,
            g: 0x62,
            b: 0x6f,
            a: 0xff
        }
    );
    // AYIQ8422 takes alpha from the high byte
    tmu.write_reg(addr::TEXTURE_MODE, fmt(9) | DECAL | 0x20);
    tmu.write_texture(8 << 17, 0x0000_c012);
    assert_eq!(
        tmu.texel::<R>(0, 0, 0, 0, BLACK),
        Rgba {
            r: 0x59,
            g: 0x62,
            b: 0x6f,
            a: 0xc0
        }
    );
}

#[test]
fn ncc_update_deferred_profile() {
    let mut tmu = one_texel(1, 0x10);
    tmu.set_profile(TexelProfile {
        ncc_update: NccUpdate::OnTextureRegWrite,
        ..Default::default()
    });
    tmu.write_reg(addr::NCC_TABLE0, 0x0000_7700);
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), OPAQUE_BLACK);
    tmu.write_reg(addr::T_DETAIL, 0);
    assert_eq!(
        tmu.texel::<R>(0, 0, 0, 0, BLACK),
        Rgba {
            r: 0x77,
            g: 0x77,
            b: 0x77,
            a: 0xff
        }
    );
}

#[test]
fn palette_writes_through_ncc0_iq() {
    let mut tmu = one_texel(5, 7);
    // I3 (odd word): entry {3, 1} = 7; the NCC table is not written
    tmu.write_reg(addr::NCC_TABLE0 + 7 * 4, 0x8312_3456);
    assert_eq!(
        tmu.texel::<R>(0, 0, 0, 0, BLACK),
        Rgba {
            r: 0x12,
            g: 0x34,
            b: 0x56,
            a: 0xff
        }
    );
    assert_eq!(tmu.ncc_regs[0][7], 0);
    // the same value on table 1 is an NCC write
    tmu.write_reg(addr::NCC_TABLE1 + 7 * 4, 0x8312_3456);
    assert_eq!(tmu.ncc_regs[1][7], 0x8312_3456);
    // AP88
    tmu.write_reg(addr::TEXTURE_MODE, fmt(14) | DECAL);
    tmu.write_texture(8 << 17, 0x0000_4007);
    assert_eq!(
        tmu.texel::<R>(0, 0, 0, 0, BLACK),
        Rgba {
            r: 0x12,
            g: 0x34,
            b: 0x56,
            a: 0x40
        }
    );
}

#[test]
fn eight_bit_formats_through_the_pipeline() {
    assert_eq!(
        one_texel(2, 0x5a).texel::<R>(0, 0, 0, 0, BLACK),
        rgba([0x5a; 4])
    );
    assert_eq!(
        one_texel(3, 0x5a).texel::<R>(0, 0, 0, 0, BLACK),
        rgba([0x5a, 0x5a, 0x5a, 0xff])
    );
    assert_eq!(
        one_texel(4, 0x5a).texel::<R>(0, 0, 0, 0, BLACK),
        rgba([0xaa, 0xaa, 0xaa, 0x55])
    );
    assert_eq!(
        one_texel(0, 0xe0).texel::<R>(0, 0, 0, 0, BLACK),
        rgba([0xff, 0, 0, 0xff])
    );
}

#[test]
fn subpixel_adjust_writes_back() {
    let mut tmu = Tmu::new(0, 1 << 20);
    tmu.write_reg(addr::START_S, 0);
    tmu.write_reg(addr::D_S_DX, tex(1) as u32);
    tmu.write_reg(addr::D_S_DY, tex(2) as u32);
    tmu.write_reg(addr::START_W, ONE_W as u32);
    tmu.write_reg(addr::D_W_DX, (1 << 26) as u32);
    // dx = 0.5, dy = 0.25 (12.4)
    tmu.subpixel_adjust(8, 4);
    assert_eq!(tmu.stw.rows[crate::stw::START][0], 1 << 32);
    assert_eq!(tmu.stw.rows[crate::stw::START][2], (1 << 32) + (1 << 27));
    tmu.subpixel_adjust(8, 4);
    assert_eq!(tmu.stw.rows[crate::stw::START][0], 2 << 32);
}

#[test]
fn float_registers_keep_32_fraction_bits() {
    let mut tmu = Tmu::new(0, 1 << 20);
    tmu.write_reg(addr::F_START_S, 1.5f32.to_bits());
    tmu.write_reg(addr::F_START_T, (-0.25f32).to_bits());
    tmu.write_reg(addr::F_START_W, 0.0f32.to_bits());
    tmu.write_reg(addr::F_D_S_DX, (1.0f32 / 3.0).to_bits());
    tmu.write_reg(addr::F_D_W_DY, 2.0f32.to_bits());
    assert_eq!(tmu.stw.rows[crate::stw::START], [3 << 31, -(1 << 30), 0]);
    // 1/3 as a float is 0xaaaaab / 2^25: 0x5555_5580 in .32
    assert_eq!(tmu.stw.rows[crate::stw::DX][0], 0x5555_5580);
    assert_eq!(tmu.stw.rows[crate::stw::DY][2], 2 << 32);
    // the fixed registers: 14.18 and 2.30
    tmu.write_reg(addr::START_S, (-3i32 << 17) as u32);
    tmu.write_reg(addr::D_W_DX, (1 << 29) as u32);
    assert_eq!(tmu.stw.rows[crate::stw::START][0], -3 << 31);
    assert_eq!(tmu.stw.rows[crate::stw::DX][2], 1 << 31);
}

#[test]
fn odd_memory_sizes_round_up() {
    assert_eq!(Tmu::new(1, 3 << 20).memory().len(), 4 << 20);
    assert_eq!(Tmu::new(2, 0).memory().len(), 1 << 20);
    assert_eq!(Tmu::new(2, 64 << 20).memory().len(), 4 << 20);
}

#[test]
fn other_tmu_passes_through_combine() {
    // textureMode 0: c_other passes unchanged (factor 0xff + 1)
    let mut tmu = one_texel(3, 0x10);
    tmu.write_reg(addr::TEXTURE_MODE, fmt(3));
    let c = Rgba {
        r: 1,
        g: 2,
        b: 3,
        a: 4,
    };
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, c), c);
}

#[test]
fn coordinate_rounding_profile() {
    // S a hair below zero (-1/2^18 of a LOD-0 texel) on row 2: floor selects texel -1,
    // which wraps to texel 7 (white); truncation selects texel 0 (green).
    for persp in [0, PERSP] {
        let mut tmu = rgb565_8x8(persp);
        set_iter(&mut tmu, -1, tex(2 * 32 + 16), tex(32), tex(32), ONE_W);
        tmu.begin_triangle::<R>();
        assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), WHITE, "persp {persp}");
        tmu.set_profile(TexelProfile {
            coord_rounding: CoordRounding::TowardZero,
            ..TexelProfile::default()
        });
        assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), GREEN, "persp {persp}");
        // Exactly zero is texel 0 either way.
        tmu.write_reg(addr::START_S, 0);
        assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), GREEN, "persp {persp}");
    }
}

#[test]
fn decal_invert_profile() {
    // Decal with both invert bits: the default passes the texel unchanged.
    let invert = (1 << 20) | (1 << 29);
    let mut tmu = rgb565_8x8(invert);
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), RED);
    tmu.set_profile(TexelProfile {
        decal_invert: DecalInvert::Applied,
        ..TexelProfile::default()
    });
    assert_eq!(
        tmu.texel::<R>(0, 0, 0, 0, BLACK),
        Rgba {
            r: 0,
            g: 255,
            b: 255,
            a: 0
        }
    );
    // Not a decal (alpha adds nothing): the invert applies under the default too.
    let mut tmu = rgb565_8x8(invert);
    let mode = (fmt(10) | DECAL | invert) & !(1 << 27);
    tmu.write_reg(addr::TEXTURE_MODE, mode);
    assert_eq!(
        tmu.texel::<R>(0, 0, 0, 0, BLACK),
        Rgba {
            r: 0,
            g: 255,
            b: 255,
            a: 255
        }
    );
}

#[test]
fn persp_divide_profile() {
    // W = 0.75, S / W = 128 LOD-0 texels exactly: the left edge of texel 4 (green) of
    // LOD 5. DOSBox's table reciprocal of 0.75 is 43690 / 2^15, a little below 4/3, so
    // it lands in texel 3 (red).
    let mut tmu = rgb565_8x8(PERSP);
    set_iter(&mut tmu, tex(96), tex(60), tex(24), tex(24), 3 << 28);
    tmu.begin_triangle::<R>();
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), GREEN);
    tmu.set_profile(TexelProfile {
        persp_divide: PerspDivide::DosboxReciprocal,
        ..TexelProfile::default()
    });
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), RED);
}

/// Every write that changes a texel reaches the next triangle through the decoded-texel
/// cache; writes that change nothing keep the decoded level.
#[test]
fn texel_cache_sees_every_write_and_keeps_what_is_unchanged() {
    let mut tmu = rgb565_8x8(0);
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), RED);
    assert!(tmu.cache.has(5));

    // A download elsewhere (LOD 4) keeps LOD 5; one over texel (3, 2) drops it.
    tmu.write_texture(addr16(4, 0, 0), 0xffff_ffff);
    assert!(tmu.cache.has(5));
    tmu.write_texture(addr16(5, 2, 2), 0x001f_f800);
    assert!(!tmu.cache.has(5));
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), BLUE);
    assert_eq!(tmu.texel::<R>(-1, 0, 0, 0, BLACK), RED);

    // Combine bits and tDetail leave the texels alone.
    tmu.write_reg(addr::TEXTURE_MODE, fmt(10) | DECAL | BILINEAR);
    tmu.write_reg(addr::T_DETAIL, 0x1234);
    tmu.write_reg(addr::TEXTURE_MODE, fmt(10) | DECAL);
    assert!(tmu.cache.has(5));
    // An NCC table write does not change RGB565 texels.
    tmu.write_reg(addr::NCC_TABLE0, 0x0000_7700);
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), BLUE);
    assert!(tmu.cache.has(5));

    // A new base address moves the texture: texel (3, 2) now reads LOD 5 of a chain 8
    // bytes higher, i.e. the stored texel (7, 2) (white).
    tmu.write_reg(addr::TEX_BASE_ADDR, 1);
    assert!(!tmu.cache.has(5));
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), WHITE);
    // A format change re-decodes the same bytes: 0xffff as ARGB1555.
    tmu.write_reg(addr::TEXTURE_MODE, fmt(11) | DECAL);
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), WHITE);
    tmu.write_reg(addr::TEXTURE_MODE, fmt(12) | DECAL);
    tmu.write_reg(addr::TEX_BASE_ADDR, 0);
    // 0xf800 (texel (2, 2) after the rewrite above) as ARGB4444: a=f, r=8, g=b=0.
    assert_eq!(tmu.texel::<R>(-1, 0, 0, 0, BLACK), rgba([0x88, 0, 0, 0xff]));
}

/// Palette writes reach P8 texels already decoded; the cached and the generic path
/// sample every texel of a level alike.
#[test]
fn texel_cache_palette_and_reference_path_agree() {
    let mut tmu = one_texel(5, 7);
    tmu.write_reg(addr::NCC_TABLE0 + 7 * 4, 0x8312_3456);
    assert_eq!(
        tmu.texel::<R>(0, 0, 0, 0, BLACK),
        rgba([0x12, 0x34, 0x56, 0xff])
    );
    tmu.write_reg(addr::NCC_TABLE0 + 7 * 4, 0x8365_4321);
    assert_eq!(
        tmu.texel::<R>(0, 0, 0, 0, BLACK),
        rgba([0x65, 0x43, 0x21, 0xff])
    );

    let mut cached = rgb565_8x8(BILINEAR);
    let mut reference = rgb565_8x8(BILINEAR);
    reference.set_generic_path(true);
    for dy in -9..9 {
        for dx in -9..9 {
            assert_eq!(
                cached.texel::<R>(dx, dy, dx, dy, BLACK),
                reference.texel::<R>(dx, dy, dx, dy, BLACK),
                "({dx}, {dy})"
            );
        }
    }
    assert!(cached.cache.has(5) && !reference.cache.has(5));
}

#[test]
fn box86_divide_arithmetic() {
    use crate::sample::{box86_divide, box86_oow};
    // 2^48 / W (.32), truncated; W <= 0 gives 0.
    assert_eq!(box86_oow(1 << 32), 1 << 16);
    assert_eq!(box86_oow(3 << 30), 87381); // 2^18 / 3 = 87381.33
    assert_eq!(box86_oow(0), 0);
    assert_eq!(box86_oow(-(1 << 32)), 0);
    // 128 / 0.75 = 170.67 texels: (2^25 * 87381 + 2^29) >> 30 = 2731 sixteenths, as 24.8.
    assert_eq!(box86_divide(128 << 32, 87381), 2731 << 4);
    // Rounded to the nearest 1/16 texel, halves up: 1 + 1/32 -> 17/16; a hair less -> 16/16.
    assert_eq!(box86_divide((1 << 32) + (1 << 27), 1 << 16), 17 << 4);
    assert_eq!(
        box86_divide((1 << 32) + (1 << 27) - (1 << 14), 1 << 16),
        16 << 4
    );
    // S is first rounded to .18 with an arithmetic shift: -1 texel stays -16 sixteenths.
    assert_eq!(box86_divide(-(1 << 32), 1 << 16), -16 << 4);
}

#[test]
fn persp_divide_box86_profile() {
    // W = 1, S = 128 - 1/1024 LOD-0 texels: a hair left of texel 4 (green) of LOD 5.
    // MAME's truncated quotient stays in texel 3 (red); 86Box rounds it to 128.0.
    let mut tmu = rgb565_8x8(PERSP);
    set_iter(&mut tmu, tex(128) - 256, tex(80), tex(32), tex(32), ONE_W);
    tmu.begin_triangle::<R>();
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), RED);
    tmu.set_profile(TexelProfile {
        persp_divide: PerspDivide::Box86,
        ..TexelProfile::default()
    });
    assert_eq!(tmu.texel::<R>(0, 0, 0, 0, BLACK), GREEN);
}

/// `NccQ2Write`: table 0's Q2 (register word 10) lands in Q2, or in I2 as 86Box stores it.
#[test]
fn ncc_table0_q2_write_target() {
    let q2 = addr::NCC_TABLE0 + 10 * 4;
    for (choice, word) in [(NccQ2Write::Q2, 10), (NccQ2Write::IntoI2, 6)] {
        let mut tmu = Tmu::new(0, 1 << 20);
        tmu.set_profile(TexelProfile {
            ncc_q2: choice,
            ..Default::default()
        });
        tmu.write_reg(q2, 0x0123_4567);
        let mut expected = [0u32; 12];
        expected[word] = 0x0123_4567;
        assert_eq!(tmu.ncc_regs[0], expected, "{choice:?}");
        // Table 1's Q2 is never redirected.
        tmu.write_reg(addr::NCC_TABLE1 + 10 * 4, 0x89);
        assert_eq!(tmu.ncc_regs[1][10], 0x89, "{choice:?}");
    }
}

/// `TextureCacheKey`: an 8-bit texel 0x5a read as I8, then the same memory bound as A8
/// without a download. Exact: A8's (0x5a, 0x5a, 0x5a, 0x5a). 86Box: the I8 decode is found
/// by base address and tLOD and reused, (0x5a, 0x5a, 0x5a, 0xff), until a download into the
/// texture drops it.
#[test]
fn texture_cache_key_choices() {
    let sample = |tmu: &mut Tmu| {
        tmu.begin_triangle::<R>();
        tmu.texel::<R>(0, 0, 0, 0, BLACK)
    };
    for (choice, stale) in [
        (TextureCacheKey::Exact, false),
        (TextureCacheKey::Box86, true),
    ] {
        let mut tmu = Tmu::new(0, 1 << 20);
        tmu.set_profile(TexelProfile {
            texture_cache: choice,
            ..Default::default()
        });
        tmu.write_reg(addr::TEXTURE_MODE, fmt(3) | DECAL);
        tmu.write_reg(addr::T_LOD, fixed_lod(8));
        tmu.write_reg(addr::TEX_BASE_ADDR, 0);
        tmu.write_texture(8 << 17, 0x5a5a_5a5a);
        set_iter(&mut tmu, 0, 0, 0, 0, ONE_W);
        assert_eq!(
            sample(&mut tmu),
            rgba([0x5a, 0x5a, 0x5a, 0xff]),
            "{choice:?}"
        );
        tmu.write_reg(addr::TEXTURE_MODE, fmt(2) | DECAL);
        let a8 = rgba([0x5a, 0x5a, 0x5a, if stale { 0xff } else { 0x5a }]);
        assert_eq!(sample(&mut tmu), a8, "{choice:?}");
        // A download into the texture drops 86Box's entry: A8 from then on.
        tmu.write_texture(8 << 17, 0x6b6b_6b6b);
        assert_eq!(sample(&mut tmu), rgba([0x6b; 4]), "{choice:?}");
    }
}

/// The hardware model's profile is every switch's `#[default]` variant, so that the
/// enums' own documentation of the default and the model cannot disagree.
#[test]
fn hardware_is_every_switch_default() {
    let d = TexelProfile {
        lod: Default::default(),
        lod_dither: Default::default(),
        bilinear: Default::default(),
        a8: Default::default(),
        rgb332_blue: Default::default(),
        filter_select: Default::default(),
        detail: Default::default(),
        ncc_q2: Default::default(),
        chain: Default::default(),
        texture_cache: Default::default(),
        ncc_update: Default::default(),
        trilinear: Default::default(),
        lod_zerofrac: Default::default(),
        coord_rounding: Default::default(),
        decal_invert: Default::default(),
        persp_divide: Default::default(),
    };
    assert_eq!(TexelProfile::HARDWARE, d);
}

/// xorshift64*: a small seeded generator, so that a failure replays.
struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn u32(&mut self) -> u32 {
        (self.next() >> 32) as u32
    }

    /// 0..n.
    fn below(&mut self, n: u32) -> u32 {
        (self.next() % u64::from(n)) as u32
    }

    fn pick<T: Copy, const N: usize>(&mut self, v: [T; N]) -> T {
        v[self.below(N as u32) as usize]
    }

    /// A signed value of about `bits` significant bits.
    fn signed(&mut self, bits: u32) -> i32 {
        let v = (self.u32() >> (32 - bits.clamp(1, 32))) as i32;
        if self.below(2) == 0 {
            v
        } else {
            v.wrapping_neg()
        }
    }
}

/// A profile with every switch random.
fn random_profile(rng: &mut XorShift) -> TexelProfile {
    TexelProfile {
        lod: rng.pick([LodCalc::Mame, LodCalc::Dosbox, LodCalc::Box86]),
        lod_dither: rng.pick([LodDither::Matrix4x4, LodDither::Off]),
        bilinear: rng.pick([BilinearPrecision::Bits4, BilinearPrecision::Bits8]),
        a8: rng.pick([A8Expansion::AlphaInRgb, A8Expansion::WhiteRgb]),
        rgb332_blue: rng.pick([Rgb332Blue::Replicated, Rgb332Blue::DosboxTable]),
        filter_select: rng.pick([FilterSelect::ByLod, FilterSelect::EitherBit]),
        detail: rng.pick([
            DetailRule::WholeLods,
            DetailRule::WholeLodsCut8,
            DetailRule::IntegerLod,
        ]),
        ncc_q2: rng.pick([NccQ2Write::Q2, NccQ2Write::IntoI2]),
        chain: ChainModel::Full,
        texture_cache: rng.pick([TextureCacheKey::Exact, TextureCacheKey::Box86]),
        ncc_update: rng.pick([NccUpdate::Immediate, NccUpdate::OnTextureRegWrite]),
        trilinear: rng.pick([Trilinear::Spec, Trilinear::Ignored]),
        lod_zerofrac: rng.pick([LodZeroFrac::Ignored, LodZeroFrac::Spec]),
        coord_rounding: rng.pick([CoordRounding::Floor, CoordRounding::TowardZero]),
        decal_invert: rng.pick([DecalInvert::Ignored, DecalInvert::Applied]),
        persp_divide: rng.pick([
            PerspDivide::Double,
            PerspDivide::DosboxReciprocal,
            PerspDivide::Box86,
        ]),
    }
}

/// Random texture registers, NCC tables and iterators, for a triangle.
fn random_state(tmu: &mut Tmu, rng: &mut XorShift) {
    // Every textureMode bit, the combine fields often Glide's usual ones.
    let mut mode = rng.u32();
    if rng.below(4) == 0 {
        mode = (mode & 0xfff) | DECAL;
    }
    tmu.write_reg(addr::TEXTURE_MODE, mode);
    tmu.write_reg(addr::T_LOD, rng.u32());
    tmu.write_reg(addr::T_DETAIL, rng.u32());
    for i in 0..4 {
        tmu.write_reg(addr::TEX_BASE_ADDR + 4 * i, rng.u32() & 0x7ffff);
    }
    for _ in 0..rng.below(8) {
        let word = rng.below(24);
        tmu.write_reg(addr::NCC_TABLE0 + 4 * word, rng.u32());
    }
    // S, T in 14.18 of various sizes; W near 1.0 or anywhere (through zero too).
    let sizes = [8, 16, 24, 28, 32];
    for reg in [addr::START_S, addr::START_T] {
        let bits = rng.pick(sizes);
        tmu.write_reg(reg, rng.signed(bits) as u32);
    }
    for reg in [addr::D_S_DX, addr::D_T_DX, addr::D_S_DY, addr::D_T_DY] {
        let bits = rng.pick(sizes);
        tmu.write_reg(reg, rng.signed(bits) as u32);
    }
    let w = if rng.below(3) == 0 {
        rng.u32() as i32
    } else {
        ONE_W / (1 + rng.below(64) as i32) + rng.signed(20)
    };
    tmu.write_reg(addr::START_W, w as u32);
    for reg in [addr::D_W_DX, addr::D_W_DY] {
        let bits = rng.pick([8, 16, 22, 26, 32]);
        tmu.write_reg(reg, rng.signed(bits) as u32);
    }
    if rng.below(4) == 0 {
        // The float aliases, with their 32 fraction bits.
        let f = |rng: &mut XorShift| ((rng.below(2000) as f32 - 1000.0) / 7.0).to_bits();
        tmu.write_reg(addr::F_START_S, f(rng));
        tmu.write_reg(addr::F_D_S_DX, f(rng));
    }
}

/// The span kernels ([`Tmu::texels`]) give, in every live lane, the texel [`Tmu::texel`]
/// (or the uncombined and 86Box-upstream forms) gives for that pixel, over random
/// texture states, profiles, gradients, chunks, live masks and upstream colours; dead lanes
/// of the output are left alone.
#[test]
fn span_lanes_match_per_pixel_texels() {
    let mut rng = XorShift(0x0005_eed7_e571_a9e5);
    for memory in 0..6 {
        let mut tmu = Tmu::new(0, 1 << 20);
        for b in tmu.ram.iter_mut() {
            *b = rng.u32() as u8;
        }
        for state in 0..60 {
            tmu.set_profile(random_profile(&mut rng));
            random_state(&mut tmu, &mut rng);
            tmu.begin_triangle::<R>();
            for chunk in 0..6 {
                let n = 1 + rng.below(LANES as u32) as usize;
                let dx0 = rng.signed(9);
                let dy0 = rng.signed(9);
                let (x0, y0) = (rng.below(1024) as i32, rng.below(1024) as i32);
                // One span, or lanes each on a row of its own (as a chunk packed from
                // several short spans has them).
                let scattered: [Lanes; 4] =
                    core::array::from_fn(|_| core::array::from_fn(|_| rng.signed(9)));
                let place = if chunk % 2 == 0 {
                    LanePlace::Row {
                        dx0,
                        dy: dy0,
                        x0,
                        y: y0,
                    }
                } else {
                    let [dx, dy, x, y] = &scattered;
                    LanePlace::Lanes { dx, dy, x, y }
                };
                let density = rng.below(4);
                let alive: [bool; LANES] = core::array::from_fn(|_| rng.below(4) >= density);
                let other: ColourLanes =
                    core::array::from_fn(|_| core::array::from_fn(|_| rng.below(256) as i32));
                let what = match rng.below(4) {
                    0 => LaneOutput::Texel,
                    1 => LaneOutput::Box86Upstream(rng.u32()),
                    _ => LaneOutput::Combined(&other),
                };
                let mut out: ColourLanes = [[-1; LANES]; 4];
                // Both forms of the stages that have an AVX-512 one (`KernelCopy`).
                if chunk % 3 == 0 {
                    tmu.texels::<R, BaselineCopy>(place, &alive, n, what, &mut out);
                } else {
                    tmu.texels::<R, Avx512Copy>(place, &alive, n, what, &mut out);
                }
                for i in 0..LANES {
                    let got = [0, 1, 2, 3].map(|c| out[c][i]);
                    if i >= n || !alive[i] {
                        assert_eq!(got, [-1; 4], "dead lane {i} written");
                        continue;
                    }
                    let (dx, dy, x, y) = place.at(i);
                    let want = match what {
                        LaneOutput::Texel => tmu.texel_uncombined::<R>(dx, dy, x, y),
                        LaneOutput::Box86Upstream(m) => {
                            tmu.texel_box86_upstream::<R>(dx, dy, x, y, m)
                        }
                        LaneOutput::Combined(o) => {
                            let o = [0, 1, 2, 3].map(|c| o[c][i] as u8);
                            tmu.texel::<R>(dx, dy, x, y, rgba(o))
                        }
                    };
                    let want = [want.r, want.g, want.b, want.a].map(i32::from);
                    assert_eq!(
                        got, want,
                        "memory {memory} state {state} chunk {chunk} lane {i}: \
                         textureMode {:#010x} tLOD {:#010x} tDetail {:#010x} {:?}",
                        tmu.texture_mode, tmu.t_lod, tmu.t_detail, tmu.profile
                    );
                }
            }
        }
    }
}

#[test]
fn a_write_changes_the_tmu_exactly_where_it_stores_the_register() {
    // The board sends a TMU only the registers `Tmu::stores` names: every other write
    // must leave the whole state (as a save state holds it) as it was, and every named
    // one must change it. (Each value is also a float of moderate size, for the float
    // iterators: 3.14159 and -123.456.)
    for offset in (0..0x400u32).step_by(4) {
        for value in [0x4049_0fdbu32, 0xc2f6_e979] {
            let mut tmu = Tmu::new(0, 2 << 20);
            let before = tmu.save_state();
            tmu.write_reg(offset, value);
            let changed = tmu.save_state() != before;
            assert_eq!(changed, Tmu::stores(offset), "{offset:#x} = {value:#x}");
        }
    }
}

//! The chain's span entry point ([`TexelSource::texels`] for [`Chain`]) gives, in every
//! live lane, what [`TexelSource::texel`] gives for that pixel: 1, 2 and 3 TMUs, both
//! wirings ([`ChainModel::Full`], [`ChainModel::Box86`]), random texture states, memory,
//! gradients, chunks and live masks. Lanes that are not live are left alone.

use pixelfx::span::{Lanes, LANES};
use pixelfx::{LanePlace, TexelSource};
use sst1_chain::Chain;
use sst1_regs::addr;
use texelfx::{
    Avx512Copy, BaselineCopy, ChainModel, LodCalc, PerspDivide, RuntimeProfile, TexelProfile,
    TextureCacheKey, Tmu,
};

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

    fn below(&mut self, n: u32) -> u32 {
        (self.next() % u64::from(n)) as u32
    }

    fn pick<T: Copy, const N: usize>(&mut self, v: [T; N]) -> T {
        v[self.below(N as u32) as usize]
    }

    fn signed(&mut self, bits: u32) -> i32 {
        let v = (self.u32() >> (32 - bits)) as i32;
        if self.below(2) == 0 {
            v
        } else {
            v.wrapping_neg()
        }
    }
}

/// textureMode combine fields that output the local texel (Glide's "decal").
const DECAL: u32 = (1 << 12) | (1 << 18) | (1 << 21) | (1 << 27);

fn random_registers(tmu: &mut Tmu, rng: &mut XorShift) {
    let mut mode = rng.u32();
    match rng.below(6) {
        0 => mode = (mode & 0xfff) | DECAL,
        // Other times local, or other alone: the upstream output shows.
        3 => mode = (mode & 0xc000_0fff) | (0x48 << 12) | (0x48 << 21),
        4 => mode = (mode & 0xc000_0fff) | (0x02 << 12) | (0x06 << 21),
        // 86Box's local-decal pattern and an all-zero combine (its chain shortcuts).
        1 => mode = (mode & !0x0064_3000) | 0x0024_1000,
        2 => mode &= 0xc000_0fff,
        _ => {}
    }
    tmu.write_reg(addr::TEXTURE_MODE, mode);
    tmu.write_reg(addr::T_LOD, rng.u32());
    tmu.write_reg(addr::T_DETAIL, rng.u32());
    tmu.write_reg(addr::TEX_BASE_ADDR, rng.u32() & 0x7ffff);
    for reg in [addr::START_S, addr::START_T, addr::D_S_DX, addr::D_T_DY] {
        let bits = rng.pick([12, 20, 26, 31]);
        tmu.write_reg(reg, rng.signed(bits) as u32);
    }
    for reg in [addr::D_T_DX, addr::D_S_DY] {
        let bits = rng.pick([12, 20, 24]);
        tmu.write_reg(reg, rng.signed(bits) as u32);
    }
    tmu.write_reg(addr::START_W, (1 << 30) / (1 + rng.below(32)));
    for reg in [addr::D_W_DX, addr::D_W_DY] {
        let bits = rng.pick([8, 16, 22, 26]);
        tmu.write_reg(reg, rng.signed(bits) as u32);
    }
}

#[test]
fn chain_lanes_match_per_pixel_texels() {
    let mut rng = XorShift(0xc4a1_7e57);
    for count in 1..=3 {
        for wiring in [ChainModel::Full, ChainModel::Box86] {
            let mut tmus: Vec<Tmu> = (0..count).map(|i| Tmu::new(i, 1 << 20)).collect();
            for tmu in tmus.iter_mut() {
                // Texels for whatever formats and layouts the states pick: most of the
                // memory written.
                for _ in 0..8 {
                    random_registers(tmu, &mut rng);
                    for _ in 0..40_000 {
                        tmu.write_texture(rng.u32() & 0x1f_fffc, rng.u32());
                    }
                }
            }
            for state in 0..150 {
                let profile = TexelProfile {
                    chain: wiring,
                    lod: rng.pick([LodCalc::Mame, LodCalc::Dosbox, LodCalc::Box86]),
                    persp_divide: rng.pick([
                        PerspDivide::Double,
                        PerspDivide::DosboxReciprocal,
                        PerspDivide::Box86,
                    ]),
                    texture_cache: rng.pick([TextureCacheKey::Exact, TextureCacheKey::Box86]),
                    ..TexelProfile::HARDWARE
                };
                for tmu in tmus.iter_mut() {
                    tmu.set_profile(profile);
                    random_registers(tmu, &mut rng);
                    tmu.begin_triangle::<RuntimeProfile>();
                }
                let mut chain = Chain::<RuntimeProfile>::new(&mut tmus);
                for chunk in 0..8 {
                    let n = 1 + rng.below(LANES as u32) as usize;
                    let (dx0, dy0) = (rng.signed(8), rng.signed(8));
                    let (x0, y0) = (rng.below(640) as i32, rng.below(480) as i32);
                    // One span, or every lane on a row of its own (a packed chunk).
                    let scattered: [Lanes; 4] =
                        core::array::from_fn(|_| core::array::from_fn(|_| rng.signed(8)));
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
                    let alive: [bool; LANES] = core::array::from_fn(|_| rng.below(5) != 0);
                    let mut out: [Lanes; 4] = [[-1; LANES]; 4];
                    // Both forms of the stages that have an AVX-512 one (`KernelCopy`).
                    if chunk % 3 == 0 {
                        chain.texels::<BaselineCopy>(place, &alive, n, &mut out);
                    } else {
                        chain.texels::<Avx512Copy>(place, &alive, n, &mut out);
                    }
                    for i in 0..LANES {
                        let got = [0, 1, 2, 3].map(|c| out[c][i]);
                        if i >= n || !alive[i] {
                            assert_eq!(got, [-1; 4], "dead lane {i} written");
                            continue;
                        }
                        let (dx, dy, x, y) = place.at(i);
                        let t = chain.texel(dx, dy, x, y);
                        let want = [t.r, t.g, t.b, t.a].map(i32::from);
                        assert_eq!(
                            got, want,
                            "{count} TMUs, {wiring:?}, state {state} chunk {chunk} lane {i}"
                        );
                    }
                }
            }
        }
    }
}

//! Texture coordinate computation and texel fetch: perspective divide, `tclampw`, LOD,
//! clamp/wrap, point sampling and bilinear filtering (spec 5.50, 5.51).
//!
//! Coordinates become 24.8 texels of LOD 0: `S/W * 256` with a double-precision divide when
//! `tpersp_st` is set, else `S >> 24` (rounded as [`crate::CoordRounding`] says), then are
//! shifted down by
//! the integer LOD. Point sampling drops the fraction; bilinear first subtracts half a texel
//! and weighs the four neighbours by the top 4 bits of each fraction (the SST-1 keeps 4
//! bits; Voodoo 2 keeps 8).
//!
//! Filter choice: `tmagfilter` when the clamped LOD equals `lodmin` (the texture is
//! magnified), `tminfilter` otherwise. The spec's prose says the reverse, but its figure and
//! all three references use this rule.
//!
//! Source: MAME `rasterizer_texture::fetch_texel` (DOSBox Staging `TEXTURE_PIPELINE` is the
//! older form of the same code; 86Box uses the same 4-bit weights).

use crate::format::Lookups;
use crate::lod::{f64_to_i32_x86, pixel_lod, PixelLod};
use crate::{BilinearPrecision, CoordRounding, LodZeroFrac, Tmu};
use sst1_regs::{TLod, TextureMode};

/// What decoding the texels of one fetch needs, gathered once per pixel.
struct Fetch<'a> {
    /// `tformat`.
    format: u32,
    /// Tables for the formats that use them.
    lookups: Lookups<'a>,
}

/// The result of one texel fetch.
pub(crate) struct Sample {
    /// The filtered texel, `[r, g, b, a]`.
    pub texel: [u8; 4],
    /// The clamped LOD, 8.8.
    pub lod: i32,
    /// The LOD fraction the combine unit sees (0 with `lod_zerofrac` when honoured).
    pub lod_fraction: u8,
    /// The integer LOD (before skipping a level the TMU does not hold) is odd.
    pub odd_lod: bool,
}

impl Tmu {
    /// Fetches the texel for iterated S, T (.32, i.e. 14.18 << 14) and W (.32, 2.30 << 2).
    pub(crate) fn sample(&self, iters: i64, itert: i64, iterw: i64, x: i32, y: i32) -> Sample {
        let mode = TextureMode(self.texture_mode);
        let persp = mode.tpersp_st();
        let floor = self.profile.coord_rounding == CoordRounding::Floor;
        let (mut s, mut t) = if persp {
            let recip = 256.0 / iterw as f64;
            let div = |v: i64| {
                let q = v as f64 * recip;
                let i = f64_to_i32_x86(q);
                // Floor: one less where truncation went up (negative, inexact, in range).
                if floor && (i as f64) > q && i != i32::MIN {
                    i - 1
                } else {
                    i
                }
            };
            (div(iters), div(itert))
        } else if floor {
            // Source: DOSBox `(int32_t)(ITERS >> 14)`, 86Box `tmu0_s >> 28`: arithmetic
            // shifts that keep the low bits when the value does not fit.
            ((iters >> 24) as i32, (itert >> 24) as i32)
        } else {
            let to_i32 = |v: i64| i32::try_from(v / (1 << 24)).unwrap_or(i32::MIN);
            (to_i32(iters), to_i32(itert))
        };
        if mode.tclampw() && iterw < 0 {
            s = 0;
            t = 0;
        }

        let p = PixelLod {
            base: self.lod_base,
            persp_w: persp.then_some(iterw),
            x,
            y,
        };
        let dither = mode.tloddither();
        let lod = pixel_lod(
            self.profile.lod,
            self.profile.lod_dither,
            &p,
            self.t_lod,
            dither,
        );
        let lodmin = (TLod(self.t_lod).lodmin() << 6) as i32;
        // lod >= 0 after the clamp, so the integer part is 0..=8.
        let ilod_raw = (lod >> 8) as usize;
        let mut ilod = ilod_raw;
        if (self.layout.lodmask >> ilod) & 1 == 0 {
            ilod += 1;
        }
        // UNVERIFIED: an odd-only texture at LOD 8 would read past LOD 8; stay on LOD 8.
        let ilod = ilod.min(8);

        let point = if lod == lodmin {
            !mode.tmagfilter()
        } else {
            !mode.tminfilter()
        };
        let fetch = Fetch {
            format: mode.format() as u32,
            lookups: self.lookups(),
        };
        let texel = if point {
            self.point(&fetch, ilod, s >> (ilod + 8), t >> (ilod + 8))
        } else {
            self.bilinear(&fetch, ilod, (s >> ilod) - 0x80, (t >> ilod) - 0x80)
        };
        let zero_frac =
            self.profile.lod_zerofrac == LodZeroFrac::Spec && TLod(self.t_lod).lod_zerofrac();
        Sample {
            texel,
            lod,
            lod_fraction: if zero_frac { 0 } else { (lod & 0xff) as u8 },
            odd_lod: ilod_raw & 1 != 0,
        }
    }

    /// Reads and decodes texel `(s, t)` of a LOD; coordinates are already in range.
    fn read(&self, f: &Fetch<'_>, lod: usize, s: u32, t: u32) -> [u8; 4] {
        let addr = self.layout.texel_addr(lod, s, t);
        let byte = |a: u32| u32::from(self.ram[(a & self.ram_mask) as usize]);
        let raw = if self.layout.bpp_shift == 0 {
            byte(addr)
        } else {
            byte(addr) | byte(addr.wrapping_add(1)) << 8
        };
        crate::format::decode(f.format, raw, &f.lookups)
    }

    /// Point sampling of integer texel coordinates.
    fn point(&self, f: &Fetch<'_>, lod: usize, s: i32, t: i32) -> [u8; 4] {
        let smax = self.layout.smax(lod) as i32;
        let tmax = self.layout.tmax(lod) as i32;
        let mut s = s;
        let mut t = t;
        if TextureMode(self.texture_mode).tclamps() {
            s = s.clamp(0, smax);
        }
        if TextureMode(self.texture_mode).tclampt() {
            t = t.clamp(0, tmax);
        }
        self.read(f, lod, (s & smax) as u32, (t & tmax) as u32)
    }

    /// Bilinear filtering; `s`, `t` are 24.8 at this LOD with half a texel subtracted.
    fn bilinear(&self, f: &Fetch<'_>, lod: usize, s: i32, t: i32) -> [u8; 4] {
        let smax = self.layout.smax(lod) as i32;
        let tmax = self.layout.tmax(lod) as i32;
        let (s0, s1) = neighbours(s >> 8, smax, TextureMode(self.texture_mode).tclamps());
        let (t0, t1) = neighbours(t >> 8, tmax, TextureMode(self.texture_mode).tclampt());
        let c00 = self.read(f, lod, s0, t0);
        let c01 = self.read(f, lod, s1, t0);
        let c10 = self.read(f, lod, s0, t1);
        let c11 = self.read(f, lod, s1, t1);
        let (sf, tf) = ((s & 0xff) as u32, (t & 0xff) as u32);
        let mut out = [0u8; 4];
        for (ch, slot) in out.iter_mut().enumerate() {
            let [a, b, c, d] = [c00[ch], c01[ch], c10[ch], c11[ch]].map(u32::from);
            *slot = match self.profile.bilinear {
                BilinearPrecision::Bits4 => {
                    let (u, v) = (sf >> 4, tf >> 4);
                    ((a * (16 - u) * (16 - v) + b * u * (16 - v) + c * (16 - u) * v + d * u * v)
                        >> 8) as u8
                }
                BilinearPrecision::Bits8 => {
                    // MAME/DOSBox SSE2 form: each row summed exactly, halved, then blended.
                    let h0 = a * (256 - sf) + b * sf;
                    let h1 = c * (256 - sf) + d * sf;
                    (((h0 >> 1) * (256 - tf) + (h1 >> 1) * tf) >> 15) as u8
                }
            };
        }
        out
    }
}

/// The two neighbouring texel coordinates of a bilinear fetch, clamped or wrapped.
///
/// Clamping pins both to 0 below the texture and both to the last texel at or beyond it
/// (MAME `fetch_texel`; DOSBox clamps each one, which gives the same pair).
fn neighbours(c: i32, max: i32, clamp: bool) -> (u32, u32) {
    let (mut c0, mut c1) = (c, c.wrapping_add(1));
    if clamp {
        if c0 < 0 {
            c0 = 0;
            c1 = 0;
        } else if c0 >= max {
            c0 = max;
            c1 = max;
        }
    }
    ((c0 & max) as u32, (c1 & max) as u32)
}

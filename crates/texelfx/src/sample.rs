//! Texture coordinate computation and texel fetch: perspective divide, `tclampw`, LOD,
//! clamp/wrap, point sampling and bilinear filtering (spec 5.50, 5.51).
//!
//! Coordinates become 24.8 texels of LOD 0: `S/W * 256` when `tpersp_st` is set (divided
//! as [`crate::PerspDivide`] says), else `S >> 24` (rounded as [`crate::CoordRounding`]
//! says), then are shifted down by the integer LOD. Point sampling drops the fraction;
//! bilinear first subtracts half a texel and weighs the four neighbours by the top 4 bits
//! of each fraction (the SST-1 keeps 4 bits; Voodoo 2 keeps 8).
//!
//! Filter choice: `tmagfilter` when the clamped LOD equals `lodmin` (the texture is
//! magnified), `tminfilter` otherwise. The spec's prose says the reverse, but its figure and
//! all three references use this rule.
//!
//! Source: MAME `rasterizer_texture::fetch_texel` (DOSBox Staging `TEXTURE_PIPELINE` is the
//! older form of the same code; 86Box uses the same 4-bit weights).

use crate::format::{self, Decode};
use crate::lod::{self, f64_to_i32_x86, pixel_lod, PixelLod};
use crate::{
    BilinearPrecision, CoordRounding, FilterSelect, LodZeroFrac, PerspDivide, TexelModel, Tmu,
};
use sst1_regs::{TLod, TextureMode};

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
    pub(crate) fn sample<M: TexelModel>(
        &mut self,
        iters: i64,
        itert: i64,
        iterw: i64,
        x: i32,
        y: i32,
    ) -> Sample {
        let profile = M::texel(&self.profile);
        let mode = TextureMode(self.texture_mode);
        let persp = mode.tpersp_st();
        let floor = profile.coord_rounding == CoordRounding::Floor;
        let (mut s, mut t) = if persp && profile.persp_divide == PerspDivide::DosboxReciprocal {
            // Source: DOSBox Staging `TEXTURE_PIPELINE`: S * (1/W as .15) >> 29 gives 14.18,
            // truncated to 32 bits; >> 10 more gives the 24.8 used here (a floor, as
            // DOSBox's later shifts are).
            let (oow, _) = crate::lod::reciplog_dosbox(iterw);
            let div = |v: i64| (oow.wrapping_mul(v) >> 29) as i32 >> 10;
            (div(iters), div(itert))
        } else if persp && profile.persp_divide == PerspDivide::Box86 {
            let oow = box86_oow(iterw);
            (box86_divide(iters, oow), box86_divide(itert, oow))
        } else if persp {
            let recip = span_recip(iterw);
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
            persp_term: persp.then(|| lod::w_term(profile.lod, iterw)),
            x,
            y,
        };
        let dither = mode.tloddither();
        let lod = pixel_lod(profile.lod, profile.lod_dither, &p, self.t_lod, dither);
        let lodmin = lod::lod_min(TLod(self.t_lod));
        // lod >= 0 after the clamp, so the integer part is 0..=8.
        let ilod_raw = (lod >> 8) as usize;
        let mut ilod = ilod_raw;
        if (self.layout.lodmask >> ilod) & 1 == 0 {
            ilod += 1;
        }
        // UNVERIFIED: an odd-only texture at LOD 8 would read past LOD 8; stay on LOD 8.
        let ilod = ilod.min(8);

        let point = match profile.filter_select {
            FilterSelect::ByLod if lod == lodmin => !mode.tmagfilter(),
            FilterSelect::ByLod => !mode.tminfilter(),
            FilterSelect::EitherBit => !mode.tmagfilter() && !mode.tminfilter(),
        };
        let texel = if self.cached || self.box86.lent.is_some() {
            if !self.cache.has(ilod) {
                self.decode_level(ilod);
            }
            self.filter::<{ Decode::CACHED }>(profile.bilinear, point, ilod, s, t)
        } else {
            self.uncached_filter(profile.bilinear, point, ilod, s, t)
        };
        let zero_frac =
            profile.lod_zerofrac == LodZeroFrac::Spec && TLod(self.t_lod).lod_zerofrac();
        Sample {
            texel,
            lod,
            lod_fraction: if zero_frac { 0 } else { (lod & 0xff) as u8 },
            odd_lod: ilod_raw & 1 != 0,
        }
    }

    /// [`Tmu::filter`] reading texels straight from memory in the current format.
    fn uncached_filter(
        &self,
        precision: BilinearPrecision,
        point: bool,
        ilod: usize,
        s: i32,
        t: i32,
    ) -> [u8; 4] {
        match self.decode {
            Decode::Lut8 => self.filter::<{ Decode::LUT8 }>(precision, point, ilod, s, t),
            Decode::LutLo16 => self.filter::<{ Decode::LUT_LO16 }>(precision, point, ilod, s, t),
            Decode::Rgb565 => self.filter::<{ Decode::RGB565 }>(precision, point, ilod, s, t),
            Decode::Argb1555 => self.filter::<{ Decode::ARGB1555 }>(precision, point, ilod, s, t),
            Decode::Argb4444 => self.filter::<{ Decode::ARGB4444 }>(precision, point, ilod, s, t),
        }
    }

    /// Decodes LOD `lod` of the bound texture into the cache, with the fetch the uncached
    /// path uses.
    pub(crate) fn decode_level(&mut self, lod: usize) {
        let mut texels = self.cache.take_buffer(lod);
        self.decode_level_into(lod, &mut texels);
        self.cache.fill(lod, &self.layout, texels);
    }

    /// Appends the decoded texels of LOD `lod` of the bound texture to `texels`, row by
    /// row, with the fetch the uncached path uses (what [`Tmu::decode_level`] caches).
    pub(crate) fn decode_level_into(&self, lod: usize, texels: &mut Vec<u32>) {
        let (w, h) = (self.layout.smax(lod) + 1, self.layout.tmax(lod) + 1);
        texels.reserve((w * h) as usize);
        let mut decode_with = |fetch: fn(&Tmu, usize, u32, u32) -> u32| {
            for t in 0..h {
                texels.extend((0..w).map(|s| fetch(self, lod, s, t)));
            }
        };
        match self.decode {
            Decode::Lut8 => decode_with(Tmu::texel_at::<{ Decode::LUT8 }>),
            Decode::LutLo16 => decode_with(Tmu::texel_at::<{ Decode::LUT_LO16 }>),
            Decode::Rgb565 => decode_with(Tmu::texel_at::<{ Decode::RGB565 }>),
            Decode::Argb1555 => decode_with(Tmu::texel_at::<{ Decode::ARGB1555 }>),
            Decode::Argb4444 => decode_with(Tmu::texel_at::<{ Decode::ARGB4444 }>),
        }
    }

    /// Point sampling or bilinear filtering of 24.8 LOD-0 coordinates at LOD `lod`, for
    /// texels decoded as `D` (a [`Decode`] constant, so that each format gets its own
    /// copy of the loop without a per-texel branch).
    #[inline]
    pub(crate) fn filter<const D: u8>(
        &self,
        precision: BilinearPrecision,
        point: bool,
        lod: usize,
        s: i32,
        t: i32,
    ) -> [u8; 4] {
        let texel = if point {
            self.point::<D>(lod, s >> (lod + 8), t >> (lod + 8))
        } else {
            self.bilinear::<D>(
                precision,
                lod,
                (s >> lod).wrapping_sub(0x80),
                (t >> lod).wrapping_sub(0x80),
            )
        };
        format::to_rgba(texel)
    }

    /// The texel `(s, t)` (in range) of LOD `lod` as ARGB: from the cache for
    /// [`Decode::CACHED`], otherwise read from memory and decoded as `D`.
    #[inline(always)]
    fn texel_at<const D: u8>(&self, lod: usize, s: u32, t: u32) -> u32 {
        if D == Decode::CACHED {
            return self.cache.texel(lod, self.layout.smax(lod) + 1, s, t);
        }
        let addr = self.layout.texel_addr(lod, s, t);
        let byte = |a: u32| u32::from(self.ram[(a & self.ram_mask) as usize]);
        if D == Decode::LUT8 {
            return self.texel_lut[byte(addr) as usize];
        }
        let raw = byte(addr) | byte(addr.wrapping_add(1)) << 8;
        match D {
            Decode::RGB565 => format::rgb565(raw),
            Decode::ARGB1555 => format::argb1555(raw),
            Decode::ARGB4444 => format::argb4444(raw),
            _ => (self.texel_lut[(raw & 0xff) as usize] & 0x00ff_ffff) | (raw >> 8) << 24,
        }
    }

    /// Point sampling of integer texel coordinates.
    #[inline(always)]
    fn point<const D: u8>(&self, lod: usize, s: i32, t: i32) -> u32 {
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
        self.texel_at::<D>(lod, (s & smax) as u32, (t & tmax) as u32)
    }

    /// Bilinear filtering; `s`, `t` are 24.8 at this LOD with half a texel subtracted.
    #[inline(always)]
    fn bilinear<const D: u8>(
        &self,
        precision: BilinearPrecision,
        lod: usize,
        s: i32,
        t: i32,
    ) -> u32 {
        let smax = self.layout.smax(lod) as i32;
        let tmax = self.layout.tmax(lod) as i32;
        let mode = TextureMode(self.texture_mode);
        let (s0, s1) = neighbours(s >> 8, smax, mode.tclamps());
        let (t0, t1) = neighbours(t >> 8, tmax, mode.tclampt());
        let c00 = self.texel_at::<D>(lod, s0, t0);
        let c01 = self.texel_at::<D>(lod, s1, t0);
        let c10 = self.texel_at::<D>(lod, s0, t1);
        let c11 = self.texel_at::<D>(lod, s1, t1);
        let (sf, tf) = ((s & 0xff) as u32, (t & 0xff) as u32);
        match precision {
            BilinearPrecision::Bits4 => {
                let (u, v) = (sf >> 4, tf >> 4);
                blend4(
                    [c00, c01, c10, c11],
                    [(16 - u) * (16 - v), u * (16 - v), (16 - u) * v, u * v],
                )
            }
            BilinearPrecision::Bits8 => {
                let mut out = 0;
                for shift in [0, 8, 16, 24] {
                    let [a, b, c, d] = [c00, c01, c10, c11].map(|v| (v >> shift) & 0xff);
                    // MAME/DOSBox SSE2 form: each row summed exactly, halved, then blended.
                    let h0 = a * (256 - sf) + b * sf;
                    let h1 = c * (256 - sf) + d * sf;
                    out |= (((h0 >> 1) * (256 - tf) + (h1 >> 1) * tf) >> 15) << shift;
                }
                out
            }
        }
    }
}

/// `256 / W` in double precision, the factor of MAME's perspective divide
/// ([`PerspDivide::Double`]).
#[inline(always)]
pub(crate) fn span_recip(iterw: i64) -> f64 {
    256.0 / iterw as f64
}

/// 86Box's 1/W for the perspective divide: `2^48 / W` in unsigned 64-bit integers, with W
/// .32 (so the quotient is 1/W as .16). A negative W is a huge unsigned divisor and gives
/// 0, as does W = 0. Source: 86Box `voodoo_tmu_fetch`.
#[inline]
pub(crate) fn box86_oow(iterw: i64) -> i64 {
    if iterw == 0 {
        0
    } else {
        ((1u64 << 48) / iterw as u64) as i64
    }
}

/// 86Box's perspective-corrected coordinate: `S` (.32) rounded to .18, times 1/W (.16 from
/// [`box86_oow`]), rounded to .4 and truncated to 32 bits; returned as 24.8 (`<< 4`, low
/// four bits zero). Source: 86Box `voodoo_tmu_fetch` (its `tex_s` is this .4 value; its
/// point sampling shifts it by `4 + lod` and its bilinear path subtracts `8 << lod` and
/// takes the 4-bit fraction after `>> lod`, which select the same texels and weights as
/// the 24.8 form does in [`Tmu::sample`]).
///
/// INACCURATE: the `<< 4` wraps for coordinates of 2^23 texels or more, where 86Box keeps
/// the sign of its .4 value; only clamped coordinates can then differ.
#[inline]
pub(crate) fn box86_divide(v: i64, oow: i64) -> i32 {
    let st = (v.wrapping_add(1 << 13) >> 14)
        .wrapping_mul(oow)
        .wrapping_add(1 << 29)
        >> 30;
    (st as i32).wrapping_shl(4)
}

/// `sum(texel[i] * weight[i]) >> 8` per channel of four ARGB texels, with weights that
/// sum to 256. The four channels are spread over 16-bit lanes of a `u64`: each product
/// and the sum stay below `255 * 256 < 2^16`, so lanes never carry into each other.
#[inline(always)]
pub(crate) fn blend4(texels: [u32; 4], weights: [u32; 4]) -> u32 {
    let spread = |v: u32| u64::from(v & 0x00ff_00ff) | u64::from((v >> 8) & 0x00ff_00ff) << 32;
    let mut sum = 0u64;
    for (v, w) in texels.into_iter().zip(weights) {
        sum += spread(v) * u64::from(w);
    }
    let lanes = (sum >> 8) & 0x00ff_00ff_00ff_00ff;
    (lanes as u32) | ((lanes >> 32) as u32) << 8
}

/// The two neighbouring texel coordinates of a bilinear fetch, clamped or wrapped.
///
/// Clamping pins both to 0 below the texture and both to the last texel at or beyond it
/// (MAME `fetch_texel`; DOSBox clamps each one, which gives the same pair).
#[inline(always)]
pub(crate) fn neighbours(c: i32, max: i32, clamp: bool) -> (u32, u32) {
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

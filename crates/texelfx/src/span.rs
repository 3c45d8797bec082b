//! Span kernels of the TMU: the texels of a chunk of up to [`LANES`] pixels of one span,
//! computed a stage at a time over all of them (structure of arrays), where
//! [`Tmu::texel`] runs every stage for one pixel.
//!
//! Stages, each one loop over the lanes, in the order of [`Tmu::texel`] (module `sample`
//! for the arithmetic of each):
//!
//! 1. S, T, W iteration;
//! 2. texture coordinates: the perspective divide as [`crate::PerspDivide`] says, or the
//!    shift of affine texturing, and `tclampw`;
//! 3. LOD per lane (its W term, bias, dither, clamp), integer LOD, point or bilinear;
//! 4. the levels the live lanes need are decoded into the cache (module `cache`); then
//!    the texel indices and 4-bit bilinear fractions of every lane (a point-sampled lane
//!    as four equal taps with zero fractions), the gather from the cache (two taps a
//!    load from a level's pairs of neighbours, where one level is sampled), and the
//!    bilinear blend two channels to a 32-bit lane (the Voodoo 2's 8-bit weights, which
//!    no model of the SST-1 uses, per lane through `Tmu::filter`);
//! 5. the detail factor and LOD fraction, and the combine unit (module [`crate::combine`])
//!    channel by channel over the lanes.
//!
//! A chunk of `n` lanes computes whole strips of 16 ([`whole_strips`]): the lanes past
//! `n` are dead, so that no stage ends in a loop over the last lanes one at a time.
//!
//! Every choice that depends only on the registers and the model (perspective, divide,
//! LOD arithmetic, clamps, combine selections) is made once per chunk; what depends on the
//! pixel (its LOD, and so its level, filter and detail factor) is a lane value. No table of
//! states: every `textureMode` / `tLOD` / `tDetail` combination and every model runs here.
//!
//! Bit-identical to [`Tmu::texel`] for every live lane (the test
//! `span_lanes_match_per_pixel_texels` compares them over random states). Only live lanes
//! touch state (the decoded-texel cache, the 86Box cache's lent entry); the cache is a
//! memo of decodes that cannot change during a triangle, so decoding the levels a chunk
//! needs before its lanes sample gives the texels the per-pixel order does. Dead lanes
//! compute values that are thrown away, with wrapping arithmetic and checked indexing so
//! that they cannot panic.

// Each lane loop reads and writes several arrays of one chunk by the lane number.
#![allow(clippy::needless_range_loop)]

use sst1_regs::{TLod, TextureMode};

use crate::combine::{self, detail_factor, AddLocal, MSelect, TextureCombine, UnitControl};
use crate::format::Decode;
use crate::lod::{self, DITHER_4X4};
use crate::sample::{box86_divide, box86_oow};
use crate::{
    BilinearPrecision, CoordRounding, FilterSelect, LodCalc, LodDither, LodZeroFrac, Output,
    PerspDivide, TexelModel, Tmu, Trilinear,
};

pub use sst1_regs::lanes::{
    Avx2Copy, Avx512Copy, BaselineCopy, KernelCopy, LanePlace, Lanes, LANES,
};

/// R, G, B, A lanes, each 0..=255 where it counts.
pub type ColourLanes = [Lanes; 4];

/// What [`Tmu::texels`] computes for each lane.
#[derive(Clone, Copy)]
pub enum LaneOutput<'a> {
    /// The combine unit's output with these upstream lanes ([`Tmu::texel`]).
    Combined(&'a ColourLanes),
    /// The filtered texel alone ([`Tmu::texel_uncombined`]).
    Texel,
    /// 86Box's upstream-TMU combine with the downstream TMU's `textureMode`
    /// ([`Tmu::texel_box86_upstream`]).
    Box86Upstream(u32),
}

/// The per-lane values of one chunk, stage by stage. Kept by the TMU between chunks
/// (`Tmu::lanes`), so that a chunk does not clear 4 KiB first: lanes a stage does not write
/// hold values of an earlier chunk, which only dead lanes read.
pub(crate) struct Chunk {
    /// Iterated S, T, W (.32).
    s: [i64; LANES],
    t: [i64; LANES],
    w: [i64; LANES],
    /// Texture coordinates, 24.8 texels of LOD 0.
    cs: Lanes,
    ct: Lanes,
    /// Clamped LOD, 8.8.
    lod: Lanes,
    /// Integer LOD sampled (a stored level, at most 8).
    ilod: Lanes,
    /// The integer LOD before skipping a level the TMU does not hold is odd (0 or 1).
    odd: Lanes,
    /// Point sampling (1) or bilinear (0).
    point: Lanes,
    /// The four texel indices of a bilinear fetch (all four the texel when point
    /// sampled), within the lane's level.
    taps: [[u32; LANES]; 4],
    /// The four texels (`0xAARRGGBB`) at `taps`.
    texels: [[u32; LANES]; 4],
    /// The 4-bit bilinear fractions in S and T (0 when point sampled).
    frac: [[u32; LANES]; 2],
    /// The filtered texels (`c_local`), R, G, B, A.
    local: ColourLanes,
    /// Detail factor (0.8), where the combine reads it.
    detail: Lanes,
    /// LOD fraction (0.8), where the combine reads it.
    lod_fraction: Lanes,
}

impl Chunk {
    fn new() -> Box<Self> {
        Box::new(Self {
            s: [0; LANES],
            t: [0; LANES],
            w: [0; LANES],
            cs: [0; LANES],
            ct: [0; LANES],
            lod: [0; LANES],
            ilod: [0; LANES],
            odd: [0; LANES],
            point: [0; LANES],
            taps: [[0; LANES]; 4],
            texels: [[0; LANES]; 4],
            frac: [[0; LANES]; 2],
            local: [[0; LANES]; 4],
            detail: [0; LANES],
            lod_fraction: [0; LANES],
        })
    }
}

/// One thread's lanes for [`Tmu::texels_shared`]: what [`Tmu::texels`] keeps in the TMU
/// (a chunk's lane values, the kept output), and the levels this thread decoded itself
/// (for one triangle: drop it when the triangle is done).
pub struct LaneScratch {
    chunk: Box<Chunk>,
    kept: Box<ColourLanes>,
    levels: [Vec<u32>; 9],
    /// Bit n set when `levels[n]` holds LOD n.
    valid: u32,
}

impl LaneScratch {
    /// Empty lanes.
    pub fn new() -> Self {
        Self {
            chunk: Chunk::new(),
            kept: Box::new([[0; LANES]; 4]),
            levels: Default::default(),
            valid: 0,
        }
    }
}

impl Default for LaneScratch {
    fn default() -> Self {
        Self::new()
    }
}

/// Zero in every lane.
static ZERO: Lanes = [0; LANES];

/// Black and transparent in every lane: the `other` lanes of the last TMU of a chain.
pub static ZERO_COLOUR: ColourLanes = [[0; LANES]; 4];

impl Tmu {
    /// The TMU's output for the live lanes of one chunk, each lane the pixel `place`
    /// gives it (offset from vertex A and screen position, as [`Tmu::texel`] takes
    /// them). For each `i < n` with `alive[i]`, lane `i` of `out` gets what
    /// [`Tmu::texel`] (or the call `what` names) gives for that pixel, bit for bit; other
    /// lanes of `out` are left as they are.
    #[inline(always)]
    pub fn texels<M: TexelModel, K: KernelCopy>(
        &mut self,
        place: LanePlace<'_>,
        alive: &[bool; LANES],
        n: usize,
        what: LaneOutput<'_>,
        out: &mut ColourLanes,
    ) {
        let Some((alive, n)) = live_lanes(alive, n) else {
            return;
        };
        let alive = &alive;
        if !self.cached && self.box86.lent.is_none() {
            // The generic path decodes from memory for every texel: per pixel.
            self.texels_per_pixel::<M>(place, alive, n, what, out);
            return;
        }
        if self.lut_stale {
            self.rebuild_lut();
        }
        let mut c = self.lanes.take().unwrap_or_else(Chunk::new);
        let needed = self.lane_levels::<M, K>(place, alive, n, &mut c);
        let mut missing = needed & !self.cache.valid();
        while missing != 0 {
            let lod = missing.trailing_zeros() as usize;
            missing &= missing - 1;
            self.decode_level(lod);
        }
        if needed.is_power_of_two() && self.filters_bilinear() {
            self.pair_level(needed.trailing_zeros() as usize);
        }
        let cache = &self.cache;
        let levels = (|lod| cache.level(lod), |lod| cache.pairs(lod));
        self.texels_from::<M>(levels, needed, alive, n, what, &mut c, out);
        self.lanes = Some(c);
    }

    /// Stages 1 to 3 of [`Tmu::texels`] for the live lanes of a chunk; returns the levels
    /// they sample (bit n for LOD n).
    #[inline(always)]
    fn lane_levels<M: TexelModel, K: KernelCopy>(
        &self,
        place: LanePlace<'_>,
        alive: &[bool; LANES],
        n: usize,
        c: &mut Chunk,
    ) -> u32 {
        let profile = M::texel(&self.profile);
        self.iterate_lanes(place, n, c);
        // The approximations (module `approx`), read once per chunk; all off is exact.
        let approx = self.approx;
        coords_lanes::<K>(
            TextureMode(self.texture_mode),
            profile.persp_divide,
            profile.coord_rounding,
            approx.float_divide,
            n,
            c,
        );
        let lod_from = approx
            .lod_per_chunk
            .then(|| alive[..n].iter().position(|&a| a).unwrap_or(0));
        self.lod_lanes::<M>(place, n, lod_from, c);
        if approx.point_sampling {
            // `textureMode`'s filter bits read as point sampling (what `Approx` says).
            c.point[..n].fill(1);
        }
        let mut needed = 0u32;
        for i in 0..n {
            if alive[i] {
                needed |= 1 << c.ilod[i];
            }
        }
        needed
    }

    /// Whether `textureMode` lets a pixel be filtered bilinearly (either filter bit; a
    /// model that chooses the filter by LOD reads one of them).
    #[inline(always)]
    fn filters_bilinear(&self) -> bool {
        let mode = TextureMode(self.texture_mode);
        mode.tminfilter() || mode.tmagfilter()
    }

    /// The decoded LOD `lod` paired for bilinear fetches, if it is not yet
    /// ([`crate::cache::TexelCache::pair`]).
    #[inline(always)]
    fn pair_level(&mut self, lod: usize) {
        if self.cache.pairs(lod).is_none() {
            self.cache.pair(lod, self.layout.smax(lod) + 1);
        }
    }

    /// Stages 4 and 5 of [`Tmu::texels`]: the texels of the live lanes from the decoded
    /// levels `level(lod)` (every level in `needed` decoded) and their pairs `pairs(lod)`
    /// where built, filtered and combined.
    #[inline(always)]
    fn texels_from<'l, M: TexelModel>(
        &self,
        (level, pairs): (
            impl Fn(usize) -> &'l [u32],
            impl Fn(usize) -> Option<&'l [u64]>,
        ),
        needed: u32,
        alive: &[bool; LANES],
        n: usize,
        what: LaneOutput<'_>,
        c: &mut Chunk,
        out: &mut ColourLanes,
    ) {
        let profile = M::texel(&self.profile);
        self.fetch_lanes::<M>((level, pairs), needed, alive, n, c);

        let zero_frac =
            profile.lod_zerofrac == LodZeroFrac::Spec && TLod(self.t_lod).lod_zerofrac();
        let trilinear = profile.trilinear == Trilinear::Spec;
        match what {
            LaneOutput::Texel => store(alive, n, &c.local, out),
            LaneOutput::Combined(_) if self.passthrough => store(alive, n, &c.local, out),
            LaneOutput::Combined(other) => {
                let uses = |m| self.combine.rgb.mselect == m || self.combine.alpha.mselect == m;
                if uses(MSelect::DetailFactor) {
                    for i in 0..n {
                        c.detail[i] =
                            i32::from(detail_factor(self.t_detail, c.lod[i], profile.detail));
                    }
                }
                if uses(MSelect::LodFraction) {
                    for i in 0..n {
                        c.lod_fraction[i] = c.lod[i] & 0xff;
                    }
                }
                let factors = Factors {
                    detail: &c.detail,
                    lod_fraction: if zero_frac { &ZERO } else { &c.lod_fraction },
                    // The reverse of `reverse_blend` on odd LODs (trilinear).
                    odd: (trilinear && self.combine.trilinear).then_some(&c.odd),
                };
                combine_lanes(&self.combine, &c.local, other, &factors, alive, n, out);
            }
            LaneOutput::Box86Upstream(mode) => {
                let downstream = TextureCombine::from_texture_mode(mode);
                for i in 0..n {
                    if !alive[i] {
                        continue;
                    }
                    let f = combine::Factors {
                        detail: detail_factor(self.t_detail, c.lod[i], profile.detail),
                        lod_fraction: if zero_frac {
                            0
                        } else {
                            (c.lod[i] & 0xff) as u8
                        },
                        odd_lod: trilinear && c.odd[i] != 0,
                    };
                    let texel = core::array::from_fn(|ch| c.local[ch][i] as u8);
                    let v = self.combine.combine_box86_upstream(texel, &f, &downstream);
                    for ch in 0..4 {
                        out[ch][i] = i32::from(v[ch]);
                    }
                }
            }
        }
    }

    /// [`Tmu::texels`] into lanes the TMU keeps, for the next TMU of the chain to read as
    /// its `other` lanes: the live lanes as [`Tmu::texels`] gives them, the others
    /// anything in 0..=255.
    #[inline(always)]
    pub fn texels_kept<M: TexelModel, K: KernelCopy>(
        &mut self,
        place: LanePlace<'_>,
        alive: &[bool; LANES],
        n: usize,
        what: LaneOutput<'_>,
    ) -> &ColourLanes {
        let mut kept = self
            .kept
            .take()
            .unwrap_or_else(|| Box::new([[0; LANES]; 4]));
        self.texels::<M, K>(place, alive, n, what, &mut kept);
        self.kept.insert(kept)
    }

    /// Readies the TMU for [`Tmu::texels_shared`] on several threads at once for the
    /// current triangle: the decode table rebuilt and the levels its `tLOD` clamp lets it
    /// sample decoded into the cache. Returns `false`, and the caller samples through
    /// [`Tmu::texels`] alone, where sampling has state of its own: the generic path (no
    /// cache), 86Box's texture cache (an entry lent per triangle) and the 8-bit bilinear
    /// weights (which read the cache itself).
    pub fn share_levels<M: TexelModel>(&mut self) -> bool {
        let profile = M::texel(&self.profile);
        if !self.cached
            || self.box86.lent.is_some()
            || profile.texture_cache == crate::TextureCacheKey::Box86
            || profile.bilinear == BilinearPrecision::Bits8
        {
            return false;
        }
        if self.lut_stale {
            self.rebuild_lut();
        }
        // The integer LODs `lod_lanes` can give: its clamp keeps the 8.8 LOD in lo..=hi
        // (lodmin where lodmin >= lodmax). A level outside (none should be) is decoded by
        // the sampling thread itself (`LaneScratch::levels`), with the same texels.
        let tl = TLod(self.t_lod);
        let lo = lod::lod_min(tl);
        let hi = ((tl.lodmax() << 6) as i32).min(0x800).max(lo);
        let lodmask = self.layout.lodmask as i32;
        for raw in (lo >> 8)..=(hi >> 8) {
            let skip = !(lodmask >> raw) & 1;
            let lod = (raw + skip).min(8) as usize;
            if !self.cache.has(lod) {
                self.decode_level(lod);
            }
            if self.filters_bilinear() {
                self.pair_level(lod);
            }
        }
        true
    }

    /// [`Tmu::texels`] on a TMU shared between threads, after [`Tmu::share_levels`]
    /// returned `true` (and nothing changed the TMU since): the same lanes bit for bit,
    /// with the chunk's lanes in `scratch` (one per thread) and a level missing from the
    /// cache decoded into `scratch`.
    #[inline(always)]
    pub fn texels_shared<M: TexelModel, K: KernelCopy>(
        &self,
        scratch: &mut LaneScratch,
        place: LanePlace<'_>,
        alive: &[bool; LANES],
        n: usize,
        what: LaneOutput<'_>,
        out: &mut ColourLanes,
    ) {
        let LaneScratch {
            chunk,
            levels,
            valid,
            ..
        } = scratch;
        let lanes = (&mut **chunk, levels, valid);
        self.texels_shared_in::<M, K>(lanes, place, alive, n, what, out);
    }

    /// [`Tmu::texels_shared`] with the parts of a [`LaneScratch`] but its kept lanes.
    #[inline(always)]
    fn texels_shared_in<M: TexelModel, K: KernelCopy>(
        &self,
        (chunk, levels, valid): (&mut Chunk, &mut [Vec<u32>; 9], &mut u32),
        place: LanePlace<'_>,
        alive: &[bool; LANES],
        n: usize,
        what: LaneOutput<'_>,
        out: &mut ColourLanes,
    ) {
        let Some((alive, n)) = live_lanes(alive, n) else {
            return;
        };
        let alive = &alive;
        let needed = self.lane_levels::<M, K>(place, alive, n, chunk);
        let mut missing = needed & !self.cache.valid() & !*valid;
        while missing != 0 {
            let lod = missing.trailing_zeros() as usize;
            missing &= missing - 1;
            levels[lod].clear();
            self.decode_level_into(lod, &mut levels[lod]);
            *valid |= 1 << lod;
        }
        let cache = &self.cache;
        let level = |lod: usize| {
            if cache.has(lod) {
                cache.level(lod)
            } else {
                &levels[lod][..]
            }
        };
        // A level decoded into the scratch has no pairs: its lanes take four taps.
        let pairs = |lod: usize| cache.pairs(lod);
        self.texels_from::<M>((level, pairs), needed, alive, n, what, chunk, out);
    }

    /// [`Tmu::texels_shared`] into `scratch`'s kept lanes, for the next TMU down the
    /// chain (as [`Tmu::texels_kept`]).
    #[inline(always)]
    pub fn texels_kept_shared<'s, M: TexelModel, K: KernelCopy>(
        &self,
        scratch: &'s mut LaneScratch,
        place: LanePlace<'_>,
        alive: &[bool; LANES],
        n: usize,
        what: LaneOutput<'_>,
    ) -> &'s ColourLanes {
        let LaneScratch {
            chunk,
            kept,
            levels,
            valid,
        } = scratch;
        let lanes = (&mut **chunk, levels, valid);
        self.texels_shared_in::<M, K>(lanes, place, alive, n, what, kept);
        kept
    }

    /// [`Tmu::texels`] one pixel at a time through [`Tmu::output`].
    #[cold]
    fn texels_per_pixel<M: TexelModel>(
        &mut self,
        place: LanePlace<'_>,
        alive: &[bool; LANES],
        n: usize,
        what: LaneOutput<'_>,
        out: &mut ColourLanes,
    ) {
        for i in 0..n {
            if !alive[i] {
                continue;
            }
            let what = match what {
                LaneOutput::Combined(o) => Output::Combined(sst1_regs::Rgba {
                    r: o[0][i] as u8,
                    g: o[1][i] as u8,
                    b: o[2][i] as u8,
                    a: o[3][i] as u8,
                }),
                LaneOutput::Texel => Output::Texel,
                LaneOutput::Box86Upstream(m) => Output::Box86Upstream(m),
            };
            let (dx, dy, x, y) = place.at(i);
            let v = self.output::<M>(dx, dy, x, y, what);
            out[0][i] = i32::from(v.r);
            out[1][i] = i32::from(v.g);
            out[2][i] = i32::from(v.b);
            out[3][i] = i32::from(v.a);
        }
    }

    /// Stage 1: S, T, W of each lane, `start + dx * d/dx + dy * d/dy` mod 2^64 (along a
    /// row, the first lane's value plus `i` steps: the same sum).
    #[inline(always)]
    fn iterate_lanes(&self, place: LanePlace<'_>, n: usize, c: &mut Chunk) {
        for (k, lanes) in [&mut c.s, &mut c.t, &mut c.w].into_iter().enumerate() {
            match place {
                LanePlace::Row { dx0, dy, .. } => {
                    let (v0, d) = (self.iterated(k, dx0, dy), self.stw.rows[crate::stw::DX][k]);
                    for (i, v) in lanes[..n].iter_mut().enumerate() {
                        *v = v0.wrapping_add((i as i64).wrapping_mul(d));
                    }
                }
                LanePlace::Lanes { dx, dy, .. } => {
                    for (i, v) in lanes[..n].iter_mut().enumerate() {
                        *v = self.iterated(k, dx[i], dy[i]);
                    }
                }
            }
        }
    }

    /// Stage 3: the LOD of each lane, its level, parity and filter (as [`Tmu::sample`]
    /// and [`lod::pixel_lod`]); with `lod_from` ([`crate::Approx::lod_per_chunk`]), the
    /// LOD of that lane (its W term computed once) for all of them.
    #[inline(always)]
    fn lod_lanes<M: TexelModel>(
        &self,
        place: LanePlace<'_>,
        n: usize,
        lod_from: Option<usize>,
        c: &mut Chunk,
    ) {
        let profile = M::texel(&self.profile);
        let mode = TextureMode(self.texture_mode);
        let tl = TLod(self.t_lod);
        let mut base = self.lod_base;
        // 86Box adds the bias at setup (see `lod::lod_base`).
        if profile.lod != LodCalc::Box86 {
            base = base.wrapping_add(tl.lodbias() << 6);
        }
        let lo = lod::lod_min(tl);
        // UNVERIFIED (as `lod::pixel_lod`): lodmax capped at 8.0.
        let hi = ((tl.lodmax() << 6) as i32).min(0x800);
        let lod = &mut c.lod;
        // With `lodmin` at or above `lodmax` (one level) the clamp below gives `lodmin`
        // whatever the W term and the dither add: neither is computed.
        let one_lod = lo >= hi;
        if mode.tpersp_st() && !one_lod {
            let w = &c.w;
            match profile.lod {
                LodCalc::Mame => w_terms(w, n, lod_from, lod, |w| lod::w_term(LodCalc::Mame, w)),
                // `Approx::float_divide`: the W term from the single-precision W.
                LodCalc::Dosbox if self.approx.float_divide => {
                    w_terms(w, n, lod_from, lod, crate::approx::w_log_f32)
                }
                LodCalc::Dosbox => {
                    // Source: DOSBox Staging `TEXTURE_PIPELINE` (as `lod::w_term`).
                    let fractions = lod::reciplog_log_fractions();
                    match lod_from {
                        Some(from) => {
                            lod[..n].fill(lod::reciplog_log_keyed(fractions, w[from % LANES]))
                        }
                        None => lod::reciplog_log_lanes(fractions, w, n, lod),
                    }
                }
                LodCalc::Box86 => w_terms(w, n, lod_from, lod, |w| lod::w_term(LodCalc::Box86, w)),
            }
        } else {
            lod[..n].fill(0);
        }
        // Only perspective texturing adds the W term.
        for v in lod[..n].iter_mut() {
            *v = v.wrapping_add(base);
        }
        if mode.tloddither() && profile.lod_dither == LodDither::Matrix4x4 && !one_lod {
            // Source: MAME `fetch_texel`, DOSBox `TEXTURE_PIPELINE` (as `lod::pixel_lod`).
            match place {
                LanePlace::Row { x0, y, .. } => {
                    let row = &DITHER_4X4[(y & 3) as usize];
                    for (i, v) in lod[..n].iter_mut().enumerate() {
                        let x = x0.wrapping_add(i as i32);
                        *v = v.wrapping_add(i32::from(row[(x & 3) as usize]) << 4);
                    }
                }
                LanePlace::Lanes { x, y, .. } => {
                    for (i, v) in lod[..n].iter_mut().enumerate() {
                        let d = DITHER_4X4[(y[i] & 3) as usize][(x[i] & 3) as usize];
                        *v = v.wrapping_add(i32::from(d) << 4);
                    }
                }
            }
        }
        // A lodmin above lodmax gives lodmin (as `lod::pixel_lod`).
        for v in lod[..n].iter_mut() {
            *v = (*v).min(hi).max(lo);
        }
        if let Some(from) = lod_from {
            // `Approx::lod_per_chunk`: that lane's whole LOD, dither included, for all.
            let v = lod[from % LANES];
            lod[..n].fill(v);
        }
        let lodmask = self.layout.lodmask as i32;
        for i in 0..n {
            // lod >= 0 after the clamp, so the integer part is 0..=15.
            let raw = lod[i] >> 8;
            let skip = !(lodmask >> raw) & 1;
            // UNVERIFIED (as `Tmu::sample`): an odd-only texture at LOD 8 stays on LOD 8.
            c.ilod[i] = (raw + skip).min(8);
            c.odd[i] = raw & 1;
        }
        let (mag, min) = (!mode.tmagfilter() as i32, !mode.tminfilter() as i32);
        match profile.filter_select {
            FilterSelect::ByLod if mag == min => c.point[..n].fill(mag),
            FilterSelect::ByLod => {
                for i in 0..n {
                    c.point[i] = if lod[i] == lo { mag } else { min };
                }
            }
            FilterSelect::EitherBit => c.point[..n].fill(mag & min),
        }
    }

    /// Stage 4: samples each live lane from the decoded levels `level(lod)` (every level
    /// in `needed` decoded): the arithmetic of [`Tmu::sample`]'s filter, with the level
    /// looked up once per chunk when all live lanes sample one level.
    #[inline(always)]
    fn fetch_lanes<'l, M: TexelModel>(
        &self,
        (level, pairs): (
            impl Fn(usize) -> &'l [u32],
            impl Fn(usize) -> Option<&'l [u64]>,
        ),
        needed: u32,
        alive: &[bool; LANES],
        n: usize,
        c: &mut Chunk,
    ) {
        let profile = M::texel(&self.profile);
        let mode = TextureMode(self.texture_mode);
        let clamp = (mode.tclamps(), mode.tclampt());
        if profile.bilinear == BilinearPrecision::Bits8 {
            // The Voodoo 2's 8-bit weights (no model of the SST-1 uses them): per lane,
            // from the cache (which `Tmu::share_levels` refuses to share).
            for i in 0..n {
                if !alive[i] {
                    continue;
                }
                let texel = self.filter::<{ Decode::CACHED }>(
                    profile.bilinear,
                    c.point[i] != 0,
                    c.ilod[i] as usize,
                    c.cs[i],
                    c.ct[i],
                );
                for ch in 0..4 {
                    c.local[ch][i] = i32::from(texel[ch]);
                }
            }
            return;
        }
        let one_level = needed.is_power_of_two();
        let all_point = c.point[..n].iter().all(|&p| p != 0);
        let (wmask, hmask) = (self.layout.wmask, self.layout.hmask);
        if one_level {
            let lod = needed.trailing_zeros();
            taps_lanes(n, c, clamp, all_point, |_| lod, wmask, hmask);
        } else {
            taps_lanes(n, c, clamp, all_point, |i| i as u32, wmask, hmask);
        }
        let tap_count = if all_point { 1 } else { 4 };
        let (taps, texels) = (&c.taps, &mut c.texels);
        if one_level {
            let lod = needed.trailing_zeros() as usize;
            match pairs(lod).filter(|_| !all_point) {
                Some(pairs) => gather_pairs(pairs, taps, n, texels),
                None => {
                    let level = level(lod);
                    for k in 0..tap_count {
                        gather(level, &taps[k], n, &mut texels[k]);
                    }
                }
            }
        } else {
            for k in 0..tap_count {
                for i in 0..n {
                    let level = level(c.ilod[i] as usize);
                    texels[k][i] = level.get(taps[k][i] as usize).copied().unwrap_or(0);
                }
            }
        }
        let local = &mut c.local;
        if all_point {
            for (ch, shift) in [16, 8, 0, 24].into_iter().enumerate() {
                for i in 0..n {
                    local[ch][i] = (texels[0][i] >> shift & 0xff) as i32;
                }
            }
            return;
        }
        // `sum(texel * weight) >> 8` per channel, the weights `(16 - u) * (16 - v)`,
        // `u * (16 - v)`, `(16 - u) * v`, `u * v` (as `sample::blend4`). The weights add
        // up to 256, so each channel's sum is below 2^16 and two channels sum in one
        // 32-bit lane without carrying into each other: blue and red, then green and
        // alpha, each in the low and high half.
        let [fu, fv] = &c.frac;
        const PAIR: u32 = 0x00ff_00ff;
        for i in 0..n {
            let (u, v) = (fu[i], fv[i]);
            let weights = [(16 - u) * (16 - v), u * (16 - v), (16 - u) * v, u * v];
            let (mut br, mut ga) = (0u32, 0u32);
            for k in 0..4 {
                br = br.wrapping_add((texels[k][i] & PAIR).wrapping_mul(weights[k]));
                ga = ga.wrapping_add((texels[k][i] >> 8 & PAIR).wrapping_mul(weights[k]));
            }
            local[0][i] = (br >> 24) as i32;
            local[1][i] = (ga >> 8 & 0xff) as i32;
            local[2][i] = (br >> 8 & 0xff) as i32;
            local[3][i] = (ga >> 24) as i32;
        }
    }
}

/// A chunk of `n` lanes as its stages take it: the live lanes (`alive` below `n`: the
/// lanes past `n` are dead whatever `alive` says of them) and the lanes computed
/// ([`whole_strips`]); `None` where no lane is live.
#[inline(always)]
fn live_lanes(alive: &[bool; LANES], n: usize) -> Option<([bool; LANES], usize)> {
    let n = n.min(LANES);
    let live: [bool; LANES] = core::array::from_fn(|i| i < n && alive[i]);
    live.iter().any(|&a| a).then_some((live, whole_strips(n)))
}

/// The lanes a chunk of `n` lanes computes: `n` rounded up to whole strips of
/// [`STRIP`] lanes (the lanes past `n` are dead: computed, never stored), so that each
/// stage's loop runs whole vectors and no lane at a time after them.
#[inline(always)]
fn whole_strips(n: usize) -> usize {
    (n.next_multiple_of(STRIP)).min(LANES)
}

/// The lanes of a strip ([`whole_strips`]): an AVX-512 vector of 32-bit lanes.
const STRIP: usize = 16;

/// `out[i] = level[taps[i]]` for the first `n` lanes, 0 where a tap is past the level.
/// Written without a branch per lane (the load's index clamped, its value dropped after),
/// so that it compiles to vector gathers where the compiler emits them (the AVX-512 copy).
#[inline(always)]
fn gather(level: &[u32], taps: &[u32; LANES], n: usize, out: &mut [u32; LANES]) {
    let Some(last) = level.len().checked_sub(1) else {
        out[..n].fill(0);
        return;
    };
    // Clamped in 32 bits: AVX2 has a vector minimum of 32-bit lanes and none of 64-bit
    // ones (measured: clamping the `usize` costs the perf_tex_heavy slice 6 % more
    // instructions). No level is 2^32 texels long.
    let last = last.min(u32::MAX as usize) as u32;
    for (o, &tap) in out[..n].iter_mut().zip(&taps[..n]) {
        let texel = level[tap.min(last) as usize];
        *o = if tap <= last { texel } else { 0 };
    }
}

/// [`gather`] of the four taps of the first `n` lanes from the level's pairs
/// ([`crate::cache::TexelCache::pair`]): a load per row of taps. The second tap of a row
/// is the first's right-hand neighbour, wrapping in the row ([`bilinear_taps`] in a
/// wrapping S; and in a clamped S, away from the edges), or the first tap itself (a
/// clamped S at an edge, and a point-sampled lane, whose taps are all one); the level
/// being whole rows, the neighbour lies past the level exactly where the first tap does.
#[inline(always)]
fn gather_pairs(pairs: &[u64], taps: &[[u32; LANES]; 4], n: usize, texels: &mut [[u32; LANES]; 4]) {
    let Some(last) = pairs.len().checked_sub(1) else {
        for t in texels.iter_mut() {
            t[..n].fill(0);
        }
        return;
    };
    // Clamped in 32 bits, as in `gather`.
    let last = last.min(u32::MAX as usize) as u32;
    let (top, bottom) = texels.split_at_mut(2);
    for (row, out) in [(0, top), (2, bottom)] {
        let (first, second) = (&taps[row], &taps[row + 1]);
        let (left, right) = out.split_at_mut(1);
        let (left, right) = (&mut left[0], &mut right[0]);
        for i in 0..n {
            let tap = first[i];
            let pair = pairs[tap.min(last) as usize];
            let pair = if tap <= last { pair } else { 0 };
            left[i] = pair as u32;
            right[i] = if second[i] == tap {
                pair as u32
            } else {
                (pair >> 32) as u32
            };
        }
    }
}

/// The texel indices and bilinear fractions of each lane (as `Tmu::point` and
/// `Tmu::bilinear`): lane `i` samples LOD `lod_of(ilod[i])` of a texture whose LOD 0 is
/// `wmask + 1` by `hmask + 1`. A point-sampled lane gets its texel in all four taps and
/// zero fractions, which the bilinear weights turn into the texel itself; with
/// `all_point` only the first tap is computed. Written as branch-free loops, one per
/// case, so that they vectorise.
#[inline(always)]
fn taps_lanes(
    n: usize,
    c: &mut Chunk,
    clamp: (bool, bool),
    all_point: bool,
    lod_of: impl Fn(i32) -> u32,
    wmask: u32,
    hmask: u32,
) {
    let all_bilinear = c.point[..n].iter().all(|&p| p == 0);
    let level = |i: usize| {
        let lod = lod_of(c.ilod[i]) & 15;
        (lod, (wmask >> lod) as i32, (hmask >> lod) as i32)
    };
    if all_point {
        for i in 0..n {
            let (lod, smax, tmax) = level(i);
            c.taps[0][i] = point_tap(c.cs[i], c.ct[i], lod, (smax, tmax), clamp);
        }
        return;
    }
    if all_bilinear {
        for i in 0..n {
            let (lod, smax, tmax) = level(i);
            let (taps, fs, ft) = bilinear_taps(c.cs[i], c.ct[i], lod, (smax, tmax), clamp);
            for (k, &tap) in taps.iter().enumerate() {
                c.taps[k][i] = tap;
            }
            c.frac[0][i] = fs;
            c.frac[1][i] = ft;
        }
        return;
    }
    for i in 0..n {
        let (lod, smax, tmax) = level(i);
        let (taps, fs, ft) = bilinear_taps(c.cs[i], c.ct[i], lod, (smax, tmax), clamp);
        let point = point_tap(c.cs[i], c.ct[i], lod, (smax, tmax), clamp);
        let is_point = c.point[i] != 0;
        for (k, &tap) in taps.iter().enumerate() {
            c.taps[k][i] = if is_point { point } else { tap };
        }
        c.frac[0][i] = if is_point { 0 } else { fs };
        c.frac[1][i] = if is_point { 0 } else { ft };
    }
}

/// The texel index of point sampling 24.8 LOD-0 coordinates at `lod`, whose width and
/// height minus 1 are `max` (as `Tmu::point`).
#[inline(always)]
fn point_tap(s: i32, t: i32, lod: u32, (smax, tmax): (i32, i32), clamp: (bool, bool)) -> u32 {
    let (mut s, mut t) = (s >> (lod + 8), t >> (lod + 8));
    // `max(0).min(max)`: `clamp` without its panic path (`max` is never negative).
    if clamp.0 {
        s = s.max(0).min(smax);
    }
    if clamp.1 {
        t = t.max(0).min(tmax);
    }
    ((t & tmax) as u32) * (smax as u32 + 1) + (s & smax) as u32
}

/// The four texel indices and the 4-bit S and T fractions of a bilinear fetch of 24.8
/// LOD-0 coordinates at `lod` (as `Tmu::bilinear`).
#[inline(always)]
fn bilinear_taps(
    s: i32,
    t: i32,
    lod: u32,
    (smax, tmax): (i32, i32),
    clamp: (bool, bool),
) -> ([u32; 4], u32, u32) {
    let s = (s >> lod).wrapping_sub(0x80);
    let t = (t >> lod).wrapping_sub(0x80);
    let (s0, s1) = neighbour_lanes(s >> 8, smax, clamp.0);
    let (t0, t1) = neighbour_lanes(t >> 8, tmax, clamp.1);
    let width = smax as u32 + 1;
    (
        [
            t0 * width + s0,
            t0 * width + s1,
            t1 * width + s0,
            t1 * width + s1,
        ],
        (s as u32 & 0xff) >> 4,
        (t as u32 & 0xff) >> 4,
    )
}

/// `sample::neighbours` without branches: clamping pins both to 0 below the texture and
/// both to `max` at or beyond it, which is `c` and `c + 1` each clamped to `0..=max`
/// (`c + 1` cannot overflow: `c` is a 24.8 coordinate shifted down by 8).
#[inline(always)]
fn neighbour_lanes(c: i32, max: i32, clamp: bool) -> (u32, u32) {
    let (mut c0, mut c1) = (c, c.wrapping_add(1));
    if clamp {
        c0 = c0.max(0).min(max);
        c1 = c1.max(0).min(max);
    }
    ((c0 & max) as u32, (c1 & max) as u32)
}

/// `lod[i] = term(w[i])` for the first `n` lanes, or `term(w[from])` in all of them
/// ([`crate::Approx::lod_per_chunk`]).
#[inline(always)]
fn w_terms(
    w: &[i64; LANES],
    n: usize,
    from: Option<usize>,
    lod: &mut Lanes,
    term: impl Fn(i64) -> i32,
) {
    if let Some(from) = from {
        lod[..n].fill(term(w[from % LANES]));
        return;
    }
    for (v, &w) in lod[..n].iter_mut().zip(&w[..n]) {
        *v = term(w);
    }
}

/// Stage 2: the 24.8 texture coordinates of each lane and `tclampw` (as [`Tmu::sample`]).
/// With `float_divide` ([`crate::Approx::float_divide`]) the perspective divide is
/// `approx::coords_f32`'s.
#[inline(always)]
fn coords_lanes<K: KernelCopy>(
    mode: TextureMode,
    divide: PerspDivide,
    rounding: CoordRounding,
    float_divide: bool,
    n: usize,
    c: &mut Chunk,
) {
    let floor = rounding == CoordRounding::Floor;
    let (s, t, w) = (&c.s, &c.t, &c.w);
    let (cs, ct) = (&mut c.cs, &mut c.ct);
    match (mode.tpersp_st(), divide) {
        (true, _) if float_divide => crate::approx::coords_f32((s, t, w), n, floor, cs, ct),
        (true, PerspDivide::DosboxReciprocal) => {
            let table = lod::reciplog_table();
            for i in 0..n {
                // Source: DOSBox Staging `TEXTURE_PIPELINE` (see `Tmu::sample`).
                let (oow, _) = lod::reciplog_in(table, w[i]);
                cs[i] = (oow.wrapping_mul(s[i]) >> 29) as i32 >> 10;
                ct[i] = (oow.wrapping_mul(t[i]) >> 29) as i32 >> 10;
            }
        }
        (true, PerspDivide::Box86) => {
            for i in 0..n {
                let oow = box86_oow(w[i]);
                cs[i] = box86_divide(s[i], oow);
                ct[i] = box86_divide(t[i], oow);
            }
        }
        #[cfg(target_arch = "x86_64")]
        (true, PerspDivide::Double) if K::AVX512 && wide::has_avx512() => {
            // SAFETY: the CPU has AVX-512 F and DQ (checked just above).
            unsafe { wide::coords_double((s, t, w), n, floor, cs, ct) }
        }
        (true, PerspDivide::Double) => {
            for i in 0..n {
                (cs[i], ct[i]) = divide_double(s[i], t[i], w[i], floor);
            }
        }
        (false, _) if floor => {
            for i in 0..n {
                cs[i] = (s[i] >> 24) as i32;
                ct[i] = (t[i] >> 24) as i32;
            }
        }
        (false, _) => {
            let to_i32 = |v: i64| i32::try_from(v / (1 << 24)).unwrap_or(i32::MIN);
            for i in 0..n {
                cs[i] = to_i32(s[i]);
                ct[i] = to_i32(t[i]);
            }
        }
    }
    if mode.tclampw() {
        for i in 0..n {
            if w[i] < 0 {
                cs[i] = 0;
                ct[i] = 0;
            }
        }
    }
}

/// Forms of the lane stages with AVX-512's own instructions, for the AVX-512 copy of the
/// kernels ([`KernelCopy::AVX512`]): the same integers as the forms written for every
/// copy (tests `wide_divide_equals_the_lane_divide` and the identity tests).
#[cfg(target_arch = "x86_64")]
mod wide {
    use super::{divide_double, Lanes, LANES};
    use std::arch::x86_64::*;

    /// Whether the CPU has what [`coords_double`] uses. `KernelCopy::AVX512` says which
    /// copy the code is compiled into, which only the CPU's check makes safe to run.
    #[inline(always)]
    pub(super) fn has_avx512() -> bool {
        std::arch::is_x86_feature_detected!("avx512f")
            && std::arch::is_x86_feature_detected!("avx512dq")
    }

    /// `coords_lanes`'s doubles divide (MAME's `S * (256 / W)`), eight lanes an
    /// instruction: DQ converts the 64-bit S, T, W to doubles directly, rounding to
    /// nearest as the exact split conversion `i64_to_f64` does, and the conversion back
    /// truncates, or rounds down for `floor`, with "integer indefinite" (`i32::MIN`) for
    /// NaN and out of range, which is what `f64_to_i32_lanes` computes.
    ///
    /// # Safety
    /// The CPU must have AVX-512 F and DQ.
    #[target_feature(enable = "avx512f,avx512dq")]
    pub(super) unsafe fn coords_double(
        (s, t, w): (&[i64; LANES], &[i64; LANES], &[i64; LANES]),
        n: usize,
        floor: bool,
        cs: &mut Lanes,
        ct: &mut Lanes,
    ) {
        const DOWN: i32 = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
        let n = n.min(LANES);
        let whole = n - n % 8;
        let scale = _mm512_set1_pd(256.0);
        for i in (0..whole).step_by(8) {
            // SAFETY: `i + 8 <= LANES`, within each array; the loads and stores are
            // unaligned.
            unsafe {
                let load = |v: &[i64; LANES]| {
                    _mm512_cvtepi64_pd(_mm512_loadu_si512(v.as_ptr().add(i).cast()))
                };
                let recip = _mm512_div_pd(scale, load(w));
                let (qs, qt) = (_mm512_mul_pd(load(s), recip), _mm512_mul_pd(load(t), recip));
                let (rs, rt) = if floor {
                    (
                        _mm512_cvt_roundpd_epi32::<DOWN>(qs),
                        _mm512_cvt_roundpd_epi32::<DOWN>(qt),
                    )
                } else {
                    (_mm512_cvttpd_epi32(qs), _mm512_cvttpd_epi32(qt))
                };
                _mm256_storeu_si256(cs.as_mut_ptr().add(i).cast(), rs);
                _mm256_storeu_si256(ct.as_mut_ptr().add(i).cast(), rt);
            }
        }
        for i in whole..n {
            (cs[i], ct[i]) = divide_double(s[i], t[i], w[i], floor);
        }
    }
}

/// One lane of the doubles divide (MAME: S * (256 / W) in doubles, truncated, or floored;
/// see `Tmu::sample`): the texture coordinates S and T, with `span_recip`'s reciprocal
/// and conversions that vectorise.
#[inline(always)]
fn divide_double(s: i64, t: i64, w: i64, floor: bool) -> (i32, i32) {
    let recip = 256.0 / i64_to_f64(w);
    let div = |v: i64| f64_to_i32_lanes(i64_to_f64(v) * recip, floor);
    (div(s), div(t))
}

/// `v as f64` (rounded to nearest, ties to even) from conversions of 32-bit halves, which
/// AVX2 has for vectors where it has none from 64 bits: `hi * 2^32` and the unsigned low
/// half are exact doubles whose sum is `v`, so the one rounding of their addition is that
/// of the direct conversion.
#[inline(always)]
fn i64_to_f64(v: i64) -> f64 {
    let hi = (v >> 32) as i32;
    let lo = (v as u32 ^ 0x8000_0000) as i32;
    f64::from(hi) * 4_294_967_296.0 + (f64::from(lo) + 2_147_483_648.0)
}

/// `lod::f64_to_i32_x86(q)` (truncation; NaN and out of range give `i32::MIN`), then with
/// `floor` one less where that went up, as `Tmu::sample` computes it, in arithmetic that
/// vectorises (Rust's saturating `as` does not): `q` in range is rounded to the nearest
/// integer by adding and subtracting `1.5 * 2^52` (exact below 2^51), stepped back by one
/// where that went away from zero (truncation) or up (floor), and read from the low bits
/// of the same sum. For `q` in range the floor is what truncating and stepping down gives.
#[inline(always)]
fn f64_to_i32_lanes(q: f64, floor: bool) -> i32 {
    const MAGIC: f64 = 6_755_399_441_055_744.0;
    let in_range = (-2_147_483_648.0..2_147_483_648.0).contains(&q);
    let nearest = (q + MAGIC) - MAGIC;
    // Floor, or truncation of a positive value: back down where rounding went up.
    let step = if floor || q >= 0.0 {
        f64::from(u8::from(nearest > q))
    } else {
        -f64::from(u8::from(nearest < q))
    };
    let r = ((nearest - step) + MAGIC).to_bits() as u32 as i32;
    if in_range {
        r
    } else {
        i32::MIN
    }
}

/// The combine unit's per-pixel inputs besides the colours, per lane.
struct Factors<'a> {
    /// Detail factor (0.8).
    detail: &'a Lanes,
    /// LOD fraction (0.8).
    lod_fraction: &'a Lanes,
    /// With trilinear in force: 1 where the LOD is odd, reversing the blend.
    odd: Option<&'a Lanes>,
}

/// Copies the live lanes of `from` into `out`.
#[inline(always)]
fn store(alive: &[bool; LANES], n: usize, from: &ColourLanes, out: &mut ColourLanes) {
    for ch in 0..4 {
        for i in 0..n {
            if alive[i] {
                out[ch][i] = from[ch][i];
            }
        }
    }
}

/// Stage 5: the combine unit over the lanes, one channel at a time (the arithmetic of
/// `combine::channel`): `clamp((blend * (factor + 1)) >> 8 + add)`, inverted if asked.
#[inline(always)]
fn combine_lanes(
    tc: &TextureCombine,
    local: &ColourLanes,
    other: &ColourLanes,
    f: &Factors<'_>,
    alive: &[bool; LANES],
    n: usize,
    out: &mut ColourLanes,
) {
    for ch in 0..4 {
        let u: &UnitControl = if ch == 3 { &tc.alpha } else { &tc.rgb };
        let factor: &Lanes = match u.mselect {
            MSelect::Zero | MSelect::Reserved => &ZERO,
            MSelect::CLocal => &local[ch],
            MSelect::AOther => &other[3],
            MSelect::ALocal => &local[3],
            MSelect::DetailFactor => f.detail,
            MSelect::LodFraction => f.lod_fraction,
        };
        let add: &Lanes = match u.add {
            AddLocal::None => &ZERO,
            AddLocal::CLocal => &local[ch],
            AddLocal::ALocal => &local[3],
        };
        let keep_other = if u.zero_other { 0 } else { -1 };
        let sub_local = if u.sub_clocal { -1 } else { 0 };
        // factor ^ 0xff unless reverse_blend (itself reversed on odd trilinear LODs).
        let flip = if u.reverse_blend { 0 } else { 0xff };
        let invert = if u.invert_output { 0xff } else { 0 };
        let (odd, odd_flip) = match f.odd {
            Some(odd) => (odd, 0xff),
            None => (&ZERO, 0),
        };
        let (c_other, c_local) = (&other[ch], &local[ch]);
        let o = &mut out[ch];
        for i in 0..n {
            let blend = (c_other[i] & keep_other).wrapping_sub(c_local[i] & sub_local);
            let fac = factor[i] ^ flip ^ (odd[i].wrapping_neg() & odd_flip);
            let v = (blend.wrapping_mul(fac.wrapping_add(1)) >> 8).wrapping_add(add[i]);
            let v = v.clamp(0, 255) ^ invert;
            if alive[i] {
                o[i] = v;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{
        bilinear_taps, divide_double, f64_to_i32_lanes, gather, gather_pairs, i64_to_f64,
        point_tap, LANES,
    };
    use crate::cache::TexelCache;
    use crate::layout::Layout;
    use crate::lod::f64_to_i32_x86;

    /// The pairs give what four gathers give, for the taps of bilinear fetches (wrapping
    /// and clamped, at and past the edges) and of point-sampled lanes, on every level
    /// shape of a 256 by 32 texture.
    #[test]
    fn pair_gathers_equal_four_gathers() {
        let mem = (1 << 22) - 1;
        let t_lod = sst1_regs::TLod(0)
            .with_lod_aspect(3)
            .with_lod_s_is_wider(true);
        let layout = Layout::new(0, t_lod.0, &[0; 4], mem);
        assert_eq!((layout.smax(0), layout.tmax(0)), (255, 31));
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for lod in 0..=8 {
            let (smax, tmax) = (layout.smax(lod), layout.tmax(lod));
            let len = ((smax + 1) * (tmax + 1)) as usize;
            let texels: Vec<u32> = (0..len).map(|_| next() as u32).collect();
            let mut cache = TexelCache::new();
            cache.fill(lod, &layout, texels.clone());
            assert!(cache.pairs(lod).is_none(), "no pairs before they are built");
            cache.pair(lod, smax + 1);
            let pairs = cache.pairs(lod).expect("paired");
            for round in 0..64 {
                let clamp = (round & 1 != 0, round & 2 != 0);
                let mut taps = [[0u32; LANES]; 4];
                for i in 0..LANES {
                    // 24.8 LOD-0 coordinates up to three textures wide either side.
                    let range = (smax as i64 + 1) << (lod + 8);
                    let s = ((next() as i64).rem_euclid(range * 7) - range * 3) as i32;
                    let t = ((next() as i64).rem_euclid(range * 7) - range * 3) as i32;
                    let max = (smax as i32, tmax as i32);
                    let four = if next() % 4 == 0 {
                        [point_tap(s, t, lod as u32, max, clamp); 4]
                    } else {
                        bilinear_taps(s, t, lod as u32, max, clamp).0
                    };
                    for k in 0..4 {
                        taps[k][i] = four[k];
                    }
                }
                let mut want = [[0u32; LANES]; 4];
                for k in 0..4 {
                    gather(&texels, &taps[k], LANES, &mut want[k]);
                }
                let mut got = [[0u32; LANES]; 4];
                gather_pairs(pairs, &taps, LANES, &mut got);
                assert_eq!(got, want, "lod {lod}, clamp {clamp:?}");
            }
        }
    }

    #[test]
    fn pairs_follow_their_level() {
        let layout = Layout::new(0, 0, &[0; 4], (1 << 22) - 1);
        let mut cache = TexelCache::new();
        let row = |v: u32| vec![v; 256 * 256];
        cache.fill(0, &layout, row(5));
        cache.pair(0, 256);
        assert_eq!(cache.pairs(0).map(|p| p[0]), Some(5 | 5 << 32));
        cache.written(0, 2, (1 << 22) - 1);
        assert!(
            cache.pairs(0).is_none(),
            "a write to the level drops its pairs"
        );
        cache.fill(0, &layout, row(6));
        assert!(
            cache.pairs(0).is_none(),
            "a level decoded again is not paired"
        );
        cache.pair(0, 256);
        assert_eq!(cache.pairs(0).map(|p| p[255]), Some(6 | 6 << 32));
        cache.clear();
        assert!(cache.pairs(0).is_none());
        cache.fill(1, &layout, vec![1; 3]);
        cache.pair(1, 128);
        assert!(
            cache.pairs(1).is_none(),
            "a level that is not whole rows gets no pairs"
        );
    }

    #[test]
    fn gather_reads_each_tap_and_zero_past_the_level() {
        let level: Vec<u32> = (0..8).map(|i| 0x100 + i).collect();
        let mut taps = [0u32; LANES];
        for (i, t) in taps.iter_mut().enumerate() {
            *t = [3, 0, 7, 8, u32::MAX, 5][i % 6];
        }
        let mut out = [0xdead_u32; LANES];
        gather(&level, &taps, 6, &mut out);
        assert_eq!(out[..6], [0x103, 0x100, 0x107, 0, 0, 0x105]);
        assert_eq!(out[6], 0xdead, "lanes past n are left alone");
        gather(&[], &taps, 6, &mut out);
        assert_eq!(out[..6], [0; 6]);
    }

    #[test]
    fn split_conversion_rounds_as_the_direct_one() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut values = vec![0, 1, -1, i64::MIN, i64::MAX, (1 << 53) + 1, -(1 << 53) - 1];
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            values.push((x as i64) >> (x % 64));
        }
        for v in values {
            assert_eq!(i64_to_f64(v).to_bits(), (v as f64).to_bits(), "{v:#x}");
        }
    }

    /// AVX-512's doubles divide against the form every copy runs, over random S, T, W
    /// and the edges: zero W (infinities and NaN), the extremes, quotients out of range
    /// and on halves, every count of lanes. Runs where the CPU has AVX-512.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn wide_divide_equals_the_lane_divide() {
        if !super::wide::has_avx512() {
            eprintln!("no AVX-512 here: the wide divide is not run");
            return;
        }
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let edges = [
            0,
            1,
            -1,
            2,
            1 << 31,
            3 << 30,
            i64::MIN,
            i64::MAX,
            1 << 40,
            -(1 << 40),
        ];
        for round in 0..4000 {
            let mut lanes = [[0i64; LANES]; 3];
            for v in lanes.iter_mut().flatten() {
                let r = next();
                *v = match r % 4 {
                    0 => edges[(r >> 8) as usize % edges.len()],
                    1 => (r as i64) >> 20,
                    _ => (r as i64) >> (r % 64),
                };
            }
            let [s, t, w] = &lanes;
            let n = round % (LANES + 1);
            let floor = round % 2 == 0;
            let (mut cs, mut ct) = ([7; LANES], [7; LANES]);
            // SAFETY: the CPU has AVX-512 F and DQ (checked above).
            unsafe { super::wide::coords_double((s, t, w), n, floor, &mut cs, &mut ct) };
            for i in 0..LANES {
                let (ws, wt) = if i < n {
                    divide_double(s[i], t[i], w[i], floor)
                } else {
                    (7, 7)
                };
                let at = (s[i], t[i], w[i], floor);
                assert_eq!((cs[i], ct[i]), (ws, wt), "lane {i} of {n}: {at:?}");
            }
        }
    }

    #[test]
    fn lane_conversion_truncates_and_floors_as_x86() {
        let per_pixel = |q: f64, floor: bool| {
            let i = f64_to_i32_x86(q);
            if floor && (i as f64) > q && i != i32::MIN {
                i - 1
            } else {
                i
            }
        };
        let mut x = 0x853c_49e6_748f_ea9bu64;
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            -2.5,
            0.999_999,
            -0.999_999,
            2_147_483_647.0,
            2_147_483_647.5,
            2_147_483_647.999,
            2_147_483_648.0,
            -2_147_483_647.5,
            -2_147_483_648.0,
            -2_147_483_648.5,
            -2_147_483_649.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e300,
            -1e300,
            4.5e15,
            -4.5e15,
        ];
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let scale = f64::from(1u32 << (x % 32) as u32);
            values.push((x as i64 >> 11) as f64 / (1u64 << 21) as f64 * scale);
        }
        for q in values {
            for floor in [false, true] {
                assert_eq!(
                    f64_to_i32_lanes(q, floor),
                    per_pixel(q, floor),
                    "{q} {floor}"
                );
            }
        }
    }
}

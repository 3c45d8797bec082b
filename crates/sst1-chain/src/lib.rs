//! TMU chaining (spec 3.2): TMU2 -> TMU1 -> TMU0 -> FBI. Each TMU's output is the next
//! one's `c_other`; the last TMU in the chain sees zero. Each TMU's own combine unit is
//! `texelfx::combine`; this crate wires the TMUs of a board into the FBI's texel source
//! ([`pixelfx::TexelSource`]), with 86Box's chain shortcuts for its model
//! ([`texelfx::ChainModel::Box86`]).

use core::marker::PhantomData;

use pixelfx::span::{Lanes, LANES};
use pixelfx::{TexelSource, TmuStage};
use sst1_regs::Rgba;
use texelfx::{
    BaselineCopy, ChainModel, ColourLanes, KernelCopy, LaneOutput, LanePlace, LaneScratch,
    TexelModel, Tmu, TmuPixel, ZERO_COLOUR,
};

/// The TMUs taking part in a triangle, upstream last, run by model `M`.
pub struct Chain<'a, M> {
    tmus: &'a mut [Tmu],
    /// How they combine (TMU 0's profile as `M` reads it, once per triangle).
    wiring: ChainModel,
    model: PhantomData<M>,
}

impl<'a, M: TexelModel> Chain<'a, M> {
    /// The chain of `tmus` (TMU 0 first) for one triangle.
    pub fn new(tmus: &'a mut [Tmu]) -> Self {
        let wiring = tmus
            .first()
            .map_or(ChainModel::Full, |t| M::texel(&t.profile()).chain);
        Self {
            tmus,
            wiring,
            model: PhantomData,
        }
    }
}

impl<M: TexelModel> TexelSource for Chain<'_, M> {
    type Band<'s>
        = SharedChain<'s, M>
    where
        Self: 's;

    /// Shared where the chain is wired in full and every TMU can share its levels
    /// ([`Tmu::share_levels`]; not 86Box's chain or texture cache).
    fn share(&mut self) -> bool {
        self.wiring == ChainModel::Full && self.tmus.iter_mut().all(|t| t.share_levels::<M>())
    }

    fn band(&self) -> SharedChain<'_, M> {
        SharedChain::new(self.tmus)
    }

    /// Pure where the chain is wired in full and no TMU has an 86Box texture cache entry
    /// lent ([`Tmu::samples_purely`]).
    fn samples_purely(&self) -> bool {
        self.wiring == ChainModel::Full && self.tmus.iter().all(Tmu::samples_purely)
    }

    #[inline]
    fn texel(&mut self, dx: i32, dy: i32, x: i32, y: i32) -> Rgba {
        match self.tmus {
            [t0, rest @ ..] if self.wiring == ChainModel::Box86 => {
                box86_texel::<M>(t0, rest.first_mut(), dx, dy, x, y)
            }
            _ => {
                // Upstream first: the last TMU sees zero, each output feeds the next down.
                let mut other = Rgba::default();
                for t in self.tmus.iter_mut().rev() {
                    other = t.texel::<M>(dx, dy, x, y, other);
                }
                other
            }
        }
    }

    /// [`Chain::texel`] with each TMU's part ([`Tmu::texel_traced`]): the same TMU
    /// calls in the same order, so the same texel and the same cache effects.
    fn texel_stages(
        &mut self,
        dx: i32,
        dy: i32,
        x: i32,
        y: i32,
        stages: &mut Vec<TmuStage>,
    ) -> Rgba {
        match self.tmus {
            [t0, rest @ ..] if self.wiring == ChainModel::Box86 => {
                box86_texel_stages::<M>(t0, rest.first_mut(), (dx, dy, x, y), stages)
            }
            _ => {
                // Upstream first, as in `texel`.
                let mut other = Rgba::default();
                for t in self.tmus.iter_mut().rev() {
                    let p = t.texel_traced::<M>(dx, dy, x, y, other);
                    stages.push(stage(t, &p));
                    other = p.output;
                }
                other
            }
        }
    }

    /// The chunk's texels a stage at a time in each TMU ([`Tmu::texels`]), upstream TMU
    /// first over all lanes, its lanes the next one's `other` lanes: for every live lane
    /// exactly what [`Chain::texel`] gives, with every model and chain wiring.
    #[inline(always)]
    fn texels<K: KernelCopy>(
        &mut self,
        place: LanePlace<'_>,
        alive: &[bool; LANES],
        n: usize,
        out: &mut [Lanes; 4],
    ) {
        match self.tmus {
            [] => zero_live_lanes(alive, n, out),
            [t0, rest @ ..] if self.wiring == ChainModel::Box86 => {
                box86_texels::<M, K>(t0, rest.first_mut(), place, alive, n, out)
            }
            [t0, upstream @ ..] => {
                // Upstream first: the last TMU sees zero, each output feeds the next down.
                // The TMUs whose output nothing reads are skipped.
                let read = upstream_read(t0, upstream);
                let mut other = &ZERO_COLOUR;
                for t in upstream[..read].iter_mut().rev() {
                    other = t.texels_kept::<M, K>(place, alive, n, LaneOutput::Combined(other));
                }
                t0.texels::<M, K>(place, alive, n, LaneOutput::Combined(other), out);
            }
        }
    }
}

/// The chain read by one render thread ([`TexelSource::band`]): the TMUs shared, each
/// with this thread's lanes ([`LaneScratch`]). Only a fully wired chain is shared.
pub struct SharedChain<'a, M> {
    tmus: &'a [Tmu],
    /// One per TMU, in the order of `tmus`.
    scratch: Vec<LaneScratch>,
    /// The model is a type only: the view is `Send` whatever `M` is.
    model: PhantomData<fn() -> M>,
}

impl<'a, M> SharedChain<'a, M> {
    /// `tmus` (TMU 0 first) with fresh lanes for one thread.
    fn new(tmus: &'a [Tmu]) -> Self {
        Self {
            tmus,
            scratch: tmus.iter().map(|_| LaneScratch::new()).collect(),
            model: PhantomData,
        }
    }
}

/// No TMU: the live lanes of `out` read zero.
fn zero_live_lanes(alive: &[bool; LANES], n: usize, out: &mut [Lanes; 4]) {
    for ch in out.iter_mut() {
        for (v, &a) in ch[..n.min(LANES)].iter_mut().zip(alive) {
            if a {
                *v = 0;
            }
        }
    }
}

impl<M: TexelModel> TexelSource for SharedChain<'_, M> {
    type Band<'s>
        = SharedChain<'s, M>
    where
        Self: 's;

    fn share(&mut self) -> bool {
        true
    }

    fn band(&self) -> SharedChain<'_, M> {
        SharedChain::new(self.tmus)
    }

    /// A shared chain is pure: [`Chain::share`] refuses 86Box's chain and texture cache.
    fn samples_purely(&self) -> bool {
        true
    }

    /// One pixel as a chunk of one live lane (what [`SharedChain::texels`] gives it).
    fn texel(&mut self, dx: i32, dy: i32, x: i32, y: i32) -> Rgba {
        let mut alive = [false; LANES];
        alive[0] = true;
        let mut out = [[0; LANES]; 4];
        let place = LanePlace::Row {
            dx0: dx,
            dy,
            x0: x,
            y,
        };
        self.texels::<BaselineCopy>(place, &alive, 1, &mut out);
        let ch = |c: usize| out[c][0] as u8;
        Rgba {
            r: ch(0),
            g: ch(1),
            b: ch(2),
            a: ch(3),
        }
    }

    /// [`Chain::texels`] of a fully wired chain, each TMU through
    /// [`Tmu::texels_shared`].
    #[inline(always)]
    fn texels<K: KernelCopy>(
        &mut self,
        place: LanePlace<'_>,
        alive: &[bool; LANES],
        n: usize,
        out: &mut [Lanes; 4],
    ) {
        let (Some((t0, upstream)), Some((s0, upstream_scratch))) =
            (self.tmus.split_first(), self.scratch.split_first_mut())
        else {
            zero_live_lanes(alive, n, out);
            return;
        };
        // Upstream first: the last TMU sees zero, each output feeds the next down.
        // The TMUs whose output nothing reads are skipped.
        let read = upstream_read(t0, upstream);
        let mut other = &ZERO_COLOUR;
        let scratch = &mut upstream_scratch[..read];
        for (t, s) in upstream[..read].iter().zip(scratch.iter_mut()).rev() {
            let what = LaneOutput::Combined(other);
            other = t.texels_kept_shared::<M, K>(s, place, alive, n, what);
        }
        let what = LaneOutput::Combined(other);
        t0.texels_shared::<M, K>(s0, place, alive, n, what, out);
    }
}

/// How many of `upstream` (the TMUs above `t0`, nearest first) a chunk samples in a fully
/// wired chain: those up to the first TMU whose output reads no `other`
/// ([`Tmu::reads_other`]); the TMUs above it are skipped where every one of them samples
/// purely ([`Tmu::samples_purely`]), else all are sampled, as the per-pixel path does.
#[inline]
fn upstream_read(t0: &Tmu, upstream: &[Tmu]) -> usize {
    let mut read = 0;
    let mut below = t0;
    while read < upstream.len() && below.reads_other() {
        below = &upstream[read];
        read += 1;
    }
    if upstream[read..].iter().all(Tmu::samples_purely) {
        read
    } else {
        upstream.len()
    }
}

/// `textureMode` bits 86Box compares to spot TMU 0's local decal, and that pattern
/// (`TEXTUREMODE_LOCAL_MASK`, `TEXTUREMODE_LOCAL`).
const BOX86_LOCAL_MASK: u32 = 0x0064_3000;
const BOX86_LOCAL: u32 = 0x0024_1000;
/// The combine bits of `textureMode` (`TEXTUREMODE_MASK`); all zero is a pass-through.
const BOX86_COMBINE_MASK: u32 = 0x3fff_f000;

/// Which TMUs a pixel (or chunk) reads under [`ChainModel::Box86`]: TMU 0 and, if
/// present, TMU 1 (a third TMU is not read).
/// Source: 86Box `voodoo_half_triangle` (the choice between the three paths).
enum Box86Route<'a> {
    /// One TMU's texel, uncombined: TMU 0 on a one-TMU board or in local-only mode, or
    /// TMU 1 where TMU 0 passes it through.
    Alone(&'a mut Tmu),
    /// TMU 1's output (under TMU 0's `textureMode`, the `u32`) into TMU 0's combine unit.
    Combined(&'a mut Tmu, &'a mut Tmu, u32),
}

impl<'a> Box86Route<'a> {
    #[inline(always)]
    fn of(t0: &'a mut Tmu, t1: Option<&'a mut Tmu>) -> Self {
        let mode = t0.texture_mode();
        match t1 {
            None => Self::Alone(t0),
            Some(_) if mode & BOX86_LOCAL_MASK == BOX86_LOCAL => Self::Alone(t0),
            Some(t1) if mode & BOX86_COMBINE_MASK == 0 => Self::Alone(t1),
            Some(t1) => Self::Combined(t0, t1, mode),
        }
    }
}

/// [`ChainModel::Box86`]'s texel for one pixel ([`Box86Route`]).
fn box86_texel<M: TexelModel>(
    t0: &mut Tmu,
    t1: Option<&mut Tmu>,
    dx: i32,
    dy: i32,
    x: i32,
    y: i32,
) -> Rgba {
    match Box86Route::of(t0, t1) {
        Box86Route::Alone(t) => t.texel_uncombined::<M>(dx, dy, x, y),
        Box86Route::Combined(t0, t1, mode) => {
            let other = t1.texel_box86_upstream::<M>(dx, dy, x, y, mode);
            t0.texel::<M>(dx, dy, x, y, other)
        }
    }
}

/// [`box86_texel`] with each TMU's part ([`Tmu::texel_traced`]), upstream first.
fn box86_texel_stages<M: TexelModel>(
    t0: &mut Tmu,
    t1: Option<&mut Tmu>,
    (dx, dy, x, y): (i32, i32, i32, i32),
    stages: &mut Vec<TmuStage>,
) -> Rgba {
    let mut one = |t: &mut Tmu, p: TmuPixel| {
        stages.push(stage(t, &p));
        p.output
    };
    match Box86Route::of(t0, t1) {
        Box86Route::Alone(t) => {
            let p = t.texel_uncombined_traced::<M>(dx, dy, x, y);
            one(t, p)
        }
        Box86Route::Combined(t0, t1, mode) => {
            let p = t1.texel_box86_upstream_traced::<M>(dx, dy, x, y, mode);
            let other = one(t1, p);
            let p = t0.texel_traced::<M>(dx, dy, x, y, other);
            one(t0, p)
        }
    }
}

/// A TMU's part of a texel as the pixel history records it.
fn stage(t: &Tmu, p: &TmuPixel) -> TmuStage {
    TmuStage {
        tmu: t.index(),
        s_32: p.s_32,
        t_32: p.t_32,
        w_32: p.w_32,
        lod_8_8: p.lod_8_8,
        lod_fraction: p.lod_fraction,
        texel: p.texel.into(),
        output: p.output.into(),
    }
}

/// [`box86_texel`] for the live lanes of one chunk: the same choice, once per chunk.
#[inline(always)]
fn box86_texels<M: TexelModel, K: KernelCopy>(
    t0: &mut Tmu,
    t1: Option<&mut Tmu>,
    place: LanePlace<'_>,
    alive: &[bool; LANES],
    n: usize,
    out: &mut ColourLanes,
) {
    match Box86Route::of(t0, t1) {
        Box86Route::Alone(t) => t.texels::<M, K>(place, alive, n, LaneOutput::Texel, out),
        Box86Route::Combined(t0, t1, mode) => {
            let upstream = LaneOutput::Box86Upstream(mode);
            let other = t1.texels_kept::<M, K>(place, alive, n, upstream);
            t0.texels::<M, K>(place, alive, n, LaneOutput::Combined(other), out);
        }
    }
}

//! Triangle rasterization: spans from [`crate::setup`], clipping, and the per-pixel walk
//! with the iterators (spec 5.15 `triangleCMD`, 5.21 clip registers, 5.19 Y origin).

use std::collections::VecDeque;
use std::ops::Range;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

pub use sst1_regs::lanes::{Avx2Copy, Avx512Copy, BaselineCopy, KernelCopy};
pub use sst1_regs::LanePlace;
use sst1_regs::Rgba;

use crate::fbi::Fbi;
use crate::fbi::PathCounts;
use crate::helpers::Helpers;
use crate::isa::VectorIsa;
use crate::iter::Iterated;
use crate::model::PixelModel;
use crate::params::TriangleParams;
use crate::pipeline::{DrawState, Source};
use crate::profile::StippleRotate;
use crate::span::{
    chunk_len, ChunkAt, ChunkJob, Lanes, Memory, Packed, RowPlace, Shader, TriangleConsts, Words,
    LANES, PACK,
};
use crate::stats::Stats;
use crate::watch::NoStages;
use crate::{box86, setup};

/// What the TMU chain gives the FBI for one pixel.
pub trait TexelSource {
    /// A view of the source for one render thread ([`TexelSource::band`]).
    type Band<'s>: TexelSource + Send
    where
        Self: 's;

    /// Readies the source to be read from several render threads at once for the
    /// current triangle, each through its own [`TexelSource::band`]; `false` where it
    /// cannot be (its texels have state of their own), and the triangle is drawn on one
    /// thread.
    fn share(&mut self) -> bool;

    /// A view for one render thread, after [`TexelSource::share`] returned `true`: it
    /// gives every texel [`TexelSource::texels`] would.
    fn band(&self) -> Self::Band<'_>;

    /// The texel for the pixel at offset `(dx, dy)` from vertex A's pixel, at screen
    /// position `(x, y)`.
    fn texel(&mut self, dx: i32, dy: i32, x: i32, y: i32) -> Rgba;

    /// Whether reading texels changes nothing that a later texel can see, so that the
    /// span kernels may skip the source for a triangle whose pixels read no texel
    /// ([`crate::pipeline::DrawState::for_span_kernels`]). This default says no.
    fn samples_purely(&self) -> bool {
        false
    }

    /// [`TexelSource::texel`] for a watched pixel ([`crate::watch`]): the same texel,
    /// with the same effect on any state of the source, and each TMU's part of it
    /// pushed to `tmus`, upstream TMU first. This default pushes nothing.
    fn texel_stages(
        &mut self,
        dx: i32,
        dy: i32,
        x: i32,
        y: i32,
        tmus: &mut Vec<crate::watch::TmuStage>,
    ) -> Rgba {
        let _ = tmus;
        self.texel(dx, dy, x, y)
    }

    /// The texels of the live lanes of one chunk ([`crate::span`]), each lane the pixel
    /// `place` gives it: for each `i < n` with `alive[i]`, its texel's R, G, B, A go to
    /// `out[0..4][i]`. Other lanes of `out` are left as they are. This default asks
    /// [`TexelSource::texel`] for the live lanes in order, as the reference path does; an
    /// override (the TMU chain's) may compute a stage at a time over the lanes, as long
    /// as every texel, and any state a later texel depends on, is what the default would
    /// give.
    #[inline(always)]
    fn texels<K: KernelCopy>(
        &mut self,
        place: LanePlace<'_>,
        alive: &[bool; LANES],
        n: usize,
        out: &mut [Lanes; 4],
    ) {
        for i in 0..n.min(LANES) {
            if alive[i] {
                let (dx, dy, x, y) = place.at(i);
                let t = self.texel(dx, dy, x, y);
                out[0][i] = t.r as i32;
                out[1][i] = t.g as i32;
                out[2][i] = t.b as i32;
                out[3][i] = t.a as i32;
            }
        }
    }
}

/// The source for untextured drawing: always zero.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoTexture;

impl TexelSource for NoTexture {
    type Band<'s> = NoTexture;

    fn share(&mut self) -> bool {
        true
    }

    fn band(&self) -> NoTexture {
        NoTexture
    }

    fn samples_purely(&self) -> bool {
        true
    }

    #[inline]
    fn texel(&mut self, _dx: i32, _dy: i32, _x: i32, _y: i32) -> Rgba {
        Rgba::default()
    }
}

impl Fbi {
    /// Draw the triangle held in the parameter registers (the `triangleCMD` command).
    /// The caller has applied subpixel correction if `fbzColorPath` asks for it.
    ///
    /// Runs the span kernels ([`crate::span`]) unless [`Fbi::set_generic_path`] forced
    /// the reference path (the pipeline pixel by pixel, every mode bit tested per pixel).
    ///
    /// `M` is the model of the chip ([`crate::model`]); the caller guarantees that the
    /// profile this FBI holds is `M`'s.
    pub fn draw_triangle<M: PixelModel, T: TexelSource>(&mut self, tex: &mut T) {
        self.stats.triangles += 1;
        let mode = self.fbz_mode();
        let Some(dest) = self.colour_buffer(mode.draw_buffer()) else {
            return;
        };
        let st = DrawState::capture::<M>(self, dest);
        if self.generic_path || !M::SPAN_KERNELS {
            self.walk::<M, T, false>(&st, tex);
        } else {
            let st = st.for_span_kernels(&M::pixel(&self.profile()), tex.samples_purely());
            self.walk::<M, T, true>(&st, tex);
        }
    }

    /// Force the reference path (every mode register read at run time for every pixel)
    /// instead of the span kernels, and fills pixel by pixel instead of by rows. Both
    /// give identical pixels and counters; the switch
    /// exists to prove that (`crates/board/tests/generic_vs_fast.rs`) and to debug the
    /// kernels.
    pub fn set_generic_path(&mut self, on: bool) {
        self.generic_path = on;
    }

    /// Shade large triangles on `threads` render threads (1: on the calling thread only;
    /// 0 counts as 1, more than [`MAX_THREADS`] as that); a textured one only where its
    /// [`TexelSource::share`] agrees. Pixels and counters are the same for every count;
    /// the calling thread is one of them, and the others are a pool of this FBI's own
    /// (one that cannot be started leaves the FBI on the calling thread alone).
    pub fn set_threads(&mut self, threads: usize) {
        let threads = threads.clamp(1, MAX_THREADS);
        if threads == self.threads {
            return;
        }
        // A pool of exactly the helpers: with more threads than cores, a helper woken for
        // a triangle may wait for the calling thread's core and start only once the
        // triangle is done.
        self.helpers = (threads > 1)
            .then(|| Helpers::new(threads - 1))
            .flatten()
            .map(std::sync::Arc::new);
        self.threads = if self.helpers.is_some() { threads } else { 1 };
    }

    /// Run the copy of the span kernels compiled for `cap`, or the best one the CPU has
    /// below it ([`crate::isa`]); returns the copy that will run. The integers are the
    /// same for every copy. Each FBI starts with [`VectorIsa::best`].
    pub fn set_vector_isa(&mut self, cap: VectorIsa) -> VectorIsa {
        self.isa = cap.min(VectorIsa::best());
        self.isa
    }

    /// The copy of the span kernels that runs ([`Fbi::set_vector_isa`]).
    pub fn vector_isa(&self) -> VectorIsa {
        self.isa
    }

    /// The render threads set with [`Fbi::set_threads`].
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// Whether the generic path is forced.
    pub fn generic_path(&self) -> bool {
        self.generic_path
    }

    /// Walk the triangle's spans and shade their pixels: a chunk of up to
    /// [`crate::span::LANES`] pixels at a time with the span kernels (`SPANS`), or one
    /// pixel at a time with the reference path. With more than one render thread
    /// ([`Fbi::set_threads`]), the rows of a large triangle are shaded in bands
    /// on several threads ([`Fbi::shade_rows_threaded`]).
    #[inline(always)]
    pub(crate) fn walk<M: PixelModel, T: TexelSource, const SPANS: bool>(
        &mut self,
        st: &DrawState,
        tex: &mut T,
    ) {
        let mode = st.mode;
        let flip = mode.y_origin();
        let profile = M::pixel(&self.profile());
        let origin = profile.param_origin;
        let a = (origin.pixel(self.params.ax), origin.pixel(self.params.ay));
        let params = self.params;
        // Only rotate-mode stipple reads the per-triangle copy.
        let per_triangle = profile.stipple_rotate == StippleRotate::PerTriangle
            && mode.enable_stipple()
            && !mode.enable_stipple_pattern();
        let mut copy = per_triangle.then(|| box86::StippleCopy::new(st.stipple));
        let consts = SPANS.then(|| match self.consts.take() {
            Some(mut c) => {
                c.update(st);
                c
            }
            None => Box::new(TriangleConsts::new(st)),
        });
        // Bands need rows that depend on nothing but themselves: no per-triangle stipple
        // copy (stepped row by row), and a texel source that can be shared
        // ([`TexelSource::share`], asked once the triangle is known to be large).
        // A triangle whose bounding box holds fewer pixels than the bands take is drawn
        // on this thread without collecting its rows first.
        // The helpers (there are some only with more than one render thread) spin from
        // here until the bands are queued ([`crate::helpers`]). (The pool's handle is
        // cloned only for such a triangle: a clone for every triangle cost small
        // triangles 2 % on two threads.)
        let woken = self
            .helpers
            .as_ref()
            .filter(|_| SPANS && copy.is_none())
            .filter(|_| box_pixels(&params) >= MIN_THREADED_PIXELS as u64)
            .cloned();
        if let Some(h) = &woken {
            h.wake();
        }
        let threaded = woken.is_some();
        // Short spans go into chunks packed from several spans (not with the per-triangle
        // stipple copy, which is stepped span by span).
        let mut pack = (SPANS && copy.is_none()).then(|| {
            let mut p = self.pack.take().unwrap_or_else(|| Box::new(Pack::new()));
            p.start(st, &self.params);
            p
        });
        let mut rows = Vec::new();
        for span in setup::spans(&params, profile.edge_rounding) {
            let (mut start, mut stop) = (span.start, span.stop);
            // Every pixel the walker visits counts as "in" (spec 5.31), clipped or not.
            self.stats.pixels_in += (stop - start) as u64;
            self.stats.spans += 1;
            let scry = st.screen_y(span.y, flip);
            // The watch forces the reference path, so only it looks for the watched pixel.
            if !SPANS {
                self.watch_clip(st, scry, start, stop);
            }
            if mode.enable_clipping() {
                let (left, right, low, high) = st.clip;
                if scry < low || scry >= high {
                    continue;
                }
                start = start.max(left);
                stop = stop.min(right);
            }
            if start >= stop {
                continue;
            }
            let row = Row {
                y: span.y,
                scry,
                start,
                stop,
                prow: profile.pattern_row.row(span.y, scry),
            };
            if threaded {
                rows.push(row);
            } else {
                self.shade_or_pack::<M, T>(
                    st,
                    &row,
                    a,
                    &mut copy,
                    tex,
                    consts.as_deref(),
                    &mut pack,
                );
            }
        }
        let banded = match (&woken, &consts) {
            (Some(h), Some(c)) => self.shade_rows_threaded::<M, T>(st, &rows, a, c, tex, h),
            _ => false,
        };
        // Banded, the helpers were released as the bands were queued; not, they are now.
        if let Some(h) = &woken {
            h.release();
        }
        if threaded && !banded {
            for row in &rows {
                self.shade_or_pack::<M, T>(
                    st,
                    row,
                    a,
                    &mut copy,
                    tex,
                    consts.as_deref(),
                    &mut pack,
                );
            }
        }
        if let (Some(p), Some(consts)) = (&mut pack, &consts) {
            self.shade_pack::<M, T>(st, p, tex, consts);
        }
        if pack.is_some() {
            self.pack = pack;
        }
        if consts.is_some() {
            self.consts = consts;
        }
    }

    /// Shade `row` ([`Fbi::shade_row`]), or, where `pack` is given and the row can go in
    /// a packed chunk ([`Pack::admits`]), add it to the pack, shading the pack first if
    /// the row does not fit in it. A row that cannot be packed shades the pack first, so
    /// that rows are shaded in the walk's order.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn shade_or_pack<M: PixelModel, T: TexelSource>(
        &mut self,
        st: &DrawState,
        row: &Row,
        a: (i32, i32),
        copy: &mut Option<box86::StippleCopy>,
        tex: &mut T,
        consts: Option<&TriangleConsts>,
        pack: &mut Option<Box<Pack>>,
    ) {
        if let (Some(p), Some(c)) = (pack.as_mut(), consts) {
            match p.admits(row, &self.fb) {
                Admit::Now => return p.push(row, a, self.fb.layout.row_pixels),
                Admit::AfterShading => {
                    self.shade_pack::<M, T>(st, p, tex, c);
                    return p.push(row, a, self.fb.layout.row_pixels);
                }
                Admit::Never => self.shade_pack::<M, T>(st, p, tex, c),
            }
        }
        self.shade_row::<M, T>(st, row, a, copy, tex, consts);
    }

    /// What the span kernels read and count of this FBI, and the frame buffer they write.
    #[inline(always)]
    fn shader_and_memory(&mut self) -> (Shader<'_>, Memory<'_>) {
        let shader = Shader {
            stats: &mut self.stats,
            counts: &mut self.path_counts,
            dither: &self.dither,
            fog_table: &self.fog_table,
            params: &self.params,
            profile: self.profile,
            isa: self.isa,
        };
        (shader, Memory::Whole(&mut self.fb.ram))
    }

    /// Shade the rows in `pack` as one chunk and empty it.
    fn shade_pack<M: PixelModel, T: TexelSource>(
        &mut self,
        st: &DrawState,
        pack: &mut Pack,
        tex: &mut T,
        consts: &TriangleConsts,
    ) {
        if pack.lanes.n == 0 {
            return;
        }
        self.path_counts.packed += pack.lanes.n as u64;
        let mut stipple = st.stipple;
        let (mut shader, mut mem) = self.shader_and_memory();
        let job = ChunkJob {
            st,
            stipple_state: &mut stipple,
            copy: None,
            tex,
            consts,
            mem: &mut mem,
        };
        shader.shade_chunk_of::<M, T, _>(job, &pack.lanes);
        pack.clear();
    }

    /// Shade one row of a triangle, by chunks with the span kernels when `consts` is
    /// given, else pixel by pixel with the reference path. `(ax, ay)` is vertex A's
    /// pixel.
    #[inline(always)]
    fn shade_row<M: PixelModel, T: TexelSource>(
        &mut self,
        st: &DrawState,
        row: &Row,
        (ax, ay): (i32, i32),
        copy: &mut Option<box86::StippleCopy>,
        tex: &mut T,
        consts: Option<&TriangleConsts>,
    ) {
        let Row {
            y,
            scry,
            start,
            stop,
            prow,
        } = *row;
        let dy = y - ay;
        let mut stipple = st.stipple;
        if let Some(c) = copy {
            c.step_row(start, stop, self.params.right_to_left);
        }
        if let Some(consts) = consts.filter(|_| stop - start > SHORT_ROW) {
            let mut x0 = start;
            while x0 < stop {
                let n = chunk_len((stop - x0) as usize);
                let at = ChunkAt {
                    x0,
                    n,
                    y,
                    scry,
                    prow,
                    span_start: start,
                    ax,
                    dy,
                };
                let it = Iterated::at(&self.params, x0 - ax, dy);
                let dest_words = Words::of(self, st.dest, x0, n, scry);
                let aux_words = st
                    .aux
                    .map_or(Words::NONE, |a| Words::of(self, a, x0, n, scry));
                if dest_words.crosses(&aux_words) {
                    self.shade_chunk_per_pixel::<M, T>(
                        st,
                        &at,
                        &it,
                        &mut stipple,
                        copy.as_ref(),
                        tex,
                    );
                } else {
                    let (mut shader, mut mem) = self.shader_and_memory();
                    let place = RowPlace {
                        at: &at,
                        it: &it,
                        params: shader.params,
                        words: (dest_words, aux_words),
                    };
                    let job = ChunkJob {
                        st,
                        stipple_state: &mut stipple,
                        copy: copy.as_ref(),
                        tex,
                        consts,
                        mem: &mut mem,
                    };
                    shader.shade_chunk_of::<M, T, _>(job, &place);
                }
                x0 += n as i32;
            }
            return;
        }
        if consts.is_some() {
            self.path_counts.short_rows += (stop - start) as u64;
        } else {
            self.path_counts.reference += (stop - start) as u64;
        }
        // A copy: the pixels below borrow the FBI mutably.
        let params = self.params;
        let watched = self.watched_column(scry);
        let mut it = Iterated::at(&params, start - ax, dy);
        for x in start..stop {
            if let Some(c) = &copy {
                stipple = c.at((x - start) as usize);
            }
            if watched == Some(x) {
                let at = (x - ax, dy, x, y);
                self.shade_watched::<M, T>(st, prow, scry, &it, &mut stipple, tex, at);
            } else {
                let r = self.shade_pixel::<M, NoStages>(
                    st,
                    x,
                    prow,
                    scry,
                    &it,
                    Source::Triangle,
                    &mut stipple,
                    || tex.texel(x - ax, dy, x, y),
                    &mut NoStages,
                );
                self.count(r);
            }
            it.step_x(&params);
        }
    }

    /// Shade `rows` (a triangle's, clipped) in bands taken from one queue by the render
    /// threads, each thread with its own counters, added up afterwards, and its own view
    /// of the texel source ([`TexelSource::band`]). A band ([`band_rows`]) is rows whose
    /// words (colour and aux alike, at the same offsets) meet no other band's: a row whose
    /// lanes run past the frame-buffer row's end into the next row, as the single walk
    /// lets them, shares a band with the rows it meets, and so do two rows on one
    /// frame-buffer row (the Y-origin flip wraps at 1024); a band shades its rows in the
    /// walk's order. So the bands give the pixels and counters of the single walk
    /// whatever the thread count. Returns `false`, having done nothing, for a small
    /// triangle (not worth the threads), a texel source that cannot be shared, colour
    /// and aux words that share memory, or rows that make only one band.
    fn shade_rows_threaded<M: PixelModel, T: TexelSource>(
        &mut self,
        st: &DrawState,
        rows: &[Row],
        a: (i32, i32),
        consts: &TriangleConsts,
        tex: &mut T,
        helpers: &Helpers,
    ) -> bool {
        let row_pixels = i64::from(self.fb.layout.row_pixels);
        let pixels: usize = rows.iter().map(|r| (r.stop - r.start) as usize).sum();
        if row_pixels == 0 || pixels < MIN_THREADED_PIXELS {
            return false;
        }
        if st.color_path.texture_enable() && st.fetch_texel && !tex.share() {
            return false;
        }
        let pieces = row_pieces(rows, row_pixels);
        let (order, bands) = band_rows(&pieces, row_pixels);
        if bands.len() < 2 {
            return false;
        }
        // The span of every band's words, as offsets from a buffer's base: the bands with
        // words are in memory order, and each ends at or past every word before it.
        let mut placed = bands.iter().filter_map(|b| b.words.as_ref());
        let Some(first) = placed.next() else {
            return false;
        };
        let (lowest, highest) = (first.start, placed.next_back().unwrap_or(first).end);
        let len = self.fb.ram.len();
        let colour = existing(st.dest, &(lowest..highest), len);
        let aux = st
            .aux
            .map_or(0..0, |b| existing(b, &(lowest..highest), len));
        let ram = &mut self.fb.ram[..];
        let (colour_words, aux_words): (&mut [u16], &mut [u16]) = if aux.is_empty() {
            (&mut ram[colour.clone()], &mut [])
        } else if colour.is_empty() {
            (&mut [], &mut ram[aux.clone()])
        } else if aux.start >= colour.end {
            let (lo, hi) = ram.split_at_mut(aux.start);
            (&mut lo[colour.clone()], &mut hi[..aux.len()])
        } else if colour.start >= aux.end {
            let (lo, hi) = ram.split_at_mut(colour.start);
            (&mut hi[..colour.len()], &mut lo[aux.clone()])
        } else {
            return false;
        };
        let colour_bands = cut_bands(&bands, colour_words, colour.start, Some(st.dest));
        let aux_bands = cut_bands(&bands, aux_words, aux.start, st.aux);
        // The pieces band after band, so that each band's are one slice of them.
        let in_bands: Vec<Piece> = order.iter().map(|&i| pieces[i]).collect();
        let parts = bands.iter().zip(colour_bands).zip(aux_bands);
        let jobs: Vec<BandJob<'_, '_>> = parts
            .map(|((band, colour), aux)| BandJob {
                rows: &in_bands[band.rows.clone()],
                colour,
                aux,
            })
            .collect();
        // This thread and up to `threads - 1` of the pool's take the bands from one
        // queue, a band at a time: a thread that starts late (woken from sleep) takes
        // fewer, and this thread never waits idle for one to start. This thread takes
        // them from the front, the helpers from the back: neighbouring bands share the
        // cache line at their boundary (rows need not start on a line), and two threads
        // shading neighbours at once move it from core to core (1.1x on
        // perf_gouraud_heavy against both taking from the front).
        let helpers_spawned = (self.threads - 1).min(jobs.len() - 1);
        let queue = Mutex::new(VecDeque::from(jobs));
        let mut counters = vec![ThreadCounters::default(); helpers_spawned + 1];
        let (dither, fog_table, params, profile, isa) = (
            &self.dither,
            &self.fog_table,
            &self.params,
            self.profile,
            self.isa,
        );
        let shade_queued = |ThreadCounters(stats, counts): &mut ThreadCounters,
                            mut source: T::Band<'_>,
                            from_back: bool| {
            let mut shader = Shader {
                stats,
                counts,
                dither,
                fog_table,
                params,
                profile,
                isa,
            };
            let next = || {
                let mut queue = queue.lock().unwrap_or_else(PoisonError::into_inner);
                if from_back {
                    queue.pop_back()
                } else {
                    queue.pop_front()
                }
            };
            while let Some(job) = next() {
                shade_band::<M, _>(&mut shader, st, job, (a, row_pixels), consts, &mut source);
            }
        };
        let (here, pool) = counters.split_first_mut().expect("one counter per thread");
        let finished = AtomicUsize::new(0);
        helpers.release();
        helpers.pool().in_place_scope(|scope| {
            for counter in pool {
                let source = tex.band();
                let (shade_queued, finished) = (&shade_queued, &finished);
                scope.spawn(move |_| {
                    shade_queued(counter, source, true);
                    finished.fetch_add(1, Ordering::Release);
                });
            }
            shade_queued(here, tex.band(), false);
            // The queue is empty, so each helper is at most one band from done: wait for
            // them here rather than sleep at the scope's end, whose wake-up takes longer
            // than a band; one that has not started is waited for here only so long.
            let waited = Instant::now();
            while finished.load(Ordering::Acquire) < helpers_spawned && waited.elapsed() < END_SPIN
            {
                std::hint::spin_loop();
            }
        });
        for ThreadCounters(stats, counts) in &counters {
            self.stats.add(stats);
            self.path_counts.add(counts);
            self.path_counts.in_bands += counts.span_kernels;
        }
        true
    }
}

/// One render thread's counters, alone in their cache lines: the threads update them
/// chunk by chunk, and counters that shared a line would move it from core to core.
#[derive(Clone, Default)]
#[repr(align(128))]
struct ThreadCounters(Stats, PathCounts);

/// The words at offsets `w` from the buffer at `base` that exist in a memory of `len`
/// words.
fn existing(base: usize, w: &Range<i64>, len: usize) -> Range<usize> {
    let len = len as i64;
    let (lo, hi) = (base as i64 + w.start, base as i64 + w.end);
    (lo.min(len) as usize)..(hi.min(len).max(lo.min(len)) as usize)
}

/// Each band's words of one buffer (at `base`; `None`: no such buffer), cut from `words`,
/// the region of them all, which starts at word `first` (the bands are in memory order).
fn cut_bands<'m>(
    bands: &[Band],
    mut words: &'m mut [u16],
    first: usize,
    base: Option<usize>,
) -> Vec<BandWords<'m>> {
    let end = first + words.len();
    let mut at = first;
    let mut slices = Vec::with_capacity(bands.len());
    for band in bands {
        let own = match (base, &band.words) {
            (Some(base), Some(w)) => existing(base, w, end),
            _ => at..at,
        };
        let own = own.start.max(at)..own.end.max(at);
        let (_, rest) = std::mem::take(&mut words).split_at_mut(own.start - at);
        let (mine, rest) = rest.split_at_mut(own.len());
        words = rest;
        at = own.end;
        slices.push(BandWords {
            words: mine,
            first: own.start as i64 - base.map_or(0, |b| b as i64),
        });
    }
    slices
}

/// A piece of a row of the walk: the columns of one frame-buffer row's words (a row
/// whose lanes run past the pitch into the next row is cut there, so that its pieces
/// and the next row's may go to different bands), and the column the row starts at.
#[derive(Clone, Copy, Debug)]
struct Piece {
    row: Row,
    row_start: i32,
}

/// The walk's rows in pieces, in the walk's order ([`Piece`]): each row cut at every
/// column that is a multiple of the pitch; columns left of 0 stay with the first piece,
/// and a row above row 0 (no words) stays whole.
fn row_pieces(rows: &[Row], row_pixels: i64) -> Vec<Piece> {
    let mut pieces = Vec::with_capacity(rows.len());
    for row in rows {
        let mut start = row.start;
        while start < row.stop {
            let column = i64::from(start.max(0));
            let end = if row.scry < 0 {
                row.stop
            } else {
                let next_pitch = (column / row_pixels + 1) * row_pixels;
                next_pitch.min(i64::from(row.stop)) as i32
            };
            pieces.push(Piece {
                row: Row {
                    start,
                    stop: end,
                    ..*row
                },
                row_start: row.start,
            });
            start = end;
        }
    }
    pieces
}

/// Row pieces of a triangle's walk that one render thread shades, in the walk's order.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Band {
    /// The pieces, as a range of the order [`band_rows`] returns (indices of
    /// [`row_pieces`]' list, ascending within each band: the walk's order).
    rows: Range<usize>,
    /// Offsets from a buffer's base of the words its pieces may touch (`None`: none).
    words: Option<Range<i64>>,
}

/// The offsets from a buffer's base of the words `row` may touch, as
/// [`crate::fb::FrameBuffer::index`] finds them (no word left of column 0 or above row
/// 0; columns past the row's end run on into the next row), memory's end not applied.
fn row_words(row: &Row, row_pixels: i64) -> Option<Range<i64>> {
    let first = i64::from(row.start.max(0));
    let stop = i64::from(row.stop);
    (row.scry >= 0 && first < stop).then(|| {
        let at = i64::from(row.scry) * row_pixels;
        at + first..at + stop
    })
}

/// The walk's row pieces cut into [`Band`]s whose words do not meet, in memory order: the
/// pieces with words sorted by their first word, each band at least [`BAND_ROWS`] of them
/// (the last may hold fewer), ending only where the next piece's words start at or past
/// the end of every word before; the pieces with no words in bands of their own, first.
/// Returns the pieces' indices band after band, and the bands as ranges of them: one
/// list for the whole walk rather than one per band (a large triangle has hundreds).
fn band_rows(pieces: &[Piece], row_pixels: i64) -> (Vec<usize>, Vec<Band>) {
    let words: Vec<Option<Range<i64>>> = pieces
        .iter()
        .map(|p| row_words(&p.row, row_pixels))
        .collect();
    let mut order: Vec<usize> = (0..pieces.len()).collect();
    // The pieces with no words first (a stable sort keeps them in the walk's order),
    // then those with words by their first word.
    order.sort_by_key(|&i| words[i].as_ref().map(|w| w.start));
    let none = order.iter().take_while(|&&i| words[i].is_none()).count();
    let mut bands: Vec<Band> = (0..none)
        .step_by(BAND_ROWS)
        .map(|at| Band {
            rows: at..(at + BAND_ROWS).min(none),
            words: None,
        })
        .collect();
    let mut band: Option<Band> = None;
    for (at, &i) in order.iter().enumerate().skip(none) {
        let w = words[i].clone().unwrap_or_default();
        match &mut band {
            Some(b) => {
                let hull = b.words.clone().unwrap_or_default();
                if b.rows.len() >= BAND_ROWS && w.start >= hull.end {
                    bands.extend(band.replace(Band {
                        rows: at..at + 1,
                        words: Some(w),
                    }));
                } else {
                    b.rows.end = at + 1;
                    b.words = Some(hull.start..hull.end.max(w.end));
                }
            }
            None => {
                band = Some(Band {
                    rows: at..at + 1,
                    words: Some(w),
                })
            }
        }
    }
    bands.extend(band);
    for b in &bands {
        order[b.rows.clone()].sort_unstable();
    }
    (order, bands)
}

/// The most render threads [`Fbi::set_threads`] takes.
pub const MAX_THREADS: usize = 256;

/// How long the calling thread waits, spinning, for the render threads to finish a
/// triangle's last bands before it sleeps until they do.
const END_SPIN: Duration = Duration::from_micros(200);

/// Rows per band of the threaded walk.
const BAND_ROWS: usize = 4;

/// The fewest pixels a triangle must have for its rows to go to the render threads.
pub(crate) const MIN_THREADED_PIXELS: usize = 4096;

/// At least as many pixels as the triangle of `p` covers: its vertices' bounding box in
/// whole pixels, with a pixel's margin on every side (each walk's spans lie between its
/// vertices' coordinates, rounded to pixel boundaries).
pub(crate) fn box_pixels(p: &TriangleParams) -> u64 {
    let span = |a: i16, b: i16, c: i16| {
        let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
        ((i32::from(hi) - i32::from(lo)) >> 4) as u64 + 3
    };
    span(p.ax, p.bx, p.cx) * span(p.ay, p.by, p.cy)
}

/// One row of a triangle after clipping: where its pixels are.
#[derive(Clone, Copy, Debug)]
struct Row {
    /// Raster row.
    y: i32,
    /// Frame-buffer row after the Y-origin flip.
    scry: i32,
    /// Columns `start..stop`.
    start: i32,
    stop: i32,
    /// Row the dither and stipple patterns are indexed with.
    prow: i32,
}

/// Whether a row can join a [`Pack`].
enum Admit {
    /// As it is.
    Now,
    /// Once the pack's rows are shaded (it does not fit with them).
    AfterShading,
    /// Not at all: it is shaded by itself ([`Fbi::shade_row`]).
    Never,
}

/// Short rows of one triangle gathered into one chunk of [`PACK`] lanes
/// ([`crate::span::Packed`]), in the walk's order. A row joins only if every pixel of it
/// has a word of its own in each buffer (the row lies in the frame buffer, within the
/// row pitch, on a frame-buffer row no other row of the pack is on) and no lane's colour
/// word can be another lane's aux word: then reading every lane's words before writing
/// any gives what shading the rows one after the other gives.
pub(crate) struct Pack {
    lanes: Packed,
    /// The rows' frame-buffer rows.
    scry: [i32; PACK],
    rows: usize,
    /// The lanes' lowest and highest word offsets.
    words: (usize, usize),
}

impl Pack {
    fn new() -> Self {
        Self {
            lanes: Packed::new(),
            scry: [0; PACK],
            rows: 0,
            words: (usize::MAX, 0),
        }
    }

    /// Empty, for a triangle drawn with `st` from `params`.
    fn start(&mut self, st: &DrawState, params: &TriangleParams) {
        self.lanes.colour_base = st.dest;
        self.lanes.aux_base = st.aux;
        self.lanes.params = *params;
        self.clear();
    }

    fn clear(&mut self) {
        self.lanes.n = 0;
        self.rows = 0;
        self.words = (usize::MAX, 0);
    }

    /// Whether `row` can join (see [`Pack`]).
    #[inline(always)]
    fn admits(&self, row: &Row, fb: &crate::fb::FrameBuffer) -> Admit {
        let len = (row.stop - row.start) as usize;
        let pitch = fb.layout.row_pixels as usize;
        if len > PACK || row.scry < 0 || row.start < 0 || row.stop as usize > pitch {
            return Admit::Never;
        }
        let first = row.scry as usize * pitch + row.start as usize;
        let last = first + len - 1;
        let bases = [Some(self.lanes.colour_base), self.lanes.aux_base];
        if bases.iter().flatten().any(|b| b + last >= fb.ram.len()) {
            return Admit::Never;
        }
        // Colour and aux words meet only if the buffers are closer than the words span.
        let apart = match self.lanes.aux_base {
            Some(aux) => aux.abs_diff(self.lanes.colour_base),
            None => usize::MAX,
        };
        let clear = |lo: usize, hi: usize| apart == 0 || apart > hi - lo;
        if !clear(first, last) {
            return Admit::Never;
        }
        let (lo, hi) = (self.words.0.min(first), self.words.1.max(last));
        let on_a_row = self.scry[..self.rows].contains(&row.scry);
        if self.lanes.n + len > PACK || on_a_row || !clear(lo, hi) {
            return Admit::AfterShading;
        }
        Admit::Now
    }

    /// Add `row`'s pixels (admitted: [`Pack::admits`]) as lanes: `(ax, ay)` is vertex
    /// A's pixel, `pitch` the frame buffer's row pitch in words.
    #[inline(always)]
    fn push(&mut self, row: &Row, (ax, ay): (i32, i32), pitch: u32) {
        let dy = row.y - ay;
        let len = (row.stop - row.start) as usize;
        let first = row.scry as usize * pitch as usize + row.start as usize;
        let l = &mut self.lanes;
        for k in 0..len {
            let j = (l.n + k) % PACK;
            let x = row.start + k as i32;
            l.x[j] = x;
            l.y[j] = row.y;
            l.dx[j] = x - ax;
            l.dy[j] = dy;
            l.prow[j] = row.prow;
            l.first[j] = k == 0;
            l.word[j] = first + k;
        }
        l.n += len;
        self.words = (self.words.0.min(first), self.words.1.max(first + len - 1));
        self.scry[self.rows % PACK] = row.scry;
        self.rows += 1;
    }
}

/// One buffer's words of a [`Band`]: the slice, and the offset from the buffer's base of
/// its first word.
struct BandWords<'m> {
    words: &'m mut [u16],
    first: i64,
}

/// A band's row pieces with the words they touch.
struct BandJob<'p, 'm> {
    rows: &'p [Piece],
    colour: BandWords<'m>,
    aux: BandWords<'m>,
}

/// A band's row pieces in order, a chunk at a time from each piece's first column (no
/// per-triangle stipple copy).
fn shade_band<M: PixelModel, T: TexelSource>(
    shader: &mut Shader<'_>,
    st: &DrawState,
    BandJob { rows, colour, aux }: BandJob<'_, '_>,
    ((ax, ay), row_pixels): ((i32, i32), i64),
    consts: &TriangleConsts,
    tex: &mut T,
) {
    let (colour_first, aux_first) = (colour.first, aux.first);
    let (colour_len, aux_len) = (colour.words.len(), aux.words.len());
    let mut memory = Memory::Band {
        colour: colour.words,
        aux: aux.words,
    };
    for &Piece { row, row_start } in rows {
        let dy = row.y - ay;
        // Rotate-mode stipple steps once for every pixel of the row before the piece.
        let mut stipple = st.stipple.rotate_left((row.start - row_start) as u32);
        // Where the row's column 0 lies in each slice (no words above row 0).
        let at = |first: i64| (row.scry >= 0).then(|| i64::from(row.scry) * row_pixels - first);
        let (colour_at, aux_at) = (at(colour_first), at(aux_first));
        let mut x0 = row.start;
        while x0 < row.stop {
            let n = chunk_len((row.stop - x0) as usize);
            let at = ChunkAt {
                x0,
                n,
                y: row.y,
                scry: row.scry,
                prow: row.prow,
                span_start: row_start,
                ax,
                dy,
            };
            let it = Iterated::at(shader.params, x0 - ax, dy);
            let place = RowPlace {
                at: &at,
                it: &it,
                params: shader.params,
                words: (
                    Words::in_band(colour_at, colour_len, x0, n),
                    Words::in_band(aux_at, aux_len, x0, n),
                ),
            };
            let job = ChunkJob {
                st,
                stipple_state: &mut stipple,
                copy: None,
                tex,
                consts,
                mem: &mut memory,
            };
            shader.shade_chunk_of::<M, T, _>(job, &place);
            x0 += n as i32;
        }
    }
}

/// Rows of at most this many pixels are shaded pixel by pixel even on the fast path:
/// a chunk's fixed cost (its lanes, its words, its stage loops) is more than that of
/// shading so few pixels one at a time. Both compute the same integers.
const SHORT_ROW: i32 = 2;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::setup::EdgeRounding;

    /// The bands of random triangles' walks, unclipped, with and without the Y-origin
    /// flip, on rows of 256, 640 and 1024 words: each row's pieces cover its columns in
    /// order, each piece's words in one frame-buffer row; every piece in one band, in the
    /// walk's order; no word of one band's pieces touched by another's; bands in memory
    /// order, each but the last of at least `BAND_ROWS` pieces; and a walk whose rows all
    /// end within the pitch cut every `BAND_ROWS` rows.
    #[test]
    fn bands_hold_every_row_and_share_no_word() {
        let triangles = setup::random_triangles(0x9e37_79b9_7f4a_7c15, 600, &[4096, 16384, 40000]);
        let (mut past_pitch, mut cut_at_pitch) = (0, 0);
        for (k, p) in triangles.enumerate() {
            let row_pixels = [256, 640, 1024][k % 3];
            let flip = k % 4 < 2;
            let rows: Vec<Row> = setup::spans(&p, EdgeRounding::FloorHalfDown)
                .map(|s| Row {
                    y: s.y,
                    scry: if flip { (200 - s.y) & 0x3ff } else { s.y },
                    start: s.start,
                    stop: s.stop,
                    prow: s.y,
                })
                .collect();
            let pieces = row_pieces(&rows, row_pixels);
            let mut at = 0;
            for row in &rows {
                let mut x = row.start;
                while x < row.stop {
                    let piece = pieces[at];
                    assert_eq!((piece.row.start, piece.row_start), (x, row.start), "{p:?}");
                    if let Some(w) = row_words(&piece.row, row_pixels) {
                        assert_eq!(w.start / row_pixels, (w.end - 1) / row_pixels, "{p:?}");
                    }
                    (x, at) = (piece.row.stop, at + 1);
                }
                assert_eq!(x, row.stop, "{p:?}");
            }
            assert_eq!(at, pieces.len(), "{p:?}");
            let (order, bands) = band_rows(&pieces, row_pixels);
            let mut seen: Vec<usize> = bands
                .iter()
                .flat_map(|b| order[b.rows.clone()].iter().copied())
                .collect();
            seen.sort_unstable();
            assert_eq!(seen, (0..pieces.len()).collect::<Vec<_>>(), "{p:?}");
            let mut last_end = i64::MIN;
            let placed: Vec<&Band> = bands.iter().filter(|b| b.words.is_some()).collect();
            for (i, band) in placed.iter().enumerate() {
                let rows = &order[band.rows.clone()];
                assert!(rows.windows(2).all(|w| w[0] < w[1]), "{p:?}");
                let hull = band.words.clone().unwrap_or_default();
                assert!(hull.start >= last_end, "{p:?}: bands out of memory order");
                last_end = hull.end;
                for &r in rows {
                    let w = row_words(&pieces[r].row, row_pixels).unwrap_or_default();
                    assert!(hull.start <= w.start && w.end <= hull.end, "{p:?}");
                }
                if i + 1 < placed.len() {
                    assert!(band.rows.len() >= BAND_ROWS, "{p:?}: a short band");
                }
            }
            past_pitch += u32::from(pieces.len() > rows.len());
            let within = rows
                .iter()
                .filter(|r| row_words(r, row_pixels).is_some())
                .count();
            if !flip
                && rows
                    .iter()
                    .all(|r| r.start >= 0 && i64::from(r.stop) <= row_pixels)
            {
                assert_eq!(placed.len(), within.div_ceil(BAND_ROWS), "{p:?}");
                cut_at_pitch += 1;
            }
        }
        assert!(
            past_pitch > 30 && cut_at_pitch > 20,
            "{past_pitch} {cut_at_pitch}"
        );
    }

    /// The bounding box never holds fewer pixels than a walk covers, for every walk, on
    /// random triangles from slivers to the whole 12.4 range.
    #[test]
    fn box_pixels_bound_every_walk() {
        for p in setup::random_triangles(0x2545_f491_4f6c_dd1d, 3000, &[64, 1024, 65536]) {
            for rounding in [
                EdgeRounding::FloorHalfDown,
                EdgeRounding::TruncHalfDown,
                EdgeRounding::Box86Fixed,
            ] {
                let covered: u64 = setup::spans(&p, rounding)
                    .map(|s| (s.stop - s.start) as u64)
                    .sum();
                assert!(covered <= box_pixels(&p), "{p:?} {rounding:?}: {covered}");
            }
        }
    }
}

//! Triangle rasterization: spans from [`crate::setup`], clipping, and the per-pixel walk
//! with the iterators (spec 5.15 `triangleCMD`, 5.21 clip registers, 5.19 Y origin).

pub use sst1_regs::LanePlace;
use sst1_regs::Rgba;

use crate::fbi::Fbi;
use crate::fbi::PathCounts;
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
    fn texels(
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
    /// the threads are rayon's global pool.
    pub fn set_threads(&mut self, threads: usize) {
        self.threads = threads.clamp(1, MAX_THREADS);
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
    fn walk<M: PixelModel, T: TexelSource, const SPANS: bool>(
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
        let threaded = SPANS
            && self.threads > 1
            && copy.is_none()
            && box_pixels(&params) >= MIN_THREADED_PIXELS as u64;
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
            let scry = self.screen_y(span.y, flip);
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
        let banded = threaded
            && consts
                .as_ref()
                .is_some_and(|c| self.shade_rows_threaded::<M, T>(st, &rows, a, c, tex));
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

    /// Shade `rows` (a triangle's, clipped) in bands of [`BAND_ROWS`] rows dealt
    /// round-robin to the render threads, each band with its own counters, added up
    /// afterwards, and its own view of the texel source ([`TexelSource::band`]). Returns
    /// `false`, having done nothing, where that could differ from shading the rows in
    /// order: a small triangle (not worth the threads), a texel source that cannot be
    /// shared, a row whose
    /// lanes would reach past the frame-buffer row's end (the single walk lets them run
    /// on into the next row), two rows on one frame-buffer row (the Y-origin flip wraps at
    /// 1024), or colour and aux rows that share memory. Otherwise every row
    /// touches only its own words, so the bands give the pixels and counters of the
    /// single walk whatever the thread count.
    fn shade_rows_threaded<M: PixelModel, T: TexelSource>(
        &mut self,
        st: &DrawState,
        rows: &[Row],
        a: (i32, i32),
        consts: &TriangleConsts,
        tex: &mut T,
    ) -> bool {
        let row_pixels = self.fb.layout.row_pixels as usize;
        let pixels: usize = rows.iter().map(|r| (r.stop - r.start) as usize).sum();
        if self.threads < 2 || row_pixels == 0 || pixels < MIN_THREADED_PIXELS {
            return false;
        }
        // Columns left of 0 have no words on either walk (`Words::from_start`,
        // `FrameBuffer::index`), so a row may start there; columns at and past the row's
        // end run on into the next row.
        if rows.iter().any(|r| r.stop as usize > row_pixels) {
            return false;
        }
        // The Y-origin flip keeps 10 bits (`Fbi::screen_y`): rows 1024 apart share a
        // frame-buffer row, which the single walk visits twice in order.
        let raster_ys = rows.iter().map(|r| r.y);
        let (Some(lowest), Some(highest)) = (raster_ys.clone().min(), raster_ys.max()) else {
            return false;
        };
        if st.mode.y_origin() && highest - lowest >= 1024 {
            return false;
        }
        if st.color_path.texture_enable() && st.fetch_texel && !tex.share() {
            return false;
        }
        let ys = rows.iter().filter(|r| r.scry >= 0).map(|r| r.scry as usize);
        let (Some(ymin), Some(ymax)) = (ys.clone().min(), ys.max()) else {
            return false;
        };
        let len = self.fb.ram.len();
        let region = |base: usize| {
            (base + ymin * row_pixels).min(len)..(base + (ymax + 1) * row_pixels).min(len)
        };
        let colour = region(st.dest);
        let aux = st.aux.map(region).unwrap_or(0..0);
        let ram = &mut self.fb.ram[..];
        let (colour_words, aux_words): (&mut [u16], &mut [u16]) = if aux.is_empty() {
            (&mut ram[colour], &mut [])
        } else if colour.is_empty() {
            (&mut [], &mut ram[aux])
        } else if aux.start >= colour.end {
            let (lo, hi) = ram.split_at_mut(aux.start);
            (&mut lo[colour], &mut hi[..aux.len()])
        } else if colour.start >= aux.end {
            let (lo, hi) = ram.split_at_mut(colour.start);
            (&mut hi[..colour.len()], &mut lo[aux])
        } else {
            return false;
        };
        let mut colour_rows: Vec<Option<&mut [u16]>> =
            colour_words.chunks_mut(row_pixels).map(Some).collect();
        let mut aux_rows: Vec<Option<&mut [u16]>> =
            aux_words.chunks_mut(row_pixels).map(Some).collect();
        let threads = self.threads;
        let mut bands: Vec<Vec<BandRow<'_>>> = (0..threads).map(|_| Vec::new()).collect();
        for (i, row) in rows.iter().enumerate() {
            let k = (row.scry >= 0).then(|| row.scry as usize - ymin);
            let (colour, aux) = (take_row(&mut colour_rows, k), take_row(&mut aux_rows, k));
            bands[(i / BAND_ROWS) % threads].push(BandRow {
                row: *row,
                colour,
                aux,
            });
        }
        let mut counters = vec![(Stats::default(), PathCounts::default()); threads];
        let (dither, fog_table, params, profile, isa) = (
            &self.dither,
            &self.fog_table,
            &self.params,
            self.profile,
            self.isa,
        );
        let sources: Vec<T::Band<'_>> = (0..threads).map(|_| tex.band()).collect();
        rayon::scope(|scope| {
            let jobs = bands.into_iter().zip(counters.iter_mut()).zip(sources);
            for ((band, (stats, counts)), mut source) in jobs {
                scope.spawn(move |_| {
                    let mut shader = Shader {
                        stats,
                        counts,
                        dither,
                        fog_table,
                        params,
                        profile,
                        isa,
                    };
                    shade_band_rows::<M, _>(&mut shader, st, band, a, consts, &mut source);
                });
            }
        });
        for (stats, counts) in &counters {
            self.stats.add(stats);
            self.path_counts.add(counts);
            self.path_counts.in_bands += counts.span_kernels;
        }
        true
    }
}

/// Row `k` of `rows`, taken out (empty where there is none).
fn take_row<'m>(rows: &mut [Option<&'m mut [u16]>], k: Option<usize>) -> &'m mut [u16] {
    k.and_then(|k| rows.get_mut(k))
        .and_then(Option::take)
        .unwrap_or_default()
}

/// The most render threads [`Fbi::set_threads`] takes.
pub const MAX_THREADS: usize = 256;

/// Rows per band of the threaded walk.
const BAND_ROWS: usize = 4;

/// The fewest pixels a triangle must have for its rows to go to the render threads.
const MIN_THREADED_PIXELS: usize = 4096;

/// At least as many pixels as the triangle of `p` covers: its vertices' bounding box in
/// whole pixels, with a pixel's margin on every side (each walk's spans lie between its
/// vertices' coordinates, rounded to pixel boundaries).
fn box_pixels(p: &TriangleParams) -> u64 {
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

/// A row of a band with the frame-buffer rows it writes (empty where a buffer has none).
struct BandRow<'m> {
    row: Row,
    colour: &'m mut [u16],
    aux: &'m mut [u16],
}

/// The rows of a band, in order, a chunk at a time (the same chunks as
/// [`Fbi::shade_row`]; no per-triangle stipple copy).
fn shade_band_rows<M: PixelModel, T: TexelSource>(
    shader: &mut Shader<'_>,
    st: &DrawState,
    band: Vec<BandRow<'_>>,
    (ax, ay): (i32, i32),
    consts: &TriangleConsts,
    tex: &mut T,
) {
    for BandRow { row, colour, aux } in band {
        let dy = row.y - ay;
        let mut stipple = st.stipple;
        let (colour_len, aux_len) = (colour.len(), aux.len());
        let mut memory = Memory::Rows { colour, aux };
        let mut x0 = row.start;
        while x0 < row.stop {
            let n = chunk_len((row.stop - x0) as usize);
            let at = ChunkAt {
                x0,
                n,
                y: row.y,
                scry: row.scry,
                prow: row.prow,
                span_start: row.start,
                ax,
                dy,
            };
            let it = Iterated::at(shader.params, x0 - ax, dy);
            let place = RowPlace {
                at: &at,
                it: &it,
                params: shader.params,
                words: (
                    Words::in_row(colour_len, x0, n),
                    Words::in_row(aux_len, x0, n),
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

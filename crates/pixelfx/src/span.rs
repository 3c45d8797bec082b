//! Span kernels: the pixel pipeline of [`crate::pipeline`] run one stage at a time over
//! up to [`LANES`] pixels of a span (structure of arrays), for whatever drawing state a
//! triangle uses.
//!
//! `Fbi::shade_pixel` (`crate::pipeline`) runs the stages for one pixel and tests every mode
//! bit for every pixel: the reference path. Here the stages are the same, in the same
//! order, with the same kill reasons and counters, but each stage is a loop over the
//! chunk's lanes whose mode decisions are taken once per chunk: an input selection
//! becomes a choice of source array, a switch becomes a mask, a disabled stage is not
//! run. No state is special: every combination of `fbzColorPath`, `alphaMode`,
//! `fogMode` and `fbzMode` runs these kernels, so there is no table of states and no
//! fallback for unusual ones. `crates/board/tests/generic_vs_fast.rs` replays every
//! trace, and a stream of random states, through both paths and requires identical
//! buffers and counters.
//!
//! A chunk's lanes are distinct pixels of one row, so reading all their destination
//! words before writing any gives what the pixel-by-pixel order gives, with one
//! exception: colour and aux buffers placed so that one lane's colour word is another
//! lane's aux word (a layout no driver sets, but registers allow). `Shader::shade_chunk`
//! detects that and shades such a chunk pixel by pixel.

use sst1_regs::{
    AlphaFunction, AlphaLocalSelect, AlphaSelect, CcMselect, CompareFunction, DepthFunction,
    FbzColorPath, FbzMode, RgbSelect, Rgba,
};

use sst1_dither::{Dither, DitherKind};
use sst1_fog::FogTable;

use crate::fbi::{Fbi, PathCounts};
use crate::isa::VectorIsa;
use crate::iter::{wfloat, Iterated, IteratorClamp};
use crate::model::PixelModel;
use crate::params::TriangleParams;
use crate::pipeline::{DrawState, Source};
use crate::profile::PixelProfile;
use crate::profile::{AlphaTestInput, AuxWrite, ZAlphaByte};
use crate::raster::{Avx2Copy, Avx512Copy, BaselineCopy, KernelCopy, LanePlace, TexelSource};
use crate::stats::Kill;
use crate::stats::Stats;
use crate::{blend, fog, stipple};

pub use sst1_regs::lanes::{Lanes, LANES};

/// The lanes `lo..hi` of a chunk whose words exist in one buffer, and the word index of
/// lane `lo` (lane `i`'s word is `first + i - lo`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Words {
    lo: usize,
    hi: usize,
    first: usize,
}

impl Words {
    pub(crate) const NONE: Words = Words {
        lo: 0,
        hi: 0,
        first: 0,
    };

    /// The words of `n` lanes from column `x0` of frame-buffer row `y` in the buffer at
    /// word `base`, as [`crate::fb::FrameBuffer::index`] finds them one at a time.
    #[inline(always)]
    pub(crate) fn of(fbi: &Fbi, base: usize, x0: i32, n: usize, y: i32) -> Self {
        if y < 0 {
            return Self::NONE;
        }
        let row = fbi.fb.layout.row_pixels as i64;
        let start = base as i64 + y as i64 * row + x0 as i64;
        Self::from_start(start, fbi.fb.ram.len() as i64, x0, n)
    }

    /// The words of `n` lanes from column `x0` of a row whose column 0 lies at `row_at`
    /// of a band's slice of `len` words (`None`: a row with no words; the threaded walk,
    /// whose bands hold every word their rows touch within memory).
    #[inline(always)]
    pub(crate) fn in_band(row_at: Option<i64>, len: usize, x0: i32, n: usize) -> Self {
        row_at.map_or(Self::NONE, |at| {
            Self::from_start(at + x0 as i64, len as i64, x0, n)
        })
    }

    /// Lane `i` at word `start + i`, existing where the column is not negative and the
    /// word is below `len`.
    #[inline(always)]
    fn from_start(start: i64, len: i64, x0: i32, n: usize) -> Self {
        let lo = (-(x0 as i64)).clamp(0, n as i64);
        let hi = (len - start).clamp(lo, n as i64);
        if lo >= hi {
            return Self::NONE;
        }
        Self {
            lo: lo as usize,
            hi: hi as usize,
            first: (start + lo) as usize,
        }
    }

    /// Whether a write through `self` to one lane can land on a word that `other` reads
    /// for a different lane.
    #[inline(always)]
    pub(crate) fn crosses(&self, other: &Words) -> bool {
        if self.lo >= self.hi || other.lo >= other.hi {
            return false;
        }
        let (a0, a1) = (self.first, self.first + (self.hi - self.lo));
        let (b0, b1) = (other.first, other.first + (other.hi - other.lo));
        let overlap = a0 < b1 && b0 < a1;
        // Same lane-to-word mapping: lane i meets only lane i.
        let same = self.first as i64 - self.lo as i64 == other.first as i64 - other.lo as i64;
        overlap && !same
    }
}

/// Where one chunk lies: `n` pixels from screen column `x0` on raster row `y`.
pub(crate) struct ChunkAt {
    /// First column.
    pub x0: i32,
    /// Pixels, 1..=[`LANES`].
    pub n: usize,
    /// Raster row (what the TMUs see).
    pub y: i32,
    /// Frame-buffer row after the Y-origin flip.
    pub scry: i32,
    /// Row the dither and stipple patterns are indexed with.
    pub prow: i32,
    /// Column of the span's first pixel (86Box's per-triangle stipple copy is indexed
    /// from it).
    pub span_start: i32,
    /// Vertex A's column and the row offset from it (the TMUs' pixel offsets).
    pub ax: i32,
    pub dy: i32,
}

/// The lanes of a packed chunk ([`Packed`]): pixels of several short spans of one
/// triangle in one chunk; also the width of a span's chunk of 9 to 16 pixels
/// ([`chunk_len`]).
pub const PACK: usize = 16;

/// Which of a chunk's two buffers a word is in.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Buffer {
    Colour,
    Aux,
}

/// Where a chunk's `L` lanes lie: what the stages read of each lane's position (its
/// column, pattern row, raw iterators, words) and nothing else, so that one kernel serves
/// the lanes of one span ([`RowPlace`]) and those of several ([`Packed`]).
pub(crate) trait Place<const L: usize> {
    /// Lanes `0..n` hold pixels.
    fn n(&self) -> usize;
    /// Lane `i`'s screen column.
    fn x(&self, i: usize) -> i32;
    /// The row lane `i`'s dither and stipple patterns are indexed with.
    fn prow(&self, i: usize) -> i32;
    /// Whether lane `i` is the first pixel of a span: the rotating stipple restarts
    /// there. (The walk restarts it for a chunk of one span.)
    fn starts_span(&self, i: usize) -> bool;
    /// The column 86Box's per-triangle stipple copy is indexed from (one span only).
    fn span_start(&self) -> i32;
    /// Every lane's raw colour iterator `c` (12.12) and Z (20.12); lane `i`'s W (32.32).
    fn colour(&self, c: usize) -> [i32; L];
    fn z(&self) -> [i32; L];
    fn w(&self, i: usize) -> i64;
    /// The lanes as the texel source takes them.
    fn texel_place(&self) -> LanePlace<'_>;
    /// The dither matrix entry of every lane, as [`Dither::matrix_value`] gives it.
    fn dither_entries(&self, dither: &Dither, kind: DitherKind) -> [i32; L];
    /// The lanes' words of `buffer` in `ram` as lanes (0 where a lane has none), and
    /// which lanes have one.
    fn load(&self, ram: &[u16], buffer: Buffer) -> ([i32; L], [bool; L]);
    /// The depth test of every lane against its aux word in `ram`: where
    /// `func(source[i], word)` fails, and `no_aux` where the lane has no aux word.
    fn depth_fails(
        &self,
        ram: &[u16],
        func: CompareFunction,
        source: &[i32; L],
        no_aux: bool,
    ) -> [bool; L];
    /// Write `values[i]` to the word of `buffer` of every live lane `i` that has one.
    fn store(&self, ram: &mut [u16], buffer: Buffer, alive: &[bool; L], values: &[u16; L]);
    /// `rgb` packed to RGB565 with the dither `kind` and written to the colour word of
    /// every live lane that has one.
    fn store_rgb565(
        &self,
        ram: &mut [u16],
        dither: &Dither,
        kind: DitherKind,
        rgb: [&[i32; L]; 3],
        alive: &[bool; L],
    );
}

/// The lanes of one chunk of one span: lane `i` is column `at.x0 + i`.
pub(crate) struct RowPlace<'a> {
    pub at: &'a ChunkAt,
    /// The iterators at the chunk's first pixel.
    pub it: &'a Iterated,
    pub params: &'a TriangleParams,
    /// The lanes' colour and aux words (checked not to cross: [`Words::crosses`]).
    pub words: (Words, Words),
}

impl<const L: usize> Place<L> for RowPlace<'_> {
    #[inline(always)]
    fn n(&self) -> usize {
        self.at.n
    }

    #[inline(always)]
    fn x(&self, i: usize) -> i32 {
        self.at.x0 + i as i32
    }

    #[inline(always)]
    fn prow(&self, _i: usize) -> i32 {
        self.at.prow
    }

    #[inline(always)]
    fn starts_span(&self, _i: usize) -> bool {
        false
    }

    #[inline(always)]
    fn span_start(&self) -> i32 {
        self.at.span_start
    }

    #[inline(always)]
    fn colour(&self, c: usize) -> [i32; L] {
        let (s, d) = (self.it.argb[c], self.params.dx[c]);
        lanes(|i| s.wrapping_add(d.wrapping_mul(i as i32)))
    }

    #[inline(always)]
    fn z(&self) -> [i32; L] {
        let (s, d) = (self.it.z, self.params.dzdx);
        lanes(|i| s.wrapping_add(d.wrapping_mul(i as i32)))
    }

    #[inline(always)]
    fn w(&self, i: usize) -> i64 {
        self.it
            .w
            .wrapping_add(self.params.dwdx.wrapping_mul(i as i64))
    }

    #[inline(always)]
    fn texel_place(&self) -> LanePlace<'_> {
        let at = self.at;
        LanePlace::Row {
            dx0: at.x0 - at.ax,
            dy: at.dy,
            x0: at.x0,
            y: at.y,
        }
    }

    #[inline(always)]
    fn dither_entries(&self, dither: &Dither, kind: DitherKind) -> [i32; L] {
        // The matrix repeats every 4 columns: its entries for the first four lanes, then
        // spread over the lanes.
        let mut row = [0i32; 4];
        for (k, e) in row.iter_mut().enumerate() {
            let x = (self.at.x0 + k as i32) as u32;
            *e = dither.matrix_value(kind, x, self.at.prow as u32) as i32;
        }
        lanes(|i| row[i & 3])
    }

    #[inline(always)]
    fn load(&self, ram: &[u16], buffer: Buffer) -> ([i32; L], [bool; L]) {
        load_words(ram, self.words_of(buffer))
    }

    #[inline(always)]
    fn depth_fails(
        &self,
        ram: &[u16],
        func: CompareFunction,
        source: &[i32; L],
        no_aux: bool,
    ) -> [bool; L] {
        // Straight from the row's words: no copy of them first.
        let mut fails = [no_aux; L];
        let w = self.words.1;
        let ram = &ram[w.first..w.first + (w.hi - w.lo)];
        let pairs = source[w.lo..w.hi]
            .iter()
            .zip(ram)
            .map(|(&s, &d)| (s, i32::from(d)));
        compare_fails(func, pairs, &mut fails[w.lo..w.hi]);
        fails
    }

    #[inline(always)]
    fn store(&self, ram: &mut [u16], buffer: Buffer, alive: &[bool; L], values: &[u16; L]) {
        store_alive(ram, self.words_of(buffer), alive, values)
    }

    #[inline(always)]
    fn store_rgb565(
        &self,
        ram: &mut [u16],
        dither: &Dither,
        kind: DitherKind,
        rgb: [&[i32; L]; 3],
        alive: &[bool; L],
    ) {
        // Packed straight into the row's words (`Dither::rgb565_row_into`).
        let w = self.words.0;
        let dst = &mut ram[w.first..w.first + (w.hi - w.lo)];
        let x0 = (self.at.x0 + w.lo as i32) as u32;
        let rgb = rgb.map(|c| &c[w.lo..w.hi]);
        dither.rgb565_row_into(kind, x0, self.at.prow as u32, rgb, &alive[w.lo..w.hi], dst);
    }
}

impl RowPlace<'_> {
    #[inline(always)]
    fn words_of(&self, buffer: Buffer) -> Words {
        match buffer {
            Buffer::Colour => self.words.0,
            Buffer::Aux => self.words.1,
        }
    }
}

/// Pixels of several short spans of one triangle in one chunk of [`PACK`] lanes, in the
/// order of the walk (built by `raster.rs`, which packs only spans whose every pixel has
/// a word of its own in each buffer and no colour word of which is another lane's aux
/// word, so that reading every lane's words before writing any gives what the walk's
/// order gives).
pub(crate) struct Packed {
    pub n: usize,
    /// Screen position, offset from vertex A's pixel (what the TMUs take).
    pub x: Lanes,
    pub y: Lanes,
    pub dx: Lanes,
    pub dy: Lanes,
    pub prow: [i32; PACK],
    pub first: [bool; PACK],
    /// Word of the lane's pixel from a buffer's first word.
    pub word: [usize; PACK],
    /// First word of the colour buffer and of the aux buffer, if there is one.
    pub colour_base: usize,
    pub aux_base: Option<usize>,
    /// The triangle's start values and gradients: a lane's raw iterators are
    /// `start + dx * d/dx + dy * d/dy` at its offsets (as [`Iterated::at`]), computed
    /// for all lanes at once when the chunk is shaded.
    pub params: TriangleParams,
}

impl Packed {
    /// Empty lanes; the buffers are set per triangle.
    pub(crate) fn new() -> Self {
        Self {
            n: 0,
            x: [0; LANES],
            y: [0; LANES],
            dx: [0; LANES],
            dy: [0; LANES],
            prow: [0; PACK],
            first: [false; PACK],
            word: [0; PACK],
            colour_base: 0,
            aux_base: None,
            params: TriangleParams::default(),
        }
    }

    /// A 32-bit iterator at every lane, as [`Iterated::at`] computes it.
    #[inline(always)]
    fn linear<const L: usize>(&self, start: i32, gx: i32, gy: i32) -> [i32; L] {
        lanes(|i| {
            start
                .wrapping_add(self.dy[i].wrapping_mul(gy))
                .wrapping_add(self.dx[i].wrapping_mul(gx))
        })
    }

    #[inline(always)]
    fn base(&self, buffer: Buffer) -> Option<usize> {
        match buffer {
            Buffer::Colour => Some(self.colour_base),
            Buffer::Aux => self.aux_base,
        }
    }
}

/// The first `L` lanes of the pack (`L` at most [`PACK`]; the pack's `n` at most `L`).
impl<const L: usize> Place<L> for Packed {
    #[inline(always)]
    fn n(&self) -> usize {
        // The lanes' arrays hold `PACK`: a wider chunk of a pack does not compile.
        const { assert!(L <= PACK) };
        self.n
    }

    #[inline(always)]
    fn x(&self, i: usize) -> i32 {
        self.x[i % LANES]
    }

    #[inline(always)]
    fn prow(&self, i: usize) -> i32 {
        self.prow[i % PACK]
    }

    #[inline(always)]
    fn starts_span(&self, i: usize) -> bool {
        self.first[i % PACK]
    }

    #[inline(always)]
    fn span_start(&self) -> i32 {
        // Never read: the walk packs no triangle that has the per-triangle copy.
        self.x[0]
    }

    #[inline(always)]
    fn colour(&self, c: usize) -> [i32; L] {
        let p = &self.params;
        self.linear(p.start[c], p.dx[c], p.dy[c])
    }

    #[inline(always)]
    fn z(&self) -> [i32; L] {
        let p = &self.params;
        self.linear(p.start_z, p.dzdx, p.dzdy)
    }

    #[inline(always)]
    fn w(&self, i: usize) -> i64 {
        let (p, i) = (&self.params, i % PACK);
        p.start_w
            .wrapping_add(i64::from(self.dy[i]).wrapping_mul(p.dwdy))
            .wrapping_add(i64::from(self.dx[i]).wrapping_mul(p.dwdx))
    }

    #[inline(always)]
    fn texel_place(&self) -> LanePlace<'_> {
        LanePlace::Lanes {
            dx: &self.dx,
            dy: &self.dy,
            x: &self.x,
            y: &self.y,
        }
    }

    #[inline(always)]
    fn dither_entries(&self, dither: &Dither, kind: DitherKind) -> [i32; L] {
        lanes(|i| dither.matrix_value(kind, self.x[i] as u32, self.prow[i] as u32) as i32)
    }

    #[inline(always)]
    fn load(&self, ram: &[u16], buffer: Buffer) -> ([i32; L], [bool; L]) {
        let mut v = [0; L];
        let mut has = [false; L];
        if let Some(base) = self.base(buffer) {
            for i in 0..self.n.min(L) {
                v[i] = i32::from(ram[base + self.word[i]]);
                has[i] = true;
            }
        }
        (v, has)
    }

    #[inline(always)]
    fn depth_fails(
        &self,
        ram: &[u16],
        func: CompareFunction,
        source: &[i32; L],
        no_aux: bool,
    ) -> [bool; L] {
        let (dst, has): ([i32; L], [bool; L]) = self.load(ram, Buffer::Aux);
        let mut fails = [false; L];
        compare_fails(func, source.iter().copied().zip(dst), &mut fails);
        lanes(|i| (fails[i] & has[i]) | (no_aux & !has[i]))
    }

    #[inline(always)]
    fn store(&self, ram: &mut [u16], buffer: Buffer, alive: &[bool; L], values: &[u16; L]) {
        if let Some(base) = self.base(buffer) {
            for i in 0..self.n.min(L) {
                if alive[i] {
                    ram[base + self.word[i]] = values[i];
                }
            }
        }
    }

    #[inline(always)]
    fn store_rgb565(
        &self,
        ram: &mut [u16],
        dither: &Dither,
        kind: DitherKind,
        rgb: [&[i32; L]; 3],
        alive: &[bool; L],
    ) {
        let entries: [i32; L] = self.dither_entries(dither, kind);
        let mut packed = [0u16; L];
        dither.rgb565_lanes(kind, &entries, rgb.map(|c| &c[..]), &mut packed);
        self.store(ram, Buffer::Colour, alive, &packed);
    }
}

/// The three 8-bit channels and alpha of a colour for every lane, on a cache line of
/// their own (vector stores that straddle two lines cost two).
#[derive(Clone, Copy)]
#[repr(C, align(64))]
struct ColourLanes<const L: usize> {
    c: [[i32; L]; 4],
}

impl<const L: usize> ColourLanes<L> {
    const ZERO: ColourLanes<L> = ColourLanes { c: [[0; L]; 4] };

    fn splat(v: Rgba) -> Self {
        Self {
            c: [
                [v.r as i32; L],
                [v.g as i32; L],
                [v.b as i32; L],
                [v.a as i32; L],
            ],
        }
    }
}

/// What every chunk of a triangle reads and no stage changes: the constant colours
/// spread over the lanes.
pub(crate) struct TriangleLanes<const L: usize> {
    color0: ColourLanes<L>,
    color1: ColourLanes<L>,
    /// `zaColor`'s depth (the depth test's source with `fbzMode` bit 20).
    za_depth: [i32; L],
    zero: [i32; L],
    zero_colour: ColourLanes<L>,
}

impl<const L: usize> TriangleLanes<L> {
    fn new(key: &LaneKey) -> Self {
        Self {
            color0: ColourLanes::splat(key.color0),
            color1: ColourLanes::splat(key.color1),
            za_depth: [key.za_depth; L],
            zero: [0; L],
            zero_colour: ColourLanes::ZERO,
        }
    }
}

/// The registers [`TriangleLanes`] spread over the lanes: `color0`, `color1` and
/// `zaColor`'s depth.
#[derive(Clone, Copy, PartialEq, Eq)]
struct LaneKey {
    color0: Rgba,
    color1: Rgba,
    za_depth: i32,
}

impl LaneKey {
    fn of(st: &DrawState) -> Self {
        Self {
            color0: st.color0,
            color1: st.color1,
            za_depth: (st.za_color & 0xffff) as i32,
        }
    }
}

/// Lanes of the narrow chunks that short spans are shaded in: the loops of a chunk run
/// over all its lanes, so a 3-pixel span costs a narrow chunk's work, not a wide one's.
pub const NARROW: usize = 8;

/// A span's pixels from here on go in one wide chunk when at least this many are left
/// (fewer run as chunks of [`PACK`] lanes, and the last 8 or fewer as a narrow one).
/// Measured: 48 was slower (heavy states 104 to 108 Mpix/s against 106 to 113).
const WIDE_FROM: usize = 40;

/// The constants of [`TriangleLanes`] for every chunk width; the wide ones are built
/// when a chunk first needs them (a small triangle has none). The FBI keeps them from
/// one triangle to the next ([`TriangleConsts::update`]), so that a triangle in the
/// constant colours of the one before builds nothing.
pub(crate) struct TriangleConsts {
    key: LaneKey,
    wide: std::sync::OnceLock<Box<TriangleLanes<LANES>>>,
    narrow: TriangleLanes<NARROW>,
    packed: TriangleLanes<PACK>,
}

impl TriangleConsts {
    pub(crate) fn new(st: &DrawState) -> Self {
        let key = LaneKey::of(st);
        Self {
            key,
            wide: std::sync::OnceLock::new(),
            narrow: TriangleLanes::new(&key),
            packed: TriangleLanes::new(&key),
        }
    }

    /// The constants of a triangle drawn with `st`: rebuilt where its constant colours
    /// differ from the last triangle's.
    #[inline(always)]
    pub(crate) fn update(&mut self, st: &DrawState) {
        let key = LaneKey::of(st);
        if key != self.key {
            self.rebuild(key);
        }
    }

    /// [`TriangleConsts::update`]'s rebuild, out of line: the compare above stays a few
    /// instructions in the walk.
    #[inline(never)]
    fn rebuild(&mut self, key: LaneKey) {
        self.key = key;
        self.narrow = TriangleLanes::new(&key);
        self.packed = TriangleLanes::new(&key);
        if let Some(wide) = self.wide.get_mut() {
            **wide = TriangleLanes::new(&key);
        }
    }

    #[inline(always)]
    fn wide(&self) -> &TriangleLanes<LANES> {
        self.wide
            .get_or_init(|| Box::new(TriangleLanes::new(&self.key)))
    }
}

/// One channel's iterated colour, clamped to 8 bits, in every lane.
#[inline(always)]
fn clamp_colour_lanes<const L: usize>(
    out: &mut [core::mem::MaybeUninit<i32>; L],
    raw: [i32; L],
    clamp: IteratorClamp,
) {
    for (v, r) in out.iter_mut().zip(raw) {
        v.write(clamp.colour(r) as i32);
    }
}

/// The four channels of a [`ColourLanes`] not yet written, to be filled lane by lane:
/// no zero fill first (zeroing a 64-lane chunk's four channels, 16 vector stores, was
/// the hottest instruction of a profile of perf_gouraud_heavy, the store queue full).
#[inline(always)]
fn uninit_channels<const L: usize>(
    store: &mut core::mem::MaybeUninit<ColourLanes<L>>,
) -> &mut [[core::mem::MaybeUninit<i32>; L]; 4] {
    // SAFETY: `ColourLanes<L>` is `[[i32; L]; 4]` in a `repr(C)` struct of one field
    // (at offset 0), so the pointer is one to that array; an array of `MaybeUninit`
    // may hold anything.
    unsafe { &mut *(store.as_mut_ptr() as *mut [[core::mem::MaybeUninit<i32>; L]; 4]) }
}

/// The pixels of the next chunk of a span with `left` pixels left: a wide chunk from
/// [`WIDE_FROM`] pixels, then chunks of [`PACK`] lanes, then a narrow one (a tail of 9
/// to 39 pixels in narrow chunks only took up to five of them, each with a chunk's
/// fixed work: 13 % slower on heavy states).
#[inline(always)]
pub(crate) fn chunk_len(left: usize) -> usize {
    if left >= WIDE_FROM {
        left.min(LANES)
    } else if left > NARROW {
        left.min(PACK)
    } else {
        left
    }
}

/// A value a lane holds, with the zero an array of lanes starts from.
pub(crate) trait Lane: Copy {
    const ZERO: Self;
}

impl Lane for i32 {
    const ZERO: Self = 0;
}

impl Lane for bool {
    const ZERO: Self = false;
}

impl Lane for u16 {
    const ZERO: Self = 0;
}

/// `[f(0), f(1), ..]`: one value per lane, as a plain loop over the array. Unlike
/// `core::array::from_fn`, which the compiler may leave as a call (and then compiles
/// for the baseline target even inside the vector kernels), this is always inlined into
/// the kernel and vectorised there.
#[inline(always)]
pub(crate) fn lanes<T: Lane, const L: usize>(mut f: impl FnMut(usize) -> T) -> [T; L] {
    let mut out = [T::ZERO; L];
    for (i, v) in out.iter_mut().enumerate() {
        *v = f(i);
    }
    out
}

/// Kill the live lanes of `alive` for which `fails` holds, counting each as `kill`.
#[inline(always)]
fn kill_where<const L: usize>(
    stats: &mut Stats,
    alive: &mut [bool; L],
    n: usize,
    kill: Kill,
    fails: impl Fn(usize) -> bool,
) {
    let n = n.min(L);
    let mut killed_lanes = [false; L];
    for i in 0..n {
        // `&`, not `&&`: every lane's test is evaluated (each is a pure read), so the
        // loop has no branch per lane; the count is a second loop, so that both
        // vectorise.
        let f = alive[i] & fails(i);
        killed_lanes[i] = f;
        alive[i] &= !f;
    }
    let killed = killed_lanes[..n].iter().map(|&k| u32::from(k)).sum::<u32>();
    if killed > 0 {
        stats.kill_many(kill, killed);
    }
}

/// `fails[i] = !func.passes(s, r)` for the `i`-th pair `(s, r)` (the depth and alpha
/// tests), the function chosen once for all lanes rather than once per lane: each arm
/// is a plain comparison loop, which vectorises.
#[inline(always)]
fn compare_fails(
    func: CompareFunction,
    pairs: impl Iterator<Item = (i32, i32)>,
    fails: &mut [bool],
) {
    macro_rules! each {
        (|$s:ident, $r:ident| $pass:expr) => {
            for (f, ($s, $r)) in fails.iter_mut().zip(pairs) {
                *f = !$pass;
            }
        };
    }
    match func {
        CompareFunction::Never => each!(|_s, _r| false),
        CompareFunction::Less => each!(|s, r| s < r),
        CompareFunction::Equal => each!(|s, r| s == r),
        CompareFunction::LessEqual => each!(|s, r| s <= r),
        CompareFunction::Greater => each!(|s, r| s > r),
        CompareFunction::NotEqual => each!(|s, r| s != r),
        CompareFunction::GreaterEqual => each!(|s, r| s >= r),
        CompareFunction::Always => each!(|_s, _r| true),
    }
}

/// The alpha test ([`crate::alpha_test::test`]) of every lane of `alpha`: where it fails.
#[inline(always)]
fn alpha_fails<const L: usize>(func: AlphaFunction, alpha: &[i32; L], reference: u8) -> [bool; L] {
    let mut fails = [false; L];
    // `alpha_test::test` takes the low 8 bits.
    let pairs = alpha.iter().map(|&a| (a & 0xff, i32::from(reference)));
    compare_fails(func, pairs, &mut fails);
    fails
}

/// `v` through an opaque identity: for a reference chosen once per chunk among several
/// arrays, it keeps the compiler from turning that one choice into an address choice
/// per lane, which does not vectorise (measured on the first 50 triangles of
/// perf_gouraud_heavy: 364 M instructions without it, 304 M with it). The value goes
/// through memory once per call, per chunk, not per lane.
#[inline(always)]
fn chosen<T>(v: T) -> T {
    core::hint::black_box(v)
}

/// `out = clamp((other - sub) * (factor ^ xor + 1) >> 8 + add) ^ invert` for every lane:
/// one channel of a combine unit (see [`crate::color_path::combine`]), its selections
/// made by the caller.
#[inline(always)]
fn combine_channel<const L: usize>(
    out: &mut [core::mem::MaybeUninit<i32>; L],
    other: &[i32; L],
    sub: &[i32; L],
    factor: &[i32; L],
    add: &[i32; L],
    xor: i32,
    invert: i32,
    zero: &[i32; L],
) {
    let is_zero = |lanes: &[i32; L]| core::ptr::eq(lanes, zero);
    // The sources are chosen per chunk; an opaque pointer keeps the compiler from
    // turning that choice into a choice per lane (an address select per element, which
    // does not vectorise).
    let (other, sub, factor, add) = chosen((other, sub, factor, add));
    if is_zero(other) && is_zero(sub) {
        // Nothing to scale (`GR_COMBINE_FUNCTION_LOCAL` and its kin): the sum alone.
        for i in 0..L {
            out[i].write(add[i].clamp(0, 255) ^ invert);
        }
    } else if is_zero(factor) && xor == 0xff {
        // A factor of 0 reversed is 256: the difference passes unscaled
        // (`(d * 256) >> 8 == d`).
        if is_zero(sub) && is_zero(add) {
            // `c_other` alone (`GR_COMBINE_FUNCTION_SCALE_OTHER` by one).
            for i in 0..L {
                out[i].write(other[i].clamp(0, 255) ^ invert);
            }
        } else {
            for i in 0..L {
                out[i].write((other[i] - sub[i] + add[i]).clamp(0, 255) ^ invert);
            }
        }
    } else {
        for i in 0..L {
            let v = ((other[i] - sub[i]) * ((factor[i] ^ xor) + 1)) >> 8;
            out[i].write((v + add[i]).clamp(0, 255) ^ invert);
        }
    }
}

/// Where a chunk's words are: the whole frame buffer (word indices), or a band's words of
/// the colour buffer and of the aux buffer (the threaded walk).
pub(crate) enum Memory<'m> {
    /// The frame buffer; [`Words`] index it.
    Whole(&'m mut [u16]),
    /// A band's words of each buffer (empty where it has none); [`Words`] index each
    /// slice.
    Band {
        colour: &'m mut [u16],
        aux: &'m mut [u16],
    },
}

impl Memory<'_> {
    #[inline(always)]
    fn colour(&mut self) -> &mut [u16] {
        match self {
            Memory::Whole(ram) => ram,
            Memory::Band { colour, .. } => colour,
        }
    }

    #[inline(always)]
    fn aux(&mut self) -> &mut [u16] {
        match self {
            Memory::Whole(ram) => ram,
            Memory::Band { aux, .. } => aux,
        }
    }
}

/// A place whose lanes [`Shader::shade_chunk_of`] shades: the width and the triangle
/// constants it is shaded with.
pub(crate) trait ShadeChunk {
    /// [`Shader::shade_chunk`] for these lanes.
    fn shade<M: PixelModel, T: TexelSource, K: KernelCopy>(
        &self,
        shader: &mut Shader<'_>,
        job: ChunkJob<'_, '_, T>,
    );
}

impl ShadeChunk for RowPlace<'_> {
    /// A wide chunk, one of [`PACK`] lanes or a narrow one, as `at.n` asks
    /// ([`chunk_len`]).
    #[inline(always)]
    fn shade<M: PixelModel, T: TexelSource, K: KernelCopy>(
        &self,
        shader: &mut Shader<'_>,
        job: ChunkJob<'_, '_, T>,
    ) {
        if self.at.n > PACK {
            let lanes = job.consts.wide();
            shader.shade_chunk::<M, T, K, LANES, _>(job, self, lanes);
        } else if self.at.n > NARROW {
            let lanes = &job.consts.packed;
            shader.shade_chunk::<M, T, K, PACK, _>(job, self, lanes);
        } else {
            let lanes = &job.consts.narrow;
            shader.shade_chunk::<M, T, K, NARROW, _>(job, self, lanes);
        }
    }
}

impl ShadeChunk for Packed {
    #[inline(always)]
    fn shade<M: PixelModel, T: TexelSource, K: KernelCopy>(
        &self,
        shader: &mut Shader<'_>,
        job: ChunkJob<'_, '_, T>,
    ) {
        // A pack of a few pixels (a triangle of a few) is a narrow chunk: every loop of
        // a chunk runs over all its lanes.
        if self.n > NARROW {
            let lanes = &job.consts.packed;
            shader.shade_chunk::<M, T, K, PACK, _>(job, self, lanes);
        } else {
            let lanes = &job.consts.narrow;
            shader.shade_chunk::<M, T, K, NARROW, _>(job, self, lanes);
        }
    }
}

/// One chunk's work for [`Shader::shade_chunk_of`]:
/// what it reads and changes besides the shader's counters (where its lanes lie is
/// given apart, as a [`Place`]).
pub(crate) struct ChunkJob<'j, 'm, T> {
    pub st: &'j DrawState,
    /// The rotating stipple register.
    pub stipple_state: &'j mut u32,
    /// 86Box's per-triangle stipple copy, as in the walker.
    pub copy: Option<&'j crate::box86::StippleCopy>,
    pub tex: &'j mut T,
    pub consts: &'j TriangleConsts,
    pub mem: &'j mut Memory<'m>,
}

/// What the span kernels read and count besides the frame buffer: the FBI's tables and
/// counters, borrowed from the FBI (or, for a band of the threaded walk, counters of its
/// own, added up afterwards).
pub(crate) struct Shader<'a> {
    pub stats: &'a mut Stats,
    pub counts: &'a mut PathCounts,
    pub dither: &'a Dither,
    pub fog_table: &'a FogTable,
    pub params: &'a TriangleParams,
    pub profile: PixelProfile,
    /// The copy of the kernels to run, where the model has them all
    /// ([`PixelModel::SIMD`]).
    pub isa: VectorIsa,
}

impl Shader<'_> {
    /// Shade one chunk ([`Shader::shade_chunk`] at the width its place asks:
    /// [`ShadeChunk::shade`]), compiled for the instructions `self.isa` names where the
    /// model has every copy ([`PixelModel::SIMD`]; `isa` is never above what the CPU
    /// has, [`crate::Fbi::set_vector_isa`]), for the baseline target otherwise. Every copy
    /// computes the same integers.
    #[inline]
    pub(crate) fn shade_chunk_of<M: PixelModel, T: TexelSource, C: ShadeChunk>(
        &mut self,
        job: ChunkJob<'_, '_, T>,
        place: &C,
    ) {
        #[cfg(target_arch = "x86_64")]
        if M::SIMD {
            match self.isa {
                // SAFETY: `isa` is at most `VectorIsa::best()`, what the CPU has.
                VectorIsa::Avx512 => unsafe { self.shade_chunk_avx512::<M, T, C>(job, place) },
                // SAFETY: as above.
                VectorIsa::Avx2 => unsafe { self.shade_chunk_avx2::<M, T, C>(job, place) },
                VectorIsa::Baseline => self.shade_chunk_baseline::<M, T, C>(job, place),
            }
            return;
        }
        self.shade_chunk_baseline::<M, T, C>(job, place);
    }

    /// [`ShadeChunk::shade`] compiled with AVX2 enabled.
    ///
    /// # Safety
    /// The CPU must have AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn shade_chunk_avx2<M: PixelModel, T: TexelSource, C: ShadeChunk>(
        &mut self,
        job: ChunkJob<'_, '_, T>,
        place: &C,
    ) {
        place.shade::<M, T, Avx2Copy>(self, job);
    }

    /// [`ShadeChunk::shade`] compiled with AVX-512 enabled.
    ///
    /// # Safety
    /// The CPU must have AVX-512 F, DQ, CD, BW and VL.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,avx512f,avx512dq,avx512cd,avx512bw,avx512vl")]
    unsafe fn shade_chunk_avx512<M: PixelModel, T: TexelSource, C: ShadeChunk>(
        &mut self,
        job: ChunkJob<'_, '_, T>,
        place: &C,
    ) {
        place.shade::<M, T, Avx512Copy>(self, job);
    }

    /// [`ShadeChunk::shade`] for the baseline target.
    #[inline(never)]
    fn shade_chunk_baseline<M: PixelModel, T: TexelSource, C: ShadeChunk>(
        &mut self,
        job: ChunkJob<'_, '_, T>,
        place: &C,
    ) {
        place.shade::<M, T, BaselineCopy>(self, job);
    }

    /// Shade one chunk: every stage of [`Fbi::shade_pixel`], a stage at a time, for the
    /// lanes `place` lays out. See [`ChunkJob`] for what it is given; `consts` are the
    /// triangle's constants at this chunk's width.
    #[inline(always)]
    pub(crate) fn shade_chunk<
        M: PixelModel,
        T: TexelSource,
        K: KernelCopy,
        const L: usize,
        P: Place<L>,
    >(
        &mut self,
        job: ChunkJob<'_, '_, T>,
        place: &P,
        consts: &TriangleLanes<L>,
    ) {
        let ChunkJob {
            st,
            stipple_state,
            copy,
            tex,
            mem,
            ..
        } = job;
        let n = place.n();
        debug_assert!((1..=L).contains(&n) && L <= LANES);
        let mode = st.mode;
        self.counts.span_kernels += n as u64;
        let profile = M::pixel(&self.profile);
        let cp = st.color_path;
        let am = st.alpha_mode;
        let fog_mode = st.fog_mode;
        let zero = &consts.zero;
        // A comparison per lane, not `fill` of the first `n` (a call to memset).
        let mut alive: [bool; L] = lanes(|i| i < n);

        // --- stipple ---
        if mode.enable_stipple() {
            let pattern = mode.enable_stipple_pattern();
            for (i, a) in alive.iter_mut().enumerate().take(n) {
                let x = place.x(i);
                if place.starts_span(i) {
                    *stipple_state = st.stipple;
                }
                if let Some(c) = copy {
                    *stipple_state = c.at((x - place.span_start()) as usize);
                }
                if !stipple::test(pattern, stipple_state, st.stipple, x, place.prow(i)) {
                    *a = false;
                    self.stats.kill(Kill::Stipple);
                }
            }
        }

        // --- iterators, depth value and test ---
        let clamp = profile.iterator_clamp;
        let raw_z = place.z();
        let z16: [i32; L] = lanes(|i| clamp.z(raw_z[i]) as i32);
        let w_at = |i: usize| place.w(i);
        let wf: [i32; L] = if mode.wbuffer_select() || fog_mode.enable_fog() {
            lanes(|i| wfloat(w_at(i), profile.wfloat) as i32)
        } else {
            *zero
        };
        let bias = mode.enable_depth_bias().then_some(st.za_color as u16);
        let unbiased = chosen(if mode.wbuffer_select() { &wf } else { &z16 });
        let depth: [i32; L] = match bias {
            Some(b) => {
                let b = b as i16 as i32;
                lanes(|i| (unbiased[i] + b).clamp(0, 0xffff))
            }
            None => *unbiased,
        };
        if mode.enable_depthbuffer() {
            let func = mode.depth_function();
            let source: &[i32; L] = chosen(if mode.depth_source_compare() {
                &consts.za_depth
            } else {
                &depth
            });
            // Without an aux buffer only "never" can fail (MAME, DOSBox Staging).
            let no_aux_fails = func == DepthFunction::Never;
            let fails = place.depth_fails(mem.aux(), func, source, no_aux_fails);
            kill_where(self.stats, &mut alive, n, Kill::DepthFunc, |i| fails[i]);
        }

        // --- colour selection ---
        let texel_store: ColourLanes<L>;
        let texel: &ColourLanes<L> = if cp.texture_enable() && st.fetch_texel {
            let mut t = ColourLanes::ZERO;
            // The texel source takes the widest chunk; a narrower one uses its first lanes.
            let mut wide_alive = [false; LANES];
            wide_alive[..L].copy_from_slice(&alive);
            let mut wide = [[0; LANES]; 4];
            tex.texels::<K>(place.texel_place(), &wide_alive, n, &mut wide);
            for (lanes, w) in t.c.iter_mut().zip(&wide) {
                lanes.copy_from_slice(&w[..L]);
            }
            texel_store = t;
            &texel_store
        } else {
            &consts.zero_colour
        };
        // A channel at a time, written out and into the lanes in place: a loop over the
        // four channels, its lanes unrolled, was vectorised across the channels with a
        // scatter per lane, and arrays returned by value were copied with memcpy. (A
        // function, not a closure: a closure the compiler leaves as a call is compiled
        // for the baseline target, outside the vector kernel.)
        let mut iterated_store = core::mem::MaybeUninit::<ColourLanes<L>>::uninit();
        let iterated: &ColourLanes<L> = {
            let lanes = uninit_channels(&mut iterated_store);
            let [r, g, b, a] = lanes;
            clamp_colour_lanes(r, place.colour(0), clamp);
            clamp_colour_lanes(g, place.colour(1), clamp);
            clamp_colour_lanes(b, place.colour(2), clamp);
            clamp_colour_lanes(a, place.colour(3), clamp);
            // SAFETY: the four calls above wrote every lane of every channel.
            unsafe { iterated_store.assume_init_ref() }
        };
        let (color0, color1) = (&consts.color0, &consts.color1);
        let other_rgb: [&[i32; L]; 3] = match cp.cc_rgbselect() {
            RgbSelect::IteratedRgb => [&iterated.c[0], &iterated.c[1], &iterated.c[2]],
            RgbSelect::Texture => [&texel.c[0], &texel.c[1], &texel.c[2]],
            RgbSelect::Color1 => [&color1.c[0], &color1.c[1], &color1.c[2]],
            _ => [zero; 3],
        };
        let other_a: &[i32; L] = match cp.cc_aselect() {
            AlphaSelect::IteratedAlpha => &iterated.c[3],
            AlphaSelect::Texture => &texel.c[3],
            AlphaSelect::Color1 => &color1.c[3],
            _ => zero,
        };

        // --- chroma key, alpha mask, alpha test on c_other ---
        if mode.enable_chromakey() {
            let key = st.chroma_key;
            let (kr, kg, kb) = (
                (key >> 16 & 0xff) as i32,
                (key >> 8 & 0xff) as i32,
                (key & 0xff) as i32,
            );
            kill_where(self.stats, &mut alive, n, Kill::Chroma, |i| {
                other_rgb[0][i] == kr && other_rgb[1][i] == kg && other_rgb[2][i] == kb
            });
        }
        if mode.enable_alpha_mask() {
            kill_where(self.stats, &mut alive, n, Kill::AlphaMask, |i| {
                other_a[i] & 1 == 0
            });
        }
        let alpha_test = am.alpha_test_enable();
        let (func, reference) = (am.alpha_function(), am.alpha_ref());
        let test_combined = profile.alpha_test_input == AlphaTestInput::Combined;
        if alpha_test && !test_combined {
            let fails = alpha_fails(func, other_a, reference);
            kill_where(self.stats, &mut alive, n, Kill::AlphaFunc, |i| fails[i]);
        }

        // --- local selection ---
        let local_rgb_store: ColourLanes<L>;
        let local_rgb: [&[i32; L]; 3] = if cp.cc_localselect_override() {
            // Texture alpha bit 7 chooses color0 instead of the iterated colour.
            let mut store = ColourLanes::<L>::ZERO;
            for (c, lanes) in store.c.iter_mut().enumerate() {
                for (i, v) in lanes.iter_mut().enumerate() {
                    *v = if texel.c[3][i] & 0x80 != 0 {
                        color0.c[c][i]
                    } else {
                        iterated.c[c][i]
                    };
                }
            }
            local_rgb_store = store;
            [
                &local_rgb_store.c[0],
                &local_rgb_store.c[1],
                &local_rgb_store.c[2],
            ]
        } else if cp.cc_localselect() {
            [&color0.c[0], &color0.c[1], &color0.c[2]]
        } else {
            [&iterated.c[0], &iterated.c[1], &iterated.c[2]]
        };
        let z_alpha: [i32; L];
        let local_a: &[i32; L] = match cp.cca_localselect() {
            AlphaLocalSelect::IteratedAlpha => &iterated.c[3],
            AlphaLocalSelect::Color0 => &color0.c[3],
            AlphaLocalSelect::IteratedZ => {
                z_alpha = lanes(|i| match profile.z_alpha {
                    ZAlphaByte::High => z16[i] >> 8,
                    ZAlphaByte::Low => z16[i] & 0xff,
                });
                &z_alpha
            }
            // UNVERIFIED: reserved on the SST-1; zero, as the reference path.
            _ => zero,
        };

        // --- colour and alpha combine ---
        let mut combined_store = core::mem::MaybeUninit::uninit();
        let combined = combine_units(
            cp,
            other_rgb,
            other_a,
            local_rgb,
            local_a,
            &texel.c[3],
            zero,
            &mut combined_store,
        );
        if alpha_test && test_combined {
            let fails = alpha_fails(func, &combined.c[3], reference);
            kill_where(self.stats, &mut alive, n, Kill::AlphaFunc, |i| fails[i]);
        }

        // --- fog ---
        let fogged_store: ColourLanes<L>;
        let fogged = if fog_mode.enable_fog() {
            let input = fog::FogLanes {
                color: &combined.c,
                alpha: &iterated.c[3],
                z: &z16,
                w: &w_at,
                wfloat: &wf,
                depth_bias: bias.map(|b| b as i16),
            };
            let mut f = ColourLanes::ZERO;
            fog::apply_fog_lanes(
                fog_mode,
                st.fog_color,
                self.fog_table,
                &input,
                profile.fog,
                &mut f.c,
            );
            fogged_store = f;
            &fogged_store
        } else {
            combined
        };

        // --- alpha blend ---
        let blended: ColourLanes<L>;
        let out = if am.alpha_blend_enable() {
            let (dst_rgb565, _) = place.load(mem.colour(), Buffer::Colour);
            let (dst_aux, has_aux) = place.load(mem.aux(), Buffer::Aux);
            let dither_value = place.dither_entries(self.dither, st.dither_matrix);
            let input = blend::BlendLanes {
                src: &fogged.c,
                prefog: &combined.c,
                dst_rgb565: &dst_rgb565,
                dst_aux: &dst_aux,
                has_aux: &has_aux,
                dither_value: &dither_value,
            };
            let mut b = ColourLanes::ZERO;
            blend::alpha_blend_lanes(am, mode, &input, profile.blend, &mut b.c);
            blended = b;
            &blended
        } else {
            fogged
        };

        // --- write ---
        if mode.rgb_buffer_mask() {
            let rgb = [&out.c[0], &out.c[1], &out.c[2]];
            place.store_rgb565(mem.colour(), self.dither, st.dither, rgb, &alive);
        }
        if aux_enabled(mode, profile.aux_write) {
            let planes = mode.enable_alpha_planes();
            let value = chosen(if planes { &out.c[3] } else { &depth });
            let value: [u16; L] = lanes(|i| value[i] as u16);
            place.store(mem.aux(), Buffer::Aux, &alive, &value);
        }
        let out_count: u32 = alive[..n].iter().map(|a| *a as u32).sum();
        self.stats.pixels_out += u64::from(out_count);
    }
}

impl Fbi {
    /// The reference path for one chunk ([`Fbi::shade_pixel`] per pixel), for the buffer
    /// layouts whose lanes alias (see the module documentation).
    #[inline(never)]
    pub(crate) fn shade_chunk_per_pixel<M: PixelModel, T: TexelSource>(
        &mut self,
        st: &DrawState,
        at: &ChunkAt,
        it: &Iterated,
        stipple_state: &mut u32,
        copy: Option<&crate::box86::StippleCopy>,
        tex: &mut T,
    ) {
        self.path_counts.aliased_layout += at.n as u64;
        let p = self.params;
        let mut it = *it;
        for i in 0..at.n {
            let x = at.x0 + i as i32;
            if let Some(c) = copy {
                *stipple_state = c.at((x - at.span_start) as usize);
            }
            let r = self.shade_pixel::<M, crate::watch::NoStages>(
                st,
                x,
                at.prow,
                at.scry,
                &it,
                Source::Triangle,
                stipple_state,
                || tex.texel(x - at.ax, at.dy, x, at.y),
                &mut crate::watch::NoStages,
            );
            self.count(r);
            it.step_x(&p);
        }
    }
}

/// Write `values[i]` to the word of every live lane `i` that has one.
#[inline(always)]
fn store_alive<const L: usize>(ram: &mut [u16], w: Words, alive: &[bool; L], values: &[u16; L]) {
    let dst = &mut ram[w.first..w.first + (w.hi - w.lo)];
    let lanes = alive[w.lo..w.hi].iter().zip(&values[w.lo..w.hi]);
    for (d, (a, v)) in dst.iter_mut().zip(lanes) {
        // A bit mask rather than a choice, so that the loop vectorises.
        let keep = (*a as u16).wrapping_sub(1);
        *d = (*v & !keep) | (*d & keep);
    }
}

/// The words of the lanes `w` covers, as lanes (0 elsewhere), and which lanes have one.
#[inline(always)]
fn load_words<const L: usize>(ram: &[u16], w: Words) -> ([i32; L], [bool; L]) {
    let mut v = [0; L];
    let mut has = [false; L];
    let src = &ram[w.first..w.first + (w.hi - w.lo)];
    for ((v, h), word) in v[w.lo..w.hi].iter_mut().zip(&mut has[w.lo..w.hi]).zip(src) {
        *v = *word as i32;
        *h = true;
    }
    (v, has)
}

/// Whether the aux buffer is written (see [`AuxWrite`]).
#[inline(always)]
pub(crate) fn aux_enabled(mode: FbzMode, aux_write: AuxWrite) -> bool {
    match aux_write {
        AuxWrite::MaskOnly => mode.aux_buffer_mask(),
        AuxWrite::MaskAndDepthOrAlphaPlanes => {
            mode.aux_buffer_mask() && (mode.enable_depthbuffer() || mode.enable_alpha_planes())
        }
    }
}

/// The colour and alpha combine units of [`crate::color_path::combine`] over every lane,
/// their selections (spec 5.16) made once.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn combine_units<'o, const L: usize>(
    cp: FbzColorPath,
    other_rgb: [&[i32; L]; 3],
    other_a: &[i32; L],
    local_rgb: [&[i32; L]; 3],
    local_a: &[i32; L],
    texel_a: &[i32; L],
    zero: &[i32; L],
    store: &'o mut core::mem::MaybeUninit<ColourLanes<L>>,
) -> &'o ColourLanes<L> {
    let out = uninit_channels(store);
    // --- colour ---
    let xor = if cp.cc_reverse_blend() { 0 } else { 0xff };
    let invert = if cp.cc_invert_output() { 0xff } else { 0 };
    for c in 0..3 {
        let other = if cp.cc_zero_other() {
            zero
        } else {
            other_rgb[c]
        };
        let sub = if cp.cc_sub_clocal() {
            local_rgb[c]
        } else {
            zero
        };
        let factor = match cp.cc_mselect() {
            CcMselect::CLocal => local_rgb[c],
            CcMselect::AOther => other_a,
            CcMselect::ALocal => local_a,
            CcMselect::TextureAlpha => texel_a,
            _ => zero,
        };
        // Bits 15:14 as one field: 1 adds c_local, 2 adds a_local, 3 adds nothing.
        let add = match (cp.cc_add_clocal(), cp.cc_add_alocal()) {
            (true, false) => local_rgb[c],
            (false, true) => local_a,
            _ => zero,
        };
        combine_channel(&mut out[c], other, sub, factor, add, xor, invert, zero);
    }

    // --- alpha ---
    let xor = if cp.cca_reverse_blend() { 0 } else { 0xff };
    let invert = if cp.cca_invert_output() { 0xff } else { 0 };
    let other = if cp.cca_zero_other() { zero } else { other_a };
    let sub = if cp.cca_sub_clocal() { local_a } else { zero };
    let factor = match cp.cca_mselect() {
        // In the alpha unit both 1 and 3 select a_local.
        CcMselect::CLocal | CcMselect::ALocal => local_a,
        CcMselect::AOther => other_a,
        CcMselect::TextureAlpha => texel_a,
        _ => zero,
    };
    let add = if cp.cca_add_clocal() || cp.cca_add_alocal() {
        local_a
    } else {
        zero
    };
    combine_channel(&mut out[3], other, sub, factor, add, xor, invert, zero);
    // SAFETY: the four calls above wrote every lane of every channel.
    unsafe { store.assume_init_ref() }
}

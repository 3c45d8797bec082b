//! Pixel history: what happened to one pixel, stage by stage (`voodoo why`,
//! docs/pixel-history.md).
//!
//! A [`PixelWatch`] names one pixel: a column and a frame-buffer row (the row after the
//! Y-origin flip, as a dump lays rows out). While one is set ([`Fbi::set_watch`]), every
//! operation that reaches that pixel leaves a [`PixelEvent`]: a triangle or an LFB write
//! through the pipeline leaves the value of every stage ([`PixelStages`]), a fast fill or
//! a raw LFB write the words it wrote. A set watch forces the reference path
//! ([`Fbi::set_generic_path`]): the span kernels have no hook and no cost, and the
//! reference path is the one [`crate::pipeline`] writes the stages in order for; the
//! two give the same pixels (`crates/board/tests/generic_vs_fast.rs`).
//!
//! The values are recorded by [`crate::pipeline`] itself as it shades the watched pixel
//! (through [`StageSink`], which for every other pixel is [`NoStages`], a sink that
//! compiles to nothing), so the history is the pipeline's own result, not a second
//! model of it.

use serde::{Deserialize, Serialize};
use sst1_regs::Rgba;

use sst1_dither::DitherKind;
use sst1_regs::{DepthFunction, FbzColorPath};

use crate::blend::BlendInput;
use crate::color_path::{self, Inputs};
use crate::fbi::Fbi;
use crate::iter::{Iterated, IteratorClamp};
use crate::model::PixelModel;
use crate::pipeline::{DrawState, Source};
use crate::raster::TexelSource;
use crate::stats::Kill;

/// The most events a watch holds before it drops the oldest (hostile-input guard: a
/// trace may touch a pixel without end). [`PixelWatch::dropped`] counts those dropped.
pub const MAX_EVENTS: usize = 1 << 16;

/// A colour as a stage passes it on: 8 bits a channel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct StageColour {
    pub r: u8,
    pub g: u8,
    pub b: u8,
    pub a: u8,
}

impl From<Rgba> for StageColour {
    fn from(c: Rgba) -> Self {
        Self {
            r: c.r,
            g: c.g,
            b: c.b,
            a: c.a,
        }
    }
}

/// Where a shaded pixel's colour came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum SourceKind {
    /// A triangle: the iterators and the TMU chain.
    Triangle,
    /// An LFB write through the pixel pipeline (`lfbMode` bit 8).
    Lfb,
}

/// The iterators at the pixel, raw (spec 5.15 formats).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct IteratedStage {
    /// Red, green, blue, alpha: 12.12 ([`crate::iter::Iterated::argb`]).
    pub rgba_12_12: [i32; 4],
    /// Z, 20.12.
    pub z_20_12: i32,
    /// W, 32.32 (the iterator's scale).
    pub w_32_32: i64,
    /// The colour after the iterator clamp: what the colour path selects as "iterated".
    pub colour: StageColour,
    /// Z after the clamp, 16-bit integer part.
    pub z16: u16,
    /// The 16-bit floating-point depth of W (spec 5.19).
    pub wfloat: u16,
    /// The value the depth test compares and the aux write stores: Z or W-float,
    /// biased by `zaColor` if `fbzMode` bit 16 says so.
    pub depth_value: i32,
}

/// The depth test's operands and outcome (spec 5.18).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct DepthStage {
    /// `fbzMode[7:5]`, by name.
    pub function: String,
    /// The source value compared: the pixel's depth value, or `zaColor[15:0]` when
    /// `fbzMode` bit 20 selects it.
    pub source: i32,
    /// The aux-buffer word compared against; `None` without an aux buffer.
    pub dest: Option<u16>,
    /// Whether the pixel passed.
    pub pass: bool,
}

/// One TMU's part of a texel: its coordinates, its LOD, the filtered texel and the
/// output of its combine unit (what the next TMU down, or the FBI, receives).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct TmuStage {
    /// TMU number (0 is the one next to the FBI).
    pub tmu: u8,
    /// Iterated S, T, W at the pixel, .32 fixed point (S, T: 14.18 << 14; W: 2.30 << 2).
    pub s_32: i64,
    pub t_32: i64,
    pub w_32: i64,
    /// The clamped LOD, 8.8.
    pub lod_8_8: i32,
    /// The LOD fraction the combine unit sees.
    pub lod_fraction: u8,
    /// The filtered texel.
    pub texel: StageColour,
    /// The TMU's output: its combine unit's result, or the texel where the chain wiring
    /// passes it on uncombined.
    pub output: StageColour,
}

/// The colour path's selections and the combine (spec 5.16 `fbzColorPath`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ColourStage {
    /// `c_other` / `a_other` as selected (the written colour for an LFB pixel).
    pub other: StageColour,
    /// `c_local` / `a_local` as selected.
    pub local: StageColour,
    /// The colour and alpha combine's result; `None` where the pixel was killed before
    /// it (chroma key, alpha mask, alpha test).
    pub combined: Option<StageColour>,
}

/// The fog unit (spec 5.17 `fogMode`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct FogStage {
    /// Whether `fogMode` bit 0 enables fog.
    pub enabled: bool,
    /// The colour out of the fog unit (its input is [`ColourStage::combined`]).
    pub output: StageColour,
}

/// The alpha blend (spec 5.18 `alphaMode`), when enabled.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct BlendStage {
    /// The source: the fog unit's output.
    pub src: StageColour,
    /// The colour before fog (`A_COLORBEFOREFOG`).
    pub prefog: StageColour,
    /// The destination pixel read from the colour buffer.
    pub dst_rgb565: u16,
    /// The aux word read (destination alpha with alpha planes).
    pub dst_aux: Option<u16>,
    /// The dither-matrix entry the dither subtraction reads.
    pub dither_value: u8,
    /// The blend's result.
    pub output: StageColour,
}

/// The dither and the writes (spec 5.19: RGB write mask, aux write).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct WriteStage {
    /// The colour dithered: the blend's output, or the fog's without blending.
    pub colour: StageColour,
    /// The dither applied: "off", "4x4" or "2x2".
    pub dither: DitherName,
    /// The matrix entry at the pixel (0 with dithering off).
    pub dither_value: u8,
    /// The RGB565 word written and its frame-buffer word index; `None` where the RGB
    /// write mask is off or the pixel is outside the buffer.
    pub colour_word: Option<WordWrite>,
    /// The aux word written (depth, or alpha with alpha planes) and its index.
    pub aux_word: Option<WordWrite>,
}

/// The dither a write applies (`sst1_dither::DitherKind`, by name).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum DitherName {
    #[default]
    Off,
    Dither4x4,
    Dither2x2,
}

impl From<sst1_dither::DitherKind> for DitherName {
    fn from(k: sst1_dither::DitherKind) -> Self {
        match k {
            sst1_dither::DitherKind::Off => DitherName::Off,
            sst1_dither::DitherKind::Dither4x4 => DitherName::Dither4x4,
            sst1_dither::DitherKind::Dither2x2 => DitherName::Dither2x2,
        }
    }
}

/// One 16-bit word written into frame-buffer memory.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct WordWrite {
    /// Index of the word in frame-buffer memory (`FrameBuffer::ram`).
    pub index: usize,
    /// The value written.
    pub value: u16,
}

/// Which hardware counter a pixel's fate moved (spec 5.31-5.35), read from the counters
/// themselves before and after the pixel was counted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Counted {
    /// `fbiPixelsOut`.
    PixelsOut,
    /// `fbiZfuncFail`.
    ZfuncFail,
    /// `fbiChromaFail`.
    ChromaFail,
    /// `fbiAfuncFail`.
    AfuncFail,
    /// None of them (stipple, clip).
    Nothing,
}

impl Counted {
    /// The counter that moved between `before` and `after` (one pixel's counting).
    pub fn between(before: &crate::Stats, after: &crate::Stats) -> Counted {
        if after.pixels_out != before.pixels_out {
            Counted::PixelsOut
        } else if after.zfunc_fail != before.zfunc_fail {
            Counted::ZfuncFail
        } else if after.chroma_fail != before.chroma_fail {
            Counted::ChromaFail
        } else if after.afunc_fail != before.afunc_fail {
            Counted::AfuncFail
        } else {
            Counted::Nothing
        }
    }
}

/// Every stage of one pixel through the pipeline, in hardware order
/// ([`crate::pipeline`]). A stage the pixel did not reach (it was killed before) is
/// `None`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct PixelStages {
    pub source: SourceKind,
    /// Screen column.
    pub x: i32,
    /// Frame-buffer row (after the Y-origin flip).
    pub row: i32,
    /// The row the dither and stipple patterns are indexed with.
    pub pattern_row: i32,
    /// The iterated values (for an LFB pixel: its colour and depth as if iterated).
    pub iterated: Option<IteratedStage>,
    /// The depth test, if `fbzMode` enables it.
    pub depth: Option<DepthStage>,
    /// The texel from the TMU chain, if texturing is on and the chain was read.
    pub texel: Option<StageColour>,
    /// Each TMU's part, upstream TMU first (empty without texturing).
    pub tmus: Vec<TmuStage>,
    pub colour: Option<ColourStage>,
    pub fog: Option<FogStage>,
    pub blend: Option<BlendStage>,
    pub write: Option<WriteStage>,
    /// Why the pipeline killed the pixel, if it did.
    pub kill: Option<Kill>,
    /// The counter the pixel's fate moved.
    pub counted: Counted,
}

impl PixelStages {
    /// Nothing recorded yet, for a pixel of `source` at `(x, row)`.
    pub(crate) fn new(source: SourceKind, x: i32, row: i32, pattern_row: i32) -> Self {
        Self {
            source,
            x,
            row,
            pattern_row,
            iterated: None,
            depth: None,
            texel: None,
            tmus: Vec::new(),
            colour: None,
            fog: None,
            blend: None,
            write: None,
            kill: None,
            counted: Counted::Nothing,
        }
    }
}

/// Where the pipeline puts the values of its stages ([`crate::pipeline`]), one method
/// per stage, each given values the pipeline has at hand. Every method does nothing by
/// default: [`NoStages`] keeps the defaults, so the pipeline for an unwatched pixel is
/// compiled as if the calls were not there. (Closures that recorded, though never
/// called, changed the LFB path's code: about 20 instructions more per LFB write under
/// callgrind. Plain calls of empty methods do not.)
pub(crate) trait StageSink {
    /// Whether the sink records (the pipeline tests it before work done only to record).
    const RECORDS: bool = false;

    /// The iterators at the pixel, the 16-bit Z and W-float, and the depth value.
    #[inline(always)]
    fn iterated(
        &mut self,
        _it: &Iterated,
        _source: &Source,
        _clamp: IteratorClamp,
        _z16: u16,
        _wfloat: u16,
        _depth_value: i32,
    ) {
    }

    /// The depth test's operands and outcome.
    #[inline(always)]
    fn depth(&mut self, _function: DepthFunction, _source: i32, _dest: Option<u16>, _pass: bool) {}

    /// The texel from the TMU chain; returns it.
    #[inline(always)]
    fn texel(&mut self, texel: Rgba) -> Rgba {
        texel
    }

    /// The colour path's inputs and its `other` selection (`local` is selected from
    /// them by the function the pipeline calls).
    #[inline(always)]
    fn colour_path(&mut self, _color_path: FbzColorPath, _inputs: &Inputs, _other: Rgba) {}

    /// The colour and alpha combine's result; returns it.
    #[inline(always)]
    fn combined(&mut self, combined: Rgba) -> Rgba {
        combined
    }

    /// The fog unit's output.
    #[inline(always)]
    fn fog(&mut self, _enabled: bool, _output: Rgba) {}

    /// The blend's inputs and result; returns the result.
    #[inline(always)]
    fn blend(&mut self, _input: &BlendInput, output: Rgba) -> Rgba {
        output
    }

    /// The colour dithered and the words written (indices into `ram`, after the write).
    #[inline(always)]
    fn write(
        &mut self,
        _colour: Rgba,
        _dither: DitherKind,
        _dither_value: u8,
        _ram: &[u16],
        _rgb: Option<usize>,
        _aux: Option<usize>,
    ) {
    }
}

/// The sink of every pixel not watched: records nothing, compiles to nothing.
pub(crate) struct NoStages;

impl StageSink for NoStages {}

impl StageSink for PixelStages {
    const RECORDS: bool = true;

    fn iterated(
        &mut self,
        it: &Iterated,
        source: &Source,
        clamp: IteratorClamp,
        z16: u16,
        wfloat: u16,
        depth_value: i32,
    ) {
        let colour = match *source {
            Source::Triangle => Rgba {
                r: clamp.colour(it.argb[0]),
                g: clamp.colour(it.argb[1]),
                b: clamp.colour(it.argb[2]),
                a: clamp.colour(it.argb[3]),
            },
            Source::Lfb(c) => c,
        };
        self.iterated = Some(IteratedStage {
            rgba_12_12: it.argb,
            z_20_12: it.z,
            w_32_32: it.w,
            colour: colour.into(),
            z16,
            wfloat,
            depth_value,
        });
    }

    fn depth(&mut self, function: DepthFunction, source: i32, dest: Option<u16>, pass: bool) {
        self.depth = Some(DepthStage {
            function: format!("{function:?}"),
            source,
            dest,
            pass,
        });
    }

    fn texel(&mut self, texel: Rgba) -> Rgba {
        self.texel = Some(texel.into());
        texel
    }

    fn colour_path(&mut self, color_path: FbzColorPath, inputs: &Inputs, other: Rgba) {
        self.colour = Some(ColourStage {
            other: other.into(),
            local: color_path::select_local(color_path, inputs).into(),
            combined: None,
        });
    }

    fn combined(&mut self, combined: Rgba) -> Rgba {
        if let Some(c) = &mut self.colour {
            c.combined = Some(combined.into());
        }
        combined
    }

    fn fog(&mut self, enabled: bool, output: Rgba) {
        self.fog = Some(FogStage {
            enabled,
            output: output.into(),
        });
    }

    fn blend(&mut self, input: &BlendInput, output: Rgba) -> Rgba {
        self.blend = Some(BlendStage {
            src: input.src.into(),
            prefog: input.prefog.into(),
            dst_rgb565: input.dst_rgb565,
            dst_aux: input.dst_aux,
            dither_value: input.dither_value,
            output: output.into(),
        });
        output
    }

    fn write(
        &mut self,
        colour: Rgba,
        dither: DitherKind,
        dither_value: u8,
        ram: &[u16],
        rgb: Option<usize>,
        aux: Option<usize>,
    ) {
        let word = |i: Option<usize>| {
            i.map(|index| WordWrite {
                index,
                value: ram[index],
            })
        };
        self.write = Some(WriteStage {
            colour: colour.into(),
            dither: dither.into(),
            dither_value,
            colour_word: word(rgb),
            aux_word: word(aux),
        });
    }
}

/// Something that happened to the watched pixel.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum PixelEvent {
    /// A triangle or pipeline LFB write shaded the pixel.
    Shaded(Box<PixelStages>),
    /// A triangle covered the pixel, or a pipeline LFB write reached it, outside the
    /// clip rectangle (`fbzMode` bit 0): killed before the pipeline.
    Clipped { source: SourceKind },
    /// `fastfillCMD` wrote the pixel.
    Fastfill {
        colour_word: Option<WordWrite>,
        aux_word: Option<WordWrite>,
    },
    /// An LFB write that bypasses the pipeline wrote the pixel.
    LfbDirect {
        colour_word: Option<WordWrite>,
        aux_word: Option<WordWrite>,
    },
}

impl PixelEvent {
    /// The word written at frame-buffer word `index`, if the event wrote it.
    pub fn wrote(&self, index: usize) -> Option<u16> {
        let (c, a) = match self {
            PixelEvent::Shaded(s) => match &s.write {
                Some(w) => (w.colour_word, w.aux_word),
                None => (None, None),
            },
            PixelEvent::Clipped { .. } => (None, None),
            PixelEvent::Fastfill {
                colour_word,
                aux_word,
            }
            | PixelEvent::LfbDirect {
                colour_word,
                aux_word,
            } => (*colour_word, *aux_word),
        };
        // The aux word is written after the colour word: where the two alias, its
        // value is the one left.
        [c, a]
            .into_iter()
            .flatten()
            .rfind(|w| w.index == index)
            .map(|w| w.value)
    }
}

/// The watched pixel and what has happened to it since the events were last taken.
#[derive(Clone, Debug)]
pub struct PixelWatch {
    /// Screen column.
    pub x: i32,
    /// Frame-buffer row.
    pub row: i32,
    events: std::collections::VecDeque<PixelEvent>,
    dropped: u64,
}

impl PixelWatch {
    /// A watch on column `x` of frame-buffer row `row`.
    pub fn new(x: i32, row: i32) -> Self {
        Self {
            x,
            row,
            events: std::collections::VecDeque::new(),
            dropped: 0,
        }
    }

    /// Whether `(x, row)` is the watched pixel.
    #[inline]
    pub fn is(&self, x: i32, row: i32) -> bool {
        self.x == x && self.row == row
    }

    /// Record an event, dropping the oldest past [`MAX_EVENTS`].
    pub(crate) fn push(&mut self, event: PixelEvent) {
        if self.events.len() == MAX_EVENTS {
            self.events.pop_front();
            self.dropped += 1;
        }
        self.events.push_back(event);
    }

    /// The events recorded since the last call, oldest first.
    pub fn take(&mut self) -> Vec<PixelEvent> {
        self.events.drain(..).collect()
    }

    /// Events dropped because more than [`MAX_EVENTS`] were waiting.
    pub fn dropped(&self) -> u64 {
        self.dropped
    }
}

impl Fbi {
    /// Watch one pixel (column `x`, frame-buffer row `row`), or stop watching (`None`).
    /// A watch forces the reference path (see the module documentation); stopping does
    /// not give the span kernels back (call [`Fbi::set_generic_path`]).
    pub fn set_watch(&mut self, watch: Option<PixelWatch>) {
        if watch.is_some() {
            self.generic_path = true;
        }
        self.watch = watch.map(Box::new);
    }

    /// The watch, if one is set.
    pub fn watch_mut(&mut self) -> Option<&mut PixelWatch> {
        self.watch.as_deref_mut()
    }

    /// The watched column on frame-buffer row `row`, if the watch is on that row.
    #[inline]
    pub(crate) fn watched_column(&self, row: i32) -> Option<i32> {
        self.watch.as_ref().filter(|w| w.row == row).map(|w| w.x)
    }

    /// Record `event` if a watch is set.
    pub(crate) fn record(&mut self, event: PixelEvent) {
        if let Some(w) = &mut self.watch {
            w.push(event);
        }
    }
}

impl Fbi {
    /// Shade the watched pixel of a triangle's row through the reference path, recording
    /// its stages, and count it. `(dx, dy, x, y)`: the pixel's offset from vertex A and
    /// its screen position, as [`crate::TexelSource::texel`] takes them.
    #[cold]
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn shade_watched<M: PixelModel, T: TexelSource>(
        &mut self,
        st: &DrawState,
        prow: i32,
        scry: i32,
        it: &Iterated,
        stipple_state: &mut u32,
        tex: &mut T,
        (dx, dy, x, y): (i32, i32, i32, i32),
    ) {
        let mut stages = PixelStages::new(SourceKind::Triangle, x, scry, prow);
        let mut tmus = Vec::new();
        let r = self.shade_pixel::<M, PixelStages>(
            st,
            x,
            prow,
            scry,
            it,
            Source::Triangle,
            stipple_state,
            || tex.texel_stages(dx, dy, x, y, &mut tmus),
            &mut stages,
        );
        stages.tmus = tmus;
        self.count_watched(stages, r);
    }

    /// Shade the watched pixel of a pipeline LFB write, recording its stages, and count
    /// it.
    #[cold]
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn shade_watched_lfb<M: PixelModel>(
        &mut self,
        st: &DrawState,
        x: i32,
        prow: i32,
        scry: i32,
        it: &Iterated,
        colour: Rgba,
        stipple_state: &mut u32,
    ) {
        let mut stages = PixelStages::new(SourceKind::Lfb, x, scry, prow);
        let r = self.shade_pixel::<M, PixelStages>(
            st,
            x,
            prow,
            scry,
            it,
            Source::Lfb(colour),
            stipple_state,
            Rgba::default,
            &mut stages,
        );
        self.count_watched(stages, r);
    }

    /// Count a watched pixel's fate and record it with the counter that moved.
    fn count_watched(&mut self, mut stages: PixelStages, r: Result<(), Kill>) {
        let before = self.stats;
        self.count(r);
        stages.kill = r.err();
        stages.counted = Counted::between(&before, &self.stats);
        self.record(PixelEvent::Shaded(Box::new(stages)));
    }

    /// A triangle's span `start..stop` on frame-buffer row `scry`, before clipping:
    /// records [`PixelEvent::Clipped`] if it covers the watched pixel and the clip
    /// rectangle leaves it out.
    pub(crate) fn watch_clip(&mut self, st: &DrawState, scry: i32, start: i32, stop: i32) {
        let Some(x) = self.watched_column(scry) else {
            return;
        };
        let (left, right, low, high) = st.clip;
        let outside = x < left || x >= right || scry < low || scry >= high;
        if (start..stop).contains(&x) && st.mode.enable_clipping() && outside {
            self.record(PixelEvent::Clipped {
                source: SourceKind::Triangle,
            });
        }
    }

    /// After a fast fill of raster rows `rows` and columns `columns` into colour buffer
    /// `dest` and aux buffer `aux`: records the words it left at the watched pixel.
    pub(crate) fn watch_fill(
        &mut self,
        rows: core::ops::Range<i32>,
        columns: core::ops::Range<i32>,
        flip: bool,
        dest: Option<usize>,
        aux: Option<usize>,
    ) {
        let Some((x, row)) = self.watch.as_ref().map(|w| (w.x, w.row)) else {
            return;
        };
        let hit = rows.clone().any(|y| self.screen_y(y, flip) == row) && columns.contains(&x);
        if hit {
            let colour_word = self.word_at(dest, x, row);
            let aux_word = self.word_at(aux, x, row);
            self.record(PixelEvent::Fastfill {
                colour_word,
                aux_word,
            });
        }
    }

    /// The word at `(x, row)` of the buffer at `base`, if there is one.
    pub(crate) fn word_at(&self, base: Option<usize>, x: i32, row: i32) -> Option<WordWrite> {
        let index = self.fb.index(base?, x, row)?;
        Some(WordWrite {
            index,
            value: self.fb.ram[index],
        })
    }
}

impl Fbi {
    /// After an LFB write that bypasses the pipeline wrote pixel `p` at `(x, row)` of
    /// colour buffer `dest`: records the words it wrote (the colour if the format
    /// carries one; the aux word if it carries what `alpha_planes` says the aux buffer
    /// holds).
    pub(crate) fn watch_lfb_direct(
        &mut self,
        dest: usize,
        x: i32,
        row: i32,
        p: &crate::lfb::LfbPixel,
        alpha_planes: bool,
    ) {
        let colour_word = p.rgb.and_then(|_| self.word_at(Some(dest), x, row));
        let aux_written = if alpha_planes {
            p.alpha.is_some()
        } else {
            p.depth.is_some()
        };
        let aux_word = aux_written
            .then(|| self.word_at(self.fb.aux_base(), x, row))
            .flatten();
        self.record(PixelEvent::LfbDirect {
            colour_word,
            aux_word,
        });
    }
}

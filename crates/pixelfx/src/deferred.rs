//! Small triangles shaded on a render thread of their own, while the calling thread goes
//! on with the trace and the register writes after them. Each batch's walk counts
//! ([`WalkCounts`]) come back as it is shaded, for the board's timing model.
//!
//! A triangle too small for bands of rows ([`crate::raster`]) is a few hundred cycles of
//! walk and shading after a few hundred of register writes; on one thread they take turns.
//! Here the calling thread keeps the FBI's registers and lends the render thread what the
//! walk writes and reads besides them: the frame-buffer memory, the fog table and the
//! profile, and the texel source's chips (`C`: the board lends its TMUs, whose register
//! and texture writes then follow the triangles, [`RenderThread::push_chips`]). Each
//! triangle goes over as a [`TriangleJob`], the drawing state and the parameters
//! captured at its command, with chip states of its own where its caller keeps some of
//! the chips' registers (`X`, the board's: each TMU's S, T, W writes since its last
//! textured triangle); the render thread runs the jobs in order on an FBI of its
//! own (its twin, whose registers are never read). [`RenderThread::settle`] takes the
//! memory and the chips back, with the counters the jobs added; the board settles
//! before anything that reads or writes the frame buffer, the counters or the tables
//! (an LFB access, a FASTFILL, a swap, a large triangle, a write to the fog table, an
//! init register or `nopCMD`, and every access that is not a write). So every pixel and
//! counter is what drawing each triangle at its command gives (the identity tests
//! replay every trace with 1, 2 and 4 threads).
//!
//! Memory is bounded: jobs go in batches of at most [`BATCH`] triangles (each with at
//! most 255 chip states) and [`BATCH_WRITES`] chip writes over a channel of [`IN_FLIGHT`]
//! batches, and the calling thread waits while it is full.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::mpsc::{self, Receiver, Sender, SyncSender, TryRecvError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use sst1_dither::Dither;
use sst1_fog::FogTable;

use crate::fb::FrameBuffer;
use crate::fbi::{Fbi, PathCounts};
use crate::isa::VectorIsa;
use crate::model::PixelModel;
use crate::params::TriangleParams;
use crate::pipeline::DrawState;
use crate::profile::PixelProfile;
use crate::raster::{NoTexture, TexelSource};
use crate::stats::Stats;

/// Triangles sent at a time (a channel operation per batch, not per triangle; 10-pixel
/// textured triangles on two threads ran in 0.90x the time with 256 as with 32,
/// measured: docs/performance.md).
const BATCH: usize = 256;

/// Chip writes sent at a time at most (a texture download between two triangles is many).
const BATCH_WRITES: usize = 4096;

/// Batches the channel holds before the calling thread waits for the render thread.
const IN_FLIGHT: usize = 16;

/// How long the render thread spins for the next batch before it sleeps, while it holds
/// the memory (a sleeping thread's wake-up is a system call on the calling thread).
const SPIN: Duration = Duration::from_micros(200);

/// How long the calling thread spins for the memory to come back before it sleeps.
const SETTLE_SPIN: Duration = Duration::from_micros(500);

/// One triangle to shade: what its command captured.
pub struct TriangleJob<C, X> {
    st: DrawState,
    params: TriangleParams,
    /// The walk of the board's model, with its texel source made from the lent chips
    /// (the triangle's chip state passed on).
    draw: DrawJob<C, X>,
    /// How many chip states the triangle has ([`RenderThread::push`]), the next in its
    /// batch's list.
    chip_states: u8,
}

/// A job's walk: the twin, the lent chips, the captured state and the triangle's chip
/// states: what its command captured for the lent chips, if anything (the board's: the
/// TMUs' S, T, W registers of a textured triangle, one per TMU, which it keeps while it
/// lends them).
pub type DrawJob<C, X> = fn(&mut Fbi, &mut C, &DrawState, &[X]);

/// A write to the lent chips (a TMU register or texture memory write: `apply` with its
/// arguments), run before triangle `before` of its batch (or after the last, where
/// `before` is their count).
struct ChipWrite<C> {
    before: u32,
    apply: fn(&mut C, [u32; 3]),
    args: [u32; 3],
}

/// What the render thread runs, in order: the triangles, with the chip writes between
/// them and the chip states of those that have one (three lists, so that a write, a
/// few words, is not stored as a triangle's hundreds of bytes, nor a chip state in the
/// triangles that have none).
struct Batch<C, X> {
    triangles: Vec<TriangleJob<C, X>>,
    writes: Vec<ChipWrite<C>>,
    chip_states: Vec<X>,
}

impl<C, X> Batch<C, X> {
    fn new() -> Self {
        Self {
            triangles: Vec::with_capacity(BATCH),
            writes: Vec::new(),
            chip_states: Vec::new(),
        }
    }

    fn is_empty(&self) -> bool {
        self.triangles.is_empty() && self.writes.is_empty()
    }

    fn clear(&mut self) {
        self.triangles.clear();
        self.writes.clear();
        self.chip_states.clear();
    }

    /// Run the batch on `twin` and `chips`, in order, each triangle's walk counts onto
    /// `counts`.
    fn run(&self, twin: &mut Fbi, chips: &mut C, counts: &mut Vec<WalkCounts>) {
        let mut writes = self.writes.iter().peekable();
        let mut chip_states = &self.chip_states[..];
        for (i, job) in self.triangles.iter().enumerate() {
            while let Some(w) = writes.next_if(|w| w.before as usize == i) {
                (w.apply)(chips, w.args);
            }
            twin.params = job.params;
            let before = (twin.stats.pixels_in, twin.stats.spans);
            let (states, rest) = chip_states.split_at(usize::from(job.chip_states));
            chip_states = rest;
            (job.draw)(twin, chips, &job.st, states);
            counts.push(WalkCounts {
                pixels: twin.stats.pixels_in.wrapping_sub(before.0),
                spans: twin.stats.spans.wrapping_sub(before.1),
            });
        }
        for w in writes {
            (w.apply)(chips, w.args);
        }
    }
}

/// What a triangle's walk counted: its pixels (`fbiPixelsIn`) and rows, what the
/// board's timing model charges for it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WalkCounts {
    pub pixels: u64,
    pub spans: u64,
}

/// What the calling thread lends: the FBI's part, and the chips.
struct Lent<C> {
    fbi: LentFbi,
    chips: C,
}

/// The FBI's part of what is lent: the frame buffer with its memory, and the tables the
/// walk reads.
struct LentFbi {
    fb: FrameBuffer,
    fog_table: FogTable,
    profile: PixelProfile,
    isa: VectorIsa,
}

/// What comes back: the memory and what the jobs added to the counters.
struct Returned<C> {
    ram: Vec<u16>,
    chips: C,
    stats: Stats,
    path_counts: PathCounts,
    /// A job panicked (a bug): the memory is as the jobs before it left it.
    panicked: bool,
}

enum Message<C, X> {
    Lend(Box<Lent<C>>),
    Jobs(Batch<C, X>),
    Settle,
}

/// How the render thread failed (a bug either way).
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RenderThreadFailed {
    /// A job panicked.
    #[error("the render thread panicked shading a triangle")]
    Panicked,
    /// The thread is gone, and the frame-buffer memory it held with it.
    #[error("the render thread stopped")]
    Stopped,
}

/// The render thread and the calling thread's end of its channels; `C`, the chips the
/// texel source is made of, lent with the memory; `X`, what each triangle's job carries
/// for them.
pub struct RenderThread<C: Send + 'static, X: Send + 'static> {
    to: Option<SyncSender<Message<C, X>>>,
    back: Receiver<Returned<C>>,
    /// Emptied batches coming back to be filled again (no allocation per batch).
    spent: Receiver<Batch<C, X>>,
    /// Each batch's walk counts, in order, once it is shaded.
    counted: Receiver<Vec<WalkCounts>>,
    batch: Batch<C, X>,
    lent: bool,
    thread: Option<JoinHandle<()>>,
}

impl<C: Send + Default + 'static, X: Send + 'static> RenderThread<C, X> {
    /// A render thread, or `None` where one cannot be started.
    pub fn start() -> Option<Self> {
        let (to, from) = mpsc::sync_channel(IN_FLIGHT);
        let (give, back) = mpsc::sync_channel(1);
        let (spend, spent) = mpsc::sync_channel(IN_FLIGHT + 2);
        // Unbounded, but the calling thread takes them at every batch it sends and at
        // every settle: at most the batches in flight wait there.
        let (count, counted) = mpsc::channel();
        let thread = std::thread::Builder::new()
            .name("voodoo-render".into())
            .spawn(move || serve(from, give, spend, count))
            .ok()?;
        Some(Self {
            to: Some(to),
            back,
            spent,
            counted,
            batch: Batch::new(),
            lent: false,
            thread: Some(thread),
        })
    }

    /// Whether the render thread holds `fbi`'s memory (jobs may be pending).
    #[inline]
    pub fn is_lent(&self) -> bool {
        self.lent
    }

    /// The walk counts of the next batch of triangles shaded, in the order they were
    /// queued, if it is done ([`RenderThread::push`] says when to ask; after a
    /// [`RenderThread::settle`], every one is there).
    pub fn counted(&self) -> Option<Vec<WalkCounts>> {
        self.counted.try_recv().ok()
    }

    /// Queue `job` with its chip states (see [`DrawJob`]), lending `fbi`'s memory and
    /// `chips` first if the render thread does not hold them (`chips` is left empty
    /// until [`RenderThread::settle`]); `true` when
    /// a batch went to the render thread (the time to collect what is
    /// [`RenderThread::counted`]). An error only where the render thread is gone (a
    /// bug; see [`RenderThread::settle`]).
    pub fn push(
        &mut self,
        fbi: &mut Fbi,
        chips: &mut C,
        mut job: TriangleJob<C, X>,
        chip_states: &[X],
    ) -> Result<bool, RenderThreadFailed>
    where
        X: Copy,
    {
        if !self.lent {
            let lent = Box::new(Lent {
                fbi: fbi.lend(),
                chips: std::mem::take(chips),
            });
            self.lent = true;
            self.send(Message::Lend(lent))?;
        }
        if !chip_states.is_empty() {
            // At most 255 (the board's: at most 3).
            let chip_states = &chip_states[..chip_states.len().min(usize::from(u8::MAX))];
            job.chip_states = chip_states.len() as u8;
            self.batch.chip_states.extend_from_slice(chip_states);
        }
        self.batch.triangles.push(job);
        if self.batch.triangles.len() == BATCH {
            self.flush()?;
            return Ok(true);
        }
        Ok(false)
    }

    /// Queue a write to the lent chips, behind the triangles queued before it; only
    /// while they are lent ([`RenderThread::is_lent`]).
    pub fn push_chips(
        &mut self,
        apply: fn(&mut C, [u32; 3]),
        args: [u32; 3],
    ) -> Result<(), RenderThreadFailed> {
        debug_assert!(self.lent);
        let before = self.batch.triangles.len() as u32;
        self.batch.writes.push(ChipWrite {
            before,
            apply,
            args,
        });
        if self.batch.writes.len() == BATCH_WRITES {
            self.flush()?;
        }
        Ok(())
    }

    /// Wait for every queued job and take the memory and the counters back into `fbi`,
    /// and the chips into `chips`. Nothing to do if the render thread does not hold the
    /// memory.
    ///
    /// An error (both are bugs): a job panicked, the memory and chips as the jobs before
    /// it left them; or the render thread is gone, and the memory with it.
    pub fn settle(&mut self, fbi: &mut Fbi, chips: &mut C) -> Result<(), RenderThreadFailed> {
        if !self.lent {
            return Ok(());
        }
        self.flush()?;
        self.send(Message::Settle)?;
        self.lent = false;
        let returned = receive(&self.back, SETTLE_SPIN).ok_or(RenderThreadFailed::Stopped)?;
        fbi.take_back(returned.ram, &returned.stats, &returned.path_counts);
        *chips = returned.chips;
        if returned.panicked {
            return Err(RenderThreadFailed::Panicked);
        }
        Ok(())
    }

    fn flush(&mut self) -> Result<(), RenderThreadFailed> {
        if self.batch.is_empty() {
            return Ok(());
        }
        let next = self.spent.try_recv().unwrap_or_else(|_| Batch::new());
        let full = std::mem::replace(&mut self.batch, next);
        self.send(Message::Jobs(full))
    }

    fn send(&self, message: Message<C, X>) -> Result<(), RenderThreadFailed> {
        match self.to.as_ref().map(|to| to.send(message)) {
            Some(Ok(())) => Ok(()),
            _ => Err(RenderThreadFailed::Stopped),
        }
    }
}

impl<C: Send + 'static, X: Send + 'static> Drop for RenderThread<C, X> {
    fn drop(&mut self) {
        // Closing the channel ends the thread (after the batch it is shading).
        self.to = None;
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// The next message, spinning for up to `spin` before sleeping; `None` once the other
/// end is gone.
fn receive<T>(from: &Receiver<T>, spin: Duration) -> Option<T> {
    let started = Instant::now();
    let mut tries = 0u32;
    loop {
        match from.try_recv() {
            Ok(m) => return Some(m),
            Err(TryRecvError::Disconnected) => return None,
            Err(TryRecvError::Empty) => {}
        }
        tries += 1;
        // The clock is read every 64 tries (a read costs as much as many tries).
        if tries.is_multiple_of(64) && started.elapsed() >= spin {
            return from.recv().ok();
        }
        std::hint::spin_loop();
    }
}

/// The render thread: shades the jobs in order on its twin FBI while it holds the memory.
fn serve<C: Default, X>(
    from: Receiver<Message<C, X>>,
    give: SyncSender<Returned<C>>,
    spend: SyncSender<Batch<C, X>>,
    count: Sender<Vec<WalkCounts>>,
) {
    let mut twin: Option<Fbi> = None;
    let mut chips = C::default();
    let mut holding = false;
    let mut panicked = false;
    loop {
        // Holding the memory, the next batch is close; not, it may be long.
        let message = if holding {
            receive(&from, SPIN)
        } else {
            from.recv().ok()
        };
        let Some(message) = message else {
            return;
        };
        match message {
            Message::Lend(lent) => {
                let Lent { fbi, chips: lent } = *lent;
                chips = lent;
                match twin.as_mut() {
                    Some(t) => t.borrow(fbi),
                    None => twin = Some(Fbi::twin(fbi)),
                }
                holding = true;
                panicked = false;
            }
            Message::Jobs(mut jobs) => {
                if let (Some(t), false) = (twin.as_mut(), panicked) {
                    let mut counts = Vec::with_capacity(jobs.triangles.len());
                    let shaded =
                        catch_unwind(AssertUnwindSafe(|| jobs.run(t, &mut chips, &mut counts)));
                    panicked = shaded.is_err();
                    // Sent before the memory at the settle: the calling thread has every
                    // batch's counts once it has the memory back.
                    if !panicked && count.send(counts).is_err() {
                        return;
                    }
                }
                jobs.clear();
                let _ = spend.try_send(jobs);
            }
            Message::Settle => {
                let Some(t) = twin.as_mut() else {
                    return;
                };
                let returned = Returned {
                    ram: std::mem::take(&mut t.fb.ram),
                    chips: std::mem::take(&mut chips),
                    stats: std::mem::take(&mut t.stats),
                    path_counts: std::mem::take(&mut t.path_counts),
                    panicked,
                };
                holding = false;
                if give.send(returned).is_err() {
                    return;
                }
            }
        }
    }
}

/// An untextured triangle's walk: counted and shaded as [`Fbi::draw_triangle`] does with
/// the span kernels and no texture.
pub fn draw_untextured<M: PixelModel, C, X>(twin: &mut Fbi, _: &mut C, st: &DrawState, _: &[X]) {
    twin.shade_job::<M, _>(st, &mut NoTexture);
}

impl Fbi {
    /// The colour buffer the triangle in the parameter registers draws into, if it may
    /// be shaded on the render thread (the board decides the rest): span kernels, no
    /// watched pixel, too small for bands of rows, and a colour buffer to draw into (a
    /// triangle with none is counted at its command, its texel source's state updated
    /// as it would be).
    #[inline]
    pub fn deferrable<M: PixelModel>(&self) -> Option<usize> {
        if !M::SPAN_KERNELS
            || self.generic_path
            || self.watch.is_some()
            || crate::raster::box_pixels(&self.params) >= crate::raster::MIN_THREADED_PIXELS as u64
        {
            return None;
        }
        self.colour_buffer(self.fbz_mode().draw_buffer())
    }

    /// The job of the triangle in the parameter registers (the `triangleCMD` command,
    /// after the FBI's subpixel correction) into colour buffer `dest`
    /// ([`Fbi::deferrable`]), drawn by `draw` (for example [`draw_untextured`]).
    pub fn triangle_job<M: PixelModel, C, X>(
        &self,
        dest: usize,
        draw: DrawJob<C, X>,
    ) -> TriangleJob<C, X> {
        TriangleJob {
            st: DrawState::capture::<M>(self, dest),
            params: self.params,
            draw,
            chip_states: 0,
        }
    }

    /// A job's triangle on the twin: counted and shaded as [`Fbi::draw_triangle`] does
    /// with the span kernels, from `tex`.
    pub fn shade_job<M: PixelModel, T: TexelSource>(&mut self, st: &DrawState, tex: &mut T) {
        self.stats.triangles += 1;
        let st = st.for_span_kernels(&M::pixel(&self.profile()), tex.samples_purely());
        self.walk::<M, T, true>(&st, tex);
    }

    /// The frame buffer with its memory (this FBI keeps the layout and buffer indices,
    /// with no memory, until [`Fbi::take_back`]) and copies of the walk's tables.
    fn lend(&mut self) -> LentFbi {
        let fb = FrameBuffer {
            ram: std::mem::take(&mut self.fb.ram),
            layout: self.fb.layout,
            front: self.fb.front,
            back: self.fb.back,
        };
        LentFbi {
            fb,
            fog_table: self.fog_table.clone(),
            profile: self.profile,
            isa: self.isa,
        }
    }

    /// The memory back, and what the render thread's jobs added to the counters.
    fn take_back(&mut self, ram: Vec<u16>, stats: &Stats, path_counts: &PathCounts) {
        self.fb.ram = ram;
        self.stats.add(stats);
        self.path_counts.add(path_counts);
        // Every pixel the twin shaded was behind the writes (packed pixels are counted
        // among the span kernels' already).
        self.path_counts.behind_writes += path_counts.span_kernels
            + path_counts.aliased_layout
            + path_counts.short_rows
            + path_counts.reference;
    }

    /// The render thread's FBI, drawing into `lent` (its registers are never read).
    fn twin(lent: LentFbi) -> Fbi {
        Fbi {
            regs: [0; 256],
            params: TriangleParams::default(),
            fb: lent.fb,
            fog_table: lent.fog_table,
            stats: Stats::default(),
            profile: lent.profile,
            dither: Dither::new(lent.profile.dither_2x2),
            generic_path: false,
            path_counts: PathCounts::default(),
            threads: 1,
            helpers: None,
            isa: lent.isa,
            watch: None,
            pack: None,
            consts: None,
        }
    }

    /// The twin drawing into `lent` again (the dither tables rebuilt only for another
    /// 2x2 matrix).
    fn borrow(&mut self, lent: LentFbi) {
        if lent.profile.dither_2x2 != self.profile.dither_2x2 {
            self.dither = Dither::new(lent.profile.dither_2x2);
        }
        self.fb = lent.fb;
        self.fog_table = lent.fog_table;
        self.profile = lent.profile;
        self.isa = lent.isa;
    }
}

//! Small untextured triangles shaded on a render thread of their own, while the calling
//! thread goes on with the trace, the register writes and the timing model after them.
//!
//! A triangle too small for bands of rows ([`crate::raster`]) is a few hundred cycles of
//! walk and shading after a few hundred of register writes; on one thread they take turns.
//! Here the calling thread keeps the registers and lends the render thread what the walk
//! writes and reads besides them: the frame-buffer memory, the fog table and the profile.
//! Each triangle goes over as a [`TriangleJob`], the drawing state and the parameters
//! captured at its command; the render thread shades the jobs in order on an FBI of its
//! own (its twin, whose registers are never read). [`RenderThread::settle`] takes the
//! memory back, with the counters the jobs added; the board settles before anything that
//! reads or writes the frame buffer, the counters or the tables (an LFB access, a
//! FASTFILL, a swap, a textured or large triangle, a write to the fog table, an init
//! register or `nopCMD`, and every access that is not a write). So every pixel and
//! counter is what drawing each triangle at its command gives (the identity tests replay
//! every trace with 1, 2 and 4 threads).
//!
//! Memory is bounded: jobs go in batches of [`BATCH`] over a channel of [`IN_FLIGHT`]
//! batches, and the calling thread waits while it is full.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::mpsc::{self, Receiver, SyncSender, TryRecvError};
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
use crate::raster::NoTexture;
use crate::stats::Stats;

/// Jobs sent at a time (a channel operation per batch, not per triangle).
const BATCH: usize = 32;

/// Batches the channel holds before the calling thread waits for the render thread.
const IN_FLIGHT: usize = 64;

/// How long the render thread spins for the next batch before it sleeps, while it holds
/// the memory (a sleeping thread's wake-up is a system call on the calling thread).
const SPIN: Duration = Duration::from_micros(200);

/// How long the calling thread spins for the memory to come back before it sleeps.
const SETTLE_SPIN: Duration = Duration::from_micros(500);

/// One triangle to shade: what its command captured.
pub struct TriangleJob {
    st: DrawState,
    params: TriangleParams,
    /// The walk of the board's model ([`draw_job`] for it).
    draw: fn(&mut Fbi, &DrawState),
}

/// What the calling thread lends: the frame buffer with its memory, and the tables the
/// walk reads.
struct Lent {
    fb: FrameBuffer,
    fog_table: FogTable,
    profile: PixelProfile,
    isa: VectorIsa,
}

/// What comes back: the memory and what the jobs added to the counters.
struct Returned {
    ram: Vec<u16>,
    stats: Stats,
    path_counts: PathCounts,
    /// A job panicked (a bug): the memory is as the jobs before it left it.
    panicked: bool,
}

enum Message {
    Lend(Box<Lent>),
    Jobs(Vec<TriangleJob>),
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

/// The render thread and the calling thread's end of its channels.
pub struct RenderThread {
    to: Option<SyncSender<Message>>,
    back: Receiver<Returned>,
    /// Emptied batches coming back to be filled again (no allocation per batch).
    spent: Receiver<Vec<TriangleJob>>,
    batch: Vec<TriangleJob>,
    lent: bool,
    thread: Option<JoinHandle<()>>,
}

impl RenderThread {
    /// A render thread, or `None` where one cannot be started.
    pub fn start() -> Option<Self> {
        let (to, from) = mpsc::sync_channel(IN_FLIGHT);
        let (give, back) = mpsc::sync_channel(1);
        let (spend, spent) = mpsc::sync_channel(IN_FLIGHT + 2);
        let thread = std::thread::Builder::new()
            .name("voodoo-render".into())
            .spawn(move || serve(from, give, spend))
            .ok()?;
        Some(Self {
            to: Some(to),
            back,
            spent,
            batch: Vec::with_capacity(BATCH),
            lent: false,
            thread: Some(thread),
        })
    }

    /// Whether the render thread holds `fbi`'s memory (jobs may be pending).
    #[inline]
    pub fn is_lent(&self) -> bool {
        self.lent
    }

    /// Queue `job`, lending `fbi`'s memory first if the render thread does not hold it.
    /// An error only where the render thread is gone (a bug; see [`RenderThread::settle`]).
    pub fn push(&mut self, fbi: &mut Fbi, job: TriangleJob) -> Result<(), RenderThreadFailed> {
        if !self.lent {
            let lent = Box::new(fbi.lend());
            self.lent = true;
            self.send(Message::Lend(lent))?;
        }
        self.batch.push(job);
        if self.batch.len() == BATCH {
            self.flush()?;
        }
        Ok(())
    }

    /// Wait for every queued job and take the memory and the counters back into `fbi`.
    /// Nothing to do if the render thread does not hold the memory.
    ///
    /// An error (both are bugs): a job panicked, the memory as the jobs before it left
    /// it; or the render thread is gone, and the memory with it.
    pub fn settle(&mut self, fbi: &mut Fbi) -> Result<(), RenderThreadFailed> {
        if !self.lent {
            return Ok(());
        }
        self.flush()?;
        self.send(Message::Settle)?;
        self.lent = false;
        let returned = receive(&self.back, SETTLE_SPIN).ok_or(RenderThreadFailed::Stopped)?;
        fbi.take_back(returned.ram, &returned.stats, &returned.path_counts);
        if returned.panicked {
            return Err(RenderThreadFailed::Panicked);
        }
        Ok(())
    }

    fn flush(&mut self) -> Result<(), RenderThreadFailed> {
        if self.batch.is_empty() {
            return Ok(());
        }
        let next = self
            .spent
            .try_recv()
            .unwrap_or_else(|_| Vec::with_capacity(BATCH));
        let full = std::mem::replace(&mut self.batch, next);
        self.send(Message::Jobs(full))
    }

    fn send(&self, message: Message) -> Result<(), RenderThreadFailed> {
        match self.to.as_ref().map(|to| to.send(message)) {
            Some(Ok(())) => Ok(()),
            _ => Err(RenderThreadFailed::Stopped),
        }
    }
}

impl Drop for RenderThread {
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
fn serve(from: Receiver<Message>, give: SyncSender<Returned>, spend: SyncSender<Vec<TriangleJob>>) {
    let mut twin: Option<Fbi> = None;
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
                match twin.as_mut() {
                    Some(t) => t.borrow(*lent),
                    None => twin = Some(Fbi::twin(*lent)),
                }
                holding = true;
                panicked = false;
            }
            Message::Jobs(mut jobs) => {
                if let (Some(t), false) = (twin.as_mut(), panicked) {
                    let shaded = catch_unwind(AssertUnwindSafe(|| {
                        for job in &jobs {
                            t.params = job.params;
                            (job.draw)(t, &job.st);
                        }
                    }));
                    panicked = shaded.is_err();
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

/// A job's walk: the triangle counted and shaded as [`Fbi::draw_triangle`] does with the
/// span kernels and no texture.
fn draw_job<M: PixelModel>(twin: &mut Fbi, st: &DrawState) {
    twin.stats.triangles += 1;
    twin.walk::<M, NoTexture, true>(st, &mut NoTexture);
}

impl Fbi {
    /// Whether the triangle in the parameter registers may be shaded on the render
    /// thread (the board decides the rest: untextured, and no texel source): span
    /// kernels, no watched pixel, and too small for bands of rows.
    #[inline]
    pub fn deferrable<M: PixelModel>(&self) -> bool {
        M::SPAN_KERNELS
            && !self.generic_path
            && self.watch.is_none()
            && crate::raster::box_pixels(&self.params) < crate::raster::MIN_THREADED_PIXELS as u64
    }

    /// The job of the untextured triangle in the parameter registers (the `triangleCMD`
    /// command, after any subpixel correction), and the pixels and spans its walk will
    /// count ([`Fbi::walk_counts`]); `None`, the triangle counted, where `fbzMode` selects
    /// no colour buffer (nothing to draw, as [`Fbi::draw_triangle`]).
    pub fn triangle_job<M: PixelModel>(&mut self) -> Option<TriangleJob> {
        let Some(dest) = self.colour_buffer(self.fbz_mode().draw_buffer()) else {
            self.stats.triangles += 1;
            return None;
        };
        Some(TriangleJob {
            st: DrawState::capture::<M>(self, dest),
            params: self.params,
            draw: draw_job::<M>,
        })
    }

    /// The frame buffer with its memory (this FBI keeps the layout and buffer indices,
    /// with no memory, until [`Fbi::take_back`]) and copies of the walk's tables.
    fn lend(&mut self) -> Lent {
        let fb = FrameBuffer {
            ram: std::mem::take(&mut self.fb.ram),
            layout: self.fb.layout,
            front: self.fb.front,
            back: self.fb.back,
        };
        Lent {
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
    fn twin(lent: Lent) -> Fbi {
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
    fn borrow(&mut self, lent: Lent) {
        if lent.profile.dither_2x2 != self.profile.dither_2x2 {
            self.dither = Dither::new(lent.profile.dither_2x2);
        }
        self.fb = lent.fb;
        self.fog_table = lent.fog_table;
        self.profile = lent.profile;
        self.isa = lent.isa;
    }
}

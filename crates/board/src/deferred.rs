//! Runs of bus writes whose small triangles are shaded on a render thread
//! ([`pixelfx::deferred`]) while the writes after them go on.
//!
//! [`Board::deferred`] borrows the board for such a run: its writes may leave triangles
//! queued, and everything else on the board waits for them ([`Deferred::board`] and the
//! end of the run settle first), so nothing outside the run can see a frame buffer whose
//! triangles are still being drawn. Inside the writes the board settles before whatever
//! reads or writes what the render thread holds (`crates/board/src/bus.rs`). The render
//! thread holds the TMUs with the memory: their register and texture writes are queued
//! behind the triangles before them ([`tmu_register`], [`tmu_texture`]), but for the S,
//! T, W registers, whose writes go with the next textured triangle ([`LentStw`]). The timing
//! model charges the queued triangles with the counts of the walks that shaded them
//! ([`TimingLog`]). [`Board::deferred`] borrows the board; [`Deferred::new`] owns one
//! (libglide3's, for a whole Glide session).

use std::borrow::BorrowMut;
use std::collections::VecDeque;

use pixelfx::pipeline::DrawState;
use pixelfx::{Fbi, RenderThread, TriangleJob, WalkCounts};
use sst1_chain::Chain;
use texelfx::{StwPending, StwWrite, Tmu};

use crate::model::ChipModel;
use crate::timing::{Timing, TriangleWork};
use crate::Board;

/// A TMU register write, `[chips, offset, value]`: to each TMU the chip mask selects
/// (bit 1 TMU 0, bit 2 TMU 1, bit 3 TMU 2).
// `&mut Vec`: the render thread's chips are the board's `Vec<Tmu>` (`RenderThread<C>`).
#[allow(clippy::ptr_arg)]
pub(crate) fn tmu_register(tmus: &mut Vec<Tmu>, [chips, offset, value]: [u32; 3]) {
    for i in selected_tmus(chips) {
        if let Some(tmu) = tmus.get_mut(i) {
            tmu.write_reg(offset, value);
        }
    }
}

/// The TMUs a register write's chip mask selects (bit 1 TMU 0, bit 2 TMU 1, bit 3 TMU 2),
/// in order, each once.
#[inline(always)]
pub(crate) fn selected_tmus(chips: u32) -> impl Iterator<Item = usize> {
    let mut mask = (chips >> 1) & 7;
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let i = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            i
        })
    })
}

/// A texture-memory write, `[tmu, offset, value]` (`offset` from the texture region's
/// base; the board has checked the TMU exists).
// `&mut Vec`: the render thread's chips are the board's `Vec<Tmu>` (`RenderThread<C>`).
#[allow(clippy::ptr_arg)]
pub(crate) fn tmu_texture(tmus: &mut Vec<Tmu>, [tmu, offset, value]: [u32; 3]) {
    if let Some(t) = tmus.get_mut(tmu as usize) {
        t.write_texture(offset, value);
    }
}

/// A textured triangle's walk on the render thread, as the board draws one: per TMU
/// (`tmu_jobs`, one each), the S, T, W register writes since the triangle before and the
/// subpixel correction (written back to the start registers), then the TMUs'
/// per-triangle state and the walk with the TMU chain as texel source.
// `&mut Vec`: the render thread's chips are the board's `Vec<Tmu>` (`RenderThread<C>`).
#[allow(clippy::ptr_arg)]
pub(crate) fn draw_textured<M: ChipModel>(
    twin: &mut Fbi,
    tmus: &mut Vec<Tmu>,
    st: &DrawState,
    tmu_jobs: &[TmuJob],
) {
    for (t, job) in tmus.iter_mut().zip(tmu_jobs) {
        t.apply_stw(&job.stw);
        if let Some((dx, dy)) = job.adjust {
            t.subpixel_adjust(dx, dy);
        }
        t.begin_triangle::<M>();
    }
    twin.shade_job::<M, _>(st, &mut Chain::<M>::new(tmus));
}

/// What a textured triangle's job carries for one TMU ([`draw_textured`]).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct TmuJob {
    /// The S, T, W register writes since the TMU's last textured triangle.
    stw: StwPending,
    /// The subpixel correction's 12.4 offsets, if the triangle has one.
    adjust: Option<(i32, i32)>,
}

/// The TMUs' S, T, W register writes while the render thread holds the TMUs: noted on
/// the calling thread and sent with the next textured triangle's job
/// ([`draw_textured`]), rather than queued write by write behind the triangles (a write
/// queued there cost the render thread about 55 instructions, and a textured triangle
/// has 9 per TMU; docs/performance.md). Nothing but the triangles reads these
/// registers, so only the triangles need them in order; the board hands the last ones
/// over when it takes the TMUs back ([`Board::settle`]).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct LentStw {
    /// TMU `i`'s writes since its last textured triangle's job.
    pending: [StwPending; 3],
}

impl LentStw {
    /// An S, T, W register write ([`texelfx::StwParams::decode`]) to the TMUs of the chip mask
    /// `chips` (bit 1 TMU 0, bit 2 TMU 1, bit 3 TMU 2).
    #[inline(always)]
    pub(crate) fn write(&mut self, chips: u32, w: StwWrite) {
        for i in selected_tmus(chips) {
            self.pending[i].note(w);
        }
    }

    /// A textured triangle's jobs for the TMUs (the first as many as the board has),
    /// with the subpixel correction `adjust`; the writes so far go with them.
    pub(crate) fn take_jobs(&mut self, adjust: Option<(i32, i32)>) -> [TmuJob; 3] {
        std::array::from_fn(|i| TmuJob {
            stw: self.pending[i].take(),
            adjust,
        })
    }

    /// Hand the writes so far over to `tmus`.
    pub(crate) fn hand_over(&mut self, tmus: &mut [Tmu]) {
        for (t, p) in tmus.iter_mut().zip(&mut self.pending) {
            t.apply_stw(&p.take());
        }
    }
}

/// The timing model's events while the render thread holds the memory: the bus writes
/// and the queued triangles, in order. Each triangle is charged with the counts of the
/// walk that shaded it, as the render thread returns them ([`TimingLog::charge_counted`]), so
/// that no triangle is walked twice; every access that reads the timing model (a read,
/// a swap, a fill, a host wait, a video register) settles first, which charges the
/// rest, so it sees what drawing each triangle at its command gives. It holds the
/// triangles in flight, a few thousand at most (`pixelfx::deferred`'s batches).
#[derive(Default)]
pub(crate) struct TimingLog {
    /// Per queued triangle not yet charged, the writes before it (since the one before)
    /// and its work but for the counts.
    triangles: VecDeque<(u32, TriangleWork)>,
    /// Writes since the last queued triangle.
    writes: u32,
}

impl TimingLog {
    fn triangle(&mut self, work: TriangleWork) {
        self.triangles
            .push_back((std::mem::take(&mut self.writes), work));
    }

    /// Charge the first triangles to `timing`, in order, with the walk counts the
    /// render thread has returned for them so far (one each), each after the writes
    /// before it; with the timing model off (`None`), only take the counts. Gives
    /// `timing` back.
    fn charge_counted<'t>(
        &mut self,
        render: &RenderThread<Vec<Tmu>, TmuJob>,
        mut timing: Option<&'t mut Timing>,
    ) -> Option<&'t mut Timing> {
        while let Some(counts) = render.counted() {
            if let Some(timing) = timing.as_deref_mut() {
                self.charge(timing, &counts);
            }
        }
        timing
    }

    fn charge(&mut self, timing: &mut Timing, counts: &[WalkCounts]) {
        debug_assert!(counts.len() <= self.triangles.len());
        for (c, (writes, work)) in counts.iter().zip(self.triangles.drain(..counts.len())) {
            timing.writes(writes);
            timing.triangle(TriangleWork {
                pixels: c.pixels,
                spans: c.spans,
                ..work
            });
        }
    }

    /// Charge the writes after the last triangle (every triangle charged).
    fn charge_writes(&mut self, timing: &mut Timing) {
        debug_assert!(self.triangles.is_empty());
        timing.writes(std::mem::take(&mut self.writes));
    }
}

/// A run of bus writes on a board (see the module documentation), which it borrows
/// (`B` = `&mut Board`, [`Board::deferred`]) or owns (`B` = [`Board`],
/// [`Deferred::new`]: a Glide library's board, written one call at a time for a whole
/// session). Dropping it waits for every queued triangle.
///
/// It is a [`RegisterBus`]: its writes may leave triangles queued; its reads settle
/// first, as the board's do.
///
/// [`RegisterBus`]: sst1_regs::RegisterBus
pub struct Deferred<B: BorrowMut<Board>> {
    board: B,
}

impl Board {
    /// A run of writes whose small triangles may be shaded on a render thread (with more
    /// than one render thread, [`Board::set_threads`]; with one, the writes are
    /// [`RegisterBus::write32`]s). Pixels, counters and timing are those of the same
    /// writes one by one.
    ///
    /// [`RegisterBus::write32`]: sst1_regs::RegisterBus::write32
    pub fn deferred(&mut self) -> Deferred<&mut Board> {
        Deferred { board: self }
    }

    /// Whether the render thread holds the frame-buffer memory.
    #[inline(always)]
    pub(crate) fn render_lent(&self) -> bool {
        self.render.as_ref().is_some_and(|r| r.is_lent())
    }

    /// Wait for every queued triangle and take the memory and the TMUs back.
    ///
    /// # Panics
    /// If the render thread failed (a bug: a triangle's walk panicked there), as the walk
    /// would have on this thread; never while this thread is already panicking.
    pub(crate) fn settle(&mut self) {
        let Some(render) = self.render.as_mut() else {
            return;
        };
        if !render.is_lent() {
            return;
        }
        if let Err(e) = render.settle(&mut self.fbi, &mut self.tmus) {
            self.render_failed(e);
            return;
        }
        self.lent_stw.hand_over(&mut self.tmus);
        // Every batch's counts are there once the memory is back.
        let timing = self.timing_on.then_some(&mut self.timing);
        if let Some(timing) = self.timing_log.charge_counted(render, timing) {
            self.timing_log.charge_writes(timing);
        }
    }

    /// Queue a triangle for the render thread ([`Board::start_render`] said it runs),
    /// lending it the memory and the TMUs if it does not hold them, with the TMUs' jobs
    /// if it is `textured` (their S, T, W register writes since the last, and the
    /// subpixel correction `tex_adjust`); the timing model charges `work` with the walk's
    /// counts when the memory comes back.
    // Inlined into its one caller (measured: out of line, 30 instructions more per
    // 10-pixel triangle on the calling thread).
    #[inline(always)]
    pub(crate) fn defer_triangle(
        &mut self,
        job: TriangleJob<Vec<Tmu>, TmuJob>,
        textured: bool,
        tex_adjust: Option<(i32, i32)>,
        work: TriangleWork,
    ) {
        let Some(render) = self.render.as_mut() else {
            return;
        };
        let pushed = if textured {
            let tmu_jobs = self.lent_stw.take_jobs(tex_adjust);
            let tmus = (self.config.tmus as usize).min(tmu_jobs.len());
            render.push(&mut self.fbi, &mut self.tmus, job, &tmu_jobs[..tmus])
        } else {
            render.push(&mut self.fbi, &mut self.tmus, job, &[])
        };
        let sent = match pushed {
            Ok(sent) => sent,
            Err(e) => return self.render_failed(e),
        };
        if self.timing_on {
            self.timing_log.triangle(work);
        }
        if sent {
            // The triangles shaded so far are charged as the writes go on, so that the
            // log (and the counts' channel) holds only what is in flight.
            let timing = self.timing_on.then_some(&mut self.timing);
            self.timing_log.charge_counted(render, timing);
        }
    }

    /// A bus write in the timing model: now, or after the triangles queued before it.
    #[inline(always)]
    pub(crate) fn time_write(&mut self) {
        if self.render_lent() {
            self.timing_log.writes += 1;
        } else {
            self.timing.write();
        }
    }

    /// `n` bus writes in a row in the timing model, as `n` [`Board::time_write`]s.
    #[inline]
    pub(crate) fn time_writes(&mut self, n: u32) {
        if self.render_lent() {
            self.timing_log.writes += n;
        } else {
            self.timing.writes(n);
        }
    }

    /// Queue a write to the TMUs the render thread holds, behind the triangles before it.
    pub(crate) fn lent_tmus(&mut self, apply: fn(&mut Vec<Tmu>, [u32; 3]), args: [u32; 3]) {
        let Some(render) = self.render.as_mut() else {
            return;
        };
        if let Err(e) = render.push_chips(apply, args) {
            self.render_failed(e);
        }
    }

    /// The render thread failed (a bug): it is dropped, and the failure panics this
    /// thread as the walk would have, unless it is already panicking.
    #[cold]
    fn render_failed(&mut self, e: pixelfx::RenderThreadFailed) {
        self.render = None;
        self.timing_log = TimingLog::default();
        self.lent_stw = LentStw::default();
        if !std::thread::panicking() {
            panic!("{e}");
        }
    }

    /// Whether the render thread runs, started if need be (the caller has checked that
    /// this is a [`Deferred`] run with more than one render thread); `false` where none
    /// can start.
    #[inline]
    pub(crate) fn start_render(&mut self) -> bool {
        if self.render.is_none() {
            self.render = pixelfx::RenderThread::start();
            if self.render.is_none() {
                // None can start: stop asking for the rest of the run.
                self.deferring = false;
            }
        }
        self.render.is_some()
    }
}

impl Deferred<Board> {
    /// A board that keeps its small triangles behind the writes for as long as it is
    /// held: as [`Board::deferred`], owned.
    pub fn new(board: Board) -> Self {
        Self { board }
    }
}

impl<B: BorrowMut<Board>> Deferred<B> {
    /// A bus write ([`RegisterBus::write32`](sst1_regs::RegisterBus::write32)).
    pub fn write32(&mut self, bus_addr: u32, value: u32) {
        let board = self.board.borrow_mut();
        board.deferring = true;
        sst1_regs::RegisterBus::write32(board, bus_addr, value);
        board.deferring = false;
    }

    /// The bus writes `writes` in order ([`Board::write32_all`]).
    pub fn write32_all(&mut self, writes: &[(u32, u32)]) {
        let board = self.board.borrow_mut();
        board.deferring = true;
        board.write32_all(writes);
        board.deferring = false;
    }

    /// The board, every queued triangle drawn.
    pub fn board(&mut self) -> &mut Board {
        let board = self.board.borrow_mut();
        board.settle();
        board
    }
}

impl<B: BorrowMut<Board>> sst1_regs::RegisterBus for Deferred<B> {
    fn write32(&mut self, bus_addr: u32, value: u32) {
        Deferred::write32(self, bus_addr, value);
    }

    fn read32(&mut self, bus_addr: u32) -> u32 {
        // The board's reads settle first.
        self.board.borrow_mut().read32(bus_addr)
    }

    fn pci_write(&mut self, offset: u32, value: u32) {
        self.board().pci_write(offset, value);
    }

    fn host_wait(&mut self, cycles: u64) {
        // The board settles first: the timing model charges what is queued.
        self.board.borrow_mut().host_wait(cycles);
    }
}

impl<B: BorrowMut<Board>> Drop for Deferred<B> {
    fn drop(&mut self) {
        let board = self.board.borrow_mut();
        board.deferring = false;
        board.settle();
    }
}

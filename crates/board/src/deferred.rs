//! Runs of bus writes whose small untextured triangles are shaded on a render thread
//! ([`pixelfx::deferred`]) while the writes after them go on.
//!
//! [`Board::deferred`] borrows the board for such a run: its writes may leave triangles
//! queued, and everything else on the board waits for them ([`Deferred::board`] and the
//! end of the run settle first), so nothing outside the run can see a frame buffer whose
//! triangles are still being drawn. Inside the writes the board settles before whatever
//! reads or writes what the render thread holds (`crates/board/src/bus.rs`).

use crate::Board;

/// A run of bus writes on a board (see the module documentation). Dropping it waits for
/// every queued triangle.
pub struct Deferred<'b> {
    board: &'b mut Board,
}

impl Board {
    /// A run of writes whose small untextured triangles may be shaded on a render thread
    /// (with more than one render thread, [`Board::set_threads`]; with one, the writes
    /// are [`RegisterBus::write32`]s). Pixels, counters and timing are those of the same
    /// writes one by one.
    ///
    /// [`RegisterBus::write32`]: sst1_regs::RegisterBus::write32
    pub fn deferred(&mut self) -> Deferred<'_> {
        Deferred { board: self }
    }

    /// Whether the render thread holds the frame-buffer memory.
    #[inline(always)]
    pub(crate) fn render_lent(&self) -> bool {
        self.render.as_ref().is_some_and(|r| r.is_lent())
    }

    /// Wait for every queued triangle and take the memory back.
    ///
    /// # Panics
    /// If the render thread failed (a bug: a triangle's walk panicked there), as the walk
    /// would have on this thread; never while this thread is already panicking.
    pub(crate) fn settle(&mut self) {
        let Some(render) = self.render.as_mut() else {
            return;
        };
        if let Err(e) = render.settle(&mut self.fbi) {
            self.render = None;
            if !std::thread::panicking() {
                panic!("{e}");
            }
        }
    }

    /// Whether a triangle may be queued for the render thread, which is started if need
    /// be: not outside a [`Deferred`] run, with one render thread, or where none can start.
    #[inline]
    pub(crate) fn defer(&mut self) -> bool {
        if !self.deferring || self.fbi.threads() < 2 {
            return false;
        }
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

impl Deferred<'_> {
    /// A bus write ([`RegisterBus::write32`](sst1_regs::RegisterBus::write32)).
    pub fn write32(&mut self, bus_addr: u32, value: u32) {
        self.board.deferring = true;
        sst1_regs::RegisterBus::write32(self.board, bus_addr, value);
        self.board.deferring = false;
    }

    /// The bus writes `writes` in order ([`Board::write32_all`]).
    pub fn write32_all(&mut self, writes: &[(u32, u32)]) {
        self.board.deferring = true;
        self.board.write32_all(writes);
        self.board.deferring = false;
    }

    /// The board, every queued triangle drawn.
    pub fn board(&mut self) -> &mut Board {
        self.board.settle();
        self.board
    }
}

impl Drop for Deferred<'_> {
    fn drop(&mut self) {
        self.board.deferring = false;
        self.board.settle();
    }
}

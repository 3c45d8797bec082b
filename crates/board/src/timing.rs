//! How long the real board would have taken: a count of graphics-clock cycles per
//! command, calibrated to the spec's performance table (spec section 2).
//!
//! The host's writes reach the chip through the PCI bus and its 64-entry FIFO; the
//! graphics engine drains the FIFO and runs each command. The two overlap, so a command
//! costs the longer of the two: the bus time of the writes that fed it, and the engine
//! time of the command itself.
//!
//! * **Bus:** every 32-bit write takes [`PCI_CLOCKS_PER_WRITE`] graphics clocks. The
//!   spec's numbers assume "the PCI Bus master is supplying data at its peak bandwidth":
//!   one write per 33 MHz PCI clock (zero-wait-state writes, spec 3), 1.5 clocks of the
//!   50 MHz graphics clock. This is what limits small triangles: a flat 10-pixel
//!   triangle is 15 writes (22.5 clocks; the spec's 1911 Ktriangles/s is 26 clocks), a
//!   textured one over 30.
//! * **Triangle engine:** setup ([`SETUP_CLOCKS`], [`SETUP_SUBPIXEL_CLOCKS`]: "7 clocks to
//!   16 clocks" with subpixel correction, spec 5.16's `fbzColorPath` bit 26 note; at
//!   least [`TEXTURE_SETUP_CLOCKS`] for a textured triangle) overlaps the rasterisation
//!   of the triangle before ("the triangle setup engine is separately pipelined from the
//!   triangle rasterization engine", the same note), so a triangle costs the longer of
//!   its setup and its rasterisation: [`RASTER_CLOCKS`] to start, [`SPAN_CLOCKS`] per
//!   scanline span and, per pixel, [`PIXEL_CLOCKS`] plus [`RMW_PIXEL_CLOCKS`] when the
//!   pixel reads the frame buffer back (depth test or alpha blending: a read-modify-write
//!   of the 64-bit interleaved memory).
//! * **FASTFILL:** two pixels per clock (spec 3: "for screen/depth-buffer clears, two
//!   pixels are written per clock") plus [`FILL_ROW_CLOCKS`] per row, fitted to the spec's
//!   3.45 ms for a 640x480 clear.
//!
//! * **Video:** the vertical retrace, which synchronised swaps wait for and `status` bit 6
//!   reads, follows the frame of the video registers and the DAC's pixel clock
//!   ([`Frame`], spec 10).
//! * **Memory FIFO:** with `fbiInit0` bit 13, frame-buffer rows queue writes behind the
//!   PCI FIFO ([`MemoryFifo`], spec 5.42, 5.46); `status` bits 27:12 read its free space.
//! * **Host time:** a trace's `wait` ops move the host's clock on between accesses.
//!
//! The constants are in 1/16 clock so that the fits need no floating point; the count is
//! exact and the same on every run (it depends only on the trace, never on the host).
//! `firmware-tests/tests/timing.rs` builds the spec's scenes and checks every row of its
//! table; docs/timing.md shows the table.

use std::collections::VecDeque;

use serde::{Deserialize, Serialize};

use crate::video::{Dac, VideoRegs};

/// Graphics clock of the boards the spec's table assumes.
pub const DEFAULT_CLOCK_HZ: u64 = 50_000_000;

/// The cycle constants' unit: 1/16 graphics clock.
const SUB: u64 = 16;

/// Bus time of one 32-bit write (1.5 clocks: 50 MHz over 33.3 MHz).
pub const PCI_CLOCKS_PER_WRITE: u64 = 24;
/// Triangle setup without subpixel correction (7 clocks).
pub const SETUP_CLOCKS: u64 = 7 * SUB;
/// Triangle setup with subpixel correction (16 clocks).
pub const SETUP_SUBPIXEL_CLOCKS: u64 = 16 * SUB;
/// Setup of a textured triangle (the TMU's S, T, W and LOD set-up): fitted to the spec's
/// textured rows, whose 10- and 25-pixel rates are the same (828 and 823 Ktriangles/s,
/// about 60 clocks a triangle, more than their bus time).
pub const TEXTURE_SETUP_CLOCKS: u64 = 58 * SUB;
/// Start of a triangle's rasterisation (the raster pipeline filling), fitted.
pub const RASTER_CLOCKS: u64 = 184;
/// Per scanline span: the edge walk's step to the next row, fitted.
pub const SPAN_CLOCKS: u64 = 6;
/// Per pixel: one pixel per clock (spec 3), plus the memory's page misses (fitted to
/// the 1000-pixel rows).
pub const PIXEL_CLOCKS: u64 = 19;
/// Per pixel that reads the destination (depth test or alpha blending), fitted.
pub const RMW_PIXEL_CLOCKS: u64 = 3;
/// Per FASTFILL row, on top of two pixels per clock.
pub const FILL_ROW_CLOCKS: u64 = 630;
/// Host time of one register or LFB read: a PCI read's round trip, taken as 3 PCI
/// clocks (4.5 graphics clocks; UNVERIFIED: the spec gives no read latency).
pub const PCI_CLOCKS_PER_READ: u64 = 72;
/// Entries of the PCI FIFO (spec 3: "an asynchronous FIFO 64 entries deep").
pub const PCI_FIFO_ENTRIES: usize = 64;
pub use crate::video::{Frame, REFRESH_HZ};
/// The count's clock (and the host time it charges) stops here (1/16 clock; 2^58 clocks,
/// 183 years at 50 MHz): however long the waits a trace asks for, no count overflows.
pub const HOST_CLOCK_MAX: u64 = 1 << 62;
/// The longest wait the host's view plays out in full (1/16 clock; 2^55 clocks, 22
/// years at 50 MHz). A longer one is shortened by whole frames, which keeps the
/// retrace's phase and is long enough for every pending command to be done.
const WAIT_MAX: u64 = 1 << 59;
/// When the host's clock passes this (1/16 clock), every time the view holds is moved
/// back by whole frames, so the clock never overflows however many waits a trace has.
const REBASE_AT: u64 = 1 << 60;
/// Frames of the host's past that a rebase keeps: more than the longest swap interval
/// (255) looks back.
const REBASE_KEEP_FRAMES: u64 = 257;

/// Where one frame's (or the whole replay's) modelled time went, in graphics clocks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct FrameTime {
    /// Total cycles.
    pub cycles: u64,
    /// Cycles of triangle commands.
    pub triangles: u64,
    /// Cycles of FASTFILL commands.
    pub fills: u64,
    /// Cycles where the bus, not the engine, was the limit (included in the above).
    pub bus_bound: u64,
    /// Cycles of the SWAPBUFFER command: waiting for vertical retrace.
    pub retrace_wait: u64,
    /// Cycles where the host's own time (a trace's `wait` lines), not the engine, was
    /// the limit (included in the above, not in `bus_bound`).
    pub host_wait: u64,
}

impl FrameTime {
    fn add(&mut self, o: &FrameTime) {
        self.cycles = self.cycles.saturating_add(o.cycles);
        self.triangles = self.triangles.saturating_add(o.triangles);
        self.fills = self.fills.saturating_add(o.fills);
        self.bus_bound = self.bus_bound.saturating_add(o.bus_bound);
        self.retrace_wait = self.retrace_wait.saturating_add(o.retrace_wait);
        self.host_wait = self.host_wait.saturating_add(o.host_wait);
    }
}

/// The most frames [`Timing`] keeps one by one; later frames still count in the totals.
pub const MAX_FRAMES: usize = 100_000;

/// The board's modelled time.
#[derive(Clone, Debug, Serialize)]
pub struct Timing {
    /// Graphics clock in Hz.
    pub clock_hz: u64,
    /// The whole replay so far.
    pub total: FrameTime,
    /// One entry per SWAPBUFFER, the first [`MAX_FRAMES`] of them.
    pub frames: Vec<FrameTime>,
    /// The frame being drawn (since the last swap).
    #[serde(skip)]
    pub(crate) current: FrameTime,
    /// Bus time (1/16 clock) of the writes since the last command.
    #[serde(skip)]
    pub(crate) pending_bus: u64,
    /// Host time (1/16 clock, trace `wait` lines) since the last command.
    #[serde(skip)]
    pub(crate) pending_wait: u64,
    /// Sub-clock remainder carried between commands (1/16 clock).
    #[serde(skip)]
    pub(crate) fraction: u64,
    /// The board's clock (1/16 clock) at the last synchronised swap.
    #[serde(skip)]
    pub(crate) last_swap: u64,
    /// What the host sees: the status register from the same costs, played out in time.
    #[serde(skip)]
    pub(crate) host: HostView,
    /// The video frame the retrace follows (from the video registers and the DAC).
    #[serde(skip)]
    pub(crate) frame: Frame,
}

/// The board as the host's bus accesses see it in time (1/16 clock since power-on, moved
/// back by whole frames when it grows large): when each queued write is taken by the
/// engine, and when the engine is done. It answers the status register (spec 5.1), so the
/// same trace reads the same values on every run. A write waits while the PCI FIFO is
/// full (with the memory FIFO on: while both are).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub(crate) struct HostView {
    /// The host's time: every access moves it on.
    pub(crate) now: u64,
    /// When the engine has finished every command taken so far.
    pub(crate) engine_free: u64,
    /// When the TMUs have finished (the last textured triangle).
    pub(crate) tmu_free: u64,
    /// When each write still queued is taken, oldest first: at most 64 in the PCI FIFO,
    /// and as many as the memory FIFO holds in front of them.
    pub(crate) fifo: TakeTimes,
    /// How many of the oldest queued writes are in the memory FIFO.
    pub(crate) in_memory: usize,
    /// The memory FIFO's size and low water mark (size 0: disabled).
    pub(crate) memory_fifo: MemoryFifo,
    /// When each swap still pending happens (at most one per queued write).
    pub(crate) swaps: VecDeque<u64>,
    /// When the last write was taken.
    pub(crate) last_taken: u64,
    /// When the last synchronised swap happened.
    pub(crate) last_swap: u64,
}

/// The times at which queued writes are taken, oldest first, held as runs of equal
/// times: behind a busy engine every write queued is taken at the same time (when the
/// command before it ends), so a FIFO of 64 writes is mostly one run, and queueing or
/// draining a write is a counter step rather than a queue operation. A save state holds
/// the times one per write, as a plain list.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(from = "Vec<u64>", into = "Vec<u64>")]
pub(crate) struct TakeTimes {
    /// `(time, writes)`, oldest first; no run is empty and no two neighbours share a
    /// time, so equal queues have equal runs.
    runs: VecDeque<(u64, usize)>,
    /// Writes in all the runs.
    len: usize,
}

impl TakeTimes {
    /// Writes queued.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// Whether no write is queued.
    #[inline]
    pub(crate) fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// When the oldest queued write is taken.
    #[inline]
    pub(crate) fn oldest(&self) -> Option<u64> {
        self.runs.front().map(|&(time, _)| time)
    }

    /// When the newest queued write is taken.
    #[inline]
    pub(crate) fn newest(&self) -> Option<u64> {
        self.runs.back().map(|&(time, _)| time)
    }

    /// Queues a write taken at `time`.
    #[inline]
    fn push_back(&mut self, time: u64) {
        match self.runs.back_mut() {
            Some((t, n)) if *t == time => *n += 1,
            _ => self.runs.push_back((time, 1)),
        }
        self.len += 1;
    }

    /// Queues `n` more writes taken at the newest time (a queue that is not empty).
    #[inline]
    fn extend_newest(&mut self, n: usize) {
        if let Some((_, count)) = self.runs.back_mut() {
            *count += n;
            self.len += n;
        }
    }

    /// Dequeues the oldest write and returns its time.
    #[inline]
    fn pop_front(&mut self) -> Option<u64> {
        let (time, n) = self.runs.front_mut()?;
        let time = *time;
        *n -= 1;
        if *n == 0 {
            self.runs.pop_front();
        }
        self.len -= 1;
        Some(time)
    }

    /// Dequeues every write taken by `now` (from the oldest, up to the first taken
    /// later) and returns how many.
    #[inline]
    fn pop_taken(&mut self, now: u64) -> usize {
        let mut taken = 0;
        while let Some(&(time, n)) = self.runs.front() {
            if time > now {
                break;
            }
            self.runs.pop_front();
            taken += n;
        }
        self.len -= taken;
        taken
    }

    /// Empties the queue.
    #[inline]
    fn clear(&mut self) {
        self.runs.clear();
        self.len = 0;
    }

    /// Moves every time back by `shift` (saturating at 0), merging runs that meet.
    fn shift_back(&mut self, shift: u64) {
        let times: Vec<u64> = std::mem::take(self).into();
        *self = times.into_iter().map(|t| t.saturating_sub(shift)).collect();
    }

    /// The distinct times queued, oldest first.
    pub(crate) fn times(&self) -> impl Iterator<Item = u64> + '_ {
        self.runs.iter().map(|&(time, _)| time)
    }
}

impl FromIterator<u64> for TakeTimes {
    fn from_iter<I: IntoIterator<Item = u64>>(times: I) -> Self {
        let mut queue = TakeTimes::default();
        for time in times {
            queue.push_back(time);
        }
        queue
    }
}

impl From<Vec<u64>> for TakeTimes {
    fn from(times: Vec<u64>) -> Self {
        times.into_iter().collect()
    }
}

impl From<TakeTimes> for Vec<u64> {
    fn from(queue: TakeTimes) -> Self {
        queue
            .runs
            .into_iter()
            .flat_map(|(time, n)| std::iter::repeat_n(time, n))
            .collect()
    }
}

/// The memory FIFO (spec 3, 5.42, 5.46): off-screen frame-buffer rows that queue the
/// host's writes behind the PCI FIFO.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct MemoryFifo {
    /// Entries it holds; 0 when disabled.
    pub entries: usize,
    /// `fbiInit4` bits 7:2: the PCI FIFO's contents go to memory once its free space
    /// falls to this.
    pub low_water_mark: usize,
}

/// Bytes of one frame-buffer row (a DRAM page) of the memory FIFO.
const MEMORY_FIFO_ROW_BYTES: usize = 4096;
/// Bytes of one memory FIFO entry: an address and its data. UNVERIFIED (the spec gives
/// no entry size; MAME stores the two words).
const MEMORY_FIFO_ENTRY_BYTES: usize = 8;
/// The most entries a memory FIFO holds (spec 3: "up to 65536 host writes").
pub const MEMORY_FIFO_MAX_ENTRIES: usize = 65_536;

impl MemoryFifo {
    /// The memory FIFO `fbiInit0` and `fbiInit4` set up on a board with `fbi_mb` MiB of
    /// frame buffer: enabled by `fbiInit0` bit 13 (spec 5.42), rows `fbiInit4` bits 17:8
    /// to 27:18 (the row start and the row at which its counters roll over, spec 5.46;
    /// the last clamped to the memory), at most [`MEMORY_FIFO_MAX_ENTRIES`].
    pub fn from_registers(fbi_init0: u32, fbi_init4: u32, fbi_mb: u32) -> Self {
        let init0 = sst1_regs::FbiInit0(fbi_init0);
        let init4 = sst1_regs::FbiInit4(fbi_init4);
        let rows = (fbi_mb as usize) << 20 >> 12;
        let start = init4.memory_fifo_row_start() as usize;
        let last = (init4.memory_fifo_row_rollover() as usize).min(rows.saturating_sub(1));
        let entries = if init0.memory_fifo_enable() && start <= last {
            ((last + 1 - start) * MEMORY_FIFO_ROW_BYTES / MEMORY_FIFO_ENTRY_BYTES)
                .min(MEMORY_FIFO_MAX_ENTRIES)
        } else {
            0
        };
        Self {
            entries,
            low_water_mark: init4.memory_fifo_low_water_mark() as usize,
        }
    }
}

impl HostView {
    /// Drops what the engine has taken by now (the oldest first: those in memory).
    #[inline]
    fn settle(&mut self) {
        let taken = self.fifo.pop_taken(self.now);
        self.in_memory = self.in_memory.saturating_sub(taken);
        while self.swaps.front().is_some_and(|&t| t <= self.now) {
            self.swaps.pop_front();
        }
    }

    /// Writes in the PCI FIFO.
    #[inline]
    fn in_pci(&self) -> usize {
        self.fifo.len() - self.in_memory
    }

    /// With the memory FIFO on, the PCI FIFO's contents go to memory (as many as fit)
    /// once its free space has fallen to the low water mark (spec 5.46: "dump PCI fifo
    /// contents to memory if PCI fifo freespace falls below this level"; at it, as MAME
    /// does, so that a mark of 0 dumps a full FIFO).
    #[inline]
    fn spill(&mut self) {
        let m = self.memory_fifo;
        if m.entries > 0
            && PCI_FIFO_ENTRIES - self.in_pci().min(PCI_FIFO_ENTRIES) <= m.low_water_mark
        {
            self.in_memory += self.in_pci().min(m.entries.saturating_sub(self.in_memory));
        }
    }

    /// A write: it crosses the bus (waiting for room in the PCI FIFO, which the memory
    /// FIFO makes behind it) and is taken when the engine has finished what came before.
    #[inline]
    fn write(&mut self) {
        self.now += PCI_CLOCKS_PER_WRITE;
        if self.engine_free <= self.now {
            // The engine is idle. Every write queued was taken by `engine_free` (the
            // times taken never decrease), and so was every swap: the queues are empty,
            // and this write is taken at once. (What the general path below does, in a
            // few instructions: everything that looks at the queues drops what has been
            // taken first.)
            self.taken_at_once();
            return;
        }
        if self.joins_newest() {
            self.fifo.push_back(self.engine_free);
            self.last_taken = self.engine_free;
            return;
        }
        self.write_queued();
    }

    /// The queues emptied and the write just made taken now (the engine idle).
    #[inline]
    fn taken_at_once(&mut self) {
        self.fifo.clear();
        self.swaps.clear();
        self.in_memory = 0;
        self.last_taken = self.now;
    }

    /// `n` writes in a row, as `n` [`HostView::write`]s: one at a time while the engine
    /// is busy, and those from the first that finds it idle on in one step (the engine
    /// stays idle: writes do not move `engine_free`).
    fn writes(&mut self, n: u32) {
        let mut left = u64::from(n);
        while left > 0 && self.engine_free > self.now + PCI_CLOCKS_PER_WRITE {
            let joining = self.joining(left);
            if joining > 0 {
                // What `write` does for each of them: count it into the newest run.
                self.now += joining * PCI_CLOCKS_PER_WRITE;
                self.fifo.extend_newest(joining as usize);
                self.last_taken = self.engine_free;
                left -= joining;
            } else {
                self.write();
                left -= 1;
            }
        }
        if left > 0 {
            self.now += left * PCI_CLOCKS_PER_WRITE;
            self.taken_at_once();
        }
    }

    /// How many of the next `left` writes, one after the other, each find the engine busy
    /// and only join the newest queued writes ([`HostView::joins_newest`] after its
    /// clock step). Each condition fails from some write on: the clock reaching the
    /// engine's end or the oldest write's take time, the PCI FIFO or the memory FIFO's
    /// low water mark filling.
    fn joining(&self, left: u64) -> u64 {
        if self.fifo.newest() != Some(self.engine_free) || !self.swaps.is_empty() {
            return 0;
        }
        let Some(oldest) = self.fifo.oldest() else {
            return 0;
        };
        // Write i (from 1) is at now + i * PCI_CLOCKS_PER_WRITE, which must stay below both.
        let until = self.engine_free.min(oldest);
        let by_clock = until.saturating_sub(self.now + 1) / PCI_CLOCKS_PER_WRITE;
        // Write i leaves 64 - (in_pci + i) free entries: more than 0, and more than the
        // low water mark with the memory FIFO on.
        let floor = if self.memory_fifo.entries == 0 {
            0
        } else {
            self.memory_fifo.low_water_mark
        };
        let by_room = PCI_FIFO_ENTRIES.saturating_sub(self.in_pci() + floor + 1) as u64;
        left.min(by_clock).min(by_room)
    }

    /// Whether a write now, with the engine busy, only joins the newest queued writes,
    /// all taken when the engine is free: nothing queued has been taken by now, no swap
    /// is pending, and the write leaves the PCI FIFO with room and above the memory
    /// FIFO's low water mark. Then the general path ([`HostView::write_queued`]) finds
    /// nothing to settle, spill or wait for, and only counts the write in.
    #[inline]
    fn joins_newest(&self) -> bool {
        let free_after = PCI_FIFO_ENTRIES.saturating_sub(self.in_pci() + 1);
        self.fifo.newest() == Some(self.engine_free)
            && self.fifo.oldest().is_some_and(|t| t > self.now)
            && self.swaps.is_empty()
            && free_after > 0
            && (self.memory_fifo.entries == 0 || free_after > self.memory_fifo.low_water_mark)
    }

    /// [`HostView::write`] without its shortcuts (for the test that they change
    /// nothing).
    #[cfg(test)]
    fn write_general(&mut self) {
        self.now += PCI_CLOCKS_PER_WRITE;
        self.write_queued();
    }

    /// [`HostView::write`] while the engine is busy.
    #[inline(never)]
    fn write_queued(&mut self) {
        self.settle();
        self.spill();
        while self.in_pci() >= PCI_FIFO_ENTRIES {
            // Full: wait for the oldest write to be taken.
            match self.fifo.pop_front() {
                Some(t) => self.now = self.now.max(t),
                None => break,
            }
            self.in_memory = self.in_memory.saturating_sub(1);
            self.settle();
            self.spill();
        }
        let taken = self.now.max(self.engine_free);
        self.fifo.push_back(taken);
        self.last_taken = taken;
        self.spill();
    }

    /// The memory FIFO is set up anew: what it held stays queued, in memory as far as
    /// it fits.
    fn set_memory_fifo(&mut self, m: MemoryFifo) {
        self.memory_fifo = m;
        self.in_memory = self.in_memory.min(m.entries);
    }

    /// Host time passes without a bus access: `cycles` graphics clocks; the engine
    /// drains the FIFO meanwhile. `period` is the frame's (1/16 clock): a wait longer
    /// than [`WAIT_MAX`] is shortened by whole frames, and the clock is moved back by
    /// whole frames past [`REBASE_AT`], so nothing overflows and the retrace keeps its
    /// phase.
    fn wait(&mut self, cycles: u64, period: u64) {
        let period = period.max(1);
        let sub = u128::from(cycles) * u128::from(SUB);
        let max = u128::from(WAIT_MAX);
        let sub = if sub > max {
            max + (sub - max) % u128::from(period)
        } else {
            sub
        };
        // At most WAIT_MAX + period, below 2^60.
        self.now += sub as u64;
        if self.now > REBASE_AT {
            let keep = REBASE_KEEP_FRAMES.saturating_mul(period).min(REBASE_AT / 2);
            let shift = (self.now - keep) / period * period;
            let back = |t: &mut u64| *t = t.saturating_sub(shift);
            back(&mut self.now);
            back(&mut self.engine_free);
            back(&mut self.tmu_free);
            back(&mut self.last_taken);
            back(&mut self.last_swap);
            self.fifo.shift_back(shift);
            self.swaps.iter_mut().for_each(back);
        }
    }

    /// The command in the last write keeps the engine busy `engine` (1/16 clock).
    fn command(&mut self, engine: u64, textured: bool) {
        self.engine_free = self.last_taken + engine;
        if textured {
            self.tmu_free = self.engine_free;
        }
    }
}

impl Default for Timing {
    fn default() -> Self {
        Self {
            clock_hz: DEFAULT_CLOCK_HZ,
            total: FrameTime::default(),
            frames: Vec::new(),
            current: FrameTime::default(),
            pending_bus: 0,
            pending_wait: 0,
            fraction: 0,
            last_swap: 0,
            host: HostView::default(),
            frame: Frame::power_on(DEFAULT_CLOCK_HZ),
        }
    }
}

/// What a triangle command did, for its cost.
#[derive(Clone, Copy, Debug, Default)]
pub struct TriangleWork {
    /// Pixels the walker visited.
    pub pixels: u64,
    /// Scanline spans it visited.
    pub spans: u64,
    /// Subpixel correction on.
    pub subpixel: bool,
    /// Texturing on.
    pub textured: bool,
    /// Depth test or alpha blending: every pixel reads the destination.
    pub read_modify_write: bool,
}

impl Timing {
    /// A 32-bit write crossed the bus.
    #[inline]
    pub(crate) fn write(&mut self) {
        self.pending_bus += PCI_CLOCKS_PER_WRITE;
        self.host.write();
    }

    /// `n` 32-bit writes crossed the bus, one after the other: as `n` [`Timing::write`]s.
    pub(crate) fn writes(&mut self, n: u32) {
        self.pending_bus += u64::from(n) * PCI_CLOCKS_PER_WRITE;
        self.host.writes(n);
    }

    /// A read crossed the bus.
    #[inline]
    pub(crate) fn read(&mut self) {
        self.host.now += PCI_CLOCKS_PER_READ;
    }

    /// Host time passes between bus accesses: `cycles` graphics clocks (a trace's
    /// `wait` line). The host's clock moves on, so the engine drains what the FIFO holds
    /// meanwhile and a `status` read after it sees that; the count charges it as feed
    /// time of the next command (a command costs the longer of its bus and host time
    /// and its engine time). Saturating: a wait of any length costs constant time.
    pub(crate) fn host_wait(&mut self, cycles: u64) {
        self.host.wait(cycles, self.frame.period);
        let sub = cycles.saturating_mul(SUB).min(HOST_CLOCK_MAX);
        self.pending_wait = self.pending_wait.saturating_add(sub).min(HOST_CLOCK_MAX);
    }

    /// The `status` register (spec 5.1) at the host's present time: `fbi_bits` is the
    /// FBI's own value, whose retrace and displayed-buffer bits are kept; PCI FIFO free
    /// space (bits 5:0), FBI, TREX and SST-1 busy (bits 7, 8, 9) and swaps pending
    /// (bits 30:28) come from the model. The memory FIFO is not modelled (bits 27:12
    /// read it empty).
    pub(crate) fn status(&mut self, fbi_bits: u32) -> u32 {
        let h = &mut self.host;
        h.settle();
        // Bit 6: 0 while the vertical retrace is active.
        let vretrace = u32::from(!self.frame.retrace_at(h.now)) << 6;
        let free = PCI_FIFO_ENTRIES.saturating_sub(h.in_pci()).min(0x3f) as u32;
        // Bits 27:12: the memory FIFO's free entries, when it is on (0xffff: empty).
        let memory = if h.memory_fifo.entries > 0 {
            ((h.memory_fifo.entries - h.in_memory).min(0xffff) as u32) << 12
        } else {
            fbi_bits & 0xffff << 12
        };
        let fbi_busy = h.engine_free > h.now;
        let tmu_busy = h.tmu_free > h.now;
        let swaps = h.swaps.len().min(7) as u32;
        let sst_busy = fbi_busy || tmu_busy || !h.fifo.is_empty();
        (fbi_bits & !(0x3f | 0x40 | 0x380 | 0xffff << 12 | 0x7 << 28))
            | memory
            | free
            | vretrace
            | u32::from(fbi_busy) << 7
            | u32::from(tmu_busy) << 8
            | u32::from(sst_busy) << 9
            | swaps << 28
    }

    /// The video registers or the DAC changed: the frame the retrace follows from now on
    /// (`video` module; its phase is counted from power-on).
    pub(crate) fn set_video(&mut self, regs: VideoRegs, dac: &Dac) {
        self.frame = Frame::new(self.clock_hz, regs, dac);
    }

    /// `fbiInit0` or `fbiInit4` changed: the memory FIFO they set up from now on.
    pub(crate) fn set_memory_fifo(&mut self, m: MemoryFifo) {
        self.host.set_memory_fifo(m);
    }

    /// The memory FIFO the host's writes queue in behind the PCI FIFO.
    pub fn memory_fifo(&self) -> MemoryFifo {
        self.host.memory_fifo
    }

    /// The video frame the retrace and `vRetrace` follow.
    pub fn frame(&self) -> Frame {
        self.frame
    }

    /// The `vRetrace` register (spec 5.37) at the host's present time: the scan line
    /// since the end of the last vertical sync.
    pub(crate) fn v_retrace(&self) -> u32 {
        self.frame.v_retrace(self.host.now)
    }

    /// A triangle command ran.
    pub(crate) fn triangle(&mut self, w: TriangleWork) {
        let mut setup = if w.subpixel {
            SETUP_SUBPIXEL_CLOCKS
        } else {
            SETUP_CLOCKS
        };
        if w.textured {
            setup = setup.max(TEXTURE_SETUP_CLOCKS);
        }
        let per_pixel = PIXEL_CLOCKS
            + if w.read_modify_write {
                RMW_PIXEL_CLOCKS
            } else {
                0
            };
        let raster = RASTER_CLOCKS + w.spans * SPAN_CLOCKS + w.pixels * per_pixel;
        let engine = setup.max(raster);
        self.host.command(engine, w.textured);
        let (cycles, bus_bound) = self.command(engine);
        self.current.triangles = self.current.triangles.saturating_add(cycles);
        self.current.bus_bound = self.current.bus_bound.saturating_add(bus_bound);
    }

    /// A FASTFILL of `rows` rows of `pixels` pixels in all ran.
    pub(crate) fn fastfill(&mut self, pixels: u64, rows: u64) {
        let engine = pixels * SUB / 2 + rows * FILL_ROW_CLOCKS;
        self.host.command(engine, false);
        let (cycles, bus_bound) = self.command(engine);
        self.current.fills = self.current.fills.saturating_add(cycles);
        self.current.bus_bound = self.current.bus_bound.saturating_add(bus_bound);
    }

    /// A SWAPBUFFER ended the frame.
    /// `value` is what was written to `swapbufferCMD`.
    pub(crate) fn swap(&mut self, value: u32) {
        let retrace = self.frame;
        let synced = value & 1 != 0;
        let interval = u64::from((value >> 1) & 0xff);
        // The host's view: the swap is pending, and the engine waits, until it happens.
        let taken = self.host.last_taken;
        let done = if synced {
            retrace.swap_time(taken, self.host.last_swap, interval)
        } else {
            taken
        };
        if synced {
            self.host.last_swap = done;
        }
        self.host.swaps.push_back(done);
        self.host.engine_free = self.host.engine_free.max(done);
        // The count: the same wait on the board's own clock (the cycles so far).
        let now = self
            .cycles()
            .saturating_mul(SUB)
            .saturating_add(self.fraction + self.pending_bus + self.pending_wait)
            .min(HOST_CLOCK_MAX);
        let wait = if synced {
            retrace.swap_time(now, self.last_swap, interval) - now
        } else {
            0
        };
        if synced {
            self.last_swap = now + wait;
        }
        self.command(wait);
        self.current.retrace_wait += wait / SUB;
        let frame = std::mem::take(&mut self.current);
        self.total.add(&frame);
        if self.frames.len() < MAX_FRAMES {
            self.frames.push(frame);
        }
    }

    /// The cost (whole clocks) of a command whose engine time is `engine` (1/16 clock),
    /// overlapped with the feed of the writes before it (their bus time and the host's
    /// waits between them); and the part of it by which the bus was the longer (the part
    /// by which the host's waits were goes to `host_wait`).
    fn command(&mut self, engine: u64) -> (u64, u64) {
        let bus = std::mem::take(&mut self.pending_bus);
        let wait = std::mem::take(&mut self.pending_wait);
        let feed = bus + wait;
        let sub = feed.max(engine) + self.fraction;
        self.fraction = sub % SUB;
        let cycles = sub / SUB;
        self.current.cycles = self.current.cycles.saturating_add(cycles);
        let excess = feed.saturating_sub(engine);
        let host = excess.min(wait);
        self.current.host_wait = self.current.host_wait.saturating_add(host / SUB);
        (cycles, (excess - host) / SUB)
    }

    /// Cycles modelled so far, the frame in progress included.
    pub fn cycles(&self) -> u64 {
        self.total.cycles.saturating_add(self.current.cycles)
    }

    /// The frame in progress (since the last swap).
    pub fn current_frame(&self) -> FrameTime {
        self.current
    }

    /// Seconds the modelled board took so far.
    pub fn seconds(&self) -> f64 {
        self.cycles() as f64 / self.clock_hz as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commands_cost_the_longer_of_bus_and_engine() {
        let mut t = Timing::default();
        // 10 writes (15 clocks of bus) feed a 10-pixel, 4-span flat triangle:
        // setup 7 clocks, rasterisation (184 + 4 * 6 + 10 * 19) / 16 = 24.875 clocks.
        for _ in 0..10 {
            t.write();
        }
        let flat = TriangleWork {
            pixels: 10,
            spans: 4,
            ..TriangleWork::default()
        };
        t.triangle(flat);
        assert_eq!(t.cycles(), 24); // 398 / 16, 14/16 carried
                                    // 40 writes (60 clocks) for a textured 1-pixel triangle: bus bound (setup 58).
        for _ in 0..40 {
            t.write();
        }
        t.triangle(TriangleWork {
            pixels: 1,
            spans: 1,
            subpixel: true,
            textured: true,
            read_modify_write: true,
        });
        assert_eq!(t.cycles(), 24 + 60); // (960 + 14) / 16 = 60, 14/16 carried
        assert_eq!(t.current_frame().bus_bound, 2);
        t.swap(0);
        assert_eq!(t.frames.len(), 1);
        assert_eq!(t.frames[0].cycles, 84);
        assert_eq!(t.total.triangles, 84);
        // A 640x480 clear: 153,600 clocks of pixels and 480 rows of 39.375.
        t.fastfill(640 * 480, 480);
        assert_eq!(t.current_frame().fills, 153_600 + 18_900);
    }

    #[test]
    fn status_reads_busy_until_the_engine_is_done_and_the_fifo_fills() {
        let mut t = Timing::default();
        // Idle: FIFO empty (0x3f), nothing busy.
        assert_eq!(t.status(0x40), 0x40 | 0x3f);
        // A fill of 640x480 (172,500 clocks) started by one write.
        t.write();
        t.fastfill(640 * 480, 480);
        let s = t.status(0);
        assert_eq!(s & 0x380, 0x280, "FBI and SST-1 busy, TREX idle: {s:#x}");
        // 100 writes while it runs: the FIFO holds 64, the host waits for the rest, so
        // the fill is over when the last is written, and the 64 writes after it are
        // taken as they arrive.
        for _ in 0..20 {
            t.write();
        }
        assert_eq!(t.status(0) & 0x3f, 64 - 20);
        for _ in 0..80 {
            t.write();
        }
        let s = t.status(0);
        assert_eq!(s & 0x3f, 0x3f, "{s:#x}");
        assert_eq!(s & 0x380, 0);
        // A swap is pending until the engine takes it.
        t.write();
        t.fastfill(640 * 480, 480);
        t.write();
        t.swap(0);
        assert_eq!((t.status(0) >> 28) & 7, 1);
        let mut reads = 0;
        while t.status(0) & 0x200 != 0 {
            t.read();
            reads += 1;
        }
        // 172,500 clocks at 4.5 clocks a read.
        assert_eq!(reads, 172_500 * 16 / PCI_CLOCKS_PER_READ as usize);
        assert_eq!((t.status(0) >> 28) & 7, 0);
    }

    #[test]
    fn the_memory_fifo_queues_writes_behind_a_full_pci_fifo() {
        // Glide's set-up on 4 MiB: rows 450 to 1023 (293,888 entries, capped at 65,536),
        // low water mark 23.
        let init0 = 1 << 13;
        let init4 = 0x3ff << 18 | 450 << 8 | 23 << 2 | 1;
        let glide = MemoryFifo::from_registers(init0, init4, 4);
        assert_eq!(glide.entries, MEMORY_FIFO_MAX_ENTRIES);
        assert_eq!(glide.low_water_mark, 23);
        // Off without fbiInit0 bit 13, or with the rows the wrong way round; on 2 MiB the
        // rows stop at 511.
        assert_eq!(MemoryFifo::from_registers(0, init4, 4).entries, 0);
        assert_eq!(
            MemoryFifo::from_registers(init0, 9 << 18 | 10 << 8, 4).entries,
            0
        );
        assert_eq!(
            MemoryFifo::from_registers(init0, 0x3ff << 18 | 500 << 8, 2).entries,
            12 * 512
        );

        let status = |t: &mut Timing| {
            let s = t.status(0xffff << 12);
            (s & 0x3f, s >> 12 & 0xffff, s & 0x200 != 0)
        };
        let mut t = Timing::default();
        assert_eq!(status(&mut t), (0x3f, 0xffff, false), "off: the FBI's bits");
        // One row: 512 entries.
        t.set_memory_fifo(MemoryFifo {
            entries: 512,
            low_water_mark: 23,
        });
        assert_eq!(status(&mut t), (0x3f, 512, false));
        t.write();
        t.fastfill(640 * 480, 480);
        // 100 writes behind the fill: each time 41 are in the PCI FIFO (23 free) they go
        // to memory: 82 there, 18 in the PCI FIFO.
        for _ in 0..100 {
            t.write();
        }
        assert_eq!(status(&mut t), (64 - 18, 512 - 82, true));
        // Up to 576 (512 + 64) queue without the host waiting.
        for _ in 100..576 {
            t.write();
        }
        assert_eq!(status(&mut t), (0, 0, true));
        let before = t.host.now;
        assert!(before < t.host.engine_free, "the host has not waited");
        // The 577th waits for the fill to end; then everything is taken at once.
        t.write();
        assert!(t.host.now >= t.host.engine_free);
        assert_eq!(status(&mut t), (0x3f, 512, false));
    }

    #[test]
    fn take_times_hold_the_queue_a_list_of_times_would() {
        // Pseudo-random pushes (often of the last time, as behind a busy engine), pops,
        // drains up to a time, shifts and clears on the runs and on a plain list: the
        // same times come out, and the runs round-trip through the list form.
        let mut runs = TakeTimes::default();
        let mut list: VecDeque<u64> = VecDeque::new();
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut time = 0u64;
        for step in 0..100_000 {
            xorshift(&mut seed);
            match seed % 16 {
                0..=8 => {
                    time += (seed >> 8) % 3 * ((seed >> 16) % 50);
                    runs.push_back(time);
                    list.push_back(time);
                }
                9..=11 => assert_eq!(runs.pop_front(), list.pop_front(), "step {step}"),
                12..=13 => {
                    let now = time.saturating_sub((seed >> 20) % 200);
                    let mut n = 0;
                    while list.front().is_some_and(|&t| t <= now) {
                        list.pop_front();
                        n += 1;
                    }
                    assert_eq!(runs.pop_taken(now), n, "step {step}");
                }
                14 => {
                    let shift = (seed >> 24) % 300;
                    runs.shift_back(shift);
                    list.iter_mut().for_each(|t| *t = t.saturating_sub(shift));
                    time = time.saturating_sub(shift);
                }
                _ if seed >> 40 & 0xff == 0 => {
                    runs.clear();
                    list.clear();
                }
                _ => {}
            }
            assert_eq!(runs.len(), list.len(), "step {step}");
            assert_eq!(runs.is_empty(), list.is_empty());
        }
        let expanded: Vec<u64> = runs.clone().into();
        assert_eq!(expanded, Vec::from(list));
        assert_eq!(TakeTimes::from(expanded), runs);
    }

    /// Two timing models in their power-on state with a memory FIFO of `entries`
    /// (0: off), for tests that drive both the same way.
    fn model_pair(entries: usize) -> (Timing, Timing) {
        let mut pair = (Timing::default(), Timing::default());
        for t in [&mut pair.0, &mut pair.1] {
            t.set_memory_fifo(MemoryFifo {
                entries,
                low_water_mark: 23,
            });
        }
        pair
    }

    /// The next value of a xorshift64 sequence (Marsaglia 13, 7, 17).
    fn xorshift(seed: &mut u64) -> u64 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        *seed
    }

    #[test]
    fn writes_in_a_row_are_single_writes() {
        // The same pseudo-random commands on two models, the writes between them made
        // one at a time on one and as one run on the other: the same state after every
        // run, with many runs that begin with the engine busy and many that end with it
        // idle.
        for memory in [0, 100] {
            let (mut a, mut b) = model_pair(memory);
            let mut seed = 0x0bad_cafe_f00d_1234u64;
            let (mut busy, mut idle) = (0u32, 0u32);
            for step in 0..50_000 {
                xorshift(&mut seed);
                let n = (seed % 90) as u32;
                busy += u32::from(b.host.engine_free > b.host.now + PCI_CLOCKS_PER_WRITE);
                for _ in 0..n {
                    a.write();
                }
                b.writes(n);
                idle += u32::from(n > 0 && b.host.engine_free <= b.host.now);
                assert_eq!(a.host, b.host, "step {step}");
                assert_eq!(a.pending_bus, b.pending_bus, "step {step}");
                for t in [&mut a, &mut b] {
                    match seed >> 20 & 255 {
                        0..=199 => t.triangle(TriangleWork {
                            pixels: seed >> 40 & 0x1f,
                            spans: seed >> 50 & 0x1f,
                            textured: seed & 1 << 30 != 0,
                            ..TriangleWork::default()
                        }),
                        200..=229 => t.fastfill(seed >> 32 & 0xfff, 4),
                        230 => t.swap(0),
                        _ => t.read(),
                    }
                }
            }
            // Runs that start behind a busy engine, and runs that end with it idle.
            assert!(busy > 10_000 && idle > 10_000, "{busy} {idle}");
            assert_eq!(a.cycles(), b.cycles());
        }
    }

    #[test]
    fn the_write_shortcuts_change_no_read() {
        // The same pseudo-random accesses (writes, triangles, fills, swaps, reads and
        // waits, with and without a memory FIFO) on two models, one of which always takes
        // the general path for writes: the same state once settled, every status read
        // the same, and both shortcuts taken many times.
        for memory in [0, 100] {
            let (mut a, mut b) = model_pair(memory);
            let mut seed = 0x1234_5678_9abc_def0u64;
            let (mut idle, mut joined) = (0u32, 0u32);
            for step in 0..200_000 {
                xorshift(&mut seed);
                for (t, general) in [(&mut a, false), (&mut b, true)] {
                    let op = seed % 100;
                    // A write, and for a command the command it carries (as the board
                    // calls them).
                    if op <= 81 {
                        t.pending_bus += PCI_CLOCKS_PER_WRITE;
                        if general {
                            t.host.write_general();
                        } else {
                            let h = &t.host;
                            idle += u32::from(h.engine_free <= h.now + PCI_CLOCKS_PER_WRITE);
                            joined += u32::from(h.joins_newest());
                            t.host.write();
                        }
                    }
                    match op {
                        0..=69 => {}
                        70..=79 => t.triangle(TriangleWork {
                            pixels: seed >> 40 & 0x3ff,
                            spans: seed >> 50 & 0x1f,
                            textured: seed & 1 << 20 != 0,
                            ..TriangleWork::default()
                        }),
                        80 => t.fastfill(seed >> 32 & 0xffff, 40),
                        81 => t.swap((seed >> 8) as u32 & 0x7),
                        82 => t.host_wait(seed >> 44),
                        _ => t.read(),
                    }
                }
                a.host.settle();
                b.host.settle();
                assert_eq!(a.host, b.host, "step {step}");
                assert_eq!(a.status(0), b.status(0), "step {step}");
                assert_eq!(a.v_retrace(), b.v_retrace());
            }
            assert_eq!(a.cycles(), b.cycles());
            assert!(
                idle > 5_000 && joined > 5_000,
                "{idle} idle, {joined} joined"
            );
        }
    }

    #[test]
    fn huge_waits_keep_the_retrace_phase_and_never_overflow() {
        let mut t = Timing::default();
        let period = Frame::power_on(DEFAULT_CLOCK_HZ).period;
        t.write();
        t.fastfill(640 * 480, 480);
        let mut exact = u128::from(t.host.now);
        for cycles in [u64::MAX, 1 << 50, u64::MAX, 12_345, u64::MAX] {
            t.host_wait(cycles);
            // A wait over WAIT_MAX is shortened by whole frames.
            let sub = u128::from(cycles) * 16;
            let played = if sub > u128::from(WAIT_MAX) {
                u128::from(WAIT_MAX) + (sub - u128::from(WAIT_MAX)) % u128::from(period)
            } else {
                sub
            };
            exact += played;
            assert!(t.host.now <= REBASE_AT);
            assert_eq!(
                u128::from(t.host.now) % u128::from(period),
                exact % u128::from(period),
                "the retrace keeps its phase"
            );
            assert_eq!(t.status(0) & 0x3bf, 0x3f, "idle after the wait");
        }
        // The count saturates.
        t.write();
        t.swap(0);
        assert_eq!(t.frames[0].host_wait, HOST_CLOCK_MAX / SUB);
        assert!(t.cycles() < u64::MAX);
    }

    #[test]
    fn synchronised_swaps_wait_for_the_retraces_their_interval_asks_for() {
        let r = Frame::power_on(DEFAULT_CLOCK_HZ);
        let period = DEFAULT_CLOCK_HZ * SUB / REFRESH_HZ;
        assert_eq!(r.period, period);
        assert_eq!(r.retrace, period * 2 / 525);
        assert!(!r.retrace_at(0) && r.retrace_at(period - 1) && !r.retrace_at(period));
        let first = period - r.retrace;
        // Interval 0: the next retrace; during one, at once.
        assert_eq!(r.swap_time(0, 0, 0), first);
        assert_eq!(r.swap_time(first + 5, 0, 0), first + 5);
        // Interval 1 after a swap at the first retrace: two retraces on.
        assert_eq!(r.swap_time(first, first, 1), first + 2 * period);
        // The count: a frame that swaps at once on an idle board waits for the retrace.
        let mut t = Timing::default();
        t.write();
        t.swap(1);
        // (The swap write itself is part of the wait from the board's clock.)
        assert_eq!(
            t.frames[0].retrace_wait,
            (first - PCI_CLOCKS_PER_WRITE) / SUB
        );
        // Unsynchronised swaps do not wait.
        t.write();
        t.swap(0);
        assert_eq!(t.frames[1].retrace_wait, 0);
        // The host sees the swap pending until the retrace.
        let mut t = Timing::default();
        t.write();
        t.swap(1 | 2 << 1);
        assert_eq!((t.status(0) >> 28) & 7, 1);
        while (t.status(0) >> 28) & 7 != 0 {
            t.read();
        }
        assert!(t.host.now >= first + 2 * period);
        assert_eq!(t.status(0) & 0x40, 0, "swapped during the retrace");
    }
}

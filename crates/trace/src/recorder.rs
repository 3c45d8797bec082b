//! A recording bus wrapper: forwards every access to the bus it wraps and logs it as a
//! [`TraceOp`], so any driver (the Glide 3 front-end, a hardware test) yields a trace.
//!
//! Accesses are logged as the SST-1 decodes them, not as they were made: the board takes
//! any 32-bit bus address but decodes only [`aperture_offset`] of it (24 bits, 4-aligned),
//! and every configuration write outside the 64 dwords of configuration space reaches no
//! register. The trace formats accept exactly the decoded forms, so every recorded trace
//! reads back and replays as the recording ran.
//!
//! Host time: a driver that knows how much time passes between its accesses says so with
//! [`RegisterBus::host_wait`] (deterministic), and [`Recorder::record_host_time`] makes the
//! recorder measure it with the host's monotonic clock. Either way the recorder logs a
//! `wait` op and passes the wait to the bus it wraps, so the board being recorded sees
//! the same time as a replay of the trace will, and every recorded `status` read replays
//! with the value it had.

use std::time::Instant;

use sst1_board::timing::DEFAULT_CLOCK_HZ;
use sst1_board::{aperture_offset, BoardConfig};
use sst1_regs::RegisterBus;

use crate::{check_pci_offset, ConfigKey, DumpBuffer, Trace, TraceOp};

/// The configuration offset a recorder logs for a write at an offset the SST-1 cannot
/// decode (not a 4-aligned offset below 0x100): `0xfc`, the last dword of configuration
/// space, which holds no SST-1 register (spec section 6 lists 0x00-0x4c). The board ignores
/// such a write exactly as it ignores one at 0xfc (it models only `initEnable`, 0x40, and
/// notes any other write as unmodelled).
pub const PCI_UNDECODED: u32 = 0xfc;

/// The aperture offset a recorder logs for an access at bus address `addr`: what the board
/// decodes ([`aperture_offset`]).
pub fn recorded_addr(addr: u32) -> u32 {
    aperture_offset(addr)
}

/// The configuration offset a recorder logs for a write at `offset`: the offset itself if
/// the trace formats accept it (4-aligned, below 0x100), else [`PCI_UNDECODED`].
pub fn recorded_pci_offset(offset: u32) -> u32 {
    if check_pci_offset(offset).is_ok() {
        offset
    } else {
        PCI_UNDECODED
    }
}

/// Where a [`Recorder`] puts what it logs: a [`Trace`] in memory, or a
/// [`TraceWriter`](crate::TraceWriter) that streams it to a file.
pub trait OpLog {
    /// Records one op.
    fn record(&mut self, op: TraceOp);
}

impl OpLog for Trace {
    fn record(&mut self, op: TraceOp) {
        self.ops.push(op);
    }
}

impl OpLog for crate::TraceWriter {
    fn record(&mut self, op: TraceOp) {
        crate::TraceWriter::record(self, &op);
    }
}

/// Wraps a [`RegisterBus`], forwards every call unchanged and logs it.
///
/// Reads are logged with the value the wrapped bus returned. Addresses and offsets are
/// logged as the board decodes them ([`recorded_addr`], [`recorded_pci_offset`]), so the
/// recorded trace is always valid and replays on a [`Board`](sst1_board::Board) exactly
/// as the accesses ran on one. The log is a [`Trace`] in memory by default; with a
/// [`TraceWriter`](crate::TraceWriter) ([`Recorder::streaming`]) memory stays constant
/// however long the recording runs.
pub struct Recorder<B: RegisterBus, L: OpLog = Trace> {
    inner: B,
    log: L,
    /// Measures the host's time between accesses, when asked to.
    clock: Option<HostClock>,
}

/// The host's time between accesses, measured with its monotonic clock
/// ([`Recorder::record_host_time`]).
#[derive(Clone, Copy, Debug)]
struct HostClock {
    /// When the last access (and its logging) returned.
    last: Instant,
    /// Host time measured and not yet logged, in nanoseconds.
    carry_ns: u128,
    /// The shortest wait logged, in graphics clocks; shorter host time carries over.
    min_cycles: u64,
}

const NANOS_PER_SECOND: u128 = 1_000_000_000;

impl HostClock {
    /// The graphics clocks to log before the next access: the time since the last one
    /// returned, with what was carried, once it reaches `min_cycles`.
    fn elapsed_cycles(&mut self) -> Option<u64> {
        self.carry_ns += self.last.elapsed().as_nanos();
        let cycles = self.carry_ns * u128::from(DEFAULT_CLOCK_HZ) / NANOS_PER_SECOND;
        if cycles == 0 || cycles < u128::from(self.min_cycles) {
            return None;
        }
        let cycles = u64::try_from(cycles).unwrap_or(u64::MAX);
        let spent = u128::from(cycles) * NANOS_PER_SECOND / u128::from(DEFAULT_CLOCK_HZ);
        self.carry_ns = self.carry_ns.saturating_sub(spent);
        Some(cycles)
    }
}

impl<B: RegisterBus> Recorder<B> {
    /// Starts a recording of `inner`, a board configured as `config`, into memory; the
    /// trace opens with the three `config` ops that describe it.
    pub fn new(inner: B, config: BoardConfig) -> Self {
        Recorder::with_log(inner, config, Trace::default())
    }

    /// The trace recorded so far.
    pub fn trace(&self) -> &Trace {
        &self.log
    }

    /// Ends the recording: the wrapped bus and the trace.
    pub fn finish(self) -> (B, Trace) {
        (self.inner, self.log)
    }
}

impl<B: RegisterBus> Recorder<B, crate::TraceWriter> {
    /// Starts a recording of `inner`, a board configured as `config`, streamed into
    /// `writer`; [`TraceWriter::finish`](crate::TraceWriter::finish) on
    /// [`Recorder::log_mut`] completes the file.
    pub fn streaming(inner: B, config: BoardConfig, writer: crate::TraceWriter) -> Self {
        Recorder::with_log(inner, config, writer)
    }
}

impl<B: RegisterBus, L: OpLog> Recorder<B, L> {
    /// Starts a recording of `inner`, a board configured as `config`, into `log`; the
    /// log opens with the three `config` ops that describe the board.
    pub fn with_log(inner: B, config: BoardConfig, mut log: L) -> Self {
        for op in [
            TraceOp::Config {
                key: ConfigKey::FbiMb,
                value: config.fbi_mb,
            },
            TraceOp::Config {
                key: ConfigKey::Tmus,
                value: config.tmus,
            },
            TraceOp::Config {
                key: ConfigKey::TmuMb,
                value: config.tmu_mb,
            },
        ] {
            log.record(op);
        }
        Self {
            inner,
            log,
            clock: None,
        }
    }

    /// From now on, measure the host's time between accesses with its monotonic clock
    /// and record it: before each access, the time since the previous one returned (the
    /// time the driver spent outside the bus, not the wrapped board's own work) becomes
    /// a `wait` op in graphics clocks of the default 50 MHz clock, passed to the wrapped
    /// bus too. Waits shorter than `min_cycles` (at least 1) are carried into the next
    /// one, so no time is lost and the trace stays short. This makes the recording
    /// depend on the host's speed: the same program records different waits on every
    /// run, while its replay is the same on every run.
    pub fn record_host_time(&mut self, min_cycles: u64) {
        self.clock = Some(HostClock {
            last: Instant::now(),
            carry_ns: 0,
            min_cycles: min_cycles.max(1),
        });
    }

    /// Logs and forwards the host time measured since the last access, if asked to.
    fn host_time(&mut self) {
        if let Some(cycles) = self.clock.as_mut().and_then(HostClock::elapsed_cycles) {
            self.wait(cycles);
        }
    }

    /// Marks the end of an access for the host clock.
    fn accessed(&mut self) {
        if let Some(clock) = &mut self.clock {
            clock.last = Instant::now();
        }
    }

    /// Logs a `wait` op and passes it to the wrapped bus.
    fn wait(&mut self, cycles: u64) {
        self.log.record(TraceOp::Wait { cycles });
        self.inner.host_wait(cycles);
    }

    /// Logs a `dump` point: a replay of the trace saves `buffer` to `file` here.
    pub fn dump(&mut self, buffer: DumpBuffer, file: &str) {
        self.log.record(TraceOp::Dump {
            buffer,
            file: file.to_owned(),
        });
    }

    /// The log.
    pub fn log(&self) -> &L {
        &self.log
    }

    /// The log, mutably.
    pub fn log_mut(&mut self) -> &mut L {
        &mut self.log
    }

    /// The wrapped bus (reading it records nothing).
    pub fn inner(&self) -> &B {
        &self.inner
    }

    /// The wrapped bus, mutably. Accesses made through it bypass the recording.
    pub fn inner_mut(&mut self) -> &mut B {
        &mut self.inner
    }

    /// Ends the recording: the wrapped bus and the log.
    pub fn into_parts(self) -> (B, L) {
        (self.inner, self.log)
    }
}

impl<B: RegisterBus, L: OpLog> RegisterBus for Recorder<B, L> {
    fn write32(&mut self, addr: u32, value: u32) {
        self.host_time();
        self.log.record(TraceOp::Write {
            addr: recorded_addr(addr),
            value,
        });
        self.inner.write32(addr, value);
        self.accessed();
    }

    fn read32(&mut self, addr: u32) -> u32 {
        self.host_time();
        let value = self.inner.read32(addr);
        self.log.record(TraceOp::Read {
            addr: recorded_addr(addr),
            value: Some(value),
        });
        self.accessed();
        value
    }

    fn pci_write(&mut self, offset: u32, value: u32) {
        self.host_time();
        self.log.record(TraceOp::Pci {
            offset: recorded_pci_offset(offset),
            value,
        });
        self.inner.pci_write(offset, value);
        self.accessed();
    }

    /// Logs the wait (a wait of 0 logs nothing) and passes it on.
    fn host_wait(&mut self, cycles: u64) {
        if cycles > 0 {
            self.wait(cycles);
        }
    }
}

//! A recording bus wrapper: forwards every access to the bus it wraps and logs it as a
//! [`TraceOp`], so any driver (the Glide 3 front-end, a hardware test) yields a trace.
//!
//! Accesses are logged as the SST-1 decodes them, not as they were made: the board takes
//! any 32-bit bus address but decodes only [`aperture_offset`] of it (24 bits, 4-aligned),
//! and every configuration write outside the 64 dwords of configuration space reaches no
//! register. The trace formats accept exactly the decoded forms, so every recorded trace
//! reads back and replays as the recording ran.

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

/// Wraps a [`RegisterBus`], forwards every call unchanged and logs it.
///
/// Reads are logged with the value the wrapped bus returned. Addresses and offsets are
/// logged as the board decodes them ([`recorded_addr`], [`recorded_pci_offset`]), so the
/// recorded trace is always valid and replays on a [`Board`](sst1_board::Board) exactly
/// as the accesses ran on one.
pub struct Recorder<B: RegisterBus> {
    inner: B,
    trace: Trace,
}

impl<B: RegisterBus> Recorder<B> {
    /// Starts a recording of `inner`, a board configured as `config`; the trace opens with
    /// the three `config` ops that describe it.
    pub fn new(inner: B, config: BoardConfig) -> Self {
        let ops = vec![
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
        ];
        Self {
            inner,
            trace: Trace { ops },
        }
    }

    /// Logs a `dump` point: a replay of the trace saves `buffer` to `file` here.
    pub fn dump(&mut self, buffer: DumpBuffer, file: &str) {
        self.trace.ops.push(TraceOp::Dump {
            buffer,
            file: file.to_owned(),
        });
    }

    /// The trace recorded so far.
    pub fn trace(&self) -> &Trace {
        &self.trace
    }

    /// The wrapped bus (reading it records nothing).
    pub fn inner(&self) -> &B {
        &self.inner
    }

    /// The wrapped bus, mutably. Accesses made through it bypass the recording.
    pub fn inner_mut(&mut self) -> &mut B {
        &mut self.inner
    }

    /// Ends the recording: the wrapped bus and the trace.
    pub fn finish(self) -> (B, Trace) {
        (self.inner, self.trace)
    }
}

impl<B: RegisterBus> RegisterBus for Recorder<B> {
    fn write32(&mut self, addr: u32, value: u32) {
        self.trace.ops.push(TraceOp::Write {
            addr: recorded_addr(addr),
            value,
        });
        self.inner.write32(addr, value);
    }

    fn read32(&mut self, addr: u32) -> u32 {
        let value = self.inner.read32(addr);
        self.trace.ops.push(TraceOp::Read {
            addr: recorded_addr(addr),
            value: Some(value),
        });
        value
    }

    fn pci_write(&mut self, offset: u32, value: u32) {
        self.trace.ops.push(TraceOp::Pci {
            offset: recorded_pci_offset(offset),
            value,
        });
        self.inner.pci_write(offset, value);
    }
}

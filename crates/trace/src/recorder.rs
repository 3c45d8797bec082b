//! A recording bus wrapper: forwards every access to the bus it wraps and logs it as a
//! [`TraceOp`], so any driver (the Glide 3 front-end, a hardware test) yields a trace.

use sst1_board::BoardConfig;
use sst1_regs::RegisterBus;

use crate::{ConfigKey, DumpBuffer, Trace, TraceOp};

/// Wraps a [`RegisterBus`], forwards every call unchanged and logs it.
///
/// Reads are logged with the value the wrapped bus returned. Accesses are logged as made:
/// one the trace formats reject (offset not 4-aligned or outside the aperture) makes the
/// recorded trace unreadable once written out.
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
        self.trace.ops.push(TraceOp::Write { addr, value });
        self.inner.write32(addr, value);
    }

    fn read32(&mut self, addr: u32) -> u32 {
        let value = self.inner.read32(addr);
        self.trace.ops.push(TraceOp::Read {
            addr,
            value: Some(value),
        });
        value
    }

    fn pci_write(&mut self, offset: u32, value: u32) {
        self.trace.ops.push(TraceOp::Pci { offset, value });
        self.inner.pci_write(offset, value);
    }
}

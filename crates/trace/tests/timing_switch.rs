//! The timing model's off switch (`Board::set_timing(false)`, `voodoo replay
//! --no-timing`): the same pixels and counters, nothing played out in time.

use std::path::Path;

use sst1_board::{Board, BufferKind};
use sst1_regs::RegisterBus;
use sst1_trace::{execute, load_trace};

fn trace(path: &str) -> sst1_trace::Trace {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../traces");
    load_trace(&root.join(path)).unwrap_or_else(|e| panic!("{e}"))
}

/// Every dump, the final buffers, the statistics and the diagnostics are the same with
/// the timing model off, for a conformance trace and a Glide SDK trace (which programs
/// the DAC, the memory FIFO and swaps synchronised to retrace); off, no cycles count.
#[test]
fn timing_off_keeps_pixels_and_counters() {
    for path in [
        "conformance/traces/fog_table.trace.gz",
        "glide-sdk/traces/test08.trace.gz",
    ] {
        let t = trace(path);
        let run = |timing: bool| {
            let mut board = Board::new(t.board_config());
            board.set_timing(timing);
            let dumps = execute(&t.ops, &mut board, |_| {});
            (board, dumps)
        };
        let (on, dumps_on) = run(true);
        let (off, dumps_off) = run(false);
        assert!(!dumps_on.is_empty(), "{path}");
        assert_eq!(dumps_on, dumps_off, "{path}");
        for kind in [BufferKind::Front, BufferKind::Back, BufferKind::Aux] {
            assert_eq!(on.dump_buffer(kind), off.dump_buffer(kind), "{path}");
        }
        assert_eq!(on.stats(), off.stats(), "{path}");
        assert_eq!(on.diagnostics(), off.diagnostics(), "{path}");
        assert!(on.timing().cycles() > 0 && !on.timing().frames.is_empty());
        assert_eq!(off.timing().cycles(), 0, "{path}");
        assert!(off.timing().frames.is_empty());
    }
}

/// Off, `status` reads the FBI's own bits: idle, FIFOs empty, outside retrace, swaps
/// never pending, right after a full-screen fill; `vRetrace` reads 0; waits do nothing.
#[test]
fn timing_off_reads_idle() {
    let mut board = Board::new(Default::default());
    board.set_timing(false);
    assert!(!board.timing_enabled());
    board.pci_write(0x40, 3);
    for (a, v) in [(0x118, 0x280), (0x11c, 0x1e0), (0x110, 0x200), (0x124, 0)] {
        board.write32(a, v);
    }
    board.write32(0x128, 1); // a synchronised swap
    assert_eq!(board.read32(0), 0x0fff_f47f, "idle, displayed buffer 1");
    board.host_wait(1_000_000);
    assert_eq!(board.read32(0x204), 0);
    assert_eq!(board.timing().cycles(), 0);
}

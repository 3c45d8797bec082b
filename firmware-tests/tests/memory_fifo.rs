//! The memory FIFO (spec 3, 5.1 bits 27:12, 5.42 bit 13, 5.46 bits 27:2): frame-buffer
//! rows that queue the host's writes behind the 64-entry PCI FIFO, so that a host
//! writing faster than the board draws waits later.

use firmware_tests::{fastfill, wait_idle, Emulator, Port, IDLE_READS};
use sst1_regs::addr;

/// `fbiInit0` as the traces leave it, with the memory FIFO enabled (bit 13).
const FBI_INIT0_MEMORY_FIFO: u32 = 0x0000_0001 | 1 << 13;
/// `fbiInit4`: one row (1000 to 1000: 4 KiB, 512 entries of address and data), low water
/// mark 23 (Glide's), PCI read wait states as the traces set them (bit 0).
const FBI_INIT4_ONE_ROW: u32 = 1000 << 18 | 1000 << 8 | 23 << 2 | 1;

/// (PCI FIFO free, memory FIFO free, SST-1 busy) from `status`.
fn fifo_state(p: &mut impl Port) -> (u32, u32, bool) {
    let s = p.read(addr::STATUS);
    (s & 0x3f, s >> 12 & 0xffff, s >> 9 & 1 != 0)
}

/// With the memory FIFO on, writes behind a full-screen FASTFILL fill the PCI FIFO to its
/// low water mark, then go to memory: after 100 writes, 82 are in memory (430 of 512 free)
/// and 18 in the PCI FIFO (46 free). 576 writes (512 + 64) queue without the host
/// waiting, so the board is still busy after them; the 577th waits for the fill, and
/// the board is idle after it. Without the memory FIFO the host waits from the 65th
/// write on, and bits 27:12 read 0xffff.
///
/// Source: spec 5.1 (bits 27:12: memory FIFO free space, 0xffff when empty), 5.42
/// (bit 13: enable), 5.46 (rows, low water mark). UNVERIFIED: 8 bytes an entry (MAME's),
/// and the dump of the whole PCI FIFO at the mark.
#[test]
fn the_memory_fifo_queues_writes_behind_the_pci_fifo() {
    let run = |memory_fifo: bool| {
        let mut p = Emulator::booted();
        if memory_fifo {
            p.write(addr::FBI_INIT4, FBI_INIT4_ONE_ROW);
            p.write(addr::FBI_INIT0, FBI_INIT0_MEMORY_FIFO);
        }
        assert!(wait_idle(&mut p, IDLE_READS));
        let idle = fifo_state(&mut p);
        fastfill(&mut p, 0x00ff_0000, 0);
        for _ in 0..100 {
            p.write(addr::COLOR0, 0);
        }
        let after_100 = fifo_state(&mut p);
        for _ in 100..576 {
            p.write(addr::COLOR0, 0);
        }
        let after_576 = fifo_state(&mut p);
        p.write(addr::COLOR0, 0);
        let after_577 = fifo_state(&mut p);
        [idle, after_100, after_576, after_577]
    };
    assert_eq!(
        run(true),
        [
            (0x3f, 512, false),
            (46, 430, true),
            (0, 0, true),
            (0x3f, 512, false)
        ]
    );
    // Without: the host waited for the fill from the 65th write on, so the board is
    // idle after 100.
    assert_eq!(
        run(false),
        [
            (0x3f, 0xffff, false),
            (0x3f, 0xffff, false),
            (0x3f, 0xffff, false),
            (0x3f, 0xffff, false)
        ]
    );
    assert_eq!(run(true), run(true));
}

//! Register sequences a driver writes, shared by tests, examples and tools.

use sst1_regs::{addr, RegisterBus};

/// `initEnable` in PCI configuration space (spec 6).
const PCI_INIT_ENABLE: u32 = 0x40;

/// The mode set Glide 3 writes for 640x480 with two colour buffers and one aux buffer in
/// 4 MiB: FBI reset, video timing, 10 tiles in X (640-pixel rows), buffer offset 150
/// pages, Y-origin swap value 479, then a 640x480 clip rectangle.
/// Source: the first register writes of every trace in `traces/conformance`.
pub const GLIDE_640X480: &[(u32, u32)] = &[
    (addr::FBI_INIT0, 0x0000_0007),
    (addr::FBI_INIT1, 0x0000_01a2),
    (addr::FBI_INIT0, 0x0000_0001),
    (addr::H_SYNC, 0x02c0_0060),
    (addr::V_SYNC, 0x020b_0002),
    (addr::BACK_PORCH, 0x0012_0032),
    (addr::VIDEO_DIMENSIONS, 0x01e0_027f),
    (addr::FBI_INIT2, 0x1874_b040),
    (addr::FBI_INIT3, 0x77de_4000),
    (addr::FBI_INIT4, 0x0000_0001),
    (addr::FBI_INIT1, 0x0020_00a2),
    (addr::CLIP_LEFT_RIGHT, 0x0000_0280),
    (addr::CLIP_LOW_Y_HIGH_Y, 0x0000_01e0),
];

/// Enable `fbiInit*` writes in PCI configuration space and write [`GLIDE_640X480`].
pub fn init_glide_640x480(bus: &mut impl RegisterBus) {
    bus.pci_write(PCI_INIT_ENABLE, 3);
    for &(a, v) in GLIDE_640X480 {
        bus.write32(a, v);
    }
}

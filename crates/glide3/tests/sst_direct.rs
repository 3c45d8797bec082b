//! The calls that reach the chip directly (src/sst.rs), as 3dfx's SST-1 Glide 3 does
//! them (gsst.c, gdraw.c): the register writes each one makes, on a stub bus.

mod common;
use common::{open_640x480, Op, Rec};
use glide::consts::*;
use glide::{BoardInfo, Glide, RegisterBus};
use std::cell::Cell;
use std::rc::Rc;

/// The packer workaround's address (TEX_BASE + 3 << 21 + 1 << 17).
const PACKER_FIX: u32 = 0x80_0000 + (3 << 21) + (1 << 17);

fn since(rec: &Rec, from: usize) -> Vec<Op> {
    rec.0.borrow()[from..].to_vec()
}

#[test]
fn config_pipeline_writes_one_register_between_packer_fixes() {
    let (rec, mut g) = open_640x480(GR_ORIGIN_UPPER_LEFT);
    let n = rec.0.borrow().len();
    g.config_pipeline(GR_TMU0, 0x120 / 4, 1);
    g.config_pipeline(GR_TMU1, 0x104 / 4, 0x55);
    assert_eq!(
        since(&rec, n),
        [
            Op::W(PACKER_FIX, 0),
            Op::W(0x800 | 0x120, 1),
            Op::W(PACKER_FIX, 0),
            Op::W(PACKER_FIX, 0),
            Op::W(0x1000 | 0x104, 0x55),
            Op::W(PACKER_FIX, 0),
        ]
    );
    let n = rec.0.borrow().len();
    g.config_pipeline(3, 0, 0);
    assert_eq!(
        g.last_error(),
        Some("grSstConfigPipeline: invalid chip ID specified")
    );
    g.config_pipeline(GR_TMU0, 0x100, 0);
    assert_eq!(
        g.last_error(),
        Some("grSstConfigPipeline: register out of range")
    );
    assert!(since(&rec, n).is_empty());
}

/// A stub bus whose status register reads `status`.
#[derive(Clone)]
struct Status(Rec, Rc<Cell<u32>>);

impl RegisterBus for Status {
    fn write32(&mut self, addr: u32, value: u32) {
        self.0.write32(addr, value);
    }
    fn read32(&mut self, addr: u32) -> u32 {
        if addr == 0 {
            self.1.get()
        } else {
            0
        }
    }
    fn pci_write(&mut self, offset: u32, value: u32) {
        self.0.pci_write(offset, value);
    }
}

#[test]
fn is_busy_sends_one_nop_until_the_chip_is_seen_idle() {
    let rec = Rec::default();
    let status = Rc::new(Cell::new(1 << 9));
    let mut g = Glide::init(
        Box::new(Status(rec.clone(), status.clone())),
        BoardInfo::new(4, 1, 4),
    );
    let nops = |rec: &Rec| {
        rec.0
            .borrow()
            .iter()
            .filter(|op| **op == Op::W(0x120, 1))
            .count()
    };
    let before = nops(&rec);
    assert!(g.is_busy());
    assert!(g.is_busy());
    assert_eq!(nops(&rec), before + 1, "one nopCMD while busy");
    status.set(0);
    assert!(!g.is_busy());
    assert!(!g.is_busy());
    assert_eq!(
        nops(&rec),
        before + 2,
        "idle seen: the next call sends another"
    );
    // Retrace: FXTRUE when status bit 6 is clear; the line is vRetrace as read.
    assert!(g.vretrace_on());
    status.set(1 << 6);
    assert!(!g.vretrace_on());
    assert_eq!(g.video_line(), 0);
}

#[test]
fn delta0_mode_loads_the_start_colour_and_zeroes_the_rgb_slopes() {
    let (rec, mut g) = open_640x480(GR_ORIGIN_UPPER_LEFT);
    let n = rec.0.borrow().len();
    g.color_combine_delta0(true);
    assert!(g.in_delta0_mode());
    assert_eq!(
        since(&rec, n),
        [
            Op::W(0x0a0, 0),
            Op::W(0x0a4, 0),
            Op::W(0x0a8, 0),
            Op::W(0x040, 0),
            Op::W(0x060, 0),
            Op::W(0x044, 0),
            Op::W(0x064, 0),
            Op::W(0x048, 0),
            Op::W(0x068, 0),
        ]
    );
    let n = rec.0.borrow().len();
    g.color_combine_delta0(false);
    assert!(!g.in_delta0_mode());
    assert!(since(&rec, n).is_empty(), "leaving the mode writes nothing");
}

/// In delta-0 mode a Gouraud triangle sends no RGB start values or slopes
/// (gglide.c `_grUpdateParamIndex`); out of it, it does.
#[test]
fn delta0_triangles_carry_no_iterated_rgb() {
    let (rec, mut g) = open_640x480(GR_ORIGIN_UPPER_LEFT);
    g.vertex_layout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    g.vertex_layout(GR_PARAM_RGB, 8, GR_PARAM_ENABLE);
    let v = [
        [10.0, 10.0, 255.0, 0.0, 0.0],
        [100.0, 20.0, 0.0, 255.0, 0.0],
        [30.0, 90.0, 0.0, 0.0, 255.0],
    ];
    let rgb_writes = |g: &mut Glide, rec: &Rec| {
        let n = rec.0.borrow().len();
        g.draw_triangle(&v[0], &v[1], &v[2]);
        // The RGB start and slope registers, integer (0x020-0x028, 0x040-0x048,
        // 0x060-0x068) or float (0x0a0-0x0a8, 0x0c0-0x0c8, 0x0e0-0x0e8).
        since(rec, n)
            .iter()
            .filter(|op| match op {
                Op::W(a, _) if *a < 0x100 => {
                    matches!(a & 0x1f, 0x00 | 0x04 | 0x08)
                        && matches!(a & !0x1f, 0x020 | 0x040 | 0x060 | 0x0a0 | 0x0c0 | 0x0e0)
                }
                _ => false,
            })
            .count()
    };
    // The colour combine of a Gouraud triangle, set again after each mode change.
    let iterated = |g: &mut Glide| {
        g.color_combine(
            GR_COMBINE_FUNCTION_LOCAL,
            GR_COMBINE_FACTOR_NONE,
            GR_COMBINE_LOCAL_ITERATED,
            GR_COMBINE_OTHER_NONE,
            false,
        )
    };
    iterated(&mut g);
    assert_eq!(
        rgb_writes(&mut g, &rec),
        9,
        "Gouraud: R, G, B starts and slopes"
    );
    g.color_combine_delta0(true);
    iterated(&mut g);
    assert_eq!(rgb_writes(&mut g, &rec), 0, "delta-0: none");
    g.color_combine_delta0(false);
    iterated(&mut g);
    assert_eq!(rgb_writes(&mut g, &rec), 9);
}

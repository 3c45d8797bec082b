//! Bad arguments reach the error callback with a message naming the call and leave
//! the state (and the register stream) unchanged.

mod common;
use common::Rec;
use glide::consts::*;
use glide::{BoardInfo, Glide};
use std::cell::RefCell;
use std::rc::Rc;

#[test]
fn bad_arguments_are_reported_and_ignored() {
    let rec = Rec::default();
    let mut g = Glide::init(Box::new(rec.clone()), BoardInfo::new(4, 1, 4));
    assert!(g.win_open(
        GR_RESOLUTION_640x480,
        GR_REFRESH_60Hz,
        GR_COLORFORMAT_ARGB,
        GR_ORIGIN_UPPER_LEFT,
        2,
        1
    ));
    let seen = Rc::new(RefCell::new(Vec::<String>::new()));
    let s2 = seen.clone();
    g.set_error_callback(Box::new(move |m, _fatal| {
        s2.borrow_mut().push(m.to_string())
    }));
    let before = g.get_state();
    let writes = rec.0.borrow().len();
    g.color_combine(
        99,
        GR_COMBINE_FACTOR_ONE,
        GR_COMBINE_LOCAL_ITERATED,
        GR_COMBINE_OTHER_ITERATED,
        false,
    );
    g.depth_buffer_mode(17);
    g.tex_clamp_mode(2, GR_TEXTURECLAMP_CLAMP, GR_TEXTURECLAMP_CLAMP);
    g.vertex_layout(GR_PARAM_RGB, 3, GR_PARAM_ENABLE);
    assert!(!g.win_open(
        GR_RESOLUTION_640x480,
        GR_REFRESH_60Hz,
        GR_COLORFORMAT_ARGB,
        GR_ORIGIN_UPPER_LEFT,
        2,
        1
    ));
    let msgs = seen.borrow().clone();
    assert_eq!(msgs.len(), 5, "{msgs:?}");
    assert!(msgs[0].starts_with("grColorCombine:"));
    assert!(msgs[1].starts_with("grDepthBufferMode:"));
    assert!(msgs[2].starts_with("grTexClampMode: invalid TMU 2"));
    assert!(msgs[3].starts_with("grVertexLayout:"));
    assert!(msgs[4].starts_with("grSstWinOpen:"));
    // get_state validates, which writes nothing when nothing changed.
    assert_eq!(g.get_state(), before);
    assert_eq!(rec.0.borrow().len(), writes);
}

#[test]
fn other_modes_open() {
    for (res, w, h) in [
        (GR_RESOLUTION_512x384, 512, 384),
        (GR_RESOLUTION_640x400, 640, 400),
        (GR_RESOLUTION_800x600, 800, 600),
        (GR_RESOLUTION_856x480, 856, 480),
        (GR_RESOLUTION_960x720, 960, 720),
    ] {
        let rec = Rec::default();
        let mut g = Glide::init(Box::new(rec.clone()), BoardInfo::new(4, 1, 4));
        assert!(g.win_open(
            res,
            GR_REFRESH_60Hz,
            GR_COLORFORMAT_ARGB,
            GR_ORIGIN_UPPER_LEFT,
            2,
            1
        ));
        assert_eq!(g.screen_size(), (w, h));
        // videoDimensions carries (height << 16) | (width - 1).
        let dims = (h << 16) | (w - 1);
        assert!(
            rec.0.borrow().contains(&common::Op::W(0x20c, dims)),
            "{res:#x}"
        );
    }
}

/// 3dfx's grLfbLock ends with grFinish (`nopCMD`) unless the type has GR_LFB_NOIDLE,
/// granted or not, and so does the lock inside grLfbReadRegion; grLfbWriteRegion's lock
/// is GR_LFB_NOIDLE and writes none (glfb.c).
#[test]
fn lfb_locks_idle_as_3dfx_does() {
    use common::Op;
    use sst1_regs::addr::NOP_CMD;
    let (rec, mut g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    let nops = |rec: &Rec| {
        rec.0
            .borrow()
            .iter()
            .filter(|op| matches!(op, Op::W(a, 0) if a & 0x3fc == NOP_CMD))
            .count()
    };
    let mut seen = nops(&rec);
    let mut step = |g: &mut Glide, what: &str, f: &dyn Fn(&mut Glide), nop: usize| {
        f(g);
        let now = nops(&rec);
        assert_eq!(now - seen, nop, "{what}");
        seen = now;
    };
    step(
        &mut g,
        "read lock",
        &|g| {
            assert!(g
                .lfb_lock(
                    GR_LFB_READ_ONLY,
                    GR_BUFFER_BACKBUFFER,
                    GR_LFBWRITEMODE_ANY,
                    0,
                    false
                )
                .is_some());
        },
        1,
    );
    step(
        &mut g,
        "unlock",
        &|g| assert!(g.lfb_unlock(GR_LFB_READ_ONLY, GR_BUFFER_BACKBUFFER)),
        0,
    );
    step(
        &mut g,
        "write lock, no idle",
        &|g| {
            let ty = GR_LFB_WRITE_ONLY | GR_LFB_NOIDLE;
            assert!(g
                .lfb_lock(ty, GR_BUFFER_BACKBUFFER, GR_LFBWRITEMODE_565, 0, false)
                .is_some());
            assert!(g.lfb_unlock(ty, GR_BUFFER_BACKBUFFER));
        },
        0,
    );
    step(
        &mut g,
        "refused lock (bad buffer)",
        &|g| {
            assert!(g
                .lfb_lock(GR_LFB_WRITE_ONLY, 7, GR_LFBWRITEMODE_565, 0, false)
                .is_none());
        },
        1,
    );
    step(
        &mut g,
        "read region",
        &|g| {
            let mut out = [0u8; 8];
            assert!(g.lfb_read_region(GR_BUFFER_BACKBUFFER, 0, 0, 2, 2, 4, &mut out));
        },
        1,
    );
    step(
        &mut g,
        "write region",
        &|g| {
            assert!(g.lfb_write_region(
                GR_BUFFER_BACKBUFFER,
                0,
                0,
                GR_LFB_SRC_FMT_565,
                2,
                2,
                false,
                4,
                &[0; 8]
            ));
        },
        0,
    );
}

/// A refused grLfbLock writes what 3dfx's writes before it refuses (glfb.c): nothing
/// when a lock of that type is held; for a read lock of a bad buffer `lfbMode` with read
/// buffer 0; for a write lock of a bad buffer or mode `zaColor`, `lfbMode` with the
/// mode ORed in as given (write buffer 0 for a bad buffer) and `fbzMode` without depth
/// bias. The values below follow glfb.c's bit operations by hand: lfbMode bits 3:0
/// format, 5:4 write buffer, 7:6 read buffer, 8 pixel pipeline, 13 Y origin (spec 5.20);
/// zaColor 15:0 depth, 31:24 alpha; fbzMode bit 16 depth bias, bit 17 Y origin.
#[test]
fn refused_lfb_locks_write_what_3dfx_writes() {
    use common::Op;
    use sst1_regs::addr::{FBZ_MODE, LFB_MODE, NOP_CMD, ZA_COLOR};
    let (rec, mut g) = common::open_640x480(GR_ORIGIN_UPPER_LEFT);
    g.lfb_constant_depth(0x1234);
    g.lfb_constant_alpha(0x56);
    g.depth_bias_level(7);
    let last = |reg: u32| {
        rec.0.borrow().iter().rev().find_map(|op| match *op {
            Op::W(a, v) if a & 0x3fc == reg => Some(v),
            _ => None,
        })
    };
    // The writes a call makes, nopCMD (grFinish) left out.
    let writes = |g: &mut Glide, f: &dyn Fn(&mut Glide) -> bool| {
        let before = rec.0.borrow().len();
        assert!(!f(g), "the lock must be refused");
        rec.0.borrow()[before..]
            .iter()
            .filter(|op| !matches!(op, Op::W(a, _) if a & 0x3fc == NOP_CMD))
            .map(|op| match *op {
                Op::W(a, v) => (a & 0x3fc, v),
                Op::Pci(a, v) => (0x1000 + a, v),
            })
            .collect::<Vec<_>>()
    };
    let lock = |ty, buffer, mode, origin, pipe| {
        move |g: &mut Glide| g.lfb_lock(ty, buffer, mode, origin, pipe).is_some()
    };
    // Drawing state first (validated before the lock), then the registers' values.
    g.depth_mask(true);
    assert!(g
        .lfb_lock(
            GR_LFB_READ_ONLY,
            GR_BUFFER_FRONTBUFFER,
            GR_LFBWRITEMODE_ANY,
            0,
            false
        )
        .is_some());
    assert!(g.lfb_unlock(GR_LFB_READ_ONLY, GR_BUFFER_FRONTBUFFER));
    let lfb = last(LFB_MODE).expect("lfbMode written");
    let fbz = last(FBZ_MODE).expect("fbzMode written");
    let za = 0x56 << 24 | 0x1234;

    // Read lock of a bad buffer: lfbMode, read buffer 0, Y origin as asked.
    let read_bad = (lfb & !(0b11 << 6 | 1 << 13)) | 1 << 13;
    assert_eq!(
        writes(
            &mut g,
            &lock(GR_LFB_READ_ONLY, 9, GR_LFBWRITEMODE_ANY, 1, false)
        ),
        [(LFB_MODE, read_bad)]
    );
    let lfb = read_bad;
    let write_lfb = |sel: u32, mode: u32, y: bool, pipe: bool| {
        (lfb & !(0b11 << 4 | 1 << 13 | 0xf | 1 << 8))
            | sel << 4
            | mode
            | u32::from(y) << 13
            | u32::from(pipe) << 8
    };
    let no_bias = fbz & !(1 << 16);
    // A refused write lock of `buffer` in `mode`: zaColor, lfbMode, fbzMode.
    let mut refused = |buffer, mode, lower_left: bool, pipe: bool| {
        let origin = u32::from(lower_left);
        writes(&mut g, &lock(GR_LFB_WRITE_ONLY, buffer, mode, origin, pipe))
    };
    // A reserved mode on the back buffer, through the pipeline with the lower-left origin.
    assert_eq!(
        refused(GR_BUFFER_BACKBUFFER, 6, true, true),
        [
            (ZA_COLOR, za),
            (LFB_MODE, write_lfb(1, 6, true, true)),
            (FBZ_MODE, no_bias | 1 << 17)
        ]
    );
    // ZA16 on a colour buffer; a colour mode on the aux buffer (write buffer 0).
    let plain = |lfb_mode: u32| [(ZA_COLOR, za), (LFB_MODE, lfb_mode), (FBZ_MODE, no_bias)];
    assert_eq!(
        refused(GR_BUFFER_FRONTBUFFER, GR_LFBWRITEMODE_ZA16, false, false),
        plain(write_lfb(0, 0xf, false, false))
    );
    assert_eq!(
        refused(GR_BUFFER_AUXBUFFER, GR_LFBWRITEMODE_565, false, false),
        plain(write_lfb(0, 0, false, false))
    );
    // A bad buffer with GR_LFBWRITEMODE_ANY: 0xff ORed in at bit 0 sets bits 7:0.
    assert_eq!(
        refused(7, GR_LFBWRITEMODE_ANY, false, false),
        plain(write_lfb(0, 0, false, false) | 0xff)
    );
    // A held lock: nothing at all; an unknown lock type: nothing.
    assert!(g
        .lfb_lock(
            GR_LFB_WRITE_ONLY,
            GR_BUFFER_BACKBUFFER,
            GR_LFBWRITEMODE_565,
            0,
            false
        )
        .is_some());
    assert_eq!(
        writes(
            &mut g,
            &lock(
                GR_LFB_WRITE_ONLY,
                GR_BUFFER_FRONTBUFFER,
                GR_LFBWRITEMODE_565,
                0,
                false
            )
        ),
        []
    );
    assert_eq!(
        writes(
            &mut g,
            &lock(5, GR_BUFFER_FRONTBUFFER, GR_LFBWRITEMODE_565, 0, false)
        ),
        []
    );
}

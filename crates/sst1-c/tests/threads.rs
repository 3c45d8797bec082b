//! One board used from several threads at once, through the C entry points (called from
//! Rust through the rlib): calls are serialised by the board's lock, so a thread reading
//! the front buffer while another writes sees whole frames, and the final state is the
//! same as from one thread.

use sst1::*;
use std::ffi::c_void;
use std::sync::atomic::{AtomicU64, Ordering};

/// The handle, to send between threads (the library serialises the calls).
#[derive(Clone, Copy)]
struct Handle(*mut Sst1Board);
// SAFETY: every call on the board takes its lock (sst1.h: "a board may be used from any
// thread").
unsafe impl Send for Handle {}
unsafe impl Sync for Handle {}

impl Handle {
    /// The pointer (a method, so that closures capture the whole `Handle`).
    fn get(self) -> *mut Sst1Board {
        self.0
    }
}

/// Registers: fbzMode, color1, fastfillCMD, swapbufferCMD.
const FBZ_MODE: u32 = 0x110;
const COLOR1: u32 = 0x148;
const FASTFILL_CMD: u32 = 0x124;
const SWAPBUFFER_CMD: u32 = 0x128;

static SWAPS_SEEN: AtomicU64 = AtomicU64::new(0);

unsafe extern "C" fn count_swap(_user: *mut c_void, _board: *mut Sst1Board, n: u64) {
    SWAPS_SEEN.fetch_max(n, Ordering::SeqCst);
}

#[test]
fn a_board_shared_by_threads_serialises_its_calls() {
    let config = Sst1Config {
        fbi_mb: 4,
        tmus: 1,
        tmu_mb: 4,
    };
    let mut board = std::ptr::null_mut();
    // SAFETY: valid pointers; the board is destroyed at the end and not used after.
    unsafe {
        assert_eq!(sst1_create(&config, 0, &mut board), OK);
        assert_eq!(
            sst1_set_swap_callback(board, Some(count_swap), std::ptr::null_mut()),
            OK
        );
        // Fills reach the back buffer (fbzMode: RGB writes on, draw buffer back); the
        // default clip rectangle is empty, so set the full 640x480 one.
        assert_eq!(sst1_write32(board, FBZ_MODE, 1 << 9 | 1 << 14), OK);
        assert_eq!(sst1_write32(board, 0x118, 640), OK);
        assert_eq!(sst1_write32(board, 0x11c, 480), OK);
    }
    let h = Handle(board);
    const FRAMES: u32 = 40;
    let (mut w, mut ht) = (0u32, 0u32);
    // SAFETY: a live board and valid out-pointers.
    unsafe { assert_eq!(sst1_display_size(h.get(), &mut w, &mut ht), OK) };
    let pixels = (w * ht) as usize;
    std::thread::scope(|s| {
        s.spawn(move || {
            for frame in 0..FRAMES {
                // SAFETY: a live board (destroyed after the scope).
                unsafe {
                    assert_eq!(sst1_write32(h.get(), COLOR1, frame * 0x0004_0404), OK);
                    assert_eq!(sst1_write32(h.get(), FASTFILL_CMD, 0), OK);
                    assert_eq!(sst1_write32(h.get(), SWAPBUFFER_CMD, 0), OK);
                }
            }
        });
        s.spawn(move || {
            let mut buf = vec![0u16; pixels];
            for _ in 0..FRAMES {
                // SAFETY: a live board; `buf` holds `pixels` values.
                unsafe {
                    assert_eq!(
                        sst1_front_buffer_rgb565(
                            h.get(),
                            buf.as_mut_ptr(),
                            buf.len(),
                            std::ptr::null_mut(),
                            std::ptr::null_mut()
                        ),
                        OK
                    );
                }
                // A whole frame: every pixel one fill's colour.
                assert!(buf.iter().all(|&p| p == buf[0]), "a torn frame");
            }
        });
    });
    let mut swaps = 0;
    // SAFETY: a live board, then destroyed and not used again.
    unsafe {
        assert_eq!(sst1_swap_count(h.get(), &mut swaps), OK);
        assert_eq!(sst1_destroy(h.get()), OK);
    }
    assert_eq!(swaps, u64::from(FRAMES));
    assert_eq!(SWAPS_SEEN.load(Ordering::SeqCst), u64::from(FRAMES));
}

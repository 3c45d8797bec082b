//! Issue "Glide 3 as 3dfx shipped it", item 3: a write-only LFB lock of the back buffer
//! must reach the board with what the program stored, whatever the front buffer holds.
//! Before, the 16-bit shadow started as the front buffer and the 32-bit one as zeros,
//! and a stored word equal to that start was never sent: a black block stored into a
//! white back buffer over a black front buffer stayed white, in 565 and 888 alike.

use std::ffi::c_void;

use glide::consts::*;
use glide3::*;

/// Opens a 640x480 session, clears the front buffer black and the back buffer white,
/// stores a 16x16 black block at (100, 50) of the back buffer through a write lock in
/// `mode`, and returns the back buffer's pixels of the block's first row.
fn black_block_into_white_back_buffer(mode: u32) -> Vec<u16> {
    grGlideInit();
    grSstSelect(0);
    let ctx = grSstWinOpen(
        0,
        GR_RESOLUTION_640x480 as i32,
        GR_REFRESH_60Hz as i32,
        GR_COLORFORMAT_ARGB as i32,
        GR_ORIGIN_UPPER_LEFT as i32,
        2,
        1,
    );
    assert_ne!(ctx, 0);
    grRenderBuffer(GR_BUFFER_FRONTBUFFER as i32);
    grBufferClear(0x0000_0000, 0, 0xffff);
    grRenderBuffer(GR_BUFFER_BACKBUFFER as i32);
    grBufferClear(0x00ff_ffff, 0, 0xffff);
    let mut info = GrLfbInfo {
        size: std::mem::size_of::<GrLfbInfo>() as i32,
        lfb_ptr: std::ptr::null_mut(),
        stride_in_bytes: 0,
        write_mode: 0,
        origin: 0,
    };
    let ok = unsafe {
        grLfbLock(
            GR_LFB_WRITE_ONLY,
            GR_BUFFER_BACKBUFFER as i32,
            mode as i32,
            GR_ORIGIN_UPPER_LEFT as i32,
            0,
            &mut info,
        )
    };
    assert_eq!(ok, 1);
    let stride = info.stride_in_bytes as usize;
    for y in 50..66 {
        for x in 100..116 {
            // SAFETY: the lock's shadow spans 1024 rows of `stride` bytes.
            unsafe {
                let row = (info.lfb_ptr as *mut u8).add(y * stride);
                if mode == GR_LFBWRITEMODE_565 {
                    *(row as *mut u16).add(x) = 0x0000;
                } else {
                    *(row as *mut u32).add(x) = 0x0000_0000;
                }
            }
        }
    }
    assert_eq!(
        grLfbUnlock(GR_LFB_WRITE_ONLY, GR_BUFFER_BACKBUFFER as i32),
        1
    );
    let mut row = vec![0u16; 20];
    let ok = unsafe {
        grLfbReadRegion(
            GR_BUFFER_BACKBUFFER as i32,
            98,
            50,
            20,
            1,
            40,
            row.as_mut_ptr() as *mut c_void,
        )
    };
    assert_eq!(ok, 1);
    grSstWinClose(ctx);
    grGlideShutdown();
    row
}

#[test]
fn stores_into_the_back_buffer_arrive_in_565_and_888() {
    for mode in [GR_LFBWRITEMODE_565, GR_LFBWRITEMODE_888] {
        let row = black_block_into_white_back_buffer(mode);
        // Two white pixels left of the block, 16 black, two white right of it.
        let mut want = vec![0xffffu16; 2];
        want.extend([0u16; 16]);
        want.extend([0xffff, 0xffff]);
        assert_eq!(row, want, "write mode {mode:#x}");
    }
}

//! Issue "Glide 3 as 3dfx shipped it", item 3: every pixel a program stores through a
//! write-only LFB lock must reach the board, whatever the front buffer holds and
//! whatever the locked buffer holds. Before, the 16-bit shadow started as the front
//! buffer and the 32-bit one as zeros, and a stored word equal to that start was never
//! sent: a black block stored into a white back buffer over a black front buffer stayed
//! white, in 565 and 888 alike. Then the shadow started as the locked buffer, and a
//! store of the value a pixel already held was still dropped: a pipelined write, which
//! blends, never happened.
//!
//! Glide's state is per process: the tests here take turns.

use std::ffi::c_void;
use std::sync::Mutex;

use glide::consts::*;
use glide3::*;

static SERIAL: Mutex<()> = Mutex::new(());

fn lfb_info() -> GrLfbInfo {
    GrLfbInfo {
        size: std::mem::size_of::<GrLfbInfo>() as i32,
        lfb_ptr: std::ptr::null_mut(),
        stride_in_bytes: 0,
        write_mode: 0,
        origin: 0,
    }
}

/// The back buffer's 565 pixels of row `y`, columns `x..x + n`.
fn back_row(x: u32, y: u32, n: u32) -> Vec<u16> {
    let mut row = vec![0u16; n as usize];
    let ok = unsafe {
        grLfbReadRegion(
            GR_BUFFER_BACKBUFFER as i32,
            x,
            y,
            n,
            1,
            2 * n,
            row.as_mut_ptr() as *mut c_void,
        )
    };
    assert_eq!(ok, 1);
    row
}

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
    let _turn = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    for mode in [GR_LFBWRITEMODE_565, GR_LFBWRITEMODE_888] {
        let row = black_block_into_white_back_buffer(mode);
        // Two white pixels left of the block, 16 black, two white right of it.
        let mut want = vec![0xffffu16; 2];
        want.extend([0u16; 16]);
        want.extend([0xffff, 0xffff]);
        assert_eq!(row, want, "write mode {mode:#x}");
    }
}

/// Through a pipelined write lock with additive blending (dithering off), a pixel
/// stored with the value it already holds doubles: 565 0x4208 (8, 16, 8) becomes
/// 0x8410 (16, 32, 16); pixels not stored keep their value. (A lone 16-bit store
/// reaches the board as a 32-bit write with its neighbour read back, as every lone
/// 16-bit write of ours does: the bus carries 32-bit writes only, so with blending the
/// neighbour would blend too.)
#[test]
fn stores_of_the_value_a_pixel_holds_reach_the_board() {
    let _turn = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
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
    grDitherMode(GR_DITHER_DISABLE as i32);
    grRenderBuffer(GR_BUFFER_BACKBUFFER as i32);
    // 0x42, 0x41, 0x42 is 565 (8, 16, 8) exactly.
    grBufferClear(0x0042_4142, 0, 0xffff);
    assert_eq!(back_row(98, 50, 20), vec![0x4208; 20]);
    grAlphaBlendFunction(
        GR_BLEND_ONE as i32,
        GR_BLEND_ONE as i32,
        GR_BLEND_ONE as i32,
        GR_BLEND_ZERO as i32,
    );
    let mut info = lfb_info();
    let ok = unsafe {
        grLfbLock(
            GR_LFB_WRITE_ONLY,
            GR_BUFFER_BACKBUFFER as i32,
            GR_LFBWRITEMODE_565 as i32,
            GR_ORIGIN_UPPER_LEFT as i32,
            1,
            &mut info,
        )
    };
    assert_eq!(ok, 1);
    let stride = info.stride_in_bytes as usize;
    assert_eq!(stride, 2048);
    for x in 100..116 {
        // SAFETY: row 50 of the lock's 1024 rows of `stride` bytes.
        unsafe { *((info.lfb_ptr as *mut u8).add(50 * stride) as *mut u16).add(x) = 0x4208 };
    }
    assert_eq!(
        grLfbUnlock(GR_LFB_WRITE_ONLY, GR_BUFFER_BACKBUFFER as i32),
        1
    );
    let mut want = vec![0x4208u16; 2];
    want.extend([0x8410u16; 16]);
    want.extend([0x4208, 0x4208]);
    assert_eq!(back_row(98, 50, 20), want);
    assert_eq!(back_row(100, 51, 16), vec![0x4208; 16]);
    grSstWinClose(ctx);
    grGlideShutdown();
}

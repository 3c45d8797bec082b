//! Linear frame buffer access: locks, direct pixel access, region copies.
//!
//! Spec sections 4 (LFB address space at 0x400000) and 5 (`lfbMode`, `zaColor`).
//! Lock and unlock write the same registers as 3dfx's SST-1 Glide 3 (glfb.c): a
//! write lock loads `zaColor` with the constant depth/alpha, clears depth biasing in
//! `fbzMode` and selects buffer, format, origin and pixel pipeline in `lfbMode`.
//! Pixel data then travels as 32-bit aperture writes; the stride is 2048 bytes for
//! 16-bit formats and 4096 for 32-bit ones.

use crate::consts::*;
use crate::hw::LFB_BASE;
use sst1_regs::addr::*;
use sst1_regs::{ColorBuffer, FbzMode, LfbMode, LfbReadBuffer, LfbWriteFormat, ZaColor};

/// What a successful `grLfbLock` reports (`GrLfbInfo_t` without the pointer).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LfbInfo {
    /// Bytes from one row to the next.
    pub stride_in_bytes: u32,
    /// Effective `GR_LFBWRITEMODE_*` (write locks).
    pub write_mode: u32,
    /// `GR_ORIGIN_*`.
    pub origin: u32,
}

/// Bytes per pixel slot in the LFB for a write mode (16-bit modes pack two pixels
/// per word; 32-bit modes use one word per pixel).
pub fn stride_for(mode: u32) -> u32 {
    match mode {
        GR_LFBWRITEMODE_565 | GR_LFBWRITEMODE_555 | GR_LFBWRITEMODE_1555 | GR_LFBWRITEMODE_ZA16 => {
            2048
        }
        _ => 4096,
    }
}

/// Pixels per row and rows of the LFB window (spec section 4: x and y are 10-bit
/// fields of an LFB address). Region copies are clipped to it.
pub const LFB_WINDOW: u32 = 1024;

/// The lock slot (0 read, 1 write) of a `GrLock_t`, or `None` for a type that is neither
/// `GR_LFB_READ_ONLY` nor `GR_LFB_WRITE_ONLY` (with or without `GR_LFB_NOIDLE`).
pub fn lock_slot(ty: u32) -> Option<usize> {
    match ty & !GR_LFB_NOIDLE {
        GR_LFB_READ_ONLY => Some(0),
        GR_LFB_WRITE_ONLY => Some(1),
        _ => None,
    }
}

/// The part of a `width` x `height` region at (`x`, `y`) inside the LFB window, as
/// (width, height); zero when it lies wholly outside. 3dfx's library does not clip and
/// lets rows past the window run into texture and register space; the window is the
/// most any LFB address can reach.
pub fn clip_to_window(x: u32, y: u32, width: u32, height: u32) -> (u32, u32) {
    let width = width.min(LFB_WINDOW.saturating_sub(x));
    let height = height.min(LFB_WINDOW.saturating_sub(y));
    if width == 0 || height == 0 {
        (0, 0)
    } else {
        (width, height)
    }
}

impl crate::Glide {
    /// `grLfbLock`. `None` when the lock is refused (already locked, bad buffer or
    /// write mode). As in 3dfx's glfb.c, only a lock refused because one is held writes
    /// nothing: a read lock of a bad buffer still writes `lfbMode` (read buffer 0), and a
    /// write lock refused for its buffer or mode still writes `zaColor`, `lfbMode` (the
    /// mode's value ORed in as given, write buffer 0 for a bad buffer) and `fbzMode`.
    pub(crate) fn lfb_lock_hw(
        &mut self,
        ty: u32,
        buffer: u32,
        write_mode: u32,
        origin: u32,
        pipeline: bool,
    ) -> Option<LfbInfo> {
        self.validate();
        let ty = ty & !GR_LFB_NOIDLE;
        let slot = usize::from(ty == GR_LFB_WRITE_ONLY);
        if self.lfb_locks[slot].is_some() {
            return None;
        }
        let y_origin = origin != 0;
        if ty == GR_LFB_READ_ONLY {
            let sel = match buffer {
                GR_BUFFER_FRONTBUFFER => Some(LfbReadBuffer::Front),
                GR_BUFFER_BACKBUFFER => Some(LfbReadBuffer::Back),
                GR_BUFFER_AUXBUFFER => Some(LfbReadBuffer::Aux),
                _ => None,
            };
            let l = LfbMode(self.st.fbi.lfb_mode)
                .with_read_buffer_select(sel.unwrap_or(LfbReadBuffer::Front))
                .with_y_origin(y_origin);
            self.hw.w(LFB_MODE, l.0);
            self.st.fbi.lfb_mode = l.0;
            sel?;
            self.lfb_locks[slot] = Some(buffer);
            return Some(LfbInfo {
                stride_in_bytes: 2048,
                write_mode: l.write_format() as u32,
                origin,
            });
        }
        // The constant depth and alpha: grDepthBiasLevel shares the register.
        let za = ZaColor::default()
            .with_constant_depth(self.st.lfb_constant_depth as u16)
            .with_constant_alpha(self.st.lfb_constant_alpha);
        self.hw.w(ZA_COLOR, za.0);
        let mut granted = !((3..=11).contains(&write_mode)
            && write_mode != GR_LFBWRITEMODE_888
            && write_mode != GR_LFBWRITEMODE_8888);
        let (sel, mode) = match buffer {
            GR_BUFFER_FRONTBUFFER | GR_BUFFER_BACKBUFFER => {
                let m = if write_mode == GR_LFBWRITEMODE_ANY {
                    GR_LFBWRITEMODE_565
                } else {
                    write_mode
                };
                granted &= m != GR_LFBWRITEMODE_ZA16;
                let sel = if buffer == GR_BUFFER_BACKBUFFER {
                    ColorBuffer::Back
                } else {
                    ColorBuffer::Front
                };
                (sel, m)
            }
            GR_BUFFER_AUXBUFFER => {
                let m = if write_mode == GR_LFBWRITEMODE_ANY {
                    GR_LFBWRITEMODE_ZA16
                } else {
                    write_mode
                };
                granted &= m == GR_LFBWRITEMODE_ZA16;
                (ColorBuffer::Front, m)
            }
            // 3dfx's release build goes on with no buffer bits and the mode as given.
            _ => {
                granted = false;
                (ColorBuffer::Front, write_mode)
            }
        };
        let mut fbz = FbzMode(self.st.fbi.fbz_mode).with_enable_depth_bias(false);
        if pipeline {
            fbz = fbz.with_y_origin(y_origin);
        }
        // GR_LFBWRITEMODE_* is the hardware write format; glfb.c ORs the whole value in
        // at bit 0, so a value past 4 bits (GR_LFBWRITEMODE_ANY for a bad buffer) sets
        // the bits above the format too.
        let l = LfbMode(
            LfbMode(self.st.fbi.lfb_mode)
                .with_write_buffer_select(sel)
                .with_y_origin(y_origin)
                .with_write_format(LfbWriteFormat::from_bits(0))
                .with_enable_pixel_pipeline(pipeline)
                .0
                | mode,
        );
        self.hw.w(LFB_MODE, l.0);
        self.st.fbi.lfb_mode = l.0;
        self.hw.w(FBZ_MODE, fbz.0);
        if !granted {
            return None;
        }
        self.lfb_locks[slot] = Some(buffer);
        Some(LfbInfo {
            stride_in_bytes: stride_for(mode),
            write_mode: mode,
            origin,
        })
    }

    /// `grLfbUnlock`: restore depth bias and `fbzMode`. False if not locked.
    pub(crate) fn lfb_unlock_hw(&mut self, ty: u32, buffer: u32) -> bool {
        let slot = usize::from(ty & !GR_LFB_NOIDLE == GR_LFB_WRITE_ONLY);
        if self.lfb_locks[slot] != Some(buffer) {
            return false;
        }
        self.hw.w(ZA_COLOR, self.st.fbi.za_color);
        self.hw.w(FBZ_MODE, self.st.fbi.fbz_mode);
        self.lfb_locks[slot] = None;
        true
    }

    /// `grLfbWriteRegion` for every source format but RLE16. `src` holds
    /// `height` rows of `stride` bytes.
    pub(crate) fn lfb_write_region_hw(
        &mut self,
        buffer: u32,
        x: u32,
        y: u32,
        format: u32,
        width: u32,
        height: u32,
        pipeline: bool,
        stride: usize,
        src: &[u8],
    ) -> bool {
        if format == GR_LFB_SRC_FMT_RLE16 {
            return false;
        }
        let (width, height) = clip_to_window(x, y, width, height);
        let Some(info) = self.lfb_lock_hw(
            GR_LFB_WRITE_ONLY | GR_LFB_NOIDLE,
            buffer,
            format,
            GR_ORIGIN_UPPER_LEFT,
            pipeline,
        ) else {
            return false;
        };
        // Source bytes past `src` read as 0; offsets saturate instead of wrapping.
        let byte = |i: usize| u32::from(src.get(i).copied().unwrap_or(0));
        let half = |i: usize| byte(i) | (byte(i.saturating_add(1)) << 8);
        let word = |i: usize| half(i) | (half(i.saturating_add(2)) << 16);
        for row in 0..height {
            // Inside the window after clipping: y + row < 1024, x + width <= 1024.
            let s = (row as usize).saturating_mul(stride);
            let dst = LFB_BASE + (y + row) * info.stride_in_bytes;
            if info.stride_in_bytes == 2048 {
                let mut addr = dst + 2 * x;
                let mut i = 0usize;
                let len = 2 * width as usize;
                if addr & 2 != 0 && len >= 2 {
                    self.hw.w16(addr, half(s) as u16);
                    addr += 2;
                    i = 2;
                }
                while i + 4 <= len {
                    self.hw.w(addr, word(s.saturating_add(i)));
                    addr += 4;
                    i += 4;
                }
                if i + 2 <= len {
                    self.hw.w16(addr, half(s.saturating_add(i)) as u16);
                }
            } else {
                for k in 0..width {
                    self.hw
                        .w(dst + 4 * (x + k), word(s.saturating_add(4 * k as usize)));
                }
            }
        }
        self.lfb_unlock_hw(GR_LFB_WRITE_ONLY, buffer);
        true
    }

    /// `grLfbReadRegion`: 16-bit pixels of `buffer` into `dst` (`stride` bytes per row).
    pub(crate) fn lfb_read_region_hw(
        &mut self,
        buffer: u32,
        x: u32,
        y: u32,
        width: u32,
        height: u32,
        stride: usize,
        dst: &mut [u8],
    ) -> bool {
        let locked = self.lfb_lock_hw(
            GR_LFB_READ_ONLY,
            buffer,
            GR_LFBWRITEMODE_ANY,
            GR_ORIGIN_UPPER_LEFT,
            false,
        );
        // 3dfx's grLfbReadRegion locks through grLfbLock without GR_LFB_NOIDLE, which
        // ends with grFinish (`nopCMD`) granted or not; grLfbWriteRegion's lock is
        // GR_LFB_NOIDLE and writes none (glfb.c).
        self.finish();
        if locked.is_none() {
            return false;
        }
        let (width, height) = clip_to_window(x, y, width, height);
        for row in 0..height {
            for col in 0..width {
                let addr = LFB_BASE + (y + row) * 2048 + 2 * (x + col);
                let w = self.hw.r(addr & !3);
                let px = if addr & 2 != 0 { w >> 16 } else { w & 0xffff } as u16;
                let o = (row as usize)
                    .saturating_mul(stride)
                    .saturating_add(2 * col as usize);
                if let Some(d) = dst.get_mut(o..o.saturating_add(2)) {
                    d.copy_from_slice(&px.to_le_bytes());
                }
            }
        }
        self.lfb_unlock_hw(GR_LFB_READ_ONLY, buffer);
        true
    }

    /// One 32-bit write into the LFB aperture at byte `offset` (direct access while
    /// write-locked).
    pub fn lfb_write32(&mut self, offset: u32, value: u32) {
        self.hw.w(LFB_BASE + (offset & 0x3f_fffc), value);
    }

    /// One 16-bit write into the LFB aperture at byte `offset`.
    pub fn lfb_write16(&mut self, offset: u32, value: u16) {
        self.hw.w16(LFB_BASE + (offset & 0x3f_fffe), value);
    }

    /// One 32-bit read from the LFB aperture at byte `offset`.
    pub fn lfb_read32(&mut self, offset: u32) -> u32 {
        self.hw.r(LFB_BASE + (offset & 0x3f_fffc))
    }
}

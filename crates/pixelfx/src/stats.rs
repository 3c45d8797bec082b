//! Statistics counters (spec 5.31-5.35) and the emulator's own command counts.

use serde::{Deserialize, Serialize};

/// Why the pixel pipeline dropped a pixel. `pipeline.rs` turns these into counters.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Kill {
    /// Outside the clip rectangle.
    Clip,
    /// Stipple bit clear.
    Stipple,
    /// Depth test failed (`fbiZfuncFail`).
    DepthFunc,
    /// Chroma-key match (`fbiChromaFail`).
    Chroma,
    /// Alpha mask bit clear (`fbiAfuncFail`).
    AlphaMask,
    /// Alpha test failed (`fbiAfuncFail`).
    AlphaFunc,
}

/// The five hardware counters plus command counts. Hardware counters are 24 bits wide
/// when read through the bus; here they are kept in full.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Stats {
    /// `fbiPixelsIn`: pixels the triangle walker processed, drawn or not.
    pub pixels_in: u64,
    /// `fbiChromaFail`.
    pub chroma_fail: u64,
    /// `fbiZfuncFail`.
    pub zfunc_fail: u64,
    /// `fbiAfuncFail` (alpha test and alpha mask).
    pub afunc_fail: u64,
    /// `fbiPixelsOut`: pixels that reached the colour buffer write (mask ignored).
    pub pixels_out: u64,
    /// Triangle commands executed.
    pub triangles: u64,
    /// FASTFILL commands executed.
    pub fastfills: u64,
    /// SWAPBUFFER commands executed.
    pub swaps: u64,
    /// Scanline spans the triangle walker visited (rows with at least one pixel, clipped
    /// or not): what the timing model charges per row.
    pub spans: u64,
}

impl Stats {
    /// Count one killed pixel.
    #[inline]
    pub fn kill(&mut self, k: Kill) {
        match k {
            Kill::DepthFunc => self.zfunc_fail += 1,
            Kill::Chroma => self.chroma_fail += 1,
            Kill::AlphaMask | Kill::AlphaFunc => self.afunc_fail += 1,
            Kill::Clip | Kill::Stipple => {}
        }
    }

    /// Add `other`'s counts to these (the counters of bands shaded apart).
    pub fn add(&mut self, other: &Stats) {
        let Stats {
            pixels_in,
            chroma_fail,
            zfunc_fail,
            afunc_fail,
            pixels_out,
            triangles,
            fastfills,
            swaps,
            spans,
        } = *other;
        self.pixels_in += pixels_in;
        self.chroma_fail += chroma_fail;
        self.zfunc_fail += zfunc_fail;
        self.afunc_fail += afunc_fail;
        self.pixels_out += pixels_out;
        self.triangles += triangles;
        self.fastfills += fastfills;
        self.swaps += swaps;
        self.spans += spans;
    }

    /// Account for `count` pixels killed for the same reason.
    #[inline]
    pub fn kill_many(&mut self, k: Kill, count: u32) {
        let count = u64::from(count);
        match k {
            Kill::DepthFunc => self.zfunc_fail += count,
            Kill::Chroma => self.chroma_fail += count,
            Kill::AlphaMask | Kill::AlphaFunc => self.afunc_fail += count,
            Kill::Clip | Kill::Stipple => {}
        }
    }

    /// Clear the five hardware counters (`nopCMD` bit 0, spec 5.22).
    pub fn clear_hardware(&mut self) {
        self.pixels_in = 0;
        self.chroma_fail = 0;
        self.zfunc_fail = 0;
        self.afunc_fail = 0;
        self.pixels_out = 0;
    }
}

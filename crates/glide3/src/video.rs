//! Video timings and DAC clock synthesis for the SST-1 video modes.
//!
//! Spec section 5 (`hSync`, `vSync`, `backPorch`, `videoDimensions`, `fbiInit1..4`).
//! The per-mode numbers below are the timing table of 3dfx's SST-1 init library
//! (`sst1init.h`, `SST_VREZ_*`), read for facts; the PLL search is the one its
//! `sst1InitComputeClkParams` performs, reproduced in single precision so the chosen
//! M/N/P match what 3dfx's driver writes to the DAC.

use crate::consts::*;

/// One video mode's timing and memory-layout parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VideoTiming {
    /// Horizontal sync pulse width, in video clocks.
    pub h_sync_on: u32,
    /// Horizontal sync off time, in video clocks.
    pub h_sync_off: u32,
    /// Vertical sync pulse width, in lines.
    pub v_sync_on: u32,
    /// Vertical sync off time, in lines.
    pub v_sync_off: u32,
    /// Horizontal back porch, in video clocks.
    pub h_back_porch: u32,
    /// Vertical back porch, in lines.
    pub v_back_porch: u32,
    /// Visible width in pixels.
    pub x_dimension: u32,
    /// Visible height in lines.
    pub y_dimension: u32,
    /// Page offset of the second colour buffer (`fbiInit2` video buffer offset, in
    /// 4 KiB pages).
    pub mem_offset: u32,
    /// Memory FIFO entries (in 32-entry units) for 1, 2 and 4 MiB of frame buffer.
    pub mem_fifo_entries: [u32; 3],
    /// Tiles in X divided by 2 (`fbiInit1` bits 7:4).
    pub tiles_in_x_over2: u32,
    /// Video FIFO threshold (`fbiInit3` bits 5:1).
    pub v_fifo_threshold: u32,
    /// Whether 24-bit video output works at this mode.
    pub video24bpp_ok: bool,
    /// Pixel clock for 16-bit output, MHz.
    pub clk_freq_16bpp: f32,
    /// Pixel clock for 24-bit output, MHz.
    pub clk_freq_24bpp: f32,
}

const fn vt(
    h: [u32; 4],
    bp: [u32; 2],
    dim: [u32; 2],
    mem_offset: u32,
    fifo: [u32; 3],
    tiles: u32,
    vfifo: u32,
    ok24: bool,
    clk: [f32; 2],
) -> VideoTiming {
    VideoTiming {
        h_sync_on: h[0],
        h_sync_off: h[1],
        v_sync_on: h[2],
        v_sync_off: h[3],
        h_back_porch: bp[0],
        v_back_porch: bp[1],
        x_dimension: dim[0],
        y_dimension: dim[1],
        mem_offset,
        mem_fifo_entries: fifo,
        tiles_in_x_over2: tiles,
        v_fifo_threshold: vfifo,
        video24bpp_ok: ok24,
        clk_freq_16bpp: clk[0],
        clk_freq_24bpp: clk[1],
    }
}

// Source: sst1init.h SST_VREZ_* tables (3dfx SST-1 init library).
const V512X256_60: VideoTiming = vt(
    [41, 626, 4, 286],
    [65, 24],
    [512, 256],
    64,
    [0x410, 0x100, 0x100],
    8,
    23,
    true,
    [23.334, 23.334],
);
const V512X384_72: VideoTiming = vt(
    [51, 591, 3, 430],
    [55, 25],
    [512, 384],
    96,
    [0x410, 0x100, 0x100],
    8,
    23,
    true,
    [20.093, 40.186],
);
const V512X384_75: VideoTiming = vt(
    [44, 616, 3, 415],
    [55, 25],
    [512, 384],
    96,
    [0x410, 0x100, 0x100],
    8,
    23,
    true,
    [20.8, 41.6],
);
const V512X384_85: VideoTiming = vt(
    [55, 599, 3, 401],
    [70, 16],
    [512, 384],
    96,
    [0x410, 0x100, 0x100],
    8,
    23,
    true,
    [22.527, 45.054],
);
const V512X384_120: VideoTiming = vt(
    [25, 650, 3, 409],
    [110, 25],
    [512, 384],
    96,
    [0x410, 0x100, 0x100],
    8,
    20,
    true,
    [33.5, 67.0],
);
const V640X400_70: VideoTiming = vt(
    [96, 704, 2, 447],
    [48, 35],
    [640, 400],
    150,
    [0, 0x430, 0x100],
    10,
    21,
    true,
    [25.175, 50.350],
);
const V640X400_75: VideoTiming = vt(
    [99, 733, 3, 429],
    [52, 25],
    [640, 400],
    150,
    [0, 0x430, 0x100],
    10,
    19,
    true,
    [27.0, 54.0],
);
const V640X400_85: VideoTiming = vt(
    [63, 767, 3, 442],
    [94, 41],
    [640, 400],
    150,
    [0, 0x430, 0x100],
    10,
    18,
    true,
    [31.5, 63.0],
);
const V640X400_120: VideoTiming = vt(
    [67, 798, 3, 424],
    [94, 16],
    [640, 400],
    150,
    [0, 0x430, 0x100],
    10,
    18,
    true,
    [44.47, 88.94],
);
/// 640x480 at 60 Hz (VESA); also used by the init code to set up the memory layout.
pub(crate) const V640X480_60: VideoTiming = vt(
    [96, 704, 2, 523],
    [38, 25],
    [640, 480],
    150,
    [0, 0x430, 0x100],
    10,
    23,
    true,
    [25.175, 50.350],
);
const V640X480_75: VideoTiming = vt(
    [63, 775, 3, 497],
    [118, 16],
    [640, 480],
    150,
    [0, 0x430, 0x100],
    10,
    21,
    true,
    [31.5, 63.0],
);
const V640X480_85: VideoTiming = vt(
    [55, 776, 3, 506],
    [78, 25],
    [640, 480],
    150,
    [0, 0x430, 0x100],
    10,
    21,
    true,
    [36.0, 72.0],
);
const V640X480_120: VideoTiming = vt(
    [45, 785, 3, 506],
    [100, 18],
    [640, 480],
    150,
    [0, 0x430, 0x100],
    10,
    17,
    true,
    [50.82, 101.64],
);
/// 800x600 at 60 Hz; also used by the init code's frame-buffer sizing.
pub(crate) const V800X600_60: VideoTiming = vt(
    [127, 927, 4, 624],
    [86, 23],
    [800, 600],
    247,
    [0, 0x6e2, 0x100],
    13,
    14,
    true,
    [40.0, 80.0],
);
const V800X600_75: VideoTiming = vt(
    [79, 975, 3, 622],
    [158, 21],
    [800, 600],
    247,
    [0, 0x6e2, 0x100],
    13,
    14,
    true,
    [49.5, 99.0],
);
const V800X600_85: VideoTiming = vt(
    [63, 983, 3, 628],
    [150, 27],
    [800, 600],
    247,
    [0, 0x6e2, 0x100],
    13,
    14,
    true,
    [56.25, 112.5],
);
const V856X480_60: VideoTiming = vt(
    [136, 1008, 2, 523],
    [100, 23],
    [856, 480],
    210,
    [0, 0x430, 0x100],
    14,
    14,
    true,
    [36.0, 72.0],
);
const V960X720_60: VideoTiming = vt(
    [200, 1013, 4, 750],
    [30, 23],
    [960, 720],
    338,
    [0, 0, 0x765],
    15,
    14,
    true,
    [56.0, 112.0],
);

/// The monitor families the SST-1 init code distinguishes (its `sst1MonitorRez`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Monitor {
    R512x256,
    R512x384,
    R640x400,
    R640x480,
    R800x600,
    R856x480,
    R960x720,
}

/// A resolved video mode: timing, refresh in Hz and monitor family.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Mode {
    pub timing: VideoTiming,
    pub refresh_hz: u32,
    pub monitor: Monitor,
}

/// One `GrResolution` entry: a mode `grSstWinOpen` can open, as `grQueryResolutions`
/// lists it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Resolution {
    /// `GR_RESOLUTION_*`.
    pub resolution: u32,
    /// `GR_REFRESH_*`.
    pub refresh: u32,
    /// Colour buffers (2 or 3).
    pub color_buffers: u32,
    /// Auxiliary buffers (0 or 1).
    pub aux_buffers: u32,
}

/// Pixels per buffer of each resolution/refresh pair `grQueryResolutions` offers
/// (0: not offered), indexed `[GR_RESOLUTION_*][GR_REFRESH_*]`. Source: 3dfx's
/// SST-1 Glide 3 diget.c `_grResolutionRefresh`; it lists fewer modes than
/// `grSstWinOpen` accepts (no 512x256, 856x480, 960x720, 800x600 at 120 Hz).
const RESOLUTION_REFRESH: [[u32; 9]; 16] = {
    let mut t = [[0u32; 9]; 16];
    // Refresh order: 60, 70, 72, 75, 80, 90, 100, 85, 120 Hz.
    t[GR_RESOLUTION_512x384 as usize] = [196608, 0, 196608, 196608, 0, 0, 0, 196608, 196608];
    t[GR_RESOLUTION_640x400 as usize] = [0, 256000, 0, 256000, 0, 0, 0, 256000, 256000];
    t[GR_RESOLUTION_640x480 as usize] = [307200, 0, 0, 307200, 0, 0, 0, 307200, 307200];
    t[GR_RESOLUTION_800x600 as usize] = [480000, 0, 0, 480000, 0, 0, 0, 480000, 0];
    t
};

/// 4 KiB pages one buffer of each resolution occupies (65536: never fits). Source:
/// diget.c `_grMemOffset`.
const MEM_OFFSET: [u32; 16] = [
    65536, 65536, 65536, 96, 65536, 65536, 150, 150, 247, 338, 210, 64, 65536, 65536, 65536, 65536,
];

/// `grQueryResolutions`: every (resolution, refresh, colour buffers, aux buffers)
/// combination matching `template` (`None` = `GR_QUERY_ANY`; out-of-range values also
/// mean "any", as in diget.c) that fits in `fbi_mb` MiB: `pixels * 2 * buffers <
/// memory` and `buffers * pages < memory pages`, in 3dfx's loop order.
pub fn query_resolutions(
    fbi_mb: u32,
    resolution: Option<u32>,
    refresh: Option<u32>,
    color_buffers: Option<u32>,
    aux_buffers: Option<u32>,
) -> Vec<Resolution> {
    let pick = |v: Option<u32>, lo: u32, hi: u32| match v {
        Some(v) if (lo..=hi).contains(&v) => v..=v,
        _ => lo..=hi,
    };
    let fbmem = fbi_mb << 20;
    let pages = fbmem >> 12;
    let mut out = Vec::new();
    for res in pick(resolution, 0, 15) {
        for rr in pick(refresh, 0, 8) {
            let px = RESOLUTION_REFRESH[res as usize][rr as usize];
            if px == 0 {
                continue;
            }
            for col in pick(color_buffers, 2, 3) {
                for aux in pick(aux_buffers, 0, 1) {
                    let n = col + aux;
                    if px * 2 * n < fbmem && n * MEM_OFFSET[res as usize] < pages {
                        out.push(Resolution {
                            resolution: res,
                            refresh: rr,
                            color_buffers: col,
                            aux_buffers: aux,
                        });
                    }
                }
            }
        }
    }
    out
}

/// Resolve a `GR_RESOLUTION_*` / `GR_REFRESH_*` pair the way the SST-1 init code does
/// (unsupported refresh rates fall back to that resolution's default). `None` for
/// resolutions the SST-1 cannot display.
pub(crate) fn find_mode(resolution: u32, refresh: u32) -> Option<Mode> {
    let hz = match refresh {
        GR_REFRESH_60Hz => 60,
        GR_REFRESH_70Hz => 70,
        GR_REFRESH_72Hz => 72,
        GR_REFRESH_75Hz => 75,
        GR_REFRESH_80Hz => 80,
        GR_REFRESH_85Hz => 85,
        GR_REFRESH_90Hz => 90,
        GR_REFRESH_100Hz => 100,
        GR_REFRESH_120Hz => 120,
        _ => return None,
    };
    let (monitor, timing, hz) = match resolution {
        GR_RESOLUTION_512x256 => (Monitor::R512x256, V512X256_60, hz),
        GR_RESOLUTION_512x384 => match hz {
            120 => (Monitor::R512x384, V512X384_120, 120),
            85 => (Monitor::R512x384, V512X384_85, 85),
            75 => (Monitor::R512x384, V512X384_75, 75),
            // UNVERIFIED: 60 Hz needs SST_ARCADE in 3dfx's code; we never select it.
            _ => (Monitor::R512x384, V512X384_72, 72),
        },
        GR_RESOLUTION_640x400 => match hz {
            120 => (Monitor::R640x400, V640X400_120, 120),
            85 => (Monitor::R640x400, V640X400_85, 85),
            75 => (Monitor::R640x400, V640X400_75, 75),
            _ => (Monitor::R640x400, V640X400_70, 70),
        },
        GR_RESOLUTION_640x480 => match hz {
            120 => (Monitor::R640x480, V640X480_120, 120),
            85 => (Monitor::R640x480, V640X480_85, 85),
            75 => (Monitor::R640x480, V640X480_75, 75),
            _ => (Monitor::R640x480, V640X480_60, 60),
        },
        GR_RESOLUTION_800x600 => match hz {
            85 => (Monitor::R800x600, V800X600_85, 85),
            75 => (Monitor::R800x600, V800X600_75, 75),
            _ => (Monitor::R800x600, V800X600_60, 60),
        },
        GR_RESOLUTION_856x480 => (Monitor::R856x480, V856X480_60, 60),
        GR_RESOLUTION_960x720 => (Monitor::R960x720, V960X720_60, 60),
        _ => return None,
    };
    Some(Mode {
        timing,
        refresh_hz: hz,
        monitor,
    })
}

/// PLL parameters for one DAC clock (ICS5342 / ATT20C409 style M, N, P).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ClkParams {
    pub m: u32,
    pub n: u32,
    pub p: u32,
}

/// Choose M, N, P so that 14.318 MHz * (M+2) / ((N+2) * 2^P) is closest to `freq`,
/// with the VCO between 120 and 240 MHz. `None` when no divider fits.
///
/// Single-precision arithmetic in the same order as 3dfx's init library, so ties
/// resolve identically (matches every DAC write in the glide-sdk traces).
pub(crate) fn compute_clk(freq: f32) -> Option<ClkParams> {
    let mut p = 4u32;
    let mut divide = 0.0f32;
    for (k, d) in [(0u32, 1.0f32), (1, 2.0), (2, 4.0), (3, 8.0)] {
        let vco = freq * d;
        if (120.0..=240.0).contains(&vco) {
            divide = d;
            p = k;
        }
    }
    if p > 3 {
        return None;
    }
    // 1 / 14.318 as the init library writes it.
    let ratio = (freq * divide) * 0.069_842_16f32;
    let mut best = 9999.0f32;
    let (mut n, mut m) = (0u32, 0u32);
    for n_plus2 in 3u32..32 {
        let m_plus2 = ((n_plus2 as f32) * ratio + 0.5) as i32;
        let mut err = (m_plus2 as f32) / (n_plus2 as f32) - ratio;
        if err < 0.0 {
            err = -err;
        }
        if err < best && m_plus2 - 2 < 127 {
            best = err;
            n = n_plus2 - 2;
            m = (m_plus2 - 2) as u32;
        }
    }
    (n != 0).then_some(ClkParams { m, n, p })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pll_matches_trace_dac_writes() {
        // test00.trace.gz: 16 MHz bring-up clock writes M=0x7b, (P<<5)|N=0x6c.
        assert_eq!(
            compute_clk(16.0),
            Some(ClkParams {
                m: 0x7b,
                n: 0xc,
                p: 3
            })
        );
        // 48 MHz graphics clock: M=0x41, (P<<5)|N=0x43.
        assert_eq!(
            compute_clk(48.0),
            Some(ClkParams {
                m: 0x41,
                n: 3,
                p: 2
            })
        );
        // 640x480 24-bit pixel clock 50.35 MHz: M=0x7d, (P<<5)|N=0x47.
        assert_eq!(
            compute_clk(50.35),
            Some(ClkParams {
                m: 0x7d,
                n: 7,
                p: 2
            })
        );
    }

    #[test]
    fn unsupported_modes_resolve_to_none() {
        assert!(find_mode(GR_RESOLUTION_1024x768, GR_REFRESH_60Hz).is_none());
        assert!(find_mode(GR_RESOLUTION_640x480, 0x77).is_none());
        let m = find_mode(GR_RESOLUTION_640x480, GR_REFRESH_72Hz).unwrap();
        assert_eq!((m.refresh_hz, m.timing.x_dimension), (60, 640));
    }
}

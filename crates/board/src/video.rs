//! Video timing: the frame's period and vertical retrace from the video registers and
//! the pixel clock (spec section 10, 5.37-5.41, 5.43), for the timing model's retrace
//! and the `vRetrace` register.
//!
//! ```text
//!   one scan line  = (hSync_on + 1) + (hSync_off + 1) VCLKs          spec 10
//!   one frame      = vSync_off + vSync_on scan lines
//!   frame:  | vSync_off lines: vRetrace counts 0, 1, ... | vSync_on lines: retrace |
//! ```
//!
//! `backPorch` and `videoDimensions` place the picture inside the `vSync_off` lines
//! (spec 10: the porches and the active area lie between the syncs), so they change
//! neither the period nor the retrace.
//!
//! The VCLK comes from the DAC's PLL: the SST-1's DAC (an ICS5342 on 3dfx's reference
//! board, as 3dfx's init library programs it) is reached through `dacData` (spec 5.48),
//! and its clock 0 runs at `14.318 MHz * (M + 2) / ((N + 2) * 2^P)`. `fbiInit1` bits 21:20
//! (spec 5.43) say whether the video timing counts that clock (`vid_clk_2x_sel`, 16-bit
//! output) or half of it (`vid_clk_2x` / 2, 24-bit output). Until a trace programs the
//! PLL and selects it (and sets `hSync` and `vSync`), the frame lasts a sixtieth of a
//! second (UNVERIFIED: the spec's tables assume 640x480 at 60 Hz).

/// The PLL's reference crystal: 14.31818 MHz (four times the NTSC colour burst,
/// 157.5 MHz / 11), as a fraction of Hz.
const CRYSTAL_HZ: (u128, u128) = (157_500_000, 11);

/// Monitor refresh rate until the registers and the DAC set one. UNVERIFIED: the spec's
/// tables assume 640x480 at 60 Hz.
pub const REFRESH_HZ: u64 = 60;

/// Lines of vertical sync and of the whole frame when `vSync` is not set: VESA
/// 640x480 at 60 Hz (2 of 525).
const DEFAULT_VSYNC_LINES: (u64, u64) = (2, 525);

/// The 1/16-clock unit of the timing model.
const SUB: u128 = 16;

// ICS5342 registers reached through `dacData` bits 10:8 (3dfx's init library, sst1init.h).
/// PLL write address.
const ICS_PLL_WR_ADDR: u32 = 4;
/// PLL parameter data.
const ICS_PLL_DATA: u32 = 5;
/// PLL control (one byte, PLL address 0xe): bits 2:0 select clock 0's frequency
/// register, bit 5 selects them (rather than the clock-select pins).
const ICS_PLL_CTRL: usize = 0xe;
const ICS_PLLCTRL_CLK0SEL: u8 = 1 << 5;
const ICS_PLLCTRL_CLK0FREQ: u8 = 0x7;
/// `dacData` bit 11: a read of the DAC, not a write.
const DAC_READ: u32 = 1 << 11;

/// The DAC's PLL registers as the trace programs them: `(M, N/P)` byte pairs for the
/// clock registers 0x0-0xb, one byte for the control register 0xe.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub(crate) struct Dac {
    /// The PLL write address (auto-incremented).
    pub(crate) address: usize,
    /// The first byte of a pair, once written.
    pub(crate) first: Option<u8>,
    /// Each PLL register's `(M, P << 5 | N)`, once written.
    pub(crate) pll: [Option<(u8, u8)>; 16],
    /// The PLL control register, once written.
    pub(crate) control: Option<u8>,
}

impl Dac {
    /// A write of `dacData` (bits 7:0 data, 10:8 DAC register, 11 read).
    pub(crate) fn write(&mut self, value: u32) {
        if value & DAC_READ != 0 {
            return;
        }
        let data = (value & 0xff) as u8;
        match (value >> 8) & 7 {
            ICS_PLL_WR_ADDR => {
                self.address = usize::from(data & 0xf);
                self.first = None;
            }
            ICS_PLL_DATA if self.address == ICS_PLL_CTRL => {
                self.control = Some(data);
                self.address = (self.address + 1) & 0xf;
            }
            ICS_PLL_DATA => match self.first.take() {
                None => self.first = Some(data),
                Some(m) => {
                    self.pll[self.address] = Some((m, data));
                    self.address = (self.address + 1) & 0xf;
                }
            },
            _ => {}
        }
    }

    /// Clock 0's frequency in Hz as a fraction, once its register is programmed and
    /// selected by the control register.
    fn clock0_hz(&self) -> Option<(u128, u128)> {
        let control = self.control?;
        if control & ICS_PLLCTRL_CLK0SEL == 0 {
            return None;
        }
        let (m, np) = self.pll[usize::from(control & ICS_PLLCTRL_CLK0FREQ)]?;
        let (n, p) = (u128::from(np & 0x1f), u128::from(np >> 5 & 3));
        Some((
            CRYSTAL_HZ.0 * (u128::from(m) + 2),
            (CRYSTAL_HZ.1 * (n + 2)) << p,
        ))
    }
}

/// The video registers the frame depends on.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct VideoRegs {
    /// `hSync` (spec 5.38).
    pub h_sync: u32,
    /// `vSync` (spec 5.39).
    pub v_sync: u32,
    /// `fbiInit1` (spec 5.43: the VCLK source, bits 21:20).
    pub fbi_init1: u32,
}

/// One frame in time (1/16 graphics clock): the period, its lines, and the retrace at
/// its end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Frame {
    /// The frame's period.
    pub period: u64,
    /// Scan lines in the frame (`vSync_on + vSync_off`).
    pub lines: u64,
    /// Lines before the retrace (`vSync_off`), which `vRetrace` counts.
    pub lines_before_retrace: u64,
    /// The retrace's length, at the end of the frame.
    pub retrace: u64,
}

impl Frame {
    /// The frame of a board with graphics clock `clock_hz`, its video registers and DAC.
    pub(crate) fn new(clock_hz: u64, regs: VideoRegs, dac: &Dac) -> Self {
        let vsync = sst1_regs::VSync(regs.v_sync);
        let (on, off) = (u64::from(vsync.v_sync_on()), u64::from(vsync.v_sync_off()));
        let programmed = on + off != 0;
        let (on, lines) = if programmed {
            (on, on + off)
        } else {
            DEFAULT_VSYNC_LINES
        };
        let clock = u128::from(clock_hz);
        let refresh = || clock * SUB / u128::from(REFRESH_HZ);
        let period = match Self::vclk_hz(regs, dac) {
            Some((num, den)) if programmed && regs.h_sync != 0 => {
                let h = sst1_regs::HSync(regs.h_sync);
                let line = u128::from(h.active_clocks() + h.inactive_clocks());
                // clock * SUB * line * lines / (num / den) (1/16 clocks).
                clock * SUB * line * u128::from(lines) * den / num
            }
            _ => refresh(),
        };
        let period = u64::try_from(period).unwrap_or(u64::MAX).clamp(1, 1 << 48);
        let retrace = (u128::from(period) * u128::from(on) / u128::from(lines)) as u64;
        Self {
            period,
            lines,
            lines_before_retrace: lines - on,
            retrace,
        }
    }

    /// The VCLK the video timing counts, as a fraction of Hz: the DAC's clock 0, halved
    /// when `fbiInit1` selects `vid_clk_2x` / 2; `None` when unknown (not programmed,
    /// or the slave clock of a scan-line interleaved pair).
    fn vclk_hz(regs: VideoRegs, dac: &Dac) -> Option<(u128, u128)> {
        let (num, den) = dac.clock0_hz()?;
        match sst1_regs::FbiInit1(regs.fbi_init1).vclk_source_select() {
            1 => Some((num, den * 2)),
            2 | 3 => Some((num, den)),
            _ => None,
        }
    }

    /// The frame when nothing is programmed: a sixtieth of a second, 525 lines.
    pub(crate) fn power_on(clock_hz: u64) -> Self {
        Self::new(clock_hz, VideoRegs::default(), &Dac::default())
    }

    /// Whether the retrace is active at `t`.
    #[inline]
    pub(crate) fn retrace_at(self, t: u64) -> bool {
        (t + self.retrace) % self.period < self.retrace
    }

    /// The `vRetrace` register at `t` (spec 5.37: the internal `vSync_off` counter): the
    /// scan line since the end of the last vertical sync, 0 to `vSync_off - 1`; 0 during
    /// the sync (UNVERIFIED: the spec does not say what the counter holds then; MAME
    /// reads 0 in vertical blank).
    pub(crate) fn v_retrace(self, t: u64) -> u32 {
        let at = u128::from(t % self.period);
        let line = (at * u128::from(self.lines) / u128::from(self.period)) as u64;
        if line < self.lines_before_retrace && !self.retrace_at(t) {
            (line & 0xfff) as u32
        } else {
            0
        }
    }

    /// When a swap taken at `taken`, synchronised to retrace with `interval`
    /// (`swapbufferCMD` bits 8:1), happens: at a retrace (at once if one is active),
    /// and not before more than `interval` retraces have begun since the last swap
    /// (spec 5.24).
    pub(crate) fn swap_time(self, taken: u64, last_swap: u64, interval: u64) -> u64 {
        // In time shifted by the retrace's length, retraces begin at whole periods.
        let (p, a) = (self.period, self.retrace);
        let u = taken + a;
        let next = if u % p < a { u } else { (u / p + 1) * p };
        let counted = ((last_swap + a) / p + interval + 1) * p;
        next.max(counted) - a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The writes 3dfx's init library makes for 640x480 at 60 Hz with 24-bit output
    /// (glide3 `set_vid_clk(50.35)`: M = 0x7d, P << 5 | N = 0x47; control 0xf8).
    fn glide_640x480(dac: &mut Dac) {
        for v in [
            ICS_PLL_WR_ADDR << 8,
            ICS_PLL_DATA << 8 | 0x7d,
            ICS_PLL_DATA << 8 | 0x47,
            ICS_PLL_WR_ADDR << 8 | 0xe,
            ICS_PLL_DATA << 8 | 0xf8,
        ] {
            dac.write(v);
        }
    }

    #[test]
    fn the_frame_follows_the_registers_and_the_pll() {
        let regs = VideoRegs {
            h_sync: 0x02c0_0060, // hSync_on 96, hSync_off 704: 802 VCLKs a line
            v_sync: 0x020b_0002, // 2 of 525 lines
            fbi_init1: 1 << 20,  // vid_clk_2x / 2
        };
        // Nothing programmed: 60 Hz.
        let f = Frame::new(50_000_000, regs, &Dac::default());
        assert_eq!(f.period, 13_333_333);
        assert_eq!((f.lines, f.lines_before_retrace), (525, 523));
        assert_eq!(f, Frame::power_on(50_000_000));
        // The PLL: 14.31818 MHz * 127 / (9 * 4) = 50.5114 MHz, halved: 25.2557 MHz; a
        // frame of 802 * 525 VCLKs lasts 16.6715 ms (59.98 Hz): 833,574.75 clocks.
        let mut dac = Dac::default();
        glide_640x480(&mut dac);
        assert_eq!(dac.clock0_hz(), Some((157_500_000 * 127, 11 * 9 * 4)));
        let f = Frame::new(50_000_000, regs, &dac);
        // 50e6 * 16 * 802 * 525 * 11 * 36 * 2 / (157.5e6 * 127), floored.
        assert_eq!(f.period, 13_337_196);
        assert_eq!(f.retrace, 50_808);
        // 16-bit output counts the PLL's clock itself: half the period.
        let f16 = Frame::new(
            50_000_000,
            VideoRegs {
                fbi_init1: 3 << 20,
                ..regs
            },
            &dac,
        );
        assert_eq!(f16.period, 6_668_598);
        // The slave clock (source 0) is unknown: 60 Hz again.
        let slave = Frame::new(
            50_000_000,
            VideoRegs {
                fbi_init1: 0,
                ..regs
            },
            &dac,
        );
        assert_eq!(slave.period, 13_333_333);
    }

    #[test]
    fn v_retrace_counts_the_lines_before_the_sync() {
        let regs = VideoRegs {
            h_sync: 0x02c0_0060,
            v_sync: 0x020b_0002,
            fbi_init1: 1 << 20,
        };
        let mut dac = Dac::default();
        glide_640x480(&mut dac);
        let f = Frame::new(50_000_000, regs, &dac);
        let line = |n: u64| (u128::from(f.period) * u128::from(n)).div_ceil(525) as u64;
        assert_eq!(f.v_retrace(0), 0);
        assert_eq!(f.v_retrace(line(1) - 1), 0);
        assert_eq!(f.v_retrace(line(1)), 1);
        assert_eq!(f.v_retrace(line(240)), 240);
        assert_eq!(f.v_retrace(line(523) - 1), 522);
        // The retrace: lines 523 and 524 read 0, and status bit 6 reads it active.
        assert!(!f.retrace_at(line(523) - 1) && f.retrace_at(line(523)));
        assert_eq!(f.v_retrace(line(523)), 0);
        assert_eq!(f.v_retrace(f.period - 1), 0);
        // The next frame starts over.
        assert_eq!(f.v_retrace(f.period + line(100)), 100);
    }

    #[test]
    fn the_dac_ignores_reads_and_keeps_pairs() {
        let mut dac = Dac::default();
        dac.write(ICS_PLL_WR_ADDR << 8 | 0x1);
        dac.write(ICS_PLL_DATA << 8 | 0x11);
        dac.write(DAC_READ | ICS_PLL_DATA << 8); // a read: no byte
        dac.write(ICS_PLL_DATA << 8 | 0x22);
        dac.write(ICS_PLL_DATA << 8 | 0x33); // register 2's first byte
        assert_eq!(dac.pll[1], Some((0x11, 0x22)));
        assert_eq!(dac.pll[2], None);
        // Clock 0 selected but register 0 never written: unknown.
        dac.write(ICS_PLL_WR_ADDR << 8 | 0xe);
        dac.write(ICS_PLL_DATA << 8 | 0x20);
        assert_eq!(dac.clock0_hz(), None);
        // Frequency register 1 selected.
        dac.write(ICS_PLL_WR_ADDR << 8 | 0xe);
        dac.write(ICS_PLL_DATA << 8 | 0x21);
        // M = 0x11, P << 5 | N = 0x22: N = 2, P = 1.
        assert_eq!(dac.clock0_hz(), Some((157_500_000 * 0x13, (11 * 4) << 1)));
    }

    #[test]
    fn hostile_registers_give_a_usable_frame() {
        let mut dac = Dac::default();
        dac.write(ICS_PLL_WR_ADDR << 8);
        dac.write(ICS_PLL_DATA << 8 | 0xff);
        dac.write(ICS_PLL_DATA << 8); // the fastest clock: 14.3 MHz * 257 / 2
        dac.write(ICS_PLL_WR_ADDR << 8 | 0xe);
        dac.write(ICS_PLL_DATA << 8 | 0x20);
        for (h, v) in [(0, 0), (1, 1), (0xffff_ffff, 0xffff_ffff), (1, 0x0fff_0000)] {
            let regs = VideoRegs {
                h_sync: h,
                v_sync: v,
                fbi_init1: 3 << 20,
            };
            let f = Frame::new(50_000_000, regs, &dac);
            assert!(f.period >= 1 && f.retrace <= f.period, "{f:?}");
            let _ = (f.v_retrace(u64::MAX / 2), f.retrace_at(1 << 62));
            assert!(f.swap_time(1 << 62, 1 << 62, 255) >= 1 << 62);
        }
    }
}

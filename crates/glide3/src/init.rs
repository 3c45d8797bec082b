//! Board bring-up: the register writes 3dfx's SST-1 Glide makes in `grGlideInit`
//! (reset, DAC detection, clock set-up, memory sizing) and in `grSstWinOpen` (video
//! timing, memory FIFO, DAC clocks, screen clear, gamma).
//!
//! Spec sections 5 (`fbiInit0..4`, `trexInit0/1`, `dacData`, `clutData`) and 6 (PCI
//! `initEnable`). The sequence, values and order are those 3dfx's SST-1 init library
//! (glide3x/sst1/init/initvg) produces, checked write for write against the
//! glide-sdk traces (tests/init_trace.rs).
//!
//! 3dfx's code reads the chip back between writes (read-modify-write of the init
//! registers, DAC identification, frame-buffer and texture memory sizing). We keep a
//! shadow of what was written instead and take the branch a board of the configured
//! size would take, so the writes do not depend on what a (possibly partial) emulated
//! board answers. [`BoardInfo`] holds the answers the traced board gave.

use crate::hw::{tmu_chip, Hw, LFB_BASE, TEX_BASE};
use crate::video::{compute_clk, Mode, Monitor, VideoTiming, V640X480_60, V800X600_60};
use sst1_regs::addr::*;

/// What Glide's hardware probing finds on the board.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BoardInfo {
    /// Frame-buffer memory in MiB (1, 2 or 4).
    pub fbi_mb: u32,
    /// Number of TMUs (1 to 3).
    pub tmus: u32,
    /// Texture memory per TMU in MiB (1, 2 or 4).
    pub tmu_mb: u32,
    /// PCI revision of the FBI. UNVERIFIED: 2 (0.5 micron part) is what the traced
    /// board reported: its init writes `ft_clk_del = 8` into `fbiInit3`.
    pub fbi_revision: u32,
    /// TMU revision from the TMU configuration strap read-back. UNVERIFIED: 1 is what
    /// the traced board reported (texture download sequencing enabled, clock delay 6).
    pub tmu_revision: u32,
    /// Graphics clock in MHz derived from the board straps (48 on the traced board:
    /// the PLL write M=0x41 N=3 P=2).
    pub grx_clk_mhz: u32,
}

impl BoardInfo {
    /// The probe results for a board of the given memory sizes and TMU count, with the
    /// revision and clock answers of the board the glide-sdk traces were made on.
    pub fn new(fbi_mb: u32, tmus: u32, tmu_mb: u32) -> Self {
        Self {
            fbi_mb: match fbi_mb {
                0..=1 => 1,
                2..=3 => 2,
                _ => 4,
            },
            tmus: tmus.clamp(1, 3),
            tmu_mb: match tmu_mb {
                0..=1 => 1,
                2..=3 => 2,
                _ => 4,
            },
            fbi_revision: 2,
            tmu_revision: 1,
            grx_clk_mhz: 48,
        }
    }
}

// fbiInit bits (spec 5: fbiInit0..4).
const GRX_RESET: u32 = 1 << 1;
const PCI_FIFO_RESET: u32 = 1 << 2;
const EN_VGA_PASSTHRU: u32 = 1 << 0;
const PCI_FIFO_LWM_SHIFT: u32 = 6;
const PCI_FIFO_LWM: u32 = 0x1f << 6;
const EN_LFB_MEMFIFO: u32 = 1 << 11;
const EN_TEX_MEMFIFO: u32 = 1 << 12;
const MEM_FIFO_EN: u32 = 1 << 13;
const MEM_FIFO_HWM_SHIFT: u32 = 14;
const MEM_FIFO_HWM: u32 = 0x7ff << 14;
const MEM_FIFO_BURST_HWM_SHIFT: u32 = 25;
const MEM_FIFO_BURST_HWM: u32 = 0x3f << 25;
const PCI_WRWS_1: u32 = 1 << 1;
const LFB_READ_EN: u32 = 1 << 3;
const VIDEO_TILES_IN_X: u32 = 0xf << 4;
const VIDEO_RESET: u32 = 1 << 8;
const VIDEO_BLANK_EN: u32 = 1 << 12;
const VIDEO_MASK: u32 = 0x7e7f_fe00;
const VIDEO_OUTPUT_24BPP: u32 =
    (1 << 13) | (1 << 14) | (1 << 15) | (1 << 16) | (1 << 20) | (1 << 22);
const VIDEO_OUTPUT_16BPP: u32 = (1 << 13) | (1 << 14) | (1 << 15) | (1 << 16) | (3 << 20);
const VIDEO_VCLK_2X_OUTPUT_DEL_SHIFT: u32 = 27;
const VIDEO_VCLK_DEL_SHIFT: u32 = 29;
const VIDEO_FILTER_EN: u32 = 1 << 25;
const DRAM_BANKING_CONFIG: u32 = 1 << 1;
const EN_FAST_RAS_READ: u32 = 1 << 5;
const EN_FAST_RD_AHEAD_WR: u32 = 1 << 7;
const SWAP_ALGORITHM: u32 = 3 << 9;
const VIDEO_BUFFER_OFFSET_SHIFT: u32 = 11;
const VIDEO_BUFFER_OFFSET: u32 = 0x1ff << 11;
const EN_DRAM_BANKED: u32 = 1 << 20;
const EN_DRAM_RD_AHEAD_FIFO: u32 = 1 << 21;
const EN_DRAM_REFRESH: u32 = 1 << 22;
const DRAM_REFRESH_CNTR: u32 = 0x1ff << 23;
const DRAM_REFRESH_16MS: u32 = 0x30 << 23;
const ALT_REGMAPPING: u32 = 1 << 0;
const VIDEO_FIFO_THRESH_SHIFT: u32 = 1;
const VIDEO_FIFO_THRESH: u32 = 0x1f << 1;
const FT_CLK_DEL_SHIFT: u32 = 13;
const FT_CLK_DEL: u32 = 0xf << 13;
const TF_FIFO_THRESH_SHIFT: u32 = 17;
const TF_FIFO_THRESH: u32 = 0x1f << 17;
const YORIGIN_TOP_SHIFT: u32 = 22;
const YORIGIN_TOP: u32 = 0x3ff << 22;
const EN_LFB_RDAHEAD: u32 = 1 << 1;
const MEM_FIFO_ROW_BASE_SHIFT: u32 = 8;
const MEM_FIFO_ROW_ROLL_SHIFT: u32 = 18;
const MEM_FIFO_LWM_SHIFT: u32 = 2;
const MEM_FIFO_FIELDS: u32 = (0x3ff << 8) | (0x3ff << 18) | (0x3f << 2);

// Power-on defaults the init code loads (sst1init.h SST_FBIINITn_DEFAULT).
const FBIINIT0_DEFAULT: u32 = 0x0000_0410;
const FBIINIT1_DEFAULT: u32 = 0x0020_1102;
const FBIINIT2_DEFAULT: u32 = 0x8000_0040;
const FBIINIT3_DEFAULT: u32 = 0x001e_4000;
const FBIINIT4_DEFAULT: u32 = 0x0000_0001;
// trexInit0/1 defaults (EDO, 16-bit, refresh 0x20; FIFO stall levels 8, tf delay 0xf).
const TREXINIT0_DEFAULT: u32 = 0x5441;
const TREXINIT1_DEFAULT: u32 = 0xf420;
const TEX_TF_CLK_DEL: u32 = 0xf << 12;
const TEX_SEND_CONFIG: u32 = 1 << 18;

// PCI configuration offsets (spec 6).
const PCI_COMMAND: u32 = 0x04;
const PCI_INIT_ENABLE: u32 = 0x40;
const PCI_BUS_SNOOP0: u32 = 0x44;
const PCI_BUS_SNOOP1: u32 = 0x48;
const PCI_VCLK_ENABLE: u32 = 0xc0;
const PCI_VCLK_DISABLE: u32 = 0xe0;
const INITWR_EN: u32 = 1 << 0;
const PCI_FIFOWR_EN: u32 = 1 << 1;
const FBIINIT23_REMAP: u32 = 1 << 2;

// ICS5342 DAC, reached through dacData (bits 7:0 data, 10:8 register, 11 read).
const DAC_RD: u32 = 1 << 11;
const ICS_PLL_WR_ADDR: u32 = 4;
const ICS_PLL_DATA: u32 = 5;
const ICS_CMD: u32 = 6;
const ICS_PLL_RD_ADDR: u32 = 7;
const ICS_PLL_VCLK0: u32 = 0x0;
const ICS_PLL_VCLK1: u32 = 0x1;
const ICS_PLL_VCLK7: u32 = 0x7;
const ICS_PLL_GCLK0: u32 = 0xa;
const ICS_PLL_GCLK1: u32 = 0xb;
const ICS_PLL_CTRL: u32 = 0xe;
const ICS_PLLCTRL_CLK1SEL: u32 = 1 << 4;
const ICS_PLLCTRL_CLK0SEL: u32 = 1 << 5;
const ICS_PLLCTRL_CLK0FREQ: u32 = 0x7;
const ICS_COLORMODE_16BPP: u32 = 0x50;
const ICS_COLORMODE_24BPP: u32 = 0x70;
/// What the traced board's DAC answered for the PLL control register.
/// UNVERIFIED: inferred from the writes 0x5ef (= 0xff & !CLK1SEL) and 0x5f8.
const ICS_PLL_CTRL_READBACK: u32 = 0xff;

// Rendering-register values the probes use (spec 5 field encodings).
const FBZCP_RGBSEL_C1: u32 = 2;
const FBZCP_RGBSEL_TMU: u32 = 1;
const FBZCP_TEXTURE: u32 = 1 << 27;
const FBZ_RGBWRMASK: u32 = 1 << 9;
const FBZ_ZAWRMASK: u32 = 1 << 10;
const FBZ_ENDITHER: u32 = 1 << 8;
const FBZ_DRAWBUFFER_BACK: u32 = 1 << 14;
const LFB_FORMAT_ZZ: u32 = 0xf;
const LFB_WRITE_BACK: u32 = 1 << 4;
const LFB_READ_BACK: u32 = 1 << 6;
const LFB_READ_AUX: u32 = 2 << 6;
const TMODE_AI88: u32 = 0xd << 8;
const TMODE_RGB565: u32 = 0xa << 8;
/// `tc_zero_other | tc_add_clocal | tca_zero_other | tca_add_clocal`: texture replace.
const TMODE_REPLACE: u32 = (1 << 12) | (1 << 18) | (1 << 21) | (1 << 27);
const TMU_SEND_CONFIG_FRACTION: u32 = 18;

/// The index of an `fbiInit` register in [`InitState::fbi_init`].
#[derive(Clone, Copy)]
enum Fi {
    I0 = 0,
    I1 = 1,
    I2 = 2,
    I3 = 3,
    I4 = 4,
}

const FI_ADDR: [u32; 5] = [FBI_INIT0, FBI_INIT1, FBI_INIT2, FBI_INIT3, FBI_INIT4];

/// Shadow of the init registers and of the probe state that 3dfx's init library keeps
/// between calls.
#[derive(Clone, Debug)]
pub(crate) struct InitState {
    fbi_init: [u32; 5],
    tmu_init0: [u32; 3],
    tmu_init1: [u32; 3],
    /// The graphics clock is programmed only by the first `grSstWinOpen` after
    /// `grGlideInit` or a `grSstWinClose` (which sets it to 30 MHz).
    grx_clk_done: bool,
    /// The video clock is enabled only by the first gamma load.
    gamma_called: bool,
    /// Memory FIFO low-water mark reported to the command transport.
    pub mem_fifo_status_lwm: u32,
}

impl InitState {
    pub(crate) fn new() -> Self {
        Self {
            // What the traced board read back before any write: the defaults.
            fbi_init: [
                FBIINIT0_DEFAULT,
                FBIINIT1_DEFAULT,
                FBIINIT2_DEFAULT,
                FBIINIT3_DEFAULT,
                FBIINIT4_DEFAULT,
            ],
            tmu_init0: [TREXINIT0_DEFAULT; 3],
            tmu_init1: [TREXINIT1_DEFAULT; 3],
            grx_clk_done: false,
            gamma_called: false,
            mem_fifo_status_lwm: 0,
        }
    }
}

/// The init-time writer: the bus, the shadow and the board answers.
pub(crate) struct Init<'a> {
    pub hw: &'a mut Hw,
    pub st: &'a mut InitState,
    pub board: &'a BoardInfo,
}

impl Init<'_> {
    fn set(&mut self, r: Fi, v: u32) {
        self.st.fbi_init[r as usize] = v;
        self.hw.w(FI_ADDR[r as usize], v);
    }
    fn get(&self, r: Fi) -> u32 {
        self.st.fbi_init[r as usize]
    }
    fn or(&mut self, r: Fi, bits: u32) {
        self.set(r, self.get(r) | bits);
    }
    fn and_not(&mut self, r: Fi, bits: u32) {
        self.set(r, self.get(r) & !bits);
    }
    fn field(&mut self, r: Fi, mask: u32, value: u32) {
        self.set(r, (self.get(r) & !mask) | value);
    }
    /// `sst1InitIdle` / `sst1InitIdleFBI`: a NOP command, then status polling (reads).
    fn idle(&mut self) {
        self.hw.w(NOP_CMD, 0);
    }
    fn dac_wr(&mut self, reg: u32, data: u32) {
        self.hw.w(DAC_DATA, (data & 0xff) | (reg << 8));
    }
    fn dac_rd(&mut self, reg: u32) {
        self.hw.w(DAC_DATA, (reg << 8) | DAC_RD);
    }

    /// `grGlideInit` for one board: map, reset, detect and size it.
    pub(crate) fn power_on(&mut self) {
        // Enable memory decoding (PCI command register): only the first mapping of
        // the board does (Source: sezero/glide sst1init.c sst1InitMapBoard).
        self.hw.pci(PCI_COMMAND, 2);
        self.registers();
    }

    /// `sst1InitRegisters`: reset the graphics and video units, reload every init
    /// register, detect the DAC, size the memories and zero the rendering registers.
    /// `grGlideInit` runs it, and so does `grSstWinOpen` after a `grSstWinClose`
    /// (Source: sezero/glide gsst.c grSstWinOpen, `closedP`; init.c initMapBoard).
    /// The resets read the init registers back, so they start from what the last
    /// session left in them.
    pub(crate) fn registers(&mut self) {
        // The TMU init values are reloaded from their defaults each time
        // (Source: sezero/glide sst1init.c sst1InitRegisters).
        self.st.tmu_init0 = [TREXINIT0_DEFAULT; 3];
        self.st.tmu_init1 = [TREXINIT1_DEFAULT; 3];
        self.hw.pci(PCI_VCLK_DISABLE, 0);
        self.hw.pci(PCI_INIT_ENABLE, INITWR_EN);
        self.hw.pci(PCI_BUS_SNOOP0, 0);
        self.hw.pci(PCI_BUS_SNOOP1, 0);

        // FT clock delay for 16 MHz bring-up: 8 on revision-2 FBIs, 0xa otherwise;
        // TREX-to-FBI FIFO threshold 8.
        let ft_clk_del = if self.board.fbi_revision == 2 {
            0x8
        } else {
            0xa
        };
        let fbi_init3 = (FBIINIT3_DEFAULT & !(FT_CLK_DEL | TF_FIFO_THRESH))
            | (ft_clk_del << FT_CLK_DEL_SHIFT)
            | (0x8 << TF_FIFO_THRESH_SHIFT);
        self.set(Fi::I3, fbi_init3);

        // Reset video, then graphics and the PCI FIFO, then release them in order.
        self.or(Fi::I1, VIDEO_RESET);
        self.or(Fi::I0, GRX_RESET | PCI_FIFO_RESET);
        self.and_not(Fi::I0, PCI_FIFO_RESET);
        self.and_not(Fi::I0, GRX_RESET);

        self.set(Fi::I0, FBIINIT0_DEFAULT);
        self.set(Fi::I1, FBIINIT1_DEFAULT);
        self.set(Fi::I2, FBIINIT2_DEFAULT);
        self.set(Fi::I3, fbi_init3);
        self.set(Fi::I4, FBIINIT4_DEFAULT);
        self.hw.pci(PCI_INIT_ENABLE, INITWR_EN | PCI_FIFOWR_EN);

        self.dac_detect();

        for t in 0..3 {
            self.hw.w(tmu_chip(t) | TREX_INIT0, self.st.tmu_init0[t]);
            self.hw.w(tmu_chip(t) | TREX_INIT1, self.st.tmu_init1[t]);
        }

        // 16 MHz graphics clock while the TMU configuration is sensed.
        self.set_grx_clk(16.0);

        self.and_not(Fi::I1, PCI_WRWS_1);
        self.or(Fi::I1, LFB_READ_EN);
        self.field(Fi::I2, SWAP_ALGORITHM, 0); // swap on vsync
        self.or(Fi::I4, EN_LFB_RDAHEAD);
        self.or(Fi::I3, ALT_REGMAPPING);
        self.field(Fi::I2, DRAM_REFRESH_CNTR, DRAM_REFRESH_16MS);
        self.or(Fi::I2, EN_DRAM_REFRESH);
        self.or(
            Fi::I2,
            EN_FAST_RAS_READ | EN_DRAM_RD_AHEAD_FIFO | EN_FAST_RD_AHEAD_WR,
        );
        self.set_resolution(&V640X480_60, false);

        // Exercise the DRAMs: clear a 100x100 corner of front buffer and aux buffer.
        self.hw.w(COLOR1, 0);
        self.hw.w(COLOR0, 0);
        self.hw.w(ZA_COLOR, 0);
        self.hw.w(CLIP_LEFT_RIGHT, 100);
        self.hw.w(CLIP_LOW_Y_HIGH_Y, 100);
        self.hw.w(FBZ_MODE, FBZ_RGBWRMASK | FBZ_ZAWRMASK);
        self.hw.w(FASTFILL_CMD, 0);
        self.hw.w(NOP_CMD, 1);

        self.clear_rendering_registers();
        self.size_fbi_memory();
        self.sense_tmus();
        self.clear_rendering_registers();

        // LFB and texture writes go through the memory FIFO.
        self.or(Fi::I0, EN_LFB_MEMFIFO);
        self.or(Fi::I0, EN_TEX_MEMFIFO);
        for a in [
            V_RETRACE,
            BACK_PORCH,
            VIDEO_DIMENSIONS,
            H_SYNC,
            V_SYNC,
            MAX_RGB_DELTA,
        ] {
            self.hw.w(a, 0);
        }
    }

    /// `grSstWinClose` on an SST-1: idle the engine, then `sst1InitShutdown`: video
    /// in reset and blanked, DRAM refresh off, a graphics-engine and PCI FIFO reset,
    /// the monitor back to the VGA, the graphics clock down to 30 MHz, idle again.
    /// Source: sezero/glide gsst.c grSstWinClose (`initIdle`, `initRestoreVideo`)
    /// and sst1init.c sst1InitShutdown, sst1InitVgaPassCtrl; checked write for write
    /// against glide-sdk test30 (tests/reopen_trace.rs).
    pub(crate) fn close(&mut self) {
        self.idle();
        // sst1InitShutdown
        self.idle();
        self.or(Fi::I1, VIDEO_RESET | VIDEO_BLANK_EN);
        self.and_not(Fi::I2, EN_DRAM_REFRESH);
        self.or(Fi::I0, GRX_RESET | PCI_FIFO_RESET);
        self.and_not(Fi::I0, PCI_FIFO_RESET);
        self.and_not(Fi::I0, GRX_RESET);
        // The VGA drives the monitor: the pass-through bit takes the board's "enable"
        // sense (clear on the traced board; see `video`), and the SST-1 output blanks.
        self.and_not(Fi::I0, EN_VGA_PASSTHRU);
        self.or(Fi::I1, VIDEO_BLANK_EN);
        self.set_grx_clk(30.0);
        // The next grSstWinOpen programs the graphics clock again.
        self.st.grx_clk_done = false;
        self.idle();
    }

    /// `sst1InitRenderingRegisters`: zero every rendering register, then idle.
    fn clear_rendering_registers(&mut self) {
        for a in [
            VERTEX_AX, VERTEX_AY, VERTEX_BX, VERTEX_BY, VERTEX_CX, VERTEX_CY,
        ] {
            self.hw.w(a, 0);
        }
        for a in (START_R..=START_W).step_by(4) {
            self.hw.w(a, 0);
        }
        for a in (D_R_DX..=D_W_DX).step_by(4) {
            self.hw.w(a, 0);
        }
        for a in (D_R_DY..=D_W_DY).step_by(4) {
            self.hw.w(a, 0);
        }
        for a in [
            FBZ_COLOR_PATH,
            FOG_MODE,
            ALPHA_MODE,
            FBZ_MODE,
            LFB_MODE,
            CLIP_LEFT_RIGHT,
            CLIP_LOW_Y_HIGH_Y,
            FOG_COLOR,
            ZA_COLOR,
            CHROMA_KEY,
            STIPPLE,
            COLOR0,
            COLOR1,
        ] {
            self.hw.w(a, 0);
        }
        self.hw.w(NOP_CMD, 1);
        for a in (FOG_TABLE..=FOG_TABLE_LAST).step_by(4) {
            self.hw.w(a, 0);
        }
        for a in [
            TEXTURE_MODE,
            T_LOD,
            T_DETAIL,
            TEX_BASE_ADDR,
            TEX_BASE_ADDR_1,
            TEX_BASE_ADDR_2,
            TEX_BASE_ADDR_3_8,
        ] {
            self.hw.w(a, 0);
        }
        for i in 0..12 {
            self.hw.w(NCC_TABLE0 + 4 * i, 0);
            self.hw.w(NCC_TABLE1 + 4 * i, 0);
        }
        self.idle();
    }

    /// Enter the DAC access window: video in reset, refresh off, fbiInit2/3 remapped
    /// to the DAC. Returns the saved fbiInit1/fbiInit2.
    fn dac_window_open(&mut self) -> (u32, u32) {
        let saved = (self.get(Fi::I1), self.get(Fi::I2));
        self.or(Fi::I1, VIDEO_RESET);
        self.and_not(Fi::I2, EN_DRAM_REFRESH);
        self.hw.pci(PCI_INIT_ENABLE, INITWR_EN | FBIINIT23_REMAP);
        saved
    }

    fn dac_window_close(&mut self, saved: (u32, u32)) {
        self.hw.pci(PCI_INIT_ENABLE, INITWR_EN | PCI_FIFOWR_EN);
        self.set(Fi::I1, saved.0);
        self.set(Fi::I2, saved.1);
    }

    /// ICS5342 detection: read GCLK1, VCLK1 and VCLK7 back (the traced board answers
    /// the ICS defaults on the first try).
    fn dac_detect(&mut self) {
        let saved = self.dac_window_open();
        for pll in [ICS_PLL_GCLK1, ICS_PLL_VCLK1, ICS_PLL_VCLK7] {
            self.dac_wr(ICS_PLL_RD_ADDR, pll);
            self.dac_rd(ICS_PLL_DATA);
            self.dac_rd(ICS_PLL_DATA);
        }
        self.dac_window_close(saved);
    }

    /// Program the ICS graphics-clock PLL (GCLK0) with the graphics unit held in reset.
    fn set_grx_clk(&mut self, mhz: f32) {
        let Some(clk) = compute_clk(mhz) else {
            return;
        };
        self.or(Fi::I0, GRX_RESET | PCI_FIFO_RESET);
        let saved = self.dac_window_open();
        self.dac_wr(ICS_PLL_RD_ADDR, ICS_PLL_CTRL);
        self.dac_rd(ICS_PLL_DATA);
        self.dac_wr(ICS_PLL_WR_ADDR, ICS_PLL_GCLK0);
        self.dac_wr(ICS_PLL_DATA, clk.m);
        self.dac_wr(ICS_PLL_DATA, (clk.p << 5) | clk.n);
        self.dac_wr(ICS_PLL_WR_ADDR, ICS_PLL_CTRL);
        self.dac_wr(ICS_PLL_DATA, ICS_PLL_CTRL_READBACK & !ICS_PLLCTRL_CLK1SEL);
        self.dac_window_close(saved);
        self.and_not(Fi::I0, PCI_FIFO_RESET);
        self.and_not(Fi::I0, GRX_RESET);
        // First texture downloads after a clock change were lost on real boards; the
        // init library writes a dummy word high in texture space to flush them.
        self.hw.w(0xf0_0000, 0xdead_beef);
    }

    /// Program the ICS video-clock PLL (VCLK0) and select it.
    fn set_vid_clk(&mut self, mhz: f32) {
        let Some(clk) = compute_clk(mhz) else {
            return;
        };
        let saved = self.dac_window_open();
        self.dac_wr(ICS_PLL_RD_ADDR, ICS_PLL_CTRL);
        self.dac_rd(ICS_PLL_DATA);
        self.dac_wr(ICS_PLL_WR_ADDR, ICS_PLL_VCLK0);
        self.dac_wr(ICS_PLL_DATA, clk.m);
        self.dac_wr(ICS_PLL_DATA, (clk.p << 5) | clk.n);
        self.dac_wr(ICS_PLL_WR_ADDR, ICS_PLL_CTRL);
        self.dac_wr(
            ICS_PLL_DATA,
            (ICS_PLL_CTRL_READBACK & !ICS_PLLCTRL_CLK0FREQ) | ICS_PLLCTRL_CLK0SEL,
        );
        self.dac_window_close(saved);
    }

    fn set_vid_mode(&mut self, video16bpp: bool) {
        let saved = self.dac_window_open();
        self.dac_wr(
            ICS_CMD,
            if video16bpp {
                ICS_COLORMODE_16BPP
            } else {
                ICS_COLORMODE_24BPP
            },
        );
        self.dac_window_close(saved);
    }

    /// `sst1InitSetResolution`: buffer offset (and banking) in fbiInit2, tiles in X in
    /// fbiInit1.
    fn set_resolution(&mut self, t: &VideoTiming, banked: bool) {
        let mut v =
            (self.get(Fi::I2) & !VIDEO_BUFFER_OFFSET) | (t.mem_offset << VIDEO_BUFFER_OFFSET_SHIFT);
        if banked {
            v |= DRAM_BANKING_CONFIG | EN_DRAM_BANKED;
        }
        self.set(Fi::I2, v);
        self.field(Fi::I1, VIDEO_TILES_IN_X, t.tiles_in_x_over2 << 4);
    }

    fn lfb_put(&mut self, x: u32, y: u32, v: u16) {
        self.hw.w16(LFB_BASE + (x << 1) + (y << 11), v);
    }

    /// Frame-buffer sizing: write patterns that only survive with enough memory and
    /// read them back; the branch taken is the one a board with `fbi_mb` takes.
    fn size_fbi_memory(&mut self) {
        let saved = (self.get(Fi::I0), self.get(Fi::I1), self.get(Fi::I2));
        self.and_not(Fi::I0, MEM_FIFO_EN);
        self.or(Fi::I2, EN_DRAM_REFRESH);
        self.idle();
        self.hw.w(FBZ_COLOR_PATH, 0);
        self.hw.w(FOG_MODE, 0);
        self.hw.w(FBZ_MODE, FBZ_RGBWRMASK | FBZ_ZAWRMASK);
        self.idle();

        // 4 MiB: depth buffer at 800x600, banked.
        self.set_resolution(&V800X600_60, true);
        self.idle();
        self.hw.w(LFB_MODE, LFB_FORMAT_ZZ | LFB_READ_AUX);
        self.idle();
        for (x, y, v) in [
            (128, 100, 0xdead),
            (0, 0, 0),
            (798, 599, 0xffff),
            (200, 200, 0x55aa),
            (20, 20, 0xffff),
            (400, 400, 0),
        ] {
            self.lfb_put(x, y, v);
        }
        self.idle();
        if self.board.fbi_mb >= 4 {
            self.hw.w(LFB_MODE, LFB_READ_BACK);
            self.idle();
        } else {
            // 2 MiB: colour buffers at 640x480.
            self.set_resolution(&V640X480_60, false);
            self.hw.w(LFB_MODE, 0);
            self.idle();
            for (x, y, v) in [(50, 100, 0xdead), (0, 0, 0), (638, 479, 0xffff)] {
                self.lfb_put(x, y, v);
            }
            self.hw.w(LFB_MODE, LFB_WRITE_BACK);
            self.idle();
            for (x, y, v) in [(178, 436, 0xaa55), (20, 20, 0), (400, 400, 0xffff)] {
                self.lfb_put(x, y, v);
            }
            self.idle();
            // UNVERIFIED: which read-back fails on a 1 MiB board; we assume the first.
            if self.board.fbi_mb == 2 {
                self.hw.w(LFB_MODE, LFB_READ_BACK);
                self.idle();
            } else {
                self.hw.w(LFB_MODE, 0);
                self.idle();
                for (x, y, v) in [
                    (10, 10, 0xdead),
                    (8, 8, 0),
                    (340, 340, 0xffff),
                    (100, 200, 0x5a5a),
                    (66, 0, 0),
                    (360, 360, 0xffff),
                ] {
                    self.lfb_put(x, y, v);
                }
                self.idle();
            }
        }
        self.set(Fi::I0, saved.0);
        self.set(Fi::I1, saved.1);
        self.set(Fi::I2, saved.2);
        self.idle();
    }

    /// The right triangle the probes render: `size` pixels, S iterating 1 per pixel
    /// in X and T 1 per pixel in Y (14.18 fixed point).
    fn probe_triangle(&mut self, size: u32) {
        let one = 1 << TMU_SEND_CONFIG_FRACTION;
        for (a, v) in [
            (VERTEX_AX, 0),
            (VERTEX_AY, 0),
            (VERTEX_BX, size << 4),
            (VERTEX_BY, 0),
            (VERTEX_CX, 0),
            (VERTEX_CY, size << 4),
            (START_S, 0),
            (START_T, 0),
            (START_W, 0),
            (D_S_DX, one),
            (D_T_DX, 0),
            (D_W_DX, 0),
            (D_S_DY, 0),
            (D_T_DY, one),
            (D_W_DY, 0),
            (TRIANGLE_CMD, 0),
        ] {
            self.hw.w(a, v);
        }
    }

    /// Read back a 4x4 block of the front buffer (the reads are not bus writes).
    fn read_4x4(&mut self) {
        self.hw.w(LFB_MODE, 0);
        self.idle();
    }

    /// TMU revision/count sensing (undither tables, configuration strap read-back)
    /// and texture memory sizing.
    fn sense_tmus(&mut self) {
        // Build the undither table: 256 grey levels from color1.
        self.hw.w(FBZ_COLOR_PATH, FBZCP_RGBSEL_C1);
        self.hw.w(FBZ_MODE, FBZ_RGBWRMASK | FBZ_ENDITHER);
        for c in 0..=255u32 {
            self.hw.w(COLOR1, (c << 16) | (c << 8) | c);
            self.probe_triangle(36);
            self.read_4x4();
        }
        // Make every TMU output its configuration straps and render them.
        for t in 0..3 {
            self.hw.w(
                tmu_chip(t) | TREX_INIT1,
                self.st.tmu_init1[t] | TEX_SEND_CONFIG,
            );
        }
        self.hw.w(FBZ_COLOR_PATH, FBZCP_RGBSEL_TMU | FBZCP_TEXTURE);
        self.hw.w(TEX_BASE_ADDR, 0);
        self.hw.w(TEXTURE_MODE, TMODE_AI88);
        self.hw.w(T_LOD, 0);
        self.probe_triangle(36);
        self.read_4x4();
        for t in 0..3 {
            self.hw.w(tmu_chip(t) | TREX_INIT1, self.st.tmu_init1[t]);
        }
        for t in 0..self.board.tmus as usize {
            self.size_tmu_memory(t);
        }
    }

    /// Texture memory sizing for TMU `t`: write three sentinels at 2, 1 and 0 MiB and
    /// texture from the highest; try 4, then 2, then 1 MiB.
    fn size_tmu_memory(&mut self, t: usize) {
        self.hw.w(LFB_MODE, 0);
        self.hw.w(FBZ_MODE, FBZ_RGBWRMASK);
        self.hw.w(FBZ_COLOR_PATH, FBZCP_RGBSEL_TMU | FBZCP_TEXTURE);
        self.hw.w(TEXTURE_MODE, TMODE_RGB565 | TMODE_REPLACE);
        self.hw.w(T_LOD, 0);
        for downstream in 0..t {
            self.hw.w(tmu_chip(downstream) | TEXTURE_MODE, 0);
        }
        let tries: &[(u32, u32)] = match self.board.tmu_mb {
            4 => &[(0x20_0000, 0x5000)],
            2 => &[(0x20_0000, 0x5000), (0x10_0000, 0x2000)],
            _ => &[(0x20_0000, 0x5000), (0x10_0000, 0x2000), (0, 0x2000)],
        };
        for &(mem, init) in tries {
            self.sense(t, mem, init);
        }
    }

    fn sense(&mut self, t: usize, mem: u32, init: u32) {
        const SENSE: [u32; 3] = [0x92f5_6eb0, 0xf2a9_16b5, 0xbadb_eef1];
        let tex = TEX_BASE + ((t as u32) << 21);
        self.idle();
        self.hw.w(
            tmu_chip(t) | TREX_INIT0,
            init | (self.st.tmu_init0[t] & !0x7000),
        );
        self.idle();
        for (i, base) in [0x20_0000u32, 0x10_0000, 0].into_iter().enumerate() {
            self.hw.w(TEX_BASE_ADDR, base >> 3);
            self.hw.w(tex, SENSE[i]);
        }
        self.hw.w(TEX_BASE_ADDR, mem >> 3);
        self.probe_triangle(4);
        self.idle();
        self.idle();
        self.hw.w(tmu_chip(t) | TREX_INIT0, self.st.tmu_init0[t]);
        self.idle();
    }

    /// `sst1InitVideo`: program timing, memory FIFO, clocks and DAC for `mode`, clear
    /// the screen and hand the monitor to the SST-1.
    pub(crate) fn video(&mut self, mode: &Mode) {
        let t = mode.timing;
        let b = *self.board;
        // 24-bit output unless the mode needs 16-bit (Obsidian GE rules).
        let video16 = !t.video24bpp_ok
            || mode.refresh_hz >= 85
            || matches!(mode.monitor, Monitor::R800x600 | Monitor::R960x720);

        self.or(Fi::I1, VIDEO_RESET);
        self.hw.pci(PCI_VCLK_ENABLE, 0);
        self.hw.w(H_SYNC, (t.h_sync_off << 16) | t.h_sync_on);
        self.hw.w(V_SYNC, (t.v_sync_off << 16) | t.v_sync_on);
        self.hw
            .w(BACK_PORCH, (t.v_back_porch << 16) | t.h_back_porch);
        self.hw.w(
            VIDEO_DIMENSIONS,
            (t.y_dimension << 16) | (t.x_dimension - 1),
        );
        self.set_resolution(&t, b.fbi_mb == 4);

        let vfifo = if b.grx_clk_mhz < 45 {
            t.v_fifo_threshold - 4
        } else {
            t.v_fifo_threshold
        };
        self.field(Fi::I3, VIDEO_FIFO_THRESH, vfifo << VIDEO_FIFO_THRESH_SHIFT);
        self.field(
            Fi::I3,
            YORIGIN_TOP,
            (t.y_dimension - 1) << YORIGIN_TOP_SHIFT,
        );

        // Memory FIFO: low water mark 23, high 54, PCI FIFO low water 13.
        let (mem_lwm, mem_hwm, pci_lwm) = (23u32, 54u32, 13u32);
        self.and_not(Fi::I4, MEM_FIFO_FIELDS);
        let roll = match b.fbi_mb {
            1 => 0xff,
            2 => 0x1ff,
            _ => 0x3ff,
        };
        self.or(Fi::I4, roll << MEM_FIFO_ROW_ROLL_SHIFT);
        let small = (b.fbi_mb == 1
            && matches!(mode.monitor, Monitor::R512x384 | Monitor::R512x256))
            || (b.fbi_mb == 2 && matches!(mode.monitor, Monitor::R800x600 | Monitor::R856x480));
        let row_base = if small {
            2 * t.mem_offset
        } else {
            3 * t.mem_offset
        };
        self.or(Fi::I4, row_base << MEM_FIFO_ROW_BASE_SHIFT);
        self.or(Fi::I4, mem_lwm << MEM_FIFO_LWM_SHIFT);
        self.field(Fi::I0, PCI_FIFO_LWM, pci_lwm << PCI_FIFO_LWM_SHIFT);
        if !(b.fbi_mb == 1 && t.x_dimension > 512) {
            let entries = t.mem_fifo_entries[match b.fbi_mb {
                1 => 0,
                2 => 1,
                _ => 2,
            }];
            self.st.mem_fifo_status_lwm = (entries << 5) | 0x1f;
            self.field(
                Fi::I0,
                MEM_FIFO_EN | MEM_FIFO_HWM | PCI_FIFO_LWM | MEM_FIFO_BURST_HWM,
                (entries << MEM_FIFO_HWM_SHIFT)
                    | (pci_lwm << PCI_FIFO_LWM_SHIFT)
                    | (mem_hwm << MEM_FIFO_BURST_HWM_SHIFT)
                    | MEM_FIFO_EN,
            );
        }

        // Video clock delays: revision-2 FBIs use output delay 2, input delay 0.
        let rev2 = b.fbi_revision == 2;
        let v_in_del = if !rev2
            && !video16
            && (mode.monitor == Monitor::R960x720
                || (mode.monitor == Monitor::R640x480 && mode.refresh_hz == 120)
                || (mode.monitor == Monitor::R800x600 && mode.refresh_hz >= 75))
        {
            2
        } else {
            0
        };
        let v_out_del = if rev2 { 2 } else { 0 };
        let delays =
            (v_in_del << VIDEO_VCLK_DEL_SHIFT) | (v_out_del << VIDEO_VCLK_2X_OUTPUT_DEL_SHIFT);
        if video16 {
            self.field(Fi::I1, VIDEO_MASK, VIDEO_OUTPUT_16BPP | delays);
        } else {
            self.field(Fi::I1, VIDEO_MASK, VIDEO_OUTPUT_24BPP | delays);
            self.or(Fi::I1, VIDEO_FILTER_EN);
            self.hw.w(MAX_RGB_DELTA, 0x08_0408);
        }

        // FBI-to-TMU and TMU-to-FBI clock delays for the FBI/TMU revisions and clock.
        let (mut ft, mut tf) = match (rev2, b.tmu_revision == 1) {
            (true, true) => (0x5, 0x5),
            (true, false) => (0x5, 0xf),
            (false, true) => (0xa, 0x6),
            (false, false) => (0xa, 0xf),
        };
        if rev2 && b.tmu_revision == 1 {
            let d = match b.grx_clk_mhz {
                55.. => 0x4,
                50..=54 => 0x5,
                48..=49 => 0x6,
                45..=47 => 0x7,
                43..=44 => 0x8,
                _ => 0x9,
            };
            ft = d;
            tf = d;
        }
        self.field(Fi::I3, FT_CLK_DEL, ft << FT_CLK_DEL_SHIFT);
        for i in 0..3 {
            self.st.tmu_init1[i] = (self.st.tmu_init1[i] & !TEX_TF_CLK_DEL) | (tf << 12);
            self.hw.w(tmu_chip(i) | TREX_INIT1, self.st.tmu_init1[i]);
        }

        if !self.st.grx_clk_done {
            self.st.grx_clk_done = true;
            self.set_grx_clk(b.grx_clk_mhz as f32);
        }
        self.set_vid_mode(video16);
        self.set_vid_clk(if video16 {
            t.clk_freq_16bpp
        } else {
            t.clk_freq_24bpp
        });

        self.and_not(Fi::I1, VIDEO_RESET);
        self.or(Fi::I2, EN_DRAM_REFRESH);

        // Clear front, aux and back buffers to black.
        self.hw.w(COLOR1, 0);
        self.hw.w(COLOR0, 0);
        self.hw.w(ZA_COLOR, 0);
        self.hw.w(CLIP_LEFT_RIGHT, t.x_dimension);
        self.hw.w(CLIP_LOW_Y_HIGH_Y, t.y_dimension);
        self.hw.w(FBZ_MODE, FBZ_RGBWRMASK | FBZ_ZAWRMASK);
        self.hw.w(FASTFILL_CMD, 0);
        self.hw.w(FBZ_MODE, FBZ_RGBWRMASK | FBZ_DRAWBUFFER_BACK);
        self.hw.w(FASTFILL_CMD, 0);
        self.hw.w(NOP_CMD, 1);

        // SST-1 drives the monitor (VGA pass-through off, blanking off).
        // UNVERIFIED: boards with the power-on pass-through strap use the opposite bit
        // sense; the traced board did not.
        self.field(Fi::I0, EN_VGA_PASSTHRU, EN_VGA_PASSTHRU);
        self.and_not(Fi::I1, VIDEO_BLANK_EN);
        self.idle();
    }

    /// `sst1InitGammaRGB`: load the 33-entry gamma CLUT (every 8th entry of the
    /// 256-entry curve, plus white).
    pub(crate) fn gamma(&mut self, r: f64, g: f64, b: f64) {
        if !self.st.gamma_called {
            self.st.gamma_called = true;
            self.hw.pci(PCI_VCLK_ENABLE, 0);
        }
        let curve = |x: u32, gamma: f64| -> u32 {
            // Double precision as the init library computes it; truncating conversion
            // of (value + 0.5).
            let v = (f64::from(x) / 255.0).powf(1.0 / gamma) * 255.0 + 0.5;
            if v.is_finite() {
                v.clamp(0.0, 255.0) as u32
            } else {
                0
            }
        };
        self.and_not(Fi::I1, VIDEO_RESET);
        for x in 0..32u32 {
            let e = x << 3;
            self.hw.w(
                CLUT_DATA,
                (x << 24) | (curve(e, r) << 16) | (curve(e, g) << 8) | curve(e, b),
            );
        }
        self.hw.w(CLUT_DATA, (32 << 24) | 0xff_ffff);
    }

    /// `sst1InitGammaTable`: load caller-supplied entries (every 8th of the first
    /// 256) the same way.
    pub(crate) fn gamma_table(&mut self, red: &[u32], green: &[u32], blue: &[u32]) {
        if !self.st.gamma_called {
            self.st.gamma_called = true;
            self.hw.pci(PCI_VCLK_ENABLE, 0);
        }
        self.and_not(Fi::I1, VIDEO_RESET);
        let at = |t: &[u32], i: usize| t.get(i).copied().unwrap_or(0) & 0xff;
        for x in 0..32usize {
            let e = x << 3;
            self.hw.w(
                CLUT_DATA,
                ((x as u32) << 24) | (at(red, e) << 16) | (at(green, e) << 8) | at(blue, e),
            );
        }
        self.hw.w(CLUT_DATA, (32 << 24) | 0xff_ffff);
    }
}

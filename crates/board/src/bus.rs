//! Decoding of the PCI aperture (spec 4 and 5): register chip select and remapping,
//! the LFB and texture regions, and PCI configuration space (spec 6).

use crate::box86;
use crate::deferred;
use crate::diagnostics::Diagnostic;
use crate::model::{with_model, ChipModel};
use crate::timing::{MemoryFifo, TriangleWork};
use crate::video::VideoRegs;
use crate::Board;
use pixelfx::{Command, NoTexture};
use sst1_chain::Chain;
use sst1_regs::{addr, map, RegisterBus};
use texelfx::Tmu;

/// Start of the linear frame buffer region.
const LFB_BASE: u32 = 0x40_0000;
/// Start of the texture download region.
const TEX_BASE: u32 = 0x80_0000;
/// `initEnable` in PCI configuration space (spec 6).
const PCI_INIT_ENABLE: u32 = 0x40;

/// The aperture offset a bus address reaches (spec section 4): the card decodes the low
/// 24 bits of a memory address (its 16 MiB window) and, every access being 32 bits wide,
/// ignores bits 1:0 (no region's decode below reads them). A recorder logs this form, so
/// that a recorded trace replays as the access did.
pub const fn aperture_offset(bus_addr: u32) -> u32 {
    bus_addr & 0x00ff_fffc
}

/// Whether a write to a register is refused and which chips store it, by register
/// index (bits of a [`ROUTES`] entry), found at compile time from the register table
/// ([`map::desc_const`]): one load per write rather than a search of the table.
struct Route;

impl Route {
    /// No register: the write is refused.
    const RESERVED: u8 = 1;
    /// Read-only: the write is refused.
    const READ_ONLY: u8 = 2;
    /// `fbiInit0`-`fbiInit4`: refused unless PCI `initEnable` bit 0 is set (spec 6).
    const INIT: u8 = 4;
    /// Any of the three above: the write may be refused.
    const CHECKED: u8 = Self::RESERVED | Self::READ_ONLY | Self::INIT;
    /// The TMUs store it: the register table sends it to them and they keep something
    /// of it ([`texelfx::Tmu::stores`]; they keep nothing of the vertices and commands).
    const TREX: u8 = 8;
    /// The FBI stores it.
    const FBI: u8 = 16;
    /// The board follows it up after the FBI stores it: the video timing or the memory
    /// FIFO ([`Board::after_video_write`]).
    const VIDEO: u8 = 32;

    const fn of(offset: u32) -> u8 {
        let Some(desc) = map::desc_const(offset) else {
            return Self::RESERVED;
        };
        let mut route = 0;
        if !desc.access.contains(map::Access::WRITE) {
            route |= Self::READ_ONLY;
        }
        if matches!(offset, addr::FBI_INIT0..=addr::FBI_INIT3 | addr::FBI_INIT4) {
            route |= Self::INIT;
        }
        if desc.chips.contains(map::Chips::TREX) && texelfx::Tmu::stores(offset) {
            route |= Self::TREX;
        }
        if desc.chips.contains(map::Chips::FBI) {
            route |= Self::FBI;
        }
        if matches!(
            offset,
            addr::DAC_DATA
                | addr::H_SYNC
                | addr::V_SYNC
                | addr::FBI_INIT0
                | addr::FBI_INIT1
                | addr::FBI_INIT4
        ) {
            route |= Self::VIDEO;
        }
        route
    }
}

/// [`Route`] bits of every register index.
static ROUTES: [u8; 256] = {
    let mut routes = [0; 256];
    let mut i = 0;
    while i < 256 {
        routes[i] = Route::of(i as u32 * 4);
        i += 1;
    }
    routes
};

/// Whether a write to register index `i` only stores a triangle parameter (vertex,
/// start and gradient registers, fixed or float) in the FBI, the TMUs or both: found from
/// [`ROUTES`] (no check, no follow-up) and the parameter block's bounds. A run of such
/// writes is stored without the rest of the write path ([`Board::write32_all`]).
static PARAMETER_ONLY: [bool; 256] = {
    let mut only = [false; 256];
    let mut i = 0;
    while i < 256 {
        let offset = i as u32 * 4;
        let parameter = (offset >= addr::VERTEX_AX && offset <= addr::D_W_DY)
            || (offset >= addr::F_VERTEX_AX && offset <= addr::F_D_W_DY);
        only[i] = parameter && ROUTES[i] & !(Route::FBI | Route::TREX) == 0;
        i += 1;
    }
    only
};

/// Whether a bus write only stores a triangle parameter ([`PARAMETER_ONLY`]): in the
/// register region and not an address of the alternate map (bit 21), whose decode
/// depends on `fbiInit3`.
#[inline(always)]
fn parameter_only(bus_addr: u32) -> bool {
    let a = aperture_offset(bus_addr);
    a < 0x20_0000 && PARAMETER_ONLY[addr::index(a)]
}

/// The chips a register-region address selects (bits 13:10; 0 means all, spec 5).
#[inline(always)]
fn chip_mask(addr: u32) -> u32 {
    match (addr >> 10) & 0xf {
        0 => 0xf,
        chips => chips,
    }
}

/// Whether a write to FBI register `offset` (normal map) changes what the render thread
/// holds or adds to ([`crate::deferred`]): the frame buffer's layout and buffer indices
/// (init registers, `videoDimensions`), the counters (`nopCMD`), the fog table. The
/// commands settle on their own.
#[inline]
fn settles_render(offset: u32) -> bool {
    matches!(
        offset & 0x3fc,
        (addr::FOG_TABLE..=addr::FOG_TABLE_LAST)
            | addr::NOP_CMD
            | addr::FBI_INIT0
            | addr::FBI_INIT1
            | addr::FBI_INIT2
            | addr::FBI_INIT3
            | addr::FBI_INIT4
            | addr::VIDEO_DIMENSIONS
    )
}

impl Board {
    /// The normal-map register offset and chip mask of a register-region address.
    fn decode_register(&self, addr: u32) -> (u32, u32) {
        let chips = chip_mask(addr);
        let mut offset = addr & 0x3fc;
        // fbiInit3 bit 0 with address bit 21 selects the alternate triangle map (spec 5).
        let remap = self.fbi.reg(addr::FBI_INIT3) & 1 != 0;
        if remap && addr & 0x20_0000 != 0 {
            offset = map::remap_offset(offset);
        }
        (offset, chips)
    }

    /// A write that only stores a triangle parameter ([`parameter_only`]): what
    /// [`Board::write_register`] does with it (TMUs first), without its checks.
    #[inline(always)]
    fn write_parameter<M: ChipModel>(&mut self, bus_addr: u32, value: u32) {
        // Not an address of the alternate map: the decode of `decode_register` without
        // the remap.
        let chips = chip_mask(bus_addr);
        let offset = bus_addr & 0x3fc;
        let route = ROUTES[addr::index(offset)];
        if route & Route::TREX != 0 {
            self.tmu_register(chips, offset, value);
        }
        if chips & 1 != 0 && route & Route::FBI != 0 {
            let stored = self.fbi.write_parameter::<M>(offset, value);
            debug_assert!(stored, "{offset:#x}");
        }
    }

    /// A register write to the TMUs of `chips` (bits 1..=3), now or behind the triangles
    /// the render thread holds. Float S/T/W writes go to the TMUs as they are: the TMU
    /// keeps their 32 fraction bits (MAME, DOSBox Staging and 86Box all do).
    #[inline(always)]
    fn tmu_register(&mut self, chips: u32, offset: u32, value: u32) {
        if self.render_lent() {
            self.lent_tmu_register(chips, offset, value);
        } else if let Some(w) = texelfx::StwParams::decode(offset, value) {
            // Decoded once for every TMU the mask selects.
            for i in deferred::selected_tmus(chips) {
                if let Some(tmu) = self.tmus.get_mut(i) {
                    tmu.write_stw(w);
                }
            }
        } else {
            deferred::tmu_register(&mut self.tmus, [chips, offset, value]);
        }
    }

    /// A register write to the TMUs of `chips` while the render thread holds them: the
    /// S, T, W registers noted here for the next textured triangle, the rest queued.
    #[inline(always)]
    fn lent_tmu_register(&mut self, chips: u32, offset: u32, value: u32) {
        if let Some(w) = texelfx::StwParams::decode(offset, value) {
            self.lent_stw.write(chips, w);
        } else {
            self.lent_tmus(deferred::tmu_register, [chips, offset, value]);
        }
    }

    fn write_register<M: ChipModel>(&mut self, bus_addr: u32, value: u32) {
        let (offset, chips) = self.decode_register(bus_addr);
        let route = ROUTES[addr::index(offset)];
        if route & Route::CHECKED != 0 {
            if route & Route::RESERVED != 0 {
                self.diagnostics.note(Diagnostic::ReservedWrite);
                return;
            }
            if route & Route::READ_ONLY != 0 {
                self.diagnostics.note(Diagnostic::ReadOnlyWrite);
                return;
            }
            if self.init_enable & 1 == 0 {
                self.diagnostics.note(Diagnostic::InitWriteDisabled);
                return;
            }
        }
        // TMU writes first: a triangle command must see the TMUs' new state.
        if route & Route::TREX != 0 {
            self.tmu_register(chips, offset, value);
        }
        if chips & 1 == 0 || route & Route::FBI == 0 {
            return;
        }
        if self.render_lent() && settles_render(offset) {
            self.settle();
        }
        match self.fbi.write_reg::<M>(offset, value) {
            Command::None => {}
            Command::Triangle => self.triangle::<M>(),
            Command::Fastfill => self.fastfill::<M>(),
            Command::Swap => {
                self.settle();
                self.fbi.swap();
                if self.timing_on {
                    self.timing.swap(value);
                }
            }
        }
        if route & Route::VIDEO != 0 {
            self.after_video_write(offset, value);
        }
    }

    /// The frame's timing follows the video registers and the DAC (spec 10), the memory
    /// FIFO `fbiInit0` and `fbiInit4` (out of line: the other writes skip it with one
    /// test of their route).
    #[inline(never)]
    fn after_video_write(&mut self, offset: u32, value: u32) {
        // The timing model charges what is queued before its video changes.
        self.settle();
        match offset {
            addr::DAC_DATA => {
                self.dac.write(value);
                self.video_changed();
            }
            addr::H_SYNC | addr::V_SYNC | addr::FBI_INIT1 => self.video_changed(),
            addr::FBI_INIT0 | addr::FBI_INIT4 => {
                self.timing.set_memory_fifo(MemoryFifo::from_registers(
                    self.fbi.reg(addr::FBI_INIT0),
                    self.fbi.reg(addr::FBI_INIT4),
                    self.config.fbi_mb,
                ));
            }
            _ => {}
        }
    }

    /// Tells the timing model the video registers or the DAC changed.
    fn video_changed(&mut self) {
        let regs = VideoRegs {
            h_sync: self.fbi.reg(addr::H_SYNC),
            v_sync: self.fbi.reg(addr::V_SYNC),
            fbi_init1: self.fbi.reg(addr::FBI_INIT1),
        };
        self.timing.set_video(regs, &self.dac);
    }

    /// Run a triangle command with the TMU chain (spec 5.15). Out of line: the register
    /// writes before it stay a small function (measured on 10-pixel triangles: the write
    /// path saved and restored registers for the walk on every write).
    #[inline(never)]
    fn triangle<M: ChipModel>(&mut self) {
        let cp = sst1_regs::FbzColorPath(self.fbi.reg(addr::FBZ_COLOR_PATH));
        let init3 = sst1_regs::FbiInit3(self.fbi.reg(addr::FBI_INIT3));
        let texturing = cp.texture_enable() && !init3.disable_texture_mapping();
        let profile = M::pixel(&self.fbi.profile());
        // ParamOrigin::RoundedVertex (86Box): the correction lasts this triangle only.
        let restores = cp.param_adjust() && !profile.param_origin.writes_back();
        // A small triangle goes to the render thread (which then holds the TMUs too),
        // into this colour buffer; any other waits for what is queued there. The cheap
        // tests first: one thread computes nothing more.
        let deferred_dest = if !restores && self.deferring && self.fbi.threads() > 1 {
            self.fbi.deferrable::<M>().filter(|_| self.start_render())
        } else {
            None
        };
        let deferring = deferred_dest.is_some();
        if !deferring {
            self.settle();
        }
        let saved = restores.then(|| box86::StartRegisters::save(&self.fbi, &self.tmus));
        let mut tex_adjust = None;
        if cp.param_adjust() {
            let (dx, dy) = self
                .fbi
                .params
                .subpixel_adjust(profile.subpixel_z, profile.param_origin);
            if texturing {
                if deferring {
                    tex_adjust = Some((dx, dy));
                } else {
                    for t in &mut self.tmus {
                        t.subpixel_adjust(dx, dy);
                    }
                }
            }
        }
        let (pixels, spans) = if let Some(dest) = deferred_dest {
            let draw: pixelfx::DrawJob<Vec<Tmu>, _> = if texturing {
                deferred::draw_textured::<M>
            } else {
                pixelfx::draw_untextured::<M, Vec<Tmu>, _>
            };
            let job = self.fbi.triangle_job::<M, _, _>(dest, draw);
            // Timed when the render thread gives the memory back, from its walk's counts.
            let work = self.triangle_work(cp, texturing, 0, 0);
            self.defer_triangle(job, texturing, tex_adjust, work);
            return;
        } else {
            let before = self.fbi.stats;
            if texturing {
                for t in &mut self.tmus {
                    t.begin_triangle::<M>();
                }
                self.fbi
                    .draw_triangle::<M, _>(&mut Chain::<M>::new(&mut self.tmus));
            } else {
                self.fbi.draw_triangle::<M, _>(&mut NoTexture);
            }
            let after = self.fbi.stats;
            (
                after.pixels_in.wrapping_sub(before.pixels_in),
                after.spans.wrapping_sub(before.spans),
            )
        };
        if let Some(saved) = saved {
            saved.restore(&mut self.fbi, &mut self.tmus);
        }
        if self.timing_on {
            let work = self.triangle_work(cp, texturing, pixels, spans);
            self.timing.triangle(work);
        }
    }

    /// What the timing model charges for the triangle command in the registers that
    /// walked `pixels` pixels in `spans` rows.
    fn triangle_work(
        &self,
        cp: sst1_regs::FbzColorPath,
        textured: bool,
        pixels: u64,
        spans: u64,
    ) -> TriangleWork {
        let am = sst1_regs::AlphaMode(self.fbi.reg(addr::ALPHA_MODE));
        TriangleWork {
            pixels,
            spans,
            subpixel: cp.param_adjust(),
            textured,
            read_modify_write: self.fbi.fbz_mode().enable_depthbuffer() || am.alpha_blend_enable(),
        }
    }

    /// Run a FASTFILL command (spec 5.23) and charge its time (out of line, as
    /// [`Board::triangle`]).
    #[inline(never)]
    fn fastfill<M: ChipModel>(&mut self) {
        self.settle();
        let mode = self.fbi.fbz_mode();
        let (left, right, low, high) = self.fbi.clip_rect();
        let rows = (high - low).max(0) as u64;
        let writes = mode.rgb_buffer_mask() || mode.aux_buffer_mask();
        let pixels = if writes {
            rows * (right - left).max(0) as u64
        } else {
            0
        };
        self.fbi.fastfill::<M>();
        if self.timing_on {
            self.timing.fastfill(pixels, if writes { rows } else { 0 });
        }
    }

    fn write_texture(&mut self, bus_addr: u32, value: u32) {
        let rel = bus_addr - TEX_BASE;
        let tmu = (rel >> 21) & 3;
        if tmu >= self.config.tmus {
            self.diagnostics.note(Diagnostic::MissingTmu);
        } else if self.render_lent() {
            self.lent_tmus(deferred::tmu_texture, [tmu, rel, value]);
        } else {
            deferred::tmu_texture(&mut self.tmus, [tmu, rel, value]);
        }
    }
}

impl Board {
    /// A bus write, run by model `M` (the board's).
    fn write32_as<M: ChipModel>(&mut self, bus_addr: u32, value: u32) {
        if self.timing_on {
            self.time_write();
        }
        // Most of a triangle's writes: a shortcut past the register checks and commands.
        if parameter_only(bus_addr) {
            self.write_parameter::<M>(bus_addr, value);
        } else {
            self.write_other::<M>(bus_addr, value);
        }
    }

    /// A bus write that is not [`parameter_only`], after its time in the timing model.
    fn write_other<M: ChipModel>(&mut self, bus_addr: u32, value: u32) {
        let bus_addr = aperture_offset(bus_addr);
        if bus_addr < LFB_BASE {
            self.write_register::<M>(bus_addr, value);
        } else if bus_addr < TEX_BASE {
            self.settle();
            self.fbi.lfb_write::<M>(bus_addr - LFB_BASE, value);
        } else {
            self.write_texture(bus_addr, value);
        }
    }
}

impl Board {
    /// The bus writes `writes` (address, value), in order: as many
    /// [`RegisterBus::write32`] calls, with the model chosen once for them all (what a
    /// replay of a run of writes saves per write).
    pub fn write32_all(&mut self, writes: &[(u32, u32)]) {
        with_model!(self.kind, M => {
            // Writes that only store a triangle parameter (most of a triangle's) are
            // stored at once and timed as one run before the next other write: what
            // `write32_as` does per write adds up to the same, and nothing in between
            // reads either.
            let mut untimed = 0u32;
            for &(bus_addr, value) in writes {
                if parameter_only(bus_addr) {
                    self.write_parameter::<M>(bus_addr, value);
                    untimed += 1;
                    if untimed == u32::MAX {
                        self.time_run(&mut untimed);
                    }
                    continue;
                }
                self.time_run(&mut untimed);
                if self.timing_on {
                    self.time_write();
                }
                self.write_other::<M>(bus_addr, value);
            }
            self.time_run(&mut untimed);
        })
    }
}

impl Board {
    /// Charges the `untimed` parameter writes of [`Board::write32_all`] as one run, and
    /// zeroes the count.
    #[inline(always)]
    fn time_run(&mut self, untimed: &mut u32) {
        if *untimed > 0 && self.timing_on {
            self.time_writes(*untimed);
        }
        *untimed = 0;
    }
}

impl RegisterBus for Board {
    fn write32(&mut self, bus_addr: u32, value: u32) {
        // The one run-time choice of model: every stage below is compiled for it.
        with_model!(self.kind, M => self.write32_as::<M>(bus_addr, value))
    }

    fn read32(&mut self, bus_addr: u32) -> u32 {
        self.settle();
        if self.timing_on {
            self.timing.read();
        }
        let bus_addr = aperture_offset(bus_addr);
        if bus_addr < LFB_BASE {
            // Reads ignore the chip field and always come from the FBI (spec 5).
            let (offset, _) = self.decode_register(bus_addr);
            let value = match map::desc_of(offset) {
                Some(d) if d.access.contains(map::Access::READ) => self.fbi.read_reg(offset),
                _ => {
                    self.diagnostics.note(Diagnostic::WriteOnlyRead);
                    self.fbi.read_reg(offset)
                }
            };
            match offset & 0x3fc {
                _ if !self.timing_on => value,
                // FIFO, busy, retrace and swap bits from the timing model.
                addr::STATUS => self.timing.status(value),
                // The scan line from the video timing (spec 5.37).
                addr::V_RETRACE => self.timing.v_retrace(),
                _ => value,
            }
        } else if bus_addr < TEX_BASE {
            self.fbi.lfb_read(bus_addr - LFB_BASE)
        } else {
            // Texture memory is write-only (spec 9).
            0xffff_ffff
        }
    }

    fn host_wait(&mut self, cycles: u64) {
        self.settle();
        if self.timing_on {
            self.timing.host_wait(cycles);
        }
    }

    fn pci_write(&mut self, offset: u32, value: u32) {
        if offset == PCI_INIT_ENABLE {
            self.init_enable = value;
        } else {
            self.diagnostics.note(Diagnostic::UnmodelledPci);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BoardConfig;

    #[test]
    fn routes_follow_the_register_table() {
        for index in 0..256u32 {
            let offset = index * 4;
            let route = ROUTES[index as usize];
            match map::desc_of(offset) {
                None => assert_eq!(route, Route::RESERVED, "{offset:#x}"),
                Some(d) => {
                    let writable = d.access.contains(map::Access::WRITE);
                    assert_eq!(route & Route::READ_ONLY == 0, writable, "{offset:#x}");
                    let trex = d.chips.contains(map::Chips::TREX);
                    let stored = texelfx::Tmu::stores(offset);
                    assert!(
                        trex || !stored,
                        "{offset:#x}: a TMU keeps a register it is not sent"
                    );
                    assert_eq!(route & Route::TREX != 0, trex && stored, "{offset:#x}");
                    let fbi = d.chips.contains(map::Chips::FBI);
                    assert_eq!(route & Route::FBI != 0, fbi, "{offset:#x}");
                }
            }
        }
        assert_eq!(ROUTES.iter().filter(|&&r| r & Route::INIT != 0).count(), 5);
    }

    #[test]
    fn a_run_of_writes_is_the_writes_one_by_one() {
        // Pseudo-random writes over the whole aperture (registers of every chip field,
        // LFB, texture memory; commands that draw replaced by NOPs, so that no random
        // triangle or fill runs) given to one board in runs and to another one at a time:
        // the same state, timing model included.
        let mut runs = Board::new(BoardConfig::default());
        let mut single = Board::new(BoardConfig::default());
        for b in [&mut runs, &mut single] {
            b.pci_write(PCI_INIT_ENABLE, 1);
        }
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut writes = Vec::new();
        for _ in 0..20_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let addr = match seed % 10 {
                0 => LFB_BASE + (seed >> 8) as u32 % 0x40_0000,
                1 => TEX_BASE + (seed >> 8) as u32 % 0x80_0000,
                _ => (seed >> 8) as u32 & 0x3f_fffc,
            };
            let draws = matches!(
                addr & 0x3fc,
                addr::TRIANGLE_CMD | addr::F_TRIANGLE_CMD | addr::FASTFILL_CMD
            );
            let addr = if draws { addr::NOP_CMD } else { addr };
            writes.push((addr, (seed >> 32) as u32));
        }
        for run in writes.chunks(37) {
            runs.write32_all(run);
        }
        for &(addr, value) in &writes {
            single.write32(addr, value);
        }
        assert_eq!(runs.save_state(), single.save_state());
        assert!(runs.diagnostics().iter().eq(single.diagnostics().iter()));
        assert!(single.fbi.stats.triangles == 0 && !single.diagnostics().is_empty());
    }

    #[test]
    fn refused_writes_are_counted_and_change_nothing() {
        let mut board = Board::new(BoardConfig::default());
        let fbz_mode = addr::FBZ_MODE;
        board.write32(fbz_mode, 0x10);
        // A reserved word, a read-only register, and fbiInit1 before initEnable.
        board.write32(0x3fc, 1);
        board.write32(addr::FBI_PIXELS_IN, 5);
        board.write32(addr::FBI_INIT1, 0x1234);
        let d = board.diagnostics();
        assert_eq!(d.count(Diagnostic::ReservedWrite), 1);
        assert_eq!(d.count(Diagnostic::ReadOnlyWrite), 1);
        assert_eq!(d.count(Diagnostic::InitWriteDisabled), 1);
        assert_eq!(board.fbi.reg(addr::FBI_INIT1), 0);
        assert_eq!(board.fbi.reg(fbz_mode), 0x10);
        // With initEnable bit 0 the init write is taken.
        board.pci_write(PCI_INIT_ENABLE, 1);
        board.write32(addr::FBI_INIT1, 0x1234);
        assert_eq!(board.fbi.reg(addr::FBI_INIT1), 0x1234);
        assert_eq!(board.diagnostics().count(Diagnostic::InitWriteDisabled), 1);
    }
}

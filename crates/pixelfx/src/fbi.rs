//! The Pixelfx (FBI) chip: its register file and the commands it executes
//! (spec 5: register table; 5.22-5.24 commands; 5.36 fogTable; 5.41-5.46 init).
//!
//! The board decodes the aperture (chip select, remap, init enable) and calls
//! [`Fbi::write_reg`] with a normal-map byte offset. Register writes that start work
//! return a [`Command`], which the board runs with the TMU chain at hand.

use sst1_dither::Dither;
use sst1_fog::FogTable;
use sst1_regs::{
    addr, map, ClipLeftRight, ClipLowYHighY, ColorBuffer, FbiInit1, FbiInit2, FbiInit3, FbzMode,
    VideoDimensions,
};

use crate::fb::FrameBuffer;
use crate::model::PixelModel;
use crate::params::TriangleParams;
use crate::profile::{GraphicsReset, PixelProfile};
use crate::stats::Stats;

/// Work a register write asks the board to do.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// Nothing beyond storing the value.
    None,
    /// `triangleCMD` / `ftriangleCMD`: draw the triangle in the parameter registers.
    Triangle,
    /// `fastfillCMD`.
    Fastfill,
    /// `swapbufferCMD`.
    Swap,
}

/// The Pixelfx chip.
pub struct Fbi {
    /// The register file, indexed by normal-map register number (offset / 4).
    pub(crate) regs: [u32; 256],
    /// The triangle parameter registers, kept in their fixed-point formats.
    pub params: TriangleParams,
    /// Frame-buffer memory and layout.
    pub fb: FrameBuffer,
    /// The fog table (spec 5.36).
    pub fog_table: FogTable,
    /// Statistics counters.
    pub stats: Stats,
    /// The disputed-behaviour switches held at run time: what the run-time-profile model
    /// ([`crate::model::RuntimeProfile`]) reads, and the fixed models' own profile (the
    /// board keeps the two in step).
    pub(crate) profile: PixelProfile,
    /// Dither tables for the profile's 2x2 matrix.
    pub(crate) dither: Dither,
    /// Force the reference path (the pipeline pixel by pixel); see [`Fbi::set_generic_path`].
    pub(crate) generic_path: bool,
    /// Which path shaded the triangles' pixels.
    pub path_counts: PathCounts,
    /// Render threads for large triangles ([`Fbi::set_threads`]).
    pub(crate) threads: usize,
    /// The render threads other than the calling one (`threads - 1` of them; `None`
    /// with one render thread).
    pub(crate) helpers: Option<std::sync::Arc<crate::helpers::Helpers>>,
    /// The copy of the span kernels that runs ([`Fbi::set_vector_isa`]).
    pub(crate) isa: crate::VectorIsa,
    /// The pixel whose history is recorded ([`Fbi::set_watch`]), if any.
    pub(crate) watch: Option<Box<crate::watch::PixelWatch>>,
    /// The lanes of packed chunks, kept from triangle to triangle so that a triangle does
    /// not build them anew (`crate::raster::Pack`; nothing in them outlives a triangle).
    pub(crate) pack: Option<Box<crate::raster::Pack>>,
    /// The constants the span kernels spread over their lanes, kept from triangle to
    /// triangle and rebuilt when the registers they come from change
    /// (`crate::span::TriangleConsts::update`).
    pub(crate) consts: Option<Box<crate::span::TriangleConsts>>,
}

/// How many triangle pixels (inside the clip rectangle) each path shaded: what
/// `voodoo replay --stats` reports, so that a state the fast path does not cover would
/// show. Not a hardware counter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct PathCounts {
    /// By the span kernels ([`crate::span`]).
    pub span_kernels: u64,
    /// Of those, on the render threads, in bands of rows ([`Fbi::set_threads`]).
    pub in_bands: u64,
    /// Of those, in chunks packed from several short rows of a triangle
    /// (`crate::span::Packed`).
    pub packed: u64,
    /// Pixel by pixel because colour and aux words of different lanes alias (a buffer
    /// layout no driver sets; [`crate::span`]).
    pub aliased_layout: u64,
    /// Pixel by pixel on the fast path because their row is so short that a chunk would
    /// cost more (`SHORT_ROW` in raster.rs): the same stages, one pixel at a time.
    pub short_rows: u64,
    /// Pixel by pixel because the reference path was forced ([`Fbi::set_generic_path`]).
    pub reference: u64,
    /// Of all the above, of small triangles shaded on the render thread while the
    /// calling thread went on with the writes after them ([`crate::deferred`]).
    pub behind_writes: u64,
}

impl PathCounts {
    /// Add `other`'s counts to these.
    pub fn add(&mut self, other: &PathCounts) {
        self.span_kernels += other.span_kernels;
        self.in_bands += other.in_bands;
        self.packed += other.packed;
        self.aliased_layout += other.aliased_layout;
        self.short_rows += other.short_rows;
        self.reference += other.reference;
        self.behind_writes += other.behind_writes;
    }
}

impl Fbi {
    /// A freshly reset FBI with `fb_mib` MiB (2 or 4) of frame buffer.
    pub fn new(fb_mib: u32) -> Self {
        let profile = PixelProfile::default();
        Self {
            regs: [0; 256],
            params: TriangleParams::default(),
            fb: FrameBuffer::new(fb_mib),
            fog_table: FogTable::default(),
            stats: Stats::default(),
            dither: Dither::new(profile.dither_2x2),
            profile,
            generic_path: false,
            path_counts: PathCounts::default(),
            threads: 1,
            helpers: None,
            isa: crate::VectorIsa::best(),
            watch: None,
            pack: None,
            consts: None,
        }
    }

    /// The accuracy profile in force.
    pub fn profile(&self) -> PixelProfile {
        self.profile
    }

    /// Choose the disputed behaviours.
    pub fn set_profile(&mut self, profile: PixelProfile) {
        self.profile = profile;
        self.dither = Dither::new(profile.dither_2x2);
    }

    /// The raw value of a register (normal-map byte offset).
    #[inline]
    pub fn reg(&self, offset: u32) -> u32 {
        self.regs[addr::index(offset)]
    }

    /// `fbzMode` as a typed view.
    #[inline]
    pub fn fbz_mode(&self) -> FbzMode {
        FbzMode(self.reg(addr::FBZ_MODE))
    }

    /// The clip rectangle `(left, right, low_y, high_y)` of `clipLeftRight` and
    /// `clipLowYHighY` (spec 5.21: left and low inclusive, right and high exclusive).
    #[inline]
    pub fn clip_rect(&self) -> (i32, i32, i32, i32) {
        let x = ClipLeftRight(self.reg(addr::CLIP_LEFT_RIGHT));
        let y = ClipLowYHighY(self.reg(addr::CLIP_LOW_Y_HIGH_Y));
        (
            x.clip_left() as i32,
            x.clip_right() as i32,
            y.clip_lowy() as i32,
            y.clip_highy() as i32,
        )
    }

    /// The Y origin subtraction value (`fbiInit3[31:22]`).
    #[inline]
    pub fn y_origin(&self) -> i32 {
        FbiInit3(self.reg(addr::FBI_INIT3)).yorigin_swapval() as i32
    }

    /// Visible width and height from `videoDimensions` (rounded up to even, as MAME and
    /// DOSBox Staging do); 640x480 before the driver has set a mode.
    pub fn display_size(&self) -> (u32, u32) {
        let v = VideoDimensions(self.reg(addr::VIDEO_DIMENSIONS));
        if v.0 == 0 {
            return (640, 480);
        }
        ((v.x_width() + 1) & !1, (v.y_height() + 1) & !1)
    }

    /// A register write. `offset` is a normal-map byte offset; the board has applied
    /// chip select and the `initEnable` gate for `fbiInit*`. `M` is the model of the chip
    /// ([`crate::model`]); the caller guarantees that the profile this FBI holds is `M`'s.
    #[inline]
    pub fn write_reg<M: PixelModel>(&mut self, offset: u32, value: u32) -> Command {
        let idx = addr::index(offset);
        let profile = M::pixel(&self.profile);
        if self.write_parameter::<M>(offset, value) {
            return Command::None;
        }
        match offset & 0x3fc {
            addr::TRIANGLE_CMD | addr::F_TRIANGLE_CMD => {
                self.params.right_to_left = value & 1 << 31 != 0;
                return Command::Triangle;
            }
            addr::FASTFILL_CMD => return Command::Fastfill,
            addr::SWAPBUFFER_CMD => return Command::Swap,
            addr::NOP_CMD => {
                if value & 1 != 0 {
                    self.stats.clear_hardware();
                }
            }
            // The mode registers keep only the bits the SST-1 implements (spec 5 register
            // table "Bits"), so that a drawing state is the same whatever a driver writes
            // into reserved bits.
            addr::FBZ_COLOR_PATH | addr::FOG_MODE | addr::FBZ_MODE | addr::LFB_MODE => {
                self.regs[idx] = value & map::mask_of(offset)
            }
            addr::FOG_TABLE..=addr::FOG_TABLE_LAST => self
                .fog_table
                .write(((offset - addr::FOG_TABLE) / 4) as usize, value),
            addr::FBI_INIT0 => {
                self.regs[idx] = value;
                // Bit 1: FBI graphics reset clears the counters (MAME, DOSBox Staging).
                if value & 2 != 0 {
                    self.stats.clear_hardware();
                    if profile.graphics_reset == GraphicsReset::ResetsBuffers {
                        // Source: 86Box `voodoo_writel`, FBIINIT0_GRAPHICS_RESET.
                        self.fb.front = 0;
                        self.fb.back = 1;
                    }
                }
                self.recompute_layout();
            }
            addr::FBI_INIT1 | addr::FBI_INIT2 | addr::FBI_INIT3 | addr::FBI_INIT4 => {
                self.regs[idx] = value;
                self.recompute_layout();
            }
            addr::VIDEO_DIMENSIONS => {
                self.regs[idx] = value;
                self.recompute_layout();
            }
            // Read-only counters and vRetrace: writes are ignored (spec 5 register table).
            addr::FBI_PIXELS_IN..=addr::FBI_PIXELS_OUT | addr::V_RETRACE => {}
            _ => self.regs[idx] = value,
        }
        Command::None
    }

    /// A write to a triangle parameter register (normal-map `offset`, 0x008..=0x0fc):
    /// what [`Fbi::write_reg`] does with it, without looking for the other registers.
    /// Returns `false`, storing nothing, if `offset` is not a parameter register.
    #[inline(always)]
    pub fn write_parameter<M: PixelModel>(&mut self, offset: u32, value: u32) -> bool {
        let profile = M::pixel(&self.profile);
        self.params
            .write(offset & 0x3fc, value, profile.float_overflow)
    }

    /// A register read (spec 5 register table: reads always come from the FBI).
    pub fn read_reg(&mut self, offset: u32) -> u32 {
        const COUNTER_MASK: u64 = 0x00ff_ffff;
        match offset & 0x3fc {
            addr::STATUS => {
                // The displayed buffer and the memory FIFO (not modelled: empty). The
                // board fills in the PCI FIFO, retrace, busy and swap bits from its
                // timing model (`sst1_board::timing`); alone, the FBI reads idle.
                0x3f | 1 << 6 | (self.fb.front as u32 & 3) << 10 | 0xffff << 12
            }
            addr::FBI_PIXELS_IN => (self.stats.pixels_in & COUNTER_MASK) as u32,
            addr::FBI_CHROMA_FAIL => (self.stats.chroma_fail & COUNTER_MASK) as u32,
            addr::FBI_ZFUNC_FAIL => (self.stats.zfunc_fail & COUNTER_MASK) as u32,
            addr::FBI_AFUNC_FAIL => (self.stats.afunc_fail & COUNTER_MASK) as u32,
            addr::FBI_PIXELS_OUT => (self.stats.pixels_out & COUNTER_MASK) as u32,
            addr::V_RETRACE => 0,
            o => self.regs[addr::index(o)],
        }
    }

    /// Derive the frame-buffer layout from the init registers (spec 5.43-5.44).
    pub(crate) fn recompute_layout(&mut self) {
        let i1 = FbiInit1(self.reg(addr::FBI_INIT1));
        let i2 = FbiInit2(self.reg(addr::FBI_INIT2));
        self.fb.recompute_layout(
            i1.video_tiles_in_x(),
            i2.video_buffer_offset(),
            i2.enable_triple_buffering(),
        );
    }

    /// SWAPBUFFER (spec 5.24): swaps are immediate in this emulator.
    pub fn swap(&mut self) {
        self.fb.swap();
        self.stats.swaps += 1;
    }

    /// Word index of the colour buffer a buffer field selects (reserved values: none).
    #[inline]
    pub fn colour_buffer(&self, select: ColorBuffer) -> Option<usize> {
        match select {
            ColorBuffer::Front => self.fb.rgb_base(self.fb.front),
            ColorBuffer::Back => self.fb.rgb_base(self.fb.back),
            _ => None,
        }
    }

    /// Screen row of raster row `y`, after the Y origin flip when `flip` is set.
    #[inline]
    pub fn screen_y(&self, y: i32, flip: bool) -> i32 {
        crate::pipeline::screen_row(self.y_origin(), y, flip)
    }
}

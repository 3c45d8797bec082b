//! Port layer for hardware-behaviour tests: register-level programs that drive an SST-1
//! only as a driver would (PCI configuration writes, 32-bit writes and reads in the
//! 16 MiB memory aperture, status polls) and then read pixels back through the linear
//! frame buffer (spec 4, 5.20.2, 7.2).
//!
//! A test program is written against [`Port`]. [`Emulator`] implements it on
//! `sst1_board::Board`; a port to a real board needs only [`Port::write`],
//! [`Port::read`] and [`Port::pci_write`] (the pixel reads have default implementations
//! that use LFB reads), so the same programs could run on hardware and settle a disputed
//! behaviour.
//!
//! The helpers here are what a driver writes: the Glide-style 640x480 init of the
//! conformance traces ([`init_640x480`]), triangle setup in the fixed-point and
//! floating-point parameter registers ([`triangle_fixed`], [`triangle_float`]), FASTFILL
//! ([`fastfill`]) and the idle wait of spec 9.3 ([`wait_idle`]). Register offsets come
//! from [`sst1_regs::addr`]; [`bits`] names the mode-register bits the programs set.

use sst1_board::{AccuracyProfile, Board, BoardConfig};
use sst1_regs::{addr, ClipLeftRight, ClipLowYHighY, LfbMode, LfbReadBuffer, RegisterBus, Status};

/// Start of the linear frame buffer in the memory aperture (spec 4).
pub const LFB_BASE: u32 = 0x40_0000;

/// `initEnable` in PCI configuration space (spec 6.16).
pub const PCI_INIT_ENABLE: u32 = 0x40;

/// Byte address of a 16-bit pixel in the LFB: 1024 pixels of 2 bytes per logical row
/// (spec 7.1: 2048 bytes per scan line for 16-bit formats and for all reads).
pub const fn lfb16(x: u32, y: u32) -> u32 {
    LFB_BASE + (y << 11) + (x << 1)
}

/// Byte address of a 32-bit pixel in the LFB: 1024 pixels of 4 bytes per logical row
/// (spec 7.1: 4096 bytes per scan line for formats 4, 5 and 12-14).
pub const fn lfb32(x: u32, y: u32) -> u32 {
    LFB_BASE + (y << 12) + (x << 2)
}

/// A buffer that LFB reads can select (`lfbMode` bits 7:6, spec 5.20).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Buffer {
    /// The displayed colour buffer (read select 0).
    Front,
    /// The drawn colour buffer (read select 1).
    Back,
    /// The depth/alpha buffer (read select 2).
    Aux,
}

impl Buffer {
    /// The `lfbMode` read-buffer-select field value, in place (bits 7:6).
    pub const fn read_select(self) -> u32 {
        let b = match self {
            Buffer::Front => LfbReadBuffer::Front,
            Buffer::Back => LfbReadBuffer::Back,
            Buffer::Aux => LfbReadBuffer::Aux,
        };
        LfbMode(0).with_read_buffer_select(b).0
    }
}

/// What a test program sees of a board: the PCI memory aperture and configuration space.
pub trait Port {
    /// One 32-bit write at byte offset `addr` of the 16 MiB memory aperture.
    fn write(&mut self, addr: u32, value: u32);

    /// One 32-bit read at byte offset `addr` of the memory aperture.
    fn read(&mut self, addr: u32) -> u32;

    /// One 32-bit write at byte `offset` of PCI configuration space (spec 6).
    fn pci_write(&mut self, offset: u32, value: u32);

    /// Let `cycles` cycles of the 50 MHz graphics clock pass without a bus access (a
    /// runner on a real board sleeps that long; the emulator's host clock moves on).
    fn wait(&mut self, cycles: u64);

    /// The raw 16-bit value of pixel `(x, y)` of `buffer`, read as a driver reads it:
    /// through an LFB read with no swapping, no swizzling and the Y origin at the top
    /// (spec 5.20.2). `lfbMode` is saved and restored around the read.
    fn read_pixel(&mut self, buffer: Buffer, x: u32, y: u32) -> u16 {
        let saved = self.read(addr::LFB_MODE);
        self.write(addr::LFB_MODE, buffer.read_select());
        let word = self.read(lfb16(x & !1, y));
        self.write(addr::LFB_MODE, saved);
        // Without word swap the left (even) pixel is in bits 15:0 (spec 5.20.2).
        if x & 1 == 0 {
            word as u16
        } else {
            (word >> 16) as u16
        }
    }

    /// The raw 16-bit value at `(x, y)` of the depth/alpha buffer (an LFB read).
    fn read_aux(&mut self, x: u32, y: u32) -> u16 {
        self.read_pixel(Buffer::Aux, x, y)
    }
}

/// The emulated board behind the port layer.
pub struct Emulator {
    board: Board,
}

impl std::fmt::Debug for Emulator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Emulator")
            .field("config", &self.board.config())
            .finish()
    }
}

impl Emulator {
    /// A 4 MiB, one-TMU board in its power-on state with the default accuracy profile.
    pub fn new() -> Self {
        Self {
            board: Board::new(BoardConfig::default()),
        }
    }

    /// A board like [`Emulator::new`] with the disputed behaviours chosen by `profile`.
    pub fn with_profile(profile: AccuracyProfile) -> Self {
        let mut board = Board::new(BoardConfig::default());
        board.set_profile(profile);
        Self { board }
    }

    /// The board, for emulator-only cross-checks (`dump_buffer`, `stats`).
    pub fn board(&self) -> &Board {
        &self.board
    }
}

impl Port for Emulator {
    fn write(&mut self, addr: u32, value: u32) {
        self.board.write32(addr, value);
    }

    fn read(&mut self, addr: u32) -> u32 {
        self.board.read32(addr)
    }

    fn pci_write(&mut self, offset: u32, value: u32) {
        self.board.pci_write(offset, value);
    }

    fn wait(&mut self, cycles: u64) {
        self.board.host_wait(cycles);
    }
}

/// The texture set-up the texel tests share.
pub mod texture {
    use sst1_regs::{FbzColorPath, RgbSelect, TextureFormat, TextureMode};

    /// Start of the texture region of the aperture (spec 4).
    pub const TEX_BASE: u32 = 0x80_0000;
    /// `textureMode` format RGB565 (bits 11:8 = 10); point sampling, no perspective.
    pub const TEX_565: u32 = TextureMode(0).with_format(TextureFormat::Rgb565).0;
    /// `textureMode` decal: `tc_zero_other` + `tc_add_clocal`, `tca_zero_other` +
    /// `tca_add_alocal` (bits 12, 18, 21, 28); format 0 (RGB332), point sampled (OR
    /// another format into bits 11:8).
    pub const DECAL: u32 = TextureMode(0)
        .with_tc_zero_other(true)
        .with_tc_add_clocal(true)
        .with_tca_zero_other(true)
        .with_tca_add_alocal(true)
        .0;
    /// `fbzColorPath`: colour from the texture, texturing on (bit 27).
    pub const COLOR_PATH_TEXTURE: u32 = FbzColorPath(0)
        .with_cc_rgbselect(RgbSelect::Texture)
        .with_texture_enable(true)
        .0;
}

/// Bits of the mode registers that the programs set, named after the spec's fields.
///
/// Each value is built with the typed views' `with_*` setters from `sst1_regs` (the one
/// place the bit positions are declared), so a program reads as the spec's field names
/// and cannot disagree with the emulator's decoding.
pub mod bits {
    use sst1_regs::{
        AlphaMode, BlendFactor, ColorBuffer, CompareFunction, FbzColorPath, FbzMode, FogMode,
        FogZa, LfbMode, LfbWriteFormat, RgbaLanes,
    };

    /// `fbzMode` (spec 5.19).
    pub mod fbz {
        use super::*;

        const M: FbzMode = FbzMode(0);
        /// Bit 0: enable the clip rectangle.
        pub const CLIP: u32 = M.with_enable_clipping(true).0;
        /// Bit 1: enable chroma-keying.
        pub const CHROMAKEY: u32 = M.with_enable_chromakey(true).0;
        /// Bit 3: W instead of Z for depth buffering.
        pub const WBUFFER: u32 = M.with_wbuffer_select(true).0;
        /// Bit 4: enable depth buffering.
        pub const DEPTH: u32 = M.with_enable_depthbuffer(true).0;
        /// Bits 7:5: depth function `f` (0 never .. 7 always, spec 5.19.1).
        pub const fn depth_function(f: u32) -> u32 {
            M.with_depth_function(CompareFunction::from_bits(f)).0
        }
        /// Bit 8: enable dithering.
        pub const DITHER: u32 = M.with_enable_dithering(true).0;
        /// Bit 9: RGB buffer write mask.
        pub const RGB_WRITE: u32 = M.with_rgb_buffer_mask(true).0;
        /// Bit 10: depth/alpha buffer write mask.
        pub const AUX_WRITE: u32 = M.with_aux_buffer_mask(true).0;
        /// Bit 11: 2x2 instead of 4x4 ordered dither.
        pub const DITHER_2X2: u32 = M.with_dither_2x2(true).0;
        /// Bit 13: alpha-channel mask.
        pub const ALPHA_MASK: u32 = M.with_enable_alpha_mask(true).0;
        /// Bits 15:14 = 1: draw into the back buffer.
        pub const DRAW_BACK: u32 = M.with_draw_buffer(ColorBuffer::Back).0;
        /// Bit 16: depth bias by `zaColor[15:0]`.
        pub const DEPTH_BIAS: u32 = M.with_enable_depth_bias(true).0;
        /// Bit 17: Y origin at the bottom of the screen.
        pub const Y_ORIGIN: u32 = M.with_y_origin(true).0;
        /// Bit 18: the aux buffer holds alpha.
        pub const ALPHA_PLANES: u32 = M.with_enable_alpha_planes(true).0;
        /// Bit 20: compare `zaColor[15:0]` instead of the pixel's depth.
        pub const DEPTH_SOURCE_COMPARE: u32 = M.with_depth_source_compare(true).0;
    }

    /// `lfbMode` (spec 5.20).
    pub mod lfb {
        use super::*;

        const L: LfbMode = LfbMode(0);
        /// Bits 3:0: write format `f`.
        pub const fn format(f: u32) -> u32 {
            L.with_write_format(LfbWriteFormat::from_bits(f)).0
        }
        /// Bits 5:4 = 1: LFB writes go to the back buffer.
        pub const WRITE_BACK: u32 = L.with_write_buffer_select(ColorBuffer::Back).0;
        /// Bit 8: LFB writes go through the pixel pipeline.
        pub const PIPELINE: u32 = L.with_enable_pixel_pipeline(true).0;
        /// Bits 10:9: RGBA lanes `l` (0 ARGB, 1 ABGR, 2 RGBA, 3 BGRA).
        pub const fn lanes(l: u32) -> u32 {
            L.with_rgba_lanes(RgbaLanes::from_bits(l)).0
        }
        /// Bit 11: swap the 16-bit words of writes.
        pub const WORD_SWAP_WRITES: u32 = L.with_word_swap_writes(true).0;
        /// Bit 12: byte swizzle writes.
        pub const BYTE_SWIZZLE_WRITES: u32 = L.with_byte_swizzle_writes(true).0;
        /// Bit 13: Y origin at the bottom of the screen.
        pub const Y_ORIGIN: u32 = L.with_y_origin(true).0;
        /// Bit 15: swap the 16-bit words of reads.
        pub const WORD_SWAP_READS: u32 = L.with_word_swap_reads(true).0;
        /// Bit 16: byte swizzle reads.
        pub const BYTE_SWIZZLE_READS: u32 = L.with_byte_swizzle_reads(true).0;
    }

    /// `alphaMode` (spec 5.18).
    pub mod alpha {
        use super::*;

        const A: AlphaMode = AlphaMode(0);
        /// Bit 0 and bits 3:1: enable the alpha test with function `f`.
        pub const fn test(f: u32) -> u32 {
            A.with_alpha_test_enable(true)
                .with_alpha_function(CompareFunction::from_bits(f))
                .0
        }
        /// Bit 4: enable alpha blending.
        pub const BLEND: u32 = A.with_alpha_blend_enable(true).0;
        /// Bits 11:8 and 15:12: RGB source and destination blend factors.
        pub const fn rgb_factors(src: u32, dst: u32) -> u32 {
            A.with_src_rgb_blend(BlendFactor::from_bits(src))
                .with_dst_rgb_blend(BlendFactor::from_bits(dst))
                .0
        }
        /// Bits 19:16 and 23:20: alpha-channel source and destination blend factors.
        pub const fn alpha_factors(src: u32, dst: u32) -> u32 {
            A.with_src_alpha_blend(BlendFactor::from_bits(src))
                .with_dst_alpha_blend(BlendFactor::from_bits(dst))
                .0
        }
        /// Bits 31:24: alpha reference value.
        pub const fn reference(r: u32) -> u32 {
            A.with_alpha_ref(r as u8).0
        }
    }

    /// `fbzColorPath` (spec 5.16).
    pub mod color_path {
        use super::*;

        /// Bit 26: subpixel correction of the start parameters.
        pub const PARAM_ADJUST: u32 = FbzColorPath(0).with_param_adjust(true).0;
    }

    /// `fogMode` (spec 5.17).
    pub mod fog {
        use super::*;

        const F: FogMode = FogMode(0);
        /// Bit 0: enable fog.
        pub const ENABLE: u32 = F.with_enable_fog(true).0;
        /// Bit 1: add zero instead of `fogColor`.
        pub const ADD: u32 = F.with_fog_add(true).0;
        /// Bit 2: multiply zero instead of the colour.
        pub const MULT: u32 = F.with_fog_mult(true).0;
        /// Bit 3: fog alpha from iterated alpha.
        pub const ALPHA: u32 = F.with_fog_za(FogZa::IteratedAlpha).0;
        /// Bit 4: fog alpha from iterated Z bits 27:20.
        pub const Z: u32 = F.with_fog_za(FogZa::IteratedZ).0;
        /// Bit 5: add `fogColor` as a constant.
        pub const CONSTANT: u32 = F.with_fog_constant(true).0;
    }
}

/// The Glide-style initialisation the conformance traces start with: PCI `initEnable`,
/// the `fbiInit*` and video registers for 640x480 with two colour buffers and an aux
/// buffer in 4 MiB, the default rendering state, and a FASTFILL of the back buffer to
/// `color1` = 0x00101030 and the aux buffer to 0xffff.
///
/// Afterwards: `fbzMode` = 0x4601 (clip on, RGB and aux writes on, drawing into the back
/// buffer), clip rectangle 640x480, `fbiInit3` Y origin swap value 479.
pub fn init_640x480(port: &mut impl Port) {
    // The mode set (source: the conformance traces' first writes), then Glide's default
    // state and a clear.
    port.pci_write(PCI_INIT_ENABLE, 0x0000_0003);
    for &(a, v) in sst1_board::presets::GLIDE_640X480 {
        port.write(a, v);
    }
    const WRITES: &[(u32, u32)] = &[
        (addr::FBZ_COLOR_PATH, 0x0000_0000),
        (addr::FOG_MODE, 0x0000_0000),
        (addr::ALPHA_MODE, 0x0000_0000),
        (addr::FBZ_MODE, 0x0000_4601),
        (addr::LFB_MODE, 0x0000_0000),
        (addr::STIPPLE, 0xffff_ffff),
        (addr::TEXTURE_MODE, 0x0824_1a00),
        (addr::T_LOD, 0x0000_0000),
        (addr::T_DETAIL, 0x0000_0000),
        (addr::NOP_CMD, 0x0000_0000),
        (addr::COLOR1, 0x0010_1030),
        (addr::ZA_COLOR, 0x0000_ffff),
        (addr::FBZ_MODE, 0x0000_4600),
        (addr::FASTFILL_CMD, 0x0000_0000),
        (addr::FBZ_MODE, 0x0000_4601),
    ];
    for &(a, v) in WRITES {
        port.write(a, v);
    }
}

/// Status reads enough for what these programs queue to finish: the board keeps drawing
/// while the host polls, and a read takes 4.5 graphics clocks in the timing model, so
/// this is 0.36 s of board time (a full-screen fill is 3.45 ms).
pub const IDLE_READS: u32 = 4_000_000;

/// Wait until the board is idle, as spec 9.3 prescribes: a NOP, then `status` bit 9
/// (SST-1 busy) read clear more than three times in a row. Returns `false` if the board
/// is still busy after `max_reads` status reads.
pub fn wait_idle(port: &mut impl Port, max_reads: u32) -> bool {
    port.write(addr::NOP_CMD, 0);
    let mut idle = 0;
    for _ in 0..max_reads {
        if Status(port.read(addr::STATUS)).sst1_busy() {
            idle = 0;
        } else {
            idle += 1;
            if idle > 3 {
                return true;
            }
        }
    }
    false
}

/// Set the clip rectangle: columns `left..right`, rows `low..high` (spec 5.21: left and
/// low inclusive, right and high exclusive; y = 0 is the top of the screen).
pub fn set_clip(port: &mut impl Port, left: u32, right: u32, low: u32, high: u32) {
    let lr = ClipLeftRight(0).with_clip_left(left).with_clip_right(right);
    let y = ClipLowYHighY(0).with_clip_lowy(low).with_clip_highy(high);
    port.write(addr::CLIP_LEFT_RIGHT, lr.0);
    port.write(addr::CLIP_LOW_Y_HIGH_Y, y.0);
}

/// FASTFILL (spec 5.23) of the current clip rectangle with `color1` = `rgb` (0x00RRGGBB)
/// and depth `zaColor` = `za`, through the masks and draw buffer already in `fbzMode`.
pub fn fastfill(port: &mut impl Port, rgb: u32, za: u32) {
    port.write(addr::COLOR1, rgb);
    port.write(addr::ZA_COLOR, za);
    port.write(addr::FASTFILL_CMD, 0);
}

/// One iterated parameter: its value at vertex A and its gradients, all in the
/// parameter's fixed-point format (12.12 colour, 20.12 Z, 2.30 W).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Param {
    /// Value at vertex A.
    pub start: i32,
    /// Change per pixel in X.
    pub dx: i32,
    /// Change per pixel in Y.
    pub dy: i32,
}

impl Param {
    /// A constant parameter.
    pub const fn flat(start: i32) -> Self {
        Self {
            start,
            dx: 0,
            dy: 0,
        }
    }
}

/// A triangle as the setup registers hold it (spec 5.2-5.14).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Triangle {
    /// Vertices A, B, C as (x, y) in 12.4 fixed point (1/16 pixel).
    pub vertices: [(i32, i32); 3],
    /// Red, green, blue, alpha (12.12).
    pub rgba: [Param; 4],
    /// Z (20.12).
    pub z: Param,
    /// W (2.30).
    pub w: Param,
}

impl Triangle {
    /// A flat-shaded triangle with vertices in whole pixels, colour `argb` (0xAARRGGBB),
    /// Z and W zero.
    pub fn flat(vertices: [(i32, i32); 3], argb: u32) -> Self {
        let ch = |shift: u32| Param::flat((((argb >> shift) & 0xff) as i32) << 12);
        Self {
            vertices: vertices.map(|(x, y)| (x << 4, y << 4)),
            rgba: [ch(16), ch(8), ch(0), ch(24)],
            ..Self::default()
        }
    }

    /// [`Triangle::flat`] over the corner (0, 0), (40, 0), (0, 40), the triangle most
    /// programs here draw.
    pub fn corner(argb: u32) -> Self {
        Self::flat([(0, 0), (40, 0), (0, 40)], argb)
    }

    /// The value for `triangleCMD`: the sign of the area in bit 31 (spec 5.15: vertices
    /// sorted by Y, `AREA = (dxAB * dyBC - dxBC * dyAB) / 2`, bit 31 set for negative).
    pub fn area_sign(&self) -> u32 {
        let mut v = self.vertices.map(|(x, y)| (x as i64, y as i64));
        v.sort_by_key(|&(_, y)| y);
        let [a, b, c] = v;
        let area = (a.0 - b.0) * (b.1 - c.1) - (b.0 - c.0) * (a.1 - b.1);
        if area < 0 {
            0x8000_0000
        } else {
            0
        }
    }
}

/// Write a triangle into the fixed-point setup registers and start it with `triangleCMD`
/// (spec 5.2-5.15). S and T are not written (untextured drawing).
pub fn triangle_fixed(port: &mut impl Port, t: &Triangle) {
    let [(ax, ay), (bx, by), (cx, cy)] = t.vertices;
    for (reg, v) in [
        (addr::VERTEX_AX, ax),
        (addr::VERTEX_AY, ay),
        (addr::VERTEX_BX, bx),
        (addr::VERTEX_BY, by),
        (addr::VERTEX_CX, cx),
        (addr::VERTEX_CY, cy),
    ] {
        // 12.4 in bits 15:0 (spec 5.2).
        port.write(reg, v as u32 & 0xffff);
    }
    for (p, [s, dx, dy]) in params(t) {
        // 12.12 colour registers hold 24 bits (spec 5.3); Z and W use all 32.
        let mask = if s == addr::START_Z || s == addr::START_W {
            u32::MAX
        } else {
            0xff_ffff
        };
        port.write(s, p.start as u32 & mask);
        port.write(dx, p.dx as u32 & mask);
        port.write(dy, p.dy as u32 & mask);
    }
    port.write(addr::TRIANGLE_CMD, t.area_sign());
}

/// Write the same triangle into the floating-point setup registers (`fvertexAx`...,
/// each the fixed value divided by its scale, exact in IEEE single for the values the
/// programs use) and start it with `ftriangleCMD` (spec 5.2-5.15).
pub fn triangle_float(port: &mut impl Port, t: &Triangle) {
    let [(ax, ay), (bx, by), (cx, cy)] = t.vertices;
    let f = |v: i32, frac: i32| (v as f64 / (1u64 << frac) as f64) as f32;
    for (reg, v) in [
        (addr::F_VERTEX_AX, ax),
        (addr::F_VERTEX_AY, ay),
        (addr::F_VERTEX_BX, bx),
        (addr::F_VERTEX_BY, by),
        (addr::F_VERTEX_CX, cx),
        (addr::F_VERTEX_CY, cy),
    ] {
        port.write(reg, f(v, 4).to_bits());
    }
    for (p, [s, dx, dy]) in params(t) {
        let frac = if s == addr::START_W { 30 } else { 12 };
        // The float registers sit 0x80 above their fixed twins (spec 5, register table).
        port.write(s + 0x80, f(p.start, frac).to_bits());
        port.write(dx + 0x80, f(p.dx, frac).to_bits());
        port.write(dy + 0x80, f(p.dy, frac).to_bits());
    }
    port.write(addr::F_TRIANGLE_CMD, t.area_sign());
}

/// Each iterated parameter of `t` with its start, d/dX and d/dY register offsets.
fn params(t: &Triangle) -> [(Param, [u32; 3]); 6] {
    [
        (t.rgba[0], [addr::START_R, addr::D_R_DX, addr::D_R_DY]),
        (t.rgba[1], [addr::START_G, addr::D_G_DX, addr::D_G_DY]),
        (t.rgba[2], [addr::START_B, addr::D_B_DX, addr::D_B_DY]),
        (t.rgba[3], [addr::START_A, addr::D_A_DX, addr::D_A_DY]),
        (t.z, [addr::START_Z, addr::D_Z_DX, addr::D_Z_DY]),
        (t.w, [addr::START_W, addr::D_W_DX, addr::D_W_DY]),
    ]
}

/// An 8-bit-per-channel colour truncated to RGB565, as the frame buffer stores it with
/// dithering off (spec 5.19 bit 8: "converted ... by bit truncation").
pub const fn rgb565_truncated(r: u32, g: u32, b: u32) -> u16 {
    ((r >> 3) << 11 | (g >> 2) << 5 | (b >> 3)) as u16
}

/// Every pixel of a rectangle `x0..x1`, `y0..y1` of `buffer` whose value is not
/// `background`, as `(x, y, value)` in row order (LFB reads).
pub fn non_background(
    port: &mut impl Port,
    buffer: Buffer,
    (x0, x1): (u32, u32),
    (y0, y1): (u32, u32),
    background: u16,
) -> Vec<(u32, u32, u16)> {
    let mut out = Vec::new();
    for y in y0..y1 {
        for x in x0..x1 {
            let v = port.read_pixel(buffer, x, y);
            if v != background {
                out.push((x, y, v));
            }
        }
    }
    out
}

impl Emulator {
    /// A fresh board after [`init_640x480`].
    pub fn booted() -> Self {
        let mut e = Self::new();
        init_640x480(&mut e);
        e
    }

    /// A board with `profile` after [`init_640x480`].
    pub fn booted_with(profile: AccuracyProfile) -> Self {
        let mut e = Self::with_profile(profile);
        init_640x480(&mut e);
        e
    }
}

/// Expected values from the documented equations, written out independently of the
/// emulator's code so that the tests check it rather than repeat it.
pub mod expect {
    /// The 4x4 ordered-dither matrix, `[y & 3][x & 3]`.
    /// Source: MAME, DOSBox Staging and 86Box agree (the spec names the algorithm only).
    pub const MATRIX_4X4: [[u32; 4]; 4] =
        [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

    /// One 8-bit colour dithered to RGB565 with matrix entry `d`:
    /// red/blue `(2v - v/16 + v/128 + d) / 16`, green `(4v - v/16 + v/64 + d) / 16`.
    /// Source: MAME (marked hardware-verified), DOSBox Staging and 86Box's tables agree.
    pub fn dither565(r: u32, g: u32, b: u32, d: u32) -> u16 {
        let rb = |v: u32| (2 * v - v / 16 + v / 128 + d) / 16;
        let g6 = (4 * g - g / 16 + g / 64 + d) / 16;
        (rb(r) << 11 | g6 << 5 | rb(b)) as u16
    }

    /// The 16-bit floating-point depth of a W whose integer part is zero and whose
    /// 32 fraction bits are `frac` (at least 2^-16): exponent = leading zeros of the
    /// fraction, mantissa = the 12 bits after the leading one, inverted, plus one.
    /// Source: spec 5.19 (W-buffer diagram: "exp = find_first_one(w\[31:16\])",
    /// "inverse of the normalized w"); the final +1 from MAME and DOSBox Staging.
    pub const fn wfloat(frac: u32) -> u16 {
        let exp = frac.leading_zeros();
        let mant = ((frac << exp) << 1) >> 20; // 12 bits after the leading one
        ((exp << 12 | (!mant & 0xfff)) + 1) as u16
    }

    /// Fog alpha from the table at depth `wf`: `fog[i] + (delta[i] * frac) >> 10` with
    /// `i = wf[15:10]`, `frac = wf[9:2]` (spec 5.17 diagram: 6-bit index, mantissa 9:2
    /// into an 8x8 multiply; delta in 6.2, spec 5.36).
    pub const fn fog_table_alpha(fog: u32, delta: u32, wf: u16) -> u32 {
        let frac = ((wf >> 2) & 0xff) as u32;
        fog + ((delta * frac) >> 10)
    }

    /// One channel of `Cout = Cin + (fogColor - Cin) * (Afog + 1) / 256` (floor),
    /// clamped. Source: spec 5.17 (fog equation, "9 signed x 8 unsigned multiply",
    /// clamp); the +1 and the shift by 8 from MAME, DOSBox Staging and 86Box.
    pub const fn fog_blend(cin: i32, fog: i32, afog: i32) -> u32 {
        let v = cin + (((fog - cin) * (afog + 1)) >> 8);
        if v < 0 {
            0
        } else if v > 255 {
            255
        } else {
            v as u32
        }
    }

    /// One reference emulator's alpha-blend arithmetic (spec 5.18.2 gives only
    /// `Dnew = S*alpha + Dold*beta`).
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum Blend {
        /// 565 widened by replicating high bits; factor x as x+1, 1-x as 256-x; the sum
        /// of the two products shifted right by 8.
        Mame,
        /// As MAME but each product shifted right by 8 (the emulator's
        /// `BlendArithmetic::PerProduct`, a hybrid).
        PerProduct,
        /// As `PerProduct` but widened with zero low bits.
        Dosbox,
        /// Replicated widening; factors x and 255-x, each product divided by 255.
        Box86,
    }

    /// The blended RGB of source `s` (alpha `sa`) over the RGB565 destination `dst`
    /// with factors `(src, dst)` (codes 0-7 of spec 5.18.2), destination alpha 0xff
    /// (no alpha planes).
    pub fn blend(arith: Blend, s: [u32; 3], sa: u32, dst: u16, factors: (u32, u32)) -> [u32; 3] {
        let d5 = |v: u32| match arith {
            Blend::Dosbox => v << 3,
            _ => v << 3 | v >> 2,
        };
        let d6 = |v: u32| match arith {
            Blend::Dosbox => v << 2,
            _ => v << 2 | v >> 4,
        };
        let dst = dst as u32;
        let d = [d5(dst >> 11), d6((dst >> 5) & 0x3f), d5(dst & 0x1f)];
        let (one, plus, div) = match arith {
            Blend::Box86 => (255, 0, 255),
            _ => (256, 1, 256),
        };
        let da = 0xff;
        let factor = |code: u32, other: u32| match code {
            0 => 0,
            1 => sa + plus,
            2 => other + plus,
            3 => da + plus,
            4 => one,
            5 => one - sa,
            6 => one - other,
            7 => one - da,
            _ => 0,
        };
        std::array::from_fn(|i| {
            let fs = factor(factors.0, d[i]);
            let fd = factor(factors.1, s[i]);
            if arith == Blend::Mame {
                ((s[i] * fs + d[i] * fd) / div).min(255)
            } else {
                ((s[i] * fs) / div + (d[i] * fd) / div).min(255)
            }
        })
    }
}

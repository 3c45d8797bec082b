//! The SST-1 register map as one table in spec order, plus name lookup, the
//! triangle-register remap and a one-line decoder for trace dumps and logs.
//!
//! Source: SST-1 Graphics Engine specification rev 1.61, section 5 (the register table
//! and, for the remap, the alternate table after it). A unit test parses both tables out
//! of the spec and checks [`REGISTERS`] and [`remap_offset`] against them.
//!
//! Offsets are byte offsets in the 1 KiB register map (`register` field, address bits
//! 9:2). The lookups ignore every other address bit (byte, chip and wrap fields).

use crate::addr;
use crate::color::Rgba;
use crate::types::*;
use bitflags::bitflags;

bitflags! {
    /// How a register may be accessed (spec section 5 table, `R/W` and `Sync?/Fifo?`
    /// columns).
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
    pub struct Access: u8 {
        /// Readable (reads always come from FBI; TREX-only registers read undefined).
        const READ = 1 << 0;
        /// Writable.
        const WRITE = 1 << 1;
        /// Writes go through the PCI bus FIFO ("Fifo? Yes").
        const FIFO = 1 << 2;
        /// The pipeline is flushed before the write takes effect ("Sync? Yes").
        const SYNC = 1 << 3;
    }
}

bitflags! {
    /// Which chips store a register (spec section 5 table, `Chip` column).
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
    pub struct Chips: u8 {
        /// Stored in FBI.
        const FBI = 1 << 0;
        /// Stored in each TREX that the address's chip field selects (spec `TREX*`).
        const TREX = 1 << 1;
        /// With [`Chips::TREX`]: written to every TREX whatever the chip field says
        /// (spec `TREX%`). The rev 1.61 table defines the symbol but no register uses it.
        const TREX_UNCONDITIONAL = 1 << 2;
    }
}

/// One 32-bit register word of the map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RegDesc {
    /// Byte offset in the normal (not remapped) map.
    pub offset: u32,
    /// Spec name; words of a table register are named `fogTable[5]`, `nccTable0[3]`.
    pub name: &'static str,
    /// Valid data bits `(hi, lo)` from the spec table, or [`RegDesc::NO_BITS`] where the
    /// spec says `n/a` (the data is ignored).
    pub bits: (u8, u8),
    /// Access flags.
    pub access: Access,
    /// Chips that store the register.
    pub chips: Chips,
    /// Spec description.
    pub description: &'static str,
}

impl RegDesc {
    /// `bits` of a register whose written data is ignored (`fastfillCMD`).
    pub const NO_BITS: (u8, u8) = (0, 1);

    /// Mask of the valid data bits (0 for [`Self::NO_BITS`]).
    pub const fn mask(&self) -> u32 {
        let (hi, lo) = self.bits;
        if hi < lo || hi > 31 {
            return 0;
        }
        let width = (hi - lo + 1) as u32;
        let low = if width == 32 {
            u32::MAX
        } else {
            (1 << width) - 1
        };
        low << lo
    }
}

const NO_BITS: (u8, u8) = RegDesc::NO_BITS;

// Access shorthands for the table: R(ead), W(rite), S(ync), F(ifo).
const R: Access = Access::READ;
const W: Access = Access::WRITE;
const RW: Access = Access::READ.union(Access::WRITE);
const WF: Access = Access::WRITE.union(Access::FIFO);
const RWF: Access = RW.union(Access::FIFO);
const WSF: Access = WF.union(Access::SYNC);
const RWSF: Access = RWF.union(Access::SYNC);

// Chip shorthands: FBI, TREX (chip-field selected), FT = FBI + TREX*.
const FBI: Chips = Chips::FBI;
const TREX: Chips = Chips::TREX;
const FT: Chips = Chips::FBI.union(Chips::TREX);

const fn reg(
    offset: u32,
    name: &'static str,
    bits: (u8, u8),
    access: Access,
    chips: Chips,
    description: &'static str,
) -> RegDesc {
    RegDesc {
        offset,
        name,
        bits,
        access,
        chips,
        description,
    }
}

/// Every register word of the SST-1 in spec order (ascending offset); reserved words
/// have no entry. Source: spec section 5, register table.
pub static REGISTERS: &[RegDesc] = TABLE;

#[rustfmt::skip]
const TABLE: &[RegDesc] = &[
    // 0x000
    reg(0x000, "status",            (31, 0),  RWF,  FBI,  "SST-1 Status"),
    reg(0x008, "vertexAx",          (15, 0),  WF,   FT,   "Vertex A x-coordinate location (12.4 format)"),
    reg(0x00c, "vertexAy",          (15, 0),  WF,   FT,   "Vertex A y-coordinate location (12.4 format)"),
    reg(0x010, "vertexBx",          (15, 0),  WF,   FT,   "Vertex B x-coordinate location (12.4 format)"),
    reg(0x014, "vertexBy",          (15, 0),  WF,   FT,   "Vertex B y-coordinate location (12.4 format)"),
    reg(0x018, "vertexCx",          (15, 0),  WF,   FT,   "Vertex C x-coordinate location (12.4 format)"),
    reg(0x01c, "vertexCy",          (15, 0),  WF,   FT,   "Vertex C y-coordinate location (12.4 format)"),
    reg(0x020, "startR",            (23, 0),  WF,   FBI,  "Starting Red parameter (12.12 format)"),
    reg(0x024, "startG",            (23, 0),  WF,   FBI,  "Starting Green parameter (12.12 format)"),
    reg(0x028, "startB",            (23, 0),  WF,   FBI,  "Starting Blue parameter (12.12 format)"),
    reg(0x02c, "startZ",            (31, 0),  WF,   FBI,  "Starting Z parameter (20.12 format)"),
    reg(0x030, "startA",            (23, 0),  WF,   FBI,  "Starting Alpha parameter (12.12 format)"),
    reg(0x034, "startS",            (31, 0),  WF,   TREX, "Starting S/W parameter (14.18 format)"),
    reg(0x038, "startT",            (31, 0),  WF,   TREX, "Starting T/W parameter (14.18 format)"),
    reg(0x03c, "startW",            (31, 0),  WF,   FT,   "Starting 1/W parameter (2.30 format)"),
    // 0x040
    reg(0x040, "dRdX",              (23, 0),  WF,   FBI,  "Change in Red with respect to X (12.12 format)"),
    reg(0x044, "dGdX",              (23, 0),  WF,   FBI,  "Change in Green with respect to X (12.12 format)"),
    reg(0x048, "dBdX",              (23, 0),  WF,   FBI,  "Change in Blue with respect to X (12.12 format)"),
    reg(0x04c, "dZdX",              (31, 0),  WF,   FBI,  "Change in Z with respect to X (20.12 format)"),
    reg(0x050, "dAdX",              (23, 0),  WF,   FBI,  "Change in Alpha with respect to X (12.12 format)"),
    reg(0x054, "dSdX",              (31, 0),  WF,   TREX, "Change in S/W with respect to X (14.18 format)"),
    reg(0x058, "dTdX",              (31, 0),  WF,   TREX, "Change in T/W with respect to X (14.18 format)"),
    reg(0x05c, "dWdX",              (31, 0),  WF,   FT,   "Change in 1/W with respect to X (2.30 format)"),
    reg(0x060, "dRdY",              (23, 0),  WF,   FBI,  "Change in Red with respect to Y (12.12 format)"),
    reg(0x064, "dGdY",              (23, 0),  WF,   FBI,  "Change in Green with respect to Y (12.12 format)"),
    reg(0x068, "dBdY",              (23, 0),  WF,   FBI,  "Change in Blue with respect to Y (12.12 format)"),
    reg(0x06c, "dZdY",              (31, 0),  WF,   FBI,  "Change in Z with respect to Y (20.12 format)"),
    reg(0x070, "dAdY",              (23, 0),  WF,   FBI,  "Change in Alpha with respect to Y (12.12 format)"),
    reg(0x074, "dSdY",              (31, 0),  WF,   TREX, "Change in S/W with respect to Y (14.18 format)"),
    reg(0x078, "dTdY",              (31, 0),  WF,   TREX, "Change in T/W with respect to Y (14.18 format)"),
    reg(0x07c, "dWdY",              (31, 0),  WF,   FT,   "Change in 1/W with respect to Y (2.30 format)"),
    // 0x080
    reg(0x080, "triangleCMD",       (31, 31), WF,   FT,   "Execute TRIANGLE command (floating point)"),
    reg(0x088, "fvertexAx",         (31, 0),  WF,   FT,   "Vertex A x-coordinate location (floating point)"),
    reg(0x08c, "fvertexAy",         (31, 0),  WF,   FT,   "Vertex A y-coordinate location (floating point)"),
    reg(0x090, "fvertexBx",         (31, 0),  WF,   FT,   "Vertex B x-coordinate location (floating point)"),
    reg(0x094, "fvertexBy",         (31, 0),  WF,   FT,   "Vertex B y-coordinate location (floating point)"),
    reg(0x098, "fvertexCx",         (31, 0),  WF,   FT,   "Vertex C x-coordinate location (floating point)"),
    reg(0x09c, "fvertexCy",         (31, 0),  WF,   FT,   "Vertex C y-coordinate location (floating point)"),
    reg(0x0a0, "fstartR",           (31, 0),  WF,   FBI,  "Starting Red parameter (floating point)"),
    reg(0x0a4, "fstartG",           (31, 0),  WF,   FBI,  "Starting Green parameter (floating point)"),
    reg(0x0a8, "fstartB",           (31, 0),  WF,   FBI,  "Starting Blue parameter (floating point)"),
    reg(0x0ac, "fstartZ",           (31, 0),  WF,   FBI,  "Starting Z parameter (floating point)"),
    reg(0x0b0, "fstartA",           (31, 0),  WF,   FBI,  "Starting Alpha parameter (floating point)"),
    reg(0x0b4, "fstartS",           (31, 0),  WF,   TREX, "Starting S/W parameter (floating point)"),
    reg(0x0b8, "fstartT",           (31, 0),  WF,   TREX, "Starting T/W parameter (floating point)"),
    reg(0x0bc, "fstartW",           (31, 0),  WF,   FT,   "Starting 1/W parameter (floating point)"),
    // 0x0c0
    reg(0x0c0, "fdRdX",             (31, 0),  WF,   FBI,  "Change in Red with respect to X (floating point)"),
    reg(0x0c4, "fdGdX",             (31, 0),  WF,   FBI,  "Change in Green with respect to X (floating point)"),
    reg(0x0c8, "fdBdX",             (31, 0),  WF,   FBI,  "Change in Blue with respect to X (floating point)"),
    reg(0x0cc, "fdZdX",             (31, 0),  WF,   FBI,  "Change in Z with respect to X (floating point)"),
    reg(0x0d0, "fdAdX",             (31, 0),  WF,   FBI,  "Change in Alpha with respect to X (floating point)"),
    reg(0x0d4, "fdSdX",             (31, 0),  WF,   TREX, "Change in S/W with respect to X (floating point)"),
    reg(0x0d8, "fdTdX",             (31, 0),  WF,   TREX, "Change in T/W with respect to X (floating point)"),
    reg(0x0dc, "fdWdX",             (31, 0),  WF,   FT,   "Change in 1/W with respect to X (floating point)"),
    reg(0x0e0, "fdRdY",             (31, 0),  WF,   FBI,  "Change in Red with respect to Y (floating point)"),
    reg(0x0e4, "fdGdY",             (31, 0),  WF,   FBI,  "Change in Green with respect to Y (floating point)"),
    reg(0x0e8, "fdBdY",             (31, 0),  WF,   FBI,  "Change in Blue with respect to Y (floating point)"),
    reg(0x0ec, "fdZdY",             (31, 0),  WF,   FBI,  "Change in Z with respect to Y (floating point)"),
    reg(0x0f0, "fdAdY",             (31, 0),  WF,   FBI,  "Change in Alpha with respect to Y (floating point)"),
    reg(0x0f4, "fdSdY",             (31, 0),  WF,   TREX, "Change in S/W with respect to Y (floating point)"),
    reg(0x0f8, "fdTdY",             (31, 0),  WF,   TREX, "Change in T/W with respect to Y (floating point)"),
    reg(0x0fc, "fdWdY",             (31, 0),  WF,   FT,   "Change in 1/W with respect to Y (floating point)"),
    // 0x100
    reg(0x100, "ftriangleCMD",      (31, 31), WF,   FT,   "Execute TRIANGLE command (floating point)"),
    reg(0x104, "fbzColorPath",      (27, 0),  RWF,  FT,   "FBI Color Path Control"),
    reg(0x108, "fogMode",           (5, 0),   RWF,  FBI,  "Fog Mode Control"),
    reg(0x10c, "alphaMode",         (31, 0),  RWF,  FBI,  "Alpha Mode Control"),
    reg(0x110, "fbzMode",           (20, 0),  RWSF, FBI,  "RGB Buffer and Depth-Buffer Control"),
    reg(0x114, "lfbMode",           (16, 0),  RWSF, FBI,  "Linear Frame Buffer Mode Control"),
    reg(0x118, "clipLeftRight",     (31, 0),  RWSF, FBI,  "Left and Right of Clipping Register"),
    reg(0x11c, "clipLowYHighY",     (31, 0),  RWSF, FBI,  "Top and Bottom of Clipping Register"),
    reg(0x120, "nopCMD",            (0, 0),   WSF,  FT,   "Execute NOP command"),
    reg(0x124, "fastfillCMD",       NO_BITS,  WSF,  FBI,  "Execute FASTFILL command"),
    reg(0x128, "swapbufferCMD",     (8, 0),   WSF,  FBI,  "Execute SWAPBUFFER command"),
    reg(0x12c, "fogColor",          (23, 0),  WSF,  FBI,  "Fog Color Value"),
    reg(0x130, "zaColor",           (31, 0),  WSF,  FBI,  "Constant Alpha/Depth Value"),
    reg(0x134, "chromaKey",         (23, 0),  WSF,  FBI,  "Chroma Key Compare Value"),
    // 0x140
    reg(0x140, "stipple",           (31, 0),  RWSF, FBI,  "Rendering Stipple Value"),
    reg(0x144, "color0",            (31, 0),  RWSF, FBI,  "Constant Color #0"),
    reg(0x148, "color1",            (31, 0),  RWSF, FBI,  "Constant Color #1"),
    reg(0x14c, "fbiPixelsIn",       (23, 0),  R,    FBI,  "Pixel Counter (Number pixels processed)"),
    reg(0x150, "fbiChromaFail",     (23, 0),  R,    FBI,  "Pixel Counter (Number pixels failed Chroma test)"),
    reg(0x154, "fbiZfuncFail",      (23, 0),  R,    FBI,  "Pixel Counter (Number pixels failed Z test)"),
    reg(0x158, "fbiAfuncFail",      (23, 0),  R,    FBI,  "Pixel Counter (Number pixels failed Alpha test)"),
    reg(0x15c, "fbiPixelsOut",      (23, 0),  R,    FBI,  "Pixel Counter (Number pixels drawn)"),
    reg(0x160, "fogTable[0]",       (31, 0),  WSF,  FBI,  "Fog table entries 0 and 1"),
    reg(0x164, "fogTable[1]",       (31, 0),  WSF,  FBI,  "Fog table entries 2 and 3"),
    reg(0x168, "fogTable[2]",       (31, 0),  WSF,  FBI,  "Fog table entries 4 and 5"),
    reg(0x16c, "fogTable[3]",       (31, 0),  WSF,  FBI,  "Fog table entries 6 and 7"),
    reg(0x170, "fogTable[4]",       (31, 0),  WSF,  FBI,  "Fog table entries 8 and 9"),
    reg(0x174, "fogTable[5]",       (31, 0),  WSF,  FBI,  "Fog table entries 10 and 11"),
    reg(0x178, "fogTable[6]",       (31, 0),  WSF,  FBI,  "Fog table entries 12 and 13"),
    reg(0x17c, "fogTable[7]",       (31, 0),  WSF,  FBI,  "Fog table entries 14 and 15"),
    // 0x180
    reg(0x180, "fogTable[8]",       (31, 0),  WSF,  FBI,  "Fog table entries 16 and 17"),
    reg(0x184, "fogTable[9]",       (31, 0),  WSF,  FBI,  "Fog table entries 18 and 19"),
    reg(0x188, "fogTable[10]",      (31, 0),  WSF,  FBI,  "Fog table entries 20 and 21"),
    reg(0x18c, "fogTable[11]",      (31, 0),  WSF,  FBI,  "Fog table entries 22 and 23"),
    reg(0x190, "fogTable[12]",      (31, 0),  WSF,  FBI,  "Fog table entries 24 and 25"),
    reg(0x194, "fogTable[13]",      (31, 0),  WSF,  FBI,  "Fog table entries 26 and 27"),
    reg(0x198, "fogTable[14]",      (31, 0),  WSF,  FBI,  "Fog table entries 28 and 29"),
    reg(0x19c, "fogTable[15]",      (31, 0),  WSF,  FBI,  "Fog table entries 30 and 31"),
    reg(0x1a0, "fogTable[16]",      (31, 0),  WSF,  FBI,  "Fog table entries 32 and 33"),
    reg(0x1a4, "fogTable[17]",      (31, 0),  WSF,  FBI,  "Fog table entries 34 and 35"),
    reg(0x1a8, "fogTable[18]",      (31, 0),  WSF,  FBI,  "Fog table entries 36 and 37"),
    reg(0x1ac, "fogTable[19]",      (31, 0),  WSF,  FBI,  "Fog table entries 38 and 39"),
    reg(0x1b0, "fogTable[20]",      (31, 0),  WSF,  FBI,  "Fog table entries 40 and 41"),
    reg(0x1b4, "fogTable[21]",      (31, 0),  WSF,  FBI,  "Fog table entries 42 and 43"),
    reg(0x1b8, "fogTable[22]",      (31, 0),  WSF,  FBI,  "Fog table entries 44 and 45"),
    reg(0x1bc, "fogTable[23]",      (31, 0),  WSF,  FBI,  "Fog table entries 46 and 47"),
    // 0x1c0
    reg(0x1c0, "fogTable[24]",      (31, 0),  WSF,  FBI,  "Fog table entries 48 and 49"),
    reg(0x1c4, "fogTable[25]",      (31, 0),  WSF,  FBI,  "Fog table entries 50 and 51"),
    reg(0x1c8, "fogTable[26]",      (31, 0),  WSF,  FBI,  "Fog table entries 52 and 53"),
    reg(0x1cc, "fogTable[27]",      (31, 0),  WSF,  FBI,  "Fog table entries 54 and 55"),
    reg(0x1d0, "fogTable[28]",      (31, 0),  WSF,  FBI,  "Fog table entries 56 and 57"),
    reg(0x1d4, "fogTable[29]",      (31, 0),  WSF,  FBI,  "Fog table entries 58 and 59"),
    reg(0x1d8, "fogTable[30]",      (31, 0),  WSF,  FBI,  "Fog table entries 60 and 61"),
    reg(0x1dc, "fogTable[31]",      (31, 0),  WSF,  FBI,  "Fog table entries 62 and 63"),
    // 0x200
    reg(0x200, "fbiInit4",          (12, 0),  RW,   FBI,  "FBI Hardware Initialization (register 4)"),
    reg(0x204, "vRetrace",          (11, 0),  R,    FBI,  "Vertical Retrace Counter"),
    reg(0x208, "backPorch",         (23, 0),  RW,   FBI,  "Video Backporch Timing Generator"),
    reg(0x20c, "videoDimensions",   (25, 0),  RW,   FBI,  "Video Screen Dimensions"),
    reg(0x210, "fbiInit0",          (31, 0),  RW,   FBI,  "FBI Hardware Initialization (register 0)"),
    reg(0x214, "fbiInit1",          (31, 0),  RW,   FBI,  "FBI Hardware Initialization (register 1)"),
    reg(0x218, "fbiInit2",          (31, 0),  RW,   FBI,  "FBI Hardware Initialization (register 2)"),
    reg(0x21c, "fbiInit3",          (31, 0),  RW,   FBI,  "FBI Hardware Initialization (register 3)"),
    reg(0x220, "hSync",             (25, 0),  W,    FBI,  "Horizontal Sync Timing Generator"),
    reg(0x224, "vSync",             (27, 0),  W,    FBI,  "Vertical Sync Timing Generator"),
    reg(0x228, "clutData",          (29, 0),  W,    FBI,  "Internal Color Lookup Table Initialization"),
    reg(0x22c, "dacData",           (31, 0),  W,    FBI,  "External DAC Initialization"),
    reg(0x230, "maxRgbDelta",       (23, 0),  W,    FBI,  "Max. RGB difference for Video Filtering"),
    // 0x300
    reg(0x300, "textureMode",       (30, 0),  WF,   TREX, "Texture Mode Control"),
    reg(0x304, "tLOD",              (23, 0),  WF,   TREX, "Texture LOD Settings"),
    reg(0x308, "tDetail",           (16, 0),  WF,   TREX, "Texture LOD Settings"),
    reg(0x30c, "texBaseAddr",       (18, 0),  WF,   TREX, "Texture Base Address"),
    reg(0x310, "texBaseAddr_1",     (18, 0),  WF,   TREX, "Texture Base Address (supplemental LOD 1)"),
    reg(0x314, "texBaseAddr_2",     (18, 0),  WF,   TREX, "Texture Base Address (supplemental LOD 2)"),
    reg(0x318, "texBaseAddr_3_8",   (18, 0),  WF,   TREX, "Texture Base Address (supplemental LOD 3-8)"),
    reg(0x31c, "trexInit0",         (31, 0),  WSF,  TREX, "TREX Hardware Initialization (register 0)"),
    reg(0x320, "trexInit1",         (31, 0),  WSF,  TREX, "TREX Hardware Initialization (register 1)"),
    reg(0x324, "nccTable0[0]",      (31, 0),  WSF,  TREX, "NCC table 0: Y0-Y3"),
    reg(0x328, "nccTable0[1]",      (31, 0),  WSF,  TREX, "NCC table 0: Y4-Y7"),
    reg(0x32c, "nccTable0[2]",      (31, 0),  WSF,  TREX, "NCC table 0: Y8-Yb"),
    reg(0x330, "nccTable0[3]",      (31, 0),  WSF,  TREX, "NCC table 0: Yc-Yf"),
    reg(0x334, "nccTable0[4]",      (26, 0),  WSF,  TREX, "NCC table 0: I0 (bit 31 set: palette write)"),
    reg(0x338, "nccTable0[5]",      (26, 0),  WSF,  TREX, "NCC table 0: I1 (bit 31 set: palette write)"),
    reg(0x33c, "nccTable0[6]",      (26, 0),  WSF,  TREX, "NCC table 0: I2 (bit 31 set: palette write)"),
    // 0x340
    reg(0x340, "nccTable0[7]",      (26, 0),  WSF,  TREX, "NCC table 0: I3 (bit 31 set: palette write)"),
    reg(0x344, "nccTable0[8]",      (26, 0),  WSF,  TREX, "NCC table 0: Q0 (bit 31 set: palette write)"),
    reg(0x348, "nccTable0[9]",      (26, 0),  WSF,  TREX, "NCC table 0: Q1 (bit 31 set: palette write)"),
    reg(0x34c, "nccTable0[10]",     (26, 0),  WSF,  TREX, "NCC table 0: Q2 (bit 31 set: palette write)"),
    reg(0x350, "nccTable0[11]",     (26, 0),  WSF,  TREX, "NCC table 0: Q3 (bit 31 set: palette write)"),
    reg(0x354, "nccTable1[0]",      (31, 0),  WSF,  TREX, "NCC table 1: Y0-Y3"),
    reg(0x358, "nccTable1[1]",      (31, 0),  WSF,  TREX, "NCC table 1: Y4-Y7"),
    reg(0x35c, "nccTable1[2]",      (31, 0),  WSF,  TREX, "NCC table 1: Y8-Yb"),
    reg(0x360, "nccTable1[3]",      (31, 0),  WSF,  TREX, "NCC table 1: Yc-Yf"),
    reg(0x364, "nccTable1[4]",      (26, 0),  WSF,  TREX, "NCC table 1: I0"),
    reg(0x368, "nccTable1[5]",      (26, 0),  WSF,  TREX, "NCC table 1: I1"),
    reg(0x36c, "nccTable1[6]",      (26, 0),  WSF,  TREX, "NCC table 1: I2"),
    reg(0x370, "nccTable1[7]",      (26, 0),  WSF,  TREX, "NCC table 1: I3"),
    reg(0x374, "nccTable1[8]",      (26, 0),  WSF,  TREX, "NCC table 1: Q0"),
    reg(0x378, "nccTable1[9]",      (26, 0),  WSF,  TREX, "NCC table 1: Q1"),
    reg(0x37c, "nccTable1[10]",     (26, 0),  WSF,  TREX, "NCC table 1: Q2"),
    // 0x380
    reg(0x380, "nccTable1[11]",     (26, 0),  WSF,  TREX, "NCC table 1: Q3"),
];

/// `REGISTERS` position of each register index (offset / 4), `NONE` for reserved words.
/// Building it also checks that the table is in ascending (spec) order.
static BY_INDEX: [u8; 256] = {
    let mut by_index = [NONE; 256];
    let mut i = 0;
    while i < TABLE.len() {
        let d = &TABLE[i];
        assert!(d.offset < 0x400 && d.offset.is_multiple_of(4));
        assert!(
            i == 0 || TABLE[i - 1].offset < d.offset,
            "not in spec order"
        );
        by_index[(d.offset / 4) as usize] = i as u8;
        i += 1;
    }
    assert!(TABLE.len() < NONE as usize);
    by_index
};
const NONE: u8 = u8::MAX;

/// The register at `offset` (bits 9:2 used), or `None` for a reserved word.
pub fn desc_of(offset: u32) -> Option<&'static RegDesc> {
    let i = BY_INDEX[addr::index(offset)];
    REGISTERS.get(usize::from(i))
}

/// The mask of the valid data bits of the register at `offset` (bits 9:2 used; 0 for a
/// reserved word), usable in constants: the one place the spec table's "Bits" column is
/// turned into masks.
pub const fn mask_of(offset: u32) -> u32 {
    match desc_const(offset) {
        Some(d) => d.mask(),
        None => 0,
    }
}

/// [`desc_of`] usable in constants (it walks the table): for tables built at compile
/// time from the register table, such as the board's per-register write routes.
pub const fn desc_const(offset: u32) -> Option<&'static RegDesc> {
    let index = addr::index(offset);
    let mut i = 0;
    while i < TABLE.len() {
        if (TABLE[i].offset / 4) as usize == index {
            return Some(&TABLE[i]);
        }
        i += 1;
    }
    None
}

/// The spec name of the register at `offset` (bits 9:2 used), `"reserved"` for gaps.
pub fn name_of(offset: u32) -> &'static str {
    desc_of(offset).map_or("reserved", |d| d.name)
}

/// The register called `name`, ignoring ASCII case and underscores, so that the spec's
/// spellings all work: `fbzMode`, `lfbMode`/`lfBMode`, `texBaseAddr38`, and the
/// variants its prose uses (`fbinit3`, `lfbmMode`, `lfMode`, `IfbMode`). A table
/// register's bare name (`fogTable`, `nccTable1`) finds its first word.
pub fn find(name: &str) -> Option<&'static RegDesc> {
    let name = ALIASES
        .iter()
        .find(|(alias, _)| same_name(alias, name))
        .map_or(name, |&(_, table_name)| table_name);
    REGISTERS.iter().find(|d| {
        same_name(d.name, name)
            || d.name
                .strip_suffix("[0]")
                .is_some_and(|b| same_name(b, name))
    })
}

/// Other spellings of register names found in the spec's prose, and the table's name.
const ALIASES: &[(&str, &str)] = &[
    ("fbinit0", "fbiInit0"),
    ("fbinit1", "fbiInit1"),
    ("fbinit2", "fbiInit2"),
    ("fbinit3", "fbiInit3"),
    ("fbinit4", "fbiInit4"),
    ("lfbmMode", "lfbMode"),
    ("lfMode", "lfbMode"),
    ("IfbMode", "lfbMode"),
];

fn same_name(a: &str, b: &str) -> bool {
    fn folded(s: &str) -> impl Iterator<Item = u8> + '_ {
        s.bytes()
            .filter(|&c| c != b'_')
            .map(|c| c.to_ascii_lowercase())
    }
    folded(a).eq(folded(b))
}

/// Normal-map byte offset of each register in the alternate (remapped) triangle
/// parameter map, indexed by the remapped register index. The alternate map groups each
/// parameter's start, d/dX and d/dY. Source: spec section 5, second table; MAME's alias
/// map agrees.
#[rustfmt::skip]
static TRIANGLE_REMAP: [u16; 64] = [
    0x000, // 0x000 status
    0x004, // 0x004 reserved
    0x008, // 0x008 vertexAx
    0x00c, // 0x00c vertexAy
    0x010, // 0x010 vertexBx
    0x014, // 0x014 vertexBy
    0x018, // 0x018 vertexCx
    0x01c, // 0x01c vertexCy
    0x020, // 0x020 startR
    0x040, // 0x024 dRdX
    0x060, // 0x028 dRdY
    0x024, // 0x02c startG
    0x044, // 0x030 dGdX
    0x064, // 0x034 dGdY
    0x028, // 0x038 startB
    0x048, // 0x03c dBdX
    0x068, // 0x040 dBdY
    0x02c, // 0x044 startZ
    0x04c, // 0x048 dZdX
    0x06c, // 0x04c dZdY
    0x030, // 0x050 startA
    0x050, // 0x054 dAdX
    0x070, // 0x058 dAdY
    0x034, // 0x05c startS
    0x054, // 0x060 dSdX
    0x074, // 0x064 dSdY
    0x038, // 0x068 startT
    0x058, // 0x06c dTdX
    0x078, // 0x070 dTdY
    0x03c, // 0x074 startW
    0x05c, // 0x078 dWdX
    0x07c, // 0x07c dWdY
    0x080, // 0x080 triangleCMD
    0x084, // 0x084 reserved
    0x088, // 0x088 fvertexAx
    0x08c, // 0x08c fvertexAy
    0x090, // 0x090 fvertexBx
    0x094, // 0x094 fvertexBy
    0x098, // 0x098 fvertexCx
    0x09c, // 0x09c fvertexCy
    0x0a0, // 0x0a0 fstartR
    0x0c0, // 0x0a4 fdRdX
    0x0e0, // 0x0a8 fdRdY
    0x0a4, // 0x0ac fstartG
    0x0c4, // 0x0b0 fdGdX
    0x0e4, // 0x0b4 fdGdY
    0x0a8, // 0x0b8 fstartB
    0x0c8, // 0x0bc fdBdX
    0x0e8, // 0x0c0 fdBdY
    0x0ac, // 0x0c4 fstartZ
    0x0cc, // 0x0c8 fdZdX
    0x0ec, // 0x0cc fdZdY
    0x0b0, // 0x0d0 fstartA
    0x0d0, // 0x0d4 fdAdX
    0x0f0, // 0x0d8 fdAdY
    0x0b4, // 0x0dc fstartS
    0x0d4, // 0x0e0 fdSdX
    0x0f4, // 0x0e4 fdSdY
    0x0b8, // 0x0e8 fstartT
    0x0d8, // 0x0ec fdTdX
    0x0f8, // 0x0f0 fdTdY
    0x0bc, // 0x0f4 fstartW
    0x0dc, // 0x0f8 fdWdX
    0x0fc, // 0x0fc fdWdY
];

/// Translates an offset in the alternate triangle-register map to the normal map.
///
/// The alternate map applies when `fbiInit3` bit 0 ([`FbiInit3::triangle_register_remap`])
/// is set and address bit 21 (the top bit of the wrap field) is 1; the caller checks
/// both. Only the register field (bits 9:2) is translated, through a 64-entry table;
/// every other address bit passes through, and register indices 0x40 and up (offsets
/// 0x100..0x3ff) are unchanged.
pub fn remap_offset(offset: u32) -> u32 {
    let index = addr::index(offset);
    match TRIANGLE_REMAP.get(index) {
        Some(&normal) => (offset & !0x3fc) | u32::from(normal),
        None => offset,
    }
}

/// One line describing a write or read of `value` at `offset` (bits 9:2 used): the
/// register's name and, for registers with a typed view, every field by name
/// (`fbzMode = FbzMode { raw: 0x00000670, ..., depth_function: LessEqual, ... }`);
/// other registers print as `name = 0x12345678`.
pub fn decode(offset: u32, value: u32) -> String {
    describe(offset, value, false)
}

/// As [`decode`], with one field per line (for people rather than logs).
pub fn decode_pretty(offset: u32, value: u32) -> String {
    describe(offset, value, true)
}

fn describe(offset: u32, value: u32, pretty: bool) -> String {
    fn show(v: &dyn core::fmt::Debug, pretty: bool) -> String {
        if pretty {
            format!("{v:#?}")
        } else {
            format!("{v:?}")
        }
    }
    let name = name_of(offset);
    let p = pretty;
    let fields = match offset & 0x3fc {
        addr::STATUS => show(&Status(value), p),
        addr::FBZ_COLOR_PATH => show(&FbzColorPath(value), p),
        addr::FOG_MODE => show(&FogMode(value), p),
        addr::ALPHA_MODE => show(&AlphaMode(value), p),
        addr::FBZ_MODE => show(&FbzMode(value), p),
        addr::LFB_MODE => show(&LfbMode(value), p),
        addr::CLIP_LEFT_RIGHT => show(&ClipLeftRight(value), p),
        addr::CLIP_LOW_Y_HIGH_Y => show(&ClipLowYHighY(value), p),
        addr::ZA_COLOR => show(&ZaColor(value), p),
        addr::CHROMA_KEY => show(&ChromaKey(value), p),
        addr::STIPPLE => show(&Stipple(value), p),
        addr::COLOR0 | addr::COLOR1 => show(&Rgba::from_argb(value), p),
        addr::FBI_INIT4 => show(&FbiInit4(value), p),
        addr::BACK_PORCH => show(&BackPorch(value), p),
        addr::VIDEO_DIMENSIONS => show(&VideoDimensions(value), p),
        addr::FBI_INIT0 => show(&FbiInit0(value), p),
        addr::FBI_INIT1 => show(&FbiInit1(value), p),
        addr::FBI_INIT2 => show(&FbiInit2(value), p),
        addr::FBI_INIT3 => show(&FbiInit3(value), p),
        addr::H_SYNC => show(&HSync(value), p),
        addr::V_SYNC => show(&VSync(value), p),
        addr::TEXTURE_MODE => show(&TextureMode(value), p),
        addr::T_LOD => show(&TLod(value), p),
        addr::T_DETAIL => show(&TDetail(value), p),
        addr::TREX_INIT0 => show(&TrexInit0(value), p),
        addr::TREX_INIT1 => show(&TrexInit1(value), p),
        _ => format!("{value:#010x}"),
    };
    format!("{name} = {fields}")
}

#[cfg(test)]
mod tests {
    use super::*;

    // The register tables of spec section 5, copied from
    // shared/reference/sst-1-spec-rev1.61.md so that the crate tests stand alone.
    const SPEC: &str = include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/spec-register-tables.md"
    ));

    /// One row of a spec register table; a range row (`0x160(352)<br>to<br>0x1dc(476)`)
    /// has `last > first`.
    #[derive(Debug)]
    struct SpecRow {
        name: String,
        first: u32,
        last: u32,
        bits: Vec<(u8, u8)>,
        chips: Option<Chips>,
        access: Access,
    }

    fn parse_offset(cell: &str) -> u32 {
        let hex = cell.trim().split('(').next().unwrap();
        u32::from_str_radix(hex.trim_start_matches("0x"), 16).unwrap()
    }

    fn parse_bits(cell: &str) -> Vec<(u8, u8)> {
        cell.split("<br>or<br>")
            .map(|b| match b.split_once(':') {
                _ if b == "n/a" => RegDesc::NO_BITS,
                Some((hi, lo)) => (hi.parse().unwrap(), lo.parse().unwrap()),
                None => (b.parse().unwrap(), b.parse().unwrap()),
            })
            .collect()
    }

    fn parse_chips(cell: &str) -> Option<Chips> {
        let mut chips = Chips::empty();
        for part in cell.split('+') {
            chips |= match part {
                "n/a" => return None,
                "FBI" => Chips::FBI,
                "TREX*" => Chips::TREX,
                "TREX%" => Chips::TREX | Chips::TREX_UNCONDITIONAL,
                other => panic!("unknown chip column {other:?}"),
            };
        }
        Some(chips)
    }

    fn parse_access(rw: &str, sync_fifo: &str) -> Access {
        let mut access = match rw {
            "R" => Access::READ,
            "W" => Access::WRITE,
            "R/W" => Access::READ | Access::WRITE,
            "n/a" => Access::empty(),
            other => panic!("unknown R/W column {other:?}"),
        };
        let (sync, fifo) = sync_fifo.split_once('/').unwrap_or((sync_fifo, sync_fifo));
        if sync.trim() == "Yes" {
            access |= Access::SYNC;
        }
        if fifo.trim() == "Yes" {
            access |= Access::FIFO;
        }
        access
    }

    /// The rows of the register table that starts at the `n`-th "| Register Name" header
    /// and runs (across page breaks) until `end`.
    fn spec_table(n: usize, end: &str) -> Vec<SpecRow> {
        let start = SPEC.match_indices("| Register Name").nth(n).unwrap().0;
        let text = &SPEC[start..];
        let text = &text[..text.find(end).unwrap()];
        text.lines()
            .filter_map(|line| {
                let cells: Vec<&str> = line
                    .trim()
                    .trim_matches('|')
                    .split('|')
                    .map(str::trim)
                    .collect();
                if cells.len() < 7 || !cells[1].starts_with("0x") {
                    return None;
                }
                let mut range = cells[1].split("<br>to<br>").map(parse_offset);
                let first = range.next().unwrap();
                Some(SpecRow {
                    name: cells[0].to_string(),
                    first,
                    last: range.next().unwrap_or(first),
                    bits: parse_bits(cells[2]),
                    chips: parse_chips(cells[3]),
                    access: parse_access(cells[4], cells[5]),
                })
            })
            .collect()
    }

    fn normal_table() -> Vec<SpecRow> {
        spec_table(0, "When **fbinit3(0)=1**")
    }

    fn remap_table() -> Vec<SpecRow> {
        spec_table(1, "### 5.1 status Register")
    }

    fn check_row(d: &RegDesc, row: &SpecRow) {
        assert!(
            row.bits.contains(&d.bits),
            "{}: bits {:?} vs spec {:?}",
            d.name,
            d.bits,
            row.bits
        );
        assert_eq!(Some(d.chips), row.chips, "{}: chips", d.name);
        assert_eq!(d.access, row.access, "{}: access", d.name);
    }

    #[test]
    fn registers_match_spec_table() {
        let rows = normal_table();
        assert_eq!(rows.first().unwrap().name, "status");
        assert_eq!(rows.last().unwrap().name, "reserved");
        let mut expected = Vec::new();
        for row in &rows {
            for offset in (row.first..=row.last).step_by(4) {
                if row.name == "reserved" {
                    assert_eq!(desc_of(offset), None, "{offset:#x} is reserved");
                    assert_eq!(name_of(offset), "reserved");
                    continue;
                }
                let word = (offset - row.first) / 4;
                let name = if row.last > row.first {
                    format!("{}[{word}]", row.name)
                } else {
                    row.name.clone()
                };
                let d = desc_of(offset).unwrap_or_else(|| panic!("no entry for {name}"));
                assert!(
                    d.name.eq_ignore_ascii_case(&name),
                    "{offset:#x}: {} vs {name}",
                    d.name
                );
                check_row(d, row);
                if row.name.starts_with("nccTable") {
                    // Spec 5.56.1: words 0-3 hold Y (31:0), words 4-11 hold I and Q (26:0).
                    assert_eq!(d.bits, if word < 4 { (31, 0) } else { (26, 0) }, "{name}");
                }
                expected.push(offset);
            }
        }
        // One entry per spec word, nothing else, in spec order.
        let ours: Vec<u32> = REGISTERS.iter().map(|d| d.offset).collect();
        assert_eq!(ours, expected);
        assert_eq!(REGISTERS.len(), 162);
    }

    #[test]
    fn remap_matches_spec_table() {
        let rows = remap_table();
        let offsets: Vec<u32> = rows.iter().map(|r| r.first).collect();
        assert_eq!(offsets, (0..=0x100).step_by(4).collect::<Vec<u32>>());
        for row in &rows {
            if row.name == "reserved" {
                assert_eq!(remap_offset(row.first), row.first);
                continue;
            }
            let d = find(&row.name).unwrap();
            assert_eq!(
                remap_offset(row.first),
                d.offset,
                "{} at {:#x}",
                row.name,
                row.first
            );
            check_row(d, row);
        }
    }

    #[test]
    fn remap_examples_and_identity() {
        assert_eq!(remap_offset(0x024), addr::D_R_DX);
        assert_eq!(remap_offset(0x040), addr::D_B_DY);
        assert_eq!(remap_offset(0x0a4), addr::F_D_R_DX);
        assert_eq!(remap_offset(0x0fc), addr::F_D_W_DY);
        for offset in (0x100..0x400).step_by(4) {
            assert_eq!(remap_offset(offset), offset);
        }
        // Only the register field is translated: wrap bit 21 and chip field 0x2 stay.
        assert_eq!(remap_offset(0x20_0800 | 0x02c), 0x20_0800 | addr::START_G);
        assert_eq!(remap_offset(0x20_0800 | 0x104), 0x20_0904);
    }

    #[test]
    fn lookups() {
        assert_eq!(name_of(addr::FBZ_MODE), "fbzMode");
        assert_eq!(name_of(0x004), "reserved");
        assert_eq!(name_of(0x3fc), "reserved");
        assert_eq!(name_of(0x174), "fogTable[5]");
        assert_eq!(name_of(0x330), "nccTable0[3]");
        // Chip and wrap bits are ignored.
        assert_eq!(name_of(0x20_0c00 | addr::TEXTURE_MODE), "textureMode");
        assert_eq!(find("fbzMode").unwrap().offset, addr::FBZ_MODE);
        assert_eq!(find("FBZMODE").unwrap().offset, addr::FBZ_MODE);
        assert_eq!(find("lfBMode").unwrap().offset, addr::LFB_MODE);
        assert_eq!(find("lfbMode").unwrap().offset, addr::LFB_MODE);
        assert_eq!(find("fbinit3").unwrap().offset, addr::FBI_INIT3);
        assert_eq!(find("fbiInit3").unwrap().offset, addr::FBI_INIT3);
        assert_eq!(find("IfbMode").unwrap().offset, addr::LFB_MODE);
        assert_eq!(
            find("texBaseAddr38").unwrap().offset,
            addr::TEX_BASE_ADDR_3_8
        );
        assert_eq!(find("texBaseAddr1").unwrap().offset, addr::TEX_BASE_ADDR_1);
        assert_eq!(find("fogTable[31]").unwrap().offset, addr::FOG_TABLE_LAST);
        assert_eq!(find("fogTable").unwrap().offset, addr::FOG_TABLE);
        assert_eq!(find("nccTable1").unwrap().offset, addr::NCC_TABLE1);
        assert_eq!(find("nccTable1[11]").unwrap().offset, 0x380);
        assert_eq!(find("fogTable[32]"), None);
        assert_eq!(find("reserved"), None);
        assert_eq!(find(""), None);
    }

    #[test]
    fn addr_constants_agree_with_table() {
        let pairs = [
            (addr::STATUS, "status"),
            (addr::TRIANGLE_CMD, "triangleCMD"),
            (addr::F_TRIANGLE_CMD, "ftriangleCMD"),
            (addr::FASTFILL_CMD, "fastfillCMD"),
            (addr::SWAPBUFFER_CMD, "swapbufferCMD"),
            (addr::FBI_PIXELS_OUT, "fbiPixelsOut"),
            (addr::FBI_INIT4, "fbiInit4"),
            (addr::V_RETRACE, "vRetrace"),
            (addr::MAX_RGB_DELTA, "maxRgbDelta"),
            (addr::TREX_INIT1, "trexInit1"),
            (addr::NCC_TABLE0, "nccTable0[0]"),
        ];
        for (offset, name) in pairs {
            assert_eq!(name_of(offset), name);
        }
    }

    #[test]
    fn masks() {
        assert_eq!(find("status").unwrap().mask(), u32::MAX);
        assert_eq!(find("fbzMode").unwrap().mask(), 0x001f_ffff);
        assert_eq!(find("triangleCMD").unwrap().mask(), 0x8000_0000);
        assert_eq!(find("nopCMD").unwrap().mask(), 1);
        assert_eq!(find("fastfillCMD").unwrap().mask(), 0);
        assert_eq!(find("nccTable0[4]").unwrap().mask(), 0x07ff_ffff);
    }

    #[test]
    fn decode_text() {
        assert_eq!(
            decode(addr::FBZ_MODE, 0x0000_0670),
            "fbzMode = FbzMode { raw: 0x00000670, enable_clipping: false, \
             enable_chromakey: false, enable_stipple: false, wbuffer_select: false, \
             enable_depthbuffer: true, depth_function: LessEqual, enable_dithering: false, \
             rgb_buffer_mask: true, aux_buffer_mask: true, dither_2x2: false, \
             enable_stipple_pattern: false, enable_alpha_mask: false, draw_buffer: Front, \
             enable_depth_bias: false, y_origin: false, enable_alpha_planes: false, \
             dither_subtract: false, depth_source_compare: false }"
        );
        assert_eq!(decode(addr::START_R, 0x0001_2000), "startR = 0x00012000");
        assert_eq!(decode(0x004, 0xdead_beef), "reserved = 0xdeadbeef");
        assert_eq!(decode(0x1d0, 7), "fogTable[28] = 0x00000007");
        assert_eq!(
            decode(addr::COLOR1, 0x80ff_4010),
            "color1 = Rgba { r: 255, g: 64, b: 16, a: 128 }"
        );
        assert_eq!(
            decode(addr::CLIP_LEFT_RIGHT, 0x0000_0280),
            "clipLeftRight = ClipLeftRight { raw: 0x00000280, clip_right: 640, clip_left: 0 }"
        );
        assert!(decode(addr::TEXTURE_MODE, 0x0a00).contains("format: Rgb565"));
        assert!(decode(addr::T_LOD, 0).starts_with("tLOD = TLod { raw: 0x00000000, lodmin: 0"));
        assert!(decode(addr::FBI_INIT3, 1).contains("triangle_register_remap: true"));
        assert!(decode(addr::ALPHA_MODE, 0x0401).contains("src_rgb_blend: One"));
    }
}

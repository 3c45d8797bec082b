//! Byte offsets of the SST-1 registers in the normal (not remapped) register map.
//!
//! Spec section 5, register table. The register index used inside the chips is
//! `offset / 4` (bits 9:2 of the aperture address).
#![allow(missing_docs)]

// 0x000
pub const STATUS: u32 = 0x000;
pub const VERTEX_AX: u32 = 0x008;
pub const VERTEX_AY: u32 = 0x00c;
pub const VERTEX_BX: u32 = 0x010;
pub const VERTEX_BY: u32 = 0x014;
pub const VERTEX_CX: u32 = 0x018;
pub const VERTEX_CY: u32 = 0x01c;
pub const START_R: u32 = 0x020;
pub const START_G: u32 = 0x024;
pub const START_B: u32 = 0x028;
pub const START_Z: u32 = 0x02c;
pub const START_A: u32 = 0x030;
pub const START_S: u32 = 0x034;
pub const START_T: u32 = 0x038;
pub const START_W: u32 = 0x03c;
// 0x040
pub const D_R_DX: u32 = 0x040;
pub const D_G_DX: u32 = 0x044;
pub const D_B_DX: u32 = 0x048;
pub const D_Z_DX: u32 = 0x04c;
pub const D_A_DX: u32 = 0x050;
pub const D_S_DX: u32 = 0x054;
pub const D_T_DX: u32 = 0x058;
pub const D_W_DX: u32 = 0x05c;
pub const D_R_DY: u32 = 0x060;
pub const D_G_DY: u32 = 0x064;
pub const D_B_DY: u32 = 0x068;
pub const D_Z_DY: u32 = 0x06c;
pub const D_A_DY: u32 = 0x070;
pub const D_S_DY: u32 = 0x074;
pub const D_T_DY: u32 = 0x078;
pub const D_W_DY: u32 = 0x07c;
// 0x080
pub const TRIANGLE_CMD: u32 = 0x080;
pub const F_VERTEX_AX: u32 = 0x088;
pub const F_VERTEX_AY: u32 = 0x08c;
pub const F_VERTEX_BX: u32 = 0x090;
pub const F_VERTEX_BY: u32 = 0x094;
pub const F_VERTEX_CX: u32 = 0x098;
pub const F_VERTEX_CY: u32 = 0x09c;
pub const F_START_R: u32 = 0x0a0;
pub const F_START_G: u32 = 0x0a4;
pub const F_START_B: u32 = 0x0a8;
pub const F_START_Z: u32 = 0x0ac;
pub const F_START_A: u32 = 0x0b0;
pub const F_START_S: u32 = 0x0b4;
pub const F_START_T: u32 = 0x0b8;
pub const F_START_W: u32 = 0x0bc;
// 0x0c0
pub const F_D_R_DX: u32 = 0x0c0;
pub const F_D_G_DX: u32 = 0x0c4;
pub const F_D_B_DX: u32 = 0x0c8;
pub const F_D_Z_DX: u32 = 0x0cc;
pub const F_D_A_DX: u32 = 0x0d0;
pub const F_D_S_DX: u32 = 0x0d4;
pub const F_D_T_DX: u32 = 0x0d8;
pub const F_D_W_DX: u32 = 0x0dc;
pub const F_D_R_DY: u32 = 0x0e0;
pub const F_D_G_DY: u32 = 0x0e4;
pub const F_D_B_DY: u32 = 0x0e8;
pub const F_D_Z_DY: u32 = 0x0ec;
pub const F_D_A_DY: u32 = 0x0f0;
pub const F_D_S_DY: u32 = 0x0f4;
pub const F_D_T_DY: u32 = 0x0f8;
pub const F_D_W_DY: u32 = 0x0fc;
// 0x100
pub const F_TRIANGLE_CMD: u32 = 0x100;
pub const FBZ_COLOR_PATH: u32 = 0x104;
pub const FOG_MODE: u32 = 0x108;
pub const ALPHA_MODE: u32 = 0x10c;
pub const FBZ_MODE: u32 = 0x110;
pub const LFB_MODE: u32 = 0x114;
pub const CLIP_LEFT_RIGHT: u32 = 0x118;
pub const CLIP_LOW_Y_HIGH_Y: u32 = 0x11c;
pub const NOP_CMD: u32 = 0x120;
pub const FASTFILL_CMD: u32 = 0x124;
pub const SWAPBUFFER_CMD: u32 = 0x128;
pub const FOG_COLOR: u32 = 0x12c;
pub const ZA_COLOR: u32 = 0x130;
pub const CHROMA_KEY: u32 = 0x134;
// 0x140
pub const STIPPLE: u32 = 0x140;
pub const COLOR0: u32 = 0x144;
pub const COLOR1: u32 = 0x148;
pub const FBI_PIXELS_IN: u32 = 0x14c;
pub const FBI_CHROMA_FAIL: u32 = 0x150;
pub const FBI_ZFUNC_FAIL: u32 = 0x154;
pub const FBI_AFUNC_FAIL: u32 = 0x158;
pub const FBI_PIXELS_OUT: u32 = 0x15c;
/// First of the 32 `fogTable` words (0x160..=0x1dc), two 8-bit entries + deltas each.
pub const FOG_TABLE: u32 = 0x160;
pub const FOG_TABLE_LAST: u32 = 0x1dc;
// 0x200
pub const FBI_INIT4: u32 = 0x200;
pub const V_RETRACE: u32 = 0x204;
pub const BACK_PORCH: u32 = 0x208;
pub const VIDEO_DIMENSIONS: u32 = 0x20c;
pub const FBI_INIT0: u32 = 0x210;
pub const FBI_INIT1: u32 = 0x214;
pub const FBI_INIT2: u32 = 0x218;
pub const FBI_INIT3: u32 = 0x21c;
pub const H_SYNC: u32 = 0x220;
pub const V_SYNC: u32 = 0x224;
pub const CLUT_DATA: u32 = 0x228;
pub const DAC_DATA: u32 = 0x22c;
pub const MAX_RGB_DELTA: u32 = 0x230;
// 0x300
pub const TEXTURE_MODE: u32 = 0x300;
pub const T_LOD: u32 = 0x304;
pub const T_DETAIL: u32 = 0x308;
pub const TEX_BASE_ADDR: u32 = 0x30c;
pub const TEX_BASE_ADDR_1: u32 = 0x310;
pub const TEX_BASE_ADDR_2: u32 = 0x314;
pub const TEX_BASE_ADDR_3_8: u32 = 0x318;
pub const TREX_INIT0: u32 = 0x31c;
pub const TREX_INIT1: u32 = 0x320;
/// First of the 12 `nccTable0` words (0x324..=0x350).
pub const NCC_TABLE0: u32 = 0x324;
/// First of the 12 `nccTable1` words (0x354..=0x380).
pub const NCC_TABLE1: u32 = 0x354;

/// Register index (offset / 4) of a byte offset.
#[inline]
pub const fn index(offset: u32) -> usize {
    ((offset >> 2) & 0xff) as usize
}

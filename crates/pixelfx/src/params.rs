//! Triangle parameters as the FBI holds them: vertices and the start/gradient values of
//! the iterated colour, depth and W (spec 5.2-5.14).
//!
//! Fixed-point formats (spec 5, register table):
//! * vertices: signed 12.4 ([`Fx12_4`]),
//! * R, G, B, A: signed 12.12, 24 bits sign-extended ([`Fx12_12`]),
//! * Z: signed 20.12 ([`Fx20_12`]),
//! * W: the register is 2.30; internally it is kept with 32 fraction bits in 64 bits
//!   ([`Fx32_32`]) so that the float registers keep their full precision. MAME and
//!   DOSBox Staging both widen W this way (fixed writes are shifted left by 2).

use sst1_regs::addr;

/// Signed 12.4 fixed point (vertex coordinates).
pub type Fx12_4 = i16;
/// Signed 12.12 fixed point in an `i32` (colour iterators).
pub type Fx12_12 = i32;
/// Signed 20.12 fixed point in an `i32` (Z iterator).
pub type Fx20_12 = i32;
/// Signed 32.32 fixed point in an `i64` (W iterators, widened from 2.30).
pub type Fx32_32 = i64;

/// The FBI's triangle parameter registers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct TriangleParams {
    /// Vertex A x, y (12.4).
    pub ax: Fx12_4,
    pub ay: Fx12_4,
    /// Vertex B x, y (12.4).
    pub bx: Fx12_4,
    pub by: Fx12_4,
    /// Vertex C x, y (12.4).
    pub cx: Fx12_4,
    pub cy: Fx12_4,
    /// Iterated colour start and gradients, in R, G, B, A order (12.12).
    pub start: [Fx12_12; 4],
    pub dx: [Fx12_12; 4],
    pub dy: [Fx12_12; 4],
    /// Iterated Z start and gradients (20.12).
    pub start_z: Fx20_12,
    pub dzdx: Fx20_12,
    pub dzdy: Fx20_12,
    /// Iterated W start and gradients (32.32).
    pub start_w: Fx32_32,
    pub dwdx: Fx32_32,
    pub dwdy: Fx32_32,
    /// Bit 31 of the last `triangleCMD` / `ftriangleCMD` write: set when the triangle
    /// is walked right to left (spec 5.15: the sign of the area).
    pub right_to_left: bool,
}

/// The pixel from which the iterators count, and what subpixel correction does.
///
/// The iterated value of a pixel is `start + dx * d/dx + dy * d/dy`, with `(dx, dy)` its
/// offset from an origin pixel derived from vertex A.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum ParamOrigin {
    /// Vertex A's own pixel, `A >> 4`; subpixel correction moves the start values by
    /// `8 - (A & 15)` sixteenths, to that pixel's centre, and writes them back (spec 5.16's
    /// "Important Note"; MAME, DOSBox Staging).
    #[default]
    VertexPixel,
    /// The first pixel the rasterizer samples, `(A + 7) >> 4` (A rounded to the nearest
    /// pixel centre, halves down); subpixel correction moves the start values by
    /// `8 - (A & 15)`, plus 16 when `A & 15 > 8`, to that pixel's centre, in a copy that
    /// lasts one triangle (86Box `voodoo_triangle`: `dx`, `dy`, `state.base_*`).
    RoundedVertex,
}

impl ParamOrigin {
    /// The origin pixel for the 12.4 vertex coordinate `v`.
    #[inline]
    pub fn pixel(self, v: Fx12_4) -> i32 {
        match self {
            ParamOrigin::VertexPixel => i32::from(v) >> 4,
            ParamOrigin::RoundedVertex => (i32::from(v) + 7) >> 4,
        }
    }

    /// The 12.4 offset from `v` to the centre of its origin pixel (subpixel correction).
    #[inline]
    pub fn subpixel_offset(self, v: Fx12_4) -> i32 {
        (self.pixel(v) << 4) + 8 - i32::from(v)
    }

    /// Whether subpixel correction writes the corrected start values back.
    pub fn writes_back(self) -> bool {
        self == ParamOrigin::VertexPixel
    }
}

/// How wide the Z part of the subpixel correction is computed (spec 5.16 does not say).
///
/// It matters only when `dZ/dx` or `dZ/dy` is so large that `offset * gradient` leaves
/// 32 bits: Glide 3's console text writes `fdZdX` ~ 6e12 (glide `test30`), and the
/// whole depth of those glyphs follows from how the correction wraps.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum SubpixelZ {
    /// `(dy * dZdY + dx * dZdX) >> 4` in 32-bit arithmetic that wraps, like the colour
    /// terms (MAME; 86Box's `int` products). With it our `test30` depth buffer equals
    /// MAME's on all 307,200 pixels.
    #[default]
    Wrap32,
    /// Each product in 64 bits, shifted on its own, then summed (DOSBox Staging's
    /// `mul_32x32_shift`): 482 majority failures on `test30/depth` against 374.
    Wide64,
}

pub use sst1_regs::float::{float_to_fixed32, float_to_fixed64, FloatOverflow};

/// Sign-extend the low 24 bits (the 12.12 colour registers are 24 bits wide).
#[inline]
const fn sext24(v: u32) -> i32 {
    ((v << 8) as i32) >> 8
}

impl TriangleParams {
    /// Apply a write to one of the parameter registers (normal-map byte `offset`,
    /// 0x008..=0x0fc). `value` is the raw bus word; float registers are converted.
    /// Returns `false` if `offset` is not an FBI parameter register.
    #[inline(always)]
    pub fn write(&mut self, offset: u32, value: u32, overflow: FloatOverflow) -> bool {
        // Float registers mirror the fixed ones 0x80 bytes higher (spec 5, register table).
        let (reg, float) = if (addr::F_VERTEX_AX..=addr::F_D_W_DY).contains(&offset) {
            (offset - 0x80, true)
        } else {
            (offset, false)
        };
        let fixed = |frac: i32| {
            if float {
                float_to_fixed32(value, frac, overflow) as u32
            } else {
                value
            }
        };
        match reg {
            addr::VERTEX_AX => self.ax = fixed(4) as i16,
            addr::VERTEX_AY => self.ay = fixed(4) as i16,
            addr::VERTEX_BX => self.bx = fixed(4) as i16,
            addr::VERTEX_BY => self.by = fixed(4) as i16,
            addr::VERTEX_CX => self.cx = fixed(4) as i16,
            addr::VERTEX_CY => self.cy = fixed(4) as i16,
            addr::START_R | addr::START_G | addr::START_B | addr::START_A => {
                self.start[channel(reg, addr::START_R)] = sext24(fixed(12))
            }
            addr::D_R_DX | addr::D_G_DX | addr::D_B_DX | addr::D_A_DX => {
                self.dx[channel(reg, addr::D_R_DX)] = sext24(fixed(12))
            }
            addr::D_R_DY | addr::D_G_DY | addr::D_B_DY | addr::D_A_DY => {
                self.dy[channel(reg, addr::D_R_DY)] = sext24(fixed(12))
            }
            addr::START_Z => self.start_z = fixed(12) as i32,
            addr::D_Z_DX => self.dzdx = fixed(12) as i32,
            addr::D_Z_DY => self.dzdy = fixed(12) as i32,
            addr::START_W | addr::D_W_DX | addr::D_W_DY => {
                let w = if float {
                    float_to_fixed64(value, 32)
                } else {
                    (value as i32 as i64) << 2
                };
                match reg {
                    addr::START_W => self.start_w = w,
                    addr::D_W_DX => self.dwdx = w,
                    _ => self.dwdy = w,
                }
            }
            _ => return false,
        }
        true
    }

    /// [`Self::write`] with the default overflow behaviour (for tests and tools).
    pub fn write_default(&mut self, offset: u32, value: u32) -> bool {
        self.write(offset, value, FloatOverflow::default())
    }

    /// Subpixel correction (fbzColorPath bit 26, spec 5.16): move the start values from
    /// vertex A to the centre of its pixel. The corrected values replace the start
    /// registers (the spec's "Important Note"), so a second triangle without new starts
    /// is corrected twice, as on hardware.
    ///
    /// Returns the 12.4 offsets `(dx, dy)` so that the TMUs can apply the same correction.
    pub fn subpixel_adjust(&mut self, z_width: SubpixelZ, origin: ParamOrigin) -> (i32, i32) {
        // Source: MAME and DOSBox Staging: offset = 8 - (coordinate & 15), in 1/16 pixel;
        // 86Box adds 16 for a fraction above 8 (ParamOrigin::RoundedVertex).
        let dx = origin.subpixel_offset(self.ax);
        let dy = origin.subpixel_offset(self.ay);
        for i in 0..4 {
            self.start[i] = self.start[i].wrapping_add(
                (dy.wrapping_mul(self.dy[i])
                    .wrapping_add(dx.wrapping_mul(self.dx[i])))
                    >> 4,
            );
        }
        let dz = match z_width {
            SubpixelZ::Wrap32 => {
                dy.wrapping_mul(self.dzdy)
                    .wrapping_add(dx.wrapping_mul(self.dzdx))
                    >> 4
            }
            SubpixelZ::Wide64 => {
                (((dy as i64 * self.dzdy as i64) >> 4) + ((dx as i64 * self.dzdx as i64) >> 4))
                    as i32
            }
        };
        self.start_z = self.start_z.wrapping_add(dz);
        self.start_w = self.start_w.wrapping_add(
            (dy as i64)
                .wrapping_mul(self.dwdy)
                .wrapping_add((dx as i64).wrapping_mul(self.dwdx))
                >> 4,
        );
        (dx, dy)
    }
}

/// Index 0..3 (R, G, B, A) of a colour register, given the register and its R sibling.
#[inline]
fn channel(reg: u32, first: u32) -> usize {
    // The spec's order is R, G, B, Z, A: skip the Z slot.
    match (reg - first) / 4 {
        0 => 0,
        1 => 1,
        2 => 2,
        _ => 3,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_conversion() {
        let w = FloatOverflow::Wrap;
        assert_eq!(float_to_fixed32(1.5f32.to_bits(), 4, w), 24);
        assert_eq!(float_to_fixed32((-1.5f32).to_bits(), 4, w), -24);
        assert_eq!(float_to_fixed32(0.0f32.to_bits(), 12, w), 0);
        assert_eq!(float_to_fixed32(1e30f32.to_bits(), 12, w), i32::MAX);
        assert_eq!(
            float_to_fixed32(1e30f32.to_bits(), 12, FloatOverflow::Indefinite),
            i32::MIN
        );
        // 0x54adc3f7 (~5.97e12) with 12 fraction bits: mantissa << 31. MAME keeps the low
        // 32 bits (0x80000000), DOSBox saturates, 86Box reads the x86 "indefinite" value.
        assert_eq!(float_to_fixed32(0x54ad_c3f7, 12, w), i32::MIN);
        assert_eq!(
            float_to_fixed32(0x54ad_c3f7, 12, FloatOverflow::Saturate),
            i32::MAX
        );
        assert_eq!(
            float_to_fixed32(0x54ad_c3f7, 12, FloatOverflow::Indefinite),
            i32::MIN
        );
        // NaN: exponent 255 -> 0x7fffffff, negated by the sign bit (MAME, DOSBox).
        assert_eq!(float_to_fixed32(0xffff_ffff, 12, w), -i32::MAX);
        assert_eq!(float_to_fixed64(0.5f32.to_bits(), 32), 1 << 31);
        assert_eq!(float_to_fixed64((-2.0f32).to_bits(), 32), -(2i64 << 32));
    }

    #[test]
    fn fixed_and_float_registers() {
        let mut p = TriangleParams::default();
        assert!(p.write_default(addr::START_R, 0x00ff_f000));
        assert_eq!(p.start[0], -4096);
        assert!(p.write_default(addr::START_A, 0x0001_0000));
        assert_eq!(p.start[3], 0x10000);
        assert!(p.write_default(addr::F_D_G_DY, 2.0f32.to_bits()));
        assert_eq!(p.dy[1], 2 << 12);
        assert!(p.write_default(addr::START_W, 0x4000_0000));
        assert_eq!(p.start_w, 1 << 32);
        assert!(p.write_default(addr::F_VERTEX_CY, 10.25f32.to_bits()));
        assert_eq!(p.cy, 164);
        assert!(!p.write_default(addr::FBZ_MODE, 0));
    }

    #[test]
    fn subpixel_adjust_writes_back() {
        let mut p = TriangleParams {
            ax: 16 * 3 + 4,
            ay: 16 * 2,
            ..Default::default()
        };
        p.dx[0] = 0x1000;
        p.dy[0] = 0x2000;
        assert_eq!(
            p.subpixel_adjust(SubpixelZ::Wrap32, ParamOrigin::VertexPixel),
            (4, 8)
        );
        // start += (8 * 0x2000 + 4 * 0x1000) >> 4
        assert_eq!(p.start[0], 0x1400);
        p.subpixel_adjust(SubpixelZ::Wrap32, ParamOrigin::VertexPixel);
        assert_eq!(p.start[0], 0x2800);
    }
}

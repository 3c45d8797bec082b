//! 86Box's structural behaviours of the Pixelfx: what the 86Box model does by another
//! construction than the chip's, not by another constant. The stages call these only
//! where a switch of the profile selects 86Box's behaviour, so no other model's
//! instance contains them.
//!
//! * the fixed-point edge walk ([`crate::setup::EdgeRounding::Box86Fixed`]);
//! * the per-triangle stipple copy ([`crate::profile::StippleRotate::PerTriangle`]).
//!
//! (86Box's rounded-vertex parameter origin is one expression,
//! [`crate::params::ParamOrigin::RoundedVertex`]; that its subpixel correction lasts one
//! triangle is the board's part, `sst1_board`'s `box86` module.)

use crate::params::TriangleParams;
use crate::setup::Span;

/// [`crate::setup::EdgeRounding::Box86Fixed`]'s walk. Source: 86Box `voodoo_triangle` (slopes, row
/// range) and `voodoo_half_triangle` (crossings, `+ 0x7000`, the empty-row test).
pub(crate) fn spans(p: &TriangleParams) -> impl Iterator<Item = Span> {
    let [ax, ay, bx, by, cx, cy] = [p.ax, p.ay, p.bx, p.by, p.cx, p.cy].map(i32::from);
    // 16.16 x per pixel of y, from 12.4 coordinates; 64-bit divide, truncated to 32 bits.
    let slope = |x0: i32, y0: i32, x1: i32, y1: i32| {
        if y1 == y0 {
            0
        } else {
            (((i64::from(x1) << 12) - (i64::from(x0) << 12)) << 4).wrapping_div(i64::from(y1 - y0))
                as i32
        }
    };
    let (d_ab, d_ac, d_bc) = (
        slope(ax, ay, bx, by),
        slope(ax, ay, cx, cy),
        slope(bx, by, cx, cy),
    );
    let right_to_left = p.right_to_left;
    let cross = |x0: i32, d: i32, dy: i32| (x0 << 12).wrapping_add(d.wrapping_mul(dy) >> 4);
    let pixel = |x: i32| x.wrapping_add(0x7000) >> 16;
    ((ay + 7) >> 4..(cy + 7) >> 4).filter_map(move |y| {
        let row = (y << 4) + 8;
        let long = cross(ax, d_ac, row - ay);
        let short = if row < by {
            cross(ax, d_ab, row - ay)
        } else {
            cross(bx, d_bc, row - by)
        };
        let (left, right) = if right_to_left {
            (short, long)
        } else {
            (long, short)
        };
        let (start, stop) = (pixel(left), pixel(right));
        (start < stop).then_some(Span { y, start, stop })
    })
}

/// 86Box's rotate-mode step (`StippleRotate::PerTriangle`): `(s << 1) | (s >> 31)` with
/// `s` a signed 32-bit `int`, so the right shift copies bit 31 into every bit.
#[inline]
pub fn stipple_step(s: u32) -> u32 {
    (s << 1) | ((s as i32) >> 31) as u32
}

/// [`crate::profile::StippleRotate::PerTriangle`]: one copy of the stipple register for
/// the whole triangle, stepped for every pixel in walk order. Source: 86Box
/// `voodoo_half_triangle`.
#[derive(Clone, Debug, Default)]
pub(crate) struct StippleCopy {
    /// The triangle's copy after the last pixel stepped.
    carried: u32,
    /// The stipple value each pixel of the current row tests, left to right.
    row: Vec<u32>,
}

impl StippleCopy {
    /// The copy at the start of a triangle: the register's value.
    pub(crate) fn new(stipple: u32) -> Self {
        Self {
            carried: stipple,
            row: Vec::new(),
        }
    }

    /// Steps the copy over the row's pixels `start..stop` in walk order (right to left
    /// when `triangleCMD` bit 31 says so) and keeps each pixel's value, rotated back by
    /// one because the stipple test rotates the value it is given left by one before
    /// testing bit 31.
    pub(crate) fn step_row(&mut self, start: i32, stop: i32, right_to_left: bool) {
        self.row.clear();
        for _ in start..stop {
            self.carried = stipple_step(self.carried);
            self.row.push(self.carried.rotate_right(1));
        }
        if right_to_left {
            self.row.reverse();
        }
    }

    /// The value the row's pixel `i` (from the row's start) tests.
    #[inline]
    pub(crate) fn at(&self, i: usize) -> u32 {
        self.row[i]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stipple_step_fills_with_ones_after_bit_31() {
        assert_eq!(stipple_step(0x4000_0001), 0x8000_0002);
        assert_eq!(stipple_step(0x8000_0002), 0xffff_ffff);
        assert_eq!(stipple_step(0xffff_ffff), 0xffff_ffff);
    }

    #[test]
    fn stipple_copy_carries_across_rows_in_walk_order() {
        let mut c = StippleCopy::new(0x4000_0001);
        c.step_row(0, 2, false);
        // Steps 0x80000002, then 0xffffffff; each kept rotated right by one.
        assert_eq!((c.at(0), c.at(1)), (0x4000_0001, 0xffff_ffff));
        let mut r = StippleCopy::new(0x4000_0001);
        r.step_row(0, 2, true);
        assert_eq!((r.at(0), r.at(1)), (0xffff_ffff, 0x4000_0001));
        // The next row continues from the carried value.
        c.step_row(5, 6, false);
        assert_eq!(c.at(0), 0xffff_ffff);
    }
}

//! TMU chaining (spec 3.2): TMU2 -> TMU1 -> TMU0 -> FBI. Each TMU's output is the next
//! one's `c_other`; the last TMU in the chain sees zero.

use pixelfx::TexelSource;
use sst1_regs::Rgba;
use texelfx::Tmu;

/// The TMUs taking part in a triangle, upstream last.
pub struct Chain<'a> {
    pub tmus: &'a mut [Tmu],
}

impl TexelSource for Chain<'_> {
    #[inline]
    fn texel(&mut self, dx: i32, dy: i32, x: i32, y: i32) -> Rgba {
        // Upstream first: the last TMU sees zero, each output feeds the next one down.
        let mut other = Rgba::default();
        for t in self.tmus.iter_mut().rev() {
            other = t.texel(dx, dy, x, y, other);
        }
        other
    }

    #[inline]
    fn begin_span(&mut self, dx: i32, dy: i32, len: usize) {
        for t in self.tmus.iter_mut() {
            t.begin_span(dx, dy, len);
        }
    }
}

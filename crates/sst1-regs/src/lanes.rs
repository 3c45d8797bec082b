//! The lanes of a span-kernel chunk, shared by the FBI's kernels (`pixelfx::span`) and
//! the TMUs' (`texelfx::span`): up to [`LANES`] pixels a chunk, one value per lane, and
//! where each lane's pixel lies ([`LanePlace`]). Not a register: a shape both chips'
//! kernels agree on, kept here because both crates read this one and neither the other.

/// The most pixels one chunk holds.
pub const LANES: usize = 64;

/// One value per lane.
pub type Lanes = [i32; LANES];

/// Where the lanes of a chunk lie: each lane's pixel offset from vertex A (what the
/// iterators are stepped by) and its screen position (what the dither matrices read).
#[derive(Clone, Copy, Debug)]
pub enum LanePlace<'a> {
    /// One span: lane `i` at offset `(dx0 + i, dy)`, screen position `(x0 + i, y)`.
    Row { dx0: i32, dy: i32, x0: i32, y: i32 },
    /// Pixels of several spans of one triangle, in the order the walk visits them: lane
    /// `i` at offset `(dx[i], dy[i])`, screen position `(x[i], y[i])`.
    Lanes {
        dx: &'a Lanes,
        dy: &'a Lanes,
        x: &'a Lanes,
        y: &'a Lanes,
    },
}

impl LanePlace<'_> {
    /// Lane `i`'s `(dx, dy, x, y)`.
    #[inline(always)]
    pub fn at(&self, i: usize) -> (i32, i32, i32, i32) {
        match *self {
            LanePlace::Row { dx0, dy, x0, y } => {
                (dx0.wrapping_add(i as i32), dy, x0.wrapping_add(i as i32), y)
            }
            LanePlace::Lanes { dx, dy, x, y } => {
                let i = i % LANES;
                (dx[i], dy[i], x[i], y[i])
            }
        }
    }
}

/// Which copy of the span kernels the lane code is compiled into (`pixelfx::isa`), as a
/// type: the kernels are written once and inlined into each copy, and a stage that has a
/// better form with one copy's instructions asks for it here, chosen when the copy is
/// compiled. Every form computes the same integers.
pub trait KernelCopy {
    /// The copy is compiled with AVX-512 F, DQ, CD, BW and VL. (The type proves nothing
    /// of the CPU: a form that uses these instructions itself checks that it has them.)
    const AVX512: bool;
}

/// The copy for the baseline target, or one without an instruction set of its own.
pub enum BaselineCopy {}

/// The copy compiled with AVX2.
pub enum Avx2Copy {}

/// The copy compiled with AVX-512.
pub enum Avx512Copy {}

impl KernelCopy for BaselineCopy {
    const AVX512: bool = false;
}

impl KernelCopy for Avx2Copy {
    const AVX512: bool = false;
}

impl KernelCopy for Avx512Copy {
    const AVX512: bool = true;
}

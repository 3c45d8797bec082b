//! The instruction sets the span kernels ([`crate::span`]) are compiled for.
//!
//! The kernels are written once, as loops over the lanes of a chunk, and compiled up to
//! three times: for the baseline target, with AVX2 and with AVX-512. Each copy computes
//! the same integers (the identity tests run every copy the CPU has against the
//! reference path); a copy only changes how many lanes one instruction handles, and
//! which operations have a vector instruction at all (AVX-512 DQ converts 64-bit
//! integers to doubles and multiplies them, which the textured lanes' S, T and W need;
//! CD counts leading zeros, which the LOD's logarithm needs; F gathers texels). Where a
//! stage has a form in one copy's own instructions that the compiler does not find from
//! the lane loop (the perspective divide's conversions, with AVX-512), the lane code is
//! told which copy it is compiled into by a type parameter ([`sst1_regs::lanes::KernelCopy`]),
//! so the choice is made when the copy is compiled.
//! Which copy runs is chosen per FBI ([`crate::Fbi::set_vector_isa`]): the best the CPU
//! has unless a caller caps it.

use std::fmt;
use std::str::FromStr;

/// A copy of the span kernels, by the instructions it may use; ordered from the fewest
/// to the most.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub enum VectorIsa {
    /// x86-64's baseline (SSE2), or any other architecture's default target.
    #[default]
    Baseline,
    /// AVX2 (x86-64-v3's vector instructions).
    Avx2,
    /// AVX-512 F, DQ, CD, BW and VL (x86-64-v4's).
    Avx512,
}

impl VectorIsa {
    /// Every copy, from the fewest instructions to the most.
    pub const ALL: [VectorIsa; 3] = [VectorIsa::Baseline, VectorIsa::Avx2, VectorIsa::Avx512];

    /// The best copy this CPU can run (found at run time).
    pub fn best() -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::is_x86_feature_detected as has;
            let avx512 = has!("avx512f") && has!("avx512dq") && has!("avx512cd");
            if avx512 && has!("avx512bw") && has!("avx512vl") {
                return VectorIsa::Avx512;
            }
            if has!("avx2") {
                return VectorIsa::Avx2;
            }
        }
        VectorIsa::Baseline
    }

    /// The copies this CPU can run, from the fewest instructions to the most.
    pub fn available() -> impl Iterator<Item = VectorIsa> {
        let best = Self::best();
        Self::ALL.into_iter().filter(move |&isa| isa <= best)
    }

    /// The name `--isa` and `VOODOO_ISA` take.
    pub fn name(self) -> &'static str {
        match self {
            VectorIsa::Baseline => "baseline",
            VectorIsa::Avx2 => "avx2",
            VectorIsa::Avx512 => "avx512",
        }
    }
}

impl fmt::Display for VectorIsa {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not one of [`VectorIsa::name`]'s.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownIsa;

impl fmt::Display for UnknownIsa {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("not baseline, avx2 or avx512")
    }
}

impl std::error::Error for UnknownIsa {}

impl FromStr for VectorIsa {
    type Err = UnknownIsa;

    fn from_str(s: &str) -> Result<Self, UnknownIsa> {
        Self::ALL
            .into_iter()
            .find(|isa| isa.name().eq_ignore_ascii_case(s))
            .ok_or(UnknownIsa)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_parse_back() {
        for isa in VectorIsa::ALL {
            assert_eq!(isa.name().parse::<VectorIsa>(), Ok(isa));
        }
        assert_eq!("AVX2".parse::<VectorIsa>(), Ok(VectorIsa::Avx2));
        assert_eq!("sse4".parse::<VectorIsa>(), Err(UnknownIsa));
    }

    #[test]
    fn available_ends_at_the_best() {
        let available: Vec<_> = VectorIsa::available().collect();
        assert_eq!(available.first(), Some(&VectorIsa::Baseline));
        assert_eq!(available.last(), Some(&VectorIsa::best()));
    }
}

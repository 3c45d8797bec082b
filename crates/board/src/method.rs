//! The methods a user can choose to draw with (`voodoo replay --method`, `VOODOO_METHOD`):
//! the two exact paths and deliberate approximations of the fast path that trade
//! exactness for speed (docs/methods.md).
//!
//! The hardware model and its exact fast path are the default. An approximate method
//! changes only how the TMUs' span kernels compute a chunk (`texelfx::Approx`, read once
//! per chunk); the register model, the FBI and every counter are the exact path's.

use texelfx::Approx;

/// How the board draws.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Method {
    /// The exact fast path: the span kernels (the default).
    #[default]
    Exact,
    /// The exact generic path, pixel by pixel ([`crate::Board::set_generic_path`]).
    Reference,
    /// Approximate: point sampling instead of bilinear filtering.
    Nearest,
    /// Approximate: the LOD once per chunk of a span (its first live pixel's) instead of
    /// per pixel.
    LodPerChunk,
    /// Approximate: the perspective divide in single precision.
    FloatDivide,
    /// Approximate: all three approximations at once.
    Fastest,
}

impl Method {
    /// Every method, the exact ones first.
    pub const ALL: [Method; 6] = [
        Method::Exact,
        Method::Reference,
        Method::Nearest,
        Method::LodPerChunk,
        Method::FloatDivide,
        Method::Fastest,
    ];

    /// The name a user types (`--method NAME`, `VOODOO_METHOD=NAME`).
    pub fn name(self) -> &'static str {
        match self {
            Method::Exact => "exact",
            Method::Reference => "reference",
            Method::Nearest => "nearest",
            Method::LodPerChunk => "lod-per-chunk",
            Method::FloatDivide => "float-divide",
            Method::Fastest => "fastest",
        }
    }

    /// The method named `name` (as [`Method::name`] spells it), if any.
    pub fn from_name(name: &str) -> Option<Method> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// One line: what the method does and, for an approximation, what it gives up.
    pub fn description(self) -> &'static str {
        match self {
            Method::Exact => "exact fast path: span kernels (the default)",
            Method::Reference => "exact generic path: pixel by pixel, every register read per pixel",
            Method::Nearest => {
                "approximate: point sampling instead of bilinear (loses the 4-bit filter fractions)"
            }
            Method::LodPerChunk => {
                "approximate: LOD once per chunk of up to 64 pixels (loses the LOD's change along a span)"
            }
            Method::FloatDivide => {
                "approximate: perspective divide in f32 (24-bit mantissa: texel coordinates move where S/W is large)"
            }
            Method::Fastest => "approximate: nearest + lod-per-chunk + float-divide",
        }
    }

    /// Whether the method draws exactly what the hardware model draws.
    pub fn is_exact(self) -> bool {
        matches!(self, Method::Exact | Method::Reference)
    }

    /// The TMUs' approximations for this method.
    pub fn approx(self) -> Approx {
        let all = Approx {
            point_sampling: true,
            lod_per_chunk: true,
            float_divide: true,
        };
        match self {
            Method::Exact | Method::Reference => Approx::EXACT,
            Method::Nearest => Approx {
                point_sampling: true,
                ..Approx::EXACT
            },
            Method::LodPerChunk => Approx {
                lod_per_chunk: true,
                ..Approx::EXACT
            },
            Method::FloatDivide => Approx {
                float_divide: true,
                ..Approx::EXACT
            },
            Method::Fastest => all,
        }
    }
}

impl core::fmt::Display for Method {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::Method;

    #[test]
    fn names_round_trip_and_only_two_methods_are_exact() {
        for m in Method::ALL {
            assert_eq!(Method::from_name(m.name()), Some(m));
            assert_eq!(m.is_exact(), m.approx().is_exact(), "{m}");
        }
        assert_eq!(Method::from_name("bilinear"), None);
        let exact: Vec<_> = Method::ALL.into_iter().filter(|m| m.is_exact()).collect();
        assert_eq!(exact, [Method::Exact, Method::Reference]);
    }
}

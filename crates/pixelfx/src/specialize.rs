//! Specialised triangle walkers: the pixel pipeline compiled with the mode registers of
//! common drawing states folded in as constants (style guide point 11; the idea follows
//! MAME's `voodoo_renderer` predefined rasterizer table).
//!
//! [`crate::pipeline`] is written once against `fbzColorPath`, `alphaMode`, `fogMode`
//! and `fbzMode`. Each of the four is a const generic parameter of the walker
//! ([`Known`]: a mask of the bits known at compile time and their values). The
//! instantiation that knows nothing ([`LIVE`] x 4) is the generic path; one that
//! knows a register's bits is the same code after constant folding: bit tests vanish,
//! the combine units' input selections become fixed and disabled stages are dropped.
//!
//! [`table_walker`] gives the walker for a triangle: the entry of [`SPECIALISED`] whose
//! key equals the triangle's [`RasterKey`], otherwise none (the model's generic walker
//! runs). A model offers the table through [`PixelModel::specialised`] (the board's
//! fixed models do; the run-time-profile model does not). A key holds every bit the FBI
//! stores (only `alphaMode.alpha_ref` is left out and read at run time), so a
//! specialised walker computes with exactly the values the generic walker reads.
//! `crates/board/tests/generic_vs_fast.rs` replays every trace both ways and requires
//! identical buffers and counters; `Board::set_generic_path` / [`Fbi::set_generic_path`]
//! force the generic walker.
//!
//! To find candidates for the table: `cargo bench -p sst1-board --bench replay --
//! --dump-raster-stats [TRACE-FILTER...]` prints the keys of the replayed triangles in
//! the table's own syntax, most pixels first.

use sst1_regs::{addr, map};

use crate::fbi::Fbi;
use crate::model::{PixelModel, Walker};
use crate::pipeline::DrawState;
use crate::raster::TexelSource;

/// A mode register as a const generic parameter: the high word is a mask of the bits
/// known at compile time, the low word their values; the other bits are read at run
/// time. Built with `known_bits`, applied with `value`.
pub type Known = u64;

/// Nothing known: read the whole register at run time (the generic path).
pub const LIVE: Known = 0;

/// The bits of each register that an exact key covers. The FBI masks unimplemented bits
/// on write (spec 5 register table), so these are all the bits `fbzColorPath`, `fogMode`
/// and `fbzMode` can hold; `alphaMode` leaves out [`ALPHA_REF_BITS`].
pub const COLOR_PATH_BITS: u32 = map::mask_of(addr::FBZ_COLOR_PATH);
/// See [`COLOR_PATH_BITS`].
pub const ALPHA_MODE_BITS: u32 = map::mask_of(addr::ALPHA_MODE) & !ALPHA_REF_BITS;
/// See [`COLOR_PATH_BITS`].
pub const FOG_MODE_BITS: u32 = map::mask_of(addr::FOG_MODE);
/// See [`COLOR_PATH_BITS`].
pub const FBZ_MODE_BITS: u32 = map::mask_of(addr::FBZ_MODE);

/// The `alphaMode` bits that are never part of a key: `alpha_ref` (bits 31:24) is only a
/// comparison operand, cheap to read at run time, and varies between otherwise equal
/// states.
pub const ALPHA_REF_BITS: u32 = 0xff00_0000;

/// A [`Known`] with the bits of `mask` known to be those of `value`.
pub const fn known_bits(mask: u32, value: u32) -> Known {
    (mask as u64) << 32 | (value & mask) as u64
}

/// The register value a walker uses: the known bits of `k`, the others from `live`.
/// The caller guarantees that the known bits equal `live`'s, so this is always `live`;
/// written this way the compiler sees the known bits as constants.
#[inline(always)]
pub(crate) const fn value(k: Known, live: u32) -> u32 {
    let mask = (k >> 32) as u32;
    (live & !mask) | k as u32
}

/// `[f(0), f(1), f(2)]`: one value per colour channel. The same as
/// `core::array::from_fn`, written out so that the compiler inlines the channel
/// arithmetic into the pixel loop instead of calling it three times.
#[inline(always)]
pub(crate) fn per_channel(mut f: impl FnMut(usize) -> i32) -> [i32; 3] {
    [f(0), f(1), f(2)]
}

/// The mode registers that select a specialised walker, as stored in the register file
/// (the FBI masks unimplemented bits on write).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct RasterKey {
    /// `fbzColorPath`.
    pub color_path: u32,
    /// `alphaMode` without [`ALPHA_REF_BITS`].
    pub alpha_mode: u32,
    /// `fogMode`.
    pub fog_mode: u32,
    /// `fbzMode`.
    pub fbz_mode: u32,
}

impl RasterKey {
    /// The key of the registers currently in `fbi` (what the next triangle would use).
    pub fn of(fbi: &Fbi) -> Self {
        Self {
            color_path: fbi.reg(addr::FBZ_COLOR_PATH) & COLOR_PATH_BITS,
            alpha_mode: fbi.reg(addr::ALPHA_MODE) & ALPHA_MODE_BITS,
            fog_mode: fbi.reg(addr::FOG_MODE) & FOG_MODE_BITS,
            fbz_mode: fbi.reg(addr::FBZ_MODE) & FBZ_MODE_BITS,
        }
    }

    /// The key of a captured drawing state.
    #[inline]
    pub(crate) fn of_state(st: &DrawState) -> Self {
        Self {
            color_path: st.color_path.0 & COLOR_PATH_BITS,
            alpha_mode: st.alpha_mode.0 & ALPHA_MODE_BITS,
            fog_mode: st.fog_mode.0 & FOG_MODE_BITS,
            fbz_mode: st.mode.0 & FBZ_MODE_BITS,
        }
    }

    /// Whether [`SPECIALISED`] has a walker for this key.
    pub fn is_specialised(&self) -> bool {
        SPECIALISED.contains(&(
            self.color_path,
            self.alpha_mode,
            self.fog_mode,
            self.fbz_mode,
        ))
    }

    /// The key as an entry of the [`SPECIALISED`] table.
    pub fn table_entry(&self) -> String {
        format!(
            "(0x{:08x}, 0x{:08x}, 0x{:02x}, 0x{:06x}),",
            self.color_path, self.alpha_mode, self.fog_mode, self.fbz_mode
        )
    }
}

/// Defines [`SPECIALISED`] and the `match` in [`table_walker`] from one list, so that the two
/// cannot drift apart.
macro_rules! specialised {
    ($( $(#[$doc:meta])* ($cp:literal, $am:literal, $fm:literal, $zm:literal), )*) => {
        /// The keys with a specialised walker: `(fbzColorPath, alphaMode & !alpha_ref,
        /// fogMode, fbzMode)`. Each entry names the trace it came from and how many
        /// triangles and pixels (`fbiPixelsIn`) of the conformance and glide-sdk traces it
        /// drew when it was added.
        pub const SPECIALISED: &[(u32, u32, u32, u32)] = &[$(($cp, $am, $fm, $zm)),*];

        /// Model `M`'s walker specialised for `key`, if the table has the key. A model
        /// offers these through [`PixelModel::specialised`].
        pub fn table_walker<M: PixelModel, T: TexelSource>(key: RasterKey) -> Option<Walker<T>> {
            match (key.color_path, key.alpha_mode, key.fog_mode, key.fbz_mode) {
                $(
                    ($cp, $am, $fm, $zm) => Some(Fbi::walk::<
                        M,
                        T,
                        { known_bits(COLOR_PATH_BITS, $cp) },
                        { known_bits(ALPHA_MODE_BITS, $am) },
                        { known_bits(FOG_MODE_BITS, $fm) },
                        { known_bits(FBZ_MODE_BITS, $zm) },
                    >),
                )*
                _ => None,
            }
        }
    };
}

specialised! {
    /// perf_tex_heavy: 720 triangles, 134370126 pixels.
    (0x08482405, 0x00005110, 0x01, 0x004739),
    /// perf_gouraud_heavy: 726 triangles, 133125329 pixels.
    (0x00000000, 0x00000000, 0x00, 0x004201),
    /// test00: 4864 triangles, 3064320 pixels.
    (0x00000002, 0x00000000, 0x00, 0x000300),
    /// tex_2tmu_modulate: 58 triangles, 1586600 pixels.
    (0x08000005, 0x00000000, 0x00, 0x004600),
    /// chroma_key: 81 triangles, 1549825 pixels.
    (0x00000000, 0x00000000, 0x00, 0x004600),
    /// stress_random: 90 triangles, 1205103 pixels.
    (0x08000005, 0x00000000, 0x00, 0x004639),
    /// board_2mb: 44 triangles, 1158089 pixels.
    (0x00000000, 0x00000000, 0x00, 0x004731),
    /// test02: 1200 triangles, 1048698 pixels.
    (0x0400613a, 0x00040400, 0x00, 0x084321),
    /// board_2mb: 82 triangles, 955505 pixels.
    (0x08482405, 0x00000000, 0x00, 0x004731),
    /// test18: 600 triangles, 921600 pixels.
    (0x0542613a, 0x00000410, 0x00, 0x084321),
    /// tex_8bit_formats: 50 triangles, 790784 pixels.
    (0x08000005, 0x00005110, 0x00, 0x004600),
    /// alpha_blend: 62 triangles, 665790 pixels.
    (0x00000000, 0x00000000, 0x00, 0x004601),
    /// test00: 6186 triangles, 528144 pixels.
    (0x0c002435, 0x00045110, 0x00, 0x0843e1),
    /// test30: 12 triangles, 523820 pixels.
    (0x0400612a, 0x00040400, 0x00, 0x094731),
    /// alpha_blend_dither: 51 triangles, 511800 pixels.
    (0x00000000, 0x00000000, 0x00, 0x004701),
    /// test08: 3 triangles, 460647 pixels.
    (0x0400612a, 0x00040400, 0x01, 0x084321),
    /// test18: 6 triangles, 331776 pixels.
    (0x0c000035, 0x00005110, 0x00, 0x084321),
    /// test06: 6 triangles, 325518 pixels.
    (0x0400613a, 0x00040400, 0x00, 0x094739),
    /// test14: 6 triangles, 325518 pixels.
    (0x0400613a, 0x00040400, 0x00, 0x094791),
    /// fog_table: 17 triangles, 311480 pixels.
    (0x00000000, 0x00000000, 0x01, 0x004639),
    /// board_2mb: 19 triangles, 278372 pixels.
    (0x08000005, 0x00000000, 0x00, 0x004631),
    /// depth_z: 30 triangles, 263957 pixels.
    (0x00000000, 0x00000000, 0x00, 0x0046f1),
    /// test04: 12 triangles, 242496 pixels.
    (0x0400612a, 0x00040400, 0x00, 0x084321),
    /// test10: 3 triangles, 221184 pixels.
    (0x0400613a, 0x00040400, 0x00, 0x0a4321),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn key_masks_are_the_spec_tables() {
        assert_eq!(COLOR_PATH_BITS, 0x0fff_ffff);
        assert_eq!(ALPHA_MODE_BITS, 0x00ff_ffff);
        assert_eq!(FOG_MODE_BITS, 0x3f);
        assert_eq!(FBZ_MODE_BITS, 0x001f_ffff);
    }

    #[test]
    fn known_bits_combine_with_live_bits() {
        assert_eq!(value(LIVE, 0x1234), 0x1234);
        assert_eq!(value(known_bits(0xff, 0x34), 0x1234), 0x1234);
        assert_eq!(known_bits(0xff, 0x1234), 0xff_0000_0034);
        let alpha = known_bits(ALPHA_MODE_BITS, 0x0000_0011);
        assert_eq!(value(alpha, 0x8000_0011), 0x8000_0011);
        assert_eq!(value(LIVE, 0xffff_ffff), 0xffff_ffff);
    }

    #[test]
    fn table_entries_are_unique_and_keys_are_in_register_range() {
        for (i, e) in SPECIALISED.iter().enumerate() {
            assert!(!SPECIALISED[..i].contains(e), "duplicate entry {e:x?}");
            // Only bits a key covers, or the entry could never match.
            assert_eq!(e.0 & !COLOR_PATH_BITS, 0, "{e:x?}");
            assert_eq!(e.1 & !ALPHA_MODE_BITS, 0, "{e:x?}");
            assert_eq!(e.2 & !FOG_MODE_BITS, 0, "{e:x?}");
            assert_eq!(e.3 & !FBZ_MODE_BITS, 0, "{e:x?}");
        }
    }
}

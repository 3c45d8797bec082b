//! 86Box's structural behaviours at the board level (see `pixelfx::box86` and texelfx's
//! for the chips' own).
//!
//! With [`pixelfx::params::ParamOrigin::RoundedVertex`] the subpixel correction moves the
//! start values in a copy that lasts one triangle (86Box `voodoo_triangle`:
//! `state.base_*`), where the chip writes them back (spec 5.16's "Important Note"). The
//! board saves the FBI's parameter registers and the TMUs' start registers before the
//! correction and restores them after the triangle.

use pixelfx::params::TriangleParams;
use pixelfx::Fbi;
use texelfx::Tmu;

/// The parameter and start registers before a triangle's subpixel correction.
pub(crate) struct StartRegisters {
    params: TriangleParams,
    tmu_starts: Vec<[i64; 3]>,
}

impl StartRegisters {
    /// What the correction of the next triangle is about to change.
    pub(crate) fn save(fbi: &Fbi, tmus: &[Tmu]) -> Self {
        Self {
            params: fbi.params,
            tmu_starts: tmus.iter().map(Tmu::start_registers).collect(),
        }
    }

    /// Puts them back after the triangle.
    pub(crate) fn restore(self, fbi: &mut Fbi, tmus: &mut [Tmu]) {
        fbi.params = self.params;
        for (t, start) in tmus.iter_mut().zip(self.tmu_starts) {
            t.restore_start_registers(start);
        }
    }
}

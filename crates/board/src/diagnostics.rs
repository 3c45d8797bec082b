//! Guest oddities: things a driver did that the board ignores, counted by category
//! instead of panicking or logging per occurrence.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A category of guest oddity.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum Diagnostic {
    /// A write to a reserved register offset (ignored, as on hardware).
    ReservedWrite,
    /// A write to a read-only register (ignored).
    ReadOnlyWrite,
    /// An `fbiInit*` write while `initEnable` bit 0 is clear (ignored, spec 5.42).
    InitWriteDisabled,
    /// A read of a write-only or TMU-only register (returns the FBI's stored value).
    WriteOnlyRead,
    /// A write to texture memory of a TMU the board does not have.
    MissingTmu,
    /// A PCI configuration write the board does not model.
    UnmodelledPci,
    /// A 16-bit write to a register or to texture memory, which take 32-bit writes
    /// only (spec 4, 9; ignored).
    NarrowWrite,
}

/// Counts per [`Diagnostic`] category.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Diagnostics {
    counts: BTreeMap<Diagnostic, u64>,
}

impl Diagnostics {
    /// Count one occurrence.
    pub fn note(&mut self, d: Diagnostic) {
        *self.counts.entry(d).or_default() += 1;
    }

    /// How often `d` happened.
    pub fn count(&self, d: Diagnostic) -> u64 {
        self.counts.get(&d).copied().unwrap_or(0)
    }

    /// Every category seen, with its count.
    pub fn iter(&self) -> impl Iterator<Item = (Diagnostic, u64)> + '_ {
        self.counts.iter().map(|(&d, &n)| (d, n))
    }

    /// True if nothing odd happened.
    pub fn is_empty(&self) -> bool {
        self.counts.is_empty()
    }
}

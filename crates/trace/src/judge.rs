//! The conformance pass rule of `traces/conformance/README.md`, for one dump against the
//! goldens of the reference emulators.
//!
//! Per pixel: where every golden holds the same value (consensus) ours must equal it;
//! where two of three agree (majority) ours must equal them; where all differ nothing is
//! required. With two goldens only, a pixel counts only where both agree.

use std::path::Path;

/// What the pass rule requires of one pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// All goldens agree on this value.
    Consensus(u16),
    /// Two of three agree on this value.
    Majority(u16),
    /// No requirement.
    Free,
}

impl Rule {
    /// The rule for one pixel given the goldens' values (two or three of them).
    pub fn of(values: &[u16]) -> Rule {
        match *values {
            [a, b] if a == b => Rule::Consensus(a),
            [a, b, c] if a == b && b == c => Rule::Consensus(a),
            [a, b, c] if a == b || a == c => Rule::Majority(a),
            [_, b, c] if b == c => Rule::Majority(b),
            _ => Rule::Free,
        }
    }

    /// Whether `value` breaks the rule.
    pub fn broken_by(self, value: u16) -> bool {
        match self {
            Rule::Consensus(v) | Rule::Majority(v) => value != v,
            Rule::Free => false,
        }
    }
}

/// How one dump fares against its goldens.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Judgement {
    /// The rule of every pixel, in the goldens' order.
    pub rules: Vec<Rule>,
    /// Whether ours has the goldens' size (if not, every required pixel fails).
    pub same_size: bool,
    /// Consensus pixels ours misses.
    pub consensus_fail: u64,
    /// Majority pixels ours misses.
    pub majority_fail: u64,
    /// Pixels where all goldens differ.
    pub free: u64,
}

impl Judgement {
    /// Pixels that break the rule.
    pub fn failing(&self) -> u64 {
        self.consensus_fail + self.majority_fail
    }
}

/// Judges `ours` against `goldens` (two or three buffers of one size; more are ignored,
/// fewer than two judge nothing).
pub fn judge(goldens: &[&[u16]], ours: &[u16]) -> Judgement {
    let goldens = &goldens[..goldens.len().min(3)];
    let len = if goldens.len() >= 2 {
        goldens.iter().map(|g| g.len()).min().unwrap_or(0)
    } else {
        0
    };
    let same_size = goldens.iter().all(|g| g.len() == ours.len());
    let mut j = Judgement {
        rules: Vec::with_capacity(len),
        same_size,
        consensus_fail: 0,
        majority_fail: 0,
        free: 0,
    };
    let mut values = [0u16; 3];
    for i in 0..len {
        for (v, g) in values.iter_mut().zip(goldens) {
            *v = g[i];
        }
        let rule = Rule::of(&values[..goldens.len()]);
        let fails = match ours.get(i) {
            Some(&v) if same_size => rule.broken_by(v),
            _ => rule != Rule::Free,
        };
        match rule {
            Rule::Free => j.free += 1,
            Rule::Consensus(_) => j.consensus_fail += u64::from(fails),
            Rule::Majority(_) => j.majority_fail += u64::from(fails),
        }
        j.rules.push(rule);
    }
    j
}

/// The largest golden dump [`load_golden`] reads, compressed or not: 64 MiB, twice the
/// largest buffer a video mode can have (4095 × 4095 values of 2 bytes).
pub const MAX_GOLDEN: u64 = 64 << 20;

/// Reads a golden dump: little-endian 16-bit values, gzip-compressed or not, at most
/// [`MAX_GOLDEN`] bytes either way. `None` if the file is missing, not a regular file
/// (never opened, so a FIFO cannot block), unreadable or too large.
pub fn load_golden(path: &Path) -> Option<Vec<u16>> {
    if !std::fs::metadata(path).ok()?.is_file() {
        return None;
    }
    let bytes = crate::read_file_bounded(path, MAX_GOLDEN).ok()?;
    let raw = crate::gunzip_with_limit(&bytes, MAX_GOLDEN).ok()?;
    Some(
        raw.chunks_exact(2)
            .map(|b| u16::from_le_bytes([b[0], b[1]]))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_for_two_and_three_goldens() {
        assert_eq!(Rule::of(&[5, 5]), Rule::Consensus(5));
        assert_eq!(Rule::of(&[5, 6]), Rule::Free);
        assert_eq!(Rule::of(&[5, 5, 5]), Rule::Consensus(5));
        assert_eq!(Rule::of(&[5, 5, 6]), Rule::Majority(5));
        assert_eq!(Rule::of(&[5, 6, 5]), Rule::Majority(5));
        assert_eq!(Rule::of(&[6, 5, 5]), Rule::Majority(5));
        assert_eq!(Rule::of(&[4, 5, 6]), Rule::Free);
    }

    #[test]
    fn counts_failures_by_kind() {
        let m: &[u16] = &[1, 1, 1, 4, 9];
        let d: &[u16] = &[1, 2, 3, 4, 8];
        let b: &[u16] = &[1, 2, 3, 5, 7];
        // Pixel 0 consensus 1; 1 majority 2; 2 majority 3; 3 majority 4; 4 free.
        let j = judge(&[m, d, b], &[1, 2, 0, 5, 0]);
        assert_eq!((j.consensus_fail, j.majority_fail, j.free), (0, 2, 1));
        let j = judge(&[m, d, b], &[0, 2, 3, 4, 0]);
        assert_eq!((j.consensus_fail, j.majority_fail, j.failing()), (1, 0, 1));
        // A buffer of another size fails every required pixel.
        let j = judge(&[m, d, b], &[1, 2]);
        assert!(!j.same_size);
        assert_eq!(j.failing(), 4);
    }
}

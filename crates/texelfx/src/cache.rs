//! Decoded-texel cache: the texels of the bound texture, decoded to ARGB one LOD at a time
//! on first use.
//!
//! The hardware reads texels from its memory for every pixel; decoding them again for
//! every pixel (and for every one of the four bilinear neighbours) costs more than reading
//! a decoded copy. A level is decoded with the same fetch the uncached path uses
//! ([`crate::Tmu::set_generic_path`] turns the cache off), so both give identical texels:
//! `crates/board/tests/generic_vs_fast.rs` replays every trace both ways.
//!
//! A cached level is dropped exactly when something it was decoded from changes:
//! - a texture download that writes a byte inside the level's memory span;
//! - a change of the texture's layout (`textureMode` format, `tLOD`, `texBaseAddr*`);
//! - a change of the 256-entry decode table (format, NCC table in use, palette, profile).
//!
//! Register writes that leave all three alone (the combine bits of `textureMode`, `tDetail`,
//! an NCC table the format does not use) keep the cache. Writes arrive between triangles,
//! so the next triangle always sees them.

use crate::layout::Layout;

/// Decoded levels of the bound texture.
pub(crate) struct TexelCache {
    /// Decoded texels (`0xAARRGGBB`) of each LOD, row-major with `smax(lod) + 1` per row.
    levels: [Vec<u32>; 9],
    /// Bit n set when `levels[n]` holds LOD n of the current texture.
    valid: u16,
    /// Memory span `(first byte, length)` each valid level was decoded from.
    spans: [(u32, u32); 9],
    /// Of each level paired ([`TexelCache::pair`]), every texel with its right-hand
    /// neighbour in the row (wrapping to the row's first): `texel | neighbour << 32`, so
    /// that a bilinear fetch reads two taps in one load.
    pairs: [Vec<u64>; 9],
    /// Bit n set when `pairs[n]` was built from `levels[n]` as it is (valid only while
    /// the level is).
    paired: u16,
}

impl TexelCache {
    /// An empty cache.
    pub fn new() -> Self {
        Self {
            levels: Default::default(),
            valid: 0,
            spans: [(0, 0); 9],
            pairs: Default::default(),
            paired: 0,
        }
    }

    /// Drops every level.
    pub fn clear(&mut self) {
        self.valid = 0;
        self.paired = 0;
    }

    /// Whether LOD `lod` is decoded.
    #[inline(always)]
    pub fn has(&self, lod: usize) -> bool {
        self.valid >> lod & 1 != 0
    }

    /// The decoded levels: bit n set when LOD n is ([`TexelCache::has`]).
    #[inline(always)]
    pub fn valid(&self) -> u32 {
        u32::from(self.valid)
    }

    /// Stores LOD `lod` of `layout`, decoded into `texels`.
    pub fn fill(&mut self, lod: usize, layout: &Layout, texels: Vec<u32>) {
        let len = (texels.len() as u32) << layout.bpp_shift;
        self.spans[lod] = (layout.lod_base[lod], len);
        self.levels[lod] = texels;
        self.valid |= 1 << lod;
        self.paired &= !(1 << lod);
    }

    /// Builds the pairs of LOD `lod` (valid), whose rows are `width` texels wide
    /// ([`TexelCache::pairs`]); a level that is not whole rows of `width` (none should
    /// be) gets none.
    pub fn pair(&mut self, lod: usize, width: u32) {
        let level = &self.levels[lod];
        let width = width as usize;
        if !self.has(lod) || width == 0 || !level.len().is_multiple_of(width) {
            return;
        }
        let pairs = &mut self.pairs[lod];
        pairs.clear();
        pairs.reserve(level.len());
        for row in level.chunks_exact(width) {
            let next = row[1..].iter().chain(&row[..1]);
            pairs.extend(
                row.iter()
                    .zip(next)
                    .map(|(&a, &b)| u64::from(a) | u64::from(b) << 32),
            );
        }
        self.paired |= 1 << lod;
    }

    /// The pairs of LOD `lod` ([`TexelCache::pair`]), where they were built from the level
    /// as it is.
    #[inline(always)]
    pub fn pairs(&self, lod: usize) -> Option<&[u64]> {
        (self.valid & self.paired & (1 << lod) != 0).then(|| &self.pairs[lod][..])
    }

    /// Exchanges the levels and their valid bits with `levels` and `valid` (how the 86Box
    /// texture cache, `crate::box86`, lends an entry for a triangle).
    pub fn swap_storage(&mut self, levels: &mut [Vec<u32>; 9], valid: &mut u16) {
        std::mem::swap(&mut self.levels, levels);
        std::mem::swap(&mut self.valid, valid);
        self.paired = 0;
    }

    /// A buffer to decode LOD `lod` into: the level's old storage, emptied.
    pub fn take_buffer(&mut self, lod: usize) -> Vec<u32> {
        self.valid &= !(1 << lod);
        self.paired &= !(1 << lod);
        let mut v = std::mem::take(&mut self.levels[lod]);
        v.clear();
        v
    }

    /// The decoded texel `(s, t)` of a valid LOD whose rows are `width` texels wide.
    #[inline(always)]
    pub fn texel(&self, lod: usize, width: u32, s: u32, t: u32) -> u32 {
        let level = &self.levels[lod];
        let i = (t * width + s) as usize;
        // A valid level holds every (s, t) of the layout it was decoded for; the fallback
        // only guards against a caller bug.
        level.get(i).copied().unwrap_or(0)
    }

    /// The levels and their valid bits (what a save state keeps of a lent 86Box entry).
    pub fn storage(&self) -> (&[Vec<u32>; 9], u16) {
        (&self.levels, self.valid)
    }

    /// The decoded texels of LOD `lod` (empty or stale unless [`TexelCache::has`] it).
    #[inline(always)]
    pub fn level(&self, lod: usize) -> &[u32] {
        &self.levels[lod]
    }

    /// Memory bytes `[addr, addr + len)` (wrapping at `mem_mask + 1`) were written: drops
    /// every level decoded from one of them.
    pub fn written(&mut self, addr: u32, len: u32, mem_mask: u32) {
        let mut valid = self.valid;
        while valid != 0 {
            let lod = valid.trailing_zeros() as usize;
            valid &= valid - 1;
            let (start, span) = self.spans[lod];
            let overlaps = (addr.wrapping_sub(start) & mem_mask) < span
                || (start.wrapping_sub(addr) & mem_mask) < len;
            if overlaps {
                self.valid &= !(1 << lod);
                self.paired &= !(1 << lod);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MEM: u32 = (1 << 20) - 1;

    fn cache_with_level(lod: usize, base_units: u32) -> (TexelCache, Layout) {
        // 16-bit texels, 256x256 LOD 0.
        let layout = Layout::new(10 << 8, 0, &[base_units, 0, 0, 0], MEM);
        let mut c = TexelCache::new();
        let n = ((layout.smax(lod) + 1) * (layout.tmax(lod) + 1)) as usize;
        c.fill(lod, &layout, vec![7; n]);
        (c, layout)
    }

    #[test]
    fn write_inside_a_level_drops_only_that_level() {
        let (mut c, layout) = cache_with_level(2, 0);
        let n = ((layout.smax(3) + 1) * (layout.tmax(3) + 1)) as usize;
        c.fill(3, &layout, vec![1; n]);
        // LOD 2 of 64x64 16-bit texels: 0x2000 bytes from 0x28000.
        assert_eq!(layout.lod_base[2], 0x28000);
        c.written(0x27ffc, 4, MEM);
        assert!(c.has(2) && c.has(3), "the word before the level");
        c.written(0x29ffc, 4, MEM);
        assert!(!c.has(2), "the level's last word");
        assert!(c.has(3));
        c.written(0x2a000, 2, MEM);
        assert!(!c.has(3), "LOD 3's first texel");
    }

    #[test]
    fn spans_wrap_at_the_end_of_memory() {
        // LOD 0 of 0x20000 bytes starting 0x8000 below the end of 1 MiB.
        let (mut c, _) = cache_with_level(0, (MEM + 1 - 0x8000) >> 3);
        c.written(0x10_0000 + 0x20000 - 0x8000, 4, MEM);
        assert!(c.has(0), "first byte after the wrapped level");
        c.written(0x100, 4, MEM);
        assert!(!c.has(0), "wrapped part of the level");
    }

    #[test]
    fn a_write_straddling_the_level_start_drops_it() {
        let (mut c, layout) = cache_with_level(1, 0);
        c.written(layout.lod_base[1] - 2, 4, MEM);
        assert!(!c.has(1));
    }

    #[test]
    fn texel_lookup_and_clear() {
        let (mut c, layout) = cache_with_level(1, 0);
        assert_eq!(c.texel(1, layout.smax(1) + 1, 5, 9), 7);
        c.clear();
        assert!(!c.has(1));
    }
}

//! 86Box's structural behaviours of the Texelfx: its texture cache, as a behaviour
//! ([`crate::TextureCacheKey::Box86`]). (Its chain shortcuts are `sst1-chain`'s.)
//!
//! 86Box decodes a texture when a triangle first uses it and keeps the decoded texels in a
//! 64-entry cache keyed by the base address, `tLOD & 0xf00fff` and, for the palette
//! formats, an XOR checksum of the palette (`voodoo_use_texture`). The texture format,
//! the NCC table in use and the NCC table contents are not part of the key, so a triangle
//! that binds the same memory with another format or table reads the texels decoded for
//! the first one. An entry is dropped only when a texture download writes into its memory
//! span, rounded out to 1 KiB (`flush_texture_cache`).
//!
//! Here the entry bound by a triangle is lent to the TMU's decoded-texel cache
//! ([`crate::cache::TexelCache`]) for the triangle, and taken back before the next register
//! or texture write.

use sst1_regs::{TLod, TextureMode};

use crate::Tmu;

impl Tmu {
    /// [`crate::TextureCacheKey::Box86`]: lends the cached decode of the bound texture to `cache`
    /// for this triangle, decoding it first (every level, with the state in force) if no
    /// entry has its key. Source: 86Box `voodoo_use_texture`.
    pub(crate) fn box86_bind(&mut self) {
        self.box86_return();
        if self.lut_stale {
            self.rebuild_lut();
        }
        let format = TextureMode(self.texture_mode).format() as u32;
        let palette = if matches!(format, 5 | 6 | 14) {
            // 86Box XORs the stored 0xffRRGGBB words; the 256 0xff bytes cancel.
            self.palette.iter().fold(0, |x, &[r, g, b]| {
                x ^ (u32::from(r) << 16 | u32::from(g) << 8 | u32::from(b))
            })
        } else {
            0
        };
        let key = Key {
            base: self.tex_base[0],
            t_lod: self.t_lod & 0x00f0_0fff,
            palette,
        };
        let i = match self.box86.find(key) {
            Some(i) => i,
            None => {
                self.cache.clear();
                let t_lod = TLod(self.t_lod);
                let (lo, hi) = (
                    (t_lod.lodmin() >> 2) as usize,
                    (t_lod.lodmax() >> 2) as usize,
                );
                let (mut first, mut last) = (u32::MAX, 0);
                for lod in 0..9 {
                    if (self.layout.lodmask >> lod) & 1 == 0 {
                        continue;
                    }
                    self.decode_level(lod);
                    if (lo..=hi.min(8)).contains(&lod) {
                        let texels = (self.layout.smax(lod) + 1) * (self.layout.tmax(lod) + 1);
                        let base = self.layout.lod_base[lod];
                        first = first.min(base);
                        last = last.max(base + (texels << self.layout.bpp_shift) - 1);
                    }
                }
                let mut entry = Entry {
                    key,
                    levels: Default::default(),
                    valid: 0,
                    span: if first <= last {
                        page_span(first, last)
                    } else {
                        (0, 0)
                    },
                };
                self.cache.swap_storage(&mut entry.levels, &mut entry.valid);
                self.box86.insert(entry)
            }
        };
        let (levels, valid) = self.box86.storage(i);
        self.cache.swap_storage(levels, valid);
        self.box86.lent = Some(i);
    }

    /// Takes a lent 86Box entry back from `cache` (before any register or texture write).
    pub(crate) fn box86_return(&mut self) {
        if let Some(i) = self.box86.lent.take() {
            let (levels, valid) = self.box86.storage(i);
            self.cache.swap_storage(levels, valid);
            self.cache.clear();
        }
    }
}

/// The key 86Box finds a decoded texture by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Key {
    /// `texBaseAddr` as written.
    pub base: u32,
    /// `tLOD & 0xf00fff`: LOD range, aspect and S-is-wider, split and odd.
    pub t_lod: u32,
    /// XOR of the palette entries for the palette formats, else 0.
    pub palette: u32,
}

/// One decoded texture.
pub(crate) struct Entry {
    pub key: Key,
    /// Decoded levels, as [`crate::cache::TexelCache`] holds them.
    pub levels: [Vec<u32>; 9],
    /// Bit n set when `levels[n]` is decoded.
    pub valid: u16,
    /// Memory span `[start, end)` whose writes drop the entry (1 KiB granularity).
    pub span: (u32, u32),
}

/// How many textures 86Box keeps per TMU (`TEX_CACHE_MAX`).
pub(crate) const CAPACITY: usize = 64;

/// The cache of one TMU.
#[derive(Default)]
pub(crate) struct Box86Cache {
    pub(crate) entries: Vec<Entry>,
    /// Round-robin replacement when full.
    pub(crate) next_victim: usize,
    /// The entry whose levels are lent to the TMU for the current triangle.
    pub lent: Option<usize>,
}

impl Box86Cache {
    /// The entry with `key`, if cached.
    pub fn find(&self, key: Key) -> Option<usize> {
        self.entries.iter().position(|e| e.key == key)
    }

    /// Stores a newly decoded entry; returns its index.
    pub fn insert(&mut self, entry: Entry) -> usize {
        if self.entries.len() < CAPACITY {
            self.entries.push(entry);
            return self.entries.len() - 1;
        }
        let i = self.next_victim;
        self.next_victim = (i + 1) % CAPACITY;
        self.entries[i] = entry;
        i
    }

    /// The levels and valid bits of entry `i`, to swap with the TMU's cache.
    pub fn storage(&mut self, i: usize) -> (&mut [Vec<u32>; 9], &mut u16) {
        let e = &mut self.entries[i];
        (&mut e.levels, &mut e.valid)
    }

    /// A texture download wrote the byte at `addr`: drops every entry whose span holds
    /// it. Must not be called while an entry is lent.
    pub fn written(&mut self, addr: u32) {
        debug_assert!(self.lent.is_none());
        self.entries
            .retain(|e| !(e.span.0 <= addr && addr < e.span.1));
        self.next_victim %= self.entries.len().max(1);
    }

    /// Drops everything.
    pub fn clear(&mut self) {
        self.entries.clear();
        self.next_victim = 0;
        self.lent = None;
    }
}

/// The span `[start, end)` of the bytes `[first, last]`, rounded out to 1 KiB as 86Box's
/// eviction test does.
pub(crate) fn page_span(first: u32, last: u32) -> (u32, u32) {
    (first & !0x3ff, (last.wrapping_add(0x400)) & !0x3ff)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(base: u32, span: (u32, u32)) -> Entry {
        Entry {
            key: Key {
                base,
                t_lod: 0,
                palette: 0,
            },
            levels: Default::default(),
            valid: 1,
            span,
        }
    }

    #[test]
    fn writes_drop_entries_by_page() {
        let mut c = Box86Cache::default();
        c.insert(entry(0, page_span(0x1010, 0x17ff)));
        c.insert(entry(1, page_span(0x4000, 0x43ff)));
        let key = |base| Key {
            base,
            t_lod: 0,
            palette: 0,
        };
        assert_eq!((c.find(key(0)), c.find(key(1))), (Some(0), Some(1)));
        // The page before the first byte is outside; the first byte's page is inside.
        c.written(0x0fff);
        assert!(c.find(key(0)).is_some());
        c.written(0x1000);
        assert!(c.find(key(0)).is_none());
        assert!(c.find(key(1)).is_some());
        c.written(0x4400);
        assert!(c.find(key(1)).is_some());
    }

    #[test]
    fn full_cache_replaces_round_robin() {
        let mut c = Box86Cache::default();
        for b in 0..CAPACITY as u32 {
            c.insert(entry(b, (0, 0)));
        }
        let i = c.insert(entry(1000, (0, 0)));
        assert_eq!(i, 0);
        let key = |base| Key {
            base,
            t_lod: 0,
            palette: 0,
        };
        assert!(c.find(key(0)).is_none());
        assert_eq!(c.find(key(1000)), Some(0));
    }
}

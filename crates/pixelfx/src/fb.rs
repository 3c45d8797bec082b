//! Frame-buffer memory and its layout (spec 5.43-5.45: `fbiInit1` video tiles in X,
//! `fbiInit2` video buffer offset and triple buffering).
//!
//! The SST-1 frame buffer is 2 or 4 MiB of 16-bit words. Colour buffers are RGB565; the
//! auxiliary buffer holds depth or alpha. The layout is derived from the init registers
//! exactly as the chip derives it:
//!
//! * row pitch = 64 pixels x `fbiInit1.video_tiles_in_x` (SST-1 tiles are 64x16 pixels),
//! * buffer *n* starts at `n * fbiInit2.video_buffer_offset * 4096` bytes,
//! * with two colour buffers the aux buffer is the third slot; with triple buffering
//!   there is no aux buffer.
//!
//! Source: spec 5.43-5.45; the buffer order and the clamping of offsets to memory follow
//! MAME and DOSBox Staging (`recompute_video_memory`), which agree.

/// Bytes in one "page" of `fbiInit2.video_buffer_offset` (spec 5.44: units of 4 KiB).
pub const BUFFER_PAGE_BYTES: u32 = 0x1000;

/// Pixels per video tile in X on the SST-1 (spec 5.43: tiles are 64x16).
pub const TILE_WIDTH: u32 = 64;

/// The frame-buffer geometry in force.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Layout {
    /// Row pitch in pixels.
    pub row_pixels: u32,
    /// Byte offsets of colour buffers 0, 1 and (with triple buffering) 2.
    pub rgb_offset: [Option<u32>; 3],
    /// Byte offset of the aux (depth/alpha) buffer, if the memory configuration has one.
    pub aux_offset: Option<u32>,
}

/// The frame-buffer RAM with its layout and the front/back buffer indices.
pub struct FrameBuffer {
    /// The memory, as 16-bit words (little-endian pixel order, word address = byte / 2).
    pub ram: Vec<u16>,
    /// Geometry derived from the init registers.
    pub layout: Layout,
    /// Index (0..3) of the displayed colour buffer.
    pub front: usize,
    /// Index (0..3) of the colour buffer being drawn.
    pub back: usize,
}

impl FrameBuffer {
    /// A frame buffer of `mib` MiB (2 or 4), cleared to zero.
    pub fn new(mib: u32) -> Self {
        let words = (mib.clamp(1, 4) as usize) << 19;
        Self {
            ram: vec![0; words],
            layout: Layout {
                row_pixels: 0,
                rgb_offset: [Some(0), Some(0), None],
                aux_offset: None,
            },
            front: 0,
            back: 1,
        }
    }

    /// Byte mask of the memory (its size minus one).
    #[inline]
    pub fn mask(&self) -> u32 {
        (self.ram.len() as u32 * 2) - 1
    }

    /// Recompute the layout from `fbiInit1.video_tiles_in_x`, `fbiInit2.video_buffer_offset`
    /// and `fbiInit2.enable_triple_buffering`.
    pub fn recompute_layout(&mut self, x_tiles: u32, buffer_pages: u32, triple: bool) {
        let mask = self.mask();
        let step = buffer_pages * BUFFER_PAGE_BYTES;
        // Offsets past the end of memory are clamped to its last byte (MAME, DOSBox).
        let clamp = |o: u32| o.min(mask);
        let (rgb2, aux) = if triple {
            (Some(2 * step), None)
        } else {
            (None, Some(2 * step))
        };
        self.layout = Layout {
            row_pixels: TILE_WIDTH * x_tiles,
            rgb_offset: [Some(0), Some(clamp(step)), rgb2.map(clamp)],
            aux_offset: aux.map(clamp),
        };
        if self.layout.rgb_offset[2].is_none() {
            if self.front == 2 {
                self.front = 0;
            }
            if self.back == 2 {
                self.back = 0;
            }
        }
    }

    /// Word index of the start of colour buffer `buf`, if it exists.
    #[inline]
    pub fn rgb_base(&self, buf: usize) -> Option<usize> {
        self.layout
            .rgb_offset
            .get(buf)
            .copied()
            .flatten()
            .map(|o| (o / 2) as usize)
    }

    /// Word index of the start of the aux buffer, if it exists.
    #[inline]
    pub fn aux_base(&self) -> Option<usize> {
        self.layout.aux_offset.map(|o| (o / 2) as usize)
    }

    /// Read one word at `base + y * pitch + x`; out-of-memory reads return 0.
    #[inline]
    pub fn read(&self, base: usize, x: i32, y: i32) -> u16 {
        self.index(base, x, y).map_or(0, |i| self.ram[i])
    }

    /// Write one word at `base + y * pitch + x`; out-of-memory writes are dropped.
    #[inline]
    pub fn write(&mut self, base: usize, x: i32, y: i32, v: u16) {
        if let Some(i) = self.index(base, x, y) {
            self.ram[i] = v;
        }
    }

    /// The words of columns `left..right` of row `y` of the buffer at `base` that exist
    /// (those [`FrameBuffer::index`] finds: columns from 0, words below the end of
    /// memory), with the first such column; `None` where there are none.
    pub fn row_words(
        &self,
        base: usize,
        left: i32,
        right: i32,
        y: i32,
    ) -> Option<(i32, std::ops::Range<usize>)> {
        let x0 = left.max(0);
        if y < 0 || x0 >= right {
            return None;
        }
        let start = base + y as usize * self.layout.row_pixels as usize + x0 as usize;
        let end = (start + (right - x0) as usize).min(self.ram.len());
        (start < end).then_some((x0, start..end))
    }

    /// Memory word index of pixel (x, y) of the buffer at `base`, or `None` outside memory.
    #[inline]
    pub fn index(&self, base: usize, x: i32, y: i32) -> Option<usize> {
        if x < 0 || y < 0 {
            return None;
        }
        let i = base + y as usize * self.layout.row_pixels as usize + x as usize;
        (i < self.ram.len()).then_some(i)
    }

    /// Swap the colour buffers (spec 5.24): two buffers alternate, three rotate.
    pub fn swap(&mut self) {
        if self.layout.rgb_offset[2].is_none() {
            self.front = 1 - self.front.min(1);
            self.back = 1 - self.front;
        } else {
            self.front = (self.front + 1) % 3;
            self.back = (self.front + 1) % 3;
        }
    }

    /// Copy out `width x height` words of a buffer starting at word `base` (row 0 first).
    /// Words outside memory read as 0, as [`FrameBuffer::read`] does; each row is copied as
    /// one slice.
    pub fn dump(&self, base: Option<usize>, width: u32, height: u32) -> Vec<u16> {
        let mut out = vec![0u16; (width * height) as usize];
        let (Some(base), Ok(width @ 1..)) = (base, usize::try_from(width)) else {
            return out;
        };
        let pitch = self.layout.row_pixels as usize;
        for (y, row) in out.chunks_exact_mut(width).enumerate() {
            let start = base + y * pitch;
            let n = self.ram.len().saturating_sub(start).min(width);
            if n > 0 {
                row[..n].copy_from_slice(&self.ram[start..start + n]);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glide_640x480_layout() {
        // fbiInit1 = 0x002000a2 -> 10 tiles; fbiInit2 video buffer offset 0x96 pages
        // (as written by the conformance traces' init).
        let mut fb = FrameBuffer::new(4);
        fb.recompute_layout(10, 0x96, false);
        assert_eq!(fb.layout.row_pixels, 640);
        assert_eq!(fb.layout.rgb_offset, [Some(0), Some(0x96000), None]);
        assert_eq!(fb.layout.aux_offset, Some(0x12c000));
    }

    /// The row-wise dump equals a pixel-by-pixel read, inside memory and past its end.
    #[test]
    fn dump_equals_reads() {
        let mut fb = FrameBuffer::new(2);
        for (i, w) in fb.ram.iter_mut().enumerate() {
            *w = (i as u16).wrapping_mul(7);
        }
        for (tiles, base, width, height) in
            [(10, 0, 640, 480), (3, 900_000, 200, 100), (0, 5, 6, 4)]
        {
            fb.recompute_layout(tiles, 0x96, false);
            let dump = fb.dump(Some(base), width, height);
            let mut expected = Vec::new();
            for y in 0..height as i32 {
                for x in 0..width as i32 {
                    expected.push(fb.read(base, x, y));
                }
            }
            assert_eq!(dump, expected, "{tiles} tiles, base {base}");
        }
        assert_eq!(fb.dump(Some(0), 0, 480), Vec::<u16>::new());
        assert_eq!(fb.dump(None, 2, 2), [0; 4]);
    }

    #[test]
    fn swap_double_and_triple() {
        let mut fb = FrameBuffer::new(4);
        fb.recompute_layout(10, 0x96, false);
        assert_eq!((fb.front, fb.back), (0, 1));
        fb.swap();
        assert_eq!((fb.front, fb.back), (1, 0));
        fb.recompute_layout(10, 0x96, true);
        fb.swap();
        assert_eq!((fb.front, fb.back), (2, 0));
    }

    #[test]
    fn out_of_memory_access_is_harmless() {
        let mut fb = FrameBuffer::new(2);
        fb.recompute_layout(16, 0x1ff, true);
        fb.write(fb.ram.len(), 5, 5, 0x1234);
        assert_eq!(fb.read(fb.ram.len(), 5, 5), 0);
        assert_eq!(fb.read(0, -1, 0), 0);
    }
}

//! FASTFILL (spec 5.23): clear the clip rectangle of the draw buffer to `color1`
//! (dithered if `fbzMode` enables dithering) and/or the aux buffer to `zaColor[15:0]`,
//! as `fbzMode`'s RGB and aux masks select.
//!
//! Rows are raster rows: with `fbzMode.y_origin` set they are flipped like triangle rows
//! (spec 5.21: "the orientation of the Y origin is defined by fbzMode bit 17"). The
//! dither cell is indexed with the raster row (see the comment in the loop).
//! Source: spec 5.23; MAME and DOSBox Staging agree on everything else.

use sst1_regs::{addr, Rgba};

use crate::fbi::Fbi;
use crate::model::PixelModel;
use crate::pipeline::DrawState;
use crate::profile::FastfillDither;

impl Fbi {
    /// Execute the FASTFILL command as model `M` ([`crate::model`]; the caller guarantees
    /// that the profile this FBI holds is `M`'s).
    pub fn fastfill<M: PixelModel>(&mut self) {
        self.stats.fastfills += 1;
        let mode = self.fbz_mode();
        let (left, right, low, high) = self.clip_rect();
        let dest = if mode.rgb_buffer_mask() {
            self.colour_buffer(mode.draw_buffer())
        } else {
            None
        };
        let aux = if mode.aux_buffer_mask() {
            self.fb.aux_base()
        } else {
            None
        };
        if dest.is_none() && aux.is_none() {
            return;
        }
        let st = DrawState::capture::<M>(self, dest.unwrap_or(0));
        let colour = Rgba::from_argb(self.reg(addr::COLOR1));
        let depth = self.reg(addr::ZA_COLOR) as u16;
        // The 4x4 cell of dithered colours, indexed [y & 3][x & 3].
        let mut cell = [[0u16; 4]; 4];
        let dither = match M::pixel(&self.profile()).fastfill_dither {
            FastfillDither::Dithered => st.dither,
            FastfillDither::Truncated => sst1_dither::DitherKind::Off,
        };
        for (cy, row) in cell.iter_mut().enumerate() {
            for (cx, v) in row.iter_mut().enumerate() {
                *v = self
                    .dither
                    .rgb565(dither, cx as u32, cy as u32, colour.r, colour.g, colour.b);
            }
        }
        for y in low..high {
            let scry = self.screen_y(y, mode.y_origin());
            // The fill's dither cell is indexed with the raster row, whatever
            // `PatternRow` says for triangles: with the screen row the glide-sdk clears
            // (lower-left origin, dithering on) differ from all three references on
            // ~120 k pixels; with the raster row on none.
            let pattern = cell[(y & 3) as usize];
            let colour_row = dest.and_then(|d| self.fb.row_words(d, left, right, scry));
            let aux_row = aux.and_then(|a| self.fb.row_words(a, left, right, scry));
            let crossing = match (&colour_row, &aux_row) {
                (Some((_, c)), Some((_, a))) => c.start < a.end && a.start < c.end,
                _ => false,
            };
            if crossing || self.generic_path {
                // Colour and aux words of one row meet (buffers less than a row
                // apart: `fbiInit2` places them whole pages apart, so only a zero
                // offset, where they are the same words, comes close), or the
                // reference path is forced: pixel by pixel, colour before aux, so that
                // each word ends as that order leaves it.
                self.fill_row_per_pixel(dest, aux, &pattern, left..right, scry, depth);
                continue;
            }
            if let Some((x0, words)) = colour_row {
                self.stats.pixels_out += words.len() as u64;
                for (k, w) in self.fb.ram[words].iter_mut().enumerate() {
                    *w = pattern[(x0 as usize + k) & 3];
                }
            }
            if let Some((_, words)) = aux_row {
                self.fb.ram[words].fill(depth);
            }
        }
        if self.watch.is_some() {
            self.watch_fill(low..high, left..right, mode.y_origin(), dest, aux);
        }
    }

    /// One row of a fill, pixel by pixel: frame-buffer row `scry`, columns `columns`,
    /// the colour from `pattern` (the dither cell's row), indexed `x & 3`.
    fn fill_row_per_pixel(
        &mut self,
        dest: Option<usize>,
        aux: Option<usize>,
        pattern: &[u16; 4],
        columns: std::ops::Range<i32>,
        scry: i32,
        depth: u16,
    ) {
        for x in columns {
            if let Some(i) = dest.and_then(|d| self.fb.index(d, x, scry)) {
                self.fb.ram[i] = pattern[(x & 3) as usize];
                self.stats.pixels_out += 1;
            }
            if let Some(i) = aux.and_then(|a| self.fb.index(a, x, scry)) {
                self.fb.ram[i] = depth;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::RuntimeProfile;
    use sst1_regs::addr;

    /// Fills with random layouts (buffers that overlap, rows that run past memory),
    /// clip rectangles, masks, dithering and Y origins, by rows and pixel by pixel: the
    /// same memory and counters.
    #[test]
    fn row_fills_equal_pixel_fills() {
        let mut x = 0x853c_49e6_748f_ea9bu64;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x as u32
        };
        let mut overlapping = 0;
        for round in 0..300 {
            let mut fbis = [Fbi::new(2), Fbi::new(2)];
            let writes = [
                // Tiles in X (row pitch), a small buffer offset in pages (buffers
                // that overlap), triple buffering.
                (addr::FBI_INIT1, (next() % 15 + 1) << 4),
                (addr::FBI_INIT2, (next() & 0x3f) << 11 | (next() & 1) << 4),
                (addr::FBI_INIT3, (next() & 0x3ff) << 22),
                // Dithering, 2x2 or not, the Y origin and either colour buffer at
                // random; with both masks in most rounds.
                (
                    addr::FBZ_MODE,
                    next() & (1 << 8 | 1 << 11 | 1 << 17 | 1 << 14)
                        | if round % 4 == 3 {
                            next() & (3 << 9)
                        } else {
                            3 << 9
                        },
                ),
                (addr::CLIP_LEFT_RIGHT, next() & 0x03ff_03ff),
                (addr::CLIP_LOW_Y_HIGH_Y, next() & 0x03ff_03ff),
                (addr::COLOR1, next()),
                (addr::ZA_COLOR, next()),
            ];
            let mut memory = Vec::new();
            for (i, fbi) in fbis.iter_mut().enumerate() {
                for &(offset, value) in &writes {
                    fbi.write_reg::<RuntimeProfile>(offset, value);
                }
                if memory.is_empty() {
                    memory = (0..fbi.fb.ram.len()).map(|_| next() as u16).collect();
                }
                fbi.fb.ram.copy_from_slice(&memory);
                fbi.set_generic_path(i == 1);
            }
            let [rows, pixels] = &mut fbis;
            // Whether the fill's colour words and aux words share memory (rows of one
            // buffer that are rows of the other: the order of the rows must be kept).
            let (left, right, low, high) = rows.clip_rect();
            let mode = rows.fbz_mode();
            let span = |base: Option<usize>| {
                let words = (low..high).filter_map(|y| {
                    let scry = rows.screen_y(y, mode.y_origin());
                    base.and_then(|b| rows.fb.row_words(b, left, right, scry))
                });
                words.fold(None, |acc: Option<(usize, usize)>, (_, w)| {
                    Some(acc.map_or((w.start, w.end), |(lo, hi)| {
                        (lo.min(w.start), hi.max(w.end))
                    }))
                })
            };
            let colour = span(
                rows.colour_buffer(mode.draw_buffer())
                    .filter(|_| mode.rgb_buffer_mask()),
            );
            let aux = span(rows.fb.aux_base().filter(|_| mode.aux_buffer_mask()));
            if let (Some(c), Some(a)) = (colour, aux) {
                overlapping += usize::from(c.0 < a.1 && a.0 < c.1);
            }
            rows.fastfill::<RuntimeProfile>();
            pixels.fastfill::<RuntimeProfile>();
            assert!(rows.fb.ram == pixels.fb.ram, "round {round}");
            assert_eq!(rows.stats, pixels.stats, "round {round}");
        }
        assert!(
            overlapping > 10,
            "{overlapping} fills whose colour and aux words share memory"
        );
    }
}

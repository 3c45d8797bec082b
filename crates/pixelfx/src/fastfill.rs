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
            for x in left..right {
                if let Some(i) = dest.and_then(|d| self.fb.index(d, x, scry)) {
                    // The fill's dither cell is indexed with the raster row, whatever
                    // `PatternRow` says for triangles: with the screen row the glide-sdk
                    // clears (lower-left origin, dithering on) differ from all three
                    // references on ~120 k pixels; with the raster row on none.
                    self.fb.ram[i] = cell[(y & 3) as usize][(x & 3) as usize];
                    self.stats.pixels_out += 1;
                }
                if let Some(i) = aux.and_then(|a| self.fb.index(a, x, scry)) {
                    self.fb.ram[i] = depth;
                }
            }
        }
        if self.watch.is_some() {
            self.watch_fill(low..high, left..right, mode.y_origin(), dest, aux);
        }
    }
}

//! Linear frame buffer access (spec 5.20 `lfbMode`, 5.20.1 write formats, 5.20.2 reads).
//!
//! A 32-bit write at aperture offset `0x400000 + o` carries two 16-bit pixels at
//! `x = (o >> 1) & 0x3ff, y = (o >> 11) & 0x3ff` (16-bit formats), or one pixel at
//! `x = (o >> 2) & 0x3ff, y = (o >> 12) & 0x3ff` (32-bit formats). `lfbMode` selects the
//! format, the lane order (ARGB, ABGR, RGBA, BGRA), word swap and byte swizzle, the buffer,
//! the Y origin, and whether the pixels go through the pixel pipeline.
//! 5- and 6-bit fields widen to 8 bits by replicating their high bits.
//! Source: spec 5.20; lane and expansion details agree in MAME and DOSBox Staging.

use sst1_regs::{addr, ColorBuffer, LfbMode, LfbReadBuffer, Rgba};

use crate::fbi::Fbi;
use crate::iter::Iterated;
use crate::model::PixelModel;
use crate::pipeline::{DrawState, Source};
use crate::profile::{LfbOrdering, LfbWordSwap};
use crate::stats::Kill;
use crate::watch::{NoStages, PixelEvent, SourceKind};

/// One pixel decoded from an LFB write.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LfbPixel {
    /// Colour, if the format carries one.
    pub rgb: Option<[u8; 3]>,
    /// Alpha, if the format carries one.
    pub alpha: Option<u8>,
    /// Depth, if the format carries one.
    pub depth: Option<u16>,
}

#[inline]
fn expand5(v: u32) -> u8 {
    let v = (v & 0x1f) as u8;
    (v << 3) | (v >> 2)
}

#[inline]
fn expand6(v: u32) -> u8 {
    let v = (v & 0x3f) as u8;
    (v << 2) | (v >> 4)
}

/// Put (r, g, b) in lane order: lanes 1 and 3 swap red and blue.
#[inline]
fn lanes(swap_rb: bool, a: u8, b: u8, c: u8) -> [u8; 3] {
    if swap_rb {
        [c, b, a]
    } else {
        [a, b, c]
    }
}

/// Decode a 16-bit colour half-word in format `fmt` (0 = 565, 1 = x555, 2 = 1555).
fn decode16(fmt: u32, lane: u32, v: u32) -> (Option<[u8; 3]>, Option<u8>) {
    let swap = lane & 1 != 0;
    // Lanes 2 and 3 put the 1-bit/unused field at the bottom for 555 formats.
    let low_flag = lane >= 2;
    match fmt {
        0 => (
            Some(lanes(swap, expand5(v >> 11), expand6(v >> 5), expand5(v))),
            None,
        ),
        1 | 2 => {
            let (c, flag) = if low_flag {
                (v >> 1, v & 1)
            } else {
                (v, (v >> 15) & 1)
            };
            let rgb = lanes(swap, expand5(c >> 10), expand5(c >> 5), expand5(c));
            (
                Some(rgb),
                (fmt == 2).then_some(if flag != 0 { 0xff } else { 0 }),
            )
        }
        _ => (None, None),
    }
}

/// Decode a 32-bit LFB word into its pixels (one or two). `None` for reserved formats.
pub fn decode(mode: LfbMode, data: u32) -> Option<(usize, [LfbPixel; 2])> {
    let fmt = mode.0 & 0xf;
    let lane = (mode.0 >> 9) & 3;
    let mut px = [LfbPixel::default(); 2];
    let halves = [data & 0xffff, data >> 16];
    match fmt {
        0..=2 => {
            for (p, &h) in px.iter_mut().zip(&halves) {
                let (rgb, alpha) = decode16(fmt, lane, h);
                *p = LfbPixel {
                    rgb,
                    alpha,
                    depth: None,
                };
            }
            Some((2, px))
        }
        4 | 5 => {
            let bytes = data.to_be_bytes(); // [31:24, 23:16, 15:8, 7:0]
            let (a, c) = if lane >= 2 {
                (bytes[3], [bytes[0], bytes[1], bytes[2]])
            } else {
                (bytes[0], [bytes[1], bytes[2], bytes[3]])
            };
            let rgb = lanes(lane & 1 != 0, c[0], c[1], c[2]);
            px[0] = LfbPixel {
                rgb: Some(rgb),
                alpha: (fmt == 5).then_some(a),
                depth: None,
            };
            Some((1, px))
        }
        12..=14 => {
            let (rgb, alpha) = decode16(fmt - 12, lane, halves[0]);
            px[0] = LfbPixel {
                rgb,
                alpha,
                depth: Some(halves[1] as u16),
            };
            Some((1, px))
        }
        15 => {
            for (p, &h) in px.iter_mut().zip(&halves) {
                *p = LfbPixel {
                    rgb: None,
                    alpha: None,
                    depth: Some(h as u16),
                };
            }
            Some((2, px))
        }
        _ => None,
    }
}

impl Fbi {
    /// `lfbMode` as a typed view.
    #[inline]
    pub fn lfb_mode(&self) -> LfbMode {
        LfbMode(self.reg(addr::LFB_MODE))
    }

    /// A 32-bit write into the LFB region; `offset` is relative to 0x400000. `M` is the
    /// model of the chip ([`crate::model`]); the caller guarantees that the profile this
    /// FBI holds is `M`'s.
    pub fn lfb_write<M: PixelModel>(&mut self, offset: u32, data: u32) {
        self.lfb_write_lanes::<M>(offset, data, u32::MAX);
    }

    /// An LFB write of the bytes of `data` that `lanes` selects (a bit set for each bit
    /// of the bus driven: `0x0000ffff` and `0xffff0000` are the two 16-bit writes at
    /// `offset` and `offset + 2`); `offset` is the 32-bit word's (bits 1:0 ignored).
    /// Spec 9: "linear frame buffer accesses may be 32-bit or 16-bit accesses, depending
    /// upon the linear frame buffer access format". The lanes are swizzled and swapped
    /// with the data (so with `lfbMode` bit 11 a write of the upper half reaches the
    /// first pixel of the pair); then a 16-bit format writes the pixel of each half
    /// written, and leaves the other pixel, its colour and its aux word alone. In the
    /// 32-bit formats, which take whole-word writes, a write without the low half
    /// writes no pixel (formats 4, 5) or only the depth of the high half (12-14), and
    /// one without the high half no depth. Source: MAME `lfb_w` (its `mem_mask` swapped
    /// with the data, and the per-pixel masks it clears). UNVERIFIED: through the pixel
    /// pipeline, a format 12-14 pixel missing its colour or depth takes them from
    /// `color1` and `zaColor`, as the formats without them do (MAME takes the bus
    /// data).
    pub fn lfb_write_lanes<M: PixelModel>(&mut self, offset: u32, data: u32, lanes: u32) {
        // One test per write: only the instance for a watched pixel looks for it
        // (`crate::watch`), so the other costs nothing per pixel.
        if self.watch.is_some() {
            self.lfb_write_watched::<M>(offset, data, lanes)
        } else {
            self.lfb_write_as::<M, false>(offset, data, lanes)
        }
    }

    /// [`Fbi::lfb_write_lanes`] while a pixel is watched (apart, so that the unwatched
    /// instance is compiled as if the watch did not exist).
    #[cold]
    #[inline(never)]
    fn lfb_write_watched<M: PixelModel>(&mut self, offset: u32, data: u32, lanes: u32) {
        self.lfb_write_as::<M, true>(offset, data, lanes)
    }

    /// [`Fbi::lfb_write_lanes`], recording the watched pixel's events if `WATCH`.
    #[inline(always)]
    fn lfb_write_as<M: PixelModel, const WATCH: bool>(
        &mut self,
        offset: u32,
        data: u32,
        lanes: u32,
    ) {
        let mut lanes = lanes;
        let profile = M::pixel(&self.profile());
        let mut mode = self.lfb_mode();
        let mut data = data;
        let ordering = profile.lfb_ordering == LfbOrdering::Applied;
        if !ordering {
            // ARGB lanes, no byte swizzle, no Y flip.
            mode = LfbMode(mode.0 & !(3 << 9 | 1 << 12 | 1 << 13));
        }
        if mode.byte_swizzle_writes() {
            data = data.swap_bytes();
            lanes = lanes.swap_bytes();
        }
        // Spec 5.20: "bit(11) of lfbMode is ignored for linear frame buffer writes using
        // formats 4 or 5" (the 32-bit colour formats).
        let is_32bit_colour = matches!(mode.0 & 0xf, 4 | 5);
        let swap = match profile.lfb_word_swap {
            LfbWordSwap::SpecIgnoredFor32Bit => !is_32bit_colour,
            LfbWordSwap::Always => true,
            LfbWordSwap::Never => false,
        };
        if mode.word_swap_writes() && swap {
            data = data.rotate_left(16);
            lanes = lanes.rotate_left(16);
        }
        let Some((count, mut pixels)) = decode(mode, data) else {
            return;
        };
        let (low, high) = (lanes & 0xffff != 0, lanes >> 16 != 0);
        let mut written = [low, high];
        if count == 1 && matches!(mode.0 & 0xf, 12..=14) {
            if !low {
                pixels[0].rgb = None;
                pixels[0].alpha = None;
            }
            if !high {
                pixels[0].depth = None;
            }
            written[0] = low || high;
        }
        let (x0, y) = if count == 2 {
            (
                ((offset >> 1) & 0x3fe) as i32,
                ((offset >> 11) & 0x3ff) as i32,
            )
        } else {
            (
                ((offset >> 2) & 0x3ff) as i32,
                ((offset >> 12) & 0x3ff) as i32,
            )
        };
        let Some(dest) = self.colour_buffer(mode.write_buffer_select()) else {
            return;
        };
        let za = self.reg(addr::ZA_COLOR);
        let fbz = self.fbz_mode();
        if mode.enable_pixel_pipeline() {
            let st = DrawState::capture::<M>(self, dest);
            // UNVERIFIED: the pipeline path flips with fbzMode's Y origin (DOSBox Staging).
            let scry = self.screen_y(y, fbz.y_origin() && ordering);
            let color1 = Rgba::from_argb(self.reg(addr::COLOR1));
            for (i, p) in pixels.iter().take(count).enumerate() {
                if !written[i] {
                    continue;
                }
                let x = x0 + i as i32;
                self.stats.pixels_in += 1;
                let (left, right, low, high) = st.clip;
                let watched = WATCH && self.watch.as_ref().is_some_and(|w| w.is(x, scry));
                if fbz.enable_clipping() && (x < left || x >= right || scry < low || scry >= high) {
                    self.count(Err(Kill::Clip));
                    if watched {
                        self.record(PixelEvent::Clipped {
                            source: SourceKind::Lfb,
                        });
                    }
                    continue;
                }
                let depth = p.depth.unwrap_or(za as u16);
                let rgb = p.rgb.unwrap_or([color1.r, color1.g, color1.b]);
                let colour = Rgba {
                    r: rgb[0],
                    g: rgb[1],
                    b: rgb[2],
                    a: p.alpha.unwrap_or((za >> 24) as u8),
                };
                // Depth enters as if iterated: Z in 20.12, W in the 32.32 iterator scale.
                let it = Iterated {
                    argb: [0; 4],
                    z: (depth as i32) << 12,
                    w: (depth as i64) << 14,
                };
                let mut stipple = st.stipple;
                let prow = profile.pattern_row.row(y, scry);
                if watched {
                    self.shade_watched_lfb::<M>(&st, x, prow, scry, &it, colour, &mut stipple);
                    continue;
                }
                let r = self.shade_pixel::<M, NoStages>(
                    &st,
                    x,
                    prow,
                    scry,
                    &it,
                    Source::Lfb(colour),
                    &mut stipple,
                    Rgba::default,
                    &mut NoStages,
                );
                self.count(r);
            }
        } else {
            let scry = self.screen_y(y, mode.y_origin());
            let dither = DrawState::capture::<M>(self, dest).dither;
            let aux = self.fb.aux_base();
            for (i, p) in pixels.iter().take(count).enumerate() {
                if !written[i] {
                    continue;
                }
                let x = x0 + i as i32;
                if let Some([r, g, b]) = p.rgb {
                    if let Some(idx) = self.fb.index(dest, x, scry) {
                        let prow = profile.pattern_row.row(y, scry);
                        self.fb.ram[idx] =
                            self.dither.rgb565(dither, x as u32, prow as u32, r, g, b);
                    }
                }
                if let Some(idx) = aux.and_then(|a| self.fb.index(a, x, scry)) {
                    if fbz.enable_alpha_planes() {
                        if let Some(a) = p.alpha {
                            self.fb.ram[idx] = a as u16;
                        }
                    } else if let Some(d) = p.depth {
                        self.fb.ram[idx] = d;
                    }
                }
                self.stats.pixels_out += 1;
                if WATCH && self.watch.as_ref().is_some_and(|w| w.is(x, scry)) {
                    self.watch_lfb_direct(dest, x, scry, p, fbz.enable_alpha_planes());
                }
            }
        }
    }

    /// A 32-bit read from the LFB region (two 16-bit pixels); `offset` relative to 0x400000.
    pub fn lfb_read(&self, offset: u32) -> u32 {
        let mode = self.lfb_mode();
        let x = ((offset >> 1) & 0x3fe) as i32;
        let y = ((offset >> 11) & 0x3ff) as i32;
        let base = match mode.read_buffer_select() {
            LfbReadBuffer::Front => self.colour_buffer(ColorBuffer::Front),
            LfbReadBuffer::Back => self.colour_buffer(ColorBuffer::Back),
            LfbReadBuffer::Aux => self.fb.aux_base(),
            _ => None,
        };
        let Some(base) = base else { return 0xffff_ffff };
        let scry = self.screen_y(y, mode.y_origin());
        let (Some(i0), Some(i1)) = (
            self.fb.index(base, x, scry),
            self.fb.index(base, x + 1, scry),
        ) else {
            return 0xffff_ffff;
        };
        let mut data = self.fb.ram[i0] as u32 | (self.fb.ram[i1] as u32) << 16;
        if mode.word_swap_reads() {
            data = data.rotate_left(16);
        }
        if mode.byte_swizzle_reads() {
            data = data.swap_bytes();
        }
        data
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::model::RuntimeProfile;

    /// An FBI with 640-pixel rows and an aux buffer, `lfbMode` = `mode`.
    fn fbi_with(mode: u32) -> Fbi {
        let mut fbi = Fbi::new(2);
        fbi.write_reg::<RuntimeProfile>(addr::FBI_INIT1, 10 << 4);
        fbi.write_reg::<RuntimeProfile>(addr::FBI_INIT2, 0x96 << 11);
        fbi.write_reg::<RuntimeProfile>(addr::LFB_MODE, mode);
        fbi
    }

    /// Colour (front buffer) and aux words of pixels 0 and 1 of row 0.
    fn words(fbi: &Fbi) -> [u16; 4] {
        let aux = fbi.fb.aux_base().unwrap();
        [
            fbi.fb.ram[0],
            fbi.fb.ram[1],
            fbi.fb.ram[aux],
            fbi.fb.ram[aux + 1],
        ]
    }

    #[test]
    fn sixteen_bit_writes_change_only_their_pixel() {
        let mut fbi = fbi_with(0); // RGB 565, front buffer, no pipeline
        fbi.lfb_write::<RuntimeProfile>(0, 0x1234_5678);
        assert_eq!(words(&fbi), [0x5678, 0x1234, 0, 0]);
        fbi.lfb_write_lanes::<RuntimeProfile>(0, 0xabcd_0000, 0xffff_0000);
        assert_eq!(words(&fbi), [0x5678, 0xabcd, 0, 0]);
        fbi.lfb_write_lanes::<RuntimeProfile>(0, 0x0000_1111, 0x0000_ffff);
        assert_eq!(words(&fbi), [0x1111, 0xabcd, 0, 0]);
        assert_eq!(fbi.stats.pixels_out, 4);
        // Word swap (bit 11) moves the lanes with the data: the upper half is pixel 0.
        let mut fbi = fbi_with(1 << 11);
        fbi.lfb_write_lanes::<RuntimeProfile>(0, 0x2222_0000, 0xffff_0000);
        assert_eq!(words(&fbi), [0x2222, 0, 0, 0]);
        // Byte swizzle (bit 12) too: the low half's bytes land in the high half.
        let mut fbi = fbi_with(1 << 12);
        fbi.lfb_write_lanes::<RuntimeProfile>(0, 0x0000_3412, 0x0000_ffff);
        assert_eq!(words(&fbi), [0, 0x1234, 0, 0]);
        // Depth, depth: one aux word.
        let mut fbi = fbi_with(15);
        fbi.lfb_write_lanes::<RuntimeProfile>(0, 0x0000_4444, 0x0000_ffff);
        assert_eq!(words(&fbi), [0, 0, 0x4444, 0]);
    }

    #[test]
    fn sixteen_bit_writes_in_32_bit_formats() {
        // Depth + RGB 565: the low half is the colour, the high half the depth.
        let mut fbi = fbi_with(12);
        fbi.lfb_write_lanes::<RuntimeProfile>(0, 0x5555_001f, 0xffff_0000);
        assert_eq!(words(&fbi), [0, 0, 0x5555, 0]);
        fbi.lfb_write_lanes::<RuntimeProfile>(0, 0x6666_001f, 0x0000_ffff);
        assert_eq!(words(&fbi), [0x001f, 0, 0x5555, 0]);
        // ARGB 8888 takes its pixel from a write with the low half only.
        let mut fbi = fbi_with(5);
        fbi.lfb_write_lanes::<RuntimeProfile>(0, 0xffff_0000, 0xffff_0000);
        assert_eq!((words(&fbi), fbi.stats.pixels_out), ([0; 4], 0));
        fbi.lfb_write_lanes::<RuntimeProfile>(0, 0x0000_00ff, 0x0000_ffff);
        assert_eq!((words(&fbi), fbi.stats.pixels_out), ([0x001f, 0, 0, 0], 1));
    }

    #[test]
    fn expand_replicates_high_bits() {
        assert_eq!(
            (expand5(0x1f), expand5(0x10), expand6(0x3f), expand6(0x20)),
            (0xff, 0x84, 0xff, 0x82)
        );
    }

    #[test]
    fn rgb565_two_pixels() {
        let (n, p) = decode(LfbMode(0), 0x001f_f800).unwrap();
        assert_eq!(n, 2);
        assert_eq!(p[0].rgb, Some([0xff, 0, 0]));
        assert_eq!(p[1].rgb, Some([0, 0, 0xff]));
        // ABGR lanes swap red and blue.
        let (_, p) = decode(LfbMode(1 << 9), 0x0000_f800).unwrap();
        assert_eq!(p[0].rgb, Some([0, 0, 0xff]));
    }

    #[test]
    fn argb1555_and_rgba5551() {
        let (_, p) = decode(LfbMode(2), 0x0000_fc00).unwrap();
        assert_eq!((p[0].rgb, p[0].alpha), (Some([0xff, 0, 0]), Some(0xff)));
        let (_, p) = decode(LfbMode(2 | 2 << 9), 0x0000_f801).unwrap();
        assert_eq!((p[0].rgb, p[0].alpha), (Some([0xff, 0, 0]), Some(0xff)));
    }

    #[test]
    fn argb8888_lanes_and_depth_formats() {
        let (n, p) = decode(LfbMode(5), 0x8011_2233).unwrap();
        assert_eq!(
            (n, p[0].rgb, p[0].alpha),
            (1, Some([0x11, 0x22, 0x33]), Some(0x80))
        );
        let (_, p) = decode(LfbMode(5 | 2 << 9), 0x1122_3380).unwrap();
        assert_eq!(
            (p[0].rgb, p[0].alpha),
            (Some([0x11, 0x22, 0x33]), Some(0x80))
        );
        let (_, p) = decode(LfbMode(12), 0xabcd_001f).unwrap();
        assert_eq!((p[0].rgb, p[0].depth), (Some([0, 0, 0xff]), Some(0xabcd)));
        let (n, p) = decode(LfbMode(15), 0x1234_5678).unwrap();
        assert_eq!((n, p[0].depth, p[1].depth), (2, Some(0x5678), Some(0x1234)));
        assert!(decode(LfbMode(3), 0).is_none());
    }
}

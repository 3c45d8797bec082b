//! `grGlideGetState` / `grGlideGetVertexLayout` as bytes: the saved value lives in the
//! caller's buffer, as in 3dfx's Glide (which copies its `GrState` into the buffer the
//! program sized with `grGet(GR_GLIDE_STATE_SIZE)`), so saving costs no memory here and a
//! copy of the buffer restores the same state.
//!
//! Layout of a saved buffer, little-endian 32-bit words:
//!
//! | word | content |
//! |---|---|
//! | 0 | tag: [`STATE_TAG`] or [`LAYOUT_TAG`] |
//! | 1 | number of payload words `n` |
//! | 2 | FNV-1a checksum of the payload words |
//! | 3 .. 3+n | the payload (fields in declaration order) |
//!
//! A buffer that does not carry the tag, whose length does not fit, whose checksum does
//! not match or whose fields are out of range is refused, so a buffer never filled by a
//! save (or overwritten since) is reported instead of restoring garbage.

use crate::draw::{Param, VertexLayout};
use crate::state::{Args, Combine, FbiConfig, GlideState, TmuConfig, Viewport};

/// "G3ST": the first word of a saved `GlideState`.
pub const STATE_TAG: u32 = 0x5453_3347;
/// "G3VL": the first word of a saved `VertexLayout`.
pub const LAYOUT_TAG: u32 = 0x4c56_3347;
/// Words before the payload: tag, length, checksum.
const HEADER_WORDS: usize = 3;

/// A value that packs into, and unpacks from, 32-bit words.
trait Words: Sized {
    fn put(&self, out: &mut Vec<u32>);
    fn take(r: &mut Reader<'_>) -> Option<Self>;
}

/// Reads a payload word by word.
struct Reader<'a>(&'a [u32]);

impl Reader<'_> {
    fn word(&mut self) -> Option<u32> {
        let (&w, rest) = self.0.split_first()?;
        self.0 = rest;
        Some(w)
    }
}

impl Words for u32 {
    fn put(&self, out: &mut Vec<u32>) {
        out.push(*self);
    }
    fn take(r: &mut Reader<'_>) -> Option<Self> {
        r.word()
    }
}

impl Words for i32 {
    fn put(&self, out: &mut Vec<u32>) {
        out.push(*self as u32);
    }
    fn take(r: &mut Reader<'_>) -> Option<Self> {
        r.word().map(|w| w as i32)
    }
}

impl Words for f32 {
    fn put(&self, out: &mut Vec<u32>) {
        out.push(self.to_bits());
    }
    fn take(r: &mut Reader<'_>) -> Option<Self> {
        r.word().map(f32::from_bits)
    }
}

impl Words for u8 {
    fn put(&self, out: &mut Vec<u32>) {
        out.push(u32::from(*self));
    }
    fn take(r: &mut Reader<'_>) -> Option<Self> {
        u8::try_from(r.word()?).ok()
    }
}

impl Words for bool {
    fn put(&self, out: &mut Vec<u32>) {
        out.push(u32::from(*self));
    }
    fn take(r: &mut Reader<'_>) -> Option<Self> {
        match r.word()? {
            0 => Some(false),
            1 => Some(true),
            _ => None,
        }
    }
}

impl<A: Words, B: Words> Words for (A, B) {
    fn put(&self, out: &mut Vec<u32>) {
        self.0.put(out);
        self.1.put(out);
    }
    fn take(r: &mut Reader<'_>) -> Option<Self> {
        Some((A::take(r)?, B::take(r)?))
    }
}

impl<T: Words + Copy + Default, const N: usize> Words for [T; N] {
    fn put(&self, out: &mut Vec<u32>) {
        self.iter().for_each(|v| v.put(out));
    }
    fn take(r: &mut Reader<'_>) -> Option<Self> {
        let mut a = [T::default(); N];
        for v in &mut a {
            *v = T::take(r)?;
        }
        Some(a)
    }
}

/// Implements [`Words`] for a struct, field by field in the order listed. The
/// destructuring `let` makes the list exhaustive: a field added to the struct and not
/// here is a compile error.
macro_rules! words_struct {
    ($ty:ident { $($field:ident),* $(,)? }) => {
        impl Words for $ty {
            fn put(&self, out: &mut Vec<u32>) {
                let $ty { $($field),* } = self;
                $( $field.put(out); )*
            }
            fn take(r: &mut Reader<'_>) -> Option<Self> {
                Some($ty { $( $field: Words::take(r)?, )* })
            }
        }
    };
}

words_struct!(FbiConfig {
    fbz_color_path,
    fog_mode,
    alpha_mode,
    fbz_mode,
    lfb_mode,
    clip_left_right,
    clip_bottom_top,
    fog_color,
    za_color,
    chroma_key,
    stipple,
    color0,
    color1,
});

words_struct!(TmuConfig {
    texture_mode,
    t_lod,
    t_detail,
    tex_base_addr,
    mm_mode,
    small_lod,
    large_lod,
    even_odd,
    st_scale,
});

words_struct!(Combine {
    function,
    factor,
    local,
    other,
    invert,
});

words_struct!(Args {
    blend,
    alpha_test_fn,
    alpha_ref,
    alpha_combine,
    alpha_controls_itrgb,
    color_combine,
    chromakey_mode,
    depth_mask,
    depth_fn,
    depth_mode,
    dither,
    render_buffer,
    color_mask,
    origin,
    chroma_color,
    chroma_range,
    chroma_range_mode,
    clip,
    depth_bias,
    fog_mode,
    fog_color,
    lfb_format,
    lfb_swizzle,
    constant_color,
});

words_struct!(Viewport {
    ox,
    oy,
    oz,
    hwidth,
    hheight,
    hdepth,
});

/// The TMU list: a count (1 to 3) and that many TMUs.
impl Words for Vec<TmuConfig> {
    fn put(&self, out: &mut Vec<u32>) {
        (self.len() as u32).put(out);
        self.iter().for_each(|t| t.put(out));
    }
    fn take(r: &mut Reader<'_>) -> Option<Self> {
        let n = r.word()?;
        if !(1..=3).contains(&n) {
            return None;
        }
        (0..n).map(|_| TmuConfig::take(r)).collect()
    }
}

words_struct!(GlideState {
    fbi,
    tmu,
    args,
    invalid,
    cull_mode,
    cc_requires_it_rgb,
    cc_requires_texture,
    ac_requires_it_alpha,
    ac_requires_texture,
    tmu_mask,
    color_format,
    num_buffers,
    allow_lod_dither,
    smooth_mode,
    coordinate_space,
    viewport,
    lfb_constant_alpha,
    lfb_constant_depth,
    screen_width,
    screen_height,
});

/// A vertex-layout entry in one word: the offset in bits 0-30 (one that `grVertexLayout`
/// accepts), enabled in bit 31.
impl Words for Param {
    fn put(&self, out: &mut Vec<u32>) {
        out.push(self.offset as u32 & 0x7fff_ffff | u32::from(self.enabled) << 31);
    }
    fn take(r: &mut Reader<'_>) -> Option<Self> {
        let w = r.word()?;
        let offset = (w & 0x7fff_ffff) as i32;
        crate::draw::offset_ok(offset).then_some(Param {
            offset,
            enabled: w >> 31 != 0,
        })
    }
}

words_struct!(VertexLayout {
    xy,
    z,
    w,
    q,
    fog,
    a,
    rgb,
    pargb,
    st,
    qn,
    packed_color,
});

/// FNV-1a over the bytes of `words`.
fn checksum(words: &[u32]) -> u32 {
    words
        .iter()
        .flat_map(|w| w.to_le_bytes())
        .fold(0x811c_9dc5, |h, b| {
            (h ^ u32::from(b)).wrapping_mul(0x0100_0193)
        })
}

/// Packs `value` behind `tag` as bytes.
fn save<T: Words>(tag: u32, value: &T) -> Vec<u8> {
    let mut payload = Vec::new();
    value.put(&mut payload);
    let header = [tag, payload.len() as u32, checksum(&payload)];
    header
        .iter()
        .chain(&payload)
        .flat_map(|w| w.to_le_bytes())
        .collect()
}

/// Unpacks a value saved behind `tag` from the start of `bytes`.
fn restore<T: Words>(tag: u32, bytes: &[u8]) -> Option<T> {
    let words: Vec<u32> = bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let (&[t, n, sum], rest) = words.split_first_chunk::<HEADER_WORDS>()?;
    let payload = rest.get(..usize::try_from(n).ok()?)?;
    if t != tag || checksum(payload) != sum {
        return None;
    }
    let mut r = Reader(payload);
    let value = T::take(&mut r)?;
    r.0.is_empty().then_some(value)
}

impl GlideState {
    /// The state as the bytes `grGlideGetState` writes to the caller's buffer; at most
    /// [`GLIDE_STATE_SIZE`](crate::get::GLIDE_STATE_SIZE) bytes for any TMU count.
    pub fn to_bytes(&self) -> Vec<u8> {
        save(STATE_TAG, self)
    }

    /// The state saved in `bytes` by [`GlideState::to_bytes`], or `None` when the bytes
    /// hold no intact saved state.
    pub fn from_bytes(bytes: &[u8]) -> Option<Self> {
        restore(STATE_TAG, bytes)
    }
}

impl VertexLayout {
    /// The layout as the bytes `grGlideGetVertexLayout` writes to the caller's buffer; at
    /// most [`GLIDE_VERTEXLAYOUT_SIZE`](crate::get::GLIDE_VERTEXLAYOUT_SIZE) bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        save(LAYOUT_TAG, self)
    }

    /// The layout saved in `bytes` by [`VertexLayout::to_bytes`], or `None` when the bytes
    /// hold no intact saved layout.
    pub fn from_bytes(bytes: &[u8]) -> Option<Self> {
        restore(LAYOUT_TAG, bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::get::{GLIDE_STATE_SIZE, GLIDE_VERTEXLAYOUT_SIZE};

    fn layout() -> VertexLayout {
        let p = |offset, enabled| Param { offset, enabled };
        VertexLayout {
            xy: p(0, true),
            z: p(8, true),
            w: p(12, false),
            q: p(16, true),
            fog: p(20, false),
            a: p(24, true),
            rgb: p(28, true),
            pargb: p(40, false),
            st: [p(44, true), p(52, false), p(1024, true)],
            qn: [p(60, true), p(64, false), p(68, false)],
            packed_color: true,
        }
    }

    #[test]
    fn a_layout_fits_its_buffer_and_comes_back() {
        let l = layout();
        let bytes = l.to_bytes();
        assert_eq!(bytes.len(), 4 * (3 + 14 + 1));
        assert!(bytes.len() <= GLIDE_VERTEXLAYOUT_SIZE as usize);
        assert_eq!(VertexLayout::from_bytes(&bytes), Some(l));
        // The buffer as the program holds it: longer than the payload.
        let mut buffer = bytes.clone();
        buffer.resize(GLIDE_VERTEXLAYOUT_SIZE as usize, 0xcd);
        assert_eq!(VertexLayout::from_bytes(&buffer), Some(l));
    }

    #[test]
    fn a_state_fits_its_buffer_for_every_tmu_count() {
        for tmus in 1..=3 {
            let mut s = GlideState::new(tmus, 0x1234);
            s.viewport.hdepth = -0.5;
            s.args.alpha_ref = 0x80;
            s.tmu[tmus - 1].st_scale = [1.5, f32::INFINITY];
            let bytes = s.to_bytes();
            assert!(
                bytes.len() <= GLIDE_STATE_SIZE as usize,
                "{tmus} TMUs: {} bytes",
                bytes.len()
            );
            assert_eq!(GlideState::from_bytes(&bytes), Some(s));
        }
    }

    #[test]
    fn damaged_or_foreign_buffers_are_refused() {
        let bytes = layout().to_bytes();
        // Every single-bit flip of a word is caught (tag, length, checksum or payload).
        for bit in 0..bytes.len() * 8 {
            let mut b = bytes.clone();
            b[bit / 8] ^= 1 << (bit % 8);
            assert_eq!(VertexLayout::from_bytes(&b), None, "bit {bit}");
        }
        assert_eq!(VertexLayout::from_bytes(&bytes[..bytes.len() - 4]), None);
        assert_eq!(VertexLayout::from_bytes(&[]), None);
        assert_eq!(VertexLayout::from_bytes(&[0u8; 100]), None);
        // A state buffer is not a layout buffer.
        let state = GlideState::new(1, 0).to_bytes();
        assert_eq!(VertexLayout::from_bytes(&state), None);
        assert_eq!(GlideState::from_bytes(&bytes), None);
    }

    #[test]
    fn out_of_range_fields_are_refused_even_with_a_good_checksum() {
        // An offset grVertexLayout refuses (not a multiple of 4).
        let mut l = layout();
        l.z.offset = 6;
        assert_eq!(VertexLayout::from_bytes(&l.to_bytes()), None);
        l.z.offset = 1028;
        assert_eq!(VertexLayout::from_bytes(&l.to_bytes()), None);
        // A TMU count outside 1..=3.
        let mut s = GlideState::new(3, 0);
        s.tmu.push(s.tmu[0]);
        assert_eq!(GlideState::from_bytes(&s.to_bytes()), None);
    }
}

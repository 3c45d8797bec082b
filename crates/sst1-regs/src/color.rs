//! Colour values that travel between pipeline stages and chips.

/// One colour with 8 bits per channel (an ARGB8888 value split into fields).
///
/// This is what a TMU hands to the next TMU or to the FBI (spec section 3.3), and what
/// the constant-colour registers `color0`/`color1` hold.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Rgba {
    pub r: u8,
    pub g: u8,
    pub b: u8,
    pub a: u8,
}

impl Rgba {
    /// From a packed `0xAARRGGBB` word, as in `color0`, `color1`, `fogColor` (alpha = bits 31:24).
    #[inline]
    pub const fn from_argb(v: u32) -> Self {
        Self {
            r: (v >> 16) as u8,
            g: (v >> 8) as u8,
            b: v as u8,
            a: (v >> 24) as u8,
        }
    }

    /// Packed `0xAARRGGBB`.
    #[inline]
    pub const fn to_argb(self) -> u32 {
        (self.a as u32) << 24 | (self.r as u32) << 16 | (self.g as u32) << 8 | self.b as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn argb_round_trip() {
        let c = Rgba::from_argb(0x80ff4010);
        assert_eq!(
            c,
            Rgba {
                r: 0xff,
                g: 0x40,
                b: 0x10,
                a: 0x80
            }
        );
        assert_eq!(c.to_argb(), 0x80ff4010);
    }
}

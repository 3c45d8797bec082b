//! Stipple test (spec 5.19 `fbzMode` bits 2 and 12, 5.28 `stipple`).
//!
//! * Pattern mode: bit `(y & 3) * 8 + (7 - (x & 7))` of the register enables the pixel.
//! * Rotate mode: the register rotates left by one for every pixel the walker visits and
//!   bit 31 enables the pixel.
//!
//! Source: spec 5.19; bit numbering and rotation per pixel from MAME and DOSBox Staging
//! (they agree; the rotating value is reloaded from the register for every scanline).

/// Returns `true` if the pixel survives the stipple test. `rotating` is the scanline's
/// working copy of the stipple register for rotate mode.
#[inline(always)]
pub fn test(pattern_mode: bool, rotating: &mut u32, reg: u32, x: i32, y: i32) -> bool {
    if pattern_mode {
        let bit = ((y & 3) << 3) | (!x & 7);
        (reg >> bit) & 1 != 0
    } else {
        *rotating = rotating.rotate_left(1);
        *rotating & 0x8000_0000 != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pattern_bits() {
        let mut r = 0;
        // Bit 7 of the register is pixel (0, 0); bit 0 is (7, 0); bit 31 is (0, 3).
        assert!(test(true, &mut r, 1 << 7, 0, 0));
        assert!(!test(true, &mut r, 1 << 7, 1, 0));
        assert!(test(true, &mut r, 1, 7, 0));
        assert!(test(true, &mut r, 1 << 31, 8, 3));
    }

    #[test]
    fn rotate_mode() {
        let mut r = 0x4000_0001u32;
        assert!(test(false, &mut r, 0, 0, 0)); // 0x80000002
        assert!(!test(false, &mut r, 0, 1, 0)); // 0x00000005
        assert_eq!(r, 5);
    }
}

//! The float registers' conversion to the fixed formats (spec 5.2: a float register is
//! converted to its fixed-point twin on write): the one converter the FBI's parameter
//! registers and the TMUs' S/T/W registers share.

/// What a float register write gives when the value does not fit the fixed format.
///
/// All three references truncate toward zero for values in range; they differ when the
/// shifted mantissa overflows 32 bits. Glide 3's console text writes such values
/// (`fstartZ` = NaN, `fdZdX` ~ 6e12 in `glide-sdk/test30`); there MAME and 86Box give
/// the same depth and DOSBox Staging another (6451 aux pixels).
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum FloatOverflow {
    /// MAME: shifts of 0..=31 keep the low 32 bits (they wrap); larger exponents give
    /// 0x7fffffff; then the sign is applied.
    #[default]
    Wrap,
    /// DOSBox Staging: the magnitude saturates at 0x7fffffff, then the sign is applied.
    Saturate,
    /// 86Box (`(int)(f * 4096.0f)` on x86): any value out of range reads 0x80000000.
    Indefinite,
}

/// Convert an IEEE single to fixed point with `frac_bits` fraction bits, truncating toward
/// zero, as the chip's float registers do (spec 5.2: float registers are converted to the
/// fixed formats on write). `overflow` says what out-of-range values give.
pub fn float_to_fixed32(bits: u32, frac_bits: i32, overflow: FloatOverflow) -> i32 {
    let exp = ((bits >> 23) & 0xff) as i32 - 127 - 23 + frac_bits;
    let mantissa = ((bits & 0x7f_ffff) | 0x80_0000) as i64;
    let negative = bits & 0x8000_0000 != 0;
    let magnitude: i64 = if exp < 0 {
        if exp <= -31 {
            0
        } else {
            mantissa >> -exp
        }
    } else {
        let wide = if exp < 40 { mantissa << exp } else { i64::MAX };
        if wide > i32::MAX as i64 {
            match overflow {
                FloatOverflow::Wrap if exp < 32 => (mantissa << exp) as u32 as i32 as i64,
                FloatOverflow::Wrap | FloatOverflow::Saturate => i32::MAX as i64,
                FloatOverflow::Indefinite => return i32::MIN,
            }
        } else {
            wide
        }
    };
    let v = magnitude as i32;
    if negative {
        v.wrapping_neg()
    } else {
        v
    }
}

/// Convert an IEEE single to 64-bit fixed point with `frac_bits` fraction bits
/// (truncating toward zero, saturating), for the W/S/T float registers of the FBI and
/// the TMUs. Source: MAME `float_to_int64(data, 32)` for the TMUs' `fstartS` .. `fdWdY`;
/// DOSBox Staging and 86Box (`(int64_t)(f * 2^32)`) keep the same 32 fraction bits.
pub fn float_to_fixed64(bits: u32, frac_bits: i32) -> i64 {
    let exp = ((bits >> 23) & 0xff) as i32 - 127 - 23 + frac_bits;
    let mantissa = ((bits & 0x7f_ffff) | 0x80_0000) as i64;
    let magnitude = if exp < 0 {
        if exp <= -64 {
            0
        } else {
            mantissa >> -exp
        }
    } else if exp < 40 {
        mantissa << exp
    } else {
        i64::MAX
    };
    if bits & 0x8000_0000 != 0 {
        magnitude.wrapping_neg()
    } else {
        magnitude
    }
}

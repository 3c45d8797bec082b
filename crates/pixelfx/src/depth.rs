//! Depth value, bias and depth test (spec 5.19 `fbzMode` bits 3-7, 16, 20; 5.19.1;
//! 5.26 `zaColor`).
//!
//! The depth value is either the clamped 16-bit Z or the 16-bit floating-point form of
//! W (W-buffering, `fbzMode` bit 3). Depth bias adds the signed `zaColor[15:0]` and
//! clamps to 0..=0xffff. With `depth_source_compare` the test uses `zaColor[15:0]`
//! instead, while the buffer is still written with the biased iterated value.
//! Source: spec 5.19 and 5.26; MAME and DOSBox Staging agree on the order.

use sst1_regs::DepthFunction;

/// The 16-bit depth value of a pixel (before the test).
#[inline(always)]
pub fn value(wbuffer: bool, z16: u16, wfloat: u16, bias: Option<u16>) -> i32 {
    let v = if wbuffer { wfloat as i32 } else { z16 as i32 };
    match bias {
        Some(b) => (v + b as i16 as i32).clamp(0, 0xffff),
        None => v,
    }
}

/// The depth comparison (spec 5.19.1): `true` if the pixel passes.
#[inline(always)]
pub fn test(func: DepthFunction, source: i32, dest: u16) -> bool {
    func.passes(source, dest as i32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bias_clamps() {
        assert_eq!(value(false, 0xfff0, 0, Some(0x0020)), 0xffff);
        assert_eq!(value(false, 0x0010, 0, Some(0xffe0)), 0);
        assert_eq!(value(true, 0, 0x1234, Some(0x0001)), 0x1235);
        assert_eq!(value(true, 0, 0x1234, None), 0x1234);
    }

    #[test]
    fn functions() {
        use sst1_regs::CompareFunction::*;
        let r: Vec<bool> = [
            Never,
            Less,
            Equal,
            LessEqual,
            Greater,
            NotEqual,
            GreaterEqual,
            Always,
        ]
        .iter()
        .map(|&f| test(f, 5, 5))
        .collect();
        assert_eq!(r, [false, false, true, true, false, false, true, true]);
        assert!(test(Less, 4, 5) && !test(Greater, 4, 5));
    }
}

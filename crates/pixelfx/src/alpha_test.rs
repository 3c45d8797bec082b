//! Alpha test (spec 5.18.1): compare `a_other` with `alphaMode.alpha_ref`.
//! Source: spec 5.18.1; MAME and DOSBox Staging agree.

use sst1_regs::AlphaFunction;

/// `true` if the pixel passes the alpha test.
#[inline(always)]
pub fn test(func: AlphaFunction, alpha: u8, reference: u8) -> bool {
    func.passes(alpha as i32, reference as i32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn all_functions_at_the_reference() {
        use sst1_regs::CompareFunction::*;
        let at: Vec<bool> = [
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
        .map(|&f| test(f, 0x80, 0x80))
        .collect();
        assert_eq!(at, [false, false, true, true, false, false, true, true]);
        assert!(test(Less, 0x7f, 0x80) && test(Greater, 0x81, 0x80));
    }
}

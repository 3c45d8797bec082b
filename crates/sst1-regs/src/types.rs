//! Typed, self-describing views of the SST-1 mode and configuration registers.
//!
//! Source: SST-1 Graphics Engine specification rev 1.61, section 5 (one subsection per
//! register, cited on each type). Each register is a `u32` newtype; every bit field the
//! spec defines has one `const fn` accessor named after the spec's field, in snake case.
//!
//! * 1-bit fields return `bool` (`true` = the bit is 1; the doc line says what 1 means).
//! * Numbers return `u8`/`u16`/`u32` (or `i32` for the spec's signed fields, sign-extended).
//! * Selector fields return a `#[repr(u8)]` enum whose discriminant is the field value.
//!   Every encoding has a variant, reserved ones included (`ReservedN`), so decoding never
//!   fails and never panics.
//!
//! Every type implements [`fmt::Debug`] by printing the raw value and then every field by
//! name (`depth_function: LessEqual`); `{:#?}` prints one field per line. Trace dumps,
//! logs and test failure reports use this.
//!
//! The field declarations below are written `hi:lo name => Type`, in ascending bit order;
//! a compile-time check rejects overlapping fields and fields whose width does not match
//! their type. Bits a register leaves undeclared are reserved.

use core::fmt;

/// Mask of the low `hi - lo + 1` bits.
const fn field_mask(hi: u32, lo: u32) -> u32 {
    if hi - lo >= 31 {
        u32::MAX
    } else {
        (1 << (hi - lo + 1)) - 1
    }
}

/// Extracts bits `hi:lo` of `v` as the field's type.
macro_rules! get_field {
    (bool, $v:expr, $hi:literal, $lo:literal) => {
        ($v >> $lo) & 1 != 0
    };
    (u8, $v:expr, $hi:literal, $lo:literal) => {
        (($v >> $lo) & field_mask($hi, $lo)) as u8
    };
    (u16, $v:expr, $hi:literal, $lo:literal) => {
        (($v >> $lo) & field_mask($hi, $lo)) as u16
    };
    (u32, $v:expr, $hi:literal, $lo:literal) => {
        ($v >> $lo) & field_mask($hi, $lo)
    };
    // Two's complement field: shift the sign bit up to bit 31, then arithmetic-shift down.
    (i32, $v:expr, $hi:literal, $lo:literal) => {
        (($v << (31 - $hi)) as i32) >> (31 - $hi + $lo)
    };
    ($e:ident, $v:expr, $hi:literal, $lo:literal) => {
        $e::from_bits($v >> $lo)
    };
}

/// Compile-time check that a field's width suits its type.
macro_rules! check_width {
    (bool, $hi:literal, $lo:literal) => {
        assert!($hi == $lo)
    };
    (u8, $hi:literal, $lo:literal) => {
        assert!($hi - $lo < 8)
    };
    (u16, $hi:literal, $lo:literal) => {
        assert!($hi - $lo < 16)
    };
    (u32, $hi:literal, $lo:literal) => {
        assert!($hi - $lo < 32)
    };
    (i32, $hi:literal, $lo:literal) => {
        assert!($hi - $lo < 32)
    };
    ($e:ident, $hi:literal, $lo:literal) => {
        assert!($hi - $lo + 1 == $e::BITS)
    };
}

/// Declares a register newtype with one accessor per field and a field-by-field `Debug`.
macro_rules! register {
    (
        $(#[$m:meta])*
        pub struct $name:ident;
        $( $(#[$fm:meta])* $hi:literal : $lo:literal $field:ident => $ty:ident, )+
    ) => {
        $(#[$m])*
        #[derive(Clone, Copy, PartialEq, Eq, Default, Hash)]
        pub struct $name(pub u32);

        impl $name {
            $(
                $(#[$fm])*
                #[inline]
                pub const fn $field(self) -> $ty {
                    get_field!($ty, self.0, $hi, $lo)
                }
            )+
        }

        // Fields lie inside the word, do not overlap, and fit their types.
        const _: () = {
            let mut used = 0u32;
            $(
                assert!($hi < 32 && $hi >= $lo);
                check_width!($ty, $hi, $lo);
                let m = field_mask($hi, $lo) << $lo;
                assert!(used & m == 0, "overlapping fields");
                used |= m;
            )+
            let _ = used;
        };

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.debug_struct(stringify!($name))
                    .field("raw", &format_args!("{:#010x}", self.0))
                    $( .field(stringify!($field), &self.$field()) )+
                    .finish()
            }
        }
    };
}

/// Declares a selector enum covering every encoding of an N-bit field.
macro_rules! field_enum {
    (
        $(#[$m:meta])*
        pub enum $name:ident : $bits:literal {
            $( $(#[$vm:meta])* $var:ident = $val:literal, )+
        }
    ) => {
        $(#[$m])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[repr(u8)]
        pub enum $name {
            $( $(#[$vm])* $var = $val, )+
        }

        impl $name {
            /// Width in bits of the register field this selector is decoded from.
            pub const BITS: u32 = $bits;
            /// Every encoding, indexed by its value (the array length forces completeness).
            const ALL: [Self; 1 << $bits] = [$( Self::$var ),+];

            /// The selector encoded in the low [`Self::BITS`] bits of `raw`; higher bits are
            /// ignored, so every input decodes.
            #[inline]
            pub const fn from_bits(raw: u32) -> Self {
                Self::ALL[(raw & ((1 << $bits) - 1)) as usize]
            }
        }

        // Variants are listed in encoding order.
        const _: () = {
            let mut i = 0;
            while i < $name::ALL.len() {
                assert!($name::ALL[i] as usize == i);
                i += 1;
            }
        };
    };
}

// ---------------------------------------------------------------------------------------
// Selector enums
// ---------------------------------------------------------------------------------------

field_enum! {
    /// `fbzColorPath` bits 1:0, `rgbselect`: the colour combine unit's `c_other` input.
    /// Source: spec 5.16.
    pub enum RgbSelect: 2 {
        /// Iterated RGB.
        IteratedRgb = 0,
        /// TREX colour output.
        Texture = 1,
        /// `color1` RGB.
        Color1 = 2,
        /// Reserved. The spec's colour-path diagram shows linear-frame-buffer RGB here, and
        /// 3dfx's Glide `sst.h` names it `SST_RGBSEL_LFB`.
        Reserved3 = 3,
    }
}

field_enum! {
    /// `fbzColorPath` bits 3:2, `aselect`: the alpha combine unit's `a_other` input.
    /// Source: spec 5.16.
    pub enum AlphaSelect: 2 {
        /// Iterated alpha.
        IteratedAlpha = 0,
        /// TREX alpha output.
        Texture = 1,
        /// `color1` alpha.
        Color1 = 2,
        /// Reserved (the diagram shows linear-frame-buffer alpha; Glide: `SST_ASEL_LFB`).
        Reserved3 = 3,
    }
}

field_enum! {
    /// `fbzColorPath` bits 6:5, `cca_localselect`: the alpha combine unit's `a_local`.
    /// Source: spec 5.16.
    pub enum AlphaLocalSelect: 2 {
        /// Iterated alpha.
        IteratedAlpha = 0,
        /// `color0` alpha.
        Color0 = 1,
        /// Iterated Z (bits 27:20 of the 20.12 Z iterator).
        IteratedZ = 2,
        /// Reserved (Glide's `sst.h` names it `SST_ALOCAL_W`).
        Reserved3 = 3,
    }
}

field_enum! {
    /// `fbzColorPath` `cc_mselect` (bits 12:10) and `cca_mselect` (bits 21:19): the blend
    /// factor of the colour / alpha combine unit. In the alpha unit `CLocal` is its local
    /// value `a_local` (the spec lists 1 and 3 both as `a_local` there).
    /// Source: spec 5.16.
    pub enum CcMselect: 3 {
        /// Zero.
        Zero = 0,
        /// `c_local` (for `cca_mselect`: `a_local`).
        CLocal = 1,
        /// `a_other`.
        AOther = 2,
        /// `a_local`.
        ALocal = 3,
        /// Texture alpha.
        TextureAlpha = 4,
        /// Reserved (Glide's `sst.h` names 5 `SST_CC_MRGBTMU`, texture RGB).
        Reserved5 = 5,
        /// Reserved.
        Reserved6 = 6,
        /// Reserved.
        Reserved7 = 7,
    }
}

field_enum! {
    /// `textureMode` `tc_mselect` (bits 16:14) and `tca_mselect` (bits 25:23): the blend
    /// factor of the texture colour / alpha combine units. Source: spec 5.50.
    pub enum TcMselect: 3 {
        /// Zero.
        Zero = 0,
        /// `c_local`.
        CLocal = 1,
        /// `a_other`.
        AOther = 2,
        /// `a_local`.
        ALocal = 3,
        /// The spec's table calls 4 `LOD`; its combine-unit diagram shows `detail_factor`
        /// (the `tDetail` blend factor, spec 5.52) at this input.
        DetailFactor = 4,
        /// `LOD_frac`: the fractional part of the LOD (`LODB_frac[7:0]` in the diagram).
        LodFrac = 5,
        /// Reserved.
        Reserved6 = 6,
        /// Reserved.
        Reserved7 = 7,
    }
}

field_enum! {
    /// A comparison function: `fbzMode` depth function (spec 5.19.1) and `alphaMode` alpha
    /// function (spec 5.18.1) share the same encoding. Read as `source OP reference`.
    pub enum CompareFunction: 3 {
        /// Never passes.
        Never = 0,
        /// `<`
        Less = 1,
        /// `==`
        Equal = 2,
        /// `<=`
        LessEqual = 3,
        /// `>`
        Greater = 4,
        /// `!=`
        NotEqual = 5,
        /// `>=`
        GreaterEqual = 6,
        /// Always passes.
        Always = 7,
    }
}

impl CompareFunction {
    /// `source OP reference`: whether a pixel passes the depth or alpha test.
    #[inline]
    pub const fn passes(self, source: i32, reference: i32) -> bool {
        match self {
            Self::Never => false,
            Self::Less => source < reference,
            Self::Equal => source == reference,
            Self::LessEqual => source <= reference,
            Self::Greater => source > reference,
            Self::NotEqual => source != reference,
            Self::GreaterEqual => source >= reference,
            Self::Always => true,
        }
    }
}

/// `fbzMode` bits 7:5 (spec 5.19.1): `DEPTH_src OP DEPTH_dst`.
pub type DepthFunction = CompareFunction;
/// `alphaMode` bits 3:1 (spec 5.18.1): `AlphaSrc OP AlphaRef`.
pub type AlphaFunction = CompareFunction;

field_enum! {
    /// An alpha-blending factor, `alphaMode` bits 11:8, 15:12, 19:16, 23:20.
    /// Source: spec 5.18.2 (mnemonics in parentheses).
    pub enum BlendFactor: 4 {
        /// Zero (`AZERO`).
        Zero = 0,
        /// Source alpha (`ASRC_ALPHA`).
        SrcAlpha = 1,
        /// Colour (`A_COLOR`): as a source factor the destination colour, as a destination
        /// factor the source colour.
        Color = 2,
        /// Destination alpha (`ADST_ALPHA`).
        DstAlpha = 3,
        /// One (`AONE`).
        One = 4,
        /// 1 - source alpha (`AOMSRC_ALPHA`).
        OneMinusSrcAlpha = 5,
        /// 1 - colour (`AOM_COLOR`) (colour chosen as for [`Self::Color`]).
        OneMinusColor = 6,
        /// 1 - destination alpha (`AOMDST_ALPHA`).
        OneMinusDstAlpha = 7,
        /// Reserved.
        Reserved8 = 8,
        /// Reserved.
        Reserved9 = 9,
        /// Reserved.
        Reserved10 = 10,
        /// Reserved.
        Reserved11 = 11,
        /// Reserved.
        Reserved12 = 12,
        /// Reserved.
        Reserved13 = 13,
        /// Reserved.
        Reserved14 = 14,
        /// 0xf: as a source factor `ASATURATE` = min(source alpha, 1 - destination alpha);
        /// as a destination factor `A_COLORBEFOREFOG`, the source colour before fog.
        SaturateOrColorBeforeFog = 15,
    }
}

field_enum! {
    /// `fogMode` bits 4:3 (`fogalpha`, `fogz`): where the fog blending alpha comes from.
    /// Source: spec 5.17.
    pub enum FogZa: 2 {
        /// The fog table, indexed by the floating-point 1/W.
        FogTable = 0,
        /// The integer part of iterated alpha (bit 3).
        IteratedAlpha = 1,
        /// Iterated Z bits 27:20 (bit 4).
        IteratedZ = 2,
        /// Both bits set: spec 5.17 says bit 4 takes precedence, so iterated Z is used.
        /// (MAME treats 3 as iterated W, a Voodoo 2 feature.)
        IteratedZAndAlpha = 3,
    }
}

field_enum! {
    /// A colour buffer selector: `fbzMode` bits 15:14 (draw buffer, spec 5.19) and
    /// `lfbMode` bits 5:4 (LFB write buffer, spec 5.20).
    pub enum ColorBuffer: 2 {
        /// Front buffer.
        Front = 0,
        /// Back buffer.
        Back = 1,
        /// Reserved.
        Reserved2 = 2,
        /// Reserved.
        Reserved3 = 3,
    }
}

field_enum! {
    /// `lfbMode` bits 7:6: the buffer LFB reads return. Source: spec 5.20.
    pub enum LfbReadBuffer: 2 {
        /// Front buffer.
        Front = 0,
        /// Back buffer.
        Back = 1,
        /// Depth/alpha (auxiliary) buffer.
        Aux = 2,
        /// Reserved.
        Reserved3 = 3,
    }
}

field_enum! {
    /// `lfbMode` bits 3:0: the linear-frame-buffer write format. Source: spec 5.20.
    pub enum LfbWriteFormat: 4 {
        /// 16-bit RGB 5-6-5.
        Rgb565 = 0,
        /// 16-bit RGB x-5-5-5.
        Rgb555 = 1,
        /// 16-bit ARGB 1-5-5-5.
        Argb1555 = 2,
        /// Reserved.
        Reserved3 = 3,
        /// 24-bit RGB x-8-8-8 (32-bit writes).
        Rgb888 = 4,
        /// 32-bit ARGB 8-8-8-8.
        Argb8888 = 5,
        /// Reserved.
        Reserved6 = 6,
        /// Reserved.
        Reserved7 = 7,
        /// Reserved.
        Reserved8 = 8,
        /// Reserved.
        Reserved9 = 9,
        /// Reserved.
        Reserved10 = 10,
        /// Reserved.
        Reserved11 = 11,
        /// 16-bit depth, 16-bit RGB 5-6-5.
        DepthRgb565 = 12,
        /// 16-bit depth, 16-bit RGB x-5-5-5.
        DepthRgb555 = 13,
        /// 16-bit depth, 16-bit ARGB 1-5-5-5.
        DepthArgb1555 = 14,
        /// 16-bit depth, 16-bit depth.
        DepthDepth = 15,
    }
}

field_enum! {
    /// `lfbMode` bits 10:9: order of the colour channels in LFB data. Source: spec 5.20.
    pub enum RgbaLanes: 2 {
        /// ARGB.
        Argb = 0,
        /// ABGR.
        Abgr = 1,
        /// RGBA.
        Rgba = 2,
        /// BGRA.
        Bgra = 3,
    }
}

field_enum! {
    /// `textureMode` bits 11:8 (`tformat`): texel format. Source: spec 5.50 (names as in
    /// 3dfx's Glide `sst.h`).
    pub enum TextureFormat: 4 {
        /// 8-bit RGB 3-3-2.
        Rgb332 = 0,
        /// 8-bit YIQ 4-2-2 (NCC).
        Yiq422 = 1,
        /// 8-bit alpha.
        A8 = 2,
        /// 8-bit intensity.
        I8 = 3,
        /// 8-bit alpha, intensity 4-4.
        Ai44 = 4,
        /// 8-bit palette (not revision 0 TMU).
        P8 = 5,
        /// Reserved.
        Reserved6 = 6,
        /// Reserved.
        Reserved7 = 7,
        /// 16-bit ARGB 8-3-3-2.
        Argb8332 = 8,
        /// 16-bit AYIQ 8-4-2-2 (NCC).
        Ayiq8422 = 9,
        /// 16-bit RGB 5-6-5.
        Rgb565 = 10,
        /// 16-bit ARGB 1-5-5-5.
        Argb1555 = 11,
        /// 16-bit ARGB 4-4-4-4.
        Argb4444 = 12,
        /// 16-bit alpha, intensity 8-8.
        Ai88 = 13,
        /// 16-bit alpha, palette 8-8 (not revision 0 TMU).
        Ap88 = 14,
        /// Reserved.
        Reserved15 = 15,
    }
}

field_enum! {
    /// `fbiInit2` bits 10:9: what a buffer swap waits for. Source: spec 5.44.
    pub enum SwapBufferAlgorithm: 2 {
        /// Based on `dac_vsync`.
        DacVsync = 0,
        /// Based on `dac_data(0)`.
        DacData0 = 1,
        /// Based on `pci_fifo_stall`.
        PciFifoStall = 2,
        /// Reserved (Glide's `sst1init.h` names it `SST_SWAP_SLISYNC`).
        Reserved3 = 3,
    }
}

// ---------------------------------------------------------------------------------------
// Rendering mode registers
// ---------------------------------------------------------------------------------------

register! {
    /// `status` (0x000), spec 5.1: FIFO free space, busy bits, displayed buffer.
    /// Read only; a write clears the PCI interrupt.
    #[doc(alias = "status")]
    pub struct Status;
    /// Bits 5:0: PCI FIFO free space (0x3f = FIFO empty).
    5:0 pci_fifo_freespace => u32,
    /// Bit 6: vertical retrace, spec polarity: `false` = retrace active, `true` = inactive.
    6:6 vertical_retrace => bool,
    /// Bit 7: FBI graphics engine busy.
    7:7 fbi_busy => bool,
    /// Bit 8: TREX busy.
    8:8 trex_busy => bool,
    /// Bit 9: SST-1 busy (any unit or FIFO).
    9:9 sst1_busy => bool,
    /// Bits 11:10: displayed buffer (0 = buffer 0, 1 = buffer 1, 2 = auxiliary, 3 reserved).
    11:10 displayed_buffer => u32,
    /// Bits 27:12: memory FIFO free space (0xffff = empty).
    27:12 memory_fifo_freespace => u32,
    /// Bits 30:28: swap buffers pending.
    30:28 swap_buffers_pending => u32,
    /// Bit 31: PCI interrupt generated (not implemented in hardware: always 0).
    31:31 pci_interrupt => bool,
}

register! {
    /// `fbzColorPath` (0x104), spec 5.16: input selects and controls of the colour
    /// combine unit (`cc_*`, bits 16:7 and 4:0) and the alpha combine unit (`cca_*`,
    /// bits 25:17 and 6:5), subpixel correction and texture enable.
    #[doc(alias = "fbzColorPath")]
    pub struct FbzColorPath;
    /// Bits 1:0: RGB select (`c_other`).
    1:0 cc_rgbselect => RgbSelect,
    /// Bits 3:2: alpha select (`a_other`).
    3:2 cc_aselect => AlphaSelect,
    /// Bit 4: `c_local` select: `false` = iterated RGB, `true` = `color0` RGB.
    4:4 cc_localselect => bool,
    /// Bits 6:5: alpha combine `a_local` select.
    6:5 cca_localselect => AlphaLocalSelect,
    /// Bit 7: `true` = texture alpha bit 7 selects `c_local` instead of `cc_localselect`.
    7:7 cc_localselect_override => bool,
    /// Bit 8: `true` = zero instead of `c_other`.
    8:8 cc_zero_other => bool,
    /// Bit 9: `true` = subtract `c_local`.
    9:9 cc_sub_clocal => bool,
    /// Bits 12:10: colour blend factor.
    12:10 cc_mselect => CcMselect,
    /// Bit 13: reverse blend (invert the blend factor's sense).
    13:13 cc_reverse_blend => bool,
    /// Bit 14: add `c_local`.
    14:14 cc_add_clocal => bool,
    /// Bit 15: add `a_local`.
    15:15 cc_add_alocal => bool,
    /// Bit 16: invert the colour output.
    16:16 cc_invert_output => bool,
    /// Bit 17: `true` = zero instead of `a_other`.
    17:17 cca_zero_other => bool,
    /// Bit 18: `true` = subtract `a_local`.
    18:18 cca_sub_clocal => bool,
    /// Bits 21:19: alpha blend factor.
    21:19 cca_mselect => CcMselect,
    /// Bit 22: alpha reverse blend.
    22:22 cca_reverse_blend => bool,
    /// Bit 23: alpha add `c_local` (`a_local`).
    23:23 cca_add_clocal => bool,
    /// Bit 24: alpha add `a_local`.
    24:24 cca_add_alocal => bool,
    /// Bit 25: invert the alpha output.
    25:25 cca_invert_output => bool,
    /// Bit 26: adjust parameters for subpixel correction.
    26:26 param_adjust => bool,
    /// Bit 27: enable texture mapping (TREX-to-FBI transfer).
    27:27 texture_enable => bool,
}

register! {
    /// `fogMode` (0x108), spec 5.17: the fog unit.
    #[doc(alias = "fogMode")]
    pub struct FogMode;
    /// Bit 0: enable fog.
    0:0 enable_fog => bool,
    /// Bit 1 (`fogadd`): `false` = add `fogColor`, `true` = add zero.
    1:1 fog_add => bool,
    /// Bit 2 (`fogmult`): `false` = multiply the colour-combine RGB, `true` = zero.
    2:2 fog_mult => bool,
    /// Bits 4:3 (`fogalpha`, `fogz`): fog alpha source.
    4:3 fog_za => FogZa,
    /// Bit 5 (`fogconstant`): `true` = add `fogColor` as a constant (overrides 4:3).
    5:5 fog_constant => bool,
}

register! {
    /// `alphaMode` (0x10c), spec 5.18: alpha test and alpha blending.
    #[doc(alias = "alphaMode")]
    pub struct AlphaMode;
    /// Bit 0: enable the alpha function (test).
    0:0 alpha_test_enable => bool,
    /// Bits 3:1: alpha function, `alpha OP alpha_ref`.
    3:1 alpha_function => AlphaFunction,
    /// Bit 4: enable alpha blending.
    4:4 alpha_blend_enable => bool,
    /// Bit 5: enable anti-aliasing (not implemented in SST-1, spec 5.18).
    5:5 antialias_enable => bool,
    /// Bits 11:8: source RGB blend factor.
    11:8 src_rgb_blend => BlendFactor,
    /// Bits 15:12: destination RGB blend factor.
    15:12 dst_rgb_blend => BlendFactor,
    /// Bits 19:16: source alpha-channel blend factor.
    19:16 src_alpha_blend => BlendFactor,
    /// Bits 23:20: destination alpha-channel blend factor.
    23:20 dst_alpha_blend => BlendFactor,
    /// Bits 31:24: alpha reference value.
    31:24 alpha_ref => u8,
}

register! {
    /// `fbzMode` (0x110), spec 5.19: clipping, chroma key, stipple, depth buffer,
    /// dithering, write masks, draw buffer, Y origin.
    #[doc(alias = "fbzMode")]
    pub struct FbzMode;
    /// Bit 0: enable the clipping rectangle.
    0:0 enable_clipping => bool,
    /// Bit 1: enable chroma-keying.
    1:1 enable_chromakey => bool,
    /// Bit 2: enable stipple register masking.
    2:2 enable_stipple => bool,
    /// Bit 3: `false` = Z, `true` = W for depth buffering.
    3:3 wbuffer_select => bool,
    /// Bit 4: enable depth buffering.
    4:4 enable_depthbuffer => bool,
    /// Bits 7:5: depth function.
    7:5 depth_function => DepthFunction,
    /// Bit 8: enable dithering.
    8:8 enable_dithering => bool,
    /// Bit 9: RGB buffer write mask (`false` = RGB writes disabled).
    9:9 rgb_buffer_mask => bool,
    /// Bit 10: depth/alpha buffer write mask (`false` = aux writes disabled).
    10:10 aux_buffer_mask => bool,
    /// Bit 11: dither algorithm: `false` = 4x4, `true` = 2x2 ordered dither.
    11:11 dither_2x2 => bool,
    /// Bit 12: stipple mode: `false` = rotate, `true` = pattern.
    12:12 enable_stipple_pattern => bool,
    /// Bit 13: enable alpha-channel mask (alpha bit 0 masks writes).
    13:13 enable_alpha_mask => bool,
    /// Bits 15:14: draw buffer.
    15:14 draw_buffer => ColorBuffer,
    /// Bit 16: enable depth biasing by `zaColor` bits 15:0.
    16:16 enable_depth_bias => bool,
    /// Bit 17: rendering Y origin: `false` = top of screen, `true` = bottom.
    17:17 y_origin => bool,
    /// Bit 18: enable alpha planes (the aux buffer holds alpha).
    18:18 enable_alpha_planes => bool,
    /// Bit 19: enable alpha-blending dither subtraction.
    19:19 dither_subtract => bool,
    /// Bit 20: depth source compare: `true` = compare `zaColor` bits 15:0 (not in FBI
    /// revision 1.0).
    20:20 depth_source_compare => bool,
}

register! {
    /// `lfbMode` (0x114; `lfBMode` in the spec's table), spec 5.20: linear frame buffer
    /// access.
    #[doc(alias = "lfbMode")]
    #[doc(alias = "lfBMode")]
    pub struct LfbMode;
    /// Bits 3:0: LFB write format.
    3:0 write_format => LfbWriteFormat,
    /// Bits 5:4: buffer LFB writes go to.
    5:4 write_buffer_select => ColorBuffer,
    /// Bits 7:6: buffer LFB reads come from.
    7:6 read_buffer_select => LfbReadBuffer,
    /// Bit 8: send LFB writes through the pixel pipeline.
    8:8 enable_pixel_pipeline => bool,
    /// Bits 10:9: RGBA lanes of LFB data.
    10:9 rgba_lanes => RgbaLanes,
    /// Bit 11: swap the two 16-bit words of LFB writes.
    11:11 word_swap_writes => bool,
    /// Bit 12: byte swizzle LFB writes.
    12:12 byte_swizzle_writes => bool,
    /// Bit 13: LFB Y origin: `false` = top of screen, `true` = bottom.
    13:13 y_origin => bool,
    /// Bit 14: W for pipelined LFB writes: `false` = LFB depth, `true` = `zaColor` 15:0.
    14:14 write_w_select => bool,
    /// Bit 15: swap the two 16-bit words of LFB reads.
    15:15 word_swap_reads => bool,
    /// Bit 16: byte swizzle LFB reads.
    16:16 byte_swizzle_reads => bool,
}

register! {
    /// `clipLeftRight` (0x118), spec 5.21: X clip edges; left inclusive, right exclusive.
    #[doc(alias = "clipLeftRight")]
    pub struct ClipLeftRight;
    /// Bits 9:0: right clipping edge (exclusive).
    9:0 clip_right => u32,
    /// Bits 25:16: left clipping edge (inclusive).
    25:16 clip_left => u32,
}

register! {
    /// `clipLowYHighY` (0x11c), spec 5.21: Y clip edges; low inclusive, high exclusive.
    /// Y = 0 is always the top of the screen, whatever the Y origin bits say.
    #[doc(alias = "clipLowYHighY")]
    pub struct ClipLowYHighY;
    /// Bits 9:0: high Y clipping edge (exclusive).
    9:0 clip_highy => u32,
    /// Bits 25:16: low Y clipping edge (inclusive).
    25:16 clip_lowy => u32,
}

register! {
    /// `zaColor` (0x130), spec 5.26: constant depth and alpha for LFB writes, FASTFILL
    /// and depth bias.
    #[doc(alias = "zaColor")]
    pub struct ZaColor;
    /// Bits 15:0: constant depth (also the depth bias, read as signed by the references).
    15:0 constant_depth => u16,
    /// Bits 31:24: constant alpha.
    31:24 constant_alpha => u8,
}

register! {
    /// `chromaKey` (0x134), spec 5.27: the 24-bit RGB chroma-key colour.
    #[doc(alias = "chromaKey")]
    pub struct ChromaKey;
    /// Bits 7:0: chroma-key blue.
    7:0 blue => u8,
    /// Bits 15:8: chroma-key green.
    15:8 green => u8,
    /// Bits 23:16: chroma-key red.
    23:16 red => u8,
}

register! {
    /// `stipple` (0x140), spec 5.28: the stipple mask (see [`FbzMode::enable_stipple`]).
    #[doc(alias = "stipple")]
    pub struct Stipple;
    /// Bits 31:0: stipple value.
    31:0 stipple_value => u32,
}

impl Stipple {
    /// The mask bit that stipple *pattern* mode uses for the pixel at `(x, y)`: row
    /// `y & 3` is byte `y & 3` of the register, and pixel `x & 7` takes bit `7 - (x & 7)`
    /// of that byte. Source: spec 5.19 (pseudo-code under bit 12).
    #[inline]
    pub const fn pattern_bit(self, x: u32, y: u32) -> bool {
        let shift = (y & 3) * 8 + (7 - (x & 7));
        (self.0 >> shift) & 1 != 0
    }
}

// ---------------------------------------------------------------------------------------
// Video timing registers (spec 5.38-5.41, section 10)
// ---------------------------------------------------------------------------------------

register! {
    /// `hSync` (0x220), spec 5.38: horizontal sync timing, in VCLKs.
    #[doc(alias = "hSync")]
    pub struct HSync;
    /// Bits 7:0 (`hSync_on`): active horizontal sync VCLKs - 1.
    7:0 h_sync_on => u32,
    /// Bits 25:16 (`hSync_off`): inactive horizontal sync VCLKs - 1.
    25:16 h_sync_off => u32,
}

impl HSync {
    /// Number of VCLKs of active horizontal sync (`hSync_on + 1`, spec section 10).
    #[inline]
    pub const fn active_clocks(self) -> u32 {
        self.h_sync_on() + 1
    }

    /// Number of VCLKs of inactive horizontal sync (`hSync_off + 1`, spec section 10);
    /// with [`Self::active_clocks`] this is the whole scan line.
    #[inline]
    pub const fn inactive_clocks(self) -> u32 {
        self.h_sync_off() + 1
    }
}

register! {
    /// `vSync` (0x224), spec 5.39: vertical sync timing, in scan lines.
    #[doc(alias = "vSync")]
    pub struct VSync;
    /// Bits 11:0 (`vSync_on`): scan lines of active vertical sync.
    11:0 v_sync_on => u32,
    /// Bits 27:16 (`vSync_off`): scan lines of inactive vertical sync.
    27:16 v_sync_off => u32,
}

register! {
    /// `backPorch` (0x208), spec 5.40: back porch timing.
    #[doc(alias = "backPorch")]
    pub struct BackPorch;
    /// Bits 7:0 (`hBackPorch`): horizontal back porch VCLKs - 2 (spec section 10).
    7:0 h_back_porch => u32,
    /// Bits 23:16 (`vBackPorch`): vertical back porch scan lines.
    23:16 v_back_porch => u32,
}

impl BackPorch {
    /// Number of VCLKs of horizontal back porch blank (`hBackPorch + 2`, spec section 10).
    #[inline]
    pub const fn h_back_porch_clocks(self) -> u32 {
        self.h_back_porch() + 2
    }
}

register! {
    /// `videoDimensions` (0x20c), spec 5.41: the displayed resolution.
    #[doc(alias = "videoDimensions")]
    pub struct VideoDimensions;
    /// Bits 9:0 (`xWidth`): X (width) dimension.
    9:0 x_width => u32,
    /// Bits 25:16 (`yHeight`): Y (height) dimension.
    25:16 y_height => u32,
}

// ---------------------------------------------------------------------------------------
// FBI initialization registers (spec 5.42-5.46)
// ---------------------------------------------------------------------------------------

register! {
    /// `fbiInit0` (0x210), spec 5.42: miscellaneous and FIFO control. Written only when
    /// PCI `initEnable` bit 0 is set; not FIFOed.
    #[doc(alias = "fbiInit0")]
    pub struct FbiInit0;
    /// Bit 0: VGA passthrough (pins `vga_pass`, `vga_pass_n`).
    0:0 vga_passthrough => bool,
    /// Bit 1: FBI graphics reset (`true` = reset).
    1:1 graphics_reset => bool,
    /// Bit 2: FBI FIFO reset (PCI FIFO and data packer).
    2:2 fifo_reset => bool,
    /// Bit 3: byte swizzle incoming register writes when `pci_address[21]` = 1.
    3:3 swizzle_register_writes => bool,
    /// Bit 4: stall PCI for the high water mark.
    4:4 stall_pci_enable => bool,
    /// Bits 10:6: PCI FIFO empty entries low water mark (0-31).
    10:6 pci_fifo_low_water_mark => u32,
    /// Bit 11: LFB accesses go through the memory FIFO.
    11:11 lfb_to_memory_fifo => bool,
    /// Bit 12: texture memory accesses go through the memory FIFO.
    12:12 texture_to_memory_fifo => bool,
    /// Bit 13: memory FIFO enable.
    13:13 memory_fifo_enable => bool,
    /// Bits 24:14: memory FIFO high water mark (its bits 15:5).
    24:14 memory_fifo_high_water_mark => u32,
    /// Bits 30:25: memory FIFO write burst high water mark (0-63).
    30:25 memory_fifo_write_burst_high_water_mark => u32,
}

register! {
    /// `fbiInit1` (0x214), spec 5.43: PCI bus and video controller configuration.
    #[doc(alias = "fbiInit1")]
    pub struct FbiInit1;
    /// Bit 0: PCI device function number (read only, power-on strap).
    0:0 pci_device_function => bool,
    /// Bit 1: PCI write wait states (`false` = 0, `true` = 1).
    1:1 pci_write_wait_states => bool,
    /// Bit 2: multi-SST configuration detected (read only).
    2:2 multi_sst1 => bool,
    /// Bit 3: enable linear frame buffer reads.
    3:3 enable_lfb_reads => bool,
    /// Bits 7:4: number of 64x16 video tiles in X, divided by 2.
    7:4 video_tiles_in_x => u32,
    /// Bit 8: video timing reset (`true` = reset).
    8:8 video_timing_reset => bool,
    /// Bit 9: software override of HSYNC/VSYNC.
    9:9 software_override => bool,
    /// Bit 10: software override HSYNC value.
    10:10 software_hsync => bool,
    /// Bit 11: software override VSYNC value.
    11:11 software_vsync => bool,
    /// Bit 12: software blanking (`true` = always blank the monitor).
    12:12 software_blank => bool,
    /// Bit 13: drive the video timing data outputs.
    13:13 drive_video_timing => bool,
    /// Bit 14: drive the video timing blank output.
    14:14 drive_video_blank => bool,
    /// Bit 15: drive the video timing hsync/vsync outputs.
    15:15 drive_video_sync => bool,
    /// Bit 16: drive the video timing dclk output.
    16:16 drive_video_dclk => bool,
    /// Bit 17: VCLK input select (`false` = `vid_clk_2x`, `true` = `vid_clk_slave`).
    17:17 vclk_input_select => bool,
    /// Bits 19:18: `vid_clk_2x` delay (0 = none, 1 = 4 ns, 2 = 6 ns, 3 = 8 ns).
    19:18 vid_clk_2x_delay => u32,
    /// Bits 21:20: VCLK source (0 = `vid_clk_slave`, 1 = `vid_clk_2x` / 2,
    /// 2 and 3 = `vid_clk_2x_sel`).
    21:20 vclk_source_select => u32,
    /// Bit 22: enable 24 bits-per-pixel video output.
    22:22 enable_24bpp_output => bool,
    /// Bit 23: enable scan-line interleaving.
    23:23 enable_scanline_interleave => bool,
    /// Bit 25: enable video edge detection filtering.
    25:25 enable_edge_filter => bool,
    /// Bit 26: invert `vid_clk_2x`.
    26:26 invert_vid_clk_2x => bool,
    /// Bits 28:27: `vid_clk_2x_sel` delay (0 = none, 1 = 4 ns, 2 = 6 ns, 3 = 8 ns).
    28:27 vid_clk_2x_sel_delay => u32,
    /// Bits 30:29: `vid_clk` delay (0 = none, 1 = 4 ns, 2 = 6 ns, 3 = 8 ns).
    30:29 vid_clk_delay => u32,
    /// Bit 31: disable the fast read-ahead-write to read-ahead-read turnaround.
    31:31 disable_fast_read_ahead => bool,
}

impl FbiInit1 {
    /// Width in pixels of one frame buffer row: `video_tiles_in_x` x 2 tiles of 64
    /// pixels. Source: spec 5.43 (tiles are 64x16; the field holds tiles / 2); MAME
    /// computes its row pitch the same way.
    #[inline]
    pub const fn row_pixels(self) -> u32 {
        self.video_tiles_in_x() * 2 * 64
    }
}

register! {
    /// `fbiInit2` (0x218), spec 5.44: DRAM, video buffer and refresh configuration.
    #[doc(alias = "fbiInit2")]
    pub struct FbiInit2;
    /// Bit 0: enable video dither subtraction.
    0:0 enable_video_dither_subtract => bool,
    /// Bit 1: DRAM banking configuration (`false` = 128Kx16, `true` = 256Kx16).
    1:1 dram_banking_configuration => bool,
    /// Bit 4: enable triple buffering.
    4:4 enable_triple_buffering => bool,
    /// Bit 5: enable fast RAS read cycles.
    5:5 enable_fast_ras_read => bool,
    /// Bit 6: enable the generated DRAM OE signal.
    6:6 enable_generated_dram_oe => bool,
    /// Bit 7: enable fast read-ahead-write turnaround.
    7:7 enable_fast_read_ahead_write => bool,
    /// Bit 8: enable pass-through dither mode (8 bpp applications).
    8:8 enable_pass_through_dither => bool,
    /// Bits 10:9: swap buffer algorithm.
    10:9 swap_buffer_algorithm => SwapBufferAlgorithm,
    /// Bits 19:11: video buffer offset, where the second colour buffer starts, in 4 KiB
    /// pages (spec: 150 for 640x480, 297 for 832x608).
    19:11 video_buffer_offset => u32,
    /// Bit 20: enable DRAM banking.
    20:20 enable_dram_banking => bool,
    /// Bit 21: enable the DRAM read-ahead FIFO.
    21:21 enable_dram_read_ahead_fifo => bool,
    /// Bit 22: DRAM refresh enable.
    22:22 refresh_enable => bool,
    /// Bits 31:23: refresh load value (the internal 14-bit counter's 5 LSBs are 0).
    31:23 refresh_load_value => u32,
}

impl FbiInit2 {
    /// Byte offset of the second colour buffer in frame buffer memory:
    /// `video_buffer_offset` x 4096. Source: MAME (`buffer_pages * 0x1000`); it fits the
    /// spec's example, 150 pages = one 640x480 16-bit buffer (614400 bytes).
    #[inline]
    pub const fn video_buffer_offset_bytes(self) -> u32 {
        self.video_buffer_offset() * 4096
    }
}

register! {
    /// `fbiInit3` (0x21c), spec 5.45: register remap, TREX interface, Y origin swap.
    #[doc(alias = "fbiInit3")]
    pub struct FbiInit3;
    /// Bit 0: triangle register address remapping (see [`crate::map::remap_offset`]).
    0:0 triangle_register_remap => bool,
    /// Bits 5:1: video FIFO threshold.
    5:1 video_fifo_threshold => u32,
    /// Bit 6: disable texture mapping (the TREX-to-FBI interface).
    6:6 disable_texture_mapping => bool,
    /// Bits 10:8: FBI memory type, read only (0 = EDO DRAM, 1 = synchronous DRAM).
    10:8 fbi_memory_type => u32,
    /// Bit 11: `VGA_PASS` reset value (read only).
    11:11 vga_pass_reset_value => bool,
    /// Bit 12: hardcode the PCI base address to 0x1f000000 (read only).
    12:12 hardcode_pci_base => bool,
    /// Bits 16:13: FBI-to-TREX bus clock delay (0-15).
    16:13 fbi_to_trex_clock_delay => u32,
    /// Bits 21:17: TREX-to-FBI bus FIFO full threshold (0-31).
    21:17 trex_to_fbi_fifo_full_threshold => u32,
    /// Bits 31:22 (`yorigin_swapval`, spec section 11): Y origin swap subtraction value;
    /// with a bottom-left origin, screen Y = this - Y.
    31:22 yorigin_swapval => u32,
}

register! {
    /// `fbiInit4` (0x200), spec 5.46: PCI read timing and memory FIFO rows.
    #[doc(alias = "fbiInit4")]
    pub struct FbiInit4;
    /// Bit 0: PCI read wait states (`false` = 1, `true` = 2).
    0:0 pci_read_wait_states => bool,
    /// Bit 1: enable read-ahead logic for LFB reads.
    1:1 enable_lfb_read_ahead => bool,
    /// Bits 7:2: memory FIFO low water mark for the PCI FIFO.
    7:2 memory_fifo_low_water_mark => u32,
    /// Bits 17:8: memory FIFO row start (base row address).
    17:8 memory_fifo_row_start => u32,
    /// Bits 27:18: memory FIFO row rollover.
    27:18 memory_fifo_row_rollover => u32,
}

// ---------------------------------------------------------------------------------------
// TREX registers (spec 5.50-5.55)
// ---------------------------------------------------------------------------------------

register! {
    /// `textureMode` (0x300), spec 5.50: texture filtering, clamping, format and the
    /// texture combine units.
    #[doc(alias = "textureMode")]
    pub struct TextureMode;
    /// Bit 0: perspective-correct S and T (`false` = linear, W forced to 1.0).
    0:0 tpersp_st => bool,
    /// Bit 1: minification filter (`false` = point sampled, `true` = bilinear).
    1:1 tminfilter => bool,
    /// Bit 2: magnification filter (`false` = point sampled, `true` = bilinear).
    2:2 tmagfilter => bool,
    /// Bit 3: force S = T = 0 when W is negative.
    3:3 tclampw => bool,
    /// Bit 4: enable LOD dithering.
    4:4 tloddither => bool,
    /// Bit 5: NCC table select (`false` = table 0, `true` = table 1).
    5:5 tnccselect => bool,
    /// Bit 6: clamp S (`false` = wrap).
    6:6 tclamps => bool,
    /// Bit 7: clamp T (`false` = wrap).
    7:7 tclampt => bool,
    /// Bits 11:8 (`tformat`): texture format.
    11:8 format => TextureFormat,
    /// Bit 12: colour: zero instead of `c_other`.
    12:12 tc_zero_other => bool,
    /// Bit 13: colour: subtract `c_local`.
    13:13 tc_sub_clocal => bool,
    /// Bits 16:14: colour blend factor.
    16:14 tc_mselect => TcMselect,
    /// Bit 17: colour reverse blend.
    17:17 tc_reverse_blend => bool,
    /// Bit 18: colour add `c_local`.
    18:18 tc_add_clocal => bool,
    /// Bit 19: colour add `a_local`.
    19:19 tc_add_alocal => bool,
    /// Bit 20: colour invert output.
    20:20 tc_invert_output => bool,
    /// Bit 21: alpha: zero instead of `c_other`.
    21:21 tca_zero_other => bool,
    /// Bit 22: alpha: subtract `c_local`.
    22:22 tca_sub_clocal => bool,
    /// Bits 25:23: alpha blend factor.
    25:23 tca_mselect => TcMselect,
    /// Bit 26: alpha reverse blend.
    26:26 tca_reverse_blend => bool,
    /// Bit 27: alpha add `c_local`.
    27:27 tca_add_clocal => bool,
    /// Bit 28: alpha add `a_local`.
    28:28 tca_add_alocal => bool,
    /// Bit 29: alpha invert output.
    29:29 tca_invert_output => bool,
    /// Bit 30: enable trilinear (blend factor inverted on odd LODs, see the diagram).
    30:30 trilinear => bool,
    /// Bit 31: sequential 8-bit download (must be 0 on revision 0 TMUs). Absent from the
    /// register table's bit range (30:0) but defined in 5.50.
    31:31 seq_8_downld => bool,
}

register! {
    /// `tLOD` (0x304), spec 5.51: LOD clamps and bias, texture layout, data swapping.
    #[doc(alias = "tLOD")]
    pub struct TLod;
    /// Bits 5:0: minimum LOD (4.2 unsigned).
    5:0 lodmin => u32,
    /// Bits 11:6: maximum LOD (4.2 unsigned).
    11:6 lodmax => u32,
    /// Bits 17:12: LOD bias (4.2 signed), sign-extended.
    17:12 lodbias => i32,
    /// Bit 18: `true` = odd LODs (with `lod_tsplit`).
    18:18 lod_odd => bool,
    /// Bit 19 (`lod_split` in rev 1.61's table): the texture holds only odd or even LODs.
    19:19 lod_tsplit => bool,
    /// Bit 20: S is the wider dimension (rectangular textures).
    20:20 lod_s_is_wider => bool,
    /// Bits 22:21: aspect ratio log2 (0 = square, 1 = 2x1, 2 = 4x1, 3 = 8x1).
    22:21 lod_aspect => u32,
    /// Bit 23: force the LOD fraction to 0.
    23:23 lod_zerofrac => bool,
    /// Bit 24: use the multiple `texBaseAddr` registers.
    24:24 tmultibaseaddr => bool,
    /// Bit 25: byte-swap incoming texture data (bytes 0<->3, 1<->2).
    25:25 tdata_swizzle => bool,
    /// Bit 26: short-swap incoming texture data (after the swizzle).
    26:26 tdata_swap => bool,
    /// Bit 27: raw direct texture memory writes. Listed in 5.51 though outside the
    /// register table's range (23:0); MAME treats it as Voodoo 2 only.
    27:27 tdirect_write => bool,
}

register! {
    /// `tDetail` (0x308), spec 5.52: detail texture blend factor,
    /// `detail_factor = max(detail_max, (detail_bias - LOD) << detail_scale)` as printed
    /// (0.8 unsigned).
    #[doc(alias = "tDetail")]
    pub struct TDetail;
    /// Bits 7:0: detail texture LOD clamp (8.0 unsigned).
    7:0 detail_max => u32,
    /// Bits 13:8: detail texture bias (6.0 signed), sign-extended.
    13:8 detail_bias => i32,
    /// Bits 16:14: detail texture scale (left shift).
    16:14 detail_scale => u32,
}

register! {
    /// `trexInit0` (0x31c): TREX memory configuration. The spec defers to the TREX spec
    /// (5.54); the fields come from 3dfx's Glide `sst1init.h` (`SST_TEX_MEM_*`).
    /// UNVERIFIED: widths where Glide gives only a shift and two values.
    #[doc(alias = "trexInit0")]
    pub struct TrexInit0;
    /// Bit 0: enable texture memory refresh.
    0:0 en_tex_mem_refresh => bool,
    /// Bits 9:1: texture memory refresh load value.
    9:1 tex_mem_refresh => u32,
    /// Bits 11:10: texture memory page size (0 = 8, 1 = 9, 2 = 10 column bits).
    11:10 tex_mem_page_size => u32,
    /// Bit 12: second RAS address bit (`false` = bit 17, `true` = bit 18).
    12:12 tex_mem_second_ras_bit => bool,
    /// Bit 14: enable the second RAS.
    14:14 en_tex_mem_second_ras => bool,
    /// Bits 17:15: texture memory type (0 = EDO, 1 = synchronous). UNVERIFIED width.
    17:15 tex_mem_type => u32,
    /// Bit 18: texture memory data size (`false` = 16-bit, `true` = 8-bit).
    18:18 tex_mem_data_size_8bit => bool,
    /// Bit 19: do an extra CAS.
    19:19 tex_mem_do_extra_cas => bool,
    /// Bit 20: two-memory support (`mem2`, spec section 12).
    20:20 tex_mem2 => bool,
}

register! {
    /// `trexInit1` (0x320): TREX interface configuration. The spec defers to the TREX
    /// spec (5.55); the fields come from 3dfx's Glide `sst1init.h` (`SST_TEX_*`).
    #[doc(alias = "trexInit1")]
    pub struct TrexInit1;
    /// Bit 0: scan-line interleave slave (`false` = master).
    0:0 tex_scanline_interleave_slave => bool,
    /// Bit 1: enable scan-line interleaving.
    1:1 en_tex_scanline_interleave => bool,
    /// Bits 6:2: FBI-to-TREX FIFO stall input level.
    6:2 tex_ft_fifo_sil => u32,
    /// Bits 10:7: TREX-to-TREX FIFO stall input level.
    10:7 tex_tt_fifo_sil => u32,
    /// Bits 15:12: TREX-to-FBI clock delay adjust.
    15:12 tex_tf_clk_del_adj => u32,
    /// Bit 16: `rg_ttcii` inhibit.
    16:16 tex_rg_ttcii_inh => bool,
    /// Bit 17: use the `rg_ttcii` inhibit.
    17:17 tex_use_rg_ttcii_inh => bool,
    /// Bit 18: send the TMU configuration to the FBI (drivers read it back to detect
    /// TMUs).
    18:18 tex_send_config => bool,
    /// Bit 19: reset the TREX FIFOs (`reset_FIFOs`, spec section 12).
    19:19 tex_reset_fifo => bool,
    /// Bit 20: reset the TREX graphics engine (`reset_graphics`, spec section 12).
    20:20 tex_reset_grx => bool,
    /// Bits 22:21: palette write timing delay (`palette_del`, spec section 12).
    22:21 tex_palette_del => u32,
    /// Bits 25:23: which configuration the TMU sends.
    25:23 tex_send_config_sel => u32,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fbz_mode_0x670() {
        // 0x670 = bits 4, 5, 6, 9, 10: depth buffer on, depth function 3, RGB + aux writes.
        let m = FbzMode(0x0000_0670);
        assert!(m.enable_depthbuffer());
        assert_eq!(m.depth_function(), DepthFunction::LessEqual);
        assert!(m.rgb_buffer_mask());
        assert!(m.aux_buffer_mask());
        assert!(!m.enable_clipping());
        assert!(!m.enable_dithering());
        assert!(!m.wbuffer_select());
        assert_eq!(m.draw_buffer(), ColorBuffer::Front);
        assert!(!m.y_origin());
        let text = format!("{m:?}");
        assert_eq!(
            text,
            "FbzMode { raw: 0x00000670, enable_clipping: false, enable_chromakey: false, \
             enable_stipple: false, wbuffer_select: false, enable_depthbuffer: true, \
             depth_function: LessEqual, enable_dithering: false, rgb_buffer_mask: true, \
             aux_buffer_mask: true, dither_2x2: false, enable_stipple_pattern: false, \
             enable_alpha_mask: false, draw_buffer: Front, enable_depth_bias: false, \
             y_origin: false, enable_alpha_planes: false, dither_subtract: false, \
             depth_source_compare: false }"
        );
    }

    #[test]
    fn fbz_mode_high_bits() {
        let m = FbzMode(0x001f_f90f);
        assert!(m.enable_clipping() && m.enable_chromakey() && m.enable_stipple());
        assert!(m.wbuffer_select());
        assert!(!m.enable_depthbuffer());
        assert_eq!(m.depth_function(), DepthFunction::Never);
        assert!(m.enable_dithering());
        assert!(!m.rgb_buffer_mask() && !m.aux_buffer_mask());
        assert!(m.dither_2x2() && m.enable_stipple_pattern() && m.enable_alpha_mask());
        assert_eq!(m.draw_buffer(), ColorBuffer::Reserved3);
        assert!(m.enable_depth_bias() && m.y_origin() && m.enable_alpha_planes());
        assert!(m.dither_subtract() && m.depth_source_compare());
    }

    #[test]
    fn fbz_color_path_fields() {
        // Texture times iterated colour with texture enabled:
        // rgbselect=1, aselect=1, cc_mselect=1 (c_local), cca_mselect=1, reverse blends,
        // plus param_adjust and texture_enable.
        let v = 1 | 1 << 2 | 1 << 10 | 1 << 13 | 1 << 19 | 1 << 22 | 1 << 26 | 1 << 27;
        let p = FbzColorPath(v);
        assert_eq!(p.cc_rgbselect(), RgbSelect::Texture);
        assert_eq!(p.cc_aselect(), AlphaSelect::Texture);
        assert!(!p.cc_localselect());
        assert_eq!(p.cca_localselect(), AlphaLocalSelect::IteratedAlpha);
        assert_eq!(p.cc_mselect(), CcMselect::CLocal);
        assert!(p.cc_reverse_blend() && !p.cc_add_clocal() && !p.cc_invert_output());
        assert_eq!(p.cca_mselect(), CcMselect::CLocal);
        assert!(p.cca_reverse_blend() && !p.cca_add_alocal());
        assert!(p.param_adjust() && p.texture_enable());

        let p = FbzColorPath(0x03ff_fff3);
        assert_eq!(p.cc_rgbselect(), RgbSelect::Reserved3);
        assert_eq!(p.cc_aselect(), AlphaSelect::IteratedAlpha);
        assert!(p.cc_localselect());
        assert_eq!(p.cca_localselect(), AlphaLocalSelect::Reserved3);
        assert!(p.cc_localselect_override() && p.cc_zero_other() && p.cc_sub_clocal());
        assert_eq!(p.cc_mselect(), CcMselect::Reserved7);
        assert!(p.cc_add_clocal() && p.cc_add_alocal() && p.cc_invert_output());
        assert!(p.cca_zero_other() && p.cca_sub_clocal() && p.cca_add_clocal());
        assert!(p.cca_invert_output());
        assert_eq!(p.cca_mselect(), CcMselect::Reserved7);
        assert!(!p.param_adjust() && !p.texture_enable());
    }

    #[test]
    fn alpha_mode_fields() {
        // Alpha test GREATER 0x80, blend src alpha / 1 - src alpha, alpha channel one/zero.
        let a = AlphaMode(0x8004_5159);
        assert!(a.alpha_test_enable());
        assert_eq!(a.alpha_function(), AlphaFunction::Greater);
        assert!(a.alpha_blend_enable());
        assert!(!a.antialias_enable());
        assert_eq!(a.src_rgb_blend(), BlendFactor::SrcAlpha);
        assert_eq!(a.dst_rgb_blend(), BlendFactor::OneMinusSrcAlpha);
        assert_eq!(a.src_alpha_blend(), BlendFactor::One);
        assert_eq!(a.dst_alpha_blend(), BlendFactor::Zero);
        assert_eq!(a.alpha_ref(), 0x80);

        let a = AlphaMode(0x00f9_f02e);
        assert!(!a.alpha_test_enable());
        assert_eq!(a.alpha_function(), AlphaFunction::Always);
        assert!(a.antialias_enable());
        assert_eq!(a.src_rgb_blend(), BlendFactor::Zero);
        assert_eq!(a.dst_rgb_blend(), BlendFactor::SaturateOrColorBeforeFog);
        assert_eq!(a.src_alpha_blend(), BlendFactor::Reserved9);
        assert_eq!(a.dst_alpha_blend(), BlendFactor::SaturateOrColorBeforeFog);
        assert_eq!(a.alpha_ref(), 0);
    }

    #[test]
    fn fog_mode_fields() {
        let f = FogMode(0x11);
        assert!(f.enable_fog() && !f.fog_add() && !f.fog_mult() && !f.fog_constant());
        assert_eq!(f.fog_za(), FogZa::IteratedZ);
        let f = FogMode(0x2e);
        assert!(!f.enable_fog() && f.fog_add() && f.fog_mult() && f.fog_constant());
        assert_eq!(f.fog_za(), FogZa::IteratedAlpha);
        assert_eq!(FogMode(0x18).fog_za(), FogZa::IteratedZAndAlpha);
        assert_eq!(FogMode(0x01).fog_za(), FogZa::FogTable);
    }

    #[test]
    fn lfb_mode_fields() {
        // Format 12, back buffer writes, aux reads, pipeline on, BGRA, every swap bit.
        let l = LfbMode(0x0001_ffdc);
        assert_eq!(l.write_format(), LfbWriteFormat::DepthRgb565);
        assert_eq!(l.write_buffer_select(), ColorBuffer::Back);
        assert_eq!(l.read_buffer_select(), LfbReadBuffer::Reserved3);
        assert!(l.enable_pixel_pipeline());
        assert_eq!(l.rgba_lanes(), RgbaLanes::Bgra);
        assert!(l.word_swap_writes() && l.byte_swizzle_writes() && l.y_origin());
        assert!(l.write_w_select() && l.word_swap_reads() && l.byte_swizzle_reads());

        let l = LfbMode(0x0000_0285);
        assert_eq!(l.write_format(), LfbWriteFormat::Argb8888);
        assert_eq!(l.write_buffer_select(), ColorBuffer::Front);
        assert_eq!(l.read_buffer_select(), LfbReadBuffer::Aux);
        assert!(!l.enable_pixel_pipeline());
        assert_eq!(l.rgba_lanes(), RgbaLanes::Abgr);
        assert!(!l.word_swap_writes() && !l.y_origin());
    }

    #[test]
    fn texture_mode_fields() {
        // Glide "decal" on RGB565 with bilinear and perspective: tc/tca replace.
        let t = TextureMode(0x0824_1a0f);
        assert!(t.tpersp_st() && t.tminfilter() && t.tmagfilter() && t.tclampw());
        assert!(!t.tloddither() && !t.tnccselect() && !t.tclamps() && !t.tclampt());
        assert_eq!(t.format(), TextureFormat::Rgb565);
        assert!(t.tc_zero_other() && !t.tc_sub_clocal());
        assert_eq!(t.tc_mselect(), TcMselect::Zero);
        assert!(t.tc_add_clocal() && !t.tc_add_alocal());
        assert!(t.tca_zero_other());
        assert_eq!(t.tca_mselect(), TcMselect::Zero);
        assert!(t.tca_add_clocal() && !t.trilinear() && !t.seq_8_downld());

        let t = TextureMode(0xc2c3_01f0);
        assert!(!t.tpersp_st() && t.tloddither() && t.tnccselect() && t.tclamps());
        assert!(t.tclampt());
        assert_eq!(t.format(), TextureFormat::Yiq422);
        assert_eq!(t.tc_mselect(), TcMselect::DetailFactor);
        assert!(t.tc_reverse_blend() && !t.tc_add_clocal() && !t.tc_invert_output());
        assert!(t.tca_sub_clocal());
        assert_eq!(t.tca_mselect(), TcMselect::LodFrac);
        assert!(t.trilinear() && t.seq_8_downld());
    }

    #[test]
    fn tlod_fields() {
        // lodmin 1.0 (4), lodmax 8.0 (32), bias -0.25 (0x3f), odd, split, aspect 2.
        let l = TLod(0x0047_f804 | 1 << 18 | 1 << 19);
        assert_eq!(l.lodmin(), 4);
        assert_eq!(l.lodmax(), 32);
        assert_eq!(l.lodbias(), -1);
        assert!(l.lod_odd() && l.lod_tsplit());
        assert!(!l.lod_s_is_wider());
        assert_eq!(l.lod_aspect(), 2);
        assert!(!l.lod_zerofrac());
        let l = TLod(0x0f91_f000);
        assert_eq!(l.lodbias(), 31);
        assert!(l.lod_s_is_wider() && l.lod_zerofrac() && l.tmultibaseaddr());
        assert!(l.tdata_swizzle() && l.tdata_swap() && l.tdirect_write());
        assert_eq!(l.lod_aspect(), 0);
        assert_eq!(TLod(0x20 << 12).lodbias(), -32);
    }

    #[test]
    fn tdetail_fields() {
        let d = TDetail(0x0001_e0ff);
        assert_eq!(d.detail_max(), 0xff);
        assert_eq!(d.detail_bias(), -32);
        assert_eq!(d.detail_scale(), 7);
        let d = TDetail(0x0000_4a10);
        assert_eq!(d.detail_max(), 0x10);
        assert_eq!(d.detail_bias(), 10);
        assert_eq!(d.detail_scale(), 1);
    }

    #[test]
    fn clip_and_constant_registers() {
        let c = ClipLeftRight(0x0010_0280);
        assert_eq!((c.clip_left(), c.clip_right()), (16, 640));
        let c = ClipLowYHighY(0xffff_ffff);
        assert_eq!((c.clip_lowy(), c.clip_highy()), (0x3ff, 0x3ff));
        let z = ZaColor(0x80ab_1234);
        assert_eq!((z.constant_depth(), z.constant_alpha()), (0x1234, 0x80));
        let k = ChromaKey(0xff10_2030);
        assert_eq!((k.red(), k.green(), k.blue()), (0x10, 0x20, 0x30));
    }

    #[test]
    fn stipple_pattern_bits() {
        // Spec 5.19: row y selects byte y & 3; x = 0 takes bit 7 of that byte.
        let s = Stipple(0x0180_0001);
        assert!(s.pattern_bit(7, 0));
        assert!(!s.pattern_bit(0, 0));
        assert!(s.pattern_bit(0, 2) && s.pattern_bit(8, 2) && s.pattern_bit(7, 3));
        assert!(!s.pattern_bit(1, 2) && !s.pattern_bit(7, 1));
        assert!(s.pattern_bit(15, 4));
        assert_eq!(s.stipple_value(), 0x0180_0001);
    }

    #[test]
    fn status_fields() {
        // Idle, empty FIFOs, retrace inactive: the value drivers poll for.
        let s = Status(0x0fff_f07f);
        assert_eq!(s.pci_fifo_freespace(), 0x3f);
        assert!(s.vertical_retrace());
        assert!(!s.fbi_busy() && !s.trex_busy() && !s.sst1_busy());
        assert_eq!(s.displayed_buffer(), 0);
        assert_eq!(s.memory_fifo_freespace(), 0xffff);
        assert_eq!(s.swap_buffers_pending(), 0);
        let s = Status(0xf000_0f80);
        assert_eq!(s.pci_fifo_freespace(), 0);
        assert!(s.fbi_busy() && s.trex_busy() && s.sst1_busy() && s.pci_interrupt());
        assert_eq!(s.displayed_buffer(), 3);
        assert_eq!(s.swap_buffers_pending(), 7);
    }

    #[test]
    fn video_timing_registers() {
        // Glide's 640x480 @ 60 Hz timing (sst1vid / sst1init): hSync 0x0310_002e etc.
        let h = HSync(0x0310_002e);
        assert_eq!((h.h_sync_on(), h.h_sync_off()), (0x2e, 0x310));
        assert_eq!((h.active_clocks(), h.inactive_clocks()), (47, 785));
        let v = VSync(0x020c_0003);
        assert_eq!((v.v_sync_on(), v.v_sync_off()), (3, 0x20c));
        let b = BackPorch(0x0022_0060);
        assert_eq!((b.h_back_porch(), b.v_back_porch()), (0x60, 0x22));
        assert_eq!(b.h_back_porch_clocks(), 0x62);
        let d = VideoDimensions(0x01e0_0280);
        assert_eq!((d.x_width(), d.y_height()), (640, 480));
    }

    #[test]
    fn fbi_init_registers() {
        // Glide's SST_FBIINIT0_DEFAULT (0x410 | LFB and texture memory FIFO bits).
        let i0 = FbiInit0(0x0000_1c10 | 1 << 3);
        assert!(i0.stall_pci_enable() && i0.swizzle_register_writes());
        assert_eq!(i0.pci_fifo_low_water_mark(), 0x10);
        assert!(i0.lfb_to_memory_fifo() && i0.texture_to_memory_fifo());
        assert!(!i0.memory_fifo_enable() && !i0.graphics_reset() && !i0.fifo_reset());
        let i0 = FbiInit0(0x7fff_c000);
        assert_eq!(i0.memory_fifo_high_water_mark(), 0x7ff);
        assert_eq!(i0.memory_fifo_write_burst_high_water_mark(), 0x3f);

        // Glide's SST_FBIINIT1_DEFAULT 0x00201102 with 5 tiles (640 pixels).
        let i1 = FbiInit1(0x0020_1102 | 5 << 4);
        assert!(i1.pci_write_wait_states() && i1.video_timing_reset() && i1.software_blank());
        assert_eq!(i1.video_tiles_in_x(), 5);
        assert_eq!(i1.row_pixels(), 640);
        assert_eq!(i1.vclk_source_select(), 2);
        assert!(!i1.enable_scanline_interleave() && !i1.enable_lfb_reads());
        let i1 = FbiInit1(0xfe00_0000);
        assert_eq!((i1.vid_clk_2x_sel_delay(), i1.vid_clk_delay()), (3, 3));
        assert!(i1.disable_fast_read_ahead() && i1.invert_vid_clk_2x());
        assert!(i1.enable_edge_filter());

        let i2 = FbiInit2(0x8000_0040 | 150 << 11 | 1 << 9 | 1 << 22);
        assert_eq!(i2.video_buffer_offset(), 150);
        assert_eq!(i2.video_buffer_offset_bytes(), 640 * 480 * 2);
        assert_eq!(i2.refresh_load_value(), 0x100);
        assert!(i2.enable_generated_dram_oe() && i2.refresh_enable());
        assert_eq!(i2.swap_buffer_algorithm(), SwapBufferAlgorithm::DacData0);

        let i3 = FbiInit3(0x001e_4041 | 479 << 22);
        assert!(i3.triangle_register_remap() && i3.disable_texture_mapping());
        assert_eq!(i3.fbi_to_trex_clock_delay(), 2);
        assert_eq!(i3.trex_to_fbi_fifo_full_threshold(), 0xf);
        assert_eq!(i3.yorigin_swapval(), 479);

        let i4 = FbiInit4(0xffff_fff1);
        assert!(i4.pci_read_wait_states() && !i4.enable_lfb_read_ahead());
        assert_eq!(i4.memory_fifo_low_water_mark(), 0x3c);
        assert_eq!(i4.memory_fifo_row_start(), 0x3ff);
        assert_eq!(i4.memory_fifo_row_rollover(), 0x3ff);
    }

    #[test]
    fn trex_init_registers() {
        // Glide's SST_TREXINIT0_DEFAULT: refresh on, 0x20, 9-bit pages, RAS bit 18, 2nd RAS.
        let t0 = TrexInit0(0x0000_5441);
        assert!(t0.en_tex_mem_refresh());
        assert_eq!(t0.tex_mem_refresh(), 0x20);
        assert_eq!(t0.tex_mem_page_size(), 1);
        assert!(t0.tex_mem_second_ras_bit() && t0.en_tex_mem_second_ras());
        assert!(!t0.tex_mem2());
        // Glide's SST_TREXINIT1_DEFAULT: FIFO levels 8 and 8, clock delay 0xf.
        let t1 = TrexInit1(0x0000_f420 | 1 << 18);
        assert_eq!(t1.tex_ft_fifo_sil(), 8);
        assert_eq!(t1.tex_tt_fifo_sil(), 8);
        assert_eq!(t1.tex_tf_clk_del_adj(), 0xf);
        assert!(t1.tex_send_config() && !t1.tex_reset_fifo());
    }

    #[test]
    fn enums_decode_every_value() {
        for v in 0..16u32 {
            assert_eq!(BlendFactor::from_bits(v) as u32, v);
            assert_eq!(TextureFormat::from_bits(v) as u32, v);
            assert_eq!(LfbWriteFormat::from_bits(v) as u32, v);
            assert_eq!(CompareFunction::from_bits(v) as u32, v & 7);
            assert_eq!(RgbSelect::from_bits(v) as u32, v & 3);
        }
        assert_eq!(
            CompareFunction::from_bits(0xffff_fffb),
            CompareFunction::LessEqual
        );
    }

    #[test]
    fn pretty_debug_is_one_field_per_line() {
        let text = format!("{:#?}", FogMode(0x21));
        assert_eq!(
            text,
            "FogMode {\n    raw: 0x00000021,\n    enable_fog: true,\n    fog_add: false,\n    \
             fog_mult: false,\n    fog_za: FogTable,\n    fog_constant: true,\n}"
        );
    }
}

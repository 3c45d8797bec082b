//! The register path: every chip access the front-end makes goes through [`Hw`].
//!
//! Glide never draws pixels itself: it only writes the SST-1 aperture (spec section 4)
//! and PCI configuration space (spec section 6) through a [`RegisterBus`]. The trace
//! recorder of `sst1-trace` wraps any bus, so the same writes can drive the emulated
//! board and be recorded.

use sst1_regs::RegisterBus;

/// Bits of the SST-1 registers that the front-end composes (spec section 5).
///
/// Names follow the datasheet field names; values are bit masks in the register.
pub(crate) mod bits {
    // fbzColorPath (spec 5.x `fbzColorPath`)
    pub const CC_LOCALSELECT_SHIFT: u32 = 4;
    pub const CC_ALOCALSELECT_SHIFT: u32 = 5;
    pub const CC_ALOCALSELECT: u32 = 3 << 5;
    pub const ALOCAL_Z: u32 = 2 << 5;
    pub const LOCALSELECT_OVERRIDE_WITH_ATEX: u32 = 1 << 7;
    pub const CC_ZERO_OTHER: u32 = 1 << 8;
    pub const CC_SUB_CLOCAL: u32 = 1 << 9;
    pub const CC_MSELECT_SHIFT: u32 = 10;
    pub const CC_REVERSE_BLEND: u32 = 1 << 13;
    pub const CC_ADD_CLOCAL: u32 = 1 << 14;
    pub const CC_ADD_ALOCAL: u32 = 1 << 15;
    pub const CC_INVERT_OUTPUT: u32 = 1 << 16;
    pub const CCA_ZERO_OTHER: u32 = 1 << 17;
    pub const CCA_SUB_CLOCAL: u32 = 1 << 18;
    pub const CCA_MSELECT_SHIFT: u32 = 19;
    pub const CCA_REVERSE_BLEND: u32 = 1 << 22;
    pub const CCA_ADD_ALOCAL: u32 = 1 << 24;
    pub const CCA_INVERT_OUTPUT: u32 = 1 << 25;
    pub const PARMADJUST: u32 = 1 << 26;
    pub const ENTEXTUREMAP: u32 = 1 << 27;
    /// All colour-combine fields (rgbselect .. cc_invert_output) plus the texture enable.
    pub const CC_FIELDS: u32 = 0x3 | (1 << 4) | (0x1ff << 8) | ENTEXTUREMAP;
    /// All alpha-combine fields (aselect, alocalselect, cca_*) plus the texture enable.
    pub const CCA_FIELDS: u32 = (0x3 << 2) | CC_ALOCALSELECT | (0x1ff << 17) | ENTEXTUREMAP;

    // fbzMode
    pub const ENRECTCLIP: u32 = 1 << 0;
    pub const ENCHROMAKEY: u32 = 1 << 1;
    pub const WBUFFER: u32 = 1 << 3;
    pub const ENDEPTHBUFFER: u32 = 1 << 4;
    pub const ZFUNC_SHIFT: u32 = 5;
    pub const ZFUNC: u32 = 7 << 5;
    pub const ENDITHER: u32 = 1 << 8;
    pub const RGBWRMASK: u32 = 1 << 9;
    pub const ZAWRMASK: u32 = 1 << 10;
    pub const DITHER2X2: u32 = 1 << 11;
    pub const DRAWBUFFER: u32 = 3 << 14;
    pub const DRAWBUFFER_BACK: u32 = 1 << 14;
    pub const ENZBIAS: u32 = 1 << 16;
    pub const YORIGIN: u32 = 1 << 17;
    pub const ENALPHABUFFER: u32 = 1 << 18;
    pub const ENDITHERSUBTRACT: u32 = 1 << 19;
    pub const ZCOMPARE_TO_ZACOLOR: u32 = 1 << 20;

    // alphaMode
    pub const ENALPHAFUNC: u32 = 1 << 0;
    pub const ALPHAFUNC_SHIFT: u32 = 1;
    pub const ALPHAFUNC: u32 = 7 << 1;
    pub const ENALPHABLEND: u32 = 1 << 4;
    pub const RGBSRCFACT_SHIFT: u32 = 8;
    pub const RGBDSTFACT_SHIFT: u32 = 12;
    pub const ASRCFACT_SHIFT: u32 = 16;
    pub const ADSTFACT_SHIFT: u32 = 20;
    pub const BLEND_FACTORS: u32 = 0xffff << 8;
    pub const ALPHAREF_SHIFT: u32 = 24;
    pub const ALPHAREF: u32 = 0xff << 24;

    // fogMode
    pub const ENFOGGING: u32 = 1 << 0;
    pub const FOGADD: u32 = 1 << 1;
    pub const FOGMULT: u32 = 1 << 2;
    pub const FOG_ALPHA: u32 = 1 << 3;
    pub const FOG_Z: u32 = 1 << 4;
    pub const FOG_CONSTANT: u32 = 1 << 5;

    // textureMode
    pub const TPERSP_ST: u32 = 1 << 0;
    pub const TMINFILTER: u32 = 1 << 1;
    pub const TMAGFILTER: u32 = 1 << 2;
    pub const TCLAMPW: u32 = 1 << 3;
    pub const TLODDITHER: u32 = 1 << 4;
    pub const TNCCSELECT: u32 = 1 << 5;
    pub const TCLAMPS: u32 = 1 << 6;
    pub const TCLAMPT: u32 = 1 << 7;
    pub const TFORMAT_SHIFT: u32 = 8;
    pub const TFORMAT: u32 = 0xf << 8;
    pub const TC_ZERO_OTHER: u32 = 1 << 12;
    pub const TC_SUB_CLOCAL: u32 = 1 << 13;
    pub const TC_MSELECT_SHIFT: u32 = 14;
    pub const TC_MSELECT: u32 = 7 << 14;
    pub const TC_REVERSE_BLEND: u32 = 1 << 17;
    pub const TC_ADD_CLOCAL: u32 = 1 << 18;
    pub const TC_ADD_ALOCAL: u32 = 1 << 19;
    pub const TC_INVERT_OUTPUT: u32 = 1 << 20;
    pub const TCA_ZERO_OTHER: u32 = 1 << 21;
    pub const TCA_SUB_CLOCAL: u32 = 1 << 22;
    pub const TCA_MSELECT_SHIFT: u32 = 23;
    pub const TCA_REVERSE_BLEND: u32 = 1 << 26;
    pub const TCA_ADD_CLOCAL: u32 = 1 << 27;
    pub const TCA_ADD_ALOCAL: u32 = 1 << 28;
    pub const TCA_INVERT_OUTPUT: u32 = 1 << 29;
    /// Both texture combine fields (bits 12..29).
    pub const TCOMBINE_ALL: u32 = 0x3ffff << 12;
    pub const TRILINEAR: u32 = 1 << 30;
    pub const SEQ_8_DOWNLD: u32 = 1 << 31;

    // tLOD
    pub const LODMIN: u32 = 0x3f;
    pub const LODMAX: u32 = 0x3f << 6;
    pub const LODBIAS_SHIFT: u32 = 12;
    pub const LODBIAS: u32 = 0x3f << 12;
    pub const LOD_ODD: u32 = 1 << 18;
    pub const LOD_TSPLIT: u32 = 1 << 19;
    pub const LOD_S_IS_WIDER: u32 = 1 << 20;
    pub const LOD_ASPECT_SHIFT: u32 = 21;
    pub const LOD_ASPECT: u32 = 3 << 21;
    pub const TMULTIBASEADDR: u32 = 1 << 24;

    // lfbMode
    pub const LFB_ENPIXPIPE: u32 = 1 << 8;
    pub const LFB_WRITE_SWAP16: u32 = 1 << 11;
    pub const LFB_WRITE_BYTESWAP: u32 = 1 << 12;
    pub const LFB_YORIGIN: u32 = 1 << 13;
}

/// Byte offset of the first texture-memory download address (spec section 8).
pub(crate) const TEX_BASE: u32 = 0x80_0000;
/// Byte offset of the linear frame buffer (spec section 4).
pub(crate) const LFB_BASE: u32 = 0x40_0000;
/// The address 3dfx's SST-1 Glide writes a zero to around writes aimed at TMU registers
/// ("packer bug" workaround): texture space, TMU field 3, bit 17 set.
/// Source: the Glide 3 SST-1 traces (`w 0xe20000 0`), derived in disst.c as
/// texture base + (3 << 21) + (1 << 17).
pub(crate) const PACKER_FIX: u32 = TEX_BASE + (3 << 21) + (1 << 17);

/// Chip-select offset of TMU `n` in the register space (spec 4: bit 11 + n).
pub(crate) const fn tmu_chip(n: usize) -> u32 {
    0x800 << n
}

/// The bus plus the helpers Glide uses to talk to the chip.
pub(crate) struct Hw {
    bus: Box<dyn RegisterBus>,
}

impl Hw {
    pub(crate) fn new(bus: Box<dyn RegisterBus>) -> Self {
        Self { bus }
    }

    /// One 32-bit register or memory write.
    pub(crate) fn w(&mut self, addr: u32, value: u32) {
        self.bus.write32(addr, value);
    }

    /// A float written to a floating-point register (its IEEE-754 bits).
    pub(crate) fn wf(&mut self, addr: u32, value: f32) {
        self.bus.write32(addr, value.to_bits());
    }

    /// A 32-bit read.
    pub(crate) fn r(&mut self, addr: u32) -> u32 {
        self.bus.read32(addr)
    }

    /// A PCI configuration write.
    pub(crate) fn pci(&mut self, offset: u32, value: u32) {
        self.bus.pci_write(offset, value);
    }

    /// The packer workaround write.
    pub(crate) fn packer(&mut self) {
        self.w(PACKER_FIX, 0);
    }

    /// A lone 16-bit frame-buffer write at byte address `addr`. The bus carries 32-bit
    /// writes only, so the neighbouring pixel is read back and written unchanged (the
    /// glide-sdk traces record lone 16-bit writes the same way).
    pub(crate) fn w16(&mut self, addr: u32, value: u16) {
        let word = addr & !3;
        let old = self.r(word);
        let merged = if addr & 2 != 0 {
            (old & 0xffff) | (u32::from(value) << 16)
        } else {
            (old & 0xffff_0000) | u32::from(value)
        };
        self.w(word, merged);
    }

    /// Take the bus back (used when the context is torn down).
    pub(crate) fn into_bus(self) -> Box<dyn RegisterBus> {
        self.bus
    }
}

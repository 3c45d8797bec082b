//! Texelfx: one SST-1 texture mapping unit (TREX / TMU).
//!
//! Spec sections 5.50-5.56 (`textureMode`, `tLOD`, `tDetail`, `texBaseAddr*`, `trexInit*`,
//! `nccTable*`), 8 (texture memory layout and downloads) and 9.4 (subpixel correction).
//!
//! For each pixel a TMU iterates S/W, T/W and 1/W, divides for perspective, computes the
//! LOD, fetches and filters texels from its own memory, then merges the result with the
//! upstream TMU's output in its texture combine unit (module [`combine`]); TMU 0's output goes
//! to the FBI. Stages, in hardware order:
//!
//! 1. iterators ([`Tmu::texel`]): `start + dx * d/dx + dy * d/dy`, S/T 14.18 and W 2.30,
//!    kept as 64-bit values with 32 fraction bits as the references do;
//! 2. coordinates, LOD, fetch and filter (modules `sample`, `lod`);
//! 3. texel decode (module `format`, NCC in [`sst1_ncc`]);
//! 4. texture combine (module [`combine`]).
//!
//! Texture memory is laid out as module `layout` describes and written by module
//! `download`. Texels are decoded one LOD at a time on first use into a cache (module
//! `cache`) that any write changing them invalidates, so every write to memory, the NCC
//! tables, the palette or a texture register takes effect on the next triangle.
//!
//! Where the reference emulators disagree, [`TexelProfile`] selects the behaviour.

mod approx;
mod box86;
mod cache;
pub mod combine;
mod download;
mod format;
mod layout;
mod lod;
mod sample;
mod span;
mod state;
mod stw;

pub use approx::Approx;
use cache::TexelCache;
pub use combine::DetailRule;
use combine::{detail_factor, Factors, TextureCombine};
use layout::Layout;
pub use span::{
    Avx2Copy, Avx512Copy, BaselineCopy, ColourLanes, KernelCopy, LaneOutput, LanePlace,
    LaneScratch, Lanes, LANES, ZERO_COLOUR,
};
use sst1_ncc::{NccRegs, NccWrite, Rgb8};
use sst1_regs::{addr, Rgba, TextureMode};
pub use state::{StateMismatch, TmuState};
pub use stw::{StwParams, StwPending, StwWrite};

/// Signed fixed point with 14 integer and 18 fraction bits (`startS`, `dSdX`, ...).
pub type Fx14_18 = i32;
/// Signed fixed point with 2 integer and 30 fraction bits (`startW`, `dWdX`, ...).
pub type Fx2_30 = i32;
/// Signed fixed point with 32 fraction bits: the internal S, T and W iterator format.
type Fx32 = i64;

/// How the LOD is computed from the gradients and W.
///
/// All three references take `log2` of the larger of `dS/dx² + dT/dx²` and
/// `dS/dy² + dT/dy²`, halve it, and add `log2(1/W)` per pixel, with different precision.
/// MAME uses doubles and a 7-bit mantissa table. DOSBox Staging reduces the gradients to
/// 18 fraction bits and interpolates a 512-entry reciprocal/log table (`fast_reciplog`,
/// rounded to 8 fraction bits). 86Box reduces the gradients to 18 fraction bits, scales the
/// log by a further 1/2 and uses `log2(2^16 / W) - 19` per pixel; it picks other LODs at
/// steep angles.
///
/// No two agree bit for bit, so there is no majority. The default is DOSBox's: measured on
/// the conformance and glide-sdk traces it leaves 265 fewer majority failures than MAME's
/// (`tmu2_combine` -203, `tmu2_trilinear` -95, `stress_random` -11, `tmu2_detail` +44;
/// no other dump changes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum LodCalc {
    /// MAME.
    Mame,
    /// DOSBox Staging.
    #[default]
    Dosbox,
    /// 86Box.
    Box86,
}

/// The LOD dither of `textureMode` bit 4.
///
/// MAME and DOSBox (the default) add the 4x4 ordered-dither matrix value / 16 (0 to 15/16,
/// average 15/32). The spec says the average is 3/8. 86Box ignores the bit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum LodDither {
    /// MAME and DOSBox Staging: `matrix[y & 3][x & 3] << 4` added to the 8.8 LOD.
    #[default]
    Matrix4x4,
    /// 86Box: no LOD dither.
    Off,
}

/// Precision of the bilinear weights.
///
/// All three references use 4 bits per fraction on the SST-1 (MAME, DOSBox: mask 0xf0;
/// 86Box: 16ths); the Voodoo 2 uses 8.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum BilinearPrecision {
    /// 4-bit S and T fractions (SST-1).
    #[default]
    Bits4,
    /// 8-bit fractions (Voodoo 2), in MAME's SSE2 arithmetic.
    Bits8,
}

/// What RGB an A8 (format 2) texel gives.
///
/// The spec table and MAME, DOSBox Staging and 86Box as read all replicate the alpha into
/// R, G and B (AI44 likewise puts its intensity in RGB in all of them). The conformance
/// README reports a disagreement on A8/AI44; the alternative here is an opaque-white RGB.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum A8Expansion {
    /// `ARGB = (a, a, a, a)`.
    #[default]
    AlphaInRgb,
    /// UNVERIFIED alternative: `ARGB = (a, ff, ff, ff)`.
    WhiteRgb,
}

/// The blue of an RGB332 texel (formats 0 and 8).
///
/// The spec's bit replication gives blue `b * 0x55` from its 2 bits (MAME, 86Box).
/// DOSBox Staging's table (`EXTRACT_332_TO_888`) ORs bits 5:4 of the texel, green's low
/// bits, into blue's top two bits in place of blue's own bits 3:2: the third term of its
/// blue is masked with `0xc0` where `0x0c` replicates. Whole cells of
/// `tex_8bit_formats` show it in DOSBox Staging's golden.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Rgb332Blue {
    /// Spec, MAME, 86Box: `b b b b` (bit replication).
    #[default]
    Replicated,
    /// DOSBox Staging: `(b | g[1:0]) 0 0 b`, with `g[1:0]` the texel's bits 5:4.
    DosboxTable,
}

/// How `textureMode`'s two filter bits choose between point sampling and bilinear.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum FilterSelect {
    /// Spec 5.50: `tmagfilter` when the LOD is clamped at `lodmin` (magnification),
    /// `tminfilter` otherwise (MAME, DOSBox Staging).
    #[default]
    ByLod,
    /// 86Box (`voodoo_get_texture`): bilinear whenever either bit is set, at any LOD.
    EitherBit,
}

/// How the TMUs of the chain combine their texels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum ChainModel {
    /// Every TMU runs its texture combine unit on its texel and the upstream output
    /// (spec 3.2, 5.50; MAME, DOSBox Staging).
    #[default]
    Full,
    /// 86Box's shortcuts (`voodoo_half_triangle`, `voodoo_tmu_fetch_and_blend`): with one
    /// TMU the texel passes with no combine at all; with two, TMU 0's texel alone when its
    /// mode is the local decal (`textureMode & 0x00643000 == 0x00241000`), TMU 1's texel
    /// alone when TMU 0's combine bits are all zero, else TMU 1 through
    /// [`combine::TextureCombine::combine_box86_upstream`] and TMU 0's full combine. A
    /// third TMU is not read.
    Box86,
}

/// Where a write to `nccTable0` Q2 lands.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum NccQ2Write {
    /// Table 0's Q2 (spec 5.56; MAME, DOSBox Staging).
    #[default]
    Q2,
    /// Table 0's I2, leaving Q2 as it was (86Box `voodoo_reg_writel`: the
    /// `SST_nccTable0_Q2` case stores into `i[2]`).
    IntoI2,
}

/// What the TMU's decoded textures are found by.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum TextureCacheKey {
    /// No behaviour: texels always reflect the memory, format and tables in force (the
    /// decoded-texel cache is invalidated exactly; spec, MAME, DOSBox Staging).
    #[default]
    Exact,
    /// 86Box: decoded textures kept by base address, `tLOD` and palette checksum only, so
    /// a new format or NCC table over the same memory reads the old decode until a
    /// download writes into it (see module `box86`).
    Box86,
}

/// When writes to the NCC tables take effect.
///
/// MAME and 86Box (the default) use a table from the next triangle on. DOSBox Staging
/// re-expands the tables only when another TMU register is written afterwards.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum NccUpdate {
    /// The next texel uses the new table.
    #[default]
    Immediate,
    /// DOSBox: the new table is used once a texture register (`textureMode` ..
    /// `trexInit1`) has been written. UNVERIFIED which registers DOSBox counts.
    OnTextureRegWrite,
}

/// Whether `textureMode` bit 30 (trilinear) reverses the blend on odd LODs.
///
/// The spec defines it and 86Box implements it (the default, as the project decided); MAME
/// marks it unimplemented and DOSBox ignores it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Trilinear {
    /// Spec and 86Box: reverse blend when the integer LOD is odd.
    #[default]
    Spec,
    /// MAME and DOSBox: the bit has no effect.
    Ignored,
}

/// Whether `tLOD` bit 23 (`lod_zerofrac`) forces the LOD fraction to 0.
///
/// The spec defines it; none of the three references implements it, so the default ignores
/// it to match their consensus.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum LodZeroFrac {
    /// MAME, DOSBox, 86Box: ignored.
    #[default]
    Ignored,
    /// Spec 5.51: the LOD fraction reads as 0.
    Spec,
}

/// How a texture coordinate with a fraction becomes a texel index: the integer part of
/// `S >> 24` without perspective, of `S / W` with it.
///
/// DOSBox Staging and 86Box (the default) shift or divide in integers, which rounds towards
/// minus infinity, so a coordinate a hair below zero selects texel -1 (the last texel when
/// wrapping). MAME's goldens behave as truncation towards zero there (its perspective path
/// converts a double with `cvttpd`); on the conformance traces this shows as one column or
/// diagonal of texels at S = 0 (`tex_filter_clamp`, `tex_clamp_wrap`, `tex_perspective`,
/// `tmu2_projected`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum CoordRounding {
    /// DOSBox Staging and 86Box: towards minus infinity.
    #[default]
    Floor,
    /// MAME: towards zero.
    TowardZero,
}

/// How the perspective divide `S / W`, `T / W` is computed.
///
/// MAME (the default) divides in double precision and truncates to 1/256 texel. DOSBox
/// Staging multiplies by a 1/W with 15 fraction bits interpolated from a 512-entry table
/// (`fast_reciplog`), which picks the neighbouring texel near texel edges: measured, it
/// adds 1776 majority failures on `tex_perspective` and 51 consensus failures on glide-sdk
/// `test20`. 86Box divides 2^48 by W in 64-bit integers (1/W as .16), multiplies by S
/// rounded to .18 and rounds the product to 1/16 texel of LOD 0, so a coordinate less than
/// 1/32 texel below a 1/16 step lands on the step where MAME's truncation stays below it.
///
/// Measured with every other switch at its default (consensus + majority failures):
///
/// | | conformance | glide-sdk |
/// |---|---|---|
/// | `Double` | 145 + 184544 | 5 + 34705 |
/// | `DosboxReciprocal` | 134 + 186141 | 56 + 34930 |
/// | `Box86` | 1609 + 222414 | 692 + 60765 |
///
/// `Box86` is 86Box's arithmetic: on `tex_perspective` ours then equal 86Box's dump on
/// 307170 of 307200 pixels (303217 with `Double`). The majority failures left with
/// `Double` on the perspective dumps (`tex_perspective` 24, `tmu2_projected` 49 and the
/// 198 of `tmu2_detail` that match no reference) are all texels whose 4-bit bilinear
/// fraction sits just below a step: DOSBox's table reciprocal and 86Box's rounding both
/// carry them over it, by different arithmetic, and MAME's exact quotient does not.
/// No one of the three arithmetics reproduces that coincidence.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum PerspDivide {
    /// MAME: double-precision divide, truncated to 1/256 texel (see
    /// [`CoordRounding`]).
    #[default]
    Double,
    /// DOSBox Staging: table reciprocal.
    DosboxReciprocal,
    /// 86Box: integer `2^48 / W`, coordinates rounded to 1/16 texel (ignores
    /// [`CoordRounding`]).
    Box86,
}

/// Whether `invert_output` applies when a TMU's combine passes its own texel through
/// (`zero_other`, no `sub_clocal`, add `c_local` / `a_local` in both units: Glide's
/// "decal" with the invert bits set, see
/// [`combine::TextureCombine::is_local_identity`]).
///
/// MAME (which reduces the mode to a plain texel fetch) and 86Box (which fetches only the
/// local texel for that register pattern) output the texel unchanged: the default. DOSBox
/// Staging runs the full combine, so the invert bits apply, as the spec's diagram draws.
/// On `tmu_combine` and `tmu2_combine` this decides whole cells.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum DecalInvert {
    /// MAME and 86Box: the texel goes out unchanged.
    #[default]
    Ignored,
    /// DOSBox Staging and the spec: the invert bits apply.
    Applied,
}

/// Switches for behaviour on which the references disagree. `Default` is the hardware
/// model, [`TexelProfile::HARDWARE`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct TexelProfile {
    /// LOD computation.
    pub lod: LodCalc,
    /// LOD dither magnitude.
    pub lod_dither: LodDither,
    /// Bilinear weight precision.
    pub bilinear: BilinearPrecision,
    /// A8 texel expansion.
    pub a8: A8Expansion,
    /// RGB332 blue expansion.
    pub rgb332_blue: Rgb332Blue,
    /// Point or bilinear.
    pub filter_select: FilterSelect,
    /// The units of `tDetail`'s bias and the LOD of the detail factor.
    pub detail: DetailRule,
    /// Where `nccTable0` Q2 writes land.
    pub ncc_q2: NccQ2Write,
    /// How the TMU chain combines (read from TMU 0's profile by the board).
    pub chain: ChainModel,
    /// What decoded textures are found by.
    pub texture_cache: TextureCacheKey,
    /// When NCC table writes take effect.
    pub ncc_update: NccUpdate,
    /// The trilinear bit.
    pub trilinear: Trilinear,
    /// The `lod_zerofrac` bit.
    pub lod_zerofrac: LodZeroFrac,
    /// Rounding of texture coordinates to texels.
    pub coord_rounding: CoordRounding,
    /// `invert_output` in the decal configuration.
    pub decal_invert: DecalInvert,
    /// The perspective divide.
    pub persp_divide: PerspDivide,
}

impl TexelProfile {
    /// The hardware model: our reading of the SST-1 for every disputed behaviour (each
    /// switch's `#[default]` variant; docs/accuracy.md gives the evidence).
    pub const HARDWARE: TexelProfile = TexelProfile {
        lod: LodCalc::Dosbox,
        lod_dither: LodDither::Matrix4x4,
        bilinear: BilinearPrecision::Bits4,
        a8: A8Expansion::AlphaInRgb,
        rgb332_blue: Rgb332Blue::Replicated,
        filter_select: FilterSelect::ByLod,
        detail: DetailRule::WholeLods,
        ncc_q2: NccQ2Write::Q2,
        chain: ChainModel::Full,
        texture_cache: TextureCacheKey::Exact,
        ncc_update: NccUpdate::Immediate,
        trilinear: Trilinear::Spec,
        lod_zerofrac: LodZeroFrac::Ignored,
        coord_rounding: CoordRounding::Floor,
        decal_invert: DecalInvert::Ignored,
        persp_divide: PerspDivide::Double,
    };
}

impl Default for TexelProfile {
    fn default() -> Self {
        Self::HARDWARE
    }
}

/// A model of the Texelfx, chosen at compile time: the seam between the texture stages
/// and the models of the chip, as `pixelfx::model` is for the pixel stages. A model with
/// fixed switches returns a constant profile, so the tests of its switches fold away.
pub trait TexelModel: 'static {
    /// The switches in force. `runtime` is the profile the TMU holds
    /// ([`Tmu::set_profile`]); a model with fixed switches ignores it.
    fn texel(runtime: &TexelProfile) -> TexelProfile;
}

/// The run-time-profile model: the profile held at run time, every switch tested per texel. For
/// experiments and for tests of this crate alone.
#[derive(Clone, Copy, Debug, Default)]
pub struct RuntimeProfile;

impl TexelModel for RuntimeProfile {
    #[inline(always)]
    fn texel(runtime: &TexelProfile) -> TexelProfile {
        *runtime
    }
}

/// What [`Tmu::output`] returns.
#[derive(Clone, Copy)]
enum Output {
    /// The combine unit's output with this upstream colour.
    Combined(Rgba),
    /// The filtered texel alone.
    Texel,
    /// 86Box's upstream-TMU combine, with the downstream TMU's `textureMode`.
    Box86Upstream(u32),
}

/// What one TMU did for one pixel ([`Tmu::texel_traced`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TmuPixel {
    /// Iterated S, T, W at the pixel (.32: S and T 14.18 << 14, W 2.30 << 2).
    pub s_32: i64,
    pub t_32: i64,
    pub w_32: i64,
    /// The clamped LOD, 8.8.
    pub lod_8_8: i32,
    /// The LOD fraction the combine unit sees.
    pub lod_fraction: u8,
    /// The filtered texel.
    pub texel: Rgba,
    /// The TMU's output (the combine unit's, or the texel uncombined).
    pub output: Rgba,
}

/// One texture mapping unit: its registers, texture memory, NCC tables and palette.
pub struct Tmu {
    /// TMU number, 0..=2.
    index: u8,
    /// Texture memory.
    ram: Vec<u8>,
    /// Memory size minus 1 (a power of two minus 1).
    ram_mask: u32,
    /// Behaviour switches held at run time: what the run-time-profile model ([`RuntimeProfile`])
    /// reads, and the fixed models' own profile (the board keeps the two in step).
    profile: TexelProfile,
    /// `textureMode`.
    texture_mode: u32,
    /// `tLOD`.
    t_lod: u32,
    /// `tDetail`.
    t_detail: u32,
    /// `texBaseAddr`, `texBaseAddr1`, `texBaseAddr2`, `texBaseAddr38`.
    tex_base: [u32; 4],
    /// `trexInit0`, `trexInit1` (stored only).
    trex_init: [u32; 2],
    /// Raw NCC table registers.
    ncc_regs: [NccRegs; 2],
    /// Expanded NCC tables in use.
    ncc: [[Rgb8; 256]; 2],
    /// NCC registers changed but not yet expanded ([`NccUpdate::OnTextureRegWrite`]).
    ncc_stale: bool,
    /// The 8-bit palette.
    palette: [Rgb8; 256],
    /// The S, T, W start values and gradients.
    stw: StwParams,
    /// Memory layout of the current texture.
    layout: Layout,
    /// Combine unit configuration from `textureMode`.
    combine: TextureCombine,
    /// Base LOD (8.8) of the current triangle.
    lod_base: i32,
    /// How texels of the current format are decoded.
    decode: format::Decode,
    /// Decoded texels (`0xAARRGGBB`) of the current format, NCC table and palette, by
    /// texel byte (see [`format::lut`]).
    texel_lut: Box<[u32; 256]>,
    /// `decode` and `texel_lut` no longer match `textureMode`, the NCC table in use, the
    /// palette or the profile; rebuilt before the next texel.
    lut_stale: bool,
    /// The combine passes the local texel through untouched (see [`DecalInvert`]).
    passthrough: bool,
    /// Decoded levels of the bound texture.
    cache: TexelCache,
    /// 86Box's texture cache ([`TextureCacheKey::Box86`]).
    box86: box86::Box86Cache,
    /// Sample through `cache` (off: decode every texel from memory, the generic path).
    cached: bool,
    /// The span kernels' lane values (module `span`), kept between chunks.
    lanes: Option<Box<span::Chunk>>,
    /// Lane outputs of [`Tmu::texels_kept`], kept for the next TMU down the chain.
    kept: Option<Box<ColourLanes>>,
    /// The span kernels' approximations in force ([`Tmu::set_approx`]; none by default).
    approx: Approx,
}

impl Tmu {
    /// A TMU with `mem_bytes` of texture memory (1, 2 or 4 MiB; other sizes are rounded up
    /// to a power of two within 1..=4 MiB). `index` is 0..=2.
    pub fn new(index: u8, mem_bytes: usize) -> Self {
        let size = mem_bytes.clamp(1 << 20, 4 << 20).next_power_of_two();
        let ram_mask = (size - 1) as u32;
        Self {
            index,
            ram: vec![0; size],
            ram_mask,
            profile: TexelProfile::default(),
            texture_mode: 0,
            t_lod: 0,
            t_detail: 0,
            tex_base: [0; 4],
            trex_init: [0; 2],
            ncc_regs: [[0; 12]; 2],
            ncc: [[[0; 3]; 256]; 2],
            ncc_stale: false,
            palette: [[0; 3]; 256],
            stw: StwParams::default(),
            layout: Layout::new(0, 0, &[0; 4], ram_mask),
            combine: TextureCombine::from_texture_mode(0),
            lod_base: 0,
            decode: format::Decode::of(0),
            texel_lut: Box::new([0; 256]),
            lut_stale: true,
            passthrough: false,
            cache: TexelCache::new(),
            box86: Default::default(),
            cached: true,
            lanes: None,
            kept: None,
            approx: Approx::EXACT,
        }
    }

    /// The TMU number given to [`Tmu::new`].
    pub fn index(&self) -> u8 {
        self.index
    }

    /// Selects the behaviour switches.
    pub fn set_profile(&mut self, p: TexelProfile) {
        self.box86_return();
        self.box86.clear();
        self.profile = p;
        self.refresh();
        if p.ncc_update == NccUpdate::Immediate {
            self.expand_ncc();
        }
    }

    /// Decode every texel from texture memory for every pixel instead of reading the
    /// decoded-texel cache (module `cache`). Output is identical either way; this is the
    /// generic path for differential tests. Off by default.
    pub fn set_generic_path(&mut self, on: bool) {
        self.cached = !on;
        self.cache.clear();
    }

    /// Choose the span kernels' approximations (module `approx`; [`Approx::EXACT`], the
    /// default, is none). The per-pixel path ignores them.
    pub fn set_approx(&mut self, approx: Approx) {
        self.approx = approx;
    }

    /// The span kernels' approximations in force.
    pub fn approx(&self) -> Approx {
        self.approx
    }

    /// The behaviour switches in use.
    pub fn profile(&self) -> TexelProfile {
        self.profile
    }

    /// The texture memory, as written.
    pub fn memory(&self) -> &[u8] {
        &self.ram
    }

    /// The last values written to `trexInit0` and `trexInit1` (spec 5.54, 5.55).
    pub fn trex_init(&self) -> [u32; 2] {
        self.trex_init
    }

    /// A register write that reached this TMU, by its normal-map byte offset
    /// (0x000..=0x3fc; other bits are ignored).
    ///
    /// S/T start and gradient registers are 14.18 ([`Fx14_18`]), W ones 2.30 ([`Fx2_30`]).
    /// The float aliases (`fstartS` 0x0b4 .. `fdWdY` 0x0fc) are accepted too, raw IEEE
    /// singles, and converted with the 32 fraction bits the references keep. Offsets that
    /// are not TMU registers are ignored.
    /// Whether [`Tmu::write_reg`] stores anything of a write to register `offset`: the
    /// S, T and W iterators, the texture registers and the NCC tables. The TMU keeps
    /// nothing of the other registers the spec sends it (the vertices and the triangle
    /// commands: its iterators count from the FBI's pixel offsets), so the board need not
    /// send it those.
    pub const fn stores(offset: u32) -> bool {
        matches!(
            offset & 0x3fc,
            addr::START_S
                | addr::START_T
                | addr::START_W
                | addr::D_S_DX
                | addr::D_T_DX
                | addr::D_W_DX
                | addr::D_S_DY
                | addr::D_T_DY
                | addr::D_W_DY
                | addr::F_START_S..=addr::F_START_W
                | addr::F_D_S_DX..=addr::F_D_W_DX
                | addr::F_D_S_DY..=addr::F_D_W_DY
                | addr::TEXTURE_MODE..=addr::TREX_INIT1
        ) || (offset & 0x3fc >= addr::NCC_TABLE0 && offset & 0x3fc < addr::NCC_TABLE1 + 48)
    }

    pub fn write_reg(&mut self, offset: u32, value: u32) {
        self.box86_return();
        let offset = offset & 0x3fc;
        if self.stw.write(offset, value) {
            return;
        }
        match offset {
            addr::TEXTURE_MODE..=addr::TREX_INIT1 => {
                match offset {
                    addr::TEXTURE_MODE => self.texture_mode = value,
                    addr::T_LOD => self.t_lod = value,
                    addr::T_DETAIL => self.t_detail = value,
                    addr::TREX_INIT0 | addr::TREX_INIT1 => {
                        self.trex_init[((offset - addr::TREX_INIT0) / 4) as usize] = value
                    }
                    _ => self.tex_base[((offset - addr::TEX_BASE_ADDR) / 4) as usize] = value,
                }
                self.refresh();
                if self.ncc_stale {
                    self.expand_ncc();
                }
            }
            o if (addr::NCC_TABLE0..addr::NCC_TABLE1 + 48).contains(&o) => {
                let word = ((o - addr::NCC_TABLE0) / 4) as usize;
                self.write_ncc(word / 12, word % 12, value);
            }
            _ => {}
        }
    }

    /// A 32-bit write into this TMU's texture download window: `addr` is the aperture offset
    /// minus 0x800000 (TMU-select bits 22:21 may still be present; they are ignored).
    pub fn write_texture(&mut self, addr: u32, value: u32) {
        self.box86_return();
        self.download(addr, value);
    }

    /// Called at the start of each triangle, after its register writes: computes the base
    /// LOD from the S/T gradients. `M` is the model of the chip ([`TexelModel`]; the caller
    /// guarantees that the profile this TMU holds is `M`'s), here and in every method that
    /// shades.
    pub fn begin_triangle<M: TexelModel>(&mut self) {
        let profile = M::texel(&self.profile);
        if profile.texture_cache == TextureCacheKey::Box86 {
            self.box86_bind();
        }
        let g = [
            self.stw.rows[stw::DX][0],
            self.stw.rows[stw::DY][0],
            self.stw.rows[stw::DX][1],
            self.stw.rows[stw::DY][1],
        ];
        self.lod_base = lod::lod_base(profile.lod, g, self.t_lod);
    }

    /// Subpixel correction of the S/T/W start registers ([`StwParams::subpixel_adjust`]).
    pub fn subpixel_adjust(&mut self, dx_12_4: i32, dy_12_4: i32) {
        self.stw.subpixel_adjust(dx_12_4, dy_12_4);
    }

    /// The S, T, W start registers (.32 fixed point), e.g. to undo a subpixel correction
    /// that lasts one triangle ([`Tmu::restore_start_registers`]).
    pub fn start_registers(&self) -> [i64; 3] {
        self.stw.rows[stw::START]
    }

    /// Sets the S, T, W start registers back to values [`Tmu::start_registers`] returned.
    pub fn restore_start_registers(&mut self, start: [i64; 3]) {
        self.stw.rows[stw::START] = start;
    }

    /// An S, T, W register write ([`StwParams::decode`]): what [`Tmu::write_reg`] does
    /// with it, decoded once for every TMU it goes to.
    #[inline]
    pub fn write_stw(&mut self, w: StwWrite) {
        self.box86_return();
        self.stw.apply(w);
    }

    /// The S, T, W register writes `pending`, as [`Tmu::write_reg`] one by one would
    /// have done them: a board that lends this TMU to a render thread notes them on the
    /// calling thread and sends them with each textured triangle.
    #[inline]
    pub fn apply_stw(&mut self, pending: &StwPending) {
        if !pending.is_empty() {
            // What every register write does first (`write_reg`).
            self.box86_return();
            pending.apply_to(&mut self.stw);
        }
    }

    /// The TMU's output for one pixel.
    ///
    /// `dx`, `dy`: integer pixel offsets from vertex A's integer position; `x`, `y`: screen
    /// position (LOD dither); `other`: the upstream TMU's output (black and transparent for
    /// the last TMU of the chain).
    pub fn texel<M: TexelModel>(&mut self, dx: i32, dy: i32, x: i32, y: i32, other: Rgba) -> Rgba {
        self.output::<M>(dx, dy, x, y, Output::Combined(other))
    }

    /// The filtered texel for one pixel, without the combine unit ([`ChainModel::Box86`]).
    pub fn texel_uncombined<M: TexelModel>(&mut self, dx: i32, dy: i32, x: i32, y: i32) -> Rgba {
        self.output::<M>(dx, dy, x, y, Output::Texel)
    }

    /// The upstream TMU's output under [`ChainModel::Box86`], with the downstream TMU's
    /// `textureMode` (whose `reverse_blend` bits 86Box applies here).
    pub fn texel_box86_upstream<M: TexelModel>(
        &mut self,
        dx: i32,
        dy: i32,
        x: i32,
        y: i32,
        downstream_mode: u32,
    ) -> Rgba {
        self.output::<M>(dx, dy, x, y, Output::Box86Upstream(downstream_mode))
    }

    /// [`Tmu::texel`] for a watched pixel (pixel history, `pixelfx::watch`): the same
    /// output, with the same effect on the TMU's caches, and the values it came from.
    pub fn texel_traced<M: TexelModel>(
        &mut self,
        dx: i32,
        dy: i32,
        x: i32,
        y: i32,
        other: Rgba,
    ) -> TmuPixel {
        self.output_traced::<M>(dx, dy, x, y, Output::Combined(other))
    }

    /// [`Tmu::texel_uncombined`] for a watched pixel ([`Tmu::texel_traced`]).
    pub fn texel_uncombined_traced<M: TexelModel>(
        &mut self,
        dx: i32,
        dy: i32,
        x: i32,
        y: i32,
    ) -> TmuPixel {
        self.output_traced::<M>(dx, dy, x, y, Output::Texel)
    }

    /// [`Tmu::texel_box86_upstream`] for a watched pixel ([`Tmu::texel_traced`]).
    pub fn texel_box86_upstream_traced<M: TexelModel>(
        &mut self,
        dx: i32,
        dy: i32,
        x: i32,
        y: i32,
        downstream_mode: u32,
    ) -> TmuPixel {
        self.output_traced::<M>(dx, dy, x, y, Output::Box86Upstream(downstream_mode))
    }

    fn output<M: TexelModel>(&mut self, dx: i32, dy: i32, x: i32, y: i32, what: Output) -> Rgba {
        self.output_traced::<M>(dx, dy, x, y, what).output
    }

    /// The TMU's output for one pixel and what it came from; [`Tmu::output`] keeps the
    /// output alone (and the compiler drops the rest).
    #[inline(always)]
    fn output_traced<M: TexelModel>(
        &mut self,
        dx: i32,
        dy: i32,
        x: i32,
        y: i32,
        what: Output,
    ) -> TmuPixel {
        let profile = M::texel(&self.profile);
        if self.lut_stale {
            self.rebuild_lut();
        }
        let at = |i| self.iterated(i, dx, dy);
        let (s, t, w) = (at(0), at(1), at(2));
        let smp = self.sample::<M>(s, t, w, x, y);
        let factors = || Factors {
            detail: detail_factor(self.t_detail, smp.lod, profile.detail),
            lod_fraction: smp.lod_fraction,
            odd_lod: profile.trilinear == Trilinear::Spec && smp.odd_lod,
        };
        let [r, g, b, a] = match what {
            Output::Texel => smp.texel,
            Output::Combined(_) if self.passthrough => smp.texel,
            Output::Combined(o) => {
                self.combine
                    .combine(smp.texel, [o.r, o.g, o.b, o.a], &factors())
            }
            Output::Box86Upstream(mode) => self.combine.combine_box86_upstream(
                smp.texel,
                &factors(),
                &TextureCombine::from_texture_mode(mode),
            ),
        };
        let [tr, tg, tb, ta] = smp.texel;
        TmuPixel {
            s_32: s,
            t_32: t,
            w_32: w,
            lod_8_8: smp.lod,
            lod_fraction: smp.lod_fraction,
            texel: Rgba {
                r: tr,
                g: tg,
                b: tb,
                a: ta,
            },
            output: Rgba { r, g, b, a },
        }
    }

    /// Whether the TMU's output reads its `other` input, the upstream TMU's output
    /// ([`combine::TextureCombine::reads_other`]; a pass-through reads its texel alone).
    pub fn reads_other(&self) -> bool {
        !self.passthrough && self.combine.reads_other()
    }

    /// Whether sampling ([`Tmu::texels`]) changes nothing that a later texel can see, so
    /// that a chunk may skip a TMU whose output nothing reads: true unless an 86Box
    /// texture cache entry is lent (its levels are decoded when first read, from the
    /// texture memory of that moment).
    pub fn samples_purely(&self) -> bool {
        self.box86.lent.is_none()
    }

    /// The raw `textureMode` register.
    pub fn texture_mode(&self) -> u32 {
        self.texture_mode
    }

    /// Iterator `i` (0 S, 1 T, 2 W; .32) at pixel offset `(dx, dy)` from vertex A:
    /// `start + dx * d/dx + dy * d/dy`, wrapping as the 64-bit references do.
    #[inline(always)]
    fn iterated(&self, i: usize, dx: i32, dy: i32) -> Fx32 {
        self.stw.iterated(i, dx, dy)
    }

    /// Recomputes what depends on the texture registers.
    fn refresh(&mut self) {
        let layout = Layout::new(self.texture_mode, self.t_lod, &self.tex_base, self.ram_mask);
        if layout != self.layout {
            self.cache.clear();
        }
        self.layout = layout;
        self.combine = TextureCombine::from_texture_mode(self.texture_mode);
        self.passthrough =
            self.profile.decal_invert == DecalInvert::Ignored && self.combine.is_local_identity();
        self.lut_stale = true;
    }

    /// Rebuilds `decode` and `texel_lut` from the current format and tables.
    fn rebuild_lut(&mut self) {
        let tformat = TextureMode(self.texture_mode).format() as u32;
        let decode = format::Decode::of(tformat);
        let lut = format::lut(tformat, &self.lookups());
        // A lent 86Box entry keeps the texels it was decoded with (TextureCacheKey::Box86).
        if (decode != self.decode || lut != *self.texel_lut) && self.box86.lent.is_none() {
            self.cache.clear();
        }
        self.decode = decode;
        *self.texel_lut = lut;
        self.lut_stale = false;
    }

    /// A write to word `word` (0..12) of NCC table `table` (0, 1), or to the palette.
    fn write_ncc(&mut self, table: usize, word: usize, value: u32) {
        match sst1_ncc::classify_write(table, word, value) {
            NccWrite::Table { table, word, value } => {
                // Words 0..4 are Y, 4..8 I, 8..12 Q: table 0's Q2 is word 10, I2 word 6.
                let word = match (self.profile.ncc_q2, table, word) {
                    (NccQ2Write::IntoI2, 0, 10) => 6,
                    _ => word,
                };
                self.ncc_regs[table][word] = value;
                match self.profile.ncc_update {
                    NccUpdate::Immediate => {
                        self.ncc[table] = sst1_ncc::expand(&self.ncc_regs[table]);
                        self.lut_stale = true;
                    }
                    NccUpdate::OnTextureRegWrite => self.ncc_stale = true,
                }
            }
            NccWrite::Palette { index, rgb } => {
                self.palette[usize::from(index)] = rgb;
                self.lut_stale = true;
            }
        }
    }

    /// Expands both NCC tables from their registers.
    fn expand_ncc(&mut self) {
        self.ncc = [
            sst1_ncc::expand(&self.ncc_regs[0]),
            sst1_ncc::expand(&self.ncc_regs[1]),
        ];
        self.ncc_stale = false;
        self.lut_stale = true;
    }

    /// The tables a texel decode needs.
    fn lookups(&self) -> format::Lookups<'_> {
        format::Lookups {
            ncc: &self.ncc[usize::from(TextureMode(self.texture_mode).tnccselect())],
            palette: &self.palette,
            a8: self.profile.a8,
            rgb332_blue: self.profile.rgb332_blue,
        }
    }
}

#[cfg(test)]
mod tests;

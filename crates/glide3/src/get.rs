//! `grGet` / `grGetString` answers and the `gu` fog-table utilities.
//!
//! Values follow 3dfx's SST-1 Glide 3 (diget.c, gu.c): 16-bit depth, RGB 5-6-5,
//! 64 fog entries, 32 gamma entries, 256-texel maximum, W range 0..0xffff, Z range
//! 0xffff..0, version string "3.01.0001".

use crate::consts::*;
use crate::x87::Ext;
use sst1_regs::addr::{
    FBI_AFUNC_FAIL, FBI_CHROMA_FAIL, FBI_PIXELS_IN, FBI_PIXELS_OUT, FBI_ZFUNC_FAIL, STATUS,
};

/// Entries in the fog table.
pub const FOG_TABLE_SIZE: usize = 64;

/// `grGetString`.
pub fn get_string(pname: u32) -> &'static str {
    match pname {
        GR_EXTENSION => "FOGALPHA ",
        GR_HARDWARE => "Voodoo Graphics",
        GR_RENDERER => "Glide",
        GR_VENDOR => "3Dfx Interactive",
        GR_VERSION => "3.01.0001",
        _ => "ERROR",
    }
}

/// `guFogTableIndexToW`: the W each fog-table entry stands for,
/// `2^(3 + i/4) / (8 - i%4)` as a `float` division (gu.c).
pub fn fog_table_index_to_w(i: i32) -> f32 {
    (2.0f64.powi(3 + (i >> 2)) as f32) / ((8 - (i & 3)) as f32)
}

/// One table entry from `f` kept in x87 extended precision: clamp to 0..1, times 255,
/// truncated to a byte. `None` stands for NaN, which the x87 converts to the
/// "integer indefinite" 0x80000000, whose low byte 0 ends up in the table.
fn entry(f: Option<Ext>) -> u8 {
    match f {
        None => 0,
        Some(f) if f.gt_one() => 255,
        Some(f) if f.lt_zero() => 0,
        Some(f) => f.mul(Ext::from_f64(255.0)).trunc_u8(),
    }
}

/// `(1 - e) * scale` with `scale = 1 / (1 - e_last)` stored as a `float`, as
/// guFogGenerateExp/Exp2 evaluate it; `e` and `e_last` are the `(float)exp(..)` terms.
fn exp_entry(e: f32, e_last: f32) -> u8 {
    let one = Ext::from_f64(1.0);
    if !e.is_finite() || !e_last.is_finite() {
        return 0;
    }
    let a = one.sub(Ext::from_f64(f64::from(e)));
    match one.div(one.sub(Ext::from_f64(f64::from(e_last)))) {
        Some(scale) if scale.to_f32().is_finite() => {
            entry(Some(a.mul(Ext::from_f64(f64::from(scale.to_f32())))))
        }
        // scale = +inf (density 0): 0 * inf is NaN, anything else saturates.
        _ if a.is_zero() => entry(None),
        _ => entry(Some(a.mul(Ext::from_f64(f64::from(f32::MAX) * 4.0)))),
    }
}

/// `guFogGenerateExp`: `f = (1 - e^(-density w)) / (1 - e^(-density w_63))`.
/// Evaluated with 3dfx's float/x87 rounding steps (gu.c): `dp = density * w` and the
/// `(float)exp(-dp)` term in single precision, the rest in x87 extended precision
/// (see the `x87` module). Verified against test08/test22/test24 (tests/fog_trace.rs).
pub fn fog_generate_exp(table: &mut [u8; FOG_TABLE_SIZE], density: f32) {
    let e = |i: i32| (-f64::from(density * fog_table_index_to_w(i))).exp() as f32;
    let e_last = e(FOG_TABLE_SIZE as i32 - 1);
    for (i, t) in table.iter_mut().enumerate() {
        *t = exp_entry(e(i as i32), e_last);
    }
}

/// `guFogGenerateExp2`: `f = (1 - e^(-(density w)^2)) / (1 - e^(-(density w_63)^2))`,
/// with the same rounding steps as [`fog_generate_exp`] (`dp * dp` is exact in the
/// double passed to `exp`). UNVERIFIED against a trace: no glide-sdk test uses it.
pub fn fog_generate_exp2(table: &mut [u8; FOG_TABLE_SIZE], density: f32) {
    let e = |i: i32| {
        let dp = f64::from(density * fog_table_index_to_w(i));
        (-(dp * dp)).exp() as f32
    };
    let e_last = e(FOG_TABLE_SIZE as i32 - 1);
    for (i, t) in table.iter_mut().enumerate() {
        *t = exp_entry(e(i as i32), e_last);
    }
}

/// `guFogGenerateLinear`: `f = (w - near) / (far - near)`, `w` capped at 65535 (a
/// `float`), the quotient and `* 255` in x87 extended precision as in gu.c.
/// UNVERIFIED against a trace: no glide-sdk test uses it.
pub fn fog_generate_linear(table: &mut [u8; FOG_TABLE_SIZE], near: f32, far: f32) {
    for (i, t) in table.iter_mut().enumerate() {
        let w = fog_table_index_to_w(i as i32).min(65535.0);
        *t = if !near.is_finite() || !far.is_finite() {
            0
        } else {
            let num = Ext::from_f64(f64::from(w)).sub(Ext::from_f64(f64::from(near)));
            let den = Ext::from_f64(f64::from(far)).sub(Ext::from_f64(f64::from(near)));
            match num.div(den) {
                Some(f) => entry(Some(f)),
                // x / 0: +-inf saturates, 0 / 0 is NaN.
                None if num.is_zero() => entry(None),
                None if num.lt_zero() => 0,
                None => 255,
            }
        };
    }
}

/// `sizeof(GrState)` in 3dfx's SST-1 Glide 3 (fxglide.h, 32-bit x86, `GLIDE_NUM_TMU`
/// 2): the size of the buffer `grGlideGetState` fills. Source: the struct compiled
/// with `gcc -m32` from sezero/glide glide3x/sst1/glide3/src/fxglide.h.
pub const GLIDE_STATE_SIZE: i32 = 588;

/// `sizeof(GrVertexLayout)` in 3dfx's SST-1 Glide 3: 11 parameters of (mode,
/// offset) plus stride, size and colour type, 4 bytes each.
pub const GLIDE_VERTEXLAYOUT_SIZE: i32 = 100;

/// What `grGet` answers for a known selector: the values and the `plength` they need.
fn expected_length(pname: u32) -> Option<u32> {
    Some(match pname {
        GR_BITS_RGBA | GR_VIEWPORT => 16,
        GR_FIFO_FULLNESS | GR_VIDEO_POSITION | GR_WDEPTH_MIN_MAX | GR_ZDEPTH_MIN_MAX => 8,
        GR_SWAP_HISTORY => 0,
        GR_BITS_DEPTH
        | GR_BITS_GAMMA
        | GR_GLIDE_STATE_SIZE
        | GR_GLIDE_VERTEXLAYOUT_SIZE
        | GR_FOG_TABLE_ENTRIES
        | GR_GAMMA_TABLE_ENTRIES
        | GR_IS_BUSY
        | GR_LFB_PIXEL_PIPE
        | GR_MAX_TEXTURE_SIZE
        | GR_MAX_TEXTURE_ASPECT_RATIO
        | GR_MEMORY_FB
        | GR_MEMORY_TMU
        | GR_MEMORY_UMA
        | GR_NUM_BOARDS
        | GR_NUM_FB
        | GR_NON_POWER_OF_TWO_TEXTURES
        | GR_NUM_TMU
        | GR_PENDING_BUFFERSWAPS
        | GR_REVISION_FB
        | GR_REVISION_TMU
        | GR_STATS_LINES
        | GR_STATS_PIXELS_AFUNC_FAIL
        | GR_STATS_PIXELS_CHROMA_FAIL
        | GR_STATS_PIXELS_DEPTHFUNC_FAIL
        | GR_STATS_PIXELS_IN
        | GR_STATS_PIXELS_OUT
        | GR_STATS_POINTS
        | GR_STATS_TRIANGLES_IN
        | GR_STATS_TRIANGLES_OUT
        | GR_NUM_SWAP_HISTORY_BUFFER
        | GR_SUPPORTS_PASSTHRU
        | GR_TEXTURE_ALIGN => 4,
        _ => return None,
    })
}

impl crate::Glide {
    /// `grGet`: fills `out` and returns what 3dfx's SST-1 Glide 3 returns (diget.c):
    /// `plength` on success; 1 (`FXTRUE`, `out` untouched) for a known selector
    /// asked with another `plength`; 0 for an unknown selector.
    ///
    /// The Programming Guide (chapter 12) says every failure returns 0; 3dfx's
    /// library starts from `FXTRUE` and only a matching `plength` overwrites it.
    /// `GR_SWAP_HISTORY` with `plength` 0 "succeeds" with 0 bytes, as there.
    pub fn get(&mut self, pname: u32, plength: u32, out: &mut [i32]) -> u32 {
        let Some(need) = expected_length(pname) else {
            return 0;
        };
        if plength != need {
            return 1;
        }
        let vp = self.st.viewport;
        let b = self.board;
        let vals: Vec<i32> = match pname {
            GR_BITS_DEPTH => vec![16],
            GR_BITS_RGBA => vec![5, 6, 5, 0],
            GR_BITS_GAMMA => vec![8],
            GR_FIFO_FULLNESS => {
                // Free memory-FIFO entries (status bits 27:12) turned into "fullness".
                let s = 0xffff - ((self.hw.r(STATUS) >> 12) & 0xffff);
                vec![((s << 8) + (s >> 8)) as i32, s as i32]
            }
            GR_GLIDE_STATE_SIZE => vec![GLIDE_STATE_SIZE],
            GR_GLIDE_VERTEXLAYOUT_SIZE => vec![GLIDE_VERTEXLAYOUT_SIZE],
            GR_FOG_TABLE_ENTRIES => vec![FOG_TABLE_SIZE as i32],
            GR_GAMMA_TABLE_ENTRIES => vec![32],
            // status bit 9: SST-1 busy (sst.h SST_BUSY).
            GR_IS_BUSY => vec![i32::from(self.hw.r(STATUS) & (1 << 9) != 0)],
            GR_LFB_PIXEL_PIPE => vec![1],
            GR_MAX_TEXTURE_SIZE => vec![256],
            GR_MAX_TEXTURE_ASPECT_RATIO => vec![3],
            GR_MEMORY_FB => vec![(b.fbi_mb << 20) as i32],
            // TMU 0's memory, whatever the TMU count.
            GR_MEMORY_TMU => vec![(b.tmu_mb << 20) as i32],
            GR_MEMORY_UMA => vec![0],
            GR_NUM_BOARDS | GR_NUM_FB => vec![1],
            GR_NON_POWER_OF_TWO_TEXTURES => vec![0],
            GR_NUM_TMU => vec![b.tmus as i32],
            // status bits 30:28: swaps pending (gglide.c _grBufferNumPending).
            GR_PENDING_BUFFERSWAPS => vec![((self.hw.r(STATUS) >> 28) & 7) as i32],
            GR_REVISION_FB => vec![b.fbi_revision as i32],
            GR_REVISION_TMU => vec![b.tmu_revision as i32],
            GR_STATS_LINES => vec![self.stats.lines as i32],
            GR_STATS_PIXELS_AFUNC_FAIL => vec![self.hw.r(FBI_AFUNC_FAIL) as i32],
            GR_STATS_PIXELS_CHROMA_FAIL => vec![self.hw.r(FBI_CHROMA_FAIL) as i32],
            GR_STATS_PIXELS_DEPTHFUNC_FAIL => vec![self.hw.r(FBI_ZFUNC_FAIL) as i32],
            GR_STATS_PIXELS_IN => vec![self.hw.r(FBI_PIXELS_IN) as i32],
            GR_STATS_PIXELS_OUT => vec![self.hw.r(FBI_PIXELS_OUT) as i32],
            GR_STATS_POINTS => vec![self.stats.points as i32],
            GR_STATS_TRIANGLES_IN => vec![self.stats.triangles_in as i32],
            GR_STATS_TRIANGLES_OUT => vec![self.stats.triangles_drawn as i32],
            GR_NUM_SWAP_HISTORY_BUFFER => vec![0],
            GR_SUPPORTS_PASSTHRU => vec![1],
            GR_TEXTURE_ALIGN => vec![8],
            GR_VIDEO_POSITION => {
                // vRetrace: bits 11:0 vertical, 27:16 horizontal (fxglide.h).
                let v = self.hw.r(sst1_regs::addr::V_RETRACE);
                vec![(v & 0xfff) as i32, ((v >> 16) & 0xfff) as i32]
            }
            GR_VIEWPORT => vec![
                (vp.ox - vp.hwidth) as i32,
                (vp.oy - vp.hheight) as i32,
                (vp.hwidth * 2.0) as i32,
                (vp.hheight * 2.0) as i32,
            ],
            GR_WDEPTH_MIN_MAX => vec![0, 0xffff],
            GR_ZDEPTH_MIN_MAX => vec![0xffff, 0],
            // GR_SWAP_HISTORY: nothing recorded on the SST-1.
            _ => vec![],
        };
        if out.len() < vals.len() {
            self.report(
                format!("grGet: output too small for selector {pname:#x}"),
                false,
            );
            return 0;
        }
        out[..vals.len()].copy_from_slice(&vals);
        plength
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fog_w_table() {
        assert_eq!(fog_table_index_to_w(0), 1.0);
        assert_eq!(fog_table_index_to_w(4), 2.0);
        // 2^(3 + 15) / (8 - 3)
        assert_eq!(fog_table_index_to_w(63), 52428.8);
    }

    #[test]
    fn linear_fog_endpoints() {
        let mut t = [0u8; FOG_TABLE_SIZE];
        fog_generate_linear(&mut t, 1.0, 1000.0);
        assert_eq!(t[0], 0);
        assert_eq!(t[63], 255);
        fog_generate_exp(&mut t, 0.001);
        assert_eq!(t[63], 255);
        assert_eq!(get_string(GR_VERSION), "3.01.0001");
    }
}

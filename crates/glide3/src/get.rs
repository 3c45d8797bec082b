//! `grGet` / `grGetString` answers and the `gu` fog-table utilities.
//!
//! Values follow 3dfx's SST-1 Glide 3 (diget.c, gu.c): 16-bit depth, RGB 5-6-5,
//! 64 fog entries, 32 gamma entries, 256-texel maximum, W range 0..0xffff, Z range
//! 0xffff..0, version string "3.01.0001".

use crate::consts::*;
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

/// `guFogTableIndexToW`: the W each fog-table entry stands for.
pub fn fog_table_index_to_w(i: i32) -> f32 {
    (2.0f64.powf(3.0 + f64::from(i >> 2)) / f64::from(8 - (i & 3))) as f32
}

fn fill(table: &mut [u8; FOG_TABLE_SIZE], f: impl Fn(usize) -> f32) {
    for (i, e) in table.iter_mut().enumerate() {
        *e = (f(i).clamp(0.0, 1.0) * 255.0) as u8;
    }
}

/// `guFogGenerateExp`: f = (1 - e^(-density w)) normalised to the last entry.
pub fn fog_generate_exp(table: &mut [u8; FOG_TABLE_SIZE], density: f32) {
    let dp = density * fog_table_index_to_w(63);
    let scale = 1.0f32 / (1.0f32 - (f64::from(-dp)).exp() as f32);
    fill(table, |i| {
        let dp = density * fog_table_index_to_w(i as i32);
        (1.0f32 - (f64::from(-dp)).exp() as f32) * scale
    });
}

/// `guFogGenerateExp2`: f = (1 - e^(-(density w)^2)) normalised to the last entry.
pub fn fog_generate_exp2(table: &mut [u8; FOG_TABLE_SIZE], density: f32) {
    let dp = density * fog_table_index_to_w(63);
    let scale = 1.0f32 / (1.0f32 - (f64::from(-(dp * dp))).exp() as f32);
    fill(table, |i| {
        let dp = density * fog_table_index_to_w(i as i32);
        (1.0f32 - (f64::from(-(dp * dp))).exp() as f32) * scale
    });
}

/// `guFogGenerateLinear`: f = (w - near) / (far - near), w capped at 65535.
pub fn fog_generate_linear(table: &mut [u8; FOG_TABLE_SIZE], near: f32, far: f32) {
    fill(table, |i| {
        let w = fog_table_index_to_w(i as i32).min(65535.0);
        (w - near) / (far - near)
    });
}

impl crate::Glide {
    /// `grGet`: fills `out` and returns the number of bytes written (0 for an unknown
    /// selector or a wrong `plength`, as 3dfx's library).
    pub fn get(&mut self, pname: u32, plength: u32, out: &mut [i32]) -> u32 {
        let vp = self.st.viewport;
        let b = self.board;
        let vals: Vec<i32> = match (pname, plength) {
            (GR_BITS_DEPTH, 4) => vec![16],
            (GR_BITS_RGBA, 16) => vec![5, 6, 5, 0],
            (GR_BITS_GAMMA, 4) => vec![8],
            (GR_FIFO_FULLNESS, 8) => {
                let s = 0xffff - ((self.hw.r(STATUS) >> 12) & 0xffff);
                vec![((s << 8) + (s >> 8)) as i32, s as i32]
            }
            (GR_GLIDE_STATE_SIZE, 4) => {
                vec![std::mem::size_of::<crate::state::GlideState>() as i32]
            }
            (GR_GLIDE_VERTEXLAYOUT_SIZE, 4) => {
                vec![std::mem::size_of::<crate::draw::VertexLayout>() as i32]
            }
            (GR_FOG_TABLE_ENTRIES, 4) => vec![FOG_TABLE_SIZE as i32],
            (GR_GAMMA_TABLE_ENTRIES, 4) => vec![32],
            (GR_IS_BUSY, 4) => vec![i32::from(self.hw.r(STATUS) & (1 << 9) != 0)],
            (GR_LFB_PIXEL_PIPE, 4) => vec![1],
            (GR_MAX_TEXTURE_SIZE, 4) => vec![256],
            (GR_MAX_TEXTURE_ASPECT_RATIO, 4) => vec![3],
            (GR_MEMORY_FB, 4) => vec![(b.fbi_mb << 20) as i32],
            (GR_MEMORY_TMU, 4) => vec![(b.tmu_mb << 20) as i32],
            (GR_MEMORY_UMA, 4) => vec![0],
            (GR_NUM_BOARDS, 4) | (GR_NUM_FB, 4) => vec![1],
            (GR_NON_POWER_OF_TWO_TEXTURES, 4) => vec![0],
            (GR_NUM_TMU, 4) => vec![b.tmus as i32],
            (GR_PENDING_BUFFERSWAPS, 4) => vec![((self.hw.r(STATUS) >> 28) & 7) as i32],
            (GR_REVISION_FB, 4) => vec![b.fbi_revision as i32],
            (GR_REVISION_TMU, 4) => vec![b.tmu_revision as i32],
            (GR_STATS_LINES, 4) => vec![self.stats.lines as i32],
            (GR_STATS_PIXELS_AFUNC_FAIL, 4) => vec![self.hw.r(FBI_AFUNC_FAIL) as i32],
            (GR_STATS_PIXELS_CHROMA_FAIL, 4) => vec![self.hw.r(FBI_CHROMA_FAIL) as i32],
            (GR_STATS_PIXELS_DEPTHFUNC_FAIL, 4) => vec![self.hw.r(FBI_ZFUNC_FAIL) as i32],
            (GR_STATS_PIXELS_IN, 4) => vec![self.hw.r(FBI_PIXELS_IN) as i32],
            (GR_STATS_PIXELS_OUT, 4) => vec![self.hw.r(FBI_PIXELS_OUT) as i32],
            (GR_STATS_POINTS, 4) => vec![self.stats.points as i32],
            (GR_STATS_TRIANGLES_IN, 4) => vec![self.stats.triangles_in as i32],
            (GR_STATS_TRIANGLES_OUT, 4) => vec![self.stats.triangles_drawn as i32],
            (GR_NUM_SWAP_HISTORY_BUFFER, 4) => vec![0],
            (GR_SWAP_HISTORY, 0) => vec![],
            (GR_SUPPORTS_PASSTHRU, 4) => vec![1],
            (GR_TEXTURE_ALIGN, 4) => vec![8],
            (GR_VIDEO_POSITION, 8) => {
                let v = self.hw.r(sst1_regs::addr::V_RETRACE);
                vec![(v & 0xfff) as i32, ((v >> 16) & 0xfff) as i32]
            }
            (GR_VIEWPORT, 16) => vec![
                (vp.ox - vp.hwidth) as i32,
                (vp.oy - vp.hheight) as i32,
                (vp.hwidth * 2.0) as i32,
                (vp.hheight * 2.0) as i32,
            ],
            (GR_WDEPTH_MIN_MAX, 8) => vec![0, 0xffff],
            (GR_ZDEPTH_MIN_MAX, 8) => vec![0xffff, 0],
            _ => return 0,
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

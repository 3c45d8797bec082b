//! A TMU's part of a save state (`sst1_board::state`).
//!
//! Saved: the registers as written, texture memory, the NCC table registers and the
//! expanded tables in use (which lag the registers under [`crate::NccUpdate::OnTextureRegWrite`]),
//! the palette, the S/T/W start and gradient registers, the triangle's base LOD, and 86Box's
//! texture cache ([`crate::TextureCacheKey::Box86`]). That cache is state, not a cache: its
//! key leaves out the format and the NCC tables, so a triangle can read texels decoded
//! under an earlier state (module `box86`), and a board without the entry would decode
//! them anew and draw something else.
//!
//! Rebuilt, not saved: the layout, the combine configuration and the texel decode table
//! (from the registers and tables), the decoded-texel cache (decoded again on first use,
//! giving the same texels), and the span kernels' scratch lanes.

use serde::{Deserialize, Serialize};
use serde_bytes::ByteBuf;

use crate::box86::{Entry, Key, CAPACITY};
use crate::Tmu;

/// One TMU's state, as [`Tmu::save_state`] takes it and [`Tmu::load_state`] puts it back.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct TmuState {
    /// TMU number.
    index: u8,
    /// Texture memory.
    #[serde(with = "serde_bytes")]
    ram: Vec<u8>,
    texture_mode: u32,
    t_lod: u32,
    t_detail: u32,
    tex_base: [u32; 4],
    trex_init: [u32; 2],
    /// The NCC table registers as written.
    ncc_regs: [[u32; 12]; 2],
    /// The two expanded NCC tables in use, 256 RGB triples each.
    #[serde(with = "serde_bytes")]
    ncc: Vec<u8>,
    /// The NCC registers have changed since the tables were expanded.
    ncc_stale: bool,
    /// The palette, 256 RGB triples.
    #[serde(with = "serde_bytes")]
    palette: Vec<u8>,
    /// S, T, W start values and gradients (.32 fixed point).
    start: [i64; 3],
    ddx: [i64; 3],
    ddy: [i64; 3],
    /// Base LOD of the last triangle (8.8).
    lod_base: i32,
    /// 86Box's texture cache: its entries in order, and the next to replace.
    box86: Vec<Box86Entry>,
    box86_next: u32,
}

/// One entry of 86Box's texture cache.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
struct Box86Entry {
    base: u32,
    t_lod: u32,
    palette: u32,
    /// The nine levels' decoded texels (`0xAARRGGBB`, little-endian).
    levels: Vec<ByteBuf>,
    valid: u16,
    span: (u32, u32),
}

/// Why a [`TmuState`] does not fit a TMU: a damaged or forged state.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StateMismatch(pub &'static str);

impl std::fmt::Display for StateMismatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.0)
    }
}

/// The most texels a level `lod` holds (LOD 0 is at most 256x256).
fn max_level_texels(lod: usize) -> usize {
    let side = (256usize >> lod).max(1);
    side * side
}

fn rgb_bytes(table: &[[u8; 3]]) -> Vec<u8> {
    table.iter().flatten().copied().collect()
}

impl Tmu {
    /// The TMU's state, for a save state.
    pub fn save_state(&self) -> TmuState {
        let box86 = self
            .box86
            .entries
            .iter()
            .enumerate()
            .map(|(i, e)| {
                // A lent entry's levels are in the decoded-texel cache for the triangle.
                let (levels, valid) = if self.box86.lent == Some(i) {
                    self.cache.storage()
                } else {
                    (&e.levels, e.valid)
                };
                Box86Entry {
                    base: e.key.base,
                    t_lod: e.key.t_lod,
                    palette: e.key.palette,
                    levels: levels
                        .iter()
                        .map(|l| {
                            ByteBuf::from(
                                l.iter().flat_map(|t| t.to_le_bytes()).collect::<Vec<u8>>(),
                            )
                        })
                        .collect(),
                    valid,
                    span: e.span,
                }
            })
            .collect();
        TmuState {
            index: self.index,
            ram: self.ram.clone(),
            texture_mode: self.texture_mode,
            t_lod: self.t_lod,
            t_detail: self.t_detail,
            tex_base: self.tex_base,
            trex_init: self.trex_init,
            ncc_regs: self.ncc_regs,
            ncc: rgb_bytes(self.ncc.as_flattened()),
            ncc_stale: self.ncc_stale,
            palette: rgb_bytes(&self.palette),
            start: self.stw.rows[crate::stw::START],
            ddx: self.stw.rows[crate::stw::DX],
            ddy: self.stw.rows[crate::stw::DY],
            lod_base: self.lod_base,
            box86,
            box86_next: self.box86.next_victim as u32,
        }
    }

    /// Puts back a state [`Tmu::save_state`] took, on a TMU with the same number and
    /// memory size. Checks every length and index first: on an error the TMU is unchanged.
    pub fn load_state(&mut self, state: TmuState) -> Result<(), StateMismatch> {
        if state.index != self.index {
            return Err(StateMismatch("the TMU number differs"));
        }
        if state.ram.len() != self.ram.len() {
            return Err(StateMismatch(
                "texture memory is not the size of the board's",
            ));
        }
        if state.ncc.len() != 2 * 256 * 3 || state.palette.len() != 256 * 3 {
            return Err(StateMismatch(
                "an NCC table or the palette is not 256 entries",
            ));
        }
        if state.box86.len() > CAPACITY || state.box86_next as usize >= CAPACITY {
            return Err(StateMismatch(
                "86Box's texture cache holds more than 64 entries",
            ));
        }
        let fits = |e: &Box86Entry| {
            e.levels.len() == 9
                && e.levels
                    .iter()
                    .enumerate()
                    .all(|(lod, l)| l.len() % 4 == 0 && l.len() / 4 <= max_level_texels(lod))
        };
        if !state.box86.iter().all(fits) {
            return Err(StateMismatch(
                "a texture of 86Box's texture cache has levels larger than 256x256",
            ));
        }
        let entries = state
            .box86
            .into_iter()
            .map(|e| Entry {
                key: Key {
                    base: e.base,
                    t_lod: e.t_lod,
                    palette: e.palette,
                },
                levels: std::array::from_fn(|lod| {
                    e.levels[lod]
                        .chunks_exact(4)
                        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                        .collect()
                }),
                valid: e.valid,
                span: e.span,
            })
            .collect();
        self.box86.lent = None;
        self.box86.entries = entries;
        self.box86.next_victim = state.box86_next as usize;
        self.cache.clear();
        self.ram = state.ram;
        self.texture_mode = state.texture_mode;
        self.t_lod = state.t_lod;
        self.t_detail = state.t_detail;
        self.tex_base = state.tex_base;
        self.trex_init = state.trex_init;
        self.ncc_regs = state.ncc_regs;
        for (i, rgb) in state.ncc.chunks_exact(3).enumerate() {
            self.ncc[i / 256][i % 256] = [rgb[0], rgb[1], rgb[2]];
        }
        self.ncc_stale = state.ncc_stale;
        for (entry, rgb) in self.palette.iter_mut().zip(state.palette.chunks_exact(3)) {
            *entry = [rgb[0], rgb[1], rgb[2]];
        }
        self.stw.rows[crate::stw::START] = state.start;
        self.stw.rows[crate::stw::DX] = state.ddx;
        self.stw.rows[crate::stw::DY] = state.ddy;
        self.lod_base = state.lod_base;
        // The layout, combine unit and decode table from the registers and tables.
        self.refresh();
        Ok(())
    }
}

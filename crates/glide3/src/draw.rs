//! Vertex layout, triangle setup, points, lines and vertex arrays.
//!
//! Spec section 5 (triangle setup registers: `FvertexAx..`, `Fr`/`FdRdX`/`FdRdY`...,
//! `FtriangleCMD`). Glide 3 on the SST-1 sends the floating-point register versions:
//! vertex coordinates snapped by adding 3 * 2^18 (which leaves 4 fraction bits in the
//! float mantissa), each parameter's start value at vertex A, and its X and Y gradients
//!
//! ```text
//! area = (xa - xb) * (yb - yc) - (xb - xc) * (ya - yb)
//! dpdx = (pa - pb) * ((yb - yc) / area) - (pb - pc) * ((ya - yb) / area)
//! dpdy = (pb - pc) * ((xa - xb) / area) - (pa - pb) * ((xb - xc) / area)
//! ```
//!
//! with the vertices sorted by snapped Y (ties broken the way 3dfx's `_trisetup`
//! does). The reference traces come from a 32-bit x87 build of 3dfx's C `_trisetup`
//! (gxdraw.c), so the rounding follows what that build keeps in 64-bit-significand
//! registers and what it stores as `float` (see the `x87` module):
//!
//! - `x + 3 * 2^18` stays in a register: the area is computed from the UNSNAPPED
//!   positions; only the vertex registers get the snapped (`f32`) values;
//! - the differences, products and the area's difference are extended; the area is
//!   stored as a `float` (`_GlideRoot.pool.temp1`);
//! - `ooa = 1 / area`, the deltas and the scaled deltas (`dxAB * ooa` ...) are
//!   `float`s;
//! - the parameter differences `dpAB = pa - pb`, `dpBC = pb - pc` are `float`s
//!   (test08's W, test20, test28's colours);
//! - each gradient (`dpAB * dyBC - dpBC * dyAB`) is evaluated extended and rounded
//!   once, when stored to its register.
//!
//! Source: 3dfx SST-1 Glide 3 gxdraw.c `_trisetup` (operation order); the rounding
//! points were found against the glide-sdk traces and are verified bit for bit by
//! tests/trisetup_trace.rs (test04 Gouraud, test06 W, test14 Z) and
//! tests/texsetup_trace.rs (7434 console-text triangles: S, T, W, in all 18 traces)
//! and tests/rounding_trace.rs (test08 W, test28 polygon colours).
//! Lines (`line`) work from the snapped positions, which the test02 trace matches.

use crate::aa::{AA_LINES, AA_POINTS, AA_TRIANGLES};
use crate::consts::*;
use crate::hw::{tmu_chip, PACKER_FIX};
use crate::x87::{self, Ext};
use sst1_regs::addr::*;
use sst1_regs::{AlphaLocalSelect, FbzColorPath, FbzMode, FogMode, FogZa};
use std::borrow::Cow;

/// Added to window coordinates so the float keeps exactly 4 fraction bits (12.4).
pub(crate) const SNAP_BIAS: f32 = (3 << 18) as f32;

/// Byte offsets of the packed-ARGB channels inside a `GR_PARAM_PARGB` word
/// (little-endian host).
const PARGB_A: i32 = 3;
const PARGB_R: i32 = 2;
const PARGB_G: i32 = 1;
const PARGB_B: i32 = 0;

/// Distance from a parameter's start register to its d/dX and d/dY registers.
const DPDX: u32 = 0x20;
const DPDY: u32 = 0x40;

/// The vertices a strip or fan keeps for `GR_TRIANGLE_STRIP_CONTINUE` and
/// `GR_TRIANGLE_FAN_CONTINUE`: 3dfx's `gc->vert1`, `gc->vert2`, `gc->vert2_status` and
/// `gc->flip`, shared by strips and fans and kept across every other call
/// (Source: sezero/glide gstrip.c _grDrawVertexList, _grDrawVertexListContinue).
/// 3dfx keeps only the position and the parameters of the data list in use; we keep
/// the whole vertex, which the setup reads the same way.
#[derive(Clone, Debug, Default)]
pub(crate) struct ListTail {
    /// A strip's second-newest vertex, or a fan's centre. Before any list, a vertex of
    /// zeros (3dfx's context starts zeroed); `fetch` reads an empty one as zeros.
    pub v1: Vec<f32>,
    /// The newest vertex; `None` when the last list had fewer than two.
    pub v2: Option<Vec<f32>>,
    /// Whether the next strip triangle is turned.
    pub flip: bool,
}

/// Parameters an iterated triangle needs (3dfx's `STATE_REQUIRES_*`).
mod req {
    pub const IT_DRGB: u32 = 1 << 0;
    pub const IT_ALPHA: u32 = 1 << 1;
    pub const OOZ: u32 = 1 << 2;
    pub const OOW_FBI: u32 = 1 << 3;
    pub const W_TMU0: u32 = 1 << 4;
    pub const ST_TMU0: u32 = 1 << 5;
    pub const W_TMU1: u32 = 1 << 6;
    pub const ST_TMU1: u32 = 1 << 7;
    pub const W_TMU2: u32 = 1 << 8;
    pub const ST_TMU2: u32 = 1 << 9;
}

/// One `grVertexLayout` entry: byte offset in the vertex and whether it is enabled.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Param {
    /// Byte offset in the vertex.
    pub offset: i32,
    /// `GR_PARAM_ENABLE` or `GR_PARAM_DISABLE`.
    pub enabled: bool,
}

/// The vertex layout (`grVertexLayout` state).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct VertexLayout {
    /// `GR_PARAM_XY`.
    pub xy: Param,
    /// `GR_PARAM_Z`.
    pub z: Param,
    /// `GR_PARAM_W`.
    pub w: Param,
    /// `GR_PARAM_Q`.
    pub q: Param,
    /// `GR_PARAM_FOG_EXT` (accepted, unused by the SST-1).
    pub fog: Param,
    /// `GR_PARAM_A`.
    pub a: Param,
    /// `GR_PARAM_RGB`.
    pub rgb: Param,
    /// `GR_PARAM_PARGB`.
    pub pargb: Param,
    /// `GR_PARAM_ST0..ST2`.
    pub st: [Param; 3],
    /// `GR_PARAM_Q0..Q2`.
    pub qn: [Param; 3],
    /// Whether colours come packed (`GR_U8`, after `GR_PARAM_PARGB`) or as floats.
    pub packed_color: bool,
}

/// Largest vertex offset `grVertexLayout` accepts, in bytes.
pub const MAX_VERTEX_OFFSET: i32 = 1024;

/// Whether `grVertexLayout` accepts `offset`: a multiple of 4 in
/// `0..=`[`MAX_VERTEX_OFFSET`].
pub fn offset_ok(offset: i32) -> bool {
    (0..=MAX_VERTEX_OFFSET).contains(&offset) && offset % 4 == 0
}

/// What one setup step sends: a parameter (start + gradients) or a packer write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Entry {
    /// Float parameter at byte offset `off` of the vertex, start register `reg`.
    Float { off: i32, reg: u32 },
    /// Byte `off` of the vertex (packed colour channel) as a float 0..255.
    Byte { off: i32, reg: u32 },
    /// The packer workaround write of 0.0 (between chip-field changes).
    Packer,
}

/// Read the float at byte offset `off` of a vertex (0.0 outside it).
pub(crate) fn fetch(v: &[f32], off: i32) -> f32 {
    usize::try_from(off)
        .ok()
        .filter(|o| o % 4 == 0)
        .and_then(|o| v.get(o / 4))
        .copied()
        .unwrap_or(0.0)
}

/// Read byte `off` of a vertex as a float (0.0 outside it).
pub(crate) fn fetch_byte(v: &[f32], off: i32) -> f32 {
    let Ok(o) = usize::try_from(off) else {
        return 0.0;
    };
    v.get(o / 4)
        .map_or(0.0, |w| f32::from(w.to_bits().to_le_bytes()[o % 4]))
}

pub(crate) fn value(v: &[f32], e: Entry) -> f32 {
    match e {
        Entry::Float { off, .. } => fetch(v, off),
        Entry::Byte { off, .. } => fetch_byte(v, off),
        Entry::Packer => 0.0,
    }
}

/// Orderable key of a float's bits (3dfx flips negative floats' magnitude bits so an
/// integer compare orders them).
fn sort_key(f: f32) -> i32 {
    let i = f.to_bits() as i32;
    if i < 0 {
        i ^ 0x7fff_ffff
    } else {
        i
    }
}

/// `c + SNAP_BIAS` as the x87 holds it (a 64-bit significand: exact for window
/// coordinates); `.to_f32()` of it is the snapped coordinate.
fn biased(c: f32) -> Ext {
    Ext::plus_snap_bias(c)
}

impl crate::Glide {
    /// `_grUpdateParamIndex` + `_grRebuildDataList`: decide which parameters a
    /// triangle carries and in which register order.
    pub(crate) fn update_param_index(&mut self) {
        let st = &self.st;
        let l = &self.layout;
        let mut p = 0u32;
        let path = FbzColorPath(st.fbi.fbz_color_path);
        if path.texture_enable() {
            let m = st.tmu_mask;
            p |= req::OOW_FBI;
            if m & 1 != 0 {
                p |= req::W_TMU0 | req::ST_TMU0;
            }
            if m & 2 != 0 {
                p |= req::W_TMU1 | req::ST_TMU1;
            }
            if m & 4 != 0 {
                p |= req::W_TMU2 | req::ST_TMU2;
            }
        }
        // gglide.c _grUpdateParamIndex: no iterated RGB in delta-0 mode.
        if st.cc_requires_it_rgb && !self.cc_delta0 {
            p |= req::IT_DRGB;
        }
        if st.ac_requires_it_alpha {
            p |= req::IT_ALPHA;
        }
        if matches!(path.cca_localselect(), AlphaLocalSelect::IteratedZ) {
            p |= req::OOZ;
        }
        let fbz = FbzMode(st.fbi.fbz_mode);
        if fbz.enable_depthbuffer() {
            p |= if fbz.wbuffer_select() {
                req::OOW_FBI
            } else {
                req::OOZ
            };
        }
        let fog = FogMode(st.fbi.fog_mode);
        if fog.enable_fog() {
            p |= match fog.fog_za() {
                FogZa::IteratedZ | FogZa::IteratedZAndAlpha => req::OOZ,
                FogZa::IteratedAlpha => req::IT_ALPHA,
                FogZa::FogTable => req::OOW_FBI,
            };
        }
        let window = st.coordinate_space == GR_WINDOW_COORDS;
        if p & req::W_TMU0 != 0 {
            let drop = if window {
                !l.qn[0].enabled
            } else {
                !l.qn[0].enabled && !l.q.enabled
            };
            if drop {
                p &= !req::W_TMU0;
            }
        }
        if p & (req::ST_TMU0 | req::ST_TMU1) == (req::ST_TMU0 | req::ST_TMU1) && !l.st[1].enabled {
            p &= !req::ST_TMU1;
        }
        if p & req::W_TMU1 != 0 {
            // 3dfx's code clears the TMU0 bit here (not TMU1); kept for identical output.
            let drop = if window {
                !l.qn[1].enabled
            } else {
                !l.qn[1].enabled && !l.q.enabled
            };
            if drop {
                p &= !req::W_TMU0;
            }
        }
        if l.packed_color {
            if !l.pargb.enabled {
                p &= !(req::IT_ALPHA | req::IT_DRGB);
            }
        } else {
            if !l.a.enabled {
                p &= !req::IT_ALPHA;
            }
            if !l.rgb.enabled {
                p &= !req::IT_DRGB;
            }
        }
        if !l.z.enabled {
            p &= !req::OOZ;
        }
        if !l.q.enabled {
            p &= !req::OOW_FBI;
        }
        if !window && !l.w.enabled {
            p &= !req::OOW_FBI;
        }
        if !l.st[0].enabled {
            p &= !req::ST_TMU0;
        }
        if !l.st[1].enabled {
            p &= !req::ST_TMU1;
        }
        if !l.qn[0].enabled {
            p &= !req::W_TMU0;
        }
        if !l.qn[1].enabled {
            p &= !req::W_TMU1;
        }
        self.param_index = p;
        self.rebuild_data_list();
    }

    fn rebuild_data_list(&mut self) {
        let p = self.param_index;
        let l = self.layout;
        let window = self.st.coordinate_space == GR_WINDOW_COORDS;
        let mut d: Vec<Entry> = Vec::with_capacity(16);
        if p & req::IT_DRGB != 0 {
            if l.packed_color {
                let o = l.pargb.offset;
                d.push(Entry::Byte {
                    off: o + PARGB_R,
                    reg: F_START_R,
                });
                d.push(Entry::Byte {
                    off: o + PARGB_G,
                    reg: F_START_G,
                });
                d.push(Entry::Byte {
                    off: o + PARGB_B,
                    reg: F_START_B,
                });
            } else {
                let o = l.rgb.offset;
                d.push(Entry::Float {
                    off: o,
                    reg: F_START_R,
                });
                d.push(Entry::Float {
                    off: o + 4,
                    reg: F_START_G,
                });
                d.push(Entry::Float {
                    off: o + 8,
                    reg: F_START_B,
                });
            }
        }
        if p & req::OOZ != 0 {
            d.push(Entry::Float {
                off: l.z.offset,
                reg: F_START_Z,
            });
        }
        if p & req::IT_ALPHA != 0 {
            if l.packed_color {
                d.push(Entry::Byte {
                    off: l.pargb.offset + PARGB_A,
                    reg: F_START_A,
                });
            } else {
                d.push(Entry::Float {
                    off: l.a.offset,
                    reg: F_START_A,
                });
            }
        }
        if p & req::ST_TMU0 != 0 {
            d.push(Entry::Float {
                off: l.st[0].offset,
                reg: F_START_S,
            });
            d.push(Entry::Float {
                off: l.st[0].offset + 4,
                reg: F_START_T,
            });
        }
        if p & req::OOW_FBI != 0 {
            d.push(Entry::Float {
                off: l.q.offset,
                reg: F_START_W,
            });
        }
        let w_source = |qn: Param| {
            if qn.enabled {
                qn.offset
            } else if window {
                l.q.offset
            } else {
                l.w.offset
            }
        };
        // Registers addressed to TMUs only: chip field 0xe (all TMUs) / 0xc (TMU1, 2).
        let all_tmus = tmu_chip(0) | tmu_chip(1) | tmu_chip(2);
        let upper_tmus = tmu_chip(1) | tmu_chip(2);
        if p & req::W_TMU0 != 0 {
            d.push(Entry::Packer);
            d.push(Entry::Float {
                off: w_source(l.qn[0]),
                reg: all_tmus | F_START_W,
            });
        }
        let packer_needed = if p & req::ST_TMU1 != 0 {
            d.push(Entry::Packer);
            d.push(Entry::Float {
                off: l.st[1].offset,
                reg: upper_tmus | F_START_S,
            });
            d.push(Entry::Float {
                off: l.st[1].offset + 4,
                reg: upper_tmus | F_START_T,
            });
            false
        } else {
            true
        };
        if p & req::W_TMU1 != 0 {
            if packer_needed {
                d.push(Entry::Packer);
            }
            d.push(Entry::Float {
                off: w_source(l.qn[1]),
                reg: upper_tmus | F_START_W,
            });
        }
        // A packer write after the last parameter if it went to a TMU-only address.
        if let Some(Entry::Float { reg, .. }) = d.last() {
            if reg & 0x3c00 != 0 {
                d.push(Entry::Packer);
            }
        }
        self.data_list = d;
    }

    pub(crate) fn send_start(&mut self, e: Entry, v: f32) -> Option<u32> {
        match e {
            Entry::Packer => {
                self.hw.wf(PACKER_FIX, 0.0);
                None
            }
            Entry::Float { reg, .. } | Entry::Byte { reg, .. } => {
                self.hw.wf(reg, v);
                Some(reg)
            }
        }
    }

    /// Window-coordinate triangle setup (`_trisetup`). Returns 1 if drawn, 0 if
    /// zero-area (or a vertex position is infinite or NaN), -1 if culled.
    pub(crate) fn trisetup(&mut self, va: &[f32], vb: &[f32], vc: &[f32]) -> i32 {
        let xo = self.layout.xy.offset;
        let finite = |v: &[f32]| fetch(v, xo).is_finite() && fetch(v, xo + 4).is_finite();
        if !(finite(va) && finite(vb) && finite(vc)) {
            // UNVERIFIED: 3dfx's code would send a NaN or infinite area to the chip;
            // we treat such a triangle as degenerate.
            return 0;
        }
        let y = |v: &[f32]| biased(fetch(v, xo + 4));
        // Bit 0 of the cull mode: 1 for GR_CULL_NEGATIVE, 0 for GR_CULL_POSITIVE.
        let mut cull = self.st.cull_mode & 1;
        let key = |v: &[f32]| sort_key(y(v).to_f32());
        let (ka, kb, kc) = (key(va), key(vb), key(vc));
        // Sort by snapped Y; every odd permutation flips the culling sense.
        let (fa, fb, fc) = if ka < kb {
            if kb > kc {
                if ka < kc {
                    cull ^= 1;
                    (va, vc, vb)
                } else {
                    (vc, va, vb)
                }
            } else {
                (va, vb, vc)
            }
        } else if kb < kc {
            if ka < kc {
                cull ^= 1;
                (vb, va, vc)
            } else {
                (vb, vc, va)
            }
        } else {
            cull ^= 1;
            (vc, vb, va)
        };
        let x = |v: &[f32]| biased(fetch(v, xo));
        let (xa, xb, xc) = (x(fa), x(fb), x(fc));
        let (ya, yb, yc) = (y(fa), y(fb), y(fc));
        let dx_ab = xa.sub(xb);
        let dx_bc = xb.sub(xc);
        let dy_ab = ya.sub(yb);
        let dy_bc = yb.sub(yc);
        let area = dx_ab.mul(dy_bc).sub(dx_bc.mul(dy_ab)).to_f32();
        if area.to_bits() & 0x7fff_ffff == 0 {
            return 0;
        }
        if self.st.cull_mode != GR_CULL_DISABLE
            && ((area.to_bits() as i32) ^ ((cull << 31) as i32)) >= 0
        {
            return -1;
        }
        self.flush_state();
        let ooa = x87::reciprocal(area);
        self.hw.wf(F_VERTEX_AX, xa.to_f32());
        self.hw.wf(F_VERTEX_AY, ya.to_f32());
        self.hw.wf(F_VERTEX_BX, xb.to_f32());
        self.hw.wf(F_VERTEX_BY, yb.to_f32());
        self.hw.wf(F_VERTEX_CX, xc.to_f32());
        self.hw.wf(F_VERTEX_CY, yc.to_f32());
        // The deltas and their products with `ooa` are `float` variables; the f32
        // product of two f32 values equals the x87 product stored to a float.
        // UNVERIFIED: whether the deltas are rounded to float before the scaling
        // (they are here) changes no traced value.
        let dx_bc = dx_bc.to_f32() * ooa;
        let dy_ab = dy_ab.to_f32() * ooa;
        let dx_ab = dx_ab.to_f32() * ooa;
        let dy_bc = dy_bc.to_f32() * ooa;
        for i in 0..self.data_list.len() {
            let e = self.data_list[i];
            let pa = value(fa, e);
            let Some(reg) = self.send_start(e, pa) else {
                continue;
            };
            let (pb, pc) = (value(fb, e), value(fc, e));
            self.hw
                .wf(reg + DPDX, x87::gradient((pa, pb), dy_bc, (pb, pc), dy_ab));
            self.hw
                .wf(reg + DPDY, x87::gradient((pb, pc), dx_ab, (pa, pb), dx_bc));
        }
        self.hw.wf(F_TRIANGLE_CMD, area);
        self.stats.triangles_drawn += 1;
        1
    }

    /// Clip-coordinate triangle: project x, y (and the parameters that need 1/w) with
    /// the viewport, then run window-coordinate setup.
    /// UNVERIFIED: 3dfx's `_grVpDrawTriangle` scales parameters inside its own setup;
    /// no glide-sdk trace exercises clip coordinates, so the operation order here is
    /// ours.
    pub(crate) fn vp_triangle(&mut self, va: &[f32], vb: &[f32], vc: &[f32]) -> i32 {
        let a = self.project(va);
        let b = self.project(vb);
        let c = self.project(vc);
        self.trisetup(&a, &b, &c)
    }

    /// Project one clip-coordinate vertex to window coordinates, in a copy of the
    /// vertex laid out as the window-coordinate path expects.
    pub(crate) fn project(&self, v: &[f32]) -> Vec<f32> {
        let l = &self.layout;
        let vp = self.st.viewport;
        let oow = 1.0 / fetch(v, l.w.offset);
        let mut out = v.to_vec();
        let mut put = |off: i32, val: f32| {
            if let Some(slot) = usize::try_from(off).ok().and_then(|o| out.get_mut(o / 4)) {
                *slot = val;
            }
        };
        put(l.xy.offset, fetch(v, l.xy.offset) * oow * vp.hwidth + vp.ox);
        put(
            l.xy.offset + 4,
            fetch(v, l.xy.offset + 4) * oow * vp.hheight + vp.oy,
        );
        if l.z.enabled {
            put(l.z.offset, fetch(v, l.z.offset) * oow * vp.hdepth + vp.oz);
        }
        if !l.packed_color {
            if l.rgb.enabled {
                for k in 0..3 {
                    put(l.rgb.offset + 4 * k, fetch(v, l.rgb.offset + 4 * k) * 255.0);
                }
            }
            if l.a.enabled {
                put(l.a.offset, fetch(v, l.a.offset) * 255.0);
            }
        }
        for t in 0..2 {
            if l.st[t].enabled {
                let scale = self.st.tmu.get(t).map_or([256.0; 2], |c| c.st_scale);
                put(l.st[t].offset, fetch(v, l.st[t].offset) * oow * scale[0]);
                put(
                    l.st[t].offset + 4,
                    fetch(v, l.st[t].offset + 4) * oow * scale[1],
                );
            }
        }
        if l.q.enabled {
            put(l.q.offset, fetch(v, l.q.offset) * oow);
        } else {
            put(l.q.offset, oow);
        }
        out
    }

    /// One triangle in the current coordinate space.
    pub(crate) fn triangle(&mut self, a: &[f32], b: &[f32], c: &[f32]) {
        self.stats.triangles_in += 1;
        if self.st.coordinate_space == GR_WINDOW_COORDS {
            self.trisetup(a, b, c);
        } else {
            self.vp_triangle(a, b, c);
        }
    }

    /// `_grDrawPoints` (window coordinates): a one-pixel triangle at the pixel centre.
    pub(crate) fn point(&mut self, v: &[f32]) {
        self.flush_state();
        let v = if self.st.coordinate_space == GR_WINDOW_COORDS {
            v.to_vec()
        } else {
            self.project(v)
        };
        let v = v.as_slice();
        if self.st.smooth_mode & AA_POINTS != 0 {
            self.aa_point(v);
            return;
        }
        let xo = self.layout.xy.offset;
        // Adding 3 * 2^22 - 0.5 truncates to an integer (round-to-nearest on x - 0.5).
        let bias = (3u32 << 22) as f32 - 0.5;
        let fx = fetch(v, xo) + bias;
        let fy = fetch(v, xo + 4) + bias;
        let mut x = (fx.to_bits() as i32).wrapping_shl(4) as u32;
        x = x.wrapping_add(8);
        let mut y = (fy.to_bits() as i32).wrapping_shl(4) as u32;
        self.hw.w(VERTEX_AX, x);
        y = y.wrapping_add(8);
        self.hw.w(VERTEX_AY, y);
        x = x.wrapping_add(8);
        self.hw.w(VERTEX_BX, x);
        self.hw.w(VERTEX_BY, y);
        y = y.wrapping_add(8);
        self.hw.w(VERTEX_CX, x);
        self.hw.w(VERTEX_CY, y);
        for i in 0..self.data_list.len() {
            let e = self.data_list[i];
            let val = value(v, e);
            self.send_start(e, val);
        }
        self.hw.w(TRIANGLE_CMD, 1);
        self.stats.points += 1;
    }

    /// `_grDrawLineStrip` for one segment (window coordinates): two half-pixel-wide
    /// triangles along the major axis.
    pub(crate) fn line(&mut self, a: &[f32], b: &[f32]) {
        self.flush_state();
        let (pa, pb);
        let (a, b) = if self.st.coordinate_space == GR_WINDOW_COORDS {
            (a, b)
        } else {
            pa = self.project(a);
            pb = self.project(b);
            (pa.as_slice(), pb.as_slice())
        };
        if self.st.smooth_mode & AA_LINES != 0 {
            self.aa_line(a, b);
            return;
        }
        let xo = self.layout.xy.offset;
        let (mut a, mut b) = (a, b);
        let mut xa = fetch(a, xo) + SNAP_BIAS;
        let mut xb = fetch(b, xo) + SNAP_BIAS;
        let mut ya = fetch(a, xo + 4) + SNAP_BIAS;
        let mut yb = fetch(b, xo + 4) + SNAP_BIAS;
        let mut ady = yb - ya;
        if (ady.to_bits() as i32) < 0 {
            std::mem::swap(&mut a, &mut b);
            ady = f32::from_bits(ady.to_bits() ^ 0x8000_0000);
            std::mem::swap(&mut xa, &mut xb);
            std::mem::swap(&mut ya, &mut yb);
        }
        let dx = f32::from_bits((xb - xa).to_bits() & 0x7fff_ffff);
        self.stats.lines += 1;
        if dx.to_bits() >= ady.to_bits() {
            if dx.to_bits() == 0 {
                return;
            }
            let m = 1.0f32 / dx;
            self.hw.wf(F_VERTEX_AX, xa);
            self.hw.wf(F_VERTEX_BX, xb);
            self.hw.wf(F_VERTEX_CX, xb);
            self.hw.wf(F_VERTEX_AY, ya - 0.5);
            self.hw.wf(F_VERTEX_BY, yb - 0.5);
            self.hw.wf(F_VERTEX_CY, yb + 0.5);
            self.line_params(a, b, m, true);
            self.hw.wf(F_TRIANGLE_CMD, dx);
            self.hw.wf(F_VERTEX_BX, xa);
            self.hw.wf(F_VERTEX_BY, ya + 0.5);
            self.hw.wf(F_TRIANGLE_CMD, -dx);
        } else {
            let m = 1.0f32 / ady;
            self.hw.wf(F_VERTEX_AY, ya);
            self.hw.wf(F_VERTEX_BY, yb);
            self.hw.wf(F_VERTEX_CY, yb);
            self.hw.wf(F_VERTEX_AX, xa - 0.5);
            self.hw.wf(F_VERTEX_BX, xb - 0.5);
            self.hw.wf(F_VERTEX_CX, xb + 0.5);
            self.line_params(a, b, m, false);
            self.hw.w(TRIANGLE_CMD, 0xffff_ffff);
            self.hw.wf(F_VERTEX_BX, xa + 0.5);
            self.hw.wf(F_VERTEX_BY, ya);
            self.hw.w(TRIANGLE_CMD, 1);
        }
    }

    fn line_params(&mut self, a: &[f32], b: &[f32], m: f32, x_major: bool) {
        for i in 0..self.data_list.len() {
            let e = self.data_list[i];
            let pa = value(a, e);
            let Some(reg) = self.send_start(e, pa) else {
                continue;
            };
            // `dp = pb - pa` is stored to a float variable, then `dp * m` is rounded
            // once (gdraw.c `_grDrawLineStrip`). test02's lines match with or without
            // the rounding of `dp`; it follows the source and test08's triangles.
            let dp = x87::difference(value(b, e), pa);
            let dp = (f64::from(dp) * f64::from(m)) as f32;
            if x_major {
                self.hw.wf(reg + DPDX, dp);
                self.hw.wf(reg + DPDY, 0.0);
            } else {
                self.hw.wf(reg + DPDX, 0.0);
                self.hw.wf(reg + DPDY, dp);
            }
        }
    }

    /// Draw `n` vertices as `GR_POINTS`, `GR_LINES`, `GR_LINE_STRIP`, `GR_TRIANGLES`,
    /// strips, fans or polygons (`grDrawVertexArray`). `at(i)` gives vertex `i`; each is
    /// asked for once, in order, and at most three are held at a time, so memory does not
    /// grow with `n`.
    pub(crate) fn draw_list<'v>(
        &mut self,
        mode: u32,
        n: usize,
        mut at: impl FnMut(usize) -> Cow<'v, [f32]>,
    ) {
        let aa = self.st.smooth_mode & AA_TRIANGLES != 0;
        match mode {
            GR_POINTS => (0..n).for_each(|i| self.point(&at(i))),
            GR_LINE_STRIP if n > 0 => {
                let mut prev = at(0);
                for i in 1..n {
                    let next = at(i);
                    self.line(&prev, &next);
                    prev = next;
                }
            }
            GR_LINES => (0..n / 2).for_each(|i| {
                let (a, b) = (at(2 * i), at(2 * i + 1));
                self.line(&a, &b);
            }),
            GR_TRIANGLES => (0..n / 3).for_each(|i| {
                let (a, b, c) = (at(3 * i), at(3 * i + 1), at(3 * i + 2));
                if aa {
                    self.aa_triangle(&a, &b, &c, [true; 3]);
                } else {
                    self.triangle(&a, &b, &c);
                }
            }),
            // Antialiased polygons: the fan with only the perimeter edges antialiased.
            // Source: 3dfx's Glide 3 for the Voodoo 2 (cvg, `_grAADrawVertexList`)
            // antialiases polygon outlines; UNVERIFIED for the SST-1 port, whose
            // grDrawVertexArray leaves strips, fans and polygons aliased.
            GR_POLYGON if aa => {
                if n < 3 {
                    return;
                }
                let center = at(0);
                let mut prev = at(1);
                for i in 1..n - 1 {
                    let next = at(i + 1);
                    self.aa_triangle(&center, &prev, &next, [i == 1, true, i + 2 == n]);
                    prev = next;
                }
            }
            GR_TRIANGLE_STRIP => self.new_strip(n, at),
            GR_TRIANGLE_FAN | GR_POLYGON => self.new_fan(n, at),
            GR_TRIANGLE_STRIP_CONTINUE => self.continue_strip(n, at),
            GR_TRIANGLE_FAN_CONTINUE => self.continue_fan(n, at),
            _ => {}
        }
    }

    /// `_grDrawVertexList` for a strip: the triangles of `n` vertices, every other one
    /// turned; the last two vertices (or the only one) and the turn are kept for a
    /// `GR_TRIANGLE_STRIP_CONTINUE`. Source: sezero/glide gstrip.c _grDrawVertexList.
    fn new_strip<'v>(&mut self, n: usize, mut at: impl FnMut(usize) -> Cow<'v, [f32]>) {
        self.list_tail.v2 = None;
        self.flush_state();
        let mut window: Vec<Cow<'v, [f32]>> = Vec::with_capacity(3);
        let mut flip = false;
        for i in 0..n {
            window.push(at(i));
            if let [a, b, c] = window.as_slice() {
                if flip {
                    self.triangle(b, a, c);
                } else {
                    self.triangle(a, b, c);
                }
                flip = !flip;
                window.remove(0);
            }
        }
        self.list_tail.flip = flip;
        // No vertex leaves the kept first vertex as it was.
        let mut kept = window.into_iter();
        if let Some(v1) = kept.next() {
            self.list_tail.v1 = v1.into_owned();
        }
        self.list_tail.v2 = kept.next().map(Cow::into_owned);
    }

    /// `_grDrawVertexList` for a fan (and a polygon): the triangles around the first
    /// vertex; the centre and the newest vertex are kept for a
    /// `GR_TRIANGLE_FAN_CONTINUE`. Source: sezero/glide gstrip.c _grDrawVertexList.
    fn new_fan<'v>(&mut self, n: usize, mut at: impl FnMut(usize) -> Cow<'v, [f32]>) {
        self.list_tail.v2 = None;
        self.flush_state();
        // UNVERIFIED: with no vertex 3dfx's code keeps the pointer array's first entry
        // (reading past the array); we keep the centre as it was.
        if n == 0 {
            return;
        }
        let center = at(0);
        let mut last = (n >= 2).then(|| at(1));
        for i in 2..n {
            let next = at(i);
            if let Some(l) = &last {
                self.triangle(&center, l, &next);
            }
            last = Some(next);
        }
        self.list_tail.v1 = center.into_owned();
        self.list_tail.v2 = last.map(Cow::into_owned);
    }

    /// `_grDrawVertexListContinue` for a strip: the strip goes on from the two kept
    /// vertices (a list of one vertex kept only one: the first vertex given becomes
    /// the second). Source: sezero/glide gstrip.c _grDrawVertexListContinue, with its
    /// quirks: the first two triangles go through the mixed-layout setup, which counts
    /// each drawn triangle twice in `GR_STATS_TRIANGLES_OUT`; and when the call draws
    /// three triangles or more the kept turn is not updated, so the next continuation
    /// starts with the turn this one started with.
    fn continue_strip<'v>(&mut self, n: usize, mut at: impl FnMut(usize) -> Cow<'v, [f32]>) {
        let mut flip = self.list_tail.flip;
        let mut i = 0;
        let v2 = match self.list_tail.v2.take() {
            Some(v2) => v2,
            // UNVERIFIED: 3dfx's code reads a vertex even when none is given; we keep
            // the strip as it was.
            None if n == 0 => return,
            None => {
                i = 1;
                at(0).into_owned()
            }
        };
        if i == n {
            self.list_tail.v2 = Some(v2);
            return;
        }
        let v1 = std::mem::take(&mut self.list_tail.v1);
        let c = at(i);
        if flip {
            self.mixed_triangle(&v2, &v1, &c, false);
        } else {
            self.mixed_triangle(&v1, &v2, &c, false);
        }
        flip = !flip;
        if i + 1 == n {
            self.list_tail.v1 = v2;
            self.list_tail.v2 = Some(c.into_owned());
            self.list_tail.flip = flip;
            return;
        }
        let d = at(i + 1);
        if flip {
            self.mixed_triangle(&c, &v2, &d, false);
        } else {
            self.mixed_triangle(&v2, &c, &d, false);
        }
        flip = !flip;
        if i + 2 == n {
            self.list_tail.v1 = c.into_owned();
            self.list_tail.v2 = Some(d.into_owned());
            self.list_tail.flip = flip;
            return;
        }
        let mut window = vec![c, d];
        for k in i + 2..n {
            window.push(at(k));
            if let [a, b, c] = window.as_slice() {
                if flip {
                    self.triangle(b, a, c);
                } else {
                    self.triangle(a, b, c);
                }
            }
            flip = !flip;
            window.remove(0);
        }
        let mut kept = window.into_iter();
        if let (Some(a), Some(b)) = (kept.next(), kept.next()) {
            self.list_tail.v1 = a.into_owned();
            self.list_tail.v2 = Some(b.into_owned());
        }
    }

    /// `_grDrawVertexListContinue` for a fan: the fan goes on around the kept centre
    /// from the kept newest vertex (a list of one vertex kept only the centre: the
    /// first vertex given becomes the newest). Source: sezero/glide gstrip.c
    /// _grDrawVertexListContinue, with its quirks: every triangle goes through the
    /// mixed-layout setup (counted twice in `GR_STATS_TRIANGLES_OUT`), and the first
    /// one through its window-coordinate version whatever the coordinate space.
    fn continue_fan<'v>(&mut self, n: usize, mut at: impl FnMut(usize) -> Cow<'v, [f32]>) {
        let mut i = 0;
        let v2 = match self.list_tail.v2.take() {
            Some(v2) => v2,
            // UNVERIFIED: as for strips, no vertex given keeps the fan as it was.
            None if n == 0 => return,
            None => {
                i = 1;
                at(0).into_owned()
            }
        };
        if i == n {
            self.list_tail.v2 = Some(v2);
            return;
        }
        let center = std::mem::take(&mut self.list_tail.v1);
        let mut last = at(i);
        self.mixed_triangle(&center, &v2, &last, true);
        for k in i + 1..n {
            let next = at(k);
            self.mixed_triangle(&center, &last, &next, false);
            last = next;
        }
        self.list_tail.v1 = center;
        self.list_tail.v2 = Some(last.into_owned());
    }

    /// A triangle through 3dfx's `_trisetup_mixed_datalist` (or its clip-coordinate
    /// `_vp_` version unless `window`): the same setup as `grDrawTriangle`, but a
    /// drawn triangle is counted twice in `GR_STATS_TRIANGLES_OUT`.
    /// Source: sezero/glide gstrip.c _trisetup_mixed_datalist (`trisDrawn++` twice).
    fn mixed_triangle(&mut self, a: &[f32], b: &[f32], c: &[f32], window: bool) {
        self.stats.triangles_in += 1;
        let drawn = if window || self.st.coordinate_space == GR_WINDOW_COORDS {
            self.trisetup(a, b, c)
        } else {
            self.vp_triangle(a, b, c)
        };
        if drawn == 1 {
            self.stats.triangles_drawn += 1;
        }
    }

    /// An antialiased triangle in the current coordinate space; `edges` says which of
    /// a-b, b-c, c-a get antialiased.
    pub(crate) fn aa_triangle(&mut self, a: &[f32], b: &[f32], c: &[f32], edges: [bool; 3]) {
        self.stats.triangles_in += 1;
        if self.st.coordinate_space == GR_WINDOW_COORDS {
            self.aa_triangle_window(a, b, c, edges);
        } else {
            let (a, b, c) = (self.project(a), self.project(b), self.project(c));
            self.aa_triangle_window(&a, &b, &c, edges);
        }
    }
}

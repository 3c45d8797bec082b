//! The `glide` target: a program of calls to every entry point of libglide3's C ABI,
//! with hostile values (out-of-range enums, sizes, counts, coordinates, NaN and infinite
//! floats, forged saved-state buffers, bad files) but memory that honours the Glide
//! contract (every pointer covers what the API says it must). No call may panic (a
//! panic reaches the error callback as "internal error", which fails the case), crash or
//! hang. The input's bytes seed the program; each case runs `CALLS_PER_CASE` (40) calls in
//! a fresh session.

use crate::rng::Rng;
use glide::consts::*;
use glide3::*;
use std::ffi::{c_char, c_void, CStr};
use std::sync::Mutex;

extern "C" {
    fn free(p: *mut c_void);
}

/// Calls of one case, in a fresh session.
const CALLS_PER_CASE: usize = 40;

/// What the error callback saw that it must never see.
static INTERNAL: Mutex<Vec<String>> = Mutex::new(Vec::new());

unsafe extern "C" fn on_error(msg: *const c_char, _fatal: FxBool) {
    // SAFETY: libglide3 passes a NUL-terminated string.
    let msg = unsafe { CStr::from_ptr(msg) }.to_string_lossy();
    if msg.contains("internal error") {
        INTERNAL
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .push(msg.into_owned());
    }
}

/// The harness's generator, with the argument shapes the calls need.
struct Gen(Rng);

impl Gen {
    fn next(&mut self) -> u64 {
        self.0.next_u64()
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n.max(1)
    }
    fn chance(&mut self, one_in: u64) -> bool {
        self.below(one_in) == 0
    }
    /// An integer argument: mostly small (valid enum ranges), sometimes extreme.
    fn int(&mut self) -> u32 {
        match self.below(8) {
            0 => [0, 1, 2, 3, 0xff, 0x100, 0x7fff_ffff, 0x8000_0000, u32::MAX]
                [self.below(9) as usize],
            1 => self.next() as u32,
            2 => self.below(0x10000) as u32,
            _ => self.below(16) as u32,
        }
    }
    fn i(&mut self) -> i32 {
        self.int() as i32
    }
    /// A float argument: ordinary, edge or non-finite.
    fn float(&mut self) -> f32 {
        match self.below(10) {
            0 => [
                0.0,
                -0.0,
                1.0,
                -1.0,
                f32::NAN,
                f32::INFINITY,
                f32::NEG_INFINITY,
                f32::MAX,
                f32::MIN_POSITIVE,
                1e-30,
                4096.0,
            ][self.below(11) as usize],
            1 => f32::from_bits(self.next() as u32),
            _ => (self.below(2_000_000) as f32) / 1000.0 - 300.0,
        }
    }
    fn byte(&mut self) -> u8 {
        self.next() as u8
    }
}

/// Memory the calls point into, each buffer as large as the contract of the calls that
/// use it asks.
struct Arena {
    /// 64 vertices of 1040 bytes (layout offsets reach 1024, plus 12 bytes of RGB).
    vertices: Vec<f32>,
    /// A mipmap of any size: 256x256 16-bit texels down to 1x1, and room to spare.
    texels: Vec<u8>,
    /// A palette or NCC table (`GuTexTable`: 1024 bytes), and gamma tables.
    table: Vec<u32>,
    /// `GR_GLIDE_STATE_SIZE` / `GR_GLIDE_VERTEXLAYOUT_SIZE` buffers, last saves kept.
    state: Vec<u8>,
    layout: Vec<u8>,
    /// `.3df` files to load.
    files: Vec<std::ffi::CString>,
}

/// Calls `$f` with the values already evaluated into the tuple `$args` (so that the
/// report shows exactly what was passed).
macro_rules! paste_call {
    ($f:ident, $args:ident $(,)?) => {
        $f()
    };
    ($f:ident, $args:ident, $a0:expr) => {
        $f($args.0)
    };
    ($f:ident, $args:ident, $a0:expr, $a1:expr) => {
        $f($args.0, $args.1)
    };
    ($f:ident, $args:ident, $a0:expr, $a1:expr, $a2:expr) => {
        $f($args.0, $args.1, $args.2)
    };
    ($f:ident, $args:ident, $a0:expr, $a1:expr, $a2:expr, $a3:expr) => {
        $f($args.0, $args.1, $args.2, $args.3)
    };
    ($f:ident, $args:ident, $a0:expr, $a1:expr, $a2:expr, $a3:expr, $a4:expr) => {
        $f($args.0, $args.1, $args.2, $args.3, $args.4)
    };
    ($f:ident, $args:ident, $a0:expr, $a1:expr, $a2:expr, $a3:expr, $a4:expr, $a5:expr, $a6:expr) => {
        $f(
            $args.0, $args.1, $args.2, $args.3, $args.4, $args.5, $args.6,
        )
    };
}

const VERTEX_WORDS: usize = 260;

struct Fuzz {
    rng: Gen,
    mem: Arena,
}

impl Fuzz {
    fn vertex(&mut self) -> *const c_void {
        let i = self.rng.below(64) as usize;
        self.mem.vertices[i * VERTEX_WORDS..].as_ptr() as *const c_void
    }

    fn scramble_vertices(&mut self) {
        for v in self.mem.vertices.iter_mut() {
            *v = match self.rng.below(12) {
                0 => f32::from_bits(self.rng.next() as u32),
                1 => [f32::NAN, f32::INFINITY, 1e30, -1e30, 0.0][self.rng.below(5) as usize],
                _ => self.rng.below(1400) as f32 - 200.0 + self.rng.below(1000) as f32 / 1000.0,
            };
        }
    }

    /// A TMU (0-3, of 1 on the board), a start address (up to 5 MiB, past the 4 MiB of
    /// texture memory) and an even/odd mask (0-4).
    fn texture_target(&mut self) -> (i32, u32, u32) {
        (
            self.rng.i() % 4,
            self.rng.int() % (5 << 20),
            self.rng.int() % 5,
        )
    }

    fn tex_info(&mut self) -> GrTexInfo {
        GrTexInfo {
            small_lod_log2: self.rng.below(12) as i32 - 2,
            large_lod_log2: self.rng.below(12) as i32 - 2,
            aspect_ratio_log2: self.rng.below(11) as i32 - 5,
            format: self.rng.below(20) as i32,
            data: self.mem.texels.as_mut_ptr() as *mut c_void,
        }
    }

    /// One random call; returns what it did, for the failure report.
    fn call(&mut self) -> String {
        let r = &mut self.rng;
        macro_rules! c {
            ($f:ident($($a:expr),*)) => {{
                let args = ($($a,)*);
                #[allow(unused_unsafe)]
                let _ = unsafe { paste_call!($f, args, $($a),*) };
                format!("{}{:?}", stringify!($f), args)
            }};
        }
        // Integer and float state calls: (name, arity) dispatched by index.
        match r.below(100) {
            0 => c!(grAlphaBlendFunction(r.i(), r.i(), r.i(), r.i())),
            1 => c!(grAlphaCombine(r.i(), r.i(), r.i(), r.i(), r.i())),
            2 => c!(grAlphaControlsITRGBLighting(r.i())),
            3 => c!(grAlphaTestFunction(r.i())),
            4 => c!(grAlphaTestReferenceValue(r.byte())),
            5 => c!(grColorCombine(r.i(), r.i(), r.i(), r.i(), r.i())),
            6 => c!(grChromakeyMode(r.i())),
            7 => c!(grChromakeyValue(r.int())),
            8 => c!(grChromaRangeExt(r.int(), r.int(), r.int())),
            9 => c!(grClipWindow(r.int(), r.int(), r.int(), r.int())),
            10 => c!(grColorMask(r.i(), r.i())),
            11 => c!(grConstantColorValue(r.int())),
            12 => c!(grCullMode(r.i())),
            13 => c!(grDepthBiasLevel(r.i())),
            14 => c!(grDepthBufferFunction(r.i())),
            15 => c!(grDepthBufferMode(r.i())),
            16 => c!(grDepthMask(r.i())),
            17 => c!(grDitherMode(r.i())),
            18 => c!(grFogColorValue(r.int())),
            19 => c!(grFogMode(r.i())),
            20 => c!(grRenderBuffer(r.i())),
            21 => c!(grEnable(r.int())),
            22 => c!(grDisable(r.int())),
            23 => c!(grCoordinateSpace(r.int())),
            24 => c!(grDepthRange(r.float(), r.float())),
            25 => c!(grViewport(r.i(), r.i(), r.i(), r.i())),
            26 => c!(grLfbConstantAlpha(r.byte())),
            27 => c!(grLfbConstantDepth(r.int())),
            28 => c!(grLfbWriteColorFormat(r.i())),
            29 => c!(grLfbWriteColorSwizzle(r.i(), r.i())),
            30 => {
                // Mostly offsets grVertexLayout accepts, so drawing reads them.
                let offset = if r.chance(4) {
                    r.i()
                } else {
                    4 * r.below(257) as i32
                };
                c!(grVertexLayout(r.int(), offset, r.int() & 1))
            }
            31 => c!(guGammaCorrectionRGB(r.float(), r.float(), r.float())),
            32 => c!(grTexClampMode(r.i(), r.i(), r.i())),
            33 => c!(grTexCombine(
                r.i(),
                r.i(),
                r.i(),
                r.i(),
                r.i(),
                r.i(),
                r.i()
            )),
            34 => c!(grTexDetailControl(r.i(), r.i(), r.byte(), r.float())),
            35 => c!(grTexFilterMode(r.i(), r.i(), r.i())),
            36 => c!(grTexLodBiasValue(r.i(), r.float())),
            37 => c!(grTexMipMapMode(r.i(), r.i(), r.i())),
            38 => c!(grTexMultibase(r.i(), r.i())),
            39 => c!(grTexNCCTable(r.int())),
            40 => c!(grBufferClear(r.int(), r.byte(), r.int())),
            41 => c!(grBufferSwap(r.int() % 4)),
            42 => c!(grSstOrigin(r.i())),
            43 => c!(grSstSelect(r.i())),
            44 => c!(grReset(r.int())),
            45 => c!(grTexMinAddress(r.i())),
            46 => c!(grTexMaxAddress(r.i())),
            47 => c!(grTexCalcMemRequired(r.i(), r.i(), r.i(), r.i())),
            48 => {
                let mut out = [0i32; 64];
                let len = r.below(80) as u32;
                let pname = r.int();
                // SAFETY: `out` holds 256 bytes, more than any plength asked here.
                unsafe { grGet(pname, len, out.as_mut_ptr()) };
                format!("grGet({pname:#x}, {len})")
            }
            49 => {
                let p = r.int();
                let s = grGetString(p);
                // SAFETY: a NUL-terminated static string.
                assert!(!unsafe { CStr::from_ptr(s) }.to_bytes().is_empty());
                format!("grGetString({p:#x})")
            }
            50 => c!(guFogTableIndexToW(r.i())),
            51 => c!(grSplash(
                r.float(),
                r.float(),
                r.float(),
                r.float(),
                r.int()
            )),
            52 => c!(grBufferNumPending()),
            53 => c!(grFinish()),
            54 => c!(grFlush()),
            55 => {
                let (res, refresh, fmt, origin) = (r.i() % 20, r.i(), r.i(), r.i() % 3);
                let (nc, na) = (r.i() % 4, r.i() % 3);
                grSstWinOpen(0, res, refresh, fmt, origin, nc, na);
                format!("grSstWinOpen({res}, {refresh}, {fmt}, {origin}, {nc}, {na})")
            }
            56 => c!(grSstWinClose(r.int())),
            57 => c!(grSelectContext(r.int())),
            58 => {
                let mut v = [0 as c_char; 80];
                // SAFETY: an 80-byte buffer.
                unsafe { grGlideGetVersion(v.as_mut_ptr()) };
                "grGlideGetVersion".into()
            }
            _ => self.call_with_memory(),
        }
    }

    /// Calls that take pointers.
    fn call_with_memory(&mut self) -> String {
        match self.rng.below(27) {
            0 => {
                let p = self.vertex();
                // SAFETY: a vertex of the arena.
                unsafe { grDrawPoint(p) };
                "grDrawPoint".into()
            }
            1 => {
                let (a, b) = (self.vertex(), self.vertex());
                // SAFETY: vertices of the arena.
                unsafe { grDrawLine(a, b) };
                "grDrawLine".into()
            }
            2 | 3 | 23 | 24 => {
                let (a, b, c) = (self.vertex(), self.vertex(), self.vertex());
                // SAFETY: vertices of the arena.
                unsafe { grDrawTriangle(a, b, c) };
                "grDrawTriangle".into()
            }
            4 => {
                let (a, b, c) = (self.vertex(), self.vertex(), self.vertex());
                let e = (self.rng.i(), self.rng.i(), self.rng.i());
                // SAFETY: vertices of the arena.
                unsafe { grAADrawTriangle(a, b, c, e.0, e.1, e.2) };
                "grAADrawTriangle".into()
            }
            5 => {
                let n = self.rng.below(40) as u32;
                let ptrs: Vec<*const c_void> = (0..n).map(|_| self.vertex()).collect();
                let mode = self.rng.int() % 12;
                // SAFETY: n vertex pointers into the arena.
                unsafe { grDrawVertexArray(mode, n, ptrs.as_ptr()) };
                format!("grDrawVertexArray({mode}, {n})")
            }
            6 => {
                // Up to 64 vertices of 1040 bytes: whatever stride, within the arena.
                let stride = [0, 4, 8, 28, 1040][self.rng.below(5) as usize];
                let n = if stride == 0 {
                    self.rng.int()
                } else {
                    self.rng.below(64) as u32
                };
                let mode = self.rng.int() % 12;
                let p = self.mem.vertices.as_ptr() as *const c_void;
                // SAFETY: n vertices `stride` bytes apart in the arena (or none read).
                unsafe { grDrawVertexArrayContiguous(mode, n, p, stride) };
                format!("grDrawVertexArrayContiguous({mode}, {n}, {stride})")
            }
            7 => {
                self.scramble_vertices();
                "scramble vertices".into()
            }
            8 => {
                let mut info = GrLfbInfo {
                    size: std::mem::size_of::<GrLfbInfo>() as i32,
                    lfb_ptr: std::ptr::null_mut(),
                    stride_in_bytes: 0,
                    write_mode: 0,
                    origin: 0,
                };
                let (ty, buf, mode, origin) = (
                    self.rng.int() % 0x22,
                    self.rng.i() % 4,
                    self.rng.i() % 0x100,
                    self.rng.i() % 2,
                );
                let pipe = self.rng.i();
                // SAFETY: a GrLfbInfo.
                let ok = unsafe { grLfbLock(ty, buf, mode, origin, pipe, &mut info) };
                if ok != 0 && ty & 1 == 1 {
                    // Write inside the locked buffer: 1024 rows of the stride.
                    for _ in 0..self.rng.below(64) {
                        let y = self.rng.below(1024) as usize;
                        let x = self.rng.below(u64::from(info.stride_in_bytes) / 4) as usize;
                        let words = info.lfb_ptr as *mut u32;
                        let at = y * info.stride_in_bytes as usize / 4 + x;
                        // SAFETY: inside the 1024 x stride bytes a lock hands out.
                        unsafe { words.add(at).write(self.rng.next() as u32) };
                    }
                }
                format!("grLfbLock({ty:#x}, {buf}, {mode:#x}, {origin}) = {ok}")
            }
            9 => {
                let (ty, buf) = (self.rng.int() % 0x22, self.rng.i() % 4);
                grLfbUnlock(ty, buf);
                format!("grLfbUnlock({ty:#x}, {buf})")
            }
            10 | 11 => {
                let big = self.rng.chance(8);
                let pick = |r: &mut Gen| {
                    if big {
                        r.int()
                    } else {
                        r.below(1100) as u32
                    }
                };
                let (x, y, w, h) = (
                    pick(&mut self.rng),
                    pick(&mut self.rng),
                    pick(&mut self.rng),
                    pick(&mut self.rng),
                );
                let fmt = self.rng.int() % 0x10;
                let pad = self.rng.below(8) as usize * 2;
                // A stride that covers the row, or 0 (every row the same); the data
                // covers h rows of it, as far as the LFB window can take them.
                let (cw, ch) = (w.min(1024) as usize, h.min(1024) as usize);
                let stride = if self.rng.chance(4) { 0 } else { cw * 4 + pad };
                let data = vec![0x5au8; stride * ch + cw * 4 + 16];
                let (buf, pipe) = (self.rng.i() % 4, self.rng.i());
                // The C call's h rows of `stride` bytes: only the clipped part is read,
                // and the arena covers it (rows past 1024 never are).
                // SAFETY: see above.
                let ok = unsafe {
                    grLfbWriteRegion(
                        buf,
                        x,
                        y,
                        fmt,
                        w,
                        h,
                        pipe,
                        stride as i32,
                        data.as_ptr() as *const c_void,
                    )
                };
                format!(
                    "grLfbWriteRegion({buf}, {x}, {y}, {fmt:#x}, {w}, {h}, stride {stride}) = {ok}"
                )
            }
            12 => {
                let (x, y) = (self.rng.below(1100) as u32, self.rng.below(1100) as u32);
                let (w, h) = (self.rng.below(1100) as u32, self.rng.below(1100) as u32);
                let (cw, ch) = (w.min(1024) as usize, h.min(1024) as usize);
                let stride = cw * 2 + self.rng.below(4) as usize * 2;
                let mut data = vec![0u8; stride * ch + 16];
                let buf = self.rng.i() % 4;
                // SAFETY: as for the write: the clipped rows fit in `data`.
                let ok = unsafe {
                    grLfbReadRegion(
                        buf,
                        x,
                        y,
                        w,
                        h,
                        stride as u32,
                        data.as_mut_ptr() as *mut c_void,
                    )
                };
                format!("grLfbReadRegion({buf}, {x}, {y}, {w}, {h}, stride {stride}) = {ok}")
            }
            13 => {
                let mut info = self.tex_info();
                let (tmu, start, eo) = self.texture_target();
                // SAFETY: GrTexInfo with texel data covering any mipmap.
                unsafe {
                    match self.rng.below(4) {
                        0 => grTexSource(tmu, start, eo, &info),
                        1 => grTexDownloadMipMap(tmu, start, eo, &info),
                        2 => {
                            grTexTextureMemRequired(eo, &info);
                        }
                        _ => grTexMultibaseAddress(tmu, self.rng.int() % 6, start, eo, &info),
                    }
                }
                info.data = std::ptr::null_mut();
                format!("texture call {info:?} tmu {tmu} start {start:#x} evenOdd {eo}")
            }
            14 => {
                let info = self.tex_info();
                let (tmu, start, eo) = self.texture_target();
                let (t, max_t) = (self.rng.i() % 300, self.rng.i() % 300);
                let data = info.data as *const c_void;
                // SAFETY: the texel arena covers a whole 256x256 16-bit level.
                let ok = unsafe {
                    grTexDownloadMipMapLevelPartial(
                        tmu,
                        start,
                        info.large_lod_log2,
                        info.small_lod_log2,
                        info.aspect_ratio_log2,
                        info.format,
                        eo,
                        data,
                        t,
                        max_t,
                    )
                };
                format!("grTexDownloadMipMapLevelPartial({tmu}, {start:#x}, {info:?}, {t}, {max_t}) = {ok}")
            }
            15 => {
                let info = self.tex_info();
                let (tmu, start, eo) = self.texture_target();
                // SAFETY: the texel arena covers a whole 256x256 16-bit level.
                unsafe {
                    grTexDownloadMipMapLevel(
                        tmu,
                        start,
                        info.large_lod_log2,
                        info.small_lod_log2,
                        info.aspect_ratio_log2,
                        info.format,
                        eo,
                        info.data,
                    )
                };
                format!("grTexDownloadMipMapLevel({tmu}, {start:#x}, {info:?})")
            }
            16 => {
                for w in self.mem.table.iter_mut() {
                    *w = self.rng.next() as u32;
                }
                let (ty, tmu) = (self.rng.int() % 4, self.rng.i() % 4);
                let (s, e) = (self.rng.i() % 300, self.rng.i() % 300);
                let p = self.mem.table.as_ptr() as *const c_void;
                // SAFETY: a 1024-byte table.
                unsafe {
                    match self.rng.below(3) {
                        0 => grTexDownloadTable(ty, p),
                        1 => grTexDownloadTablePartial(ty, p, s, e),
                        _ => grTexDownloadTableExt(tmu, ty, p),
                    }
                }
                format!("table download type {ty} tmu {tmu} range {s}..{e}")
            }
            17 => {
                let n = self.rng.int() % 300;
                let t = self.mem.table.as_ptr();
                // SAFETY: 256 entries each (n above 256 is cut to 256).
                unsafe { grLoadGammaTable(n, t, t, t) };
                let mut fog = [0u8; 64];
                // SAFETY: 64-entry tables.
                unsafe {
                    grFogTable(fog.as_ptr());
                    guFogGenerateExp(fog.as_mut_ptr(), self.rng.float());
                    guFogGenerateExp2(fog.as_mut_ptr(), self.rng.float());
                    guFogGenerateLinear(fog.as_mut_ptr(), self.rng.float(), self.rng.float());
                    grFogTable(fog.as_ptr());
                }
                format!("gamma {n}, fog tables")
            }
            18 => {
                // Save, then restore the buffer as saved, damaged or foreign.
                let (state, layout) = (self.mem.state.as_mut_ptr(), self.mem.layout.as_mut_ptr());
                let how = self.rng.below(4);
                // SAFETY: buffers of the sizes grGet answers.
                unsafe {
                    if how != 3 {
                        grGlideGetState(state as *mut c_void);
                        grGlideGetVertexLayout(layout as *mut c_void);
                    }
                    if how == 1 {
                        let i = self.rng.below(self.mem.state.len() as u64) as usize;
                        self.mem.state[i] ^= 1 << self.rng.below(8);
                        let i = self.rng.below(self.mem.layout.len() as u64) as usize;
                        self.mem.layout[i] = self.rng.byte();
                    }
                    grGlideSetState(state as *const c_void);
                    grGlideSetVertexLayout(layout as *const c_void);
                }
                format!("state save/restore, variant {how}")
            }
            19 => {
                let t = GrResolution {
                    resolution: self.rng.i() % 20,
                    refresh: self.rng.i() % 12,
                    num_color_buffers: self.rng.i() % 5,
                    num_aux_buffers: self.rng.i() % 3,
                };
                let mut out = vec![t; 4096];
                // SAFETY: more entries than any template matches.
                unsafe { grQueryResolutions(&t, out.as_mut_ptr()) };
                let (mut x, mut y) = (0, 0);
                // SAFETY: output pointers.
                unsafe { guQueryResolutionXYExt(self.rng.i(), &mut x, &mut y) };
                format!("grQueryResolutions({t:?})")
            }
            20 => {
                let names: [&CStr; 5] = [
                    c"grTexDownloadTableExt",
                    c"guQueryResolutionXYExt",
                    c"grSetNumPendingBuffers",
                    c"grGetRegistryOrEnvironmentStringExt",
                    c"nonsense",
                ];
                let n = names[self.rng.below(5) as usize];
                // SAFETY: NUL-terminated names.
                unsafe {
                    grGetProcAddress(n.as_ptr());
                    grGetRegistryOrEnvironmentStringExt(c"HOME".as_ptr());
                    grGetRegistryOrEnvironmentStringExt(c"VOODOO_NOT_SET_ANYWHERE".as_ptr());
                }
                grSetNumPendingBuffers(self.rng.i());
                format!("grGetProcAddress({n:?})")
            }
            21 => {
                let f = &self.mem.files[self.rng.below(self.mem.files.len() as u64) as usize];
                let mut info = Gu3dfInfo {
                    header: Gu3dfHeader {
                        width: 0,
                        height: 0,
                        small_lod: 0,
                        large_lod: 0,
                        aspect_ratio: 0,
                        format: 0,
                    },
                    table: [0; 256],
                    data: self.mem.texels.as_mut_ptr() as *mut c_void,
                    mem_required: 0,
                };
                // SAFETY: a file name and a Gu3dfInfo whose buffer covers any mipmap.
                let ok = unsafe {
                    let ok = gu3dfGetInfo(f.as_ptr(), &mut info);
                    if self.rng.chance(3) {
                        info.header.large_lod = self.rng.i() % 12;
                        info.header.format = self.rng.i() % 20;
                        info.mem_required = info.mem_required.min(self.mem.texels.len() as u32);
                    }
                    ok + gu3dfLoad(f.as_ptr(), &mut info)
                };
                format!("gu3df {f:?} = {ok}")
            }
            22 => {
                // Null pointers where Glide takes them.
                // SAFETY: null is checked by every entry point.
                unsafe {
                    grDrawTriangle(std::ptr::null(), self.vertex(), std::ptr::null());
                    grDrawVertexArray(0, 3, std::ptr::null());
                    grGlideSetState(std::ptr::null());
                    grLfbLock(0, 0, 0, 0, 0, std::ptr::null_mut());
                    grTexSource(0, 0, 3, std::ptr::null());
                    gu3dfGetInfo(std::ptr::null(), std::ptr::null_mut());
                }
                "null pointers".into()
            }
            25 => {
                // 3dfx's undeclared SST-1 entry points (issue 15 item 2).
                let mut hwc = GrHwConfiguration::default();
                let mut stats = GrSstPerfStats::default();
                let (mut tris_in, mut tris_out) = (0, 0);
                // SAFETY: pointers to locals, or null (checked by every entry point).
                unsafe {
                    grSstQueryBoards(&mut hwc);
                    grSstQueryHardware(&mut hwc);
                    grSstQueryBoards(std::ptr::null_mut());
                    grSstQueryHardware(std::ptr::null_mut());
                    grSstPerfStats(&mut stats);
                    grSstPerfStats(std::ptr::null_mut());
                    grTriStats(&mut tris_in, &mut tris_out);
                    grTriStats(std::ptr::null_mut(), std::ptr::null_mut());
                    grGetRegistryOrEnvironmentString(c"HOME".as_ptr() as *mut c_char);
                    grGetRegistryOrEnvironmentString(std::ptr::null_mut());
                }
                grSstVidMode(self.rng.int(), std::ptr::null_mut());
                grSstIsBusy();
                grSstVRetraceOn();
                grSstVideoLine();
                grSstScreenWidth();
                grSstScreenHeight();
                grCheckForRoom(self.rng.i());
                grSstConfigPipeline(self.rng.i(), self.rng.int(), self.rng.int());
                grGlideShamelessPlug(self.rng.i());
                guAlphaSource(self.rng.i());
                guColorCombineFunction(self.rng.i());
                guEndianSwapBytes(self.rng.int() as u16);
                guEndianSwapWords(self.rng.int());
                _grChromaModeExt(self.rng.i());
                _grChromaRangeExt(self.rng.int(), self.rng.int(), self.rng.i());
                // At most 256 x 256 pixels of the texel arena; dst sized by a NULL call.
                let (w, h) = (self.rng.below(257) as u32, self.rng.below(257) as u32);
                let src = self.mem.texels.as_ptr() as *const c_void;
                // SAFETY: w x h 16-bit pixels lie inside the arena; dst holds the
                // bytes the NULL call counts.
                unsafe {
                    let n = guEncodeRLE16(std::ptr::null_mut(), src, w, h);
                    let mut dst = vec![0u32; n.max(0) as usize / 4];
                    guEncodeRLE16(dst.as_mut_ptr() as *mut c_void, src, w, h);
                }
                let mip = guTexCreateColorMipMap();
                // SAFETY: the library's malloc'ed mipmap (or null), freed once.
                unsafe { free(mip as *mut c_void) };
                "3dfx's undeclared entry points".into()
            }
            _ if self.rng.chance(20) => {
                grGlideShutdown();
                grGlideInit();
                "grGlideShutdown + grGlideInit".into()
            }
            _ => {
                // SAFETY: a GR_GLIDE_STATE_SIZE buffer filled with noise.
                for b in self.mem.state.iter_mut() {
                    *b = self.rng.byte();
                }
                unsafe { grGlideSetState(self.mem.state.as_ptr() as *const c_void) };
                "grGlideSetState(noise)".into()
            }
        }
    }
}

/// `.3df` files: a valid one, a truncated one, random bytes, /dev/zero, a missing one.
fn files(dir: &std::path::Path, rng: &mut Gen) -> Vec<std::ffi::CString> {
    std::fs::create_dir_all(dir).expect("scratch dir");
    let mut valid = b"3df v1.0\nrgb565\nlod range: 1 8\naspect ratio: 1 1\n".to_vec();
    valid.extend(vec![0x42; 2 * (64 + 16 + 4 + 1)]);
    let mut p8 = b"3df v1.0\np8\nlod range: 4 4\naspect ratio: 2 1\n".to_vec();
    p8.extend(vec![0x17; 1024 + 8]);
    let random: Vec<u8> = (0..3000).map(|_| rng.byte()).collect();
    let mut list = Vec::new();
    for (name, bytes) in [
        ("valid.3df", valid.clone()),
        ("truncated.3df", valid[..70].to_vec()),
        ("p8.3df", p8),
        ("random.3df", random),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, bytes).expect("write .3df");
        list.push(std::ffi::CString::new(path.to_string_lossy().into_owned()).unwrap());
    }
    list.push(c"/dev/zero".to_owned());
    list.push(c"/nonexistent/file.3df".to_owned());
    list
}

/// Scratch files of the `.3df` calls, written once per process.
fn scratch_files() -> &'static [std::ffi::CString] {
    static FILES: std::sync::OnceLock<Vec<std::ffi::CString>> = std::sync::OnceLock::new();
    FILES.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("voodoo-fuzz-glide-{}", std::process::id()));
        files(&dir, &mut Gen(Rng::new(7)))
    })
}

/// FNV-1a of the input: the program's seed.
fn seed_of(input: &[u8]) -> u64 {
    input.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// Seeds: a few programs.
pub fn seeds(_repo: &crate::corpus::Repository) -> Vec<Vec<u8>> {
    (0u64..8).map(|i| i.to_le_bytes().to_vec()).collect()
}

/// Runs the program the input seeds; panics on an internal error.
pub fn run(input: &[u8]) {
    let mut setup = Gen(Rng::new(seed_of(input) ^ 0x5a5a));
    let mut fuzz = Fuzz {
        rng: Gen(Rng::new(seed_of(input))),
        mem: Arena {
            vertices: vec![0.0; 64 * VERTEX_WORDS],
            texels: (0..2 * 256 * 256 * 2).map(|_| setup.byte()).collect(),
            table: vec![0; 256],
            state: vec![0; 588],
            layout: vec![0; 100],
            files: scratch_files().to_vec(),
        },
    };
    grErrorSetCallback(Some(on_error));
    INTERNAL
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
        .clear();
    fuzz.scramble_vertices();
    grGlideInit();
    grSstWinOpen(
        0,
        GR_RESOLUTION_640x480 as i32,
        GR_REFRESH_60Hz as i32,
        0,
        0,
        2,
        1,
    );
    // A layout that reads every parameter, so that drawing calls draw.
    for (param, offset) in [
        (GR_PARAM_XY, 0),
        (GR_PARAM_Z, 8),
        (GR_PARAM_Q, 12),
        (GR_PARAM_A, 16),
        (GR_PARAM_RGB, 20),
        (GR_PARAM_ST0, 32),
        (GR_PARAM_Q0, 40),
        (GR_PARAM_ST1, 44),
    ] {
        grVertexLayout(param, offset, GR_PARAM_ENABLE);
    }
    let mut calls = Vec::with_capacity(CALLS_PER_CASE);
    for _ in 0..CALLS_PER_CASE {
        calls.push(fuzz.call());
        let internal = std::mem::take(
            &mut *INTERNAL
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner),
        );
        if !internal.is_empty() {
            grGlideShutdown();
            panic!("{internal:?} after the calls:\n{}", calls.join("\n"));
        }
    }
    grGlideShutdown();
}

//! libglide3: the Glide 3 C ABI over the emulated SST-1.
//!
//! Every `gr*`/`gu*` function of the Glide 3.0 API (Glide 3.0 Programming Guide,
//! shared/seeds/001) is exported under its Glide name with the C calling convention;
//! `include/glide.h` declares them. Calls are forwarded to the `glide3` crate, which
//! writes the registers of an emulated `sst1_board::Board`.
//!
//! Environment:
//! * `VOODOO_PNG=path`: save the front buffer as PNG after buffer swaps.
//!   `VOODOO_PNG_SWAPS=1,3` picks the swaps (1-based); without it every swap
//!   overwrites the file. With more than one swap listed, `_swapN` is inserted
//!   before the extension.
//! * `VOODOO_TRACE=path`: record the whole run with `sst1_trace::Recorder`, streamed
//!   into the file (`sst1_trace::TraceWriter`) and completed at `grGlideShutdown`: text
//!   format (shared/docs/trace-text-format.md), or the binary
//!   form when the name ends in `.vtrace`; gzip-compressed when it ends in `.gz`. After
//!   every buffer swap the trace gets a `dump front STEM_swapN_front.raw` point (STEM:
//!   the file name up to its first dot), so `voodoo replay` reproduces each displayed
//!   frame. With `VOODOO_TRACE_HOST_TIME=1` the trace also holds the program's own time
//!   between bus accesses, from the host's clock (`wait` lines of at least 1 us;
//!   `sst1_trace::Recorder::record_host_time`), so its polling replays as it ran.
//! * `VOODOO_WINDOW=1`: show the front buffer in a live window, updated at every buffer
//!   swap (`window` module; needs a display and the default cargo feature `window`, else one
//!   line on stderr and the run stays headless).
//! * `VOODOO_FBI_MB`, `VOODOO_TMUS`, `VOODOO_TMU_MB`: the board (default 4, 1, 4).
//! * `VOODOO_MODEL`: the model of the board, `hardware` (the default) or a reference
//!   emulator's, `mame`, `dosbox-staging` or `86box` (`voodoo replay --model`).
//! * `VOODOO_METHOD`: how the board draws (`voodoo replay --method`): `exact` (the
//!   default), `reference`, or an approximation that trades exactness for speed,
//!   `nearest`, `lod-per-chunk`, `float-divide` or `fastest` (docs/methods.md).
//! * `VOODOO_THREADS=N`: render threads, for large triangles in bands of rows and small
//!   ones behind the writes (`sst1_board::Deferred`) (default: the
//!   machine's cores; `voodoo replay --threads`). The pixels are the same for every N.
//! * `VOODOO_ISA`: the copy of the span kernels, `baseline`, `avx2` or `avx512`, capped
//!   by what the CPU has (default: the best it has; `voodoo replay --isa`). The pixels
//!   are the same for every copy.
//! * `VOODOO_SAVE_STATE=path`: save the whole board (`sst1_board::state`) at
//!   `grGlideShutdown`, or, with `VOODOO_SAVE_STATE_SWAP=N`, right after the Nth buffer
//!   swap (1-based). With `VOODOO_TRACE` the state records how many trace ops had been
//!   written, so `voodoo replay TRACE --resume path` goes on from there.
//! * `VOODOO_LOAD_STATE=path`: load a saved board at the first successful
//!   `grSstWinOpen` of a session, after its own register writes.
//!
//! Headless by default: without `VOODOO_WINDOW` there is no window; the board is the only
//! output.

#![allow(clippy::missing_safety_doc)]
// Glide spells constants in mixed case; we keep the SDK spelling.
#![allow(non_upper_case_globals, non_snake_case)]

use glide::consts::*;
use glide::{BoardInfo, Glide, GlideState, TexInfo, VertexLayout};
use sst1_board::{
    AccuracyProfile, Board, BoardConfig, BufferKind, Deferred, Method, Reference, VectorIsa,
};
use sst1_regs::RegisterBus;
use sst1_trace::{DumpBuffer, Recorder, TraceWriter};
use std::borrow::Cow;
use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::io::Read;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::{Mutex, PoisonError};

mod window;

/// `FxBool`.
pub type FxBool = c_int;
/// `GrErrorCallbackFnc_t`.
pub type ErrorFn = Option<unsafe extern "C" fn(*const c_char, FxBool)>;

/// The emulated board, shared by the Glide context (which writes it through the bus)
/// and the C layer (which reads it for PNG output). Its small triangles are shaded on a
/// render thread behind the writes (`sst1_board::Deferred`, with more than one render
/// thread); the C layer reaches the board through [`Deferred::board`], which draws them
/// first.
type SharedBoard = Rc<RefCell<Deferred<Board>>>;

/// The `sst1_trace` recorder wrapping the board, streaming into the trace file; shared so
/// the C layer can add dump points and finish the file at shutdown.
type SharedRecorder = Rc<RefCell<Recorder<SharedBoard, TraceWriter>>>;

/// The bus Glide writes: the board, or the recorder in front of it (`VOODOO_TRACE`).
enum Bus {
    Direct(SharedBoard),
    Recorded(SharedRecorder),
}

impl RegisterBus for Bus {
    fn write32(&mut self, addr: u32, value: u32) {
        match self {
            Bus::Direct(b) => b.write32(addr, value),
            Bus::Recorded(r) => r.borrow_mut().write32(addr, value),
        }
    }
    fn read32(&mut self, addr: u32) -> u32 {
        match self {
            Bus::Direct(b) => b.read32(addr),
            Bus::Recorded(r) => r.borrow_mut().read32(addr),
        }
    }
    fn pci_write(&mut self, offset: u32, value: u32) {
        match self {
            Bus::Direct(b) => b.pci_write(offset, value),
            Bus::Recorded(r) => r.borrow_mut().pci_write(offset, value),
        }
    }
}

/// A run being recorded: the recorder, the output file and the stem of dump names.
struct Recording {
    recorder: SharedRecorder,
    path: PathBuf,
    stem: String,
}

impl Recording {
    /// Starts recording when `VOODOO_TRACE` names a file: the file is created now and the
    /// run streams into it (memory does not grow with the run). A file that cannot be
    /// created is said once on stderr and the run goes on unrecorded.
    fn from_env(board: &SharedBoard, cfg: BoardConfig) -> Option<Self> {
        let path = PathBuf::from(std::env::var_os("VOODOO_TRACE")?);
        let name = path.file_name()?.to_string_lossy().into_owned();
        let stem: String = name
            .split('.')
            .next()
            .unwrap_or("trace")
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let writer = match TraceWriter::create(&path) {
            Ok(writer) => writer,
            Err(e) => {
                eprintln!(
                    "glide3: cannot write {}: {e}; not recording",
                    path.display()
                );
                return None;
            }
        };
        let mut recorder = Recorder::streaming(board.clone(), cfg, writer);
        if std::env::var_os("VOODOO_TRACE_HOST_TIME").is_some_and(|v| !v.is_empty() && v != "0") {
            // 50 graphics clocks: 1 us at 50 MHz.
            recorder.record_host_time(50);
        }
        Some(Self {
            recorder: Rc::new(RefCell::new(recorder)),
            path,
            stem: if stem.is_empty() {
                "trace".into()
            } else {
                stem
            },
        })
    }

    /// The dump name of the front buffer after swap `n` (1-based).
    fn dump_name(stem: &str, n: u32) -> String {
        format!("{stem}_swap{n}_front.raw")
    }

    /// Completes the trace file: text, or binary for `.vtrace`, gzip when the name ends
    /// in `.gz` (the convention of `voodoo convert`).
    fn finish(&self) -> std::io::Result<()> {
        self.recorder.borrow_mut().log_mut().finish()
    }
}

/// Words in an LFB shadow: 1024 rows of 4096 bytes.
const LFB_WORDS: usize = 1024 * 1024;

/// What a write lock's shadow holds where the program has not stored: a 16-bit
/// pixel slot (16-bit formats, two a word) or a 32-bit one. Unlock sends every slot
/// that differs from it, so every pixel the program stores reaches the board, the
/// value the buffer already holds included (on the SST-1 each store is a bus write,
/// and a pipelined write blends, depth-tests and counts). INACCURATE: a store of
/// exactly this value is taken for no store; the values are chosen to be unlikely
/// (no grey, no primary, no common chroma key, alpha 0x5a in 32-bit formats). The
/// stores also arrive once each, in address order, at unlock, where the hardware sees
/// each one as it is made.
const UNWRITTEN16: u16 = 0x5aa5;
/// See [`UNWRITTEN16`].
const UNWRITTEN32: u32 = 0x5aa5_5aa5;

/// Host-side stand-in for the mapped LFB while a lock is held. The two shadows (read
/// and write lock) are allocated once per process and never freed, so the pointer
/// `grLfbLock` hands out stays valid whatever the program does after (a refused unlock,
/// a second lock, `grGlideShutdown`): a stale pointer can only reach these words.
struct LfbShadow {
    /// What the program sees through `GrLfbInfo_t::lfbPtr`.
    words: Box<[u32]>,
    /// The lock's row stride in bytes: 2048 (16-bit slots) or 4096 (32-bit).
    stride: u32,
}

impl LfbShadow {
    fn new() -> Self {
        Self {
            words: vec![0; LFB_WORDS].into_boxed_slice(),
            stride: 2048,
        }
    }
}

/// Everything one Glide session (`grGlideInit` to `grGlideShutdown`) holds.
struct Ctx {
    glide: Glide,
    board: SharedBoard,
    recording: Option<Recording>,
    png: Option<(String, Option<Vec<u32>>)>,
    window: Option<window::LiveWindow>,
    /// `VOODOO_SAVE_STATE` and `VOODOO_SAVE_STATE_SWAP`.
    save_state: Option<(PathBuf, Option<u32>)>,
    /// `VOODOO_LOAD_STATE`, until the first successful `grSstWinOpen` loads it.
    load_state: Option<PathBuf>,
}

/// The process's Glide state: the session, if one is open, and the LFB shadows, which
/// outlive sessions.
struct Process {
    session: Option<Ctx>,
    lfb: [Option<LfbShadow>; 2],
}

/// [`Process`] behind the lock that makes Glide's state per process, as in 3dfx's
/// library: any thread may call, one at a time.
struct Shared(Process);

// SAFETY: the only non-`Send` parts of a `Process` are the `Rc`s that share the board
// and the recorder between the Glide context, the C layer and the recorder, and the
// boxed bus and error callback of `Glide`. Every clone of those `Rc`s lives inside the
// same `Process` (none is handed out), the error callback captures nothing, and the
// `Process` is only reached through `PROCESS`'s mutex, so at any time one thread at most
// touches any of them: moving the whole tree between threads is sound.
unsafe impl Send for Shared {}

static PROCESS: Mutex<Shared> = Mutex::new(Shared(Process {
    session: None,
    lfb: [None, None],
}));

/// What `grErrorSetCallback` asked for. Process-wide, and kept from before `grGlideInit`
/// to after `grGlideShutdown`.
#[derive(Clone, Copy)]
enum ErrorSink {
    /// Never set: errors are dropped.
    Unset,
    /// Set to NULL: errors go to stderr.
    Stderr,
    /// The program's callback.
    Program(unsafe extern "C" fn(*const c_char, FxBool)),
}

static ERROR_SINK: Mutex<ErrorSink> = Mutex::new(ErrorSink::Unset);

/// Most errors one entry point queues for delivery; later ones are counted.
const MAX_PENDING: usize = 64;

thread_local! {
    /// Errors raised during this thread's current entry point, delivered when it
    /// returns, with no lock held, so a callback may call Glide again.
    static PENDING: RefCell<(Vec<(String, bool)>, usize)> = const { RefCell::new((Vec::new(), 0)) };
    /// How deep this thread is in entry points (one calls another for some calls).
    static DEPTH: Cell<u32> = const { Cell::new(0) };
    /// Whether this thread holds `PROCESS` (taking it again would deadlock).
    static HOLDING: Cell<bool> = const { Cell::new(false) };
}

/// Queues an error for the program's callback.
fn raise(msg: String, fatal: bool) {
    PENDING.with(|p| {
        let (list, dropped) = &mut *p.borrow_mut();
        if list.len() < MAX_PENDING {
            list.push((msg, fatal));
        } else {
            *dropped += 1;
        }
    });
}

/// Hands this thread's queued errors to the program's callback (or stderr).
fn deliver_errors() {
    let (mut list, dropped) = PENDING.with(|p| std::mem::take(&mut *p.borrow_mut()));
    if dropped > 0 {
        list.push((format!("glide3: {dropped} more errors not reported"), false));
    }
    if list.is_empty() {
        return;
    }
    let sink = *ERROR_SINK.lock().unwrap_or_else(PoisonError::into_inner);
    for (msg, fatal) in list {
        match sink {
            ErrorSink::Unset => {}
            ErrorSink::Stderr => eprintln!("glide3: {msg}"),
            ErrorSink::Program(cb) => {
                let s = CString::new(msg.replace('\0', " ")).unwrap_or_default();
                // SAFETY: a C function pointer registered by the program, called with a
                // NUL-terminated string that outlives the call. No lock is held, so the
                // callback may call any Glide function.
                unsafe { cb(s.as_ptr(), FxBool::from(fatal)) };
            }
        }
    }
}

/// The text of a panic's payload.
fn panic_text(payload: &(dyn std::any::Any + Send)) -> &str {
    payload
        .downcast_ref::<&str>()
        .copied()
        .or_else(|| payload.downcast_ref::<String>().map(String::as_str))
        .unwrap_or("panic")
}

/// The body of every exported function: runs `body`, turns a panic into an error
/// reported as `CALL: internal error: ...` (and the call's default result), and, when
/// the outermost entry point returns, delivers the errors raised during it. No panic
/// crosses the C boundary.
fn entry<R: Default>(call: &str, body: impl FnOnce() -> R) -> R {
    DEPTH.set(DEPTH.get() + 1);
    let result = catch_unwind(AssertUnwindSafe(body)).unwrap_or_else(|payload| {
        raise(
            format!("{call}: internal error: {}", panic_text(&*payload)),
            false,
        );
        R::default()
    });
    DEPTH.set(DEPTH.get() - 1);
    if DEPTH.get() == 0 {
        deliver_errors();
    }
    result
}

/// Clears [`HOLDING`] when the process lock is let go, unwinding included.
struct Holding;

impl Drop for Holding {
    fn drop(&mut self) {
        HOLDING.set(false);
    }
}

/// Runs `f` with the process's state locked. Call inside [`entry`].
fn with_process<R>(f: impl FnOnce(&mut Process) -> R) -> R {
    // Re-entering would deadlock; entry() turns the panic into an error.
    assert!(!HOLDING.get(), "Glide re-entered while it holds its state");
    // A panic while locked poisons the mutex; the state stays memory-safe, so go on.
    let mut guard = PROCESS.lock().unwrap_or_else(PoisonError::into_inner);
    HOLDING.set(true);
    let _holding = Holding;
    f(&mut guard.0)
}

/// Runs `f` on the open session; the default result when none is open.
fn with<R: Default>(f: impl FnOnce(&mut Ctx) -> R) -> R {
    with_process(|p| p.session.as_mut().map(f).unwrap_or_default())
}

fn board_config() -> BoardConfig {
    let env = |k: &str, d: u32| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    BoardConfig {
        fbi_mb: env("VOODOO_FBI_MB", 4),
        tmus: env("VOODOO_TMUS", 1),
        tmu_mb: env("VOODOO_TMU_MB", 4),
    }
    .sanitized()
}

/// The model of the board `VOODOO_MODEL` names: `hardware` (the default: our reading of
/// the SST-1), or one reference emulator's model, `mame`, `dosbox-staging` or `86box`.
/// Any other value is said once on stderr and the hardware model runs.
fn model_profile() -> AccuracyProfile {
    let Ok(name) = std::env::var("VOODOO_MODEL") else {
        return AccuracyProfile::default();
    };
    match Reference::from_name(&name) {
        Some(r) => r.profile(),
        None if name == "hardware" => AccuracyProfile::default(),
        None => {
            eprintln!(
                "glide3: VOODOO_MODEL={name:.40} is not hardware, mame, dosbox-staging or 86box; \
                 running the hardware model"
            );
            AccuracyProfile::default()
        }
    }
}

/// The method `VOODOO_METHOD` names ([`Method::name`]); unset is the exact fast path.
/// Any other value is said once on stderr and the exact fast path runs.
fn draw_method() -> Method {
    let Ok(name) = std::env::var("VOODOO_METHOD") else {
        return Method::Exact;
    };
    Method::from_name(name.trim()).unwrap_or_else(|| {
        let names: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
        eprintln!(
            "glide3: VOODOO_METHOD={name:.40} is not one of {}; drawing exactly",
            names.join(", ")
        );
        Method::Exact
    })
}

/// `VOODOO_THREADS`, or the machine's cores; a value that is not a number counts as
/// unset, and at most 256 threads are used.
fn render_threads() -> usize {
    std::env::var("VOODOO_THREADS")
        .ok()
        .and_then(|v| v.trim().parse::<usize>().ok())
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .clamp(1, 256)
}

/// The copy of the span kernels `VOODOO_ISA` names, or the best the CPU has. Any other
/// value is said once on stderr and the best runs.
fn vector_isa() -> VectorIsa {
    let Ok(name) = std::env::var("VOODOO_ISA") else {
        return VectorIsa::best();
    };
    name.trim().parse().unwrap_or_else(|e| {
        eprintln!(
            "glide3: VOODOO_ISA={name:.40} is {e}; running {}",
            VectorIsa::best()
        );
        VectorIsa::best()
    })
}

fn png_setting() -> Option<(String, Option<Vec<u32>>)> {
    let path = std::env::var("VOODOO_PNG").ok()?;
    let swaps = std::env::var("VOODOO_PNG_SWAPS")
        .ok()
        .map(|s| s.split(',').filter_map(|n| n.trim().parse().ok()).collect());
    Some((path, swaps))
}

/// `VOODOO_SAVE_STATE` and the swap `VOODOO_SAVE_STATE_SWAP` names (`None`: at
/// `grGlideShutdown`; a value that is not a number is said on stderr and ignored).
fn save_state_setting() -> Option<(PathBuf, Option<u32>)> {
    let path = PathBuf::from(std::env::var_os("VOODOO_SAVE_STATE")?);
    let swap = std::env::var("VOODOO_SAVE_STATE_SWAP").ok().and_then(|v| {
        let n = v.trim().parse::<u32>().ok().filter(|&n| n > 0);
        if n.is_none() {
            eprintln!(
                "glide3: VOODOO_SAVE_STATE_SWAP={v:.40} is not a swap number (1, 2, ...); \
                 saving the state at grGlideShutdown"
            );
        }
        n
    });
    Some((path, swap))
}

/// Saves the board to `path` (with the trace ops written so far, when recording).
fn save_board_state(ctx: &Ctx, path: &std::path::Path) {
    let ops = ctx
        .recording
        .as_ref()
        .map(|r| r.recorder.borrow().log().ops_written());
    let mut board = ctx.board.borrow_mut();
    let board = board.board();
    let bytes = match ops {
        Some(n) => board.save_state_after(n),
        None => board.save_state(),
    };
    if let Err(e) = sst1_trace::write_file_replacing(path, &bytes) {
        eprintln!("glide3: cannot save the board state: {e}");
    }
}

/// Loads the board saved at `path` (`VOODOO_LOAD_STATE`); a file that cannot be read or
/// is refused is said on stderr and the board stays as it is.
fn load_board_state(ctx: &Ctx, path: &std::path::Path) {
    let mut board = ctx.board.borrow_mut();
    let board = board.board();
    let limit = sst1_board::state::max_state_len(board.config()) as u64;
    let loaded = sst1_trace::read_file_bounded(path, limit)
        .map_err(|e| e.to_string())
        .and_then(|bytes| board.load_state(&bytes).map_err(|e| e.to_string()));
    if let Err(e) = loaded {
        eprintln!(
            "glide3: VOODOO_LOAD_STATE={}: {e}; not loaded",
            path.display()
        );
    }
}

/// Save the front buffer as RGB PNG (RGB565 expanded by bit replication).
fn save_png(board: &Board, path: &str) {
    let (w, h) = board.display_size();
    let px = board.dump_buffer(BufferKind::Front);
    let mut rgb = Vec::with_capacity((w * h * 3) as usize);
    for &p in px.iter().take((w * h) as usize) {
        rgb.extend(sst1_trace::rgb565_to_rgb8(p));
    }
    if let Err(e) = image::save_buffer(path, &rgb, w, h, image::ExtendedColorType::Rgb8) {
        eprintln!("glide3: cannot write {path}: {e}");
    }
}

fn after_swap(ctx: &mut Ctx) {
    let n = ctx.glide.swap_count();
    if let Some(r) = &ctx.recording {
        r.recorder
            .borrow_mut()
            .dump(DumpBuffer::Front, &Recording::dump_name(&r.stem, n));
    }
    if let Some((path, Some(swap))) = &ctx.save_state {
        if *swap == n {
            save_board_state(ctx, path);
        }
    }
    if let Some(w) = &ctx.window {
        w.show(ctx.board.borrow_mut().board());
    }
    let Some((path, swaps)) = ctx.png.clone() else {
        return;
    };
    match swaps {
        None => save_png(ctx.board.borrow_mut().board(), &path),
        Some(list) if list.contains(&n) => {
            let out = if list.len() > 1 {
                match path.rfind('.') {
                    Some(i) => format!("{}_swap{n}{}", &path[..i], &path[i..]),
                    None => format!("{path}_swap{n}"),
                }
            } else {
                path
            };
            save_png(ctx.board.borrow_mut().board(), &out);
        }
        Some(_) => {}
    }
}

/// Words of a C vertex: enough for every enabled layout parameter.
fn vertex_words(layout: &VertexLayout) -> usize {
    let mut end = layout.xy.offset + 8;
    for (prm, size) in [
        (layout.z, 4),
        (layout.w, 4),
        (layout.q, 4),
        (layout.fog, 4),
        (layout.a, 4),
        (layout.rgb, 12),
        (layout.pargb, 4),
        (layout.st[0], 8),
        (layout.st[1], 8),
        (layout.st[2], 8),
        (layout.qn[0], 4),
        (layout.qn[1], 4),
        (layout.qn[2], 4),
    ] {
        if prm.enabled {
            end = end.max(prm.offset + size);
        }
    }
    (end.max(0) as usize).div_ceil(4)
}

/// Read one C vertex: enough words for every enabled layout parameter.
unsafe fn vertex(layout: &VertexLayout, p: *const c_void) -> Vec<f32> {
    if p.is_null() {
        return Vec::new();
    }
    let src = p as *const f32;
    // SAFETY: the Glide contract: the vertex holds every parameter of the layout.
    (0..vertex_words(layout))
        .map(|i| unsafe { src.add(i).read_unaligned() })
        .collect()
}

/// Words of a vertex that [`Vertices`] keeps on the stack: every parameter of a layout
/// packed from offset 0 takes 20.
const INLINE_WORDS: usize = 32;

/// A primitive's C vertices read once (a point's, a line's or a triangle's): on the
/// stack when each has at most [`INLINE_WORDS`] words, else in one allocation.
struct Vertices<const N: usize> {
    inline: [[f32; INLINE_WORDS]; N],
    heap: Vec<f32>,
    words: usize,
}

impl<const N: usize> Vertices<N> {
    /// # Safety
    /// Each pointer is a Glide vertex (not null) holding every parameter of `layout`.
    unsafe fn read(layout: &VertexLayout, at: [*const c_void; N]) -> Self {
        let words = vertex_words(layout);
        let mut v = Self {
            inline: [[0.0; INLINE_WORDS]; N],
            heap: Vec::new(),
            words,
        };
        if words > INLINE_WORDS {
            v.heap.reserve_exact(words * N);
        }
        for (k, p) in at.into_iter().enumerate() {
            let src = p as *const f32;
            for i in 0..words {
                // SAFETY: the caller's contract.
                let w = unsafe { src.add(i).read_unaligned() };
                if words > INLINE_WORDS {
                    v.heap.push(w);
                } else {
                    v.inline[k][i] = w;
                }
            }
        }
        v
    }

    /// Vertex `k`'s words.
    fn get(&self, k: usize) -> &[f32] {
        if self.words > INLINE_WORDS {
            &self.heap[k * self.words..(k + 1) * self.words]
        } else {
            &self.inline[k][..self.words]
        }
    }
}

// ----- init and windows ------------------------------------------------------------

/// `grGlideInit`.
#[no_mangle]
pub extern "C" fn grGlideInit() {
    entry("grGlideInit", || {
        with_process(|p| {
            if p.session.is_some() {
                return;
            }
            let cfg = board_config();
            let mut board = Board::new(cfg);
            board.set_profile(model_profile());
            board.set_method(draw_method());
            board.set_threads(render_threads());
            board.set_vector_isa(vector_isa());
            let board = Rc::new(RefCell::new(Deferred::new(board)));
            let recording = Recording::from_env(&board, cfg);
            let bus = match &recording {
                Some(r) => Bus::Recorded(r.recorder.clone()),
                None => Bus::Direct(board.clone()),
            };
            let mut glide = Glide::init(
                Box::new(bus),
                BoardInfo::new(cfg.fbi_mb, cfg.tmus, cfg.tmu_mb),
            );
            glide.set_error_callback(Box::new(|msg: &str, fatal: bool| {
                raise(msg.to_owned(), fatal)
            }));
            p.session = Some(Ctx {
                glide,
                board,
                recording,
                png: png_setting(),
                window: window::LiveWindow::from_env(),
                save_state: save_state_setting(),
                load_state: std::env::var_os("VOODOO_LOAD_STATE").map(PathBuf::from),
            });
        })
    })
}

/// `grGlideShutdown`.
#[no_mangle]
pub extern "C" fn grGlideShutdown() {
    entry("grGlideShutdown", || {
        let Some(ctx) = with_process(|p| p.session.take()) else {
            return;
        };
        if let Some((path, None)) = &ctx.save_state {
            save_board_state(&ctx, path);
        }
        drop(ctx.glide.shutdown());
        if let Some(r) = &ctx.recording {
            if let Err(e) = r.finish() {
                eprintln!("glide3: cannot write {}: {e}", r.path.display());
            }
        }
    })
}

/// `grGlideGetVersion`: copies "3.01.0001" into an 80-byte buffer.
#[no_mangle]
pub unsafe extern "C" fn grGlideGetVersion(version: *mut c_char) {
    entry("grGlideGetVersion", || {
        if version.is_null() {
            return;
        }
        let v = b"3.01.0001\0";
        // SAFETY: the caller provides 80 bytes.
        unsafe { std::ptr::copy_nonoverlapping(v.as_ptr() as *const c_char, version, v.len()) };
    })
}

/// `grSstSelect`.
#[no_mangle]
pub extern "C" fn grSstSelect(which: c_int) {
    entry("grSstSelect", || {
        with(|c| c.glide.sst_select(which));
    })
}

/// `grSstWinOpen`: returns a non-zero context on success.
#[no_mangle]
pub extern "C" fn grSstWinOpen(
    _hwnd: u32,
    res: i32,
    refresh: i32,
    format: i32,
    origin: i32,
    ncolor: c_int,
    naux: c_int,
) -> u32 {
    entry("grSstWinOpen", || {
        with(|c| {
            let opened = c.glide.win_open(
                res as u32,
                refresh as u32,
                format as u32,
                origin as u32,
                ncolor,
                naux,
            );
            if opened {
                if let Some(path) = c.load_state.take() {
                    load_board_state(c, &path);
                }
            }
            u32::from(opened)
        })
    })
}

/// `grSstWinClose`.
#[no_mangle]
pub extern "C" fn grSstWinClose(_context: u32) -> FxBool {
    entry("grSstWinClose", || {
        with(|c| FxBool::from(c.glide.win_close()))
    })
}

/// `grSelectContext`.
#[no_mangle]
pub extern "C" fn grSelectContext(context: u32) -> FxBool {
    entry("grSelectContext", || FxBool::from(context != 0))
}

/// `grSstOrigin`.
#[no_mangle]
pub extern "C" fn grSstOrigin(origin: i32) {
    entry("grSstOrigin", || {
        with(|c| c.glide.sst_origin(origin as u32));
    })
}

/// `grErrorSetCallback`: the callback is the process's, kept across sessions and valid
/// before `grGlideInit`; NULL sends errors to stderr.
#[no_mangle]
pub extern "C" fn grErrorSetCallback(f: ErrorFn) {
    entry("grErrorSetCallback", || {
        *ERROR_SINK.lock().unwrap_or_else(PoisonError::into_inner) = match f {
            Some(cb) => ErrorSink::Program(cb),
            None => ErrorSink::Stderr,
        };
    })
}

// ----- queries -----------------------------------------------------------------------

/// `grGet`: the answers of 3dfx's SST-1 Glide 3 (see `Glide::get`): `plength` bytes
/// written on success, 1 with `params` untouched for a known selector asked with
/// another `plength`, 0 for an unknown selector or a null `params`.
#[no_mangle]
pub unsafe extern "C" fn grGet(pname: u32, plength: u32, params: *mut i32) -> u32 {
    entry("grGet", || {
        if params.is_null() {
            return 0;
        }
        let mut buf = [0i32; 4];
        let n = with_process(|p| match p.session.as_mut() {
            Some(c) => c.glide.get(pname, plength, &mut buf),
            // Valid before grGlideInit (Guide chapter 3; diget.c probes the bus): one board.
            None if pname == GR_NUM_BOARDS => {
                buf[0] = 1;
                if plength == 4 {
                    4
                } else {
                    1
                }
            }
            None => 0,
        });
        if n == plength {
            let words = (n as usize / 4).min(4);
            // SAFETY: the caller provides plength bytes.
            unsafe { std::ptr::copy_nonoverlapping(buf.as_ptr(), params, words) };
        }
        n
    })
}

/// `grGetString`.
#[no_mangle]
pub extern "C" fn grGetString(pname: u32) -> *const c_char {
    static STRINGS: [&CStr; 6] = [
        c"FOGALPHA ",
        c"Voodoo Graphics",
        c"Glide",
        c"3Dfx Interactive",
        c"3.01.0001",
        c"ERROR",
    ];
    entry("grGetString", || {
        let s = glide::get::get_string(pname);
        STRINGS.iter().find(|c| c.to_str() == Ok(s)).copied()
    })
    .unwrap_or(STRINGS[5])
    .as_ptr()
}

/// `grReset`: statistics counters or the vertex layout (see `Glide::reset`).
#[no_mangle]
pub extern "C" fn grReset(what: u32) -> FxBool {
    entry("grReset", || with(|c| FxBool::from(c.glide.reset(what))))
}

/// `GrResolution`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct GrResolution {
    /// `GR_RESOLUTION_*` or `GR_QUERY_ANY`.
    pub resolution: i32,
    /// `GR_REFRESH_*` or `GR_QUERY_ANY`.
    pub refresh: i32,
    /// Colour buffers or `GR_QUERY_ANY`.
    pub num_color_buffers: c_int,
    /// Aux buffers or `GR_QUERY_ANY`.
    pub num_aux_buffers: c_int,
}

/// `grQueryResolutions`: the size in bytes of the matching `GrResolution` list,
/// written to `output` unless it is null (3dfx diget.c).
#[no_mangle]
pub unsafe extern "C" fn grQueryResolutions(
    template: *const GrResolution,
    output: *mut GrResolution,
) -> i32 {
    entry("grQueryResolutions", || {
        // SAFETY: the caller's template (checked for null).
        let Some(t) = (unsafe { template.as_ref() }).copied() else {
            return 0;
        };
        let any = |v: i32| u32::try_from(v).ok();
        let list = with(|c| {
            c.glide.query_resolutions(
                any(t.resolution),
                any(t.refresh),
                any(t.num_color_buffers),
                any(t.num_aux_buffers),
            )
        });
        if !output.is_null() {
            for (i, r) in list.iter().enumerate() {
                // SAFETY: the caller sized `output` from a previous null-output call.
                unsafe {
                    output.add(i).write(GrResolution {
                        resolution: r.resolution as i32,
                        refresh: r.refresh as i32,
                        num_color_buffers: r.color_buffers as c_int,
                        num_aux_buffers: r.aux_buffers as c_int,
                    })
                };
            }
        }
        (list.len() * std::mem::size_of::<GrResolution>()) as i32
    })
}

/// `guQueryResolutionXYExt` (through `grGetProcAddress`): the size of a resolution.
/// UNVERIFIED: unknown resolutions give 0 x 0 (3dfx indexes its table unchecked).
pub unsafe extern "C" fn guQueryResolutionXYExt(res: i32, x: *mut u32, y: *mut u32) {
    entry("guQueryResolutionXYExt", || {
        const XY: [(u32, u32); 16] = [
            (320, 200),
            (320, 240),
            (400, 256),
            (512, 384),
            (640, 200),
            (640, 350),
            (640, 400),
            (640, 480),
            (800, 600),
            (960, 720),
            (856, 480),
            (512, 256),
            (1024, 768),
            (1280, 1024),
            (1600, 1200),
            (400, 300),
        ];
        let (w, h) = usize::try_from(res)
            .ok()
            .and_then(|i| XY.get(i).copied())
            .unwrap_or((0, 0));
        // SAFETY: the caller's output pointers (checked for null).
        unsafe {
            if let Some(x) = x.as_mut() {
                *x = w;
            }
            if let Some(y) = y.as_mut() {
                *y = h;
            }
        }
    })
}

/// `grGetRegistryOrEnvironmentStringExt` (through `grGetProcAddress`): `getenv`.
pub unsafe extern "C" fn grGetRegistryOrEnvironmentStringExt(name: *const c_char) -> *mut c_char {
    /// The strings handed out, by name: kept for the process (an entry is never replaced
    /// or removed), like the environment string 3dfx returns, so a pointer stays valid.
    static ENV: Mutex<Option<HashMap<String, CString>>> = Mutex::new(None);
    entry("grGetRegistryOrEnvironmentStringExt", || {
        if name.is_null() {
            return None;
        }
        // SAFETY: the caller's NUL-terminated name.
        let key = unsafe { CStr::from_ptr(name) }
            .to_string_lossy()
            .into_owned();
        let value = std::env::var(&key).ok()?;
        let mut env = ENV.lock().unwrap_or_else(PoisonError::into_inner);
        let s = env
            .get_or_insert_with(HashMap::new)
            .entry(key)
            .or_insert_with(|| CString::new(value.replace('\0', "")).unwrap_or_default());
        Some(s.as_ptr() as *mut c_char)
    })
    .unwrap_or(std::ptr::null_mut())
}

/// `grSetNumPendingBuffers` (exported, and in `grGetProcAddress`'s table): the number
/// of swaps `grBufferSwap` lets queue up before it spins on the status register
/// (gsst.c stores it; gglide.c `grBufferSwap` waits on it). Our swaps finish at once
/// and never pend, so it is accepted and unused (3dfx would spin for ever below 0).
#[no_mangle]
pub extern "C" fn grSetNumPendingBuffers(_n: i32) {
    entry("grSetNumPendingBuffers", || {})
}

/// `GrProc`.
pub type GrProc = Option<unsafe extern "C" fn() -> c_int>;

/// `grGetProcAddress`: the extensions of 3dfx's SST-1 Glide 3 (diget.c
/// `_extensionTable`, without the texus2 quantizers); null for any other name.
#[no_mangle]
pub unsafe extern "C" fn grGetProcAddress(name: *const c_char) -> GrProc {
    entry("grGetProcAddress", || {
        if name.is_null() {
            return None;
        }
        // SAFETY: the caller's NUL-terminated name.
        let name = unsafe { CStr::from_ptr(name) }.to_bytes();
        let p: *const () = match name {
            b"guQueryResolutionXYExt" => guQueryResolutionXYExt as *const (),
            b"grGetRegistryOrEnvironmentStringExt" => {
                grGetRegistryOrEnvironmentStringExt as *const ()
            }
            b"grTexDownloadTableExt" => grTexDownloadTableExt as *const (),
            b"grSetNumPendingBuffers" => grSetNumPendingBuffers as *const (),
            _ => return None,
        };
        // SAFETY: GrProc is an untyped function pointer; the caller casts it back to the
        // extension's real signature, as with 3dfx's library.
        Some(unsafe { std::mem::transmute::<*const (), unsafe extern "C" fn() -> c_int>(p) })
    })
}

/// `grSplash`: 3dfx draws its animated logo; the emulation shows nothing.
#[no_mangle]
pub extern "C" fn grSplash(_x: f32, _y: f32, _w: f32, _h: f32, _frame: u32) {
    entry("grSplash", || {})
}

// ----- state ------------------------------------------------------------------------

macro_rules! forward {
    ($( $(#[$m:meta])* fn $name:ident($($a:ident: $t:ty),*) => $method:ident($($e:expr),*); )*) => {
        $(
            $(#[$m])*
            #[no_mangle]
            pub extern "C" fn $name($($a: $t),*) {
                entry(stringify!($name), || with(|c| c.glide.$method($($e),*)));
            }
        )*
    };
}

forward! {
    /// `grAlphaBlendFunction`.
    fn grAlphaBlendFunction(a: i32, b: i32, c2: i32, d: i32) => alpha_blend_function(a as u32, b as u32, c2 as u32, d as u32);
    /// `grAlphaCombine`.
    fn grAlphaCombine(f: i32, fa: i32, l: i32, o: i32, inv: FxBool) => alpha_combine(f as u32, fa as u32, l as u32, o as u32, inv != 0);
    /// `grAlphaControlsITRGBLighting`.
    fn grAlphaControlsITRGBLighting(e: FxBool) => alpha_controls_itrgb_lighting(e != 0);
    /// `grAlphaTestFunction`.
    fn grAlphaTestFunction(f: i32) => alpha_test_function(f as u32);
    /// `grAlphaTestReferenceValue`.
    fn grAlphaTestReferenceValue(v: u8) => alpha_test_reference_value(v);
    /// `grColorCombine`.
    fn grColorCombine(f: i32, fa: i32, l: i32, o: i32, inv: FxBool) => color_combine(f as u32, fa as u32, l as u32, o as u32, inv != 0);
    /// `grChromakeyMode`.
    fn grChromakeyMode(m: i32) => chromakey_mode(m as u32);
    /// `grChromakeyValue`.
    fn grChromakeyValue(v: u32) => chromakey_value(v);
    /// `grChromaRangeExt`.
    fn grChromaRangeExt(v: u32, r: u32, m: u32) => chroma_range(v, r, m);
    /// `grClipWindow`.
    fn grClipWindow(a: u32, b: u32, c2: u32, d: u32) => clip_window(a, b, c2, d);
    /// `grColorMask`.
    fn grColorMask(rgb: FxBool, a: FxBool) => color_mask(rgb != 0, a != 0);
    /// `grConstantColorValue`.
    fn grConstantColorValue(v: u32) => constant_color_value(v);
    /// `grCullMode`.
    fn grCullMode(m: i32) => cull_mode(m as u32);
    /// `grDepthBiasLevel`.
    fn grDepthBiasLevel(l: i32) => depth_bias_level(l);
    /// `grDepthBufferFunction`.
    fn grDepthBufferFunction(f: i32) => depth_buffer_function(f as u32);
    /// `grDepthBufferMode`.
    fn grDepthBufferMode(m: i32) => depth_buffer_mode(m as u32);
    /// `grDepthMask`.
    fn grDepthMask(e: FxBool) => depth_mask(e != 0);
    /// `grDisableAllEffects`.
    fn grDisableAllEffects() => disable_all_effects();
    /// `grDitherMode`.
    fn grDitherMode(m: i32) => dither_mode(m as u32);
    /// `grFogColorValue`.
    fn grFogColorValue(v: u32) => fog_color_value(v);
    /// `grFogMode`.
    fn grFogMode(m: i32) => fog_mode(m as u32);
    /// `grRenderBuffer`.
    fn grRenderBuffer(b: i32) => render_buffer(b as u32);
    /// `grEnable`.
    fn grEnable(m: u32) => enable(m);
    /// `grDisable`.
    fn grDisable(m: u32) => disable(m);
    /// `grCoordinateSpace`.
    fn grCoordinateSpace(m: u32) => coordinate_space(m);
    /// `grDepthRange`.
    fn grDepthRange(n: f32, f: f32) => depth_range(n, f);
    /// `grViewport`.
    fn grViewport(x: i32, y: i32, w: i32, h: i32) => viewport(x, y, w, h);
    /// `grLfbConstantAlpha`.
    fn grLfbConstantAlpha(a: u8) => lfb_constant_alpha(a);
    /// `grLfbConstantDepth`.
    fn grLfbConstantDepth(d: u32) => lfb_constant_depth(d);
    /// `grLfbWriteColorFormat`.
    fn grLfbWriteColorFormat(f: i32) => lfb_write_color_format(f as u32);
    /// `grLfbWriteColorSwizzle`.
    fn grLfbWriteColorSwizzle(b: FxBool, w: FxBool) => lfb_write_color_swizzle(b != 0, w != 0);
    /// `grVertexLayout`.
    fn grVertexLayout(p: u32, o: i32, m: u32) => vertex_layout(p, o, m);
    /// `grFinish`.
    fn grFinish() => finish();
    /// `guGammaCorrectionRGB`.
    fn guGammaCorrectionRGB(r: f32, g: f32, b: f32) => gamma_correction_rgb(r, g, b);
    /// `grTexClampMode`.
    fn grTexClampMode(t: i32, s: i32, tt: i32) => tex_clamp_mode(t as u32, s as u32, tt as u32);
    /// `grTexCombine`.
    fn grTexCombine(t: i32, rf: i32, rfa: i32, af: i32, afa: i32, ri: FxBool, ai: FxBool) => tex_combine(t as u32, rf as u32, rfa as u32, af as u32, afa as u32, ri != 0, ai != 0);
    /// `grTexDetailControl`.
    fn grTexDetailControl(t: i32, b: c_int, s: u8, m: f32) => tex_detail_control(t as u32, b, s, m);
    /// `grTexFilterMode`.
    fn grTexFilterMode(t: i32, mi: i32, ma: i32) => tex_filter_mode(t as u32, mi as u32, ma as u32);
    /// `grTexLodBiasValue`.
    fn grTexLodBiasValue(t: i32, v: f32) => tex_lod_bias_value(t as u32, v);
    /// `grTexMipMapMode`.
    fn grTexMipMapMode(t: i32, m: i32, b: FxBool) => tex_mipmap_mode(t as u32, m as u32, b != 0);
    /// `grTexMultibase`.
    fn grTexMultibase(t: i32, e: FxBool) => tex_multibase(t as u32, e != 0);
    /// `grTexNCCTable`.
    fn grTexNCCTable(t: u32) => tex_ncc_table_select(t);
}

/// `grFlush`: nothing is buffered on the host.
#[no_mangle]
pub extern "C" fn grFlush() {
    entry("grFlush", || {})
}

/// `grFogTable`: 64 entries.
#[no_mangle]
pub unsafe extern "C" fn grFogTable(table: *const u8) {
    entry("grFogTable", || {
        if table.is_null() {
            return;
        }
        let mut t = [0u8; 64];
        // SAFETY: the caller provides 64 entries (GR_FOG_TABLE_ENTRIES).
        unsafe { std::ptr::copy_nonoverlapping(table, t.as_mut_ptr(), 64) };
        with(|c| c.glide.fog_table(&t));
    })
}

/// `grLoadGammaTable`.
#[no_mangle]
pub unsafe extern "C" fn grLoadGammaTable(n: u32, r: *const u32, g: *const u32, b: *const u32) {
    entry("grLoadGammaTable", || {
        if r.is_null() || g.is_null() || b.is_null() {
            return;
        }
        let n = n.min(256) as usize;
        // SAFETY: the caller provides n entries in each table.
        let (r, g, b) = unsafe {
            (
                std::slice::from_raw_parts(r, n),
                std::slice::from_raw_parts(g, n),
                std::slice::from_raw_parts(b, n),
            )
        };
        with(|c| c.glide.load_gamma_table(r, g, b));
    })
}

// The saved state and vertex layout live in the caller's buffer (`glide::saved`), as
// in 3dfx's Glide: saving allocates nothing, and a copy of a buffer restores the same
// value.

/// Copies `bytes` into the program's `size`-byte buffer at `buf` (null: nothing).
unsafe fn save_to(buf: *mut c_void, size: i32, bytes: &[u8]) {
    if buf.is_null() {
        return;
    }
    debug_assert!(bytes.len() <= size as usize);
    let n = bytes.len().min(size as usize);
    // SAFETY: the caller's buffer holds `size` bytes (what grGet answers for it).
    unsafe { std::ptr::copy_nonoverlapping(bytes.as_ptr(), buf as *mut u8, n) };
}

/// The program's `size`-byte buffer at `buf` (null: empty).
unsafe fn saved_bytes<'a>(buf: *const c_void, size: i32) -> &'a [u8] {
    if buf.is_null() {
        return &[];
    }
    // SAFETY: the caller's buffer holds `size` bytes (what grGet answers for it).
    unsafe { std::slice::from_raw_parts(buf as *const u8, size as usize) }
}

/// `grGlideGetState`: fills a `GR_GLIDE_STATE_SIZE`-byte buffer.
#[no_mangle]
pub unsafe extern "C" fn grGlideGetState(state: *mut c_void) {
    entry("grGlideGetState", || {
        let bytes = with(|c| c.glide.get_state().to_bytes());
        // SAFETY: a GR_GLIDE_STATE_SIZE buffer.
        unsafe { save_to(state, glide::get::GLIDE_STATE_SIZE, &bytes) };
    })
}

/// `grGlideSetState`: restores a buffer `grGlideGetState` filled (or a copy of one).
#[no_mangle]
pub unsafe extern "C" fn grGlideSetState(state: *const c_void) {
    entry("grGlideSetState", || {
        // SAFETY: a GR_GLIDE_STATE_SIZE buffer.
        let bytes = unsafe { saved_bytes(state, glide::get::GLIDE_STATE_SIZE) };
        with(|c| match GlideState::from_bytes(bytes) {
            Some(s) => c.glide.set_state(&s),
            None => c
                .glide
                .report_error("grGlideSetState: state was not saved by grGlideGetState"),
        })
    })
}

/// `grGlideGetVertexLayout`: fills a `GR_GLIDE_VERTEXLAYOUT_SIZE`-byte buffer.
#[no_mangle]
pub unsafe extern "C" fn grGlideGetVertexLayout(layout: *mut c_void) {
    entry("grGlideGetVertexLayout", || {
        let bytes = with(|c| c.glide.get_vertex_layout().to_bytes());
        // SAFETY: a GR_GLIDE_VERTEXLAYOUT_SIZE buffer.
        unsafe { save_to(layout, glide::get::GLIDE_VERTEXLAYOUT_SIZE, &bytes) };
    })
}

/// `grGlideSetVertexLayout`: restores a buffer `grGlideGetVertexLayout` filled.
#[no_mangle]
pub unsafe extern "C" fn grGlideSetVertexLayout(layout: *const c_void) {
    entry("grGlideSetVertexLayout", || {
        // SAFETY: a GR_GLIDE_VERTEXLAYOUT_SIZE buffer.
        let bytes = unsafe { saved_bytes(layout, glide::get::GLIDE_VERTEXLAYOUT_SIZE) };
        with(|c| match VertexLayout::from_bytes(bytes) {
            Some(l) => c.glide.set_vertex_layout(&l),
            None => c.glide.report_error(
                "grGlideSetVertexLayout: layout was not saved by grGlideGetVertexLayout",
            ),
        })
    })
}

// ----- drawing ----------------------------------------------------------------------

/// Reports a null vertex pointer (3dfx: "NULL pointer passed"); true if one is null.
fn null_vertex(call: &str, ptrs: &[*const c_void]) -> bool {
    let bad = ptrs.iter().any(|p| p.is_null());
    if bad {
        with(|c| {
            c.glide
                .report_error(&format!("{call}: NULL pointer passed"))
        });
    }
    bad
}

/// `grDrawPoint`.
#[no_mangle]
pub unsafe extern "C" fn grDrawPoint(p: *const c_void) {
    entry("grDrawPoint", || {
        if null_vertex("grDrawPoint", &[p]) {
            return;
        }
        with(|c| {
            let l = c.glide.get_vertex_layout();
            // SAFETY: Glide vertex pointer.
            let v = unsafe { Vertices::read(&l, [p]) };
            c.glide.draw_point(v.get(0));
        });
    })
}

/// `grDrawLine`.
#[no_mangle]
pub unsafe extern "C" fn grDrawLine(a: *const c_void, b: *const c_void) {
    entry("grDrawLine", || {
        if null_vertex("grDrawLine", &[a, b]) {
            return;
        }
        with(|c| {
            let l = c.glide.get_vertex_layout();
            // SAFETY: Glide vertex pointers.
            let v = unsafe { Vertices::read(&l, [a, b]) };
            c.glide.draw_line(v.get(0), v.get(1));
        });
    })
}

/// `grDrawTriangle`.
#[no_mangle]
pub unsafe extern "C" fn grDrawTriangle(a: *const c_void, b: *const c_void, cc: *const c_void) {
    entry("grDrawTriangle", || {
        if null_vertex("grDrawTriangle", &[a, b, cc]) {
            return;
        }
        with(|c| {
            let l = c.glide.get_vertex_layout();
            // SAFETY: Glide vertex pointers (checked non-null).
            let v = unsafe { Vertices::read(&l, [a, b, cc]) };
            c.glide.draw_triangle(v.get(0), v.get(1), v.get(2));
        });
    })
}

/// `grAADrawTriangle`: the triangle with alpha-blended edge triangles on the edges
/// whose flag is set.
#[no_mangle]
pub unsafe extern "C" fn grAADrawTriangle(
    a: *const c_void,
    b: *const c_void,
    cc: *const c_void,
    ab: FxBool,
    bc: FxBool,
    ca: FxBool,
) {
    entry("grAADrawTriangle", || {
        if null_vertex("grAADrawTriangle", &[a, b, cc]) {
            return;
        }
        with(|c| {
            let l = c.glide.get_vertex_layout();
            // SAFETY: Glide vertex pointers (checked non-null).
            let v = unsafe { Vertices::read(&l, [a, b, cc]) };
            c.glide
                .aa_draw_triangle(v.get(0), v.get(1), v.get(2), ab != 0, bc != 0, ca != 0);
        });
    })
}

/// `grDrawVertexArray`: `pointers` is an array of `count` vertex pointers.
#[no_mangle]
pub unsafe extern "C" fn grDrawVertexArray(mode: u32, count: u32, pointers: *const *const c_void) {
    entry("grDrawVertexArray", || {
        if null_vertex("grDrawVertexArray", &[pointers as *const c_void]) {
            return;
        }
        // SAFETY: `count` vertex pointers.
        let list = unsafe { std::slice::from_raw_parts(pointers, count as usize) };
        if null_vertex("grDrawVertexArray", list) {
            return;
        }
        with(|c| {
            let l = c.glide.get_vertex_layout();
            // One vertex read at a time: no memory in proportion to `count`.
            c.glide.draw_vertex_array_with(mode, list.len(), |i| {
                // SAFETY: a non-null Glide vertex pointer.
                Cow::Owned(unsafe { vertex(&l, list[i]) })
            });
        });
    })
}

/// `grDrawVertexArrayContiguous`: `count` vertices `stride` bytes apart.
#[no_mangle]
pub unsafe extern "C" fn grDrawVertexArrayContiguous(
    mode: u32,
    count: u32,
    data: *const c_void,
    stride: u32,
) {
    entry("grDrawVertexArrayContiguous", || {
        if null_vertex("grDrawVertexArrayContiguous", &[data]) {
            return;
        }
        with(|c| {
            let l = c.glide.get_vertex_layout();
            let base = data as *const u8;
            // One vertex read at a time: no memory in proportion to `count`.
            let stride = stride as usize;
            c.glide
                .draw_vertex_array_contiguous_with(mode, count as usize, stride, |i| {
                    // (count - 1) * stride < 2^64: no overflow on a 64-bit host.
                    let p = base.wrapping_add(i.wrapping_mul(stride)) as *const c_void;
                    // SAFETY: vertex `i` of the caller's `count` vertices `stride` apart.
                    Cow::Owned(unsafe { vertex(&l, p) })
                });
        });
    })
}

// ----- buffers ----------------------------------------------------------------------

/// `grBufferClear`.
#[no_mangle]
pub extern "C" fn grBufferClear(color: u32, alpha: u8, depth: u32) {
    entry("grBufferClear", || {
        with(|c| c.glide.buffer_clear(color, alpha, depth));
    })
}

/// `grBufferSwap`; saves the PNG when `VOODOO_PNG` asks for this swap.
#[no_mangle]
pub extern "C" fn grBufferSwap(interval: u32) {
    entry("grBufferSwap", || {
        with(|c| {
            c.glide.buffer_swap(interval);
            after_swap(c);
        });
    })
}

/// `grBufferNumPending`.
#[no_mangle]
pub extern "C" fn grBufferNumPending() -> c_int {
    entry("grBufferNumPending", || {
        with(|c| c.glide.buffer_num_pending() as c_int)
    })
}

// ----- LFB --------------------------------------------------------------------------

/// `GrLfbInfo_t`.
#[repr(C)]
pub struct GrLfbInfo {
    /// sizeof(GrLfbInfo_t).
    pub size: c_int,
    /// Host pointer to the (shadowed) frame buffer.
    pub lfb_ptr: *mut c_void,
    /// Row stride in bytes.
    pub stride_in_bytes: u32,
    /// Effective write mode.
    pub write_mode: i32,
    /// Origin.
    pub origin: i32,
}

/// `grLfbLock`: the pointer is a host shadow; a read lock fills it from the board,
/// a write lock sends what the program stored into it when unlocked (see
/// `UNWRITTEN16`).
#[no_mangle]
pub unsafe extern "C" fn grLfbLock(
    ty: u32,
    buffer: i32,
    mode: i32,
    origin: i32,
    pipeline: FxBool,
    info: *mut GrLfbInfo,
) -> FxBool {
    entry("grLfbLock", || {
        if info.is_null() {
            with(|c| {
                c.glide
                    .report_error("grLfbLock: NULL info structure passed")
            });
            return 0;
        }
        with_process(|p| {
            let Some(c) = p.session.as_mut() else {
                return 0;
            };
            // Refused (and reported) unless the type, buffer and mode are valid and the
            // slot is free: only then is the shadow touched.
            let Some(li) =
                c.glide
                    .lfb_lock(ty, buffer as u32, mode as u32, origin as u32, pipeline != 0)
            else {
                return 0;
            };
            let Some(slot) = glide::lfb::lock_slot(ty) else {
                return 0;
            };
            let write = slot == 1;
            let shadow = p.lfb[slot].get_or_insert_with(LfbShadow::new);
            shadow.stride = li.stride_in_bytes;
            if write {
                // Every slot starts as "not stored": unlock sends the slots the
                // program stored into, whatever it stored (see UNWRITTEN16). Reading
                // through a write lock sees these values, not the buffer.
                shadow.words.fill(if li.stride_in_bytes == 2048 {
                    u32::from(UNWRITTEN16) * 0x1_0001
                } else {
                    UNWRITTEN32
                });
            } else {
                shadow.words.fill(0);
                // Fill what the program can see from the board (16-bit layout).
                let (w, h) = c.glide.screen_size();
                let (w, h) = glide::lfb::clip_to_window(0, 0, w.div_ceil(2), h);
                for y in 0..h as usize {
                    for x in 0..w as usize {
                        shadow.words[y * 512 + x] = c.glide.lfb_read32((y * 2048 + x * 4) as u32);
                    }
                }
            }
            // SAFETY: checked non-null above.
            unsafe {
                (*info).lfb_ptr = shadow.words.as_mut_ptr() as *mut c_void;
                (*info).stride_in_bytes = li.stride_in_bytes;
                (*info).write_mode = li.write_mode as i32;
                (*info).origin = li.origin as i32;
            }
            1
        })
    })
}

/// `grLfbUnlock`: what the program stored through a write lock reaches the board first. An unlock that
/// does not match the lock fails and leaves the lock (and its pointer) as they were.
#[no_mangle]
pub extern "C" fn grLfbUnlock(ty: u32, buffer: i32) -> FxBool {
    entry("grLfbUnlock", || {
        with_process(|p| {
            let Some(c) = p.session.as_mut() else {
                return 0;
            };
            let holds = c.glide.lfb_locked_buffer(ty) == Some(buffer as u32);
            if let (true, Some(1), Some(shadow)) = (holds, glide::lfb::lock_slot(ty), &p.lfb[1]) {
                send_stored(&mut c.glide, shadow);
            }
            FxBool::from(c.glide.lfb_unlock(ty, buffer as u32))
        })
    })
}

/// Sends what the program stored into a write lock's shadow: each 32-bit slot, or each
/// 16-bit one (a 32-bit write when both halves of a word were stored, else a 16-bit
/// write of the stored half), that differs from the "not stored" value.
fn send_stored(glide: &mut Glide, shadow: &LfbShadow) {
    for (i, &w) in shadow.words.iter().enumerate() {
        let offset = (i * 4) as u32;
        if shadow.stride != 2048 {
            if w != UNWRITTEN32 {
                glide.lfb_write32(offset, w);
            }
            continue;
        }
        let (lo, hi) = (w as u16, (w >> 16) as u16);
        match (lo != UNWRITTEN16, hi != UNWRITTEN16) {
            (true, true) => glide.lfb_write32(offset, w),
            (true, false) => glide.lfb_write16(offset, lo),
            (false, true) => glide.lfb_write16(offset + 2, hi),
            (false, false) => {}
        }
    }
}

/// Bytes of caller memory a region of `height` rows `stride` apart, `row_bytes` used in
/// each, covers.
fn region_bytes(height: u32, stride: usize, row_bytes: usize) -> usize {
    match height {
        0 => 0,
        h => (h as usize - 1) * stride + row_bytes,
    }
}

/// `grLfbWriteRegion`: clipped to the LFB window (`glide::lfb::clip_to_window`); only
/// the rows and pixels inside it are read from `data`.
#[no_mangle]
pub unsafe extern "C" fn grLfbWriteRegion(
    buffer: i32,
    x: u32,
    y: u32,
    fmt: u32,
    w: u32,
    h: u32,
    pipeline: FxBool,
    stride: i32,
    data: *const c_void,
) -> FxBool {
    entry("grLfbWriteRegion", || {
        if data.is_null() || stride < 0 {
            return 0;
        }
        let (cw, ch) = glide::lfb::clip_to_window(x, y, w, h);
        let pixel_bytes = if glide::lfb::stride_for(fmt) == 2048 {
            2
        } else {
            4
        };
        let len = region_bytes(ch, stride as usize, cw as usize * pixel_bytes);
        // SAFETY: the caller provides h rows of stride bytes, each with w pixels; `len`
        // covers the clipped part of them.
        let src = unsafe { std::slice::from_raw_parts(data as *const u8, len) };
        with(|c| {
            FxBool::from(c.glide.lfb_write_region(
                buffer as u32,
                x,
                y,
                fmt,
                cw,
                ch,
                pipeline != 0,
                stride as usize,
                src,
            ))
        })
    })
}

/// `grLfbReadRegion`: 16-bit pixels, clipped to the LFB window; the caller's memory
/// outside the clipped part is left as it was.
#[no_mangle]
pub unsafe extern "C" fn grLfbReadRegion(
    buffer: i32,
    x: u32,
    y: u32,
    w: u32,
    h: u32,
    stride: u32,
    data: *mut c_void,
) -> FxBool {
    entry("grLfbReadRegion", || {
        if data.is_null() {
            return 0;
        }
        let (cw, ch) = glide::lfb::clip_to_window(x, y, w, h);
        let len = region_bytes(ch, stride as usize, cw as usize * 2);
        // SAFETY: the caller provides h rows of stride bytes, each with w pixels; `len`
        // covers the clipped part of them.
        let dst = unsafe { std::slice::from_raw_parts_mut(data as *mut u8, len) };
        with(|c| {
            FxBool::from(
                c.glide
                    .lfb_read_region(buffer as u32, x, y, cw, ch, stride as usize, dst),
            )
        })
    })
}

// ----- textures ---------------------------------------------------------------------

/// `GrTexInfo`.
#[repr(C)]
#[derive(Debug)]
pub struct GrTexInfo {
    /// Smallest LOD.
    pub small_lod_log2: i32,
    /// Largest LOD.
    pub large_lod_log2: i32,
    /// Aspect ratio.
    pub aspect_ratio_log2: i32,
    /// Texture format.
    pub format: i32,
    /// Texel data.
    pub data: *mut c_void,
}

unsafe fn tex_info(p: *const GrTexInfo) -> Option<(TexInfo, *const c_void)> {
    // SAFETY: caller's GrTexInfo pointer (checked for null).
    let i = unsafe { p.as_ref()? };
    Some((
        TexInfo {
            small_lod: i.small_lod_log2.max(0) as u32,
            large_lod: i.large_lod_log2.max(0) as u32,
            aspect: i.aspect_ratio_log2,
            format: i.format.max(0) as u32,
        },
        i.data,
    ))
}

/// Bytes of host data a mipmap (levels large..=small) occupies.
fn host_bytes(info: &TexInfo) -> usize {
    let texel = if info.format >= GR_TEXFMT_16BIT { 2 } else { 1 };
    (info.small_lod..=info.large_lod.min(8))
        .map(|l| {
            let (w, h) = glide::tex::level_wh(l, info.aspect);
            (w * h) as usize * texel
        })
        .sum()
}

/// `grTexMinAddress`.
#[no_mangle]
pub extern "C" fn grTexMinAddress(tmu: i32) -> u32 {
    entry("grTexMinAddress", || {
        with(|c| c.glide.tex_min_address(tmu as u32))
    })
}

/// `grTexMaxAddress`.
#[no_mangle]
pub extern "C" fn grTexMaxAddress(tmu: i32) -> u32 {
    entry("grTexMaxAddress", || {
        with(|c| c.glide.tex_max_address(tmu as u32))
    })
}

/// `grTexTextureMemRequired`.
#[no_mangle]
pub unsafe extern "C" fn grTexTextureMemRequired(even_odd: u32, info: *const GrTexInfo) -> u32 {
    entry("grTexTextureMemRequired", || {
        // SAFETY: caller's GrTexInfo.
        let Some((i, _)) = (unsafe { tex_info(info) }) else {
            return 0;
        };
        with(|c| c.glide.tex_texture_mem_required(even_odd, &i))
    })
}

/// `grTexCalcMemRequired`.
#[no_mangle]
pub extern "C" fn grTexCalcMemRequired(small: i32, large: i32, aspect: i32, format: i32) -> u32 {
    entry("grTexCalcMemRequired", || {
        with(|c| {
            c.glide.tex_calc_mem_required(
                small.max(0) as u32,
                large.max(0) as u32,
                aspect,
                format.max(0) as u32,
            )
        })
    })
}

/// `grTexSource`.
#[no_mangle]
pub unsafe extern "C" fn grTexSource(tmu: i32, start: u32, even_odd: u32, info: *const GrTexInfo) {
    entry("grTexSource", || {
        // SAFETY: caller's GrTexInfo.
        if let Some((i, _)) = unsafe { tex_info(info) } {
            with(|c| c.glide.tex_source(tmu as u32, start, even_odd, &i));
        }
    })
}

/// `grTexMultibaseAddress`.
#[no_mangle]
pub unsafe extern "C" fn grTexMultibaseAddress(
    tmu: i32,
    range: u32,
    start: u32,
    even_odd: u32,
    info: *const GrTexInfo,
) {
    entry("grTexMultibaseAddress", || {
        // SAFETY: caller's GrTexInfo.
        if let Some((i, _)) = unsafe { tex_info(info) } {
            with(|c| {
                c.glide
                    .tex_multibase_address(tmu as u32, range, start, even_odd, &i)
            });
        }
    })
}

/// `grTexDownloadMipMap`.
#[no_mangle]
pub unsafe extern "C" fn grTexDownloadMipMap(
    tmu: i32,
    start: u32,
    even_odd: u32,
    info: *const GrTexInfo,
) {
    entry("grTexDownloadMipMap", || {
        // SAFETY: caller's GrTexInfo.
        let Some((i, data)) = (unsafe { tex_info(info) }) else {
            return;
        };
        if data.is_null() {
            return;
        }
        // SAFETY: the texel data covers every level of the mipmap.
        let bytes = unsafe { std::slice::from_raw_parts(data as *const u8, host_bytes(&i)) };
        with(|c| {
            c.glide
                .tex_download_mipmap(tmu as u32, start, even_odd, &i, bytes)
        });
    })
}

/// `grTexDownloadMipMapLevel`.
#[no_mangle]
pub unsafe extern "C" fn grTexDownloadMipMapLevel(
    tmu: i32,
    start: u32,
    lod: i32,
    large: i32,
    aspect: i32,
    format: i32,
    even_odd: u32,
    data: *const c_void,
) {
    entry("grTexDownloadMipMapLevel", || {
        // SAFETY: forwarded with the whole level.
        let (_, h) = glide::tex::level_wh(lod.max(0) as u32, aspect);
        unsafe {
            grTexDownloadMipMapLevelPartial(
                tmu,
                start,
                lod,
                large,
                aspect,
                format,
                even_odd,
                data,
                0,
                h as c_int - 1,
            )
        };
    })
}

/// `grTexDownloadMipMapLevelPartial`.
#[no_mangle]
pub unsafe extern "C" fn grTexDownloadMipMapLevelPartial(
    tmu: i32,
    start: u32,
    lod: i32,
    large: i32,
    aspect: i32,
    format: i32,
    even_odd: u32,
    data: *const c_void,
    t: c_int,
    max_t: c_int,
) -> FxBool {
    entry("grTexDownloadMipMapLevelPartial", || {
        if data.is_null() {
            with(|c| {
                c.glide
                    .report_error("grTexDownloadMipMapLevelPartial: NULL pointer passed")
            });
            return 0;
        }
        // Only rows that lie inside the level are read; any other range is refused
        // (and reported) below without reading the caller's data.
        let level = lod.max(0) as u32;
        let len = if glide::tex::rows_ok(level, aspect, t, max_t) {
            let (w, _) = glide::tex::level_wh(level, aspect);
            let texel = if format >= GR_TEXFMT_16BIT as i32 {
                2
            } else {
                1
            };
            (w as usize) * texel * (max_t - t + 1) as usize
        } else {
            0
        };
        // SAFETY: rows t..=max_t of the level, which the caller provides.
        let bytes = unsafe { std::slice::from_raw_parts(data as *const u8, len) };
        with(|c| {
            FxBool::from(c.glide.tex_download_mipmap_level_partial(
                tmu as u32,
                start,
                lod.max(0) as u32,
                large.max(0) as u32,
                aspect,
                format.max(0) as u32,
                even_odd,
                bytes,
                t,
                max_t,
            ))
        })
    })
}

/// Palette (`GuTexPalette`: 256 x FxU32) or NCC table (`GuNccTable`: 16 + 4x3x2... the
/// SST-1 packed form is the last 12 words) download.
unsafe fn download_table(tmu: u32, ty: u32, data: *const c_void, start: usize, end: usize) {
    if data.is_null() {
        return;
    }
    if ty == GR_TEXTABLE_PALETTE {
        let mut pal = [0u32; 256];
        // SAFETY: a GuTexPalette has 256 words.
        unsafe { std::ptr::copy_nonoverlapping(data as *const u32, pal.as_mut_ptr(), 256) };
        with(|c| c.glide.tex_download_palette_range(tmu, &pal, start, end));
    } else {
        // GuNccTable: yRGB[16] bytes, iRGB[4][3] i16, qRGB[4][3] i16, packed_data[12] u32.
        let mut packed = [0u32; 12];
        // SAFETY: the packed words sit at byte 64 of a GuNccTable.
        unsafe {
            std::ptr::copy_nonoverlapping(
                (data as *const u8).add(64) as *const u32,
                packed.as_mut_ptr(),
                12,
            )
        };
        with(|c| c.glide.tex_download_ncc_table(tmu, ty, &packed));
    }
}

/// `grTexDownloadTable`.
#[no_mangle]
pub unsafe extern "C" fn grTexDownloadTable(ty: u32, data: *const c_void) {
    entry("grTexDownloadTable", || {
        // SAFETY: forwarded table pointer.
        unsafe { download_table(0, ty, data, 0, 255) };
    })
}

/// `grTexDownloadTablePartial`.
#[no_mangle]
pub unsafe extern "C" fn grTexDownloadTablePartial(
    ty: u32,
    data: *const c_void,
    start: c_int,
    end: c_int,
) {
    entry("grTexDownloadTablePartial", || {
        // SAFETY: forwarded table pointer.
        unsafe { download_table(0, ty, data, start.max(0) as usize, end.max(0) as usize) };
    })
}

/// `grTexDownloadTableExt`.
#[no_mangle]
pub unsafe extern "C" fn grTexDownloadTableExt(tmu: i32, ty: u32, data: *const c_void) {
    entry("grTexDownloadTableExt", || {
        // SAFETY: forwarded table pointer.
        unsafe { download_table(tmu as u32, ty, data, 0, 255) };
    })
}

// ----- gu utilities -----------------------------------------------------------------

/// `guFogTableIndexToW`.
#[no_mangle]
pub extern "C" fn guFogTableIndexToW(i: c_int) -> f32 {
    entry("guFogTableIndexToW", || glide::get::fog_table_index_to_w(i))
}

unsafe fn fog_out(t: *mut u8, f: impl FnOnce(&mut [u8; 64])) {
    if t.is_null() {
        return;
    }
    let mut table = [0u8; 64];
    f(&mut table);
    // SAFETY: the caller provides 64 entries.
    unsafe { std::ptr::copy_nonoverlapping(table.as_ptr(), t, 64) };
}

/// `guFogGenerateExp`.
#[no_mangle]
pub unsafe extern "C" fn guFogGenerateExp(t: *mut u8, density: f32) {
    entry("guFogGenerateExp", || {
        // SAFETY: caller's 64-entry table.
        unsafe { fog_out(t, |x| glide::get::fog_generate_exp(x, density)) };
    })
}

/// `guFogGenerateExp2`.
#[no_mangle]
pub unsafe extern "C" fn guFogGenerateExp2(t: *mut u8, density: f32) {
    entry("guFogGenerateExp2", || {
        // SAFETY: caller's 64-entry table.
        unsafe { fog_out(t, |x| glide::get::fog_generate_exp2(x, density)) };
    })
}

/// `guFogGenerateLinear`.
#[no_mangle]
pub unsafe extern "C" fn guFogGenerateLinear(t: *mut u8, near: f32, far: f32) {
    entry("guFogGenerateLinear", || {
        // SAFETY: caller's 64-entry table.
        unsafe { fog_out(t, |x| glide::get::fog_generate_linear(x, near, far)) };
    })
}

// ----- .3DF files -------------------------------------------------------------------

/// `Gu3dfHeader`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct Gu3dfHeader {
    /// Width of the largest level.
    pub width: u32,
    /// Height of the largest level.
    pub height: u32,
    /// `GR_LOD_LOG2_*` of the smallest level.
    pub small_lod: c_int,
    /// `GR_LOD_LOG2_*` of the largest level.
    pub large_lod: c_int,
    /// `GR_ASPECT_LOG2_*`.
    pub aspect_ratio: i32,
    /// `GR_TEXFMT_*`.
    pub format: i32,
}

/// `Gu3dfInfo`: the header, the table (`GuTexTable`: a `GuNccTable` or a
/// `GuTexPalette` in 1024 bytes), the caller's texel buffer and its size.
#[repr(C)]
#[derive(Debug)]
pub struct Gu3dfInfo {
    /// Parsed header.
    pub header: Gu3dfHeader,
    /// `GuTexTable` storage.
    pub table: [u32; 256],
    /// Texel buffer of `mem_required` bytes, provided by the caller for `gu3dfLoad`.
    pub data: *mut c_void,
    /// Bytes of all the levels.
    pub mem_required: u32,
}

/// Reads a whole file named by a C string.
/// Reads at most `limit` bytes from the start of the file named by a C string.
unsafe fn read_file(name: *const c_char, limit: usize) -> Option<Vec<u8>> {
    if name.is_null() {
        return None;
    }
    // SAFETY: the caller's NUL-terminated file name.
    let name = unsafe { CStr::from_ptr(name) };
    let file = std::fs::File::open(name.to_str().ok()?).ok()?;
    let mut bytes = Vec::new();
    file.take(limit as u64).read_to_end(&mut bytes).ok()?;
    Some(bytes)
}

/// `gu3dfGetInfo`: fills `info->header` and `info->mem_required`.
#[no_mangle]
pub unsafe extern "C" fn gu3dfGetInfo(filename: *const c_char, info: *mut Gu3dfInfo) -> FxBool {
    entry("gu3dfGetInfo", || {
        // SAFETY: the caller's file name and Gu3dfInfo (checked for null).
        let (Some(file), Some(info)) = (
            unsafe { read_file(filename, glide::g3df::MAX_HEADER_BYTES) },
            unsafe { info.as_mut() },
        ) else {
            return 0;
        };
        let Ok(i) = glide::g3df::get_info(&file) else {
            return 0;
        };
        info.header = Gu3dfHeader {
            width: i.header.width,
            height: i.header.height,
            small_lod: i.header.small_lod as c_int,
            large_lod: i.header.large_lod as c_int,
            aspect_ratio: i.header.aspect,
            format: i.header.format as i32,
        };
        info.mem_required = i.mem_required;
        1
    })
}

/// `gu3dfLoad`: the table into `info->table` and the texels into `info->data`
/// (`info->mem_required` bytes; 16-bit texels in host order).
#[no_mangle]
pub unsafe extern "C" fn gu3dfLoad(filename: *const c_char, info: *mut Gu3dfInfo) -> FxBool {
    entry("gu3dfLoad", || {
        // SAFETY: the caller's file name and Gu3dfInfo (checked for null).
        let (Some(file), Some(info)) = (
            unsafe { read_file(filename, glide::g3df::MAX_FILE_BYTES) },
            unsafe { info.as_mut() },
        ) else {
            return 0;
        };
        if info.data.is_null() {
            return 0;
        }
        let h = info.header;
        let header = glide::g3df::Gu3dfHeader {
            width: h.width,
            height: h.height,
            small_lod: h.small_lod.clamp(0, 8) as u32,
            large_lod: h.large_lod.clamp(0, 8) as u32,
            aspect: h.aspect_ratio,
            format: h.format.max(0) as u32,
        };
        let Ok((table, data)) = glide::g3df::load(&file, &header) else {
            return 0;
        };
        match table {
            glide::g3df::TexTable::None => {}
            glide::g3df::TexTable::Palette(p) => info.table = *p,
            glide::g3df::TexTable::Ncc(n) => {
                // GuNccTable: yRGB[16] u8, iRGB[4][3] i16, qRGB[4][3] i16, packed_data[12].
                let mut bytes = Vec::with_capacity(112);
                bytes.extend_from_slice(&n.y);
                for v in n.i.iter().chain(n.q.iter()).flatten() {
                    bytes.extend_from_slice(&v.to_ne_bytes());
                }
                for w in n.packed {
                    bytes.extend_from_slice(&w.to_ne_bytes());
                }
                for (dst, src) in info.table.iter_mut().zip(bytes.chunks_exact(4)) {
                    *dst = u32::from_ne_bytes([src[0], src[1], src[2], src[3]]);
                }
            }
        }
        // SAFETY: the caller's buffer holds mem_required bytes, which is `data.len()`
        // for the header gu3dfGetInfo filled.
        unsafe {
            std::ptr::copy_nonoverlapping(
                data.as_ptr(),
                info.data as *mut u8,
                data.len().min(info.mem_required as usize),
            )
        };
        1
    })
}

// ----- the rest of 3dfx's SST-1 Glide 3 exports -------------------------------------
//
// Entry points 3dfx's SST-1 Glide 3 library exports but its headers do not declare
// (Glide 2 leftovers and utilities). Facts from 3dfx's source tree
// (glide3x/sst1/glide3/src), file named at each function.

/// `grSstVidMode(FxU32 whichSst, FxVideoTimingInfo *timing)` (disst.c): 3dfx keeps
/// the pointer for board `whichSst` and its next `grSstWinOpen` programs those video
/// timings instead of its table's. Not declared by 3dfx's headers (programs declare it
/// themselves). Ours accepts and ignores the timings: `grSstWinOpen` uses the table's
/// for the resolution asked (custom timings are not modelled yet). A board past
/// 3dfx's `MAX_NUM_SST` (4) is an error, as in 3dfx's debug build.
#[no_mangle]
pub extern "C" fn grSstVidMode(which: u32, _timing: *mut c_void) {
    entry("grSstVidMode", || {
        if which >= 4 {
            raise(
                format!("grSstVidMode:  {which} greater than MAX_NUM_SST (4)"),
                false,
            );
        }
    })
}

/// `FxBool grSstIsBusy(void)` (gsst.c): writes `nopCMD` = 1 unless one is outstanding
/// (which clears the pixel counters), then the status register's busy bit.
/// UNVERIFIED: no timing model yet; our board is always idle, so this is FXFALSE
/// and every call writes `nopCMD`. FXFALSE without a session.
#[no_mangle]
pub extern "C" fn grSstIsBusy() -> FxBool {
    entry("grSstIsBusy", || with(|c| FxBool::from(c.glide.is_busy())))
}

/// `FxBool grSstVRetraceOn(void)` (gsst.c): FXTRUE when the status register's
/// `SST_VRETRACE` bit is clear. UNVERIFIED: no timing model yet; our board's bit
/// flips at every status read, so consecutive calls alternate. FXFALSE without a session.
#[no_mangle]
pub extern "C" fn grSstVRetraceOn() -> FxBool {
    entry("grSstVRetraceOn", || {
        with(|c| FxBool::from(c.glide.vretrace_on()))
    })
}

/// `FxU32 grSstVideoLine(void)` (gsst.c): the `vRetrace` register as read.
/// UNVERIFIED: no timing model yet; an idle board of ours reads 0. 0 without a session.
#[no_mangle]
pub extern "C" fn grSstVideoLine() -> u32 {
    entry("grSstVideoLine", || with(|c| c.glide.video_line()))
}

/// `FxU32 grSstScreenWidth(void)` (disst.c): the open window's width (0 without a
/// session, where 3dfx asserts).
#[no_mangle]
pub extern "C" fn grSstScreenWidth() -> u32 {
    entry("grSstScreenWidth", || with(|c| c.glide.screen_size().0))
}

/// `FxU32 grSstScreenHeight(void)` (disst.c): the open window's height (0 without a
/// session).
#[no_mangle]
pub extern "C" fn grSstScreenHeight() -> u32 {
    entry("grSstScreenHeight", || with(|c| c.glide.screen_size().1))
}

/// `GrSstPerfStats_t` (3dfx glide.h): the FBI's five pixel counters.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GrSstPerfStats {
    /// Pixels processed (`fbiPixelsIn`).
    pub pixels_in: u32,
    /// Pixels not drawn for the chroma key (`fbiChromaFail`).
    pub chroma_fail: u32,
    /// Pixels not drawn for the depth test (`fbiZfuncFail`).
    pub z_func_fail: u32,
    /// Pixels not drawn for the alpha test (`fbiAfuncFail`).
    pub a_func_fail: u32,
    /// Pixels drawn (`fbiPixelsOut`).
    pub pixels_out: u32,
}

/// `void grSstPerfStats(GrSstPerfStats_t *)` (gsst.c): reads the five counters in
/// 3dfx's order (single board: no SLI sum). NULL is an error; nothing is written
/// without a session.
#[no_mangle]
pub unsafe extern "C" fn grSstPerfStats(stats: *mut GrSstPerfStats) {
    entry("grSstPerfStats", || {
        with(|c| {
            if stats.is_null() {
                c.glide.report_error("grSstPerfStats: NULL pointer");
                return;
            }
            let mut v = [0u32; 5];
            for (out, pname) in v.iter_mut().zip([
                GR_STATS_PIXELS_IN,
                GR_STATS_PIXELS_CHROMA_FAIL,
                GR_STATS_PIXELS_DEPTHFUNC_FAIL,
                GR_STATS_PIXELS_AFUNC_FAIL,
                GR_STATS_PIXELS_OUT,
            ]) {
                let mut word = [0i32; 1];
                c.glide.get(pname, 4, &mut word);
                *out = word[0] as u32;
            }
            let [pixels_in, chroma_fail, z_func_fail, a_func_fail, pixels_out] = v;
            // SAFETY: the caller's GrSstPerfStats_t (checked for null).
            unsafe {
                stats.write_unaligned(GrSstPerfStats {
                    pixels_in,
                    chroma_fail,
                    z_func_fail,
                    a_func_fail,
                    pixels_out,
                })
            };
        })
    })
}

/// `void grTriStats(FxU32 *trisProcessed, FxU32 *trisDrawn)` (diglide.c): the
/// triangle counters (`GR_STATS_TRIANGLES_IN`/`_OUT`). Null pointers are skipped;
/// 0 and 0 without a session (3dfx's counters outlive `grGlideShutdown`).
#[no_mangle]
pub unsafe extern "C" fn grTriStats(processed: *mut u32, drawn: *mut u32) {
    entry("grTriStats", || {
        let s = with(|c| {
            let s = c.glide.stats();
            (s.triangles_in, s.triangles_drawn)
        });
        // SAFETY: the caller's counters (checked for null).
        unsafe {
            if let Some(p) = processed.as_mut() {
                *p = s.0;
            }
            if let Some(d) = drawn.as_mut() {
                *d = s.1;
            }
        }
    })
}

/// `void grCheckForRoom(FxI32 n)` (gglide.c): waits until the command FIFO has room
/// for `n` bytes. Our board's FIFO is always empty, so it returns at once.
#[no_mangle]
pub extern "C" fn grCheckForRoom(_n: i32) {
    entry("grCheckForRoom", || {})
}

/// `GrTMUConfig_t` (3dfx fxglide.h).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GrTmuConfig {
    /// `tmuRev`.
    pub tmu_rev: c_int,
    /// `tmuRam`, MiB.
    pub tmu_ram: c_int,
}

/// `GrVoodooConfig_t` (3dfx fxglide.h, `GLIDE_NUM_TMU` 2 from glidesys.h); the largest
/// member of the `sstBoard` union, so the union's layout.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GrVoodooConfig {
    /// `fbRam`, MiB.
    pub fb_ram: c_int,
    /// `fbiRev`.
    pub fbi_rev: c_int,
    /// `nTexelfx`.
    pub n_texelfx: c_int,
    /// `sliDetect`.
    pub sli_detect: FxBool,
    /// `tmuConfig[GLIDE_NUM_TMU]`.
    pub tmu_config: [GrTmuConfig; 2],
}

/// One entry of `GrHwConfiguration::SSTs`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GrSstConfig {
    /// `GrSstType`: `GR_SSTTYPE_VOODOO` (0).
    pub ty: c_int,
    /// `sstBoard.VoodooConfig`.
    pub board: GrVoodooConfig,
}

/// `GrHwConfiguration` (3dfx fxglide.h, `MAX_NUM_SST` 4): 148 bytes. Not in 3dfx's
/// Glide 3 headers, so not in ours; Glide 2 programs bring their own.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GrHwConfiguration {
    /// `num_sst`.
    pub num_sst: c_int,
    /// `SSTs[MAX_NUM_SST]`.
    pub ssts: [GrSstConfig; 4],
}

const _: () = assert!(std::mem::size_of::<GrHwConfiguration>() == 148);

/// `FxBool grSstQueryBoards(GrHwConfiguration *)` (disst.c, valid before
/// `grGlideInit`): sets `num_sst` (one board) and nothing else; FXTRUE.
/// FXFALSE for NULL.
#[no_mangle]
pub unsafe extern "C" fn grSstQueryBoards(hwc: *mut GrHwConfiguration) -> FxBool {
    entry("grSstQueryBoards", || {
        if hwc.is_null() {
            raise("grSstQueryBoards: NULL pointer".into(), false);
            return 0;
        }
        // SAFETY: the caller's GrHwConfiguration (checked for null); only its first
        // field is written, as 3dfx's.
        unsafe { std::ptr::addr_of_mut!((*hwc).num_sst).write_unaligned(1) };
        1
    })
}

/// `FxBool grSstQueryHardware(GrHwConfiguration *)` (disst.c): copies the
/// configuration `grGlideInit` detected (gpci.c `_grSstDetectResources`: one
/// `GR_SSTTYPE_VOODOO` board, no SLI, each TMU's revision and memory) and returns
/// whether a board was found. Without a session the configuration is all zeros and
/// the answer FXFALSE, as 3dfx's before `grGlideInit`. TMUs past `GLIDE_NUM_TMU` (2)
/// are counted in `nTexelfx` but have no entry. FXFALSE for NULL.
#[no_mangle]
pub unsafe extern "C" fn grSstQueryHardware(hwc: *mut GrHwConfiguration) -> FxBool {
    entry("grSstQueryHardware", || {
        if hwc.is_null() {
            raise("grSstQueryHardware: NULL pointer".into(), false);
            return 0;
        }
        let hw = with(|c| Some(c.glide.query_hardware()));
        let mut out = GrHwConfiguration::default();
        if let Some(h) = hw {
            out.num_sst = h.num_sst as c_int;
            let b = &mut out.ssts[0].board;
            b.fb_ram = h.fb_ram as c_int;
            b.fbi_rev = h.fbi_rev as c_int;
            b.n_texelfx = h.num_tmu as c_int;
            for t in b.tmu_config.iter_mut().take(h.num_tmu as usize) {
                *t = GrTmuConfig {
                    tmu_rev: h.tmu_rev as c_int,
                    tmu_ram: h.tmu_ram as c_int,
                };
            }
        }
        // SAFETY: the caller's GrHwConfiguration (checked for null).
        unsafe { hwc.write_unaligned(out) };
        FxBool::from(out.num_sst > 0)
    })
}

/// `void grSstConfigPipeline(GrChipID_t chip, GrSstRegister reg, FxU32 value)`
/// (gsst.c; compiled out of later trees): writes `value` to word register `reg` of
/// TMU `chip` (`GR_FBI` is 0, TMU 0's value). See `Glide::config_pipeline`.
#[no_mangle]
pub extern "C" fn grSstConfigPipeline(chip: i32, reg: u32, value: u32) {
    entry("grSstConfigPipeline", || {
        with(|c| c.glide.config_pipeline(chip as u32, reg, value))
    })
}

/// `void grGlideShamelessPlug(const FxBool mode)` (diglide.c): the same switch as
/// `grEnable`/`grDisable(GR_SHAMELESS_PLUG)` (distate.c), the 3Dfx logo drawn at
/// each swap. Ours draws no logo, as with `grEnable(GR_SHAMELESS_PLUG)`.
#[no_mangle]
pub extern "C" fn grGlideShamelessPlug(mode: FxBool) {
    entry("grGlideShamelessPlug", || {
        with(|c| {
            if mode != 0 {
                c.glide.enable(GR_SHAMELESS_PLUG)
            } else {
                c.glide.disable(GR_SHAMELESS_PLUG)
            }
        })
    })
}

/// `char *grGetRegistryOrEnvironmentString(char *)` (diget.c): `getenv`; the same
/// function `grGetProcAddress` gives for `grGetRegistryOrEnvironmentStringExt`.
#[no_mangle]
pub unsafe extern "C" fn grGetRegistryOrEnvironmentString(name: *mut c_char) -> *mut c_char {
    entry("grGetRegistryOrEnvironmentString", || {
        // SAFETY: forwarded as the caller gave it.
        unsafe { grGetRegistryOrEnvironmentStringExt(name) }
    })
}

/// `void guAlphaSource(GrAlphaSource_t)` (gu.c): one `grAlphaCombine` per source;
/// another value is an error and changes nothing.
#[no_mangle]
pub extern "C" fn guAlphaSource(mode: i32) {
    entry("guAlphaSource", || {
        with(|c| {
            let (function, factor, local, other) = match mode as u32 {
                GR_ALPHASOURCE_CC_ALPHA => (
                    GR_COMBINE_FUNCTION_LOCAL,
                    GR_COMBINE_FACTOR_NONE,
                    GR_COMBINE_LOCAL_CONSTANT,
                    GR_COMBINE_OTHER_NONE,
                ),
                GR_ALPHASOURCE_ITERATED_ALPHA => (
                    GR_COMBINE_FUNCTION_LOCAL,
                    GR_COMBINE_FACTOR_NONE,
                    GR_COMBINE_LOCAL_ITERATED,
                    GR_COMBINE_OTHER_NONE,
                ),
                GR_ALPHASOURCE_TEXTURE_ALPHA => (
                    GR_COMBINE_FUNCTION_SCALE_OTHER,
                    GR_COMBINE_FACTOR_ONE,
                    GR_COMBINE_LOCAL_NONE,
                    GR_COMBINE_OTHER_TEXTURE,
                ),
                GR_ALPHASOURCE_TEXTURE_ALPHA_TIMES_ITERATED_ALPHA => (
                    GR_COMBINE_FUNCTION_SCALE_OTHER,
                    GR_COMBINE_FACTOR_LOCAL,
                    GR_COMBINE_LOCAL_ITERATED,
                    GR_COMBINE_OTHER_TEXTURE,
                ),
                _ => {
                    c.glide
                        .report_error("guAlphaSource: unknown alpha source mode");
                    return;
                }
            };
            c.glide.alpha_combine(function, factor, local, other, false);
        })
    })
}

/// `void guColorCombineFunction(GrColorCombineFnc_t)` (gu.c): leaves delta-0 mode,
/// then one `grColorCombine` per function; the two `*_DELTA0` functions enter
/// delta-0 mode first (see `Glide::color_combine_delta0`). Another value is an error
/// after leaving delta-0 mode, as 3dfx's.
#[no_mangle]
pub extern "C" fn guColorCombineFunction(fnc: i32) {
    entry("guColorCombineFunction", || {
        with(|c| {
            use glide::consts::{
                GR_COMBINE_FACTOR_LOCAL as F_LOCAL, GR_COMBINE_FACTOR_LOCAL_ALPHA as F_LALPHA,
                GR_COMBINE_FACTOR_NONE as F_NONE, GR_COMBINE_FACTOR_ONE as F_ONE,
                GR_COMBINE_FACTOR_TEXTURE_ALPHA as F_TALPHA, GR_COMBINE_FUNCTION_BLEND as BLEND,
                GR_COMBINE_FUNCTION_LOCAL as LOCAL, GR_COMBINE_FUNCTION_SCALE_OTHER as SCALE,
                GR_COMBINE_FUNCTION_SCALE_OTHER_ADD_LOCAL as SCALE_ADD,
                GR_COMBINE_FUNCTION_SCALE_OTHER_ADD_LOCAL_ALPHA as SCALE_ADD_ALPHA,
                GR_COMBINE_FUNCTION_SCALE_OTHER_MINUS_LOCAL as SCALE_SUB,
                GR_COMBINE_FUNCTION_ZERO as ZERO, GR_COMBINE_LOCAL_CONSTANT as L_CONST,
                GR_COMBINE_LOCAL_ITERATED as L_ITER, GR_COMBINE_LOCAL_NONE as L_NONE,
                GR_COMBINE_OTHER_ITERATED as O_ITER, GR_COMBINE_OTHER_NONE as O_NONE,
                GR_COMBINE_OTHER_TEXTURE as O_TEX,
            };
            c.glide.color_combine_delta0(false);
            let (function, factor, local, other, invert) = match fnc as u32 {
                GR_COLORCOMBINE_ZERO => (ZERO, F_NONE, L_NONE, O_NONE, false),
                GR_COLORCOMBINE_CCRGB => (LOCAL, F_NONE, L_CONST, O_NONE, false),
                GR_COLORCOMBINE_ITRGB_DELTA0 | GR_COLORCOMBINE_ITRGB => {
                    (LOCAL, F_NONE, L_ITER, O_NONE, false)
                }
                GR_COLORCOMBINE_DECAL_TEXTURE => (SCALE, F_ONE, L_NONE, O_TEX, false),
                GR_COLORCOMBINE_TEXTURE_TIMES_CCRGB => (SCALE, F_LOCAL, L_CONST, O_TEX, false),
                GR_COLORCOMBINE_TEXTURE_TIMES_ITRGB_DELTA0
                | GR_COLORCOMBINE_TEXTURE_TIMES_ITRGB => (SCALE, F_LOCAL, L_ITER, O_TEX, false),
                GR_COLORCOMBINE_TEXTURE_TIMES_ITRGB_ADD_ALPHA => {
                    (SCALE_ADD_ALPHA, F_LOCAL, L_ITER, O_TEX, false)
                }
                GR_COLORCOMBINE_TEXTURE_TIMES_ALPHA => (SCALE, F_LALPHA, L_NONE, O_TEX, false),
                GR_COLORCOMBINE_TEXTURE_TIMES_ALPHA_ADD_ITRGB => {
                    (SCALE_ADD, F_LALPHA, L_ITER, O_TEX, false)
                }
                GR_COLORCOMBINE_TEXTURE_ADD_ITRGB => (SCALE_ADD, F_ONE, L_ITER, O_TEX, false),
                GR_COLORCOMBINE_TEXTURE_SUB_ITRGB => (SCALE_SUB, F_ONE, L_ITER, O_TEX, false),
                GR_COLORCOMBINE_CCRGB_BLEND_ITRGB_ON_TEXALPHA => {
                    (BLEND, F_TALPHA, L_CONST, O_ITER, false)
                }
                GR_COLORCOMBINE_DIFF_SPEC_A => (SCALE_ADD, F_LALPHA, L_ITER, O_TEX, false),
                GR_COLORCOMBINE_DIFF_SPEC_B => (SCALE_ADD_ALPHA, F_LOCAL, L_ITER, O_TEX, false),
                GR_COLORCOMBINE_ONE => (ZERO, F_NONE, L_NONE, O_NONE, true),
                _ => {
                    c.glide
                        .report_error("guColorCombineFunction: unsupported color combine function");
                    return;
                }
            };
            if matches!(
                fnc as u32,
                GR_COLORCOMBINE_ITRGB_DELTA0 | GR_COLORCOMBINE_TEXTURE_TIMES_ITRGB_DELTA0
            ) {
                c.glide.color_combine_delta0(true);
            }
            c.glide
                .color_combine(function, factor, local, other, invert);
        })
    })
}

/// `FxU32 guEndianSwapWords(FxU32)` (gu.c): the two 16-bit halves exchanged.
#[no_mangle]
pub extern "C" fn guEndianSwapWords(value: u32) -> u32 {
    entry("guEndianSwapWords", || value.rotate_left(16))
}

/// `FxU16 guEndianSwapBytes(FxU16)` (gu.c): the two bytes exchanged.
#[no_mangle]
pub extern "C" fn guEndianSwapBytes(value: u16) -> u16 {
    entry("guEndianSwapBytes", || value.swap_bytes())
}

extern "C" {
    fn malloc(size: usize) -> *mut c_void;
}

/// `FxU16 *guTexCreateColorMipMap(void)` (gu.c): a `malloc`ed RGB565 mipmap of nine
/// levels, 256x256 down to 1x1, each one colour: red, green, blue, white, black, red,
/// green, blue, white (174,762 bytes; the program `free`s it). NULL when `malloc` fails.
#[no_mangle]
pub extern "C" fn guTexCreateColorMipMap() -> *mut u16 {
    entry("guTexCreateColorMipMap", || {
        const COLORS: [u16; 9] = [
            0xf800, 0x07e0, 0x001f, 0xffff, 0x0000, 0xf800, 0x07e0, 0x001f, 0xffff,
        ];
        let texels: usize = (0..9).map(|l| (256usize >> l) * (256 >> l)).sum();
        // SAFETY: malloc of a fixed size; the result is checked for null.
        let p = unsafe { malloc(texels * 2) } as *mut u16;
        if p.is_null() {
            return None;
        }
        let mut at = 0;
        for (l, color) in COLORS.iter().enumerate() {
            let n = (256usize >> l) * (256 >> l);
            for i in at..at + n {
                // SAFETY: i < texels, inside the allocation.
                unsafe { p.add(i).write(*color) };
            }
            at += n;
        }
        Some(p)
    })
    .unwrap_or(std::ptr::null_mut())
}

/// 3dfx's `guEncodeRLE16` loop (gu.c), step for step, over the `src.len()` pixels the
/// caller declared: words of `length << 16 | color`, `color` read as a signed 16-bit
/// value (so for colours from 0x8000 up it is sign-extended over the length, and never
/// equals the next pixel, which is read unsigned: their runs are 1 long). The loop
/// counts one pixel too many per run, so it stops early or runs on; where 3dfx's would
/// then read past the image, ours stops there (UNVERIFIED what 3dfx's gives then), and
/// where its 16-bit run length would wrap (32,768 equal pixels), ours ends the run.
/// Returns the bytes written (or, with `dst` None, that would be).
fn encode_rle16(src: &[u16], mut dst: Option<&mut dyn FnMut(usize, u32)>, count: i32) -> i32 {
    let mut remaining = count;
    let (mut at, mut bytes) = (0usize, 0i32);
    loop {
        let more = remaining != 0;
        remaining = remaining.wrapping_sub(1);
        if !more {
            return bytes;
        }
        let Some(&first) = src.get(at) else {
            return bytes;
        };
        let color = i32::from(first as i16);
        let mut length: i16 = 1;
        while remaining.wrapping_sub(i32::from(length)) != 0 {
            let Some(&next) = src.get(at + length as usize) else {
                return bytes;
            };
            if i32::from(next) != color || length == i16::MAX {
                break;
            }
            length += 1;
        }
        if let Some(put) = dst.as_mut() {
            put(bytes as usize / 4, (length as u32) << 16 | color as u32);
        }
        bytes += 4;
        at += length as usize;
        remaining = remaining.wrapping_sub(i32::from(length));
    }
}

/// `int guEncodeRLE16(void *dst, void *src, FxU32 width, FxU32 height)` (gu.c):
/// RGB565 pixels into 32-bit run words, `dst` NULL to count the bytes only; see
/// `encode_rle16` for 3dfx's loop, which this follows (its off-by-one included).
/// `dst` must hold the byte count a NULL-`dst` call returns. NULL `src` gives 0.
#[no_mangle]
pub unsafe extern "C" fn guEncodeRLE16(
    dst: *mut c_void,
    src: *const c_void,
    width: u32,
    height: u32,
) -> c_int {
    entry("guEncodeRLE16", || {
        if src.is_null() {
            return 0;
        }
        let count = width.wrapping_mul(height);
        let pixels = (width as usize)
            .saturating_mul(height as usize)
            .min(isize::MAX as usize / 2);
        // SAFETY: the caller's width x height image of 16-bit pixels.
        let src = unsafe { std::slice::from_raw_parts(src as *const u16, pixels) };
        let dst = dst as *mut u32;
        let mut put = |i: usize, word: u32| {
            // SAFETY: the caller sized `dst` from a NULL-`dst` call: word i is inside.
            unsafe { dst.add(i).write_unaligned(word) }
        };
        encode_rle16(
            src,
            (!dst.is_null()).then_some(&mut put as &mut dyn FnMut(usize, u32)),
            count as i32,
        )
    })
}

/// `void _grChromaModeExt(GrChromakeyMode_t)` (distate.c): stores the mode as
/// `grChromakeyMode` does; on the SST-1 only `GR_CHROMAKEY_ENABLE` enables the key,
/// any other value disables it (gglide.c `_grChromakeyMode`).
#[no_mangle]
pub extern "C" fn _grChromaModeExt(mode: i32) {
    entry("_grChromaModeExt", || {
        with(|c| {
            c.glide
                .chromakey_mode(if mode as u32 == GR_CHROMAKEY_ENABLE {
                    GR_CHROMAKEY_ENABLE
                } else {
                    GR_CHROMAKEY_DISABLE
                })
        })
    })
}

/// `void _grChromaRangeExt(GrColor_t color, GrColor_t range, GrChromaRangeMode_t)`
/// (distate.c): stores the key colour as `grChromakeyValue` does, and the range and
/// mode, which the SST-1 has no hardware for (gglide.c `_grChromaRange`).
#[no_mangle]
pub extern "C" fn _grChromaRangeExt(color: u32, range: u32, mode: i32) {
    entry("_grChromaRangeExt", || {
        with(|c| c.glide.chroma_range(color, range, mode as u32))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    static SEEN: Mutex<Vec<String>> = Mutex::new(Vec::new());

    unsafe extern "C" fn record(msg: *const c_char, _fatal: FxBool) {
        // SAFETY: entry() hands over a NUL-terminated string.
        let s = unsafe { CStr::from_ptr(msg) }
            .to_string_lossy()
            .into_owned();
        SEEN.lock().unwrap_or_else(PoisonError::into_inner).push(s);
    }

    /// One test for everything that touches the process's state (tests run on threads of
    /// one process): a panic inside an entry point, on purpose, never crosses the C
    /// boundary; it reaches the error callback and Glide goes on working.
    #[test]
    fn a_panic_inside_an_entry_point_becomes_an_error() {
        grErrorSetCallback(Some(record));
        // With no lock held.
        let r: u32 = entry("grPanicTest", || panic!("on purpose"));
        assert_eq!(r, 0);
        // With the process lock held: the mutex is poisoned, and recovered.
        let r: FxBool = entry("grPanicLocked", || with_process(|_| panic!("while locked")));
        assert_eq!(r, 0);
        // Taking the lock again from inside (it would deadlock) panics instead.
        let r: u32 = entry("grPanicNested", || with_process(|_| with_process(|_| 7)));
        assert_eq!(r, 0);
        // Errors raised inside one entry point arrive when it returns, in order, and the
        // callback may call Glide.
        grGlideInit();
        let mut tmus = 0;
        // SAFETY: a 4-byte answer into an i32.
        assert_eq!(unsafe { grGet(GR_NUM_TMU, 4, &mut tmus) }, 4);
        assert_eq!(tmus, 1);
        grDepthBufferFunction(99);
        grGlideShutdown();
        let seen = SEEN.lock().unwrap_or_else(PoisonError::into_inner).clone();
        assert_eq!(
            seen,
            [
                "grPanicTest: internal error: on purpose",
                "grPanicLocked: internal error: while locked",
                "grPanicNested: internal error: Glide re-entered while it holds its state",
                "grDepthBufferFunction: invalid compare function",
            ]
        );
    }

    /// A primitive's vertices read at once equal each vertex read on its own, on the
    /// stack and past it (offsets up to `grVertexLayout`'s largest).
    #[test]
    fn vertices_read_together_as_one_by_one() {
        let words: Vec<f32> = (0..3 * 300).map(|i| i as f32 * 0.5).collect();
        let at = |k: usize| words[k * 300..].as_ptr() as *const c_void;
        for (rgb_at, st1_at) in [(8, 20), (8, 116), (4, 124), (600, 12), (1012, 1016)] {
            let mut l = VertexLayout::default();
            l.xy.enabled = true;
            (l.rgb.offset, l.rgb.enabled) = (rgb_at, true);
            (l.st[1].offset, l.st[1].enabled) = (st1_at, true);
            // SAFETY: every vertex has 300 words, more than any layout reads.
            let (three, one) = unsafe {
                (
                    Vertices::read(&l, [at(0), at(1), at(2)]),
                    [0, 1, 2].map(|k| vertex(&l, at(k))),
                )
            };
            for (k, v) in one.iter().enumerate() {
                assert_eq!(three.get(k), &v[..], "rgb at {rgb_at}, vertex {k}");
            }
            assert_eq!(one[0].len(), vertex_words(&l));
        }
    }

    /// 3dfx's RLE16 loop, off-by-one and sign extension included (gu.c).
    #[test]
    fn rle16_follows_3dfx_loop() {
        let run = |src: &[u16]| {
            let mut words = Vec::new();
            let n = encode_rle16(
                src,
                Some(&mut |i: usize, w: u32| {
                    assert_eq!(i, words.len());
                    words.push(w)
                }),
                src.len() as i32,
            );
            assert_eq!(encode_rle16(src, None, src.len() as i32), n);
            assert_eq!(n as usize, 4 * words.len());
            words
        };
        // The count drops one pixel per run: the last pixel is never encoded.
        assert_eq!(run(&[0x1234, 0x0042]), [0x0001_1234]);
        assert_eq!(run(&[7, 7, 7, 9]), [0x0003_0007]);
        // From 0x8000 up the colour is sign-extended over the length.
        assert_eq!(run(&[0x8000, 0x8000]), [0xffff_8000]);
        // An odd count runs on past its end: we stop where 3dfx reads past the image.
        assert_eq!(run(&[1, 2, 3]), [0x0001_0001, 0x0001_0002]);
        assert_eq!(run(&[]), [0u32; 0]);
        // A run of 40,000 equal pixels ends at 32,767 (3dfx's length would wrap).
        let long = vec![5u16; 40_000];
        assert_eq!(run(&long), [0x7fff_0005, 0x1c3f_0005]);
    }

    /// Every function this library exports runs its body through `entry` under its own
    /// name (the `forward!` macro through `stringify!`), so no panic can cross the C
    /// boundary from any of them.
    #[test]
    fn every_exported_function_goes_through_entry() {
        let src = include_str!("lib.rs");
        let mut checked = 0;
        for (at, _) in src.match_indices("extern \"C\" fn ") {
            let rest = &src[at + "extern \"C\" fn ".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == '$')
                .collect();
            if name.is_empty() || name == "record" {
                continue; // a function-pointer type, or this test's callback
            }
            let open = rest.find('{').expect("a body");
            let mut depth = 0;
            let body_len = rest[open..]
                .char_indices()
                .find_map(|(i, c)| {
                    match c {
                        '{' => depth += 1,
                        '}' => depth -= 1,
                        _ => {}
                    }
                    (depth == 0).then_some(i)
                })
                .expect("a closed body");
            let body = &rest[open..open + body_len];
            let wanted = if name == "$name" {
                "entry(stringify!($name)".to_owned()
            } else {
                format!("entry(\"{name}\"")
            };
            assert!(body.contains(&wanted), "{name} does not go through entry()");
            checked += 1;
        }
        assert!(checked > 50, "only {checked} functions found");
    }
}

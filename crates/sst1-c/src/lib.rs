//! libsst1: the emulated SST-1 board as a C ABI, for host emulators.
//!
//! `include/sst1.h` declares every function and says what it does; this file is the
//! implementation. A host makes a board (`sst1_create`), forwards its guest's accesses
//! to the card's memory aperture and PCI configuration space (`sst1_write32`,
//! `sst1_read32`, `sst1_pci_write`, ...), and reads the displayed frame back
//! (`sst1_front_buffer_rgb565`, `sst1_front_buffer_rgba8`), told of each buffer swap by
//! a callback.
//!
//! Rules every entry point follows:
//! * no panic crosses the C boundary: the body runs under `catch_unwind` (`guard`) and
//!   a panic is returned as `SST1_ERR_INTERNAL`;
//! * every argument is checked before anything changes, and a bad one is returned as
//!   its [`Error`] code; enum arguments arrive as integers (a C enum may hold any value)
//!   and are decoded here;
//! * the board sits behind a mutex, and the swap callback is called after the lock is
//!   released and after the last use of the handle, so it may call back into the
//!   library, even to destroy the board.
//!
//! 16-bit writes reach the LFB (one pixel of a 16-bit format); in the register and
//! texture regions, which the SST-1 takes 32 bits wide only, they are refused.

#![allow(clippy::missing_safety_doc)]

use sst1_board::{Board, BoardConfig, BufferKind, Model, Reference, StateError, VectorIsa};
use sst1_regs::{addr, RegisterBus};
use std::ffi::{c_char, c_int, c_void, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// `SST1_API_VERSION`.
pub const API_VERSION: u32 = 3;
/// `SST1_APERTURE_SIZE`: the 16 MiB memory aperture.
pub const APERTURE_SIZE: u32 = 0x100_0000;
/// `SST1_LFB_BASE`: start of the LFB region.
const LFB_BASE: u32 = 0x40_0000;
/// `SST1_TEXTURE_BASE`: start of the texture region.
const TEXTURE_BASE: u32 = 0x80_0000;
/// `SST1_PCI_CONFIG_SIZE`: PCI configuration space.
pub const PCI_CONFIG_SIZE: u32 = 0x100;
/// `SST1_MAX_RENDER_THREADS`.
pub const MAX_RENDER_THREADS: u32 = 256;

/// `sst1_result`: `SST1_OK` is 0, each error a positive code. Keep in step with the
/// header's enum (the test `header_matches_the_library` compares them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(i32)]
pub enum Error {
    /// `SST1_ERR_NULL`.
    Null = 1,
    /// `SST1_ERR_BAD_OFFSET`.
    BadOffset = 2,
    /// `SST1_ERR_MISALIGNED`.
    Misaligned = 3,
    /// `SST1_ERR_BAD_SIZE`.
    BadSize = 4,
    /// `SST1_ERR_BUFFER_TOO_SMALL`.
    BufferTooSmall = 5,
    /// `SST1_ERR_BAD_CONFIG`.
    BadConfig = 6,
    /// `SST1_ERR_BAD_ARGUMENT`.
    BadArgument = 7,
    /// `SST1_ERR_UNSUPPORTED`.
    Unsupported = 8,
    /// `SST1_ERR_INTERNAL`.
    Internal = 9,
    /// `SST1_ERR_BAD_STATE`.
    BadState = 10,
    /// `SST1_ERR_STATE_VERSION`.
    StateVersion = 11,
    /// `SST1_ERR_STATE_MISMATCH`.
    StateMismatch = 12,
}

/// `SST1_OK`.
pub const OK: c_int = 0;

impl Error {
    /// Every code, in order.
    pub const ALL: [Error; 12] = [
        Error::Null,
        Error::BadOffset,
        Error::Misaligned,
        Error::BadSize,
        Error::BufferTooSmall,
        Error::BadConfig,
        Error::BadArgument,
        Error::Unsupported,
        Error::Internal,
        Error::BadState,
        Error::StateVersion,
        Error::StateMismatch,
    ];

    /// What `sst1_error_string` says, NUL-terminated.
    fn text(self) -> &'static CStr {
        match self {
            Error::Null => c"a required pointer is NULL",
            Error::BadOffset => c"offset outside the aperture or configuration space",
            Error::Misaligned => c"offset not aligned to the access size",
            Error::BadSize => c"access size is not 2 or 4 bytes",
            Error::BufferTooSmall => c"buffer too small for the result",
            Error::BadConfig => c"not a board configuration the SST-1 comes in",
            Error::BadArgument => c"argument out of range",
            Error::Unsupported => c"not modelled by this version of the board",
            Error::Internal => c"internal error in libsst1",
            Error::BadState => c"not a save state, or a damaged one",
            Error::StateVersion => c"save state in a format version this libsst1 does not read",
            Error::StateMismatch => c"save state of another board configuration or model",
        }
    }
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text().to_string_lossy())
    }
}

impl std::error::Error for Error {}

type Result<T> = std::result::Result<T, Error>;

/// `sst1_config`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sst1Config {
    /// Frame-buffer memory in MiB.
    pub fbi_mb: u32,
    /// Number of TMUs.
    pub tmus: u32,
    /// Texture memory per TMU in MiB.
    pub tmu_mb: u32,
}

impl Sst1Config {
    /// The board configuration, if the SST-1 comes in it (the values a trace's `config`
    /// lines accept). Out-of-range values are refused, not sanitized as
    /// `BoardConfig::sanitized` would: a host asking for 8 MiB should hear it gets none.
    fn board_config(self) -> Result<BoardConfig> {
        let ok = matches!(self.fbi_mb, 2 | 4)
            && matches!(self.tmus, 1..=3)
            && matches!(self.tmu_mb, 1 | 2 | 4);
        if !ok {
            return Err(Error::BadConfig);
        }
        Ok(BoardConfig {
            fbi_mb: self.fbi_mb,
            tmus: self.tmus,
            tmu_mb: self.tmu_mb,
        })
    }
}

/// `sst1_time`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sst1Time {
    /// Modelled graphics-clock cycles.
    pub cycles: u64,
    /// The graphics clock in Hz.
    pub clock_hz: u64,
    /// Buffer swaps executed.
    pub swaps: u64,
}

/// `sst1_swap_callback`.
pub type SwapCallback = Option<unsafe extern "C" fn(*mut c_void, *mut Sst1Board, u64)>;

/// The registered swap callback and its user pointer.
#[derive(Clone, Copy)]
struct Callback {
    function: unsafe extern "C" fn(*mut c_void, *mut Sst1Board, u64),
    user: *mut c_void,
}

// SAFETY: the user pointer is the host's, handed back to its callback untouched; the
// library never dereferences it. The header tells the host that the callback runs on
// whichever thread made the write, so what the pointer may be used from is the host's
// to arrange.
unsafe impl Send for Callback {}

/// What the board's lock guards.
struct Inner {
    board: Board,
    /// `sst1_set_render_threads`'s setting (0: the library's choice).
    render_threads: u32,
    /// Swaps already reported to the callback.
    swaps_reported: u64,
    callback: Option<Callback>,
}

/// `sst1_board`: what `sst1_create` hands out.
pub struct Sst1Board {
    inner: Mutex<Inner>,
}

impl Sst1Board {
    /// The board's state, locked. A panic while locked (caught by [`guard`]) poisons the
    /// mutex; the state is still memory-safe, so later calls go on with it.
    fn lock(&self) -> MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl Inner {
    /// The callback to call, and the swap count to give it, if the board swapped since
    /// the last report. Called after every write.
    fn swap_to_report(&mut self) -> Option<(Callback, u64)> {
        let swaps = self.board.stats().swaps;
        if swaps == self.swaps_reported {
            return None;
        }
        self.swaps_reported = swaps;
        self.callback.map(|c| (c, swaps))
    }
}

/// The C model number of `model`.
fn model_number(model: Model) -> c_int {
    match model {
        Model::Reference(Reference::Mame) => 1,
        Model::Reference(Reference::DosboxStaging) => 2,
        Model::Reference(Reference::Box86) => 3,
        // The C API makes only fixed models; a custom one reports as the hardware model
        // it departs from.
        Model::Hardware | Model::Custom(_) => 0,
    }
}

/// The model C's `sst1_model` value `n` stands for.
fn model_of(n: c_int) -> Result<Model> {
    match n {
        0 => Ok(Model::Hardware),
        1 => Ok(Model::Reference(Reference::Mame)),
        2 => Ok(Model::Reference(Reference::DosboxStaging)),
        3 => Ok(Model::Reference(Reference::Box86)),
        _ => Err(Error::BadArgument),
    }
}

/// The copy of the span kernels C's `sst1_isa` value `n` stands for.
fn isa_of(n: c_int) -> Result<VectorIsa> {
    match n {
        0 => Ok(VectorIsa::Baseline),
        1 => Ok(VectorIsa::Avx2),
        2 => Ok(VectorIsa::Avx512),
        _ => Err(Error::BadArgument),
    }
}

/// C's `sst1_isa` value of `isa`.
fn isa_number(isa: VectorIsa) -> c_int {
    match isa {
        VectorIsa::Baseline => 0,
        VectorIsa::Avx2 => 1,
        VectorIsa::Avx512 => 2,
    }
}

/// The buffer C's `sst1_buffer` value `n` stands for.
fn buffer_of(n: c_int) -> Result<BufferKind> {
    match n {
        0 => Ok(BufferKind::Front),
        1 => Ok(BufferKind::Back),
        2 => Ok(BufferKind::Aux),
        _ => Err(Error::BadArgument),
    }
}

/// The body of every entry point: its result as a C code, a panic as
/// `SST1_ERR_INTERNAL`. No panic crosses the C boundary.
fn guard(body: impl FnOnce() -> Result<()>) -> c_int {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => OK,
        Ok(Err(e)) => e as c_int,
        Err(_) => Error::Internal as c_int,
    }
}

/// The board behind a handle.
///
/// # Safety
/// `board` is NULL or a live handle from `sst1_create`.
unsafe fn handle<'a>(board: *const Sst1Board) -> Result<&'a Sst1Board> {
    // SAFETY: the caller's promise; NULL is refused.
    unsafe { board.as_ref() }.ok_or(Error::Null)
}

/// Stores `value` through `out`.
///
/// # Safety
/// `out` is NULL or valid for a write of `T`.
unsafe fn store<T>(out: *mut T, value: T) -> Result<()> {
    if out.is_null() {
        return Err(Error::Null);
    }
    // SAFETY: not NULL, and valid by the caller's promise.
    unsafe { out.write(value) };
    Ok(())
}

/// Stores `value` through `out` unless it is NULL (an optional out-parameter).
///
/// # Safety
/// `out` is NULL or valid for a write of `T`.
unsafe fn store_optional<T>(out: *mut T, value: T) {
    if !out.is_null() {
        // SAFETY: not NULL, and valid by the caller's promise.
        unsafe { out.write(value) };
    }
}

/// Checks an aperture offset for an access of `size` bytes.
fn check_aperture(offset: u32, size: u32) -> Result<()> {
    if offset >= APERTURE_SIZE {
        return Err(Error::BadOffset);
    }
    if !offset.is_multiple_of(size) {
        return Err(Error::Misaligned);
    }
    Ok(())
}

/// Runs a write on the board and then, with the lock released and the handle no longer
/// used, the swap callback if the write swapped. `write` checks its arguments and
/// writes.
///
/// # Safety
/// `board` is NULL or a live handle.
unsafe fn write_and_report(
    board: *mut Sst1Board,
    write: impl FnOnce(&mut Board) -> Result<()>,
) -> c_int {
    let mut report = None;
    let rc = guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        let mut inner = b.lock();
        write(&mut inner.board)?;
        report = inner.swap_to_report();
        Ok(())
    });
    if let Some((callback, swaps)) = report {
        // SAFETY: a function the host registered for this, called as the header says:
        // its user pointer, the board, the count. Nothing here touches the board after
        // it, so it may destroy the board.
        unsafe { (callback.function)(callback.user, board, swaps) };
    }
    rc
}

/// A 32-bit read, checked.
fn read32(board: &Sst1Board, offset: u32) -> Result<u32> {
    check_aperture(offset, 4)?;
    Ok(board.lock().board.read32(offset))
}

/// A 16-bit read, checked: the half of the 32-bit read that bit 1 selects.
fn read16(board: &Sst1Board, offset: u32) -> Result<u16> {
    check_aperture(offset, 2)?;
    let word = board.lock().board.read32(offset & !3);
    Ok(if offset & 2 != 0 {
        (word >> 16) as u16
    } else {
        word as u16
    })
}

/// A 16-bit write, checked: into the LFB (`Board::write16`); refused in the register
/// and texture regions, which the SST-1 takes 32 bits wide only (spec 4, 9).
fn write16(board: &mut Board, offset: u32, value: u16) -> Result<()> {
    check_aperture(offset, 2)?;
    if !(LFB_BASE..TEXTURE_BASE).contains(&offset) {
        return Err(Error::Unsupported);
    }
    board.write16(offset, value);
    Ok(())
}

/// Copies buffer `which` into the caller's `len` values at `pixels` with `convert`
/// (`per_pixel` outputs for each pixel), storing the size.
///
/// # Safety
/// `pixels` is NULL or valid for `len` writes of `T`; `width`, `height` NULL or valid.
unsafe fn copy_buffer<T: Copy, const N: usize>(
    board: &Sst1Board,
    which: BufferKind,
    pixels: *mut T,
    len: usize,
    width: *mut u32,
    height: *mut u32,
    convert: impl Fn(u16) -> [T; N],
) -> Result<()> {
    if pixels.is_null() {
        return Err(Error::Null);
    }
    let inner = board.lock();
    let (w, h) = inner.board.display_size();
    // SAFETY: the caller's promise for the size pointers.
    unsafe {
        store_optional(width, w);
        store_optional(height, h);
    }
    let need = (w as usize) * (h as usize) * N;
    if len < need {
        return Err(Error::BufferTooSmall);
    }
    let values = inner.board.dump_buffer(which);
    drop(inner);
    // SAFETY: `pixels` is not NULL and holds `len >= need` values (the caller's promise).
    let out = unsafe { std::slice::from_raw_parts_mut(pixels, need) };
    for (chunk, &v) in out.chunks_exact_mut(N).zip(&values) {
        chunk.copy_from_slice(&convert(v));
    }
    Ok(())
}

// ---------------------------------------------------------------------------------
// Library

/// `sst1_api_version`.
#[no_mangle]
pub extern "C" fn sst1_api_version() -> u32 {
    API_VERSION
}

/// `sst1_error_string`.
#[no_mangle]
pub extern "C" fn sst1_error_string(result: c_int) -> *const c_char {
    match Error::ALL.into_iter().find(|&e| e as c_int == result) {
        Some(e) => e.text().as_ptr(),
        None if result == OK => c"no error".as_ptr(),
        None => c"unknown error".as_ptr(),
    }
}

/// `sst1_model_from_name`.
#[no_mangle]
pub unsafe extern "C" fn sst1_model_from_name(name: *const c_char, model: *mut c_int) -> c_int {
    guard(|| {
        if name.is_null() || model.is_null() {
            return Err(Error::Null);
        }
        // SAFETY: a NUL-terminated string by the header's contract.
        let name = unsafe { CStr::from_ptr(name) };
        let found = match name.to_str() {
            Ok("hardware") => Model::Hardware,
            Ok(n) => Model::Reference(Reference::from_name(n).ok_or(Error::BadArgument)?),
            Err(_) => return Err(Error::BadArgument),
        };
        // SAFETY: not NULL, valid by the caller's promise.
        unsafe { store(model, model_number(found)) }
    })
}

// ---------------------------------------------------------------------------------
// Boards

/// `sst1_create`.
#[no_mangle]
pub unsafe extern "C" fn sst1_create(
    config: *const Sst1Config,
    model: c_int,
    board: *mut *mut Sst1Board,
) -> c_int {
    guard(|| {
        if board.is_null() {
            return Err(Error::Null);
        }
        // SAFETY: not NULL, valid by the caller's promise; cleared first so that every
        // failure leaves NULL there.
        unsafe { board.write(std::ptr::null_mut()) };
        // SAFETY: NULL or a valid config, by the caller's promise.
        let config = unsafe { config.as_ref() }.ok_or(Error::Null)?;
        let config = config.board_config()?;
        let model = model_of(model)?;
        let mut b = Board::new(config);
        b.set_model(model);
        let handle = Box::new(Sst1Board {
            inner: Mutex::new(Inner {
                board: b,
                render_threads: 0,
                swaps_reported: 0,
                callback: None,
            }),
        });
        // SAFETY: as above.
        unsafe { board.write(Box::into_raw(handle)) };
        Ok(())
    })
}

/// `sst1_destroy`.
#[no_mangle]
pub unsafe extern "C" fn sst1_destroy(board: *mut Sst1Board) -> c_int {
    guard(|| {
        if !board.is_null() {
            // SAFETY: a handle from sst1_create, not used again (the caller's promise).
            drop(unsafe { Box::from_raw(board) });
        }
        Ok(())
    })
}

/// `sst1_get_config`.
#[no_mangle]
pub unsafe extern "C" fn sst1_get_config(
    board: *const Sst1Board,
    config: *mut Sst1Config,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        if config.is_null() {
            return Err(Error::Null);
        }
        let c = b.lock().board.config();
        let out = Sst1Config {
            fbi_mb: c.fbi_mb,
            tmus: c.tmus,
            tmu_mb: c.tmu_mb,
        };
        // SAFETY: not NULL, valid by the caller's promise.
        unsafe { store(config, out) }
    })
}

/// `sst1_set_model`.
#[no_mangle]
pub unsafe extern "C" fn sst1_set_model(board: *mut Sst1Board, model: c_int) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        let model = model_of(model)?;
        b.lock().board.set_model(model);
        Ok(())
    })
}

/// `sst1_get_model`.
#[no_mangle]
pub unsafe extern "C" fn sst1_get_model(board: *const Sst1Board, model: *mut c_int) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        let m = model_number(b.lock().board.model());
        // SAFETY: NULL or valid, by the caller's promise.
        unsafe { store(model, m) }
    })
}

/// `sst1_set_render_threads`.
#[no_mangle]
pub unsafe extern "C" fn sst1_set_render_threads(board: *mut Sst1Board, threads: u32) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        if threads > MAX_RENDER_THREADS {
            return Err(Error::BadArgument);
        }
        let mut inner = b.lock();
        inner.render_threads = threads;
        let n = if threads == 0 {
            std::thread::available_parallelism().map_or(1, |n| n.get())
        } else {
            threads as usize
        };
        inner.board.set_threads(n);
        Ok(())
    })
}

/// `sst1_get_render_threads`.
#[no_mangle]
pub unsafe extern "C" fn sst1_get_render_threads(
    board: *const Sst1Board,
    threads: *mut u32,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        let n = b.lock().render_threads;
        // SAFETY: NULL or valid, by the caller's promise.
        unsafe { store(threads, n) }
    })
}

/// `sst1_set_vector_isa`.
#[no_mangle]
pub unsafe extern "C" fn sst1_set_vector_isa(
    board: *mut Sst1Board,
    isa: c_int,
    used: *mut c_int,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        let isa = isa_of(isa)?;
        let running = b.lock().board.set_vector_isa(isa);
        // SAFETY: NULL or valid, by the caller's promise.
        unsafe { store_optional(used, isa_number(running)) };
        Ok(())
    })
}

/// `sst1_get_vector_isa`.
#[no_mangle]
pub unsafe extern "C" fn sst1_get_vector_isa(board: *const Sst1Board, isa: *mut c_int) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        let running = isa_number(b.lock().board.vector_isa());
        // SAFETY: NULL or valid, by the caller's promise.
        unsafe { store(isa, running) }
    })
}

// ---------------------------------------------------------------------------------
// Bus accesses

/// `sst1_write32`.
#[no_mangle]
pub unsafe extern "C" fn sst1_write32(board: *mut Sst1Board, offset: u32, value: u32) -> c_int {
    // SAFETY: the caller's promise.
    unsafe {
        write_and_report(board, |b| {
            check_aperture(offset, 4)?;
            b.write32(offset, value);
            Ok(())
        })
    }
}

/// `sst1_write16`.
#[no_mangle]
pub unsafe extern "C" fn sst1_write16(board: *mut Sst1Board, offset: u32, value: u16) -> c_int {
    // SAFETY: the caller's promise.
    unsafe { write_and_report(board, |b| write16(b, offset, value)) }
}

/// `sst1_read32`.
#[no_mangle]
pub unsafe extern "C" fn sst1_read32(board: *mut Sst1Board, offset: u32, value: *mut u32) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        if value.is_null() {
            return Err(Error::Null);
        }
        let v = read32(b, offset)?;
        // SAFETY: not NULL, valid by the caller's promise.
        unsafe { store(value, v) }
    })
}

/// `sst1_read16`.
#[no_mangle]
pub unsafe extern "C" fn sst1_read16(board: *mut Sst1Board, offset: u32, value: *mut u16) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        if value.is_null() {
            return Err(Error::Null);
        }
        let v = read16(b, offset)?;
        // SAFETY: not NULL, valid by the caller's promise.
        unsafe { store(value, v) }
    })
}

/// `sst1_write`.
#[no_mangle]
pub unsafe extern "C" fn sst1_write(
    board: *mut Sst1Board,
    offset: u32,
    size: u32,
    value: u32,
) -> c_int {
    // SAFETY: the caller's promise.
    unsafe {
        write_and_report(board, |b| match size {
            4 => {
                check_aperture(offset, 4)?;
                b.write32(offset, value);
                Ok(())
            }
            2 => write16(b, offset, value as u16),
            _ => Err(Error::BadSize),
        })
    }
}

/// `sst1_read`.
#[no_mangle]
pub unsafe extern "C" fn sst1_read(
    board: *mut Sst1Board,
    offset: u32,
    size: u32,
    value: *mut u32,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        if value.is_null() {
            return Err(Error::Null);
        }
        let v = match size {
            4 => read32(b, offset)?,
            2 => u32::from(read16(b, offset)?),
            _ => return Err(Error::BadSize),
        };
        // SAFETY: not NULL, valid by the caller's promise.
        unsafe { store(value, v) }
    })
}

/// `sst1_pci_write`.
#[no_mangle]
pub unsafe extern "C" fn sst1_pci_write(board: *mut Sst1Board, offset: u32, value: u32) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        if offset >= PCI_CONFIG_SIZE {
            return Err(Error::BadOffset);
        }
        if !offset.is_multiple_of(4) {
            return Err(Error::Misaligned);
        }
        b.lock().board.pci_write(offset, value);
        Ok(())
    })
}

// ---------------------------------------------------------------------------------
// The displayed frame

/// `sst1_display_size`.
#[no_mangle]
pub unsafe extern "C" fn sst1_display_size(
    board: *const Sst1Board,
    width: *mut u32,
    height: *mut u32,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        if width.is_null() && height.is_null() {
            return Err(Error::Null);
        }
        let (w, h) = b.lock().board.display_size();
        // SAFETY: NULL or valid, by the caller's promise.
        unsafe {
            store_optional(width, w);
            store_optional(height, h);
        }
        Ok(())
    })
}

/// `sst1_read_buffer`.
#[no_mangle]
pub unsafe extern "C" fn sst1_read_buffer(
    board: *const Sst1Board,
    which: c_int,
    pixels: *mut u16,
    capacity: usize,
    width: *mut u32,
    height: *mut u32,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        let which = buffer_of(which)?;
        // SAFETY: the caller's promise for the pointers and capacity.
        unsafe { copy_buffer(b, which, pixels, capacity, width, height, |v| [v]) }
    })
}

/// `sst1_front_buffer_rgb565`.
#[no_mangle]
pub unsafe extern "C" fn sst1_front_buffer_rgb565(
    board: *const Sst1Board,
    pixels: *mut u16,
    capacity: usize,
    width: *mut u32,
    height: *mut u32,
) -> c_int {
    // SAFETY: the caller's promise.
    unsafe { sst1_read_buffer(board, 0, pixels, capacity, width, height) }
}

/// `sst1_front_buffer_rgba8`.
#[no_mangle]
pub unsafe extern "C" fn sst1_front_buffer_rgba8(
    board: *const Sst1Board,
    rgba: *mut u8,
    capacity: usize,
    width: *mut u32,
    height: *mut u32,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        // SAFETY: the caller's promise for the pointers and capacity.
        unsafe {
            copy_buffer(b, BufferKind::Front, rgba, capacity, width, height, |v| {
                let [r, g, b] = sst1_trace::rgb565_to_rgb8(v);
                [r, g, b, 0xff]
            })
        }
    })
}

/// `sst1_set_swap_callback`.
#[no_mangle]
pub unsafe extern "C" fn sst1_set_swap_callback(
    board: *mut Sst1Board,
    callback: SwapCallback,
    user: *mut c_void,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        let mut inner = b.lock();
        // Swaps before the callback was set are not reported to it.
        inner.swaps_reported = inner.board.stats().swaps;
        inner.callback = callback.map(|function| Callback { function, user });
        Ok(())
    })
}

/// `sst1_swap_count`.
#[no_mangle]
pub unsafe extern "C" fn sst1_swap_count(board: *const Sst1Board, count: *mut u64) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        let n = b.lock().board.stats().swaps;
        // SAFETY: NULL or valid, by the caller's promise.
        unsafe { store(count, n) }
    })
}

// ---------------------------------------------------------------------------------
// Time and vertical retrace

/// `sst1_get_time`.
#[no_mangle]
pub unsafe extern "C" fn sst1_get_time(board: *const Sst1Board, time: *mut Sst1Time) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        let inner = b.lock();
        let timing = inner.board.timing();
        let t = Sst1Time {
            cycles: timing.cycles(),
            clock_hz: timing.clock_hz,
            swaps: inner.board.stats().swaps,
        };
        drop(inner);
        // SAFETY: NULL or valid, by the caller's promise.
        unsafe { store(time, t) }
    })
}

/// `sst1_advance_time`: host time with no bus access, as graphics clocks of the board
/// (`RegisterBus::host_wait`, what a trace's `wait` line does).
#[no_mangle]
pub unsafe extern "C" fn sst1_advance_time(board: *mut Sst1Board, nanoseconds: u64) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        let mut inner = b.lock();
        let hz = u128::from(inner.board.timing().clock_hz);
        let cycles =
            u64::try_from(u128::from(nanoseconds) * hz / 1_000_000_000).unwrap_or(u64::MAX);
        inner.board.host_wait(cycles);
        Ok(())
    })
}

/// `sst1_vertical_retrace`.
#[no_mangle]
pub unsafe extern "C" fn sst1_vertical_retrace(board: *mut Sst1Board, active: *mut c_int) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        if active.is_null() {
            return Err(Error::Null);
        }
        // status bit 6 reads 0 while the retrace is active (spec 5.1).
        let status = b.lock().board.read32(addr::STATUS);
        // SAFETY: not NULL, valid by the caller's promise.
        unsafe { store(active, c_int::from(status & 0x40 == 0)) }
    })
}

// ---------------------------------------------------------------------------------
// Save states

/// The C code of a refused save state.
fn state_error(e: &StateError) -> Error {
    match e {
        StateError::NewerVersion { .. } | StateError::OlderVersion { .. } => Error::StateVersion,
        StateError::OtherConfig { .. } | StateError::OtherModel { .. } => Error::StateMismatch,
        StateError::NotAState | StateError::Corrupt(_) | StateError::TooLarge { .. } => {
            Error::BadState
        }
    }
}

/// `sst1_save_state`.
#[no_mangle]
pub unsafe extern "C" fn sst1_save_state(
    board: *const Sst1Board,
    buffer: *mut c_void,
    capacity: usize,
    length: *mut usize,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        if length.is_null() {
            return Err(Error::Null);
        }
        let state = b.lock().board.save_state();
        // SAFETY: not NULL, valid by the caller's promise.
        unsafe { store(length, state.len()) }?;
        if buffer.is_null() {
            // The size query.
            return Ok(());
        }
        if capacity < state.len() {
            return Err(Error::BufferTooSmall);
        }
        // SAFETY: `buffer` is not NULL and holds `capacity >= state.len()` bytes (the
        // caller's promise); a fresh Vec does not overlap it.
        unsafe { std::ptr::copy_nonoverlapping(state.as_ptr(), buffer.cast::<u8>(), state.len()) };
        Ok(())
    })
}

/// `sst1_load_state`.
#[no_mangle]
pub unsafe extern "C" fn sst1_load_state(
    board: *mut Sst1Board,
    state: *const c_void,
    length: usize,
) -> c_int {
    guard(|| {
        // SAFETY: the caller's promise.
        let b = unsafe { handle(board) }?;
        if state.is_null() {
            return Err(Error::Null);
        }
        // SAFETY: not NULL, `length` readable bytes by the caller's promise.
        let bytes = unsafe { std::slice::from_raw_parts(state.cast::<u8>(), length) };
        let mut inner = b.lock();
        inner.board.load_state(bytes).map_err(|e| state_error(&e))?;
        // The restored swap count is not a swap to report.
        inner.swaps_reported = inner.board.stats().swaps;
        Ok(())
    })
}

/* sst1.h -- the voodoo-rs emulated SST-1 (3dfx Voodoo Graphics) board as a C library.
 *
 * Written for this project. libsst1 is the board itself, driven the way a host
 * emulator's memory handlers drive a PCI card: 32- and 16-bit accesses at offsets of
 * the card's 16 MiB memory aperture and writes to its PCI configuration space. It is
 * for PC and arcade emulators that need a Voodoo Graphics card; Glide programs use
 * libglide3 instead (crates/glide3-c).
 *
 *   aperture offset     region
 *   0x000000-0x3fffff   registers (bits 13:10 chip select, bit 21 the alternate map)
 *   0x400000-0x7fffff   linear frame buffer (LFB)
 *   0x800000-0xffffff   texture memory (bits 22:21 select the TMU)
 *
 * Commands (triangles, fills, buffer swaps) run to completion inside the write that
 * starts them, so the frame buffer is up to date when a write returns.
 *
 * Errors: every function returns an sst1_result (or a value documented with it). No
 * argument, however wrong, crashes the library: NULL pointers, offsets outside the
 * aperture, misaligned offsets, access sizes other than 2 and 4, buffers too small and
 * out-of-range enum values are refused with a code and change nothing. A Rust panic
 * inside the library never crosses into the caller; it is returned as
 * SST1_ERR_INTERNAL (a bug of ours; the board stays usable but its state may be off).
 * The one thing the library cannot check is a pointer that is not NULL but does not
 * point where it should (a board already destroyed, a buffer shorter than its stated
 * capacity): that is undefined behaviour, as in any C library.
 *
 * Threads: a board may be used from any thread. Each call on a board holds that board's
 * lock for its duration, so calls on one board from several threads are serialised;
 * different boards share nothing and run in parallel. The swap callback is called with
 * the lock released (see sst1_set_swap_callback).
 */
#ifndef VOODOO_RS_SST1_H
#define VOODOO_RS_SST1_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The version of this interface that sst1_api_version() returns. It grows by one when
 * a function or a field is added; existing ones keep their meaning. */
#define SST1_API_VERSION 3

/* Size of the memory aperture in bytes (16 MiB). Valid offsets are below it. */
#define SST1_APERTURE_SIZE 0x1000000u
/* Start of the LFB region and of the texture region in the aperture. */
#define SST1_LFB_BASE 0x400000u
#define SST1_TEXTURE_BASE 0x800000u
/* Size of PCI configuration space in bytes. Valid configuration offsets are below it. */
#define SST1_PCI_CONFIG_SIZE 0x100u
/* The most render threads sst1_set_render_threads accepts. */
#define SST1_MAX_RENDER_THREADS 256u

/* What a call returned. SST1_OK is 0; every error is a positive value. */
typedef enum sst1_result {
    /* The call did what it says. */
    SST1_OK = 0,
    /* A pointer the call needs is NULL. */
    SST1_ERR_NULL = 1,
    /* An offset outside the aperture (at or above SST1_APERTURE_SIZE) or outside PCI
     * configuration space (at or above SST1_PCI_CONFIG_SIZE). */
    SST1_ERR_BAD_OFFSET = 2,
    /* An offset not aligned to the access: 32-bit accesses and PCI configuration
     * writes need a multiple of 4, 16-bit accesses a multiple of 2. */
    SST1_ERR_MISALIGNED = 3,
    /* An access size other than 2 or 4 bytes (sst1_read, sst1_write). */
    SST1_ERR_BAD_SIZE = 4,
    /* The caller's buffer holds fewer elements than the result needs; the width and
     * height are still reported, so the caller can size the buffer and call again. */
    SST1_ERR_BUFFER_TOO_SMALL = 5,
    /* A board configuration the SST-1 does not come in (see sst1_config). */
    SST1_ERR_BAD_CONFIG = 6,
    /* An argument out of its range: an unknown model or buffer, a thread count above
     * SST1_MAX_RENDER_THREADS, a model name the library does not know. */
    SST1_ERR_BAD_ARGUMENT = 7,
    /* Something this version of the board does not model (the call's documentation
     * says what); nothing changed. */
    SST1_ERR_UNSUPPORTED = 8,
    /* A bug in the library (an internal panic, caught). */
    SST1_ERR_INTERNAL = 9,
    /* sst1_load_state: not a save state, or a damaged, cut-short or forged one. */
    SST1_ERR_BAD_STATE = 10,
    /* sst1_load_state: a state in a format version this library does not read (newer,
     * or older than the one it writes). */
    SST1_ERR_STATE_VERSION = 11,
    /* sst1_load_state: a state of a board with another configuration or model. */
    SST1_ERR_STATE_MISMATCH = 12
} sst1_result;

/* The model the chips run. Where the reference emulators disagree about what the
 * SST-1 does, each model makes one choice (docs/accuracy.md). */
typedef enum sst1_model {
    /* Our reading of the SST-1: what `voodoo replay` and libglide3 run. The default. */
    SST1_MODEL_HARDWARE = 0,
    /* The board as MAME emulates it. */
    SST1_MODEL_MAME = 1,
    /* The board as DOSBox Staging emulates it. */
    SST1_MODEL_DOSBOX_STAGING = 2,
    /* The board as 86Box emulates it. */
    SST1_MODEL_86BOX = 3
} sst1_model;

/* A buffer of the frame buffer. */
typedef enum sst1_buffer {
    /* The colour buffer being displayed (RGB565). */
    SST1_BUFFER_FRONT = 0,
    /* The colour buffer being drawn (RGB565). */
    SST1_BUFFER_BACK = 1,
    /* The auxiliary buffer: 16-bit depth or alpha values as stored. */
    SST1_BUFFER_AUX = 2
} sst1_buffer;

/* What is on the board. The SST-1 comes with 2 or 4 MiB of frame-buffer memory and
 * one to three TMUs of 1, 2 or 4 MiB of texture memory each; any other value is
 * refused with SST1_ERR_BAD_CONFIG. The usual board is { 4, 1, 4 }. */
typedef struct sst1_config {
    /* Frame-buffer memory in MiB: 2 or 4. */
    uint32_t fbi_mb;
    /* Number of TMUs (Texelfx chips): 1, 2 or 3. */
    uint32_t tmus;
    /* Texture memory of each TMU in MiB: 1, 2 or 4. */
    uint32_t tmu_mb;
} sst1_config;

/* The board's modelled time (docs/timing.md): graphics-clock cycles counted from the
 * commands the board ran and the bus accesses that fed them, the same on every run. */
typedef struct sst1_time {
    /* Graphics-clock cycles the real board would have taken so far. */
    uint64_t cycles;
    /* The graphics clock in Hz (50 MHz). cycles / clock_hz is the time in seconds. */
    uint64_t clock_hz;
    /* Buffer swaps (swapbufferCMD) executed so far: the frames drawn. */
    uint64_t swaps;
} sst1_time;

/* An emulated board. Opaque: made by sst1_create, freed by sst1_destroy. */
typedef struct sst1_board sst1_board;

/* Called after a write whose swapbufferCMD swapped the buffers: `user` is the pointer
 * given to sst1_set_swap_callback, `board` the board, `swap_count` the number of swaps
 * so far (1 for the first). */
typedef void (*sst1_swap_callback)(void *user, sst1_board *board, uint64_t swap_count);

/* ------------------------------------------------------------------------------ */
/* Library                                                                          */

/* The version of the interface the library implements (SST1_API_VERSION when the
 * library and this header match). */
uint32_t sst1_api_version(void);

/* A short English description of `result`, e.g. "offset outside the aperture". Never
 * NULL: an unknown value gives "unknown error". The string is static; do not free it. */
const char *sst1_error_string(sst1_result result);

/* The model named `name`: "hardware", "mame", "dosbox-staging" or "86box" (the names
 * of `voodoo replay --model`), stored in *model. SST1_ERR_NULL if either pointer is
 * NULL, SST1_ERR_BAD_ARGUMENT (and *model unchanged) for any other name. */
sst1_result sst1_model_from_name(const char *name, sst1_model *model);

/* ------------------------------------------------------------------------------ */
/* Boards                                                                           */

/* Makes a board in its power-on state with configuration *config, running `model`, and
 * stores it in *board. SST1_ERR_NULL if `config` or `board` is NULL,
 * SST1_ERR_BAD_CONFIG if *config is not a board the SST-1 comes as,
 * SST1_ERR_BAD_ARGUMENT for an unknown model; *board is then set to NULL (if it is not
 * NULL itself). Free the board with sst1_destroy. */
sst1_result sst1_create(const sst1_config *config, sst1_model model, sst1_board **board);

/* Frees `board` and everything it holds. NULL is allowed and does nothing (SST1_OK).
 * The board must not be used again, nor be in use by another thread. May be called
 * from the board's own swap callback (the library does not touch the board after the
 * callback returns). */
sst1_result sst1_destroy(sst1_board *board);

/* Stores the board's configuration in *config. SST1_ERR_NULL if a pointer is NULL. */
sst1_result sst1_get_config(const sst1_board *board, sst1_config *config);

/* Makes the chips run `model` from the next access on; the frame buffer, texture
 * memory and registers are kept. SST1_ERR_BAD_ARGUMENT for an unknown model. */
sst1_result sst1_set_model(sst1_board *board, sst1_model model);

/* Stores the model the chips run in *model. */
sst1_result sst1_get_model(const sst1_board *board, sst1_model *model);

/* Sets how many threads the board may render on: 0 lets the library choose (the
 * machine's cores), 1 to SST1_MAX_RENDER_THREADS asks for that many (more is
 * SST1_ERR_BAD_ARGUMENT); sst1_get_render_threads returns the setting. Until it is
 * called the board renders on the calling thread. Every command still completes inside
 * the write that starts it; the rows of a large triangle are shaded in bands
 * on that many threads meanwhile. The output is the same for every setting. */
sst1_result sst1_set_render_threads(sst1_board *board, uint32_t threads);

/* Stores the setting of sst1_set_render_threads in *threads (0 until it is called). */
sst1_result sst1_get_render_threads(const sst1_board *board, uint32_t *threads);

/* The copies of the fast path's span kernels, by the instructions they may use (API
 * version 3). Every copy gives the same pixels, counters and cycles; only the speed
 * differs. Only the hardware model has the vector copies; the others run the baseline
 * one whatever is set. */
typedef enum sst1_isa {
    SST1_ISA_BASELINE = 0,
    SST1_ISA_AVX2 = 1,
    SST1_ISA_AVX512 = 2
} sst1_isa;

/* Runs the copy `isa` names, or the best the CPU has below it, and stores the copy
 * that will run in *used (which may be NULL). SST1_ERR_BAD_ARGUMENT for a value not in
 * sst1_isa. A board starts with the best copy the CPU has. */
sst1_result sst1_set_vector_isa(sst1_board *board, sst1_isa isa, sst1_isa *used);

/* Stores the copy of the kernels the board runs in *isa. */
sst1_result sst1_get_vector_isa(const sst1_board *board, sst1_isa *isa);

/* ------------------------------------------------------------------------------ */
/* Bus accesses: what a host's memory and PCI configuration handlers call           */

/* A 32-bit write of `value` at aperture `offset` (a multiple of 4, below
 * SST1_APERTURE_SIZE; the host subtracts the card's base address). Register writes
 * go to the chips the address selects, LFB writes into the frame buffer in the
 * format lfbMode sets, texture writes into the selected TMU's memory; writes the board
 * ignores (reserved or read-only registers, fbiInit registers while PCI initEnable
 * bit 0 is clear, a TMU the board does not have) are accepted as the hardware accepts
 * them (SST1_OK). A command register write runs the command before returning; a
 * swapbufferCMD calls the swap callback before returning. */
sst1_result sst1_write32(sst1_board *board, uint32_t offset, uint32_t value);

/* A 16-bit write at aperture `offset` (a multiple of 2). In the LFB it is the half of
 * a 32-bit LFB write that bit 1 of `offset` selects, and changes only what that half
 * carries: in the 16-bit formats (lfbMode 0-2, 15) one pixel, its neighbour in the
 * 32-bit word left as it is; lfbMode's word swap and byte swizzle move the half with
 * the data (with word swap, a write at offset + 2 stores the first pixel of the
 * pair). In the 32-bit formats a write of the low half stores the pixel (formats 4,
 * 5) or its colour (12-14), one of the high half only the depth of 12-14 (API
 * version 2; version 1 refused every 16-bit write). The SST-1 takes only 32-bit
 * writes in the register and texture regions (spec sections 4 and 9; 86Box drops
 * 16-bit writes there): such a write returns SST1_ERR_UNSUPPORTED and changes
 * nothing. */
sst1_result sst1_write16(sst1_board *board, uint32_t offset, uint16_t value);

/* A 32-bit read at aperture `offset` (a multiple of 4), stored in *value. Register
 * reads come from the FBI whatever the chip field says; `status` (offset 0) reports
 * the timing model's FIFO, busy, retrace and swap-pending bits at the host's present
 * time, which every bus access moves on. LFB reads return two 16-bit pixels of the
 * buffer lfbMode selects; texture memory is write-only and reads 0xffffffff. A read
 * has no effect on the frame buffer. */
sst1_result sst1_read32(sst1_board *board, uint32_t offset, uint32_t *value);

/* A 16-bit read at aperture `offset` (a multiple of 2), stored in *value: the half of
 * the 32-bit read at offset & ~3 that the bus's byte lanes select (bits 15:0 when bit
 * 1 of `offset` is clear, bits 31:16 when it is set). It counts as one bus read. */
sst1_result sst1_read16(sst1_board *board, uint32_t offset, uint16_t *value);

/* sst1_write32 (size 4) or sst1_write16 (size 2, the low 16 bits of `value`), for
 * hosts whose handlers take the size as an argument. SST1_ERR_BAD_SIZE for any other
 * size. */
sst1_result sst1_write(sst1_board *board, uint32_t offset, uint32_t size, uint32_t value);

/* sst1_read32 (size 4) or sst1_read16 (size 2, zero-extended) into *value.
 * SST1_ERR_BAD_SIZE for any other size. */
sst1_result sst1_read(sst1_board *board, uint32_t offset, uint32_t size, uint32_t *value);

/* A write of `value` to PCI configuration space at byte `offset` (a multiple of 4,
 * below SST1_PCI_CONFIG_SIZE). The board models initEnable (0x40: bit 0 enables
 * writes to fbiInit0-4); writes elsewhere are accepted and ignored (counted in the
 * board's diagnostics). Configuration reads (vendor and device ID, base address) are
 * the host's PCI model's to answer: the board keeps no configuration header. */
sst1_result sst1_pci_write(sst1_board *board, uint32_t offset, uint32_t value);

/* ------------------------------------------------------------------------------ */
/* The displayed frame                                                              */

/* Stores the size of the video mode (the videoDimensions register, each side rounded
 * down to an even number) in *width and *height; 640 by 480 until a driver sets it. Either pointer may be NULL (not stored); at
 * least one must be given, else SST1_ERR_NULL. */
sst1_result sst1_display_size(const sst1_board *board, uint32_t *width, uint32_t *height);

/* Copies buffer `which` of the display's size into `pixels`: width * height 16-bit
 * values, row 0 (the first row in memory) first, each row left to right; RGB565 for the
 * colour buffers, depth or alpha as stored for SST1_BUFFER_AUX. This is what
 * `voodoo replay` dumps. `capacity` is the number of uint16_t values `pixels` holds;
 * if it is less than width * height, nothing is copied and SST1_ERR_BUFFER_TOO_SMALL
 * is returned. *width and *height (either may be NULL) are stored in both cases. */
sst1_result sst1_read_buffer(const sst1_board *board, sst1_buffer which, uint16_t *pixels,
                             size_t capacity, uint32_t *width, uint32_t *height);

/* sst1_read_buffer(board, SST1_BUFFER_FRONT, ...): the displayed frame in RGB565. */
sst1_result sst1_front_buffer_rgb565(const sst1_board *board, uint16_t *pixels,
                                     size_t capacity, uint32_t *width, uint32_t *height);

/* The displayed frame as RGBA8: width * height pixels of 4 bytes, R, G, B, A in that
 * order in memory, A always 255, rows as sst1_read_buffer. Each 5- or 6-bit field of
 * RGB565 widens to 8 bits by repeating its high bits (as `voodoo replay --png`).
 * `capacity` is the number of bytes `rgba` holds; less than 4 * width * height gives
 * SST1_ERR_BUFFER_TOO_SMALL and copies nothing. *width and *height as for
 * sst1_read_buffer. */
sst1_result sst1_front_buffer_rgba8(const sst1_board *board, uint8_t *rgba, size_t capacity,
                                    uint32_t *width, uint32_t *height);

/* Registers `callback` to be called, with `user`, after each write that swaps the
 * buffers (a swapbufferCMD executed); NULL removes it. The callback runs on the thread
 * that made the write, before that write's call returns, with the board's lock
 * released: it may call any function on this board (read the front buffer, write,
 * even sst1_destroy), and a write it makes that swaps calls it again. The swap happens
 * when the command is written: the board does not hold a synchronised swap back until
 * the vertical retrace (the timing model counts that wait: status bits 30:28, and
 * sst1_get_time). Polling sst1_swap_count after each write gives the same
 * information without a callback. */
sst1_result sst1_set_swap_callback(sst1_board *board, sst1_swap_callback callback, void *user);

/* Stores the number of buffer swaps executed so far in *count. */
sst1_result sst1_swap_count(const sst1_board *board, uint64_t *count);

/* ------------------------------------------------------------------------------ */
/* Time and vertical retrace                                                        */

/* Stores the board's modelled time in *time: the cycles counted by the timing model
 * from the accesses and commands so far (docs/timing.md). */
sst1_result sst1_get_time(const sst1_board *board, sst1_time *time);

/* Tells the board that `nanoseconds` of host time passed with no bus access (the
 * guest's CPU was busy elsewhere): the board's clock moves on by that many graphics
 * clocks (rounded down), its engine drains its FIFOs meanwhile, and video timing moves
 * on, as a trace's `wait` line does (docs/traces.md). Host time is not the board's
 * work: sst1_get_time's cycles do not grow. Without it, each bus access moves the
 * host's time on (1.5 graphics clocks a write, 4.5 a read). */
sst1_result sst1_advance_time(sst1_board *board, uint64_t nanoseconds);

/* Stores in *active whether the vertical retrace is active now (1) or not (0), from
 * the timing model's 60 Hz frame and the vSync register. This is one bus read of
 * `status` (its bit 6 reads 0 during the retrace), and moves the host's time on as a
 * read does. */
sst1_result sst1_vertical_retrace(sst1_board *board, int *active);

/* ------------------------------------------------------------------------------ */
/* Save states (API version 2)                                                      */

/* Saves the whole board -- registers, FIFOs and timing, frame buffer, texture memory,
 * NCC tables, palette, fog table, counters, PCI configuration -- into `buffer` as a
 * versioned byte string (docs/save-states.md), and stores its length in *length. With
 * `buffer` NULL it only stores the length (the size query; a 4 MiB board with one
 * 4 MiB TMU takes about 8 MiB). SST1_ERR_NULL if `length` is NULL,
 * SST1_ERR_BUFFER_TOO_SMALL (with *length set, nothing copied) if `capacity` is less
 * than the length. The render-thread setting and the swap callback are not part of
 * the state. */
sst1_result sst1_save_state(const sst1_board *board, void *buffer, size_t capacity,
                            size_t *length);

/* Replaces the board's state with the save state in the `length` bytes at `state`,
 * from sst1_save_state (or `voodoo replay --save-at`) on a board of the same
 * configuration and model; the board then goes on exactly as the saved one would
 * have. The render threads and the swap callback stay as they are, and the restored
 * swap count is not reported to the callback. Refused, with the board unchanged:
 * SST1_ERR_NULL if `state` is NULL, SST1_ERR_STATE_VERSION for another format version,
 * SST1_ERR_STATE_MISMATCH for another configuration or model (sst1_set_model first),
 * SST1_ERR_BAD_STATE for anything that is not an intact state. */
sst1_result sst1_load_state(sst1_board *board, const void *state, size_t length);

#ifdef __cplusplus
}
#endif

#endif /* VOODOO_RS_SST1_H */

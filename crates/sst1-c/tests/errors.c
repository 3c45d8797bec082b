/* errors.c -- every error libsst1 returns, from C: each wrong argument gets its code and
 * changes nothing; then the features with no trace to show them (16-bit reads, the
 * model, render threads, time, retrace, a callback that calls back in and one that
 * destroys the board). Prints "ok" and exits 0 when everything holds. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sst1.h"

static int failures;

#define EXPECT(cond)                                                                   \
    do {                                                                               \
        if (!(cond)) {                                                                 \
            fprintf(stderr, "errors.c:%d: %s\n", __LINE__, #cond);                     \
            failures++;                                                                \
        }                                                                              \
    } while (0)

#define EXPECT_RC(call, rc)                                                            \
    do {                                                                               \
        sst1_result got_ = (call);                                                     \
        if (got_ != (rc)) {                                                            \
            fprintf(stderr, "errors.c:%d: %s returned %d (%s), expected %s\n", __LINE__, \
                    #call, (int)got_, sst1_error_string(got_), #rc);                   \
            failures++;                                                                \
        }                                                                              \
    } while (0)

/* Register offsets (the SST-1's register map). */
#define REG_STATUS 0x000u
#define REG_FBZMODE 0x110u
#define REG_LFBMODE 0x114u
#define REG_FASTFILL_CMD 0x124u
#define REG_SWAPBUFFER_CMD 0x128u
#define REG_COLOR1 0x148u
#define REG_FBIINIT1 0x214u
#define REG_FBIINIT2 0x218u
#define REG_VIDEO_DIMENSIONS 0x20cu
#define REG_CLIP_LEFT_RIGHT 0x118u
#define REG_CLIP_LOW_Y_HIGH_Y 0x11cu

struct reentry {
    int calls;
    uint16_t first_pixel;
};

/* A swap callback that calls back into the library: reads the front buffer. */
static void read_back(void *user, sst1_board *board, uint64_t swap_count) {
    struct reentry *r = user;
    r->calls++;
    (void)swap_count;
    uint32_t w = 0, h = 0;
    if (sst1_display_size(board, &w, &h) != SST1_OK || w == 0 || h == 0) {
        return;
    }
    uint16_t *px = malloc((size_t)w * h * sizeof *px);
    if (px != NULL &&
        sst1_front_buffer_rgb565(board, px, (size_t)w * h, NULL, NULL) == SST1_OK) {
        r->first_pixel = px[0];
    }
    free(px);
}

/* A swap callback that destroys its board. */
static void destroy_it(void *user, sst1_board *board, uint64_t swap_count) {
    (void)swap_count;
    *(int *)user = sst1_destroy(board) == SST1_OK;
}

/* A 64x32 display: rows of two 64-pixel tiles (fbiInit1 bits 7:4), buffers 8 KiB (two
 * 4 KiB pages, fbiInit2 bits 19:11) apart, clipped to the display. */
static void small_display(sst1_board *b) {
    EXPECT_RC(sst1_pci_write(b, 0x40, 1), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_FBIINIT1, 1u << 4), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_FBIINIT2, 2u << 11), SST1_OK);
    /* videoDimensions: width - 1 in bits 9:0, height - 1 in bits 25:16. */
    EXPECT_RC(sst1_write32(b, REG_VIDEO_DIMENSIONS, (31u << 16) | 63u), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_CLIP_LEFT_RIGHT, 64u), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_CLIP_LOW_Y_HIGH_Y, 32u), SST1_OK);
}

int main(void) {
    EXPECT(sst1_api_version() == SST1_API_VERSION);

    /* Error strings: one for each code, and for anything else. */
    for (int r = SST1_OK; r <= SST1_ERR_INTERNAL; r++) {
        const char *s = sst1_error_string((sst1_result)r);
        EXPECT(s != NULL && strlen(s) > 0 && strcmp(s, "unknown error") != 0);
    }
    EXPECT(strcmp(sst1_error_string((sst1_result)-1), "unknown error") == 0);
    EXPECT(strcmp(sst1_error_string((sst1_result)1000), "unknown error") == 0);

    /* Model names. */
    sst1_model m = SST1_MODEL_MAME;
    EXPECT_RC(sst1_model_from_name("hardware", &m), SST1_OK);
    EXPECT(m == SST1_MODEL_HARDWARE);
    EXPECT_RC(sst1_model_from_name("86box", &m), SST1_OK);
    EXPECT(m == SST1_MODEL_86BOX);
    EXPECT_RC(sst1_model_from_name("dosbox-staging", &m), SST1_OK);
    EXPECT(m == SST1_MODEL_DOSBOX_STAGING);
    EXPECT_RC(sst1_model_from_name("vote", &m), SST1_ERR_BAD_ARGUMENT);
    EXPECT(m == SST1_MODEL_DOSBOX_STAGING);
    EXPECT_RC(sst1_model_from_name(NULL, &m), SST1_ERR_NULL);
    EXPECT_RC(sst1_model_from_name("mame", NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_model_from_name("\xff\xfe", &m), SST1_ERR_BAD_ARGUMENT);

    /* Creation. */
    sst1_config good = {.fbi_mb = 4, .tmus = 2, .tmu_mb = 2};
    sst1_board *b = (sst1_board *)&good; /* not NULL, to see it cleared */
    EXPECT_RC(sst1_create(NULL, SST1_MODEL_HARDWARE, &b), SST1_ERR_NULL);
    EXPECT(b == NULL);
    EXPECT_RC(sst1_create(&good, SST1_MODEL_HARDWARE, NULL), SST1_ERR_NULL);
    sst1_config bad[] = {{3, 1, 4}, {8, 1, 4}, {0, 1, 4}, {4, 0, 4}, {4, 4, 4},
                         {4, 1, 3}, {4, 1, 8}, {4, 1, 0}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        b = (sst1_board *)&good;
        EXPECT_RC(sst1_create(&bad[i], SST1_MODEL_HARDWARE, &b), SST1_ERR_BAD_CONFIG);
        EXPECT(b == NULL);
    }
    EXPECT_RC(sst1_create(&good, (sst1_model)4, &b), SST1_ERR_BAD_ARGUMENT);
    EXPECT(b == NULL);
    EXPECT_RC(sst1_create(&good, (sst1_model)-1, &b), SST1_ERR_BAD_ARGUMENT);
    EXPECT_RC(sst1_create(&good, SST1_MODEL_MAME, &b), SST1_OK);
    EXPECT(b != NULL);
    EXPECT_RC(sst1_destroy(NULL), SST1_OK);

    /* NULL boards everywhere. */
    uint32_t u32 = 0;
    sst1_isa isa = SST1_ISA_BASELINE;
    uint16_t u16 = 0;
    uint64_t u64 = 0;
    int active = 0;
    sst1_config c;
    sst1_time t;
    uint16_t px[4];
    uint8_t rgba[16];
    EXPECT_RC(sst1_get_config(NULL, &c), SST1_ERR_NULL);
    EXPECT_RC(sst1_set_model(NULL, SST1_MODEL_MAME), SST1_ERR_NULL);
    EXPECT_RC(sst1_get_model(NULL, &m), SST1_ERR_NULL);
    EXPECT_RC(sst1_set_render_threads(NULL, 1), SST1_ERR_NULL);
    EXPECT_RC(sst1_get_render_threads(NULL, &u32), SST1_ERR_NULL);
    EXPECT_RC(sst1_set_vector_isa(NULL, SST1_ISA_BASELINE, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_get_vector_isa(NULL, &isa), SST1_ERR_NULL);
    EXPECT_RC(sst1_write32(NULL, 0, 0), SST1_ERR_NULL);
    EXPECT_RC(sst1_write16(NULL, 0, 0), SST1_ERR_NULL);
    EXPECT_RC(sst1_read32(NULL, 0, &u32), SST1_ERR_NULL);
    EXPECT_RC(sst1_read16(NULL, 0, &u16), SST1_ERR_NULL);
    EXPECT_RC(sst1_write(NULL, 0, 4, 0), SST1_ERR_NULL);
    EXPECT_RC(sst1_read(NULL, 0, 4, &u32), SST1_ERR_NULL);
    EXPECT_RC(sst1_pci_write(NULL, 0x40, 1), SST1_ERR_NULL);
    EXPECT_RC(sst1_display_size(NULL, &u32, &u32), SST1_ERR_NULL);
    EXPECT_RC(sst1_read_buffer(NULL, SST1_BUFFER_FRONT, px, 4, NULL, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_front_buffer_rgb565(NULL, px, 4, NULL, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_front_buffer_rgba8(NULL, rgba, 16, NULL, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_set_swap_callback(NULL, NULL, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_swap_count(NULL, &u64), SST1_ERR_NULL);
    EXPECT_RC(sst1_get_time(NULL, &t), SST1_ERR_NULL);
    EXPECT_RC(sst1_advance_time(NULL, 1000), SST1_ERR_NULL);
    EXPECT_RC(sst1_vertical_retrace(NULL, &active), SST1_ERR_NULL);

    /* NULL out-parameters. */
    EXPECT_RC(sst1_get_config(b, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_get_model(b, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_get_render_threads(b, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_get_vector_isa(b, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_read32(b, 0, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_read16(b, 0, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_read(b, 0, 4, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_display_size(b, NULL, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_read_buffer(b, SST1_BUFFER_FRONT, NULL, 4, NULL, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_front_buffer_rgba8(b, NULL, 16, NULL, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_swap_count(b, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_get_time(b, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_vertical_retrace(b, NULL), SST1_ERR_NULL);

    /* The board as made. */
    EXPECT_RC(sst1_get_config(b, &c), SST1_OK);
    EXPECT(c.fbi_mb == 4 && c.tmus == 2 && c.tmu_mb == 2);
    EXPECT_RC(sst1_get_model(b, &m), SST1_OK);
    EXPECT(m == SST1_MODEL_MAME);
    EXPECT_RC(sst1_set_model(b, (sst1_model)7), SST1_ERR_BAD_ARGUMENT);
    EXPECT_RC(sst1_get_model(b, &m), SST1_OK);
    EXPECT(m == SST1_MODEL_MAME);
    EXPECT_RC(sst1_set_model(b, SST1_MODEL_HARDWARE), SST1_OK);
    EXPECT_RC(sst1_get_model(b, &m), SST1_OK);
    EXPECT(m == SST1_MODEL_HARDWARE);

    /* Render threads: kept, bounded. */
    EXPECT_RC(sst1_get_render_threads(b, &u32), SST1_OK);
    EXPECT(u32 == 0);
    EXPECT_RC(sst1_set_render_threads(b, 8), SST1_OK);
    EXPECT_RC(sst1_set_render_threads(b, SST1_MAX_RENDER_THREADS + 1), SST1_ERR_BAD_ARGUMENT);
    EXPECT_RC(sst1_get_render_threads(b, &u32), SST1_OK);
    EXPECT(u32 == 8);

    /* Copies of the kernels: capped by the CPU's, never above what was asked. */
    sst1_isa best, used;
    EXPECT_RC(sst1_get_vector_isa(b, &best), SST1_OK);
    EXPECT(best >= SST1_ISA_BASELINE && best <= SST1_ISA_AVX512);
    EXPECT_RC(sst1_set_vector_isa(b, SST1_ISA_BASELINE, &used), SST1_OK);
    EXPECT(used == SST1_ISA_BASELINE);
    EXPECT_RC(sst1_get_vector_isa(b, &isa), SST1_OK);
    EXPECT(isa == SST1_ISA_BASELINE);
    EXPECT_RC(sst1_set_vector_isa(b, (sst1_isa)3, &used), SST1_ERR_BAD_ARGUMENT);
    EXPECT_RC(sst1_set_vector_isa(b, SST1_ISA_AVX512, NULL), SST1_OK);
    EXPECT_RC(sst1_get_vector_isa(b, &isa), SST1_OK);
    EXPECT(isa == best);

    /* Offsets, alignment and sizes. */
    EXPECT_RC(sst1_write32(b, SST1_APERTURE_SIZE, 0), SST1_ERR_BAD_OFFSET);
    EXPECT_RC(sst1_write32(b, 0xfffffffcu, 0), SST1_ERR_BAD_OFFSET);
    EXPECT_RC(sst1_write32(b, REG_FBZMODE + 2, 0), SST1_ERR_MISALIGNED);
    EXPECT_RC(sst1_write32(b, REG_FBZMODE + 1, 0), SST1_ERR_MISALIGNED);
    EXPECT_RC(sst1_read32(b, SST1_APERTURE_SIZE, &u32), SST1_ERR_BAD_OFFSET);
    EXPECT_RC(sst1_read32(b, 2, &u32), SST1_ERR_MISALIGNED);
    EXPECT_RC(sst1_read16(b, 1, &u16), SST1_ERR_MISALIGNED);
    EXPECT_RC(sst1_read16(b, SST1_APERTURE_SIZE - 1, &u16), SST1_ERR_MISALIGNED);
    EXPECT_RC(sst1_read16(b, SST1_APERTURE_SIZE, &u16), SST1_ERR_BAD_OFFSET);
    EXPECT_RC(sst1_write16(b, 3, 0), SST1_ERR_MISALIGNED);
    EXPECT_RC(sst1_write16(b, SST1_APERTURE_SIZE, 0), SST1_ERR_BAD_OFFSET);
    EXPECT_RC(sst1_write(b, 0, 1, 0), SST1_ERR_BAD_SIZE);
    EXPECT_RC(sst1_write(b, 0, 8, 0), SST1_ERR_BAD_SIZE);
    EXPECT_RC(sst1_write(b, 0, 0, 0), SST1_ERR_BAD_SIZE);
    EXPECT_RC(sst1_read(b, 0, 3, &u32), SST1_ERR_BAD_SIZE);
    EXPECT_RC(sst1_read(b, 0, 2, &u32), SST1_OK);
    EXPECT_RC(sst1_pci_write(b, SST1_PCI_CONFIG_SIZE, 0), SST1_ERR_BAD_OFFSET);
    EXPECT_RC(sst1_pci_write(b, 0x41, 0), SST1_ERR_MISALIGNED);
    /* 16-bit writes to registers and texture memory (32-bit only on the SST-1):
     * refused, nothing written. */
    EXPECT_RC(sst1_write16(b, REG_FBZMODE, 0x1234), SST1_ERR_UNSUPPORTED);
    EXPECT_RC(sst1_write16(b, SST1_TEXTURE_BASE + 2, 0x1234), SST1_ERR_UNSUPPORTED);
    EXPECT_RC(sst1_write(b, REG_FBZMODE + 2, 2, 0x1234), SST1_ERR_UNSUPPORTED);
    EXPECT_RC(sst1_read32(b, REG_FBZMODE, &u32), SST1_OK);
    EXPECT(u32 == 0);

    /* Reads: 32 and 16 bits agree; texture memory reads all ones. */
    EXPECT_RC(sst1_write32(b, REG_COLOR1, 0x11223344u), SST1_OK);
    EXPECT_RC(sst1_read32(b, REG_COLOR1, &u32), SST1_OK);
    EXPECT(u32 == 0x11223344u);
    EXPECT_RC(sst1_read16(b, REG_COLOR1, &u16), SST1_OK);
    EXPECT(u16 == 0x3344);
    EXPECT_RC(sst1_read16(b, REG_COLOR1 + 2, &u16), SST1_OK);
    EXPECT(u16 == 0x1122);
    EXPECT_RC(sst1_read(b, REG_COLOR1 + 2, 2, &u32), SST1_OK);
    EXPECT(u32 == 0x1122);
    EXPECT_RC(sst1_read(b, REG_COLOR1, 4, &u32), SST1_OK);
    EXPECT(u32 == 0x11223344u);
    EXPECT_RC(sst1_read32(b, SST1_TEXTURE_BASE, &u32), SST1_OK);
    EXPECT(u32 == 0xffffffffu);

    /* fbiInit writes need PCI initEnable bit 0 (accepted, ignored without it). */
    EXPECT_RC(sst1_write32(b, REG_FBIINIT1, 0x5a5a0000u), SST1_OK);
    EXPECT_RC(sst1_read32(b, REG_FBIINIT1, &u32), SST1_OK);
    EXPECT(u32 != 0x5a5a0000u);

    /* Buffers: too small, bad kind; sizes reported either way. */
    small_display(b);
    uint32_t w = 0, h = 0;
    EXPECT_RC(sst1_display_size(b, &w, &h), SST1_OK);
    EXPECT(w == 64 && h == 32);
    EXPECT_RC(sst1_display_size(b, NULL, &h), SST1_OK);
    size_t n = (size_t)w * h;
    uint16_t *buf = calloc(n, sizeof *buf);
    uint8_t *rgb = calloc(n * 4, 1);
    EXPECT(buf != NULL && rgb != NULL);
    w = h = 0;
    EXPECT_RC(sst1_read_buffer(b, SST1_BUFFER_FRONT, buf, n - 1, &w, &h),
              SST1_ERR_BUFFER_TOO_SMALL);
    EXPECT(w == 64 && h == 32);
    EXPECT_RC(sst1_read_buffer(b, (sst1_buffer)3, buf, n, &w, &h), SST1_ERR_BAD_ARGUMENT);
    EXPECT_RC(sst1_read_buffer(b, (sst1_buffer)-1, buf, n, &w, &h), SST1_ERR_BAD_ARGUMENT);
    EXPECT_RC(sst1_front_buffer_rgba8(b, rgb, n * 4 - 1, &w, &h), SST1_ERR_BUFFER_TOO_SMALL);
    EXPECT_RC(sst1_front_buffer_rgb565(b, buf, 0, NULL, NULL), SST1_ERR_BUFFER_TOO_SMALL);

    /* A fill of the back buffer, then a swap: the callback sees it and reads the new
     * front buffer through the library. */
    struct reentry r = {0, 0};
    EXPECT_RC(sst1_set_swap_callback(b, read_back, &r), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_COLOR1, 0x00ff0000u), SST1_OK); /* red */
    /* fbzMode: RGB buffer mask on (bit 9), draw the back buffer (bits 15:14 = 1). */
    EXPECT_RC(sst1_write32(b, REG_FBZMODE, (1u << 9) | (1u << 14)), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_FASTFILL_CMD, 0), SST1_OK);
    EXPECT(r.calls == 0);
    EXPECT_RC(sst1_read_buffer(b, SST1_BUFFER_BACK, buf, n, NULL, NULL), SST1_OK);
    EXPECT(buf[0] == 0xf800);
    EXPECT_RC(sst1_write32(b, REG_SWAPBUFFER_CMD, 0), SST1_OK);
    EXPECT(r.calls == 1);
    EXPECT(r.first_pixel == 0xf800);
    EXPECT_RC(sst1_swap_count(b, &u64), SST1_OK);
    EXPECT(u64 == 1);
    EXPECT_RC(sst1_front_buffer_rgb565(b, buf, n, NULL, NULL), SST1_OK);
    EXPECT(buf[0] == 0xf800 && buf[n - 1] == 0xf800);
    EXPECT_RC(sst1_front_buffer_rgba8(b, rgb, n * 4, NULL, NULL), SST1_OK);
    EXPECT(rgb[0] == 0xff && rgb[1] == 0 && rgb[2] == 0 && rgb[3] == 0xff);
    /* A 16-bit LFB read of the front buffer (lfbMode read buffer 0: front). */
    EXPECT_RC(sst1_write32(b, REG_LFBMODE, 0), SST1_OK);
    EXPECT_RC(sst1_read16(b, SST1_LFB_BASE + 2, &u16), SST1_OK);
    EXPECT(u16 == 0xf800);
    /* 16-bit LFB writes store one pixel each (lfbMode 0: RGB 565 into the front
     * buffer), leaving its neighbour in the 32-bit word alone. */
    EXPECT_RC(sst1_write16(b, SST1_LFB_BASE + 2, 0x07e0), SST1_OK);
    EXPECT_RC(sst1_read32(b, SST1_LFB_BASE, &u32), SST1_OK);
    EXPECT(u32 == 0x07e0f800u);
    EXPECT_RC(sst1_write(b, SST1_LFB_BASE, 2, 0x001f), SST1_OK);
    EXPECT_RC(sst1_read32(b, SST1_LFB_BASE, &u32), SST1_OK);
    EXPECT(u32 == 0x07e0001fu);
    EXPECT_RC(sst1_read32(b, SST1_LFB_BASE + 4, &u32), SST1_OK);
    EXPECT(u32 == 0xf800f800u);
    /* A refused write is no swap; removing the callback stops the calls. */
    EXPECT_RC(sst1_write32(b, REG_SWAPBUFFER_CMD + 1, 0), SST1_ERR_MISALIGNED);
    EXPECT_RC(sst1_set_swap_callback(b, NULL, NULL), SST1_OK);
    EXPECT_RC(sst1_write(b, REG_SWAPBUFFER_CMD, 4, 0), SST1_OK);
    EXPECT(r.calls == 1);
    EXPECT_RC(sst1_swap_count(b, &u64), SST1_OK);
    EXPECT(u64 == 2);

    /* Time: counted from the work; host time passes without adding to it. */
    EXPECT_RC(sst1_get_time(b, &t), SST1_OK);
    EXPECT(t.clock_hz == 50000000u && t.cycles > 0 && t.swaps == 2);
    EXPECT_RC(sst1_advance_time(b, 1000000), SST1_OK);
    sst1_time t2;
    EXPECT_RC(sst1_get_time(b, &t2), SST1_OK);
    EXPECT(t2.cycles == t.cycles);
    /* Vertical retrace: not active at first; polling status reaches one. */
    EXPECT_RC(sst1_vertical_retrace(b, &active), SST1_OK);
    EXPECT(active == 0);
    long polls = 0;
    while (active == 0 && polls < 1000000) {
        EXPECT_RC(sst1_vertical_retrace(b, &active), SST1_OK);
        polls++;
    }
    EXPECT(active == 1);
    EXPECT_RC(sst1_read32(b, REG_STATUS, &u32), SST1_OK);
    EXPECT((u32 & 0x40) == 0);
    /* Host time moves the board on: 2 ms later the retrace (2 of 525 lines) is over. */
    EXPECT_RC(sst1_advance_time(b, 2000000), SST1_OK);
    EXPECT_RC(sst1_vertical_retrace(b, &active), SST1_OK);
    EXPECT(active == 0);

    /* A callback that destroys its board. */
    int destroyed = 0;
    EXPECT_RC(sst1_set_swap_callback(b, destroy_it, &destroyed), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_SWAPBUFFER_CMD, 0), SST1_OK);
    EXPECT(destroyed == 1);

    free(buf);
    free(rgb);
    if (failures != 0) {
        fprintf(stderr, "%d failures\n", failures);
        return 1;
    }
    printf("ok\n");
    return 0;
}

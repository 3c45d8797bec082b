/* state.c -- save states through libsst1: a board saved and loaded into a second board
 * goes on exactly as the first (same pixels, swap count, modelled time and status), and
 * every refusal is its code with the loading board unchanged. Prints "ok" and exits 0
 * when everything holds. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sst1.h"

static int failures;

#define EXPECT(cond)                                                                   \
    do {                                                                               \
        if (!(cond)) {                                                                 \
            fprintf(stderr, "state.c:%d: %s\n", __LINE__, #cond);                      \
            failures++;                                                                \
        }                                                                              \
    } while (0)

#define EXPECT_RC(call, rc)                                                            \
    do {                                                                               \
        sst1_result got_ = (call);                                                     \
        if (got_ != (rc)) {                                                            \
            fprintf(stderr, "state.c:%d: %s returned %d (%s), expected %s\n", __LINE__,  \
                    #call, (int)got_, sst1_error_string(got_), #rc);                   \
            failures++;                                                                \
        }                                                                              \
    } while (0)

#define REG_STATUS 0x000u
#define REG_FBZMODE 0x110u
#define REG_FASTFILL_CMD 0x124u
#define REG_SWAPBUFFER_CMD 0x128u
#define REG_COLOR1 0x148u
#define REG_FBIINIT1 0x214u
#define REG_FBIINIT2 0x218u
#define REG_VIDEO_DIMENSIONS 0x20cu
#define REG_CLIP_LEFT_RIGHT 0x118u
#define REG_CLIP_LOW_Y_HIGH_Y 0x11cu

/* A 64x32 display (as errors.c sets it up). */
static void small_display(sst1_board *b) {
    EXPECT_RC(sst1_pci_write(b, 0x40, 1), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_FBIINIT1, 1u << 4), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_FBIINIT2, 2u << 11), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_VIDEO_DIMENSIONS, (31u << 16) | 63u), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_CLIP_LEFT_RIGHT, 64u), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_CLIP_LOW_Y_HIGH_Y, 32u), SST1_OK);
}

/* Fills the back buffer with `colour`, writes a few LFB and texture words and swaps. */
static void frame(sst1_board *b, uint32_t colour) {
    EXPECT_RC(sst1_write32(b, REG_FBZMODE, 1u << 9), SST1_OK); /* RGB writes on */
    EXPECT_RC(sst1_write32(b, REG_COLOR1, colour), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_FASTFILL_CMD, 0), SST1_OK);
    EXPECT_RC(sst1_write32(b, SST1_LFB_BASE + 8, colour ^ 0x12345678u), SST1_OK);
    EXPECT_RC(sst1_write32(b, SST1_TEXTURE_BASE + 64, colour), SST1_OK);
    EXPECT_RC(sst1_write32(b, REG_SWAPBUFFER_CMD, 0), SST1_OK);
}

/* The front buffer's 64x32 pixels. */
static void front(sst1_board *b, uint16_t *px) {
    uint32_t w = 0, h = 0;
    EXPECT_RC(sst1_front_buffer_rgb565(b, px, 64 * 32, &w, &h), SST1_OK);
    EXPECT(w == 64 && h == 32);
}

/* Two boards read the same: front buffer, swaps, modelled time, status. */
static void same(sst1_board *a, sst1_board *b) {
    static uint16_t pa[64 * 32], pb[64 * 32];
    front(a, pa);
    front(b, pb);
    EXPECT(memcmp(pa, pb, sizeof pa) == 0);
    sst1_time ta, tb;
    EXPECT_RC(sst1_get_time(a, &ta), SST1_OK);
    EXPECT_RC(sst1_get_time(b, &tb), SST1_OK);
    EXPECT(ta.cycles == tb.cycles && ta.swaps == tb.swaps && ta.cycles > 0);
    uint32_t sa = 0, sb = 1;
    EXPECT_RC(sst1_read32(a, REG_STATUS, &sa), SST1_OK);
    EXPECT_RC(sst1_read32(b, REG_STATUS, &sb), SST1_OK);
    EXPECT(sa == sb);
}

static void count_swaps(void *user, sst1_board *board, uint64_t swap_count) {
    (void)board;
    *(uint64_t *)user = swap_count;
}

int main(void) {
    for (int r = SST1_ERR_BAD_STATE; r <= SST1_ERR_STATE_MISMATCH; r++) {
        EXPECT(strcmp(sst1_error_string((sst1_result)r), "unknown error") != 0);
    }
    EXPECT(sst1_api_version() == 3);

    sst1_config config = {.fbi_mb = 4, .tmus = 1, .tmu_mb = 2};
    sst1_board *a = NULL, *b = NULL;
    EXPECT_RC(sst1_create(&config, SST1_MODEL_HARDWARE, &a), SST1_OK);
    EXPECT_RC(sst1_create(&config, SST1_MODEL_HARDWARE, &b), SST1_OK);
    small_display(a);
    frame(a, 0x00ff0000u);
    frame(a, 0x0000ff00u);

    /* The size query, a buffer too small, NULL arguments. */
    size_t len = 0, len2 = 0;
    EXPECT_RC(sst1_save_state(a, NULL, 0, &len), SST1_OK);
    EXPECT(len > (4u << 20) + (2u << 20));
    unsigned char *state = malloc(len);
    EXPECT(state != NULL);
    EXPECT_RC(sst1_save_state(a, state, len - 1, &len2), SST1_ERR_BUFFER_TOO_SMALL);
    EXPECT(len2 == len);
    EXPECT_RC(sst1_save_state(a, state, len, NULL), SST1_ERR_NULL);
    EXPECT_RC(sst1_save_state(NULL, state, len, &len2), SST1_ERR_NULL);
    EXPECT_RC(sst1_save_state(a, state, len, &len2), SST1_OK);
    EXPECT(len2 == len);
    EXPECT(memcmp(state, "SST1STAT", 8) == 0);

    /* Loaded into the second board: it reads as the first, the restored swaps are not
     * reported, and both go on alike. */
    uint64_t reported = 0;
    EXPECT_RC(sst1_set_swap_callback(b, count_swaps, &reported), SST1_OK);
    EXPECT_RC(sst1_load_state(b, state, len), SST1_OK);
    EXPECT(reported == 0);
    same(a, b);
    frame(a, 0x000000ffu);
    frame(b, 0x000000ffu);
    EXPECT(reported == 3);
    same(a, b);

    /* Refusals: each its code, the board unchanged. */
    size_t before_len = 0;
    EXPECT_RC(sst1_save_state(b, NULL, 0, &before_len), SST1_OK);
    unsigned char *before = malloc(before_len);
    EXPECT_RC(sst1_save_state(b, before, before_len, &before_len), SST1_OK);
    EXPECT_RC(sst1_load_state(b, NULL, len), SST1_ERR_NULL);
    EXPECT_RC(sst1_load_state(NULL, state, len), SST1_ERR_NULL);
    EXPECT_RC(sst1_load_state(b, state, len / 2), SST1_ERR_BAD_STATE);
    EXPECT_RC(sst1_load_state(b, state, 0), SST1_ERR_BAD_STATE);
    EXPECT_RC(sst1_load_state(b, "not a state at all", 18), SST1_ERR_BAD_STATE);
    unsigned char version = state[8]; /* the format version */
    state[8] = 99;
    EXPECT_RC(sst1_load_state(b, state, len), SST1_ERR_STATE_VERSION);
    state[8] = (unsigned char)(version - 1); /* an older format */
    EXPECT_RC(sst1_load_state(b, state, len), SST1_ERR_STATE_VERSION);
    state[8] = version;
    unsigned char *after = malloc(before_len);
    EXPECT_RC(sst1_save_state(b, after, before_len, &len2), SST1_OK);
    EXPECT(len2 == before_len && memcmp(before, after, before_len) == 0);

    sst1_config other = {.fbi_mb = 2, .tmus = 1, .tmu_mb = 2};
    sst1_board *c = NULL;
    EXPECT_RC(sst1_create(&other, SST1_MODEL_HARDWARE, &c), SST1_OK);
    EXPECT_RC(sst1_load_state(c, state, len), SST1_ERR_STATE_MISMATCH);
    EXPECT_RC(sst1_destroy(c), SST1_OK);
    EXPECT_RC(sst1_create(&config, SST1_MODEL_MAME, &c), SST1_OK);
    EXPECT_RC(sst1_load_state(c, state, len), SST1_ERR_STATE_MISMATCH);
    EXPECT_RC(sst1_set_model(c, SST1_MODEL_HARDWARE), SST1_OK);
    EXPECT_RC(sst1_load_state(c, state, len), SST1_OK);

    free(after);
    free(before);
    free(state);
    EXPECT_RC(sst1_destroy(c), SST1_OK);
    EXPECT_RC(sst1_destroy(b), SST1_OK);
    EXPECT_RC(sst1_destroy(a), SST1_OK);
    if (failures) {
        fprintf(stderr, "%d failure(s)\n", failures);
        return 1;
    }
    puts("ok");
    return 0;
}

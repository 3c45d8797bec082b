/* abuse.c -- a hostile Glide program: every way of misusing libglide3 found by the
 * hostile-input review (issue 11, items 1-10) must give an error or the hardware's
 * behaviour, never a crash, a read or write outside the program's memory, or memory
 * that grows with a count. Prints "ok", or one "FAIL item N: ..." line per failure.
 *
 * Argument "plain" also checks peak memory (VmHWM); "asan" (a build with
 * -fsanitize=address, whose allocator keeps freed memory in quarantine) skips those
 * checks and draws fewer vertices. A second argument N runs only item N (to see each
 * fail on its own against an older library). */
#include <glide.h>
#include <glideutl.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

static int failures;
static int errors;
static char last[256];
static int measure_memory;
static int only; /* 0: every item; N: only item N (to see one fail on its own) */

static int want(int item)
{
    return only == 0 || only == item;
}

/* What the error callback does besides counting: 1 calls grGet, 2 shuts Glide down. */
static int reenter;
static FxI32 reentered_tmus = -1;

static void on_error(const char *msg, FxBool fatal)
{
    (void)fatal;
    errors++;
    snprintf(last, sizeof(last), "%s", msg);
    if (reenter == 1) {
        grGet(GR_NUM_TMU, 4, &reentered_tmus);
    } else if (reenter == 2) {
        reenter = 0;
        grGlideShutdown();
    }
}

#define CHECK(item, cond)                                                             \
    do {                                                                              \
        if (!(cond)) {                                                                \
            printf("FAIL item %d: line %d: %s (errors %d, last \"%s\")\n", item,      \
                   __LINE__, #cond, errors, last);                                    \
            failures++;                                                               \
        }                                                                             \
    } while (0)

/* An error was reported since `before` and the last one starts with `prefix`. */
static int reported(int before, const char *prefix)
{
    return errors > before && strncmp(last, prefix, strlen(prefix)) == 0;
}

/* Peak resident memory of this process in KiB (VmHWM). */
static long peak_kib(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    long kib = -1;
    if (!f)
        return -1;
    while (fgets(line, sizeof(line), f))
        if (sscanf(line, "VmHWM: %ld kB", &kib) == 1)
            break;
    fclose(f);
    return kib;
}

static FxI32 counter(FxU32 which)
{
    FxI32 v = -1;
    grGet(which, 4, &v);
    return v;
}

static FxU16 pixel(GrBuffer_t buffer, FxU32 x, FxU32 y)
{
    FxU16 px = 0x1234;
    grLfbReadRegion(buffer, x, y, 1, 1, 2, &px);
    return px;
}

static void open_window(void)
{
    grGlideInit();
    grSstSelect(0);
    grSstWinOpen(0, GR_RESOLUTION_640x480, GR_REFRESH_60Hz, GR_COLORFORMAT_ARGB,
                 GR_ORIGIN_UPPER_LEFT, 2, 1);
    grVertexLayout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    grColorCombine(GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE,
                   GR_COMBINE_LOCAL_CONSTANT, GR_COMBINE_OTHER_NONE, FXFALSE);
    grConstantColorValue(0xffffffff);
}

/* Item 9: Glide's state is per process; this thread draws one triangle. */
static FxI32 thread_triangles = -1;

static void *draw_from_thread(void *arg)
{
    (void)arg;
    float v[3][2] = {{100, 100}, {140, 100}, {100, 140}};
    grRenderBuffer(GR_BUFFER_BACKBUFFER);
    grDrawTriangle(v[0], v[1], v[2]);
    thread_triangles = counter(GR_STATS_TRIANGLES_IN);
    return NULL;
}

int main(int argc, char **argv)
{
    measure_memory = argc > 1 && strcmp(argv[1], "plain") == 0;
    only = argc > 2 ? atoi(argv[2]) : 0;
    int before;

    /* Item 8: a callback set before grGlideInit is kept. */
    grErrorSetCallback(on_error);
    open_window();
    before = errors;
    grDepthBufferFunction(42);
    if (want(8))
        CHECK(8, reported(before, "grDepthBufferFunction"));

    /* Item 4: vertex arrays are drawn without a copy in proportion to the count. */
    if (want(4)) {
        const FxU32 n = measure_memory ? 1000000 : 100000;
        float *xy = malloc(n * 2 * sizeof(float));
        const void **ptrs = malloc(n * sizeof(void *));
        for (FxU32 i = 0; i < n; i++) {
            xy[2 * i] = 5.0f + (float)(i % 7);
            xy[2 * i + 1] = 5.0f;
            ptrs[i] = &xy[2 * i];
        }
        FxI32 points = counter(GR_STATS_POINTS);
        long peak = peak_kib();
        grDrawVertexArrayContiguous(GR_POINTS, n, xy, 8);
        grDrawVertexArray(GR_POINTS, n, (void *)ptrs);
        CHECK(4, counter(GR_STATS_POINTS) == points + 2 * (FxI32)n);
        if (measure_memory)
            CHECK(4, peak_kib() - peak < 16 * 1024);
        /* A zero stride is refused, as in the Rust API. */
        before = errors;
        grDrawVertexArrayContiguous(GR_POINTS, 0xffffffffu, xy, 0);
        CHECK(4, reported(before, "grDrawVertexArrayContiguous: stride"));
        CHECK(4, counter(GR_STATS_POINTS) == points + 2 * (FxI32)n);
        free(ptrs);
        free(xy);
    }

    /* Item 5: saving state or layout costs nothing per call; copies restore. */
    if (want(5)) {
        FxI32 state_size = 0, layout_size = 0;
        grGet(GR_GLIDE_STATE_SIZE, 4, &state_size);
        grGet(GR_GLIDE_VERTEXLAYOUT_SIZE, 4, &layout_size);
        char *state = calloc(1, (size_t)state_size);
        char *copy = calloc(1, (size_t)state_size);
        char *layout = calloc(1, (size_t)layout_size);
        long peak = peak_kib();
        for (int i = 0; i < 200000; i++) {
            memset(state, 0, (size_t)state_size);
            grGlideGetState(state);
            memset(layout, 0, (size_t)layout_size);
            grGlideGetVertexLayout(layout);
        }
        if (measure_memory)
            CHECK(5, peak_kib() - peak < 8 * 1024);
        memcpy(copy, state, (size_t)state_size);
        grConstantColorValue(0xff00ff00);
        before = errors;
        grGlideSetState(copy);
        grGlideSetVertexLayout(layout);
        CHECK(5, errors == before);
        /* The restored constant colour draws white again. */
        float v[3][2] = {{10, 20}, {30, 20}, {10, 40}};
        grBufferClear(0, 0, 0);
        grDrawTriangle(v[0], v[1], v[2]);
        CHECK(5, pixel(GR_BUFFER_BACKBUFFER, 12, 22) == 0xffff);
        /* A buffer no save filled is refused. */
        memset(copy, 0x5a, (size_t)state_size);
        before = errors;
        grGlideSetState(copy);
        CHECK(5, reported(before, "grGlideSetState: state was not saved"));
        before = errors;
        grGlideSetVertexLayout(copy);
        CHECK(5, reported(before, "grGlideSetVertexLayout: layout was not saved"));
        free(layout);
        free(copy);
        free(state);
    }

    /* Item 6: .3df reads are bounded, whatever the file. */
    if (want(6)) {
        Gu3dfInfo info;
        memset(&info, 0, sizeof(info));
        long peak = peak_kib();
        CHECK(6, !gu3dfGetInfo("/dev/zero", &info));
        static FxU8 texels[256 * 256 * 2];
        info.data = texels;
        CHECK(6, !gu3dfLoad("/dev/zero", &info));
        if (measure_memory)
            CHECK(6, peak_kib() - peak < 8 * 1024);
    }

    /* Item 7: invalid lock types are reported and refused. */
    if (want(7)) {
        const FxU32 types[] = {2, 5, 0x20, 0xffffffffu};
        for (unsigned i = 0; i < sizeof(types) / sizeof(types[0]); i++) {
            GrLfbInfo_t info;
            info.size = sizeof(info);
            before = errors;
            CHECK(7, !grLfbLock(types[i], GR_BUFFER_BACKBUFFER, GR_LFBWRITEMODE_565,
                                GR_ORIGIN_UPPER_LEFT, FXFALSE, &info));
            CHECK(7, reported(before, "grLfbLock: invalid lock type"));
        }
    }

    /* Item 1: an unlock that fails leaves the lock and its pointer usable. */
    if (want(1)) {
        GrLfbInfo_t info;
        info.size = sizeof(info);
        grBufferClear(0, 0, 0);
        CHECK(1, grLfbLock(GR_LFB_WRITE_ONLY, GR_BUFFER_BACKBUFFER, GR_LFBWRITEMODE_565,
                           GR_ORIGIN_UPPER_LEFT, FXFALSE, &info));
        FxU16 *lfb = info.lfbPtr;
        FxU32 row = info.strideInBytes / 2;
        CHECK(1, !grLfbUnlock(GR_LFB_WRITE_ONLY, GR_BUFFER_FRONTBUFFER));
        lfb[10 * row + 20] = 0xf800;
        CHECK(1, grLfbUnlock(GR_LFB_WRITE_ONLY, GR_BUFFER_BACKBUFFER));
        CHECK(1, pixel(GR_BUFFER_BACKBUFFER, 20, 10) == 0xf800);

        CHECK(1, grLfbLock(GR_LFB_READ_ONLY, GR_BUFFER_BACKBUFFER, GR_LFBWRITEMODE_ANY,
                           GR_ORIGIN_UPPER_LEFT, FXFALSE, &info));
        const volatile FxU16 *rd = info.lfbPtr;
        CHECK(1, !grLfbUnlock(GR_LFB_READ_ONLY, GR_BUFFER_AUXBUFFER));
        CHECK(1, rd[10 * (info.strideInBytes / 2) + 20] == 0xf800);
        CHECK(1, grLfbUnlock(GR_LFB_READ_ONLY, GR_BUFFER_BACKBUFFER));
    }

    /* Item 3: a partial download never reads past the level's rows. */
    if (want(3)) {
        long page = sysconf(_SC_PAGESIZE);
        char *mem = mmap(NULL, 2 * (size_t)page, PROT_READ | PROT_WRITE,
                         MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        CHECK(3, mem != MAP_FAILED);
        if (mem != MAP_FAILED) {
            mprotect(mem + page, (size_t)page, PROT_NONE);
            /* An 8x8 RGB565 level (128 bytes) that ends at the guard page. */
            void *level = mem + page - 128;
            memset(level, 0x11, 128);
            before = errors;
            CHECK(3, !grTexDownloadMipMapLevelPartial(GR_TMU0, 0, GR_LOD_LOG2_8, GR_LOD_LOG2_8,
                                                      GR_ASPECT_LOG2_1x1, GR_TEXFMT_RGB_565,
                                                      GR_MIPMAPLEVELMASK_BOTH, level, 0, 200));
            CHECK(3, reported(before, "grTexDownloadMipMapLevelPartial: invalid row range"));
            CHECK(3, grTexDownloadMipMapLevelPartial(GR_TMU0, 0, GR_LOD_LOG2_8, GR_LOD_LOG2_8,
                                                     GR_ASPECT_LOG2_1x1, GR_TEXFMT_RGB_565,
                                                     GR_MIPMAPLEVELMASK_BOTH, level, 4, 7));
            munmap(mem, 2 * (size_t)page);
        }
    }

    /* Item 10: a region is clipped to the LFB window; nothing wraps to the next row. */
    if (want(10)) {
        static FxU16 white[1100];
        for (int i = 0; i < 1100; i++)
            white[i] = 0xffff;
        grRenderBuffer(GR_BUFFER_BACKBUFFER);
        grBufferClear(0, 0, 0);
        CHECK(10, grLfbWriteRegion(GR_BUFFER_BACKBUFFER, 1000, 0, GR_LFB_SRC_FMT_565, 1100, 1,
                                   FXFALSE, 2200, white));
        CHECK(10, pixel(GR_BUFFER_BACKBUFFER, 1023, 0) == 0xffff);
        for (FxU32 x = 0; x < 80; x++)
            CHECK(10, pixel(GR_BUFFER_BACKBUFFER, x, 1) == 0);
        /* Wholly outside the window: nothing to write. */
        CHECK(10, grLfbWriteRegion(GR_BUFFER_BACKBUFFER, 0, 5000, GR_LFB_SRC_FMT_565,
                                   0x10000, 0x10000, FXFALSE, 0, white));
        CHECK(10, pixel(GR_BUFFER_BACKBUFFER, 0, 0) == 0);
    }

    /* Item 9: a second thread draws on the same board. */
    if (want(9)) {
        pthread_t t;
        grBufferClear(0, 0, 0);
        FxI32 tris = counter(GR_STATS_TRIANGLES_IN);
        pthread_create(&t, NULL, draw_from_thread, NULL);
        pthread_join(t, NULL);
        CHECK(9, thread_triangles == tris + 1);
        CHECK(9, pixel(GR_BUFFER_BACKBUFFER, 105, 105) == 0xffff);
    }

    /* Item 2: the error callback may call Glide, even grGlideShutdown. */
    if (want(2)) {
        reenter = 1;
        before = errors;
        grDepthBufferFunction(43);
        CHECK(2, reported(before, "grDepthBufferFunction"));
        CHECK(2, reentered_tmus == 1);
        reenter = 2;
        grDepthBufferFunction(44);
        CHECK(2, reenter == 0);
        /* Shut down from the callback; a new session opens and works. */
        FxI32 boards = 0;
        grGet(GR_NUM_BOARDS, 4, &boards);
        CHECK(2, boards == 1);
        open_window();
        before = errors;
        grDepthBufferFunction(45);
        CHECK(2, reported(before, "grDepthBufferFunction"));
    }

    grGlideShutdown();
    if (failures == 0)
        printf("ok\n");
    return failures != 0;
}

/* api.c -- the query and utility entry points from C: grGet (every answer 3dfx's
 * SST-1 Glide 3 gives on the default 4 MiB, 1-TMU board), grQueryResolutions,
 * grGetProcAddress, grReset, grGlideGetState/SetState through copied buffers, table
 * downloads and .3df files written here. Prints "ok". Argument: a scratch directory. */
#include <glide.h>
#include <glideutl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;

#define CHECK(cond)                                                   \
    do {                                                              \
        if (!(cond)) {                                                \
            printf("line %d: %s\n", __LINE__, #cond);                 \
            failures++;                                               \
        }                                                             \
    } while (0)

static const char *write_file(const char *dir, const char *name, const void *bytes, size_t n)
{
    static char path[512];
    snprintf(path, sizeof(path), "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f)
        return NULL;
    fwrite(bytes, 1, n, f);
    fclose(f);
    return path;
}

typedef void (*XYExt)(GrScreenResolution_t, FxU32 *, FxU32 *);

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : ".";
    FxI32 v[4] = {7, 7, 7, 7};

    /* GR_NUM_BOARDS works before grGlideInit. */
    CHECK(grGet(GR_NUM_BOARDS, 4, v) == 4 && v[0] == 1);

    grGlideInit();
    grSstSelect(0);
    CHECK(grSstWinOpen(0, GR_RESOLUTION_640x480, GR_REFRESH_60Hz, GR_COLORFORMAT_ARGB,
                       GR_ORIGIN_UPPER_LEFT, 2, 1) != 0);

    CHECK(grGet(GR_MEMORY_FB, 4, v) == 4 && v[0] == 4 << 20);
    CHECK(grGet(GR_VIEWPORT, 16, v) == 16 && v[2] == 640 && v[3] == 480);
    /* Wrong plength: FXTRUE, nothing written. */
    v[0] = 7;
    CHECK(grGet(GR_BITS_DEPTH, 8, v) == 1 && v[0] == 7);
    CHECK(grGet(0x7777, 4, v) == 0);
    CHECK(grGet(GR_BITS_DEPTH, 4, NULL) == 0);
    CHECK(strcmp(grGetString(GR_HARDWARE), "Voodoo Graphics") == 0);

    /* Resolutions: size query, then the list. */
    GrResolution any = {GR_QUERY_ANY, GR_QUERY_ANY, GR_QUERY_ANY, GR_QUERY_ANY};
    FxI32 size = grQueryResolutions(&any, NULL);
    CHECK(size == 64 * (FxI32)sizeof(GrResolution));
    GrResolution *list = malloc(size);
    CHECK(grQueryResolutions(&any, list) == size);
    CHECK(list[0].resolution == GR_RESOLUTION_512x384 && list[0].numColorBuffers == 2);
    free(list);

    /* Extensions. */
    CHECK(grGetProcAddress("grTexDownloadTableExt") != NULL);
    CHECK(grGetProcAddress("grSetNumPendingBuffers") != NULL);
    CHECK(grGetProcAddress("grChromaRangeExt") == NULL);
    /* Through void (*)(void) so -Wcast-function-type accepts the cast back. */
    XYExt xy = (XYExt)(void (*)(void))grGetProcAddress("guQueryResolutionXYExt");
    /* Called with its arguments through GrProc itself, as 3dfx's test programs do. */
    GrProc pending = grGetProcAddress("grSetNumPendingBuffers");
    if (pending)
        pending(2);
    FxU32 w = 0, h = 0;
    if (xy)
        xy(GR_RESOLUTION_800x600, &w, &h);
    CHECK(w == 800 && h == 600);

    /* Counters. */
    CHECK(grReset(GR_STATS_TRIANGLES) && grReset(GR_STATS_PIXELS));
    CHECK(!grReset(GR_BITS_DEPTH));

    /* State through a copied buffer. */
    CHECK(grGet(GR_GLIDE_STATE_SIZE, 4, v) == 4 && v[0] == 588);
    void *saved = malloc(v[0]), *copy = malloc(v[0]);
    grDepthBufferMode(GR_DEPTHBUFFER_WBUFFER);
    grGlideGetState(saved);
    memcpy(copy, saved, v[0]);
    grDepthBufferMode(GR_DEPTHBUFFER_DISABLE);
    grGlideSetState(copy);
    /* Saving again into the same buffer keeps working. */
    grGlideGetState(saved);
    grGlideSetState(saved);
    free(saved);
    free(copy);
    CHECK(grGet(GR_GLIDE_VERTEXLAYOUT_SIZE, 4, v) == 4 && v[0] == 100);
    void *layout = malloc(v[0]);
    grVertexLayout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    grGlideGetVertexLayout(layout);
    grReset(GR_VERTEX_PARAMETER);
    grGlideSetVertexLayout(layout);
    free(layout);

    /* A 4x4 RGB565 .3df with levels 4, 2, 1: 16 + 4 + 1 texels, big-endian. */
    unsigned char rgb[64 + 42];
    const char *hdr = "3df v1.1\nrgb565\nlod range: 1 4\naspect ratio: 1 1\n";
    size_t hl = strlen(hdr);
    memcpy(rgb, hdr, hl);
    for (int i = 0; i < 21; i++) {
        rgb[hl + 2 * i] = 0xf8;
        rgb[hl + 2 * i + 1] = (unsigned char)i;
    }
    const char *path = write_file(dir, "rgb.3df", rgb, hl + 42);
    Gu3dfInfo info;
    memset(&info, 0, sizeof(info));
    CHECK(path && gu3dfGetInfo(path, &info));
    CHECK(info.header.width == 4 && info.header.height == 4);
    CHECK(info.header.large_lod == GR_LOD_LOG2_4 && info.header.small_lod == GR_LOD_LOG2_1);
    CHECK(info.header.format == GR_TEXFMT_RGB_565 && info.mem_required == 42);
    FxU16 texels[21];
    info.data = texels;
    CHECK(gu3dfLoad(path, &info));
    CHECK(texels[0] == 0xf800 && texels[20] == 0xf814);
    /* One byte short: refused. */
    path = write_file(dir, "short.3df", rgb, hl + 41);
    CHECK(path && gu3dfGetInfo(path, &info) && !gu3dfLoad(path, &info));
    CHECK(!gu3dfGetInfo("/nonexistent/x.3df", &info));

    /* A 2x2 P8 .3df: palette then 4 + 1 texels; download table and texture. */
    unsigned char p8[128 + 1024 + 5];
    hdr = "3df v1.1\np8\nlod range: 1 2\naspect ratio: 1 1\n";
    hl = strlen(hdr);
    memcpy(p8, hdr, hl);
    for (int i = 0; i < 256; i++) {
        p8[hl + 4 * i] = 0;
        p8[hl + 4 * i + 1] = (unsigned char)i;
        p8[hl + 4 * i + 2] = 0x12;
        p8[hl + 4 * i + 3] = 0x34;
    }
    for (int i = 0; i < 5; i++)
        p8[hl + 1024 + i] = (unsigned char)(i + 1);
    path = write_file(dir, "pal.3df", p8, hl + 1024 + 5);
    CHECK(path && gu3dfGetInfo(path, &info) && info.mem_required == 5);
    unsigned char idx[5];
    info.data = idx;
    CHECK(gu3dfLoad(path, &info));
    CHECK(info.table.palette.data[255] == 0x00ff1234 && idx[4] == 5);
    grTexDownloadTable(GR_TEXTABLE_PALETTE, &info.table.palette);
    grTexDownloadTablePartial(GR_TEXTABLE_PALETTE, &info.table.palette, 8, 15);
    GrTexInfo ti = {GR_LOD_LOG2_1, GR_LOD_LOG2_2, GR_ASPECT_LOG2_1x1, GR_TEXFMT_P_8, idx};
    grTexDownloadMipMap(GR_TMU0, grTexMinAddress(GR_TMU0), GR_MIPMAPLEVELMASK_BOTH, &ti);

    grGlideShutdown();
    if (failures == 0)
        printf("ok\n");
    return failures != 0;
}

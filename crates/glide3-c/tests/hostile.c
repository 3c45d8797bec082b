/* hostile.c -- bad arguments must reach the error callback with a message naming the
 * call and change nothing: no triangle counted, no pixel drawn. Prints "ok". */
#include <glide.h>
#include <stdio.h>
#include <string.h>

static int errors;
static char last[256];

static void on_error(const char *msg, FxBool fatal)
{
    (void)fatal;
    errors++;
    snprintf(last, sizeof(last), "%s", msg);
}

static int expect(int n, const char *prefix)
{
    if (errors != n || strncmp(last, prefix, strlen(prefix)) != 0) {
        printf("after %s: %d errors, last \"%s\"\n", prefix, errors, last);
        return 0;
    }
    return 1;
}

static FxU16 texels[256 * 256];

int main(void)
{
    grGlideInit();
    grSstSelect(0);
    if (!grSstWinOpen(0, GR_RESOLUTION_640x480, GR_REFRESH_60Hz, GR_COLORFORMAT_ARGB,
                      GR_ORIGIN_UPPER_LEFT, 2, 1))
        return 1;
    grErrorSetCallback(on_error);
    grVertexLayout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    float v[2] = { 10.0f, 10.0f };

    grDrawTriangle(v, NULL, v);
    if (!expect(1, "grDrawTriangle: NULL pointer passed"))
        return 1;
    grDepthBufferFunction(42);
    if (!expect(2, "grDepthBufferFunction: invalid compare function"))
        return 1;
    /* A 256x256 RGB565 texture (128 KiB) starting 1 KiB before the end of TMU memory. */
    GrTexInfo big = { GR_LOD_LOG2_256, GR_LOD_LOG2_256, GR_ASPECT_LOG2_1x1, GR_TEXFMT_RGB_565, texels };
    FxU32 start = grTexMaxAddress(GR_TMU0) - 1024;
    grTexDownloadMipMap(GR_TMU0, start, GR_MIPMAPLEVELMASK_BOTH, &big);
    if (!expect(3, "grTexDownloadMipMap: insufficient texture ram"))
        return 1;
    grTexSource(GR_TMU0, start, GR_MIPMAPLEVELMASK_BOTH, &big);
    if (!expect(4, "grTexSource: insufficient texture ram"))
        return 1;

    FxI32 tris = -1, pixels = -1;
    grGet(GR_STATS_TRIANGLES_IN, 4, &tris);
    grGet(GR_STATS_PIXELS_OUT, 4, &pixels);
    if (tris != 0 || pixels != 0) {
        printf("state changed: %d triangles, %d pixels\n", tris, pixels);
        return 1;
    }
    grGlideShutdown();
    printf("ok\n");
    return 0;
}

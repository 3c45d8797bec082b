/* small_triangles.c -- many small triangles through libglide3, for timing the library
 * (docs/performance.md, "The Glide library"): `small_triangles g|t [COUNT]`, Gouraud or
 * bilinear-textured triangles of about 10 pixels each (default 200,000), a buffer swap
 * every 20,000. Build and run:
 *   cargo build --release -p glide3-c
 *   cc -O2 -std=gnu17 -I crates/glide3-c/include crates/glide3-c/bench/small_triangles.c \
 *      -L target/release -lglide3 -lm -o /tmp/small_triangles
 *   time VOODOO_THREADS=2 LD_LIBRARY_PATH=target/release /tmp/small_triangles t */
#include <glide.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
typedef struct { float x, y, oow, r, g, b, s, t; } Vtx;
static FxU16 texels[64 * 64];
static unsigned st = 12345;
static float rnd(void) { st = st * 1103515245u + 12345u; return (float)((st >> 8) & 0xffff) / 65536.0f; }
int main(int argc, char **argv)
{
    int tex = argc > 1 && strcmp(argv[1], "t") == 0;
    int count = argc > 2 ? atoi(argv[2]) : 200000;
    grGlideInit();
    grSstSelect(0);
    if (!grSstWinOpen(0, GR_RESOLUTION_640x480, GR_REFRESH_60Hz, GR_COLORFORMAT_ARGB, GR_ORIGIN_UPPER_LEFT, 2, 1)) return 1;
    grVertexLayout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_Q, 8, GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_RGB, 12, GR_PARAM_ENABLE);
    if (tex) {
        for (int i = 0; i < 64 * 64; i++) texels[i] = (FxU16)(i * 2654435761u >> 7);
        GrTexInfo info = { GR_LOD_LOG2_64, GR_LOD_LOG2_64, GR_ASPECT_LOG2_1x1, GR_TEXFMT_RGB_565, texels };
        FxU32 start = grTexMinAddress(GR_TMU0);
        grTexDownloadMipMap(GR_TMU0, start, GR_MIPMAPLEVELMASK_BOTH, &info);
        grTexSource(GR_TMU0, start, GR_MIPMAPLEVELMASK_BOTH, &info);
        grTexCombine(GR_TMU0, GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE, GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE, FXFALSE, FXFALSE);
        grTexFilterMode(GR_TMU0, GR_TEXTUREFILTER_BILINEAR, GR_TEXTUREFILTER_BILINEAR);
        grVertexLayout(GR_PARAM_ST0, 24, GR_PARAM_ENABLE);
        grColorCombine(GR_COMBINE_FUNCTION_SCALE_OTHER, GR_COMBINE_FACTOR_LOCAL, GR_COMBINE_LOCAL_ITERATED, GR_COMBINE_OTHER_TEXTURE, FXFALSE);
    } else {
        grColorCombine(GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE, GR_COMBINE_LOCAL_ITERATED, GR_COMBINE_OTHER_NONE, FXFALSE);
    }
    grBufferClear(0, 0, 0);
    for (int i = 0; i < count; i++) {
        float cx = rnd() * 630.0f, cy = rnd() * 470.0f;
        Vtx v[3];
        for (int k = 0; k < 3; k++) {
            float w = 0.5f + rnd();
            v[k].x = cx + rnd() * 5.0f; v[k].y = cy + rnd() * 5.0f; v[k].oow = w;
            v[k].r = rnd() * 255; v[k].g = rnd() * 255; v[k].b = rnd() * 255;
            v[k].s = rnd() * 64 * w; v[k].t = rnd() * 64 * w;
        }
        grDrawTriangle(&v[0], &v[1], &v[2]);
        if (i % 20000 == 19999) grBufferSwap(0);
    }
    grBufferSwap(0);
    grGlideShutdown();
    return 0;
}

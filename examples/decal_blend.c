/* decal_blend.c -- transparency and chroma-key decals.
 * A flat blue background, a half-transparent red quad blended over it with
 * (src alpha, 1 - src alpha), and a green decal whose magenta pixels are removed by
 * the chroma key; the decal is written through grLfbWriteRegion. */
#include <glide.h>
#include <stdio.h>

typedef struct { float x, y, a; } Vtx;

static FxU16 decal[32 * 32];

int main(void)
{
    grGlideInit();
    grSstSelect(0);
    if (!grSstWinOpen(0, GR_RESOLUTION_640x480, GR_REFRESH_60Hz, GR_COLORFORMAT_ARGB,
                      GR_ORIGIN_UPPER_LEFT, 2, 1)) {
        fprintf(stderr, "decal_blend: grSstWinOpen failed\n");
        return 1;
    }
    grBufferClear(0x0000c0, 0, 0);

    /* 50% red over blue. */
    grVertexLayout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_A, 2 * sizeof(float), GR_PARAM_ENABLE);
    grConstantColorValue(0xffff0000);
    grColorCombine(GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE,
                   GR_COMBINE_LOCAL_CONSTANT, GR_COMBINE_OTHER_NONE, FXFALSE);
    grAlphaCombine(GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE,
                   GR_COMBINE_LOCAL_ITERATED, GR_COMBINE_OTHER_NONE, FXFALSE);
    grAlphaBlendFunction(GR_BLEND_SRC_ALPHA, GR_BLEND_ONE_MINUS_SRC_ALPHA, GR_BLEND_ZERO, GR_BLEND_ZERO);
    Vtx q[4] = { { 100, 100, 128 }, { 400, 100, 128 }, { 400, 300, 128 }, { 100, 300, 128 } };
    void *fan[4] = { &q[0], &q[1], &q[2], &q[3] };
    grDrawVertexArray(GR_TRIANGLE_FAN, 4, fan);

    /* Chroma-keyed decal: magenta is transparent. */
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 32; x++)
            decal[y * 32 + x] = ((x - 16) * (x - 16) + (y - 16) * (y - 16) < 144) ? 0x07e0 : 0xf81f;
    grAlphaBlendFunction(GR_BLEND_ONE, GR_BLEND_ZERO, GR_BLEND_ONE, GR_BLEND_ZERO);
    grChromakeyValue(0xff00ff);
    grChromakeyMode(GR_CHROMAKEY_ENABLE);
    for (int i = 0; i < 4; i++)
        grLfbWriteRegion(GR_BUFFER_BACKBUFFER, 200 + 40 * i, 180, GR_LFB_SRC_FMT_565, 32, 32,
                         FXTRUE, 32 * sizeof(FxU16), decal);
    grChromakeyMode(GR_CHROMAKEY_DISABLE);

    grBufferSwap(1);
    grGlideShutdown();
    return 0;
}

/* lfb_overlay.c -- a 3D scene with 2D overlays written through the linear frame buffer.
 * A depth-buffered Gouraud floor and two interpenetrating triangles, then a HUD: a
 * status bar written with a grLfbLock write pointer (RGB565, no pixel pipeline), a
 * gauge written with grLfbWriteRegion through the pixel pipeline with a constant
 * depth in front of everything, and a half-transparent panel blended over the scene
 * (ARGB1555 pixels through the pipeline with alpha blending on). The back buffer is
 * read back with grLfbReadRegion to check the status bar landed.
 * Build: cc -std=gnu17 -I crates/glide3-c/include examples/lfb_overlay.c -L <dir> -lglide3 */
#include <glide.h>
#include <stdio.h>

typedef struct { float x, y, ooz, r, g, b, a; } Vtx;

static FxU16 gauge[24 * 96];
static FxU16 panel[64 * 160];

int main(void)
{
    grGlideInit();
    grSstSelect(0);
    if (!grSstWinOpen(0, GR_RESOLUTION_640x480, GR_REFRESH_60Hz, GR_COLORFORMAT_ARGB,
                      GR_ORIGIN_UPPER_LEFT, 2, 1)) {
        fprintf(stderr, "lfb_overlay: grSstWinOpen failed\n");
        return 1;
    }
    grVertexLayout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_Z, 2 * sizeof(float), GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_RGB, 3 * sizeof(float), GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_A, 6 * sizeof(float), GR_PARAM_ENABLE);
    grColorCombine(GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE,
                   GR_COMBINE_LOCAL_ITERATED, GR_COMBINE_OTHER_NONE, FXFALSE);
    grDepthBufferMode(GR_DEPTHBUFFER_ZBUFFER);
    grDepthBufferFunction(GR_CMP_LESS);
    grDepthMask(FXTRUE);
    grBufferClear(0x000000, 0, 0xffff);

    /* Floor: dark near the horizon, bright near the viewer. */
    Vtx floor[4] = {
        { 200.0f, 240.0f, 60000.0f,  20.0f,  40.0f,  20.0f, 255.0f },
        { 440.0f, 240.0f, 60000.0f,  20.0f,  40.0f,  20.0f, 255.0f },
        { 640.0f, 480.0f, 10000.0f,  60.0f, 200.0f,  60.0f, 255.0f },
        {   0.0f, 480.0f, 10000.0f,  60.0f, 200.0f,  60.0f, 255.0f },
    };
    grDrawTriangle(&floor[0], &floor[1], &floor[2]);
    grDrawTriangle(&floor[0], &floor[2], &floor[3]);
    /* Two triangles cutting through each other. */
    Vtx t1[3] = { { 180.0f, 100.0f, 20000.0f, 255.0f, 64.0f, 0.0f, 255.0f },
                  { 460.0f, 160.0f, 50000.0f, 255.0f, 200.0f, 0.0f, 255.0f },
                  { 260.0f, 400.0f, 20000.0f, 200.0f, 0.0f, 0.0f, 255.0f } };
    Vtx t2[3] = { { 440.0f,  90.0f, 20000.0f, 0.0f, 64.0f, 255.0f, 255.0f },
                  { 380.0f, 410.0f, 20000.0f, 0.0f, 200.0f, 255.0f, 255.0f },
                  { 150.0f, 200.0f, 50000.0f, 0.0f, 0.0f, 200.0f, 255.0f } };
    grDrawTriangle(&t1[0], &t1[1], &t1[2]);
    grDrawTriangle(&t2[0], &t2[1], &t2[2]);

    /* Status bar through a write lock: a blue band with a white tick every 32 pixels. */
    GrLfbInfo_t info;
    info.size = sizeof(info);
    if (!grLfbLock(GR_LFB_WRITE_ONLY, GR_BUFFER_BACKBUFFER, GR_LFBWRITEMODE_565,
                   GR_ORIGIN_UPPER_LEFT, FXFALSE, &info)) {
        fprintf(stderr, "lfb_overlay: grLfbLock failed\n");
        return 1;
    }
    for (int y = 8; y < 24; y++) {
        FxU16 *row = (FxU16 *)((char *)info.lfbPtr + y * info.strideInBytes);
        for (int x = 8; x < 632; x++)
            row[x] = (x % 32 == 0) ? 0xffff : 0x001f;
    }
    grLfbUnlock(GR_LFB_WRITE_ONLY, GR_BUFFER_BACKBUFFER);

    /* Gauge: a vertical bar through the pipeline at constant depth 0 (in front). */
    for (int y = 0; y < 96; y++)
        for (int x = 0; x < 24; x++)
            gauge[y * 24 + x] = (y > 30) ? (FxU16)(0xf800 | ((95 - y) / 2) << 5) : 0x2104;
    grLfbConstantDepth(0);
    grDepthBufferFunction(GR_CMP_LEQUAL);
    grLfbWriteRegion(GR_BUFFER_BACKBUFFER, 600, 360, GR_LFB_SRC_FMT_565, 24, 96, FXTRUE,
                     24 * sizeof(FxU16), gauge);

    /* Half-transparent panel: ARGB1555 with alpha 1, blended with a constant 50 %. */
    for (int i = 0; i < 64 * 160; i++)
        panel[i] = 0x8000 | (12 << 10) | (12 << 5) | 20;
    grDepthBufferMode(GR_DEPTHBUFFER_DISABLE);
    grLfbConstantAlpha(0x80);
    grAlphaBlendFunction(GR_BLEND_SRC_ALPHA, GR_BLEND_ONE_MINUS_SRC_ALPHA, GR_BLEND_ZERO, GR_BLEND_ZERO);
    grAlphaCombine(GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE,
                   GR_COMBINE_LOCAL_CONSTANT, GR_COMBINE_OTHER_NONE, FXFALSE);
    grConstantColorValue(0x80000000);
    grLfbWriteRegion(GR_BUFFER_BACKBUFFER, 16, 400, GR_LFB_SRC_FMT_555, 160, 64, FXTRUE,
                     160 * sizeof(FxU16), panel);

    /* Read the bar back. */
    FxU16 back[4];
    if (!grLfbReadRegion(GR_BUFFER_BACKBUFFER, 30, 10, 4, 1, sizeof(back), back)
        || back[0] != 0x001f || back[2] != 0xffff) {
        fprintf(stderr, "lfb_overlay: read back %04x %04x %04x %04x\n",
                back[0], back[1], back[2], back[3]);
        return 1;
    }
    grBufferSwap(1);
    grGlideShutdown();
    return 0;
}

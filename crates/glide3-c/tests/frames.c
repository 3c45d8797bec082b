/* frames.c -- three frames drawn with one texture downloaded before the first (so a
 * board restored after frame 1 needs the texture memory, the fog table and the
 * registers from the state), for the save-state test (tests/save_state.rs). */
#include <glide.h>
#include <stdio.h>

typedef struct { float x, y, oow, sow, tow; } Vtx;

static FxU16 texels[64 * 64];

int main(void)
{
    grGlideInit();
    grSstSelect(0);
    if (!grSstWinOpen(0, GR_RESOLUTION_640x480, GR_REFRESH_60Hz, GR_COLORFORMAT_ARGB,
                      GR_ORIGIN_UPPER_LEFT, 2, 1)) {
        fprintf(stderr, "frames: grSstWinOpen failed\n");
        return 1;
    }
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++)
            texels[y * 64 + x] = (FxU16)((((x >> 2) ^ (y >> 3)) & 1) ? 0x07e0 + x : 0xf81f - y);

    GrTexInfo info;
    info.smallLodLog2 = GR_LOD_LOG2_64;
    info.largeLodLog2 = GR_LOD_LOG2_64;
    info.aspectRatioLog2 = GR_ASPECT_LOG2_1x1;
    info.format = GR_TEXFMT_RGB_565;
    info.data = texels;
    FxU32 start = grTexMinAddress(GR_TMU0);
    grTexDownloadMipMap(GR_TMU0, start, GR_MIPMAPLEVELMASK_BOTH, &info);
    grTexSource(GR_TMU0, start, GR_MIPMAPLEVELMASK_BOTH, &info);
    grTexCombine(GR_TMU0, GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE,
                 GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE, FXFALSE, FXFALSE);
    grTexFilterMode(GR_TMU0, GR_TEXTUREFILTER_BILINEAR, GR_TEXTUREFILTER_BILINEAR);
    grColorCombine(GR_COMBINE_FUNCTION_SCALE_OTHER, GR_COMBINE_FACTOR_ONE,
                   GR_COMBINE_LOCAL_NONE, GR_COMBINE_OTHER_TEXTURE, FXFALSE);
    GrFog_t fog[GR_FOG_TABLE_SIZE];
    guFogGenerateExp(fog, 0.5f);
    grFogTable(fog);
    grFogColorValue(0x203040);
    grFogMode(GR_FOG_WITH_TABLE_ON_W);
    grVertexLayout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_Q, 2 * sizeof(float), GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_ST0, 3 * sizeof(float), GR_PARAM_ENABLE);

    for (int frame = 0; frame < 3; frame++) {
        float dx = 60.0f * frame;
        Vtx v[3] = {
            {  40.0f + dx, 460.0f, 1.0f,   0.0f,          0.0f },
            { 400.0f + dx, 440.0f, 1.0f,   510.0f,        0.0f },
            { 200.0f + dx,  60.0f, 0.2f,   51.0f,         102.0f },
        };
        grBufferClear(0x203040, 0, 0);
        grDrawTriangle(&v[0], &v[1], &v[2]);
        grBufferSwap(1);
    }
    grGlideShutdown();
    return 0;
}

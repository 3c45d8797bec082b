/* textured_fog.c -- a checkerboard-textured quad receding into exponential fog.
 * Downloads a 64x64 RGB565 texture, draws two triangles with per-vertex 1/w and
 * table fog on W. */
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
        fprintf(stderr, "textured_fog: grSstWinOpen failed\n");
        return 1;
    }
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++)
            texels[y * 64 + x] = (((x >> 3) ^ (y >> 3)) & 1) ? 0xf800 : 0xffe0;

    GrTexInfo info;
    info.smallLodLog2 = GR_LOD_LOG2_64;
    info.largeLodLog2 = GR_LOD_LOG2_64;
    info.aspectRatioLog2 = GR_ASPECT_LOG2_1x1;
    info.format = GR_TEXFMT_RGB_565;
    info.data = texels;
    FxU32 start = grTexMinAddress(GR_TMU0);
    if (start + grTexTextureMemRequired(GR_MIPMAPLEVELMASK_BOTH, &info) > grTexMaxAddress(GR_TMU0))
        return 1;
    grTexDownloadMipMap(GR_TMU0, start, GR_MIPMAPLEVELMASK_BOTH, &info);
    grTexSource(GR_TMU0, start, GR_MIPMAPLEVELMASK_BOTH, &info);
    grTexCombine(GR_TMU0, GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE,
                 GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE, FXFALSE, FXFALSE);
    grTexFilterMode(GR_TMU0, GR_TEXTUREFILTER_BILINEAR, GR_TEXTUREFILTER_BILINEAR);
    grTexClampMode(GR_TMU0, GR_TEXTURECLAMP_WRAP, GR_TEXTURECLAMP_WRAP);
    grColorCombine(GR_COMBINE_FUNCTION_SCALE_OTHER, GR_COMBINE_FACTOR_ONE,
                   GR_COMBINE_LOCAL_NONE, GR_COMBINE_OTHER_TEXTURE, FXFALSE);

    GrFog_t fog[GR_FOG_TABLE_SIZE];
    guFogGenerateExp(fog, 0.35f);
    grFogTable(fog);
    grFogColorValue(0x404060);
    grFogMode(GR_FOG_WITH_TABLE_ON_W);

    grVertexLayout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_Q, 2 * sizeof(float), GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_ST0, 3 * sizeof(float), GR_PARAM_ENABLE);

    /* Near edge at w = 1, far edge at w = 8; s and t span 4 texture repeats. */
    Vtx v[4] = {
        {  40.0f, 460.0f, 1.0f,          0.0f,          0.0f },
        { 600.0f, 460.0f, 1.0f,  4 * 255.0f,           0.0f },
        { 390.0f, 120.0f, 0.125f, 4 * 255.0f * 0.125f, 4 * 255.0f * 0.125f },
        { 250.0f, 120.0f, 0.125f, 0.0f,                4 * 255.0f * 0.125f },
    };
    grBufferClear(0x404060, 0, 0);
    grDrawTriangle(&v[0], &v[1], &v[2]);
    grDrawTriangle(&v[0], &v[2], &v[3]);
    grBufferSwap(1);
    grGlideShutdown();
    return 0;
}

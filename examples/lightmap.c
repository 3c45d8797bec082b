/* lightmap.c -- multi-pass light mapping on one TMU.
 * Pass 1 draws a brick wall (64x64 RGB565, bilinear, wrapped four times) into the
 * depth buffer. Pass 2 draws the same quad again with an 8-bit intensity light map
 * (a soft spot) blended as dst * src (GR_BLEND_DST_COLOR, GR_BLEND_ZERO), with the
 * depth test set to GR_CMP_EQUAL and depth writes off, so only the wall is lit.
 * Build: cc -std=gnu17 -I crates/glide3-c/include examples/lightmap.c -L <dir> -lglide3 -lm */
#include <glide.h>
#include <math.h>
#include <stdio.h>

typedef struct { float x, y, ooz, oow, sow, tow; } Vtx;

static FxU16 bricks[64 * 64];
static FxU8 light[64 * 64];

static void draw_quad(const Vtx *v)
{
    grDrawTriangle(&v[0], &v[1], &v[2]);
    grDrawTriangle(&v[0], &v[2], &v[3]);
}

int main(void)
{
    grGlideInit();
    grSstSelect(0);
    if (!grSstWinOpen(0, GR_RESOLUTION_640x480, GR_REFRESH_60Hz, GR_COLORFORMAT_ARGB,
                      GR_ORIGIN_UPPER_LEFT, 2, 1)) {
        fprintf(stderr, "lightmap: grSstWinOpen failed\n");
        return 1;
    }
    /* Bricks: 16x8 texel bricks, offset every other row, grey mortar. */
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) {
            int row = y / 8, bx = (x + (row & 1) * 8) % 16;
            int mortar = (y % 8 == 0) || (bx == 0);
            bricks[y * 64 + x] = mortar ? 0x8410 : (FxU16)(0xa000 | ((row * 3 & 7) << 6));
        }
    /* Light map: a soft spot off centre, dim ambient elsewhere. */
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) {
            float dx = (x - 24) / 20.0f, dy = (y - 28) / 20.0f;
            float l = 0.25f + 0.75f * expf(-(dx * dx + dy * dy));
            light[y * 64 + x] = (FxU8)(l * 255.0f);
        }

    GrTexInfo wall = { GR_LOD_LOG2_64, GR_LOD_LOG2_64, GR_ASPECT_LOG2_1x1, GR_TEXFMT_RGB_565, bricks };
    GrTexInfo lmap = { GR_LOD_LOG2_64, GR_LOD_LOG2_64, GR_ASPECT_LOG2_1x1, GR_TEXFMT_INTENSITY_8, light };
    FxU32 wall_at = grTexMinAddress(GR_TMU0);
    FxU32 lmap_at = wall_at + grTexTextureMemRequired(GR_MIPMAPLEVELMASK_BOTH, &wall);
    grTexDownloadMipMap(GR_TMU0, wall_at, GR_MIPMAPLEVELMASK_BOTH, &wall);
    grTexDownloadMipMap(GR_TMU0, lmap_at, GR_MIPMAPLEVELMASK_BOTH, &lmap);

    grVertexLayout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_Z, 2 * sizeof(float), GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_Q, 3 * sizeof(float), GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_ST0, 4 * sizeof(float), GR_PARAM_ENABLE);
    grTexCombine(GR_TMU0, GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE,
                 GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE, FXFALSE, FXFALSE);
    grTexFilterMode(GR_TMU0, GR_TEXTUREFILTER_BILINEAR, GR_TEXTUREFILTER_BILINEAR);
    grColorCombine(GR_COMBINE_FUNCTION_SCALE_OTHER, GR_COMBINE_FACTOR_ONE,
                   GR_COMBINE_LOCAL_NONE, GR_COMBINE_OTHER_TEXTURE, FXFALSE);
    grDepthBufferMode(GR_DEPTHBUFFER_ZBUFFER);
    grDepthMask(FXTRUE);
    grDepthBufferFunction(GR_CMP_LESS);

    /* A wall in perspective: the right edge is twice as far away. */
    const float s = 4 * 255.0f;
    Vtx q[4] = {
        {  60.0f,  40.0f, 20000.0f, 1.0f,  0.0f,     0.0f },
        { 560.0f, 140.0f, 40000.0f, 0.5f,  s * 0.5f, 0.0f },
        { 560.0f, 340.0f, 40000.0f, 0.5f,  s * 0.5f, s * 0.5f },
        {  60.0f, 440.0f, 20000.0f, 1.0f,  0.0f,     s },
    };
    grBufferClear(0x102030, 0, 0xffff);

    /* Pass 1: the base texture. */
    grTexClampMode(GR_TMU0, GR_TEXTURECLAMP_WRAP, GR_TEXTURECLAMP_WRAP);
    grTexSource(GR_TMU0, wall_at, GR_MIPMAPLEVELMASK_BOTH, &wall);
    draw_quad(q);

    /* Pass 2: the light map once across the wall, modulating what is there. */
    Vtx l[4];
    for (int i = 0; i < 4; i++) {
        l[i] = q[i];
        l[i].sow = q[i].sow / 4.0f;
        l[i].tow = q[i].tow / 4.0f;
    }
    grTexClampMode(GR_TMU0, GR_TEXTURECLAMP_CLAMP, GR_TEXTURECLAMP_CLAMP);
    grTexSource(GR_TMU0, lmap_at, GR_MIPMAPLEVELMASK_BOTH, &lmap);
    grDepthBufferFunction(GR_CMP_EQUAL);
    grDepthMask(FXFALSE);
    grAlphaBlendFunction(GR_BLEND_DST_COLOR, GR_BLEND_ZERO, GR_BLEND_ONE, GR_BLEND_ZERO);
    draw_quad(l);

    grBufferSwap(1);
    grGlideShutdown();
    return 0;
}

/* gouraud.c -- one Gouraud-shaded triangle (red, green, blue corners) on black.
 * Build: cc -std=gnu17 -I crates/glide3-c/include examples/gouraud.c -L <dir> -lglide3 */
#include <glide.h>
#include <stdio.h>

typedef struct { float x, y, r, g, b; } Vtx;

int main(void)
{
    grGlideInit();
    grSstSelect(0);
    if (!grSstWinOpen(0, GR_RESOLUTION_640x480, GR_REFRESH_60Hz, GR_COLORFORMAT_ARGB,
                      GR_ORIGIN_UPPER_LEFT, 2, 1)) {
        fprintf(stderr, "gouraud: grSstWinOpen failed\n");
        return 1;
    }
    grVertexLayout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_RGB, 2 * sizeof(float), GR_PARAM_ENABLE);
    grColorCombine(GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE,
                   GR_COMBINE_LOCAL_ITERATED, GR_COMBINE_OTHER_NONE, FXFALSE);

    Vtx a = { 192.0f, 144.0f, 255.0f, 0.0f, 0.0f };
    Vtx b = { 512.0f, 192.0f, 0.0f, 255.0f, 0.0f };
    Vtx c = { 320.0f, 384.0f, 0.0f, 0.0f, 255.0f };
    for (int frame = 0; frame < 2; frame++) {
        grBufferClear(0x000000, 0, 0);
        grDrawTriangle(&a, &b, &c);
        grBufferSwap(1);
    }
    grGlideShutdown();
    return 0;
}

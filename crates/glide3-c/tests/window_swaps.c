/* The live window of libglide3 (VOODOO_WINDOW=1), for tests/window.rs: draws the
 * same frame (a clear and a Gouraud triangle) and swaps it until the window has
 * written the capture VOODOO_WINDOW_CAPTURE names, or 1000 swaps have gone by. */
#include <glide.h>
#include <stdlib.h>
#include <unistd.h>

int main(void) {
    const char *capture = getenv("VOODOO_WINDOW_CAPTURE");
    if (!capture)
        return 2;
    grGlideInit();
    grSstSelect(0);
    if (!grSstWinOpen(0, GR_RESOLUTION_640x480, GR_REFRESH_60Hz, GR_COLORFORMAT_ARGB,
                      GR_ORIGIN_UPPER_LEFT, 2, 1))
        return 1;
    grVertexLayout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_RGB, 8, GR_PARAM_ENABLE);
    grColorCombine(GR_COMBINE_FUNCTION_LOCAL, GR_COMBINE_FACTOR_NONE,
                   GR_COMBINE_LOCAL_ITERATED, GR_COMBINE_OTHER_NONE, FXFALSE);
    float a[5] = {100.0f, 400.0f, 255.0f, 0.0f, 0.0f};
    float b[5] = {320.0f, 60.0f, 0.0f, 255.0f, 0.0f};
    float c[5] = {560.0f, 420.0f, 0.0f, 0.0f, 255.0f};
    for (int i = 0; i < 1000 && access(capture, F_OK) != 0; i++) {
        grBufferClear(0x00203040, 0, 0xffff);
        grDrawTriangle(a, b, c);
        grBufferSwap(1);
        usleep(10000);
    }
    grGlideShutdown();
    return access(capture, F_OK) == 0 ? 0 : 3;
}

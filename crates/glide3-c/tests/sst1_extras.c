/* sst1_extras.c -- the entry points 3dfx's SST-1 Glide 3 library exports without
 * declaring them in its headers (Glide 2 leftovers and utilities). A program that
 * uses them declares them itself, as this one does. Each call is checked against
 * what it must do; prints "ok". */
#include <glide.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A program's own video timing record (the layout is the program's business: the
 * library never reads it). */
typedef struct {
    FxU32 hSyncOn, hSyncOff, vSyncOn, vSyncOff;
    FxU32 hBackPorch, vBackPorch, xDimension, yDimension;
} FxVideoTimingInfo;

typedef struct { int tmuRev, tmuRam; } TmuConfig;
typedef struct {
    int fbRam, fbiRev, nTexelfx;
    FxBool sliDetect;
    TmuConfig tmuConfig[2];
} VoodooConfig;
typedef struct {
    int num_sst;
    struct { int type; VoodooConfig voodoo; } SSTs[4];
} GrHwConfiguration;

FX_ENTRY void FX_CALL grSstVidMode(FxU32 whichSst, FxVideoTimingInfo *vidTimings);
FX_ENTRY FxBool FX_CALL grSstIsBusy(void);
FX_ENTRY FxBool FX_CALL grSstVRetraceOn(void);
FX_ENTRY FxU32 FX_CALL grSstVideoLine(void);
FX_ENTRY FxU32 FX_CALL grSstScreenWidth(void);
FX_ENTRY FxU32 FX_CALL grSstScreenHeight(void);
FX_ENTRY void FX_CALL grSstPerfStats(GrSstPerfStats_t *pStats);
FX_ENTRY void FX_CALL grTriStats(FxU32 *trisProcessed, FxU32 *trisDrawn);
FX_ENTRY void FX_CALL grCheckForRoom(FxI32 n);
FX_ENTRY FxBool FX_CALL grSstQueryBoards(GrHwConfiguration *hwc);
FX_ENTRY FxBool FX_CALL grSstQueryHardware(GrHwConfiguration *hwc);
FX_ENTRY void FX_CALL grSstConfigPipeline(GrChipID_t chip, FxU32 reg, FxU32 value);
FX_ENTRY void FX_CALL grSetNumPendingBuffers(FxI32 n);
FX_ENTRY void FX_CALL grGlideShamelessPlug(const FxBool mode);
FX_ENTRY char *FX_CALL grGetRegistryOrEnvironmentString(char *name);
FX_ENTRY void FX_CALL guAlphaSource(GrAlphaSource_t mode);
FX_ENTRY void FX_CALL guColorCombineFunction(GrColorCombineFnc_t fnc);
FX_ENTRY FxU16 FX_CALL guEndianSwapBytes(FxU16 value);
FX_ENTRY FxU32 FX_CALL guEndianSwapWords(FxU32 value);
FX_ENTRY FxU16 *FX_CALL guTexCreateColorMipMap(void);
FX_ENTRY int FX_CALL guEncodeRLE16(void *dst, void *src, FxU32 width, FxU32 height);
FX_ENTRY void FX_CALL _grChromaModeExt(GrChromakeyMode_t mode);
FX_ENTRY void FX_CALL _grChromaRangeExt(GrColor_t color, GrColor_t range, GrChromaRangeMode_t mode);

static int errors;
static char last[256];

static void on_error(const char *msg, FxBool fatal)
{
    (void)fatal;
    errors++;
    snprintf(last, sizeof(last), "%s", msg);
}

#define CHECK(cond)                                                      \
    do {                                                                 \
        if (!(cond)) {                                                   \
            printf("line %d: %s (last error \"%s\")\n", __LINE__, #cond, last); \
            return 1;                                                    \
        }                                                                \
    } while (0)

typedef struct { float x, y, r, g, b, a; } Vtx;

/* One triangle covering (100, 100), every vertex the colour (r, g, b, a). */
static void triangle(float r, float g, float b, float a)
{
    Vtx v[3] = { { 50, 50, r, g, b, a }, { 200, 60, r, g, b, a }, { 90, 200, r, g, b, a } };
    grDrawTriangle(&v[0], &v[1], &v[2]);
}

/* The back buffer's RGB565 pixel at (100, 100). */
static FxU16 pixel(void)
{
    FxU16 px = 0x1234;
    grLfbReadRegion(GR_BUFFER_BACKBUFFER, 100, 100, 1, 1, 2, &px);
    return px;
}

static FxU32 stat(FxU32 pname)
{
    FxI32 v = -1;
    grGet(pname, 4, &v);
    return (FxU32)v;
}

int main(void)
{
    GrHwConfiguration hwc;
    FxVideoTimingInfo timing = { 96, 704, 2, 523, 40, 25, 640, 480 };

    /* Before grGlideInit: QueryBoards sets num_sst only; QueryHardware finds nothing. */
    memset(&hwc, 0x55, sizeof hwc);
    CHECK(sizeof(GrHwConfiguration) == 148);
    CHECK(grSstQueryBoards(&hwc) == FXTRUE);
    CHECK(hwc.num_sst == 1 && hwc.SSTs[0].type == 0x55555555);
    CHECK(grSstQueryHardware(&hwc) == FXFALSE && hwc.num_sst == 0 && hwc.SSTs[0].voodoo.fbRam == 0);
    CHECK(grSstQueryBoards(NULL) == FXFALSE);
    grSstVidMode(0, &timing); /* accepted; the table's timings are used */
    CHECK(grSstScreenWidth() == 0 && grSstIsBusy() == FXFALSE);
    CHECK(guEndianSwapBytes(0x1234) == 0x3412 && guEndianSwapBytes(0xff00) == 0x00ff);
    CHECK(guEndianSwapWords(0x12345678u) == 0x56781234u);

    /* 3dfx's RLE16 loop drops one pixel of count per run: 7 7 7 9 is one run of three
     * 7s; from 0x8000 up a colour is sign-extended over the length. */
    FxU16 img[4] = { 7, 7, 7, 9 }, img2[2] = { 0x8000, 0x8000 };
    FxU32 rle[4] = { 0, 0, 0, 0 };
    CHECK(guEncodeRLE16(NULL, img, 4, 1) == 4);
    CHECK(guEncodeRLE16(rle, img, 2, 2) == 4 && rle[0] == 0x00030007u && rle[1] == 0);
    CHECK(guEncodeRLE16(rle, img2, 2, 1) == 4 && rle[0] == 0xffff8000u);
    CHECK(guEncodeRLE16(rle, NULL, 2, 1) == 0);

    grGlideInit();
    grErrorSetCallback(on_error);
    memset(&hwc, 0x55, sizeof hwc);
    CHECK(grSstQueryHardware(&hwc) == FXTRUE && hwc.num_sst == 1);
    CHECK(hwc.SSTs[0].type == 0 && hwc.SSTs[0].voodoo.sliDetect == FXFALSE);
    CHECK(hwc.SSTs[0].voodoo.fbRam == 4 && hwc.SSTs[0].voodoo.nTexelfx == 1);
    CHECK(hwc.SSTs[0].voodoo.fbiRev == (int)stat(GR_REVISION_FB));
    CHECK(hwc.SSTs[0].voodoo.tmuConfig[0].tmuRam == 4);
    CHECK(hwc.SSTs[0].voodoo.tmuConfig[0].tmuRev == (int)stat(GR_REVISION_TMU));
    CHECK(hwc.SSTs[0].voodoo.tmuConfig[1].tmuRam == 0 && hwc.SSTs[1].type == 0);

    grSstSelect(0);
    grSstVidMode(0, &timing);
    CHECK(grSstWinOpen(0, GR_RESOLUTION_640x480, GR_REFRESH_60Hz, GR_COLORFORMAT_ARGB,
                       GR_ORIGIN_UPPER_LEFT, 2, 1));
    CHECK(grSstScreenWidth() == 640 && grSstScreenHeight() == 480);
    grSstVidMode(4, &timing);
    CHECK(errors == 1 && strncmp(last, "grSstVidMode:", 13) == 0);

    /* The timing model's retrace: off, then on within a frame of status reads
     * (1/60 s at 4.5 graphics clocks a read), then off again. vRetrace reads the
     * scan line, below the 525 lines of the 640x480 mode. */
    CHECK(grSstVideoLine() < 525);
    long reads = 0;
    while (grSstVRetraceOn() && reads < 1000000)
        reads++;
    while (!grSstVRetraceOn() && reads < 1000000)
        reads++;
    FxBool on = grSstVRetraceOn();
    while (grSstVRetraceOn() && reads < 1000000)
        reads++;
    CHECK(on == FXTRUE && reads < 1000000);
    grCheckForRoom(64);
    grSetNumPendingBuffers(2);
    CHECK(grGetProcAddress("grSetNumPendingBuffers") != NULL);
    grGlideShamelessPlug(FXTRUE);
    grGlideShamelessPlug(FXFALSE);
    CHECK(errors == 1);

    setenv("VOODOO_EXTRAS_TEST", "yes", 1);
    char *s = grGetRegistryOrEnvironmentString("VOODOO_EXTRAS_TEST");
    CHECK(s != NULL && strcmp(s, "yes") == 0);
    CHECK(grGetRegistryOrEnvironmentString("VOODOO_EXTRAS_NOT_SET") == NULL);
    CHECK(grGetRegistryOrEnvironmentString(NULL) == NULL);

    grVertexLayout(GR_PARAM_XY, 0, GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_RGB, 8, GR_PARAM_ENABLE);
    grVertexLayout(GR_PARAM_A, 20, GR_PARAM_ENABLE);
    grBufferClear(0, 0, 0);

    /* Iterated red; the counters see the triangle. */
    guColorCombineFunction(GR_COLORCOMBINE_ITRGB);
    triangle(255, 0, 0, 255);
    CHECK(pixel() == 0xf800);
    GrSstPerfStats_t ps;
    memset(&ps, 0xff, sizeof ps);
    grSstPerfStats(&ps);
    CHECK(ps.pixelsOut > 0 && ps.pixelsOut == stat(GR_STATS_PIXELS_OUT));
    CHECK(ps.pixelsIn > 0 && ps.pixelsIn == stat(GR_STATS_PIXELS_IN));
    CHECK(ps.chromaFail == 0 && ps.zFuncFail == 0 && ps.aFuncFail == 0);
    FxU32 in = 99, drawn = 99;
    grTriStats(&in, &drawn);
    CHECK(in == 1 && drawn == 1);
    grTriStats(NULL, NULL);
    grSstPerfStats(NULL);
    CHECK(errors == 2 && strcmp(last, "grSstPerfStats: NULL pointer") == 0);
    /* grSstIsBusy writes nopCMD = 1, which clears the pixel counters; it answers
     * busy until the board has drawn the triangle (the timing model). */
    long spins = 0;
    while (grSstIsBusy() && spins < 10000000)
        spins++;
    CHECK(spins < 10000000);
    grSstPerfStats(&ps);
    CHECK(ps.pixelsIn == 0 && ps.pixelsOut == 0);

    /* Constant colour; delta-0 mode (start colour 0, no slopes, no iterated RGB);
     * then iterated again; constant one. */
    grConstantColorValue(0xff0000ffu);
    guColorCombineFunction(GR_COLORCOMBINE_CCRGB);
    triangle(255, 0, 0, 255);
    CHECK(pixel() == 0x001f);
    guColorCombineFunction(GR_COLORCOMBINE_ITRGB_DELTA0);
    triangle(255, 0, 0, 255);
    CHECK(pixel() == 0x0000);
    guColorCombineFunction(GR_COLORCOMBINE_ITRGB);
    triangle(0, 255, 0, 255);
    CHECK(pixel() == 0x07e0);
    guColorCombineFunction(GR_COLORCOMBINE_ONE);
    triangle(255, 0, 0, 255);
    CHECK(pixel() == 0xffff);
    guColorCombineFunction(99);
    CHECK(errors == 3 && strncmp(last, "guColorCombineFunction:", 23) == 0);

    /* Alpha from the constant (0: nothing blended in), then from the vertices. */
    guColorCombineFunction(GR_COLORCOMBINE_ITRGB);
    grBufferClear(0, 0, 0);
    grAlphaBlendFunction(GR_BLEND_SRC_ALPHA, GR_BLEND_ONE_MINUS_SRC_ALPHA, GR_BLEND_ONE, GR_BLEND_ZERO);
    grConstantColorValue(0x00000000u);
    guAlphaSource(GR_ALPHASOURCE_CC_ALPHA);
    triangle(255, 0, 0, 255);
    CHECK(pixel() == 0x0000);
    guAlphaSource(GR_ALPHASOURCE_ITERATED_ALPHA);
    triangle(255, 0, 0, 255);
    CHECK(pixel() == 0xf800);
    guAlphaSource(7);
    CHECK(errors == 4 && strcmp(last, "guAlphaSource: unknown alpha source mode") == 0);
    grAlphaBlendFunction(GR_BLEND_ONE, GR_BLEND_ZERO, GR_BLEND_ONE, GR_BLEND_ZERO);

    /* The chroma key through the underscore names. The key compares the combine's
     * "other" colour, here the constant (green): the triangle is keyed out, until a
     * mode other than GR_CHROMAKEY_ENABLE turns the key off. */
    grBufferClear(0, 0, 0);
    grConstantColorValue(0xff00ff00u);
    _grChromaRangeExt(0x0000ff00u, 0x0000ff00u, 0);
    _grChromaModeExt(GR_CHROMAKEY_ENABLE);
    triangle(255, 0, 0, 255);
    CHECK(pixel() == 0x0000);
    grSstPerfStats(&ps);
    CHECK(ps.chromaFail > 0);
    _grChromaModeExt(2);
    triangle(255, 0, 0, 255);
    CHECK(pixel() == 0xf800);
    CHECK(errors == 4);

    /* A raw register write; an unknown chip or register is refused. */
    grSstConfigPipeline(GR_TMU0, 0x120 / 4, 1);
    CHECK(errors == 4);
    grSstConfigPipeline(7, 0, 0);
    CHECK(errors == 5 && strcmp(last, "grSstConfigPipeline: invalid chip ID specified") == 0);
    grSstConfigPipeline(GR_TMU0, 0x100, 0);
    CHECK(errors == 6 && strcmp(last, "grSstConfigPipeline: register out of range") == 0);

    FxU16 *mip = guTexCreateColorMipMap();
    CHECK(mip != NULL);
    CHECK(mip[0] == 0xf800 && mip[65535] == 0xf800 && mip[65536] == 0x07e0);
    CHECK(mip[65536 + 16384] == 0x001f && mip[65536 + 16384 + 4096] == 0xffff);
    CHECK(mip[65536 + 16384 + 4096 + 1024] == 0x0000);
    CHECK(mip[87296] == 0xf800 && mip[87375] == 0x07e0 && mip[87376] == 0x001f);
    CHECK(mip[87379] == 0x001f && mip[87380] == 0xffff);
    free(mip);

    grSstWinClose(0);
    grGlideShutdown();
    printf("ok\n");
    return 0;
}

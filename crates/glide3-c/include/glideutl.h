/* glideutl.h -- Glide 3 utility functions (voodoo-rs libglide3). */
#ifndef VOODOO_RS_GLIDEUTL_H
#define VOODOO_RS_GLIDEUTL_H

#include "glide.h"

#ifdef __cplusplus
extern "C" {
#endif

/* .3DF texture files and texture tables. */
typedef struct {
    FxU32 width, height;
    int small_lod, large_lod;
    GrAspectRatio_t aspect_ratio;
    GrTextureFormat_t format;
} Gu3dfHeader;

typedef struct {
    FxU8 yRGB[16];
    FxI16 iRGB[4][3];
    FxI16 qRGB[4][3];
    FxU32 packed_data[12];
} GuNccTable;

typedef struct {
    FxU32 data[256];
} GuTexPalette;

typedef union {
    GuNccTable nccTable;
    GuTexPalette palette;
} GuTexTable;

typedef struct {
    Gu3dfHeader header;
    GuTexTable table;
    void *data;
    FxU32 mem_required; /* bytes of the mipmap */
} Gu3dfInfo;

FX_ENTRY FxBool FX_CALL gu3dfGetInfo(const char *filename, Gu3dfInfo *info);
FX_ENTRY FxBool FX_CALL gu3dfLoad(const char *filename, Gu3dfInfo *data);

/* Entries in a Glide fog table. */
#define GR_FOG_TABLE_SIZE 64

FX_ENTRY void FX_CALL guGammaCorrectionRGB(FxFloat red, FxFloat green, FxFloat blue);
FX_ENTRY float FX_CALL guFogTableIndexToW(int i);
FX_ENTRY void FX_CALL guFogGenerateExp(GrFog_t *fogtable, float density);
FX_ENTRY void FX_CALL guFogGenerateExp2(GrFog_t *fogtable, float density);
FX_ENTRY void FX_CALL guFogGenerateLinear(GrFog_t *fogtable, float nearZ, float farZ);

#ifdef __cplusplus
}
#endif

#endif

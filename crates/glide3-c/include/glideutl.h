/* glideutl.h -- Glide 3 utility functions (voodoo-rs libglide3). */
#ifndef VOODOO_RS_GLIDEUTL_H
#define VOODOO_RS_GLIDEUTL_H

#include "glide.h"

#ifdef __cplusplus
extern "C" {
#endif

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

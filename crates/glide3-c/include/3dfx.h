/* 3dfx.h -- basic fixed-size types used by the Glide 3 headers.
 * Part of voodoo-rs (libglide3 for the emulated SST-1). Written for this project;
 * the type names and sizes are the Glide 3 SDK's interface. */
#ifndef VOODOO_RS_3DFX_H
#define VOODOO_RS_3DFX_H

#include <stdint.h>

typedef uint8_t  FxU8;
typedef int8_t   FxI8;
typedef uint16_t FxU16;
typedef int16_t  FxI16;
typedef uint32_t FxU32;
typedef int32_t  FxI32;
typedef int      FxBool;
typedef float    FxFloat;
typedef double   FxDouble;

#define FXTRUE   1
#define FXFALSE  0
#define FXBIT(i) (1L << (i))

#endif

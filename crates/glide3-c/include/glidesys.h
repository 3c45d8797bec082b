/* glidesys.h -- platform selection for the Glide 3 headers (voodoo-rs).
 * libglide3 targets the emulated SST-1 (Voodoo Graphics) on 64-bit hosts; calls use
 * the platform's default C calling convention. */
#ifndef VOODOO_RS_GLIDESYS_H
#define VOODOO_RS_GLIDESYS_H

#define GLIDE_HW_SST1   0x1
#define GLIDE_PLATFORM  GLIDE_HW_SST1
#define GLIDE_NUM_TMU   3

#ifndef FX_ENTRY
#define FX_ENTRY extern
#endif
#ifndef FX_CALL
#define FX_CALL
#endif

#endif

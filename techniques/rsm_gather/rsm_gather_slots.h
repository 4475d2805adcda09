// gibench - the GL slots of technique `rsm_gather` (rsm_gather.frag), for C and GLSL alike: only
// #define lines and // comments. Full screen over the G-buffer (GIB_UNIT_GBUF_*), the VPLs on
// GIB_VPL_SSBO_VPLS (techniques/common/common_slots.h).
#ifndef RSM_GATHER_SLOTS_H
#define RSM_GATHER_SLOTS_H

#include "harness/gl/bindings.h"

#define RSM_GATHER_LOC_VPLS 2         // int: VPLs gathered
#define RSM_GATHER_LOC_EPS 3          // float: the clamp distance

#endif

// gibench - the GL slots of technique `ldm_ao` (ldm_ao.frag; ldm_env draws the same shader with
// LDM_SKY), for C and GLSL alike: only #define lines and // comments. Full screen over the
// G-buffer (GIB_UNIT_GBUF_*), the LDM page bound by ldm_bind_page (GIB_SSBO_LDM_*, ldm_slots.h).
#ifndef LDM_AO_SLOTS_H
#define LDM_AO_SLOTS_H

#include "harness/gl/bindings.h"

#define LDM_AO_LOC_FIRST 5            // int: the bound page's first LDM
#define LDM_AO_LOC_COUNT 6            // int: its LDMs
#define LDM_AO_LOC_WEIGHT 7           // float: 2 / N
#define LDM_AO_LOC_DMAX 8             // float: +inf unbounded
#define LDM_AO_LOC_OBSCURANCE 9       // int
#define LDM_AO_LOC_OFFSET 10          // float: texels
#define LDM_AO_LOC_SKY 11             // vec3: LDM_SKY only

#endif

// gibench - the GL slots of the layered depth maps (techniques/ldm/), for C and GLSL alike: only
// #define lines and // comments. The LDMs' buffers are shared by the LDM techniques (bindings.h's
// family range): every technique that traces them binds a page with ldm_bind_page.
#ifndef LDM_SLOTS_H
#define LDM_SLOTS_H

#include "harness/gl/bindings.h"

// The LDMs' shared buffers, in bindings.h's family range (3..7).
#define GIB_SSBO_LDM_INFO (GIB_SSBO_FAMILY_FIRST + 0)     // directions and views
#define GIB_SSBO_LDM_HEADS (GIB_SSBO_FAMILY_FIRST + 1)    // per-pixel list heads of the bound page
#define GIB_SSBO_LDM_NODES (GIB_SSBO_FAMILY_FIRST + 2)    // list nodes of the bound page
#define GIB_SSBO_LDM_STATUS (GIB_SSBO_FAMILY_FIRST + 3)   // overflow and contention flags
#define GIB_SSBO_LDM_COUNTERS (GIB_SSBO_FAMILY_FIRST + 4) // fragment counters

// Counting and building (ldm_count.frag, ldm_build.vert/.frag): instanced scene draws, one
// instance an LDM, with GIB_LOC_MATERIAL and the alpha mask on GIB_UNIT_ALPHA_TEX.
#define LDM_LOC_FIRST_LDM 5           // int: the LDM of instance 0

// The probe (ldm_probe.comp): rays against the LDMs, page by page.
#define LDM_PROBE_SSBO_RAYS (GIB_SSBO_OWN_FIRST + 0) // vec4[]: origin, w the LDM and sign
#define LDM_PROBE_SSBO_HITS (GIB_SSBO_OWN_FIRST + 1) // float[]: distances
#define LDM_PROBE_LOC_COUNT 0         // int: rays
#define LDM_PROBE_LOC_FIRST 1         // int: the bound page's first LDM
#define LDM_PROBE_LOC_PAGE_COUNT 2    // int: its LDMs
#define LDM_PROBE_LOC_EPS 3           // float

#endif

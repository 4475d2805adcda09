// gibench - the GL slots of technique `ldm_indirect` (photon_trace.comp, splat.*), for C and GLSL
// alike: only #define lines and // comments. The tracing reads the light views (GIB_UNIT_LV_*),
// the G-buffer (GIB_UNIT_GBUF_*) and the bound LDM page (GIB_SSBO_LDM_*, ldm_slots.h).
#ifndef LDM_INDIRECT_SLOTS_H
#define LDM_INDIRECT_SLOTS_H

#include "harness/gl/bindings.h"

#define LDMI_SSBO_PHOTONS (GIB_SSBO_OWN_FIRST + 0) // struct Photon[] (photon.glsl)
#define LDMI_SSBO_COMMAND (GIB_SSBO_OWN_FIRST + 1) // the splats' indirect draw and the overflow
#define LDMI_SSBO_AUDIT (GIB_SSBO_OWN_FIRST + 2)   // the flux audit (AUDIT builds)

// Photon tracing (photon_trace.comp).
#define LDMI_TRACE_LOC_LIGHT 0         // int
#define LDMI_TRACE_LOC_FACE 1          // int: the light-view layer traced
#define LDMI_TRACE_LOC_RES 4           // int: light-view photon resolution
#define LDMI_TRACE_LOC_FIRST 5         // int: the bound page's first LDM
#define LDMI_TRACE_LOC_COUNT 6         // int: its LDMs
#define LDMI_TRACE_LOC_SPLIT_WEIGHT 7  // float: 2 / N
#define LDMI_TRACE_LOC_VIEW_PROJ 8     // mat4: the camera's, maps p - its origin
#define LDMI_TRACE_LOC_SIZE 9          // ivec2: the camera's image
#define LDMI_TRACE_LOC_OFFSET 10       // float: texels
#define LDMI_TRACE_LOC_CAPACITY 11     // uint: photons
#define LDMI_TRACE_LOC_ORIGIN 12       // vec3: the camera's origin
#define LDMI_TRACE_LOC_FIRST_PAGE 13   // int: 1 for the first page (AUDIT builds)

// Splatting (splat.vert/.geom/.frag): points expanded to quads with GIB_LOC_VIEW_PROJ and
// GIB_LOC_ORIGIN, shaded over the G-buffer (GIB_UNIT_GBUF_*).
#define LDMI_SPLAT_LOC_TOPO_BIAS 2     // float
#define LDMI_SPLAT_LOC_EYE 3           // vec3 (AUDIT builds)
#define LDMI_SPLAT_LOC_TAN_SIZE 4      // vec4: xy tan of the half-angles, zw the image size (AUDIT)

#endif

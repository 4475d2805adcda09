// gibench - the GL slots of technique `ispm_caustics` (its .comp/.vert/.geom/.frag and
// caustics.glsl, list_lookup.glsl), for C and GLSL alike: only #define lines and // comments.
// Every storage buffer has one binding in all of the technique's passes. Passes that draw the
// scene or read the camera's lists take GIB_LOC_MATERIAL, GIB_LOC_VIEW_PROJ and GIB_LOC_ORIGIN
// (harness/gl/bindings.h); the emission reads the light views (GIB_UNIT_LV_*).
#ifndef ISPM_CAUSTICS_SLOTS_H
#define ISPM_CAUSTICS_SLOTS_H

#include "harness/gl/bindings.h"

// Storage buffers.
#define ISPM_SSBO_HEADS (GIB_SSBO_OWN_FIRST + 0)     // the camera's lists: a head per pixel
#define ISPM_SSBO_NODES (GIB_SSBO_OWN_FIRST + 1)     //   struct Node[] (caustics.glsl)
#define ISPM_SSBO_PHOTONS (GIB_SSBO_OWN_FIRST + 2)   // struct Photon[] (caustics.glsl)
#define ISPM_SSBO_STATUS (GIB_SSBO_OWN_FIRST + 3)    // list count, overflows, longest list
#define ISPM_SSBO_COUNTS (GIB_SSBO_OWN_FIRST + 4)    // the lists' lengths
#define ISPM_SSBO_FIRST_HIT (GIB_SSBO_OWN_FIRST + 5) // a photon's nearest hit, atomicMin
#define ISPM_SSBO_COMMAND (GIB_SSBO_OWN_FIRST + 6)   // the lines' and points' indirect draws
#define ISPM_SSBO_RANDOM (GIB_SSBO_OWN_FIRST + 7)    // vec4[]: the random numbers of create

// The camera's lists (list_lookup.glsl, list_build.frag, peel.frag, layers.comp).
#define ISPM_LOC_FORWARD 7            // vec3: the camera's forward axis
#define ISPM_LOC_RES 8                // int: ray_res, the lists' side
#define ISPM_LOC_RIGHT_TAN 10         // vec3: camera right / P[0]
#define ISPM_LOC_UP_TAN 11            // vec3: camera up / P[5]
#define ISPM_LIST_LOC_CAPACITY 9      // uint: nodes in the pool (list_build.frag)
#define ISPM_PEEL_LOC_LAYER 8         // int: the layer peeled (peel.frag)
#define ISPM_UNIT_PREV_LAYER (GIB_UNIT_OWN_FIRST + 0) // peel.frag: the layer peeled before
#define ISPM_UNIT_LAYER_FIRST (GIB_UNIT_OWN_FIRST + 0) // layers.comp: the 4 layers
#define ISPM_LAYERS 4

// The specular mask's mips (mask_mip.comp).
#define ISPM_MIP_IMAGE_DST (GIB_IMAGE_OWN_FIRST + 0) // r32f 2D array, level l
#define ISPM_MIP_IMAGE_SRC (GIB_IMAGE_OWN_FIRST + 1) //   level l - 1
#define ISPM_MIP_LOC_LEVEL 2          // int
#define ISPM_MIP_LOC_RES 3            // int: the side of the level written

// Emission (emit.comp).
#define ISPM_EMIT_UNIT_MASK (GIB_UNIT_OWN_FIRST + 0) // the specular mask with its mips
#define ISPM_EMIT_LOC_LEVEL 2         // int: the mask level emitted from
#define ISPM_EMIT_LOC_RES 3           // int: its side
#define ISPM_EMIT_LOC_CAPACITY 4      // uint: photons
#define ISPM_EMIT_LOC_EYE 5           // vec3
#define ISPM_EMIT_LOC_FORWARD 7       // vec3
#define ISPM_EMIT_LOC_PIXEL_SCALE 8   // float: a ray_res pixel's side at depth 1
#define ISPM_EMIT_LOC_TMIN_FLOOR 9    // float: scene units

// Tracing (trace.vert/.frag) and the hits' resolve (resolve.comp).
#define ISPM_TRACE_LOC_TMAX 12        // float: a photon ray's length
#define ISPM_TRACE_LOC_CAPACITY 13    // uint: photons
#define ISPM_TRACE_LOC_SLACK 14       // float: pixels (trace.frag)
#define ISPM_TRACE_LOC_DEPTH 16       // float: pixel footprints (trace.frag)
#define ISPM_RESOLVE_LOC_SPLAT_SCALE 14 // float: C of h = C sqrt(area)
#define ISPM_RESOLVE_LOC_HMAX 15      // float: the largest splat radius

// Splatting (splat.vert/.geom/.frag) over the G-buffer's position and normal (GIB_UNIT_GBUF_*).
#define ISPM_SPLAT_LOC_DELTA 2        // float: the Gaussian kernel's delta

// Shading and upsampling (shade.frag), full screen over the G-buffer (GIB_UNIT_GBUF_*).
#define ISPM_SHADE_UNIT_IRRADIANCE (GIB_UNIT_OWN_FIRST + 0) // the splats
#define ISPM_SHADE_UNIT_LOW_POSITION (GIB_UNIT_OWN_FIRST + 1) // the splats' G-buffer
#define ISPM_SHADE_UNIT_LOW_NORMAL (GIB_UNIT_OWN_FIRST + 2)
#define ISPM_SHADE_LOC_DIVISOR 2      // int: splat_res_divisor
#define ISPM_SHADE_LOC_EYE 3          // vec3

// The Phong lobe sampler's probe (phong_probe.comp, tests/ispm_caustics/test_caustics_probes.c).
#define ISPM_PROBE_SSBO_IN (GIB_SSBO_OWN_FIRST + 0)  // vec4[]: xy xi1 xi2
#define ISPM_PROBE_SSBO_OUT (GIB_SSBO_OWN_FIRST + 1) // vec4[]: xyz d, w accepted
#define ISPM_PROBE_LOC_R 2            // vec3: the mirror direction
#define ISPM_PROBE_LOC_NORMAL 3       // vec3
#define ISPM_PROBE_LOC_N 4            // float: the Phong exponent
#define ISPM_PROBE_LOC_COUNT 5        // int

#endif

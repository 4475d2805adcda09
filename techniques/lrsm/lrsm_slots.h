// gibench - the GL slots of technique `lrsm` (lrsm_build.comp, lrsm_cone.frag, lrsm_probe.comp and
// the files they include), for C and GLSL alike: only #define lines and // comments. The cone
// pass reads the G-buffer (GIB_UNIT_GBUF_*), the light views (GIB_UNIT_LV_*) and the occlusion
// voxels (GIB_UNIT_VOXELS, GIB_LOC_VOXEL_*: harness/gl/bindings.h).
#ifndef LRSM_SLOTS_H
#define LRSM_SLOTS_H

#include "harness/gl/bindings.h"

// The layers (lrsm_common.glsl, lrsm_sample.glsl): every pass that builds or samples them.
#define LRSM_SSBO_TABLE (GIB_SSBO_OWN_FIRST + 0)       // vec4 per light: z0, z1, window
#define LRSM_UNIT_RADIANCE (GIB_UNIT_OWN_FIRST + 0)    // 2D arrays with mips, a layer a face
#define LRSM_UNIT_NORMAL (GIB_UNIT_OWN_FIRST + 1)      //   x depth and normal parts
#define LRSM_UNIT_DEPTH (GIB_UNIT_OWN_FIRST + 2)
#define LRSM_LOC_DEPTH_PARTS (GIB_LOC_OWN_FIRST + 0)   // int: D
#define LRSM_LOC_NORMAL_PARTS (GIB_LOC_OWN_FIRST + 1)  // int: N

// Construction (lrsm_build.comp).
#define LRSM_IMAGE_RADIANCE (GIB_IMAGE_OWN_FIRST + 0)  // the layers, level 0 written
#define LRSM_IMAGE_NORMAL (GIB_IMAGE_OWN_FIRST + 1)
#define LRSM_IMAGE_DEPTH (GIB_IMAGE_OWN_FIRST + 2)
#define LRSM_IMAGES 3
#define LRSM_BUILD_LOC_FACE (GIB_LOC_OWN_FIRST + 2)    // int: the light-view face
#define LRSM_BUILD_LOC_LIGHT (GIB_LOC_OWN_FIRST + 3)   // int: its light
#define LRSM_BUILD_LOC_HALF (GIB_LOC_OWN_FIRST + 4)    // int: a layer's side
#define LRSM_BUILD_LOC_JACOBIAN (GIB_LOC_OWN_FIRST + 5) // int: 1 texels weighted by area

// Sampling (lrsm_sample.glsl): the cone pass and the probe.
#define LRSM_LOC_MIP_CLAMP 7          // float
#define LRSM_LOC_LIGHTS 8             // int: lights in the table
#define LRSM_LOC_BACKFACE 14          // int: 0 Eq. 8's cosine, 1 Eq. 8 as a test only
#define LRSM_LOC_SEAMS 15             // int: 1 every face the footprint overlaps
#define LRSM_LOC_VISIBILITY 17        // int: 1 Eq. 12's window widened by 1 / <n.l>

// The cone pass (lrsm_cone.frag), full screen.
#define LRSM_CONE_LOC_EYE 9           // vec3
#define LRSM_CONE_LOC_APERTURE 10     // float: radians, full angle
#define LRSM_CONE_LOC_START_OFFSET 11 // float: voxels
#define LRSM_CONE_LOC_STEP_FACTOR 12  // float
#define LRSM_CONE_LOC_MAX_DISTANCE 13 // float: grid sides
#define LRSM_CONE_LOC_COVERAGE 16     // int: 1 L normalised by the lit coverage
#define LRSM_CONE_LOC_HITS 18         // int: 1 the share of rays meeting the lit planes

// The probe (lrsm_probe.comp): points sampled as the cone pass samples.
#define LRSM_PROBE_SSBO_IN (GIB_SSBO_OWN_FIRST + 1)    // the points and their footprints
#define LRSM_PROBE_SSBO_OUT (GIB_SSBO_OWN_FIRST + 2)   //   and what they sample
#define LRSM_PROBE_LOC_COUNT 9        // int: points

// The cone probe (lrsm_cone_probe.comp, tests): the occlusion of given cones, with the cones'
// start offset, step and length (LRSM_CONE_LOC_*) and the occlusion voxels (GIB_UNIT_VOXELS).
#define LRSM_CONE_PROBE_SSBO_IN (GIB_SSBO_OWN_FIRST + 1)   // per cone: (x, aperture), (n), (dir)
#define LRSM_CONE_PROBE_SSBO_OUT (GIB_SSBO_OWN_FIRST + 2)  //   and its occlusion
#define LRSM_CONE_PROBE_LOC_COUNT 9   // int: cones

#endif

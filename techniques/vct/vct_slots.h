// gibench - the GL slots of technique `vct` (vct_*.vert/.frag/.comp, vct_trace.glsl), for C and
// GLSL alike: only #define lines and // comments. The radiance volume takes the occlusion voxels'
// slots (GIB_UNIT_VOXELS and GIB_LOC_VOXEL_ORIGIN/SIZE/RES, harness/gl/bindings.h) so
// that the cones read it with common/voxel_cone.glsl.
#ifndef VCT_SLOTS_H
#define VCT_SLOTS_H

#include "harness/gl/bindings.h"

// Injection (vct_inject.vert/.frag): light-view texels (GIB_UNIT_LV_*) drawn as points.
#define VCT_INJECT_LOC_LIGHT 2        // int
#define VCT_INJECT_LOC_LV_RES 3       // int: the light views' side
#define VCT_INJECT_LOC_FACE 4         // int: the light-view face

// Resolve (vct_resolve.comp): sums to averages, in place, and the fill from the light views
// (GIB_UNIT_LV_*, bound for the injection).
#define VCT_RESOLVE_UNIT_OCCUPANCY (GIB_UNIT_OWN_FIRST + 0) // the occlusion voxels
#define VCT_RESOLVE_IMAGE_RADIANCE (GIB_IMAGE_OWN_FIRST + 0)
#define VCT_RESOLVE_IMAGE_NORMAL (GIB_IMAGE_OWN_FIRST + 1)
#define VCT_RESOLVE_LOC_LIGHTS 2      // int: lights whose views fill occupied, unlit voxels
#define VCT_RESOLVE_LOC_LV_RES 3      // int: the light views' side

// Several lights (vct_accumulate.comp): one light's sums, injected into the normal volume, added to
// the radiance volume as its average.
#define VCT_ACCUMULATE_IMAGE_SCRATCH (GIB_IMAGE_OWN_FIRST + 0)
#define VCT_ACCUMULATE_IMAGE_RADIANCE (GIB_IMAGE_OWN_FIRST + 1)

// The anisotropic mips (vct_aniso.comp): level 0 from the base volume (FROM_BASE), then each
// level from the one below; the six directions' textures (+x -x +y -y +z -z, vct.h) are read
// and written as arrays.
#define VCT_ANISO_LOC_LEVEL 2         // int: the level written
#define VCT_ANISO_UNIT_RADIANCE (GIB_UNIT_OWN_FIRST + 0)    // FROM_BASE: the base volume
#define VCT_ANISO_UNIT_NORMAL (GIB_UNIT_OWN_FIRST + 1)
#define VCT_ANISO_UNIT_SRC_FIRST (GIB_UNIT_OWN_FIRST + 0)   // the six directions, level - 1
#define VCT_ANISO_IMAGE_DST_FIRST (GIB_IMAGE_OWN_FIRST + 0) // the six directions, level

#define VCT_LOBES_UNIT_SRC_FIRST (GIB_UNIT_OWN_FIRST + 0)   // the lobes (x, y, z), level - 1
#define VCT_LOBES_IMAGE_DST_FIRST (GIB_IMAGE_OWN_FIRST + 0) // the lobes (x, y, z), level

// The cones (vct_trace.glsl): the shading pass and the probe.
#define VCT_UNIT_ANISO_FIRST (GIB_UNIT_OWN_FIRST + 0)       // the six directions' mips
#define VCT_UNIT_LOBE_FIRST (GIB_UNIT_OWN_FIRST + 6)        // the emission lobes' mips (x, y, z)
#define VCT_LOC_FRONT_FACES 12        // int: 1 a sample's light limited to faces toward the apex
#define VCT_LOC_STEP_FACTOR 7         // float
#define VCT_LOC_START_OFFSET 8        // float: voxels, along the surface normal
#define VCT_LOC_LEVEL_BIAS 9          // float: levels finer than log2(d)
#define VCT_LOC_CLEARANCE 11          // int: 0 a sample shrunk to its height, 1 lifted

// Shading (vct_shade.frag), full screen over the G-buffer (GIB_UNIT_GBUF_*).
#define VCT_SHADE_LOC_EYE 2           // vec3
#define VCT_SHADE_LOC_LIGHT_COUNT 3   // int
#define VCT_SHADE_LOC_TAN_HALF 4      // float: tan(aperture / 2)
#define VCT_SHADE_LOC_MAX_DIST 5      // float: world units

// The probe (vct_probe.comp): cones from given points.
#define VCT_PROBE_SSBO_IN (GIB_SSBO_OWN_FIRST + 1)   // per cone: (p, tan_half), (n, max), (D, 0)
#define VCT_PROBE_SSBO_OUT (GIB_SSBO_OWN_FIRST + 2)  //   and what it reads
#define VCT_PROBE_LOC_COUNT 10        // int: cones

#endif

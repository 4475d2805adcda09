// gibench - the GL slots of technique `multires_ir` (multires_*.comp/.frag and
// multires_common.glsl), for C and GLSL alike: only #define lines and // comments. The passes
// read the G-buffer (GIB_UNIT_GBUF_*); the gathering reads the VPLs (GIB_VPL_SSBO_VPLS,
// techniques/common/common_slots.h).
#ifndef MULTIRES_IR_SLOTS_H
#define MULTIRES_IR_SLOTS_H

#include "harness/gl/bindings.h"

// Every pass (multires_common.glsl).
#define MULTIRES_LOC_SIZE 2                          // ivec2: W, H
#define MULTIRES_LOC_LEVELS 3                        // int
#define MULTIRES_LOC_DEPTH_THRESHOLD 4               // float: relative
#define MULTIRES_LOC_NORMAL_CHORD 5                  // float: 2 sin(theta / 2)
#define MULTIRES_LOC_LEVEL 6                         // int: the level written
#define MULTIRES_LOC_EYE 7                           // vec3
#define MULTIRES_UNIT_LO (GIB_UNIT_OWN_FIRST + 0)    // the min-max mips, flattened
#define MULTIRES_UNIT_HI (GIB_UNIT_OWN_FIRST + 1)
#define MULTIRES_UNIT_MEAN (GIB_UNIT_OWN_FIRST + 2)  // the regions' mean position
#define MULTIRES_UNIT_NSUM (GIB_UNIT_OWN_FIRST + 3)  //   and normal sum

// The mips (multires_mips.comp): the same four images, written level by level.
#define MULTIRES_IMAGE_LO (GIB_IMAGE_OWN_FIRST + 0)
#define MULTIRES_IMAGE_HI (GIB_IMAGE_OWN_FIRST + 1)
#define MULTIRES_IMAGE_MEAN (GIB_IMAGE_OWN_FIRST + 2)
#define MULTIRES_IMAGE_NSUM (GIB_IMAGE_OWN_FIRST + 3)

// Gathering (multires_gather.frag).
#define MULTIRES_UNIT_VALID (GIB_UNIT_OWN_FIRST + 5) // the valid regions' mask (stencil = 0)
#define MULTIRES_GATHER_LOC_VPLS 8                   // int: VPLs gathered
#define MULTIRES_GATHER_LOC_EPS 9                    // float: the clamp distance

// Upsampling and the resolve (multires_upsample.frag).
#define MULTIRES_UNIT_IRRADIANCE (GIB_UNIT_OWN_FIRST + 4) // every level's irradiance, flattened

#endif

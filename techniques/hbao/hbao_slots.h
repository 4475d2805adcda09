// gibench - the GL slots of technique `hbao` (hbao.frag, hbao_blur.frag), for C and GLSL alike:
// only #define lines and // comments (harness/gl/bindings.h has the shared slots). Both passes
// are full screen over the G-buffer (GIB_UNIT_GBUF_POSITION, GIB_UNIT_GBUF_NORMAL).
#ifndef HBAO_SLOTS_H
#define HBAO_SLOTS_H

#include "harness/gl/bindings.h"

// The horizon search (hbao.frag).
#define HBAO_LOC_EYE 0                // vec3
#define HBAO_LOC_RIGHT 1              // vec3: world direction of screen +x
#define HBAO_LOC_UP 2                 // vec3: world direction of screen +y
#define HBAO_LOC_FORWARD 3            // vec3: viewing direction
#define HBAO_LOC_FOCAL_PX 4           // float: pixels per unit of lateral offset / depth
#define HBAO_LOC_RADIUS 5             // float: R, world units
#define HBAO_LOC_DIRS 6               // int
#define HBAO_LOC_STEPS 7              // int
#define HBAO_LOC_BIAS 8               // float: tangent angle bias, radians
#define HBAO_LOC_FALLOFF 9            // int
#define HBAO_LOC_MAX_RADIUS_PX 10     // float: 0 no clamp
#define HBAO_LOC_FINAL 11             // int: 1 the output image, 0 the blur's input

// The separable blur (hbao_blur.frag).
#define HBAO_BLUR_UNIT_AO (GIB_UNIT_OWN_FIRST + 0) // the pass's input
#define HBAO_BLUR_LOC_EYE 0           // vec3
#define HBAO_BLUR_LOC_FORWARD 1       // vec3
#define HBAO_BLUR_LOC_AXIS 2          // ivec2: (1, 0) or (0, 1)
#define HBAO_BLUR_LOC_RADIUS 3        // int: taps each side
#define HBAO_BLUR_LOC_TOLERANCE 4     // float: plane distance scale, a fraction of depth
#define HBAO_BLUR_LOC_FINAL 5         // int: 1 the output image

#endif

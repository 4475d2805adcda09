// gibench - the GL slots of the shared passes under techniques/common/, one table for C and GLSL
// (both include this file: only #define lines and // comments, valid in both languages). The
// shared slots are in harness/gl/bindings.h; these are the passes' own uniform locations, storage
// buffers, texture units and image units, by the file that declares them. A literal number in a
// glUniform*, glBind* call or a layout(location|binding = ...) under techniques/ fails the test
// slots_named (tests/layers/check_slots.py).
#ifndef GIB_COMMON_SLOTS_H
#define GIB_COMMON_SLOTS_H

#include "harness/gl/bindings.h"

// G-buffer (gbuffer.vert, gbuffer.frag): a scene draw, with GIB_LOC_MATERIAL, GIB_LOC_VIEW_PROJ,
// GIB_LOC_ORIGIN and the material's textures on GIB_UNIT_ALBEDO_TEX, GIB_UNIT_ALPHA_TEX.
#define GIB_GBUFFER_LOC_EYE 2           // vec3: the camera's eye

// Direct lighting (direct_light.frag), full screen over the G-buffer.
#define GIB_DIRECT_LOC_EYE 2            // vec3
#define GIB_DIRECT_LOC_LIGHT_COUNT 3    // int

// Light views (light_view.frag): a scene draw per face.
#define GIB_LV_LOC_FORWARD 2            // vec3: the face's viewing direction
#define GIB_LV_LOC_KIND 3               // int: enum gib_lv_kind
#define GIB_LV_LOC_LIGHT 4              // int: the light's index
#define GIB_LV_LOC_TEXEL 5              // float: a texel's side

// Voxelization (voxelize.comp).
#define GIB_VOXELIZE_SSBO_POSITIONS (GIB_SSBO_OWN_FIRST + 0) // the GPU scene's positions
#define GIB_VOXELIZE_SSBO_INDICES (GIB_SSBO_OWN_FIRST + 1)   //   its triangles
#define GIB_VOXELIZE_SSBO_WORK (GIB_SSBO_OWN_FIRST + 2)      // the deferred triangles' list
#define GIB_VOXELIZE_SSBO_UVS (GIB_SSBO_OWN_FIRST + 3)       // the GPU scene's texture coords
#define GIB_VOXELIZE_UNIT_MASK_FIRST (GIB_UNIT_OWN_FIRST + 0) // 6 alpha masks, one pass's
#define GIB_VOXELIZE_MASKS 6
#define GIB_VOXELIZE_IMAGE_VOXELS (GIB_IMAGE_OWN_FIRST + 0)  // r8 3D, level 0 written
#define GIB_VOXELIZE_LOC_ORIGIN (GIB_LOC_OWN_FIRST + 0)      // vec3: the grid's lowest corner
#define GIB_VOXELIZE_LOC_INV_VOXEL (GIB_LOC_OWN_FIRST + 1)   // float: res / side
#define GIB_VOXELIZE_LOC_RES (GIB_LOC_OWN_FIRST + 2)         // int
#define GIB_VOXELIZE_LOC_TRIANGLES (GIB_LOC_OWN_FIRST + 3)   // uint: the scene's triangles
#define GIB_VOXELIZE_LOC_MASK_FIRST (GIB_LOC_OWN_FIRST + 7)  // int: the first mask, < 0 none

// The voxels' mips (voxel_mip.comp): one level from the one below.
#define GIB_VOXEL_MIP_IMAGE_DST (GIB_IMAGE_OWN_FIRST + 0)    // r8 3D, level l
#define GIB_VOXEL_MIP_IMAGE_SRC (GIB_IMAGE_OWN_FIRST + 1)    //        level l - 1

// VPLs: extraction (vpl_extract.comp), gathering (vpl_gather.glsl), the probe (vpl_probe.comp).
#define GIB_VPL_SSBO_VPLS (GIB_SSBO_OWN_FIRST + 0)           // struct Vpl[] (vpl_gather.glsl)
#define GIB_VPL_SSBO_CELLS (GIB_SSBO_OWN_FIRST + 1)          // extraction: the strata
#define GIB_VPL_SSBO_TEXELS (GIB_SSBO_OWN_FIRST + 2)         //   and their texels
#define GIB_VPL_LOC_RES 2                                    // int: the light views' side
#define GIB_VPL_LOC_COUNT 3                                  // int: VPLs extracted
#define GIB_VPL_PROBE_SSBO_IN (GIB_SSBO_OWN_FIRST + 1)       // the probe's points and normals
#define GIB_VPL_PROBE_SSBO_OUT (GIB_SSBO_OWN_FIRST + 2)      //   and their irradiance
#define GIB_VPL_PROBE_LOC_COUNT 2                            // int: points
#define GIB_VPL_PROBE_LOC_VPLS 3                             // int: VPLs gathered
#define GIB_VPL_PROBE_LOC_EPS 4                              // float: the clamp distance

#endif

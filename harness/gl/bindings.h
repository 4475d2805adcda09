// gibench — the GL binding points every pass shares, one table for C and GLSL (both include this
// file: only #define lines and // comments, valid in both languages). A shared slot has a name
// here; a pass's own resources use the ranges marked "own", named in its technique's slots header
// (techniques/<name>/<name>_slots.h; ARCHITECTURE.md, "GL bindings").
#ifndef GIB_BINDINGS_H
#define GIB_BINDINGS_H

// Shader storage buffers.
#define GIB_SSBO_MATERIALS 0      // struct Material[] (techniques/common/scene.glsl)
#define GIB_SSBO_LIGHTS 1         // struct Light[]
#define GIB_SSBO_LIGHT_VIEWS 2    // the light views' table (techniques/common/light_view.glsl)
#define GIB_SSBO_FAMILY_FIRST 3   // 3..7: buffers a family of techniques shares, named in the
                                  //   family's slots header
#define GIB_SSBO_OWN_FIRST 8      // 8..15: a pass's own buffers

// Texture units.
#define GIB_UNIT_ALBEDO_TEX 0     // during scene draws: the material's albedo texture
#define GIB_UNIT_ALPHA_TEX 1      //                     and its alpha mask
#define GIB_UNIT_GBUF_POSITION 0  // during full-screen passes: the G-buffer (gbuffer.h)
#define GIB_UNIT_GBUF_NORMAL 1
#define GIB_UNIT_GBUF_ALBEDO 2
#define GIB_UNIT_GBUF_SPECULAR 3
#define GIB_UNIT_LV_DEPTH 4       // the light views' depth (shadow lookups)
#define GIB_UNIT_LV_POSITION 5    // the light views' reflective shadow map
#define GIB_UNIT_LV_NORMAL 6
#define GIB_UNIT_LV_FLUX 7
#define GIB_UNIT_LV_SPECULAR 8
#define GIB_UNIT_LV_PACKED0 4     // packed views (GIB_LV_PACKED16): rgb reflected radiance, a depth
#define GIB_UNIT_LV_PACKED1 5     //   xyz normal facing the light, w <n.l>
#define GIB_UNIT_VOXELS 9         // occlusion voxels, R8 3D with mips (common/voxels.h)
#define GIB_UNIT_OWN_FIRST 10     // 10..18: a pass's own textures

// Uniform locations (per program). 0, 1 and 6 are taken in programs that draw the scene
// (gib_gpu_scene_draw, common/gbuffer.vert); full-screen and compute passes may use 0..19.
#define GIB_LOC_MATERIAL 0        // int: material of the range being drawn (gib_gpu_scene_draw)
#define GIB_LOC_VIEW_PROJ 1       // mat4: view-projection relative to GIB_LOC_ORIGIN
#define GIB_LOC_ORIGIN 6          // vec3: the view's origin (positions are sent as p - origin)
#define GIB_LOC_OWN_FIRST 2       // 2..5 and 7..19: a pass's own uniforms
#define GIB_LOC_LV_FIRST 20       // 20..23: the shadow lookup (common/shadow_lookup.glsl)
#define GIB_LOC_LV_PCF_RADIUS (GIB_LOC_LV_FIRST + 1)    //   int: (2r+1)^2 taps
#define GIB_LOC_LV_NORMAL_OFFSET (GIB_LOC_LV_FIRST + 2) //   float: along the normal, texels
#define GIB_LOC_VOXEL_FIRST 24    // 24..28: the occlusion voxels' grid (common/voxel_cone.glsl)
#define GIB_LOC_VOXEL_ORIGIN (GIB_LOC_VOXEL_FIRST + 0)  //   vec3: the grid's lowest corner
#define GIB_LOC_VOXEL_SIZE (GIB_LOC_VOXEL_FIRST + 1)    //   float: its side
#define GIB_LOC_VOXEL_RES (GIB_LOC_VOXEL_FIRST + 2)     //   int: voxels a side
#define GIB_LOC_VOXEL_DENSITY (GIB_LOC_VOXEL_FIRST + 3) //   int: occupancy to a step's opacity
#define GIB_LOC_VOXEL_CONE_ONLY (GIB_LOC_VOXEL_FIRST + 4) // int: the diffuse gather's one cone, < 0 all

// Image units (glBindImageTexture, layout(binding = N, format) image*): no shared ones.
#define GIB_IMAGE_OWN_FIRST 0     // 0..7: a pass's own images

#endif

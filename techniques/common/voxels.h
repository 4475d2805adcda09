/* gibench — occlusion voxels (LRSM, Sugihara et al. 2014, Sec. 3.2 and 5): the scene as binary
 * voxels, one byte each (R8 3D texture: 1 where a triangle touches the voxel, 0 elsewhere),
 * rebuilt every frame and mipmapped by averaging, so that a cone's sphere sample reads its
 * occlusion from the mip level of its diameter (Sec. 3.1; techniques/common/voxel_cone.glsl).
 *
 * Voxelisation is exact and conservative: a compute shader tests each voxel near each triangle
 * with the separating-axis triangle/box overlap test (Akenine-Moller 2001), so a voxel a triangle
 * touches is never missed, whatever the triangle's size or slope (Mesa has no conservative
 * rasterisation, and its geometry shaders run on one thread). Triangles with an alpha mask set
 * only the voxels where the mask is mostly solid, as the G-buffer and light views cut them out. */
#ifndef GIB_VOXELS_H
#define GIB_VOXELS_H

#include <stdint.h>

#include "harness/base/error.h"
#include "harness/gl/gpu_scene.h"
#include "harness/gl/ledger.h"
#include "harness/gl/timers.h"

#define GIB_VOXELS_MIN_RES 64
#define GIB_VOXELS_MAX_RES 512

typedef struct gib_voxels {
    int res;            /* voxels per side */
    float origin[3];    /* min corner of the cubic grid, scene frame (gib_gpu_scene.scene) */
    float size;         /* side of the cube in world units; one voxel is size / res */
    unsigned texture;   /* GL_TEXTURE_3D, GL_R8, full mip chain: 1/0 occupancy at level 0,
                           box-filtered averages above (voxel_mip.comp) */
    /* private */
    unsigned program[4]; /* voxelize.comp: per triangle / per large triangle; with alpha masks */
    unsigned program_mip; /* voxel_mip.comp */
    unsigned work;      /* SSBO (voxelize.comp): dispatch header, large triangles, masks */
    uint32_t triangle_count;
    int mask_count, *mask_tex; /* the scene's alpha masks: compact id - 1 -> scene texture */
} gib_voxels;

/* The texture's bytes (R8, res^3 with its full mip chain), exactly as the ledger counts them. */
uint64_t gib_voxels_bytes(int res);
/* Sets up res^3 voxels (64..512) over the scene's bounds: a cube centred on them, 1.5 + floor(res /
 * 64) voxels of margin on each side (voxels.c says why). Allocates "<label>.occupancy" (the texture, gib_voxels_bytes) and
 * "<label>_work.triangles" (the large-triangle list and each triangle's alpha mask, 8 bytes per
 * triangle + 16: scratch, a structure of its own so that "<label>" is the paper's) through the
 * ledger. */
int gib_voxels_create(gib_voxels *v, const gib_gpu_scene *scene, int res, const char *label,
                      gib_ledger *ledger, gib_error *err);
/* Clears, voxelises the scene's current positions (moving scenes: after gib_gpu_scene_set_time)
 * and generates the mips: one timed pass `pass` (timers may be NULL). */
void gib_voxels_build(gib_voxels *v, const gib_gpu_scene *scene, gib_timers *timers,
                      const char *pass);
/* The mip chain from level 0 (the last step of gib_voxels_build; on its own for tests and timing). */
void gib_voxels_mips(gib_voxels *v);
/* Binds the texture to GIB_UNIT_VOXELS and sets the grid uniforms of voxel_cone.glsl on the
 * CURRENT program (locations GIB_LOC_VOXEL_FIRST + 0..2). */
void gib_voxels_bind(const gib_voxels *v);
void gib_voxels_destroy(gib_voxels *v, gib_ledger *ledger);

#endif

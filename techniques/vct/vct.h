/* gibench technique `vct` — dense voxel cone tracing (Crassin et al. 2011) as the LRSM paper ran
 * it for its comparison (Sugihara et al. 2014, Sec. 6): a dense grid with radiance + occlusion
 * (RGBA16F) and normal (RGBA16F) per base voxel, injected from the light views, and anisotropic
 * mips of pre-integrated radiance and occlusion for each of the 6 axis directions.
 *
 * Known limits of the method as built (measured, see the tests): the coarse levels pre-integrate
 * whole cells, so a cone's own surface and walls behind the sample darken wide cones in closed
 * rooms (the paper: VCT's anisotropic mips are "sometimes over conservative", Sec. 6); a wall
 * thinner than a voxel lit on both sides has one voxel, one averaged normal, and leaks radiance.
 *
 * The volume (vct_volume.c) is exposed here so tests can build mips of synthetic data and check
 * the memory plan without a technique run. */
#ifndef GIB_VCT_H
#define GIB_VCT_H

#include <stdbool.h>
#include <stdint.h>

#include "harness/base/error.h"
#include "harness/gl/gpu_scene.h"
#include "harness/gl/ledger.h"

/* The 6 anisotropic directions, in this order: the direction a cone TRAVELS along (+x: the
 * values a cone moving toward +x sees, front-to-back in +x). */
enum { VCT_PX = 0, VCT_NX, VCT_PY, VCT_NY, VCT_PZ, VCT_NZ, VCT_DIRECTIONS };

/* The memory plan: exact bytes of each voxel structure at `res` voxels a side, as the ledger
 * counts them once allocated. radiance and normal: RGBA16F res^3 (base level only, the paper's
 * "base voxels"); aniso: 6 RGBA16F textures of (res/2)^3 with full mip chains (the paper's
 * formats); lobes: 3 more alike, only with `front_faces` (0 without). */
typedef struct vct_plan {
    uint64_t radiance, normal, aniso, lobes, voxels, total;
} vct_plan;
/* voxels: the shared occlusion voxels the occupancy comes from (common/voxels.h: R8 res^3 with
 * its chain, and 8 bytes a triangle + 16 of work list); 0 for triangles < 0 (no scene: the
 * volume alone, as the tests build it). */
void vct_plan_bytes(int res, long long triangles, bool lobes, vct_plan *plan);
/* The budget: `budget_mb` (decimal MB) if > 0, else the device's: GL_NVX_gpu_memory_info's
 * currently available memory where the extension exists, otherwise half the physical memory
 * (sysconf). `what` names the source, for the message. Needs a current context for the GL query. */
uint64_t vct_budget_bytes(double budget_mb, const char **what);

typedef struct vct_volume {
    int res;
    float origin[3], size;      /* the cubic grid over the scene's bounds (scene frame) */
    unsigned radiance, normal;  /* RGBA16F 3D, 1 level: rgb = outgoing radiance (W/m^2/sr),
                                   a = occupancy; normal: xyz, w = 1 where light was injected */
    unsigned aniso[VCT_DIRECTIONS];/* RGBA16F 3D (res/2)^3, full chain: premultiplied radiance,
                                      alpha = occlusion, pre-integrated along the direction */
    unsigned lobe[3];              /* RGBA16F 3D as aniso, per axis: the emission lobes
                                      (vct_lobes.comp), the luminance of the lit surfaces facing
                                      + and - along it and where it comes from */
    int aniso_levels;
    unsigned fbo, vao;             /* the injection's layered framebuffer (radiance, normal) */
    unsigned scratch_fbo;          /* several lights: one light's sums into the normal volume */
    unsigned inject_program, resolve_program, accumulate_program, mip_base_program, mip_program;
    unsigned lobe_base_program, lobe_program;
} vct_volume;

/* Allocates (labels "radiance.base", "normal.base", "aniso.<dir>", with `lobes` "lobes" for
 * front_faces) for a grid of side `size` at
 * `origin`. A GL_OUT_OF_MEMORY fails with GIB_ERR_OUT_OF_MEMORY. The caller checks the plan against
 * the budget first (vct_plan_check). */
int vct_volume_create(vct_volume *v, const float origin[3], float size, int res, bool lobes,
                      gib_ledger *ledger, gib_error *err);
/* The plan against the budget (budget_mb as vct_budget_bytes), recorded in the ledger first
 * (gib_ledger_plan: the row's mem_planned_by_structure, by the allocations' structure names):
 * over the budget, fails with GIB_ERR_OUT_OF_MEMORY naming the planned and available bytes. */
int vct_plan_check(const vct_plan *plan, int res, double budget_mb, gib_ledger *ledger,
                   gib_error *err);
/* Clears the base voxels, injects the light views' texels (bound: gib_light_views_bind; `lv_res`
 * texels a side, light l's faces first_face[l] .. + faces_of[l]), resolves the sums into
 * averages and takes the occupancy (alpha) from `occupancy`, the occlusion voxels' R8 texture
 * (common/voxels.h) of the same grid, built this frame. Several lights are averaged one by one and
 * their radiances added (vct_accumulate.comp). With `fill`, an occupied voxel no texel landed in
 * takes the light of the surface the light views see in it (vct_resolve.comp). */
void vct_volume_inject(vct_volume *v, unsigned occupancy, int lv_res, const int *first_face,
                       const int *faces_of, int lights, bool fill);
/* The anisotropic mips (Crassin et al. 2011, Sec. 4): level 0 of each direction from the base
 * voxels, level k+1 from level k, by compositing the 2 voxels along the direction front to back
 * and averaging the 4 pairs. */
void vct_volume_mips(vct_volume *v);
/* How cones march (vct_trace.glsl): the step as a multiple of the sample's diameter, the start
 * along the normal in voxels, the levels finer than the paper's log2(d) a sample reads, and how a
 * sample clears the receiver's plane (0 shrunk to its height, 1 lifted along the normal). */
typedef struct vct_cone_settings {
    float step_factor, start_offset;
    int sample_level, clearance;
    int front_faces;   /* 1: a sample's light limited to surfaces whose front faces the apex */
} vct_cone_settings;
/* Binds the volume and the cone settings for vct_trace.glsl on the current program. */
void vct_volume_bind_cones(const vct_volume *v, const vct_cone_settings *c);
void vct_volume_destroy(vct_volume *v, gib_ledger *ledger);

#endif

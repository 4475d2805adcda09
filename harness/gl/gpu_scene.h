/* gibench — the scene on the GPU, uploaded once per scene and shared by every technique run on it
 * (ARCHITECTURE.md, "Data flow of a matrix row"). Its memory is counted in its own ledger (the CSV's scene_bytes), apart
 * from each technique's. Layout seen by shaders: techniques/common/scene.glsl. */
#ifndef GIB_GPU_SCENE_H
#define GIB_GPU_SCENE_H

#include "scenes/scene.h"
#include "ledger.h"

struct gib_gpu_scene {
    const gib_scene *scene;  /* the scene in its frame (scene.h, gib_scene_frame): &frame->scene.
                              * Positions, lights and cameras are moved next to the origin when
                              * the scene lies far from it; images are the same. */
    gib_scene_frame *frame;  /* owned */
    float *pose;             /* moving scenes: room for the largest moving mesh's positions and
                                normals, allocated once at upload (gib_gpu_scene_set_time) */
    unsigned vao;
    unsigned positions, normals, uvs, indices;
    unsigned materials;      /* SSBO, binding 0 (struct Material in scene.glsl) */
    unsigned lights;         /* SSBO, binding 1 (struct Light) */
    unsigned *textures;      /* one GL texture per scene texture (sRGB8_A8 for colour, mipmapped) */
    unsigned white;          /* 1x1 white texture for materials without one */
    gib_ledger ledger;
};
typedef struct gib_gpu_scene gib_gpu_scene;

int gib_gpu_scene_upload(const gib_scene *scene, gib_gpu_scene *gpu, gib_error *err);
void gib_gpu_scene_free(gib_gpu_scene *gpu);
/* Uploads the positions and normals of the scene's moving meshes at time t (gib_motion_pose);
 * nothing for a static scene. The CPU-side scene is not changed. */
int gib_gpu_scene_set_time(const gib_gpu_scene *gpu, double t, gib_error *err);

/* Binds the material and light SSBOs (bindings 0 and 1). */
void gib_gpu_scene_bind(const gib_gpu_scene *gpu);
/* Draws every triangle range with the current program: sets `layout(location = 0) uniform int
 * u_material` and binds the albedo texture to unit 0 and the alpha mask to unit 1. */
void gib_gpu_scene_draw(const gib_gpu_scene *gpu);
/* The same, each range drawn `instances` times (gl_InstanceID tells the copies apart). */
void gib_gpu_scene_draw_instanced(const gib_gpu_scene *gpu, int instances);

#endif

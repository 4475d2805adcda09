/* gibench — internals of the reference renderer shared by its source files (not a public API).
 *
 *   ref_world.c      the Embree scene built from a gib_scene, the alpha-mask filter, ray casting,
 *                    surface points and robust ray offsets
 *   ref_estimators.c one estimator per light-transport component (DESIGN.md, "Light-transport
 *                    components"): direct and ao
 *   reference.c      the render loop (threads, per-pixel statistics, progress), EXR attributes */
#ifndef GIB_REF_INTERNAL_H
#define GIB_REF_INTERNAL_H

#include <embree3/rtcore.h>

#include "reference.h"
#include "rng.h"

typedef struct ref_world {
    RTCDevice device;
    RTCScene scene;          /* NULL when the scene has no triangles: every ray misses */
    const gib_scene *gs;
    float eps;               /* ray offset, gib_reference_ray_eps() */
    char embree_msg[512];    /* last message from Embree's error callback */
} ref_world;

/* A visible surface point, oriented for shading. */
typedef struct ref_hit {
    float p[3];              /* position, interpolated from the triangle's vertices */
    float n[3];              /* shading normal: interpolated vertex normal, unit length */
    float ng[3];             /* geometric normal, unit length, on the same side as n */
    float uv[2];
    uint32_t prim;
    const gib_material *mat;
    int back;                /* seen from behind a one-sided material: shades to 0 */
} ref_hit;

int ref_world_build(ref_world *w, const gib_scene *gs, gib_error *err);
void ref_world_free(ref_world *w);

/* Casts the ray (o, d) from tnear = 0 and fills hit, oriented toward the viewer at -d.
 * Returns 1 on a hit, 0 on a miss. */
int ref_trace(const ref_world *w, const float o[3], const float d[3], ref_hit *hit);

/* 1 when a surface lies on the ray (o, d) within (0, tfar]. */
int ref_occluded(const ref_world *w, const float o[3], const float d[3], float tfar);

/* Origin for a ray leaving h in direction d: offset along the geometric normal, toward the side d
 * points to, by w->eps. */
void ref_offset_origin(const ref_world *w, const ref_hit *h, const float d[3], float o[3]);

/* Bilinear texture lookup with repeat wrap; texel rows run top-down, t = 1 - v. */
void ref_tex_sample(const gib_texture *t, float u, float v, float out[4]);

/* Estimators. Each adds the rays it casts to *rays. */
void ref_est_direct(const ref_world *w, const ref_hit *h, const float wo[3], float out[3],
                    long long *rays);
/* One cosine-weighted visibility sample: 1 when unoccluded within dmax (<= 0 or inf: unbounded). */
float ref_est_ao(const ref_world *w, const ref_hit *h, float dmax, ref_pcg32 *rng, long long *rays);

/* Small vector helpers. */
static inline float ref_dot(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

#endif

/* gibench — the light evaluation of THE light definitions (camera_light.c; ARCHITECTURE.md, "One scene
 * model for both sides"), defined here, static inline, so that it inlines into the path tracer's
 * next-event estimation, which runs it at every path vertex for every light (the same IEEE
 * operations in the same order as a call would, so the images are bit-identical).
 * Plain single-precision formulas, mirrored line by line in techniques/common/scene.glsl.
 * Included by scene.h; do not include it directly. */
#ifndef GIB_LIGHT_EVAL_H
#define GIB_LIGHT_EVAL_H

#include <math.h>

static inline float gib_dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline float gib_spot_falloff_cos(const gib_light *l, float cos_outer,
                                         const float dir_from_light[3])
{
    /* Compare cosines instead of angles: no acos, and theta == outer counts as inside on both
     * sides. dir_from_light need not be unit length; the axis is (the loader normalises it). */
    const float len = sqrtf(gib_dot3(dir_from_light, dir_from_light));
    if (!(len > 0.0f))
        return 0.0f;
    const float cos_theta = gib_dot3(dir_from_light, l->direction) / len;
    if (cos_theta < cos_outer)
        return 0.0f;
    /* Clamped so an outer angle beyond 90 degrees never takes pow() of a negative number. */
    float c = fmaxf(cos_theta, 0.0f);
    /* Cosine falloff (e = 1, the Cornell and Sponza spots) is common and powf costly at every path
     * vertex: the shortcut gives the identical value. */
    return l->spot_exponent == 1.0f ? c : powf(c, l->spot_exponent);
}

static inline int gib_light_eval_cos(const gib_light *l, float cos_outer, const float p[3],
                                     float wi[3], float *dist, float E[3])
{
    if (l->type == GIB_LIGHT_DIRECTIONAL) {
        wi[0] = -l->direction[0];
        wi[1] = -l->direction[1];
        wi[2] = -l->direction[2];
        *dist = INFINITY;
        E[0] = l->intensity[0];
        E[1] = l->intensity[1];
        E[2] = l->intensity[2];
        return 1;
    }
    float d[3] = {l->position[0] - p[0], l->position[1] - p[1], l->position[2] - p[2]};
    const float r2 = gib_dot3(d, d);
    /* A point exactly at the light receives nothing rather than an infinity (hard case "light
     * touching a surface"): finite output is required of every estimator. */
    if (!(r2 > 0.0f)) {
        wi[0] = 0.0f;
        wi[1] = 1.0f;
        wi[2] = 0.0f;
        *dist = 0.0f;
        E[0] = E[1] = E[2] = 0.0f;
        return 0;
    }
    const float r = sqrtf(r2);
    wi[0] = d[0] / r;
    wi[1] = d[1] / r;
    wi[2] = d[2] / r;
    *dist = r;
    float falloff = 1.0f;
    if (l->type == GIB_LIGHT_SPOT) {
        const float from_light[3] = {-wi[0], -wi[1], -wi[2]};
        falloff = gib_spot_falloff_cos(l, cos_outer, from_light);
        if (falloff <= 0.0f) {
            E[0] = E[1] = E[2] = 0.0f;
            return 0;
        }
    }
    E[0] = l->intensity[0] * falloff / r2;
    E[1] = l->intensity[1] * falloff / r2;
    E[2] = l->intensity[2] * falloff / r2;
    return 1;
}

#endif

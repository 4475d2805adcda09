/* gibench — the frame both renderers work in (scene.h, gib_scene_frame): a scene far from the
 * origin is moved next to it before any arithmetic, so that hit points, ray offsets, shadow-map
 * distances and LDM depths keep the precision of the scene's size, not of its distance to the
 * world's origin (ARCHITECTURE.md, "Hard cases": hard_far). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

/* The scene's vertex bounding box, its diagonal and its largest coordinate magnitude. */
static void frame_bounds(const gib_scene *s, double lo[3], double hi[3], double *diag,
                         double *amax)
{
    *diag = *amax = 0.0;
    for (int k = 0; k < 3; k++)
        lo[k] = hi[k] = 0.0;
    if (!s || !s->positions || s->vertex_count == 0)
        return;
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (uint32_t i = 0; i < s->vertex_count; i++)
        for (int k = 0; k < 3; k++) {
            double c = s->positions[3 * (size_t)i + k];
            lo[k] = c < lo[k] ? c : lo[k];
            hi[k] = c > hi[k] ? c : hi[k];
            *amax = fabs(c) > *amax ? fabs(c) : *amax;
        }
    double d2 = 0.0;
    for (int k = 0; k < 3; k++)
        d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    *diag = sqrt(d2);
}

void gib_scene_frame_origin(const gib_scene *s, float origin[3])
{
    double lo[3], hi[3], diag, amax;
    frame_bounds(s, lo, hi, &diag, &amax);
    origin[0] = origin[1] = origin[2] = 0.0f;
    if (!(amax > GIB_FRAME_FAR * diag) || !isfinite(amax))
        return; /* near the origin: the scene's own coordinates, bit for bit */
    /* The box's centre on a grid of the largest power of two not above the diagonal: a float
     * vertex minus a multiple of it is exact whenever the vertex's own spacing is not finer than
     * the grid or the difference stays within 2^24 of that spacing, i.e. for every vertex but
     * those much nearer the origin than the scene's size. */
    double g = diag > 0.0 ? exp2(floor(log2(diag))) : exp2(floor(log2(amax)) - 23.0);
    for (int k = 0; k < 3; k++)
        origin[k] = (float)(g * nearbyint(0.5 * (lo[k] + hi[k]) / g));
}

static void frame_sub(float *v, const float o[3])
{
    for (int k = 0; k < 3; k++)
        v[k] = (float)((double)v[k] - (double)o[k]);
}

int gib_scene_frame_make(const gib_scene *s, gib_scene_frame *f, gib_error *err)
{
    memset(f, 0, sizeof *f);
    f->scene = *s;
    gib_scene_frame_origin(s, f->origin);
    f->moved = f->origin[0] != 0.0f || f->origin[1] != 0.0f || f->origin[2] != 0.0f;
    if (!f->moved)
        return 0;
    gib_scene *t = &f->scene;
    size_t nv = (size_t)s->vertex_count, nl = s->light_count, nc = s->camera_count;
    t->positions = f->positions = gib_calloc(3 * (nv ? nv : 1), sizeof(float), err);
    t->lights = f->lights = gib_calloc(nl ? nl : 1, sizeof(gib_light), err);
    t->cameras = f->cameras = gib_calloc(nc ? nc : 1, sizeof(gib_camera), err);
    if (!f->positions || !f->lights || !f->cameras) {
        gib_scene_frame_free(f);
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "scene '%s': out of memory for its copy moved next to the origin",
                             s->name);
    }
    memcpy(f->positions, s->positions, 3 * nv * sizeof(float));
    for (size_t i = 0; i < nv; i++)
        frame_sub(f->positions + 3 * i, f->origin);
    if (nl)
        memcpy(f->lights, s->lights, nl * sizeof *f->lights);
    for (size_t i = 0; i < nl; i++)
        if (f->lights[i].type != GIB_LIGHT_DIRECTIONAL)
            frame_sub(f->lights[i].position, f->origin);
    if (nc)
        memcpy(f->cameras, s->cameras, nc * sizeof *f->cameras);
    for (size_t i = 0; i < nc; i++) {
        frame_sub(f->cameras[i].eye, f->origin);
        frame_sub(f->cameras[i].target, f->origin);
    }
    frame_sub(t->bounds_min, f->origin);
    frame_sub(t->bounds_max, f->origin);
    return 0;
}

void gib_scene_frame_free(gib_scene_frame *f)
{
    free(f->positions);
    free(f->lights);
    free(f->cameras);
    memset(f, 0, sizeof *f);
}

/* gibench — light vertices: the second strategy of `full` and `higher` (ref_path.c).
 *
 * Why: a camera path finds the light that a diffuse surface y reflects toward an earlier vertex x
 * only when x's bounce happens to hit y. Where a light sits close to a wall (a lamp under a
 * ceiling), a small bright patch of y carries much of the indirect light, and cosine-distributed
 * bounces hit it rarely: those few paths are most of the noise. A light vertex y sampled from the
 * light itself lands on that patch as often as the light sends its power there; connected to x by
 * a shadow ray it estimates the same paths with a different density. Multiple importance sampling
 * (Veach 1997, Ch. 9; the balance heuristic) keeps, for each path, the strategy whose density is
 * high there: camera bounces for y close to x (corners, where the connection's 1 / d^2 blows up),
 * light vertices for bright patches far away. The weights of the two strategies add up to 1 for
 * every path, so the sum is unbiased: a light subpath of one surface vertex connected to every
 * vertex of the camera path, the s = 2 strategies of bidirectional path tracing (Veach 1997,
 * Ch. 10; Lafortune and Willems 1993). Connecting at every camera vertex matters in a closed room,
 * where the patch lights every bounce: at the first vertex only, the closed room's noise fell by
 * 1.2x, at every vertex by 3.8x (reference/PERFORMANCE.md).
 *
 * The connection goes through the diffuse lobes at both ends (the Phong lobe at y and Phong or
 * mirror lobes at x stay with camera paths alone, weight 1) and follows the camera strategy's
 * rules exactly: x's direction leaves through its geometric surface and its shading hemisphere,
 * y's reflected radiance is next-event estimation's (gib_light_eval_cos, the shading cosine), y is
 * seen on the side the light shines on, and textures are read at level 0 as at any bounce hit. */
#include <math.h>

#include "ref_internal.h"

int ref_light_emits(const gib_light *l)
{
    return ref_lum(l->intensity) > 0.0f &&
           (l->type != GIB_LIGHT_SPOT || cosf(l->spot_outer_deg * (REF_PI / 180.0f)) < 1.0f);
}

float ref_light_power(const ref_world *w, const gib_light *l)
{
    float lum = ref_lum(l->intensity);
    if (!(lum > 0.0f))
        return 0.0f;
    if (l->type == GIB_LIGHT_DIRECTIONAL)
        return lum * REF_PI * w->bradius * w->bradius;
    if (l->type == GIB_LIGHT_SPOT) {
        float co = cosf(l->spot_outer_deg * (REF_PI / 180.0f));
        return lum * 2.0f * REF_PI * (1.0f - co);
    }
    return lum * 4.0f * REF_PI;
}

int ref_light_pick_build(ref_world *w, gib_error *err)
{
    const gib_scene *gs = w->gs;
    double total = 0.0;
    for (uint32_t i = 0; i < gs->light_count; i++)
        total += ref_light_power(w, &gs->lights[i]);
    if (!(total > 0.0))
        return 0;
    if (!(w->light_pick = gib_calloc(gs->light_count, sizeof(float), err)))
        return -1;
    for (uint32_t i = 0; i < gs->light_count; i++)
        w->light_pick[i] = (float)(ref_light_power(w, &gs->lights[i]) / total);
    return 0;
}

/* The density of emitted directions (per steradian; a directional light's per unit area across
 * its disk). Spots emit uniformly over their cone, cos(outer) as next-event estimation has it. */
static float ref_emit_density(const ref_world *w, uint32_t i)
{
    const gib_light *l = &w->gs->lights[i];
    if (l->type == GIB_LIGHT_DIRECTIONAL)
        return 1.0f / (REF_PI * w->bradius * w->bradius);
    if (l->type == GIB_LIGHT_SPOT)
        return 1.0f / (2.0f * REF_PI * (1.0f - w->spot_cos[i]));
    return 1.0f / (4.0f * REF_PI);
}

/* A point within the ray offset of a positional light has density 0: that is the light touching
 * a surface (ARCHITECTURE.md, "Hard cases"), which next-event estimation's shadow ray does not
 * test and camera bounces practically never reach; light vertices leave it to them (weight 1
 * there), so that both strategies keep the renderer's convention (a light resting on a surface
 * lights the rest of the scene, not the patch under it). */
float ref_lv_density(const ref_world *w, uint32_t i, const float wi[3], float dist,
                     const float ng[3])
{
    float c = ref_dot(ng, wi);
    if (!w->light_pick || !(c > 0.0f) || !(w->light_pick[i] > 0.0f))
        return 0.0f;
    float p = w->light_pick[i] * ref_emit_density(w, i) * c;
    if (w->gs->lights[i].type == GIB_LIGHT_DIRECTIONAL)
        return p;
    return dist > w->eps ? p / (dist * dist) : 0.0f;
}

/* The light of a light vertex: the first whose cumulative probability exceeds u. */
static uint32_t ref_pick_light(const ref_world *w, float u)
{
    uint32_t last = 0;
    float acc = 0.0f;
    for (uint32_t i = 0; i < w->gs->light_count; i++) {
        if (!(w->light_pick[i] > 0.0f))
            continue;
        last = i;
        acc += w->light_pick[i];
        if (u < acc)
            return i;
    }
    return last; /* u past the rounded sum */
}

/* The emitted ray of light i from (u1, u2): origin o, direction d. A positional light's ray
 * starts w->eps along d, so that it passes what lies within eps of the light, as next-event
 * estimation's shadow ray does (it stops eps short): the two strategies agree on what a light
 * sees, a surface the light touches included. */
static void ref_emit_ray(const ref_world *w, uint32_t i, float u1, float u2, float o[3],
                         float d[3])
{
    const gib_light *l = &w->gs->lights[i];
    float t[3], b[3], phi = 2.0f * REF_PI * u2;
    if (l->type == GIB_LIGHT_DIRECTIONAL) { /* a disk across the bounding sphere, facing it */
        float R = w->bradius, r = R * sqrtf(u1);
        ref_basis(l->direction, t, b);
        for (int k = 0; k < 3; k++) {
            d[k] = l->direction[k];
            o[k] = w->bcentre[k] - R * d[k] + r * cosf(phi) * t[k] + r * sinf(phi) * b[k];
        }
        return;
    }
    float axis[3] = {0.0f, 0.0f, 1.0f}, ct = 1.0f - 2.0f * u1;
    if (l->type == GIB_LIGHT_SPOT) {
        ct = 1.0f - u1 * (1.0f - w->spot_cos[i]);
        axis[0] = l->direction[0], axis[1] = l->direction[1], axis[2] = l->direction[2];
    }
    float st = sqrtf(ref_fmaxf(0.0f, 1.0f - ct * ct));
    ref_basis(axis, t, b);
    for (int k = 0; k < 3; k++)
        d[k] = st * cosf(phi) * t[k] + st * sinf(phi) * b[k] + ct * axis[k];
    for (int k = 0; k < 3; k++)
        o[k] = l->position[k] + w->eps * d[k];
}

uint32_t ref_lv_ray(const ref_world *w, float u0, float u1, float u2, float o[3], float d[3])
{
    uint32_t i = ref_pick_light(w, u0);
    ref_emit_ray(w, i, u1, u2, o, d);
    return i;
}

/* 1 when next-event estimation at y sees the light along wi at distance dist: its own shadow ray
 * (ref_nee_visible's origin, direction and tfar). The emission ray that found y usually says so
 * already, but not always the same: next-event estimation's ray leaves y offset along y's normal
 * and ends eps short of the light, so next to a light that touches a surface it can end on the
 * far side of that surface and be stopped by it (a lamp on a ceiling lights no floor point but
 * the one straight below, for next-event estimation; a ray from the lamp reaches all of them).
 * Light vertices must estimate next-event estimation's integrand, whatever its conventions, or
 * the two strategies' images part (a closed box with a light on its ceiling: 2-4%). */
static int ref_lv_nee_sees(const ref_world *w, const ref_hit *y, const float wi[3], float dist,
                           long long *rays)
{
    float o[3], tfar = isinf(dist) ? INFINITY : dist - w->eps;
    ref_offset_origin(w, y, wi, o);
    if (!(tfar > 0.0f))
        return 1;
    ++*rays;
    return !ref_occluded(w, o, wi, tfar);
}

void ref_lv_sample(const ref_world *w, ref_rng *rng, ref_lvert *lv, long long *rays)
{
    float u0 = 0.0f, u1, u2;
    lv->ok = 0;
    if (w->gs->light_count > 1)
        u0 = ref_rng_1d(rng);
    ref_rng_2d(rng, &u1, &u2);
    if (!w->light_pick)
        return;
    float o[3], d[3], wi[3], dist, E[3];
    uint32_t i = ref_lv_ray(w, u0, u1, u2, o, d);
    ref_hit y;
    ++*rays;
    if (!ref_trace(w, o, d, &y) || y.back ||
        !gib_light_eval_cos(&w->gs->lights[i], w->spot_cos[i], y.p, wi, &dist, E))
        return;
    float cosn = ref_dot(y.n, wi), pdf = ref_lv_density(w, i, wi, dist, y.ng);
    if (!(cosn > 0.0f) || !(pdf > 0.0f) || !ref_lv_nee_sees(w, &y, wi, dist, rays))
        return;
    float kd[3];
    ref_albedo(w, &y, kd);
    for (int k = 0; k < 3; k++) {
        lv->rad[k] = kd[k] * (1.0f / REF_PI) * E[k] * cosn / pdf;
        lv->p[k] = y.p[k];
        lv->ng[k] = y.ng[k];
    }
    lv->pdf = pdf;
    lv->ok = lv->rad[0] > 0.0f || lv->rad[1] > 0.0f || lv->rad[2] > 0.0f;
}

float ref_camera_density(const float x[3], const float nx[3], float pa_lobe, const float y[3],
                         const float ngy[3])
{
    float v[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
    float d2 = ref_dot(v, v);
    if (!(d2 > 0.0f))
        return 0.0f;
    float cx = ref_dot(nx, v), cy = -ref_dot(ngy, v);
    if (!(cx > 0.0f) || !(cy > 0.0f))
        return 0.0f;
    return pa_lobe * (1.0f / REF_PI) * cx * cy / (d2 * d2); /* cosines of unnormalised v: / d^4 */
}

int ref_lv_connect(const ref_world *w, const ref_hit *h, const ref_lvert *lv, float pa_lobe,
                   float g[3], long long *rays)
{
    float v[3] = {lv->p[0] - h->p[0], lv->p[1] - h->p[1], lv->p[2] - h->p[2]};
    float d2 = ref_dot(v, v);
    if (!(d2 > 0.0f))
        return 0;
    float dist = sqrtf(d2), wc[3] = {v[0] / dist, v[1] / dist, v[2] / dist};
    float cx = ref_dot(h->n, wc), cy = -ref_dot(lv->ng, wc);
    if (!(cx > 0.0f) || !(ref_dot(h->ng, wc) > 0.0f) || !(cy > 0.0f))
        return 0;
    float pa = ref_camera_density(h->p, h->n, pa_lobe, lv->p, lv->ng);
    float geo = cx * cy / d2 * (1.0f / REF_PI) * ref_mis_weight(lv->pdf, pa);
    if (!(geo > 0.0f))
        return 0;
    float o[3], t[3], dir[3];
    ref_offset_origin(w, h, wc, o);
    const float back[3] = {-wc[0], -wc[1], -wc[2]};
    ref_offset_point(w, lv->p, lv->ng, back, t);
    for (int k = 0; k < 3; k++)
        dir[k] = t[k] - o[k];
    float len = sqrtf(ref_dot(dir, dir));
    if (!(len > 0.0f))
        return 0;
    for (int k = 0; k < 3; k++)
        dir[k] /= len;
    ++*rays;
    if (ref_occluded(w, o, dir, len))
        return 0;
    for (int k = 0; k < 3; k++)
        g[k] = geo * lv->rad[k];
    return 1;
}

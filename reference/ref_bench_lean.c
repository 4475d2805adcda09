/* gibench — the bench's lean tracer: a next-event-estimation path tracer that casts the same kind
 * of rays as `full` and does as little else as it can, on the path tracer's own world (BVH,
 * triangle records, lights): a reference point for the throughput ratio on this machine and scene
 * (gibench bench reference, rows lean_tracer and lean_replay; only for the `full` component).
 *
 * Why it exists: the path tracer's rays/s over Embree's on the same rays depends on the machine as
 * much as on the renderer (a ray's own work costs a roughly fixed time, and a path's dependent
 * rays cannot overlap as a replay's do); the lean tracer shows what is left when the renderer's
 * own work is cut down to what a path needs.
 *
 * Its rays follow `full`'s structure (reference.c ref_row_task, ref_path.c): one visible point per
 * pixel at the pixel centre with its next-event estimation once (the back of a one-sided surface
 * ends there), then spp paths from it: cosine continuations above the geometric surface, a shadow
 * ray to every delta light that reaches the vertex (origin offset and tfar as ref_nee_visible's),
 * roulette from min_depth on the throughput after the bounce, at most max_depth vertices, a path
 * ended at the back of a one-sided surface or at a surface that reflects nothing; and where the
 * path tracer's render used light vertices (p->strategies), per path a light vertex (a ray from a
 * light chosen by power and the vertex's shadow ray back to it, ref_connect.c) with a shadow ray
 * to every vertex below max_depth that faces it, and the roulette doubled as full's then is. So
 * that its paths are as long as the path tracer's, the throughput uses each material's mean
 * reflectance: its albedo times the mean of its albedo texture (the mip pyramid's last level)
 * plus its specular reflectance, all treated as one diffuse lobe (its roulette on that mean; ours
 * on the untextured constants over the lobe's probability). What it leaves out: shading normals,
 * texels, Phong and mirror lobes, the sky's rays, light tracing, per-pixel statistics and the
 * image; so the bench runs it only on scenes without a sky or mirrors (ref_lean_applies), where
 * its rays match ours in kind and number (within 0.1-2.5% on the committed scenes). Its rays are
 * replayed by Embree alone in the same repeats, as the path tracer's are. It sums its radiance
 * only to keep the work observable; the values are not an image of anything and are not
 * checked. */
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "ref_internal.h"

/* Roulette on twice the throughput with light vertices, as full's (ref_path.c, REF_RR_LV). */
#define REF_LEAN_RR 2.0f

typedef struct ref_lean {
    const ref_world *w;
    const gib_camera *cam;
    int width, height, spp, min_depth, max_depth;
    int lv;                  /* light vertices, as the path tracer's render chose */
    const float (*refl)[3];  /* per material: mean reflectance (see above) */
    atomic_llong rays;
    _Atomic double checksum;
} ref_lean;

/* A lean hit: the point, its unit geometric normal facing the ray's origin, its material's mean
 * reflectance. Returns 0 at the back of a one-sided surface. */
typedef struct ref_lean_hit {
    float p[3], ng[3];
    const float *refl;
} ref_lean_hit;

static int ref_lean_fill(const ref_lean *c, const ref_pending *pq, ref_lean_hit *h)
{
    const ref_world *w = c->w;
    const ref_tri *t = &w->tris[pq->prim];
    float *n = h->ng;
    n[0] = pq->rh.hit.Ng_x, n[1] = pq->rh.hit.Ng_y, n[2] = pq->rh.hit.Ng_z;
    float len = sqrtf(ref_dot(n, n)), s = len > 0.0f ? 1.0f / len : 0.0f;
    if (s == 0.0f) { /* a degenerate triangle: face the viewer, as ref_fill_hit does */
        n[0] = -pq->d[0], n[1] = -pq->d[1], n[2] = -pq->d[2];
        s = 1.0f;
    } else if (w->gs->normals) { /* the side of the vertex normals, as ref_fill_hit */
        float b1 = pq->rh.hit.u, b2 = pq->rh.hit.v, b0 = 1.0f - b1 - b2, vn[3];
        for (int k = 0; k < 3; k++)
            vn[k] = b0 * t->n[0][k] + b1 * t->n[1][k] + b2 * t->n[2][k];
        if (ref_dot(n, vn) < 0.0f)
            s = -s;
    }
    if (ref_dot(n, pq->d) * s > 0.0f) { /* seen from behind */
        if (!w->gs->materials[t->mat].two_sided)
            return 0;
        s = -s;
    }
    for (int k = 0; k < 3; k++) {
        n[k] *= s;
        h->p[k] = pq->o[k] + pq->rh.ray.tfar * pq->d[k];
    }
    h->refl = c->refl[t->mat];
    return 1;
}

/* Next-event estimation to every light from h: adds the unoccluded lights' beta * refl * E * cos
 * to out (the diffuse lobe's 1/pi left out: no image is made). */
static void ref_lean_nee(const ref_lean *c, const ref_lean_hit *h, const float beta[3],
                         float out[3], long long *rays)
{
    const ref_world *w = c->w;
    const gib_scene *gs = w->gs;
    for (uint32_t l = 0; l < gs->light_count; l++) {
        float wi[3], dist, E[3];
        if (!gib_light_eval_cos(&gs->lights[l], w->spot_cos[l], h->p, wi, &dist, E))
            continue;
        float cs = ref_dot(wi, h->ng);
        if (!(cs > 0.0f) || (E[0] == 0.0f && E[1] == 0.0f && E[2] == 0.0f))
            continue;
        float o[3], tfar = isinf(dist) ? INFINITY : dist - w->eps;
        ref_offset_point(w, h->p, h->ng, wi, o);
        if (tfar > 0.0f) {
            ++*rays;
            if (ref_occluded(w, o, wi, tfar))
                continue;
        }
        for (int k = 0; k < 3; k++)
            out[k] += beta[k] * h->refl[k] * E[k] * cs;
    }
}

static int ref_lean_dark(const float v[3])
{
    return !(v[0] > 0.0f || v[1] > 0.0f || v[2] > 0.0f);
}

/* The path's light vertex: a ray from a light (ref_connect.c's choice and emission); ok = 0 when
 * it misses, reaches the back of a one-sided surface, or a surface that reflects nothing. */
static void ref_lean_lv(const ref_lean *c, ref_pcg32 *rng, ref_lean_hit *lv, int *ok,
                        long long *rays)
{
    const ref_world *w = c->w;
    *ok = 0;
    if (!c->lv)
        return;
    float u0 = ref_pcg32_float(rng), u1 = ref_pcg32_float(rng), u2 = ref_pcg32_float(rng);
    ref_pending pq;
    float o[3], d[3], wi[3], dist, E[3];
    uint32_t l = ref_lv_ray(w, u0, u1, u2, o, d);
    ++*rays;
    if (!ref_trace_start(w, o, d, &pq) || !ref_lean_fill(c, &pq, lv) || ref_lean_dark(lv->refl) ||
        !gib_light_eval_cos(&w->gs->lights[l], w->spot_cos[l], lv->p, wi, &dist, E))
        return;
    /* the vertex's own shadow ray toward the light, as ref_connect.c checks next-event
     * estimation's view */
    float tfar = isinf(dist) ? INFINITY : dist - w->eps;
    ref_offset_point(w, lv->p, lv->ng, wi, o);
    if (tfar > 0.0f) {
        ++*rays;
        if (ref_occluded(w, o, wi, tfar))
            return;
    }
    *ok = 1;
}

/* The light vertex's shadow ray to h when each faces the other; adds beta * refl * refl_lv to
 * out when they see each other (the geometric factor left out: no image is made). */
static void ref_lean_connect(const ref_lean *c, const ref_lean_hit *h, const ref_lean_hit *lv,
                             const float beta[3], float out[3], long long *rays)
{
    const ref_world *w = c->w;
    float v[3] = {lv->p[0] - h->p[0], lv->p[1] - h->p[1], lv->p[2] - h->p[2]};
    const float back[3] = {-v[0], -v[1], -v[2]};
    if (!(ref_dot(h->ng, v) > 0.0f) || !(ref_dot(lv->ng, back) > 0.0f))
        return;
    float o[3], t[3], d[3];
    ref_offset_point(w, h->p, h->ng, v, o);
    ref_offset_point(w, lv->p, lv->ng, back, t);
    for (int k = 0; k < 3; k++)
        d[k] = t[k] - o[k];
    float len = sqrtf(ref_dot(d, d));
    if (!(len > 0.0f))
        return;
    for (int k = 0; k < 3; k++)
        d[k] /= len;
    ++*rays;
    if (!ref_occluded(w, o, d, len))
        for (int k = 0; k < 3; k++)
            out[k] += beta[k] * h->refl[k] * lv->refl[k];
}

static void ref_lean_row(void *ctx, int y)
{
    ref_lean *c = ctx;
    const ref_world *w = c->w;
    long long rays = 0;
    float sum[3] = {0.0f, 0.0f, 0.0f};
    for (int x = 0; x < c->width; x++) {
        ref_pcg32 rng;
        ref_pcg32_seed(&rng, (uint64_t)y * (uint64_t)c->width + (uint64_t)x, 0x1ea9u);
        float o[3], d[3], one[3] = {1.0f, 1.0f, 1.0f};
        gib_camera_ray(c->cam, c->width, c->height, (float)x + 0.5f, (float)y + 0.5f, o, d);
        ref_pending pq;
        ref_lean_hit h1;
        ++rays;
        if (!ref_trace_start(w, o, d, &pq) || !ref_lean_fill(c, &pq, &h1))
            continue;
        if (ref_lean_dark(h1.refl))
            continue;
        ref_lean_nee(c, &h1, one, sum, &rays);
        for (int s = 0; s < c->spp; s++) {
            float beta[3] = {h1.refl[0], h1.refl[1], h1.refl[2]};
            ref_lean_hit h = h1, lv;
            int lv_ok;
            ref_lean_lv(c, &rng, &lv, &lv_ok, &rays);
            for (int depth = 1; depth < c->max_depth; depth++) {
                if (lv_ok)
                    ref_lean_connect(c, &h, &lv, beta, sum, &rays);
                ref_sample_cosine(h.ng, ref_pcg32_float(&rng), ref_pcg32_float(&rng), d);
                if (depth >= c->min_depth) {
                    float q = ref_fmaxf(beta[0], ref_fmaxf(beta[1], beta[2]));
                    q = ref_fminf(1.0f, c->lv ? REF_LEAN_RR * q : q);
                    if (!(ref_pcg32_float(&rng) < q))
                        break;
                    for (int k = 0; k < 3; k++)
                        beta[k] /= q;
                }
                ref_offset_point(w, h.p, h.ng, d, o);
                ++rays;
                if (!ref_trace_start(w, o, d, &pq) || !ref_lean_fill(c, &pq, &h) ||
                    ref_lean_dark(h.refl))
                    break;
                ref_lean_nee(c, &h, beta, sum, &rays);
                for (int k = 0; k < 3; k++)
                    beta[k] *= h.refl[k];
            }
        }
    }
    atomic_fetch_add(&c->rays, rays);
    double prev = atomic_load(&c->checksum);
    while (!atomic_compare_exchange_weak(&c->checksum, &prev, prev + sum[0] + sum[1] + sum[2]))
        ;
}

int ref_lean_applies(const gib_scene *s, int component)
{
    if (component != GIB_COMP_FULL || ref_has_sky(s))
        return 0;
    for (uint32_t m = 0; m < s->material_count; m++)
        if (s->materials[m].spec_type == GIB_SPEC_MIRROR)
            return 0;
    return 1;
}

double ref_lean_render(const ref_world *w, const gib_ref_params *p, int threads, long long *rays)
{
    const gib_scene *gs = w->gs;
    float(*refl)[3] = malloc((gs->material_count ? gs->material_count : 1) * sizeof *refl);
    if (!refl)
        return -1.0;
    for (uint32_t m = 0; m < gs->material_count; m++) {
        const gib_material *g = &gs->materials[m];
        float t[4] = {1.0f, 1.0f, 1.0f, 1.0f};
        const float huge[4] = {1e30f, 0.0f, 0.0f, 1e30f}; /* the pyramid's last level: the mean */
        if (g->albedo_tex >= 0 && w->mips && w->mips[g->albedo_tex].levels > 0)
            ref_mip_sample(&w->mips[g->albedo_tex], 0.5f, 0.5f, huge, t);
        int spec = g->spec_type != GIB_SPEC_NONE;
        for (int k = 0; k < 3; k++)
            refl[m][k] = g->albedo[k] * t[k] + (spec ? g->specular[k] : 0.0f);
    }
    ref_lean c = {.w = w, .cam = &gs->cameras[p->camera], .width = p->width, .height = p->height,
                  .lv = w->light_pick && p->strategies == GIB_REF_STRATEGIES_LIGHT_VERTICES,
                  .spp = p->spp, .refl = (const float(*)[3])refl,
                  .min_depth = p->min_depth > 0 ? p->min_depth : GIB_REF_DEFAULT_MIN_DEPTH,
                  .max_depth = p->max_depth > 0 ? p->max_depth : GIB_REF_DEFAULT_MAX_DEPTH};
    atomic_init(&c.rays, 0);
    atomic_init(&c.checksum, 0.0);
    double t0 = ref_now();
    ref_parallel(threads, c.height, ref_lean_row, &c, NULL);
    double t = ref_now() - t0;
    *rays = atomic_load(&c.rays);
    free(refl);
    return t;
}

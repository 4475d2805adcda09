/* gibench — the bench's lean tracer: the least work a path tracer with next-event estimation can
 * do per ray, on the path tracer's own world (BVH, triangle records, lights), as a ceiling for the
 * throughput ratio that any renderer reaches on this machine and scene (gibench bench reference,
 * rows lean_tracer and lean_replay).
 *
 * Why it exists: the target is the path tracer's rays/s over Embree's on the same rays,
 * and that ratio depends on the machine as much as on the renderer. A ray's own work (choosing
 * it, shading its hit) costs a roughly fixed time, while Embree's time per ray grows with the
 * scene; and a path's rays depend on each other (a continuation starts where the last ray hit), so
 * the processor cannot overlap one ray's traversal with the next as it does when the same rays
 * are replayed back to back. The lean tracer measures what is left when the renderer's own work is
 * cut to nothing more than the path needs: the same ray structure as `full` (one visible point per
 * pixel, at the pixel centre, with its next-event estimation once; then `spp` paths from it:
 * cosine continuations, next-event estimation to every light at each later vertex, Russian
 * roulette from min_depth, at most max_depth vertices; a sky's rays are left out), but the
 * geometric normal as the shading
 * normal, the material's constant albedo (no texel, no cut-out beyond Embree's own filter), no
 * Phong or mirror lobe, no per-pixel statistics and no image. Its rays are replayed by Embree
 * alone in the same repeat, as the path tracer's are: its paired ratio is the best a path tracer
 * with these rays gets here. It computes a checksum of its radiance only to keep the work
 * observable; its values are not an image of anything and are not checked. */
#include <math.h>
#include <stdatomic.h>
#include <string.h>

#include "ref_internal.h"

typedef struct ref_lean {
    const ref_world *w;
    const gib_camera *cam;
    int width, height, spp, min_depth, max_depth;
    atomic_llong rays;
    _Atomic double checksum;
} ref_lean;

/* The hit as the lean tracer shades it: position, unit geometric normal facing the ray's origin,
 * constant albedo. */
static void ref_lean_hit(const ref_world *w, const ref_pending *pq, float p[3], float n[3],
                         const float **albedo)
{
    n[0] = pq->rh.hit.Ng_x, n[1] = pq->rh.hit.Ng_y, n[2] = pq->rh.hit.Ng_z;
    float s = 1.0f / sqrtf(ref_dot(n, n));
    if (ref_dot(n, pq->d) > 0.0f)
        s = -s;
    for (int k = 0; k < 3; k++) {
        n[k] *= s;
        p[k] = pq->o[k] + pq->rh.ray.tfar * pq->d[k] + w->eps * n[k]; /* offset origin */
    }
    *albedo = w->gs->materials[w->tris[pq->prim].mat].albedo;
}

/* Next-event estimation to every light from p (normal n): adds the unoccluded light's
 * beta * albedo * E * cos to out (the 1/pi of the diffuse lobe left out: no image is made). */
static void ref_lean_nee(const ref_world *w, const float p[3], const float n[3],
                         const float beta[3], const float a[3], float out[3], long long *rays)
{
    const gib_scene *gs = w->gs;
    for (uint32_t l = 0; l < gs->light_count; l++) {
        float wi[3], dist, E[3];
        if (!gib_light_eval_cos(&gs->lights[l], w->spot_cos[l], p, wi, &dist, E))
            continue;
        float cs = ref_dot(wi, n);
        if (!(cs > 0.0f))
            continue;
        ++*rays;
        if (!ref_occluded(w, p, wi, dist))
            for (int k = 0; k < 3; k++)
                out[k] += beta[k] * a[k] * E[k] * cs;
    }
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
        float o[3], d[3], p1[3], n1[3];
        const float *a1, one[3] = {1.0f, 1.0f, 1.0f};
        gib_camera_ray(c->cam, c->width, c->height, (float)x + 0.5f, (float)y + 0.5f, o, d);
        ref_pending pq;
        ++rays;
        if (!ref_trace_start(w, o, d, &pq))
            continue;
        ref_lean_hit(w, &pq, p1, n1, &a1);
        ref_lean_nee(w, p1, n1, one, a1, sum, &rays);
        for (int s = 0; s < c->spp; s++) {
            float beta[3] = {a1[0], a1[1], a1[2]}, p[3], n[3];
            memcpy(p, p1, sizeof p);
            memcpy(n, n1, sizeof n);
            for (int depth = 1; depth < c->max_depth; depth++) {
                ref_sample_cosine(n, ref_pcg32_float(&rng), ref_pcg32_float(&rng), d);
                if (depth >= c->min_depth) {
                    float q = ref_fminf(1.0f, ref_fmaxf(beta[0], ref_fmaxf(beta[1], beta[2])));
                    if (!(ref_pcg32_float(&rng) < q))
                        break;
                    for (int k = 0; k < 3; k++)
                        beta[k] /= q;
                }
                ++rays;
                if (!ref_trace_start(w, p, d, &pq))
                    break;
                const float *a;
                ref_lean_hit(w, &pq, p, n, &a);
                ref_lean_nee(w, p, n, beta, a, sum, &rays);
                for (int k = 0; k < 3; k++)
                    beta[k] *= a[k];
            }
        }
    }
    atomic_fetch_add(&c->rays, rays);
    double prev = atomic_load(&c->checksum);
    while (!atomic_compare_exchange_weak(&c->checksum, &prev, prev + sum[0] + sum[1] + sum[2]))
        ;
}

double ref_lean_render(const ref_world *w, const gib_ref_params *p, int threads, long long *rays)
{
    ref_lean c = {.w = w, .cam = &w->gs->cameras[p->camera], .width = p->width,
                  .height = p->height, .spp = p->spp,
                  .min_depth = p->min_depth > 0 ? p->min_depth : GIB_REF_DEFAULT_MIN_DEPTH,
                  .max_depth = p->max_depth > 0 ? p->max_depth : GIB_REF_DEFAULT_MAX_DEPTH};
    atomic_init(&c.rays, 0);
    atomic_init(&c.checksum, 0.0);
    double t0 = ref_now();
    ref_parallel(threads, c.height, ref_lean_row, &c, NULL);
    double t = ref_now() - t0;
    *rays = atomic_load(&c.rays);
    return t;
}

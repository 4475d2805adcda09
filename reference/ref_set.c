/* gibench — several components of one scene at one instant rendered together
 * (gib_reference_render_set): what a matrix asks of a scene (direct, indirect, glossy, caustic,
 * ..., at each of its sizes) from one world, and of each view (camera and size) with one primary
 * ray per pixel and round.
 *
 * Each component keeps everything a render of it alone has (reference.c's ref_run): its own
 * statistics, its own random streams (seeded with its component, as alone), its own light passes
 * and its own rounds toward its own target noise; only the work that does not depend on the
 * component is done once: the BVH and texture pyramids, each view's primary rays, ray
 * differentials and filtered albedo, and the rays of AO images that differ only in dmax or
 * obscurance (the same seeds draw the same directions: one closest-hit ray serves them all). So
 * each component's image, standard error and sample count are those of its render alone, bit for
 * bit, and a cache entry written from a set is the entry a render alone writes. The rounds run together: round k takes every component still short of its
 * target (or fixed spp) to its own k-th goal; a component that is done is skipped, and the set
 * ends when the most demanding one is. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ref_run.h"

typedef struct ref_set {
    ref_run *runs;
    int n;
    int *active;     /* per run: it takes samples this round */
    const int *view; /* per run: the first run of its view (camera and size) */
    int at;          /* the view being sampled: runs k with view[k] == at */
    int keep_back;   /* an auxiliary component of it is active: back faces keep their footprint */
} ref_set;

/* The AO images of the view being sampled that share their rays (ref_ao_ray: the same sampler
 * and seed draw the same numbers): their runs into ao; fewer than two share nothing (0). */
static int ref_set_ao_group(const ref_set *st, int *ao)
{
    int n = 0;
    for (int k = 0; k < st->n; k++) {
        const gib_ref_params *p = &st->runs[k].c.p, *p0 = n ? &st->runs[ao[0]].c.p : p;
        if (st->active[k] && st->view[k] == st->at && p->component == GIB_COMP_AO &&
            p->sampler == p0->sampler && p->seed == p0->seed)
            ao[n++] = k;
    }
    return n >= 2 ? n : 0;
}

/* The AO group's samples at visible point h: each sample's ray cast once, as far as the farthest
 * dmax of the runs taking that sample, each run's value from its first hit (ref_ao_value). */
static void ref_set_ao(const ref_set *st, const int *ao, int nao, size_t pix, const ref_hit *h,
                       long long *rays)
{
    const ref_ctx *c = &st->runs[ao[0]].c;
    int lo = st->runs[ao[0]].s0, hi = st->runs[ao[0]].s1;
    for (int i = 1; i < nao; i++) {
        const ref_run *r = &st->runs[ao[i]];
        lo = r->s0 < lo ? r->s0 : lo;
        hi = r->s1 > hi ? r->s1 : hi;
    }
    for (int s = lo; s < hi; s++) {
        ref_rng rng;
        ref_rng_seed_sample(&rng, c->p.sampler, pix, (uint64_t)s, c->p.seed, GIB_COMP_AO);
        float o[3], d[3], tfar = 0.0f;
        ref_ao_ray(c->w, h, &rng, o, d);
        for (int i = 0; i < nao; i++) {
            const ref_run *r = &st->runs[ao[i]];
            float dmax = r->c.p.dmax > 0.0f && isfinite(r->c.p.dmax) ? r->c.p.dmax : INFINITY;
            if (s >= r->s0 && s < r->s1 && dmax > tfar)
                tfar = dmax;
        }
        float t = ref_hit_distance(c->w, o, d, tfar);
        for (int i = 0; i < nao; i++) {
            ref_run *r = &st->runs[ao[i]];
            if (s < r->s0 || s >= r->s1)
                continue;
            float v = ref_ao_value(t, r->c.p.dmax, r->c.p.obscurance), v3[3] = {v, v, v};
            ref_pixel_add(r, pix, s, v3);
            rays[ao[i]]++; /* the ray each would have cast alone */
        }
    }
}

static void ref_set_row_task(void *ctx, int y)
{
    ref_set *st = ctx;
    const ref_ctx *c0 = &st->runs[st->at].c;
    const int W = c0->p.width;
    long long rays[GIB_REF_SET_MAX] = {0};
    int ao[GIB_REF_SET_MAX], nao = ref_set_ao_group(st, ao), in_ao[GIB_REF_SET_MAX] = {0};
    for (int i = 0; i < nao; i++)
        in_ao[ao[i]] = 1;
    for (int x = 0; x < W; x++) {
        size_t pix = (size_t)y * (size_t)W + (size_t)x;
        ref_hit h;
        float wo[3];
        long long primary = 0;
        int hit = ref_primary_hit(c0, x, y, st->keep_back, &h, wo, &primary);
        for (int k = 0; k < st->n; k++) {
            ref_run *r = &st->runs[k];
            if (!st->active[k] || st->view[k] != st->at || !r->c.camera_part)
                continue;
            rays[k] += primary; /* each component's count is what it casts alone */
            ref_hit hk = h; /* the component's own part (full's x1 next-event) stays its own */
            if (!in_ao[k] && hit && ref_pixel_ready(&r->c, &hk, wo, &rays[k]))
                ref_pixel_samples(r, pix, &hk, wo, &rays[k]);
        }
        if (nao && hit && !h.back)
            ref_set_ao(st, ao, nao, pix, &h, rays);
    }
    for (int k = 0; k < st->n; k++) {
        ref_run *r = &st->runs[k];
        if (!st->active[k] || st->view[k] != st->at || !r->c.camera_part)
            continue;
        atomic_fetch_add(&r->prog->rays, rays[k]);
        atomic_fetch_add(&r->prog->units, (long long)W * (r->s1 - r->s0));
    }
}

/* The instant every component must share (one world), and each one's own checks. */
static int ref_set_check(const gib_scene *scene, const gib_ref_params *p, int n, gib_error *err)
{
    if (n < 1 || n > GIB_REF_SET_MAX)
        return gib_fail(err, "reference: a set holds 1 to %d components, got %d",
                        GIB_REF_SET_MAX, n);
    for (int i = 0; i < n; i++) {
        if (ref_check_params(scene, &p[i], err) < 0)
            return -1;
        gib_ref_params a, b;
        gib_reference_normalize(scene, &p[0], &a);
        gib_reference_normalize(scene, &p[i], &b);
        if (b.time != a.time)
            return gib_fail(err, "reference: a set's components share one instant (one world): "
                                 "%s asks for time %g, %s for %g",
                            gib_component_name(a.component), (double)a.time,
                            gib_component_name(b.component), (double)b.time);
    }
    return 0;
}

/* view[k]: the first run that sees what run k sees (camera and size). */
static void ref_set_views(const ref_run *runs, int n, int *view)
{
    for (int k = 0; k < n; k++) {
        const gib_ref_params *a = &runs[k].c.p;
        view[k] = k;
        for (int j = 0; j < k && view[k] == k; j++) {
            const gib_ref_params *b = &runs[j].c.p;
            if (a->width == b->width && a->height == b->height && a->camera == b->camera)
                view[k] = j;
        }
    }
}

/* The rounds of every component, together; 0 or -1 with err. */
static int ref_set_rounds(ref_set *st, int nthreads, ref_tally *t, gib_error *err)
{
    int goal[GIB_REF_SET_MAX], done[GIB_REF_SET_MAX], left = st->n;
    for (int k = 0; k < st->n; k++)
        goal[k] = st->runs[k].c.p.spp, done[k] = 0;
    while (left > 0) {
        for (int k = 0; k < st->n; k++) {
            ref_run *r = &st->runs[k];
            st->active[k] = !done[k];
            if (done[k])
                continue;
            r->s0 = t[k].n;
            r->s1 = goal[k];
            r->prog->round = ++t[k].rounds;
            r->prog->spp_goal = goal[k];
            r->prog->units_target = (long long)goal[k] * r->prog->units_per_spp;
        }
        for (st->at = 0; st->at < st->n; st->at++) { /* each view with samples to take */
            st->keep_back = 0;
            int any = 0;
            for (int k = 0; k < st->n; k++)
                if (st->active[k] && st->view[k] == st->at) {
                    any |= st->runs[k].c.camera_part;
                    st->keep_back |= st->runs[k].c.p.component >= GIB_COMP_ALBEDO;
                }
            if (any)
                ref_parallel(nthreads, st->runs[st->at].c.p.height, ref_set_row_task, st,
                             st->runs[0].prog);
        }
        for (int k = 0; k < st->n; k++) {
            ref_run *r = &st->runs[k];
            if (!st->active[k])
                continue;
            if (r->c.light_part && ref_light_round(r, nthreads) < 0)
                return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                                     "reference: out of memory for light-tracing splats");
            if (ref_round_end(r, &t[k], &goal[k])) {
                done[k] = 1;
                left--;
                ref_progress_end(r->prog);
            }
        }
    }
    return 0;
}

/* The set on an already built world. */
static int ref_set_world(const ref_world *w, const gib_scene *scene, const gib_ref_params *p,
                         int n, gib_image *out, gib_image *stderr_img, gib_ref_stats *stats,
                         gib_error *err)
{
    ref_run runs[GIB_REF_SET_MAX];
    ref_progress prog[GIB_REF_SET_MAX];
    ref_tally t[GIB_REF_SET_MAX];
    int active[GIB_REF_SET_MAX], view[GIB_REF_SET_MAX], ready = 0, rc = -1;
    const int nthreads = ref_thread_count(&p[0]);
    const double t0 = ref_now();
    for (int k = 0; k < n; k++) {
        memset(&out[k], 0, sizeof out[k]);
        if (stderr_img)
            memset(&stderr_img[k], 0, sizeof stderr_img[k]);
    }
    for (; ready < n; ready++) {
        t[ready] = (ref_tally){.t0 = t0};
        int setup = ref_run_setup(&runs[ready], w, scene, &p[ready], &prog[ready], t0, nthreads,
                                  err);
        prog[ready].enabled = 0; /* the threads' display is the set's (below) */
        if (setup < 0) {
            ready++;
            goto done;
        }
        const int W = runs[ready].c.p.width, H = runs[ready].c.p.height;
        if (gib_image_alloc(&out[ready], W, H, 3, err) < 0 ||
            (stderr_img && gib_image_alloc(&stderr_img[ready], W, H, 3, err) < 0)) {
            ready++;
            goto done;
        }
    }
    char what[160] = "";
    for (int k = 0; k < n; k++)
        snprintf(what + strlen(what), sizeof what - strlen(what), "%s%s", k ? "+" : "",
                 gib_component_name(p[k].component));
    prog[0].enabled = !p[0].quiet; /* one progress line: the first component's counts */
    prog[0].what = what;
    ref_set_views(runs, n, view);
    ref_set st = {.runs = runs, .n = n, .active = active, .view = view};
    if (ref_set_rounds(&st, nthreads, t, err) < 0)
        goto done;
    for (int k = 0; k < n; k++) {
        prog[k].threads_used = prog[0].threads_used;
        ref_write_images(&runs[k], t[k].n, &out[k], stderr_img ? &stderr_img[k] : NULL);
        if (stats)
            ref_fill_stats(&stats[k], &runs[k], scene, &p[k], &t[k]);
    }
    rc = 0;

done:
    for (int k = 0; k < ready; k++) {
        if (rc < 0) {
            gib_image_free(&out[k]);
            if (stderr_img)
                gib_image_free(&stderr_img[k]);
        }
        ref_run_free(&runs[k]);
    }
    return rc;
}

int gib_reference_render_set(const gib_scene *scene, const gib_ref_params *p, int n,
                             gib_image *out, gib_image *stderr_img, gib_ref_stats *stats,
                             gib_error *err)
{
    if (ref_set_check(scene, p, n, err) < 0)
        return -1;
    double t0 = ref_now();
    gib_scene posed;
    if (gib_scene_posed(scene, p[0].time, &posed, err) < 0)
        return gib_error_prefix(err, "reference");
    ref_world w;
    if (ref_world_build(&w, &posed, err) < 0) {
        gib_scene_posed_free(&posed);
        return gib_error_prefix(err, "reference");
    }
    int rc = ref_set_world(&w, &posed, p, n, out, stderr_img, stats, err);
    ref_world_free(&w);
    gib_scene_posed_free(&posed);
    for (int k = 0; rc == 0 && stats && k < n; k++)
        stats[k].seconds = ref_now() - t0; /* the set's, the BVH build included */
    return rc;
}

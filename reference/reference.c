/* gibench — the reference renderer's render loop: primary rays through pixel centres, per-pixel
 * sampling and statistics, light-tracing passes, sampling rounds toward a target noise, and the
 * threads (ARCHITECTURE.md, "Reference renderer").
 *
 * Two parts, each with its own per-pixel statistics, added at the end:
 *  - camera part: at each pixel, the primary hit is found once per round and every sample of the
 *    round is drawn there; sample s uses its own numbers (sampler.h: a PCG32 generator, or
 *    Sobol points of its batch's scramble) and is accumulated in sample order (Welford; with
 *    Sobol also into its batch's sum) by the one thread that owns the row;
 *  - light part (caustic, full, higher in scenes with mirrors): pass s traces width*height
 *    particles, in fixed chunks; the chunks' splats are added into the pass image in chunk order,
 *    and each pixel's pass values are accumulated in pass order.
 * So every bit of the image, its standard error and the statistics is independent of the thread
 * count, and a round structure (--target-noise) gives the pixels of one plain run of the same
 * total spp. The two parts are independent, so their variances of the mean add. The camera
 * part's variance of the mean: with random numbers, the samples' variance over n; with Sobol,
 * the spread of the batch means (reference.h, GIB_REF_SAMPLER_SOBOL). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ref_run.h"

#define REF_MAX_THREADS 256
#define REF_MAX_SIZE 32768
#define REF_GROUP_PIXELS (1 << 20) /* pass images held at once, in pixels (24 MiB) */


/* 1 when the task should skip its work: an interrupt was requested and a finished round is saved
 * to fall back to (without one, the round in progress is finished instead). */
static int ref_abandon(ref_run *r)
{
    if (!r->can_abandon || !atomic_load(&r->stop->requested))
        return 0;
    atomic_store(&r->abandoned, 1);
    return 1;
}

static inline void ref_welford(double *mean, double *m2, int n, const float v[3])
{
    for (int c = 0; c < 3; c++) {
        double delta = (double)v[c] - mean[c];
        mean[c] += delta / n;
        m2[c] += delta * ((double)v[c] - mean[c]);
    }
}

int ref_primary_hit(const ref_ctx *c, int x, int y, int keep_back, ref_hit *h, float wo[3],
                    long long *rays)
{
    const int W = c->p.width, H = c->p.height;
    float o[3], d[3];
    /* Pixel centres only, no jitter: the GL techniques rasterise there without anti-aliasing,
     * so both sides see the same surface point and the error measures light transport, not
     * aliasing. */
    gib_camera_ray(c->cam, W, H, (float)x + 0.5f, (float)y + 0.5f, o, d);
    ++*rays;
    if (!ref_trace(c->w, o, d, h))
        return 0; /* a miss: 0, exactly */
    wo[0] = -d[0], wo[1] = -d[1], wo[2] = -d[2];
    if (h->back && !keep_back)
        return 1;
    ref_hit_differentials(c->w, c->cam, W, H, x, y, h);
    ref_albedo(c->w, h, h->kd); /* trilinear once per pixel, not once per sample */
    h->has_kd = 1;
    return 1;
}

int ref_pixel_ready(const ref_ctx *c, ref_hit *h, const float wo[3], long long *rays)
{
    if (h->back && c->p.component < GIB_COMP_ALBEDO)
        return 0; /* the back of a one-sided surface: 0, exactly */
    if (c->p.component == GIB_COMP_FULL) { /* next-event estimation at x1: once per pixel */
        ref_mat m;
        ref_material(c->w, h, &m);
        ref_nee(c->w, h, &m, wo, h->nee_dif, h->nee_spec, rays);
        h->has_nee = 1;
    }
    return 1;
}

int ref_pixel_hit(const ref_ctx *c, int x, int y, ref_hit *h, float wo[3], long long *rays)
{
    return ref_primary_hit(c, x, y, c->p.component >= GIB_COMP_ALBEDO, h, wo, rays) &&
           ref_pixel_ready(c, h, wo, rays);
}

void ref_pixel_samples(ref_run *r, size_t pix, const ref_hit *h, const float wo[3],
                       long long *rays)
{
    const ref_ctx *c = &r->c;
    /* the pixel's samples in batches, each on its sample's own stream (ref_sample_camera) */
    for (int s0 = r->s0; s0 < r->s1; s0 += REF_PATH_BATCH) {
        int nb = r->s1 - s0 < REF_PATH_BATCH ? r->s1 - s0 : REF_PATH_BATCH;
        ref_rng rng[REF_PATH_BATCH];
        float v[REF_PATH_BATCH][3];
        for (int i = 0; i < nb; i++)
            ref_rng_seed_sample(&rng[i], c->p.sampler, pix, (uint64_t)(s0 + i), c->p.seed,
                                c->p.component);
        ref_sample_camera(c, h, wo, nb, rng, v, rays);
        for (int i = 0; i < nb; i++)
            ref_pixel_add(r, pix, s0 + i, v[i]);
    }
}

void ref_pixel_add(ref_run *r, size_t pix, int s, const float v[3])
{
    ref_welford(&r->cm[pix * 3], &r->cm2[pix * 3], s + 1, v);
    if (r->cb)
        for (int k = 0; k < 3; k++)
            r->cb[(pix * 3 + k) * GIB_REF_SOBOL_BATCHES + (size_t)s % GIB_REF_SOBOL_BATCHES] +=
                (double)v[k];
}

static void ref_row_task(void *ctx, int y)
{
    ref_run *r = ctx;
    const ref_ctx *c = &r->c;
    const int W = c->p.width;
    long long rays = 0;
    for (int x = 0; x < W; x++) {
        if (ref_abandon(r))
            return;
        size_t pix = (size_t)y * (size_t)W + (size_t)x;
        ref_hit h;
        float wo[3];
        if (ref_pixel_hit(c, x, y, &h, wo, &rays))
            ref_pixel_samples(r, pix, &h, wo, &rays);
    }
    atomic_fetch_add(&r->prog->rays, rays);
    atomic_fetch_add(&r->prog->units, (long long)W * (r->s1 - r->s0));
    if (c->w->time_embree)
        atomic_fetch_add(&r->prog->embree_ticks, (long long)ref_embree_ticks_take());
}

static void ref_chunk_task(void *ctx, int task)
{
    ref_run *r = ctx;
    const ref_ctx *c = &r->c;
    int pass = r->g0 + task / r->chunks, chunk = task % r->chunks;
    long long n = ref_light_particles(c), first = (long long)chunk * REF_LIGHT_CHUNK;
    int count = (int)(n - first < REF_LIGHT_CHUNK ? n - first : REF_LIGHT_CHUNK);
    long long rays = 0;
    ref_splats *out = &r->splats[task];
    out->n = 0;
    if (ref_abandon(r))
        return;
    ref_light_chunk(c, (uint64_t)pass, (uint32_t)chunk, count, out, &rays);
    atomic_fetch_add(&r->prog->rays, rays);
    atomic_fetch_add(&r->prog->units, (long long)count);
    if (c->w->time_embree)
        atomic_fetch_add(&r->prog->embree_ticks, (long long)ref_embree_ticks_take());
}

/* Each pixel takes its pass values in pass order; pass images are cleared for the next group. */
static void ref_pass_rows_task(void *ctx, int y)
{
    ref_run *r = ctx;
    const int W = r->c.p.width;
    const size_t npx = (size_t)W * (size_t)r->c.p.height;
    for (int x = 0; x < W; x++) {
        size_t pix = (size_t)y * (size_t)W + (size_t)x;
        for (int g = 0; g < r->gn; g++) {
            double *img = r->pass_img + ((size_t)g * npx + pix) * 3;
            float v[3] = {(float)img[0], (float)img[1], (float)img[2]};
            if (v[0] != 0.0f || v[1] != 0.0f || v[2] != 0.0f || r->lm[pix * 3] != 0.0 ||
                r->lm[pix * 3 + 1] != 0.0 || r->lm[pix * 3 + 2] != 0.0)
                ref_welford(&r->lm[pix * 3], &r->lm2[pix * 3], r->g0 + g + 1, v);
            img[0] = img[1] = img[2] = 0.0;
        }
    }
}

int ref_light_round(ref_run *r, int nthreads)
{
    const ref_ctx *c = &r->c;
    const size_t npx = (size_t)c->p.width * (size_t)c->p.height;
    for (int g0 = r->s0; g0 < r->s1; g0 += r->group) {
        r->g0 = g0;
        r->gn = r->s1 - g0 < r->group ? r->s1 - g0 : r->group;
        ref_parallel(nthreads, r->gn * r->chunks, ref_chunk_task, r, r->prog);
        if (atomic_load(&r->abandoned))
            return 0; /* the round is undone from r->saved */
        for (int t = 0; t < r->gn * r->chunks; t++) { /* chunk order: deterministic sums */
            const ref_splats *sp = &r->splats[t];
            if (sp->oom)
                return -1;
            double *img = r->pass_img + (size_t)(t / r->chunks) * npx * 3;
            for (size_t i = 0; i < sp->n; i++)
                for (int k = 0; k < 3; k++)
                    img[(size_t)sp->s[i].pix * 3 + k] += sp->s[i].v[k];
        }
        ref_parallel(nthreads, c->p.height, ref_pass_rows_task, r, r->prog);
    }
    return 0;
}

int ref_check_params(const gib_scene *scene, const gib_ref_params *p, gib_error *err)
{
    if (!scene || !p)
        return gib_fail(err, "reference: no scene or no parameters");
    if (p->component < 0 || p->component >= GIB_COMP_COUNT)
        return gib_fail(err, "reference: unknown component %d", p->component);
    if (p->width < 1 || p->height < 1 || p->width > REF_MAX_SIZE || p->height > REF_MAX_SIZE)
        return gib_fail(err, "reference: image size %dx%d out of range (1 to %d)", p->width,
                        p->height, REF_MAX_SIZE);
    if (p->spp < 1)
        return gib_fail(err, "reference: spp must be at least 1, got %d", p->spp);
    gib_ref_params q;
    gib_reference_normalize(scene, p, &q);
    if (p->spp < 2 && !ref_deterministic(scene, q.component, q.max_depth))
        return gib_fail(err,
                        "reference: component %s samples at random: spp must be at least 2 (with "
                        "one sample the variance, hence the standard error, is unknown)",
                        gib_component_name(p->component));
    if (p->sampler != GIB_REF_SAMPLER_DEFAULT && p->sampler != GIB_REF_SAMPLER_SOBOL &&
        p->sampler != GIB_REF_SAMPLER_RANDOM)
        return gib_fail(err, "reference: unknown sampler %d (sobol %d, random %d)", p->sampler,
                        GIB_REF_SAMPLER_SOBOL, GIB_REF_SAMPLER_RANDOM);
    if (p->strategies < GIB_REF_STRATEGIES_AUTO ||
        p->strategies > GIB_REF_STRATEGIES_LIGHT_VERTICES)
        return gib_fail(err, "reference: unknown strategies %d (auto %d, camera %d, "
                             "light-vertices %d)", p->strategies, GIB_REF_STRATEGIES_AUTO,
                        GIB_REF_STRATEGIES_CAMERA, GIB_REF_STRATEGIES_LIGHT_VERTICES);
    if (p->threads < 0)
        return gib_fail(err, "reference: threads must be >= 0 (0 = all cores), got %d",
                        p->threads);
    if (isnan(p->dmax))
        return gib_fail(err, "reference: dmax is NaN");
    if (p->obscurance && p->component == GIB_COMP_AO && !(p->dmax > 0.0f && isfinite(p->dmax)))
        return gib_fail(err, "reference: obscurance needs a finite dmax > 0 (rho(d) = d / dmax)");
    if (p->max_depth < 0 || p->min_depth < 0 || p->max_specular < 0 || p->max_spp < 0)
        return gib_fail(err, "reference: max_depth, min_depth, max_specular and max_spp must be "
                             ">= 0 (0 = default)");
    if (!(p->target_noise >= 0.0) || !isfinite(p->target_noise))
        return gib_fail(err, "reference: target_noise must be >= 0, got %g", p->target_noise);
    if (p->target_noise > 0.0 && p->max_spp > 0 && p->max_spp < p->spp)
        return gib_fail(err, "reference: max_spp %d is below spp %d", p->max_spp, p->spp);
    if (!isfinite(p->time))
        return gib_fail(err, "reference: time must be finite, got %g", (double)p->time);
    if (p->camera < 0 || (uint32_t)p->camera >= scene->camera_count || !scene->cameras)
        return gib_fail(err, "reference: scene '%s' has %u camera(s), camera %d asked for",
                        scene->name, scene->camera_count, p->camera);
    return 0;
}

int ref_thread_count(const gib_ref_params *p)
{
    long n = p->threads > 0 ? p->threads : sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > REF_MAX_THREADS ? REF_MAX_THREADS : (int)n;
}

/* The variance of pixel value i's mean after n samples (n > 1): the camera part's (the samples'
 * variance over n, or with Sobol batches the batch means' spread: B equal batches, B = n when
 * n <= GIB_REF_SOBOL_BATCHES, as gib_reference_normalize and ref_next_goal keep it) plus the
 * light part's (its passes' variance over n). */
static double ref_var_of_mean(const ref_run *r, size_t i, int n)
{
    double v = r->lm2 ? r->lm2[i] / (n - 1) / n : 0.0;
    if (!r->cb)
        return v + r->cm2[i] / (n - 1) / n;
    const int B = n < GIB_REF_SOBOL_BATCHES ? n : GIB_REF_SOBOL_BATCHES;
    const double *s = r->cb + i * GIB_REF_SOBOL_BATCHES, per = (double)(n / B);
    double mb = 0.0, ss = 0.0;
    for (int b = 0; b < B; b++)
        mb += s[b] / per;
    mb /= B;
    for (int b = 0; b < B; b++)
        ss += (s[b] / per - mb) * (s[b] / per - mb);
    return v + ss / ((double)B * (B - 1));
}

/* Image mean and noise RMSE over pixels and channels, in pixel order. */
static void ref_summary(const ref_run *r, int n, double *mean, double *noise)
{
    const size_t m = (size_t)r->c.p.width * (size_t)r->c.p.height * 3;
    double sum = 0.0, var = 0.0;
    for (size_t i = 0; i < m; i++) {
        sum += r->cm[i] + (r->lm ? r->lm[i] : 0.0);
        if (n > 1)
            var += ref_var_of_mean(r, i, n);
    }
    *mean = sum / (double)m;
    *noise = sqrt(var / (double)m);
}

/* The next round's total spp: the noise falls as 1/sqrt(spp), aim 10% past the target, grow at
 * most 4x per round (a noisy early estimate cannot overshoot far), never past max_spp. With
 * Sobol batches, above GIB_REF_SOBOL_BATCHES a multiple of it (max_spp is one: normalised). */
static int ref_next_goal(int n, double rel, double target, int max_spp, int sobol)
{
    double need = ceil((double)n * (rel / target) * (rel / target) * 1.1);
    if (!(need <= 4.0 * n))
        need = 4.0 * n;
    if (need > max_spp)
        need = max_spp;
    int goal = need > n ? (int)need : n + 1;
    if (sobol)
        goal = ref_sobol_round_spp(goal);
    return goal < max_spp ? goal : max_spp;
}

static int ref_run_alloc(ref_run *r, gib_error *err)
{
    const size_t m = (size_t)r->c.p.width * (size_t)r->c.p.height * 3;
    r->cm = gib_calloc(m, sizeof *r->cm, err);
    r->cm2 = r->cm ? gib_calloc(m, sizeof *r->cm2, err) : NULL;
    if (!r->cm2)
        return -1;
    if (r->c.p.sampler == GIB_REF_SAMPLER_SOBOL && r->c.camera_part && r->c.p.spp > 1 &&
        !(r->cb = gib_calloc(m * GIB_REF_SOBOL_BATCHES, sizeof *r->cb, err)))
        return -1;
    if (!r->c.light_part)
        return 0;
    long long n = ref_light_particles(&r->c);
    r->chunks = (int)((n + REF_LIGHT_CHUNK - 1) / REF_LIGHT_CHUNK);
    int group = (int)(REF_GROUP_PIXELS / (m / 3));
    group = group < 1 ? 1 : group;
    int passes = r->c.p.target_noise > 0.0 ? r->c.p.max_spp : r->c.p.spp;
    group = group < passes ? group : passes;
    r->group = group;
    r->lm = gib_calloc(m, sizeof *r->lm, err);
    r->lm2 = r->lm ? gib_calloc(m, sizeof *r->lm2, err) : NULL;
    r->pass_img = r->lm2 ? gib_calloc((size_t)group * m, sizeof *r->pass_img, err) : NULL;
    r->splats = r->pass_img ? gib_calloc((size_t)group * r->chunks, sizeof *r->splats, err) : NULL;
    return r->splats ? 0 : -1;
}

/* Keeps (save 1) or restores (save 0) the statistics of the last finished round. */
static void ref_run_saved(ref_run *r, int save)
{
    const size_t m = (size_t)r->c.p.width * (size_t)r->c.p.height * 3;
    double *arr[5] = {r->cm, r->cm2, r->lm, r->lm2, r->cb};
    size_t len[5] = {m, m, m, m, m * GIB_REF_SOBOL_BATCHES}, at = 0;
    for (int i = 0; i < 5; at += len[i], i++)
        if (arr[i]) {
            if (save)
                memcpy(r->saved + at, arr[i], len[i] * sizeof *arr[i]);
            else
                memcpy(arr[i], r->saved + at, len[i] * sizeof *arr[i]);
        }
}

void ref_run_free(ref_run *r)
{
    free(r->saved);
    if (r->splats)
        for (size_t i = 0; i < (size_t)r->group * r->chunks; i++)
            free(r->splats[i].s);
    free(r->splats);
    free(r->pass_img);
    free(r->lm2);
    free(r->lm);
    free(r->cb);
    free(r->cm2);
    free(r->cm);
}

static void ref_ctx_init(ref_ctx *c, const ref_world *w, const gib_scene *scene,
                         const gib_ref_params *p)
{
    memset(c, 0, sizeof *c);
    c->w = w;
    c->cam = &w->gs->cameras[p->camera]; /* the camera in the world's frame */
    gib_reference_normalize(scene, p, &c->p);
    gib_camera_basis(c->cam, c->right, c->up, c->fwd);
    c->tan_half = tanf(0.5f * c->cam->vfov_deg * (REF_PI / 180.0f));
    c->aspect = (float)p->width / (float)p->height;
    int comp = c->p.component;
    c->light_part = w->has_mirror && (comp == GIB_COMP_CAUSTIC ||
                                      ((comp == GIB_COMP_FULL || comp == GIB_COMP_HIGHER) &&
                                       c->p.max_depth >= 2));
    c->camera_part = comp != GIB_COMP_CAUSTIC || w->has_specular;
    c->lv_on = 0; /* ref_choose_strategies */
}

/* full and higher's strategies: as asked, or by the pilot (ref_pilot.c). */
static void ref_choose_strategies(ref_run *r, int nthreads)
{
    ref_ctx *c = &r->c;
    if (!c->w->light_pick || !ref_light_vertices(c->w->gs, &c->p))
        return;
    if (c->p.strategies == GIB_REF_STRATEGIES_AUTO) {
        r->pilot_gain = ref_pilot_gain(c, nthreads);
        c->lv_on = r->pilot_gain > 1.0;
    } else {
        c->lv_on = c->p.strategies == GIB_REF_STRATEGIES_LIGHT_VERTICES;
    }
}

static void ref_progress_init(ref_progress *prog, const ref_run *r, const gib_ref_params *p,
                              double t0)
{
    const gib_ref_params *np = &r->c.p;
    memset(prog, 0, sizeof *prog);
    prog->enabled = !p->quiet;
    prog->tty = isatty(STDERR_FILENO);
    prog->what = gib_component_name(np->component);
    prog->t0 = t0;
    prog->units_per_spp = (r->c.camera_part ? (long long)np->width * np->height : 0) +
                          (r->c.light_part ? ref_light_particles(&r->c) : 0);
    prog->target = np->target_noise;
    prog->noise_rel = -1.0;
    atomic_init(&prog->units, 0);
    atomic_init(&prog->rays, 0);
    atomic_init(&prog->embree_ticks, 0);
}

int ref_round_end(ref_run *r, ref_tally *t, int *goal)
{
    const gib_ref_params *np = &r->c.p;
    t->n = *goal;
    ref_summary(r, t->n, &t->mean, &t->noise);
    double rel = t->mean > 0.0 ? t->noise / t->mean : (t->noise > 0.0 ? INFINITY : 0.0);
    ref_progress_round(r->prog, t->n, rel);
    if (!(np->target_noise > 0.0))
        return 1;
    t->reached = rel <= np->target_noise;
    if (t->reached || t->n >= np->max_spp)
        return 1;
    *goal = ref_next_goal(t->n, rel, np->target_noise, np->max_spp,
                          np->sampler == GIB_REF_SAMPLER_SOBOL);
    return 0;
}

int ref_run_setup(ref_run *r, const ref_world *w, const gib_scene *scene, const gib_ref_params *p,
                  ref_progress *prog, double t0, int nthreads, gib_error *err)
{
    memset(r, 0, sizeof *r);
    ref_ctx_init(&r->c, w, scene, p);
    r->prog = prog;
    ref_progress_init(prog, r, p, t0);
    ref_choose_strategies(r, nthreads);
    atomic_init(&r->abandoned, 0);
    return ref_run_alloc(r, err);
}

/* The rounds: each takes every pixel's samples up to its goal, until the target noise or
 * max_spp is reached, or an interrupt stops them (a round in progress is then undone). 0, or -1
 * with err filled. */
static int ref_rounds(ref_run *r, const gib_ref_params *p, int nthreads, ref_tally *t,
                      gib_error *err)
{
    ref_progress *prog = r->prog;
    const gib_ref_params *np = &r->c.p;
    int goal = np->spp;
    for (;;) {
        r->s0 = t->n;
        r->s1 = goal;
        prog->round = ++t->rounds;
        prog->spp_goal = goal;
        prog->units_target = (long long)goal * prog->units_per_spp;
        if (r->c.camera_part)
            ref_parallel(nthreads, np->height, ref_row_task, r, prog);
        if (r->c.light_part && ref_light_round(r, nthreads) < 0)
            return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                                 "reference: out of memory for light-tracing splats");
        if (atomic_load(&r->abandoned)) { /* interrupted: back to the last finished round */
            ref_run_saved(r, 0);
            t->rounds--;
            t->interrupted = 1;
            break;
        }
        int last = ref_round_end(r, t, &goal);
        if (p->interrupt)
            atomic_store(&p->interrupt->rounds_done, t->rounds);
        if (last)
            break;
        if (p->interrupt && atomic_load(&p->interrupt->requested)) {
            t->interrupted = 1;
            break;
        }
        if (r->saved) {
            ref_run_saved(r, 1);
            r->can_abandon = 1;
        }
    }
    ref_progress_end(prog);
    return 0;
}

void ref_write_images(const ref_run *r, int n, gib_image *out, gib_image *stderr_img)
{
    const size_t count = (size_t)r->c.p.width * r->c.p.height * 3;
    for (size_t i = 0; i < count; i++) {
        double v = r->cm[i] + (r->lm ? r->lm[i] : 0.0);
        out->px[i] = (float)v;
        if (stderr_img)
            stderr_img->px[i] = n > 1 ? (float)sqrt(ref_var_of_mean(r, i, n)) : 0.0f;
    }
}

void ref_fill_stats(gib_ref_stats *stats, const ref_run *r, const gib_scene *scene,
                    const gib_ref_params *p, const ref_tally *t)
{
    const ref_world *w = r->c.w;
    const gib_ref_params *np = &r->c.p;
    const ref_progress *prog = r->prog;
    memset(stats, 0, sizeof *stats);
    stats->mean = t->mean;
    stats->noise_rmse = t->noise;
    stats->rays = atomic_load(&prog->rays);
    stats->spp = t->n;
    stats->rounds = t->rounds;
    /* a target asked of a deterministic estimator is met: normalisation dropped it, the
     * noise is exactly 0 */
    stats->target_reached = np->target_noise > 0.0 ? t->reached : p->target_noise > 0.0;
    stats->interrupted = t->interrupted;
    stats->deterministic = ref_deterministic(scene, np->component, np->max_depth);
    stats->seconds = ref_now() - t->t0;
    stats->render_seconds = stats->seconds;
    stats->threads = prog->threads_used;
    stats->light_vertices = r->c.lv_on;
    stats->pilot_gain = r->pilot_gain;
    if (w->time_embree) { /* ticks to seconds at the rate the clock ran during this render,
                           * less the clock reads themselves (one pair a ray) */
        double k = (double)(ref_ticks() - t->k0), wall = ref_now() - t->t0;
        double ke = (double)(atomic_load(&prog->embree_ticks) +
                             (long long)ref_embree_ticks_take()) -
                    (double)stats->rays * ref_ticks_overhead();
        stats->embree_cpu_seconds = k > 0.0 && ke > 0.0 ? ke * wall / k : 0.0;
    }
}

int ref_render_world(const ref_world *w, const gib_scene *scene, const gib_ref_params *p,
                     gib_image *out, gib_image *stderr_img, gib_ref_stats *stats, gib_error *err)
{
    ref_tally t = {.t0 = ref_now()};
    t.k0 = w->time_embree ? ref_ticks() : 0;
    memset(out, 0, sizeof *out);
    if (stderr_img)
        memset(stderr_img, 0, sizeof *stderr_img);
    ref_run r;
    ref_progress prog;
    const int nthreads = ref_thread_count(p);
    int rc = -1;
    if (ref_run_setup(&r, w, scene, p, &prog, t.t0, nthreads, err) < 0)
        goto done;
    const int W = r.c.p.width, H = r.c.p.height;
    r.stop = p->interrupt;
    if (r.stop && r.c.p.target_noise > 0.0 &&
        !(r.saved = gib_calloc((size_t)W * H * 3 * (4 + GIB_REF_SOBOL_BATCHES), sizeof *r.saved,
                               err)))
        goto done;
    if (gib_image_alloc(out, W, H, 3, err) < 0 ||
        (stderr_img && gib_image_alloc(stderr_img, W, H, 3, err) < 0))
        goto done;
    if (ref_rounds(&r, p, nthreads, &t, err) < 0)
        goto done;
    ref_write_images(&r, t.n, out, stderr_img);
    if (stats)
        ref_fill_stats(stats, &r, scene, p, &t);
    rc = 0;

done:
    if (rc < 0) {
        gib_image_free(out);
        if (stderr_img)
            gib_image_free(stderr_img);
    }
    ref_run_free(&r);
    return rc;
}

int gib_reference_render(const gib_scene *scene, const gib_ref_params *p, gib_image *out,
                         gib_image *stderr_img, gib_ref_stats *stats, gib_error *err)
{
    if (ref_check_params(scene, p, err) < 0)
        return -1;
    double t0 = ref_now();
    /* A moving scene is rendered as it is at p->time: the world is built from its posed vertex
     * arrays (a static scene's are its own). */
    gib_scene posed;
    if (gib_scene_posed(scene, p->time, &posed, err) < 0)
        return gib_error_prefix(err, "reference");
    ref_world w;
    if (ref_world_build(&w, &posed, err) < 0) {
        gib_scene_posed_free(&posed);
        return gib_error_prefix(err, "reference");
    }
    int rc = ref_render_world(&w, &posed, p, out, stderr_img, stats, err);
    ref_world_free(&w);
    gib_scene_posed_free(&posed);
    if (rc == 0 && stats)
        stats->seconds = ref_now() - t0; /* the BVH build included */
    return rc;
}

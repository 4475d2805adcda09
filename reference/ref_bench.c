/* gibench — the reference renderer's throughput benchmark (gibench bench reference).
 *
 * Six figures on one scene and one BVH, all threads:
 *  - raw_random: rtcIntersect1 on random incoherent rays (origins uniform in the scene's bounding
 *    box, directions uniform on the sphere): Embree's own speed, nothing else;
 *  - raw_diffuse: rtcIntersect1 on Aila and Laine's "diffuse" rays (ref_diffuse_log): random
 *    incoherent rays as the ray-tracing literature measures them, leaving visible surfaces;
 *  - raw_replay: the path tracer's own rays — recorded from a single-threaded render of the same
 *    component at a lower resolution, closest-hit and shadow rays as cast — replayed with each
 *    ray API: single rays (rtcIntersect1 / rtcOccluded1), streams (rtcIntersect1M /
 *    rtcOccluded1M, 256 rays per call) and packets of 4, 8 and 16 (consecutive rays of one kind);
 *  - path_tracer: the renderer itself (sampling, shading, textures, statistics; BVH, triangle
 *    records and mip maps prebuilt, their time is the world_build row), rays per second over all
 *    the rays it casts.
 *  - path_tracer_embree: the time the path tracer spends inside Embree's ray calls (a second
 *    render with a clock read around each): Embree's speed inside the renderer. Its paired ratio
 *    to the replay (same rays) is how much the renderer's memory traffic slows Embree down; the
 *    path tracer's time less this one is the renderer's own work.
 *  - lean_tracer and lean_replay (component `full`, scenes without a sky or mirrors): the lean
 *    tracer (ref_bench_lean.c: the path tracer's kind of rays with as little other work as a
 *    path allows) and its own rays replayed with each API; the lean rows' paired ratios are over
 *    the fastest replay of the lean tracer's rays. The lean tracer's ratio is the reference point
 *    for the path tracer's: what a renderer that does almost nothing but trace these paths
 *    reaches on this machine and scene.
 * The yardstick for the path tracer is the replay, the same rays with nothing else done; the other
 * two raw figures place the scene among published figures (reference/PERFORMANCE.md, "The
 * yardsticks").
 * Nothing here is asserted: performance is measured, reported and written to CSV, never a test's
 * pass/fail condition. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ref_internal.h"

#define REF_BENCH_CHUNK 4096
#define REF_BENCH_RANDOM_RAYS (4 << 20)

typedef struct ref_replay {
    const ref_world *w;
    const ref_raylog *log;
    int api;                 /* 1: single, 0: stream, 4/8/16: packets */
    atomic_llong hits;       /* keeps the work observable */
} ref_replay;

static void ref_replay_single(const ref_replay *rp, size_t a, size_t b, long long *hits)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (size_t i = a; i < b; i++) {
        if (rp->log->occl[i]) {
            struct RTCRay r = rp->log->rays[i];
            rtcOccluded1(rp->w->scene, &ctx, &r);
            *hits += r.tfar < 0.0f;
        } else {
            struct RTCRayHit rh;
            rh.ray = rp->log->rays[i];
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(rp->w->scene, &ctx, &rh);
            *hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
    }
}

static void ref_replay_stream(const ref_replay *rp, size_t a, size_t b, long long *hits)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    struct RTCRayHit rh[256];
    struct RTCRay ro[256];
    size_t i = a;
    while (i < b) {
        unsigned nh = 0, no = 0;
        for (; i < b && nh < 256 && no < 256; i++) {
            if (rp->log->occl[i]) {
                ro[no++] = rp->log->rays[i];
            } else {
                rh[nh].ray = rp->log->rays[i];
                rh[nh].hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh[nh++].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            }
        }
        if (nh)
            rtcIntersect1M(rp->w->scene, &ctx, rh, nh, sizeof rh[0]);
        if (no)
            rtcOccluded1M(rp->w->scene, &ctx, ro, no, sizeof ro[0]);
        for (unsigned k = 0; k < nh; k++)
            *hits += rh[k].hit.geomID != RTC_INVALID_GEOMETRY_ID;
        for (unsigned k = 0; k < no; k++)
            *hits += ro[k].tfar < 0.0f;
    }
}

/* Packets of width K from consecutive rays of one kind (SOA structs of rtcore_ray.h). */
#define REF_PACKET_FN(K)                                                                           \
    static void ref_replay_p##K(const ref_replay *rp, size_t a, size_t b, long long *hits)         \
    {                                                                                              \
        struct RTCIntersectContext ctx;                                                            \
        rtcInitIntersectContext(&ctx);                                                             \
        struct RTCRayHit##K rh;                                                                    \
        struct RTCRay##K ro;                                                                       \
        _Alignas(64) int valid[K]; /* Embree reads it as one aligned vector */                     \
        memset(&rh, 0, sizeof rh); /* inactive lanes hold a valid (empty) ray too */               \
        memset(&ro, 0, sizeof ro);                                                                 \
        size_t i = a;                                                                              \
        while (i < b) {                                                                            \
            int occl = rp->log->occl[i], n = 0;                                                    \
            for (; i < b && n < K && rp->log->occl[i] == occl; i++, n++) {                         \
                const struct RTCRay *r = &rp->log->rays[i];                                        \
                struct RTCRay##K *d = occl ? &ro : &rh.ray;                                        \
                d->org_x[n] = r->org_x, d->org_y[n] = r->org_y, d->org_z[n] = r->org_z;            \
                d->dir_x[n] = r->dir_x, d->dir_y[n] = r->dir_y, d->dir_z[n] = r->dir_z;            \
                d->tnear[n] = r->tnear, d->tfar[n] = r->tfar, d->time[n] = 0.0f;                   \
                d->mask[n] = r->mask, d->id[n] = 0, d->flags[n] = 0;                               \
                rh.hit.geomID[n] = RTC_INVALID_GEOMETRY_ID;                                        \
                rh.hit.instID[0][n] = RTC_INVALID_GEOMETRY_ID;                                     \
                valid[n] = -1;                                                                     \
            }                                                                                      \
            for (int k = n; k < K; k++)                                                            \
                valid[k] = 0;                                                                      \
            if (occl) {                                                                            \
                rtcOccluded##K(valid, rp->w->scene, &ctx, &ro);                                    \
                for (int k = 0; k < n; k++)                                                        \
                    *hits += ro.tfar[k] < 0.0f;                                                    \
            } else {                                                                               \
                rtcIntersect##K(valid, rp->w->scene, &ctx, &rh);                                   \
                for (int k = 0; k < n; k++)                                                        \
                    *hits += rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;                          \
            }                                                                                      \
        }                                                                                          \
    }
REF_PACKET_FN(4)
REF_PACKET_FN(8)
REF_PACKET_FN(16)

static void ref_replay_task(void *ctx, int task)
{
    ref_replay *rp = ctx;
    size_t a = (size_t)task * REF_BENCH_CHUNK, b = a + REF_BENCH_CHUNK;
    if (b > rp->log->n)
        b = rp->log->n;
    long long hits = 0;
    switch (rp->api) {
    case 0: ref_replay_stream(rp, a, b, &hits); break;
    case 4: ref_replay_p4(rp, a, b, &hits); break;
    case 8: ref_replay_p8(rp, a, b, &hits); break;
    case 16: ref_replay_p16(rp, a, b, &hits); break;
    default: ref_replay_single(rp, a, b, &hits);
    }
    atomic_fetch_add(&rp->hits, hits);
}

static void ref_row(gib_ref_bench_row *row, const char *measure, const char *api, long long rays,
                    double seconds)
{
    memset(row, 0, sizeof *row);
    snprintf(row->measure, sizeof row->measure, "%s", measure);
    snprintf(row->api, sizeof row->api, "%s", api);
    row->rays = rays;
    row->seconds = seconds;
    row->mrays_per_s = seconds > 0.0 ? (double)rays / seconds * 1e-6 : 0.0;
}

static int ref_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sorts v[0..n) (n >= 1); returns the least, with the median and the greatest. */
static double ref_sorted_stats(double *v, int n, double *median, double *max)
{
    qsort(v, (size_t)n, sizeof *v, ref_cmp_double);
    *median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    *max = v[n - 1];
    return v[0];
}

/* Random rays: origins uniform in the bounding box, directions uniform on the sphere. */
static int ref_random_log(const ref_world *w, ref_raylog *log, gib_error *err)
{
    const gib_scene *gs = w->gs;
    log->n = log->cap = REF_BENCH_RANDOM_RAYS;
    log->rays = malloc(log->n * sizeof *log->rays);
    log->occl = calloc(log->n, 1);
    if (!log->rays || !log->occl)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "bench: out of memory for %zu random rays", log->n);
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = 0; i < gs->vertex_count; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], gs->positions[3 * (size_t)i + k]);
            hi[k] = fmaxf(hi[k], gs->positions[3 * (size_t)i + k]);
        }
    ref_pcg32 rng;
    ref_pcg32_seed(&rng, 12345u, 678u);
    for (size_t i = 0; i < log->n; i++) {
        float o[3], z = 1.0f - 2.0f * ref_pcg32_float(&rng), phi = 2.0f * REF_PI * ref_pcg32_float(&rng);
        float s = sqrtf(fmaxf(0.0f, 1.0f - z * z)), d[3] = {s * cosf(phi), s * sinf(phi), z};
        for (int k = 0; k < 3; k++)
            o[k] = lo[k] + (hi[k] - lo[k]) * ref_pcg32_float(&rng);
        ref_ray_init(&log->rays[i], o, d, INFINITY);
    }
    return 0;
}

/* Diffuse rays, the incoherent workload of Aila and Laine 2009 ("Understanding the Efficiency of
 * Ray Traversal on GPUs", HPG; primary, ambient-occlusion and diffuse rays): from the visible
 * point of a random position in the image, a cosine-distributed direction about the geometric
 * normal facing the camera, closest hit, unbounded. Unlike bounding-box rays, every origin is on
 * a surface the camera sees, as a path tracer's bounce rays are (pixels whose primary ray
 * misses draw again). The primary rays themselves are cast here, not timed. */
static int ref_diffuse_log(const ref_world *w, const gib_ref_params *p, ref_raylog *log,
                           gib_error *err)
{
    const gib_camera *cam = &w->gs->cameras[p->camera];
    log->n = log->cap = REF_BENCH_RANDOM_RAYS;
    log->rays = malloc(log->n * sizeof *log->rays);
    log->occl = calloc(log->n, 1);
    if (!log->rays || !log->occl)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "bench: out of memory for %zu diffuse rays", log->n);
    ref_pcg32 rng;
    ref_pcg32_seed(&rng, 24680u, 1357u);
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    size_t i = 0;
    for (long tries = 0; i < log->n; tries++) {
        if (tries >= (1l << 20) && (long)i < tries / 100) /* under 1% of the image */
            return gib_fail(err, "bench: camera %d of '%s' sees (almost) no surface: no "
                                 "diffuse rays", p->camera, w->gs->name);
        float o[3], d[3];
        gib_camera_ray(cam, p->width, p->height, ref_pcg32_float(&rng) * (float)p->width,
                       ref_pcg32_float(&rng) * (float)p->height, o, d);
        struct RTCRayHit rh;
        ref_ray_init(&rh.ray, o, d, INFINITY);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(w->scene, &ctx, &rh);
        float u1 = ref_pcg32_float(&rng), u2 = ref_pcg32_float(&rng);
        float n[3] = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
        float len = sqrtf(ref_dot(n, n));
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || !(len > 0.0f))
            continue;
        float side = ref_dot(n, d) > 0.0f ? -1.0f / len : 1.0f / len, dir[3], org[3];
        for (int k = 0; k < 3; k++)
            n[k] *= side;
        ref_sample_cosine(n, u1, u2, dir);
        for (int k = 0; k < 3; k++)
            org[k] = o[k] + rh.ray.tfar * d[k] + w->eps * n[k];
        ref_ray_init(&log->rays[i++], org, dir, INFINITY);
    }
    return 0;
}

static double ref_replay_run(const ref_world *w, const ref_raylog *log, int api, int threads)
{
    ref_replay rp = {.w = w, .log = log, .api = api};
    atomic_init(&rp.hits, 0);
    int tasks = (int)((log->n + REF_BENCH_CHUNK - 1) / REF_BENCH_CHUNK);
    double t0 = ref_now();
    ref_parallel(threads, tasks, ref_replay_task, &rp, NULL);
    return ref_now() - t0;
}

static const struct {
    int api;
    const char *name;
} ref_apis[] = {{1, "rtcIntersect1"}, {0, "rtcIntersect1M"}, {4, "rtcIntersect4"},
                {8, "rtcIntersect8"}, {16, "rtcIntersect16"}};
enum { NAPI = sizeof ref_apis / sizeof ref_apis[0] };
/* The measures in the CSV's order; the lean tracer's rows last, where it applies
 * (ref_lean_applies). */
enum { M_PT, M_PTE, M_RND, M_DIF, M_API, M_LEAN = M_API + NAPI, M_LAPI, NM = M_LAPI + NAPI };

/* What the benchmark's steps share: the world, the ray logs and every repeat's times. */
typedef struct ref_bench_run {
    const gib_scene *scene;
    const gib_ref_params *p;     /* &fixed once the strategies are chosen */
    gib_ref_params fixed;        /* the request with full's strategies fixed (ref_bench_record) */
    ref_world w;
    int threads, lean, reps;
    ref_raylog rnd, dif, rec, lrec; /* random, diffuse, the path tracer's and the lean tracer's */
    double t[NM][GIB_REF_BENCH_MAX_REPEATS];
    double best_replay[GIB_REF_BENCH_MAX_REPEATS], best_lean[GIB_REF_BENCH_MAX_REPEATS];
    long long nrays[NM];
    FILE *log;
    gib_error *err;
} ref_bench_run;

/* The ray logs: the path tracer's rays, recorded single-threaded at a resolution that gives ~3M
 * rays, the lean tracer's at the same size, the random and the diffuse rays. */
static int ref_bench_record(ref_bench_run *b)
{
    const gib_ref_params *p = b->p;
    gib_image img = {0};
    gib_ref_stats st;
    gib_ref_params q = *p;
    q.quiet = 1;
    q.threads = 1;
    if (ref_render_world(&b->w, b->scene, &q, &img, NULL, &st, b->err) < 0) /* also warms caches */
        return -1;
    gib_image_free(&img);
    /* the strategies this render chose (its pilot, at the bench's size) for every later render,
     * the recorded rays' smaller one included, and the lean tracer */
    b->fixed = *p;
    b->fixed.strategies = st.light_vertices ? GIB_REF_STRATEGIES_LIGHT_VERTICES
                                            : GIB_REF_STRATEGIES_CAMERA;
    b->p = p = &b->fixed;
    q.strategies = b->fixed.strategies;
    double scale = sqrt(3e6 / fmax((double)st.rays, 1.0));
    q.width = scale < 1.0 ? (int)fmax(8.0, p->width * scale) : p->width;
    q.height = scale < 1.0 ? (int)fmax(8.0, p->height * scale) : p->height;
    b->w.log = &b->rec;
    int ok = ref_render_world(&b->w, b->scene, &q, &img, NULL, NULL, b->err);
    gib_image_free(&img);
    long long lean_rays = 0;
    b->w.log = &b->lrec; /* the lean tracer's rays, at the same size */
    double lean_t = ok == 0 && b->lean ? ref_lean_render(&b->w, &q, 1, &lean_rays) : 0.0;
    b->w.log = NULL;
    if (ok == 0 && b->lean && (lean_t < 0.0 || lean_rays == 0 || b->lrec.n != (size_t)lean_rays))
        return gib_fail(b->err, "bench: the lean tracer %s (%zu rays logged of %lld)",
                        lean_t < 0.0 ? "ran out of memory"
                                     : "cast no ray, or its ray log is incomplete",
                        b->lrec.n, lean_rays);
    if (ok < 0 || ref_random_log(&b->w, &b->rnd, b->err) < 0 ||
        ref_diffuse_log(&b->w, p, &b->dif, b->err) < 0)
        return -1;
    return 0;
}

/* Repeat rep's path tracer rows: the render, and the same render again with the time inside
 * Embree's calls counted (not in the path_tracer row: the clock reads cost ~2% of it): Embree's
 * own speed inside the path tracer, whose paired ratio to the replay's shows how much the
 * renderer's memory traffic slows Embree down. CPU seconds over threads, the replay's wall
 * time's equivalent. */
static int ref_bench_path_tracer(ref_bench_run *b, int rep, gib_ref_stats *st)
{
    gib_image img = {0};
    gib_ref_params q = *b->p;
    q.quiet = 1;
    if (ref_render_world(&b->w, b->scene, &q, &img, NULL, st, b->err) < 0)
        return -1;
    gib_image_free(&img);
    b->t[M_PT][rep] = st->seconds;
    b->nrays[M_PT] = st->rays;
    b->w.time_embree = 1;
    gib_ref_stats ste;
    int te = ref_render_world(&b->w, b->scene, &q, &img, NULL, &ste, b->err);
    b->w.time_embree = 0;
    if (te < 0)
        return -1;
    gib_image_free(&img);
    if (!(ste.embree_cpu_seconds > 0.0) || ste.threads < 1)
        return gib_fail(b->err, "bench: the time inside Embree's calls could not be measured "
                                "(%.3g s on %d threads; calls cheaper than the clock reads?)",
                        ste.embree_cpu_seconds, ste.threads);
    b->t[M_PTE][rep] = ste.embree_cpu_seconds / ste.threads; /* the threads it really ran */
    b->nrays[M_PTE] = ste.rays;
    return 0;
}

/* One repeat: every measure once. */
static int ref_bench_repeat(ref_bench_run *b, int rep)
{
    gib_ref_stats st;
    if (ref_bench_path_tracer(b, rep, &st) < 0)
        return -1;
    b->t[M_RND][rep] = ref_replay_run(&b->w, &b->rnd, 1, b->threads);
    b->t[M_DIF][rep] = ref_replay_run(&b->w, &b->dif, 1, b->threads);
    double best = INFINITY;
    for (int i = 0; i < NAPI; i++) {
        b->t[M_API + i][rep] = ref_replay_run(&b->w, &b->rec, ref_apis[i].api, b->threads);
        best = fmin(best, b->t[M_API + i][rep]);
    }
    b->best_replay[rep] = best;
    b->best_lean[rep] = INFINITY;
    if (b->lean) {
        b->t[M_LEAN][rep] = ref_lean_render(&b->w, b->p, b->threads, &b->nrays[M_LEAN]);
        if (b->t[M_LEAN][rep] < 0.0)
            return gib_fail(b->err, "bench: the lean tracer ran out of memory");
        for (int i = 0; i < NAPI; i++) {
            b->t[M_LAPI + i][rep] = ref_replay_run(&b->w, &b->lrec, ref_apis[i].api, b->threads);
            b->best_lean[rep] = fmin(b->best_lean[rep], b->t[M_LAPI + i][rep]);
        }
    }
    if (b->log) {
        fprintf(b->log, "bench: repeat %d: path tracer %.3f s, replay (fastest API) %.3f s, "
                        "paired ratio %.3f",
                rep + 1, st.seconds, best,
                ((double)st.rays / st.seconds) / ((double)b->rec.n / best));
        if (b->lean)
            fprintf(b->log, "; lean tracer's %.4f",
                    ((double)b->nrays[M_LEAN] / b->t[M_LEAN][rep]) /
                        ((double)b->lrec.n / b->best_lean[rep]));
        fputc('\n', b->log);
    }
    return 0;
}

/* Measure m's row: the best, median and worst time of the repeats, and the paired ratios. */
static void ref_bench_row(const ref_bench_run *b, int m, gib_ref_bench_row *row)
{
    const char *measure = m == M_PT     ? "path_tracer"
                          : m == M_PTE  ? "path_tracer_embree"
                          : m == M_RND  ? "raw_random"
                          : m == M_DIF  ? "raw_diffuse"
                          : m == M_LEAN ? "lean_tracer"
                          : m > M_LEAN  ? "lean_replay"
                                        : "raw_replay";
    const char *api = m <= M_DIF || m == M_LEAN ? "rtcIntersect1"
                      : m > M_LEAN               ? ref_apis[m - M_LAPI].name
                                                 : ref_apis[m - M_API].name;
    int of_lean = m >= M_LEAN; /* paired with the fastest replay of the lean tracer's rays */
    double sec[GIB_REF_BENCH_MAX_REPEATS], pair[GIB_REF_BENCH_MAX_REPEATS];
    for (int rep = 0; rep < b->reps; rep++) {
        sec[rep] = b->t[m][rep];
        pair[rep] = ((double)b->nrays[m] / b->t[m][rep]) /
                    ((double)(of_lean ? b->lrec.n : b->rec.n) /
                     (of_lean ? b->best_lean : b->best_replay)[rep]);
    }
    double med, max, best = ref_sorted_stats(sec, b->reps, &med, &max);
    ref_row(row, measure, api, b->nrays[m], best);
    row->seconds_median = med, row->seconds_max = max;
    row->paired_min = ref_sorted_stats(pair, b->reps, &row->paired_median, &row->paired_max);
    row->repeats = b->reps;
}

/* After the world_build row: the ray logs, then `repeats` rounds, each running every measure
 * once, interleaved: the machine may be shared and its speed drifts (on the 2-core virtual
 * machine of the committed results, one run's repeats spread by +-10% while the ratio of two
 * measures within a repeat moves less). Each row keeps the best time (the run least disturbed),
 * the median and the worst, and the paired ratios: the row's rays/s over the fastest replay's in
 * the same repeat. Returns the row count, or -1. */
static int ref_bench_measure(ref_bench_run *b, gib_ref_bench_row *rows, int n, int max_rows)
{
    if (ref_bench_record(b) < 0)
        return -1;
    const int nm = b->lean ? NM : M_LEAN;
    b->nrays[M_RND] = (long long)b->rnd.n;
    b->nrays[M_DIF] = (long long)b->dif.n;
    for (int i = 0; i < NAPI; i++) {
        b->nrays[M_API + i] = (long long)b->rec.n;
        b->nrays[M_LAPI + i] = (long long)b->lrec.n;
    }
    b->nrays[M_LEAN] = 0;
    for (int rep = 0; rep < b->reps; rep++)
        if (ref_bench_repeat(b, rep) < 0)
            return -1;
    for (int m = 0; m < nm && n < max_rows; m++)
        ref_bench_row(b, m, &rows[n++]);
    return n;
}

int gib_reference_bench(const gib_scene *scene, const gib_ref_params *p, int repeats, FILE *log,
                        gib_ref_bench_row *rows, int max_rows, gib_error *err)
{
    if (ref_check_params(scene, p, err) < 0)
        return -1;
    if (scene->triangle_count == 0)
        return gib_fail(err, "bench: scene '%s' has no triangles", scene->name);
    if (repeats > GIB_REF_BENCH_MAX_REPEATS)
        return gib_fail(err, "bench: at most %d repeats, got %d", GIB_REF_BENCH_MAX_REPEATS,
                        repeats);
    ref_bench_run run, *b = &run;
    memset(b, 0, sizeof *b);
    b->scene = scene;
    b->p = p;
    b->log = log;
    b->err = err;
    b->threads = p->threads > 0 ? p->threads : (int)sysconf(_SC_NPROCESSORS_ONLN);
    b->threads = b->threads < 1 ? 1 : b->threads;
    b->lean = ref_lean_applies(scene, p->component); /* `full`'s kind of paths */
    b->reps = repeats < 1 ? 1 : repeats;
    double t0 = ref_now();
    if (ref_world_build(&b->w, scene, err) < 0)
        return gib_error_prefix(err, "bench");
    double build = ref_now() - t0;
    int rc = -1;
    if (max_rows >= 1) {
        ref_row(&rows[0], "world_build", "rtcCommitScene", 0, build);
        rows[0].repeats = 1;
        rows[0].seconds_median = rows[0].seconds_max = build;
        rc = ref_bench_measure(b, rows, 1, max_rows);
    }
    ref_raylog *logs[] = {&b->rnd, &b->dif, &b->rec, &b->lrec};
    for (int i = 0; i < 4; i++) {
        free(logs[i]->rays);
        free(logs[i]->occl);
    }
    ref_world_free(&b->w);
    return rc;
}

/* gibench — the reference renderer's render loop: primary rays through pixel centres, per-pixel
 * sampling and statistics, threads, progress, and the EXR attributes (DESIGN.md, "Reference
 * renderer").
 *
 * Determinism: a pixel's samples come from its own PCG32 (rng.h) and are accumulated in sample
 * order by one thread; image-wide sums are formed per row and added in row order at the end. So
 * the image, its standard error and the statistics are bit-identical whatever the thread count
 * and whichever thread took which row. */
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

#include "../harness/base/hash.h"
#include "ref_internal.h"

#define REF_MAX_THREADS 256
#define REF_MAX_SIZE 32768

static const char *const ref_component_names[GIB_COMP_COUNT] = {"ao", "direct"};

const char *gib_component_name(int component)
{
    if (component < 0 || component >= GIB_COMP_COUNT)
        return "unknown";
    return ref_component_names[component];
}

int gib_component_parse(const char *name)
{
    for (int i = 0; name && i < GIB_COMP_COUNT; i++)
        if (strcmp(name, ref_component_names[i]) == 0)
            return i;
    return -1;
}

static double ref_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct ref_job {
    const ref_world *w;
    const gib_camera *cam;
    const gib_ref_params *p;
    float *out, *sd;        /* sd may be NULL */
    double *row_sum;        /* per row: sum over pixels and channels of the pixel mean */
    double *row_var;        /* per row: sum over pixels and channels of variance / spp */
    long long *row_rays;
    atomic_int next_row;
    atomic_int rows_done;
    atomic_llong rays_done; /* for progress only */
} ref_job;

static void ref_render_row(ref_job *j, int y)
{
    const gib_ref_params *p = j->p;
    const int W = p->width, H = p->height;
    long long rays = 0;
    double sum = 0.0, var_sum = 0.0;
    for (int x = 0; x < W; x++) {
        size_t pix = (size_t)y * (size_t)W + (size_t)x;
        float o[3], d[3];
        /* Pixel centres only, no jitter: the GL techniques rasterise there without anti-aliasing,
         * so both sides see the same surface point and the error measures light transport, not
         * aliasing. */
        gib_camera_ray(j->cam, W, H, (float)x + 0.5f, (float)y + 0.5f, o, d);
        ++rays;
        double mean[3] = {0.0, 0.0, 0.0}, m2[3] = {0.0, 0.0, 0.0};
        ref_hit h;
        if (ref_trace(j->w, o, d, &h) && !h.back) {
            float wo[3] = {-d[0], -d[1], -d[2]};
            ref_pcg32 rng;
            ref_pcg32_seed_pixel(&rng, pix, p->seed, p->component);
            for (int s = 1; s <= p->spp; s++) {
                float v[3];
                if (p->component == GIB_COMP_DIRECT) {
                    ref_est_direct(j->w, &h, wo, v, &rays);
                } else {
                    v[0] = v[1] = v[2] = ref_est_ao(j->w, &h, p->dmax, &rng, &rays);
                }
                for (int c = 0; c < 3; c++) { /* Welford: stable for any spp */
                    double delta = (double)v[c] - mean[c];
                    mean[c] += delta / s;
                    m2[c] += delta * ((double)v[c] - mean[c]);
                }
            }
        } /* a miss, or the back of a one-sided surface: 0 in every component, exactly */
        for (int c = 0; c < 3; c++) {
            /* Sample variance (n - 1); with one sample it is unknown and reported as 0. */
            double var = p->spp > 1 ? m2[c] / (p->spp - 1) : 0.0;
            j->out[pix * 3 + c] = (float)mean[c];
            if (j->sd)
                j->sd[pix * 3 + c] = (float)sqrt(var / p->spp);
            sum += mean[c];
            var_sum += var / p->spp;
        }
    }
    j->row_sum[y] = sum;
    j->row_var[y] = var_sum;
    j->row_rays[y] = rays;
}

static void *ref_worker(void *arg)
{
    ref_job *j = arg;
#if defined(__x86_64__) || defined(__i386__)
    /* Flush denormals to zero, as Embree recommends for speed; every worker sets the same mode,
     * so results stay independent of the thread count. */
    unsigned csr = _mm_getcsr();
    _mm_setcsr(csr | 0x8040);
#endif
    for (;;) {
        int y = atomic_fetch_add(&j->next_row, 1);
        if (y >= j->p->height)
            break;
        ref_render_row(j, y);
        atomic_fetch_add(&j->rays_done, j->row_rays[y]);
        atomic_fetch_add(&j->rows_done, 1);
    }
#if defined(__x86_64__) || defined(__i386__)
    _mm_setcsr(csr); /* the caller's thread may run this too: give its FP mode back */
#endif
    return NULL;
}

static void ref_progress(ref_job *j, double t0)
{
    int rows = atomic_load(&j->rows_done);
    long long rays = atomic_load(&j->rays_done);
    double el = ref_now() - t0;
    double rate = el > 0.0 ? (double)rays / el : 0.0;
    char left[32] = "?";
    if (rows > 0)
        snprintf(left, sizeof left, "%.0f", el * (double)(j->p->height - rows) / rows);
    fprintf(stderr, "\rreference %s: %d/%d rows, %.2f Mrays/s, %s s left   ",
            gib_component_name(j->p->component), rows, j->p->height, rate * 1e-6, left);
    fflush(stderr);
}

static int ref_check_params(const gib_scene *scene, const gib_ref_params *p, gib_error *err)
{
    if (!scene || !p)
        return gib_fail(err, "reference: no scene or no parameters");
    if (p->component < 0 || p->component >= GIB_COMP_COUNT)
        return gib_fail(err, "reference: unknown component %d (expected ao or direct)",
                        p->component);
    if (p->width < 1 || p->height < 1 || p->width > REF_MAX_SIZE || p->height > REF_MAX_SIZE)
        return gib_fail(err, "reference: image size %dx%d out of range (1 to %d)", p->width,
                        p->height, REF_MAX_SIZE);
    if (p->spp < 1)
        return gib_fail(err, "reference: spp must be at least 1, got %d", p->spp);
    if (p->threads < 0)
        return gib_fail(err, "reference: threads must be >= 0 (0 = all cores), got %d",
                        p->threads);
    if (isnan(p->dmax))
        return gib_fail(err, "reference: dmax is NaN");
    if (p->camera < 0 || (uint32_t)p->camera >= scene->camera_count || !scene->cameras)
        return gib_fail(err, "reference: scene '%s' has %u camera(s), camera %d asked for",
                        scene->name, scene->camera_count, p->camera);
    return 0;
}

static int ref_thread_count(const gib_ref_params *p)
{
    long n = p->threads > 0 ? p->threads : sysconf(_SC_NPROCESSORS_ONLN);
    if (n < 1)
        n = 1;
    if (n > REF_MAX_THREADS)
        n = REF_MAX_THREADS;
    if (n > p->height)
        n = p->height;
    return (int)n;
}

int gib_reference_render(const gib_scene *scene, const gib_ref_params *p, gib_image *out,
                         gib_image *stderr_img, gib_ref_stats *stats, gib_error *err)
{
    if (ref_check_params(scene, p, err) < 0)
        return -1;
    double t0 = ref_now();
    memset(out, 0, sizeof *out);
    if (stderr_img)
        memset(stderr_img, 0, sizeof *stderr_img);

    ref_world w;
    if (ref_world_build(&w, scene, err) < 0)
        return gib_error_prefix(err, "reference");

    ref_job *j = gib_calloc(1, sizeof *j, err);
    double *rows = gib_calloc(2 * (size_t)p->height, sizeof *rows, err);
    long long *row_rays = gib_calloc((size_t)p->height, sizeof *row_rays, err);
    pthread_t *tid = NULL;
    int nthreads = ref_thread_count(p), started = 0, rc = -1;
    if (!j || !rows || !row_rays)
        goto done;
    tid = gib_calloc((size_t)nthreads, sizeof *tid, err);
    if (!tid)
        goto done;
    if (gib_image_alloc(out, p->width, p->height, 3, err) < 0)
        goto done;
    if (stderr_img && gib_image_alloc(stderr_img, p->width, p->height, 3, err) < 0)
        goto done;

    j->w = &w;
    j->cam = &scene->cameras[p->camera];
    j->p = p;
    j->out = out->px;
    j->sd = stderr_img ? stderr_img->px : NULL;
    j->row_sum = rows;
    j->row_var = rows + p->height;
    j->row_rays = row_rays;
    atomic_init(&j->next_row, 0);
    atomic_init(&j->rows_done, 0);
    atomic_init(&j->rays_done, 0);

    for (int i = 0; i < nthreads; i++) {
        if (pthread_create(&tid[i], NULL, ref_worker, j) != 0)
            break; /* fewer threads is slower, not wrong */
        started++;
    }
    if (started == 0)
        ref_worker(j);

    int progress = !p->quiet && isatty(STDERR_FILENO), printed = 0;
    if (progress && started > 0) {
        double last = ref_now(); /* first line after 0.25 s: short renders stay silent */
        while (atomic_load(&j->rows_done) < p->height) {
            struct timespec nap = {0, 20 * 1000 * 1000};
            nanosleep(&nap, NULL);
            double now = ref_now();
            if (now - last >= 0.25) {
                ref_progress(j, t0);
                printed = 1;
                last = now;
            }
        }
    }
    for (int i = 0; i < started; i++)
        pthread_join(tid[i], NULL);
    if (printed) /* leave the line clean for the caller's own log line */
        fprintf(stderr, "\r%78s\r", "");

    double sum = 0.0, var = 0.0;
    long long rays = 0;
    for (int y = 0; y < p->height; y++) { /* row order: the same sums for any thread count */
        sum += j->row_sum[y];
        var += j->row_var[y];
        rays += j->row_rays[y];
    }
    double n = 3.0 * (double)p->width * (double)p->height;
    if (stats) {
        stats->mean = sum / n;
        stats->noise_rmse = sqrt(var / n);
        stats->rays = rays;
        stats->seconds = ref_now() - t0;
    }
    rc = 0;

done:
    if (rc < 0) {
        gib_image_free(out);
        if (stderr_img)
            gib_image_free(stderr_img);
    }
    free(tid);
    free(row_rays);
    free(rows);
    free(j);
    ref_world_free(&w);
    return rc;
}

/* ---- EXR header attributes ---- */

static int ref_attr(gib_kv *attrs, int max, int *n, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

static int ref_attr(gib_kv *attrs, int max, int *n, const char *key, const char *fmt, ...)
{
    if (*n >= max)
        return -1;
    gib_kv *kv = &attrs[*n];
    snprintf(kv->key, sizeof kv->key, "%s", key);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(kv->value, sizeof kv->value, fmt, ap);
    va_end(ap);
    ++*n;
    return 0;
}

int gib_reference_attrs(const gib_scene *scene, const gib_ref_params *p, const gib_ref_stats *s,
                        gib_kv *attrs, int max_attrs)
{
    int n = 0;
    char hex[17];
    gib_hash_hex(scene ? scene->content_hash : 0, hex);
    /* dmax <= 0 and dmax = inf give the same image, so they are written alike. */
    int unbounded = !(p->dmax > 0.0f) || isinf(p->dmax);
    ref_attr(attrs, max_attrs, &n, "component", "%s", gib_component_name(p->component));
    ref_attr(attrs, max_attrs, &n, "spp", "%d", p->spp);
    ref_attr(attrs, max_attrs, &n, "seconds", "%.3f", s ? s->seconds : 0.0);
    ref_attr(attrs, max_attrs, &n, "scene_hash", "%s", hex);
    ref_attr(attrs, max_attrs, &n, "renderer_version", "%s", GIB_REFERENCE_VERSION);
    ref_attr(attrs, max_attrs, &n, "noise_rmse", "%.9g", s ? s->noise_rmse : 0.0);
    ref_attr(attrs, max_attrs, &n, "mean", "%.9g", s ? s->mean : 0.0);
    ref_attr(attrs, max_attrs, &n, "width", "%d", p->width);
    ref_attr(attrs, max_attrs, &n, "height", "%d", p->height);
    if (unbounded)
        ref_attr(attrs, max_attrs, &n, "dmax", "%s", "inf");
    else
        ref_attr(attrs, max_attrs, &n, "dmax", "%.9g", (double)p->dmax);
    ref_attr(attrs, max_attrs, &n, "seed", "%llu", (unsigned long long)p->seed);
    ref_attr(attrs, max_attrs, &n, "camera", "%d", p->camera);
    return n;
}

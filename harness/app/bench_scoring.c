/* gibench bench scoring — what scoring one row costs on the CPU, by thread count: each metric
 * alone and the whole row (gib_score_pair, with and without its images), on a synthetic HDR pair
 * (a reference and a biased, noisy test image) or on two EXRs, repeated, printed and written to
 * CSV with the machine and the revision. Each metric's value is in the CSV beside its time, so a
 * run also shows that the thread count changes no number. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "app.h"
#include "bench_scoring.h"
#include "harness/base/hash.h"
#include "harness/imaging/flip.h"
#include "harness/imaging/score.h"
#include "options.h"

static const gib_command_doc doc = {
    "bench", "scoring [options]",
    "Times the scoring of one row on the CPU (harness/imaging/score.h) at each thread count\n"
    "of --threads (default 1 and every core): `errors` (RMSE and its scales), `metrics`\n"
    "(those and SSIM), `flip_ldr`, `flip_hdr`, `row` (every metric once, gib_score_pair) and\n"
    "`row_images` (the same writing the row's EXR and PNGs into a temporary folder). The\n"
    "pair is synthetic (a room's radiance with a black sky, a highlight 100x the walls and a\n"
    "light strip; the test 7% dim with noise, fireflies and a light leak) unless --ref and\n"
    "--test name EXRs. --repeat N rounds (default 5), each timing every thread count in turn,\n"
    "so all see the machine's same load; the rows give the median, interquartile range, least\n"
    "and greatest time, the speed-up over one thread and the parallel fraction p it implies\n"
    "(Amdahl: speed-up = 1 / (1 - p + p / threads)) with the speed-up p predicts on 16\n"
    "cores. The thread count of a scoring run is GIBENCH_SCORE_THREADS (default every core).\n"};

enum { M_ERRORS, M_METRICS, M_FLIP_LDR, M_FLIP_HDR, M_ROW, M_ROW_IMAGES, M_COUNT };
static const char *const measure_name[M_COUNT] = {"errors", "metrics", "flip_ldr", "flip_hdr",
                                                  "row", "row_images"};

#define MAX_THREAD_COUNTS 8
#define MAX_REPEAT 101

/* ---- the synthetic pair ---- */

static float hash01(uint32_t a, uint32_t b)
{
    uint32_t x = gib_hash_mix32(a * 0x9E3779B1u ^ (b + 0x7F4A7C15u) * 0x85EBCA77u);
    return (float)(x >> 8) / 16777216.0f;
}

/* A room's radiance at (u, v) in [0,1]^2 (v down): a black sky through a window, lit walls falling
 * off across the image, a checkered floor, a shadowed box, thin dark frames, a light strip and a
 * highlight 100 times the walls. */
static void room_radiance(float u, float v, float rgb[3])
{
    static const float wall[3] = {0.9f, 0.8f, 0.7f}, floor_c[3] = {0.5f, 0.6f, 0.8f};
    const float lit = 0.15f + 0.5f * u * (1.0f - 0.6f * v);
    const int checker = ((int)(u * 40.0f) + (int)(v * 24.0f)) % 2;
    const int box = u > 0.3f && u < 0.45f && v > 0.45f && v < 0.85f;
    const int frame = fmodf(u * 13.0f, 1.0f) < 0.004f;
    const float du = u - 0.72f, dv = (v - 0.35f) * 0.5625f;
    const float spot = 20.0f * expf(-(du * du + dv * dv) / (0.03f * 0.03f));
    for (int c = 0; c < 3; c++) {
        float x = v > 0.7f ? lit * floor_c[c] * (checker ? 0.6f : 1.0f) : lit * wall[c];
        if (box)
            x *= c == 0 ? 0.35f : 0.2f;
        if (frame)
            x *= 0.1f;
        rgb[c] = x + spot;
    }
    if (v > 0.2f && v < 0.23f && u > 0.4f && u < 0.6f)
        rgb[0] = rgb[1] = rgb[2] = 8.0f;
    if (v < 0.2f && u < 0.8f)
        rgb[0] = rgb[1] = rgb[2] = 0.0f;
}

/* The technique's image of it: 7% dim, slightly warm, with noise of 20% of the radiance,
 * fireflies in one pixel of 2000 and a light leak on the wall. */
static void technique_radiance(const float ref[3], float u, float v, uint32_t i, float rgb[3])
{
    const int leak = u > 0.1f && u < 0.2f && v > 0.5f && v < 0.6f;
    const int firefly = hash01(i, 99) < 0.0005f;
    for (int c = 0; c < 3; c++) {
        float g = hash01(i, (uint32_t)c) + hash01(i, (uint32_t)c + 3) + hash01(i, (uint32_t)c + 6);
        float x = ref[c] * (c == 0 ? 0.95f : 0.92f) * (1.0f + 0.4f * (g - 1.5f));
        x += 0.01f * (g - 1.5f) + (leak ? 0.3f : 0.0f) + (firefly ? 30.0f : 0.0f);
        rgb[c] = x > 0.0f ? x : 0.0f;
    }
}

static int make_pair(int w, int h, gib_image *ref, gib_image *test, gib_error *err)
{
    if (gib_image_alloc(ref, w, h, 4, err) < 0)
        return -1;
    if (gib_image_alloc(test, w, h, 4, err) < 0) {
        gib_image_free(ref);
        return -1;
    }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const size_t i = (size_t)y * w + x;
            const float u = ((float)x + 0.5f) / (float)w, v = ((float)y + 0.5f) / (float)h;
            room_radiance(u, v, &ref->px[4 * i]);
            technique_radiance(&ref->px[4 * i], u, v, (uint32_t)i, &test->px[4 * i]);
            ref->px[4 * i + 3] = test->px[4 * i + 3] = 1.0f;
        }
    return 0;
}

/* ---- the measures ---- */

typedef struct bench_pair {
    gib_image ref, test;
    float *rgb;            /* ref, test, clamped ref, clamped test: 3 floats per pixel each */
    char dir[4096];        /* where row_images writes */
    double value[M_COUNT]; /* each measure's number, from the last timing */
} bench_pair;

/* The packed RGB copies FLIP's functions take (exposure 1), made once, outside the timings. */
static int pack_rgb(bench_pair *p, gib_error *err)
{
    const size_t n = (size_t)p->ref.width * p->ref.height;
    if (!(p->rgb = gib_calloc(12 * n, sizeof(float), err)))
        return -1;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            float r = p->ref.px[i * p->ref.channels + c], t = p->test.px[i * p->test.channels + c];
            p->rgb[3 * i + c] = r;
            p->rgb[3 * (n + i) + c] = t;
            p->rgb[3 * (2 * n + i) + c] = fminf(fmaxf(r, 0.0f), 1.0f);
            p->rgb[3 * (3 * n + i) + c] = fminf(fmaxf(t, 0.0f), 1.0f);
        }
    return 0;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* Runs measure k once; its number goes to p->value[k]. Returns the milliseconds, or -1. */
static double measure(bench_pair *p, int k, gib_error *err)
{
    const int w = p->ref.width, h = p->ref.height;
    const size_t n = (size_t)w * h;
    const float ppd = gib_flip_default_ppd();
    gib_metrics m;
    int rc = 0;
    double t0 = now_ms();
    switch (k) {
    case M_ERRORS: rc = gib_metrics_errors(&p->ref, &p->test, &m, err); break;
    case M_METRICS: rc = gib_metrics_compute(&p->ref, &p->test, 1.0f, &m, err); break;
    case M_FLIP_LDR:
        m.flip = gib_flip_ldr(p->rgb + 6 * n, p->rgb + 9 * n, w, h, ppd, NULL, err);
        break;
    case M_FLIP_HDR:
        m.hdrflip = gib_flip_hdr(p->rgb, p->rgb + 3 * n, w, h, ppd, NULL, NULL, NULL, err);
        break;
    case M_ROW: rc = gib_score_pair(&p->ref, &p->test, 1.0f, NULL, NULL, &m, err); break;
    case M_ROW_IMAGES: rc = gib_score_pair(&p->ref, &p->test, 1.0f, p->dir, "row", &m, err); break;
    }
    double ms = now_ms() - t0;
    /* errors: the RMSE; metrics: SSIM; the FLIPs and the rows: their FLIP or HDR-FLIP mean. */
    p->value[k] = k == M_ERRORS ? m.rmse : k == M_METRICS ? m.ssim : k == M_FLIP_LDR ? m.flip
                                                                                   : m.hdrflip;
    return rc < 0 ? -1.0 : ms;
}

/* ---- statistics and output ---- */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The q-quantile of n sorted values, linearly interpolated (numpy's default). */
static double quantile(const double *v, int n, double q)
{
    double pos = q * (n - 1);
    int i = (int)pos;
    return i + 1 < n ? v[i] + (pos - i) * (v[i + 1] - v[i]) : v[n - 1];
}

typedef struct bench_stats {
    double median, iqr, min, max;
} bench_stats;

static bench_stats stats_of(double *ms, int n)
{
    qsort(ms, (size_t)n, sizeof *ms, cmp_double);
    return (bench_stats){quantile(ms, n, 0.5), quantile(ms, n, 0.75) - quantile(ms, n, 0.25),
                         ms[0], ms[n - 1]};
}

typedef struct bench_run {
    int width, height, repeat, nthreads, threads[MAX_THREAD_COUNTS];
    const char *source; /* "synthetic" or the reference EXR's path */
    char machine[256];
    long cores;
    double ms[MAX_THREAD_COUNTS][M_COUNT][MAX_REPEAT];
    double value[MAX_THREAD_COUNTS][M_COUNT];
} bench_run;

/* One CSV line and one printed line per thread count and measure. */
static void write_rows(bench_run *b, FILE *f)
{
    printf("%dx%d %s, %d repeats, %ld cores, %s, %s\n", b->width, b->height, b->source, b->repeat,
           b->cores, b->machine, gib_git_revision());
    printf("  %7s %-10s %10s %9s %9s %9s %8s %6s %7s  %s\n", "threads", "metric", "median_ms",
           "iqr_ms", "min_ms", "max_ms", "speedup", "p", "at_16", "value");
    for (int m = 0; m < M_COUNT; m++) {
        bench_stats one = {0};
        for (int t = 0; t < b->nthreads; t++) {
            bench_stats s = stats_of(b->ms[t][m], b->repeat);
            if (t == 0)
                one = s;
            const int n = b->threads[t];
            const double sp = one.median / s.median;
            /* Amdahl's parallel fraction from the speed-up at n threads, and what it gives on 16. */
            const double p = n > 1 ? (1.0 - 1.0 / sp) / (1.0 - 1.0 / n) : NAN;
            const double at16 = n > 1 ? 1.0 / (1.0 - p + p / 16.0) : NAN;
            printf("  %7d %-10s %10.2f %9.2f %9.2f %9.2f %8.3f %6.3f %7.2f  %.17g\n", n,
                   measure_name[m], s.median, s.iqr, s.min, s.max, sp, p, at16, b->value[t][m]);
            if (f)
                fprintf(f, "%d,%d,%s,%d,%s,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.17g,%ld,%s,%s\n",
                        b->width, b->height, b->source, n, measure_name[m], b->repeat, s.median,
                        s.iqr, s.min, s.max, sp, p, at16, b->value[t][m], b->cores, b->machine,
                        gib_git_revision());
        }
    }
}

/* Every round times every thread count in turn. Returns 0 or -1 after a message. */
static int run_rounds(bench_run *b, bench_pair *p)
{
    gib_error err = {0};
    for (int r = 0; r < b->repeat; r++)
        for (int t = 0; t < b->nthreads; t++) {
            gib_score_threads_set(b->threads[t]);
            for (int m = 0; m < M_COUNT; m++) {
                double ms = measure(p, m, &err);
                if (ms < 0) {
                    fprintf(stderr, "gibench bench: scoring: %s\n", err.msg);
                    return -1;
                }
                b->ms[t][m][r] = ms;
                b->value[t][m] = p->value[m];
            }
            fprintf(stderr, "\rround %d/%d, %d threads   ", r + 1, b->repeat, b->threads[t]);
        }
    fputc('\n', stderr);
    gib_score_threads_set(0);
    return 0;
}

/* ---- options ---- */

typedef struct scoring_opts {
    const char *size, *threads, *out, *ref, *test;
    long repeat;
} scoring_opts;

/* "1,2,16" into b->threads; "" or NULL: 1 and the online cores. Returns 0 or -1 after a message. */
static int parse_threads(const char *list, bench_run *b)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    b->cores = cores > 0 ? cores : 1;
    if (!list) {
        b->threads[0] = 1;
        b->nthreads = 1 + (b->cores > 1);
        b->threads[1] = (int)b->cores;
        return 0;
    }
    const char *s = list;
    for (b->nthreads = 0; *s; b->nthreads++) {
        char *end;
        long v = strtol(s, &end, 10);
        if (end == s || v < 1 || v > 1024 || (*end && *end != ',') ||
            b->nthreads == MAX_THREAD_COUNTS) {
            fprintf(stderr, "gibench bench: --threads '%s': up to %d counts from 1 to 1024, "
                            "comma-separated\n", list, MAX_THREAD_COUNTS);
            return -1;
        }
        b->threads[b->nthreads] = (int)v;
        s = *end ? end + 1 : end;
    }
    if (b->nthreads == 0 || b->threads[0] != 1) {
        fprintf(stderr, "gibench bench: --threads '%s': the first count must be 1 (the speed-ups' "
                        "base)\n", list);
        return -1;
    }
    return 0;
}

/* The pair: the EXRs named, or the synthetic one at --size. Returns 0 or -1 after a message. */
static int load_pair(const scoring_opts *o, bench_run *b, bench_pair *p)
{
    gib_error err = {0};
    int rc;
    if (o->ref || o->test) {
        rc = !o->ref || !o->test ? gib_fail(&err, "--ref and --test go together")
             : gib_exr_read(o->ref, &p->ref, NULL, NULL, &err) < 0 ? -1
             : gib_exr_read(o->test, &p->test, NULL, NULL, &err);
        b->source = o->ref;
    } else {
        rc = gib_parse_size("--size", o->size, &b->width, &b->height, &err);
        if (rc == 0)
            rc = make_pair(b->width, b->height, &p->ref, &p->test, &err);
        b->source = "synthetic";
    }
    if (rc == 0)
        rc = gib_metrics_check(&p->ref, &p->test, &err);
    if (rc == 0)
        rc = pack_rgb(p, &err);
    if (rc < 0) {
        fprintf(stderr, "gibench bench: scoring: %s\n", err.msg);
        return -1;
    }
    b->width = p->ref.width;
    b->height = p->ref.height;
    return 0;
}

/* A temporary folder for row_images. Returns 0 or -1 after a message. */
static int make_dir(bench_pair *p)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(p->dir, sizeof p->dir, "%s/gibench-scoring-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(p->dir)) {
        fprintf(stderr, "gibench bench: scoring: cannot make a folder %s\n", p->dir);
        return -1;
    }
    return 0;
}

static void remove_dir(const bench_pair *p)
{
    static const char *const files[] = {"row.exr", "row.png", "row_error.png", "row_flip.png"};
    char path[4200];
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        snprintf(path, sizeof path, "%s/%s", p->dir, files[i]);
        remove(path);
    }
    remove(p->dir);
}

static int write_csv(bench_run *b, const char *out)
{
    FILE *f = NULL;
    char part[4200];
    if (out) {
        snprintf(part, sizeof part, "%s.part", out);
        if (!(f = fopen(part, "w"))) {
            fprintf(stderr, "gibench bench: cannot write %s\n", part);
            return 1;
        }
        fputs("width,height,pair,threads,metric,repeats,median_ms,iqr_ms,min_ms,max_ms,"
              "speedup,amdahl_p,amdahl_at_16,value,cores,machine,git\n", f);
    }
    write_rows(b, f);
    if (!f)
        return 0;
    if (fclose(f) != 0 || rename(part, out) != 0) {
        fprintf(stderr, "gibench bench: writing %s failed\n", out);
        remove(part);
        return 1;
    }
    printf("-> %s\n", out);
    return 0;
}

int gib_bench_scoring(int argc, char **argv)
{
    scoring_opts o = {.size = "1280x720", .repeat = 5};
    const gib_option opts[] = {
        GIB_OPTION_TEXT("--size", &o.size, "WxH", "the synthetic pair's size (1280x720)"),
        GIB_OPTION_TEXT("--ref", &o.ref, "F.exr", "a reference instead of the synthetic pair"),
        GIB_OPTION_TEXT("--test", &o.test, "F.exr", "the image scored against --ref"),
        GIB_OPTION_TEXT("--threads", &o.threads, "1,N[,...]", "thread counts (1 and every core)"),
        GIB_OPTION_INT("--repeat", &o.repeat, 1, MAX_REPEAT, "N", "rounds (default 5)"),
        GIB_OPTION_TEXT("--out", &o.out, "F.csv", "write the rows here"),
        {0}};
    int rc = gib_options_parse(&doc, opts, argc, argv, NULL, NULL, 0);
    if (rc != GIB_OPTIONS_PROCEED)
        return rc;
    bench_run *b = calloc(1, sizeof *b);
    bench_pair p = {0};
    rc = !b || parse_threads(o.threads, b) < 0 || load_pair(&o, b, &p) < 0 || make_dir(&p) < 0;
    if (rc == 0) {
        b->repeat = (int)o.repeat;
        gib_bench_machine_name(b->machine, sizeof b->machine);
        rc = run_rounds(b, &p) < 0 ? 1 : write_csv(b, o.out);
        remove_dir(&p);
    }
    gib_image_free(&p.ref);
    gib_image_free(&p.test);
    free(p.rgb);
    free(b);
    return rc;
}

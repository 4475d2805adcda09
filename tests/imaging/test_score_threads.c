/* Unit tests for the scoring threads (harness/imaging/parallel.h, score.h): a row's metrics, FLIP
 * maps and images are the same bit for bit on 1, 2, 3 and 7 threads, on the odd, non-square pairs
 * of score_pairs.h, and equal to what the single-thread implementation gave before the threads.
 * Also the team (every item once, a team reused), the thread count's sources and gib_float_kth.
 *
 * Usage: test_score_threads OUTDIR (the images of threads 1 and 3 go to OUTDIR/t1, OUTDIR/t3).
 * Exit status: the number of failed checks (capped). */
#include "tests/common/check.h"
#include "tests/imaging/score_pairs.h"
#include "harness/imaging/flip.h"
#include "harness/imaging/parallel.h"
#include "harness/imaging/score.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int failures;

static const int thread_counts[] = {1, 2, 3, 7};
#define NCOUNTS ((int)(sizeof thread_counts / sizeof *thread_counts))

/* What gib_metrics_compute and the FLIPs gave on each pair before the scoring threads (the
 * single-thread code at c10f35c, printed with %a): rmse, rel_rmse, psnr, ssim, ref_mean,
 * mean_ratio, black_rmse, flip, hdrflip, nonfinite. They are equal bit for bit here (glibc 2.36);
 * the tolerances below leave room for another libm's last bits (FLIP's powf, expf, cbrtf). */
static const struct {
    double v[9];
    long nonfinite;
} before[SCORE_PAIRS] = {
    {{0x1.ef3840612b12dp-3, 0x1.7110defba7021p-1, 0x1.42a3091d1cca4p+5, 0x1.d0d9fc824a774p-1,
      0x1.578177630b528p-2, 0x1.cc527f501822ap-1, 0x1.7280ac4347352p+0, 0x1.5fe35a7334e7cp-3,
      0x1.a257cd93bbdeap-3}, 0},
    {{0x1.b89f475e0e3d3p-3, 0x1.89f3f70465e51p-1, 0x1.4aa1e1543a5a1p+5, 0x1.26928cc287381p-1,
      0x1.1e53a5e736fe2p-2, 0x1.cec932849cdb9p-1, 0x1.702450ae9f968p+0, 0x1.1904c1f444444p-3,
      0x1.154ac02bf49f5p-2}, 0},
    {{0x1.ef3b7d24fd839p-3, 0x1.71112c7ea3a5cp-1, 0x1.42a294d3924cbp+5, 0x1.d050ac2a604a8p-1,
      0x1.57836e1bdc3e5p-2, 0x1.cc52011e7559p-1, 0x1.72830b61df3b1p+0, 0x1.60033b4e75b73p-3, NAN},
     2},
};
static const char *const field_names[9] = {"rmse", "rel_rmse", "psnr", "ssim", "ref_mean",
                                           "mean_ratio", "black_rmse", "flip", "hdrflip"};

static void fields(const gib_metrics *m, double v[9])
{
    const double f[9] = {m->rmse, m->rel_rmse, m->psnr, m->ssim, m->ref_mean,
                         m->mean_ratio, m->black_rmse, m->flip, m->hdrflip};
    memcpy(v, f, sizeof f);
}

/* Pair k scored on every thread count: each field the same bits as on one thread. */
static void test_pair_threads(int k, gib_metrics *one)
{
    gib_image ref, test;
    if (score_pairs_make(k, &ref, &test) < 0) {
        CHECK(0, "pair %d: out of memory", k);
        return;
    }
    for (int c = 0; c < NCOUNTS; c++) {
        gib_score_threads_set(thread_counts[c]);
        gib_metrics m;
        gib_error err = {0};
        int rc = gib_score_pair(&ref, &test, score_pairs_exposure(k), NULL, NULL, &m, &err);
        CHECK(rc == 0, "pair %d, %d threads: %s", k, thread_counts[c], err.msg);
        if (c == 0) {
            *one = m;
            continue;
        }
        double a[9], b[9];
        fields(one, a);
        fields(&m, b);
        char what[96], detail[160];
        snprintf(what, sizeof what, "pair %d: %d threads = 1 thread", k, thread_counts[c]);
        snprintf(detail, sizeof detail, "all 9 means bit for bit, nonfinite %ld = %ld",
                 m.nonfinite, one->nonfinite);
        CHECK_TRUE(what, !memcmp(a, b, sizeof a) && m.nonfinite == one->nonfinite, detail);
    }
    gib_image_free(&ref);
    gib_image_free(&test);
}

/* One thread's numbers against the implementation before the threads. */
static void test_pair_before(int k, const gib_metrics *m)
{
    double v[9];
    fields(m, v);
    int same = m->nonfinite == before[k].nonfinite;
    for (int f = 0; f < 9; f++) {
        char what[96];
        snprintf(what, sizeof what, "pair %d: %s as before the threads", k, field_names[f]);
        const double want = before[k].v[f];
        same &= !memcmp(&want, &v[f], sizeof want) || (isnan(want) && isnan(v[f]));
        if (isnan(want)) {
            CHECK_TRUE(what, isnan(v[f]), "NaN (HDR-FLIP of a non-finite sample)");
            continue;
        }
        const int flip = f >= 7;
        CHECK_NEAR(what, want, v[f], (flip ? 1e-6 : 1e-12) * fabs(want),
                   flip ? "relative 1e-6: float pipeline, another libm's last bits"
                        : "relative 1e-12: double sums in the same order");
    }
    char what[96];
    snprintf(what, sizeof what, "pair %d: identical to before the threads", k);
    CHECK_TRUE(what, same, same ? "every field bit for bit" : "within the tolerances only");
}

/* LDR-FLIP's and HDR-FLIP's per-pixel maps of pair 0 on each thread count. */
static void test_flip_maps(void)
{
    gib_image ref, test;
    if (score_pairs_make(0, &ref, &test) < 0)
        return;
    const int w = ref.width, h = ref.height;
    const size_t n = (size_t)w * h;
    float *rgb = malloc(2 * 3 * n * sizeof(float)), *maps = malloc(2 * NCOUNTS * n * sizeof(float));
    for (size_t i = 0; i < n && rgb; i++)
        for (int c = 0; c < 3; c++) {
            rgb[3 * i + c] = ref.px[4 * i + c];
            rgb[3 * (n + i) + c] = test.px[4 * i + c];
        }
    for (int c = 0; c < NCOUNTS && rgb && maps; c++) {
        gib_score_threads_set(thread_counts[c]);
        gib_error err = {0};
        float *ldr = maps + 2 * c * n, *hdr = ldr + n;
        gib_flip_ldr(rgb, rgb + 3 * n, w, h, gib_flip_default_ppd(), ldr, &err);
        gib_flip_hdr(rgb, rgb + 3 * n, w, h, gib_flip_default_ppd(), hdr, NULL, NULL, &err);
        if (c == 0)
            continue;
        char what[96];
        snprintf(what, sizeof what, "FLIP maps: %d threads = 1 thread", thread_counts[c]);
        CHECK_TRUE(what, !memcmp(maps, ldr, 2 * n * sizeof(float)),
                   "LDR and HDR maps bit for bit (157x83)");
    }
    CHECK(rgb && maps, "FLIP maps: out of memory");
    free(rgb);
    free(maps);
    gib_image_free(&ref);
    gib_image_free(&test);
}

/* The whole file's bytes equal. */
static int same_file(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    int same = fa && fb;
    while (same) {
        int ca = fgetc(fa), cb = fgetc(fb);
        same = ca == cb;
        if (ca == EOF)
            break;
    }
    if (fa)
        fclose(fa);
    if (fb)
        fclose(fb);
    return same;
}

/* The row's images written on 1 thread (in turn) and on 3 (beside the metrics) are the same. */
static void test_images(const char *outdir)
{
    gib_image ref, test;
    if (score_pairs_make(0, &ref, &test) < 0)
        return;
    char dir[2][1100];
    const int counts[2] = {1, 3};
    for (int c = 0; c < 2; c++) {
        snprintf(dir[c], sizeof dir[c], "%s/t%d", outdir, counts[c]);
        mkdir(outdir, 0755);
        mkdir(dir[c], 0755);
        gib_score_threads_set(counts[c]);
        gib_metrics m;
        gib_error err = {0};
        int rc = gib_score_pair(&ref, &test, 1.7f, dir[c], "row", &m, &err);
        CHECK(rc == 0, "images on %d threads: %s", counts[c], err.msg);
    }
    static const char *const files[] = {"row.exr", "row.png", "row_error.png", "row_flip.png"};
    for (int f = 0; f < 4; f++) {
        char a[1200], b[1200], what[96];
        snprintf(a, sizeof a, "%s/%s", dir[0], files[f]);
        snprintf(b, sizeof b, "%s/%s", dir[1], files[f]);
        snprintf(what, sizeof what, "%s: 3 threads = 1 thread", files[f]);
        CHECK_TRUE(what, same_file(a, b), "byte for byte");
    }
    gib_image_free(&ref);
    gib_image_free(&test);
}

static void count_item(void *ctx, int item)
{
    ((int *)ctx)[item]++;
}

/* Every item runs exactly once, on a team run several times. */
static void test_team(void)
{
    enum { N = 1001 };
    static int hits[N];
    gib_team *team = gib_team_start(7);
    for (int run = 0; run < 5; run++)
        gib_team_run(team, N, count_item, hits);
    gib_parallel(3, N, count_item, hits);
    gib_team_run(NULL, N, count_item, hits);
    int ok = 1;
    for (int i = 0; i < N; i++)
        ok &= hits[i] == 7;
    CHECK_TRUE("team: each of 1001 items once per run", ok, "7 runs: 5 on one team, 2 others");
    CHECK_TRUE("team of 7 has 7 threads", gib_team_size(team) == 7, "unless the system refused");
    gib_team_stop(team);
    CHECK_TRUE("a team of one is no team", gib_team_start(1) == NULL, "the caller's thread");
}

/* gib_score_threads: the set count, else GIBENCH_SCORE_THREADS, else the cores. */
static void test_thread_count(void)
{
    gib_score_threads_set(5);
    CHECK_TRUE("set count wins", gib_score_threads() == 5, "5");
    gib_score_threads_set(0);
    setenv("GIBENCH_SCORE_THREADS", "3", 1);
    CHECK_TRUE("GIBENCH_SCORE_THREADS=3", gib_score_threads() == 3, "3");
    setenv("GIBENCH_SCORE_THREADS", "3x", 1);
    const int cores = gib_score_threads();
    unsetenv("GIBENCH_SCORE_THREADS");
    CHECK_TRUE("a bad GIBENCH_SCORE_THREADS falls back to the cores",
               cores == gib_score_threads() && cores >= 1, "with one warning");
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* gib_float_kth against qsort, on values with many duplicates (a black image's zeros). */
static void test_kth(void)
{
    enum { N = 513 };
    float v[N], sorted[N], work[N];
    int ok = 1;
    for (int i = 0; i < N; i++)
        v[i] = i % 3 ? 0.0f : (float)((i * 7919) % 101) / 7.0f;
    memcpy(sorted, v, sizeof v);
    qsort(sorted, N, sizeof *sorted, cmp_float);
    for (int n = 1; n <= N; n += 37)
        for (int k = 0; k < n; k++) {
            memcpy(work, v, sizeof v);
            memcpy(sorted, v, (size_t)n * sizeof *v);
            qsort(sorted, (size_t)n, sizeof *sorted, cmp_float);
            ok &= gib_float_kth(work, (size_t)n, (size_t)k) == sorted[k];
        }
    CHECK_TRUE("gib_float_kth = qsort's element k", ok, "every k of 14 lengths, 2/3 zeros");
}

int main(int argc, char **argv)
{
    const char *outdir = argc > 1 ? argv[1] : ".";
    for (int k = 0; k < SCORE_PAIRS; k++) {
        gib_metrics one = {0};
        test_pair_threads(k, &one);
        test_pair_before(k, &one);
    }
    test_flip_maps();
    char dir[1024];
    mkdir(outdir, 0755);
    snprintf(dir, sizeof dir, "%s/score_threads", outdir);
    test_images(dir);
    test_team();
    test_thread_count();
    test_kth();
    gib_score_threads_set(0);
    printf("%d failure(s)\n", failures);
    return failures > 100 ? 100 : failures;
}

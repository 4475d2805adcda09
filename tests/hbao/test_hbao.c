/* hbao (Bavoil, Sainz and Dimitrov 2008; the LDM paper's baseline, Aalund et al. 2015 Sec. 5.1)
 * against the reference `ao` with the same d_max.
 *
 *  0. d_max = inf is rejected by the parameter range (a screen-space kernel needs a finite radius).
 *  1. On cornell and plane_box: every value finite and in [0, 1]; 0 wherever the reference has no
 *     hit, except on silhouette pixels (a reference hit among the 8 neighbours), where rasterised
 *     coverage and the ray cast can disagree about a pixel centre lying on an edge (plane_box's far
 *     edge has one such pixel at 256x256).
 *  2. On plane_box's open ground (d_max = 1 m, the cube's size), at pixels whose whole 5x5
 *     neighbourhood has reference AO exactly 1 (no reference ray hit anything within d_max), hbao
 *     must give > 0.98: a flat receiver must not occlude itself (measured: >= 0.9998; the margin
 *     is for the blur's reach toward the occluded zone, where W(r) -> 0 anyway).
 *  3. Determinism: two runs (create, render, destroy each) are bit-identical.
 *  4. Cornell, d_max = 0.1 m, default parameters, against a 1024-spp reference. Screen-space AO
 *     is an approximation (front layer only, uniform instead of cosine weighting, attenuation
 *     W(r)), so the bounds catch a broken implementation, not a small regression. Measured at
 *     128x128 with llvmpipe (see the printout): rel_rmse 0.12, SSIM 0.90, occlusion correlation
 *     0.94. An image with no occlusion at all scores rel_rmse 0.25 and one with the reference's
 *     mean everywhere 0.20, so rel_rmse < 0.18 separates them with margin on both sides;
 *     SSIM > 0.85; and the Pearson correlation of the occlusion 1 - ao with the reference's over
 *     hit pixels > 0.8 catches darkening in the wrong places even when the error magnitude looks
 *     plausible. Checked by breaking the shader on purpose: no occlusion (rel_rmse 0.25, SSIM
 *     0.68), inverted view vector (0.72, 0.30, correlation -0.27), marching the wrong way along
 *     each direction (0.20, 0.78, 0.73): each fails at least two of the three bounds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "harness/app/runner.h"
#include "harness/imaging/metrics.h"
#include "reference/reference.h"
#include "tests/common/check.h"

#define N 128
#define REL_RMSE_MAX 0.18
#define SSIM_MIN 0.85
#define CORR_MIN 0.8

static int failures;
static const gib_technique *tech;

static int run_hbao(const gib_gpu_scene *gpu, const char *dmax, gib_run_result *r)
{
    gib_params p;
    gib_error err;
    gib_params_default(tech, &p);
    if (gib_param_set(tech, &p, "dmax", dmax, &err) < 0) {
        CHECK(0, "dmax=%s: %s", dmax, err.msg);
        return 0;
    }
    gib_run_technique(gpu, tech, &p, 0, N, N, 1, 1, r);
    CHECK(r->ok, "hbao: %s: %s", r->status, r->err.msg);
    return r->ok;
}

static int reference(const gib_scene *s, float dmax, int spp, gib_image *ref)
{
    gib_ref_params rp = {.component = GIB_COMP_AO, .width = N, .height = N, .spp = spp,
                         .dmax = dmax, .seed = 1, .quiet = 1};
    gib_ref_stats st;
    gib_error err;
    if (gib_reference_render(s, &rp, ref, NULL, &st, &err) < 0) {
        CHECK(0, "reference: %s", err.msg);
        return 0;
    }
    printf("  reference %s, dmax %g, %d spp: noise rmse %.4f\n", s->name, dmax, spp,
           st.noise_rmse);
    return 1;
}

static float at(const gib_image *im, int x, int y)
{
    return im->px[((size_t)y * im->width + x) * im->channels];
}

/* Check 1: finite, in [0, 1], R = G = B, and 0 where the reference has no hit (but silhouettes). */
static void check_range(const char *name, const gib_image *ao, const gib_image *ref)
{
    long bad = 0, miss = 0, silhouette = 0;
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) {
            const float *p = &ao->px[((size_t)y * N + x) * ao->channels];
            if (!isfinite(p[0]) || p[0] < 0.0f || p[0] > 1.0f || p[1] != p[0] || p[2] != p[0])
                bad++;
            if (at(ref, x, y) != 0.0f || p[0] == 0.0f)
                continue;
            int near_hit = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int u = x + dx, v = y + dy;
                    if (u >= 0 && v >= 0 && u < N && v < N && at(ref, u, v) != 0.0f)
                        near_hit = 1;
                }
            near_hit ? silhouette++ : miss++;
        }
    char what[64], d[256];
    snprintf(what, sizeof what, "%s: in [0, 1], grey, 0 where no hit", name);
    snprintf(d, sizeof d, "%ld values non-finite, outside [0,1] or not grey; %ld no-hit pixels "
             "non-zero (%ld more on silhouettes, allowed)", bad, miss, silhouette);
    CHECK_TRUE(what, bad == 0 && miss == 0, d);
}

/* Check 2: ~1 on open ground. */
static void check_open(const gib_image *ao, const gib_image *ref)
{
    long n = 0;
    float lo = 1.0f;
    for (int y = 2; y < N - 2; y++)
        for (int x = 2; x < N - 2; x++) {
            int open = 1;
            for (int dy = -2; dy <= 2 && open; dy++)
                for (int dx = -2; dx <= 2; dx++)
                    if (at(ref, x + dx, y + dy) != 1.0f)
                        open = 0;
            if (!open)
                continue;
            n++;
            if (at(ao, x, y) < lo)
                lo = at(ao, x, y);
        }
    char d[128];
    snprintf(d, sizeof d, "%ld pixels (> %d), min hbao %.5f (> 0.98)", n, N * N / 10, lo);
    CHECK_TRUE("plane_box open ground: a flat receiver does not occlude itself",
               n > N * N / 10 && lo > 0.98f, d);
}

static double occlusion_correlation(const gib_image *ao, const gib_image *ref)
{
    double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    for (int i = 0; i < N * N; i++) {
        double b = ref->px[i * ref->channels];
        if (b == 0.0)
            continue;
        double a = 1.0 - ao->px[i * ao->channels];
        b = 1.0 - b;
        n++, sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
    }
    double cov = sab / n - sa / n * sb / n;
    return cov / sqrt((saa / n - sa / n * sa / n) * (sbb / n - sb / n * sb / n));
}

static double pass_ms(const gib_run_result *r, const char *name)
{
    for (int i = 0; i < r->pass_count; i++)
        if (!strcmp(r->passes[i].name, name))
            return r->passes[i].median_ms;
    return NAN;
}

int main(void)
{
    gib_error err;
    gib_gl_info info;
    gib_scene cornell, plane;
    gib_gpu_scene gcornell, gplane;
    if (!(tech = gib_technique_find("hbao"))) {
        CHECK(0, "technique hbao is not registered");
        return 1;
    }
    if (gib_scene_load("cornell", &cornell, &err) < 0 ||
        gib_scene_load("plane_box", &plane, &err) < 0 ||
        gib_gl_init(GIB_BACKEND_AUTO, &info, &err) < 0 ||
        gib_gpu_scene_upload(&cornell, &gcornell, &err) < 0 ||
        gib_gpu_scene_upload(&plane, &gplane, &err) < 0) {
        CHECK(0, "set-up: %s", err.msg);
        return 1;
    }
    printf("renderer %s, hbao at %dx%d\n", info.renderer, N, N);
    gib_params p;
    gib_params_default(tech, &p);
    int inf_rejected = gib_param_set(tech, &p, "dmax", "inf", &err) < 0;
    CHECK_TRUE("0. dmax=inf rejected (a screen-space kernel needs a finite radius)", inf_rejected,
               inf_rejected ? err.msg : "ACCEPTED");

    gib_image ref_c, ref_p;
    gib_run_result rc, rp, again;
    if (!reference(&cornell, 0.1f, 1024, &ref_c) || !reference(&plane, 1.0f, 64, &ref_p) ||
        !run_hbao(&gcornell, "0.1", &rc) || !run_hbao(&gplane, "1", &rp) ||
        !run_hbao(&gcornell, "0.1", &again))
        return 1;
    const gib_image *ao_c = &rc.images[0], *ao_p = &rp.images[0];

    printf("1. range and no-hit pixels\n");
    check_range("cornell", ao_c, &ref_c);
    check_range("plane_box", ao_p, &ref_p);

    printf("2. open plane\n");
    check_open(ao_p, &ref_p);

    size_t bytes = sizeof(float) * (size_t)N * N * ao_c->channels;
    int same = again.images[0].width == N && !memcmp(again.images[0].px, ao_c->px, bytes);
    CHECK_TRUE("3. determinism: two runs bit-identical", same, same ? "" : "DIFFER");

    gib_metrics m;
    if (gib_metrics_compute(&ref_c, ao_c, cornell.exposure, &m, &err) < 0) {
        CHECK(0, "metrics: %s", err.msg);
        return 1;
    }
    double corr = occlusion_correlation(ao_c, &ref_c);
    printf("4. cornell dmax 0.1 m: rmse %.4f rel_rmse %.4f (< %.2f) psnr %.2f dB ssim %.4f "
           "(> %.2f) occlusion correlation %.3f (> %.2f); hbao pass %.2f ms, total gpu %.2f ms\n",
           m.rmse, m.rel_rmse, REL_RMSE_MAX, m.psnr, m.ssim, SSIM_MIN, corr, CORR_MIN,
           pass_ms(&rc, "hbao"), rc.gpu_total.median_ms);
    char d[128];
    snprintf(d, sizeof d, "%ld non-finite", (long)m.nonfinite);
    CHECK_TRUE("4. cornell: every pixel finite", m.nonfinite == 0, d);
    snprintf(d, sizeof d, "rel_rmse %.4f < %.2f (no occlusion: 0.25, the reference's mean: 0.20)",
             m.rel_rmse, REL_RMSE_MAX);
    CHECK_TRUE("4. cornell: rel_rmse below REL_RMSE_MAX", m.rel_rmse < REL_RMSE_MAX, d);
    snprintf(d, sizeof d, "ssim %.4f > %.2f", m.ssim, SSIM_MIN);
    CHECK_TRUE("4. cornell: SSIM above SSIM_MIN", m.ssim > SSIM_MIN, d);
    snprintf(d, sizeof d, "%.3f > %.2f (darkening in the wrong places)", corr, CORR_MIN);
    CHECK_TRUE("4. cornell: occlusion correlation above CORR_MIN", corr > CORR_MIN, d);

    if (getenv("GIB_TEST_OUT")) {
        char path[1024];
        snprintf(path, sizeof path, "%s/hbao_cornell.png", getenv("GIB_TEST_OUT"));
        gib_png_write_preview(path, ao_c, cornell.exposure, &err);
        snprintf(path, sizeof path, "%s/hbao_cornell_error.png", getenv("GIB_TEST_OUT"));
        gib_png_write_error_map(path, &ref_c, ao_c, 0, &err);
    }
    printf("%s\n", failures ? "FAIL" : "PASS");
    gib_image_free(&ref_c);
    gib_image_free(&ref_p);
    gib_run_result_free(&rc);
    gib_run_result_free(&rp);
    gib_run_result_free(&again);
    gib_gpu_scene_free(&gcornell);
    gib_gpu_scene_free(&gplane);
    gib_gl_shutdown();
    gib_scene_free(&cornell);
    gib_scene_free(&plane);
    return failures != 0;
}

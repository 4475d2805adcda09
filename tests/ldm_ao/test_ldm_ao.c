/* ldm_ao on the Cornell box (Aalund et al. 2015, Sec. 3.3):
 *  1. converges toward the reference `ao` as the number of directions grows: the RMSE at N = 512 is
 *     below 0.9 x the RMSE at N = 32. The reference's own noise (printed) is part of both errors and
 *     the same for both, so the margin is on the LDM error; with 2048 spp its noise RMSE is ~0.01
 *     while the measured gap is several times that.
 *  2. is deterministic: two frames rendered in the same run are bit-identical (no random numbers).
 *  3. gives finite output in [0, 1] (the estimator 2/N sum cos is at most ~1 + 1/N, see test_eqsp).
 *  4. agrees on the open plane: on plane_box's ground plane far from the box, with dmax small, the
 *     AO must be ~1: (2/N) sum |cos| to within 1/N (test_eqsp's bound) plus the texel margin. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "harness/app/runner.h"
#include "harness/imaging/metrics.h"
#include "reference/reference.h"
#include "tests/common/check.h"

static int failures;

static int run(const gib_gpu_scene *gpu, int n, const char *dmax, int frames, gib_run_result *r)
{
    const gib_technique *t = gib_technique_find("ldm_ao");
    gib_params p;
    gib_params_default(t, &p);
    char nbuf[32];
    snprintf(nbuf, sizeof nbuf, "%d", n);
    gib_error err;
    gib_param_set(t, &p, "directions", nbuf, &err);
    gib_param_set(t, &p, "ldm_res", "128", &err);
    gib_param_set(t, &p, "dmax", dmax, &err);
    gib_run_technique(gpu, t, &p, 0, 64, 64, 0, frames, r);
    if (!r->ok)
        fprintf(stderr, "ldm_ao N=%d: %s: %s\n", n, r->status, r->err.msg);
    return r->ok;
}

int main(void)
{
    gib_error err;
    gib_gl_info info;
    gib_scene scene, plane;
    gib_gpu_scene gpu, gplane;
    if (gib_scene_load("cornell", &scene, &err) < 0 || gib_scene_load("plane_box", &plane, &err) < 0 ||
        gib_gl_init(GIB_BACKEND_AUTO, &info, &err) < 0 || gib_gpu_scene_upload(&scene, &gpu, &err) < 0 ||
        gib_gpu_scene_upload(&plane, &gplane, &err) < 0) {
        CHECK(0, "set-up: %s", err.msg);
        return 1;
    }
    char d[256];
    gib_ref_params rp = {.component = GIB_COMP_AO, .width = 64, .height = 64, .spp = 2048,
                         .dmax = INFINITY, .seed = 1, .quiet = 1};
    gib_image ref;
    gib_ref_stats st;
    if (gib_reference_render(&scene, &rp, &ref, NULL, &st, &err) < 0) {
        CHECK(0, "reference: %s", err.msg);
        return 1;
    }
    gib_run_result r32, r512, again;
    if (!run(&gpu, 32, "inf", 1, &r32) || !run(&gpu, 512, "inf", 1, &r512) ||
        !run(&gpu, 32, "inf", 1, &again))
        return 1;
    gib_metrics m32, m512;
    gib_metrics_compute(&ref, &r32.images[0], 1, &m32, &err);
    gib_metrics_compute(&ref, &r512.images[0], 1, &m512, &err);
    printf("renderer %s; reference ao 2048 spp, noise rmse %.4f\n", info.renderer, st.noise_rmse);
    printf("N=32:  rmse %.5f ssim %.4f gpu %.1f ms\nN=512: rmse %.5f ssim %.4f gpu %.1f ms\n",
           m32.rmse, m32.ssim, r32.gpu_total.median_ms, m512.rmse, m512.ssim,
           r512.gpu_total.median_ms);
    snprintf(d, sizeof d, "rmse(N=512) %.5f, 0.9 x rmse(N=32) %.5f (ratio %.3f)", m512.rmse,
             0.9 * m32.rmse, m512.rmse / m32.rmse);
    CHECK_TRUE("converges: rmse(N=512) < 0.9 x rmse(N=32)", m512.rmse < 0.9 * m32.rmse, d);
    size_t nb = sizeof(float) * 3 * 64 * 64;
    CHECK_TRUE("deterministic: two renders of N=32 bit-identical",
               !memcmp(r32.images[0].px, again.images[0].px, nb), "");
    float lo = 1e30f, hi = -1e30f;
    for (int i = 0; i < 64 * 64 * 3; i++) {
        float v = r512.images[0].px[i];
        if (!isfinite(v))
            lo = -INFINITY;
        lo = fminf(lo, v), hi = fmaxf(hi, v);
    }
    CHECK_AT_LEAST("N=512: smallest value (-inf if any is not finite)", lo, 0,
                   "finite output, an occlusion in [0, 1]");
    CHECK_AT_MOST("N=512: largest value", hi, 1.0f + 1.0f / 512 + 1e-3f,
                  "the estimator 2/N sum cos is at most ~1 + 1/N (test_eqsp), plus 1e-3");
    /* Open plane: reference pixels that are exactly 1 with dmax = 0.05 (nothing within 5 cm). */
    gib_ref_params pp = rp;
    pp.dmax = 0.05f;
    pp.spp = 64;
    gib_image pref;
    gib_run_result rp128;
    if (gib_reference_render(&plane, &pp, &pref, NULL, &st, &err) < 0 || !run(&gplane, 128, "0.05", 1, &rp128))
        return 1;
    int count = 0;
    double worst = 0;
    for (int i = 0; i < 64 * 64; i++)
        if (pref.px[3 * i] == 1.0f) {
            count++;
            worst = fmax(worst, fabs(rp128.images[0].px[3 * i] - 1.0));
        }
    snprintf(d, sizeof d, "%d pixels", count);
    CHECK_TRUE("open plane: more than 100 pixels with nothing within 5 cm", count > 100, d);
    CHECK_AT_MOST("open plane, N=128: worst |AO - 1|", worst, 1.0 / 128 + 1e-3,
                  "test_eqsp's 1/N plus the texel margin");
    /* 5. A node buffer too small for the lists: the row's status says overflow, never ok. */
    {
        const gib_technique *t = gib_technique_find("ldm_ao");
        gib_params p;
        gib_params_default(t, &p);
        gib_param_set(t, &p, "directions", "32", &err);
        gib_param_set(t, &p, "node_budget", "0.5", &err);
        gib_run_result ro;
        gib_run_technique(&gpu, t, &p, 0, 64, 64, 0, 1, &ro);
        snprintf(d, sizeof d, "status '%.32s' (%.160s)", ro.status, ro.err.msg);
        CHECK_TRUE("node_budget 0.5 reports status 'overflow'",
                   !ro.ok && !strcmp(ro.status, "overflow"), d);
        gib_run_result_free(&ro);
    }
    gib_run_result_free(&r32);
    gib_run_result_free(&r512);
    gib_run_result_free(&again);
    gib_run_result_free(&rp128);
    gib_image_free(&ref);
    gib_image_free(&pref);
    gib_gpu_scene_free(&gpu);
    gib_gpu_scene_free(&gplane);
    gib_scene_free(&scene);
    gib_scene_free(&plane);
    gib_gl_shutdown();
    printf("%s\n", failures ? "FAIL" : "PASS");
    return failures != 0;
}

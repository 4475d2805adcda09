/* The thesis' Fig. 4.2 on scenes/ring_occluded.scene: photons the ring's platform (a slab 5 and 6
 * surfaces deep from the camera) should stop. Scored, as gibench run scores it, against the
 * reference's `caustic`, which is dark everywhere the camera sees (the slab shadows the lower
 * platform under it, and the ring's caustic falls on the hidden slab):
 *  - per-pixel linked lists (layers 0) keep every fragment, find the slab and leave the visible
 *    image dark: its RMSE under LISTS_MAX (the reference's own noise and at most a few stray
 *    splats);
 *  - 4 depth layers (layers 4) miss the slab and the photons land on the lower platform in view:
 *    RMSE at least LEAK_RATIO x the lists' and above LEAK_MIN (measured on llvmpipe at these
 *    settings: lists 0, layers ~0.018).
 * Equal images (as the earlier layout of this scene gave: the leaked photons landed out of view)
 * fail the test. */
#include <math.h>
#include <stdio.h>

#include "harness/app/runner.h"
#include "harness/imaging/metrics.h"
#include "reference/reference.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

#define LISTS_MAX 0.002
#define LEAK_RATIO 5.0
#define LEAK_MIN 0.005

static double run(gib_gl_fixture *fx, const gib_image *ref, const char *layers, int w, int h)
{
    const gib_technique *t = gib_technique_find("ispm_caustics");
    gib_params p;
    gib_params_default(t, &p);
    gib_error err;
    gib_param_set(t, &p, "rsm_res", "256", &err);
    gib_param_set(t, &p, "mask_level", "1", &err);
    gib_param_set(t, &p, "ray_res", "128", &err);
    gib_param_set(t, &p, "layers", layers, &err);
    gib_run_result r;
    gib_run_technique(&fx->gpu, t, &p, 0, w, h, 0, 1, &r);
    double rmse = NAN;
    gib_metrics m;
    if (!r.ok)
        CHECK(0, "layers %s: %s: %s", layers, r.status, r.err.msg);
    else if (gib_metrics_compute(ref, &r.images[0], 1.0f, &m, &err) < 0)
        CHECK(0, "layers %s: %s", layers, err.msg);
    else
        rmse = m.rmse;
    printf("layers %s: %s, caustic RMSE %.6g against the reference\n", layers, r.counters, rmse);
    gib_run_result_free(&r);
    return rmse;
}

int main(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "ring_occluded") < 0)
        return 1;
    const int W = 96, H = 96;
    gib_image ref;
    gib_ref_stats st;
    if (gib_fixture_reference(&fx, GIB_COMP_CAUSTIC, W, H, 16, &ref, &st) < 0)
        return 1;
    printf("reference caustic: mean %.6g, noise RMSE %.6g\n", st.mean, st.noise_rmse);
    double lists = run(&fx, &ref, "0", W, H), peeled = run(&fx, &ref, "4", W, H);
    CHECK_AT_MOST("lists (layers 0): RMSE against the reference", lists, LISTS_MAX,
                  "the reference's own noise and at most a few stray splats");
    CHECK_AT_LEAST("4 depth layers: RMSE against the reference", peeled, LEAK_MIN,
                   "the layers miss the slab and photons land in view; measured ~0.018");
    snprintf(check_msg, sizeof check_msg, "4 depth layers: RMSE (bound %.0fx the lists' %.6g)",
             LEAK_RATIO, lists);
    CHECK_AT_LEAST(check_msg, peeled, LEAK_RATIO * lists,
                   "equal images (the leaked photons out of view) must fail");
    gib_image_free(&ref);
    gib_fixture_close(&fx);
    return failures != 0;
}

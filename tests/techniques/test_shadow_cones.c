/* The voxel techniques' shadow cones (lrsm's and vct's `direct`) against the path tracer's exact
 * direct light, instantiated over both techniques, voxel_res 64, 128 and 256, and the Cornell box
 * under its two lights (the cube view's light under the ceiling, and cornell_spot45's spot), at
 * W x H.
 *
 * Held, with what each catches:
 *  - the mean within MEAN_TOL of the reference's: lit surfaces are exact and the cones only soften
 *    shadow edges and darken surfaces lit at grazing (measured 0.94-0.99, the spot at 64^3 the
 *    lowest; the tolerance leaves room for another driver's rounding). A cone that does not
 *    taper toward a light hung under the ceiling takes the ceiling for an occluder: -24% in
 *    test_lrsm_cornell;
 *  - the light put where the reference has none (the boxes' umbrae, the faces turned from the
 *    light), over the mean where it is lit, at most DARK_MAX (measured 0.0014-0.0067: where cones
 *    cross the boxes' one-voxel shells between samples): the paper's mean occupancy reads those
 *    shells as alpha ~ 1/d and let 3.4% through (lrsm at 128^3; 7.4% at 256^3). */
#include <math.h>
#include <stdio.h>

#include "harness/app/runner.h"
#include "reference/reference.h"
#include "tests/common/block_stats.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures; /* every check (check.h); the cases also return their own count */
static char check_msg[512]; /* what a CHECK_TRUE line says */

#define W 64
#define H 64
#define MEAN_TOL 0.08
#define DARK_MAX 0.01

/* The image's mean over the pixels the reference leaves black, over its mean where the reference
 * is lit (all channels). */
static double light_where_reference_dark(const gib_image *ref, const gib_image *im)
{
    double dark = 0, lit = 0;
    long ndark = 0, nlit = 0, n = (long)ref->width * ref->height;
    for (long i = 0; i < n; i++) {
        double r = 0, v = 0;
        for (int c = 0; c < 3; c++) {
            r += ref->px[i * ref->channels + c];
            v += im->px[i * im->channels + c];
        }
        if (r > 1e-6) {
            lit += v;
            nlit++;
        } else {
            dark += v;
            ndark++;
        }
    }
    return ndark && nlit && lit > 0 ? (dark / ndark) / (lit / nlit) : 0;
}

/* One technique at one voxel_res against the reference; returns the failures. */
static int check(gib_gl_fixture *fx, const char *scene, const char *name, const char *res,
                 const gib_image *ref)
{
    const gib_technique *t = gib_technique_find(name);
    gib_params p;
    gib_error err;
    gib_params_default(t, &p);
    if (gib_param_set(t, &p, "voxel_res", res, &err) < 0) {
        CHECK(0, "%s", err.msg);
        return 1;
    }
    gib_run_result r;
    gib_run_technique(&fx->gpu, t, &p, 0, W, H, 0, 1, &r);
    if (!r.ok) {
        CHECK(0, "%s: %s: %s", name, r.status, r.err.msg);
        return 1;
    }
    int failures = 0, found = 0;
    for (int o = 0; o < r.output_count; o++) {
        if (r.output_components[o] != GIB_OUT_DIRECT)
            continue;
        const gib_image *im = &r.images[o];
        found = 1;
        if (gib_image_count_nonfinite(im)) {
            CHECK(0, "%s %s voxel_res=%s: non-finite pixels", scene, name, res);
            continue;
        }
        double ratio = gib_rgb_mean(im) / gib_rgb_mean(ref);
        snprintf(check_msg, sizeof check_msg, "%s %s voxel_res=%s: direct mean / reference's",
                 scene, name, res);
        CHECK_NEAR(check_msg, 1.0, ratio, MEAN_TOL,
                   "lit surfaces exact, cones soften shadow edges and grazing light: measured "
                   "0.94-0.99, room for another driver's rounding");
        double dark = light_where_reference_dark(ref, im);
        snprintf(check_msg, sizeof check_msg,
                 "%s %s voxel_res=%s: light where the reference is dark / where lit", scene, name,
                 res);
        CHECK_AT_MOST(check_msg, dark, DARK_MAX,
                      "measured 0.0014-0.0067, cones crossing the boxes' one-voxel shells; the "
                      "paper's mean occupancy lets 3.4% through");
    }
    CHECK(found, "%s gave no direct image", name);
    gib_run_result_free(&r);
    return failures;
}

int main(void)
{
    static const char *const scenes[] = {"cornell", "cornell_spot45"};
    static const char *const techniques[] = {"lrsm", "vct"};
    static const char *const resolutions[] = {"64", "128", "256"};
    for (int s = 0; s < 2; s++) {
        gib_gl_fixture fx;
        if (gib_fixture_open(&fx, scenes[s]) < 0)
            return 1;
        gib_image ref;
        if (gib_fixture_reference(&fx, GIB_COMP_DIRECT, W, H, 1, &ref, NULL) < 0)
            return 1;
        for (int t = 0; t < 2; t++)
            for (int v = 0; v < 3; v++)
                failures += check(&fx, scenes[s], techniques[t], resolutions[v], &ref);
        gib_image_free(&ref);
        gib_fixture_close(&fx);
    }
    printf("%s: shadow cones against the exact direct light\n", failures ? "FAIL" : "PASS");
    return failures ? 1 : 0;
}

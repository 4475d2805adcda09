/* The voxel techniques' indirect energy against their voxel resolution, instantiated over `lrsm`
 * and `vct` (their default parameters but voxel_res) on the Cornell box (a cube light view) and
 * cornell_spot45 (one perspective view) at 64x64 against 1024-spp `indirect` references: a finer
 * grid describes the same scene, so the image's mean must not drift with it. For each technique and
 * scene, the mean over the reference's (all channels) at voxel_res 64, 128 and 256:
 *  - within [LO, HI] of the reference's at every resolution (per technique: vct 0.8-1.15, measured
 *    0.92-1.00; lrsm 0.8-1.05, measured 0.88-0.94 on the Cornell box and 0.855-0.91 under the
 *    spot: below the reference for the reasons tests/lrsm/test_lrsm_cornell.c gives, but never
 *    above it). The figure is 15% at 128x128, which the closing notes report; the test
 *    holds 20% so that another renderer's rounding does not decide it. Eq. 12's own window,
 *    visibility 0, measured 0.66-0.74 and fails;
 *  - the smallest over the largest at least MIN_RATIO = 0.9, within 10% of itself (measured 0.95
 *    for vct, 0.93-0.94 for lrsm). The paper's literal readings fell with the grid: vct 0.67 /
 *    0.56 / 0.50 (ratio 0.75: sample_level 0 reads the receiver's own cells, more of them the finer
 *    the voxels), lrsm 0.49 / 0.38 / 0.29 (ratio 0.59: its tilted cones' samples reached their own
 *    surface).
 * And vct in the furnace against its closed form, with and without the fill (furnace_case), and
 * over open ground (open_plane_case). */
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
#define REF_SPP 1024
#define MIN_RATIO 0.9
#define FURNACE_MIN_RATIO 0.85
#define FILL_GAIN 0.9
#define OPEN_LO 0.8
#define OPEN_HI 1.3

static const struct {
    const char *technique;
    double lo, hi;
} cases[] = {{"vct", 0.8, 1.15}, {"lrsm", 0.8, 1.05}};
static const char *const resolutions[] = {"64", "128", "256"};
#define NRES ((int)(sizeof resolutions / sizeof resolutions[0]))

/* The technique's indirect mean at voxel_res `res` (and `name` = `value` where name is not NULL),
 * or -1 on failure. */
static double indirect_mean_with(gib_gl_fixture *fx, const gib_technique *t, const char *res,
                                 const char *name, const char *value)
{
    gib_params p;
    gib_error err;
    gib_params_default(t, &p);
    if (gib_param_set(t, &p, "voxel_res", res, &err) < 0 ||
        (name && gib_param_set(t, &p, name, value, &err) < 0)) {
        CHECK(0, "%s", err.msg);
        return -1;
    }
    gib_run_result r;
    gib_run_technique(&fx->gpu, t, &p, 0, W, H, 0, 1, &r);
    if (!r.ok) {
        CHECK(0, "%s: %s: %s", t->name, r.status, r.err.msg);
        return -1;
    }
    double m = -1;
    for (int o = 0; o < r.output_count; o++)
        if (r.output_components[o] == GIB_OUT_INDIRECT && !gib_image_count_nonfinite(&r.images[o]))
            m = gib_rgb_mean(&r.images[o]);
    gib_run_result_free(&r);
    if (m < 0)
        CHECK(0, "%s gave no finite indirect image", t->name);
    return m;
}

static double indirect_mean(gib_gl_fixture *fx, const gib_technique *t, const char *res)
{
    return indirect_mean_with(fx, t, res, NULL, NULL);
}

/* vct in the furnace (closed form: every wall's one-bounce indirect radiance is rho x its direct,
 * 0.5 x 0.159155) with `fill` = value: the mean over the closed form's at each voxel_res into
 * ratio[]; returns -1 when a render fails. */
static int furnace_means(gib_gl_fixture *fx, const char *fill, double ratio[NRES])
{
    const gib_technique *t = gib_technique_find("vct");
    const double want = 0.5 * 0.159155;
    for (int i = 0; i < NRES; i++) {
        double m = indirect_mean_with(fx, t, resolutions[i], "fill", fill);
        if (m < 0)
            return -1;
        ratio[i] = m / want;
        printf("     vct fill=%s furnace voxel_res %s: indirect mean %.3f of the closed form's\n",
               fill, resolutions[i], ratio[i]);
    }
    return 0;
}

/* The furnace with and without the fill. With it, the smallest mean over the largest across
 * voxel_res at least FURNACE_MIN_RATIO (measured 0.63 / 0.66 / 0.67, ratio 0.94). Point injection
 * alone (fill=0) leaves the sphere's corner-clipped voxels black, more of them the finer the grid
 * for the same light views: at 256^3 it must stay below FILL_GAIN of the fill's (measured 0.580
 * against 0.671, 0.86). What is left below 1 is the cones' occlusion (trilinear samples of a
 * one-voxel shell composited as a medium, tests/vct/test_vct_cornell.c), which neither bound
 * judges: the ratio's bound is 0.85, not the 0.9 it was while cones read the sphere's wall
 * repeated beyond the grid (0.83 / 0.80 / 0.77 then), because the honest loss varies with the
 * grid by a few percent on its own. */
static int furnace_case(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "furnace") < 0)
        return 1;
    double ours[NRES], literal[NRES];
    int rc = furnace_means(&fx, "1", ours) < 0 || furnace_means(&fx, "0", literal) < 0;
    gib_fixture_close(&fx);
    if (rc)
        return 1;
    double lo = INFINITY, hi = 0;
    for (int i = 0; i < NRES; i++) {
        lo = fmin(lo, ours[i]);
        hi = fmax(hi, ours[i]);
    }
    const double finest = literal[NRES - 1] / ours[NRES - 1];
    int before = failures;
    CHECK_AT_LEAST("vct furnace, fill: smallest mean over the largest", lo / hi,
                   FURNACE_MIN_RATIO,
                   "the honest thin-shell loss varies with the grid by a few percent; measured "
                   "0.94");
    /* Strictly below FILL_GAIN, which CHECK_AT_MOST is not. */
    snprintf(check_msg, sizeof check_msg,
             "vct furnace: at voxel_res %s point injection %.3f of the fill's (below %.2f)",
             resolutions[NRES - 1], finest, FILL_GAIN);
    CHECK_TRUE(check_msg, finest < FILL_GAIN, "");
    int ok = failures == before;
    return !ok;
}

/* vct over open ground (plane_box: a lit box on a plane, nothing above) against its 1024-spp
 * reference: the mean within OPEN_LO..OPEN_HI at every voxel_res (measured 1.09 / 1.03 / 0.99 at
 * 64x64). A grazing cone's sample lifted only clear of its own level's cells still read the coarser
 * blended level's, which hold the lit plane itself: the plane lit itself to 3.4-4.9x the
 * reference's mean (vct_trace.glsl); the shrink of clearance 0 measures 1.5-1.9x. */
static int open_plane_case(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "plane_box") < 0)
        return 1;
    gib_image ref;
    if (gib_fixture_reference(&fx, GIB_COMP_INDIRECT, W, H, REF_SPP, &ref, NULL) < 0) {
        gib_fixture_close(&fx);
        return 1;
    }
    const double want = gib_rgb_mean(&ref);
    const gib_technique *t = gib_technique_find("vct");
    int failures = 0;
    for (int i = 0; i < NRES; i++) {
        double m = indirect_mean(&fx, t, resolutions[i]);
        CHECK(m >= 0, "vct plane_box voxel_res %s: the render failed", resolutions[i]);
        snprintf(check_msg, sizeof check_msg,
                 "vct plane_box voxel_res %s: indirect mean over the reference's",
                 resolutions[i]);
        CHECK_AT_LEAST(check_msg, m / want, OPEN_LO,
                       "measured 1.09 / 1.03 / 0.99; the plane lighting itself read 3.4-4.9x");
        CHECK_AT_MOST(check_msg, m / want, OPEN_HI,
                      "measured 1.09 / 1.03 / 0.99; the plane lighting itself read 3.4-4.9x");
    }
    gib_image_free(&ref);
    gib_fixture_close(&fx);
    return failures;
}

/* Each case's means on `scene` against its reference: the band at every voxel_res and the ratio. */
static int scene_case(const char *scene)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, scene) < 0)
        return 1;
    gib_image ref;
    if (gib_fixture_reference(&fx, GIB_COMP_INDIRECT, W, H, REF_SPP, &ref, NULL) < 0) {
        gib_fixture_close(&fx);
        return 1;
    }
    double want = gib_rgb_mean(&ref);
    int failures = 0;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const gib_technique *t = gib_technique_find(cases[k].technique);
        double lo = INFINITY, hi = 0;
        for (int i = 0; i < NRES; i++) {
            double m = indirect_mean(&fx, t, resolutions[i]);
            if (m < 0) {
                failures++;
                continue;
            }
            double ratio = m / want;
            snprintf(check_msg, sizeof check_msg,
                     "%s %s voxel_res %s: indirect mean over the reference's", scene, t->name,
                     resolutions[i]);
            CHECK_AT_LEAST(check_msg, ratio, cases[k].lo,
                           "the issue's 15%, held at 20% against another renderer's rounding; "
                           "Eq. 12's own window read 0.66-0.74");
            CHECK_AT_MOST(check_msg, ratio, cases[k].hi,
                          "vct: the issue's 15%; lrsm: below the reference, never above it");
            lo = fmin(lo, ratio);
            hi = fmax(hi, ratio);
        }
        snprintf(check_msg, sizeof check_msg,
                 "%s %s: the smallest mean over the largest across voxel_res (0 if none)", scene,
                 t->name);
        CHECK_AT_LEAST(check_msg, hi > 0 ? lo / hi : 0.0, MIN_RATIO,
                       "a finer grid describes the same scene: within 10%; measured 0.93-0.95");
    }
    gib_image_free(&ref);
    gib_fixture_close(&fx);
    return failures;
}

int main(void)
{
    failures += scene_case("cornell") + scene_case("cornell_spot45");
    failures += furnace_case();
    failures += open_plane_case();
    printf("%s: voxel techniques' energy against voxel_res\n", failures ? "FAIL" : "PASS");
    return failures ? 1 : 0;
}

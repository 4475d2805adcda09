/* The voxel techniques' `cone` parameter (lrsm, vct), instantiated over both: each diffuse cone
 * rendered alone (weight 1) is the cone's share of the whole gather, so the per-cone images that
 * `gibench reference --cone i` scores are the pieces of the image every other row scores.
 *
 * Held on cornell_spot45 at W x H, voxel_res 64: sum_i w_i image(cone = i) equals image(cone =
 * -1) to SPLIT_TOL of the image's mean (the same shader sums the same cones in the same order;
 * measured 6e-7 (lrsm) and 1.3e-6 (vct) relative, float rounding); each cone's image is finite,
 * not black (in this box every cone sees lit floor or walls from many pixels) and differs from
 * the gather by more than DIFFER_MIN of its mean somewhere (measured 5-21) (a parameter that was ignored would
 * render the gather six times, whose weighted sum is the gather again). The weights are those of
 * the set (harness/base/cone_set.h, checked against the shaders' by test_voxel_cone). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "harness/app/runner.h"
#include "harness/base/cone_set.h"
#include "tests/common/block_stats.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures; /* every check (check.h); the cases also return their own count */
static char check_msg[512]; /* what a CHECK_TRUE line says */

#define W 32
#define H 32
#define SPLIT_TOL 1e-4
#define DIFFER_MIN 1.0

/* The technique's indirect image with `cone` (string), into out; 0 or -1. */
static int render_indirect(gib_gl_fixture *fx, const gib_technique *t, const char *cone,
                           gib_image *out)
{
    char cone_kv[24];
    snprintf(cone_kv, sizeof cone_kv, "cone=%s", cone);
    const char *const params[] = {"voxel_res=64", cone_kv, NULL};
    return gib_fixture_render(fx, t->name, params, 0, W, H, GIB_OUT_INDIRECT, out);
}

static int check(gib_gl_fixture *fx, const char *name)
{
    const gib_technique *t = gib_technique_find(name);
    gib_image whole, part;
    if (render_indirect(fx, t, "-1", &whole) < 0)
        return 1;
    const long n = (long)W * H * whole.channels;
    double *sum = calloc((size_t)n, sizeof *sum);
    int failures = 0;
    for (int i = 0; i < GIB_DIFFUSE_CONES; i++) {
        char cone[12];
        snprintf(cone, sizeof cone, "%d", i);
        if (render_indirect(fx, t, cone, &part) < 0) {
            failures++;
            continue;
        }
        double m = gib_rgb_mean(&part), differ = 0;
        for (long k = 0; k < n; k++)
            differ = fmax(differ, fabs(part.px[k] - whole.px[k]));
        differ /= gib_rgb_mean(&whole);
        int ok = !gib_image_count_nonfinite(&part) && m > 0 && differ > DIFFER_MIN;
        snprintf(check_msg, sizeof check_msg,
                 "%s cone %d alone: mean %.5f, differs from the gather by up to %.2f of its mean "
                 "(at least %.2f)",
                 name, i, m, differ, DIFFER_MIN);
        CHECK_TRUE(check_msg, ok, "");
        for (long k = 0; k < n; k++)
            sum[k] += gib_diffuse_cone_weight(i) * part.px[k];
        gib_image_free(&part);
    }
    double worst = 0, mean = gib_rgb_mean(&whole);
    for (long k = 0; k < n; k++)
        worst = fmax(worst, fabs(sum[k] - whole.px[k]));
    int ok = mean > 0 && worst <= SPLIT_TOL * mean;
    snprintf(check_msg, sizeof check_msg,
             "%s: the weighted sum of the 6 cones' images against the gather: worst pixel off by "
             "%.3g of the mean (bound %.0e)",
             name, worst / mean, SPLIT_TOL);
    CHECK_TRUE(check_msg, ok, "");
    free(sum);
    gib_image_free(&whole);
    return failures;
}

int main(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "cornell_spot45") < 0)
        return 1;
    failures += check(&fx, "lrsm") + check(&fx, "vct");
    gib_fixture_close(&fx);
    printf("%s: the diffuse gather split into its cones\n", failures ? "FAIL" : "PASS");
    return failures ? 1 : 0;
}

/* vct's gather as a continuous function of the cone aperture: the indirect mean of
 * cornell_spot45 at W x H, voxel_res 256, at diffuse_aperture FIRST, FIRST + STEP, ... LAST
 * degrees. Every pixel's cones take the same steps, so a choice that jumps with the aperture (a
 * sample's level crossing an integer, its last sample dropped at the cone's end) moves the whole
 * image at once; a half-degree wider cone is a nearly equal integral and must give a nearly
 * equal image.
 *
 * Held: consecutive means differ by at most JUMP_MAX of the smaller (measured at most 0.05 here,
 * 61.5 -> 62; the touching spheres' steps leave a ripple of about +-10% over 10 degrees, which
 * PERFORMANCE.md, "The lift of each level", describes). With both levels a fetch blends lifted
 * by the coarser one's cells (vct_trace.glsl says why each level has its own), the same sweep
 * jumped by 0.24 (60 -> 60.5) and 0.40 (61 -> 61.5). */
#include <stdio.h>

#include "techniques/technique.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures; /* every check (check.h); the cases also return their own count */
static char check_msg[512]; /* what a CHECK_TRUE line says */

#define W 64
#define H 64
#define FIRST 59.5
#define LAST 62.0
#define STEP 0.5
#define JUMP_MAX 0.08

static double indirect_mean(gib_gl_fixture *fx, double aperture)
{
    char ap_kv[48];
    snprintf(ap_kv, sizeof ap_kv, "diffuse_aperture=%g", aperture);
    const char *const params[] = {"voxel_res=256", ap_kv, NULL};
    return gib_fixture_render_mean(fx, "vct", params, 0, W, H, GIB_OUT_INDIRECT);
}

int main(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "cornell_spot45") < 0)
        return 1;
    double prev = indirect_mean(&fx, FIRST);
    if (!(prev > 0))
        failures++;
    for (double a = FIRST + STEP; a <= LAST + 1e-9 && !failures; a += STEP) {
        double m = indirect_mean(&fx, a);
        if (!(m > 0)) {
            failures++;
            break;
        }
        double jump = (m > prev ? m - prev : prev - m) / (m < prev ? m : prev);
        snprintf(check_msg, sizeof check_msg,
                 "vct diffuse_aperture %.1f -> %.1f: indirect mean %.5f -> %.5f, relative jump",
                 a - STEP, a, prev, m);
        CHECK_AT_MOST(check_msg, jump, JUMP_MAX,
                      "a half-degree wider cone is a nearly equal integral; measured at most 0.05");
        prev = m;
    }
    gib_fixture_close(&fx);
    printf("%s: vct's gather continuous in its aperture\n", failures ? "FAIL" : "PASS");
    return failures ? 1 : 0;
}

/* rsm_gather and multires_ir in the furnace (scenes/furnace.scene: a closed sphere R = 1 m, albedo
 * a = 0.5, a point light I = 1 W/sr at the centre) against the closed form of one bounce,
 * L = a^2 I / (pi R^2) = 0.0795775 (ideal sphere; the tessellated one's area mean is 0.079601).
 * Inside a sphere cos_l = cos_x = d / 2R, so every VPL gives x the irradiance Phi / (4 pi R^2)
 * wherever it stands: the image is uniform and its level checks the units of the whole chain (the
 * light views' flux, the VPLs' sum, the gather's 1/pi's, rho/pi at the pixel) whatever the pattern.
 * Tolerances: the image mean within MEAN_TOL = 0.2% (facets: 0.06%; measured -0.08%); every
 * pixel within PIXEL_TOL = 1.5%: eps = 0.05 m (clamp_distance) dims a pixel within 5 cm of a VPL
 * by at most that VPL's share of the flux (~1/223 of it on average for the 223 VPLs with a
 * surface, up to ~2x that for a grid cell at a cube face's centre, whose texels see the largest
 * solid angles): measured worst 0.77%. A wrong factor in the chain (a 1/pi, the region sums, the
 * albedo) is off by far more. multires_ir's regions shade their mean position on the same
 * uniform image. */
#include <math.h>
#include <stdio.h>

#include "harness/app/runner.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

#define W 64
#define H 48
#define MEAN_TOL 0.002
#define PIXEL_TOL 0.015

int main(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "furnace") < 0)
        return 1;
    const double want = 0.25 / M_PI;
    const char *names[] = {"rsm_gather", "multires_ir"};
    for (int k = 0; k < 2; k++) {
        const gib_technique *t = gib_technique_find(names[k]);
        if (!t) {
            printf("SKIP: %s is not registered\n", names[k]);
            continue;
        }
        gib_params p;
        gib_params_default(t, &p);
        gib_run_result r;
        gib_run_technique(&fx.gpu, t, &p, 0, W, H, 0, 1, &r);
        if (!r.ok) {
            CHECK(0, "%s: %s: %s", names[k], r.status, r.err.msg);
            failures++;
            continue;
        }
        double worst = 0, mean = 0;
        long n = (long)W * H * 3, bad = 0;
        for (long i = 0; i < n; i++) {
            double v = r.images[0].px[i], e = fabs(v / want - 1);
            mean += v / n;
            if (!(e <= PIXEL_TOL))
                bad++;
            if (!(e <= worst))
                worst = e;
        }
        snprintf(check_msg, sizeof check_msg,
                 "%s in the furnace (%s): mean %.6f over the closed form %.6f", names[k],
                 fx.info.renderer, mean, want);
        CHECK_NEAR(check_msg, 1, mean / want, MEAN_TOL, "the facets: 0.06%; measured -0.08%");
        snprintf(check_msg, sizeof check_msg,
                 "%s in the furnace: worst pixel's relative error (%ld values beyond)", names[k],
                 bad);
        CHECK_AT_MOST(check_msg, worst, PIXEL_TOL,
                      "eps = 0.05 m dims a pixel near a VPL by at most its flux share; measured "
                      "0.77%");
        /* `bad` also counts the NaNs, which `worst` may not keep. */
        CHECK(bad == 0, "%s: %ld values beyond %.1f%% of the closed form (or not a number)",
              names[k], bad, 100 * PIXEL_TOL);
        gib_run_result_free(&r);
    }
    gib_fixture_close(&fx);
    return failures != 0;
}

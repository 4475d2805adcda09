/* `lrsm` in the furnace (scenes/furnace.scene: inside a closed sphere R = 1 m of albedo a = 0.5, a
 * point light I = 1 W/sr at the centre): every wall point's outgoing radiance is (a/pi) I / R^2 =
 * 0.159155 and the one-bounce indirect a^2 / pi I / R^2 = 0.079577 (a times the wall's radiance).
 *
 * 1. The LRSM's radiance lookup (Algorithm 1 through the probe) at 200 wall points in random
 *    directions, with v_c along the inward normal (N = 1) and r_c = 5 cm: it must return the wall's
 *    outgoing radiance a I / (pi R^2) within LOOKUP_TOL = 1% (half-float storage 0.05%, the
 *    facets 0.06%, mips of a curved wall). This checks Table 1's conversion of the light view's
 *    FLUX into radiance on a cube light view, its cos^3 solid angle included (without it the
 *    points near the faces' corners read up to 5x too much). Run again on
 *    tests/lrsm/furnace_spot.scene (a 40-degree spot at the centre: one perspective view).
 * 2. The whole technique at 64x48: `direct` (shadow cones; nothing occludes the wall from the
 *    light) within DIRECT_TOL = 0.2% of 0.159155 everywhere (measured 2e-7); `indirect` finite,
 *    positive, not above the answer (no light created, INDIRECT_MAX = 1.01) and at least
 *    INDIRECT_MIN = 0.70 of it. It stays below the answer because the occlusion voxels are
 *    isotropic mean occupancies: a one-voxel-thick wall seen through a sample d voxels wide is only
 *    partly opaque, so part of each cone passes the wall (Eq. 1). Read as a density over the step
 *    (parameter opacity = 1, the default; voxel_cone.glsl) the wall stops ~86% per sample. A
 *    sample's light as the share of its rays meeting the lit wall's plane (hits = 1, the default;
 *    lrsm_hits.glsl) puts the level at 0.80 of the answer, its LRSM radiance taken over the lit
 *    coverage inside it (hits = 0, coverage = 1; lrsm_cone.frag) at 0.81; with Eq. 5's coverage
 *    counted again by the voxels' alpha, before samples were kept off their own surface, it was
 *    0.42; the paper's reading of the occupancy (opacity = 0: alpha = mean occupancy ~ 1/d) gives
 *    0.012: both fail the lower bound. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "harness/app/runner.h"
#include "tests/lrsm/lrsm_setup.h"
#include "tests/common/check.h"

static int failures; /* every check (check.h); the cases also return their own count */
static char check_msg[512]; /* what a CHECK_TRUE line says */

#define LOOKUP_TOL 0.01
#define DIRECT_TOL 0.002
#define INDIRECT_MAX 1.01
#define INDIRECT_MIN 0.70
#define PROBES 200

int main(int argc, char **argv)
{
    gib_gl_fixture fx;
    gib_error err;
    /* With a scene argument (tests/lrsm/furnace_spot.scene): part 1 only, on the spot's one
     * perspective view, the probes within 28 degrees of its axis (the mips a 5 cm sample reads
     * there span ~6 degrees; the cone's edge at 40 degrees, beyond which the wall is dark, must
     * stay out of them). */
    int spot = argc > 1;
    if (gib_fixture_open(&fx, spot ? argv[1] : "furnace") < 0)
        return 1;
    if (spot && (fx.scene.light_count != 1 ||
                 gib_light_view_kind(&fx.scene.lights[0]) != GIB_LV_PERSPECTIVE)) {
        CHECK(0, "%s: expected one spot light with a perspective view", argv[1]);
        return 1;
    }
    const double wall = 0.5 / M_PI, indirect = 0.25 / M_PI;

    /* 1. */
    lrsm_setup s;
    if (lrsm_setup_build(&s, &fx, 512) < 0)
        return 1;
    static float in[8 * PROBES], out[4 * PROBES];
    srand(3);
    for (int i = 0; i < PROBES; i++) {
        double d[3], len;
        do {
            len = 0;
            for (int k = 0; k < 3; k++) {
                d[k] = 2.0 * rand() / RAND_MAX - 1;
                len += d[k] * d[k];
            }
            len = len > 1 || len < 1e-4 ? 2 : len;
            if (spot && len <= 1) {
                const float *a = fx.scene.lights[0].direction;
                double c = (d[0] * a[0] + d[1] * a[1] + d[2] * a[2]) / sqrt(len);
                len = c >= cos(28 * M_PI / 180) ? len : 2;
            }
        } while (len > 1);
        len = sqrt(len);
        for (int k = 0; k < 3; k++) {
            in[8 * i + k] = (float)(0.9997 * d[k] / len);   /* on the faceted wall */
            in[8 * i + 4 + k] = (float)(-d[k] / len);       /* inward normal */
        }
        in[8 * i + 3] = 0.05f;
        in[8 * i + 7] = 0;
    }
    if (lrsm_layers_probe(&s.L, &s.lv, 0, 1, in, PROBES, out, &err) < 0) {
        CHECK(0, "probe: %s", err.msg);
        return 1;
    }
    double worst = 0, mean = 0;
    for (int i = 0; i < PROBES; i++)
        for (int c = 0; c < 3; c++) {
            worst = fmax(worst, fabs(out[4 * i + c] / wall - 1));
            mean += out[4 * i + c] / (3.0 * PROBES);
        }
    snprintf(check_msg, sizeof check_msg,
             "LRSM lookup (%s light view) at %d wall points (mean %.6f): largest relative "
             "deviation from a I / (pi R^2) = %.6f",
             spot ? "perspective" : "cube", PROBES, mean, wall);
    CHECK_AT_MOST(check_msg, worst, LOOKUP_TOL,
                  "half-float storage 0.05%, the facets 0.06%, mips of a curved wall");
    lrsm_setup_destroy(&s);
    if (spot) {
        gib_fixture_close(&fx);
        printf("%s: lrsm lookup in the furnace lit by a spot\n", failures ? "FAIL" : "PASS");
        return failures ? 1 : 0;
    }

    /* 2. */
    const gib_technique *t = gib_technique_find("lrsm");
    gib_params p;
    gib_params_default(t, &p);
    gib_run_result r;
    gib_run_technique(&fx.gpu, t, &p, 0, 64, 48, 0, 1, &r);
    if (!r.ok) {
        CHECK(0, "lrsm: %s: %s", r.status, r.err.msg);
        return 1;
    }
    for (int o = 0; o < r.output_count; o++) {
        const gib_image *im = &r.images[o];
        long nonfinite = gib_image_count_nonfinite(im);
        double sum = 0, dev = 0;
        int n = im->width * im->height;
        for (int i = 0; i < n; i++)
            for (int c = 0; c < 3; c++) {
                double v = im->px[i * im->channels + c];
                sum += v / (3.0 * n);
                dev = fmax(dev, fabs(v / wall - 1));
            }
        CHECK(!nonfinite, "output %d: %ld non-finite pixels", o, nonfinite);
        if (r.output_components[o] == GIB_OUT_DIRECT) {
            snprintf(check_msg, sizeof check_msg,
                     "direct (mean %.6f): largest relative deviation from %.6f", sum, wall);
            CHECK_AT_MOST(check_msg, dev, DIRECT_TOL,
                          "nothing occludes the wall from the light; measured 2e-7");
        } else if (r.output_components[o] == GIB_OUT_INDIRECT) {
            snprintf(check_msg, sizeof check_msg,
                     "indirect: mean (%.4f of the one-bounce answer %.6f)", sum / indirect,
                     indirect);
            CHECK_AT_LEAST(check_msg, sum, INDIRECT_MIN * indirect,
                           "isotropic occlusion voxels let part of each cone pass the wall "
                           "(Eq. 1); measured 0.80, the paper's readings 0.42 and 0.012");
            CHECK_AT_MOST(check_msg, sum, INDIRECT_MAX * indirect, "no light created");
        } else {
            CHECK_NEAR("glossy: mean", 0, sum, 0, "no specular lobe in the furnace");
        }
    }
    gib_run_result_free(&r);
    gib_fixture_close(&fx);
    printf("%s: lrsm in the furnace\n", failures ? "FAIL" : "PASS");
    return failures ? 1 : 0;
}

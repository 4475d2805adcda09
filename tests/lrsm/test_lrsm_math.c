/* The pure math of `lrsm` (techniques/lrsm/lrsm_math.c, the CPU mirror of lrsm_common.glsl):
 *  - the erf approximation (Abramowitz and Stegun 7.1.26) against C's erf: its bound 1.5e-7;
 *  - Eq. 12 in closed form against Simpson integration of the Gaussian over [zc - rc, zc + rc],
 *    including sigma -> 0 (the floored variance) and a sample far outside the depth range. The
 *    closed form is two Phi values, each within 7.5e-8 of the truth, and Simpson's rule on 20000
 *    intervals over at most 16 sigma is exact to ~1e-12, so VIS_TOL = 2e-7;
 *  - the static depth partitions: membership with the overlap band, Eq. 15's decays adding up to 1
 *    across a band (k(t) + k(1 - t) = 1), open outer ends; the <n.l> partitions;
 *  - the merge of a 2x2 block that straddles a depth discontinuity: each layer gets only its own
 *    side (variance 0), opacities are the member shares;
 *  - a cone sample's share of rays meeting a plane (parameter hits): the cap cosine's closed form
 *    against its definition integrated over the flattened cap on a 1000 x 1000 grid (error ~1e-4,
 *    CAP_TOL = 1e-3); a plane facing the axis anywhere behind the first sample is met by a
 *    touching-sphere sequence of a 60-degree cone (composited share >= TILE_MIN = 0.99, sharp or spread); a plane
 *    through the centre at every tilt against the exact share of rays through a disk, from which
 *    the Gaussian stand-in for the disk's projection differs by at most 0.081 (HITS_TOL = 0.09);
 *    a plane far from the sample met by none; the plane spread of a pure tilt is 0. */
#include <math.h>
#include <stdio.h>

#include "techniques/lrsm/lrsm_math.h"
#include "tests/common/check.h"

#define ERF_TOL 1.5e-7
#define VIS_TOL 2e-7
#define CAP_TOL 1e-3
#define TILE_MIN 0.99
#define HITS_TOL 0.09

static int failures;

/* CHECK with the values compared, at the caller's file:line. */
#define CHECK_GOT(ok, what, got, want)                                                             \
    CHECK(ok, "%s: got %.10g, expected %.10g", what, (double)(got), (double)(want))

/* Simpson's rule of the N(mu, sigma2) density over [a, b] (restricted to mu +- 8 sigma). */
static double gauss_integral(double a, double b, double mu, double sigma2)
{
    double s = sqrt(sigma2 > LRSM_MIN_VARIANCE ? sigma2 : LRSM_MIN_VARIANCE);
    a = fmax(a, mu - 8 * s);
    b = fmin(b, mu + 8 * s);
    if (b <= a)
        return 0;
    int n = 20000;
    double h = (b - a) / n, sum = 0;
    for (int i = 0; i <= n; i++) {
        double z = a + i * h, w = i == 0 || i == n ? 1 : i % 2 ? 4 : 2;
        sum += w * exp(-(z - mu) * (z - mu) / (2 * s * s)) / (s * sqrt(2 * M_PI));
    }
    return sum * h / 3;
}

/* The mean of max(a + b x, 0) over the unit disk (x its first coordinate), on a grid. */
static double cap_cosine_grid(double a, double b)
{
    int n = 1000;
    double sum = 0;
    long count = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double x = -1 + (i + 0.5) * 2 / n, y = -1 + (j + 0.5) * 2 / n;
            if (x * x + y * y > 1)
                continue;
            sum += fmax(a + b * x, 0);
            count++;
        }
    return sum / count;
}

static void check_plane_hits(void)
{
    static const double tilts[] = {0, 30, 60, 80, 90, 100, 120, 150, 180};
    for (int i = 0; i < (int)(sizeof tilts / sizeof *tilts); i++)
        for (double sh = 0; sh <= 0.51; sh += 0.25) {
            double t = tilts[i] * M_PI / 180;
            double got = lrsm_cap_cosine(cos(t), sin(t), sh), want = cap_cosine_grid(cos(t), sh * sin(t));
            char what[80];
            snprintf(what, sizeof what, "cap cosine, tilt %g, sin_half %g", tilts[i], sh);
            CHECK_NEAR(what, want, got, CAP_TOL, "the 1000 x 1000 grid's integral errs by ~1e-4");
        }
    /* A touching-sphere sequence of a 60-degree cone (r = t tan 30, next centre one diameter on)
     * against a plane facing the axis at depth D. */
    for (double spread = 0; spread <= 0.021; spread += 0.02) {
        double worst = 1;
        /* from the first sample's step on, three spreads in (what lies before it is not met) */
        for (double D = 0.05 + 3 * spread; D < 2; D += 0.01) {
            double pass = 1;
            for (double t = 0.04; t < 4; t += 2 * t * tan(M_PI / 6)) {
                double r = t * tan(M_PI / 6);
                pass *= 1 - lrsm_plane_hits(D - t, 1, r, 1, spread * spread);
            }
            worst = fmin(worst, 1 - pass);
        }
        CHECK_AT_LEAST(spread > 0 ? "a facing plane met, spread 2 cm" : "a facing plane met", worst,
                       TILE_MIN, "a 60-degree cone's touching spheres meet a plane it faces");
    }
    double worst = 0;
    for (double E = 0.01; E < 1; E += 0.01) {
        double sa = sqrt(1 - E * E), c = fmin(1, E / sa);
        double exact = (2 / M_PI) * (asin(c) + c * sqrt(1 - c * c));
        worst = fmax(worst, fabs(lrsm_plane_hits(0, E, 1, 1, 0) - exact));
    }
    CHECK_AT_MOST("a plane through the centre vs the disk's exact share", worst, HITS_TOL,
                  "the Gaussian stand-in for the disk's projection differs by at most 0.081");
    CHECK_GOT(lrsm_plane_hits(5, 0.5, 1, 1, 0) < 1e-6 && lrsm_plane_hits(-5, 0.5, 1, 1, 0) < 1e-6,
              "a plane far from the sample", lrsm_plane_hits(5, 0.5, 1, 1, 0), 0);
    double r = 0.1, th = M_PI / 3;
    CHECK_GOT(lrsm_plane_spread(pow(r * tan(th), 2) / 3, cos(th), r) < 1e-12 &&
              fabs(lrsm_plane_spread(0.01, 1, r) - 0.01) < 1e-12, "plane spread: tilt removed",
              lrsm_plane_spread(pow(r * tan(th), 2) / 3, cos(th), r), 0);
}

int main(void)
{
    double worst = 0;
    for (double x = -6; x <= 6; x += 1e-3)
        worst = fmax(worst, fabs(lrsm_erf(x) - erf(x)));
    CHECK_GOT(worst < ERF_TOL, "erf approximation, largest error on [-6, 6]", worst, ERF_TOL);
    printf("erf (A&S 7.1.26): largest |error| %.3g on [-6, 6] (bound %.2g)\n", worst, ERF_TOL);

    /* Eq. 12: (zc, rc, mu, sigma2). */
    static const double cases[][4] = {
        {0.5, 0.05, 0.5, 0.01},    {0.5, 0.05, 0.52, 0.0004}, {0.3, 0.1, 0.6, 0.02},
        {0.5, 0.2, 0.5, 1e-6},     {0.5, 0.01, 0.5, 0.25},    {0.1, 0.3, 0.9, 0.04},
        {0.5, 0.05, 0.5, 0.0},     {0.5, 0.05, 0.56, 0.0},    {0.5, 0.05, 0.54, 1e-12},
        {50.0, 0.05, 0.5, 0.01},   {-40.0, 1.0, 0.3, 0.0},    {0.5, 1e-6, 0.5, 0.01},
    };
    double vworst = 0;
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const double *c = cases[i];
        double got = lrsm_visibility(c[0], c[1], c[2], c[3]);
        double want = gauss_integral(c[0] - c[1], c[0] + c[1], c[2], c[3]);
        char what[128];
        snprintf(what, sizeof what, "Eq. 12 at zc %g rc %g mu %g sigma^2 %g", c[0], c[1], c[2], c[3]);
        CHECK_NEAR(what, want, got, VIS_TOL,
                   "two Phi values, each within 7.5e-8; Simpson exact to ~1e-12");
        CHECK_AT_LEAST(what, got, -VIS_TOL, "a visibility, in [0, 1] to VIS_TOL");
        CHECK_AT_MOST(what, got, 1 + VIS_TOL, "a visibility, in [0, 1] to VIS_TOL");
        vworst = fmax(vworst, fabs(got - want));
    }
    printf("Eq. 12 against Simpson: largest |difference| %.3g over %u cases (tolerance %.1g)\n", vworst,
           (unsigned)(sizeof cases / sizeof cases[0]), VIS_TOL);
    /* sigma -> 0: the indicator of |mu - zc| < rc, away from the edges by a few floored sigmas. */
    double smin = sqrt(LRSM_MIN_VARIANCE);
    CHECK_GOT(fabs(lrsm_visibility(0.5, 0.05, 0.5 + 0.05 - 6 * smin, 0) - 1) < 1e-6, "sigma 0 inside", 
              lrsm_visibility(0.5, 0.05, 0.5 + 0.05 - 6 * smin, 0), 1);
    CHECK_GOT(lrsm_visibility(0.5, 0.05, 0.5 + 0.05 + 6 * smin, 0) < 1e-6, "sigma 0 outside",
              lrsm_visibility(0.5, 0.05, 0.5 + 0.05 + 6 * smin, 0), 0);
    CHECK_GOT(lrsm_visibility(100.0, 0.5, 0.5, 0.01) == 0.0, "far outside the depth range",
              lrsm_visibility(100.0, 0.5, 0.5, 0.01), 0);
    CHECK_GOT(isfinite(lrsm_visibility(0.5, 0.05, 0.5, -1e-5)), "negative variance (cancellation)",
              lrsm_visibility(0.5, 0.05, 0.5, -1e-5), 1);

    /* Partitions: [0, 10] in 2, overlap 0.2: w = 5, delta = 1, layers [-0.5, 5.5] and [4.5, 10.5]. */
    lrsm_partition p = {.z0 = 0, .z1 = 10, .parts = 2, .overlap = 0.2};
    double lo, hi;
    lrsm_layer_range(&p, 1, &lo, &hi);
    CHECK_GOT(fabs(lo - 4.5) < 1e-12 && fabs(hi - 10.5) < 1e-12, "layer 1 range", lo, 4.5);
    CHECK_GOT(lrsm_in_depth_layer(&p, 0, 4.4) && !lrsm_in_depth_layer(&p, 1, 4.4), "4.4 in layer 0 only", 0, 0);
    CHECK_GOT(lrsm_in_depth_layer(&p, 0, 5.0) && lrsm_in_depth_layer(&p, 1, 5.0), "5.0 in both", 0, 0);
    CHECK_GOT(!lrsm_in_depth_layer(&p, 0, 5.6) && lrsm_in_depth_layer(&p, 1, 5.6), "5.6 in layer 1 only", 0, 0);
    CHECK_GOT(lrsm_in_depth_layer(&p, 0, -3) && lrsm_in_depth_layer(&p, 1, 30), "open outer ends", 0, 0);
    CHECK_GOT(lrsm_layer_overlaps(&p, 1, 3.0, 4.6) && !lrsm_layer_overlaps(&p, 1, 3.0, 4.4) &&
              lrsm_layer_overlaps(&p, 0, 5.4, 9) && !lrsm_layer_overlaps(&p, 0, 5.6, 9),
              "layers met by a sample's depth interval", 0, 0);
    double dworst = 0;
    for (double z = -1; z <= 11; z += 0.01)
        dworst = fmax(dworst, fabs(lrsm_decay(&p, 0, z) + lrsm_decay(&p, 1, z) - 1));
    CHECK_GOT(dworst < 1e-12, "Eq. 15 decays add to 1", dworst, 0);
    CHECK_GOT(lrsm_decay(&p, 0, 4.5) == 1.0 && fabs(lrsm_decay(&p, 0, 5.0) - 0.5) < 1e-12 &&
              lrsm_decay(&p, 0, 5.5) == 0.0, "Eq. 15 across the band", lrsm_decay(&p, 0, 5.0), 0.5);
    CHECK_GOT(lrsm_normal_part(0.0, 2) == -1 && lrsm_normal_part(0.3, 2) == 0 &&
              lrsm_normal_part(0.7, 2) == 1 && lrsm_normal_part(1.0, 2) == 1, "<n.l> partitions", 0, 0);

    /* A block straddling a discontinuity: z = 2 (left column) and z = 8 (right column). */
    lrsm_texel block[4];
    for (int i = 0; i < 4; i++) {
        lrsm_texel t = {.valid = 1, .z = i & 1 ? 8.0 : 2.0, .n = {0, 0, 1}, .cosnl = 1,
                        .radiance = {1, 2, 3}, .area = 1};
        block[i] = t;
    }
    lrsm_layer_texel out[4];
    lrsm_build_block(&p, 2, block, out);
    for (int d = 0; d < 2; d++) {
        const lrsm_layer_texel *o = &out[d * 2 + 1];
        lrsm_layer_range(&p, d, &lo, &hi);
        double a = o->depth[2], mu = o->depth[0] / a, var = o->depth[1] / a - mu * mu;
        double want = ((d ? 8.0 : 2.0) - lo) / (hi - lo);
        CHECK_GOT(fabs(a - 0.5) < 1e-12 && fabs(mu - want) < 1e-12 && fabs(var) < 1e-12 &&
                  fabs(o->radiance[1] - 1.0) < 1e-12 && fabs(o->normal[2] - 0.5) < 1e-12 &&
                  out[d * 2].depth[2] == 0, "block across a discontinuity", mu, want);
    }
    /* Area weights (Eq. 3's Jacobian): a texel three times the area of its neighbour counts three
     * times in the filtered radiance; the weight's factors. */
    lrsm_texel w2[4] = {{.valid = 1, .z = 2, .n = {0, 0, 1}, .cosnl = 1, .radiance = {1, 1, 1},
                         .area = 1},
                        {.valid = 1, .z = 2, .n = {0, 0, 1}, .cosnl = 1, .radiance = {5, 5, 5},
                         .area = 3}};
    lrsm_build_block(&p, 2, w2, out);
    double mean = out[1].radiance[0] / out[1].radiance[3];
    CHECK_GOT(fabs(mean - 4.0) < 1e-12 && fabs(out[1].normal[3] - 0.5) < 1e-12,
              "area-weighted radiance of a block", mean, 4.0);
    CHECK_GOT(fabs(lrsm_area_weight(2, 3, 10, 1, 0.5) - 0.2) < 1e-12 &&
              fabs(lrsm_area_weight(0, 5, 10, 1, 1) - 0.025) < 1e-12 &&
              fabs(lrsm_area_weight(0, 5, 10, 0.5, 0.01) - 0.25 * 0.125) < 1e-12,
              "area weight: tilt 0.1 / <n.l> up to 1, (z / zfar)^2 cos^3", lrsm_area_weight(0, 5, 10, 1, 1),
              0.025);
    check_plane_hits();
    if (failures) {
        CHECK(0, "%d check(s)", failures);
        return 1;
    }
    printf("PASS: lrsm math\n");
    return 0;
}

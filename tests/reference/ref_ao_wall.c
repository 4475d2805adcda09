/* Reference renderer, `ao` next to a large wall, against analytic values (ARCHITECTURE.md, "Reference
 * renderer": AO of simple configurations).
 *
 * Setup: floor y = 0; a wall in the plane x = 1 spanning y in [0, 60], z in [-60, 60]; the camera
 * looks straight down at floor points at distances a = 1 - x from 0.7 to 2.3 from the wall.
 *
 * Where the AO rays start: at the floor point P moved up by the renderer's ray offset eps
 * (gib_reference_ray_eps, 1e-4 of the scene diagonal, 0.013 here), since every cosine-weighted
 * direction points up. The expected values below are for that origin, so they are exact for what
 * the renderer estimates; the offset is not hidden inside the tolerance.
 *
 * dmax = infinity. AO = 1 - F, F the form factor from the origin (normal +y) to the part of the
 * wall above it, a rectangle, by Lambert's polygon formula:
 *     F = (1 / 2 pi) | sum_i  angle(R_i, R_i+1) * (n . unit(R_i x R_i+1)) |,
 * R_i the rectangle's corners relative to the origin. For an infinite wall every direction with
 * d.x > 0 meets it, which is half the cosine-weighted hemisphere: F = 0.5, AO = 0.5 whatever a.
 * A 60 m wall at a <= 2.3 m gives F within ~2% of that; the test uses the exact F.
 *
 * dmax = D finite (1.5 here). A direction d is occluded iff it reaches the wall within D, i.e.
 * d.x >= c with c = a / D (the wall is far larger than D, so its edges never matter). Malley's
 * method: cosine-weighted directions project to points (d.x, d.z) uniform on the unit disk, so
 *     P(occluded) = area{disk, x >= c} / pi = (acos(c) - c sqrt(1 - c^2)) / pi,   c < 1,
 * and 0 when c >= 1: AO = 1 - (acos(c) - c sqrt(1 - c^2)) / pi. (c = 0 gives 0.5, as above.)
 * Pixels with a >= D must be exactly 1 with zero standard error.
 *
 * Obscurance, dmax = D = 1.5 (Zhukov's rho(d) = min(d / D, 1), d the distance to the occluder):
 * direction d meets the wall at distance a / d.x, so with c = a / D and x = d.x uniform-on-disk as
 * above, rho = 1 for x <= c and c / x for x > c. Integrating over the disk (chord 2 sqrt(1 - x^2)):
 *     O = 1 - (1/pi) [ (acos c - c s) - 2 c (ln((1 + s) / c) - s) ],   s = sqrt(1 - c^2),
 * using  integral_c^1 2 sqrt(1 - x^2) / x dx = 2 (ln((1 + s) / c) - s); and for the variance
 *     E[rho^2] = 1 - (1/pi) [ (acos c - c s) - 2 c^2 (s / c + asin c - pi / 2) ],
 * using  integral_c^1 2 sqrt(1 - x^2) / x^2 dx = 2 (s / c + asin c - pi / 2). c -> 0 gives 0.5 for
 * both (every hit at the wall's foot blocks fully); c >= 1 gives exactly 1. The distance is
 * measured from the ray origin, which the offset moves up, not toward the wall: a is exact.
 *
 * Tolerances: each AO sample is 0 or 1, so a pixel mean is binomial (obscurance: the analytic
 * variance above instead). The image-wide sum of
 * (measured - expected) must lie within 3 of the renderer's own standard errors (root sum of
 * squares), each pixel within 5 of its analytic binomial standard error, and the renderer's
 * variance must match the analytic binomial variance sum to 5% (it is an average over 1024
 * pixels; its own relative spread is ~1%). */
/* Each case runs with both samplers (reference.h): Sobol, whose variance must not exceed the
 * independent samples' (rt_zstats_check), and independent PCG32 numbers, whose variance must
 * match the analytic one. */
#include <math.h>

#include "ref_test_util.h"

int main(void)
{
    const float wall_x = 1.0f, wall_h = 60.0f, wall_z = 60.0f;
    gib_scene s;
    rt_scene_init(&s, "ao_wall");
    int m = rt_material(&s, 0.5f, 0.5f, 0.5f);
    rt_floor(&s, 0.0f, -3.0f, wall_x, -wall_z, wall_z, m);
    {
        const float a[3] = {wall_x, 0, wall_z}, b[3] = {wall_x, 0, -wall_z},
                    c[3] = {wall_x, wall_h, -wall_z}, d[3] = {wall_x, wall_h, wall_z};
        const float n[3] = {-1, 0, 0};
        rt_quad(&s, a, b, c, d, n, m);
    }
    const float eye[3] = {-0.5f, 3.0f, 0.0f}, tgt[3] = {-0.5f, 0.0f, 0.0f}, up[3] = {0, 0, -1};
    rt_camera(&s, eye, tgt, up, 30.0f);
    const double eps = gib_reference_ray_eps(&s);

    const int W = 32, H = 32, spp = 256;
    const float dmaxes[3] = {INFINITY, 1.5f, 1.5f};
    static const char *const names[3] = {"ao dmax inf", "ao dmax 1.5", "obscurance dmax 1.5"};
    for (int run = 0; run < 6; run++) { /* each case with Sobol, then with independent samples */
        const int k = run % 3, sobol = run < 3;
        gib_ref_params p = rt_params(GIB_COMP_AO, W, H, spp);
        p.sampler = sobol ? GIB_REF_SAMPLER_SOBOL : GIB_REF_SAMPLER_RANDOM;
        p.dmax = dmaxes[k];
        p.obscurance = k == 2;
        double var1 = 0.0; /* one sample's variance */
        gib_image img, sd;
        gib_ref_stats st;
        rt_render(&s, &p, &img, &sd, &st);
        rt_zstats z = {0};
        z.sobol = sobol;
        int exact_ones = 0, exact_bad = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double P[3];
                if (!rt_hit_plane_y(&s, 0, W, H, x, y, 0.0, P))
                    continue;
                double a = wall_x - P[0], expect;
                if (isinf(dmaxes[k])) {
                    double z0 = -wall_z - P[2], z1 = wall_z - P[2], top = wall_h - eps;
                    double R[4][3] = {{a, 0, z0}, {a, 0, z1}, {a, top, z1}, {a, top, z0}};
                    expect = 1.0 - rt_form_factor_up(R, 4);
                } else {
                    double c = a / dmaxes[k], sc = sqrt(fmax(0.0, 1.0 - c * c));
                    double cap = acos(fmin(c, 1.0)) - c * sc;
                    if (c >= 1.0) {
                        expect = 1.0;
                    } else if (k == 1) {
                        expect = 1.0 - cap / M_PI;
                    } else {
                        expect = 1.0 - (cap - 2.0 * c * (log((1.0 + sc) / c) - sc)) / M_PI;
                        double e2 =
                            1.0 - (cap - 2.0 * c * c * (sc / c + asin(c) - M_PI / 2.0)) / M_PI;
                        var1 = e2 - expect * expect;
                    }
                }
                if (k != 2)
                    var1 = expect * (1.0 - expect);
                double got = img.px[(y * W + x) * 3], se = sd.px[(y * W + x) * 3];
                if (expect == 1.0) {
                    exact_ones++;
                    exact_bad += got != 1.0 || se != 0.0;
                    continue;
                }
                rt_zstats_add(&z, got, se, expect, var1, spp);
                if (x == W / 2 && y == H / 2)
                    printf("%s, centre pixel: a = %.4f m, expected %.5f measured %.5f "
                           "stderr %.5f\n",
                           names[k], a, expect, got, se);
            }
        CHECK(z.n > 100, "too few pixels with a non-trivial expected value: %d", z.n);
        char what[64];
        snprintf(what, sizeof what, "%s, %s", names[k], sobol ? "sobol" : "random");
        rt_zstats_check(&z, what);
        CHECK(exact_bad == 0, "%s: %d of %d pixels beyond dmax are not exactly 1/0",
              names[k], exact_bad, exact_ones);
        CHECK(!k || exact_ones > 50, "test geometry: only %d pixels beyond dmax", exact_ones);
        printf("%s, %d pixels: mean expected %.6f measured %.6f, stderr of the mean %.6f "
               "(deviation %.2f sigma, max 3); worst pixel %.2f sigma; variance ratio %.4f; "
               "%d pixels beyond dmax exactly 1; noise_rmse %.5f\n",
               what, z.n, z.esum / z.n, z.msum / z.n, sqrt(z.var_r) / z.n, z.zsum, z.worst_z,
               z.var_r / z.var_a, exact_ones, st.noise_rmse);
        gib_image_free(&img);
        gib_image_free(&sd);
    }
    printf("(infinite wall limit 0.5; eps %.5f)\n", eps);
    rt_scene_free(&s);
    return failures ? 1 : 0;
}

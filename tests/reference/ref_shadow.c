/* Reference renderer, shadows in `direct`: a square occluder between a point light and a floor.
 *
 * Setup: light at (0, 4, 0); occluder x, z in [-0.5, 0.5] at y = 2; floor at y = 0. The segment
 * from a floor point P to the light crosses y = 2 at (P.x / 2, P.z / 2), so P is in the (hard,
 * point-light) shadow exactly when |P.x| < 1 and |P.z| < 1.
 * Expected: pixels whose floor point lies at least 0.02 inside the shadow square are exactly 0 (a
 * shadow ray that hits returns nothing, there is no other light, and nothing is added); pixels at
 * least 0.02 outside equal the unshadowed rho/pi * I cos / r^2 to 1e-4 relative (deterministic,
 * float only). The 0.02 margin keeps the check off the penumbra-free edge, where the pixel's
 * floor point and the occluder's edge are within float rounding of each other. Pixels that see
 * the occluder itself are skipped. */
#include <math.h>

#include "ref_test_util.h"

int main(void)
{
    gib_scene s;
    rt_scene_init(&s, "shadow");
    int m = rt_material(&s, 0.5f, 0.5f, 0.5f);
    rt_floor(&s, 0.0f, -10.0f, 10.0f, -10.0f, 10.0f, m);
    rt_floor(&s, 2.0f, -0.5f, 0.5f, -0.5f, 0.5f, m);
    rt_point_light(&s, 0.0f, 4.0f, 0.0f, 8.0f, 8.0f, 8.0f);
    const float eye[3] = {3.0f, 3.0f, 3.0f}, tgt[3] = {0.0f, 0.0f, 0.0f}, up[3] = {0, 1, 0};
    rt_camera(&s, eye, tgt, up, 40.0f);

    const int W = 48, H = 48;
    gib_ref_params p = rt_params(GIB_COMP_DIRECT, W, H, 1);
    gib_image img;
    gib_ref_stats st;
    rt_render(&s, &p, &img, NULL, &st);

    int shadowed = 0, lit = 0, bad_shadow = 0;
    double worst = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double P[3], Q[3];
            if (rt_hit_plane_y(&s, 0, W, H, x, y, 2.0, Q) && fabs(Q[0]) <= 0.52 &&
                fabs(Q[2]) <= 0.52)
                continue; /* sees the occluder (or its edge) */
            if (!rt_hit_plane_y(&s, 0, W, H, x, y, 0.0, P))
                continue;
            const float *v = &img.px[(y * W + x) * 3];
            double m_in = fmax(fabs(P[0]), fabs(P[2]));
            if (m_in < 0.98) {
                shadowed++;
                if (v[0] != 0.0f || v[1] != 0.0f || v[2] != 0.0f) {
                    bad_shadow++;
                    fprintf(stderr, "pixel (%d,%d) floor (%.3f,%.3f) in shadow has %g\n", x, y,
                            P[0], P[2], v[0]);
                }
            } else if (m_in > 1.02) {
                double d[3] = {-P[0], 4.0 - P[1], -P[2]};
                double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                double expect = 0.5 / M_PI * 8.0 * (d[1] / sqrt(r2)) / r2;
                double rel = fabs(v[0] - expect) / expect;
                worst = rel > worst ? rel : worst;
                lit++;
            }
        }
    CHECK(shadowed >= 20 && lit >= 20, "test geometry: %d shadowed, %d lit pixels", shadowed,
          lit);
    CHECK(bad_shadow == 0, "%d of %d shadowed pixels are not exactly 0", bad_shadow, shadowed);
    CHECK_AT_MOST("lit pixels: max relative error", worst, 1e-4, "deterministic, float only");
    printf("shadowed pixels: %d, all exactly 0 (expected 0); lit pixels: %d, max relative error "
           "%.3g vs rho/pi I cos/r^2 (tolerance 1e-4)\n",
           shadowed, lit, worst);

    gib_image_free(&img);
    rt_scene_free(&s);
    return failures ? 1 : 0;
}

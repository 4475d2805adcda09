/* Reference renderer, `direct` from a spot light: the falloff cos^e(theta) inside the outer angle
 * and nothing outside (scene.h, gib_light_eval).
 *
 * Setup: a spot 3 m above a diffuse plane pointing straight down, e = 8, outer angle 35 degrees.
 * For a point at angle theta from the axis, theta is also the incidence angle, so
 *   L = (rho / pi) * I * cos^e(theta) * cos(theta) / r^2,   r = h / cos(theta).
 * Checked: every pixel with theta < 34 degrees against that (1e-4 relative: deterministic, float
 * only; the cos^8 makes the relative error 8x the cosine's, still ~1e-6), every pixel with
 * theta > 36 degrees exactly 0 (the degree of margin keeps the test off the cone's edge, where
 * float rounding decides), and the ratio off-axis / on-axis after dividing out cos(theta) / r^2,
 * which isolates cos^e. */
#include <math.h>

#include "ref_test_util.h"

int main(void)
{
    gib_scene s;
    rt_scene_init(&s, "direct_spot");
    int m = rt_material(&s, 0.7f, 0.7f, 0.7f);
    rt_floor(&s, 0.0f, -20.0f, 20.0f, -20.0f, 20.0f, m);
    const float pos[3] = {0.0f, 3.0f, 0.0f}, dir[3] = {0.0f, -1.0f, 0.0f};
    const double I = 20.0, e = 8.0, outer = 35.0, rho = 0.7;
    rt_spot_light(&s, pos, dir, (float)I, (float)e, (float)outer);
    const float eye[3] = {0.0f, 6.0f, 0.0f}, tgt[3] = {0.0f, 0.0f, 0.0f}, up[3] = {0, 0, -1};
    rt_camera(&s, eye, tgt, up, 90.0f);

    const int W = 32, H = 32;
    gib_ref_params p = rt_params(GIB_COMP_DIRECT, W, H, 1);
    gib_image img;
    gib_ref_stats st;
    rt_render(&s, &p, &img, NULL, &st);

    double worst = 0.0;
    int inside = 0, outside = 0, outside_bad = 0;
    /* Track the most central and the most off-axis lit pixel for the cos^e ratio. */
    double c_axis = -1.0, v_axis = 0.0, c_off = 2.0, v_off = 0.0, g_axis = 0.0, g_off = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double P[3];
            if (!rt_hit_plane_y(&s, 0, W, H, x, y, 0.0, P))
                continue;
            double d[3] = {pos[0] - P[0], pos[1] - P[1], pos[2] - P[2]};
            double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            double cos_t = d[1] / sqrt(r2); /* angle from the axis = angle of incidence */
            double theta = acos(cos_t) * 180.0 / M_PI;
            double got = img.px[(y * W + x) * 3];
            if (theta < outer - 1.0) {
                double expect = rho / M_PI * I * pow(cos_t, e) * cos_t / r2;
                double rel = fabs(got - expect) / expect;
                worst = rel > worst ? rel : worst;
                inside++;
                double geom = cos_t / r2;
                if (cos_t > c_axis) {
                    c_axis = cos_t;
                    v_axis = got;
                    g_axis = geom;
                }
                if (cos_t < c_off) {
                    c_off = cos_t;
                    v_off = got;
                    g_off = geom;
                }
            } else if (theta > outer + 1.0) {
                outside++;
                if (img.px[(y * W + x) * 3] != 0.0f || img.px[(y * W + x) * 3 + 1] != 0.0f ||
                    img.px[(y * W + x) * 3 + 2] != 0.0f)
                    outside_bad++;
            }
        }
    CHECK(inside > 50 && outside > 50, "test geometry: %d pixels inside, %d outside", inside,
          outside);
    CHECK_AT_MOST("inside the cone: max relative error", worst, 1e-4,
                  "deterministic, float only; cos^8 makes it 8x the cosine's, still ~1e-6");
    CHECK(outside_bad == 0, "%d pixels outside the cone are not exactly 0", outside_bad);

    double ratio = (v_off / g_off) / (v_axis / g_axis);
    double expect_ratio = pow(c_off, e) / pow(c_axis, e);
    CHECK_NEAR("falloff ratio off-axis / on-axis vs cos^e ratio", expect_ratio, ratio,
               1e-4 * expect_ratio, "deterministic, float only: 1e-4 relative");
    printf("inside: %d pixels, max relative error %.3g (tolerance 1e-4); outside: %d pixels, all "
           "exactly 0\n",
           inside, worst, outside);
    printf("axis pixel theta %.2f deg, off-axis pixel theta %.2f deg: falloff ratio measured %.7f "
           "expected cos^8 ratio %.7f\n",
           acos(c_axis) * 180 / M_PI, acos(c_off) * 180 / M_PI, ratio, expect_ratio);

    gib_image_free(&img);
    rt_scene_free(&s);
    return failures ? 1 : 0;
}

/* Reference renderer, `direct` from a point light over a diffuse plane (ARCHITECTURE.md, "Reference
 * renderer": validated against a point light over a plane).
 *
 * Expected, at every pixel: L = (rho / pi) * I * cos(theta) / r^2, with the visible point found by
 * intersecting the pixel-centre camera ray with the plane in double precision.
 * Tolerance: 1e-4 relative. The estimator is deterministic (no random numbers), so the only error
 * is float arithmetic: the hit point interpolated in float (~1e-6 relative), r^2 and the cosine.
 * Also: spp 1 and spp 4 give bit-identical images and a zero standard error (the estimator is
 * deterministic, so the renderer takes one sample whatever spp asks, and reports spp 1), and the
 * ray count is exactly one primary plus one shadow ray per pixel. */
#include <math.h>
#include <string.h>

#include "ref_test_util.h"

int main(void)
{
    gib_scene s;
    rt_scene_init(&s, "direct_point");
    int m = rt_material(&s, 0.8f, 0.5f, 0.2f);
    rt_floor(&s, 0.0f, -10.0f, 10.0f, -10.0f, 10.0f, m);
    const float L[3] = {0.3f, 2.0f, -0.2f}, I[3] = {10.0f, 5.0f, 2.5f};
    rt_point_light(&s, L[0], L[1], L[2], I[0], I[1], I[2]);
    const float eye[3] = {0.0f, 4.0f, 0.0f}, tgt[3] = {0.0f, 0.0f, 0.0f}, up[3] = {0, 0, -1};
    rt_camera(&s, eye, tgt, up, 60.0f);

    const int W = 32, H = 32;
    gib_ref_params p = rt_params(GIB_COMP_DIRECT, W, H, 1);
    gib_image img, sd, img4, sd4;
    gib_ref_stats st, st4;
    rt_render(&s, &p, &img, &sd, &st);
    p.spp = 4;
    rt_render(&s, &p, &img4, &sd4, &st4);

    double worst = 0.0;
    int wx = 0, wy = 0, checked = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double P[3];
            if (!rt_hit_plane_y(&s, 0, W, H, x, y, 0.0, P))
                continue;
            double d[3] = {L[0] - P[0], L[1] - P[1], L[2] - P[2]};
            double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            double cos_t = d[1] / sqrt(r2);
            for (int c = 0; c < 3; c++) {
                double e = s.materials[m].albedo[c] / M_PI * I[c] * cos_t / r2;
                double got = img.px[(y * W + x) * 3 + c];
                double rel = fabs(got - e) / e;
                if (rel > worst) {
                    worst = rel;
                    wx = x;
                    wy = y;
                }
            }
            checked++;
        }
    CHECK(checked == W * H, "every pixel should see the plane, %d did", checked);
    char what[96];
    snprintf(what, sizeof what, "max relative error (at pixel (%d, %d))", wx, wy);
    CHECK_AT_MOST(what, worst, 1e-4,
                  "deterministic: float arithmetic only (hit point ~1e-6, r^2, the cosine)");
    /* Three sample pixels for the log: expected vs measured. */
    const int probe[3][2] = {{16, 16}, {3, 5}, {29, 30}};
    for (int i = 0; i < 3; i++) {
        int x = probe[i][0], y = probe[i][1];
        double P[3];
        rt_hit_plane_y(&s, 0, W, H, x, y, 0.0, P);
        double d[3] = {L[0] - P[0], L[1] - P[1], L[2] - P[2]};
        double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        double e = 0.8 / M_PI * 10.0 * (d[1] / sqrt(r2)) / r2;
        printf("pixel (%2d,%2d): expected R %.7f measured %.7f stderr %.1g\n", x, y, e,
               img.px[(y * W + x) * 3], sd.px[(y * W + x) * 3]);
    }
    printf("max relative error over %d pixels x 3 channels: %.3g (tolerance 1e-4)\n", checked,
           worst);

    size_t bytes = (size_t)W * H * 3 * sizeof(float);
    CHECK(memcmp(img.px, img4.px, bytes) == 0, "spp 4 differs from spp 1");
    int sd_zero = 1;
    for (int i = 0; i < W * H * 3; i++)
        sd_zero &= sd.px[i] == 0.0f && sd4.px[i] == 0.0f;
    CHECK(sd_zero, "a deterministic estimator must have zero standard error");
    CHECK(st.noise_rmse == 0.0 && st4.noise_rmse == 0.0, "noise_rmse %g / %g, expected 0",
          st.noise_rmse, st4.noise_rmse);
    CHECK(st.rays == 2LL * W * H, "rays %lld, expected %d", st.rays, 2 * W * H);
    CHECK(st4.rays == 2LL * W * H && st4.spp == 1 && st4.deterministic,
          "spp 4: rays %lld (expected %d), spp %d (expected 1)", st4.rays, 2 * W * H, st4.spp);
    printf("stats: mean %.6f noise_rmse %g rays %lld (spp 4: %lld)\n", st.mean, st.noise_rmse,
           st.rays, st4.rays);

    gib_image_free(&img);
    gib_image_free(&sd);
    gib_image_free(&img4);
    gib_image_free(&sd4);
    rt_scene_free(&s);
    return failures ? 1 : 0;
}

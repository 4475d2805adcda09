/* Reference renderer, `ao` on an open plane, seen obliquely so that the top rows see the sky.
 *
 * Expected: every pixel that sees the plane is exactly 1 with a standard error of exactly 0 —
 * nothing lies above the plane, so every cosine-weighted ray escapes and every sample is 1 (no
 * tolerance: a single occluded sample would show as a value below 1). Every pixel whose primary
 * ray misses is exactly 0 in every channel (the renderer's rule for misses). Checked for bounded
 * and unbounded dmax. */
#include "ref_test_util.h"

int main(void)
{
    gib_scene s;
    rt_scene_init(&s, "ao_plane");
    int m = rt_material(&s, 0.5f, 0.5f, 0.5f);
    rt_floor(&s, 0.0f, -10.0f, 10.0f, -10.0f, 10.0f, m);
    const float eye[3] = {0.0f, 1.0f, 3.0f}, tgt[3] = {0.0f, 0.5f, 0.0f}, up[3] = {0, 1, 0};
    rt_camera(&s, eye, tgt, up, 60.0f);

    const int W = 32, H = 32, spp = 16;
    const float dmaxes[2] = {0.0f, 0.5f};
    for (int k = 0; k < 2; k++) {
        gib_ref_params p = rt_params(GIB_COMP_AO, W, H, spp);
        p.dmax = dmaxes[k];
        gib_image img, sd;
        gib_ref_stats st;
        rt_render(&s, &p, &img, &sd, &st);
        int hits = 0, misses = 0, bad = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double P[3];
                int hit = rt_hit_plane_y(&s, 0, W, H, x, y, 0.0, P) && P[0] > -10 &&
                          P[0] < 10 && P[2] > -10 && P[2] < 10;
                for (int c = 0; c < 3; c++) {
                    float v = img.px[(y * W + x) * 3 + c], e = sd.px[(y * W + x) * 3 + c];
                    if (v != (hit ? 1.0f : 0.0f) || e != 0.0f)
                        bad++;
                }
                hits += hit;
                misses += !hit;
            }
        CHECK(hits > 100 && misses > 100, "test geometry: %d hits, %d misses", hits, misses);
        CHECK(bad == 0, "dmax %g: %d values differ from 1 (plane) / 0 (sky)", dmaxes[k], bad);
        CHECK(st.noise_rmse == 0.0, "noise_rmse %g, expected 0", st.noise_rmse);
        CHECK(st.rays == (long long)W * H + (long long)hits * spp, "rays %lld, expected %lld",
              st.rays, (long long)W * H + (long long)hits * spp);
        printf("dmax %s: %d plane pixels all exactly 1 (expected 1, stderr 0), %d sky pixels all "
               "exactly 0; rays %lld\n",
               k ? "0.5" : "inf", hits, misses, st.rays);
        gib_image_free(&img);
        gib_image_free(&sd);
    }
    rt_scene_free(&s);
    return failures ? 1 : 0;
}

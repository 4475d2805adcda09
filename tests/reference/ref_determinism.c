/* Reference renderer, determinism (DESIGN.md, "Reference renderer": a rerun gives the same image
 * bit for bit).
 *
 * Expected: renders with 1, 2, 3 and 7 threads give bit-identical images, standard-error images
 * and statistics (mean, noise_rmse, rays): each pixel has its own seeded generator and
 * image-wide sums are taken in row order. A different seed must change the image (else the seed
 * is ignored). The scene has an occluder with an alpha mask, so the Embree filter callbacks run
 * concurrently too. No tolerance: equality of bytes. */
#include <string.h>

#include "ref_test_util.h"

static void rt_build(gib_scene *s)
{
    rt_scene_init(s, "determinism");
    int m = rt_material(s, 0.6f, 0.6f, 0.6f);
    rt_floor(s, 0.0f, -4.0f, 4.0f, -4.0f, 4.0f, m);
    /* A checkerboard cut-out above the floor. */
    float rgba[8 * 8 * 4];
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++)
            for (int c = 0; c < 4; c++)
                rgba[(y * 8 + x) * 4 + c] = ((x + y) & 1) ? 1.0f : 0.0f;
    int mc = rt_material(s, 0.3f, 0.6f, 0.9f);
    s->materials[mc].alpha_tex = rt_texture(s, 8, 8, rgba);
    s->materials[mc].two_sided = 1;
    s->features |= GIB_FEAT_ALPHA_MASK;
    rt_floor(s, 0.4f, -1.0f, 1.0f, -1.0f, 1.0f, mc);
    const float a[3] = {1.5f, 0, 1.5f}, b[3] = {1.5f, 0, -1.5f}, c[3] = {1.5f, 1.5f, -1.5f},
                d[3] = {1.5f, 1.5f, 1.5f}, n[3] = {-1, 0, 0};
    rt_quad(s, a, b, c, d, n, m);
    rt_point_light(s, -0.5f, 2.0f, 0.5f, 5.0f, 5.0f, 5.0f);
    const float eye[3] = {-2.5f, 2.5f, 2.5f}, tgt[3] = {0.5f, 0.0f, 0.0f}, up[3] = {0, 1, 0};
    rt_camera(s, eye, tgt, up, 55.0f);
}

int main(void)
{
    gib_scene s;
    rt_build(&s);
    const int W = 40, H = 37; /* odd height: rows do not split evenly over the threads */
    const int threads[4] = {1, 2, 3, 7};
    for (int comp = 0; comp < GIB_COMP_COUNT; comp++) {
        gib_image base = {0}, base_sd = {0};
        gib_ref_stats base_st = {0};
        gib_ref_params p = rt_params(comp, W, H, comp == GIB_COMP_AO ? 32 : 2);
        p.dmax = 1.0f;
        size_t bytes = (size_t)W * H * 3 * sizeof(float);
        for (int i = 0; i < 4; i++) {
            gib_image img, sd;
            gib_ref_stats st;
            p.threads = threads[i];
            rt_render(&s, &p, &img, &sd, &st);
            if (i == 0) {
                base = img;
                base_sd = sd;
                base_st = st;
                continue;
            }
            RT_CHECK(memcmp(img.px, base.px, bytes) == 0, "%s: %d threads: image differs from 1",
                     gib_component_name(comp), threads[i]);
            RT_CHECK(memcmp(sd.px, base_sd.px, bytes) == 0,
                     "%s: %d threads: stderr differs from 1", gib_component_name(comp), threads[i]);
            RT_CHECK(st.mean == base_st.mean && st.noise_rmse == base_st.noise_rmse &&
                         st.rays == base_st.rays,
                     "%s: %d threads: statistics differ", gib_component_name(comp), threads[i]);
            gib_image_free(&img);
            gib_image_free(&sd);
        }
        if (comp == GIB_COMP_AO) {
            gib_image img;
            p.seed = 2;
            rt_render(&s, &p, &img, NULL, NULL);
            RT_CHECK(memcmp(img.px, base.px, bytes) != 0, "ao: seed 2 gives the seed-1 image");
            gib_image_free(&img);
        }
        printf("%s: threads 1, 2, 3, 7 bit-identical (image, stderr, stats); mean %.6f "
               "noise_rmse %.6f rays %lld\n",
               gib_component_name(comp), base_st.mean, base_st.noise_rmse, base_st.rays);
        gib_image_free(&base);
        gib_image_free(&base_sd);
    }
    rt_scene_free(&s);
    return rt_failures ? 1 : 0;
}

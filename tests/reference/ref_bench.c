/* Reference renderer throughput: a benchmark, not in ctest (target bench_ref_throughput).
 *
 * Usage: ref_bench [scene-name-or-path]. Without an argument it builds a ~100k-triangle scene
 * procedurally: an open box (floor, back and left walls) holding a 10 x 10 grid of UV spheres of
 * 1024 triangles each, lit by a point light. Prints rays/s for `direct` (1 spp, 512x512 and
 * 1024x1024) and `ao` (64 spp, 256x256, dmax unbounded and 0.5 m), with all cores and with one
 * thread. Rays/s counts every ray (primary, shadow, ao) over the whole call, BVH build included. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ref_test_util.h"

static void rt_sphere(gib_scene *s, const float c[3], float r, int seg, int rings, int mat)
{
    uint32_t v0 = s->vertex_count, t0 = s->triangle_count;
    uint32_t nv = (uint32_t)((seg + 1) * (rings + 1)), nt = (uint32_t)(2 * seg * rings);
    s->positions = realloc(s->positions, 3 * sizeof(float) * (v0 + nv));
    s->normals = realloc(s->normals, 3 * sizeof(float) * (v0 + nv));
    s->uvs = realloc(s->uvs, 2 * sizeof(float) * (v0 + nv));
    s->indices = realloc(s->indices, 3 * sizeof(uint32_t) * (t0 + nt));
    s->tri_material = realloc(s->tri_material, sizeof(uint32_t) * (t0 + nt));
    if (!s->positions || !s->normals || !s->uvs || !s->indices || !s->tri_material)
        abort();
    for (int j = 0; j <= rings; j++)
        for (int i = 0; i <= seg; i++) {
            double th = M_PI * j / rings, ph = 2.0 * M_PI * i / seg;
            float n[3] = {(float)(sin(th) * cos(ph)), (float)cos(th), (float)(sin(th) * sin(ph))};
            uint32_t v = v0 + (uint32_t)(j * (seg + 1) + i);
            for (int k = 0; k < 3; k++) {
                s->normals[3 * v + k] = n[k];
                s->positions[3 * v + k] = c[k] + r * n[k];
            }
            s->uvs[2 * v] = (float)i / seg;
            s->uvs[2 * v + 1] = (float)j / rings;
        }
    uint32_t t = t0;
    for (int j = 0; j < rings; j++)
        for (int i = 0; i < seg; i++) {
            uint32_t a = v0 + (uint32_t)(j * (seg + 1) + i), b = a + 1, cc = a + (uint32_t)seg + 1,
                     d = cc + 1;
            /* counter-clockwise seen from outside */
            uint32_t tri[6] = {a, b, d, a, d, cc};
            memcpy(s->indices + 3 * t, tri, sizeof tri);
            s->tri_material[t] = s->tri_material[t + 1] = (uint32_t)mat;
            t += 2;
        }
    s->vertex_count += nv;
    s->triangle_count += nt;
}

static void rt_build(gib_scene *s)
{
    rt_scene_init(s, "bench_spheres");
    int m = rt_material(s, 0.7f, 0.7f, 0.7f);
    rt_floor(s, 0.0f, -6, 6, -6, 6, m);
    const float n_back[3] = {0, 0, 1}, n_left[3] = {1, 0, 0};
    const float b0[3] = {-6, 0, -6}, b1[3] = {6, 0, -6}, b2[3] = {6, 6, -6}, b3[3] = {-6, 6, -6};
    rt_quad(s, b0, b1, b2, b3, n_back, m);
    const float l0[3] = {-6, 0, 6}, l1[3] = {-6, 0, -6}, l2[3] = {-6, 6, -6}, l3[3] = {-6, 6, 6};
    rt_quad(s, l0, l1, l2, l3, n_left, m);
    for (int i = 0; i < 10; i++)
        for (int j = 0; j < 10; j++) {
            float c[3] = {-4.5f + i, 0.45f + 0.3f * (float)((i * 7 + j * 3) % 5) / 5.0f,
                          -4.5f + j};
            rt_sphere(s, c, 0.45f, 32, 16, m);
        }
    rt_point_light(s, 1.0f, 5.0f, 2.0f, 40.0f, 40.0f, 40.0f);
    const float eye[3] = {5.0f, 5.0f, 9.0f}, tgt[3] = {-1.0f, 0.0f, -1.0f}, up[3] = {0, 1, 0};
    rt_camera(s, eye, tgt, up, 50.0f);
}

static void rt_run(const gib_scene *s, int comp, int size, int spp, float dmax, int threads)
{
    gib_ref_params p = rt_params(comp, size, size, spp);
    p.dmax = dmax;
    p.threads = threads;
    gib_image img;
    gib_ref_stats st;
    rt_render(s, &p, &img, NULL, &st);
    printf("%-6s %4dx%-4d spp %3d dmax %-4s threads %s: %6.2f s, %9lld rays, %6.2f Mrays/s, "
           "mean %.4f, noise_rmse %.5f\n",
           gib_component_name(comp), size, size, spp, dmax > 0 ? "0.5" : "inf",
           threads ? "1  " : "all", st.seconds, st.rays, st.rays / st.seconds * 1e-6, st.mean,
           st.noise_rmse);
    gib_image_free(&img);
}

int main(int argc, char **argv)
{
    gib_scene s;
    int loaded = 0;
    if (argc > 1) {
        gib_error err = {0};
        if (gib_scene_load(argv[1], &s, &err) < 0) {
            fprintf(stderr, "ref_bench: %s\n", err.msg);
            return 1;
        }
        loaded = 1;
    } else {
        rt_build(&s);
    }
    printf("scene '%s': %u triangles, ray eps %.3g\n", s.name, s.triangle_count,
           gib_reference_ray_eps(&s));
    /* A 1x1 image costs one BVH build and two rays: the fixed cost inside every number below. */
    rt_run(&s, GIB_COMP_DIRECT, 1, 1, 0.0f, 0);
    for (int threads = 0; threads <= 1; threads++) {
        rt_run(&s, GIB_COMP_DIRECT, 512, 1, 0.0f, threads);
        rt_run(&s, GIB_COMP_DIRECT, 1024, 1, 0.0f, threads);
        rt_run(&s, GIB_COMP_AO, 256, 64, 0.0f, threads);
        rt_run(&s, GIB_COMP_AO, 256, 64, 0.5f, threads);
    }
    if (loaded)
        gib_scene_free(&s);
    else
        rt_scene_free(&s);
    return 0;
}

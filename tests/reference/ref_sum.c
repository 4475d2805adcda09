/* Reference renderer: the components add up. With max_depth 2 (paths of at most two surface
 * vertices), every path class is counted by exactly one component (reference.h); enumerated with
 * x1 the visible point, x2 the vertex before it, D diffuse, S Phong or mirror:
 *
 *   1 vertex    L D E, L S E                      direct
 *   2 vertices  L D D E      (x1 D, x2 D)         indirect
 *               L D S E      (x1 S, x2 D)         glossy
 *               L S D E      (x1 D, x2 S)         caustic (max_specular 1)
 *               L S S E      (x1 S, x2 S)         higher  (= full minus the four above)
 *   not counted by any: L E and L S_mirror E (a point light seen directly or in a mirror: zero
 *   measure at a pixel centre), L S_mirror S_mirror E (the same, twice mirrored).
 *
 * So full(max_depth 2) = direct + indirect + glossy + caustic + higher, in expectation. The scene
 * has every class: a closed box with a glossy Phong floor (rho_d 0.35, rho_s 0.35, n 12), coloured
 * diffuse walls, a mirror panel (rho_s 0.9) on the back wall and a point light. The estimators are
 * independent: direct by next-event estimation, indirect and glossy by one sampled bounce, caustic
 * by light tracing (Phong and mirror), higher and full by camera paths plus light tracing of the
 * mirror-first paths, each with its own seeds.
 *
 * Each class is estimated with the same strategy, hence the same pixel footprint, in every
 * component (reference.h: mirror-first paths light traced, over the pixel's area; all others from
 * the camera, at its centre), so the equality is exact in expectation, pixel by pixel.
 *
 * Tolerances, per channel: the image means must agree within 3 standard errors of their
 * difference (the renderer's own errors of the independent renders, added in quadrature), and
 * every 4x4 block's within 4 (64 blocks x 3 channels; a block mean of 16 pixels is near normal
 * where a single pixel of light tracing is not). Then a negative control: leaving `higher` out
 * must fail the same check (else the check has no power).
 *
 * The same again with the box open to a sky (no ceiling; sky 0.5 0.55 0.65) as well as the point
 * light: every class above then also has the sky as its L (L_sky D E in direct, L_sky D D E in
 * indirect, L_sky D S E in glossy, L_sky S D E in caustic — the sky in the mirror and the glossy
 * floor, from camera paths — and L_sky S S E in higher), each found by the sky's next-event
 * estimation at its light-side vertex in every component, so the same equality must hold, and a
 * sky path counted by two parts, or by one part and not by full, shows as a difference here. (A
 * double count inside the path tracer that full and higher share would cancel: ref_sky's exact
 * full = rho_d L on an open plane catches that one.) */
#include <math.h>
#include <stdlib.h>

#include "ref_test_util.h"

static void rt_box(gib_scene *s, int sky)
{
    rt_scene_init(s, sky ? "sum_box_sky" : "sum_box");
    int floor_m = rt_material(s, 0.35f, 0.35f, 0.35f);
    s->materials[floor_m].spec_type = GIB_SPEC_PHONG;
    s->materials[floor_m].specular[0] = s->materials[floor_m].specular[1] =
        s->materials[floor_m].specular[2] = 0.35f;
    s->materials[floor_m].phong_n = 12.0f;
    int white = rt_material(s, 0.7f, 0.7f, 0.7f), red = rt_material(s, 0.6f, 0.15f, 0.1f);
    int green = rt_material(s, 0.15f, 0.55f, 0.15f), back = rt_material(s, 0.5f, 0.5f, 0.45f);
    int mirror = rt_material(s, 0.0f, 0.0f, 0.0f);
    s->materials[mirror].spec_type = GIB_SPEC_MIRROR;
    s->materials[mirror].specular[0] = s->materials[mirror].specular[1] =
        s->materials[mirror].specular[2] = 0.9f;
    s->features |= GIB_FEAT_SPECULAR | GIB_FEAT_MIRROR | GIB_FEAT_CLOSED;
    rt_floor(s, 0.0f, -1, 1, -1, 1, floor_m);
    if (sky) /* open to a sky instead of the ceiling */
        rt_sky(s, 0.5f, 0.55f, 0.65f);
    else { /* ceiling, normal down */
        const float a[3] = {-1, 2, -1}, b[3] = {1, 2, -1}, c[3] = {1, 2, 1}, d[3] = {-1, 2, 1};
        const float n[3] = {0, -1, 0};
        rt_quad(s, a, b, c, d, n, white);
    }
    { /* left x = -1, normal +x */
        const float a[3] = {-1, 0, 1}, b[3] = {-1, 0, -1}, c[3] = {-1, 2, -1}, d[3] = {-1, 2, 1};
        const float n[3] = {1, 0, 0};
        rt_quad(s, a, b, c, d, n, red);
    }
    { /* right x = 1, normal -x */
        const float a[3] = {1, 0, -1}, b[3] = {1, 0, 1}, c[3] = {1, 2, 1}, d[3] = {1, 2, -1};
        const float n[3] = {-1, 0, 0};
        rt_quad(s, a, b, c, d, n, green);
    }
    { /* back z = -1, normal +z */
        const float a[3] = {-1, 0, -1}, b[3] = {1, 0, -1}, c[3] = {1, 2, -1}, d[3] = {-1, 2, -1};
        const float n[3] = {0, 0, 1};
        rt_quad(s, a, b, c, d, n, back);
    }
    { /* front z = 1, normal -z (behind the camera) */
        const float a[3] = {1, 0, 1}, b[3] = {-1, 0, 1}, c[3] = {-1, 2, 1}, d[3] = {1, 2, 1};
        const float n[3] = {0, 0, -1};
        rt_quad(s, a, b, c, d, n, white);
    }
    { /* the mirror panel, 1 cm in front of the back wall */
        const float a[3] = {-0.6f, 0.3f, -0.99f}, b[3] = {0.6f, 0.3f, -0.99f},
                    c[3] = {0.6f, 1.5f, -0.99f}, d[3] = {-0.6f, 1.5f, -0.99f};
        const float n[3] = {0, 0, 1};
        rt_quad(s, a, b, c, d, n, mirror);
    }
    rt_point_light(s, 0.35f, 1.7f, -0.1f, 2.0f, 2.0f, 2.0f);
    const float eye[3] = {0.0f, 1.2f, 0.95f}, tgt[3] = {0.0f, 0.6f, -1.0f}, up[3] = {0, 1, 0};
    rt_camera(s, eye, tgt, up, 65.0f);
}

enum { W = 32, H = 32, NB = 4 };

typedef struct sums { /* per channel: summed pixel values and summed variances of the mean */
    double img[3][W * H], var[3][W * H];
} sums;

static void rt_add(const gib_scene *s, int comp, int spp, sums *acc, sums *acc2, double *mean)
{
    gib_ref_params p = rt_params(comp, W, H, spp);
    /* Independent samples: the 4-sigma bound on 192 blocks assumes block standard errors of many
     * degrees of freedom; Sobol's come from 8 batches a pixel (7 each, Student-t tails), which
     * would need a wider bound. The sum's exactness does not depend on the sampler; Sobol's
     * unbiasedness is tested against closed forms (ref_ao_wall, ref_sky, ref_noise_honest). */
    p.sampler = GIB_REF_SAMPLER_RANDOM;
    p.max_depth = 2;
    p.max_specular = 1;
    gib_image img, sd;
    gib_ref_stats st;
    rt_render(s, &p, &img, &sd, &st);
    *mean = 0.0;
    int bad = 0;
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++) {
            double v = img.px[3 * i + c], e = sd.px[3 * i + c];
            bad += !isfinite(v);
            acc->img[c][i] += v;
            acc->var[c][i] += e * e; /* independent renders: variances add */
            if (acc2) {
                acc2->img[c][i] += v;
                acc2->var[c][i] += e * e;
            }
            *mean += v / (3 * W * H);
        }
    CHECK(bad == 0, "%s: %d non-finite pixels", gib_component_name(comp), bad);
    printf("  %-8s %5d spp: mean %.6f  noise_rmse %.3g  %.2f s\n", gib_component_name(comp),
           spp, *mean, st.noise_rmse, st.seconds);
    gib_image_free(&img);
    gib_image_free(&sd);
}

/* The image means' z (signed) and the largest |z| of the 4x4 block means between a and b. */
static void rt_diff(const sums *a, const sums *b, double *zmean, double *zblock)
{
    rt_z_diff(&a->img[0][0], &a->var[0][0], &b->img[0][0], &b->var[0][0], W, H, NB, zmean,
              zblock);
}

static void rt_sum(int sky)
{
    gib_scene s;
    rt_box(&s, sky);
    sums *parts = calloc(1, sizeof *parts), *full = calloc(1, sizeof *full);
    sums *nohigher = calloc(1, sizeof *nohigher);
    if (!parts || !full || !nohigher) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    const int comps[5] = {GIB_COMP_DIRECT, GIB_COMP_INDIRECT, GIB_COMP_GLOSSY, GIB_COMP_CAUSTIC,
                          GIB_COMP_HIGHER};
    const int spp[5] = {sky ? 256 : 1, 256, 256, 1024, 512}; /* direct: random with a sky */
    double means[5], mfull;
    printf("components, %dx%d, max_depth 2, %s:\n", W, H,
           sky ? "open box under a sky (no ceiling)" : "closed box");
    for (int i = 0; i < 5; i++)
        rt_add(&s, comps[i], spp[i], parts, comps[i] != GIB_COMP_HIGHER ? nohigher : NULL,
               &means[i]);
    rt_add(&s, GIB_COMP_FULL, 1024, full, NULL, &mfull);
    for (int i = 0; i < 5; i++)
        CHECK(means[i] > 0.0, "%s is 0: the scene lacks its paths", gib_component_name(comps[i]));
    double zm, zb, zm0, zb0;
    rt_diff(parts, full, &zm, &zb);
    rt_diff(nohigher, full, &zm0, &zb0);
    double sum = 0.0;
    for (int i = 0; i < 5; i++)
        sum += means[i];
    printf("sum of components %.6f vs full %.6f: image means differ by %.2f sigma (max 3, worst "
           "channel), worst 4x4 block %.2f sigma (max 4)\n",
           sum, mfull, zm, zb);
    printf("negative control, higher left out: %.2f sigma, worst block %.2f sigma (must fail)\n",
           zm0, zb0);
    CHECK_NEAR("sum vs full: image means' difference (standard errors)", 0, zm, 3.0,
               "3 standard errors of the difference, the renders' own in quadrature");
    CHECK_AT_MOST("sum vs full: worst 4x4 block (standard errors)", zb, 4.0,
                  "a block mean of 16 pixels is near normal; 64 blocks x 3 channels");
    CHECK(fabs(zm0) > 3.0 || zb0 > 4.0, "without higher the sum still matches full: the check "
          "cannot see a missing path class");
    free(parts);
    free(full);
    free(nohigher);
    rt_scene_free(&s);
}

int main(void)
{
    rt_sum(0);
    rt_sum(1);
    return failures ? 1 : 0;
}

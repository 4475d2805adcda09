/* Reference renderer, `caustic` (L S D E, light tracing) from a plane mirror, against the closed
 * form: a plane mirror of reflectance rho_s shows the point light mirrored through its plane, so
 * the light it reflects onto the floor is that of a point light of intensity rho_s I at the
 * mirrored position L':
 *     L_caustic(P) = (rho_d / pi) rho_s I cos(theta') / |P - L'|^2,   cos(theta') = (L'_y - P_y) / |P - L'|,
 * wherever the segment P -> L' crosses the mirror inside its extent and nothing else blocks it.
 *
 * Setup: diffuse floor y = 0 (rho_d 0.6) for x <= 1; a mirror wall x = 1, y in [0, 3], z in [-3, 3],
 * rho_s 0.8, rho_d 0, facing the light; point light I = 4 at L = (0, 1, 0), so L' = (2, 1, 0). Every
 * floor point in view sees L' through the mirror (the crossing is at height (1 - P_x)/(2 - P_x) <
 * 1 and |z| < 3), so the closed form holds at every pixel. The camera looks straight down from
 * 3 m and does not see the mirror.
 *
 * The ray offset: a reflected particle leaves the mirror from a point moved by the renderer's eps
 * (gib_reference_ray_eps, 1.4 mm here) along the mirror's normal, i.e. every reflected ray is
 * shifted by -eps in x, which is the same as mirroring the light to L' = (2 - eps, 1, 0). The
 * expected values use that L' (the offset is not hidden in the tolerance: ignoring it biases the
 * mean by 0.3%, which 16k passes resolve).
 *
 * What is compared: light tracing splats into the pixel a point projects to, so a caustic pixel is
 * the AVERAGE of the radiance over the pixel's area (reference.h); the expected value of each
 * pixel is the closed form averaged over 8 x 8 points of its footprint on the floor (the closed
 * form is smooth: the midpoint rule's error is below 1e-5 relative). The image mean must lie within
 * 3 standard errors (the renderer's own) of the expected mean, and every 4 x 4 block within 4 (its
 * 16 pixels x passes make the block mean nearly normal; one pixel's splat counts are too sparse).
 * Also: `direct` of the mirror-only path is not counted twice — `direct` at these pixels is the
 * unmirrored light alone, checked exactly (deterministic, 1e-4 relative). */
#include <math.h>
#include <string.h>

#include "ref_test_util.h"

static const double LP[3] = {0.0, 1.0, 0.0};
static double LM[3] = {2.0, 1.0, 0.0};
static const double I = 4.0, RHO_D = 0.6, RHO_S = 0.8;

static double rt_point_term(const double P[3], const double L[3], double inten)
{
    double d[3] = {L[0] - P[0], L[1] - P[1], L[2] - P[2]};
    double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    return RHO_D / M_PI * inten * (d[1] / sqrt(r2)) / r2;
}

int main(void)
{
    gib_scene s;
    rt_scene_init(&s, "caustic_mirror");
    int floor_m = rt_material(&s, (float)RHO_D, (float)RHO_D, (float)RHO_D);
    int mirror = rt_material(&s, 0.0f, 0.0f, 0.0f);
    s.materials[mirror].spec_type = GIB_SPEC_MIRROR;
    s.materials[mirror].specular[0] = s.materials[mirror].specular[1] =
        s.materials[mirror].specular[2] = (float)RHO_S;
    s.features |= GIB_FEAT_MIRROR;
    rt_floor(&s, 0.0f, -6.0f, 1.0f, -6.0f, 6.0f, floor_m);
    {
        const float a[3] = {1, 0, 3}, b[3] = {1, 0, -3}, c[3] = {1, 3, -3}, d[3] = {1, 3, 3};
        const float n[3] = {-1, 0, 0};
        rt_quad(&s, a, b, c, d, n, mirror);
    }
    rt_point_light(&s, (float)LP[0], (float)LP[1], (float)LP[2], (float)I, (float)I, (float)I);
    const float eye[3] = {-0.5f, 3.0f, 0.0f}, tgt[3] = {-0.5f, 0.0f, 0.0f}, up[3] = {0, 0, -1};
    rt_camera(&s, eye, tgt, up, 50.0f);
    LM[0] = 2.0 - gib_reference_ray_eps(&s);

    const int W = 32, H = 32, B = 4, passes = 8192;
    gib_ref_params p = rt_params(GIB_COMP_CAUSTIC, W, H, passes);
    gib_image img, sd;
    gib_ref_stats st;
    rt_render(&s, &p, &img, &sd, &st);

    double expect[32 * 32];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double acc = 0.0;
            for (int j = 0; j < 8; j++)
                for (int i = 0; i < 8; i++) {
                    float o[3], d[3];
                    gib_camera_ray(&s.cameras[0], W, H, (float)x + (i + 0.5f) / 8.0f,
                                   (float)y + (j + 0.5f) / 8.0f, o, d);
                    double t = -(double)o[1] / d[1], P[3];
                    for (int k = 0; k < 3; k++)
                        P[k] = o[k] + t * d[k];
                    acc += rt_point_term(P, LM, RHO_S * I);
                }
            expect[y * W + x] = acc / 64.0;
        }
    double mean_e = 0.0, mean_m = 0.0, var = 0.0, worst = 0.0;
    for (int i = 0; i < W * H; i++) {
        mean_e += expect[i] / (W * H);
        mean_m += img.px[3 * i] / (W * H);
        var += (double)sd.px[3 * i] * sd.px[3 * i];
    }
    double se_mean = sqrt(var) / (W * H);
    for (int by = 0; by < H; by += B)
        for (int bx = 0; bx < W; bx += B) {
            double e = 0.0, m = 0.0, v = 0.0;
            for (int y = by; y < by + B; y++)
                for (int x = bx; x < bx + B; x++) {
                    e += expect[y * W + x];
                    m += img.px[3 * (y * W + x)];
                    v += (double)sd.px[3 * (y * W + x)] * sd.px[3 * (y * W + x)];
                }
            double z = fabs(m - e) / sqrt(v);
            worst = z > worst ? z : worst;
        }
    double zmean = (mean_m - mean_e) / se_mean;
    char what[160];
    snprintf(what, sizeof what, "caustic: image mean %.6f vs expected %.6f (standard errors)",
             mean_m, mean_e);
    CHECK_NEAR(what, 0, zmean, 3.0, "3 of the renderer's own standard errors");
    CHECK_AT_MOST("caustic: worst 4x4 block (standard errors)", worst, 4.0,
                  "16 pixels x passes make a block mean nearly normal");
    int cx = W / 2, cy = H / 2;
    printf("caustic, centre pixel: expected %.6f measured %.6f stderr %.6f\n", expect[cy * W + cx],
           img.px[3 * (cy * W + cx)], sd.px[3 * (cy * W + cx)]);
    printf("caustic, %d passes of %d particles: image mean expected %.6f measured %.6f, stderr of "
           "the mean %.2g (%.2f sigma, max 3); worst 4x4 block %.2f sigma (max 4); %lld rays in "
           "%.2f s\n",
           passes, W * H, mean_e, mean_m, se_mean, zmean, worst, st.rays, st.seconds);
    gib_image_free(&img);
    gib_image_free(&sd);

    /* direct: the light itself only (the mirrored light is caustic's). */
    p = rt_params(GIB_COMP_DIRECT, W, H, 1);
    rt_render(&s, &p, &img, NULL, &st);
    double wrel = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double P[3];
            rt_hit_plane_y(&s, 0, W, H, x, y, 0.0, P);
            double e = rt_point_term(P, LP, I);
            wrel = fmax(wrel, fabs(img.px[3 * (y * W + x)] - e) / e);
        }
    CHECK_AT_MOST("direct: max relative error vs the unmirrored light", wrel, 1e-4,
                  "deterministic: float arithmetic only");
    printf("direct: the unmirrored light only, max relative error %.3g (tol 1e-4)\n", wrel);
    gib_image_free(&img);
    rt_scene_free(&s);
    return failures ? 1 : 0;
}

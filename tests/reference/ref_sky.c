/* Reference renderer, a uniform sky (gib_scene.sky, radiance L seen by every ray that escapes)
 * against analytic values. No other light in any of these scenes.
 *
 * 1. Open plane (20 x 20 m, nothing above), Lambertian rho_d, seen obliquely so that the top rows
 *    miss. direct = rho_d / pi integral L V cos dw = rho_d L (V = 1 everywhere). The estimator
 *    samples cosine-weighted directions, each with weight rho_d L V, and every one escapes, so
 *    each sample IS rho_d L: expected exactly the float product rho_d * L in every plane pixel
 *    with standard error exactly 0 (tolerance 0: one blocked or mis-weighted sample would show).
 *    Pixels whose primary ray misses are exactly 0 (misses are 0, the sky itself is not drawn).
 *    On the same plane: indirect, glossy, caustic exactly 0 and full (max_depth 3) exactly
 *    rho_d L — a bounce that escapes sees the sky but adds nothing, because `direct`'s sky
 *    sampling already counts that path (counting it again would give 2 rho_d L in full).
 * 1b. The plane Phong (rho_d 0.3, rho_s 0.4, n 20): direct = L (rho_d + rho_s A(theta_o)), A the
 *    normalised Phong lobe's directional albedo clipped by the horizon,
 *        A = integral_H (n + 2) / (2 pi) max(0, r . w)^n (n . w) dw,
 *    computed here by quadrature over the lobe (closed form in phi, 20000 midpoints in cos alpha,
 *    error < 1e-7).
 *    The Phong part is sampled from the lobe (weight (n + 2) / (n + 1) cos, 0 below the horizon),
 *    so it is random: the image-wide mean of (measured - expected) must lie within 3 of the
 *    renderer's own standard errors and every pixel within 5 of its own.
 * 2. The ao_wall geometry (floor y = 0, a 60 m wall at x = 1; ref_ao_wall.c): direct from the sky
 *    on the floor = rho_d L AO, AO = 1 - F the analytic unoccluded fraction (F the wall's form
 *    factor from the ray origin, which the ray offset moves eps up: exact for what is estimated).
 *    Each sample is 0 or rho_d L, so a pixel's variance is (rho_d L)^2 AO (1 - AO) / spp:
 *    image-wide deviation within 3 renderer standard errors, each pixel within 5 analytic ones,
 *    the renderer's variance within 5% of the analytic (its own relative spread is ~1%).
 * 2b. The wall a mirror (rho_s 0.8, no diffuse part): the floor sees the sky in it, L_sky S D E,
 *    which is `caustic` (max_specular 1): rho_d rho_s L F (every direction that hits the wall is
 *    mirrored upward and escapes); `direct` stays rho_d L AO (the mirror occludes), and `full`
 *    (max_depth 2) is their sum rho_d L (1 - F + rho_s F). Same checks, with the variance of
 *    full the sum of its two independent binary samples'.
 * 3. Interface: direct with a sky is random (spp 1 refused), full with one vertex too, higher with
 *    one vertex stays deterministic (0); the sky changes the cache key; the EXR header says it. */
/* 1b and 2 run with both samplers (reference.h): Sobol (variance at most the independent
 * samples'; its per-pixel standard errors have 7 degrees of freedom, hence the wider per-pixel
 * bound in 1b) and independent PCG32 numbers (variance equal to the analytic one). */
#include <math.h>
#include <string.h>

#include "ref_test_util.h"

static const float SKY[3] = {0.2f, 0.22f, 0.25f};

/* The horizon-clipped albedo of the normalised Phong lobe (exponent ne) about the mirror direction
 * of a view at cos theta_o = co from the normal: in the lobe's frame, c = cos alpha has density
 * (ne + 1) c^ne, and n . w = c co + sqrt(1 - c^2) sin(theta_o) cos phi, whose positive part
 * averages over phi to (a phi0 + b sin phi0) / pi with cos phi0 = -a / b. */
static double rt_phong_albedo(double ne, double co)
{
    const int N = 20000;
    double so = sqrt(fmax(0.0, 1.0 - co * co)), sum = 0.0;
    for (int i = 0; i < N; i++) {
        double c = (i + 0.5) / N, a = c * co, b = sqrt(1.0 - c * c) * so, avg;
        if (a >= b)
            avg = a;
        else if (a <= -b)
            avg = 0.0;
        else {
            double phi0 = acos(-a / b);
            avg = (a * phi0 + b * sin(phi0)) / M_PI;
        }
        sum += (ne + 1.0) * pow(c, ne) * (ne + 2.0) / (ne + 1.0) * avg;
    }
    return sum / N;
}

static void test_plane(void)
{
    gib_scene s;
    rt_scene_init(&s, "sky_plane");
    const float kd[3] = {0.5f, 0.4f, 0.3f};
    int m = rt_material(&s, kd[0], kd[1], kd[2]);
    rt_floor(&s, 0.0f, -10.0f, 10.0f, -10.0f, 10.0f, m);
    rt_sky(&s, SKY[0], SKY[1], SKY[2]);
    const float eye[3] = {0.0f, 1.0f, 3.0f}, tgt[3] = {0.0f, 0.5f, 0.0f}, up[3] = {0, 1, 0};
    rt_camera(&s, eye, tgt, up, 60.0f);
    const int W = 32, H = 32;
    const int comps[6] = {GIB_COMP_DIRECT, GIB_COMP_INDIRECT, GIB_COMP_GLOSSY, GIB_COMP_CAUSTIC,
                          GIB_COMP_FULL, GIB_COMP_AO};
    for (int i = 0; i < 6; i++) {
        const int comp = comps[i];
        gib_ref_params p = rt_params(comp, W, H, 16);
        p.max_depth = 3;
        gib_image img, sd;
        gib_ref_stats st;
        rt_render(&s, &p, &img, &sd, &st);
        int hits = 0, bad = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double P[3];
                int hit = rt_hit_plane_y(&s, 0, W, H, x, y, 0.0, P) && fabs(P[0]) < 10 &&
                          fabs(P[2]) < 10;
                hits += hit;
                for (int c = 0; c < 3; c++) {
                    float want = 0.0f;
                    if (hit && (comp == GIB_COMP_DIRECT || comp == GIB_COMP_FULL))
                        want = kd[c] * SKY[c];
                    else if (hit && comp == GIB_COMP_AO)
                        want = 1.0f;
                    bad += img.px[(y * W + x) * 3 + c] != want || sd.px[(y * W + x) * 3 + c] != 0;
                }
            }
        CHECK(hits > 100 && hits < W * H - 100, "test geometry: %d plane pixels", hits);
        CHECK(bad == 0, "open plane, %s: %d values differ from the exact answer",
              gib_component_name(comp), bad);
        printf("open plane, %-8s: %d plane pixels exactly %s, stderr 0; %d sky pixels exactly "
               "0%s\n",
               gib_component_name(comp), hits,
               comp == GIB_COMP_DIRECT || comp == GIB_COMP_FULL ? "rho_d * L (0.1 0.088 0.075)"
               : comp == GIB_COMP_AO                           ? "1"
                                                               : "0",
               W * H - hits, bad ? " — FAILED" : "");
        gib_image_free(&img);
        gib_image_free(&sd);
    }

    /* 1b: Phong */
    const float rd = 0.3f, rs = 0.4f, ne = 20.0f;
    s.materials[m].albedo[0] = s.materials[m].albedo[1] = s.materials[m].albedo[2] = rd;
    s.materials[m].spec_type = GIB_SPEC_PHONG;
    s.materials[m].specular[0] = s.materials[m].specular[1] = s.materials[m].specular[2] = rs;
    s.materials[m].phong_n = ne;
    s.features |= GIB_FEAT_SPECULAR;
    /* With Sobol samples a pixel's standard error comes from its 8 batches (7 degrees of
     * freedom): the same false-alarm rate as 5 sigma of a normal (5.7e-7 two-sided) is 17 of
     * Student's t with 7 degrees of freedom. */
    for (int sobol = 1; sobol >= 0; sobol--) {
        const double px_max = sobol ? 17.0 : 5.0;
        const int spp = 256;
        gib_ref_params p = rt_params(GIB_COMP_DIRECT, W, H, spp);
        p.sampler = sobol ? GIB_REF_SAMPLER_SOBOL : GIB_REF_SAMPLER_RANDOM;
        gib_image img, sd;
        gib_ref_stats st;
        rt_render(&s, &p, &img, &sd, &st);
        double worst_sum = 0.0, worst_px = 0.0, amin = 1.0, amax = 0.0, esum = 0.0, msum = 0.0;
        static double alb[32 * 32];
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double P[3], v[3];
                alb[y * W + x] = -1.0;
                if (!rt_hit_plane_y(&s, 0, W, H, x, y, 0.0, P) || fabs(P[0]) >= 10 ||
                    fabs(P[2]) >= 10)
                    continue;
                for (int k = 0; k < 3; k++)
                    v[k] = (double)s.cameras[0].eye[k] - P[k];
                double co = v[1] / sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
                alb[y * W + x] = rt_phong_albedo(ne, co);
            }
        int n = 0;
        for (int c = 0; c < 3; c++) {
            double dsum = 0.0, var = 0.0;
            for (int y = 0; y < H; y++)
                for (int x = 0; x < W; x++) {
                    double A = alb[y * W + x];
                    if (A < 0.0)
                        continue;
                    amin = fmin(amin, A), amax = fmax(amax, A);
                    double expect = SKY[c] * (rd + rs * A);
                    double got = img.px[(y * W + x) * 3 + c], se = sd.px[(y * W + x) * 3 + c];
                    dsum += got - expect;
                    var += se * se;
                    double z =
                        se > 0.0 ? fabs(got - expect) / se : (got != expect ? INFINITY : 0);
                    worst_px = fmax(worst_px, z);
                    if (c == 0)
                        esum += expect, msum += got, n++;
                }
            double z = dsum / sqrt(var);
            worst_sum = fabs(z) > fabs(worst_sum) ? z : worst_sum;
        }
        CHECK_NEAR("Phong plane: image-wide deviation, worst channel (sigma)", 0, worst_sum, 3.0,
                   "3 of the renderer's own standard errors");
        CHECK_AT_MOST(sobol ? "Phong plane, sobol: worst pixel (sigma)"
                            : "Phong plane, random: worst pixel (sigma)",
                      worst_px, px_max,
                      sobol ? "5.7e-7 two-sided false alarms: Student's t, 7 degrees of freedom"
                            : "5.7e-7 two-sided false alarms: 5 sigma of a normal");
        CHECK(st.noise_rmse > 0.0 && st.spp == spp, "Phong plane: noise %g, spp %d",
              st.noise_rmse, st.spp);
        printf("Phong plane (rho_d 0.3, rho_s 0.4, n 20), direct, %d spp, %d pixels: red mean "
               "expected %.6f measured %.6f (lobe albedo A %.4f .. %.4f); image-wide deviation "
               "%.2f sigma (max 3, worst channel), worst pixel %.2f sigma (max %.0f); noise_rmse %.2g (%s)\n",
               spp, n, esum / n, msum / n, amin, amax, worst_sum, worst_px, px_max, st.noise_rmse,
               sobol ? "sobol" : "random");
        gib_image_free(&img);
        gib_image_free(&sd);
    }
    rt_scene_free(&s);
}

/* 2 and 2b: one component on the wall scene; expect(a, F) per pixel, var1 one sample's variance
 * (red channel; the others are the same samples scaled by L). */
static void test_wall_component(const gib_scene *s, int comp, const char *what, double rd,
                                double rs)
{
    const int W = 32, H = 32, spp = 256;
    const double eps = gib_reference_ray_eps(s), L = SKY[0];
    for (int sobol = 1; sobol >= 0; sobol--) {
        gib_ref_params p = rt_params(comp, W, H, spp);
        p.sampler = sobol ? GIB_REF_SAMPLER_SOBOL : GIB_REF_SAMPLER_RANDOM;
        p.max_depth = 2;
        p.max_specular = 1;
        gib_image img, sd;
        gib_ref_stats st;
        rt_render(s, &p, &img, &sd, &st);
        rt_zstats z = {0};
        z.sobol = sobol;
        double cexp = 0.0, cgot = 0.0, cse = 0.0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double P[3];
                if (!rt_hit_plane_y(s, 0, W, H, x, y, 0.0, P))
                    continue;
                double a = 1.0 - P[0], z0 = -60.0 - P[2], z1 = 60.0 - P[2], top = 60.0 - eps;
                double R[4][3] = {{a, 0, z0}, {a, 0, z1}, {a, top, z1}, {a, top, z0}};
                double F = rt_form_factor_up(R, 4), expect, var1;
                double dl = rd * L, ml = rd * rs * L; /* a lit diffuse sample, a mirrored one */
                if (comp == GIB_COMP_DIRECT)
                    expect = dl * (1.0 - F), var1 = dl * dl * F * (1.0 - F);
                else if (comp == GIB_COMP_CAUSTIC)
                    expect = ml * F, var1 = ml * ml * F * (1.0 - F);
                else
                    expect = dl * (1.0 - F) + ml * F, var1 = (dl * dl + ml * ml) * F * (1.0 - F);
                double got = img.px[(y * W + x) * 3], se = sd.px[(y * W + x) * 3];
                rt_zstats_add(&z, got, se, expect, var1, spp);
                if (x == W / 2 && y == H / 2)
                    cexp = expect, cgot = got, cse = se;
            }
        CHECK(z.n == W * H, "test geometry: %d of %d pixels on the floor", z.n, W * H);
        char name[160];
        snprintf(name, sizeof name, "%s, %s", what, sobol ? "sobol" : "random");
        rt_zstats_check(&z, name);
        printf("%s, %d spp, red: centre pixel expected %.5f measured %.5f stderr %.5f; mean of %d "
               "pixels expected %.6f measured %.6f, stderr of the mean %.6f (deviation %.2f sigma, "
               "max 3); worst pixel %.2f sigma (max 5); variance ratio %.4f (random: within 5%%; "
               "sobol: at most 1.05)\n",
               name, spp, cexp, cgot, cse, z.n, z.esum / z.n, z.msum / z.n, sqrt(z.var_r) / z.n,
               z.zsum, z.worst_z, z.var_r / z.var_a);
        gib_image_free(&img);
        gib_image_free(&sd);
    }
}

static void test_wall(void)
{
    gib_scene s;
    rt_scene_init(&s, "sky_wall");
    const float rd = 0.5f, rs = 0.8f;
    int m = rt_material(&s, rd, rd, rd);
    rt_floor(&s, 0.0f, -3.0f, 1.0f, -60.0f, 60.0f, m);
    int wm = rt_material(&s, rd, rd, rd);
    const float a[3] = {1, 0, 60}, b[3] = {1, 0, -60}, c[3] = {1, 60, -60}, d[3] = {1, 60, 60};
    const float n[3] = {-1, 0, 0};
    rt_quad(&s, a, b, c, d, n, wm);
    rt_sky(&s, SKY[0], SKY[1], SKY[2]);
    const float eye[3] = {-0.5f, 3.0f, 0.0f}, tgt[3] = {-0.5f, 0.0f, 0.0f}, up[3] = {0, 0, -1};
    rt_camera(&s, eye, tgt, up, 30.0f);
    test_wall_component(&s, GIB_COMP_DIRECT, "diffuse wall, direct = rho_d L AO", rd, 0.0);

    gib_material *w = &s.materials[wm];
    w->albedo[0] = w->albedo[1] = w->albedo[2] = 0.0f;
    w->spec_type = GIB_SPEC_MIRROR;
    w->specular[0] = w->specular[1] = w->specular[2] = rs;
    s.features |= GIB_FEAT_SPECULAR | GIB_FEAT_MIRROR;
    test_wall_component(&s, GIB_COMP_DIRECT, "mirror wall, direct = rho_d L AO", rd, rs);
    test_wall_component(&s, GIB_COMP_CAUSTIC, "mirror wall, caustic = rho_d rho_s L F", rd, rs);
    test_wall_component(&s, GIB_COMP_FULL, "mirror wall, full (depth 2) = direct + caustic", rd,
                        rs);
    rt_scene_free(&s);
}

static void test_api(void)
{
    gib_scene s;
    rt_scene_init(&s, "sky_api");
    int m = rt_material(&s, 0.5f, 0.5f, 0.5f);
    rt_floor(&s, 0.0f, -1, 1, -1, 1, m);
    const float eye[3] = {0, 2, 2}, tgt[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    rt_camera(&s, eye, tgt, up, 45.0f);
    gib_ref_params p = rt_params(GIB_COMP_DIRECT, 8, 8, 1);
    uint64_t key0 = gib_reference_cache_key(&s, &p);
    CHECK(gib_component_deterministic(&s, GIB_COMP_DIRECT), "direct without sky: exact");
    rt_sky(&s, 0.2f, 0.22f, 0.25f);
    CHECK(!gib_component_deterministic(&s, GIB_COMP_DIRECT), "direct with a sky is random");
    gib_image img;
    gib_error err = {0};
    int rc = gib_reference_render(&s, &p, &img, NULL, NULL, &err);
    CHECK(rc < 0 && strstr(err.msg, "at least 2"), "direct with a sky at 1 spp: rc %d '%s'", rc,
          err.msg);
    p.spp = 2;
    uint64_t key1 = gib_reference_cache_key(&s, &p);
    s.sky[2] = 0.3f;
    uint64_t key2 = gib_reference_cache_key(&s, &p);
    CHECK(key0 != key1 && key1 != key2, "the sky must change the cache key");
    gib_ref_params f = rt_params(GIB_COMP_FULL, 8, 8, 2), h = rt_params(GIB_COMP_HIGHER, 8, 8, 2);
    f.max_depth = h.max_depth = 1;
    gib_ref_stats st;
    gib_ref_stats sh;
    gib_image hi;
    rt_render(&s, &h, &hi, NULL, &sh);
    CHECK(sh.deterministic && sh.spp == 1 && sh.mean == 0.0,
          "higher, max_depth 1, with a sky: deterministic 0 (got det %d spp %d mean %g)",
          sh.deterministic, sh.spp, sh.mean);
    gib_image_free(&hi);
    rt_render(&s, &f, &img, NULL, &st);
    CHECK(!st.deterministic && st.spp == 2, "full, max_depth 1, with a sky: random");
    gib_kv kv[GIB_REF_ATTR_COUNT];
    int n = gib_reference_attrs(&s, &p, &st, kv, GIB_REF_ATTR_COUNT);
    const char *sky = NULL, *est = NULL;
    for (int i = 0; i < n; i++) {
        if (!strcmp(kv[i].key, "sky"))
            sky = kv[i].value;
        if (!strcmp(kv[i].key, "estimator"))
            est = kv[i].value;
    }
    CHECK(sky && !strcmp(sky, "0.200000003 0.219999999 0.300000012"), "sky attribute '%s'",
          sky ? sky : "(missing)");
    CHECK(est && !strcmp(est, "random"), "estimator attribute '%s'", est ? est : "(missing)");
    printf("interface: direct with a sky random (spp 1 refused: %s); full depth 1 random, higher "
           "depth 1 deterministic 0; the sky changes the cache key; header sky = '%s'\n",
           err.msg, sky ? sky : "");
    gib_image_free(&img);
    rt_scene_free(&s);
}

int main(void)
{
    test_plane();
    test_wall();
    test_api();
    return failures ? 1 : 0;
}

/* Reference renderer, materials in `direct`: textures, cut-out masks, the normalised Phong lobe,
 * mirrors and one-/two-sided surfaces (scene.h's material model).
 *
 * Every expected value is analytic and the estimator is deterministic, so the tolerance is float
 * rounding: 1e-4 relative (2e-4 for the Phong lobe, whose exponent 20 multiplies the cosine's
 * relative rounding error by 20), and exact zeros where nothing may arrive. */
#include <math.h>
#include <string.h>

#include "reference/ref_internal.h"
#include "ref_test_util.h"

static const float EYE[3] = {0.0f, 4.0f, 0.0f}, TGT[3] = {0, 0, 0}, UP[3] = {0, 0, -1};
static const float LP[3] = {0.3f, 2.0f, -0.2f};
static const double LI = 6.0;

/* 1. The bilinear sampler, on a 2x2 texture A B / C D (row 0 on top, t = 1 - v). */
static void test_sampler(void)
{
    const float rgba[16] = {1, 0, 0, 1, /* A */ 0, 1, 0, 1, /* B */
                            0, 0, 1, 1, /* C */ 1, 1, 1, 0 /* D */};
    gib_texture t;
    memset(&t, 0, sizeof t);
    t.width = t.height = 2;
    t.rgba = (float *)rgba;
    struct {
        float u, v, expect[4];
        const char *why;
    } cases[] = {
        {0.25f, 0.75f, {1, 0, 0, 1}, "texel centre of A (top-left)"},
        {0.75f, 0.25f, {1, 1, 1, 0}, "texel centre of D (bottom-right)"},
        {0.5f, 0.75f, {0.5f, 0.5f, 0, 1}, "half way A-B"},
        {0.0f, 0.75f, {0.5f, 0.5f, 0, 1}, "u = 0 wraps: half way B-A"},
        {1.25f, -0.25f, {1, 0, 0, 1}, "repeat in u and v: A"},
        {0.25f, 0.5f, {0.5f, 0, 0.5f, 1}, "half way A-C (vertical)"},
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        float out[4];
        ref_tex_sample(&t, cases[i].u, cases[i].v, out);
        for (int c = 0; c < 4; c++) {
            char what[128];
            snprintf(what, sizeof what, "sampler %s: channel %d = %g, |error| from %g",
                     cases[i].why, c, out[c], cases[i].expect[c]);
            CHECK_AT_MOST(what, fabsf(out[c] - cases[i].expect[c]), 1e-6f, "float rounding");
        }
    }
    printf("sampler: %u bilinear/wrap cases exact to 1e-6\n",
           (unsigned)(sizeof cases / sizeof cases[0]));
}

/* Renders `direct` of a floor seen from above and returns the max relative error against
 * expect(P, wo, out) at every pixel (P the analytic floor point, wo toward the eye); channels
 * expected to be 0 must be exactly 0 and are counted in *zeros_bad otherwise. */
typedef void (*rt_expect_fn)(const double P[3], const double wo[3], double out[3]);

static double rt_check_floor(const gib_scene *s, rt_expect_fn expect, double skip,
                             int *zeros_bad)
{
    const int W = 32, H = 32;
    gib_ref_params p = rt_params(GIB_COMP_DIRECT, W, H, 1);
    gib_image img;
    gib_ref_stats st;
    rt_render(s, &p, &img, NULL, &st);
    double worst = 0.0;
    *zeros_bad = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double P[3], wo[3], e[3];
            rt_hit_plane_y(s, 0, W, H, x, y, 0.0, P);
            /* skip > 0: floor points with |x|, |z| < skip see an occluder or lie in its shadow */
            const float *v = &img.px[(y * W + x) * 3];
            if (fmax(fabs(P[0]), fabs(P[2])) < skip)
                continue;
            double len = 0.0;
            for (int k = 0; k < 3; k++) {
                wo[k] = EYE[k] - P[k];
                len += wo[k] * wo[k];
            }
            for (int k = 0; k < 3; k++)
                wo[k] /= sqrt(len);
            expect(P, wo, e);
            for (int c = 0; c < 3; c++) {
                if (e[c] == 0.0) {
                    *zeros_bad += v[c] != 0.0f;
                    continue;
                }
                double rel = fabs(v[c] - e[c]) / e[c];
                worst = rel > worst ? rel : worst;
            }
        }
    gib_image_free(&img);
    return worst;
}

static double rt_irradiance(const double P[3], double *cos_t, double wi[3])
{
    double d[3] = {LP[0] - P[0], LP[1] - P[1], LP[2] - P[2]};
    double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    for (int k = 0; k < 3; k++)
        wi[k] = d[k] / sqrt(r2);
    *cos_t = wi[1];
    return LI / r2;
}

static double g_albedo[3];
static void expect_diffuse(const double P[3], const double wo[3], double out[3])
{
    (void)wo;
    double c, wi[3], E = rt_irradiance(P, &c, wi);
    for (int k = 0; k < 3; k++)
        out[k] = g_albedo[k] / M_PI * E * c;
}

static double g_spec, g_n;
static void expect_phong(const double P[3], const double wo[3], double out[3])
{
    double c, wi[3], E = rt_irradiance(P, &c, wi);
    double r[3] = {-wo[0], wo[1], -wo[2]}; /* 2 (n.wo) n - wo with n = +y */
    double rw = r[0] * wi[0] + r[1] * wi[1] + r[2] * wi[2];
    double lobe = rw > 0.0 ? g_spec * (g_n + 2.0) / (2.0 * M_PI) * pow(rw, g_n) : 0.0;
    for (int k = 0; k < 3; k++)
        out[k] = (g_albedo[k] / M_PI + lobe) * E * c;
}

static void rt_lit_floor(gib_scene *s, int *mat)
{
    rt_scene_init(s, "materials");
    *mat = rt_material(s, 0.8f, 0.8f, 0.8f);
    rt_floor(s, 0.0f, -10.0f, 10.0f, -10.0f, 10.0f, *mat);
    rt_point_light(s, LP[0], LP[1], LP[2], (float)LI, (float)LI, (float)LI);
    rt_camera(s, EYE, TGT, UP, 60.0f);
}

int main(void)
{
    test_sampler();
    gib_scene s;
    int m, zb;
    double worst;

    /* 2. Albedo texture: a constant texel multiplies the albedo. */
    rt_lit_floor(&s, &m);
    const float tex[4] = {0.5f, 0.25f, 1.0f, 1.0f};
    s.materials[m].albedo_tex = rt_texture(&s, 1, 1, tex);
    g_albedo[0] = 0.8 * 0.5, g_albedo[1] = 0.8 * 0.25, g_albedo[2] = 0.8;
    worst = rt_check_floor(&s, expect_diffuse, 0.0, &zb);
    CHECK_AT_MOST("albedo texture: max relative error", worst, 1e-4,
                  "deterministic: float rounding, 1e-4 relative");
    printf("albedo texture: max relative error %.3g vs albedo*texel/pi E cos (tol 1e-4)\n", worst);
    rt_scene_free(&s);

    /* 3. Cut-out masks: an occluder at y = 1 between the light and the floor, its mask's first
     * channel 0 (other channels 1, to show only the first counts): invisible and casts no shadow.
     * With the first channel 1 it hides the floor under it and casts a shadow (pixels under it
     * are then skipped; the shadow test proper is ref_shadow). */
    for (int opaque = 0; opaque < 2; opaque++) {
        rt_lit_floor(&s, &m);
        const float mask[4] = {(float)opaque, 1.0f, 1.0f, 1.0f};
        int mo = rt_material(&s, 0.1f, 0.1f, 0.1f);
        s.materials[mo].alpha_tex = rt_texture(&s, 1, 1, mask);
        s.materials[mo].two_sided = 1;
        rt_floor(&s, 1.0f, -0.4f, 0.4f, -0.4f, 0.4f, mo);
        g_albedo[0] = g_albedo[1] = g_albedo[2] = 0.8;
        /* Opaque: the occluder hides floor points with |x|, |z| < 0.54 (eye at height 4) and
         * shadows those within 0.8 of (-0.3, 0.2), the light's mirror image through its centre
         * (light at height 2, occluder at 1): skip |x|, |z| < 1.3. */
        worst = rt_check_floor(&s, expect_diffuse, opaque ? 1.3 : 0.0, &zb);
        CHECK_AT_MOST(opaque ? "mask opaque: max relative error" : "mask clear: max relative error",
                      worst, 1e-4, "deterministic: float rounding, 1e-4 relative");
        /* Floor points in the occluder's shadow (within 0.8 of (-0.3, 0.2), 0.05 margin) but not
         * hidden by it (beyond 0.54 + 0.05) are exactly 0 when opaque, lit when clear. */
        gib_ref_params p = rt_params(GIB_COMP_DIRECT, 32, 32, 1);
        gib_image img;
        rt_render(&s, &p, &img, NULL, NULL);
        int in_shadow = 0, dark = 0;
        for (int y = 0; y < 32; y++)
            for (int x = 0; x < 32; x++) {
                double P[3];
                rt_hit_plane_y(&s, 0, 32, 32, x, y, 0.0, P);
                if (fmax(fabs(P[0] + 0.3), fabs(P[2] - 0.2)) < 0.75 &&
                    fmax(fabs(P[0]), fabs(P[2])) > 0.59) {
                    in_shadow++;
                    dark += img.px[(y * 32 + x) * 3] == 0.0f;
                }
            }
        CHECK(in_shadow >= 10, "test geometry: %d pixels in the visible shadow", in_shadow);
        CHECK(dark == (opaque ? in_shadow : 0), "mask %s: %d of %d shadow pixels are 0",
              opaque ? "opaque" : "clear", dark, in_shadow);
        gib_image_free(&img);
        printf("alpha mask %s: %d of %d pixels in the occluder's shadow exactly 0\n",
               opaque ? "opaque" : "clear", dark, in_shadow);
        printf("alpha mask %s: max relative error %.3g vs unshadowed floor (tol 1e-4)\n",
               opaque ? "opaque (pixels near the occluder skipped)" : "clear (all pixels)",
               worst);
        rt_scene_free(&s);
    }

    /* 4. Normalised Phong: rho_d 0.3 + rho_s 0.5 (n + 2)/(2 pi) max(0, r.wi)^n, n = 20. */
    rt_lit_floor(&s, &m);
    s.materials[m].albedo[0] = s.materials[m].albedo[1] = s.materials[m].albedo[2] = 0.3f;
    s.materials[m].spec_type = GIB_SPEC_PHONG;
    s.materials[m].specular[0] = s.materials[m].specular[1] = s.materials[m].specular[2] = 0.5f;
    s.materials[m].phong_n = 20.0f;
    g_albedo[0] = g_albedo[1] = g_albedo[2] = 0.3;
    g_spec = 0.5;
    g_n = 20.0;
    worst = rt_check_floor(&s, expect_phong, 0.0, &zb);
    CHECK_AT_MOST("phong: max relative error", worst, 2e-4,
                  "float rounding; the exponent 20 multiplies the cosine's error by 20");
    printf("phong n=20: max relative error %.3g vs analytic BRDF (tol 2e-4)\n", worst);

    /* 5. Mirror: its delta lobe cannot see a delta light, so only rho_d is lit; with rho_d = 0
     * the image is exactly 0. */
    s.materials[m].spec_type = GIB_SPEC_MIRROR;
    g_albedo[0] = g_albedo[1] = g_albedo[2] = 0.3;
    worst = rt_check_floor(&s, expect_diffuse, 0.0, &zb);
    CHECK_AT_MOST("mirror: max relative error", worst, 1e-4,
                  "deterministic: float rounding, 1e-4 relative");
    s.materials[m].albedo[0] = s.materials[m].albedo[1] = s.materials[m].albedo[2] = 0.0f;
    g_albedo[0] = g_albedo[1] = g_albedo[2] = 0.0;
    rt_check_floor(&s, expect_diffuse, 0.0, &zb);
    CHECK(zb == 0, "pure mirror: %d values are not exactly 0", zb);
    printf("mirror: diffuse part only (max rel. error %.3g), pure mirror exactly 0\n", worst);
    rt_scene_free(&s);

    /* 6. Sides: the camera looks at the back of the floor from below (the floor's normal points
     * away from it). One-sided: exactly 0 in direct and ao. Two-sided: the normal flips to face
     * the viewer, and a light below lights it like a floor seen from above. */
    for (int two = 0; two < 2; two++) {
        rt_scene_init(&s, "sides");
        m = rt_material(&s, 0.8f, 0.8f, 0.8f);
        s.materials[m].two_sided = two;
        rt_floor(&s, 0.0f, -10.0f, 10.0f, -10.0f, 10.0f, m);
        rt_point_light(&s, LP[0], -LP[1], LP[2], (float)LI, (float)LI, (float)LI);
        const float eye[3] = {0, -4, 0}, up[3] = {0, 0, 1};
        rt_camera(&s, eye, TGT, up, 60.0f);
        gib_ref_params p = rt_params(GIB_COMP_DIRECT, 32, 32, 1);
        gib_image img, ao;
        rt_render(&s, &p, &img, NULL, NULL);
        p.component = GIB_COMP_AO;
        p.spp = 4;
        rt_render(&s, &p, &ao, NULL, NULL);
        int nonzero = 0, ones = 0;
        double w2 = 0.0;
        for (int y = 0; y < 32; y++)
            for (int x = 0; x < 32; x++) {
                double P[3];
                rt_hit_plane_y(&s, 0, 32, 32, x, y, 0.0, P);
                double d[3] = {LP[0] - P[0], -LP[1] - P[1], LP[2] - P[2]};
                double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                double e = 0.8 / M_PI * LI * (-d[1] / sqrt(r2)) / r2;
                float v = img.px[(y * 32 + x) * 3];
                nonzero += v != 0.0f;
                ones += ao.px[(y * 32 + x) * 3] == 1.0f;
                double rel = fabs(v - e) / e;
                w2 = rel > w2 ? rel : w2;
            }
        if (!two) {
            CHECK(nonzero == 0, "one-sided back: %d pixels are not 0", nonzero);
            CHECK(ones == 0, "one-sided back: %d ao pixels are not 0", ones);
            printf("one-sided seen from behind: direct and ao exactly 0 at all 1024 pixels\n");
        } else {
            CHECK_AT_MOST("two-sided back: max relative error", w2, 1e-4,
                          "deterministic: float rounding, 1e-4 relative");
            CHECK(ones == 32 * 32, "two-sided back: only %d ao pixels are 1", ones);
            printf("two-sided seen from behind: max relative error %.3g (tol 1e-4), ao 1 "
                   "everywhere\n",
                   w2);
        }
        gib_image_free(&img);
        gib_image_free(&ao);
        rt_scene_free(&s);
    }
    return failures ? 1 : 0;
}

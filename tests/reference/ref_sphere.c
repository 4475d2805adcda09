/* Reference renderer, a closed diffuse sphere seen from inside with a point light at its centre
 * (and, last, a spot and a texture: rt_spot_sphere):
 * `direct`, `indirect` and `full` against their closed forms (the furnace-like case of ARCHITECTURE.md,
 * "Reference renderer": validated against cases with known answers).
 *
 * For an ideal sphere of radius R, albedo a, point light of intensity I at the centre, every wall
 * point is lit by E0 = I / R^2 at normal incidence, so
 *     direct   = (a / pi) E0                       (L D E)
 *     indirect = a * direct = (a^2 / pi) E0         (L D D E: the wall sees only wall of radiance
 *                                                   `direct`, and the irradiance inside a closed
 *                                                   surface of uniform radiance L is pi L)
 *     full     = direct (1 - a^D) / (1 - a)         (D = max_depth vertices; -> direct / (1 - a))
 *
 * The mesh: a flat-shaded icosphere (icosahedron subdivided 5 times, 20480 faces, vertices on the
 * sphere, face normals pointing in). A point p on a face whose plane lies at distance h from the
 * centre sees the light at r = |p| in [h, R] under cos = h / r, so its irradiance I h / r^3 lies in
 * E0 [h / R, (R / h)^2]. With h_min the smallest face distance, every wall's direct radiance lies in
 * direct [lo, hi] = direct [h_min / R, (R / h_min)^2] (about [0.99978, 1.00044]); by induction
 * every bounce's radiance lies in the same relative interval, so indirect and full do too. That
 * interval is the tessellation's bias bound, computed from the mesh, not guessed.
 *
 * Checks:
 *  - direct (deterministic): every pixel within [lo, hi] of the closed form, exactly (1e-5 slack
 *    for float rounding);
 *  - indirect (also each diffuse cone's share, gib_ref_params.cone) and full: the image mean within
 *    3 standard errors of the mean (from the renderer's
 *    own per-pixel errors) of the interval [lo, hi] x closed form, and no 4x4 block's mean
 *    further than 4 of its standard errors from the interval (36 blocks: a 4-sigma excursion of
 *    a correct renderer has odds of about 1 in 400). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ref_test_util.h"

static double vlen(const double v[3])
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* Subdivides each triangle of tris (n of them, 9 doubles each) into 4, vertices pushed to |v| = 1. */
static double *subdivide(const double *tris, int n)
{
    double *out = malloc(sizeof(double) * 9 * 4 * (size_t)n);
    if (!out)
        abort();
    for (int t = 0; t < n; t++) {
        const double *a = tris + 9 * t, *b = a + 3, *c = a + 6;
        double ab[3], bc[3], ca[3];
        for (int k = 0; k < 3; k++) {
            ab[k] = a[k] + b[k];
            bc[k] = b[k] + c[k];
            ca[k] = c[k] + a[k];
        }
        double lab = vlen(ab), lbc = vlen(bc), lca = vlen(ca);
        for (int k = 0; k < 3; k++)
            ab[k] /= lab, bc[k] /= lbc, ca[k] /= lca;
        const double *parts[4][3] = {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}};
        for (int p = 0; p < 4; p++)
            for (int v = 0; v < 3; v++)
                memcpy(out + 9 * (4 * t + p) + 3 * v, parts[p][v], 3 * sizeof(double));
    }
    return out;
}

/* Appends the icosphere (radius R, centre 0) as flat faces with inward normals; returns h_min. */
static double rt_icosphere(gib_scene *s, double R, int levels, int mat)
{
    const double g = (1.0 + sqrt(5.0)) / 2.0;
    double v[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                       {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    static const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int i = 0; i < 12; i++) {
        double l = vlen(v[i]);
        for (int k = 0; k < 3; k++)
            v[i][k] /= l;
    }
    int n = 20;
    double *tris = malloc(sizeof(double) * 9 * 20);
    if (!tris)
        abort();
    for (int t = 0; t < 20; t++)
        for (int k = 0; k < 3; k++)
            memcpy(tris + 9 * t + 3 * k, v[f[t][k]], 3 * sizeof(double));
    for (int l = 0; l < levels; l++) {
        double *next = subdivide(tris, n);
        free(tris);
        tris = next;
        n *= 4;
    }
    double hmin = INFINITY;
    /* one allocation for all faces (rt_quad grows the arrays a quad at a time, which is quadratic
     * for 20k faces under AddressSanitizer's realloc) */
    uint32_t v0 = s->vertex_count, t0 = s->triangle_count;
    s->positions = realloc(s->positions, sizeof(float) * 3 * (v0 + 3 * (size_t)n));
    s->normals = realloc(s->normals, sizeof(float) * 3 * (v0 + 3 * (size_t)n));
    s->uvs = realloc(s->uvs, sizeof(float) * 2 * (v0 + 3 * (size_t)n));
    s->indices = realloc(s->indices, sizeof(uint32_t) * 3 * (t0 + (size_t)n));
    s->tri_material = realloc(s->tri_material, sizeof(uint32_t) * (t0 + (size_t)n));
    if (!s->positions || !s->normals || !s->uvs || !s->indices || !s->tri_material)
        abort();
    for (int t = 0; t < n; t++) {
        double *a = tris + 9 * t, e1[3], e2[3], c[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = a[3 + k] - a[k];
            e2[k] = a[6 + k] - a[k];
        }
        c[0] = e1[1] * e2[2] - e1[2] * e2[1];
        c[1] = e1[2] * e2[0] - e1[0] * e2[2];
        c[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double lc = vlen(c), h = fabs(c[0] * a[0] + c[1] * a[1] + c[2] * a[2]) / lc;
        double sgn = (c[0] * a[0] + c[1] * a[1] + c[2] * a[2]) > 0 ? -1.0 : 1.0; /* inward */
        uint32_t v = v0 + 3 * (uint32_t)t;
        for (int j = 0; j < 3; j++) {
            for (int k = 0; k < 3; k++) {
                s->positions[3 * (size_t)(v + j) + k] = (float)(R * a[3 * j + k]);
                s->normals[3 * (size_t)(v + j) + k] = (float)(sgn * c[k] / lc);
            }
            s->uvs[2 * (size_t)(v + j)] = s->uvs[2 * (size_t)(v + j) + 1] = 0.0f;
            s->indices[3 * (size_t)(t0 + t) + j] = v + (uint32_t)j;
        }
        s->tri_material[t0 + t] = (uint32_t)mat;
        hmin = fmin(hmin, h * R);
    }
    s->vertex_count += 3 * (uint32_t)n;
    s->triangle_count += (uint32_t)n;
    free(tris);
    /* positions are rounded to float: bound the face distances of the rounded mesh too */
    return hmin * (1.0 - 1e-6);
}

typedef struct result {
    double mean, se_mean, worst_z;
} result;

/* Compares an image with the interval [lo, hi] x expect: the image mean, and the means of 4x4
 * pixel blocks (a block's 16 x spp samples make its mean close to normal even for the skewed
 * samples of Russian roulette, where a single pixel's sample variance is unreliable). */
static result rt_compare(const gib_image *img, const gib_image *sd, double expect, double lo,
                         double hi)
{
    result r = {0, 0, 0};
    const int W = img->width, H = img->height, n = W * H, B = 4;
    double var = 0.0;
    for (int i = 0; i < n; i++) {
        r.mean += img->px[3 * i] / n;
        var += (double)sd->px[3 * i] * sd->px[3 * i];
    }
    r.se_mean = sqrt(var) / n;
    for (int by = 0; by + B <= H; by += B)
        for (int bx = 0; bx + B <= W; bx += B) {
            double m = 0.0, v = 0.0;
            for (int y = by; y < by + B; y++)
                for (int x = bx; x < bx + B; x++) {
                    m += img->px[3 * (y * W + x)] / (B * B);
                    v += (double)sd->px[3 * (y * W + x)] * sd->px[3 * (y * W + x)];
                }
            double se = sqrt(v) / (B * B);
            double d = m < expect * lo ? expect * lo - m : m > expect * hi ? m - expect * hi : 0.0;
            double z = se > 0.0 ? d / se : (d > 0.0 ? INFINITY : 0.0);
            r.worst_z = z > r.worst_z ? z : r.worst_z;
        }
    return r;
}

/* The same sphere lit by a SPOT at its centre, its albedo from a TEXTURE, seen where the spot
 * does not reach: paths whose vertices are mostly unlit (the spot covers 9% of the wall), with
 * textured bounces and Russian roulette, against a closed form.
 *
 * On a sphere the form factor between two wall points is constant: cos_x cos_y / |x - y|^2 =
 * 1 / (4 R^2), since both cosines are |x - y| / (2 R). So whatever lights the wall, the light it
 * reflects once is spread evenly: a flux Phi landing on walls of albedo a gives every wall point
 * the irradiance a Phi / (4 pi R^2) after one bounce, hence the radiance
 *     L2 = a^2 Phi / (4 pi^2 R^2)         (paths of 2 vertices: L D D E)
 * and each further vertex multiplies by a. A wall point outside the cone has no direct light, so
 *     full = L2 (1 - a^(D-1)) / (1 - a)   (D = max_depth vertices)
 * The spot's flux: intensity I cos^e(theta) inside the outer angle theta_o,
 *     Phi = 2 pi I (1 - cos^(e+1) theta_o) / (e + 1).
 * a is the texture's value, the sRGB decode of an 8-bit code (the texture path of Sponza: 8-bit
 * storage, bilinear lookups at bounce hits), on a material whose own albedo is 1, so that Russian
 * roulette's untextured throughput estimate differs from the true throughput.
 *
 * Tolerance: the image mean within 3 standard errors (the renderer's own) of the closed form
 * widened by a tessellation allowance of 1e-3 relative: the flat faces lie between h_min and R
 * from the centre (h_min / R = 0.99971), so the polyhedron's form factors differ from the
 * sphere's by a few 1e-4 per bounce; 1e-3 is about three times that and half the noise (2048
 * spp: a standard error of 2e-3 relative, so a bias of 1% fails). */
static void rt_spot_sphere(void)
{
    const double R = 2.0, I = 30.0, e = 1.0, outer = 35.0;
    const int code = 190, D = 8;
    const float c8 = (float)code / 255.0f;
    const float at = powf((c8 + 0.055f) / 1.055f, 2.4f); /* the loader's decode (textures.c) */
    const double a = at;
    gib_scene s;
    rt_scene_init(&s, "closed_sphere_spot");
    int m = rt_material(&s, 1.0f, 1.0f, 1.0f);
    float rgba[4 * 4 * 4];
    for (int i = 0; i < 16; i++)
        rgba[4 * i] = rgba[4 * i + 1] = rgba[4 * i + 2] = at, rgba[4 * i + 3] = 1.0f;
    s.materials[m].albedo_tex = rt_texture(&s, 4, 4, rgba);
    rt_icosphere(&s, R, 5, m);
    const float pos[3] = {0, 0, 0}, dir[3] = {0, 1, 0};
    rt_spot_light(&s, pos, dir, (float)I, (float)e, (float)outer);
    /* looking down: every visible point is more than 90 degrees from the spot's axis */
    const float eye[3] = {0.3f, 0.1f, -0.2f}, tgt[3] = {0.5f, -2.0f, 0.4f}, up[3] = {0, 0, 1};
    rt_camera(&s, eye, tgt, up, 70.0f);
    s.features |= GIB_FEAT_CLOSED;
    const double phi = 2.0 * M_PI * I * (1.0 - pow(cos(outer * M_PI / 180.0), e + 1.0)) / (e + 1.0);
    const double L2 = a * a * phi / (4.0 * M_PI * M_PI * R * R);
    const double expect = L2 * (1.0 - pow(a, D - 1)) / (1.0 - a), allow = 1e-3;

    gib_ref_params p = rt_params(GIB_COMP_FULL, 24, 24, 2048);
    p.max_depth = D;
    gib_image img, sd;
    gib_ref_stats st;
    rt_render(&s, &p, &img, &sd, &st);
    result r = rt_compare(&img, &sd, expect, 1.0 - allow, 1.0 + allow);
    double dev = fmax(0.0, fabs(r.mean - expect) - allow * expect);
    char what[192];
    snprintf(what, sizeof what,
             "spot, textured, full: mean %.6f, distance outside %.6f +- %.1e relative", r.mean,
             expect, allow);
    CHECK_AT_MOST(what, dev, 3.0 * r.se_mean, "3 standard errors of the mean, the renderer's own");
    CHECK_AT_MOST("spot, textured, full: worst 4x4 block (std. errors)", r.worst_z, 4.0,
                  "36 blocks: a correct renderer's 4-sigma excursion has odds ~1 in 400");
    printf("spot, textured (a = %.6f), full, unlit wall: expected %.6f (+-%.0e relative for the "
           "tessellation), measured mean %.6f, stderr of the mean %.2g (%.2f sigma outside, max "
           "3); worst 4x4 block %.2f sigma (max 4); %d spp, max_depth %d, %lld rays\n",
           a, expect, allow, r.mean, r.se_mean, dev / r.se_mean, r.worst_z, p.spp, D, st.rays);
    gib_image_free(&img);
    gib_image_free(&sd);
    rt_scene_free(&s);
}

int main(void)
{
    const double R = 2.0, a = 0.7, I = 5.0;
    gib_scene s;
    rt_scene_init(&s, "closed_sphere");
    int m = rt_material(&s, (float)a, (float)a, (float)a);
    double hmin = rt_icosphere(&s, R, 5, m);
    rt_point_light(&s, 0, 0, 0, (float)I, (float)I, (float)I);
    const float eye[3] = {0.4f, 0.2f, 0.1f}, tgt[3] = {-2.0f, -0.3f, 0.6f}, up[3] = {0, 1, 0};
    rt_camera(&s, eye, tgt, up, 70.0f);
    s.features |= GIB_FEAT_CLOSED;
    const double lo = hmin / R, hi = (R / hmin) * (R / hmin);
    const double direct = a / M_PI * I / (R * R);
    printf("icosphere: %u faces, h_min/R = %.6f: tessellation interval [%.6f, %.6f]\n",
           s.triangle_count, hmin / R, lo, hi);

    const int W = 24, H = 24;
    gib_image img, sd;
    gib_ref_stats st;

    gib_ref_params p = rt_params(GIB_COMP_DIRECT, W, H, 1);
    rt_render(&s, &p, &img, &sd, &st);
    result r = {0, 0, 0};
    for (int i = 0; i < W * H; i++) {
        double v = img.px[3 * i];
        r.mean += v / (W * H);
        r.worst_z += v < direct * (lo - 1e-5) || v > direct * (hi + 1e-5);
    }
    CHECK(r.worst_z == 0.0, "direct: %g pixels lie outside [%.6f, %.6f] x %.6f", r.worst_z, lo,
          hi, direct);
    printf("direct:   expected %.6f (interval [%.6f, %.6f]), measured mean %.6f, stderr 0 "
           "(deterministic); all pixels inside: %s\n",
           direct, direct * lo, direct * hi, r.mean, r.worst_z == 0.0 ? "yes" : "NO");
    gib_image_free(&img);
    gib_image_free(&sd);

    struct {
        int comp, spp, depth;
        double expect;
    } cases[2] = {{GIB_COMP_INDIRECT, 16, 0, a * direct},
                  {GIB_COMP_FULL, 512, 48, direct * (1.0 - pow(a, 48)) / (1.0 - a)}};
    for (int c = 0; c < 2; c++) {
        p = rt_params(cases[c].comp, W, H, cases[c].spp);
        p.max_depth = cases[c].depth;
        rt_render(&s, &p, &img, &sd, &st);
        r = rt_compare(&img, &sd, cases[c].expect, lo, hi);
        double e = cases[c].expect;
        double dev = r.mean < e * lo ? e * lo - r.mean : r.mean > e * hi ? r.mean - e * hi : 0.0;
        char what[192];
        snprintf(what, sizeof what, "%s: mean %.6f, distance outside [%.6f, %.6f]",
                 gib_component_name(cases[c].comp), r.mean, e * lo, e * hi);
        CHECK_AT_MOST(what, dev, 3.0 * r.se_mean,
                      "3 standard errors of the mean, the renderer's own");
        snprintf(what, sizeof what, "%s: worst 4x4 block outside the interval (std. errors)",
                 gib_component_name(cases[c].comp));
        CHECK_AT_MOST(what, r.worst_z, 4.0,
                      "36 blocks: a correct renderer's 4-sigma excursion has odds ~1 in 400");
        printf("%-8s: expected %.6f (interval [%.6f, %.6f]), measured mean %.6f, stderr of the "
               "mean %.2g (%.2f sigma outside the interval, max 3); worst 4x4 block %.2f sigma "
               "(max 4); %d spp%s\n",
               gib_component_name(cases[c].comp), e, e * lo, e * hi, r.mean, r.se_mean,
               dev / r.se_mean, r.worst_z, cases[c].spp,
               cases[c].depth ? ", max_depth 48 (a^48 = 4e-8)" : "");
        gib_image_free(&img);
        gib_image_free(&sd);
    }
    /* One diffuse cone's share (gib_ref_params.cone): the wall sees radiance `direct` in every
     * direction, so each cone's cap mean times a is the whole indirect, for every cone of the set
     * and every aperture whose cap stays above the surface (a cap sampled wrongly, or weighted by
     * the cosine, would not be flat): the central cone at 120 degrees too. */
    const float apertures[7] = {60, 60, 60, 60, 60, 60, 120};
    for (int k = 0; k < 7; k++) {
        p = rt_params(GIB_COMP_INDIRECT, W, H, 16);
        p.cone = k < 6 ? k + 1 : 1;
        p.cone_aperture = apertures[k];
        rt_render(&s, &p, &img, &sd, &st);
        const double e = a * direct;
        r = rt_compare(&img, &sd, e, lo, hi);
        double dev = r.mean < e * lo ? e * lo - r.mean : r.mean > e * hi ? r.mean - e * hi : 0.0;
        char what[192];
        snprintf(what, sizeof what,
                 "indirect, cone %d of aperture %.0f: mean %.6f, distance outside [%.6f, %.6f]",
                 p.cone - 1, (double)apertures[k], r.mean, e * lo, e * hi);
        CHECK_AT_MOST(what, dev, 3.0 * r.se_mean,
                      "3 standard errors of the mean, the renderer's own");
        snprintf(what, sizeof what, "indirect, cone %d of aperture %.0f: worst 4x4 block",
                 p.cone - 1, (double)apertures[k]);
        CHECK_AT_MOST(what, r.worst_z, 4.0,
                      "36 blocks: a correct renderer's 4-sigma excursion has odds ~1 in 400");
        printf("indirect, cone %d (aperture %.0f): measured mean %.6f (%.2f sigma outside the "
               "interval), worst block %.2f sigma\n", p.cone - 1, (double)apertures[k], r.mean,
               dev / r.se_mean, r.worst_z);
        gib_image_free(&img);
        gib_image_free(&sd);
    }
    printf("closed forms: direct (a/pi) I/R^2 = %.6f, indirect a x direct = %.6f, full direct / "
           "(1 - a) = %.6f\n",
           direct, a * direct, direct / (1.0 - a));
    rt_scene_free(&s);
    rt_spot_sphere();
    return failures ? 1 : 0;
}

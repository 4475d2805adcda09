/* The LRSM's layers and their sampling, on the GPU, from a synthetic light view (the real
 * construction pass lrsm_build.comp and the real lookup lrsm_sample.glsl through a probe):
 *  1. random texels (depths, <n.l>, radiance, a tenth empty) in the paper's packed RSM format
 *     (two RGBA16F textures, light_view.h): every layer texel of level 0, its radiance weighted by
 *     each texel's area (lrsm_area_weight, `jacobian` 1), equals the CPU mirror
 *     lrsm_build_block() run on the texels as the half floats hold them (read back), within the
 *     layers' formats' rounding: half floats (relative 2^-11 a value, RAD_TOL 2e-3 for a sum of 4)
 *     and 16-bit UNORM (2^-16, DEPTH_TOL 3e-5);
 *  2. a depth discontinuity (z = 2 left of column 37 of 64, z = 8 right of it, partitions [0, 5]
 *     and [5, 10]): at EVERY mip level each layer texel holds one side only (mean depth within
 *     0.02 of 2 or 8, variance below 1e-4 of the layer's range squared); the same check run on a
 *     single layer (D = 1) must find straddling texels, so it can fail;
 *  3. with the discontinuity in the middle of the view, probes of lrsm_sample (Algorithm 1) with v_c
 *     toward the light: on a flat lit surface it
 *     returns R <n.v_c> (Eq. 5 with V = 1: Eq. 12 of a sample 9 floored sigmas wide), within
 *     PROBE_TOL 1% (half-float radiance and normals); nothing between the two surfaces; a wide
 *     sample centred on the discontinuity returns half (A = 1/2, Eq. 14); a surface inside the
 *     overlap band (z = 5.2, in both layers) is counted once: Eq. 15's decays add to 1; a sample
 *     centred in one layer whose sphere reaches a surface of the next sees it (the layers met by
 *     [z_c - r_c, z_c + r_c] are read: lrsm_sample.glsl). */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "harness/gl/context.h"
#include "techniques/lrsm/lrsm.h"
#include "techniques/lrsm/lrsm_math.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

#define RES 64
#define HALF (RES / 2)
#define RAD_TOL 2e-3
#define DEPTH_TOL 3e-5
#define PROBE_TOL 0.01

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

/* The light view in the paper's packed format (light_view.h, GIB_LV_PACKED16). */
typedef struct synth {
    float radiance_depth[RES * RES * 4], normal_nl[RES * RES * 4];
} synth;

/* The side of a light-view texel (the orthographic view's, world units). */
static double texel_side;

static void upload(const gib_light_views *lv, const synth *s)
{
    glTextureSubImage3D(lv->textures[0], 0, 0, 0, 0, RES, RES, 1, GL_RGBA, GL_FLOAT,
                        s->radiance_depth);
    glTextureSubImage3D(lv->textures[1], 0, 0, 0, 0, RES, RES, 1, GL_RGBA, GL_FLOAT, s->normal_nl);
}

/* A texel facing the light at <n.l> = c (l = -forward) at depth z, reflecting the radiance of a
 * flux f per texel: f (k + 1) / 3 c / (pi s^2) in channel k (what the light view writes for an
 * orthographic view of texels of side s). */
static void set_texel(synth *s, const gib_lv_face *face, int i, float z, float c, float f)
{
    float t[3], b[3], l[3] = {-face->forward[0], -face->forward[1], -face->forward[2]};
    gib_ortho_basis(l, t, b);
    float sn = sqrtf(fmaxf(0.0f, 1 - c * c));
    for (int k = 0; k < 3; k++) {
        s->normal_nl[4 * i + k] = c * l[k] + sn * t[k];
        s->radiance_depth[4 * i + k] =
            (float)(f * (k + 1) / 3.0 * c / (M_PI * texel_side * texel_side));
    }
    s->normal_nl[4 * i + 3] = c;
    s->radiance_depth[4 * i + 3] = z;
}

static void read_level(unsigned tex, int level, float *out, int side, int layers)
{
    glGetTextureImage(tex, level, GL_RGBA, GL_FLOAT, (GLsizei)(sizeof(float) * 4 * side * side * layers),
                      out);
}

/* Part 2's check over every level; returns the number of texels holding both sides. */
static int straddling(const lrsm_layers *L, const lrsm_partition *p, int verbose)
{
    int bad = 0, layers = L->depth_parts * L->normal_parts;
    float *buf = malloc(sizeof(float) * 4 * HALF * HALF * layers);
    for (int level = 0; (HALF >> level) > 0; level++) {
        int side = HALF >> level;
        read_level(L->depth, level, buf, side, layers);
        for (int l = 0; l < layers; l++) {
            double lo, hi;
            lrsm_layer_range(p, l / L->normal_parts, &lo, &hi);
            for (int i = 0; i < side * side; i++) {
                const float *v = buf + 4 * ((size_t)l * side * side + i);
                if (v[2] < 1e-3)
                    continue;
                double mu = v[0] / v[2], var = v[1] / v[2] - mu * mu, z = lo + mu * (hi - lo);
                if ((fabs(z - 2) > 0.02 && fabs(z - 8) > 0.02) || var > 1e-4) {
                    if (verbose && bad < 3)
                        printf("  level %d layer %d texel %d: mean depth %.4f, variance %.3g\n", level,
                               l, i, z, var);
                    bad++;
                }
            }
        }
    }
    free(buf);
    return bad;
}

static void probe_check(const lrsm_layers *L, const gib_light_views *lv, const float *in, int n,
                        const double *want, const char *const *what)
{
    float out[4 * 8];
    gib_error err;
    if (lrsm_layers_probe(L, lv, 0, 1, in, n, out, &err) < 0) {
        CHECK(0, "probe: %s", err.msg);
        return;
    }
    for (int i = 0; i < n; i++) {
        double got = out[4 * i + 1];  /* green */
        if (want[i] != 0) {
            snprintf(check_msg, sizeof check_msg, "probe %s: L %.6g over the expected %.6g",
                     what[i], got, want[i]);
            CHECK_NEAR(check_msg, 1, got / want[i], PROBE_TOL, "half-float radiance and normals");
            continue;
        }
        /* Nothing there: strictly below 1e-6 (a strict bound, which CHECK_AT_MOST is not). */
        int ok = fabs(got) < 1e-6;
        snprintf(check_msg, sizeof check_msg, "probe %s: L %.6g, expected 0 (|L| < 1e-6)",
                 what[i], got);
        CHECK_TRUE(check_msg, ok, "");
    }
}

int main(void)
{
    gib_gl_fixture fx;
    gib_error err;
    if (gib_fixture_open(&fx, "water") < 0)   /* one directional light: one orthographic face */
        return 1;
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    gib_light_views lv;
    lrsm_layers L;
    if (gib_light_views_create(&lv, &fx.gpu, RES, GIB_LV_PACKED16, "rsm", &ledger, &err) < 0 ||
        lrsm_layers_create(&L, &lv, 2, 2, 0.2f, &ledger, &err) < 0) {
        CHECK(0, "set-up: %s", err.msg);
        return 1;
    }
    const gib_lv_face *face = &lv.faces[0];
    double s = lv.texel[0];
    texel_side = s;
    L.jacobian = 1; /* texels weighted by area (an orthographic view: by 0.1 / <n.l> up to 1) */
    lrsm_layers_set_range(&L, 0, 0, 10);
    lrsm_partition p = {.z0 = 0, .z1 = 10, .parts = 2, .overlap = 0.2};
    static synth sy;

    /* 1. Random texels against the CPU mirror. */
    srand(7);
    for (int i = 0; i < RES * RES; i++) {
        float z = 0.5f + 9 * (float)rand() / RAND_MAX, c = 0.02f + 0.98f * (float)rand() / RAND_MAX;
        float f = 0.1f + (float)rand() / RAND_MAX;
        set_texel(&sy, face, i, rand() % 10 == 0 ? INFINITY : z, c, f);
    }
    upload(&lv, &sy);
    /* The CPU mirror reads what the half floats hold: the texels read back. */
    static synth held;
    glGetTextureImage(lv.textures[0], 0, GL_RGBA, GL_FLOAT, sizeof held.radiance_depth,
                      held.radiance_depth);
    glGetTextureImage(lv.textures[1], 0, GL_RGBA, GL_FLOAT, sizeof held.normal_nl, held.normal_nl);
    lrsm_texel cpu[RES * RES];
    for (int i = 0; i < RES * RES; i++) {
        const float *rz = &held.radiance_depth[4 * i], *nl = &held.normal_nl[4 * i];
        lrsm_texel t = {.valid = !isinf(rz[3]), .z = rz[3], .cosnl = nl[3],
                        .area = lrsm_area_weight(2, rz[3], p.z1, 1.0, nl[3])};
        for (int k = 0; k < 3; k++) {
            t.n[k] = nl[k];
            t.radiance[k] = rz[k];
        }
        cpu[i] = t;
    }
    lrsm_layers_build(&L, &lv);
    static float rad[4 * HALF * HALF * 4], nrm[4 * HALF * HALF * 4], dep[4 * HALF * HALF * 4];
    read_level(L.radiance, 0, rad, HALF, 4);
    read_level(L.normal, 0, nrm, HALF, 4);
    read_level(L.depth, 0, dep, HALF, 4);
    double wr = 0, wn = 0, wd = 0;
    for (int by = 0; by < HALF; by++)
        for (int bx = 0; bx < HALF; bx++) {
            lrsm_texel block[4];
            for (int i = 0; i < 4; i++)
                block[i] = cpu[(2 * by + (i >> 1)) * RES + 2 * bx + (i & 1)];
            lrsm_layer_texel out[4];
            lrsm_build_block(&p, 2, block, out);
            for (int l = 0; l < 4; l++) {
                size_t g = 4 * ((size_t)l * HALF * HALF + by * HALF + bx);
                for (int k = 0; k < 4; k++) {
                    double want = out[l].radiance[k];
                    wr = fmax(wr, fabs(rad[g + k] - want) / fmax(fabs(want), 1e-3));
                }
                for (int k = 0; k < 3; k++) {
                    wn = fmax(wn, fabs(nrm[g + k] - out[l].normal[k]));
                    wd = fmax(wd, fabs(dep[g + k] - out[l].depth[k]));
                }
                wn = fmax(wn, fabs(nrm[g + 3] - out[l].normal[3]));
            }
        }
    CHECK_AT_MOST("random texels vs lrsm_build_block: radiance (rel.)", wr, RAD_TOL,
                  "half floats: relative 2^-11 a value, 2e-3 for a sum of 4");
    CHECK_AT_MOST("random texels vs lrsm_build_block: normal", wn, RAD_TOL,
                  "half floats: relative 2^-11 a value, 2e-3 for a sum of 4");
    CHECK_AT_MOST("random texels vs lrsm_build_block: depth", wd, DEPTH_TOL,
                  "16-bit UNORM rounding, 2^-16");

    /* 2. A depth discontinuity, z = 2 left of column 37 and 8 from there (not on a block boundary
     * of any level, so that the blocks of every level across it mix both sides), <n.l> = 0.9. */
    const float c = 0.9f, f = 0.5f;
    for (int y = 0; y < RES; y++)
        for (int x = 0; x < RES; x++)
            set_texel(&sy, face, y * RES + x, x < 37 ? 2.0f : 8.0f, c, f);
    upload(&lv, &sy);
    lrsm_layers_build(&L, &lv);
    int bad = straddling(&L, &p, 1);
    printf("%s discontinuity, 2 x 2 layers: %d filtered texels straddle it (every level)\n",
           bad ? "FAIL" : "PASS", bad);
    failures += bad != 0;
    {
        lrsm_layers one;
        lrsm_partition p1 = {.z0 = 0, .z1 = 10, .parts = 1, .overlap = 0.2};
        if (lrsm_layers_create(&one, &lv, 1, 2, 0.2f, &ledger, &err) < 0) {
            CHECK(0, "set-up: %s", err.msg);
            return 1;
        }
        lrsm_layers_set_range(&one, 0, 0, 10);
        lrsm_layers_build(&one, &lv);
        int b1 = straddling(&one, &p1, 0);
        snprintf(check_msg, sizeof check_msg,
                 "the check finds %d straddling texels with one depth layer (it must find some)",
                 b1);
        CHECK_TRUE(check_msg, b1, "");
        lrsm_layers_destroy(&one, &ledger);
    }
    /* Probes (3.): the discontinuity in the middle of the view, world points at (u, v) of the view
     * and depth z. */
    for (int y = 0; y < RES; y++)
        for (int x = 0; x < RES; x++)
            set_texel(&sy, face, y * RES + x, x < RES / 2 ? 2.0f : 8.0f, c, f);
    upload(&lv, &sy);
    lrsm_layers_build(&L, &lv);
    double r = 0.5 * s * RES, R = f * 2.0 / 3 * c / (M_PI * s * s), want_flat = R * c;
    float in[8 * 8];
    int n = 0;
    float pts[][5] = {{0.25f, 0.5f, 2, 0.3f}, {0.75f, 0.5f, 8, 0.3f}, {0.25f, 0.5f, 5, 0.3f},
                      {0.5f, 0.5f, 2, (float)(8 * 2 * s)}};
    for (int i = 0; i < 4; i++, n++) {
        float a = (2 * pts[i][0] - 1) * (float)r, b = (2 * pts[i][1] - 1) * (float)r;
        for (int k = 0; k < 3; k++) {
            in[8 * n + k] = face->origin[k] + face->forward[k] * pts[i][2] + face->right[k] * a +
                            face->up[k] * b;
            in[8 * n + 4 + k] = -face->forward[k];
        }
        in[8 * n + 3] = pts[i][3];
        in[8 * n + 7] = 0;
    }
    const double want[4] = {want_flat, want_flat, 0, 0.5 * want_flat};
    const char *const what[4] = {"on the near surface", "on the far surface", "between them",
                                 "16 layer texels wide on the discontinuity"};
    probe_check(&L, &lv, in, 4, want, what);
    /* A surface inside the overlap band: right half at z = 5.2. */
    for (int y = 0; y < RES; y++)
        for (int x = RES / 2; x < RES; x++)
            set_texel(&sy, face, y * RES + x, 5.2f, c, f);
    upload(&lv, &sy);
    lrsm_layers_build(&L, &lv);
    for (int k = 0; k < 3; k++)
        in[8 * 1 + k] += face->forward[k] * (5.2f - 8.0f);
    const double want_band[1] = {want_flat};
    const char *const what_band[1] = {"on a surface in the overlap band (z = 5.2)"};
    probe_check(&L, &lv, in + 8, 1, want_band, what_band);
    /* A sample centred in the near layer only whose sphere reaches a surface of the far one: depth
     * range [0, 1] (layers [-0.025, 0.525] and [0.475, 1.025]), every texel at z = 0.8, the sample
     * at z_c = 0.35 with r_c = 0.5. The paper's rule (layers holding z_c) reads nothing here. */
    lrsm_layers_set_range(&L, 0, 0, 1);
    for (int i = 0; i < RES * RES; i++)
        set_texel(&sy, face, i, 0.8f, c, f);
    upload(&lv, &sy);
    lrsm_layers_build(&L, &lv);
    for (int k = 0; k < 3; k++)
        in[8 * 1 + k] += face->forward[k] * (0.35f - 5.2f);
    in[8 * 1 + 3] = 0.5f;
    const char *const what_far[1] = {"centred in one layer, reaching a surface of the next"};
    probe_check(&L, &lv, in + 8, 1, want_band, what_far);

    lrsm_layers_destroy(&L, &ledger);
    gib_light_views_destroy(&lv, &ledger);
    gib_fixture_close(&fx);
    printf("%s: lrsm layers\n", failures ? "FAIL" : "PASS");
    return failures ? 1 : 0;
}

/* Reference renderer, filtered textures at primary hits (ref_texture.c): the mip pyramid, GL's
 * trilinear lookup, the ray differentials (Igehy 1999) and the LOD they give, and the end result
 * in the `albedo` component; the compact cut-out masks against the floats they replace.
 *
 * Expected values are exact (box averages, linear blends, GL's 8-bit sRGB rounding of mip levels,
 * and the closed-form pixel footprint of a camera looking straight down at a plane), so tolerances
 * are float rounding: 1e-6 absolute on texel values, 1e-4 relative on derivatives. */
#include <math.h>
#include <string.h>

#include "reference/ref_internal.h"
#include "ref_test_util.h"
#include "tests/common/check.h"


static int close_to(float a, float b, float tol)
{
    return fabsf(a - b) <= tol;
}

/* 1. Pyramid levels are 2x2 box averages (3 wide at an odd edge), down to 1x1. */
static void test_pyramid(void)
{
    float rgba[4 * 4 * 4];
    for (int i = 0; i < 16; i++)
        for (int c = 0; c < 4; c++)
            rgba[4 * i + c] = (float)(i + 1) * (c + 1);
    gib_texture t;
    memset(&t, 0, sizeof t);
    t.width = t.height = 4;
    t.rgba = rgba;
    ref_mip m;
    gib_error err;
    CHECK(ref_mip_build(&m, &t, &err) == 0, "pyramid build");
    CHECK(m.levels == 3 && m.w[1] == 2 && m.h[2] == 1, "4x4 gives 3 levels: %d", m.levels);
    /* level 1 texel (0,0) averages texels 1, 2, 5, 6 (values i + 1): 3.5; level 2 the mean 8.5 */
    CHECK(close_to(m.lv[1][0], 3.5f, 1e-6f) && close_to(m.lv[1][4 * 3 + 3], 4.0f * 13.5f, 1e-5f),
          "level 1: %g %g", m.lv[1][0], m.lv[1][15]);
    CHECK(close_to(m.lv[2][0], 8.5f, 1e-6f), "level 2: %g, expected 8.5", m.lv[2][0]);

    /* 2. Trilinear at LOD 0.5 on the centre of texel 0 (u = 1/8, v = 7/8 since t = 1 - v):
     * half level 0 there (exactly texel 0: 1) and half level 1 bilinear at that point (a quarter
     * texel from level-1 texel (0,0) toward both wrapped neighbours: 0.75^2 * 3.5 + 0.75 * 0.25 *
     * (5.5 + 11.5) + 0.25^2 * 13.5 = 6.0). duv gives rho = sqrt(2): du/dx = sqrt(2)/4. */
    float duv[4] = {sqrtf(2.0f) / 4.0f, 0.0f, 0.0f, 0.0f}, out[4];
    CHECK(close_to(ref_mip_lod(&m, duv), 0.5f, 1e-6f), "lod %g, expected 0.5",
          ref_mip_lod(&m, duv));
    ref_mip_sample(&m, 0.125f, 0.875f, duv, out);
    float l1 = 0.5625f * 3.5f + 0.1875f * (5.5f + 11.5f) + 0.0625f * 13.5f;
    CHECK(close_to(out[0], 0.5f * 1.0f + 0.5f * l1, 1e-5f), "trilinear %g, expected %g", out[0],
          0.5f * 1.0f + 0.5f * l1);
    /* magnification (LOD < 0) and no derivatives: level 0 bilinear, the texel itself */
    duv[0] = 0.01f;
    ref_mip_sample(&m, 0.125f, 0.875f, duv, out);
    CHECK(close_to(out[0], 1.0f, 1e-6f), "magnified: %g, expected 1", out[0]);
    ref_mip_sample(&m, 0.125f, 0.875f, NULL, out);
    CHECK(close_to(out[0], 1.0f, 1e-6f), "no derivatives: %g, expected 1", out[0]);
    /* beyond the last level: the 1x1 level */
    duv[0] = 100.0f;
    ref_mip_sample(&m, 0.3f, 0.6f, duv, out);
    CHECK(close_to(out[0], 8.5f, 1e-5f), "LOD past the top: %g, expected 8.5", out[0]);
    ref_mip_free(&m);

    /* odd size: 3x3 -> one 1x1 level, the mean of all 9 */
    float odd[9 * 4];
    for (int i = 0; i < 9; i++)
        for (int c = 0; c < 4; c++)
            odd[4 * i + c] = (float)i;
    t.width = t.height = 3;
    t.rgba = odd;
    CHECK(ref_mip_build(&m, &t, &err) == 0 && m.levels == 2, "3x3 pyramid");
    CHECK(close_to(m.lv[1][0], 4.0f, 1e-6f), "3x3 top level %g, expected the mean 4",
          m.lv[1][0]);
    ref_mip_free(&m);

    /* 8-bit textures (every colour the decode of some k/255, as loaded from files) are kept as GL
     * keeps them: sRGB8, level 0 exact, the mips rounded to 8 bits. A 2x2 texture of 0 and 1:
     * level 1 holds decode(round(encode(0.5) * 255) / 255) = decode(188/255), not 0.5. */
    float bw[16] = {0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 0, 1};
    t.width = t.height = 2;
    t.rgba = bw;
    CHECK(ref_mip_build(&m, &t, &err) == 0 && m.srgb8 && m.levels == 2, "8-bit texture kept "
          "as sRGB8 (srgb8 %d, levels %d)", m.srgb8, m.levels);
    ref_mip_sample(&m, 0.75f, 0.75f, NULL, out); /* texel (1, 0): white, exactly */
    CHECK(out[0] == 1.0f && out[3] == 1.0f, "sRGB8 level 0 texel: %g, expected 1", out[0]);
    duv[0] = 10.0f;
    ref_mip_sample(&m, 0.3f, 0.6f, duv, out);
    double c = 188.0 / 255.0, want = pow((c + 0.055) / 1.055, 2.4);
    CHECK_NEAR("sRGB8 level 1", want, out[0], 1e-6, "float rounding: 1e-6 absolute on texels");
    ref_mip_free(&m);
    printf("pyramid, trilinear blend, magnification, odd sizes, sRGB8 levels (0.5 stored as "
           "%.6f, as GL rounds it): exact\n", want);
}

/* 3. Differentials of a floor seen straight down: the floor is parallel to the image plane, so a
 * pixel covers fp = 2 h tan(fov/2) / H metres everywhere; with u = (x - x0) / S and
 * v = (z1 - z) / S, du/dx = fp / S, dv/dy = -fp / S (image down is +z), the cross terms 0.
 * 4. The albedo image of a 1-texel checkerboard (0 and 1) minified past LOD 1: every level from 1
 * up holds 0.5 in linear (0.50287 after GL's 8-bit sRGB rounding), so every pixel is that times
 * the albedo — where level 0 at the pixel centre would alias between 0 and the albedo. */
static void test_floor(void)
{
    const float h = 4.0f, fov = 60.0f, S = 10.0f;
    const int W = 32, H = 32, T = 256;
    gib_scene s;
    rt_scene_init(&s, "texture_floor");
    int m = rt_material(&s, 0.8f, 0.8f, 0.8f);
    static float checker[256 * 256 * 4];
    for (int y = 0; y < T; y++)
        for (int x = 0; x < T; x++)
            for (int c = 0; c < 4; c++)
                checker[(y * T + x) * 4 + c] = (float)((x + y) & 1);
    s.materials[m].albedo_tex = rt_texture(&s, T, T, checker);
    s.features |= GIB_FEAT_TEXTURES;
    rt_floor(&s, 0.0f, -S / 2, S / 2, -S / 2, S / 2, m);
    const float eye[3] = {0.3f, h, -0.2f}, tgt[3] = {0.3f, 0.0f, -0.2f}, up[3] = {0, 0, -1};
    rt_camera(&s, eye, tgt, up, fov);
    const double fp = 2.0 * h * tan(0.5 * fov * M_PI / 180.0) / H;

    ref_world w;
    gib_error err;
    if (ref_world_build(&w, &s, &err) < 0) {
        CHECK(0, "%s", err.msg);
        failures++;
        return;
    }
    double worst = 0.0, lod_min = INFINITY, lod_max = -INFINITY;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float o[3], d[3];
            gib_camera_ray(&s.cameras[0], W, H, x + 0.5f, y + 0.5f, o, d);
            ref_hit hit;
            if (!ref_trace(&w, o, d, &hit)) {
                failures++;
                continue;
            }
            ref_hit_differentials(&w, &s.cameras[0], W, H, x, y, &hit);
            const double want[4] = {fp / S, 0.0, 0.0, -fp / S};
            for (int k = 0; k < 4; k++)
                worst = fmax(worst, fabs(hit.duv[k] - want[k]) / (fp / S));
            double lod = ref_mip_lod(&w.mips[0], hit.duv);
            lod_min = fmin(lod_min, lod);
            lod_max = fmax(lod_max, lod);
        }
    double lod_want = log2(T * fp / S);
    CHECK_AT_MOST("differentials: max error, relative to du/dx", worst, 1e-4,
                  "float rounding: 1e-4 relative on derivatives");
    CHECK_NEAR("differentials: smallest LOD", lod_want, lod_min, 1e-3,
               "float rounding (the file's tolerances are)");
    CHECK_NEAR("differentials: largest LOD", lod_want, lod_max, 1e-3,
               "float rounding (the file's tolerances are)");
    printf("differentials: du/dx = %.6f expected, max error %.2g of it (tol 1e-4); LOD %.4f "
           "expected, measured %.4f .. %.4f\n",
           fp / S, worst, lod_want, lod_min, lod_max);
    ref_world_free(&w);

    gib_ref_params p = rt_params(GIB_COMP_ALBEDO, W, H, 1);
    gib_image img;
    rt_render(&s, &p, &img, NULL, NULL);
    int bad = 0;
    const double grey = pow((188.0 / 255.0 + 0.055) / 1.055, 2.4), want = 0.8 * grey;
    for (int i = 0; i < W * H * 3; i++)
        bad += fabs(img.px[i] - want) > 1e-6;
    CHECK(bad == 0, "albedo: %d values differ from %.6f", bad, want);
    printf("albedo of a minified 1-texel checkerboard (LOD %.2f): all %d values %.6f = 0.8 x "
           "the 8-bit mid grey %.6f (tol 1e-6)\n",
           lod_want, W * H * 3, want, grey);
    gib_image_free(&img);
    rt_scene_free(&s);
}

/* 3. Cut-out masks in their compact form (one byte a texel indexing the distinct first-channel
 * values) give bit for bit the lookup of the floats, at sizes that are not multiples of the 8x8
 * tile, with u and v outside [0, 1], and with -0 and +0 kept apart; more than 256 distinct values
 * fall back to the floats. Exact: the same floats in the same arithmetic. */
static void test_mask(void)
{
    enum { W = 37, H = 21 };
    static float rgba[W * H * 4];
    for (int pass = 0; pass < 2; pass++) {
        int distinct = pass == 0 ? 200 : 300;
        for (int i = 0; i < W * H; i++) {
            int k = (i * 7919) % distinct;
            rgba[4 * i] = k == 0 ? -0.0f : k == 1 ? 0.0f : 0.5f + 0.5f * sinf((float)k);
            rgba[4 * i + 1] = rgba[4 * i + 2] = 0.25f, rgba[4 * i + 3] = 1.0f;
        }
        gib_texture t;
        memset(&t, 0, sizeof t);
        t.width = W, t.height = H, t.rgba = rgba;
        ref_mask m;
        gib_error err;
        CHECK(ref_mask_build(&m, &t, &err) == 0, "mask build");
        CHECK((m.code != NULL) == (pass == 0), "%d distinct values: compact form %s", distinct,
              m.code ? "built" : "not built");
        uint32_t state = 12345u;
        int mismatches = 0;
        for (int n = 0; n < 20000; n++) {
            state = state * 1664525u + 1013904223u;
            float u = (float)(state >> 8) / 16777216.0f * 3.0f - 1.0f;
            state = state * 1664525u + 1013904223u;
            float v = (float)(state >> 8) / 16777216.0f * 3.0f - 1.0f;
            if (n < 64) /* texel centres, where the lookup is one texel exactly */
                u = ((float)(n % W) + 0.5f) / W, v = 1.0f - ((float)(n % H) + 0.5f) / H;
            float a[4], b = ref_mask_sample(&m, u, v);
            ref_tex_sample(&t, u, v, a);
            mismatches += memcmp(&a[0], &b, sizeof b) != 0;
        }
        CHECK(mismatches == 0, "%d distinct values: %d of 20000 lookups differ from the floats",
              distinct, mismatches);
        printf("mask with %d distinct values: compact %d, 20000 lookups bit-identical to the "
               "floats: %s\n", distinct, m.code != NULL, mismatches == 0 ? "yes" : "no");
        ref_mask_free(&m);
    }
}

/* 5. The sRGB8 pyramid, which ref_mip_build makes straight from the packed texels, equals texel
 * for texel the pyramid made the plain way: each level decoded to floats (sRGB via the loader's
 * decode, alpha k / 255), box-filtered (2x2, 3 wide at an odd edge, sums in row order), and each
 * value rounded to the nearest 8-bit code (sRGB: the number of encoded midpoints at or below it,
 * counted in double). Odd sizes, single rows and columns, flat blocks and noisy ones; exact. */
static float srgb_decode8(int k)
{
    float c = (float)k / 255.0f;
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

static unsigned srgb_code_plain(float v)
{
    unsigned k = 0;
    while (k < 255) {
        double c = (k + 0.5) / 255.0;
        double mid = c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
        if (!((double)v >= mid))
            break;
        k++;
    }
    return k;
}

/* One level from the previous, both as codes (4 a texel, row-major): decode, box, round. */
static void level_plain(const uint8_t *src, int sw, int sh, uint8_t *dst, int dw, int dh)
{
    for (int y = 0; y < dh; y++)
        for (int x = 0; x < dw; x++) {
            int y1 = (y == dh - 1 && sh > 2 * dh) ? 2 * y + 2 : 2 * y + 1;
            int x1 = (x == dw - 1 && sw > 2 * dw) ? 2 * x + 2 : 2 * x + 1;
            y1 = y1 < sh ? y1 : sh - 1;
            x1 = x1 < sw ? x1 : sw - 1;
            float acc[4] = {0, 0, 0, 0};
            int n = 0;
            for (int yy = 2 * y; yy <= y1; yy++)
                for (int xx = 2 * x; xx <= x1; xx++, n++)
                    for (int c = 0; c < 4; c++) {
                        int k = src[((size_t)yy * sw + xx) * 4 + c];
                        acc[c] += c < 3 ? srgb_decode8(k) : (float)k / 255.0f;
                    }
            for (int c = 0; c < 4; c++) {
                float v = acc[c] / (float)n;
                dst[((size_t)y * dw + x) * 4 + c] =
                    (uint8_t)(c < 3 ? srgb_code_plain(v) : (unsigned)lrintf(v * 255.0f));
            }
        }
}

/* Mismatching texels of level l of m against the codes want (row-major), read from 4x4 tiles. */
static int level_mismatches(const ref_mip *m, int l, const uint8_t *want)
{
    const int w = m->w[l], h = m->h[l], tw = (w + 3) / 4;
    int bad = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint32_t got = m->lv8[l][((size_t)(y >> 2) * tw + (x >> 2)) * 16 + (y & 3) * 4 + (x & 3)];
            for (int c = 0; c < 4; c++)
                bad += ((got >> (8 * c)) & 255u) != want[((size_t)y * w + x) * 4 + c];
        }
    return bad;
}

/* A W x H 8-bit texture: codes (4 a texel) and their decoded floats; the left half flat by 4x4
 * blocks, the right half noise. */
static void fill_texture(int W, int H, uint32_t state, uint8_t *codes, float *rgba)
{
    for (int i = 0; i < W * H * 4; i++) {
        int x = (i / 4) % W, y = (i / 4) / W;
        state = state * 1664525u + 1013904223u;
        int k = x < W / 2 ? (int)(((x / 4) * 37 + (y / 4) * 91 + i % 4 * 53) % 256)
                          : (int)(state >> 24);
        codes[i] = (uint8_t)(i % 4 == 3 && (state & 0x100) ? 255 : k);
        rgba[i] = i % 4 < 3 ? srgb_decode8(codes[i]) : (float)codes[i] / 255.0f;
    }
}

/* Channel values of m's levels that differ from the plain pyramid of the level-0 codes
 * codes[0] (codes[1] and codes[0] are overwritten on the way up); *levels counts the levels. */
static int plain_mismatches(const ref_mip *m, uint8_t (*codes)[64 * 64 * 4], int *levels)
{
    int bad = level_mismatches(m, 0, codes[0]);
    for (int l = 1; l < m->levels; l++, (*levels)++) {
        level_plain(codes[(l - 1) & 1], m->w[l - 1], m->h[l - 1], codes[l & 1], m->w[l], m->h[l]);
        int b = level_mismatches(m, l, codes[l & 1]);
        CHECK(b == 0, "%dx%d level %d (%dx%d): %d channel values differ", m->w[0], m->h[0], l,
              m->w[l], m->h[l], b);
        bad += b;
    }
    return bad;
}

static uint8_t codes[2][64 * 64 * 4];
static float rgba[64 * 64 * 4];

static void test_srgb8_pyramid(void)
{
    static const int sizes[][2] = {{37, 5}, {1, 9}, {9, 1}, {64, 64}, {33, 17}, {3, 3}, {2, 7}};
    int levels = 0, bad = 0;
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        const int W = sizes[s][0], H = sizes[s][1];
        fill_texture(W, H, 777u + (uint32_t)s, codes[0], rgba);
        gib_texture t;
        memset(&t, 0, sizeof t);
        t.width = W, t.height = H, t.rgba = rgba;
        ref_mip m;
        gib_error err;
        if (ref_mip_build(&m, &t, &err) != 0 || !m.srgb8) {
            CHECK(0, "%dx%d: no sRGB8 pyramid", W, H);
            continue;
        }
        bad += plain_mismatches(&m, codes, &levels);
        ref_mip_free(&m);
    }
    CHECK(bad == 0, "sRGB8 pyramids: %d channel values differ from decode -> box -> round", bad);
    printf("sRGB8 pyramids of 7 sizes (37x5 .. 64x64, odd edges, flat and noisy blocks): %d "
           "levels equal to decode -> box filter -> round, value for value: %s\n",
           levels, bad == 0 ? "yes" : "no");
}

/* 6. A texture of the same path and size as an earlier one takes the earlier pyramid only when its
 * level 0 packs the same: while that pyramid is held and after it is freed (kept idle); one
 * channel of one texel changed gives a pyramid of its own, equal to the plain one. */
static void test_srgb8_share(void)
{
    enum { W = 33, H = 17, LAST = (W * H - 1) * 4 + 1 };
    fill_texture(W, H, 99u, codes[0], rgba);
    gib_texture t;
    memset(&t, 0, sizeof t);
    snprintf(t.path, sizeof t.path, "%s", "ref_texture_share.png");
    t.width = W, t.height = H, t.rgba = rgba;
    ref_mip a, b, c, d;
    gib_error err;
    int rc = ref_mip_build(&a, &t, &err) | ref_mip_build(&b, &t, &err);
    const uint32_t *first = a.lv8[0];
    const int held = b.lv8[0] == first;
    ref_mip_free(&a);
    ref_mip_free(&b);
    rc |= ref_mip_build(&c, &t, &err);
    const int idle = c.lv8[0] == first;
    codes[0][LAST] ^= 1;
    rgba[LAST] = srgb_decode8(codes[0][LAST]);
    rc |= ref_mip_build(&d, &t, &err);
    const int own = d.lv8[0] != first;
    int levels = 0, bad = rc == 0 && d.srgb8 ? plain_mismatches(&d, codes, &levels) : -1;
    CHECK(rc == 0 && held && idle && own && bad == 0,
          "sharing: shared while held %d, after freed %d, own pyramid when one texel differs %d "
          "(%d values differ from the plain pyramid)", held, idle, own, bad);
    printf("shared pyramids: taken while held %s, after freed %s; one texel changed: its own "
           "pyramid %s, equal to the plain one %s\n", held ? "yes" : "no", idle ? "yes" : "no",
           own ? "yes" : "no", bad == 0 ? "yes" : "no");
    ref_mip_free(&c);
    ref_mip_free(&d);
}

int main(void)
{
    test_pyramid();
    test_floor();
    test_mask();
    test_srgb8_pyramid();
    test_srgb8_share();
    return failures ? 1 : 0;
}

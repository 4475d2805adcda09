/* Unit tests for harness/imaging/flip: LDR-FLIP and HDR-FLIP means against NVIDIA's reference
 * implementation (github.com/NVlabs/flip, FLIP.h at commit 1eb247c) on constructed image pairs,
 * plus properties the papers' definitions imply.
 *
 * The expected means below were computed by the reference implementation's FLIP::evaluate on
 * exactly these pairs: `test_flip --dump DIR` writes them as raw floats and
 * tests/imaging/flip_ref_driver.cpp (compiled against the reference's FLIP.h, see its header)
 * prints their means. The reference's own test images (images/test.png, test.exr) could not be
 * obtained here, so its published means (LDR 0.159691, HDR 0.283478) are not checked.
 *
 * Usage: test_flip [--dump DIR]. Exit status: number of failed checks. */
#include "tests/common/check.h"
#include "harness/imaging/flip.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;



static uint32_t rng_state;
static float rnd(void) /* xorshift32 in [0,1) */
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return (float)(rng_state >> 8) / 16777216.0f;
}

enum { W = 96, H = 64, NPAIRS = 4 };
static const char *const pair_names[NPAIRS] = {"ldr_noise", "ldr_shift_blur", "hdr_noise",
                                               "hdr_highlight"};

/* Pair k, linear RGB: a scene of gradients, a checkerboard and coloured discs (edges, points,
 * colour), and a test image with noise (pairs 0, 2), a colour shift plus a box blur (1), or a
 * missing highlight and a brighter patch (3). Pairs 2 and 3 are HDR (values up to ~40). */
static void make_pair(int k, float *ref, float *test)
{
    rng_state = 0x9e3779b9u + (uint32_t)k;
    int hdr = k >= 2;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float *p = ref + 3 * (y * W + x);
            float u = (float)x / W, v = (float)y / H;
            p[0] = 0.8f * u;
            p[1] = 0.6f * v;
            p[2] = 0.3f + 0.2f * u * v;
            if (((x / 8) + (y / 8)) % 2 == 0 && y > H / 2) {
                p[0] *= 0.2f;
                p[1] *= 0.2f;
                p[2] *= 0.2f;
            }
            float dx = (float)x - 24, dy = (float)y - 20, dx2 = (float)x - 70, dy2 = (float)y - 40;
            if (dx * dx + dy * dy < 100) {
                p[0] = 0.9f;
                p[1] = 0.1f;
                p[2] = 0.1f;
            }
            if (dx2 * dx2 + dy2 * dy2 < 36) {
                p[0] = 0.1f;
                p[1] = 0.2f;
                p[2] = 0.95f;
            }
            if (hdr) {
                for (int c = 0; c < 3; c++)
                    p[c] *= 2.0f;
                if (abs(x - 50) < 3 && abs(y - 12) < 3)
                    p[0] = p[1] = p[2] = 40.0f; /* a highlight, 5 stops above the rest */
            }
        }
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const float *p = ref + 3 * (y * W + x);
            float *q = test + 3 * (y * W + x);
            for (int c = 0; c < 3; c++) {
                float v = p[c];
                if (k == 0 || k == 2)
                    v = v + (rnd() - 0.5f) * 0.2f * (hdr ? 2.0f : 1.0f);
                if (k == 1) {
                    float s = 0;
                    for (int j = -1; j <= 1; j++)
                        for (int i = -1; i <= 1; i++) {
                            int xx = x + i < 0 ? 0 : x + i >= W ? W - 1 : x + i;
                            int yy = y + j < 0 ? 0 : y + j >= H ? H - 1 : y + j;
                            s += ref[3 * (yy * W + xx) + c];
                        }
                    v = s / 9.0f + (c == 0 ? 0.05f : c == 2 ? -0.05f : 0.0f);
                }
                if (k == 3) {
                    if (abs(x - 50) < 3 && abs(y - 12) < 3)
                        v = 4.0f;
                    else if (x > 60 && y < 20)
                        v *= 1.5f;
                }
                q[c] = v < 0 ? 0 : v;
            }
        }
}

/* Means from the reference implementation (flip_ref_driver, FLIP.h 1eb247c, default 67.02 ppd;
 * HDR with the ACES tone mapper and the reference-derived exposure range). */
static const double expected_mean[NPAIRS] = {0.1245406, 0.2362045, 0.2760477, 0.0632101};
/* Both HDR references share their luminance maximum (the highlight) and median. */
static const double expected_start[2] = {-4.2386308, -4.2386308};
static const double expected_stop[2] = {2.1855767, 2.1855767};

static int dump(const char *dir)
{
    static float ref[3 * W * H], test[3 * W * H];
    for (int k = 0; k < NPAIRS; k++) {
        make_pair(k, ref, test);
        char path[4096];
        snprintf(path, sizeof path, "%s/%s.f32", dir, pair_names[k]);
        FILE *f = fopen(path, "wb");
        int dims[3] = {W, H, k >= 2};
        if (!f || fwrite(dims, sizeof dims, 1, f) != 1 || fwrite(ref, sizeof ref, 1, f) != 1 ||
            fwrite(test, sizeof test, 1, f) != 1) {
            fprintf(stderr, "test_flip: cannot write %s\n", path);
            return 1;
        }
        fclose(f);
        printf("%s\n", path);
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 3 && !strcmp(argv[1], "--dump"))
        return dump(argv[2]);
    static float ref[3 * W * H], test[3 * W * H], map[W * H];
    gib_error err = {0};
    const float ppd = gib_flip_default_ppd();
    CHECK_NEAR("default ppd = 0.7*3840/0.7*pi/180", 67.0206432, ppd, 1e-4, "float rounding");

    /* Against the reference implementation. Tolerance 1e-5 (measured differences are ~1e-7): the
     * same float filters summed in the same order; what differs is cbrtf against powf(x, 1/3),
     * the mean summed in double here and in float there, and the 7 printed decimals. A wrong
     * constant or filter moves these means by 1e-3 or more. */
    for (int k = 0; k < NPAIRS; k++) {
        make_pair(k, ref, test);
        char what[96];
        if (k < 2) {
            double m = gib_flip_ldr(ref, test, W, H, ppd, map, &err);
            snprintf(what, sizeof what, "LDR-FLIP mean, %s", pair_names[k]);
            CHECK_NEAR(what, expected_mean[k], m, 1e-5, "vs NVlabs/flip FLIP.h");
        } else {
            float start, stop;
            double m = gib_flip_hdr(ref, test, W, H, ppd, map, &start, &stop, &err);
            snprintf(what, sizeof what, "HDR-FLIP mean, %s", pair_names[k]);
            CHECK_NEAR(what, expected_mean[k], m, 1e-5, "vs NVlabs/flip FLIP.h");
            snprintf(what, sizeof what, "HDR-FLIP start exposure, %s", pair_names[k]);
            CHECK_NEAR(what, expected_start[k - 2], start, 1e-5, "vs FLIP.h, float log2");
            snprintf(what, sizeof what, "HDR-FLIP stop exposure, %s", pair_names[k]);
            CHECK_NEAR(what, expected_stop[k - 2], stop, 1e-5, "vs FLIP.h, float log2");
        }
        float lo = 1, hi = 0;
        for (int i = 0; i < W * H; i++) {
            lo = fminf(lo, map[i]);
            hi = fmaxf(hi, map[i]);
        }
        snprintf(what, sizeof what, "error map in [0,1], %s", pair_names[k]);
        CHECK_TRUE(what, lo >= 0 && hi <= 1 && hi > lo, "FLIP's error is a value in [0,1]");
    }

    /* Identical images: no colour difference, so the error is exactly 0 (Eq. 9: 0^(1-f) = 0). */
    make_pair(0, ref, test);
    CHECK_NEAR("LDR-FLIP(a, a)", 0.0, gib_flip_ldr(ref, ref, W, H, ppd, NULL, &err), 0.0, "exact");
    CHECK_NEAR("HDR-FLIP(a, a)", 0.0, gib_flip_hdr(ref, ref, W, H, ppd, NULL, NULL, NULL, &err),
               0.0, "exact");
    /* Green against blue, flat: the colour difference is the largest there is, cmax, which the
     * compression of Sec. 4.2 maps to exactly 1; flat images have no features. */
    for (int i = 0; i < W * H; i++) {
        ref[3 * i] = 0, ref[3 * i + 1] = 1, ref[3 * i + 2] = 0;
        test[3 * i] = 0, test[3 * i + 1] = 0, test[3 * i + 2] = 1;
    }
    CHECK_NEAR("LDR-FLIP(green, blue) = 1", 1.0, gib_flip_ldr(ref, test, W, H, ppd, NULL, &err),
               1e-5, "cmax maps to 1, float rounding");
    /* Values over 1 are clamped in LDR-FLIP, as the reference clamps its input. */
    for (int i = 0; i < 3 * W * H; i++)
        test[i] = ref[i] * 5.0f;
    CHECK_NEAR("LDR-FLIP clamps: (g, 5g) = 0", 0.0, gib_flip_ldr(ref, test, W, H, ppd, NULL, &err),
               0.0, "exact");

    /* Bad input: a NaN gives NaN and a message naming the image. */
    test[3 * 7 + 1] = NAN;
    double m = gib_flip_ldr(ref, test, W, H, ppd, NULL, &err);
    CHECK_TRUE("NaN in test -> NaN mean", isnan(m), err.msg);
    CHECK_TRUE("message names the test image", strstr(err.msg, "test image") != NULL, err.msg);
    /* Over half the reference black (a caustic component): the median of the positive
     * luminances sets the stop exposure (our stated choice; FLIP.h would get an infinite range). */
    make_pair(2, ref, test);
    for (int i = 0; i < 3 * W * H * 6 / 10; i++)
        ref[i] = test[i] = 0.0f;
    float s0, s1;
    m = gib_flip_hdr(ref, test, W, H, ppd, NULL, &s0, &s1, &err);
    CHECK_TRUE("HDR-FLIP, 60% black reference: finite range",
               isfinite(m) && isfinite(s1) && s1 > s0, "median of the positive luminances");
    /* A black reference has no HDR exposure range. */
    memset(ref, 0, sizeof ref);
    memset(test, 0, sizeof test);
    m = gib_flip_hdr(ref, test, W, H, ppd, NULL, NULL, NULL, &err);
    CHECK_TRUE("HDR-FLIP of a black reference -> NaN", isnan(m), err.msg);

    /* The magma map's ends, as matplotlib's magma (the reference tool's colour map). */
    unsigned char c0[3], c1[3];
    gib_flip_magma(0.0f, c0);
    gib_flip_magma(1.0f, c1);
    CHECK_TRUE("magma(0) = (0,0,4)", c0[0] == 0 && c0[1] == 0 && c0[2] == 4, "dark end");
    CHECK_TRUE("magma(1) = (252,253,191)", c1[0] == 252 && c1[1] == 253 && c1[2] == 191,
               "light end");

    printf("%d failure(s)\n", failures);
    return failures > 100 ? 100 : failures;
}

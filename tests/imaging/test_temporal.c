/* The temporal error (harness/imaging/temporal.h) on constructed sequences with known answers:
 *  - a steady sequence against a steady reference scores 0 (rmse, peak, FLIP);
 *  - one pixel flickering by a (every channel) against a steady reference: peak = a,
 *    rmse = a / sqrt(pixels) (to 1e-9: plain arithmetic);
 *  - a sequence that moves exactly as the reference scores 0 while `frozen` (a sequence standing
 *    still) does not, and a frozen sequence scores `frozen`;
 *  - the reference's noise taken out: the truth against a reference with independent Gaussian
 *    noise sigma per frame scores rmse ~ sqrt(2) sigma and rmse_denoised ~ 0; a known flicker of
 *    RMS f beside that noise comes back as f. Tolerances: with 64x64x3 samples over 7 pairs
 *    (86,016) a mean square has a relative standard error of sqrt(2 / 86016) = 0.5%, so rmse is
 *    held to 5% of sqrt(2) sigma and the recovered f to 5% (ten standard errors and more; a wrong
 *    factor, noise counted once instead of twice, moves them by 30-40%); rmse_denoised of the truth
 *    is the square root of a difference of two nearly equal mean squares, 3 standard errors of
 *    which (0.03 sigma^2) give 0.17 sigma, so it is held below 0.25 sigma (noise counted once:
 *    1 sigma);
 *  - bad input: fewer than 2 frames, sizes that differ, non-finite samples (GIB_ERR_NON_FINITE). */
#include "harness/imaging/temporal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;
#include "tests/common/check.h"

enum { W = 64, H = 64, N = 8 };

static gib_image ref[N], test[N];

static void alloc_all(void)
{
    for (int k = 0; k < N; k++) {
        gib_error err = {0};
        if (gib_image_alloc(&ref[k], W, H, 3, &err) < 0 ||
            gib_image_alloc(&test[k], W, H, 3, &err) < 0) {
            CHECK(0, "%s", err.msg);
            exit(1);
        }
    }
}

/* A smooth pattern that moves with time k. */
static float scene(int x, int y, int c, double k)
{
    return (float)(0.5 + 0.3 * sin(0.2 * x + 0.3 * k + c) * cos(0.15 * y - 0.2 * k));
}

static double gaussian(void)
{
    double u1 = (rand() + 1.0) / (RAND_MAX + 2.0), u2 = (rand() + 1.0) / (RAND_MAX + 2.0);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

/* Fills frame k of img with the scene at time `moving ? k : 0`, plus `noise` sigma, plus
 * `flicker` at one pixel (0, 0) on odd frames. */
static void fill(gib_image *img, int k, int moving, double noise, double flicker)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++) {
                double v = scene(x, y, c, moving ? k : 0) + noise * gaussian();
                if (x == 0 && y == 0 && (k & 1))
                    v += flicker;
                img->px[(y * W + x) * 3 + c] = (float)v;
            }
}

static gib_temporal run(int ref_moving, double ref_noise, int test_moving, double flicker,
                        double noise_rmse, int want_flip)
{
    for (int k = 0; k < N; k++) {
        fill(&ref[k], k, ref_moving, ref_noise, 0);
        fill(&test[k], k, test_moving, 0, flicker);
    }
    gib_temporal t;
    gib_error err = {0};
    CHECK(!(gib_temporal_compute(ref, test, N, noise_rmse, 1.0f, want_flip, &t, &err) < 0),
          "%s", err.msg);
    return t;
}

static void known_answers(void)
{
    gib_temporal t = run(0, 0, 0, 0, 0, 1);
    CHECK(t.rmse == 0 && t.peak == 0 && t.frozen == 0 && t.flip == 0,
          "steady: rmse %g peak %g frozen %g flip %g, want 0", t.rmse, t.peak, t.frozen, t.flip);

    const double a = 0.25;
    t = run(0, 0, 0, a, 0, 1);
    CHECK(fabs(t.peak - a) < 1e-6, "one flickering pixel: peak %.9g, want %g", t.peak, a);
    CHECK(fabs(t.rmse - a / sqrt((double)W * H)) < 1e-7, "one flickering pixel: rmse %.9g, want %.9g",
          t.rmse, a / sqrt((double)W * H));
    CHECK(t.flip > 0, "one flickering pixel: FLIP %g, want > 0", t.flip);
    printf("one pixel flickering by %g: peak %.6g, rmse %.6g, FLIP %.6g\n", a, t.peak, t.rmse,
           t.flip);

    t = run(1, 0, 1, 0, 0, 1);
    CHECK(t.rmse == 0 && t.peak == 0 && t.flip == 0 && t.frozen > 0.01,
          "moving as the reference: rmse %g peak %g flip %g (want 0), frozen %g (want > 0.01)",
          t.rmse, t.peak, t.flip, t.frozen);
    gib_temporal frozen = run(1, 0, 0, 0, 0, 0);
    CHECK(fabs(frozen.rmse - t.frozen) < 1e-9 && isnan(frozen.flip),
          "a frozen sequence scores frozen: %.9g vs %.9g (FLIP %g, not asked: NaN)", frozen.rmse,
          t.frozen, frozen.flip);
}

static void reference_noise(void)
{
    const double sigma = 0.02, f = 0.03;
    srand(7);
    gib_temporal t = run(1, sigma, 1, 0, sigma, 0);
    printf("truth against a reference with noise %.4g: rmse %.5g (sqrt(2) sigma %.5g), denoised "
           "%.5g\n", sigma, t.rmse, sqrt(2.0) * sigma, t.rmse_denoised);
    CHECK(fabs(t.rmse - sqrt(2.0) * sigma) < 0.05 * sqrt(2.0) * sigma &&
              t.rmse_denoised < 0.25 * sigma,
          "truth against a noisy reference: rmse %.5g (want %.5g), denoised %.5g (want ~0)",
          t.rmse, sqrt(2.0) * sigma, t.rmse_denoised);
    /* A flicker of RMS f over every sample: independent Gaussian noise of sigma f / sqrt(2) on
     * each of the technique's frames gives frame differences of RMS f. */
    for (int k = 0; k < N; k++) {
        fill(&ref[k], k, 1, sigma, 0);
        fill(&test[k], k, 1, f / sqrt(2.0), 0);
    }
    gib_error err = {0};
    gib_temporal_compute(ref, test, N, sigma, 1.0f, 0, &t, &err);
    CHECK(fabs(t.rmse_denoised - f) < 0.05 * f, "flicker %.4g beside reference noise %.4g: "
          "denoised %.5g, rmse %.5g", f, sigma, t.rmse_denoised, t.rmse);
    printf("flicker %.4g beside that noise: denoised %.5g\n", f, t.rmse_denoised);
}

static void bad_input(void)
{
    run(0, 0, 0, 0, 0, 0);
    gib_temporal t;
    gib_error err = {0};
    CHECK(gib_temporal_compute(ref, test, 1, 0, 1, 0, &t, &err) < 0 && strstr(err.msg, "1 frame"),
          "one frame refused: '%s'", err.msg);
    gib_image small = {0};
    gib_image_alloc(&small, W / 2, H, 3, &err);
    gib_image keep = test[3];
    test[3] = small;
    CHECK(gib_temporal_compute(ref, test, N, 0, 1, 0, &t, &err) < 0 &&
              strstr(err.msg, "technique frame 3"), "size mismatch named: '%s'", err.msg);
    test[3] = keep;
    gib_image_free(&small);
    ref[5].px[17] = NAN;
    CHECK(gib_temporal_compute(ref, test, N, 0, 1, 0, &t, &err) < 0 &&
              err.code == GIB_ERR_NON_FINITE && strstr(err.msg, "reference frame 5"),
          "NaN named with its code: '%s'", err.msg);
}

int main(void)
{
    alloc_all();
    known_answers();
    reference_noise();
    bad_input();
    for (int k = 0; k < N; k++) {
        gib_image_free(&ref[k]);
        gib_image_free(&test[k]);
    }
    printf("%s: temporal error (%d failure(s))\n", failures ? "FAIL" : "PASS", failures);
    return failures ? 1 : 0;
}

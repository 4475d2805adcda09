/* What makes a number trustworthy, checked on constructed cases with known answers:
 * - black_rmse is sqrt(mean ref^2) over the samples the RMSE uses; mean_ratio is the test's mean
 *   over the reference's (0 for black, 0.5 for the reference halved);
 * - gib_rmse_interval removes a noisy reference's bias from the RMSE and its 95% interval covers
 *   the true error: a truth G, a reference R = G + noise estimated from 8 batches (as the path
 *   tracer does), a technique T = G + d with a known true RMSE; over 300 trials the de-noised
 *   error's mean is within 1% of the truth and the interval covers it in 90-99% of them (a
 *   binomial at 0.95 over 300 trials has a standard deviation of 1.3%: the band is over 3 sigma);
 * - gib_stats_quantile interpolates as numpy's default (type 7);
 * - the timers never count the cold first frame, whatever `record` says (an OpenGL context);
 * - gib_ref_spp_to_rank grows a reference by powers of two until its noise is at most 0.18 of the
 *   row's de-noised error, capped at the growth allowed. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/app/refrank.h"
#include "harness/gl/timers.h"
#include "harness/imaging/metrics.h"
#include "tests/common/check.h"
#include "tests/common/gl_fixture.h"

#include <glad/gl.h>

static int failures;

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double uniform(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return ((rng_state >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

static double gauss(void)
{
    return sqrt(-2.0 * log(uniform())) * cos(6.283185307179586 * uniform());
}

static void test_black(void)
{
    gib_image ref, test;
    gib_error err;
    gib_image_alloc(&ref, 4, 2, 3, &err);
    gib_image_alloc(&test, 4, 2, 3, &err);
    double sum = 0;
    for (int i = 0; i < 24; i++) {
        ref.px[i] = (float)(0.1 * (i % 5));
        test.px[i] = 0.0f;
        sum += (double)ref.px[i] * ref.px[i];
    }
    gib_metrics m;
    gib_metrics_compute(&ref, &test, 1.0f, &m, &err);
    CHECK(fabs(m.black_rmse - sqrt(sum / 24)) < 1e-9, "black_rmse %.9g, want %.9g", m.black_rmse,
          sqrt(sum / 24));
    CHECK(fabs(m.rmse - m.black_rmse) < 1e-9, "a black test image scores black_rmse (%.9g vs %.9g)",
          m.rmse, m.black_rmse);
    CHECK(m.mean_ratio == 0.0, "a black test image's mean_ratio %.9g, want 0", m.mean_ratio);
    for (int i = 0; i < 24; i++)
        test.px[i] = 0.5f * ref.px[i];
    gib_metrics_compute(&ref, &test, 1.0f, &m, &err);
    CHECK(fabs(m.mean_ratio - 0.5) < 1e-6, "the reference halved: mean_ratio %.9g, want 0.5",
          m.mean_ratio);
    gib_image_free(&ref);
    gib_image_free(&test);
}

/* One trial: the de-noised error and whether the interval covers the true RMSE. */
static void trial(int pixels, double sigma, double bias, double *denoised, int *covered)
{
    double sq = 0, var = 0;
    for (int i = 0; i < pixels; i++) {
        double b[8], mean = 0, s = 0;
        for (int k = 0; k < 8; k++) /* each batch: 8x the variance of their mean */
            mean += (b[k] = sigma * sqrt(8.0) * gauss()) / 8;
        for (int k = 0; k < 8; k++)
            s += (b[k] - mean) * (b[k] - mean);
        var += s / (8.0 * 7.0); /* the variance of the mean from the batches' spread */
        double d = (bias * (i % 2 ? 1 : -1)) - mean; /* T - R with T - G = +-bias, R - G = mean */
        sq += d * d;
    }
    gib_rmse_bounds bnd;
    gib_rmse_interval(sqrt(sq / pixels), sqrt(var / pixels), pixels, &bnd);
    *denoised = bnd.denoised;
    *covered = bnd.lo <= bias && bias <= bnd.hi;
}

static void test_interval(const char *what, int pixels, double sigma, double bias)
{
    const int trials = 300;
    double sum = 0;
    int covered = 0;
    for (int t = 0; t < trials; t++) {
        double d;
        int c;
        trial(pixels, sigma, bias, &d, &c);
        sum += d;
        covered += c;
    }
    double mean = sum / trials, rate = (double)covered / trials;
    printf("%s: true RMSE %.4g, noise %.4g: mean de-noised %.5g, coverage %.3f\n", what, bias,
           sigma, mean, rate);
    if (bias > 0)
        CHECK(fabs(mean - bias) <= 0.01 * bias, "%s: mean de-noised error %.6g, true %.6g (1%%)",
              what, mean, bias);
    char label[160];
    snprintf(label, sizeof label, "%s: the 95%% interval's coverage of the truth, %d trials", what,
             trials);
    CHECK_AT_LEAST(label, rate, 0.90,
                   "a binomial at 0.95 over 300 trials: sd 1.3%, the band over 3 sigma");
    CHECK_AT_MOST(label, rate, 0.99 + (bias == 0),
                  "a binomial at 0.95 over 300 trials: sd 1.3%, the band over 3 sigma");
}

static void test_exact_reference(void)
{
    gib_rmse_bounds b;
    gib_rmse_interval(0.25, 0.0, 100, &b);
    CHECK(b.lo == 0.25 && b.denoised == 0.25 && b.hi == 0.25,
          "a noiseless reference leaves the RMSE as it is: %g [%g, %g]", b.denoised, b.lo, b.hi);
}

static void test_quantile(void)
{
    const double v[] = {7, 1, 3, 5}; /* sorted 1 3 5 7: numpy quantile 0.25 = 2.5, 0.75 = 5.5 */
    CHECK(gib_stats_quantile(v, 4, 0.25) == 2.5, "q25 %g", gib_stats_quantile(v, 4, 0.25));
    CHECK(gib_stats_quantile(v, 4, 0.75) == 5.5, "q75 %g", gib_stats_quantile(v, 4, 0.75));
    CHECK(gib_stats_quantile(v, 4, 0.5) == 4.0, "median %g", gib_stats_quantile(v, 4, 0.5));
    CHECK(gib_stats_quantile(v, 1, 0.75) == 7.0, "one value %g", gib_stats_quantile(v, 1, 0.75));
}

/* Four frames all asking to be recorded, each with one pass: the first is the cold one, kept
 * apart (first_ms), and the statistics are over the other three. */
static void test_cold_frame(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "cornell") < 0) {
        failures++;
        return;
    }
    gib_timers t;
    gib_timers_init(&t);
    for (int f = 0; f < 4; f++) {
        gib_timers_frame_begin(&t, 1);
        gib_timer_begin(&t, "clear");
        glClear(GL_COLOR_BUFFER_BIT);
        gib_timer_end(&t);
        gib_timers_frame_end(&t);
    }
    gib_pass_stats st[2], gpu, cpu;
    int n = gib_timers_stats(&t, st, 2, &gpu, &cpu);
    CHECK(t.frames == 3, "4 frames begun with record = 1: %d timed (the cold one never)", t.frames);
    CHECK(n == 1 && !strcmp(st[0].name, "clear"), "one pass 'clear' (%d)", n);
    CHECK(cpu.first_ms > 0 && cpu.iqr_ms >= 0 && cpu.min_ms <= cpu.median_ms &&
          cpu.median_ms <= cpu.max_ms, "cold frame %.3f ms apart; median %.3f in [%.3f, %.3f]",
          cpu.first_ms, cpu.median_ms, cpu.min_ms, cpu.max_ms);
    gib_timers_destroy(&t);
    gib_fixture_close(&fx);
}

static void test_spp_to_rank(void)
{
    /* noise 0.01 against an RMSE of 0.1: already a tenth, kept */
    CHECK(gib_ref_spp_to_rank(64, 0.01, 0.1, 10000, 16) == 64, "quiet enough: kept");
    /* noise 0.01, RMSE 0.03 (true ~0.0283): target 0.18 x 0.0283 = 0.0051, (0.01/0.0051)^2 = 3.9:
     * 4x */
    int s = gib_ref_spp_to_rank(64, 0.01, 0.03, 10000, 16);
    CHECK(s == 256, "noise a third of the error: 256 spp, got %d", s);
    CHECK(gib_ref_spp_to_rank(64, 0.01, 0.011, 10000, 16) == 1024, "capped at 16x: %d",
          gib_ref_spp_to_rank(64, 0.01, 0.011, 10000, 16));
    CHECK(gib_ref_spp_to_rank(64, 0.01, 0.011, 10000, 1) == 64, "growth 1: never grows");
}

int main(void)
{
    test_black();
    test_exact_reference();
    test_interval("biased technique, noisy reference", 2000, 0.02, 0.01);
    test_interval("noise as large as the error", 2000, 0.01, 0.01);
    test_interval("exact technique", 2000, 0.01, 0.0);
    test_quantile();
    test_cold_frame();
    test_spp_to_rank();
    printf("%s: %d failures\n", failures ? "FAIL" : "PASS", failures);
    return failures ? 1 : 0;
}

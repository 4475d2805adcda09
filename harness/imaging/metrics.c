/* gibench — RMSE, relative RMSE, PSNR and SSIM as ARCHITECTURE.md "Metrics" defines them.
 *
 * SSIM replicates scikit-image 0.19's structural_similarity(gaussian_weights=True, sigma=1.5,
 * use_sample_covariance=False, data_range=1): scipy.ndimage.gaussian_filter with truncate 3.5
 * (radius int(3.5 * 1.5 + 0.5) = 5, 11 normalised taps), then the mean of the SSIM map cropped by
 * 5 pixels on every side. Only positions whose window lies wholly inside the image survive that
 * crop, so the filter's boundary mode ('reflect') never influences the result and we evaluate the
 * interior positions alone.
 *
 * The SSIM map's rows and the channels' pixels are spread over the scoring threads (parallel.h);
 * the map is summed row by row in order and the error sums in a single pass in pixel order, as one
 * thread sums them, so every number is the same whatever the thread count. */
#include "metrics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "parallel.h"

#define SSIM_RADIUS 5
#define SSIM_TAPS (2 * SSIM_RADIUS + 1)
#define SSIM_SIGMA 1.5
#define SSIM_K1 0.01
#define SSIM_K2 0.03

/* scipy's _gaussian_kernel1d: exp(-0.5 x^2 / sigma^2), normalised to sum 1. */
static void ssim_kernel(double k[SSIM_TAPS])
{
    double sum = 0.0;
    for (int i = 0; i < SSIM_TAPS; ++i) {
        double x = (double)(i - SSIM_RADIUS);
        k[i] = exp(-0.5 * x * x / (SSIM_SIGMA * SSIM_SIGMA));
        sum += k[i];
    }
    for (int i = 0; i < SSIM_TAPS; ++i)
        k[i] /= sum;
}

/* One output row of the SSIM map: its sum over the valid columns. col: width * 5 doubles of
 * scratch for the vertical pass (five moments interleaved so the horizontal pass reads them
 * contiguously). */
static double ssim_row(const float *a, const float *b, int width, int oy, const double k[SSIM_TAPS],
                       double *col)
{
    const int ow = width - 2 * SSIM_RADIUS;
    const double c1 = (SSIM_K1 * 1.0) * (SSIM_K1 * 1.0);
    const double c2 = (SSIM_K2 * 1.0) * (SSIM_K2 * 1.0);
    for (int x = 0; x < width; ++x) {
        double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
        for (int t = 0; t < SSIM_TAPS; ++t) {
            size_t i = (size_t)(oy + t) * (size_t)width + (size_t)x;
            double va = a[i], vb = b[i], w = k[t];
            sa += w * va;
            sb += w * vb;
            saa += w * va * va;
            sbb += w * vb * vb;
            sab += w * va * vb;
        }
        double *c = &col[(size_t)x * 5];
        c[0] = sa;
        c[1] = sb;
        c[2] = saa;
        c[3] = sbb;
        c[4] = sab;
    }
    double row_sum = 0.0;
    for (int ox = 0; ox < ow; ++ox) {
        double m[5] = {0, 0, 0, 0, 0};
        const double *c = &col[(size_t)ox * 5];
        for (int t = 0; t < SSIM_TAPS; ++t, c += 5) {
            double w = k[t];
            m[0] += w * c[0];
            m[1] += w * c[1];
            m[2] += w * c[2];
            m[3] += w * c[3];
            m[4] += w * c[4];
        }
        double ux = m[0], uy = m[1];
        double vx = m[2] - ux * ux, vy = m[3] - uy * uy, vxy = m[4] - ux * uy;
        double num = (2.0 * ux * uy + c1) * (2.0 * vxy + c2);
        double den = (ux * ux + uy * uy + c1) * (vx + vy + c2);
        row_sum += num / den;
    }
    return row_sum;
}

/* SSIM's rows in bands, one band an item; each row's sum kept apart for the ordered reduction. */
#define SSIM_BAND 8

typedef struct ssim_job {
    const float *a, *b;
    int width, rows;
    double k[SSIM_TAPS];
    double *row_sum; /* per output row */
    int failed;      /* a band's scratch could not be allocated */
} ssim_job;

static void ssim_band(void *ctx, int item)
{
    ssim_job *j = ctx;
    double *col = malloc((size_t)j->width * 5 * sizeof(double));
    if (!col) {
        j->failed = 1;
        return;
    }
    const int end = (item + 1) * SSIM_BAND < j->rows ? (item + 1) * SSIM_BAND : j->rows;
    for (int oy = item * SSIM_BAND; oy < end; ++oy)
        j->row_sum[oy] = ssim_row(j->a, j->b, j->width, oy, j->k, col);
    free(col);
}

double gib_ssim_gray_on(gib_team *team, const float *a, const float *b, int width, int height)
{
    /* No window fits: scikit-image refuses such images, and there is no honest number to give. */
    if (!a || !b || width < SSIM_TAPS || height < SSIM_TAPS)
        return NAN;
    const int oh = height - 2 * SSIM_RADIUS; /* valid output rows */
    const int ow = width - 2 * SSIM_RADIUS;  /* valid output columns */
    ssim_job j = {.a = a, .b = b, .width = width, .rows = oh};
    ssim_kernel(j.k);
    j.row_sum = malloc((size_t)oh * sizeof(double));
    if (!j.row_sum)
        return NAN;
    gib_team_run(team, (oh + SSIM_BAND - 1) / SSIM_BAND, ssim_band, &j);
    /* Row by row in order, as a single thread sums them: the same total whatever the threads. */
    double total = 0.0;
    for (int oy = 0; oy < oh; ++oy)
        total += j.row_sum[oy];
    free(j.row_sum);
    return j.failed ? NAN : total / ((double)ow * (double)oh);
}

double gib_ssim_gray(const float *a, const float *b, int width, int height)
{
    gib_team *team = gib_team_start(0);
    double s = gib_ssim_gray_on(team, a, b, width, height);
    gib_team_stop(team);
    return s;
}

/* Pixels [first, end) of img's SSIM channel. */
static void ssim_channel_span(const gib_image *img, float exposure, float *out, size_t first,
                              size_t end)
{
    const int c = img->channels;
    for (size_t i = first; i < end; ++i) {
        const float *p = &img->px[i * (size_t)c];
        double y = c >= 3 ? 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2] : (double)p[0];
        /* gib_srgb_encode clamps to [0,1] (NaN to 0), so the data range is exactly 1. */
        out[i] = gib_srgb_encode((float)((double)exposure * y));
    }
}

void gib_ssim_channel(const gib_image *img, float exposure, float *out)
{
    ssim_channel_span(img, exposure, out, 0, (size_t)img->width * (size_t)img->height);
}

/* The finite pairs' sums (a single pass in pixel order: the sums of a single thread). */
static void error_sums(const gib_image *ref, const gib_image *test, gib_metrics *out)
{
    const size_t n = (size_t)ref->width * (size_t)ref->height;
    const int rc = ref->channels, tc = test->channels;
    double sum_sq = 0.0, sum_ref = 0.0, sum_test = 0.0, sum_ref_sq = 0.0, peak = -INFINITY;
    size_t npairs = 0;
    long nonfinite = 0;
    for (size_t i = 0; i < n; ++i) {
        for (int k = 0; k < 3; ++k) {
            double r = ref->px[i * rc + k], t = test->px[i * tc + k];
            int rf = isfinite(r), tf = isfinite(t);
            nonfinite += !rf + !tf;
            /* A broken sample is reported through the count, never averaged into the error. */
            if (!rf || !tf)
                continue;
            double d = t - r;
            sum_sq += d * d;
            sum_ref += r;
            sum_test += t;
            sum_ref_sq += r * r;
            if (r > peak)
                peak = r;
            ++npairs;
        }
    }
    out->nonfinite = nonfinite;
    if (npairs == 0) {
        out->rmse = out->rel_rmse = out->psnr = out->ref_mean = out->black_rmse = NAN;
        out->mean_ratio = NAN;
        return;
    }
    out->rmse = sqrt(sum_sq / (double)npairs);
    out->black_rmse = sqrt(sum_ref_sq / (double)npairs);
    out->ref_mean = sum_ref / (double)npairs;
    out->mean_ratio = sum_ref > 0.0 ? sum_test / sum_ref : sum_test == 0.0 ? 1.0 : INFINITY;
    if (out->ref_mean > 0.0)
        out->rel_rmse = out->rmse / out->ref_mean;
    else
        out->rel_rmse = out->rmse == 0.0 ? 0.0 : INFINITY;
    /* Identical images give +inf, the honest answer (CSV writers print "inf"). */
    out->psnr = out->rmse == 0.0 ? INFINITY : 20.0 * log10(peak / out->rmse);
}

int gib_metrics_check(const gib_image *ref, const gib_image *test, gib_error *err)
{
    if (!ref || !test || !ref->px || !test->px)
        return gib_fail(err, "metrics: missing image");
    if (ref->width != test->width || ref->height != test->height)
        return gib_fail(err, "metrics: size mismatch (reference %dx%d, test %dx%d)", ref->width,
                        ref->height, test->width, test->height);
    if (ref->channels < 3 || test->channels < 3)
        return gib_fail(err, "metrics: need RGB images (reference has %d channels, test %d)",
                        ref->channels, test->channels);
    return 0;
}

int gib_metrics_errors(const gib_image *ref, const gib_image *test, gib_metrics *out,
                       gib_error *err)
{
    memset(out, 0, sizeof *out);
    if (gib_metrics_check(ref, test, err) < 0)
        return -1;
    error_sums(ref, test, out);
    out->ssim = NAN;
    return 0;
}

/* The first step of gib_metrics_compute: item 0 the error sums, the others bands of rows of both
 * SSIM channels, so the sums' single pass runs beside the conversion. */
#define CHANNEL_BAND 16

typedef struct channels_job {
    const gib_image *ref, *test;
    float exposure;
    float *ga, *gb;
    gib_metrics *out;
} channels_job;

static void channels_item(void *ctx, int item)
{
    channels_job *j = ctx;
    if (item == 0) {
        error_sums(j->ref, j->test, j->out);
        return;
    }
    const size_t w = (size_t)j->ref->width, h = (size_t)j->ref->height;
    const size_t y0 = (size_t)(item - 1) * CHANNEL_BAND;
    const size_t y1 = y0 + CHANNEL_BAND < h ? y0 + CHANNEL_BAND : h;
    ssim_channel_span(j->ref, j->exposure, j->ga, y0 * w, y1 * w);
    ssim_channel_span(j->test, j->exposure, j->gb, y0 * w, y1 * w);
}

int gib_metrics_compute_on(gib_team *team, const gib_image *ref, const gib_image *test,
                           float exposure, gib_metrics *out, gib_error *err)
{
    memset(out, 0, sizeof *out);
    if (gib_metrics_check(ref, test, err) < 0)
        return -1;
    const size_t n = (size_t)ref->width * (size_t)ref->height;
    float *ga = gib_calloc(n, sizeof(float), err);
    float *gb = gib_calloc(n, sizeof(float), err);
    if (!ga || !gb) {
        free(ga);
        free(gb);
        return gib_error_prefix(err, "metrics: SSIM channels");
    }
    channels_job cj = {.ref = ref, .test = test, .exposure = exposure, .ga = ga, .gb = gb,
                       .out = out};
    gib_team_run(team, 1 + (ref->height + CHANNEL_BAND - 1) / CHANNEL_BAND, channels_item, &cj);
    out->ssim = gib_ssim_gray_on(team, ga, gb, ref->width, ref->height);
    free(ga);
    free(gb);
    return 0;
}

int gib_metrics_compute(const gib_image *ref, const gib_image *test, float exposure,
                        gib_metrics *out, gib_error *err)
{
    gib_team *team = gib_team_start(0);
    int rc = gib_metrics_compute_on(team, ref, test, exposure, out, err);
    gib_team_stop(team);
    return rc;
}

void gib_rmse_interval(double rmse, double noise_rmse, long pixels, gib_rmse_bounds *out)
{
    const double mse = rmse * rmse, noise = noise_rmse * noise_rmse;
    const double d = mse - noise; /* unbiased: E[mse] = true mse + noise */
    const double n = pixels > 0 ? (double)pixels : 1.0;
    const double dpos = d > 0.0 ? d : 0.0;
    /* var(mse) = (4 D S + 2 S^2) / N for Gaussian noise of variance S over N pixels, plus the
     * variance of S itself, estimated from 8 batches (7 degrees of freedom): 2 S^2 / (7 N). */
    const double se = sqrt((4.0 * dpos * noise + 2.0 * noise * noise * (1.0 + 1.0 / 7.0)) / n);
    out->denoised = sqrt(dpos);
    out->lo = d - 1.96 * se > 0.0 ? sqrt(d - 1.96 * se) : 0.0;
    out->hi = d + 1.96 * se > 0.0 ? sqrt(d + 1.96 * se) : 0.0;
}

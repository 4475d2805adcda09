/* gibench — RMSE, relative RMSE, PSNR and SSIM as ARCHITECTURE.md "Metrics" defines them.
 *
 * SSIM replicates scikit-image 0.19's structural_similarity(gaussian_weights=True, sigma=1.5,
 * use_sample_covariance=False, data_range=1): scipy.ndimage.gaussian_filter with truncate 3.5
 * (radius int(3.5 * 1.5 + 0.5) = 5, 11 normalised taps), then the mean of the SSIM map cropped by
 * 5 pixels on every side. Only positions whose window lies wholly inside the image survive that
 * crop, so the filter's boundary mode ('reflect') never influences the result and we evaluate the
 * interior positions alone. */
#include "metrics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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

double gib_ssim_gray(const float *a, const float *b, int width, int height)
{
    /* No window fits: scikit-image refuses such images, and there is no honest number to give. */
    if (!a || !b || width < SSIM_TAPS || height < SSIM_TAPS)
        return NAN;
    double k[SSIM_TAPS];
    ssim_kernel(k);

    const int oh = height - 2 * SSIM_RADIUS; /* valid output rows */
    const int ow = width - 2 * SSIM_RADIUS;  /* valid output columns */
    /* Vertical pass for one output row over all columns, five moments interleaved so the
     * horizontal pass reads them contiguously. */
    double *col = malloc((size_t)width * 5 * sizeof(double));
    if (!col)
        return NAN;

    const double c1 = (SSIM_K1 * 1.0) * (SSIM_K1 * 1.0);
    const double c2 = (SSIM_K2 * 1.0) * (SSIM_K2 * 1.0);
    double total = 0.0;
    for (int oy = 0; oy < oh; ++oy) {
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
        total += row_sum;
    }
    free(col);
    return total / ((double)ow * (double)oh);
}

void gib_ssim_channel(const gib_image *img, float exposure, float *out)
{
    const int c = img->channels;
    const size_t n = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; i < n; ++i) {
        const float *p = &img->px[i * (size_t)c];
        double y = c >= 3 ? 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2] : (double)p[0];
        /* gib_srgb_encode clamps to [0,1] (NaN to 0), so the data range is exactly 1. */
        out[i] = gib_srgb_encode((float)((double)exposure * y));
    }
}

int gib_metrics_compute(const gib_image *ref, const gib_image *test, float exposure,
                        gib_metrics *out, gib_error *err)
{
    memset(out, 0, sizeof *out);
    if (!ref || !test || !ref->px || !test->px)
        return gib_fail(err, "metrics: missing image");
    if (ref->width != test->width || ref->height != test->height)
        return gib_fail(err, "metrics: size mismatch (reference %dx%d, test %dx%d)", ref->width,
                        ref->height, test->width, test->height);
    if (ref->channels < 3 || test->channels < 3)
        return gib_fail(err, "metrics: need RGB images (reference has %d channels, test %d)",
                        ref->channels, test->channels);

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
    } else {
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

    float *ga = gib_calloc(n, sizeof(float), err);
    float *gb = gib_calloc(n, sizeof(float), err);
    if (!ga || !gb) {
        free(ga);
        free(gb);
        return gib_error_prefix(err, "metrics: SSIM channels");
    }
    gib_ssim_channel(ref, exposure, ga);
    gib_ssim_channel(test, exposure, gb);
    out->ssim = gib_ssim_gray(ga, gb, ref->width, ref->height);
    free(ga);
    free(gb);
    return 0;
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

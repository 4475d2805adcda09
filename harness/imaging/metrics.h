/* gibench — image metrics, as ARCHITECTURE.md "Metrics" defines them.
 *
 * RMSE over all linear RGB samples; relative RMSE = RMSE / mean of the reference's samples;
 * PSNR = 20 log10(peak / RMSE) with peak = max reference sample (linear data have no fixed range);
 * SSIM (Wang et al. 2004) on one channel srgb_encode(clamp(exposure * Y, 0, 1)),
 * Y = 0.2126 R + 0.7152 G + 0.0722 B, 11x11 Gaussian window (sigma 1.5, truncated at 3.5 sigma
 * as scikit-image does, i.e. radius 5), K1 = 0.01, K2 = 0.03, data range 1, population
 * covariance, mean over the valid (border-cropped) window positions — equal to scikit-image's
 * structural_similarity(a, b, gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
 * data_range=1) to 1e-4. */
#ifndef GIB_METRICS_H
#define GIB_METRICS_H

#include "image.h"
#include "parallel.h"

typedef struct gib_metrics {
    double rmse, rel_rmse, psnr, ssim;
    double ref_mean;
    /* The image's energy against the reference's: mean of the test's samples over the reference's,
     * over the same samples (1 = the reference's energy; 0 for black; +inf when only the
     * reference is black). */
    double mean_ratio;
    double black_rmse; /* what an all-black image scores: sqrt(mean of ref^2) over the same samples */
    /* LDR-FLIP and HDR-FLIP means (harness/imaging/flip.h); gib_metrics_compute leaves them 0,
     * gib_score_pair (score.h) fills them. */
    double flip, hdrflip;
    long nonfinite; /* NaN/Inf samples in the test image (the reference's are counted too) */
} gib_metrics;

/* Both images must have the same size and >= 3 channels (only RGB is compared). When any sample
 * is non-finite, nonfinite > 0 and the other fields are computed over the finite pairs only
 * (a row with nonfinite > 0 is never `ok`). */
int gib_metrics_compute(const gib_image *ref, const gib_image *test, float exposure,
                        gib_metrics *out, gib_error *err);
/* The same on a team already started (NULL: the caller's thread alone); the numbers do not depend
 * on the team's size. */
int gib_metrics_compute_on(gib_team *team, const gib_image *ref, const gib_image *test,
                           float exposure, gib_metrics *out, gib_error *err);
/* 0 when gib_metrics_compute takes the pair, else -1 with its message. */
int gib_metrics_check(const gib_image *ref, const gib_image *test, gib_error *err);

/* gib_metrics_compute without SSIM (left NaN): the error and its scales alone, one pass over the
 * samples, for a caller that needs no more (ranking a reference by its noise against the error). */
int gib_metrics_errors(const gib_image *ref, const gib_image *test, gib_metrics *out,
                       gib_error *err);

/* SSIM of two single-channel images already in [0,1] (w*h floats each), as above. NaN when
 * either side is under 11 pixels (no valid window position; scikit-image refuses such images). */
double gib_ssim_gray(const float *a, const float *b, int width, int height);
double gib_ssim_gray_on(gib_team *team, const float *a, const float *b, int width, int height);

/* The SSIM channel of a linear RGB image: srgb_encode(clamp(exposure * Y, 0, 1)). out: w*h floats. */
void gib_ssim_channel(const gib_image *img, float exposure, float *out);

/* The error against the truth a noisy reference estimates, with a 95% interval. A reference with
 * per-pixel noise n (mean variance S = noise_rmse^2) adds S to the expected squared error:
 * E[rmse^2] = D + S, D the technique's true mean squared error. So D is estimated by rmse^2 - S;
 * its standard error, for Gaussian noise spread evenly over `pixels` independent pixels, is
 * sqrt((4 D S + 2 S^2 + 2 S^2 / 7) / pixels) (the last term: S itself is estimated from 8
 * batches, 7 degrees of freedom). Channels of a pixel share their paths, so pixels, not samples,
 * are the independent units (conservative). Noise concentrated in few pixels widens the true
 * interval beyond this one. denoised = sqrt(max(D, 0)); lo and hi the roots of D -/+ 1.96 se,
 * clamped at 0. A deterministic reference (noise 0) gives lo = denoised = hi = rmse. */
typedef struct gib_rmse_bounds {
    double denoised, lo, hi;
} gib_rmse_bounds;
void gib_rmse_interval(double rmse, double noise_rmse, long pixels, gib_rmse_bounds *out);

#endif

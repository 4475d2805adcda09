/* gibench — temporal stability of an image sequence against its reference sequence
 * (ARCHITECTURE.md, "Metrics": "Temporal error").
 *
 * A per-frame error cannot tell a technique that flickers from one that is steady: both may sit
 * at the same distance from each frame's reference. What moves between frames is measured on the
 * frame-to-frame differences instead: for frames 0..n-1 of the technique (T) and of the reference
 * (R), dT_k = T_{k+1} - T_k and dR_k = R_{k+1} - R_k, and
 *
 *   rmse  = sqrt(mean over k, pixels and RGB of (dT_k - dR_k)^2)      (0: changes as the reference)
 *   peak  = max over pixels of sqrt(mean over k and RGB of (dT_k - dR_k)^2)
 *   frozen = sqrt(mean of dR_k^2): what a sequence that never changes scores (the temporal analogue
 *            of the black image: a technique above it changes more wrongly than standing still)
 *
 * A steady sequence against a steady reference scores 0; a single pixel flickering between v and
 * v + a (every channel) scores peak = a and rmse = a / sqrt(pixels). The references are Monte Carlo
 * estimates with independent noise per frame, so dR_k carries twice a frame's noise variance: with
 * ref_noise_rmse the frames' noise RMSE (gib_reference's estimate), the expected rmse^2 is the true
 * one plus 2 noise^2, and rmse_denoised = sqrt(max(rmse^2 - 2 noise^2, 0)) (as gib_rmse_interval
 * does for one frame).
 *
 * A perceptual version: flip = the mean over k of |FLIP(T_k, T_{k+1}) - FLIP(R_k, R_{k+1})|, the
 * LDR-FLIP (harness/imaging/flip.h) of consecutive frames at the scene's exposure: how much more (or
 * less) visible the change between two frames is than the reference's. FLIP is an image metric; its
 * authors point to video metrics for sequences (ColorVideoVDP, FovVideoVDP), which need PyTorch and
 * are not packaged in Debian, so this simpler pairwise reading stands in for them. */
#ifndef GIB_TEMPORAL_H
#define GIB_TEMPORAL_H

#include "image.h"

typedef struct gib_temporal {
    double rmse, rmse_denoised, peak, frozen;
    double flip; /* NaN where not computed (want_flip 0) */
    int pairs;   /* frame pairs: frames - 1 */
} gib_temporal;

/* frames >= 2 images in each sequence, all of one size with >= 3 channels (RGB compared).
 * Non-finite samples are an error naming the frame. want_flip: also the FLIP version (costs one
 * LDR-FLIP per frame pair and sequence). */
int gib_temporal_compute(const gib_image *ref, const gib_image *test, int frames,
                         double ref_noise_rmse, float exposure, int want_flip, gib_temporal *out,
                         gib_error *err);

#endif

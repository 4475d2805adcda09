/* gibench — FLIP image difference (Andersson et al., "FLIP: A Difference Evaluator for Alternating
 * Images", HPG 2020) and HDR-FLIP (Andersson et al., "Visualizing Errors in Rendered High Dynamic
 * Range Images", Eurographics 2021 short paper), following the equations of the papers and the
 * separable filtering of NVIDIA's reference implementation (github.com/NVlabs/flip, FLIP.h and
 * misc/separatedConvolutions.pdf), so that means agree with that implementation.
 *
 * Inputs are linear RGB, 3 floats per pixel, row 0 on top. The per-pixel error is in [0,1]; the
 * mean is the plain mean over all pixels, as the reference tool prints it. */
#ifndef GIB_FLIP_H
#define GIB_FLIP_H

#include "harness/base/error.h"
#include "harness/imaging/image.h"
#include "harness/imaging/parallel.h"

/* Pixels per degree of the reference implementation's default viewing condition: a 0.7 m wide,
 * 3840-pixel monitor seen from 0.7 m: 0.7 * 3840 / 0.7 * pi / 180 = 67.02 ppd. */
float gib_flip_default_ppd(void);

/* LDR-FLIP of two linear RGB images (values are clamped to [0,1] first, as the reference does).
 * map (w*h floats) receives the per-pixel error when non-NULL. Returns the mean error, or NaN when
 * a sample is non-finite or memory runs out (*err says which). */
double gib_flip_ldr(const float *ref, const float *test, int w, int h, float ppd, float *map,
                    gib_error *err);

/* HDR-FLIP with the ACES tone mapper: LDR-FLIP of the exposed, tone-mapped, clamped pair at
 * exposures start..stop (HDR-FLIP paper Sec. 3; count max(2, ceil(stop - start))), per-pixel
 * maximum over exposures. The exposure range comes from the reference (paper Sec. 3.2):
 * start = log2(x_max / Y_max), stop = log2(x_max / Y_median), x_max solving tonemap(x) = 0.85.
 * The range is stored in *start and *stop when they are non-NULL. Returns the mean, or NaN with
 * *err set when the reference is black (no exposure range), a sample is non-finite, or memory
 * runs out. */
double gib_flip_hdr(const float *ref, const float *test, int w, int h, float ppd, float *map,
                    float *start, float *stop, gib_error *err);

/* What a row reports of two images (>= 3 channels each, RGB compared): LDR-FLIP of the images the
 * PNG previews show, clamp(exposure * rgb, 0, 1) per channel (NaN to 0), into *ldr, and HDR-FLIP
 * of the linear radiance into *hdr, both at gib_flip_default_ppd(), on a team already started
 * (NULL: the caller's thread). ldr_map (w*h floats) gets the LDR-FLIP map when non-NULL. A mean is
 * NaN where it is undefined: sizes that differ (both), a non-finite sample or a black reference
 * (HDR-FLIP). Returns -1 (err set) only when out of memory. */
int gib_flip_pair_on(gib_team *team, const gib_image *ref, const gib_image *test, float exposure,
                     float *ldr_map, double *ldr, double *hdr, gib_error *err);

/* The magma colour map the reference tool paints error maps with (matplotlib's magma, sRGB), at
 * t in [0,1]. */
void gib_flip_magma(float t, unsigned char rgb[3]);

/* Writes a FLIP error map (w*h floats in [0,1]) as a magma-coloured 8-bit PNG. */
int gib_flip_write_png(const char *path, const float *map, int w, int h, gib_error *err);

#endif

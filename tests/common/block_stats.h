/* gibench tests — image statistics shared by the tests: an image's mean, and errors over blocks
 * for the tests that hold a technique to a noisy reference by its block means (block averages
 * cancel most of the reference's noise). */
#ifndef GIB_TEST_BLOCK_STATS_H
#define GIB_TEST_BLOCK_STATS_H

#include "harness/imaging/image.h"

/* The mean of an image's first three channels over every pixel. */
double gib_rgb_mean(const gib_image *im);

/* Over the block x block means of channel c of two w x h RGB images (3 floats a pixel): the
 * RMSE of img's block means against ref's relative to ref's mean (block_rel) and the ratio of the
 * two images' means (mean_ratio). w and h are multiples of block. */
void gib_block_error(const float *ref, const float *img, int w, int h, int block, int c,
                     double *block_rel, double *mean_ratio);

#endif

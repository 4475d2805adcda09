/* gibench tests — image statistics over blocks (block_stats.h). */
#include "tests/common/block_stats.h"

#include <math.h>

void gib_block_error(const float *ref, const float *img, int w, int h, int block, int c,
                     double *block_rel, double *mean_ratio)
{
    double se = 0, mref = 0, mimg = 0;
    int nb = 0;
    for (int by = 0; by < h; by += block)
        for (int bx = 0; bx < w; bx += block) {
            double a = 0, b = 0;
            for (int y = by; y < by + block; y++)
                for (int x = bx; x < bx + block; x++) {
                    a += ref[(y * w + x) * 3 + c];
                    b += img[(y * w + x) * 3 + c];
                }
            a /= block * block;
            b /= block * block;
            se += (b - a) * (b - a);
            mref += a;
            mimg += b;
            nb++;
        }
    mref /= nb;
    mimg /= nb;
    *block_rel = sqrt(se / nb) / mref;
    *mean_ratio = mimg / mref;
}

double gib_rgb_mean(const gib_image *im)
{
    double s = 0;
    long n = (long)im->width * im->height;
    for (long i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            s += im->px[i * im->channels + c];
    return n ? s / (3.0 * (double)n) : 0;
}

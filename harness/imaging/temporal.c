#include "temporal.h"

#include <math.h>
#include <stdlib.h>

#include "flip.h"

static int check_sequences(const gib_image *ref, const gib_image *test, int frames,
                           gib_error *err)
{
    if (frames < 2)
        return gib_fail(err, "temporal error: %d frame(s), at least 2 needed", frames);
    const int w = ref[0].width, h = ref[0].height;
    for (int k = 0; k < frames; k++) {
        const gib_image *pair[2] = {&ref[k], &test[k]};
        for (int s = 0; s < 2; s++) {
            if (pair[s]->width != w || pair[s]->height != h || pair[s]->channels < 3)
                return gib_fail(err, "temporal error: %s frame %d is %dx%d with %d channels, "
                                "frame 0 of the reference %dx%d (RGB needed)",
                                s ? "technique" : "reference", k, pair[s]->width,
                                pair[s]->height, pair[s]->channels, w, h);
            if (gib_image_count_nonfinite(pair[s]))
                return gib_fail_code(err, GIB_ERR_NON_FINITE,
                                     "temporal error: %s frame %d has non-finite samples",
                                     s ? "technique" : "reference", k);
        }
    }
    return 0;
}

/* The sample c of pixel i in image img. */
static double at(const gib_image *img, size_t i, int c)
{
    return img->px[i * (size_t)img->channels + (size_t)c];
}

/* rmse, peak and frozen over every frame pair (the header's definitions). */
static void difference_errors(const gib_image *ref, const gib_image *test, int frames,
                              gib_temporal *out)
{
    const size_t n = (size_t)ref[0].width * (size_t)ref[0].height;
    double sum = 0, sum_ref = 0, peak = 0;
    for (size_t i = 0; i < n; i++) {
        double pixel = 0;
        for (int k = 0; k + 1 < frames; k++)
            for (int c = 0; c < 3; c++) {
                const double dr = at(&ref[k + 1], i, c) - at(&ref[k], i, c);
                const double dt = at(&test[k + 1], i, c) - at(&test[k], i, c);
                pixel += (dt - dr) * (dt - dr);
                sum_ref += dr * dr;
            }
        sum += pixel;
        pixel = sqrt(pixel / (3.0 * (frames - 1)));
        if (pixel > peak)
            peak = pixel;
    }
    const double count = 3.0 * (double)n * (frames - 1);
    out->rmse = sqrt(sum / count);
    out->frozen = sqrt(sum_ref / count);
    out->peak = peak;
}

/* The LDR-FLIP input of a frame: clamp(exposure * rgb) per channel, 3 floats a pixel. */
static void exposed(const gib_image *img, float exposure, float *out)
{
    const size_t n = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            out[3 * i + c] = fminf(fmaxf(exposure * (float)at(img, i, c), 0.0f), 1.0f);
}

/* Mean over frame pairs of |FLIP(T_k, T_k+1) - FLIP(R_k, R_k+1)|. */
static int flip_difference(const gib_image *ref, const gib_image *test, int frames,
                           float exposure, double *out, gib_error *err)
{
    const int w = ref[0].width, h = ref[0].height;
    const size_t n = 3 * (size_t)w * (size_t)h;
    float *buf = malloc(4 * n * sizeof *buf);
    if (!buf)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "temporal FLIP: out of memory for %dx%d frames", w, h);
    float *r0 = buf, *r1 = buf + n, *t0 = buf + 2 * n, *t1 = buf + 3 * n;
    const float ppd = gib_flip_default_ppd();
    double sum = 0;
    int rc = 0;
    for (int k = 0; k + 1 < frames && rc == 0; k++) {
        exposed(&ref[k], exposure, r0);
        exposed(&ref[k + 1], exposure, r1);
        exposed(&test[k], exposure, t0);
        exposed(&test[k + 1], exposure, t1);
        const double fr = gib_flip_ldr(r0, r1, w, h, ppd, NULL, err);
        const double ft = gib_flip_ldr(t0, t1, w, h, ppd, NULL, err);
        if (isnan(fr) || isnan(ft))
            rc = -1;
        sum += fabs(ft - fr);
    }
    free(buf);
    *out = sum / (frames - 1);
    return rc;
}

int gib_temporal_compute(const gib_image *ref, const gib_image *test, int frames,
                         double ref_noise_rmse, float exposure, int want_flip, gib_temporal *out,
                         gib_error *err)
{
    out->flip = NAN;
    out->pairs = frames - 1;
    if (check_sequences(ref, test, frames, err) < 0)
        return -1;
    difference_errors(ref, test, frames, out);
    const double noise2 = ref_noise_rmse > 0 ? 2.0 * ref_noise_rmse * ref_noise_rmse : 0.0;
    out->rmse_denoised = sqrt(fmax(out->rmse * out->rmse - noise2, 0.0));
    if (want_flip && flip_difference(ref, test, frames, exposure, &out->flip, err) < 0)
        return -1;
    return 0;
}

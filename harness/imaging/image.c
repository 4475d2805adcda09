/* gibench — linear float images, sRGB encoding, PNG previews and false-colour error maps.
 * EXR I/O lives in exr.c. */
#include "image.h"

#include "oiio_shim.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int gib_image_alloc(gib_image *img, int width, int height, int channels, gib_error *err)
{
    img->width = img->height = img->channels = 0;
    img->px = NULL;
    if (width <= 0 || height <= 0)
        return gib_fail(err, "image size %dx%d is not positive", width, height);
    if (channels != 1 && channels != 3 && channels != 4)
        return gib_fail(err, "image channel count %d is not 1, 3 or 4", channels);
    size_t n = (size_t)width * (size_t)height;
    if (n > SIZE_MAX / sizeof(float) / (size_t)channels)
        return gib_fail(err, "image size %dx%dx%d overflows", width, height, channels);
    img->px = gib_calloc(n * (size_t)channels, sizeof(float), err);
    if (!img->px)
        return -1;
    img->width = width;
    img->height = height;
    img->channels = channels;
    return 0;
}

void gib_image_free(gib_image *img)
{
    if (!img)
        return;
    free(img->px);
    img->px = NULL;
    img->width = img->height = img->channels = 0;
}

long gib_image_count_nonfinite(const gib_image *img)
{
    if (!img || !img->px)
        return 0;
    size_t n = (size_t)img->width * (size_t)img->height * (size_t)img->channels;
    long count = 0;
    for (size_t i = 0; i < n; ++i)
        count += !isfinite(img->px[i]);
    return count;
}

const char *gib_kv_get(const gib_kv *attrs, int nattrs, const char *key)
{
    for (int i = 0; attrs && i < nattrs; ++i)
        if (strcmp(attrs[i].key, key) == 0)
            return attrs[i].value;
    return NULL;
}

float gib_srgb_encode(float linear)
{
    /* `!(x > 0)` also sends NaN to black, so a broken pixel cannot poison 8-bit output or SSIM. */
    if (!(linear > 0.0f))
        return 0.0f;
    if (linear >= 1.0f)
        return 1.0f;
    /* IEC 61966-2-1 piecewise OETF, evaluated in double so the SSIM channel is reproducible. */
    double v = linear;
    v = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
    return (float)v;
}

static unsigned char to_u8(float v01)
{
    if (!(v01 > 0.0f))
        return 0;
    if (v01 >= 1.0f)
        return 255;
    return (unsigned char)(v01 * 255.0f + 0.5f);
}

/* To a temporary name renamed on success, as the EXRs: a full disk or a kill never leaves a
 * truncated PNG that a later run would take for finished (the runner keeps existing previews). */
int gib_png_write8(const char *path, int w, int h, int c, const unsigned char *data,
                   gib_error *err)
{
    char buf[1024], tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid());
    if (gib_oiio_write_png8(tmp, w, h, c, data, buf, (int)sizeof buf) != 0) {
        unlink(tmp);
        return gib_fail(err, "%s", buf);
    }
    if (rename(tmp, path) != 0) {
        unlink(tmp);
        return gib_fail(err, "png '%s': cannot rename the written file into place", path);
    }
    return 0;
}

int gib_png_write_preview(const char *path, const gib_image *img, float exposure, gib_error *err)
{
    if (!img || !img->px || img->width <= 0 || img->height <= 0)
        return gib_fail(err, "png '%s': empty image", path);
    const int c = img->channels;
    if (c != 1 && c != 3 && c != 4)
        return gib_fail(err, "png '%s': %d channels (need 1, 3 or 4)", path, c);
    size_t n = (size_t)img->width * (size_t)img->height * (size_t)c;
    unsigned char *data = gib_calloc(n, 1, err);
    if (!data)
        return gib_error_prefix(err, "png '%s'", path);
    for (size_t i = 0; i < n; ++i) {
        /* Alpha is coverage, not radiance: neither exposed nor sRGB-encoded. */
        int is_alpha = c == 4 && i % 4 == 3;
        float v = img->px[i];
        data[i] = is_alpha ? to_u8(v) : to_u8(gib_srgb_encode(exposure * v));
    }
    int rc = gib_png_write8(path, img->width, img->height, c, data, err);
    free(data);
    return rc;
}

/* Viridis sampled at 9 evenly spaced points (matplotlib's table): perceptually uniform and
 * readable by colour-blind viewers, so error magnitudes compare visually across maps. */
static const float viridis[9][3] = {
    {0.267004f, 0.004874f, 0.329415f}, {0.278826f, 0.175490f, 0.483397f},
    {0.229739f, 0.322361f, 0.545706f}, {0.172719f, 0.448791f, 0.557885f},
    {0.127568f, 0.566949f, 0.550556f}, {0.157851f, 0.683765f, 0.501686f},
    {0.369214f, 0.788888f, 0.382914f}, {0.678489f, 0.863742f, 0.189503f},
    {0.993248f, 0.906157f, 0.143936f},
};

static void ramp(float t, unsigned char rgb[3])
{
    if (!(t > 0.0f))
        t = 0.0f;
    if (t > 1.0f)
        t = 1.0f;
    float x = t * 8.0f;
    int i = (int)x;
    if (i > 7)
        i = 7;
    float f = x - (float)i;
    for (int k = 0; k < 3; ++k)
        rgb[k] = to_u8(viridis[i][k] + f * (viridis[i + 1][k] - viridis[i][k]));
}

/* A quickselect with a three-way partition, so images with many equal values (black pixels) stay
 * linear; a median of three as the pivot. */
float gib_float_kth(float *v, size_t n, size_t k)
{
    size_t lo = 0, hi = n; /* the answer lies in v[lo, hi) */
    while (hi - lo > 1) {
        float a = v[lo], b = v[lo + (hi - lo) / 2], c = v[hi - 1];
        float p = a < b ? (b < c ? b : a < c ? c : a) : (a < c ? a : b < c ? c : b);
        size_t lt = lo, i = lo, gt = hi; /* [lo,lt) < p, [lt,i) == p, [gt,hi) > p */
        while (i < gt) {
            float x = v[i];
            if (x < p) {
                v[i++] = v[lt];
                v[lt++] = x;
            } else if (x > p) {
                v[i] = v[--gt];
                v[gt] = x;
            } else {
                i++;
            }
        }
        if (k < lt)
            hi = lt;
        else if (k >= gt)
            lo = gt;
        else
            return p;
    }
    return v[lo];
}

int gib_png_write_error_map(const char *path, const gib_image *ref, const gib_image *test,
                            float max_err, gib_error *err)
{
    if (!ref || !test || !ref->px || !test->px)
        return gib_fail(err, "error map '%s': missing image", path);
    if (ref->width != test->width || ref->height != test->height)
        return gib_fail(err, "error map '%s': size mismatch (reference %dx%d, test %dx%d)", path,
                        ref->width, ref->height, test->width, test->height);
    if (ref->channels != test->channels)
        return gib_fail(err, "error map '%s': channel mismatch (reference %d, test %d)", path,
                        ref->channels, test->channels);
    const int c = ref->channels;
    const int nc = c >= 3 ? 3 : c; /* alpha is not part of the error */
    const size_t n = (size_t)ref->width * (size_t)ref->height;

    float *e = gib_calloc(n, sizeof(float), err);
    float *finite = gib_calloc(n, sizeof(float), err);
    unsigned char *rgb = gib_calloc(n * 3, 1, err);
    if (!e || !finite || !rgb) {
        free(e);
        free(finite);
        free(rgb);
        return gib_error_prefix(err, "error map '%s'", path);
    }
    size_t nfinite = 0;
    for (size_t i = 0; i < n; ++i) {
        double s = 0.0;
        for (int k = 0; k < nc; ++k) {
            double d = (double)test->px[i * c + k] - (double)ref->px[i * c + k];
            s += d * d;
        }
        e[i] = (float)sqrt(s / nc); /* NaN or Inf when any sample is non-finite */
        if (isfinite(e[i]))
            finite[nfinite++] = e[i];
    }
    float scale = max_err;
    if (!(scale > 0.0f)) {
        /* The 99th percentile, not the max, so a few fireflies do not flatten the map to black. */
        scale = 0.0f;
        if (nfinite > 0)
            scale = gib_float_kth(finite, nfinite, (size_t)(0.99 * (double)(nfinite - 1) + 0.5));
        if (!(scale > 0.0f))
            scale = 1.0f; /* identical images: everything maps to the bottom of the ramp */
    }
    for (size_t i = 0; i < n; ++i) {
        if (!isfinite(e[i])) {
            rgb[i * 3 + 0] = 255;
            rgb[i * 3 + 1] = 0;
            rgb[i * 3 + 2] = 255;
        } else {
            ramp(e[i] / scale, &rgb[i * 3]);
        }
    }
    int rc = gib_png_write8(path, ref->width, ref->height, 3, rgb, err);
    free(e);
    free(finite);
    free(rgb);
    return rc;
}

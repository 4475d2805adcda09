/* gibench — linear float images, EXR I/O with metadata, PNG previews and error maps.
 *
 * Images are linear RGB radiance, row 0 is the TOP row (as the camera model in ARCHITECTURE.md), pixels
 * interleaved, `channels` floats per pixel (1, 3 or 4). */
#ifndef GIB_IMAGE_H
#define GIB_IMAGE_H

#include "harness/base/error.h"

typedef struct gib_image {
    int width, height, channels;
    float *px; /* width * height * channels floats, row-major, row 0 on top */
} gib_image;

/* A string attribute stored in (or read from) an EXR header. */
typedef struct gib_kv {
    char key[64];
    char value[256];
} gib_kv;

int gib_image_alloc(gib_image *img, int width, int height, int channels, gib_error *err);
void gib_image_free(gib_image *img);
/* Number of NaN or Inf values among all channels' samples. */
long gib_image_count_nonfinite(const gib_image *img);

/* Writes an EXR (OpenEXR core C API, 32-bit float channels R,G,B[,A] or Y, ZIP compression) with
 * the given string attributes in its header. */
int gib_exr_write(const char *path, const gib_image *img, const gib_kv *attrs, int nattrs,
                  gib_error *err);
/* Reads an EXR written by gib_exr_write (or any RGB/RGBA/Y float or half EXR) into 3 channels
 * (Y is replicated, A dropped). If attrs is non-NULL, *attrs receives a malloc'd array of the
 * header's string attributes and *nattrs its length. Errors name the file. A header claiming more
 * than GIB_EXR_MAX_PIXELS pixels, a side over GIB_EXR_MAX_SIDE, or more chunks than the file has
 * room for is refused before anything is allocated. */
#define GIB_EXR_MAX_SIDE 65536
#define GIB_EXR_MAX_PIXELS (1LL << 26)
int gib_exr_read(const char *path, gib_image *img, gib_kv **attrs, int *nattrs, gib_error *err);
/* Looks up a key in an attribute list; NULL if absent. */
const char *gib_kv_get(const gib_kv *attrs, int nattrs, const char *key);

/* Converts linear to display: srgb_encode(clamp(exposure * v, 0, 1)). */
float gib_srgb_encode(float linear);
/* Writes 8-bit PNG pixels (c = 1, 3 or 4 channels, rows top first) to a temporary name renamed into
 * place on success, so a full disk or a kill never leaves a truncated PNG. */
int gib_png_write8(const char *path, int w, int h, int c, const unsigned char *data,
                   gib_error *err);
/* Writes an 8-bit sRGB PNG preview of a linear image, scaled by exposure first. */
int gib_png_write_preview(const char *path, const gib_image *img, float exposure, gib_error *err);
/* Writes a false-colour error map PNG: per-pixel RMS over channels of (test - ref), mapped with a
 * perceptual colour ramp from 0 to `max_err` (if max_err <= 0, the 99th percentile of the error is
 * used). Non-finite pixels of either image are drawn magenta. */
int gib_png_write_error_map(const char *path, const gib_image *ref, const gib_image *test,
                            float max_err, gib_error *err);

/* The k-th smallest of v[0, n) (k < n; v sorted ascending, v[k]), the value qsort would leave at
 * index k, in linear time; v's order is changed. For finite values (a NaN breaks the order). */
float gib_float_kth(float *v, size_t n, size_t k);

#endif

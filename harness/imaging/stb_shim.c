/* gibench — oiio_shim.h's two functions over Debian's libstb (stb_image, stb_image_write) instead
 * of OpenImageIO, for builds with -DGIB_OIIO=OFF (the self-contained bundle: OpenImageIO's library
 * closure is hundreds of MB). Reads PNG, JPEG, TGA, BMP, PSD, GIF, HDR, PIC and PNM; no EXR (gibench
 * reads its own EXRs with harness/imaging/exr.c). libstb holds the implementations: this file
 * includes the headers only. */
#include "oiio_shim.h"
#include "rgba_expand.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>
#include <stb_image_write.h>

static int shim_fail(char *errbuf, int errbuf_len, const char *fmt, ...)
{
    if (errbuf && errbuf_len > 0) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(errbuf, (size_t)errbuf_len, fmt, ap);
        va_end(ap);
    }
    return -1;
}

/* The first four channels of pixel i of an image of nc channels, as floats in the file's scale: 8
 * and 16 bits divided by their maximum, HDR as stored. */
static void get_px(const void *src, int kind, size_t i, int nc, float s[4])
{
    for (int c = 0; c < nc && c < 4; c++) {
        const size_t k = i * (size_t)nc + (size_t)c;
        s[c] = kind == 0   ? ((const stbi_uc *)src)[k] / 255.0f
               : kind == 1 ? ((const stbi_us *)src)[k] / 65535.0f
                           : ((const float *)src)[k];
    }
}

/* The size a PNG's IHDR claims, read directly: stb_image refuses a header whose pixels would pass
 * 1 GiB without saying its size ("unknown image type"), and the error should name the size. */
static int png_claimed_size(FILE *f, long long *w, long long *h)
{
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char b[24];
    const long pos = ftell(f);
    const size_t got = fread(b, 1, sizeof b, f);
    fseek(f, pos, SEEK_SET);
    if (got != sizeof b || memcmp(b, sig, 8) || memcmp(b + 12, "IHDR", 4))
        return 0;
    *w = (long long)b[16] << 24 | b[17] << 16 | b[18] << 8 | b[19];
    *h = (long long)b[20] << 24 | b[21] << 16 | b[22] << 8 | b[23];
    return 1;
}

int gib_oiio_read_rgba(const char *path, int *width, int *height, float **rgba, char *errbuf,
                       int errbuf_len)
{
    *rgba = NULL;
    FILE *f = fopen(path, "rb");
    if (!f)
        return shim_fail(errbuf, errbuf_len, "cannot open image '%s': %s", path, strerror(errno));
    int w = 0, h = 0, nc = 0;
    if (!stbi_info_from_file(f, &w, &h, &nc)) {
        long long cw, ch;
        if (png_claimed_size(f, &cw, &ch) && cw * ch > GIB_IMAGE_MAX_PIXELS) {
            fclose(f);
            return shim_fail(errbuf, errbuf_len, "image '%s' claims %lldx%lld pixels: over "
                             "gibench's limit of %lld pixels", path, cw, ch,
                             (long long)GIB_IMAGE_MAX_PIXELS);
        }
        const char *why = stbi_failure_reason();
        fclose(f);
        return shim_fail(errbuf, errbuf_len, "cannot open image '%s': %s", path,
                         why ? why : "unknown format");
    }
    if (w <= 0 || h <= 0 || nc <= 0) {
        fclose(f);
        return shim_fail(errbuf, errbuf_len, "image '%s': invalid size %dx%d with %d channels", path,
                         w, h, nc);
    }
    /* A few bytes of header can claim any size: bounded before anything of that size is
     * allocated (a 69-byte PNG claiming 60000x60000 asked for 58 GB). */
    if ((long long)w * h > GIB_IMAGE_MAX_PIXELS || nc > GIB_IMAGE_MAX_CHANNELS) {
        fclose(f);
        return shim_fail(errbuf, errbuf_len, "image '%s' claims %dx%d pixels with %d channels: "
                         "over gibench's limit of %lld pixels and %d channels", path, w, h, nc,
                         (long long)GIB_IMAGE_MAX_PIXELS, GIB_IMAGE_MAX_CHANNELS);
    }
    /* The file's own depth: 8 bits, 16 bits, or floats for Radiance HDR (stbi_loadf would apply a
     * gamma to 8-bit data, which the contract forbids). */
    const int kind = stbi_is_hdr_from_file(f) ? 2 : stbi_is_16_bit_from_file(f) ? 1 : 0;
    int lw = 0, lh = 0, lnc = 0;
    void *src = kind == 0   ? (void *)stbi_load_from_file(f, &lw, &lh, &lnc, 0)
                : kind == 1 ? (void *)stbi_load_from_file_16(f, &lw, &lh, &lnc, 0)
                            : (void *)stbi_loadf_from_file(f, &lw, &lh, &lnc, 0);
    fclose(f);
    if (!src) {
        const char *why = stbi_failure_reason();
        return shim_fail(errbuf, errbuf_len, "cannot read image '%s': %s", path,
                         why ? why : "decoding failed");
    }
    if (lw != w || lh != h || lnc != nc) {
        stbi_image_free(src);
        return shim_fail(errbuf, errbuf_len, "image '%s': header says %dx%dx%d, pixels %dx%dx%d",
                         path, w, h, nc, lw, lh, lnc);
    }
    float *out = malloc((size_t)w * h * 4 * sizeof(float));
    if (!out) {
        stbi_image_free(src);
        return shim_fail(errbuf, errbuf_len, "image '%s': out of memory (%dx%d)", path, w, h);
    }
    const size_t n = (size_t)w * h;
    for (size_t i = 0; i < n; ++i) {
        float s[4] = {0.0f, 0.0f, 0.0f, 1.0f};
        get_px(src, kind, i, nc, s);
        gib_rgba_expand(s, nc, &out[i * 4]);
    }
    stbi_image_free(src);
    *width = w;
    *height = h;
    *rgba = out;
    return 0;
}

int gib_oiio_write_png8(const char *path, int width, int height, int channels,
                        const unsigned char *data, char *errbuf, int errbuf_len)
{
    if (width <= 0 || height <= 0 || (channels != 1 && channels != 3 && channels != 4))
        return shim_fail(errbuf, errbuf_len, "png '%s': invalid size %dx%d with %d channels", path,
                         width, height, channels);
    if ((long long)width * channels > 0x7fffffff)
        return shim_fail(errbuf, errbuf_len, "png '%s': rows of %dx%d bytes are too long", path,
                         width, channels);
    /* Always PNG, whatever the file name's extension: the contract is "write PNG". */
    errno = 0;
    if (!stbi_write_png(path, width, height, channels, data, width * channels)) {
        const int e = errno;
        return shim_fail(errbuf, errbuf_len, "cannot write png '%s': %s", path,
                         e ? strerror(e) : "stb_image_write failed");
    }
    return 0;
}

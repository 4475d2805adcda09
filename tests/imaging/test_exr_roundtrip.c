/* Every EXR gib_exr_write writes reads back bit for bit, in gib_exr_read and in OpenImageIO
 * (harness/imaging/exr.c, the comment above gib_exr_write).
 *
 * 1. The case that corrupted a reference (hard_far indirect 64x64): a ZIP chunk whose zlib stream
 *    is exactly as long as its raw pixels. The test builds such chunks on purpose (it computes
 *    the chunk's zlib size as OpenEXR does) for several widths and channel counts, checks that
 *    the size really ties, and round trips them.
 * 2. Incompressible (random finite floats: the raw fallback) and compressible (smooth) pixels
 *    over heights 1..70 (full and partial 16-line chunks), widths 1, 3, 17, 64, and 1, 3 and 4
 *    channels, each read back by gib_exr_read; OpenImageIO, the second reader, reads the heights
 *    that stand for every chunk layout (one partial chunk, one full, a full one and one line,
 *    several full ones and a partial one). Under AddressSanitizer each OpenImageIO read maps and
 *    poisons a fresh scanline buffer (millions of page faults over the whole sweep, most of the
 *    test's time on a busy machine), and the other heights add no layout it has not read.
 * Usage: test_exr_roundtrip [output_dir]. Prints one line per failure and a summary; the exit
 * status is the number of failed checks (capped). */
#include "tests/common/check.h"
#include "harness/imaging/image.h"
#include "harness/imaging/oiio_shim.h"

#include <openexr.h>
#include <zlib.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { LINES = 16 }; /* scanlines per ZIP chunk */

static int failures, checks;

/* Counts a check; CHECK prints what failed and why (tests/common/check.h). */
#define check(ok, why, what)                                                                       \
    do {                                                                                           \
        ++checks;                                                                                  \
        CHECK(ok, "%s: %s", (what), (why));                                                        \
    } while (0)

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static uint32_t rng(void)
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(rng_state >> 32);
}

/* Random bits that make a finite float (NaN and Inf have exponent 255), sign and denormals
 * included. */
static float random_finite(void)
{
    for (;;) {
        uint32_t u = rng();
        if (((u >> 23) & 0xffu) != 0xffu) {
            float f;
            memcpy(&f, &u, sizeof f);
            return f;
        }
    }
}

static void fill_random(gib_image *img)
{
    size_t n = (size_t)img->width * img->height * img->channels;
    for (size_t i = 0; i < n; ++i)
        img->px[i] = random_finite();
}

static void fill_smooth(gib_image *img)
{
    for (int y = 0; y < img->height; ++y)
        for (int x = 0; x < img->width; ++x)
            for (int k = 0; k < img->channels; ++k)
                img->px[((size_t)y * img->width + x) * img->channels + k] =
                    0.25f + 0.01f * (float)x + 0.02f * (float)y + 0.5f * (float)k;
}

/* Channel k of the image at position j of the file's (alphabetical) order: Y; B G R; A B G R. */
static int file_channel(int channels, int j)
{
    return channels == 1 ? 0 : channels - 1 - j;
}

/* The chunk's bytes as OpenEXR packs them: per line, per channel in file order, little endian. */
static size_t pack_chunk(const gib_image *img, int y0, int lines, uint8_t *out)
{
    size_t n = 0;
    for (int y = y0; y < y0 + lines && y < img->height; ++y)
        for (int j = 0; j < img->channels; ++j)
            for (int x = 0; x < img->width; ++x) {
                const float *p = &img->px[((size_t)y * img->width + x) * img->channels];
                uint32_t u;
                memcpy(&u, &p[file_channel(img->channels, j)], sizeof u);
                for (int b = 0; b < 4; ++b)
                    out[n++] = (uint8_t)(u >> (8 * b));
            }
    return n;
}

/* The length of the zlib stream OpenEXR's ZIP compressor makes of n packed bytes: even bytes then
 * odd bytes, each byte replaced by its difference to the one before (+128), then compress2 at the
 * library's default level. */
static size_t zip_size(const uint8_t *packed, size_t n)
{
    uint8_t *t = malloc(n), *z = malloc(compressBound(n));
    size_t half = (n + 1) / 2;
    for (size_t i = 0; i < n; ++i)
        t[(i & 1) ? half + i / 2 : i / 2] = packed[i];
    for (size_t i = n - 1; i > 0; --i)
        t[i] = (uint8_t)(t[i] - t[i - 1] + 128);
    int level = -1;
    exr_get_default_zip_compression_level(&level);
    uLongf zn = compressBound(n);
    int rc = compress2(z, &zn, t, n, level);
    free(t);
    free(z);
    return rc == Z_OK ? (size_t)zn : 0;
}

static int same_bits(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Compares what gib_exr_read and OpenImageIO read from path with img, bit for bit. */
static void check_read_back(const char *path, const gib_image *img, int with_oiio,
                            const char *what)
{
    gib_image back;
    gib_error err;
    int ok = gib_exr_read(path, &back, NULL, NULL, &err) == 0;
    check(ok, ok ? "" : err.msg, what);
    if (ok) {
        ok = back.width == img->width && back.height == img->height;
        for (size_t i = 0; ok && i < (size_t)img->width * img->height; ++i)
            for (int k = 0; k < 3; ++k) /* Y is read into R, G and B; A is dropped */
                ok &= same_bits(back.px[i * 3 + k],
                                img->px[i * img->channels + (img->channels == 1 ? 0 : k)]);
        check(ok, "gib_exr_read's pixels differ from those written", what);
        gib_image_free(&back);
    }
    if (!with_oiio)
        return;
    int w = 0, h = 0;
    float *rgba = NULL;
    char msg[512];
    ok = gib_oiio_read_rgba(path, &w, &h, &rgba, msg, sizeof msg) == 0;
    check(ok, ok ? "" : msg, what);
    if (ok) {
        ok = w == img->width && h == img->height;
        for (size_t i = 0; ok && i < (size_t)w * h; ++i)
            for (int k = 0; k < 4; ++k) {
                float want = k == 3 && img->channels < 4 ? 1.0f
                                                          : img->px[i * img->channels +
                                                                    (img->channels == 1 ? 0 : k)];
                ok &= same_bits(rgba[i * 4 + k], want);
            }
        check(ok, "OpenImageIO's pixels differ from those written", what);
    }
    free(rgba);
}

static void round_trip(const char *path, const gib_image *img, int with_oiio, const char *what)
{
    gib_error err;
    int ok = gib_exr_write(path, img, NULL, 0, &err) == 0;
    check(ok, ok ? "" : err.msg, what);
    if (ok)
        check_read_back(path, img, with_oiio, what);
}

/* The heights OpenImageIO also reads in the sweep: one line, a partial chunk, a full chunk, a full
 * chunk and one line, two full chunks, several full chunks and a partial one. */
static int oiio_height(int h)
{
    return h == 1 || h == 7 || h == LINES || h == LINES + 1 || h == 2 * LINES || h == 70;
}

/* Makes the first chunk of img (random finite floats) tie: its zlib stream exactly as long as
 * its packed bytes. Zeroing mantissa bytes one at a time (the floats stay finite) shrinks the
 * stream about a byte at a time from just over the raw size; returns 0 if no count ties. */
static int make_tie(gib_image *img, uint8_t *packed)
{
    const size_t nfloat = (size_t)img->width * LINES * img->channels;
    for (size_t m = 0; m < 3 * nfloat; ++m) {
        uint8_t *bytes = (uint8_t *)&img->px[m / 3];
        bytes[m % 3] = 0; /* bytes 0..2 of a little-endian float: mantissa, exponent's low bit */
        size_t n = pack_chunk(img, 0, LINES, packed);
        size_t z = zip_size(packed, n);
        if (z == n)
            return 1;
        if (z + 64 < n)
            return 0; /* well past the raw size: this draw skipped it */
    }
    return 0;
}

/* Chunks whose zlib stream ties with their raw size, for several widths and channel counts;
 * images of 40 lines, so the tie is followed by a full and a partial chunk. */
static void test_tie(const char *dir)
{
    static const int widths[] = {64, 17, 3, 1};
    static const int chans[] = {3, 1, 4};
    char path[1024], what[128];
    snprintf(path, sizeof path, "%s/exr_tie.exr", dir);
    uint8_t *packed = malloc((size_t)64 * LINES * 4 * 4);
    for (size_t wi = 0; wi < sizeof widths / sizeof *widths; ++wi)
        for (size_t ci = 0; ci < sizeof chans / sizeof *chans; ++ci) {
            gib_image img;
            gib_error err;
            gib_image_alloc(&img, widths[wi], 40, chans[ci], &err);
            int tied = 0;
            for (int draw = 0; draw < 50 && !tied; ++draw) {
                fill_random(&img);
                tied = make_tie(&img, packed);
            }
            snprintf(what, sizeof what, "tie %dx40 %d channels", widths[wi], chans[ci]);
            /* Tiny chunks (1 or 3 pixels wide) may have no count that ties exactly. */
            if (tied)
                round_trip(path, &img, 1, what);
            else if (widths[wi] >= 17)
                check(0, "no chunk with a zlib stream as long as its raw bytes was found", what);
            printf("%s: %s\n", what, tied ? "built and round-tripped" : "no tie (skipped)");
            gib_image_free(&img);
        }
    free(packed);
}

static void test_sweep(const char *dir)
{
    static const int widths[] = {1, 3, 17, 64};
    static const int chans[] = {1, 3, 4};
    char path[1024], what[128];
    snprintf(path, sizeof path, "%s/exr_sweep.exr", dir);
    int before = failures;
    for (int h = 1; h <= 70; ++h)
        for (size_t wi = 0; wi < sizeof widths / sizeof *widths; ++wi)
            for (size_t ci = 0; ci < sizeof chans / sizeof *chans; ++ci)
                for (int smooth = 0; smooth < 2; ++smooth) {
                    gib_image img;
                    gib_error err;
                    gib_image_alloc(&img, widths[wi], h, chans[ci], &err);
                    if (smooth)
                        fill_smooth(&img);
                    else
                        fill_random(&img);
                    snprintf(what, sizeof what, "%s %dx%d %d channels",
                             smooth ? "smooth" : "random", widths[wi], h, chans[ci]);
                    round_trip(path, &img, oiio_height(h), what);
                    gib_image_free(&img);
                }
    printf("sweep (heights 1..70, widths 1 3 17 64, 1 3 4 channels, random and smooth; "
           "OpenImageIO at heights 1 7 16 17 32 70): %s\n",
           failures == before ? "all bit-exact" : "FAILED");
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : ".";
    test_tie(dir);
    test_sweep(dir);
    printf("%d of %d checks failed\n", failures, checks);
    return failures > 100 ? 100 : failures;
}

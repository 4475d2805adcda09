/* Writes deterministic image pairs and our SSIM for each, so test_ssim_skimage.py can compare
 * with scikit-image. Usage: ssim_dump OUTDIR
 *   OUTDIR/NAME_a.f32, NAME_b.f32: the two SSIM channels (gib_ssim_channel), row-major
 *     little-endian float32, width*height each;
 *   OUTDIR/pairs.txt: one line "NAME WIDTH HEIGHT SSIM" per pair (SSIM with %.17g).
 * The pairs are built in linear RGB and go through gib_ssim_channel, so exposure, the luminance
 * weights, the clamp and the sRGB curve are all exercised on the way to gib_ssim_gray. */
#include "harness/imaging/image.h"
#include "harness/imaging/metrics.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint32_t rng_state = 0x9e3779b9u;
static double urand(void) /* xorshift32: identical on every platform */
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return (double)rng_state / 4294967296.0;
}

typedef enum { NOISE, BLUR, OFFSET, STRUCTURE, LOW_CONTRAST, HDR_CLAMP, GRADIENT } pair_kind;

typedef struct {
    const char *name;
    int w, h;
    pair_kind kind;
    float exposure;
} pair_spec;

static const pair_spec pairs[] = {
    {"noise_64x48", 64, 48, NOISE, 1.0f},
    {"blur_100x100", 100, 100, BLUR, 1.0f},
    {"offset_37x53", 37, 53, OFFSET, 1.0f},
    {"structure_128x96", 128, 96, STRUCTURE, 1.0f},
    {"lowcontrast_80x80", 80, 80, LOW_CONTRAST, 1.0f},
    {"hdr_clamp_90x70", 90, 70, HDR_CLAMP, 1.0f},
    {"hdr_exposure_90x70", 90, 70, HDR_CLAMP, 0.3f},
    {"gradient_11x11", 11, 11, GRADIENT, 1.0f}, /* exactly one valid window position */
    {"noise_12x31", 12, 31, NOISE, 2.0f},
    {"blur_512x512", 512, 512, BLUR, 1.0f},
};

/* A scene-like linear reference: smooth shading, hard edges and texture. Values reach ~1.3. */
static float scene(int x, int y, int w, int h, int c)
{
    double u = (double)x / w, v = (double)y / h;
    double shade = 0.15 + 0.6 * u * (1.0 - 0.5 * v);
    double checker = ((x / 8 + y / 8) % 2) ? 0.25 : 0.0;
    double ring = 0.2 * sin(0.35 * hypot(x - 0.4 * w, y - 0.6 * h));
    double tint = c == 0 ? 1.0 : c == 1 ? 0.9 : 0.7;
    return (float)(tint * (shade + checker + ring + 0.2));
}

static void make_pair(const pair_spec *p, gib_image *a, gib_image *b)
{
    const int w = p->w, h = p->h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                float *pa = &a->px[((size_t)y * w + x) * 3 + c];
                float *pb = &b->px[((size_t)y * w + x) * 3 + c];
                double v = scene(x, y, w, h, c);
                switch (p->kind) {
                case NOISE:
                    *pa = (float)v;
                    *pb = (float)(v + 0.15 * (urand() - 0.5));
                    break;
                case BLUR:
                case OFFSET:
                    *pa = (float)v;
                    *pb = (float)(v + (p->kind == OFFSET ? 0.08 : 0.0));
                    break;
                case STRUCTURE: /* same brightness, different structure */
                    *pa = (float)v;
                    *pb = (float)(0.5 + 0.3 * sin(0.2 * x) * cos(0.27 * y));
                    break;
                case LOW_CONTRAST: /* tiny variance: C1/C2 dominate */
                    *pa = (float)(0.2 + 0.01 * urand());
                    *pb = (float)(0.2 + 0.01 * urand());
                    break;
                case HDR_CLAMP: /* up to ~9: much of the image clips at exposure 1 */
                    *pa = (float)(7.0 * v * v);
                    *pb = (float)(7.0 * v * v * (0.8 + 0.4 * urand()));
                    break;
                case GRADIENT:
                    *pa = (float)((x + y) / 20.0);
                    *pb = (float)((x * y) / 100.0);
                    break;
                }
            }
    if (p->kind == BLUR) { /* 3x3 box blur of a into b, clamped at the borders */
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 3; ++c) {
                    double s = 0;
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            int xx = x + dx < 0 ? 0 : x + dx >= w ? w - 1 : x + dx;
                            int yy = y + dy < 0 ? 0 : y + dy >= h ? h - 1 : y + dy;
                            s += a->px[((size_t)yy * w + xx) * 3 + c];
                        }
                    b->px[((size_t)y * w + x) * 3 + c] = (float)(s / 9.0);
                }
    }
}

static int write_f32(const char *dir, const char *name, const char *suffix, const float *v,
                     size_t n)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s_%s.f32", dir, name, suffix);
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "ssim_dump: cannot create '%s'\n", path);
        return -1;
    }
    /* x86 and ARM Linux are little-endian, the format the Python side reads ('<f4'). */
    size_t wrote = fwrite(v, sizeof(float), n, f);
    int bad = fclose(f) != 0 || wrote != n;
    if (bad)
        fprintf(stderr, "ssim_dump: cannot write '%s'\n", path);
    return bad ? -1 : 0;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: ssim_dump OUTDIR\n");
        return 2;
    }
    const char *dir = argv[1];
    char list[1024];
    snprintf(list, sizeof list, "%s/pairs.txt", dir);
    FILE *out = fopen(list, "w");
    if (!out) {
        fprintf(stderr, "ssim_dump: cannot create '%s'\n", list);
        return 1;
    }
    int rc = 0;
    for (size_t i = 0; i < sizeof pairs / sizeof pairs[0] && rc == 0; ++i) {
        const pair_spec *p = &pairs[i];
        gib_error err = {0};
        gib_image a, b;
        if (gib_image_alloc(&a, p->w, p->h, 3, &err) || gib_image_alloc(&b, p->w, p->h, 3, &err)) {
            fprintf(stderr, "ssim_dump: %s\n", err.msg);
            return 1;
        }
        make_pair(p, &a, &b);
        size_t n = (size_t)p->w * p->h;
        float *ga = malloc(n * sizeof(float)), *gb = malloc(n * sizeof(float));
        if (!ga || !gb) {
            fprintf(stderr, "ssim_dump: out of memory\n");
            return 1;
        }
        gib_ssim_channel(&a, p->exposure, ga);
        gib_ssim_channel(&b, p->exposure, gb);
        double s = gib_ssim_gray(ga, gb, p->w, p->h);
        if (write_f32(dir, p->name, "a", ga, n) || write_f32(dir, p->name, "b", gb, n))
            rc = 1;
        fprintf(out, "%s %d %d %.17g\n", p->name, p->w, p->h, s);
        free(ga);
        free(gb);
        gib_image_free(&a);
        gib_image_free(&b);
    }
    if (fclose(out) != 0) {
        fprintf(stderr, "ssim_dump: cannot write '%s'\n", list);
        rc = 1;
    }
    return rc;
}

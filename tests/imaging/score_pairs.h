/* gibench tests — the image pairs test_score_threads.c scores: odd, non-square sizes, HDR values,
 * RGBA and RGB. Pair 0: a 157x83 RGBA room (lit walls, a black window, a highlight 25x the walls)
 * and a dimmer, noisy test image; pair 1: 64x45 RGB whose reference is black over 60% of its
 * pixels (HDR-FLIP's median of the positive luminances); pair 2: pair 0 with one NaN and one Inf
 * in the test image. Scored at exposure 1.7 (pairs 0, 2) and 1 (pair 1). */
#ifndef GIB_TEST_SCORE_PAIRS_H
#define GIB_TEST_SCORE_PAIRS_H

#include <math.h>
#include <stdint.h>

#include "harness/base/hash.h"
#include "harness/imaging/image.h"

#define SCORE_PAIRS 3

static inline float score_pairs_noise(uint32_t i, uint32_t c)
{
    uint32_t x = gib_hash_mix32(i * 0x9E3779B1u ^ (c + 1u) * 0x85EBCA77u);
    return (float)(x >> 8) / 16777216.0f - 0.5f; /* in [-0.5, 0.5) */
}

static inline float score_pairs_exposure(int k)
{
    return k == 1 ? 1.0f : 1.7f;
}

/* Pair k into ref and test (allocated here). Returns 0, or -1 when memory runs out. */
static inline int score_pairs_make(int k, gib_image *ref, gib_image *test)
{
    gib_error err;
    const int w = k == 1 ? 64 : 157, h = k == 1 ? 45 : 83, c = k == 1 ? 3 : 4;
    if (gib_image_alloc(ref, w, h, c, &err) < 0 || gib_image_alloc(test, w, h, c, &err) < 0)
        return -1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const size_t i = (size_t)y * w + x;
            const float u = (float)x / (float)w, v = (float)y / (float)h;
            const float du = u - 0.7f, dv = v - 0.4f;
            const int dark = k == 1 ? u + 0.5f * v < 0.75f : v < 0.15f && u < 0.5f;
            for (int ch = 0; ch < 3; ch++) {
                float r = 0.05f + 0.6f * u * (1.0f - 0.5f * v) * (ch == 2 ? 0.7f : 1.0f);
                if ((x / 7 + y / 5) % 2)
                    r *= 0.5f;
                r += 25.0f * expf(-(du * du + dv * dv) / 0.002f);
                r = dark ? 0.0f : r;
                ref->px[i * c + ch] = r;
                float t = 0.9f * r * (1.0f + 0.5f * score_pairs_noise((uint32_t)i, (uint32_t)ch));
                test->px[i * c + ch] = t + 0.02f * score_pairs_noise((uint32_t)i, 7u + ch);
            }
            if (c == 4)
                ref->px[i * c + 3] = test->px[i * c + 3] = 1.0f;
        }
    if (k == 2) {
        test->px[(size_t)(17 * w + 33) * c + 1] = NAN;
        test->px[(size_t)(60 * w + 101) * c + 0] = INFINITY;
    }
    return 0;
}

#endif

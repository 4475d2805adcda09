/* Reference renderer, the camera samples' numbers (reference/sampler.h: Owen-scrambled Sobol,
 * Burley 2020).
 *
 * Expected:
 *  - dimension 1 computed by shifts and masks equals the xor of its direction numbers (100,000
 *    indices); the unscrambled first two Sobol dimensions are a (0,2)-sequence: for every m <= 12, each
 *    block of 2^m consecutive indices starting at a multiple of 2^m holds exactly one point in
 *    every elementary interval [a 2^-i, (a+1) 2^-i) x [b 2^-j, (b+1) 2^-j), i + j = m;
 *  - so does what the renderer draws: the first 2^m samples of one pixel's batch (samples
 *    b, b + 8, b + 16, ... of the pixel), in every dimension set (sets 0 to 5, two pixels, two
 *    batches): Owen scrambling keeps nets, and the index shuffle maps the first 2^m indices onto an
 *    aligned block of 2^m. A 1D request's numbers are stratified into 2^m equal intervals;
 *  - the 2D star discrepancy of 256 such points is below that of 256 PCG32 points, averaged over
 *    16 pixels (Sobol nets: O(log^2 N / N), about 0.02 here; independent points: about
 *    1/sqrt(N) scale, about 0.06), by at least a factor 2;
 *  - the numbers are a function of (pixel, sample, set, seed) alone: the same call twice gives the
 *    same bits, and another pixel, seed or batch gives other numbers.
 * No tolerance: counts are exact; the discrepancy comparison has a factor 2 margin over means that
 * differ by ~3x. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ref_test_util.h"
#include "reference/sampler.h"

/* 1 when pts (n = 2^m points, coordinates as 32-bit fractions) hold exactly one point in every
 * elementary interval of volume 2^-m. */
static int is_net(const uint32_t (*pts)[2], int m)
{
    int n = 1 << m, ok = 1;
    int *count = calloc((size_t)n, sizeof *count);
    for (int i = 0; i <= m && ok; i++) {
        int j = m - i;
        memset(count, 0, (size_t)n * sizeof *count);
        for (int k = 0; k < n; k++) {
            uint32_t a = i ? pts[k][0] >> (32 - i) : 0, b = j ? pts[k][1] >> (32 - j) : 0;
            count[(a << j) | b]++;
        }
        for (int k = 0; k < n; k++)
            ok &= count[k] == 1;
    }
    free(count);
    return ok;
}

/* Exact 2D star discrepancy of n points in [0,1)^2: sup over anchored boxes [0,x) x [0,y) of
 * |count/n - xy|, attained at boxes whose corners are point coordinates (or 1), open or closed. */
static double star_discrepancy(const double (*p)[2], int n)
{
    double worst = 0.0;
    for (int a = 0; a <= n; a++) {
        double x = a < n ? p[a][0] : 1.0;
        for (int b = 0; b <= n; b++) {
            double y = b < n ? p[b][1] : 1.0;
            int open = 0, closed = 0;
            for (int k = 0; k < n; k++) {
                open += p[k][0] < x && p[k][1] < y;
                closed += p[k][0] <= x && p[k][1] <= y;
            }
            double v = x * y;
            worst = fmax(worst, fmax(v - (double)open / n, (double)closed / n - v));
        }
    }
    return worst;
}

/* Dimension 1 by its definition: the xor of the direction numbers v_j of the index's set bits,
 * v_0 = 2^31, v_j = v_(j-1) xor (v_(j-1) >> 1). */
static uint32_t sobol1_by_directions(uint32_t index)
{
    uint32_t v = 0x80000000u, y = 0;
    for (uint32_t i = index; i; i >>= 1, v ^= v >> 1)
        if (i & 1u)
            y ^= v;
    return y;
}

static void test_unscrambled(void)
{
    ref_pcg32 g;
    ref_pcg32_seed(&g, 5, 7);
    int same = 1;
    for (int k = 0; k < 100000; k++) {
        uint32_t i = k < 4096 ? (uint32_t)k : ref_pcg32_next(&g), x0, x1;
        ref_sobol2(i, &x0, &x1);
        same &= x1 == sobol1_by_directions(i) && x0 == ref_reverse_bits(i);
    }
    CHECK(same, "sobol dimension 1: the shift-and-mask transform differs from the direction "
                "numbers' xor");
    enum { M = 12 };
    static uint32_t pts[1 << M][2];
    for (int m = 0; m <= M; m++)
        for (uint32_t block = 0; block < 3; block++) {
            uint32_t first = block << m;
            for (uint32_t k = 0; k < (1u << m); k++)
                ref_sobol2(first + k, &pts[k][0], &pts[k][1]);
            CHECK(is_net((const uint32_t(*)[2])pts, m),
                  "sobol: indices %u .. %u are not a (0,%d,2)-net", first, first + (1u << m) - 1,
                  m);
        }
    printf("unscrambled Sobol dimensions 0 and 1: aligned blocks of 2^0 .. 2^%d are (0,m,2)-nets\n",
           M);
}

static void test_renderer_sets(void)
{
    enum { M = 10, B = GIB_REF_SOBOL_BATCHES };
    static uint32_t pts[1 << M][2];
    static uint32_t one[1 << M][2];
    int checked = 0;
    for (uint64_t pix = 0; pix < 2; pix++)
        for (int batch = 0; batch < 2; batch++)
            for (uint32_t set = 0; set < 6; set++)
                for (int m = 1; m <= M; m++) {
                    for (int k = 0; k < (1 << m); k++) {
                        ref_rng r;
                        ref_rng_seed_sample(&r, GIB_REF_SAMPLER_SOBOL, 1000 + pix * 77,
                                            (uint64_t)k * B + (uint64_t)batch, 1, GIB_COMP_FULL);
                        CHECK(r.index == (uint32_t)k, "sample %d of batch %d has index %u",
                              k * B + batch, batch, r.index);
                        for (uint32_t s = 0; s < set; s++)
                            (void)ref_rng_1d(&r); /* sets before this one */
                        float u1, u2;
                        ref_rng_2d(&r, &u1, &u2);
                        /* 24 bits of each number: intervals up to 2^-10 need only 10 of them */
                        pts[k][0] = (uint32_t)(u1 * 0x1p24f) << 8;
                        pts[k][1] = (uint32_t)(u2 * 0x1p24f) << 8;
                        /* the same set asked for one number: its first coordinate */
                        ref_rng_seed_sample(&r, GIB_REF_SAMPLER_SOBOL, 1000 + pix * 77,
                                            (uint64_t)k * B + (uint64_t)batch, 1, GIB_COMP_FULL);
                        for (uint32_t s = 0; s < set; s++)
                            (void)ref_rng_1d(&r);
                        one[k][0] = (uint32_t)(ref_rng_1d(&r) * 0x1p24f) << 8;
                        one[k][1] = 0;
                    }
                    CHECK(is_net((const uint32_t(*)[2])pts, m),
                          "pixel %llu batch %d set %u: the first 2^%d samples are not a "
                          "(0,%d,2)-net",
                          (unsigned long long)pix, batch, set, m, m);
                    /* 1D: 2^m intervals of [0,1), one point each (a 2D net's first coordinate) */
                    int ok = 1;
                    char *seen = calloc((size_t)1 << m, 1);
                    for (int k = 0; k < (1 << m); k++) {
                        uint32_t a = one[k][0] >> (32 - m);
                        ok &= !seen[a];
                        seen[a] = 1;
                    }
                    free(seen);
                    CHECK(ok, "pixel %llu batch %d set %u: 1D numbers of 2^%d samples not "
                              "stratified", (unsigned long long)pix, batch, set, m);
                    checked++;
                }
    printf("renderer's Sobol sets: %d prefixes of 2^1 .. 2^%d batch samples are (0,m,2)-nets, "
           "their 1D numbers stratified\n", checked, M);
}

static void test_discrepancy(void)
{
    enum { N = 256, PIXELS = 16 };
    static double sob[N][2], rnd[N][2];
    double ds = 0.0, dr = 0.0;
    for (uint64_t pix = 0; pix < PIXELS; pix++) {
        for (int k = 0; k < N; k++) {
            ref_rng r;
            float u1, u2;
            ref_rng_seed_sample(&r, GIB_REF_SAMPLER_SOBOL, pix, (uint64_t)k * GIB_REF_SOBOL_BATCHES,
                                3, GIB_COMP_INDIRECT);
            ref_rng_2d(&r, &u1, &u2);
            sob[k][0] = u1, sob[k][1] = u2;
            ref_rng_seed_sample(&r, GIB_REF_SAMPLER_RANDOM, pix, (uint64_t)k, 3,
                                GIB_COMP_INDIRECT);
            ref_rng_2d(&r, &u1, &u2);
            rnd[k][0] = u1, rnd[k][1] = u2;
        }
        ds += star_discrepancy((const double(*)[2])sob, N) / PIXELS;
        dr += star_discrepancy((const double(*)[2])rnd, N) / PIXELS;
    }
    printf("2D star discrepancy of %d points, mean of %d pixels: sobol %.4f, random %.4f\n", N,
           PIXELS, ds, dr);
    CHECK(ds * 2.0 < dr, "sobol's star discrepancy %.4f is not below half of random's %.4f", ds,
          dr);
}

static void test_determinism(void)
{
    ref_rng a, b;
    float x1, y1, x2, y2;
    ref_rng_seed_sample(&a, GIB_REF_SAMPLER_SOBOL, 42, 13, 1, GIB_COMP_AO);
    ref_rng_seed_sample(&b, GIB_REF_SAMPLER_SOBOL, 42, 13, 1, GIB_COMP_AO);
    for (int s = 0; s < 20; s++) {
        ref_rng_2d(&a, &x1, &y1);
        ref_rng_2d(&b, &x2, &y2);
        CHECK(x1 == x2 && y1 == y2, "set %d: the same sample gives other numbers", s);
    }
    const uint64_t other[3][3] = {{43, 13, 1}, {42, 13, 2}, {42, 14, 1}}; /* pixel, sample, seed */
    ref_rng_seed_sample(&a, GIB_REF_SAMPLER_SOBOL, 42, 13, 1, GIB_COMP_AO);
    ref_rng_2d(&a, &x1, &y1);
    for (int i = 0; i < 3; i++) {
        ref_rng_seed_sample(&b, GIB_REF_SAMPLER_SOBOL, other[i][0], other[i][1], other[i][2],
                            GIB_COMP_AO);
        ref_rng_2d(&b, &x2, &y2);
        CHECK(x1 != x2 || y1 != y2, "pixel/sample/seed change %d gives the same numbers", i);
    }
    printf("numbers depend on (pixel, sample, set, seed) and nothing else\n");
}

int main(void)
{
    test_unscrambled();
    test_renderer_sets();
    test_discrepancy();
    test_determinism();
    return failures != 0;
}

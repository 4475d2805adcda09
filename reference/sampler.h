/* gibench — the reference renderer's camera-sample numbers: independent random numbers (PCG32,
 * rng.h) or Owen-scrambled Sobol points, chosen by gib_ref_params.sampler.
 *
 * Sobol (the default): Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)), Sec. 4-5:
 * every call for one or two numbers opens a new "dimension set" (padding: Sec. 5), whose points
 * are the first two dimensions of the Sobol sequence (a (0,2)-sequence), Owen-scrambled per
 * coordinate (Sec. 3, the hash approximating a nested uniform scramble) and taken in a shuffled
 * order: the sample's index is itself Owen-scrambled (Sec. 4), a different shuffle per set, so
 * that sets do not correlate with each other. All seeds come from a hash of (pixel, batch, seed,
 * component, set), so a number depends on nothing but (pixel, sample index, dimension set):
 * deterministic whatever the threads or rounds, as the PCG streams are.
 *
 * Why sets of two: Burley's paper pads with 4D sets; our estimators consume numbers in 1D
 * (lobe choice, roulette) and 2D (a direction) groups, so 2D sets keep each direction's two numbers
 * stratified together, and a 1D request uses the set's first coordinate alone (a (0,1)-sequence).
 *
 * Batches (the honest noise estimate): a pixel's sample s belongs to batch b = s mod
 * GIB_REF_SOBOL_BATCHES, where it is sample s / GIB_REF_SOBOL_BATCHES of that batch's own
 * scramble. Batches use independent scrambles, so their means are independent, unbiased
 * estimates (randomised QMC: Owen 1997; L'Ecuyer and Lemieux 2002's replicates): the variance of
 * their mean comes from the spread of the batch means (reference.c), not from the spread of
 * single samples, which overstates a low-discrepancy estimator's error. Within a batch, the
 * first 2^k samples of every set form a (0,k,2)-net: the index shuffle maps aligned blocks of 2^k
 * indices onto aligned blocks (its flips of index bit j depend only on higher bits; tested in
 * tests/reference/ref_sampler.c). */
#ifndef GIB_REF_SAMPLER_H
#define GIB_REF_SAMPLER_H

#include <stdint.h>

#include "reference/reference.h"
#include "rng.h"

typedef struct ref_rng {
    ref_pcg32 pcg;   /* GIB_REF_SAMPLER_RANDOM */
    uint64_t key;    /* sobol: hash of (pixel, batch, seed, component) */
    uint32_t index;  /* sobol: the sample's index within its batch */
    uint32_t set;    /* sobol: the next dimension set */
    int sobol;
} ref_rng;

static inline uint32_t ref_reverse_bits(uint32_t x)
{
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
}

/* Burley 2020, Listing 2 (after Laine and Karras 2011): a bijection in which bit p changes as a
 * function of bits below p only (adding the seed carries upward; x * even constant has bit p made
 * of bits below p). */
static inline uint32_t ref_lk_permutation(uint32_t x, uint32_t seed)
{
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/* Burley 2020, Listing 3: the nested uniform scramble of a 32-bit fraction (bit 31 the first
 * binary digit): each digit flipped as a function of the digits before it (Owen 1995). */
static inline uint32_t ref_owen_scramble(uint32_t x, uint32_t seed)
{
    return ref_reverse_bits(ref_lk_permutation(ref_reverse_bits(x), seed));
}

/* The first two dimensions of the Sobol sequence as 32-bit fractions (bit 31 the first digit).
 * Dimension 0 is the van der Corput sequence: the index's bits reversed. Dimension 1 has direction
 * numbers v_0 = 2^31, v_j = v_(j-1) xor (v_(j-1) >> 1) (primitive polynomial x + 1, Joe and Kuo's
 * first entry): v_j's digit d + 1 is C(j, d) mod 2, which by Lucas' theorem is 1 exactly when the
 * bits of d are a subset of those of j. So digit d + 1 of x1 is the xor of the index bits j whose
 * bits contain d's: a superset-xor transform over the 5-bit bit positions, five shift-and-mask
 * steps instead of a loop over 32 direction numbers (the loop is the test's reference). */
static inline uint32_t ref_sobol_dim1_reversed(uint32_t index)
{
    uint32_t z = index;
    z ^= (z >> 1) & 0x55555555u;
    z ^= (z >> 2) & 0x33333333u;
    z ^= (z >> 4) & 0x0f0f0f0fu;
    z ^= (z >> 8) & 0x00ff00ffu;
    z ^= (z >> 16) & 0x0000ffffu;
    return z; /* digit d + 1 at bit d: reversed */
}

static inline void ref_sobol2(uint32_t index, uint32_t *x0, uint32_t *x1)
{
    *x0 = ref_reverse_bits(index);
    *x1 = ref_reverse_bits(ref_sobol_dim1_reversed(index));
}

/* 32-bit fraction to [0, 1): its top 24 bits, exact in a float, never 1 (as ref_pcg32_float). */
static inline float ref_u32_float(uint32_t x)
{
    return (float)(x >> 8) * 0x1p-24f;
}

/* The point of dimension set `set` for (key, index), as 32-bit fractions; b only when want_b.
 * Owen scrambling a digit-reversed value is reversing the permutation of the raw one
 * (ref_owen_scramble(reverse(y)) = reverse(lk(y))), which saves two reversals per coordinate. */
static inline void ref_sobol_set(uint64_t key, uint32_t index, uint32_t set, uint32_t *a,
                                 uint32_t *b, int want_b)
{
    uint64_t h = ref_mix64(key ^ ((uint64_t)(set + 1) * 0xd1b54a32d192ed03ull));
    uint32_t idx = ref_owen_scramble(index, (uint32_t)h); /* the shuffle (Burley Sec. 4) */
    *a = ref_reverse_bits(ref_lk_permutation(idx, (uint32_t)(h >> 32)));
    if (want_b) {
        uint32_t seed_b = (uint32_t)(((h ^ (h >> 29)) * 0xbf58476d1ce4e5b9ull) >> 32);
        *b = ref_reverse_bits(ref_lk_permutation(ref_sobol_dim1_reversed(idx), seed_b));
    }
}

/* The sobol key of (pixel or stream, batch, seed, component). */
static inline uint64_t ref_sobol_key(uint64_t stream, uint32_t batch, uint64_t seed,
                                     int component)
{
    uint64_t h = ref_mix64(ref_mix64(ref_mix64(seed ^ 0x5851f42d4c957f2dull) ^ stream) ^
                           (uint64_t)(uint32_t)component);
    return ref_mix64(h ^ ((uint64_t)batch * 0x9e3779b97f4a7c15ull));
}

/* Sets r up for camera sample `sample` of pixel `pix`. */
static inline void ref_rng_seed_sample(ref_rng *r, int sampler, uint64_t pix, uint64_t sample,
                                       uint64_t seed, int component)
{
    r->sobol = sampler == GIB_REF_SAMPLER_SOBOL;
    r->set = 0;
    if (r->sobol) {
        uint32_t batch = (uint32_t)(sample % GIB_REF_SOBOL_BATCHES);
        r->index = (uint32_t)(sample / GIB_REF_SOBOL_BATCHES);
        r->key = ref_sobol_key(pix, batch, seed, component);
    } else {
        ref_pcg32_seed_sample(&r->pcg, pix, sample, seed, component);
    }
}

static inline float ref_rng_1d(ref_rng *r)
{
    if (!r->sobol)
        return ref_pcg32_float(&r->pcg);
    uint32_t a, b;
    ref_sobol_set(r->key, r->index, r->set++, &a, &b, 0);
    return ref_u32_float(a);
}

/* Two numbers stratified together (one dimension set); with PCG, two successive numbers. */
static inline void ref_rng_2d(ref_rng *r, float *u1, float *u2)
{
    if (!r->sobol) {
        *u1 = ref_pcg32_float(&r->pcg);
        *u2 = ref_pcg32_float(&r->pcg);
        return;
    }
    uint32_t a, b;
    ref_sobol_set(r->key, r->index, r->set++, &a, &b, 1);
    *u1 = ref_u32_float(a);
    *u2 = ref_u32_float(b);
}

#endif

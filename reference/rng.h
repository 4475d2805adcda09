/* gibench — the reference renderer's random numbers: PCG32 (O'Neill 2014, pcg32_random_r) seeded
 * per SAMPLE from a hash of (stream, sample index, seed, component); a stream is a pixel, or a
 * chunk of a light-tracing pass.
 *
 * Why per sample: ARCHITECTURE.md, "Reference renderer" asks for a rerun to give the same image bit for
 * bit. Each sample owns its generator, so which thread renders which row cannot change a single
 * bit, and sample N is the same number whether it is drawn in one go or in a later round of a
 * --target-noise run. */
#ifndef GIB_REF_RNG_H
#define GIB_REF_RNG_H

#include <stdint.h>

typedef struct ref_pcg32 {
    uint64_t state;
    uint64_t inc; /* stream selector, always odd */
} ref_pcg32;

/* splitmix64's finaliser (Steele et al. 2014): a bijective 64-bit mix, so distinct inputs never
 * collide and neighbouring pixels get unrelated seeds. */
static inline uint64_t ref_mix64(uint64_t z)
{
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static inline uint32_t ref_pcg32_next(ref_pcg32 *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ull + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((0u - rot) & 31u));
}

static inline void ref_pcg32_seed(ref_pcg32 *r, uint64_t initstate, uint64_t initseq)
{
    r->state = 0;
    r->inc = (initseq << 1u) | 1u;
    (void)ref_pcg32_next(r);
    r->state += initstate;
    (void)ref_pcg32_next(r);
}

/* The generator of one sample: state and stream both come from the hash, so two samples (or
 * pixels, seeds, components) share neither a sequence nor a shifted copy of one. Camera samples
 * use stream = pixel index; light passes use stream = REF_LIGHT_STREAM | chunk, sample = pass. */
#define REF_LIGHT_STREAM (1ull << 63)
static inline void ref_pcg32_seed_sample(ref_pcg32 *r, uint64_t stream, uint64_t sample,
                                         uint64_t seed, int component)
{
    uint64_t h = ref_mix64(ref_mix64(ref_mix64(seed) ^ stream) ^ (uint64_t)(uint32_t)component);
    h = ref_mix64(h ^ (sample * 0x9e3779b97f4a7c15ull));
    ref_pcg32_seed(r, h, ref_mix64(h ^ 0x2545f4914f6cdd1dull));
}

/* Uniform in [0, 1): the top 24 bits, so every value is exact in a float and 1 is never
 * returned. */
static inline float ref_pcg32_float(ref_pcg32 *r)
{
    return (float)(ref_pcg32_next(r) >> 8) * 0x1p-24f;
}

#endif

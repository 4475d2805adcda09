/* gibench — 64-bit FNV-1a content hashing, used for scene hashes and the reference cache key.
 * Not cryptographic: it detects changed inputs, not tampering. */
#ifndef GIB_HASH_H
#define GIB_HASH_H

#include <stddef.h>
#include <stdint.h>

#define GIB_HASH_INIT 0xcbf29ce484222325ull

uint64_t gib_hash_bytes(uint64_t h, const void *data, size_t n);
uint64_t gib_hash_str(uint64_t h, const char *s);       /* includes the terminating NUL */
uint64_t gib_hash_u64(uint64_t h, uint64_t v);
uint64_t gib_hash_f32(uint64_t h, float v);
/* Hashes a file's bytes; returns -1 (and leaves *h) when the file cannot be read. */
int gib_hash_file(uint64_t *h, const char *path);
/* 16 lowercase hex digits plus NUL. */
void gib_hash_hex(uint64_t h, char out[17]);

/* A 32-bit integer finaliser (xor-shift-multiply, constants of C. Wellons' lowbias32): well-mixed
 * bits from a counter, for noise that must be the same on every machine (synthetic test images). */
static inline uint32_t gib_hash_mix32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7FEB352Du;
    x ^= x >> 15;
    x *= 0x846CA68Bu;
    return x ^ (x >> 16);
}

#endif

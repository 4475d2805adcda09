#include "hash.h"

#include <stdio.h>
#include <string.h>

uint64_t gib_hash_bytes(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

uint64_t gib_hash_str(uint64_t h, const char *s)
{
    return gib_hash_bytes(h, s ? s : "", (s ? strlen(s) : 0) + 1);
}

uint64_t gib_hash_u64(uint64_t h, uint64_t v) { return gib_hash_bytes(h, &v, sizeof v); }

uint64_t gib_hash_f32(uint64_t h, float v)
{
    if (v == 0.0f)
        v = 0.0f; /* -0 and +0 hash alike */
    return gib_hash_bytes(h, &v, sizeof v);
}

int gib_hash_file(uint64_t *h, const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    unsigned char buf[1 << 16];
    size_t n;
    uint64_t acc = *h;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0)
        acc = gib_hash_bytes(acc, buf, n);
    int bad = ferror(f);
    fclose(f);
    if (bad)
        return -1;
    *h = acc;
    return 0;
}

void gib_hash_hex(uint64_t h, char out[17])
{
    snprintf(out, 17, "%016llx", (unsigned long long)h);
}

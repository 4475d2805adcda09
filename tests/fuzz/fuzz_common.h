/* gibench fuzz targets (libFuzzer, tests/fuzz/README.md): the project's parsers read files by
 * path, so each input is written to one temporary file per process and parsed from there, exactly
 * as gibench reads a user's file. */
#ifndef GIB_FUZZ_COMMON_H
#define GIB_FUZZ_COMMON_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The temporary files made so far, removed when the process exits normally. */
static char fuzz_temp_paths[4][512];

static inline void fuzz_temp_remove(void)
{
    for (int i = 0; i < 4; i++)
        if (fuzz_temp_paths[i][0])
            unlink(fuzz_temp_paths[i]);
}

/* Writes data to a per-process file ending in ext ("scene", "matrix", "exr"...) under $TMPDIR
 * (default /tmp); returns its path (static storage), or NULL when it cannot be written. */
static inline const char *fuzz_temp_file(const uint8_t *data, size_t size, const char *ext)
{
    static char path[512];
    const char *dir = getenv("TMPDIR");
    snprintf(path, sizeof path, "%s/gibench-fuzz-%ld.%s", dir && *dir ? dir : "/tmp", (long)getpid(),
             ext);
    int known = 0, free_slot = -1;
    for (int i = 0; i < 4; i++) {
        known |= !strcmp(fuzz_temp_paths[i], path);
        if (free_slot < 0 && !fuzz_temp_paths[i][0])
            free_slot = i;
    }
    if (!known && free_slot >= 0) {
        if (free_slot == 0)
            atexit(fuzz_temp_remove);
        snprintf(fuzz_temp_paths[free_slot], sizeof fuzz_temp_paths[0], "%s", path);
    }
    FILE *f = fopen(path, "wb");
    if (!f)
        return NULL;
    size_t w = size ? fwrite(data, 1, size, f) : 0;
    if (fclose(f) != 0 || w != size)
        return NULL;
    return path;
}

/* Inputs that stand for several files are parts separated by "####\n". Returns the next part of
 * [*p, end) with its length in *len and moves *p past its separator; after the last part (no
 * separator follows it) *p is NULL, and a call then returns an empty part at end. */
static inline const char *fuzz_next_part(const char **p, const char *end, size_t *len)
{
    const char *start = *p, *q = start;
    if (!start) {
        *len = 0;
        return end;
    }
    while (q + 5 <= end && memcmp(q, "####\n", 5) != 0)
        q++;
    if (q + 5 > end) {
        *len = (size_t)(end - start);
        *p = NULL;
    } else {
        *len = (size_t)(q - start);
        *p = q + 5;
    }
    return start;
}

#endif

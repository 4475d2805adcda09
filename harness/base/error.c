#include "error.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int gib_fail(gib_error *err, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
    }
    return -1;
}

int gib_error_prefix(gib_error *err, const char *fmt, ...)
{
    if (!err)
        return -1;
    char prefix[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(prefix, sizeof prefix, fmt, ap);
    va_end(ap);
    char old[sizeof err->msg];
    memcpy(old, err->msg, sizeof old);
    snprintf(err->msg, sizeof err->msg, "%.500s: %.1500s", prefix, old);
    return -1;
}

void *gib_calloc(size_t n, size_t size, gib_error *err)
{
    if (n == 0 || size == 0) {
        n = 1;
        size = 1;
    }
    void *p = calloc(n, size);
    if (!p)
        gib_fail(err, "out of memory allocating %zu x %zu bytes", n, size);
    return p;
}

void *gib_realloc_array(void *p, size_t n, size_t size, gib_error *err)
{
    if (size && n > SIZE_MAX / size) {
        gib_fail(err, "allocation of %zu x %zu bytes overflows", n, size);
        return NULL;
    }
    void *q = realloc(p, (n && size) ? n * size : 1);
    if (!q)
        gib_fail(err, "out of memory allocating %zu x %zu bytes", n, size);
    return q;
}

char *gib_strdup(const char *s)
{
    if (!s)
        return NULL;
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, s, n);
    return d;
}

#include "error.h"

#include "status.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void set_message(gib_error *err, gib_error_code code, const char *fmt, va_list ap)
{
    err->code = code;
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
}

int gib_fail(gib_error *err, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        set_message(err, GIB_ERR_FAILED, fmt, ap);
        va_end(ap);
    }
    return -1;
}

int gib_fail_code(gib_error *err, gib_error_code code, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        set_message(err, code, fmt, ap);
        va_end(ap);
    }
    return -1;
}

int gib_error_code_status(gib_error_code code)
{
    switch (code) {
    case GIB_ERR_OUT_OF_MEMORY: return GIB_STATUS_OUT_OF_MEMORY;
    case GIB_ERR_SHADER: return GIB_STATUS_SHADER_FAILED;
    case GIB_ERR_OVERFLOW: return GIB_STATUS_OVERFLOW;
    case GIB_ERR_NON_FINITE: return GIB_STATUS_NONFINITE;
    case GIB_ERR_REFERENCE: return GIB_STATUS_REFERENCE_FAILED;
    case GIB_ERR_NONE:
    case GIB_ERR_FAILED: break;
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
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                      "out of memory allocating %zu x %zu bytes", n, size);
    return p;
}

void *gib_realloc_array(void *p, size_t n, size_t size, gib_error *err)
{
    if (size && n > SIZE_MAX / size) {
        gib_fail_code(err, GIB_ERR_OVERFLOW, "allocation of %zu x %zu bytes overflows", n, size);
        return NULL;
    }
    void *q = realloc(p, (n && size) ? n * size : 1);
    if (!q)
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                      "out of memory allocating %zu x %zu bytes", n, size);
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

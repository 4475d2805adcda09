/* gibench — an external technique's timings.json (external.h; format in
 * examples/external_renderer/README.md):
 *
 *   {"gpu_ms": [1.9, 2.0, 2.1],          per timed frame, or one number (a median)
 *    "cpu_ms": [...],                    optional, the same
 *    "first_frame_ms": 35.0,             optional: the cold first frame (default: the command's
 *                                        wall time)
 *    "passes": {"trace": [1.2, 1.3], "denoise": 0.7},   optional, per pass as gpu_ms
 *    "memory_bytes": 12345678,           optional: the peak the renderer allocated
 *    "renderer": "NVIDIA H100 (Vulkan 1.3)",             optional: the rows' renderer column
 *    "counters": "rays=123;spp=4"}       optional: the rows' counters column
 *
 * A flat object read by key, not a general JSON parser: each key once, at the top level (the
 * names under "passes" aside). A value of the wrong type is an error, never a guessed number. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "external.h"

#define MAX_VALUES 4096

static const char *skip_ws(const char *p)
{
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')
        p++;
    return p;
}

/* The value after "key": (its first character), or NULL when the key is absent. */
static const char *find_key(const char *text, const char *key)
{
    char pat[80];
    snprintf(pat, sizeof pat, "\"%s\"", key);
    for (const char *p = strstr(text, pat); p; p = strstr(p + 1, pat)) {
        const char *q = skip_ws(p + strlen(pat));
        if (*q == ':')
            return skip_ws(q + 1);
    }
    return NULL;
}

/* A number or an array of numbers at p: up to max into v; returns their count, -1 if malformed;
 * *end gets the character after the value. */
static int parse_numbers(const char *p, double *v, int max, const char **end)
{
    char *e;
    if (*p != '[') {
        v[0] = strtod(p, &e);
        if (e == p || !isfinite(v[0]))
            return -1;
        *end = e;
        return 1;
    }
    int n = 0;
    p = skip_ws(p + 1);
    while (*p != ']') {
        if (n == max)
            return -1;
        v[n] = strtod(p, &e);
        if (e == p || !isfinite(v[n]))
            return -1;
        n++;
        p = skip_ws(e);
        if (*p == ',')
            p = skip_ws(p + 1);
        else if (*p != ']')
            return -1;
    }
    *end = p + 1;
    return n;
}

/* A JSON string at p (no escapes beyond \" and \\) into out. Returns 0, or -1 if malformed. */
static int parse_string(const char *p, char *out, size_t len, const char **end)
{
    if (*p != '"')
        return -1;
    size_t n = 0;
    for (p++; *p && *p != '"'; p++) {
        if (*p == '\\' && p[1])
            p++;
        if (n + 1 < len)
            out[n++] = *p;
    }
    out[n] = 0;
    if (*p != '"')
        return -1;
    *end = p + 1;
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median, min, max and interquartile range (quartiles interpolated) of n values. */
static void stats(double *v, int n, gib_pass_stats *s)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    double q[3];
    for (int k = 0; k < 3; k++) {
        double pos = (n - 1) * (k + 1) / 4.0;
        int i = (int)pos;
        q[k] = i + 1 < n ? v[i] + (pos - i) * (v[i + 1] - v[i]) : v[i];
    }
    s->median_ms = q[1];
    s->min_ms = v[0];
    s->max_ms = v[n - 1];
    s->iqr_ms = q[2] - q[0];
}

/* "name": numbers (times in ms) into s. Returns the count, 0 when absent, -1 when malformed. */
static int key_stats(const char *text, const char *key, gib_pass_stats *s, double *buf,
                     gib_error *err)
{
    const char *p = find_key(text, key), *end;
    if (!p)
        return 0;
    int n = parse_numbers(p, buf, MAX_VALUES, &end);
    if (n <= 0)
        return gib_fail(err, "timings.json: \"%s\" is not a finite number or a non-empty list of "
                        "them (at most %d)", key, MAX_VALUES);
    stats(buf, n, s);
    return n;
}

/* "passes": {"name": numbers, ...}. */
static int read_passes(const char *text, gib_run_result *r, double *buf, gib_error *err)
{
    const char *p = find_key(text, "passes"), *end;
    if (!p)
        return 0;
    if (*p != '{')
        return gib_fail(err, "timings.json: \"passes\" is not an object");
    p = skip_ws(p + 1);
    while (*p != '}') {
        if (r->pass_count == GIB_TIMER_MAX_PASSES)
            return gib_fail(err, "timings.json: more than %d passes", GIB_TIMER_MAX_PASSES);
        gib_pass_stats *s = &r->passes[r->pass_count];
        memset(s, 0, sizeof *s);
        if (parse_string(p, s->name, sizeof s->name, &end) < 0 || *(p = skip_ws(end)) != ':')
            return gib_fail(err, "timings.json: \"passes\": expected \"name\": ms");
        int n = parse_numbers(skip_ws(p + 1), buf, MAX_VALUES, &end);
        if (n <= 0)
            return gib_fail(err, "timings.json: pass \"%s\" is not a number or list of them",
                            s->name);
        stats(buf, n, s);
        s->first_ms = NAN;
        r->pass_count++;
        p = skip_ws(end);
        if (*p == ',')
            p = skip_ws(p + 1);
        else if (*p != '}')
            return gib_fail(err, "timings.json: \"passes\": expected , or }");
    }
    return 0;
}

/* The optional strings and numbers: renderer, counters, memory_bytes, first_frame_ms. */
static int read_scalars(const char *text, gib_run_result *r, gib_error *err)
{
    const char *p, *end;
    double v;
    if ((p = find_key(text, "renderer")) && parse_string(p, r->renderer, sizeof r->renderer,
                                                         &end) < 0)
        return gib_fail(err, "timings.json: \"renderer\" is not a string");
    if ((p = find_key(text, "counters")) && parse_string(p, r->counters, sizeof r->counters,
                                                         &end) < 0)
        return gib_fail(err, "timings.json: \"counters\" is not a string");
    if ((p = find_key(text, "memory_bytes"))) {
        if (parse_numbers(p, &v, 1, &end) != 1 || *p == '[' || v < 0)
            return gib_fail(err, "timings.json: \"memory_bytes\" is not a number >= 0");
        r->technique_bytes = (uint64_t)v;
    }
    if ((p = find_key(text, "first_frame_ms"))) {
        if (parse_numbers(p, &v, 1, &end) != 1 || *p == '[' || v < 0)
            return gib_fail(err, "timings.json: \"first_frame_ms\" is not a number >= 0");
        r->first_frame_ms = v;
    }
    return 0;
}

int gib_external_read_timings(const char *path, gib_run_result *r, gib_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return gib_fail(err, "cannot read %s", path);
    char *text = malloc(1 << 20);
    double *buf = malloc(MAX_VALUES * sizeof *buf);
    size_t n = text ? fread(text, 1, (1 << 20) - 1, f) : 0;
    fclose(f);
    int rc = -1;
    if (!text || !buf)
        gib_fail(err, "out of memory reading %s", path);
    else {
        text[n] = 0;
        int frames = key_stats(text, "gpu_ms", &r->gpu_total, buf, err);
        if (frames >= 0 && key_stats(text, "cpu_ms", &r->cpu_total, buf, err) >= 0 &&
            read_passes(text, r, buf, err) == 0 && read_scalars(text, r, err) == 0) {
            rc = 0;
            if (frames > 1)
                r->frames = frames;
        }
    }
    free(text);
    free(buf);
    return rc;
}

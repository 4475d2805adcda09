/* Fuzz target: the command line's values. The input is "technique\nname\nvalue\nsize\nnumber":
 * gib_param_set (`--param name=value` and a matrix's parameter values), gib_parse_size (`--size`),
 * gib_parse_int / gib_parse_float (every numeric option). A technique name that is not
 * registered is taken modulo the registry, so every technique's specs are reached. */
#include <string.h>

#include "harness/app/app.h"
#include "techniques/technique.h"

static const char *next_line(const char **p, const char *end, char *out, size_t cap)
{
    size_t n = 0;
    while (*p < end && **p != '\n') {
        if (n + 1 < cap)
            out[n++] = **p;
        (*p)++;
    }
    if (*p < end)
        (*p)++;
    out[n] = '\0';
    return out;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *p = (const char *)data, *end = p + size;
    char tech[128], name[128], value[256], sz[128], num[128];
    next_line(&p, end, tech, sizeof tech);
    next_line(&p, end, name, sizeof name);
    next_line(&p, end, value, sizeof value);
    next_line(&p, end, sz, sizeof sz);
    next_line(&p, end, num, sizeof num);
    int count = 0;
    const gib_technique *const *all = gib_techniques(&count);
    const gib_technique *t = gib_technique_find(tech);
    if (!t && count > 0)
        t = all[(unsigned char)tech[0] % count];
    gib_error err;
    if (t) {
        gib_params params;
        gib_params_default(t, &params);
        gib_param_set(t, &params, name, value, &err);
        for (int i = 0; t->params[i].name; i++) /* every accepted value lies in its range */
            if (params.values[i] < t->params[i].min || params.values[i] > t->params[i].max)
                __builtin_trap();
    }
    int w, h;
    if (gib_parse_size("--size", sz, &w, &h, &err) == 0 && (w <= 0 || h <= 0))
        __builtin_trap();
    long l;
    double d;
    gib_parse_int("--frames", num, 0, 1000, &l, &err);
    if (gib_parse_float("--time", num, -1e6, 1e6, &d, &err) == 0 && !(d >= -1e6 && d <= 1e6))
        __builtin_trap();
    return 0;
}

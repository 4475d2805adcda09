#include "every_technique.h"

#include "harness/app/technique_check.h"

#include <stdio.h>

int every_technique(const gib_technique **out, int max)
{
    int n = 0, count = 0;
    const gib_technique *const *run = gib_techniques(&count);
    for (int i = 0; i < count; i++, n++)
        if (n < max)
            out[n] = run[i];
    const gib_technique *const *tests = gib_techniques_test_only(&count);
    for (int i = 0; i < count; i++, n++)
        if (n < max)
            out[n] = tests[i];
    return n;
}

int technique_runs_on(const gib_technique *t, const gib_scene *s, char *why, size_t len)
{
    return gib_technique_runs_on(t, s, why, len); /* harness/app/technique_check.c */
}

#include "every_technique.h"

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
    char f[256];
    if ((s->features & t->scene_needs) != t->scene_needs) {
        gib_features_str(t->scene_needs & ~s->features, f, sizeof f);
        snprintf(why, len, "scene lacks %s", f);
        return 0;
    }
    if (t->scene_needs_any && !(s->features & t->scene_needs_any)) {
        gib_features_str(t->scene_needs_any, f, sizeof f);
        snprintf(why, len, "scene has none of %s", f);
        return 0;
    }
    return 1;
}

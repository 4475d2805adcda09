/* gibench list — techniques with their parameters and defaults, scenes with their features. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "harness/base/status.h"
#include "options.h"

static void print_components(unsigned bits)
{
    const char *names[] = {"ao", "direct", "indirect", "glossy", "caustic"};
    int first = 1;
    for (int i = 0; i < 5; i++)
        if (bits & (1u << i)) {
            printf("%s%s", first ? "" : ",", names[i]);
            first = 0;
        }
}

int gib_cmd_list(int argc, char **argv)
{
    static const gib_command_doc doc = {
        "list", "",
        "Prints every technique (its source, output components, passes and parameters with\n"
        "defaults and ranges), the statuses a result row can hold, and every scene file\n"
        "(availability and features).\n"};
    const gib_option none[] = {{0}};
    int rc = gib_options_parse(&doc, none, argc, argv, NULL, NULL, 0);
    if (rc != GIB_OPTIONS_PROCEED)
        return rc;
    int n;
    const gib_technique *const *all = gib_techniques(&n);
    puts("techniques:");
    for (int i = 0; i < n; i++) {
        const gib_technique *t = all[i];
        printf("  %-14s outputs ", t->name);
        print_components(t->components);
        printf("  — %s\n", t->source);
        if (gib_technique_origin(t))
            printf("      plugin: %s\n", gib_technique_origin(t));
        printf("      passes:");
        for (int k = 0; t->passes && t->passes[k]; k++)
            printf(" %s", t->passes[k]);
        putchar('\n');
        for (int k = 0; t->params && t->params[k].name; k++) {
            const gib_param_spec *p = &t->params[k];
            printf("      %-16s %-5s default %-8g [%g, %g]  %s\n", p->name,
                   p->type == GIB_PARAM_INT      ? "int"
                   : p->type == GIB_PARAM_LENGTH ? "len"
                                                 : "float",
                   p->def, p->min, p->max, p->help);
            for (int c = 0; p->choices && p->choices[c].name; c++)
                printf("%s%s = %g%s", c ? ", " : "                       values: ",
                       p->choices[c].name, p->choices[c].value, p->choices[c + 1].name ? "" : "\n");
            if (p->multiple_of > 1)
                printf("                       a multiple of %d\n", p->multiple_of);
        }
        for (int k = 0; t->rules && t->rules[k].rule; k++)
            printf("      rule (%s): %s\n", t->rules[k].params, t->rules[k].rule);
        for (int k = 0; t->presets && t->presets[k].name; k++)
            printf("      preset=%-9s %s\n          sets %s\n", t->presets[k].name,
                   t->presets[k].why, t->presets[k].values);
    }
    puts("statuses (a result row's `status`):");
    for (int s = 0; s < GIB_STATUS_COUNT; s++)
        printf("  %-20s %s\n", gib_status_name((gib_status)s), gib_status_doc((gib_status)s));
    gib_scene_info *infos = NULL;
    int count = 0;
    gib_error err;
    if (gib_scene_list(&infos, &count, &err) < 0) {
        fprintf(stderr, "gibench list: %s\n", err.msg);
        return 1;
    }
    const char *root = gib_scene_data_root();
    printf("scenes (scene files in %s; shared data in %s):\n", gib_scene_dir(),
           root ? root : "(none: set GIBENCH_SCENES)");
    for (int i = 0; i < count; i++) {
        if (!infos[i].available) {
            printf("  %-16s unavailable: %s\n", infos[i].name, infos[i].why_unavailable);
            continue;
        }
        gib_scene s;
        char feats[256] = "?";
        if (gib_scene_load(infos[i].name, &s, &err) == 0) {
            gib_features_str(s.features, feats, sizeof feats);
            printf("  %-16s %u triangles, %u lights, features: %s\n", infos[i].name,
                   s.triangle_count, s.light_count, feats);
            if (s.ignored[0]) /* a glTF's features gibench drops (scenes/FORMAT.md) */
                printf("  %-16s ignored: %s\n", "", s.ignored);
            gib_scene_free(&s);
        } else {
            printf("  %-16s error: %s\n", infos[i].name, err.msg);
        }
        if (infos[i].description[0])
            printf("  %-16s %s\n", "", infos[i].description);
    }
    free(infos);
    return 0;
}

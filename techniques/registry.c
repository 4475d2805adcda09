/* gibench — the list of techniques, and the parameter handling every technique shares.
 *
 * Two lists, and the techniques plugins add (gib_technique_register, harness/app/plugins.c). `registry` is what gibench runs: `gibench list`, matrices and gib_technique_find see
 * it and nothing else. `test_only` holds techniques that are compiled and tested like the others
 * but never benchmarked (the template a new technique is copied from): the tests that walk every
 * technique (tests/techniques/) walk both lists, through gib_techniques_test_only(). */
#include <stdio.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "technique.h"

extern const gib_technique gib_technique_direct;
extern const gib_technique gib_technique_hbao;
extern const gib_technique gib_technique_ldm_ao;
extern const gib_technique gib_technique_ldm_indirect;
extern const gib_technique gib_technique_ldm_env;
extern const gib_technique gib_technique_lrsm;
extern const gib_technique gib_technique_vct;
extern const gib_technique gib_technique_rsm_gather;
extern const gib_technique gib_technique_multires_ir;
extern const gib_technique gib_technique_ispm_caustics;
extern const gib_technique gib_technique_template;

static const gib_technique *const registry[] = {
    &gib_technique_direct,
    &gib_technique_hbao,
    &gib_technique_ldm_ao,
    &gib_technique_ldm_indirect,
    &gib_technique_ldm_env,
    &gib_technique_lrsm,
    &gib_technique_vct,
    &gib_technique_rsm_gather,
    &gib_technique_multires_ir,
    &gib_technique_ispm_caustics,
};

static const gib_technique *const test_only[] = {
    &gib_technique_template,
};

#define BUILTIN_COUNT ((int)(sizeof registry / sizeof registry[0]))

/* The built-in techniques then the plugins' (gib_technique_register, before any thread starts);
 * plugin_count 0: gib_techniques() hands out `registry` itself. */
static const gib_technique *with_plugins[BUILTIN_COUNT + GIB_MAX_PLUGIN_TECHNIQUES];
static const char *plugin_origin[GIB_MAX_PLUGIN_TECHNIQUES];
static int plugin_count;

const gib_technique *const *gib_techniques(int *count)
{
    *count = BUILTIN_COUNT + plugin_count;
    return plugin_count ? with_plugins : registry;
}

int gib_technique_register(const gib_technique *t, const char *origin, gib_error *err)
{
    if (!t || !t->name || !t->name[0])
        return gib_fail(err, "%s: a technique without a name", origin);
    for (int i = 0; i < BUILTIN_COUNT; i++)
        if (!strcmp(registry[i]->name, t->name))
            return gib_fail(err, "%s: technique '%s' has the name of a built-in technique",
                            origin, t->name);
    for (int i = 0; i < (int)(sizeof test_only / sizeof test_only[0]); i++)
        if (!strcmp(test_only[i]->name, t->name))
            return gib_fail(err, "%s: technique '%s' has the name of a built-in (test-only) "
                            "technique", origin, t->name);
    for (int i = 0; i < plugin_count; i++)
        if (!strcmp(with_plugins[BUILTIN_COUNT + i]->name, t->name))
            return gib_fail(err, "%s: technique '%s' is already loaded from %s", origin, t->name,
                            plugin_origin[i]);
    if (plugin_count >= GIB_MAX_PLUGIN_TECHNIQUES)
        return gib_fail(err, "%s: technique '%s': more than %d plugin techniques", origin, t->name,
                        GIB_MAX_PLUGIN_TECHNIQUES);
    if (!plugin_count)
        memcpy(with_plugins, registry, sizeof registry);
    plugin_origin[plugin_count] = origin;
    with_plugins[BUILTIN_COUNT + plugin_count++] = t;
    return 0;
}

const char *gib_technique_origin(const gib_technique *t)
{
    for (int i = 0; i < plugin_count; i++)
        if (with_plugins[BUILTIN_COUNT + i] == t)
            return plugin_origin[i];
    return NULL;
}

const gib_technique *const *gib_techniques_test_only(int *count)
{
    *count = (int)(sizeof test_only / sizeof test_only[0]);
    return test_only;
}

const gib_technique *gib_technique_find(const char *name)
{
    int n;
    const gib_technique *const *all = gib_techniques(&n);
    for (int i = 0; i < n; i++)
        if (!strcmp(all[i]->name, name))
            return all[i];
    return NULL;
}

int gib_param_index(const gib_technique *t, const char *name)
{
    for (int i = 0; t->params && t->params[i].name; i++)
        if (!strcmp(t->params[i].name, name))
            return i;
    return -1;
}

void gib_params_default(const gib_technique *t, gib_params *p)
{
    memset(p, 0, sizeof *p);
    for (int i = 0; t->params && t->params[i].name && i < GIB_MAX_PARAMS; i++) {
        p->values[i] = t->params[i].def;
        p->count = i + 1;
    }
}

static int preset_count(const gib_technique *t)
{
    int n = 0;
    while (t->presets && t->presets[n].name)
        n++;
    return n;
}

/* GIB_PRESET_PARAM's value: a preset's name (or its number). */
static int set_preset(const gib_technique *t, gib_params *p, int i, const char *value,
                      gib_error *err)
{
    int n = preset_count(t);
    char names[256] = GIB_PRESET_DEFAULT;
    for (int k = 0; k <= n; k++) {
        const char *name = k ? t->presets[k - 1].name : GIB_PRESET_DEFAULT;
        char num[16];
        snprintf(num, sizeof num, "%d", k);
        if (!strcmp(value, name) || !strcmp(value, num)) {
            p->values[i] = k;
            return 0;
        }
        if (k) {
            strncat(names, ", ", sizeof names - strlen(names) - 1);
            strncat(names, name, sizeof names - strlen(names) - 1);
        }
    }
    return gib_fail(err, "technique '%s': parameter '%s' = %s names no preset (it has: %s)",
                    t->name, GIB_PRESET_PARAM, value, names);
}

const char *gib_params_preset_name(const gib_technique *t, const gib_params *p)
{
    int i = gib_param_index(t, GIB_PRESET_PARAM);
    int k = i < 0 ? 0 : (int)p->values[i];
    return k > 0 && k <= preset_count(t) ? t->presets[k - 1].name : GIB_PRESET_DEFAULT;
}

int gib_preset_values(const gib_technique *t, const gib_preset *ps, int *index, double *value,
                      int max, gib_error *err)
{
    int preset_i = gib_param_index(t, GIB_PRESET_PARAM), n = 0;
    char text[1024];
    snprintf(text, sizeof text, "%s", ps->values);
    char *save = NULL;
    for (char *kv = strtok_r(text, ";", &save); kv; kv = strtok_r(NULL, ";", &save)) {
        char *eq = strchr(kv, '=');
        int pi = eq ? (*eq = 0, gib_param_index(t, kv)) : -1;
        if (pi < 0 || pi == preset_i || n >= max)
            return gib_fail(err, "technique '%s': preset '%s' sets '%s', which is no parameter of "
                            "it", t->name, ps->name, kv);
        gib_params one;
        gib_params_default(t, &one);
        if (gib_param_set(t, &one, kv, eq + 1, err) < 0)
            return gib_error_prefix(err, "preset '%s'", ps->name);
        index[n] = pi;
        value[n++] = one.values[pi];
    }
    return n;
}

int gib_params_apply_preset(const gib_technique *t, gib_params *p, const unsigned char *named,
                            gib_error *err)
{
    int i = gib_param_index(t, GIB_PRESET_PARAM);
    int k = i < 0 ? 0 : (int)p->values[i];
    if (k <= 0 || k > preset_count(t))
        return 0;
    int index[GIB_MAX_PARAMS];
    double value[GIB_MAX_PARAMS];
    int n = gib_preset_values(t, &t->presets[k - 1], index, value, GIB_MAX_PARAMS, err);
    for (int j = 0; j < n; j++)
        if (!named || !named[index[j]])
            p->values[index[j]] = value[j];
    return n < 0 ? -1 : 0;
}

const char *gib_param_choice_name(const gib_param_spec *s, double value)
{
    for (int k = 0; s->choices && s->choices[k].name; k++)
        if (s->choices[k].value == value)
            return s->choices[k].name;
    return NULL;
}

/* "algorithm1 = 0, planes = 1": a parameter's choices for an error message. */
static void list_choices(const gib_param_spec *s, char *out, size_t len)
{
    out[0] = 0;
    for (int k = 0; s->choices && s->choices[k].name; k++) {
        size_t used = strlen(out);
        snprintf(out + used, len - used, "%s%s = %g", k ? ", " : "", s->choices[k].name,
                 s->choices[k].value);
    }
}

/* One value against its spec: the range, the choices, the multiple. */
static int check_value(const gib_technique *t, const gib_param_spec *s, double v, gib_error *err)
{
    if (!(v >= s->min && v <= s->max))
        return gib_fail(err, "technique '%s': parameter '%s' = %g is outside [%g, %g] (%s)",
                        t->name, s->name, v, s->min, s->max, s->help);
    if (s->choices && !gib_param_choice_name(s, v)) {
        char names[256];
        list_choices(s, names, sizeof names);
        return gib_fail(err, "technique '%s': parameter '%s' = %g is none of its values (%s)",
                        t->name, s->name, v, names);
    }
    if (s->multiple_of > 1 && fmod(v, s->multiple_of) != 0)
        return gib_fail(err, "technique '%s': parameter '%s' = %g must be a multiple of %d (%s)",
                        t->name, s->name, v, s->multiple_of, s->help);
    return 0;
}

/* "hits = 1 (planes), backface = 0 (cosine)": the values a rule relates. */
static void rule_values(const gib_technique *t, const gib_params *p, const char *params, char *out,
                        size_t len)
{
    char names[256];
    snprintf(names, sizeof names, "%s", params);
    out[0] = 0;
    char *save = NULL;
    for (char *n = strtok_r(names, ",", &save); n; n = strtok_r(NULL, ",", &save)) {
        int i = gib_param_index(t, n);
        if (i < 0)
            continue;
        const char *choice = gib_param_choice_name(&t->params[i], p->values[i]);
        size_t used = strlen(out);
        snprintf(out + used, len - used, "%s%s = %g%s%s%s", used ? ", " : "", n, p->values[i],
                 choice ? " (" : "", choice ? choice : "", choice ? ")" : "");
    }
}

int gib_params_check(const gib_technique *t, const gib_params *p, gib_error *err)
{
    for (int i = 0; t->params && t->params[i].name && i < p->count; i++)
        if (strcmp(t->params[i].name, GIB_PRESET_PARAM) &&
            check_value(t, &t->params[i], p->values[i], err) < 0)
            return -1;
    for (int r = 0; t->rules && t->rules[r].rule; r++)
        if (!t->rules[r].holds(t, p)) {
            char values[512];
            rule_values(t, p, t->rules[r].params, values, sizeof values);
            return gib_fail(err, "technique '%s': %s break a rule: %s", t->name, values,
                            t->rules[r].rule);
        }
    return 0;
}

/* A choice's name, or NAN when value names none of them. */
static double choice_value(const gib_param_spec *s, const char *value)
{
    for (int k = 0; s->choices && s->choices[k].name; k++)
        if (!strcmp(s->choices[k].name, value))
            return s->choices[k].value;
    return NAN;
}

int gib_param_set(const gib_technique *t, gib_params *p, const char *name, const char *value,
                  gib_error *err)
{
    int i = gib_param_index(t, name);
    if (i < 0) {
        char known[512] = "";
        for (int k = 0; t->params && t->params[k].name; k++) {
            strncat(known, k ? ", " : "", sizeof known - strlen(known) - 1);
            strncat(known, t->params[k].name, sizeof known - strlen(known) - 1);
        }
        return gib_fail(err, "technique '%s' has no parameter '%s' (it has: %s)", t->name, name,
                        known[0] ? known : "none");
    }
    const gib_param_spec *s = &t->params[i];
    if (!strcmp(name, GIB_PRESET_PARAM))
        return set_preset(t, p, i, value, err);
    char *end = NULL;
    errno = 0;
    double v = choice_value(s, value);
    if (!isnan(v))
        end = NULL;
    else if (!strcmp(value, "inf") || !strcmp(value, "unbounded"))
        v = INFINITY;
    else
        v = strtod(value, &end);
    if (end && (end == value || *end || errno)) {
        char names[256];
        list_choices(s, names, sizeof names);
        return gib_fail(err, "technique '%s': parameter '%s' expects %s%s%s, got '%s'", t->name,
                        name, names[0] ? "one of its values (" : "a number", names,
                        names[0] ? ")" : "", value);
    }
    if (s->type == GIB_PARAM_INT && (v != floor(v) || isinf(v)))
        return gib_fail(err, "technique '%s': parameter '%s' expects an integer, got '%s'",
                        t->name, name, value);
    if (check_value(t, s, v, err) < 0)
        return -1;
    p->values[i] = v;
    return 0;
}

static int declared_index(const gib_technique *t, const char *name)
{
    int i = gib_param_index(t, name);
    if (i < 0) {
        fprintf(stderr, "gibench: technique '%s' reads parameter '%s', which it does not declare\n",
                t->name, name);
        abort();
    }
    return i;
}

int gib_param_int(const gib_technique *t, const gib_params *p, const char *name)
{
    return (int)p->values[declared_index(t, name)];
}

double gib_param_float(const gib_technique *t, const gib_params *p, const char *name)
{
    return p->values[declared_index(t, name)];
}

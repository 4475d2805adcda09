/* Every technique's descriptor against the contract of techniques/technique.h: parameter specs
 * that the CLI and matrices can rely on, reference bindings that name real parameters, and
 * gib_param_int/float stopping the process on an undeclared name in every build (this test is
 * compiled with NDEBUG in the release build, where the old assert did nothing). The test-only
 * techniques (the template) are held to the same rules, and stay out of what gibench runs: not
 * in gib_techniques(), not found by name. Presets set what they say and are named back. Choices,
 * multiples and rules between parameters are refused before any GL. No GL needed. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "techniques/technique.h"
#include "tests/techniques/every_technique.h"

static int failures;
#include "tests/common/check.h"

static const unsigned all_outputs =
    GIB_OUT_AO | GIB_OUT_DIRECT | GIB_OUT_INDIRECT | GIB_OUT_GLOSSY | GIB_OUT_CAUSTIC;

static void check_params(const gib_technique *t)
{
    int n = 0;
    for (; t->params && t->params[n].name; n++) {
        const gib_param_spec *s = &t->params[n];
        CHECK(s->name[0], "%s: parameter %d has an empty name", t->name, n);
        CHECK(s->type == GIB_PARAM_INT || s->type == GIB_PARAM_FLOAT || s->type == GIB_PARAM_LENGTH,
              "%s.%s: unknown type %d", t->name, s->name, s->type);
        CHECK(s->help && s->help[0], "%s.%s: no help text", t->name, s->name);
        CHECK(s->min <= s->max, "%s.%s: range [%g, %g] is empty", t->name, s->name, s->min, s->max);
        CHECK(s->def >= s->min && s->def <= s->max, "%s.%s: default %g outside [%g, %g]", t->name,
              s->name, s->def, s->min, s->max);
        if (s->type == GIB_PARAM_INT)
            CHECK(s->def == floor(s->def) && !isinf(s->def), "%s.%s: integer with default %g",
                  t->name, s->name, s->def);
        for (int k = 0; k < n; k++)
            CHECK(strcmp(t->params[k].name, s->name), "%s: parameter '%s' declared twice", t->name,
                  s->name);
    }
    /* gib_params holds GIB_MAX_PARAMS values in spec order. */
    CHECK(n <= GIB_MAX_PARAMS, "%s: %d parameters, at most %d", t->name, n, GIB_MAX_PARAMS);
    gib_params p;
    gib_params_default(t, &p);
    CHECK(p.count == n, "%s: defaults fill %d values for %d parameters", t->name, p.count, n);
}

/* Its passes declared: at least one, each a non-empty name [a-z0-9_]+, none twice. */
static void check_passes(const gib_technique *t)
{
    int n = 0;
    for (; t->passes && t->passes[n]; n++) {
        const char *name = t->passes[n];
        CHECK(name[0] && strspn(name, "abcdefghijklmnopqrstuvwxyz0123456789_") == strlen(name),
              "%s: pass name '%s' is not [a-z0-9_]+", t->name, name);
        for (int k = 0; k < n; k++)
            CHECK(strcmp(t->passes[k], name), "%s: pass '%s' declared twice", t->name, name);
    }
    CHECK(n > 0, "%s: no passes declared", t->name);
}

static void check_reference(const gib_technique *t)
{
    int binds_dmax = 0;
    for (const gib_ref_binding *b = t->reference; b && b->setting != GIB_REF_END; b++) {
        int i = gib_param_index(t, b->param);
        CHECK(i >= 0, "%s: reference binding names parameter '%s', which it does not declare",
              t->name, b->param);
        CHECK(b->components && !(b->components & ~t->components),
              "%s: binding of '%s' for components 0x%x, technique outputs 0x%x", t->name, b->param,
              b->components, t->components);
        CHECK(b->setting == GIB_REF_AO_DMAX || b->setting == GIB_REF_AO_OBSCURANCE,
              "%s: binding of '%s' to unknown setting %d", t->name, b->param, b->setting);
        if (b->setting == GIB_REF_AO_DMAX || b->setting == GIB_REF_AO_OBSCURANCE)
            CHECK(b->components == GIB_OUT_AO, "%s: an ao setting bound for components 0x%x",
                  t->name, b->components);
        if (b->setting == GIB_REF_AO_DMAX && i >= 0) {
            binds_dmax = 1;
            /* a distance in scene units: a matrix's [scene_scale] must scale it with the scene */
            CHECK(t->params[i].type == GIB_PARAM_LENGTH, "%s: dmax bound to '%s', not a length",
                  t->name, b->param);
        }
        if (b->setting == GIB_REF_AO_OBSCURANCE && i >= 0)
            CHECK(t->params[i].type == GIB_PARAM_INT && t->params[i].min >= 0 &&
                      t->params[i].max <= 1,
                  "%s: obscurance bound to '%s', which is not a 0/1 switch", t->name, b->param);
    }
    if (t->components & GIB_OUT_AO)
        CHECK(binds_dmax, "%s outputs ao but binds no parameter to the reference's dmax", t->name);
}

/* Runs f in a child and reports whether it died of SIGABRT with the expected message. */
static int aborts_naming(const gib_technique *t, int as_float, const char *name)
{
    int fds[2];
    if (pipe(fds) < 0)
        return 0;
    pid_t pid = fork();
    if (pid == 0) {
        dup2(fds[1], 2);
        gib_params p;
        gib_params_default(t, &p);
        volatile double v = as_float ? gib_param_float(t, &p, name) : gib_param_int(t, &p, name);
        (void)v;
        _exit(0);
    }
    close(fds[1]);
    char msg[512] = "";
    ssize_t got = read(fds[0], msg, sizeof msg - 1);
    msg[got > 0 ? got : 0] = 0;
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT && strstr(msg, t->name) &&
           strstr(msg, name);
}

/* A test-only technique is checked like the others but gibench never sees it. */
static void check_test_only(void)
{
    int count = 0, n = 0;
    const gib_technique *const *tests = gib_techniques_test_only(&count);
    const gib_technique *const *run = gib_techniques(&n);
    CHECK(count > 0, "no test-only technique (the template)");
    for (int i = 0; i < count; i++) {
        CHECK(!gib_technique_find(tests[i]->name), "test-only '%s' is found by name",
              tests[i]->name);
        for (int k = 0; k < n; k++)
            CHECK(run[k] != tests[i] && strcmp(run[k]->name, tests[i]->name),
                  "test-only '%s' is among the techniques gibench runs", tests[i]->name);
    }
}

/* A technique's presets: a technique with presets declares GIB_PRESET_PARAM over exactly their
 * numbers; each preset's values are parameters of it within their ranges, not the preset itself;
 * applied, a preset sets each of its values, leaves a parameter set explicitly as it was, and is
 * named back; a name that is no preset is refused naming the ones there are. */
static void check_presets(const gib_technique *t)
{
    int n = 0;
    while (t->presets && t->presets[n].name)
        n++;
    int pi = gib_param_index(t, GIB_PRESET_PARAM);
    CHECK(n == 0 ? pi < 0 : pi >= 0 && t->params[pi].type == GIB_PARAM_INT &&
                                t->params[pi].def == 0 && t->params[pi].min == 0 &&
                                t->params[pi].max == n,
          "%s: %d presets but parameter '%s' %s", t->name, n, GIB_PRESET_PARAM,
          pi < 0 ? "undeclared" : "not an integer over [0, presets] with default 0");
    for (int k = 0; k < n && pi >= 0; k++) {
        const gib_preset *ps = &t->presets[k];
        CHECK(strcmp(ps->name, GIB_PRESET_DEFAULT) && ps->why && ps->why[0],
              "%s: preset %d is named '%s' or says nothing of itself", t->name, k, ps->name);
        gib_params p, kept;
        gib_error err = {0};
        gib_params_default(t, &p);
        CHECK(gib_param_set(t, &p, GIB_PRESET_PARAM, ps->name, &err) == 0 &&
                  gib_params_apply_preset(t, &p, NULL, &err) == 0,
              "%s: preset '%s' does not apply: %s", t->name, ps->name, err.msg);
        CHECK(!strcmp(gib_params_preset_name(t, &p), ps->name), "%s: preset '%s' named back as '%s'",
              t->name, ps->name, gib_params_preset_name(t, &p));
        int index[GIB_MAX_PARAMS];
        double value[GIB_MAX_PARAMS];
        int nv = gib_preset_values(t, ps, index, value, GIB_MAX_PARAMS, &err);
        CHECK(nv > 0, "%s: preset '%s' sets nothing, or what it sets is refused: %s", t->name,
              ps->name, err.msg);
        for (int j = 0; j < nv; j++) {
            const gib_param_spec *spec = &t->params[index[j]];
            CHECK(value[j] >= spec->min && value[j] <= spec->max && p.values[index[j]] == value[j],
                  "%s: preset '%s' gives %s = %g, not its %g", t->name, ps->name, spec->name,
                  p.values[index[j]], value[j]);
            /* named explicitly, the parameter keeps the value it was set to */
            unsigned char named[GIB_MAX_PARAMS] = {0};
            gib_params_default(t, &kept);
            gib_param_set(t, &kept, GIB_PRESET_PARAM, ps->name, &err);
            named[index[j]] = 1;
            CHECK(gib_params_apply_preset(t, &kept, named, &err) == 0 &&
                      kept.values[index[j]] == spec->def,
                  "%s: preset '%s' overrode %s, which was set explicitly", t->name, ps->name,
                  spec->name);
        }
    }
    if (pi >= 0) {
        gib_params p;
        gib_error err = {0};
        gib_params_default(t, &p);
        CHECK(gib_param_set(t, &p, GIB_PRESET_PARAM, "no_such_preset", &err) < 0 &&
                  strstr(err.msg, "no_such_preset") && (n == 0 || strstr(err.msg, t->presets[0].name)),
              "%s: an unknown preset accepted, or refused without naming the presets: %s", t->name,
              err.msg);
        CHECK(!strcmp(gib_params_preset_name(t, &p), GIB_PRESET_DEFAULT), "%s: defaults named '%s'",
              t->name, gib_params_preset_name(t, &p));
    }
}

/* A technique's own constraints: every choice a distinct, in-range value accepted by its name and
 * its number; the defaults and every preset satisfy every rule (a rule the defaults break would
 * refuse every run), and each rule names parameters the technique declares. */
static void check_constraints(const gib_technique *t)
{
    for (int i = 0; t->params && t->params[i].name; i++) {
        const gib_param_spec *s = &t->params[i];
        for (int k = 0; s->choices && s->choices[k].name; k++) {
            gib_params p;
            gib_error err = {0};
            gib_params_default(t, &p);
            CHECK(gib_param_set(t, &p, s->name, s->choices[k].name, &err) == 0 &&
                      p.values[i] == s->choices[k].value,
                  "%s: %s = %s not accepted as %g: %s", t->name, s->name, s->choices[k].name,
                  s->choices[k].value, err.msg);
            for (int j = 0; j < k; j++)
                CHECK(s->choices[j].value != s->choices[k].value &&
                          strcmp(s->choices[j].name, s->choices[k].name),
                      "%s: %s has two choices alike", t->name, s->name);
        }
        CHECK(!s->choices || gib_param_choice_name(s, s->def), "%s: %s's default is no choice",
              t->name, s->name);
        CHECK(s->multiple_of <= 1 || (s->type == GIB_PARAM_INT && fmod(s->def, s->multiple_of) == 0),
              "%s: %s's default %g is no multiple of %d", t->name, s->name, s->def, s->multiple_of);
    }
    for (int r = 0; t->rules && t->rules[r].rule; r++) {
        char names[256];
        snprintf(names, sizeof names, "%s", t->rules[r].params);
        char *save = NULL;
        for (char *n = strtok_r(names, ",", &save); n; n = strtok_r(NULL, ",", &save))
            CHECK(gib_param_index(t, n) >= 0, "%s: rule '%s' names '%s', no parameter of it",
                  t->name, t->rules[r].rule, n);
        CHECK(t->rules[r].holds != NULL, "%s: rule '%s' has no test", t->name, t->rules[r].rule);
    }
    for (int k = 0; k <= 0 || (t->presets && t->presets[k - 1].name); k++) {
        gib_params p;
        gib_error err = {0};
        gib_params_default(t, &p);
        if (k > 0) {
            gib_param_set(t, &p, GIB_PRESET_PARAM, t->presets[k - 1].name, &err);
            gib_params_apply_preset(t, &p, NULL, &err);
        }
        CHECK(gib_params_check(t, &p, &err) == 0, "%s: preset '%s' breaks its own rules: %s",
              t->name, k ? t->presets[k - 1].name : GIB_PRESET_DEFAULT, err.msg);
    }
}

/* The three kinds of constraint, each refused with no GL and no scene, the error naming the
 * parameter(s), the value(s) and what they break: a value outside an enumeration, an integer no
 * multiple of its step, a combination a rule forbids. */
static void refused(const char *tech, const char *const *kv, const char *want1, const char *want2)
{
    const gib_technique *t = gib_technique_find(tech);
    CHECK_TRUE("technique registered", t != NULL, tech);
    if (!t)
        return;
    gib_params p;
    gib_error err = {0};
    gib_params_default(t, &p);
    int rc = 0;
    for (int i = 0; kv[i] && rc == 0; i += 2)
        rc = gib_param_set(t, &p, kv[i], kv[i + 1], &err);
    if (rc == 0)
        rc = gib_params_check(t, &p, &err);
    char what[96];
    snprintf(what, sizeof what, "%s %s=%s refused", tech, kv[0], kv[1]);
    CHECK_TRUE(what, rc < 0 && strstr(err.msg, want1) && strstr(err.msg, want2), err.msg);
}

static void check_refusals(void)
{
    refused("ispm_caustics", (const char *const[]){"layers", "2", NULL}, "'layers' = 2",
            "lists = 0, peeled = 4");
    refused("lrsm", (const char *const[]){"hits", "rays", NULL}, "'hits'", "algorithm1 = 0");
    refused("lrsm", (const char *const[]){"rsm_res", "513", NULL}, "'rsm_res' = 513",
            "multiple of 2");
    refused("lrsm", (const char *const[]){"hits", "planes", "backface", "cosine", NULL},
            "backface = 0 (cosine)", "act only with hits = algorithm1");
    refused("lrsm", (const char *const[]){"coverage", "0", NULL}, "coverage = 0",
            "act only with hits = algorithm1");
    refused("ispm_caustics", (const char *const[]){"rsm_res", "16", "mask_level", "5", NULL},
            "mask_level = 5", "rsm_res >> mask_level >= 1");
    refused("ldm_ao", (const char *const[]){"obscurance", "1", NULL}, "dmax = inf",
            "finite dmax > 0");
    /* the same values the rule forbids with hits = planes are fine with hits = algorithm1 */
    const gib_technique *t = gib_technique_find("lrsm");
    gib_params p;
    gib_error err = {0};
    gib_params_default(t, &p);
    CHECK_TRUE("lrsm hits=algorithm1 backface=cosine accepted",
               gib_param_set(t, &p, "hits", "algorithm1", &err) == 0 &&
                   gib_param_set(t, &p, "backface", "cosine", &err) == 0 &&
                   gib_params_check(t, &p, &err) == 0 && p.values[gib_param_index(t, "hits")] == 0,
               err.msg);
}

int main(void)
{
    const gib_technique *all[EVERY_TECHNIQUE_MAX];
    int count = every_technique(all, EVERY_TECHNIQUE_MAX), run = 0;
    gib_techniques(&run);
    CHECK(run > 0, "empty registry");
    CHECK(count <= EVERY_TECHNIQUE_MAX, "%d techniques, the test holds %d", count,
          EVERY_TECHNIQUE_MAX);
    for (int i = 0; i < count && i < EVERY_TECHNIQUE_MAX; i++) {
        const gib_technique *t = all[i];
        CHECK(t->name && t->name[0] && t->source && t->source[0], "technique %d: no name or source",
              i);
        CHECK(t->components && !(t->components & ~all_outputs), "%s: components 0x%x", t->name,
              t->components);
        CHECK(t->create && t->render && t->destroy, "%s: missing create/render/destroy", t->name);
        if (i < run)
            CHECK(gib_technique_find(t->name) == t, "%s: not found by its name", t->name);
        for (int k = 0; k < i; k++)
            CHECK(strcmp(all[k]->name, t->name), "technique '%s' registered twice", t->name);
        check_params(t);
        check_passes(t);
        check_reference(t);
        check_presets(t);
        check_constraints(t);
    }
    check_test_only();
    check_refusals();
    /* An undeclared name stops the process (the release build has NDEBUG: no assert). */
    const gib_technique *t = all[0];
    CHECK(aborts_naming(t, 0, "no_such_parameter"), "gib_param_int on an unknown name went on");
    CHECK(aborts_naming(t, 1, "no_such_parameter"), "gib_param_float on an unknown name went on");
    if (t->params && t->params[0].name)
        CHECK(!aborts_naming(t, 1, t->params[0].name), "a declared name stopped the process");
    printf("%d techniques checked (%d test-only): %s\n", count, count - run,
           failures ? "FAILED" : "ok");
    return failures ? 1 : 0;
}

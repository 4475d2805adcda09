/* gibench — the checks every technique is held to (technique_check.h): moved here from
 * tests/techniques/test_registry.c and test_contract_gl.c so that those tests and `gibench
 * check-technique` run the same code over built-in and plugin techniques. */
#include "technique_check.h"

#include <glad/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "harness/gl/timers.h"
#include "harness/gl/view.h"

/* One check: counts and prints a FAIL line when cond is false. `failures` and `out` are locals. */
#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            failures++;                                                                            \
            fprintf(out, "FAIL ");                                                                 \
            fprintf(out, __VA_ARGS__);                                                             \
            fputc('\n', out);                                                                      \
        }                                                                                          \
    } while (0)

static const unsigned all_outputs =
    GIB_OUT_AO | GIB_OUT_DIRECT | GIB_OUT_INDIRECT | GIB_OUT_GLOSSY | GIB_OUT_CAUSTIC;

static int check_basics(const gib_technique *t, FILE *out)
{
    int failures = 0;
    CHECK(t->name && t->name[0] && t->source && t->source[0], "technique: no name or source");
    const char *name = t->name ? t->name : "?";
    CHECK(t->components && !(t->components & ~all_outputs), "%s: components 0x%x", name,
          t->components);
    CHECK(t->create && t->render && t->destroy, "%s: missing create/render/destroy", name);
    return failures;
}

static int check_params(const gib_technique *t, FILE *out)
{
    int failures = 0, n = 0;
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
    return failures;
}

/* Its passes declared: at least one, each a non-empty name [a-z0-9_]+, none twice. */
static int check_passes(const gib_technique *t, FILE *out)
{
    int failures = 0, n = 0;
    for (; t->passes && t->passes[n]; n++) {
        const char *name = t->passes[n];
        CHECK(name[0] && strspn(name, "abcdefghijklmnopqrstuvwxyz0123456789_") == strlen(name),
              "%s: pass name '%s' is not [a-z0-9_]+", t->name, name);
        for (int k = 0; k < n; k++)
            CHECK(strcmp(t->passes[k], name), "%s: pass '%s' declared twice", t->name, name);
    }
    CHECK(n > 0, "%s: no passes declared", t->name);
    return failures;
}

static int check_reference(const gib_technique *t, FILE *out)
{
    int failures = 0, binds_dmax = 0;
    for (const gib_ref_binding *b = t->reference; b && b->setting != GIB_REF_END; b++) {
        int i = b->param ? gib_param_index(t, b->param) : -1;
        CHECK(i >= 0, "%s: reference binding names parameter '%s', which it does not declare",
              t->name, b->param ? b->param : "(null)");
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
    return failures;
}

/* A technique's presets: a technique with presets declares GIB_PRESET_PARAM over exactly their
 * numbers; each preset's values are parameters of it within their ranges, not the preset itself;
 * applied, a preset sets each of its values, leaves a parameter set explicitly as it was, and is
 * named back; a name that is no preset is refused naming the ones there are. */
static int check_presets(const gib_technique *t, FILE *out)
{
    int failures = 0, n = 0;
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
    return failures;
}

/* A technique's own constraints: every choice a distinct, in-range value accepted by its name and
 * its number; the defaults and every preset satisfy every rule (a rule the defaults break would
 * refuse every run), and each rule names parameters the technique declares. */
static int check_constraints(const gib_technique *t, FILE *out)
{
    int failures = 0;
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
        snprintf(names, sizeof names, "%s", t->rules[r].params ? t->rules[r].params : "");
        char *save = NULL;
        for (char *n = strtok_r(names, ",", &save); n; n = strtok_r(NULL, ",", &save))
            CHECK(gib_param_index(t, n) >= 0, "%s: rule '%s' names '%s', no parameter of it",
                  t->name, t->rules[r].rule, n);
        CHECK(t->rules[r].holds != NULL, "%s: rule '%s' has no test", t->name, t->rules[r].rule);
    }
    for (int r = 0; t->rules && t->rules[r].rule; r++)
        if (!t->rules[r].holds)
            return failures; /* gib_params_check would call it */
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
    return failures;
}

/* Prints a group's PASS line when verbose; returns its failures. */
static int group(const gib_technique *t, const char *what, int failures, FILE *out, int verbose)
{
    if (verbose)
        fprintf(out, "%s %s descriptor: %s\n", failures ? "FAIL" : "PASS", t->name, what);
    return failures;
}

int gib_check_descriptor(const gib_technique *t, FILE *out, int verbose)
{
    int failures = check_basics(t, out);
    if (!t->name)
        return failures;
    group(t, "name, source, components, create/render/destroy", failures, out, verbose);
    failures += group(t, "params", check_params(t, out), out, verbose);
    failures += group(t, "passes", check_passes(t, out), out, verbose);
    failures += group(t, "reference bindings", check_reference(t, out), out, verbose);
    failures += group(t, "presets", check_presets(t, out), out, verbose);
    failures += group(t, "choices, multiples and rules", check_constraints(t, out), out, verbose);
    return failures;
}

/* ---- at run time ---- */

int gib_counters_parse(const char *s)
{
    while (*s) {
        const char *name = s;
        while ((*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') || *s == '_')
            s++;
        if (s == name || *s++ != '=')
            return 0;
        char *end;
        strtod(s, &end);
        if (end == s || (*end && *end != ';'))
            return 0;
        s = *end ? end + 1 : end;
        if (*end && !*s)
            return 0; /* a trailing ';' */
    }
    return 1;
}

int gib_technique_runs_on(const gib_technique *t, const gib_scene *s, char *why, size_t len)
{
    char f[256];
    if ((s->features & t->scene_needs) != t->scene_needs) {
        gib_features_str(t->scene_needs & ~s->features, f, sizeof f);
        snprintf(why, len, "scene lacks %.200s", f);
        return 0;
    }
    if (t->scene_needs_any && !(s->features & t->scene_needs_any)) {
        gib_features_str(t->scene_needs_any, f, sizeof f);
        snprintf(why, len, "scene has none of %.200s", f);
        return 0;
    }
    return 1;
}

static const char *const SCENES[GIB_CHECK_SCENE_COUNT] = {"furnace", "plane_box_sky", "ring"};
static const int SIZES[2][2] = {{32, 24}, {48, 40}};
#define FRAMES 2
#define MAX_TARGETS 5

void gib_check_scenes_free(gib_check_scenes *s)
{
    for (int i = 0; i < GIB_CHECK_SCENE_COUNT; i++)
        if (s->state[i] > 0) {
            gib_gpu_scene_free(&s->gpu[i]);
            gib_scene_free(&s->scene[i]);
            s->state[i] = 0;
        }
}

/* The first scene of SCENES t accepts, loaded on first use: its index, or -1 (printed). */
static int scene_for(const gib_technique *t, gib_check_scenes *s, FILE *out, int *failures)
{
    char why[GIB_CHECK_SCENE_COUNT][256];
    for (int i = 0; i < GIB_CHECK_SCENE_COUNT; i++) {
        if (s->state[i] == 0) {
            gib_error err;
            int rc = gib_scene_load(SCENES[i], &s->scene[i], &err);
            if (rc == 0 && gib_gpu_scene_upload(&s->scene[i], &s->gpu[i], &err) < 0) {
                gib_scene_free(&s->scene[i]);
                rc = -1;
            }
            s->state[i] = rc == 0 ? 1 : -1;
            if (rc < 0) {
                ++*failures;
                fprintf(out, "FAIL scene %s: %s\n", SCENES[i], err.msg);
            }
        }
        if (s->state[i] > 0 && gib_technique_runs_on(t, &s->scene[i], why[i], sizeof why[i]))
            return i;
        if (s->state[i] < 0)
            snprintf(why[i], sizeof why[i], "not loaded");
    }
    fprintf(out, "SKIP %s: no test scene it runs on (", t->name);
    for (int i = 0; i < GIB_CHECK_SCENE_COUNT; i++)
        fprintf(out, "%s%s: %s", i ? "; " : "", SCENES[i], why[i]);
    fprintf(out, ")\n");
    return -1;
}

/* The output targets the runner would hand the technique (harness/app/runner.c), in a ledger of
 * their own. Returns the count, or -1. */
static int make_targets(unsigned components, int w, int h, gib_ledger *ledger,
                        gib_image_target *targets, gib_error *err)
{
    unsigned depth = gib_gpu_renderbuffer(ledger, "output.depth", GL_DEPTH_COMPONENT24, w, h, err);
    if (!depth)
        return -1;
    int n = 0;
    for (unsigned bit = 1; bit && n < MAX_TARGETS; bit <<= 1) {
        if (!(components & bit))
            continue;
        unsigned tex = gib_gpu_texture(ledger, "output.color", GL_TEXTURE_2D, w, h, 1, GL_RGBA32F,
                                       1, err);
        if (!tex)
            return -1;
        unsigned fbo = 0;
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
        glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
        const float zero[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero);
        targets[n++] = (gib_image_target){.component = bit, .fbo = fbo, .texture = tex};
    }
    return n;
}

/* Non-finite RGB values over the targets. */
static long nonfinite_outputs(const gib_image_target *targets, int n, int w, int h)
{
    float *rgba = malloc((size_t)w * h * 16);
    long bad = 0;
    for (int i = 0; rgba && i < n; i++) {
        glGetTextureImage(targets[i].texture, 0, GL_RGBA, GL_FLOAT, w * h * 16, rgba);
        for (long p = 0; p < (long)w * h; p++)
            for (int c = 0; c < 3; c++)
                bad += !isfinite(rgba[4 * p + c]);
    }
    free(rgba);
    return rgba ? bad : -1;
}

/* Whether `name` is one of the passes t's descriptor declares. */
static int declared_pass(const gib_technique *t, const char *name)
{
    for (int i = 0; t->passes && t->passes[i]; i++)
        if (!strcmp(t->passes[i], name))
            return 1;
    return 0;
}

/* What the frames left: the passes, the status, the counters, the images. */
static int check_frames(const gib_technique *t, void *self, const gib_timers *timers,
                        const gib_image_target *targets, int n, int w, int h, FILE *out)
{
    int failures = 0;
    CHECK(timers->pass_count > 0, "%s %dx%d: no timed pass", t->name, w, h);
    for (int i = 0; i < timers->pass_count; i++)
        CHECK(declared_pass(t, timers->names[i]), "%s %dx%d: pass '%s' is not in its descriptor's "
              "passes", t->name, w, h, timers->names[i]);
    CHECK(timers->active < 0, "%s %dx%d: a pass left open after render", t->name, w, h);
    gib_status status = t->status ? t->status(self) : GIB_STATUS_OK;
    CHECK(gib_status_name(status) != NULL, "%s %dx%d: status %d is not one of status.h's",
          t->name, w, h, (int)status);
    char counters[256] = "";
    if (t->counters)
        t->counters(self, counters, sizeof counters);
    CHECK(gib_counters_parse(counters), "%s %dx%d: counters '%s' are not name=value;...", t->name,
          w, h, counters);
    long bad = nonfinite_outputs(targets, n, w, h);
    CHECK(bad == 0, "%s %dx%d: %ld non-finite output values", t->name, w, h, bad);
    fprintf(out, "  %dx%d: %d passes, status %s, counters '%s', %ld non-finite\n", w, h,
            timers->pass_count, gib_status_name(status), counters, bad);
    return failures;
}

/* create, FRAMES x render, the checks, destroy, at one size. */
static int run_size(const gib_technique *t, const gib_gpu_scene *gpu, int w, int h, FILE *out)
{
    int failures = 0;
    gib_error err = {0};
    gib_ledger ledger, outputs;
    gib_ledger_init(&ledger);
    gib_ledger_init(&outputs);
    gib_image_target targets[MAX_TARGETS];
    int n = make_targets(t->components, w, h, &outputs, targets, &err);
    gib_params p;
    gib_params_default(t, &p);
    glGetError();
    void *self = n > 0 ? t->create(gpu, &p, w, h, &ledger, &err) : NULL;
    CHECK(self, "%s %dx%d: create failed: %s", t->name, w, h, err.msg);
    if (self) {
        gib_timers timers;
        gib_timers_init(&timers);
        gib_view view;
        gib_view_make(gpu->scene, &gpu->scene->cameras[0], w, h, 0, &view);
        int rc = 0;
        for (int f = 0; f < FRAMES && rc == 0; f++) {
            gib_timers_frame_begin(&timers, 1);
            rc = t->render(self, &view, &timers, targets, n, &err);
            gib_timers_frame_end(&timers);
        }
        CHECK(rc == 0, "%s %dx%d: render failed: %s", t->name, w, h, err.msg);
        CHECK(gib_gl_check(t->name, &err) == 0, "%s %dx%d: GL error after render: %s", t->name, w,
              h, err.msg);
        failures += check_frames(t, self, &timers, targets, n, w, h, out);
        gib_timers_destroy(&timers);
        t->destroy(self);
        CHECK(ledger.count == 0 && ledger.current_bytes == 0,
              "%s %dx%d: destroy left %d objects, %llu bytes in the ledger (first '%s')", t->name,
              w, h, ledger.count, (unsigned long long)ledger.current_bytes,
              ledger.count ? ledger.entries[0].label : "");
        CHECK(gib_gl_check(t->name, &err) == 0, "%s %dx%d: GL error after destroy: %s", t->name,
              w, h, err.msg);
    }
    gib_ledger_release_all(&ledger);
    for (int i = 0; i < n; i++)
        glDeleteFramebuffers(1, &targets[i].fbo);
    gib_ledger_release_all(&outputs);
    return failures;
}

int gib_check_runtime(const gib_technique *t, gib_check_scenes *scenes, FILE *out, int verbose)
{
    int failures = 0;
    int s = scene_for(t, scenes, out, &failures);
    if (s < 0)
        return -1;
    const double start = gib_now_ms();
    fprintf(out, "%s on %s:\n", t->name, scenes->scene[s].name);
    for (int k = 0; k < 2; k++) {
        int f = run_size(t, &scenes->gpu[s], SIZES[k][0], SIZES[k][1], out);
        if (verbose)
            fprintf(out, "%s %s contract at run time, %s %dx%d: create, 2 frames, destroy\n",
                    f ? "FAIL" : "PASS", t->name, scenes->scene[s].name, SIZES[k][0], SIZES[k][1]);
        failures += f;
    }
    fprintf(out, "  (%.1f s)\n", (gib_now_ms() - start) / 1000);
    return failures;
}

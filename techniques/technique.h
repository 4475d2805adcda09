/* gibench — the uniform technique interface (ARCHITECTURE.md, "The technique contract").
 *
 * A technique is a module in techniques/<name>/ that fills one gib_technique, listed in
 * techniques/registry.c. It never creates a GL context, opens files or prints: the harness gives it
 * the scene on the GPU, its validated parameters, a memory ledger and a timer set, and reads back
 * the images it renders into the targets it is handed. */
#ifndef GIB_TECHNIQUE_H
#define GIB_TECHNIQUE_H

#include <stddef.h>
#include <stdint.h>

#include "harness/base/error.h"
#include "harness/base/status.h"
#include "harness/gl/gpu_scene.h"
#include "harness/gl/ledger.h"
#include "harness/gl/timers.h"
#include "harness/gl/view.h"
#include "scenes/scene.h"

/* ---- parameters ---- */

/* GIB_PARAM_LENGTH: a float in scene units (dmax); a matrix's [scene_scale] scales it with the
 * scene, so a scaled twin of a scene runs the same test. */
enum gib_param_type { GIB_PARAM_INT = 0, GIB_PARAM_FLOAT = 1, GIB_PARAM_LENGTH = 2 };

/* A named value of an enumerated parameter: `--param hits=planes` sets hits to 1. The CSVs keep
 * the number; `gibench list` and `gibench describe` print the names. */
typedef struct gib_param_choice {
    const char *name;     /* "planes" */
    double value;         /* 1 */
} gib_param_choice;

/* Fields after `help` are optional and zero by default (none); a spec lists only what it needs. */
typedef struct gib_param_spec {
    const char *name;     /* "shadow_res" — the CLI (--param name=value), matrix and CSV name */
    int type;             /* enum gib_param_type */
    double def;           /* default */
    double min, max;      /* inclusive range; a value outside is rejected before any rendering */
    const char *help;
    const gib_param_choice *choices; /* the only values it takes, terminated by {0}: a name or its
                                      * number is accepted, anything else refused */
    int multiple_of;      /* > 1: an integer's value must be a multiple of it (rsm_res even: 2) */
} gib_param_spec;

#define GIB_MAX_PARAMS 24

/* A named reading of a technique: the values of some of its parameters that together give it, e.g.
 * `paper`, its paper's literal reading beside the defaults, which depart from it where the literal
 * reading breaks. A technique with presets declares the parameter GIB_PRESET_PARAM (an integer, 0 =
 * the defaults, i = presets[i - 1]), which it never reads itself: gib_params_apply_preset sets the
 * values. In a matrix, on the command line and in the results the value is the preset's name. */
typedef struct gib_preset {
    const char *name;     /* "paper" */
    const char *values;   /* "hits=0;backface=0": each a parameter of the technique */
    const char *why;      /* what it is, and where it is undefined or broken, what it takes */
} gib_preset;

#define GIB_PRESET_PARAM "preset"
#define GIB_PRESET_DEFAULT "default"

/* Validated values, in the order of the technique's spec list. */
typedef struct gib_params {
    int count;
    double values[GIB_MAX_PARAMS];
} gib_params;

struct gib_technique;

/* A rule between parameters, declared in the descriptor and checked with the values before any
 * scene is loaded (gib_params_check): a breaking combination is refused naming the parameters,
 * their values and the rule, never found inside create(). */
typedef struct gib_param_rule {
    const char *params;   /* "hits,backface,coverage": the parameters it relates */
    const char *rule;     /* the rule in words, with its reason */
    int (*holds)(const struct gib_technique *t, const gib_params *p);
} gib_param_rule;

/* ---- components (light-transport parts a technique outputs) ---- */

enum gib_component_bit {
    GIB_OUT_AO = 1u << 0,
    GIB_OUT_DIRECT = 1u << 1,
    GIB_OUT_INDIRECT = 1u << 2,
    GIB_OUT_GLOSSY = 1u << 3,
    GIB_OUT_CAUSTIC = 1u << 4,
};

/* ---- the reference a technique is scored against ----
 * Each output component is scored against the reference of the same name (GIB_OUT_AO against the
 * path tracer's `ao`, ...). Where that reference has settings of its own, the technique says which
 * of its parameters gives each one; a setting no binding names keeps the reference's default
 * (ARCHITECTURE.md, "The technique contract"). */
enum gib_ref_setting {
    GIB_REF_END = 0,
    GIB_REF_AO_DMAX,        /* ao: the largest occluder distance (a GIB_PARAM_LENGTH; inf: none) */
    GIB_REF_AO_OBSCURANCE,  /* ao: 1 = Zhukov's obscurance min(d/dmax, 1) instead of visibility */
};

typedef struct gib_ref_binding {
    unsigned components;    /* GIB_OUT_* bits whose reference this setting configures */
    int setting;            /* enum gib_ref_setting */
    const char *param;      /* the technique's parameter that gives its value */
} gib_ref_binding;

/* ---- what the harness hands a technique: gib_view (harness/gl/view.h), the GPU scene, the
 * ledger and the timers (harness/gl/) ---- */

/* One RGBA32F colour texture per output component (in the order of the component bits), bound to
 * the FBO the harness made; the technique renders into it with bottom-up GL rows and the harness
 * flips on read-back. */
typedef struct gib_image_target {
    unsigned component;   /* one GIB_OUT_* bit */
    unsigned fbo;         /* framebuffer with the colour texture at attachment 0 and a depth buffer */
    unsigned texture;     /* GL_RGBA32F, width x height */
} gib_image_target;

typedef struct gib_technique {
    const char *name;            /* "direct" */
    const char *source;          /* "rasterised direct light with PCF shadow maps (Williams 1978)" */
    unsigned components;         /* GIB_OUT_* bits it outputs */
    const gib_param_spec *params;/* terminated by {0} */
    const gib_param_rule *rules; /* between its parameters (terminated by {0}; NULL: none) */
    /* The passes its render() brackets with gib_timer_begin, NULL-terminated: the names of its
     * rows in <matrix>_passes.csv, which the report's tables read (a frame may run fewer). */
    const char *const *passes;
    /* How its parameters set its references (terminated by {0}; NULL: none). A technique that
     * outputs `ao` must bind GIB_REF_AO_DMAX: AO has no meaning without its range. */
    const gib_ref_binding *reference;
    /* Named readings (terminated by {0}; NULL: none); see gib_preset. */
    const gib_preset *presets;
    unsigned scene_needs;        /* GIB_FEAT_* bits the scene must have (all of them) */
    unsigned scene_needs_any;    /* GIB_FEAT_* bits of which the scene needs at least one (0: none) */
    /* Allocates everything for images of width x height (through the ledger) and builds shaders. */
    void *(*create)(const gib_gpu_scene *scene, const gib_params *params, int width, int height,
                    gib_ledger *ledger, gib_error *err);
    /* Renders one frame; targets[i] matches the i-th set bit of components. Every pass is bracketed
     * by gib_timer_begin/end. Returns 0, or -1 with err set (a shader or overflow failure). */
    int (*render)(void *self, const gib_view *view, gib_timers *timers,
                  const gib_image_target *targets, int target_count, gib_error *err);
    /* Optional: a status for conditions found while rendering (GIB_STATUS_OVERFLOW, ...; harness/
     * base/status.h), GIB_STATUS_OK when the image is an answer. NaN and infinities are the
     * runner's to find (GIB_STATUS_NONFINITE), not the technique's. */
    gib_status (*status)(void *self);
    /* Optional: what the last frame counted, as name=value pairs joined by ';' ("photons=6954"),
     * written to the row's `counters` column (a photon count the thesis' tables are indexed by). */
    void (*counters)(void *self, char *buf, size_t len);
    void (*destroy)(void *self);
} gib_technique;

/* registry.c: the techniques gibench runs (the built-in ones, then those plugins added), and one of
 * them by name (NULL: none). */
const gib_technique *const *gib_techniques(int *count);
const gib_technique *gib_technique_find(const char *name);

/* ---- plugins: techniques built outside this repository (docs/adding-a-technique.md, "As a
 * plugin") ----
 * The version of this contract: of gib_technique, gib_param_spec, gib_view, ... and of what the
 * harness hands a technique. It changes with any change a technique built against an older
 * technique.h would misread; gibench refuses a plugin built with another version. */
#define GIB_CONTRACT_VERSION 1
/* A plugin is a shared library (`gibench --plugin PATH`, $GIBENCH_PLUGINS) exporting one function
 * of this type named GIB_PLUGIN_ENTRY: its descriptors (their count in *count) and the
 * GIB_CONTRACT_VERSION it was compiled with in *contract_version. It links nothing of gibench's:
 * the functions it calls (gib_*, glad's GL pointers) are resolved in the gibench executable, which
 * exports them. */
#define GIB_PLUGIN_ENTRY "gib_plugin_techniques"
/* Marks the entry point exported from a plugin built with hidden symbols (gibench_add_plugin). */
#define GIB_PLUGIN_EXPORT __attribute__((visibility("default")))
typedef const gib_technique *const *(*gib_plugin_entry_fn)(int *count, int *contract_version);
#define GIB_MAX_PLUGIN_TECHNIQUES 64
/* Adds a plugin's technique after the built-in ones (`origin`: the plugin's file): 0, or -1 with err
 * naming the file when its name is a built-in's, a test-only technique's or an earlier plugin's. */
int gib_technique_register(const gib_technique *t, const char *origin, gib_error *err);
/* The plugin file technique t came from, or NULL for a built-in. */
const char *gib_technique_origin(const gib_technique *t);
/* Techniques only tests run (the template, techniques/template/): compiled and tested like the
 * others, never in gib_techniques(), `gibench list` or a matrix. */
const gib_technique *const *gib_techniques_test_only(int *count);

/* Index of a parameter by name, or -1. */
int gib_param_index(const gib_technique *t, const char *name);
/* Fills defaults. */
void gib_params_default(const gib_technique *t, gib_params *p);
/* Parses "value" for parameter `name` of technique t and stores it; errors name the technique, the
 * parameter, the value and the valid range. */
int gib_param_set(const gib_technique *t, gib_params *p, const char *name, const char *value,
                  gib_error *err);
/* Checks a complete set of values against the technique's specs (range, choices, multiple) and
 * its rules: 0, or -1 with err naming the parameter(s), the value(s) and what they break. */
int gib_params_check(const gib_technique *t, const gib_params *p, gib_error *err);
/* The name of parameter i's value among its choices, or NULL when it has none or matches none. */
const char *gib_param_choice_name(const gib_param_spec *s, double value);
/* The parameters preset ps sets and their values, parsed and range-checked: up to max pairs into
 * index[] and value[]; returns their count, or -1 with err set naming the preset and the entry. */
int gib_preset_values(const gib_technique *t, const gib_preset *ps, int *index, double *value,
                      int max, gib_error *err);
/* Sets the values of the preset p names (its GIB_PRESET_PARAM) on every parameter of that preset
 * but those named[i] marks as set explicitly (a matrix's list, --param), which keep their value.
 * named may be NULL. Returns 0, or -1 with err set when the preset's text is malformed. */
int gib_params_apply_preset(const gib_technique *t, gib_params *p, const unsigned char *named,
                            gib_error *err);
/* The name of the preset a parameter set selects: GIB_PRESET_DEFAULT, or presets[i - 1].name. */
const char *gib_params_preset_name(const gib_technique *t, const gib_params *p);
/* Integer and float accessors by name. A name the technique does not declare is a bug in the
 * technique: the process stops with a message naming both (in every build, not only with asserts). */
int gib_param_int(const gib_technique *t, const gib_params *p, const char *name);
double gib_param_float(const gib_technique *t, const gib_params *p, const char *name);

#endif

#include "schema.h"

#include <ini.h>
#include <math.h>
#include <string.h>

#include "app.h"
#include "harness/base/cone_set.h"
#include "harness/base/hash.h"
#include "harness/base/status.h"
#include "history.h"
#include "options.h"
#include "runner.h"

#define GIB_COL_DESC(id, name, kind, key, doc) {name, kind, key, doc},
const gib_column gib_run_columns[GIB_C_COUNT] = {GIB_RUN_COLUMNS(GIB_COL_DESC)};
const gib_column gib_pass_columns[GIB_P_COUNT] = {GIB_PASS_COLUMNS(GIB_COL_DESC)};
const gib_column gib_seq_columns[GIB_S_COUNT] = {GIB_SEQ_COLUMNS(GIB_COL_DESC)};
#undef GIB_COL_DESC

int gib_schema_key(const gib_column *cols, int ncols, unsigned flag, int *out, int max)
{
    int n = 0;
    for (int i = 0; i < ncols; i++)
        if ((cols[i].key & flag) && n < max)
            out[n++] = i;
    return n;
}

/* ---- a matrix's parameter columns ---- */

typedef struct named_params {
    char tech[64][64], param[64][64];
    int count, overflow;
} named_params;

/* [params.T] key and [profile.P] T.key: the parameters the matrix file sets or varies. */
static int collect_named(void *user, const char *section, const char *key, const char *value)
{
    (void)value;
    named_params *np = user;
    const char *tech = NULL, *param = key;
    size_t tlen = 0;
    if (!strncmp(section, "params.", 7)) {
        tech = section + 7;
        tlen = strlen(tech);
    } else if (!strncmp(section, "profile.", 8) && strchr(key, '.')) {
        tech = key;
        tlen = (size_t)(strchr(key, '.') - key);
        param = strchr(key, '.') + 1;
    }
    if (!tech)
        return 1;
    if (np->count == 64) {
        np->overflow = 1;
        return 1;
    }
    snprintf(np->tech[np->count], sizeof np->tech[0], "%.*s", (int)tlen, tech);
    snprintf(np->param[np->count], sizeof np->param[0], "%s", param);
    np->count++;
    return 1;
}

static int is_named(const named_params *np, const char *tech, const char *param)
{
    for (int i = 0; i < np->count; i++)
        if (!strcmp(np->tech[i], tech) && !strcmp(np->param[i], param))
            return 1;
    return 0;
}

static int add_column(gib_table_layout *l, const char *tech, const char *name, gib_error *err)
{
    for (int k = GIB_C_COUNT; k < l->count; k++)
        if (!strcmp(l->names[k], name))
            return 0;
    if (l->count == GIB_TABLE_MAX_COLS)
        return gib_fail(err, "technique '%s' parameter '%s': the results table holds %d columns at "
                        "most (GIB_TABLE_MAX_COLS in harness/app/schema.h)", tech, name,
                        GIB_TABLE_MAX_COLS);
    l->names[l->count++] = name;
    return 0;
}

int gib_table_layout_of(const gib_matrix *m, gib_table_layout *l, gib_error *err)
{
    l->count = 0;
    for (int i = 0; i < GIB_C_COUNT; i++)
        l->names[l->count++] = gib_run_columns[i].name;
    for (int i = 0; m->sequence > 1 && i < GIB_S_COUNT; i++)
        l->names[l->count++] = gib_seq_columns[i].name;
    named_params np = {0};
    if (ini_parse(m->path, collect_named, &np) != 0)
        return gib_fail(err, "%s: cannot be read again for its parameter names", m->path);
    if (np.overflow)
        return gib_fail(err, "%s: names more than 64 parameters: the results table's parameter "
                        "columns cannot all be kept (harness/app/schema.c)", m->path);
    int n;
    const gib_technique *const *all = gib_techniques(&n);
    for (int t = 0; t < n; t++)
        for (int p = 0; all[t]->params && all[t]->params[p].name; p++)
            if (is_named(&np, all[t]->name, all[t]->params[p].name) &&
                add_column(l, all[t]->name, all[t]->params[p].name, err) < 0)
                return -1;
    return 0;
}

/* ---- image names ---- */

/* Fields in braces are the row's; {at} is "_t<time>" for a time other than 0 (the names of runs
 * at t = 0 stay what they were), {params_hash} the 64-bit FNV-1a of params (with its NUL). After
 * filling, ';' becomes '_' and '=' '-'. A short name longer than IMAGE_NAME_MAX takes the long
 * template: file names stop at 255 bytes, and a row's images add suffixes such as "_error.png". */
static const char image_template[] =
    "{scene}_{technique}_{params}_{width}x{height}{at}_{component}";
static const char image_template_long[] =
    "{scene}_{technique}_p{params_hash}_{width}x{height}{at}_{component}";
#define IMAGE_NAME_MAX (240 - 16 - (int)sizeof "_error.png" + 1)

typedef struct image_fields {
    const char *scene, *technique, *params, *component;
    char width[16], height[16], at[48], params_hash[17];
} image_fields;

static const char *image_field(const image_fields *f, const char *name, size_t n)
{
#define FIELD(s, v) if (n == sizeof s - 1 && !strncmp(name, s, n)) return v
    FIELD("scene", f->scene);
    FIELD("technique", f->technique);
    FIELD("params", f->params);
    FIELD("component", f->component);
    FIELD("width", f->width);
    FIELD("height", f->height);
    FIELD("at", f->at);
    FIELD("params_hash", f->params_hash);
#undef FIELD
    return "";
}

static void fill_template(const char *tpl, const image_fields *f, char *out, size_t len)
{
    size_t o = 0;
    for (const char *p = tpl; *p && o + 1 < len;) {
        const char *close = *p == '{' ? strchr(p, '}') : NULL;
        if (!close) {
            out[o++] = *p++;
            continue;
        }
        for (const char *v = image_field(f, p + 1, (size_t)(close - p - 1)); *v && o + 1 < len; v++)
            out[o++] = *v == ';' ? '_' : *v == '=' ? '-' : *v;
        p = close + 1;
    }
    out[o] = 0;
}

void gib_image_name(const char *scene, const char *technique, const char *params, int width,
                    int height, double time, const char *component, char *out, size_t len)
{
    image_fields f = {.scene = scene, .technique = technique, .params = params,
                      .component = component};
    snprintf(f.width, sizeof f.width, "%d", width);
    snprintf(f.height, sizeof f.height, "%d", height);
    if (time != 0.0)
        snprintf(f.at, sizeof f.at, "_t%g", time);
    gib_hash_hex(gib_hash_str(GIB_HASH_INIT, params), f.params_hash);
    fill_template(image_template, &f, out, len);
    if ((int)strlen(out) > IMAGE_NAME_MAX)
        fill_template(image_template_long, &f, out, len);
}

/* ---- JSON export ---- */

/* A JSON string: quotes and backslashes escaped (the descriptors hold no control characters). */
static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"' || *s == '\\')
            fputc('\\', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

static void json_columns(FILE *f, const char *name, const char *file, const gib_column *c, int n)
{
    fprintf(f, "  \"%s\": {\n    \"file\": \"%s\",\n    \"columns\": [\n", name, file);
    for (int i = 0; i < n; i++) {
        fprintf(f, "      {\"name\": \"%s\", \"kind\": \"%s\", \"row_key\": %s, \"run_key\": %s, "
                   "\"doc\": ", c[i].name, c[i].kind, c[i].key & GIB_KEY_ROW ? "true" : "false",
                c[i].key & GIB_KEY_RUN ? "true" : "false");
        json_str(f, c[i].doc);
        fprintf(f, "}%s\n", i + 1 < n ? "," : "");
    }
    fprintf(f, "    ]\n  },\n");
}

/* "reference_params": per component, the technique parameters that set its reference (every
 * technique's gib_ref_binding, each parameter once) with the setting and its default ("inf":
 * unbounded). */
static void json_reference_params(FILE *f)
{
    int n;
    const gib_technique *const *all = gib_techniques(&n);
    const char *sep = "";
    fprintf(f, "  \"reference_params\": {");
    for (unsigned bit = 1; bit <= GIB_OUT_CAUSTIC; bit <<= 1) {
        const gib_ref_binding *seen[16];
        int nseen = 0;
        for (int t = 0; t < n; t++)
            for (const gib_ref_binding *b = all[t]->reference; b && b->setting != GIB_REF_END; b++) {
                int dup = 0;
                for (int k = 0; k < nseen; k++)
                    dup |= !strcmp(seen[k]->param, b->param);
                if ((b->components & bit) && !dup && nseen < 16)
                    seen[nseen++] = b;
            }
        if (!nseen)
            continue;
        fprintf(f, "%s\"%s\": [", sep, gib_output_name(bit));
        for (int k = 0; k < nseen; k++) {
            double d = gib_ref_setting_default(seen[k]->setting);
            fprintf(f, "%s{\"param\": \"%s\", \"setting\": \"%s\", \"default\": ", k ? ", " : "",
                    seen[k]->param, gib_ref_setting_name(seen[k]->setting));
            if (isinf(d))
                fprintf(f, "\"inf\"}");
            else
                fprintf(f, "%.9g}", d);
        }
        fprintf(f, "]");
        sep = ", ";
    }
    fprintf(f, "},\n");
}

/* A JSON number, "inf" / "-inf" as strings (JSON has no infinity). */
static void json_num(FILE *f, double v)
{
    if (isinf(v))
        fprintf(f, v > 0 ? "\"inf\"" : "\"-inf\"");
    else
        fprintf(f, "%.9g", v);
}

static void json_strings(FILE *f, const char *const *s)
{
    fputc('[', f);
    for (int i = 0; s && s[i]; i++) {
        fputs(i ? ", " : "", f);
        json_str(f, s[i]);
    }
    fputc(']', f);
}

/* A parameter's own constraints beyond its range: "choices" {name: value} and "multiple_of". */
static void json_param_rules_of_one(FILE *f, const gib_param_spec *p)
{
    if (p->choices) {
        fprintf(f, ", \"choices\": {");
        for (int k = 0; p->choices[k].name; k++) {
            fprintf(f, "%s", k ? ", " : "");
            json_str(f, p->choices[k].name);
            fprintf(f, ": ");
            json_num(f, p->choices[k].value);
        }
        fputc('}', f);
    }
    if (p->multiple_of > 1)
        fprintf(f, ", \"multiple_of\": %d", p->multiple_of);
}

static void json_technique(FILE *f, const gib_technique *t)
{
    static const char *const types[] = {"int", "float", "length"};
    fprintf(f, "    {\"name\": ");
    json_str(f, t->name);
    fprintf(f, ", \"source\": ");
    json_str(f, t->source);
    fprintf(f, ",\n     \"outputs\": [");
    const char *sep = "";
    for (unsigned bit = 1; bit <= GIB_OUT_CAUSTIC; bit <<= 1)
        if (t->components & bit) {
            fprintf(f, "%s\"%s\"", sep, gib_output_name(bit));
            sep = ", ";
        }
    fprintf(f, "], \"passes\": ");
    json_strings(f, t->passes);
    fprintf(f, ",\n     \"params\": [");
    for (int i = 0; t->params[i].name; i++) {
        const gib_param_spec *p = &t->params[i];
        fprintf(f, "%s\n       {\"name\": \"%s\", \"type\": \"%s\", \"default\": ", i ? "," : "",
                p->name, types[p->type]);
        json_num(f, p->def);
        fprintf(f, ", \"min\": ");
        json_num(f, p->min);
        fprintf(f, ", \"max\": ");
        json_num(f, p->max);
        fprintf(f, ", \"help\": ");
        json_str(f, p->help);
        json_param_rules_of_one(f, p);
        fputc('}', f);
    }
    fprintf(f, "],\n     \"rules\": [");
    for (int i = 0; t->rules && t->rules[i].rule; i++) {
        fprintf(f, "%s{\"params\": ", i ? ", " : "");
        json_str(f, t->rules[i].params);
        fprintf(f, ", \"rule\": ");
        json_str(f, t->rules[i].rule);
        fputc('}', f);
    }
    fprintf(f, "],\n     \"presets\": [");
    for (int i = 0; t->presets && t->presets[i].name; i++) {
        fprintf(f, "%s{\"name\": ", i ? ", " : "");
        json_str(f, t->presets[i].name);
        fprintf(f, ", \"values\": ");
        json_str(f, t->presets[i].values);
        fputc('}', f);
    }
    fprintf(f, "]}");
}

/* "techniques": every registered technique's descriptor: outputs, passes, parameters, presets;
 * "harness_passes": the passes the runner itself times; "statuses": harness/base/status.h. */
static void json_techniques(FILE *f)
{
    int n;
    const gib_technique *const *all = gib_techniques(&n);
    fprintf(f, "  \"techniques\": [\n");
    for (int t = 0; t < n; t++) {
        json_technique(f, all[t]);
        fprintf(f, "%s\n", t + 1 < n ? "," : "");
    }
    fprintf(f, "  ],\n  \"harness_passes\": [\"%s\"],\n  \"statuses\": [\n", GIB_SCENE_UPDATE_PASS);
    for (int s = 0; s < GIB_STATUS_COUNT; s++) {
        fprintf(f, "    {\"name\": \"%s\", \"doc\": ", gib_status_name((gib_status)s));
        json_str(f, gib_status_doc((gib_status)s));
        fprintf(f, "}%s\n", s + 1 < GIB_STATUS_COUNT ? "," : "");
    }
    fprintf(f, "  ],\n");
}

void gib_schema_write_json(FILE *f)
{
    fprintf(f, "{\n  \"version\": 1,\n");
    json_columns(f, "runs", "{matrix}.csv", gib_run_columns, GIB_C_COUNT);
    json_columns(f, "passes", "{matrix}_passes.csv", gib_pass_columns, GIB_P_COUNT);
    json_columns(f, "sequence", "{matrix}.csv, after the base columns, where the matrix's "
                 "sequence is above 1", gib_seq_columns, GIB_S_COUNT);
    fprintf(f, "  \"param_columns\": \"after the base columns: the parameters the matrix file names, "
               "in registry order; every parameter is in params\",\n");
    fprintf(f, "  \"params\": {\"column\": \"params\", \"separator\": \";\", \"assign\": \"=\"},\n");
    fprintf(f, "  \"image_name\": {\n    \"template\": \"%s\",\n", image_template);
    fprintf(f, "    \"long_template\": \"%s\",\n", image_template_long);
    fprintf(f, "    \"long_when_over\": %d,\n", IMAGE_NAME_MAX);
    fprintf(f, "    \"at\": \"_t%%g of time, empty at time 0\",\n    \"params_hash\": \"fnv1a64\",\n");
    fprintf(f, "    \"replace\": {\";\": \"_\", \"=\": \"-\"}\n  },\n");
    fprintf(f, "  \"cone_set\": {\"aperture_deg\": %g, \"weights\": [", GIB_DIFFUSE_CONE_APERTURE_DEG);
    for (int i = 0; i < GIB_DIFFUSE_CONES; i++)
        fprintf(f, "%.9g%s", gib_diffuse_cone_weight(i), i + 1 < GIB_DIFFUSE_CONES ? ", " : "]},\n");
    json_reference_params(f);
    json_techniques(f);
    fprintf(f, "  \"revision\": \"%s\",\n", gib_git_revision());
    fprintf(f, "  \"software_renderers\": [");
    for (int i = 0; gib_software_renderers[i]; i++)
        fprintf(f, "%s\"%s\"", i ? ", " : "", gib_software_renderers[i]);
    fprintf(f, "]\n}\n");
}

static const gib_command_doc describe_doc = {
    "describe", "[--out FILE]   (also: gibench schema)",
    "Prints what the binary knows as JSON: the columns of a matrix's runs and passes tables, the\n"
    "columns of a row's and a run's identity, the names of a row's images, every technique's\n"
    "outputs, passes, parameters and presets, the passes the runner times, the row statuses with\n"
    "what each means, the parameters that set each component's reference, the diffuse cone set,\n"
    "the software renderers and the revision (the build writes it to build/schema.json;\n"
    "harness/reporting/schema.py reads it, and tests/report/test_describe.py checks what it\n"
    "uses).\n"};

int gib_cmd_schema(int argc, char **argv)
{
    const char *out = NULL;
    const gib_option opts[] = {GIB_OPTION_TEXT("--out", &out, "FILE", "write here, not to stdout"),
                               {0}};
    int rc = gib_options_parse(&describe_doc, opts, argc, argv, NULL, NULL, 0);
    if (rc != GIB_OPTIONS_PROCEED)
        return rc;
    FILE *f = out ? fopen(out, "w") : stdout;
    if (!f) {
        fprintf(stderr, "gibench describe: cannot write %s\n", out);
        return 1;
    }
    gib_schema_write_json(f);
    if (out && fclose(f) != 0) {
        fprintf(stderr, "gibench describe: cannot write %s\n", out);
        return 1;
    }
    return 0;
}

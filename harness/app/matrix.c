#include "matrix.h"

#include <ini.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reference/reference.h"
#include "app.h"
#include "refrank.h"

/* What the file says, before expansion; profile keys override base keys. */
typedef struct raw_value {
    char section[64], key[64], value[512];
    int line;
} raw_value;

typedef struct parse_state {
    const char *path;
    FILE *f;
    int line;
    raw_value *vals;
    int count, cap;
    gib_error *err;
    int failed;
    char sections[32][64]; /* every [section] seen, even empty ones (inih reports only keys) */
    int nsections;
} parse_state;

/* Counting lines in the reader is how errors found after parsing still name their line. */
static char *reader(char *buf, int size, void *user)
{
    parse_state *s = user;
    char *r = fgets(buf, size, s->f);
    if (r) {
        s->line++;
        const char *p = r + strspn(r, " \t");
        const char *e = *p == '[' ? strchr(p, ']') : NULL;
        if (e && s->nsections < 32)
            snprintf(s->sections[s->nsections++], sizeof s->sections[0], "%.*s", (int)(e - p - 1),
                     p + 1);
    }
    return r;
}

static int handler(void *user, const char *section, const char *name, const char *value)
{
    parse_state *s = user;
    if (s->count == s->cap) {
        s->cap = s->cap ? s->cap * 2 : 64;
        raw_value *n = realloc(s->vals, sizeof *n * s->cap);
        if (!n) {
            gib_fail(s->err, "%s:%d: out of memory", s->path, s->line);
            s->failed = 1;
            return 0;
        }
        s->vals = n;
    }
    raw_value *v = &s->vals[s->count++];
    snprintf(v->section, sizeof v->section, "%s", section);
    snprintf(v->key, sizeof v->key, "%s", name);
    snprintf(v->value, sizeof v->value, "%s", value);
    v->line = s->line;
    return 1;
}

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    char *e = s + strlen(s);
    while (e > s && (e[-1] == ' ' || e[-1] == '\t'))
        *--e = 0;
    return s;
}

/* Splits a comma-separated list in place. */
static int split_list(char *s, char **items, int max)
{
    int n = 0;
    for (char *tok = strtok(s, ","); tok && n < max; tok = strtok(NULL, ","))
        if (*(tok = trim(tok)))
            items[n++] = tok;
    return n;
}

void gib_params_key(const gib_technique *t, const gib_params *p, char *out, int out_len)
{
    int used = 0;
    out[0] = 0;
    for (int i = 0; t->params && t->params[i].name && used < out_len; i++) {
        const char *sep = i ? ";" : "";
        if (strcmp(t->params[i].name, GIB_PRESET_PARAM))
            used += snprintf(out + used, out_len - used, "%s%s=%g", sep, t->params[i].name,
                             p->values[i]);
        else if (p->values[i] != 0) /* the defaults' rows keep the key they always had */
            used += snprintf(out + used, out_len - used, "%s%s=%s", sep, t->params[i].name,
                             gib_params_preset_name(t, p));
    }
}

/* The effective value of [matrix] key: the profile's when it sets it. */
static const raw_value *lookup(const parse_state *s, const char *profile_section, const char *key)
{
    const raw_value *found = NULL;
    for (int i = 0; i < s->count; i++)
        if (!strcmp(s->vals[i].section, "matrix") && !strcmp(s->vals[i].key, key))
            found = &s->vals[i];
    for (int i = 0; i < s->count; i++)
        if (!strcmp(s->vals[i].section, profile_section) && !strcmp(s->vals[i].key, key))
            found = &s->vals[i];
    return found;
}

static const char *const matrix_keys[] = {"description", "scenes", "techniques", "sizes", "camera",
                                          "frames", "warmup", "times", "dt", "ref_spp_growth",
                                          "sequence", NULL};

/* ref_spp_<component>: samples per pixel of that component's reference. */
static int ref_spp_component(const char *k)
{
    return strncmp(k, "ref_spp_", 8) ? -1 : gib_component_parse(k + 8);
}

static int known_matrix_key(const char *k)
{
    for (int i = 0; matrix_keys[i]; i++)
        if (!strcmp(matrix_keys[i], k))
            return 1;
    return ref_spp_component(k) >= 0;
}

/* The file's name, path and the chosen profile; psec receives the profile's section name. */
static void name_matrix(gib_matrix *m, const char *path, const char *profile, char *psec,
                        size_t psec_len)
{
    snprintf(m->path, sizeof m->path, "%s", path);
    const char *base = strrchr(path, '/');
    snprintf(m->name, sizeof m->name, "%s", base ? base + 1 : path);
    char *dot = strstr(m->name, ".matrix");
    if (dot)
        *dot = 0;
    snprintf(m->profile, sizeof m->profile, "%s", profile);
    snprintf(psec, psec_len, "profile.%s", profile);
}

/* ---- external techniques ([external.NAME], external.h) ---- */

const gib_external *gib_matrix_external(const gib_matrix *m, const gib_technique *t)
{
    for (int i = 0; t && i < m->external_count; i++)
        if (t == &m->externals[i].technique)
            return &m->externals[i];
    return NULL;
}

/* A technique by name: the matrix's externals (by NAME or ext:NAME), then the registry. */
static const gib_technique *find_technique(const gib_matrix *m, const char *name)
{
    for (int i = 0; i < m->external_count; i++)
        if (!strcmp(name, m->externals[i].name) || !strcmp(name, m->externals[i].tech_name))
            return &m->externals[i].technique;
    return gib_technique_find(name);
}

/* The external named in section "external.NAME", made on its first key. */
static gib_external *external_of(const parse_state *s, const raw_value *v, gib_matrix *m)
{
    const char *name = v->section + 9;
    for (int i = 0; i < m->external_count; i++)
        if (!strcmp(m->externals[i].name, name))
            return &m->externals[i];
    if (!*name || strlen(name) >= sizeof m->externals[0].name ||
        strspn(name, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") !=
            strlen(name)) {
        gib_fail(s->err, "%s:%d: [%s]: an external's name is 1 to 63 letters, digits, _ - .",
                 s->path, v->line, v->section);
        return NULL;
    }
    if (gib_technique_find(name)) {
        gib_fail(s->err, "%s:%d: [%s]: '%s' is a built-in technique's name: name the external "
                 "otherwise", s->path, v->line, v->section, name);
        return NULL;
    }
    if (m->external_count == GIB_MAX_EXTERNALS) {
        gib_fail(s->err, "%s:%d: more than %d externals", s->path, v->line, GIB_MAX_EXTERNALS);
        return NULL;
    }
    if (!m->externals && !(m->externals = calloc(GIB_MAX_EXTERNALS, sizeof *m->externals))) {
        gib_fail_code(s->err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    gib_external *x = &m->externals[m->external_count++];
    snprintf(x->name, sizeof x->name, "%s", name);
    x->line = v->line;
    return x;
}

/* Every [external.NAME] section's keys, then each external completed. */
static int load_externals(const parse_state *s, gib_matrix *m)
{
    for (int i = 0; i < s->count; i++) {
        const raw_value *v = &s->vals[i];
        if (strncmp(v->section, "external.", 9))
            continue;
        gib_external *x = external_of(s, v, m);
        if (!x)
            return -1;
        if (gib_external_set(x, v->key, trim((char *)v->value), s->err) < 0)
            return gib_error_prefix(s->err, "%s:%d: [%s]", s->path, v->line, v->section);
    }
    for (int i = 0; i < m->external_count; i++)
        if (gib_external_finish(&m->externals[i], s->path, s->err) < 0)
            return gib_error_prefix(s->err, "%s:%d", s->path, m->externals[i].line);
    return 0;
}

/* Every section and key is checked, so a typo never silently changes what runs. */
static int check_sections(const parse_state *s, const gib_matrix *m, const char *profile,
                          const char *psec)
{
    int have_profile = 0;
    for (int i = 0; i < s->nsections; i++)
        have_profile |= !strcmp(s->sections[i], psec);
    for (int i = 0; i < s->count; i++) {
        const raw_value *v = &s->vals[i];
        if (!strcmp(v->section, "matrix") || !strncmp(v->section, "profile.", 8)) {
            const char *dotk = strchr(v->key, '.');
            if (!known_matrix_key(v->key) && !(dotk && !strncmp(v->section, "profile.", 8)))
                return gib_fail(s->err, "%s:%d: unknown key '%s' in [%s]", s->path, v->line,
                                v->key, v->section);
        } else if (!strcmp(v->section, "scene_scale") || !strncmp(v->section, "external.", 9)) {
            continue; /* checked against the scene list (load_scene_scale), load_externals */
        } else if (!strncmp(v->section, "params.", 7)) {
            if (!find_technique(m, v->section + 7))
                return gib_fail(s->err, "%s:%d: [%s]: unknown technique '%s'", s->path, v->line,
                                v->section, v->section + 7);
        } else {
            return gib_fail(s->err, "%s:%d: unknown section [%s] (expected [matrix], "
                            "[params.TECHNIQUE], [scene_scale], [external.NAME] or "
                            "[profile.NAME])", s->path,
                            v->line, v->section);
        }
    }
    if (!have_profile && strcmp(profile, "default"))
        return gib_fail(s->err, "%s: has no [profile.%s] section", s->path, profile);
    return 0;
}

/* The integer keys (camera, frames, warmup, ref_spp_growth, sequence, ref_spp_<component>) and the
 * description, with their defaults. */
static int load_settings(const parse_state *s, const char *psec, gib_matrix *m)
{
    const raw_value *v;
    m->frames = 5;
    m->warmup = 2;
    m->ref_spp_growth = GIB_REF_SPP_GROWTH_DEFAULT;
    m->sequence = 1;
    struct { char key[48]; int *dst; long min, max; } ints[5 + GIB_MATRIX_MAX_COMPONENTS] = {
        {"camera", &m->camera, 0, 64}, {"frames", &m->frames, 1, 256}, {"warmup", &m->warmup, 0, 100},
        {"ref_spp_growth", &m->ref_spp_growth, 1, 1024},
        {"sequence", &m->sequence, 1, GIB_MATRIX_MAX_SEQUENCE}};
    size_t nints = 5;
    for (int c = 0; c < GIB_COMP_COUNT && c < GIB_MATRIX_MAX_COMPONENTS; c++, nints++) {
        snprintf(ints[nints].key, sizeof ints[nints].key, "ref_spp_%s", gib_component_name(c));
        ints[nints].dst = &m->ref_spp[c];
        ints[nints].min = 1;
        ints[nints].max = 1 << 24;
    }
    for (size_t i = 0; i < nints; i++) {
        if (!(v = lookup(s, psec, ints[i].key)))
            continue;
        long x;
        if (gib_parse_int(ints[i].key, trim((char *)v->value), ints[i].min, ints[i].max, &x,
                          s->err) < 0)
            return gib_error_prefix(s->err, "%s:%d", s->path, v->line);
        *ints[i].dst = (int)x;
    }
    if ((v = lookup(s, psec, "description")))
        snprintf(m->description, sizeof m->description, "%s", v->value);
    return 0;
}

/* The matrix's lists, crossed with each technique's parameter lists into runs. */
typedef struct matrix_axes {
    char scenes_buf[512], techs_buf[512], sizes_buf[512];
    char *scenes[GIB_MATRIX_MAX_LIST], *techs[GIB_MATRIX_MAX_LIST];
    int ns, nt, nz;
    int techs_line;                       /* where techniques is set, for its errors */
    int ws[GIB_MATRIX_MAX_LIST], hs[GIB_MATRIX_MAX_LIST];
    double times[GIB_MATRIX_MAX_LIST];
    int ntimes;
    double scale[GIB_MATRIX_MAX_LIST];    /* [scene_scale] per scene (1: none) */
    int scale_line[GIB_MATRIX_MAX_LIST];
} matrix_axes;

/* Instants and frame spacing for moving scenes (a static scene looks the same at each). */
static int load_times(const parse_state *s, const char *psec, gib_matrix *m, matrix_axes *ax)
{
    const raw_value *v;
    ax->times[0] = 0.0;
    ax->ntimes = 1;
    if ((v = lookup(s, psec, "times"))) {
        char times_buf[512], *items[GIB_MATRIX_MAX_LIST];
        snprintf(times_buf, sizeof times_buf, "%s", v->value);
        ax->ntimes = split_list(times_buf, items, GIB_MATRIX_MAX_LIST);
        if (!ax->ntimes)
            return gib_fail(s->err, "%s:%d: empty list for times", s->path, v->line);
        for (int i = 0; i < ax->ntimes; i++)
            if (gib_parse_float("times", items[i], -1e6, 1e6, &ax->times[i], s->err) < 0)
                return gib_error_prefix(s->err, "%s:%d", s->path, v->line);
    }
    if ((v = lookup(s, psec, "dt")) &&
        gib_parse_float("dt", trim((char *)v->value), 0.0, 1e4, &m->dt, s->err) < 0)
        return gib_error_prefix(s->err, "%s:%d", s->path, v->line);
    return 0;
}

/* scenes, techniques and sizes: each size parsed, each scene's file present. */
static int load_lists(const parse_state *s, const char *psec, matrix_axes *ax)
{
    char *sizes[GIB_MATRIX_MAX_LIST];
    const raw_value *vs = lookup(s, psec, "scenes"), *vt = lookup(s, psec, "techniques"),
                    *vz = lookup(s, psec, "sizes");
    if (!vs || !vt || !vz)
        return gib_fail(s->err, "%s: [matrix] needs scenes, techniques and sizes", s->path);
    snprintf(ax->scenes_buf, sizeof ax->scenes_buf, "%s", vs->value);
    snprintf(ax->techs_buf, sizeof ax->techs_buf, "%s", vt->value);
    snprintf(ax->sizes_buf, sizeof ax->sizes_buf, "%s", vz->value);
    ax->ns = split_list(ax->scenes_buf, ax->scenes, GIB_MATRIX_MAX_LIST);
    ax->nt = split_list(ax->techs_buf, ax->techs, GIB_MATRIX_MAX_LIST);
    ax->nz = split_list(ax->sizes_buf, sizes, GIB_MATRIX_MAX_LIST);
    ax->techs_line = vt->line;
    for (int i = 0; i < ax->nz; i++)
        if (gib_parse_size("sizes", sizes[i], &ax->ws[i], &ax->hs[i], s->err) < 0)
            return gib_error_prefix(s->err, "%s:%d", s->path, vz->line);
    for (int i = 0; i < ax->ns; i++) {
        char sf[1200];
        snprintf(sf, sizeof sf, "%s/%s.scene", gib_scene_dir(), ax->scenes[i]);
        FILE *f = fopen(sf, "r");
        if (!f)
            return gib_fail(s->err, "%s:%d: unknown scene '%s' (no %s)", s->path, vs->line,
                            ax->scenes[i], sf);
        fclose(f);
    }
    return 0;
}

/* [scene_scale]: scene = factor; the length parameters (GIB_PARAM_LENGTH) of that
 * scene's runs are multiplied by it. */
static int load_scene_scale(const parse_state *s, matrix_axes *ax)
{
    for (int i = 0; i < ax->ns; i++) {
        ax->scale[i] = 1.0;
        ax->scale_line[i] = 0;
    }
    for (int k = 0; k < s->count; k++) {
        const raw_value *rv = &s->vals[k];
        if (strcmp(rv->section, "scene_scale"))
            continue;
        int si = -1;
        for (int i = 0; i < ax->ns; i++)
            if (!strcmp(ax->scenes[i], rv->key))
                si = i;
        if (si < 0)
            return gib_fail(s->err, "%s:%d: [scene_scale]: '%s' is not one of the matrix's scenes",
                            s->path, rv->line, rv->key);
        char *end;
        double x = strtod(rv->value, &end);
        if (end == rv->value || *trim(end) || !(x > 0.0) || !isfinite(x))
            return gib_fail(s->err, "%s:%d: [scene_scale]: %s expects a finite number > 0, got '%s'",
                            s->path, rv->line, rv->key, rv->value);
        ax->scale[si] = x;
        ax->scale_line[si] = rv->line;
    }
    return 0;
}

/* One technique's parameter lists: [params.T] key, overridden by [profile.P] T.key. */
typedef struct param_lists {
    const gib_technique *t;
    int np;
    char sec[80]; /* "params.T" */
    char alias[72]; /* an external's plain name ([params.NAME] as well as [params.ext:NAME]) */
    int counts[GIB_MAX_PARAMS];
    double values[GIB_MAX_PARAMS][GIB_MATRIX_MAX_LIST];
    unsigned char named[GIB_MAX_PARAMS]; /* the file sets this parameter (a preset leaves it) */
} param_lists;

/* The parameter raw value rv sets for pl's technique ([params.T], or T.key in the profile's
 * section; T its name or, for an external, its plain name), else NULL. */
static const char *param_of(const raw_value *rv, const char *psec, const param_lists *pl)
{
    const char *names[2] = {pl->t->name, pl->alias};
    for (int k = 0; k < 2; k++) {
        size_t len = strlen(names[k]);
        if (!len)
            continue;
        if (!strncmp(rv->section, "params.", 7) && !strcmp(rv->section + 7, names[k]))
            return rv->key;
        if (!strcmp(rv->section, psec) && !strncmp(rv->key, names[k], len) && rv->key[len] == '.')
            return rv->key + len + 1;
    }
    return NULL;
}

/* Every key naming a parameter of the technique names one it has. */
static int check_param_names(const parse_state *s, const char *psec, const param_lists *pl)
{
    const gib_technique *t = pl->t;
    for (int k = 0; k < s->count; k++) {
        const raw_value *rv = &s->vals[k];
        const char *pname = param_of(rv, psec, pl);
        if (!pname)
            continue;
        if (gib_param_index(t, pname) < 0) {
            gib_error e2;
            gib_param_set(t, &(gib_params){0}, pname, "0", &e2);
            return gib_fail(s->err, "%s:%d: %s", s->path, rv->line, e2.msg);
        }
    }
    return 0;
}

/* Parameter pi's list of values: its default alone when no section sets it. */
static int load_param_list(const parse_state *s, const char *psec, param_lists *pl, int pi)
{
    const gib_technique *t = pl->t;
    const raw_value *pv = NULL;
    for (int pass = 0; pass < 2; pass++) /* [params.T], then the profile's T.key over it */
        for (int k = 0; k < s->count; k++) {
            const char *pn = param_of(&s->vals[k], psec, pl);
            if (pn && !strcmp(pn, t->params[pi].name) &&
                (strcmp(s->vals[k].section, psec) == 0) == pass)
                pv = &s->vals[k];
        }
    if (!pv) {
        pl->counts[pi] = 1;
        pl->values[pi][0] = t->params[pi].def;
        return 0;
    }
    pl->named[pi] = 1;
    char list[512], *items[GIB_MATRIX_MAX_LIST];
    snprintf(list, sizeof list, "%s", pv->value);
    pl->counts[pi] = split_list(list, items, GIB_MATRIX_MAX_LIST);
    if (!pl->counts[pi])
        return gib_fail(s->err, "%s:%d: empty list for %s", s->path, pv->line, t->params[pi].name);
    for (int k = 0; k < pl->counts[pi]; k++) {
        gib_params tmp;
        gib_params_default(t, &tmp);
        if (gib_param_set(t, &tmp, t->params[pi].name, items[k], s->err) < 0)
            return gib_error_prefix(s->err, "%s:%d", s->path, pv->line);
        pl->values[pi][k] = tmp.values[pi];
    }
    return 0;
}

static int load_param_lists(const parse_state *s, const char *psec, param_lists *pl)
{
    const gib_technique *t = pl->t;
    pl->np = 0;
    while (t->params && t->params[pl->np].name)
        pl->np++;
    snprintf(pl->sec, sizeof pl->sec, "params.%s", t->name);
    if (check_param_names(s, psec, pl) < 0)
        return -1;
    for (int pi = 0; pi < pl->np; pi++)
        if (load_param_list(s, psec, pl, pi) < 0)
            return -1;
    return 0;
}

/* Combination c of the parameter lists (the first parameter varying fastest), with scene si's
 * [scene_scale] applied to its lengths, then its preset's values on the parameters the file does
 * not set. */
static int set_combo(const matrix_axes *ax, const param_lists *pl, int si, int c, gib_params *out,
                     const char *path, gib_error *err)
{
    const gib_technique *t = pl->t;
    int rest = c;
    for (int pi = 0; pi < pl->np; pi++) {
        const gib_param_spec *ps = &t->params[pi];
        double x = pl->values[pi][rest % pl->counts[pi]];
        rest /= pl->counts[pi];
        if (ps->type == GIB_PARAM_LENGTH && ax->scale[si] != 1.0) {
            x *= ax->scale[si];
            if (!(x >= ps->min && x <= ps->max))
                return gib_fail(err, "%s:%d: [scene_scale] %s = %g makes %s.%s %g, "
                                "outside [%g, %g]", path, ax->scale_line[si], ax->scenes[si],
                                ax->scale[si], t->name, ps->name, x, ps->min, ps->max);
        }
        out->values[pi] = x;
    }
    if (gib_params_apply_preset(t, out, pl->named, err) < 0)
        return gib_error_prefix(err, "%s", path);
    return 0;
}

/* Appends the technique's runs: scenes x parameter combinations x instants x sizes. */
static int expand_runs(gib_matrix *m, const matrix_axes *ax, const param_lists *pl,
                       const char *path, gib_error *err)
{
    const gib_technique *t = pl->t;
    int combos = 1;
    for (int pi = 0; pi < pl->np; pi++)
        combos *= pl->counts[pi];
    for (int si = 0; si < ax->ns; si++)
        for (int c = 0; c < combos; c++)
            for (int zi = 0; zi < ax->nz * ax->ntimes; zi++) {
                gib_matrix_run *nr = realloc(m->runs, sizeof *nr * (m->run_count + 1));
                if (!nr)
                    return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
                m->runs = nr;
                gib_matrix_run *r = &m->runs[m->run_count++];
                memset(r, 0, sizeof *r);
                snprintf(r->scene, sizeof r->scene, "%s", ax->scenes[si]);
                r->technique = t;
                gib_params_default(t, &r->params);
                if (set_combo(ax, pl, si, c, &r->params, path, err) < 0)
                    return -1;
                if (gib_params_check(t, &r->params, err) < 0)
                    return gib_error_prefix(err, "%s: [%s] on scene %s", path, pl->sec,
                                            ax->scenes[si]);
                if (pl->alias[0])
                    gib_external_params_key(gib_matrix_external(m, t), &r->params, r->params_key,
                                            sizeof r->params_key);
                else
                    gib_params_key(t, &r->params, r->params_key, sizeof r->params_key);
                r->width = ax->ws[zi % ax->nz];
                r->height = ax->hs[zi % ax->nz];
                r->time = ax->times[zi / ax->nz];
            }
    return 0;
}

/* Everything after the file is read: checks, settings, lists and the runs, in that order (so
 * the first error a file has is the one reported). */
static int build_matrix(const parse_state *s, const char *profile, gib_matrix *m)
{
    char psec[64];
    name_matrix(m, s->path, profile, psec, sizeof psec);
    matrix_axes ax;
    if (load_externals(s, m) < 0 || check_sections(s, m, profile, psec) < 0 ||
        load_settings(s, psec, m) < 0 ||
        load_times(s, psec, m, &ax) < 0 || load_lists(s, psec, &ax) < 0 ||
        load_scene_scale(s, &ax) < 0)
        return -1;
    for (int ti = 0; ti < ax.nt; ti++) {
        param_lists pl = {.t = find_technique(m, ax.techs[ti])};
        const gib_external *x = gib_matrix_external(m, pl.t);
        if (!pl.t)
            return gib_fail(s->err, "%s:%d: unknown technique '%s' (see gibench list, or declare "
                            "it in [external.%s])", s->path, ax.techs_line, ax.techs[ti],
                            ax.techs[ti]);
        if (x && m->sequence > 1)
            return gib_fail(s->err, "%s:%d: external '%s' renders one frame a row: not with "
                            "sequence = %d", s->path, ax.techs_line, x->name, m->sequence);
        if (x)
            snprintf(pl.alias, sizeof pl.alias, "%s", x->name);
        if (load_param_lists(s, psec, &pl) < 0 || expand_runs(m, &ax, &pl, s->path, s->err) < 0)
            return -1;
    }
    return 0;
}

int gib_matrix_load(const char *path, const char *profile, gib_matrix *m, gib_error *err)
{
    memset(m, 0, sizeof *m);
    parse_state s = {.path = path, .err = err};
    s.f = fopen(path, "r");
    if (!s.f)
        return gib_fail(err, "matrix file '%s' cannot be opened", path);
    int rc = ini_parse_stream(reader, &s, handler, &s);
    fclose(s.f);
    int status = -1;
    if (rc != 0 || s.failed) {
        if (!s.failed)
            gib_fail(err, "%s:%d: syntax error (expected [section] or key = value)", path,
                     rc > 0 ? rc : s.line);
    } else {
        status = build_matrix(&s, profile, m);
    }
    free(s.vals);
    if (status < 0)
        gib_matrix_free(m);
    return status;
}


void gib_matrix_free(gib_matrix *m)
{
    free(m->externals);
    m->externals = NULL;
    m->external_count = 0;
    free(m->runs);
    m->runs = NULL;
    m->run_count = 0;
}

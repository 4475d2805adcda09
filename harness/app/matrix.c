#include "matrix.h"

#include <ini.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reference/reference.h"
#include "app.h"

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
    for (int i = 0; t->params && t->params[i].name && used < out_len; i++)
        used += snprintf(out + used, out_len - used, "%s%s=%g", i ? ";" : "", t->params[i].name,
                         p->values[i]);
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
                                          NULL};

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
        goto out;
    }
    snprintf(m->path, sizeof m->path, "%s", path);
    const char *base = strrchr(path, '/');
    snprintf(m->name, sizeof m->name, "%s", base ? base + 1 : path);
    char *dot = strstr(m->name, ".matrix");
    if (dot)
        *dot = 0;
    snprintf(m->profile, sizeof m->profile, "%s", profile);
    char psec[64];
    snprintf(psec, sizeof psec, "profile.%s", profile);

    /* Every section and key is checked, so a typo never silently changes what runs. */
    int have_profile = 0;
    for (int i = 0; i < s.nsections; i++)
        have_profile |= !strcmp(s.sections[i], psec);
    for (int i = 0; i < s.count; i++) {
        raw_value *v = &s.vals[i];
        if (!strcmp(v->section, "matrix") || !strncmp(v->section, "profile.", 8)) {
            const char *dotk = strchr(v->key, '.');
            if (!known_matrix_key(v->key) && !(dotk && !strncmp(v->section, "profile.", 8))) {
                gib_fail(err, "%s:%d: unknown key '%s' in [%s]", path, v->line, v->key,
                         v->section);
                goto out;
            }
        } else if (!strcmp(v->section, "scene_scale")) {
            continue; /* checked against the scene list below */
        } else if (!strncmp(v->section, "params.", 7)) {
            const gib_technique *t = gib_technique_find(v->section + 7);
            if (!t) {
                gib_fail(err, "%s:%d: [%s]: unknown technique '%s'", path, v->line, v->section,
                         v->section + 7);
                goto out;
            }
        } else {
            gib_fail(err, "%s:%d: unknown section [%s] (expected [matrix], [params.TECHNIQUE], "
                     "[scene_scale] or [profile.NAME])", path, v->line, v->section);
            goto out;
        }
    }
    if (!have_profile && strcmp(profile, "default")) {
        gib_fail(err, "%s: has no [profile.%s] section", path, profile);
        goto out;
    }

    const raw_value *v;
    m->frames = 5;
    m->warmup = 2;
    m->ref_spp_growth = 16;
    struct { char key[48]; int *dst; long min, max; } ints[4 + GIB_MATRIX_MAX_COMPONENTS] = {
        {"camera", &m->camera, 0, 64}, {"frames", &m->frames, 1, 256}, {"warmup", &m->warmup, 0, 100},
        {"ref_spp_growth", &m->ref_spp_growth, 1, 1024}};
    size_t nints = 4;
    for (int c = 0; c < GIB_COMP_COUNT && c < GIB_MATRIX_MAX_COMPONENTS; c++, nints++) {
        snprintf(ints[nints].key, sizeof ints[nints].key, "ref_spp_%s", gib_component_name(c));
        ints[nints].dst = &m->ref_spp[c];
        ints[nints].min = 1;
        ints[nints].max = 1 << 24;
    }
    for (size_t i = 0; i < nints; i++) {
        if (!(v = lookup(&s, psec, ints[i].key)))
            continue;
        long x;
        if (gib_parse_int(ints[i].key, trim((char *)v->value), ints[i].min, ints[i].max, &x, err) < 0) {
            gib_error_prefix(err, "%s:%d", path, v->line);
            goto out;
        }
        *ints[i].dst = (int)x;
    }
    if ((v = lookup(&s, psec, "description")))
        snprintf(m->description, sizeof m->description, "%s", v->value);
    /* Instants and frame spacing for moving scenes (a static scene looks the same at each). */
    double times[GIB_MATRIX_MAX_LIST] = {0.0};
    int ntimes = 1;
    if ((v = lookup(&s, psec, "times"))) {
        char times_buf[512], *items[GIB_MATRIX_MAX_LIST];
        snprintf(times_buf, sizeof times_buf, "%s", v->value);
        ntimes = split_list(times_buf, items, GIB_MATRIX_MAX_LIST);
        if (!ntimes) {
            gib_fail(err, "%s:%d: empty list for times", path, v->line);
            goto out;
        }
        for (int i = 0; i < ntimes; i++)
            if (gib_parse_float("times", items[i], -1e6, 1e6, &times[i], err) < 0) {
                gib_error_prefix(err, "%s:%d", path, v->line);
                goto out;
            }
    }
    if ((v = lookup(&s, psec, "dt")) &&
        gib_parse_float("dt", trim((char *)v->value), 0.0, 1e4, &m->dt, err) < 0) {
        gib_error_prefix(err, "%s:%d", path, v->line);
        goto out;
    }

    char scenes_buf[512], techs_buf[512], sizes_buf[512];
    char *scenes[GIB_MATRIX_MAX_LIST], *techs[GIB_MATRIX_MAX_LIST], *sizes[GIB_MATRIX_MAX_LIST];
    const raw_value *vs = lookup(&s, psec, "scenes"), *vt = lookup(&s, psec, "techniques"),
                    *vz = lookup(&s, psec, "sizes");
    if (!vs || !vt || !vz) {
        gib_fail(err, "%s: [matrix] needs scenes, techniques and sizes", path);
        goto out;
    }
    snprintf(scenes_buf, sizeof scenes_buf, "%s", vs->value);
    snprintf(techs_buf, sizeof techs_buf, "%s", vt->value);
    snprintf(sizes_buf, sizeof sizes_buf, "%s", vz->value);
    int ns = split_list(scenes_buf, scenes, GIB_MATRIX_MAX_LIST);
    int nt = split_list(techs_buf, techs, GIB_MATRIX_MAX_LIST);
    int nz = split_list(sizes_buf, sizes, GIB_MATRIX_MAX_LIST);
    int ws[GIB_MATRIX_MAX_LIST], hs[GIB_MATRIX_MAX_LIST];
    for (int i = 0; i < nz; i++)
        if (gib_parse_size("sizes", sizes[i], &ws[i], &hs[i], err) < 0) {
            gib_error_prefix(err, "%s:%d", path, vz->line);
            goto out;
        }
    for (int i = 0; i < ns; i++) {
        char sf[1200];
        snprintf(sf, sizeof sf, "%s/%s.scene", gib_scene_dir(), scenes[i]);
        FILE *f = fopen(sf, "r");
        if (!f) {
            gib_fail(err, "%s:%d: unknown scene '%s' (no %s)", path, vs->line, scenes[i], sf);
            goto out;
        }
        fclose(f);
    }
    /* [scene_scale]: scene = factor; the length parameters (GIB_PARAM_LENGTH) of that
     * scene's runs are multiplied by it. */
    double scale[GIB_MATRIX_MAX_LIST];
    int scale_line[GIB_MATRIX_MAX_LIST];
    for (int i = 0; i < ns; i++) {
        scale[i] = 1.0;
        scale_line[i] = 0;
    }
    for (int k = 0; k < s.count; k++) {
        const raw_value *rv = &s.vals[k];
        if (strcmp(rv->section, "scene_scale"))
            continue;
        int si = -1;
        for (int i = 0; i < ns; i++)
            if (!strcmp(scenes[i], rv->key))
                si = i;
        if (si < 0) {
            gib_fail(err, "%s:%d: [scene_scale]: '%s' is not one of the matrix's scenes", path,
                     rv->line, rv->key);
            goto out;
        }
        char *end;
        double x = strtod(rv->value, &end);
        if (end == rv->value || *trim(end) || !(x > 0.0) || !isfinite(x)) {
            gib_fail(err, "%s:%d: [scene_scale]: %s expects a finite number > 0, got '%s'", path,
                     rv->line, rv->key, rv->value);
            goto out;
        }
        scale[si] = x;
        scale_line[si] = rv->line;
    }
    for (int ti = 0; ti < nt; ti++) {
        const gib_technique *t = gib_technique_find(techs[ti]);
        if (!t) {
            gib_fail(err, "%s:%d: unknown technique '%s' (see gibench list)", path, vt->line,
                     techs[ti]);
            goto out;
        }
        /* Parameter lists: [params.T] key, overridden by [profile.P] T.key. */
        int np = 0;
        while (t->params && t->params[np].name)
            np++;
        char lists[GIB_MAX_PARAMS][512];
        int counts[GIB_MAX_PARAMS];
        double values[GIB_MAX_PARAMS][GIB_MATRIX_MAX_LIST];
        char sec[80];
        snprintf(sec, sizeof sec, "params.%s", t->name);
        for (int k = 0; k < s.count; k++) {
            raw_value *rv = &s.vals[k];
            int in_params = !strcmp(rv->section, sec);
            int in_prof = !strcmp(rv->section, psec) && !strncmp(rv->key, t->name, strlen(t->name)) &&
                          rv->key[strlen(t->name)] == '.';
            if (!in_params && !in_prof)
                continue;
            const char *pname = in_params ? rv->key : rv->key + strlen(t->name) + 1;
            if (gib_param_index(t, pname) < 0) {
                gib_error e2;
                gib_param_set(t, &(gib_params){0}, pname, "0", &e2);
                gib_fail(err, "%s:%d: %s", path, rv->line, e2.msg);
                goto out;
            }
        }
        for (int pi = 0; pi < np; pi++) {
            const raw_value *pv = NULL;
            char pkey[128];
            for (int k = 0; k < s.count; k++)
                if (!strcmp(s.vals[k].section, sec) && !strcmp(s.vals[k].key, t->params[pi].name))
                    pv = &s.vals[k];
            snprintf(pkey, sizeof pkey, "%s.%s", t->name, t->params[pi].name);
            for (int k = 0; k < s.count; k++)
                if (!strcmp(s.vals[k].section, psec) && !strcmp(s.vals[k].key, pkey))
                    pv = &s.vals[k];
            if (!pv) {
                counts[pi] = 1;
                values[pi][0] = t->params[pi].def;
                continue;
            }
            snprintf(lists[pi], sizeof lists[pi], "%s", pv->value);
            char *items[GIB_MATRIX_MAX_LIST];
            counts[pi] = split_list(lists[pi], items, GIB_MATRIX_MAX_LIST);
            if (!counts[pi]) {
                gib_fail(err, "%s:%d: empty list for %s", path, pv->line, t->params[pi].name);
                goto out;
            }
            for (int k = 0; k < counts[pi]; k++) {
                gib_params tmp;
                gib_params_default(t, &tmp);
                if (gib_param_set(t, &tmp, t->params[pi].name, items[k], err) < 0) {
                    gib_error_prefix(err, "%s:%d", path, pv->line);
                    goto out;
                }
                values[pi][k] = tmp.values[pi];
            }
        }
        int combos = 1;
        for (int pi = 0; pi < np; pi++)
            combos *= counts[pi];
        for (int si = 0; si < ns; si++)
            for (int c = 0; c < combos; c++)
                for (int zi = 0; zi < nz * ntimes; zi++) {
                    gib_matrix_run *nr = realloc(m->runs, sizeof *nr * (m->run_count + 1));
                    if (!nr) {
                        gib_fail(err, "out of memory");
                        goto out;
                    }
                    m->runs = nr;
                    gib_matrix_run *r = &m->runs[m->run_count++];
                    memset(r, 0, sizeof *r);
                    snprintf(r->scene, sizeof r->scene, "%s", scenes[si]);
                    r->technique = t;
                    gib_params_default(t, &r->params);
                    int rest = c;
                    for (int pi = 0; pi < np; pi++) {
                        const gib_param_spec *ps = &t->params[pi];
                        double x = values[pi][rest % counts[pi]];
                        rest /= counts[pi];
                        if (ps->type == GIB_PARAM_LENGTH && scale[si] != 1.0) {
                            x *= scale[si];
                            if (!(x >= ps->min && x <= ps->max)) {
                                gib_fail(err, "%s:%d: [scene_scale] %s = %g makes %s.%s %g, "
                                         "outside [%g, %g]", path, scale_line[si], scenes[si],
                                         scale[si], t->name, ps->name, x, ps->min, ps->max);
                                goto out;
                            }
                        }
                        r->params.values[pi] = x;
                    }
                    gib_params_key(t, &r->params, r->params_key, sizeof r->params_key);
                    r->width = ws[zi % nz];
                    r->height = hs[zi % nz];
                    r->time = times[zi / nz];
                }
    }
    status = 0;
out:
    free(s.vals);
    if (status < 0)
        gib_matrix_free(m);
    return status;
}

void gib_matrix_free(gib_matrix *m)
{
    free(m->runs);
    m->runs = NULL;
    m->run_count = 0;
}

/* gibench — the .scene text format (scenes/FORMAT.md): INI read with libinih, into a
 * gib_scene_spec that scene_build.c turns into geometry.
 *
 * libinih does not tell its handler the line number (Debian builds it without
 * INI_HANDLER_LINENO), so the file is fed through a reader that returns one physical line per call
 * and counts them: inih's own count equals ours, and every error, including those found after
 * parsing (a missing mesh file), names file:line. The reader also
 *  - strips leading whitespace, because inih would otherwise read an indented line as the
 *    continuation of the previous value (INI_ALLOW_MULTILINE) instead of as a key;
 *  - opens sections itself, because inih calls no handler for a section without keys, which would
 *    let an unknown but empty section pass unnoticed;
 *  - rejects lines longer than inih's buffer, which inih would silently split in two. */
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "scene_internal.h"

enum section_kind { SEC_NONE, SEC_SCENE, SEC_MESH, SEC_MATERIAL, SEC_LIGHT, SEC_CAMERA };

static const char *const scene_keys[] = {"description", "exposure", "data",   "closed",
                                         "sky",         "shift",    "gltf",   "camera",
                                         "lights",      "materials", NULL};
/* The first 13 are the mesh's own (7 placement, 6 motion); the rest are generator keys
 * (gib_proc_key_parse). */
static const char *const mesh_keys[] = {
    "file",     "procedural", "scale", "rotate", "translate", "material", "smooth_angle",
    "keys",     "key_rotate", "key_translate", "pivot", "loop", "waves",
    "size",     "radius",     "thickness", "tubes", "segments",  "sides",    "seed",
    "subdivisions", "height", NULL};
static const char *const material_keys[] = {"albedo",    "specular", "phong_n", "mirror",
                                            "two_sided", NULL}; /* order = GIB_MS_* bits */
static const char *const light_keys[] = {"type",      "position", "direction",   "target",
                                         "intensity", "exponent", "outer_angle", NULL};
static const char *const camera_keys[] = {"eye", "target", "up", "fov", NULL};

typedef struct parse_ctx {
    FILE *fp;
    const char *path;
    int lineno;
    gib_scene_spec *spec;
    gib_error *err;
    int failed;
    enum section_kind sec;
    int sec_index; /* into the spec's array for that kind */
    unsigned seen; /* keys given in the current section, by index in its key table */
    char *buf;     /* the current physical line */
    size_t buf_cap;
} parse_ctx;

static int ctx_fail(parse_ctx *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static int ctx_fail(parse_ctx *c, const char *fmt, ...)
{
    if (c->failed)
        return -1; /* keep the first error */
    char msg[1536];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    gib_fail(c->err, "%s:%d: %s", c->path, c->lineno, msg);
    c->failed = 1;
    return -1;
}

/* "light 'key'", "[scene]": how messages name the current section. */
static void section_label(const parse_ctx *c, char *out, size_t n)
{
    const gib_scene_spec *s = c->spec;
    switch (c->sec) {
    case SEC_SCENE: snprintf(out, n, "[scene]"); break;
    case SEC_MESH: snprintf(out, n, "mesh '%s'", s->meshes[c->sec_index].name); break;
    case SEC_MATERIAL: snprintf(out, n, "material '%s'", s->materials[c->sec_index].name); break;
    case SEC_LIGHT: snprintf(out, n, "light '%s'", s->lights[c->sec_index].l.name); break;
    case SEC_CAMERA: snprintf(out, n, "camera '%s'", s->cameras[c->sec_index].c.name); break;
    default: snprintf(out, n, "(no section)"); break;
    }
}

/* ------------------------------------------------------------------ sections */

static int grow_array(void **arr, int count, size_t elem, gib_error *err)
{
    void *p = gib_realloc_array(*arr, (size_t)count + 1, elem, err);
    if (!p)
        return -1;
    *arr = p;
    memset((char *)p + (size_t)count * elem, 0, elem);
    return 0;
}

static int name_taken(const parse_ctx *c, enum section_kind k, const char *name)
{
    const gib_scene_spec *s = c->spec;
    int n = k == SEC_MESH       ? s->mesh_count
            : k == SEC_MATERIAL ? s->material_count
            : k == SEC_LIGHT    ? s->light_count
                                : s->camera_count;
    for (int i = 0; i < n; i++) {
        const char *o = k == SEC_MESH       ? s->meshes[i].name
                        : k == SEC_MATERIAL ? s->materials[i].name
                        : k == SEC_LIGHT    ? s->lights[i].l.name
                                            : s->cameras[i].c.name;
        int line = k == SEC_MESH       ? s->meshes[i].line
                   : k == SEC_MATERIAL ? s->materials[i].line
                   : k == SEC_LIGHT    ? s->lights[i].line
                                       : s->cameras[i].line;
        if (strcmp(o, name) == 0)
            return line;
    }
    return 0;
}

/* A new [mesh|material|light|camera.NAME] section n of kind k, with the kind's defaults; it becomes
 * the current section. */
static int append_section(parse_ctx *c, enum section_kind k, const char *n)
{
    gib_scene_spec *s = c->spec;
    c->sec = k;
    switch (k) {
    case SEC_MESH: {
        if (grow_array((void **)&s->meshes, s->mesh_count, sizeof *s->meshes, c->err))
            return c->failed = 1, -1;
        gib_mesh_spec *m = &s->meshes[s->mesh_count];
        snprintf(m->name, sizeof m->name, "%s", n);
        m->line = c->lineno;
        m->scale[0] = m->scale[1] = m->scale[2] = 1.0f;
        m->smooth_angle_deg = 60.0f;
        c->sec_index = s->mesh_count++;
        break;
    }
    case SEC_MATERIAL: {
        if (grow_array((void **)&s->materials, s->material_count, sizeof *s->materials, c->err))
            return c->failed = 1, -1;
        gib_material_spec *m = &s->materials[s->material_count];
        snprintf(m->name, sizeof m->name, "%s", n);
        m->line = c->lineno;
        c->sec_index = s->material_count++;
        break;
    }
    case SEC_LIGHT: {
        if (grow_array((void **)&s->lights, s->light_count, sizeof *s->lights, c->err))
            return c->failed = 1, -1;
        gib_light_spec *l = &s->lights[s->light_count];
        snprintf(l->l.name, sizeof l->l.name, "%s", n);
        l->line = c->lineno;
        l->l.spot_exponent = 1.0f;
        l->l.spot_outer_deg = 90.0f;
        c->sec_index = s->light_count++;
        break;
    }
    case SEC_CAMERA: {
        if (grow_array((void **)&s->cameras, s->camera_count, sizeof *s->cameras, c->err))
            return c->failed = 1, -1;
        gib_camera_spec *cs = &s->cameras[s->camera_count];
        snprintf(cs->c.name, sizeof cs->c.name, "%s", n);
        cs->line = c->lineno;
        cs->c.up[1] = 1.0f;
        cs->c.vfov_deg = 45.0f;
        c->sec_index = s->camera_count++;
        break;
    }
    default: break;
    }
    return 0;
}

static int open_section(parse_ctx *c, char *text)
{
    char *end = strchr(text, ']');
    if (!end)
        return ctx_fail(c, "section header '%s' lacks its closing ']'", text);
    *end = '\0';
    char *name = text + 1;
    while (*name == ' ' || *name == '\t')
        name++;
    for (char *e = name + strlen(name); e > name && (e[-1] == ' ' || e[-1] == '\t');)
        *--e = '\0';

    gib_scene_spec *s = c->spec;
    c->seen = 0;
    if (strcmp(name, "scene") == 0) {
        if (s->scene_line)
            return ctx_fail(c, "[scene] appears twice (first at line %d)", s->scene_line);
        s->scene_line = c->lineno;
        c->sec = SEC_SCENE;
        return 0;
    }
    static const struct {
        const char *prefix;
        enum section_kind kind;
        size_t maxlen;
    } kinds[] = {
        {"mesh.", SEC_MESH, sizeof(((gib_mesh_spec *)0)->name)},
        {"material.", SEC_MATERIAL, sizeof(((gib_material *)0)->name)},
        {"light.", SEC_LIGHT, sizeof(((gib_light *)0)->name)},
        {"camera.", SEC_CAMERA, sizeof(((gib_camera *)0)->name)},
    };
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        size_t pl = strlen(kinds[k].prefix);
        if (strncmp(name, kinds[k].prefix, pl) != 0)
            continue;
        const char *n = name + pl;
        if (!n[0])
            return ctx_fail(c, "section [%s] needs a name after the dot, e.g. [%sfloor]", name,
                            kinds[k].prefix);
        if (strlen(n) >= kinds[k].maxlen)
            return ctx_fail(c, "section name '%s' is too long (at most %zu characters)", n,
                            kinds[k].maxlen - 1);
        int first = name_taken(c, kinds[k].kind, n);
        if (first)
            return ctx_fail(c, "section [%s] appears twice (first at line %d)", name, first);
        return append_section(c, kinds[k].kind, n);
    }
    return ctx_fail(c,
                    "unknown section [%s] (known: [scene], [mesh.NAME], [material.NAME], "
                    "[light.NAME], [camera.NAME])",
                    name);
}

/* ------------------------------------------------------------------ the reader */

static char *reader(char *str, int num, void *stream)
{
    parse_ctx *c = stream;
    if (c->failed)
        return NULL; /* stop at the first error: later ones are usually its consequences */
    size_t len = 0;
    int ch, any = 0;
    while ((ch = getc(c->fp)) != EOF) {
        any = 1;
        if (len + 2 > c->buf_cap) {
            size_t cap = c->buf_cap ? 2 * c->buf_cap : 256;
            char *nb = realloc(c->buf, cap);
            if (!nb) {
                gib_fail(c->err, "%s:%d: out of memory", c->path, c->lineno + 1);
                c->failed = 1;
                return NULL;
            }
            c->buf = nb;
            c->buf_cap = cap;
        }
        if (ch == '\n')
            break;
        c->buf[len++] = (char)ch;
    }
    if (!any)
        return NULL;
    c->buf[len] = '\0';
    c->lineno++;
    if (len > 0 && c->buf[len - 1] == '\r')
        c->buf[--len] = '\0';
    char *line = c->buf;
    while (*line == ' ' || *line == '\t')
        line++;
    size_t n = strlen(line);
    if (num < 4 || n + 3 > (size_t)num) {
        ctx_fail(c,
                 "line is %zu characters long; at most %d fit (split the value or shorten "
                 "it)",
                 n, num - 3);
        return NULL;
    }
    if (line[0] == '[') {
        char copy[1024];
        snprintf(copy, sizeof copy, "%s", line);
        if (open_section(c, copy))
            return NULL;
    }
    memcpy(str, line, n);
    str[n] = '\n';
    str[n + 1] = '\0';
    return str;
}

/* ------------------------------------------------------------------ values */

/* Parses between min_n and max_n numbers. On failure fills a message "expects 3 numbers, got
 * 'abc'". */
static int parse_floats(const char *v, float *out, int min_n, int max_n, int *got, char *msg,
                        size_t msg_len)
{
    int n = 0;
    const char *p = v;
    int ok = 1;
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == ',')
            p++;
        if (!*p)
            break;
        char *end;
        float f = strtof(p, &end);
        if (end == p || !isfinite(f) || (*end && *end != ' ' && *end != '\t' && *end != ',')) {
            ok = 0;
            break;
        }
        if (n < max_n)
            out[n] = f;
        n++;
        p = end;
    }
    if (ok && n >= min_n && n <= max_n) {
        if (got)
            *got = n;
        return 0;
    }
    if (min_n == max_n)
        snprintf(msg, msg_len, "expects %d number%s, got '%s'", min_n, min_n == 1 ? "" : "s", v);
    else if (max_n == min_n + 1)
        snprintf(msg, msg_len, "expects %d or %d numbers, got '%s'", min_n, max_n, v);
    else
        snprintf(msg, msg_len, "expects %d to %d numbers, got '%s'", min_n, max_n, v);
    return -1;
}

static int parse_bool(const char *v, int *out)
{
    if (!strcmp(v, "1") || !strcasecmp(v, "true") || !strcasecmp(v, "yes") || !strcasecmp(v, "on"))
        return *out = 1, 0;
    if (!strcmp(v, "0") || !strcasecmp(v, "false") || !strcasecmp(v, "no") || !strcasecmp(v, "off"))
        return *out = 0, 0;
    return -1;
}

static int key_index(const char *const *keys, const char *name)
{
    for (int i = 0; keys[i]; i++)
        if (strcmp(keys[i], name) == 0)
            return i;
    return -1;
}

static void key_list(const char *const *keys, char *out, size_t n)
{
    size_t used = 0;
    out[0] = '\0';
    for (int i = 0; keys[i] && used < n; i++) {
        int w = snprintf(out + used, n - used, "%s%s", i ? ", " : "", keys[i]);
        if (w < 0)
            break;
        used += (size_t)w;
    }
}

/* One `key = value` line of the current section, as the section's handler sees it. */
typedef struct key_line {
    int k;             /* index of the key in its section's key table */
    const char *name, *value;
    char label[192];   /* how messages name the section (section_label) */
} key_line;

/* Copies a string value into a fixed field, failing when it does not fit. */
#define COPY_STR(field, value)                                                                     \
    (strlen(value) >= sizeof(field) ? ctx_fail(c, "%s: '%s' is too long (at most %zu characters)", \
                                               label, name, sizeof(field) - 1)                     \
                                    : (snprintf(field, sizeof(field), "%s", value), 0))

#define FLOATS(dst, lo, hi, got)                                                                   \
    (parse_floats(value, dst, lo, hi, got, msg, sizeof msg)                                        \
         ? ctx_fail(c, "%s: '%s' %s", label, name, msg)                                            \
         : 0)

/* The handlers below return 0, or -1 after ctx_fail. */

static int scene_key(parse_ctx *c, const key_line *kl)
{
    const char *label = kl->label, *name = kl->name, *value = kl->value;
    char msg[768];
    gib_scene_spec *s = c->spec;
    int rc = 0, k = kl->k;
    if (k == 0)
        rc = COPY_STR(s->description, value);
    else if (k == 1) {
        rc = FLOATS(&s->exposure, 1, 1, NULL);
        if (!rc && !(s->exposure > 0.0f))
            rc = ctx_fail(c, "%s: 'exposure' must be positive, got '%s'", label, value);
    } else if (k == 2) {
        rc = COPY_STR(s->data, value);
        s->data_line = c->lineno;
    } else if (k == 4) {
        rc = FLOATS(s->sky, 3, 3, NULL);
        if (!rc && !(s->sky[0] >= 0 && s->sky[1] >= 0 && s->sky[2] >= 0 &&
                     isfinite(s->sky[0] + s->sky[1] + s->sky[2])))
            rc = ctx_fail(c, "%s: 'sky' must be 3 finite radiances >= 0, got '%s'", label, value);
    } else if (k == 5) {
        rc = FLOATS(s->shift, 3, 3, NULL);
        if (!rc && !isfinite(s->shift[0] + s->shift[1] + s->shift[2]))
            rc = ctx_fail(c, "%s: 'shift' must be 3 finite numbers, got '%s'", label, value);
    } else if (k == 6) {
        rc = COPY_STR(s->gltf, value);
        s->gltf_line = c->lineno;
    } else if (k == 7) {
        s->camera_line = c->lineno;
        if (strncmp(value, "gltf:", 5) == 0 && value[5])
            rc = COPY_STR(s->gltf_camera_name, value + 5);
        else if (strcmp(value, "gltf") != 0)
            rc = ctx_fail(c, "%s: 'camera' expects 'gltf' or 'gltf:NAME' (the glTF file's "
                             "cameras, or the one named), got '%s'", label, value);
        s->gltf_camera = 1;
    } else if (k == 8 || k == 9) {
        *(k == 8 ? &s->lights_line : &s->materials_line) = c->lineno;
        *(k == 8 ? &s->gltf_lights : &s->gltf_materials) = 1;
        if (strcmp(value, "gltf") != 0)
            rc = ctx_fail(c, "%s: '%s' expects 'gltf' (take them from the [scene] gltf file), "
                             "got '%s'", label, name, value);
    } else if (parse_bool(value, &s->closed))
        rc = ctx_fail(c, "%s: 'closed' expects 0 or 1, got '%s'", label, value);
    return rc;
}

/* key_rotate or key_translate: 3 numbers per key. */
static int mesh_key_transforms(parse_ctx *c, const key_line *kl, gib_mesh_spec *m)
{
    const char *label = kl->label, *name = kl->name, *value = kl->value;
    char msg[768];
    int got = 0, rot = kl->k == 8;
    float tmp[3 * GIB_MOTION_MAX_KEYS];
    int rc = FLOATS(tmp, 3, 3 * GIB_MOTION_MAX_KEYS, &got);
    if (!rc && got % 3)
        rc = ctx_fail(c, "%s: '%s' takes 3 numbers per key, got %d numbers", label, name, got);
    float(*dst)[3] = rot ? m->key_rotate : m->key_translate;
    for (int i = 0; !rc && i < got; i++)
        dst[i / 3][i % 3] = tmp[i];
    *(rot ? &m->key_rotate_n : &m->key_translate_n) = got;
    *(rot ? &m->key_rotate_line : &m->key_translate_line) = c->lineno;
    return rc;
}

/* waves: 4 numbers per wave (amplitude wavelength direction_deg speed). */
static int mesh_waves(parse_ctx *c, const key_line *kl, gib_mesh_spec *m)
{
    const char *label = kl->label, *name = kl->name, *value = kl->value;
    char msg[768];
    int got = 0;
    float tmp[4 * GIB_MOTION_MAX_WAVES];
    int rc = FLOATS(tmp, 4, 4 * GIB_MOTION_MAX_WAVES, &got);
    if (!rc && got % 4)
        rc = ctx_fail(c,
                      "%s: 'waves' takes 4 numbers per wave (amplitude wavelength "
                      "direction_deg speed), got %d numbers",
                      label, got);
    for (int i = 0; !rc && i < got / 4; i++) {
        const float *w = tmp + 4 * i;
        if (!(w[0] >= 0.0f) || !(w[1] > 0.0f))
            rc = ctx_fail(c,
                          "%s: wave %d: amplitude must be >= 0 and wavelength > 0, got "
                          "%g and %g",
                          label, i + 1, (double)w[0], (double)w[1]);
        memcpy(m->waves[i], w, sizeof m->waves[i]);
    }
    m->wave_count = got / 4;
    m->waves_line = c->lineno;
    return rc;
}

/* The mesh's motion keys (FORMAT.md, "Motion"): keys, key_rotate, key_translate, pivot, loop,
 * waves. */
static int mesh_motion_key(parse_ctx *c, const key_line *kl, gib_mesh_spec *m)
{
    const char *label = kl->label, *name = kl->name, *value = kl->value;
    char msg[768];
    int rc = 0;
    switch (kl->k) {
    case 7:
        rc = FLOATS(m->key_time, 1, GIB_MOTION_MAX_KEYS, &m->key_count);
        m->keys_line = c->lineno;
        for (int i = 1; !rc && i < m->key_count; i++)
            if (!(m->key_time[i] > m->key_time[i - 1]))
                rc = ctx_fail(c, "%s: 'keys' (times in seconds) must increase, got '%s'", label,
                              value);
        break;
    case 8:
    case 9: rc = mesh_key_transforms(c, kl, m); break;
    case 10:
        rc = FLOATS(m->pivot, 3, 3, NULL);
        m->pivot_line = c->lineno;
        break;
    case 11:
        m->loop_line = c->lineno;
        if (parse_bool(value, &m->loop))
            rc = ctx_fail(c, "%s: 'loop' expects 0 or 1, got '%s'", label, value);
        break;
    default: rc = mesh_waves(c, kl, m); break;
    }
    return rc;
}

static int mesh_key(parse_ctx *c, const key_line *kl)
{
    const char *label = kl->label, *name = kl->name, *value = kl->value;
    char msg[768];
    gib_mesh_spec *m = &c->spec->meshes[c->sec_index];
    int rc = 0, got = 0;
    switch (kl->k) {
    case 0:
        rc = COPY_STR(m->file, value);
        m->file_line = c->lineno;
        break;
    case 1:
        rc = COPY_STR(m->procedural, value);
        m->procedural_line = c->lineno;
        break;
    case 2:
        rc = FLOATS(m->scale, 1, 3, &got);
        if (!rc && got == 1)
            m->scale[1] = m->scale[2] = m->scale[0];
        if (!rc && (m->scale[0] == 0.0f || m->scale[1] == 0.0f || m->scale[2] == 0.0f))
            rc = ctx_fail(c, "%s: 'scale' must not be 0, got '%s'", label, value);
        break;
    case 3: rc = FLOATS(m->rotate_deg, 3, 3, NULL); break;
    case 4: rc = FLOATS(m->translate, 3, 3, NULL); break;
    case 5:
        rc = COPY_STR(m->material, value);
        m->material_line = c->lineno;
        break;
    case 6:
        rc = FLOATS(&m->smooth_angle_deg, 1, 1, NULL);
        if (!rc && !(m->smooth_angle_deg >= 0.0f && m->smooth_angle_deg <= 180.0f))
            rc = ctx_fail(c, "%s: 'smooth_angle' must be 0..180 degrees, got '%s'", label,
                          value);
        break;
    case 7: case 8: case 9: case 10: case 11: case 12: rc = mesh_motion_key(c, kl, m); break;
    default:
        if (gib_proc_key_parse(&m->params, name, value, c->lineno, msg, sizeof msg))
            rc = ctx_fail(c, "%s: %s", label, msg);
        break;
    }
    return rc;
}

static int material_key(parse_ctx *c, const key_line *kl)
{
    const char *label = kl->label, *name = kl->name, *value = kl->value;
    char msg[768];
    gib_material_spec *m = &c->spec->materials[c->sec_index];
    int rc = 0, k = kl->k;
    m->set |= 1u << k;
    m->key_line[k] = c->lineno;
    if (k == 0 || k == 1) {
        float *dst = k == 0 ? m->albedo : m->specular;
        rc = FLOATS(dst, 3, 3, NULL);
        if (!rc &&
            (dst[0] < 0 || dst[1] < 0 || dst[2] < 0 || dst[0] > 1 || dst[1] > 1 || dst[2] > 1))
            rc = ctx_fail(c, "%s: '%s' must be between 0 and 1 per channel, got '%s'", label,
                          name, value);
    } else if (k == 2) {
        rc = FLOATS(&m->phong_n, 1, 1, NULL);
        if (!rc && !(m->phong_n > 0.0f))
            rc = ctx_fail(c, "%s: 'phong_n' must be positive, got '%s'", label, value);
    } else if (parse_bool(value, k == 3 ? &m->mirror : &m->two_sided)) {
        rc = ctx_fail(c, "%s: '%s' expects 0 or 1, got '%s'", label, name, value);
    }
    return rc;
}

static int light_key(parse_ctx *c, const key_line *kl)
{
    const char *label = kl->label, *name = kl->name, *value = kl->value;
    char msg[768];
    gib_light_spec *l = &c->spec->lights[c->sec_index];
    int rc = 0;
    switch (kl->k) {
    case 0:
        l->type_set = 1;
        if (!strcmp(value, "point"))
            l->l.type = GIB_LIGHT_POINT;
        else if (!strcmp(value, "spot"))
            l->l.type = GIB_LIGHT_SPOT;
        else if (!strcmp(value, "directional"))
            l->l.type = GIB_LIGHT_DIRECTIONAL;
        else
            rc = ctx_fail(c, "%s: unknown light type '%s' (known: point, spot, directional)",
                          label, value);
        break;
    case 1:
        rc = FLOATS(l->l.position, 3, 3, NULL);
        l->position_set = 1;
        break;
    case 2:
        rc = FLOATS(l->l.direction, 3, 3, NULL);
        l->direction_set = 1;
        l->direction_line = c->lineno;
        break;
    case 3:
        rc = FLOATS(l->target, 3, 3, NULL);
        l->target_set = 1;
        l->target_line = c->lineno;
        break;
    case 4:
        rc = FLOATS(l->l.intensity, 3, 3, NULL);
        l->intensity_set = 1;
        if (!rc && (l->l.intensity[0] < 0 || l->l.intensity[1] < 0 || l->l.intensity[2] < 0))
            rc = ctx_fail(c, "%s: 'intensity' must not be negative, got '%s'", label, value);
        break;
    case 5:
        rc = FLOATS(&l->l.spot_exponent, 1, 1, NULL);
        if (!rc && l->l.spot_exponent < 0.0f)
            rc = ctx_fail(c, "%s: 'exponent' must be >= 0, got '%s'", label, value);
        break;
    default:
        rc = FLOATS(&l->l.spot_outer_deg, 1, 1, NULL);
        if (!rc && !(l->l.spot_outer_deg > 0.0f && l->l.spot_outer_deg <= 180.0f))
            rc = ctx_fail(c,
                          "%s: 'outer_angle' must be in (0, 180] degrees (a half-angle), "
                          "got '%s'",
                          label, value);
        break;
    }
    return rc;
}

static int camera_key(parse_ctx *c, const key_line *kl)
{
    const char *label = kl->label, *name = kl->name, *value = kl->value;
    char msg[768];
    gib_camera_spec *cs = &c->spec->cameras[c->sec_index];
    int rc = 0, k = kl->k;
    if (k == 0) {
        rc = FLOATS(cs->c.eye, 3, 3, NULL);
        cs->eye_set = 1;
    } else if (k == 1) {
        rc = FLOATS(cs->c.target, 3, 3, NULL);
        cs->target_set = 1;
    } else if (k == 2) {
        rc = FLOATS(cs->c.up, 3, 3, NULL);
    } else {
        rc = FLOATS(&cs->c.vfov_deg, 1, 1, NULL);
        if (!rc && !(cs->c.vfov_deg > 0.0f && cs->c.vfov_deg < 180.0f))
            rc = ctx_fail(c, "%s: 'fov' (vertical, degrees) must be in (0, 180), got '%s'",
                          label, value);
    }
    return rc;
}

/* inih's callback: finds the key in the current section's table, refuses unknown and repeated
 * keys, and hands the value to the section's handler. */
static int handler(void *user, const char *section, const char *name, const char *value)
{
    (void)section; /* the reader tracks sections itself */
    parse_ctx *c = user;
    if (c->failed)
        return 0;
    key_line kl = {.name = name, .value = value};
    char known[256];
    section_label(c, kl.label, sizeof kl.label);
    const char *const *keys = c->sec == SEC_SCENE      ? scene_keys
                              : c->sec == SEC_MESH     ? mesh_keys
                              : c->sec == SEC_MATERIAL ? material_keys
                              : c->sec == SEC_LIGHT    ? light_keys
                              : c->sec == SEC_CAMERA   ? camera_keys
                                                       : NULL;
    if (!keys)
        return ctx_fail(c, "'%s = %s' comes before any section; start with [scene]", name, value),
               0;
    int k = kl.k = key_index(keys, name);
    if (k < 0) {
        key_list(keys, known, sizeof known);
        return ctx_fail(c, "%s: unknown key '%s' (known: %s)", kl.label, name, known), 0;
    }
    if (c->seen & (1u << k))
        return ctx_fail(c, "%s: '%s' is given twice", kl.label, name), 0;
    c->seen |= 1u << k;
    int rc = 0;
    switch (c->sec) {
    case SEC_SCENE: rc = scene_key(c, &kl); break;
    case SEC_MESH: rc = mesh_key(c, &kl); break;
    case SEC_MATERIAL: rc = material_key(c, &kl); break;
    case SEC_LIGHT: rc = light_key(c, &kl); break;
    case SEC_CAMERA: rc = camera_key(c, &kl); break;
    default: break;
    }
    return rc == 0;
}

/* ------------------------------------------------------------------ entry points */

int gib_scene_parse(const char *path, gib_scene_spec *spec, gib_error *err)
{
    memset(spec, 0, sizeof *spec);
    spec->exposure = 1.0f;
    if (snprintf(spec->path, sizeof spec->path, "%s", path) >= (int)sizeof spec->path)
        return gib_fail(err, "scene file path too long: '%s'", path);
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(spec->name, sizeof spec->name, "%s", base);
    size_t bl = strlen(spec->name);
    if (bl > 6 && strcmp(spec->name + bl - 6, ".scene") == 0)
        spec->name[bl - 6] = '\0';

    FILE *fp = fopen(path, "rb");
    if (!fp)
        return gib_fail(err, "cannot open scene file '%s'", path);
    parse_ctx c = {.fp = fp, .path = spec->path, .spec = spec, .err = err};
    int rc = ini_parse_stream(reader, &c, handler, &c);
    fclose(fp);
    free(c.buf);
    spec->line_count = c.lineno;
    if (c.failed || rc != 0) {
        if (!c.failed) {
            if (rc > 0)
                gib_fail(err,
                         "%s:%d: cannot read this line: expected '[section]', 'key = "
                         "value' or a comment starting with ';' or '#'",
                         spec->path, rc);
            else
                gib_fail(err, "%s: libinih failed (%d)", spec->path, rc);
        }
        gib_scene_spec_free(spec);
        return -1;
    }
    if (gib_scene_validate(spec, err)) {
        gib_scene_spec_free(spec);
        return -1;
    }
    return 0;
}

void gib_scene_spec_free(gib_scene_spec *spec)
{
    free(spec->meshes);
    free(spec->materials);
    free(spec->lights);
    free(spec->cameras);
    spec->meshes = NULL;
    spec->materials = NULL;
    spec->lights = NULL;
    spec->cameras = NULL;
    spec->mesh_count = spec->material_count = spec->light_count = spec->camera_count = 0;
}

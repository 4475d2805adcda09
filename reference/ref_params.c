/* gibench — the reference renderer's parameters: component names, normalisation, the hash the
 * cache keys on, and the EXR header attributes (ARCHITECTURE.md, "Reference renderer": cached under a key
 * that hashes everything that changes the image). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "harness/base/cone_set.h"
#include "harness/base/hash.h"
#include "ref_internal.h"

static const char *const ref_component_names[GIB_COMP_COUNT] = {
    "ao", "direct", "indirect", "glossy", "caustic", "full", "higher", "albedo", "normal", "depth"};

const char *gib_component_name(int component)
{
    if (component < 0 || component >= GIB_COMP_COUNT)
        return "unknown";
    return ref_component_names[component];
}

int gib_component_parse(const char *name)
{
    for (int i = 0; name && i < GIB_COMP_COUNT; i++)
        if (strcmp(name, ref_component_names[i]) == 0)
            return i;
    return -1;
}

static int ref_scene_has_specular(const gib_scene *s)
{
    for (uint32_t m = 0; s && m < s->material_count; m++) {
        const gib_material *mt = &s->materials[m];
        if (mt->spec_type != GIB_SPEC_NONE &&
            (mt->specular[0] > 0.0f || mt->specular[1] > 0.0f || mt->specular[2] > 0.0f))
            return 1;
    }
    return 0;
}

static int ref_scene_has_mirror(const gib_scene *s)
{
    for (uint32_t m = 0; s && m < s->material_count; m++) {
        const gib_material *mt = &s->materials[m];
        if (mt->spec_type == GIB_SPEC_MIRROR &&
            (mt->specular[0] > 0.0f || mt->specular[1] > 0.0f || mt->specular[2] > 0.0f))
            return 1;
    }
    return 0;
}

int ref_deterministic(const gib_scene *s, int comp, int max_depth)
{
    switch (comp) {
    case GIB_COMP_DIRECT: /* every light a delta: next-event estimation is exact; a sky is not */
        return !ref_has_sky(s);
    case GIB_COMP_ALBEDO:
    case GIB_COMP_NORMAL:
    case GIB_COMP_DEPTH:
        return 1;
    case GIB_COMP_GLOSSY: /* identically 0 without a specular lobe */
    case GIB_COMP_CAUSTIC:
        return !ref_scene_has_specular(s);
    case GIB_COMP_FULL: /* one vertex: direct */
        return max_depth == 1 && !ref_has_sky(s);
    case GIB_COMP_HIGHER: /* one vertex: 0 */
        return max_depth == 1;
    default:
        return 0;
    }
}

const char *gib_ref_sampler_name(int sampler)
{
    return sampler == GIB_REF_SAMPLER_RANDOM                                   ? "random"
           : sampler == GIB_REF_SAMPLER_SOBOL || sampler == GIB_REF_SAMPLER_DEFAULT ? "sobol"
                                                                                : "unknown";
}

int gib_ref_sampler_parse(const char *name)
{
    if (name && !strcmp(name, "sobol"))
        return GIB_REF_SAMPLER_SOBOL;
    if (name && !strcmp(name, "random"))
        return GIB_REF_SAMPLER_RANDOM;
    return -1;
}

static const char *const ref_strategies_names[] = {"auto", "camera", "light-vertices"};

const char *gib_ref_strategies_name(int strategies)
{
    return strategies >= 0 && strategies <= GIB_REF_STRATEGIES_LIGHT_VERTICES
               ? ref_strategies_names[strategies]
               : "unknown";
}

int gib_ref_strategies_parse(const char *name)
{
    for (int i = 0; name && i <= GIB_REF_STRATEGIES_LIGHT_VERTICES; i++)
        if (!strcmp(name, ref_strategies_names[i]))
            return i;
    return -1;
}

int ref_sobol_round_spp(int spp)
{
    const int B = GIB_REF_SOBOL_BATCHES;
    if (spp <= B)
        return spp;
    return spp > (1 << 30) - B ? (1 << 30) / B * B : (spp + B - 1) / B * B;
}

int gib_component_deterministic(const gib_scene *scene, int component)
{
    return ref_deterministic(scene, component, GIB_REF_DEFAULT_MAX_DEPTH);
}

int ref_light_vertices(const gib_scene *s, const gib_ref_params *q)
{
    const int c = q->component;
    if (!s || !((c == GIB_COMP_FULL && q->max_depth >= 2) ||
                (c == GIB_COMP_HIGHER && q->max_depth >= 3)))
        return 0;
    for (uint32_t i = 0; i < s->light_count; i++)
        if (ref_light_emits(&s->lights[i]))
            return 1;
    return 0;
}

void gib_reference_normalize(const gib_scene *scene, const gib_ref_params *p, gib_ref_params *o)
{
    *o = *p;
    const int c = p->component;
    o->threads = 0;
    o->quiet = 0;
    o->interrupt = NULL;
    if (!scene || !scene->motion_count)
        o->time = 0.0f; /* a static scene is the same at every instant */
    int bounded = p->dmax > 0.0f && isfinite(p->dmax);
    if (c == GIB_COMP_AO) {
        o->dmax = bounded ? p->dmax : INFINITY; /* <= 0 and inf: the same unbounded image */
        o->obscurance = bounded && p->obscurance ? 1 : 0;
    } else {
        o->dmax = INFINITY;
        o->obscurance = 0;
    }
    int paths = c == GIB_COMP_FULL || c == GIB_COMP_HIGHER;
    o->max_depth = paths ? (p->max_depth > 0 ? p->max_depth : GIB_REF_DEFAULT_MAX_DEPTH) : 0;
    o->min_depth = paths ? (p->min_depth > 0 ? p->min_depth : GIB_REF_DEFAULT_MIN_DEPTH) : 0;
    o->max_specular = (c == GIB_COMP_CAUSTIC || c == GIB_COMP_HIGHER)
                          ? (p->max_specular > 0 ? p->max_specular : GIB_REF_DEFAULT_MAX_SPECULAR)
                          : 0;
    o->cone = c == GIB_COMP_INDIRECT && p->cone > 0 ? p->cone : 0;
    o->cone_aperture = o->cone ? (p->cone_aperture > 0.0f ? p->cone_aperture
                                                          : GIB_DIFFUSE_CONE_APERTURE_DEG)
                               : 0.0f;
    if (paths && o->min_depth > o->max_depth)
        o->min_depth = o->max_depth; /* no roulette: the same image */
    o->strategies = GIB_REF_STRATEGIES_AUTO; /* kept only where light vertices are possible */
    if (paths && ref_light_vertices(scene, o))
        o->strategies = p->strategies == GIB_REF_STRATEGIES_CAMERA ||
                                p->strategies == GIB_REF_STRATEGIES_LIGHT_VERTICES
                            ? p->strategies
                            : GIB_REF_STRATEGIES_AUTO;
    o->sampler = p->sampler == GIB_REF_SAMPLER_RANDOM ? GIB_REF_SAMPLER_RANDOM
                                                      : GIB_REF_SAMPLER_SOBOL;
    if (ref_deterministic(scene, c, o->max_depth)) {
        o->spp = 1;
        o->target_noise = 0.0;
        o->max_spp = 0;
        o->seed = 0;
        o->sampler = GIB_REF_SAMPLER_SOBOL; /* no numbers drawn: every sampler the same image */
    } else if (p->target_noise > 0.0) {
        o->max_spp = p->max_spp > 0 ? p->max_spp : GIB_REF_DEFAULT_MAX_SPP;
    } else {
        o->target_noise = 0.0;
        o->max_spp = 0;
    }
    if (o->sampler == GIB_REF_SAMPLER_SOBOL) { /* equal batches (reference.h) */
        o->spp = ref_sobol_round_spp(o->spp);
        o->max_spp = ref_sobol_round_spp(o->max_spp);
    }
}

uint64_t gib_reference_params_hash(const gib_scene *scene, const gib_ref_params *p)
{
    gib_ref_params n;
    gib_reference_normalize(scene, p, &n);
    uint64_t h = gib_hash_str(GIB_HASH_INIT, GIB_REFERENCE_VERSION);
    h = gib_hash_u64(h, (uint64_t)n.component);
    h = gib_hash_u64(h, (uint64_t)n.width << 32 | (uint64_t)(uint32_t)n.height);
    h = gib_hash_u64(h, (uint64_t)n.spp);
    h = gib_hash_f32(h, n.dmax);
    h = gib_hash_u64(h, (uint64_t)n.obscurance);
    h = gib_hash_u64(h, (uint64_t)n.max_depth);
    h = gib_hash_u64(h, (uint64_t)n.min_depth);
    h = gib_hash_u64(h, (uint64_t)n.max_specular);
    h = gib_hash_bytes(h, &n.target_noise, sizeof n.target_noise);
    h = gib_hash_u64(h, (uint64_t)n.max_spp);
    h = gib_hash_u64(h, n.seed);
    h = gib_hash_u64(h, (uint64_t)n.sampler);
    if (scene && scene->cameras && n.camera >= 0 && (uint32_t)n.camera < scene->camera_count) {
        const gib_camera *cam = &scene->cameras[n.camera];
        h = gib_hash_bytes(h, cam->eye, sizeof cam->eye);
        h = gib_hash_bytes(h, cam->target, sizeof cam->target);
        h = gib_hash_bytes(h, cam->up, sizeof cam->up);
        h = gib_hash_f32(h, cam->vfov_deg);
    }
    /* The sky is scene content, which the scene's content hash already covers for a scene read
     * from a file (its bytes); hashed here too for scenes built in C, whose content_hash is
     * whatever the builder set. Scenes without a sky hash nothing more. */
    if (ref_has_sky(scene))
        h = gib_hash_bytes(h, scene->sky, sizeof scene->sky);
    if (scene && scene->motion_count)
        h = gib_hash_f32(gib_hash_str(h, "time"), n.time);
    if (ref_light_vertices(scene, &n) && n.strategies != GIB_REF_STRATEGIES_CAMERA)
        h = gib_hash_u64(gib_hash_str(h, "light vertices"), (uint64_t)n.strategies);
    /* camera paths alone hash as they did before light vertices */
    if (n.cone) /* the whole hemisphere's images hash as they did before cones could be asked */
        h = gib_hash_f32(gib_hash_u64(gib_hash_str(h, "cone"), (uint64_t)n.cone), n.cone_aperture);
    return h;
}

uint64_t gib_reference_cache_key(const gib_scene *scene, const gib_ref_params *p)
{
    uint64_t h = gib_reference_params_hash(scene, p);
    return gib_hash_u64(h, scene ? scene->content_hash : 0);
}

/* ---- EXR header attributes ---- */

static int ref_attr(gib_kv *attrs, int max, int *n, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

static int ref_attr(gib_kv *attrs, int max, int *n, const char *key, const char *fmt, ...)
{
    if (*n >= max)
        return -1;
    gib_kv *kv = &attrs[*n];
    snprintf(kv->key, sizeof kv->key, "%s", key);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(kv->value, sizeof kv->value, fmt, ap);
    va_end(ap);
    ++*n;
    return 0;
}

/* full and higher's `strategies`: which the image used (the stats say; without them, what the
 * parameters ask) and how they were chosen. */
static void ref_attr_strategies(const gib_scene *scene, const gib_ref_params *q,
                                const gib_ref_stats *s, gib_kv *attrs, int max_attrs, int *n)
{
    const int possible = ref_light_vertices(scene, q);
    const int lv = s ? s->light_vertices
                     : possible && q->strategies != GIB_REF_STRATEGIES_CAMERA;
    const char *what = lv ? "camera paths and light vertices, balance heuristic" : "camera paths";
    if (possible && q->strategies == GIB_REF_STRATEGIES_AUTO && s)
        ref_attr(attrs, max_attrs, n, "strategies", s->pilot_gain > 0.0
                 ? "%s; pilot: light vertices %.3g x as efficient"
                 : "%s; pilot: nothing to measure", what, s->pilot_gain);
    else
        ref_attr(attrs, max_attrs, n, "strategies", "%s; %s", what,
                 possible ? "asked" : "no light vertices possible");
}

int gib_reference_attrs(const gib_scene *scene, const gib_ref_params *p, const gib_ref_stats *s,
                        gib_kv *attrs, int max_attrs)
{
    int n = 0;
    char hex[17], key[17];
    gib_ref_params q;
    gib_reference_normalize(scene, p, &q);
    gib_hash_hex(scene ? scene->content_hash : 0, hex);
    gib_hash_hex(gib_reference_cache_key(scene, p), key);
    const int c = q.component;
    const int mirror = ref_scene_has_mirror(scene);
    const int lt_full = (c == GIB_COMP_FULL || c == GIB_COMP_HIGHER) && mirror && q.max_depth >= 2;
    const int lt = lt_full || (c == GIB_COMP_CAUSTIC && mirror);
    const char *footprint = lt ? "centre+area (area: mirror-first paths)" : "centre";
    const char *missing = (c == GIB_COMP_FULL || c == GIB_COMP_HIGHER) && mirror &&
                                  q.max_depth >= 3
                              ? "L S_mirror (.*) S_mirror E: mirror next to the light and at the "
                                "visible point"
                              : "none";
    ref_attr(attrs, max_attrs, &n, "component", "%s", gib_component_name(c));
    ref_attr(attrs, max_attrs, &n, "spp", "%d", s && s->spp > 0 ? s->spp : q.spp);
    ref_attr(attrs, max_attrs, &n, "seconds", "%.3f", s ? s->seconds : 0.0);
    ref_attr(attrs, max_attrs, &n, "scene_hash", "%s", hex);
    ref_attr(attrs, max_attrs, &n, "renderer_version", "%s", GIB_REFERENCE_VERSION);
    ref_attr(attrs, max_attrs, &n, "noise_rmse", "%.9g", s ? s->noise_rmse : 0.0);
    ref_attr(attrs, max_attrs, &n, "mean", "%.9g", s ? s->mean : 0.0);
    ref_attr(attrs, max_attrs, &n, "width", "%d", q.width);
    ref_attr(attrs, max_attrs, &n, "height", "%d", q.height);
    if (isinf(q.dmax))
        ref_attr(attrs, max_attrs, &n, "dmax", "%s", "inf");
    else
        ref_attr(attrs, max_attrs, &n, "dmax", "%.9g", (double)q.dmax);
    ref_attr(attrs, max_attrs, &n, "seed", "%llu", (unsigned long long)p->seed);
    ref_attr(attrs, max_attrs, &n, "camera", "%d", q.camera);
    ref_attr(attrs, max_attrs, &n, "obscurance", "%d", q.obscurance);
    ref_attr(attrs, max_attrs, &n, "max_depth", "%d", q.max_depth);
    ref_attr(attrs, max_attrs, &n, "min_depth", "%d", q.min_depth);
    ref_attr(attrs, max_attrs, &n, "max_specular", "%d", q.max_specular);
    if (q.cone)
        ref_attr(attrs, max_attrs, &n, "cone", "%d of %d, aperture %.9g degrees", q.cone - 1,
                 GIB_DIFFUSE_CONES, (double)q.cone_aperture);
    ref_attr(attrs, max_attrs, &n, "target_noise", "%.9g", q.target_noise);
    ref_attr(attrs, max_attrs, &n, "max_spp", "%d", q.max_spp);
    ref_attr(attrs, max_attrs, &n, "rounds", "%d", s ? s->rounds : 0);
    ref_attr(attrs, max_attrs, &n, "estimator", "%s",
             ref_deterministic(scene, c, q.max_depth) ? "deterministic" : "random");
    ref_attr(attrs, max_attrs, &n, "sampler", "%s",
             ref_deterministic(scene, c, q.max_depth) ? "none" : gib_ref_sampler_name(q.sampler));
    ref_attr(attrs, max_attrs, &n, "footprint", "%s", footprint);
    ref_attr(attrs, max_attrs, &n, "missing", "%s", missing);
    ref_attr(attrs, max_attrs, &n, "cache_key", "%s", key);
    ref_attr(attrs, max_attrs, &n, "sky", "%.9g %.9g %.9g",
             scene ? (double)scene->sky[0] : 0.0, scene ? (double)scene->sky[1] : 0.0,
             scene ? (double)scene->sky[2] : 0.0);
    ref_attr(attrs, max_attrs, &n, "stop", "%s",
             s && s->interrupted       ? "interrupted"
             : !(q.target_noise > 0.0) ? "spp"
             : s && s->target_reached  ? "target"
                                       : "max_spp");
    if (scene && scene->motion_count)
        ref_attr(attrs, max_attrs, &n, "time", "%.9g", (double)q.time);
    if (c == GIB_COMP_FULL || c == GIB_COMP_HIGHER)
        ref_attr_strategies(scene, &q, s, attrs, max_attrs, &n);
    return n;
}

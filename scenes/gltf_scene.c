/* gibench — what a .scene takes from a glTF 2.0 file on request (FORMAT.md, "glTF scenes"):
 * cameras, KHR_lights_punctual lights and materials, read from the file's JSON with the reader of
 * gltf_bounds.c (assimp's import keeps only the meshes: scene_build.c matches its materials to
 * the file's by index, assimp 5.2's glTF2 importer keeping the file's order and adding one for
 * primitives without a material last).
 *
 * The mapping, stated in FORMAT.md:
 *  - cameras (perspective only): eye at the node's world origin, looking down its -Z with its +Y
 *    up, vertical fov = yfov; aspectRatio, znear and zfar are not part of gibench's camera (the
 *    aspect is the image's);
 *  - lights: glTF's photometric intensities to gibench's radiometric ones at 683 lm/W (candela
 *    -> W/sr for point and spot, lux -> W/m^2 for directional), times `color`; a spot's smooth
 *    falloff between its inner and outer cone becomes cos^e inside the outer cone, e chosen so
 *    that both emit the same power (gib_gltf_spot_exponent; e = 0 for a hard cone);
 *  - materials: rho_d = baseColor (1 - metallic), rho_s = baseColor metallic as a normalised
 *    Phong lobe of exponent n = 2 / alpha^2 - 2, alpha = roughness^2 (Walter et al. 2007's
 *    Beckmann-Phong equivalence), at least 1; n >= GIB_GLTF_PHONG_MAX a mirror. Dielectrics' 4%
 *    Fresnel reflection has no counterpart (no Fresnel in gibench): they are Lambertian;
 *  - extras.gibench on a material or a light (what `gibench export` writes, external_job.c):
 *    gibench's exact values, preferred to the mapping while the file's own values are the ones
 *    recorded beside them ("core"), so that an edit made since wins.
 * Whatever gibench cannot model is refused naming the file and the feature; what is harmless to
 * drop goes into info->ignored. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "gltf_file.h"

/* ------------------------------------------------------------------ the numbers of the mapping */

float gib_gltf_phong_n(float roughness)
{
    const double r = fmin(fmax((double)roughness, 0.0), 1.0), alpha = r * r;
    if (alpha * alpha * GIB_GLTF_PHONG_MAX <= 2.0)
        return INFINITY; /* n >= GIB_GLTF_PHONG_MAX: a mirror */
    return (float)fmax(2.0 / (alpha * alpha) - 2.0, 1.0);
}

/* Power of glTF's spot (t^2, t from 0 at cos outer to 1 at cos inner) over that of cos^e inside
 * the outer cone, both per 2 pi per unit intensity; e by bisection (the latter falls with e). */
float gib_gltf_spot_exponent(double inner, double outer)
{
    const double ci = cos(inner), co = cos(outer);
    const double want = (1.0 - ci) + (ci - co) / 3.0;
    double lo = 0.0, hi = 1e4;
    if ((1.0 - co) <= want * (1.0 + 1e-12))
        return 0.0f;
    for (int i = 0; i < 200; i++) {
        const double e = 0.5 * (lo + hi), p = (1.0 - pow(co, e + 1.0)) / (e + 1.0);
        if (p > want)
            lo = e;
        else
            hi = e;
    }
    return (float)(0.5 * (lo + hi));
}

/* ------------------------------------------------------------------ extensions */

/* What each extension the file uses is to gibench: handled, harmless to drop (noted), or
 * material-only (checked only with materials = gltf); any other is refused. */
enum { EXT_HANDLED, EXT_IGNORED, EXT_MATERIAL_IGNORED, EXT_MATERIAL_REFUSED };
static const struct {
    const char *name;
    int kind;
    const char *note; /* ignored: what the list says; refused: why */
} ext_table[] = {
    {"KHR_lights_punctual", EXT_HANDLED, NULL},
    {"KHR_materials_emissive_strength", EXT_HANDLED, NULL}, /* emissive itself is refused */
    {"KHR_xmp_json_ld", EXT_IGNORED, "KHR_xmp_json_ld metadata"},
    {"KHR_materials_ior", EXT_MATERIAL_IGNORED, "KHR_materials_ior (no dielectric Fresnel lobe)"},
    {"KHR_materials_specular", EXT_MATERIAL_IGNORED,
     "KHR_materials_specular (no dielectric Fresnel lobe)"},
    {"KHR_materials_variants", EXT_MATERIAL_IGNORED, "KHR_materials_variants (default materials used)"},
    {"KHR_materials_transmission", EXT_MATERIAL_REFUSED, "transmission"},
    {"KHR_materials_volume", EXT_MATERIAL_REFUSED, "volumes"},
    {"KHR_materials_clearcoat", EXT_MATERIAL_REFUSED, "clearcoat"},
    {"KHR_materials_sheen", EXT_MATERIAL_REFUSED, "sheen"},
    {"KHR_materials_iridescence", EXT_MATERIAL_REFUSED, "iridescence"},
    {"KHR_materials_anisotropy", EXT_MATERIAL_REFUSED, "anisotropy"},
    {"KHR_materials_dispersion", EXT_MATERIAL_REFUSED, "dispersion"},
    {"KHR_materials_diffuse_transmission", EXT_MATERIAL_REFUSED, "diffuse transmission"},
    {"KHR_materials_unlit", EXT_MATERIAL_REFUSED, "unlit (emissive-like) materials"},
    {"KHR_materials_pbrSpecularGlossiness", EXT_MATERIAL_REFUSED, "the specular-glossiness model"},
    {"KHR_texture_transform", EXT_MATERIAL_REFUSED, "texture transforms"},
    {"KHR_texture_basisu", EXT_MATERIAL_REFUSED, "KTX2/Basis textures"},
    {"EXT_texture_webp", EXT_MATERIAL_REFUSED, "WebP textures"},
};

static int ext_find(const char *name)
{
    for (size_t i = 0; i < sizeof ext_table / sizeof ext_table[0]; i++)
        if (strcmp(ext_table[i].name, name) == 0)
            return (int)i;
    return -1;
}

static int check_extension(const gfile *f, const char *name, unsigned want, char *ignored,
                           size_t cap, gib_error *err)
{
    int e = ext_find(name);
    if (e < 0)
        return gib_fail(err, "glTF '%s': uses extension '%s', which gibench does not read "
                             "(FORMAT.md, \"glTF scenes\")", f->path, name);
    const int mat = (want & GIB_GLTF_MATERIALS) != 0;
    switch (ext_table[e].kind) {
    case EXT_IGNORED: note(ignored, cap, ext_table[e].note); break;
    case EXT_MATERIAL_IGNORED:
        if (mat)
            note(ignored, cap, ext_table[e].note);
        break;
    case EXT_MATERIAL_REFUSED:
        if (mat)
            return gib_fail(err, "glTF '%s': uses extension '%s': gibench cannot model %s",
                            f->path, name, ext_table[e].note);
        break;
    default: break;
    }
    return 0;
}

static int check_extensions(const gfile *f, unsigned want, char *ignored, size_t cap,
                            gib_error *err)
{
    static const char *const lists[] = {"extensionsUsed", "extensionsRequired"};
    for (int l = 0; l < 2; l++) {
        int a = gib_json_get(f->j, 0, lists[l]);
        for (int k = -1; (k = gib_json_child(f->j, a, k)) >= 0;) {
            char name[128];
            if (gib_json_str(f->j, k, name, sizeof name) ||
                check_extension(f, name, want, ignored, cap, err))
                return -1;
        }
    }
    return 0;
}

/* ------------------------------------------------------------------ geometry features */

static int check_geometry(const gfile *f, unsigned want, char *ignored, size_t cap,
                          gib_error *err)
{
    if (count(f, gib_json_get(f->j, 0, "skins")))
        return gib_fail(err, "glTF '%s': has skins (skinned meshes): gibench reads static meshes "
                             "only", f->path);
    if (count(f, gib_json_get(f->j, 0, "animations")))
        return gib_fail(err, "glTF '%s': has animations: gibench reads static scenes only "
                             "(FORMAT.md, \"Motion\" for gibench's own)", f->path);
    for (int n = -1; (n = gib_json_child(f->j, gib_json_get(f->j, 0, "nodes"), n)) >= 0;)
        if (gib_json_get(f->j, n, "skin") >= 0)
            return gib_fail(err, "glTF '%s': a node has a skin: gibench reads static meshes only",
                            f->path);
    int mi = 0;
    for (int m = -1; (m = gib_json_child(f->j, gib_json_get(f->j, 0, "meshes"), m)) >= 0; mi++) {
        int prims = gib_json_get(f->j, m, "primitives");
        for (int p = -1; (p = gib_json_child(f->j, prims, p)) >= 0;) {
            double mode = 4;
            if (gib_json_get(f->j, p, "targets") >= 0)
                return gib_fail(err, "glTF '%s': mesh %d has morph targets: gibench reads static "
                                     "meshes only", f->path, mi);
            if ((want & GIB_GLTF_MATERIALS) &&
                gib_json_get(f->j, gib_json_get(f->j, p, "attributes"), "COLOR_0") >= 0)
                return gib_fail(err, "glTF '%s': mesh %d has vertex colours (COLOR_0), which "
                                     "gibench's materials cannot carry", f->path, mi);
            if (num(f, p, "mode", 4, &mode) == 0 && mode < 4)
                note(ignored, cap, "point and line primitives");
        }
    }
    return 0;
}

/* ------------------------------------------------------------------ materials */

/* The texture a textureInfo names, as a path (a file beside the glTF) or an image ref. */
static int texture_ref(const gfile *f, int info, const char *what, const char *mname,
                       char *ignored, size_t cap, double mask_scale, char *out, size_t out_len,
                       gib_error *err)
{
    int ti, src, tc = 0;
    double texcoord = 0;
    if (index_of(f, info, "index", &ti) || ti < 0 || num(f, info, "texCoord", 0, &texcoord))
        return gib_fail(err, "glTF '%s': material '%s': %s has no valid 'index'", f->path, mname,
                        what);
    tc = (int)texcoord;
    if (tc != 0)
        return gib_fail(err, "glTF '%s': material '%s': %s reads TEXCOORD_%d; gibench has one "
                             "set of texture coordinates", f->path, mname, what, tc);
    if (gib_json_get(f->j, info, "extensions") >= 0)
        return gib_fail(err, "glTF '%s': material '%s': %s has extensions (texture transforms): "
                             "not supported", f->path, mname, what);
    const int tex = top(f, "textures", ti);
    if (tex < 0 || index_of(f, tex, "source", &src) || src < 0 || top(f, "images", src) < 0)
        return gib_fail(err, "glTF '%s': material '%s': %s: texture %d has no image gibench "
                             "reads (KTX2 and WebP are not)", f->path, mname, what, ti);
    int smp = -1;
    if (index_of(f, tex, "sampler", &smp) == 0 && smp >= 0) {
        double ws = 10497, wt = 10497;
        num(f, top(f, "samplers", smp), "wrapS", 10497, &ws);
        num(f, top(f, "samplers", smp), "wrapT", 10497, &wt);
        if (ws != 10497 || wt != 10497)
            note(ignored, cap, "texture wrap modes other than repeat");
    }
    const int img = top(f, "images", src);
    const int uri = gib_json_get(f->j, img, "uri");
    const char *s;
    size_t n;
    if (mask_scale > 0) { /* the image's alpha, read from the file (textures.c) */
        if ((size_t)snprintf(out, out_len, "%s#mask%d:%.9g", f->path, src, mask_scale) >= out_len)
            return gib_fail(err, "glTF '%s': image path too long", f->path);
        return 0;
    }
    if (uri >= 0 && gib_json_span(f->j, uri, &s, &n) == 0 && !(n >= 5 && memcmp(s, "data:", 5) == 0)) {
        char rel[GIB_PATH_MAX], dir[GIB_PATH_MAX];
        gib_json_str(f->j, uri, rel, sizeof rel);
        if (strchr(rel, '%'))
            return gib_fail(err, "glTF '%s': image '%s': percent-encoded URIs are not read",
                            f->path, rel);
        gib_path_dirname(f->path, dir, sizeof dir);
        if (gib_path_join(dir, rel, out, out_len))
            return gib_fail(err, "glTF '%s': image path too long", f->path);
        return 0;
    }
    if (uri < 0 && gib_json_get(f->j, img, "bufferView") < 0)
        return gib_fail(err, "glTF '%s': image %d has neither uri nor bufferView", f->path, src);
    if ((size_t)snprintf(out, out_len, "%s#image%d", f->path, src) >= out_len)
        return gib_fail(err, "glTF '%s': image path too long", f->path);
    return 0;
}

/* Whether extras.gibench at g still describes the file: its "core" (what the exporter wrote as
 * the file's own values) equals have[0..n-1], within the printing of a float. Extras without
 * "core" are taken as they are. */
int gib_gltf_extras_current(const gfile *f, int g, const double *have, int n)
{
    double core[8];
    if (gib_json_get(f->j, g, "core") < 0)
        return 1;
    if (n > 8 || nums(f, g, "core", core, n))
        return 0;
    for (int k = 0; k < n; k++)
        if (!(fabs(core[k] - have[k]) <= 1e-6 * fmax(1.0, fabs(core[k]))))
            return 0;
    return 1;
}

/* extras.gibench of material mt: the exact gibench material (albedo, specular, spec_type,
 * phong_n, two_sided, alpha_texture) that `gibench export` writes beside the metallic-roughness
 * mapping, preferred to it while the file's factors are the ones it recorded (an editor that
 * changed them keeps its change; the stale extras are then listed as ignored). */
static int material_extras(const gfile *f, int mt, const char *name, gib_mat_desc *d,
                           char *ignored, size_t cap, gib_error *err)
{
    const int g = gib_json_get(f->j, gib_json_get(f->j, mt, "extras"), "gibench");
    const int pbr = gib_json_get(f->j, mt, "pbrMetallicRoughness");
    double have[5] = {1, 1, 1, 1, 1}, a[3], sp[3] = {0, 0, 0}, n = 1;
    if (g < 0)
        return 0;
    nums(f, pbr, "baseColorFactor", have, 3);
    num(f, pbr, "metallicFactor", 1, &have[3]);
    num(f, pbr, "roughnessFactor", 1, &have[4]);
    if (!gib_gltf_extras_current(f, g, have, 5)) {
        note(ignored, cap, "gibench extras of materials edited since export (their "
                           "metallic-roughness is used)");
        return 0;
    }
    char type[16] = "none";
    const int ts = gib_json_get(f->j, g, "spec_type"), ds = gib_json_get(f->j, g, "two_sided");
    const int st = (ts >= 0 && gib_json_str(f->j, ts, type, sizeof type)) ? -1
                   : !strcmp(type, "none")   ? GIB_SPEC_NONE
                   : !strcmp(type, "mirror") ? GIB_SPEC_MIRROR
                   : !strcmp(type, "phong")  ? GIB_SPEC_PHONG : -1;
    int ok = gib_json_get(f->j, g, "albedo") >= 0 && nums(f, g, "albedo", a, 3) == 0 &&
             nums(f, g, "specular", sp, 3) == 0 && num(f, g, "phong_n", 1, &n) == 0 && st >= 0 &&
             (st != GIB_SPEC_PHONG || n > 0);
    for (int k = 0; ok && k < 3; k++)
        ok = a[k] >= 0 && sp[k] >= 0 && a[k] + (st != GIB_SPEC_NONE ? sp[k] : 0) <= 1 + 1e-6;
    if (!ok)
        return gib_fail(err, "glTF '%s': material '%s': extras.gibench needs albedo (3 numbers), "
                             "and may give specular (3), spec_type (none, mirror, phong), "
                             "phong_n (> 0), two_sided, alpha_texture; albedo + specular at "
                             "most 1 per channel", f->path, name);
    for (int k = 0; k < 3; k++) {
        d->m.albedo[k] = (float)a[k];
        d->m.specular[k] = st != GIB_SPEC_NONE ? (float)sp[k] : 0.0f;
    }
    d->m.spec_type = st;
    d->m.phong_n = st == GIB_SPEC_PHONG ? (float)n : 1.0f;
    if (ds >= 0)
        d->m.two_sided = is_true(f, ds);
    const int at = gib_json_get(f->j, g, "alpha_texture");
    return at >= 0 ? texture_ref(f, at, "extras.gibench.alpha_texture", name, ignored, cap, 0.0,
                                 d->alpha_path, sizeof d->alpha_path, err)
                   : 0;
}

static int read_material(const gfile *f, int mt, int mi, gib_mat_desc *d, char *ignored,
                         size_t cap, gib_error *err)
{
    char name[128] = "";
    if (gib_json_str(f->j, gib_json_get(f->j, mt, "name"), name, sizeof name) || !name[0])
        snprintf(name, sizeof name, "material%d", mi);
    *d = gib_mat_desc_diffuse(name, 1, 1, 1);
    d->source_index = mi;
    const int pbr = gib_json_get(f->j, mt, "pbrMetallicRoughness");
    double base[4] = {1, 1, 1, 1}, metal = 1, rough = 1, emit[3] = {0, 0, 0};
    if (nums(f, pbr, "baseColorFactor", base, 4) || num(f, pbr, "metallicFactor", 1, &metal) ||
        num(f, pbr, "roughnessFactor", 1, &rough) || nums(f, mt, "emissiveFactor", emit, 3))
        return gib_fail(err, "glTF '%s': material '%s': baseColorFactor, metallicFactor, "
                             "roughnessFactor or emissiveFactor is not numbers", f->path, name);
    if (emit[0] > 0 || emit[1] > 0 || emit[2] > 0)
        return gib_fail(err, "glTF '%s': material '%s' is emissive (emissiveFactor %g %g %g): "
                             "gibench has no emissive surfaces (area lights)", f->path, name,
                        emit[0], emit[1], emit[2]);
    char mode[16] = "OPAQUE";
    double cutoff = 0.5;
    gib_json_str(f->j, gib_json_get(f->j, mt, "alphaMode"), mode, sizeof mode);
    const int mask = strcmp(mode, "MASK") == 0;
    if (!mask && strcmp(mode, "OPAQUE") != 0)
        return gib_fail(err, "glTF '%s': material '%s': alphaMode %s is not supported (gibench "
                             "has opaque and alpha-masked materials, no blending)", f->path, name,
                        mode);
    if (mask && (num(f, mt, "alphaCutoff", 0.5, &cutoff) || !(cutoff > 0 && cutoff <= 1)))
        return gib_fail(err, "glTF '%s': material '%s': alphaCutoff must be in (0, 1]", f->path,
                        name);
    const int ext = gib_json_get(f->j, mt, "extensions");
    for (int k = -1; (k = gib_json_child(f->j, ext, k)) >= 0;) {
        char en[128];
        gib_json_str(f->j, k, en, sizeof en);
        int e = ext_find(en);
        if (e < 0 || ext_table[e].kind == EXT_MATERIAL_REFUSED)
            return gib_fail(err, "glTF '%s': material '%s' uses extension '%s': gibench cannot "
                                 "model %s", f->path, name, en,
                            e < 0 ? "it" : ext_table[e].note);
        if (ext_table[e].kind == EXT_MATERIAL_IGNORED)
            note(ignored, cap, ext_table[e].note);
    }
    if (gib_json_get(f->j, mt, "normalTexture") >= 0)
        note(ignored, cap, "normal maps");
    if (gib_json_get(f->j, mt, "occlusionTexture") >= 0)
        note(ignored, cap, "occlusion maps");
    if (gib_json_get(f->j, pbr, "metallicRoughnessTexture") >= 0)
        note(ignored, cap, "metallic-roughness textures (their factors are used)");
    d->m.two_sided = is_true(f, gib_json_get(f->j, mt, "doubleSided")); /* default false */
    metal = fmin(fmax(metal, 0.0), 1.0);
    rough = fmin(fmax(rough, 0.0), 1.0);
    for (int c = 0; c < 3; c++) {
        const double b = fmin(fmax(base[c], 0.0), 1.0);
        d->m.albedo[c] = (float)(b * (1.0 - metal));
        d->m.specular[c] = (float)(b * metal);
    }
    if (metal > 0 && (d->m.specular[0] > 0 || d->m.specular[1] > 0 || d->m.specular[2] > 0)) {
        const float n = gib_gltf_phong_n((float)rough);
        d->m.spec_type = isfinite(n) ? GIB_SPEC_PHONG : GIB_SPEC_MIRROR;
        d->m.phong_n = isfinite(n) ? n : 1.0f;
    } else {
        d->m.specular[0] = d->m.specular[1] = d->m.specular[2] = 0.0f;
    }
    const int bct = gib_json_get(f->j, pbr, "baseColorTexture");
    if (bct >= 0 && texture_ref(f, bct, "baseColorTexture", name, ignored, cap, 0.0,
                                d->albedo_path, sizeof d->albedo_path, err))
        return -1;
    /* MASK: a texel is kept where alpha x baseColorFactor.a >= alphaCutoff; gibench's mask keeps
     * it where the mask's first channel >= 0.5, so the mask is alpha x (factor.a 0.5 / cutoff). */
    const double a = fmin(fmax(base[3], 0.0), 1.0);
    if (mask && bct < 0 && a < cutoff)
        return gib_fail(err, "glTF '%s': material '%s': alphaMode MASK with alpha %g below its "
                             "alphaCutoff %g and no texture: the material is invisible", f->path,
                        name, a, cutoff);
    if (mask && bct >= 0 && texture_ref(f, bct, "baseColorTexture", name, ignored, cap,
                                        a * 0.5 / cutoff, d->alpha_path, sizeof d->alpha_path,
                                        err))
        return -1;
    return material_extras(f, mt, name, d, ignored, cap, err);
}

/* Material mt's factors and flags as assimp would report them (gib_gltf_match). */
static void raw_material(const gfile *f, int mt, float raw[6], unsigned *flags, char name[128])
{
    const int pbr = gib_json_get(f->j, mt, "pbrMetallicRoughness");
    double v[4] = {1, 1, 1, 1}, m = 1, r = 1;
    nums(f, pbr, "baseColorFactor", v, 4);
    num(f, pbr, "metallicFactor", 1, &m);
    num(f, pbr, "roughnessFactor", 1, &r);
    for (int k = 0; k < 4; k++)
        raw[k] = (float)v[k];
    raw[4] = (float)m;
    raw[5] = (float)r;
    name[0] = '\0';
    gib_json_str(f->j, gib_json_get(f->j, mt, "name"), name, 128);
    *flags = (name[0] ? GIB_SRC_NAMED : 0u) |
             (gib_json_get(f->j, pbr, "baseColorTexture") >= 0 ? GIB_SRC_BASE_TEX : 0u) |
             (is_true(f, gib_json_get(f->j, mt, "doubleSided")) ? GIB_SRC_TWO_SIDED : 0u);
}

static int read_materials(const gfile *f, gib_gltf_info *out, gib_error *err)
{
    const int arr = gib_json_get(f->j, 0, "materials"), n = count(f, arr);
    out->mats = calloc((size_t)n + 1, sizeof *out->mats);
    out->raw = calloc((size_t)n + 1, sizeof *out->raw);
    out->raw_flags = calloc((size_t)n + 1, sizeof *out->raw_flags);
    out->raw_name = calloc((size_t)n + 1, sizeof *out->raw_name);
    if (!out->mats || !out->raw || !out->raw_flags || !out->raw_name)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "glTF '%s': out of memory", f->path);
    int i = 0;
    for (int k = -1; (k = gib_json_child(f->j, arr, k)) >= 0; i++) {
        if (read_material(f, k, i, &out->mats[i], out->ignored, sizeof out->ignored, err))
            return -1;
        raw_material(f, k, out->raw[i], &out->raw_flags[i], out->raw_name[i]);
        out->mat_count = i + 1;
    }
    return 0;
}

static int same_mapping(const gib_mat_desc *a, const gib_mat_desc *b)
{
    const gib_material *x = &a->m, *y = &b->m;
    return memcmp(x->albedo, y->albedo, sizeof x->albedo) == 0 &&
           memcmp(x->specular, y->specular, sizeof x->specular) == 0 &&
           x->spec_type == y->spec_type && x->phong_n == y->phong_n &&
           x->two_sided == y->two_sided && strcmp(a->albedo_path, b->albedo_path) == 0;
}

int gib_gltf_match(const gib_gltf_info *info, const gib_mat_desc *d, const char *path,
                   gib_error *err)
{
    if (d->src_flags & GIB_SRC_LAST)
        return -1;
    /* pass 0: name, flags and factors; pass 1 (a name written with JSON escapes, which assimp
     * decodes and gib_json_str keeps): flags and factors alone */
    for (int pass = 0; pass < 2; pass++) {
        int found = -1;
        for (int i = 0; i < info->mat_count; i++) {
            const unsigned bits = pass ? GIB_SRC_BASE_TEX | GIB_SRC_TWO_SIDED
                                       : GIB_SRC_NAMED | GIB_SRC_BASE_TEX | GIB_SRC_TWO_SIDED;
            if ((info->raw_flags[i] ^ d->src_flags) & bits)
                continue;
            if (!pass && (d->src_flags & GIB_SRC_NAMED) && strcmp(info->raw_name[i], d->m.name))
                continue;
            int k = 0;
            while (k < 6 && fabsf(info->raw[i][k] - d->src_pbr[k]) <= 1e-6f)
                k++;
            if (k < 6)
                continue;
            if (found < 0)
                found = i;
            else if (!same_mapping(&info->mats[found], &info->mats[i]))
                return gib_fail(err, "glTF '%s': materials %d and %d cannot be told apart after "
                                     "assimp's import (same factors, no distinct names); give "
                                     "them names", path, found, i), -2;
        }
        if (found >= 0)
            return found;
    }
    return gib_fail(err, "glTF '%s': assimp's material '%s' matches none of the file's", path,
                    d->m.name), -2;
}

/* ------------------------------------------------------------------ entry points */

/* The image files of the materials' base colour textures (and of gibench's masks) are there: a
 * missing one is named with the glTF that names it, whether the materials are taken or assimp
 * reads them. */
static int image_files(const gfile *f, gib_error *err)
{
    for (int m = -1; (m = gib_json_child(f->j, gib_json_get(f->j, 0, "materials"), m)) >= 0;) {
        const int pbr = gib_json_get(f->j, m, "pbrMetallicRoughness");
        const int g = gib_json_get(f->j, gib_json_get(f->j, m, "extras"), "gibench");
        const int info[2] = {gib_json_get(f->j, pbr, "baseColorTexture"),
                             gib_json_get(f->j, g, "alpha_texture")};
        for (int k = 0; k < 2; k++) {
            int ti = -1, src = -1;
            if (info[k] < 0 || index_of(f, info[k], "index", &ti) ||
                index_of(f, top(f, "textures", ti), "source", &src) || src < 0)
                continue; /* texture_ref says what is wrong, where the materials are taken */
            const int uri = gib_json_get(f->j, top(f, "images", src), "uri");
            if (uri >= 0 && uri_file_there(f->path, f->j, uri, "image", src, err))
                return -1;
        }
    }
    return 0;
}

int gib_gltf_read(const char *path, unsigned want, gib_gltf_info *out, gib_error *err)
{
    memset(out, 0, sizeof *out);
    gfile f;
    if (gfile_open(path, &f, err))
        return -1;
    int rc = check_extensions(&f, want, out->ignored, sizeof out->ignored, err) ||
             check_geometry(&f, want, out->ignored, sizeof out->ignored, err) ||
             image_files(&f, err) ||
             gib_gltf_read_nodes(&f, want, out, err) ||
             ((want & GIB_GLTF_MATERIALS) && read_materials(&f, out, err)) ? -1 : 0;
    gfile_close(&f);
    if (rc)
        gib_gltf_info_free(out);
    return rc;
}

void gib_gltf_info_free(gib_gltf_info *info)
{
    free(info->cameras);
    free(info->camera_alias);
    free(info->lights);
    free(info->mats);
    free(info->raw);
    free(info->raw_flags);
    free(info->raw_name);
    memset(info, 0, sizeof *info);
}

/* ------------------------------------------------------------------ embedded images */

int gib_gltf_image_ref(const char *path)
{
    const char *h = strrchr(path, '#');
    const int mask = h && strncmp(h, "#mask", 5) == 0;
    if (!h || (!mask && strncmp(h, "#image", 6) != 0))
        return 0;
    const char *c = h + (mask ? 5 : 6);
    if (*c < '0' || *c > '9')
        return 0;
    while (*c >= '0' && *c <= '9')
        c++;
    if (mask) {
        char *e;
        if (*c != ':' || !(strtod(c + 1, &e) > 0) || *e)
            return 0;
        return 2;
    }
    return *c ? 0 : 1;
}

static int b64(int c)
{
    return c >= 'A' && c <= 'Z'   ? c - 'A'
           : c >= 'a' && c <= 'z' ? c - 'a' + 26
           : c >= '0' && c <= '9' ? c - '0' + 52
           : c == '+'             ? 62
           : c == '/'             ? 63
                                  : -1;
}

/* A data: URI's payload, decoded (malloc'd). */
static int data_uri(const char *s, size_t n, unsigned char **out, size_t *len)
{
    const char *p = NULL;
    for (size_t i = 0; i + 8 <= n && !p; i++)
        p = memcmp(s + i, ";base64,", 8) == 0 ? s + i + 8 : NULL;
    if (!p)
        return -1;
    size_t k = n - (size_t)(p - s), o = 0;
    unsigned char *b = malloc(k / 4 * 3 + 3);
    if (!b)
        return -1;
    unsigned acc = 0;
    int bits = 0;
    for (size_t i = 0; i < k; i++) {
        int v = b64((unsigned char)p[i]);
        if (v < 0)
            break; /* '=' padding */
        acc = (acc << 6) | (unsigned)v;
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            b[o++] = (unsigned char)(acc >> bits);
        }
    }
    *out = b;
    *len = o;
    return 0;
}

/* Buffer bi's bytes (malloc'd copy). */
static int buffer_bytes(const gfile *f, int bi, unsigned char **out, size_t *len, gib_error *err)
{
    const int b = top(f, "buffers", bi), uri = gib_json_get(f->j, b, "uri");
    const char *s;
    size_t n;
    if (b < 0)
        return gib_fail(err, "glTF '%s': buffer %d does not exist", f->path, bi);
    if (uri < 0) {
        if (!f->bin || bi != 0)
            return gib_fail(err, "glTF '%s': buffer %d has no uri and no BIN chunk", f->path, bi);
        *out = malloc(f->bin_len + 1);
        if (!*out)
            return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "glTF '%s': out of memory", f->path);
        memcpy(*out, f->bin, f->bin_len);
        *len = f->bin_len;
        return 0;
    }
    gib_json_span(f->j, uri, &s, &n);
    if (n >= 5 && memcmp(s, "data:", 5) == 0)
        return data_uri(s, n, out, len) ? gib_fail(err, "glTF '%s': buffer %d: a data: URI "
                                                        "without base64", f->path, bi) : 0;
    char rel[GIB_PATH_MAX], dir[GIB_PATH_MAX], joined[GIB_PATH_MAX], found[GIB_PATH_MAX];
    gib_json_str(f->j, uri, rel, sizeof rel);
    gib_path_dirname(f->path, dir, sizeof dir);
    if (gib_path_join(dir, rel, joined, sizeof joined) ||
        gib_path_resolve_ci(joined, found, sizeof found))
        return gib_fail(err, "glTF '%s': buffer file '%s' not found", f->path, rel);
    return read_all(found, (char **)out, len, err);
}

static int image_bytes(const char *ref, unsigned char **bytes, size_t *len, char ext[8],
                       gib_error *err)
{
    char path[GIB_PATH_MAX];
    const char *h = strrchr(ref, '#');
    snprintf(path, sizeof path, "%.*s", (int)(h - ref), ref);
    const int ii = atoi(h + (h[1] == 'm' ? 5 : 6));
    gfile f;
    if (gfile_open(path, &f, err))
        return -1;
    int rc = 0, img = top(&f, "images", ii), uri = gib_json_get(f.j, img, "uri"), bv = -1;
    char mime[64] = "";
    gib_json_str(f.j, gib_json_get(f.j, img, "mimeType"), mime, sizeof mime);
    if (uri >= 0) {
        const char *s;
        size_t n;
        gib_json_span(f.j, uri, &s, &n);
        if (n > 11 && memcmp(s, "data:image/", 11) == 0)
            snprintf(mime, sizeof mime, "%.*s", (int)strcspn(s + 5, ";,"), s + 5);
        if (!(n >= 5 && memcmp(s, "data:", 5) == 0)) { /* a file beside the glTF (masks) */
            char rel[GIB_PATH_MAX], dir[GIB_PATH_MAX], joined[GIB_PATH_MAX], found[GIB_PATH_MAX];
            gib_json_str(f.j, uri, rel, sizeof rel);
            gib_path_dirname(path, dir, sizeof dir);
            const char *dot = strrchr(rel, '.');
            if (!mime[0])
                snprintf(mime, sizeof mime, "%s", dot && (strcasecmp(dot, ".jpg") == 0 ||
                                                          strcasecmp(dot, ".jpeg") == 0)
                                                      ? "image/jpeg" : "image/png");
            if (gib_path_join(dir, rel, joined, sizeof joined) ||
                gib_path_resolve_ci(joined, found, sizeof found))
                rc = gib_fail(err, "glTF '%s': image file '%s' not found", path, rel);
            else
                rc = read_all(found, (char **)bytes, len, err);
        } else if (data_uri(s, n, bytes, len))
            rc = gib_fail(err, "glTF '%s': image %d: a data: URI without base64", path, ii);
    } else if (index_of(&f, img, "bufferView", &bv) || bv < 0 || top(&f, "bufferViews", bv) < 0) {
        rc = gib_fail(err, "glTF '%s': image %d has no valid bufferView", path, ii);
    } else {
        const int v = top(&f, "bufferViews", bv);
        double off = 0, blen = 0;
        int bi = 0;
        unsigned char *buf = NULL;
        size_t have = 0;
        num(&f, v, "byteOffset", 0, &off);
        num(&f, v, "byteLength", 0, &blen);
        index_of(&f, v, "buffer", &bi);
        if ((rc = buffer_bytes(&f, bi, &buf, &have, err)) == 0) {
            if (off < 0 || blen < 0 || off + blen > (double)have)
                rc = gib_fail(err, "glTF '%s': image %d: bufferView %d lies outside its buffer",
                              path, ii, bv);
            else if ((*bytes = malloc((size_t)blen + 1)) == NULL)
                rc = gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "glTF '%s': out of memory", path);
            else
                memcpy(*bytes, buf + (size_t)off, (size_t)blen), *len = (size_t)blen;
        }
        free(buf);
    }
    if (rc == 0)
        snprintf(ext, 8, "%s", strcmp(mime, "image/jpeg") == 0 ? ".jpg" : ".png");
    if (rc == 0 && strcmp(mime, "image/jpeg") != 0 && strcmp(mime, "image/png") != 0) {
        free(*bytes);
        *bytes = NULL;
        rc = gib_fail(err, "glTF '%s': image %d has mimeType '%s'; gibench reads image/png and "
                           "image/jpeg", path, ii, mime);
    }
    gfile_close(&f);
    return rc;
}

int gib_gltf_image_bytes(const char *ref, unsigned char **bytes, size_t *len, char ext[8],
                         float *mask_scale, char *errbuf, int errbuf_len)
{
    gib_error e;
    *bytes = NULL;
    *len = 0;
    *mask_scale = gib_gltf_image_ref(ref) == 2 ? strtof(strrchr(ref, ':') + 1, NULL) : 0.0f;
    if (!gib_gltf_image_ref(ref)) {
        snprintf(errbuf, (size_t)errbuf_len, "'%s' is not a glTF image", ref);
        return -1;
    }
    if (image_bytes(ref, bytes, len, ext, &e)) {
        snprintf(errbuf, (size_t)errbuf_len, "%s", e.msg);
        return -1;
    }
    return 0;
}

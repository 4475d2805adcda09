/* gibench — an external technique's job (external.h), also what `gibench export` writes: the
 * scene at the row's instant as a JSON description beside a glTF 2.0 file that holds the whole
 * scene (geometry, materials, the row's camera, the lights), and the outputs expected back. The
 * format is documented in examples/external_renderer/README.md; the glTF reads back through a
 * .scene's `gltf =` (scenes/FORMAT.md, "glTF scenes"). */
#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "external.h"
#include "harness/imaging/image.h"
#include "harness/imaging/oiio_shim.h"

/* A JSON string (quotes, backslashes and control characters escaped). */
static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

/* A finite number (%.9g), or null. */
static void json_num(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.9g", v);
    else
        fputs("null", f);
}

/* A double that reads back as the same double: %.9g where it is a float's value (shorter, and
 * exact for a float), else %.17g; null when not finite. */
static void json_dbl(FILE *f, double v)
{
    if (!isfinite(v))
        fputs("null", f);
    else
        fprintf(f, (double)(float)v == v ? "%.9g" : "%.17g", v == 0 ? 0.0 : v); /* not -0 */
}

static void json_dbls(FILE *f, const double *v, int n)
{
    fputc('[', f);
    for (int i = 0; i < n; i++) {
        json_dbl(f, v[i]);
        fputs(i < n - 1 ? ", " : "]", f);
    }
}

static void json_vec3(FILE *f, const float *v)
{
    fputc('[', f);
    for (int i = 0; i < 3; i++) {
        json_num(f, v[i]);
        fputs(i < 2 ? ", " : "]", f);
    }
}

/* ---- the glTF: one shared vertex buffer, one mesh (one primitive) per material that has
 * triangles, the row's camera, the lights (KHR_lights_punctual), each in core glTF as the importer
 * (scenes/gltf_scene.c, gltf_nodes.c) reads it back, and gibench's exact values in extras where
 * core glTF cannot carry them (scenes/FORMAT.md, "glTF scenes") ---- */

/* The triangles of each material, in material order: per material its first index and count
 * (indices into the reordered list `out`). Returns 0, or -1 when out of memory. */
static int group_by_material(const gib_scene *s, uint32_t **out, uint32_t *first, uint32_t *count)
{
    *out = malloc((size_t)s->triangle_count * 3 * sizeof **out + 4);
    if (!*out)
        return -1;
    memset(count, 0, s->material_count * sizeof *count);
    for (uint32_t t = 0; t < s->triangle_count; t++)
        count[s->tri_material[t]] += 3;
    for (uint32_t m = 0, acc = 0; m < s->material_count; m++) {
        first[m] = acc;
        acc += count[m];
    }
    uint32_t *fill = calloc(s->material_count ? s->material_count : 1, sizeof *fill);
    if (!fill) {
        free(*out);
        return -1;
    }
    for (uint32_t t = 0; t < s->triangle_count; t++) {
        uint32_t m = s->tri_material[t];
        memcpy(*out + first[m] + fill[m], s->indices + 3 * (size_t)t, 3 * sizeof(uint32_t));
        fill[m] += 3;
    }
    free(fill);
    return 0;
}

/* scene.bin: positions, normals, uvs (vertex_count each), then the grouped indices. glTF's
 * texture coordinates have v = 0 at the image's top row, gibench's at its bottom (scene.h). */
static int write_bin(const char *path, const gib_scene *s, const uint32_t *idx, gib_error *err)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return gib_fail(err, "cannot write %s", path);
    size_t nv = s->vertex_count, ni = (size_t)s->triangle_count * 3;
    int ok = fwrite(s->positions, 12, nv, f) == nv && fwrite(s->normals, 12, nv, f) == nv;
    for (size_t v = 0; ok && v < nv; v++) { /* uvs, zero where the scene has none */
        const float uv[2] = {s->uvs ? s->uvs[2 * v] : 0.0f,
                             s->uvs ? 1.0f - s->uvs[2 * v + 1] : 0.0f};
        ok = fwrite(uv, 8, 1, f) == 1;
    }
    ok = ok && fwrite(idx, 4, ni, f) == ni;
    if (fclose(f) != 0 || !ok)
        return gib_fail(err, "cannot write %s", path);
    return 0;
}

/* The accessors: positions (with their bounds), normals, uvs, then one index list per material
 * that has triangles (count[m] > 0), in material order. */
static void gltf_accessors(FILE *f, const gib_scene *s, const uint32_t *first,
                           const uint32_t *count)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = 0; v < s->vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], s->positions[3 * v + k]);
            hi[k] = fmaxf(hi[k], s->positions[3 * v + k]);
        }
    size_t nv = s->vertex_count;
    fprintf(f, "  \"bufferViews\": [\n"
               "    {\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": %zu, \"target\": 34962},\n"
               "    {\"buffer\": 0, \"byteOffset\": %zu, \"byteLength\": %zu, \"target\": 34962},\n"
               "    {\"buffer\": 0, \"byteOffset\": %zu, \"byteLength\": %zu, \"target\": 34962},\n"
               "    {\"buffer\": 0, \"byteOffset\": %zu, \"byteLength\": %zu, \"target\": 34963}\n"
               "  ],\n",
            nv * 12, nv * 12, nv * 12, nv * 24, nv * 8, nv * 32,
            (size_t)s->triangle_count * 12);
    fprintf(f, "  \"accessors\": [\n    {\"bufferView\": 0, \"componentType\": 5126, \"count\": %zu, "
               "\"type\": \"VEC3\", \"min\": ", nv);
    json_vec3(f, lo);
    fputs(", \"max\": ", f);
    json_vec3(f, hi);
    fprintf(f, "},\n    {\"bufferView\": 1, \"componentType\": 5126, \"count\": %zu, \"type\": "
               "\"VEC3\"},\n    {\"bufferView\": 2, \"componentType\": 5126, \"count\": %zu, "
               "\"type\": \"VEC2\"}", nv, nv);
    for (uint32_t m = 0; m < s->material_count; m++)
        if (count[m])
            fprintf(f, ",\n    {\"bufferView\": 3, \"byteOffset\": %zu, \"componentType\": 5125, "
                       "\"count\": %u, \"type\": \"SCALAR\"}", (size_t)first[m] * 4, count[m]);
    fputs("\n  ],\n", f);
}

/* ---- the camera and the lights as nodes ---- */

static void v3_cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static void v3_normalize(double v[3])
{
    const double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; l > 0 && k < 3; k++)
        v[k] /= l;
}

/* The unit quaternion (x, y, z, w) of the rotation whose matrix has the columns ax, ay, az
 * (orthonormal, right-handed): Shepperd's method, led by the largest of w, x, y, z. */
static void quat_from_axes(const double ax[3], const double ay[3], const double az[3], double q[4])
{
    const double tr = ax[0] + ay[1] + az[2];
    if (tr > 0) {
        const double s = 2.0 * sqrt(1.0 + tr);
        q[0] = (ay[2] - az[1]) / s, q[1] = (az[0] - ax[2]) / s, q[2] = (ax[1] - ay[0]) / s;
        q[3] = 0.25 * s;
    } else if (ax[0] >= ay[1] && ax[0] >= az[2]) {
        const double s = 2.0 * sqrt(1.0 + ax[0] - ay[1] - az[2]);
        q[0] = 0.25 * s, q[1] = (ay[0] + ax[1]) / s, q[2] = (az[0] + ax[2]) / s;
        q[3] = (ay[2] - az[1]) / s;
    } else if (ay[1] >= az[2]) {
        const double s = 2.0 * sqrt(1.0 + ay[1] - ax[0] - az[2]);
        q[0] = (ay[0] + ax[1]) / s, q[1] = 0.25 * s, q[2] = (az[1] + ay[2]) / s;
        q[3] = (az[0] - ax[2]) / s;
    } else {
        const double s = 2.0 * sqrt(1.0 + az[2] - ax[0] - ay[1]);
        q[0] = (az[0] + ax[2]) / s, q[1] = (az[1] + ay[2]) / s, q[2] = 0.25 * s;
        q[3] = (ax[1] - ay[0]) / s;
    }
}

/* The row's camera as a node at the eye whose -Z is the view direction and +Y the camera's up
 * (gibench's basis, gib_camera_basis, in double): the importer's reading (gltf_nodes.c). */
static void gltf_camera_node(FILE *f, const gib_camera *c)
{
    double fwd[3], up[3], right[3], y[3], z[3], q[4];
    for (int k = 0; k < 3; k++)
        fwd[k] = (double)c->target[k] - c->eye[k], up[k] = c->up[k];
    v3_normalize(fwd);
    v3_cross(fwd, up, right);
    v3_normalize(right);
    v3_cross(right, fwd, y);
    for (int k = 0; k < 3; k++)
        z[k] = -fwd[k];
    quat_from_axes(right, y, z, q);
    fputs(",\n    {\"name\": ", f);
    json_str(f, c->name);
    fputs(", \"camera\": 0, \"translation\": ", f);
    json_vec3(f, c->eye);
    fputs(", \"rotation\": ", f);
    json_dbls(f, q, 4);
    fputc('}', f);
}

/* Light i's node: at its position (not a directional light's), its -Z along the light's
 * direction (spot and directional lights; a point light's node is not turned). */
static void gltf_light_node(FILE *f, const gib_light *l, uint32_t i)
{
    fputs(",\n    {\"name\": ", f);
    json_str(f, l->name);
    if (l->type != GIB_LIGHT_DIRECTIONAL) {
        fputs(", \"translation\": ", f);
        json_vec3(f, l->position);
    }
    if (l->type != GIB_LIGHT_POINT) {
        double z[3], a[3] = {0, 1, 0}, x[3], y[3], q[4];
        for (int k = 0; k < 3; k++)
            z[k] = -(double)l->direction[k];
        v3_normalize(z);
        if (fabs(z[1]) > 0.9)
            a[0] = 1, a[1] = 0;
        v3_cross(a, z, x);
        v3_normalize(x);
        v3_cross(z, x, y);
        quat_from_axes(x, y, z, q);
        fputs(", \"rotation\": ", f);
        json_dbls(f, q, 4);
    }
    fprintf(f, ", \"extensions\": {\"KHR_lights_punctual\": {\"light\": %u}}}", i);
}

/* ---- KHR_lights_punctual: the importer's mapping inverted ---- */

/* The importer's luminous efficacy (scenes/FORMAT.md, "glTF scenes"): 683 lm/W. */
#define GLTF_LM_PER_W 683.0

/* Light l in glTF's terms: core[0..2] colour (its largest channel 1), core[3] intensity (cd
 * for point and spot, lux for directional), and for a spot core[4..5] the inner and outer cone
 * angles: the outer angle gibench's (at most pi/2), the inner one that makes glTF's smooth edge
 * emit the power of gibench's cos^e inside the outer cone (the importer's rule solved for the
 * inner angle; e beyond what an inner angle of 0 gives keeps 0). */
static void light_core(const gib_light *l, double core[6])
{
    const double m = fmax(fmax(l->intensity[0], l->intensity[1]), l->intensity[2]);
    for (int k = 0; k < 3; k++)
        core[k] = m > 0 ? l->intensity[k] / m : 1.0;
    core[3] = m > 0 ? m * GLTF_LM_PER_W : 0.0;
    if (l->type != GIB_LIGHT_SPOT)
        return;
    const double o = fmin((double)l->spot_outer_deg, 90.0) * M_PI / 180.0, co = cos(o);
    const double e = l->spot_exponent, p = (1.0 - pow(co, e + 1.0)) / (e + 1.0);
    const double ci = 1.0 - (3.0 * p - (1.0 - co)) / 2.0;
    core[4] = acos(fmin(fmax(ci, co), 1.0));
    core[5] = o;
}

static void gltf_lights(FILE *f, const gib_scene *s)
{
    static const char *types[] = {"point", "spot", "directional"};
    fputs("  \"extensions\": {\"KHR_lights_punctual\": {\"lights\": [", f);
    for (uint32_t i = 0; i < s->light_count; i++) {
        const gib_light *l = &s->lights[i];
        const int spot = l->type == GIB_LIGHT_SPOT;
        double c[6];
        light_core(l, c);
        fprintf(f, "%s\n    {\"name\": ", i ? "," : "");
        json_str(f, l->name);
        fprintf(f, ", \"type\": \"%s\", \"color\": ", types[l->type % 3]);
        json_dbls(f, c, 3);
        fputs(", \"intensity\": ", f);
        json_dbl(f, c[3]);
        if (spot) {
            fputs(", \"spot\": {\"innerConeAngle\": ", f);
            json_dbl(f, c[4]);
            fputs(", \"outerConeAngle\": ", f);
            json_dbl(f, c[5]);
            fputc('}', f);
        }
        fputs(",\n     \"extras\": {\"gibench\": {\"intensity\": ", f);
        json_vec3(f, l->intensity);
        if (spot)
            fprintf(f, ", \"spot_exponent\": %.9g, \"spot_outer_deg\": %.9g", l->spot_exponent,
                    l->spot_outer_deg);
        fputs(", \"core\": ", f);
        json_dbls(f, c, spot ? 6 : 4);
        fputs("}}}", f);
    }
    fputs("\n  ]}},\n", f);
}

/* ---- materials and images ---- */

/* Material mt as metallic-roughness, the importer's mapping inverted: core[0..2] the base colour
 * rho_d + rho_s, core[3] metallic (the specular share of the base colour, exact where it is the
 * same in every channel), core[4] roughness: 1 without a lobe, 0 for a mirror, and for a Phong
 * lobe r with n = 2 / alpha^2 - 2, alpha = r^2 (exact for 1 <= n < 9998; outside, the importer's
 * clamp to n >= 1 and its mirror above). */
static void material_core(const gib_material *mt, double core[5])
{
    const int lobe = mt->spec_type != GIB_SPEC_NONE;
    double sb = 0, ss = 0;
    for (int k = 0; k < 3; k++) {
        core[k] = (double)mt->albedo[k] + (lobe ? mt->specular[k] : 0.0f);
        sb += core[k];
        ss += lobe ? mt->specular[k] : 0.0f;
    }
    core[3] = sb > 0 ? ss / sb : 0.0;
    core[4] = !lobe || ss == 0 ? 1.0
              : mt->spec_type == GIB_SPEC_MIRROR ? 0.0
                                                 : pow(2.0 / ((double)mt->phong_n + 2.0), 0.25);
    if (ss == 0)
        core[3] = 0.0;
}

static void gltf_material(FILE *f, const gib_material *mt, uint32_t m)
{
    static const char *spec[] = {"none", "mirror", "phong"};
    double c[5];
    material_core(mt, c);
    fprintf(f, "%s\n    {\"name\": ", m ? "," : "");
    json_str(f, mt->name);
    fprintf(f, ", \"doubleSided\": %s, \"pbrMetallicRoughness\": {\"baseColorFactor\": ",
            mt->two_sided ? "true" : "false");
    const double base[4] = {c[0], c[1], c[2], 1.0};
    json_dbls(f, base, 4);
    fputs(", \"metallicFactor\": ", f);
    json_dbl(f, c[3]);
    fputs(", \"roughnessFactor\": ", f);
    json_dbl(f, c[4]);
    if (mt->albedo_tex >= 0)
        fprintf(f, ", \"baseColorTexture\": {\"index\": %d}", mt->albedo_tex);
    fprintf(f, "},\n     \"extras\": {\"gibench_material\": %u, \"gibench\": {\"albedo\": ", m);
    json_vec3(f, mt->albedo);
    fputs(", \"specular\": ", f);
    json_vec3(f, mt->specular);
    fprintf(f, ", \"spec_type\": \"%s\", \"phong_n\": %.9g, \"two_sided\": %s",
            spec[mt->spec_type % 3], mt->phong_n, mt->two_sided ? "true" : "false");
    if (mt->alpha_tex >= 0)
        fprintf(f, ", \"alpha_texture\": {\"index\": %d}", mt->alpha_tex);
    fputs(", \"core\": ", f);
    json_dbls(f, c, 5);
    fputs("}}}", f);
}

/* Whether a path can stand in a glTF URI as it is: no character URIs percent-encode (the
 * importer refuses '%'). */
static int uri_safe(const char *p)
{
    for (; *p; p++)
        if (!(isalnum((unsigned char)*p) || strchr("/-._~+", *p)))
            return 0;
    return 1;
}

/* Texture t as loaded, written to path as an 8-bit RGB PNG: colour sRGB-encoded (textures are
 * decoded to linear), a mask as it is. */
static int write_texture_png(const gib_texture *tx, int srgb, const char *path, gib_error *err)
{
    const size_t n = (size_t)tx->width * (size_t)tx->height;
    unsigned char *px = malloc(n * 3 + 1);
    if (!px)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory writing %s", path);
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            const float v = tx->rgba[4 * i + (size_t)c];
            px[3 * i + (size_t)c] =
                (unsigned char)lrintf(255.0f * (srgb ? gib_srgb_encode(v) : fminf(fmaxf(v, 0), 1)));
        }
    char eb[512];
    const int rc = gib_oiio_write_png8(path, tx->width, tx->height, 3, px, eb, (int)sizeof eb);
    free(px);
    return rc ? gib_fail(err, "cannot write %s: %s", path, eb) : 0;
}

/* Image t's URI: the texture's own file by its absolute path where glTF readers take it as it
 * is (a PNG or JPEG whose path needs no percent-encoding); else the texture as loaded, written
 * beside the glTF as texture<t>.png (an image inside a .glb, another format, an odd path). */
static int image_uri(const gib_scene *s, uint32_t t, const char *dir, char *uri, size_t cap,
                     gib_error *err)
{
    const char *p = s->textures[t].path, *dot = strrchr(p, '.');
    char abs[PATH_MAX];
    const int png_jpeg = dot && (!strcasecmp(dot, ".png") || !strcasecmp(dot, ".jpg") ||
                                 !strcasecmp(dot, ".jpeg"));
    if (png_jpeg && realpath(p, abs) && strlen(abs) < cap && uri_safe(abs)) {
        snprintf(uri, cap, "%s", abs);
        return 0;
    }
    int colour = 0;
    for (uint32_t m = 0; m < s->material_count; m++)
        colour |= s->materials[m].albedo_tex == (int)t;
    char path[2200];
    snprintf(uri, cap, "texture%u.png", t);
    if ((size_t)snprintf(path, sizeof path, "%s/texture%u.png", dir, t) >= sizeof path)
        return gib_fail(err, "the job folder's path is too long: %s", dir);
    return write_texture_png(&s->textures[t], colour, path, err);
}

/* Materials (metallic-roughness, gibench's exact material in extras.gibench, the index into
 * job.json's materials in extras.gibench_material), then the images and their textures. */
static int gltf_materials(FILE *f, const gib_scene *s, const char *dir, gib_error *err)
{
    fputs("  \"materials\": [", f);
    for (uint32_t m = 0; m < s->material_count; m++)
        gltf_material(f, &s->materials[m], m);
    fputs("\n  ],\n", f);
    if (!s->texture_count) /* glTF's arrays are never empty */
        return 0;
    fputs("  \"images\": [", f);
    for (uint32_t t = 0; t < s->texture_count; t++) {
        char uri[PATH_MAX];
        if (image_uri(s, t, dir, uri, sizeof uri, err))
            return -1;
        fprintf(f, "%s\n    {\"uri\": ", t ? "," : "");
        json_str(f, uri);
        fputc('}', f);
    }
    fputs("\n  ],\n  \"textures\": [", f);
    for (uint32_t t = 0; t < s->texture_count; t++)
        fprintf(f, "%s\n    {\"source\": %u}", t ? "," : "", t);
    fputs("\n  ],\n", f);
    return 0;
}

/* ---- the file ---- */

/* The scene's root nodes: 0 holds the meshes; then the camera and the lights. The sky, the
 * exposure and closedness (not glTF's) go into the scene's extras.gibench. */
static void gltf_scene(FILE *f, const gib_scene *s)
{
    fputs("  \"scene\": 0,\n  \"scenes\": [{\"nodes\": [0, 1", f);
    for (uint32_t i = 0; i < s->light_count; i++)
        fprintf(f, ", %u", i + 2);
    fputs("],\n    \"extras\": {\"gibench\": {\"sky\": ", f);
    json_vec3(f, s->sky);
    fprintf(f, ", \"exposure\": %.9g, \"closed\": %d, \"description\": ", s->exposure,
            (s->features & GIB_FEAT_CLOSED) != 0);
    json_str(f, s->description);
    fputs("}}}],\n", f);
}

static void gltf_nodes(FILE *f, const gib_external_request *rq, const uint32_t *count)
{
    const gib_scene *s = rq->scene;
    const gib_camera *c = &rq->scene->cameras[rq->camera];
    uint32_t meshes = 0;
    for (uint32_t m = 0; m < s->material_count; m++)
        meshes += count[m] > 0;
    fputs("  \"nodes\": [{\"name\": \"world\"", f);
    for (uint32_t k = 0; k < meshes; k++) /* glTF's arrays are never empty */
        fprintf(f, "%s%u", k ? ", " : ", \"children\": [", k + 2 + s->light_count);
    fputs(meshes ? "]}" : "}", f);
    gltf_camera_node(f, c);
    for (uint32_t i = 0; i < s->light_count; i++)
        gltf_light_node(f, &s->lights[i], i);
    for (uint32_t k = 0; k < meshes; k++)
        fprintf(f, ",\n    {\"mesh\": %u}", k);
    fputs("],\n  \"meshes\": [", f);
    for (uint32_t m = 0, k = 0; m < s->material_count; m++)
        if (count[m]) {
            fprintf(f, "%s\n    {\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1, "
                       "\"TEXCOORD_0\": 2}, \"indices\": %u, \"material\": %u, \"mode\": 4}]}",
                    k ? "," : "", k + 3, m);
            k++;
        }
    fputs("\n  ],\n  \"cameras\": [{\"name\": ", f);
    json_str(f, c->name);
    fputs(", \"type\": \"perspective\", \"perspective\": {\"yfov\": ", f);
    json_dbl(f, (double)c->vfov_deg * M_PI / 180.0);
    fputs(", \"aspectRatio\": ", f);
    json_dbl(f, (double)rq->width / rq->height);
    fputs(", \"znear\": 0.001}}],\n", f);
}

static int gltf_body(FILE *f, const gib_external_request *rq, const char *dir,
                     const uint32_t *first, const uint32_t *count, gib_error *err)
{
    const gib_scene *s = rq->scene;
    fputs("{\n  \"asset\": {\"version\": \"2.0\", \"generator\": \"gibench\"},\n", f);
    if (s->light_count)
        fputs("  \"extensionsUsed\": [\"KHR_lights_punctual\"],\n", f);
    gltf_scene(f, s);
    gltf_nodes(f, rq, count);
    if (s->light_count)
        gltf_lights(f, s);
    if (gltf_materials(f, s, dir, err))
        return -1;
    gltf_accessors(f, s, first, count);
    fprintf(f, "  \"buffers\": [{\"uri\": \"scene.bin\", \"byteLength\": %zu}]\n}\n",
            (size_t)s->vertex_count * 32 + (size_t)s->triangle_count * 12);
    return 0;
}

static int write_gltf(const char *dir, const gib_external_request *rq, gib_error *err)
{
    const gib_scene *s = rq->scene;
    char path[2048];
    uint32_t *idx, *first = calloc(s->material_count + 1, 4), *count = calloc(s->material_count + 1, 4);
    if (!first || !count || group_by_material(s, &idx, first, count) < 0) {
        free(first), free(count);
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory writing the glTF");
    }
    snprintf(path, sizeof path, "%s/scene.bin", dir);
    int rc = write_bin(path, s, idx, err);
    free(idx);
    snprintf(path, sizeof path, "%s/scene.gltf", dir);
    FILE *f = rc == 0 ? fopen(path, "w") : NULL;
    if (rc == 0 && !f)
        rc = gib_fail(err, "cannot write %s", path);
    if (f) {
        rc = gltf_body(f, rq, dir, first, count, err);
        if (fclose(f) != 0 && rc == 0)
            rc = gib_fail(err, "cannot write %s", path);
    }
    free(first), free(count);
    return rc;
}

/* ---- job.json ---- */

static void job_camera(FILE *f, const gib_external_request *rq)
{
    const gib_camera *c = &rq->scene->cameras[rq->camera];
    float right[3], up[3], fwd[3];
    gib_camera_basis(c, right, up, fwd);
    fputs("  \"camera\": {\"name\": ", f);
    json_str(f, c->name);
    fputs(", \"position\": ", f);
    json_vec3(f, c->eye);
    fputs(", \"target\": ", f);
    json_vec3(f, c->target);
    fputs(", \"look\": ", f);
    json_vec3(f, fwd);
    fputs(", \"up\": ", f);
    json_vec3(f, up);
    fputs(", \"right\": ", f);
    json_vec3(f, right);
    fprintf(f, ", \"vfov_deg\": %.9g, \"width\": %d, \"height\": %d, \"row0\": \"top\",\n"
               "    \"rays\": \"pixel (x, y) centre: dir = normalize(look + sx * right + sy * up), "
               "sx = (2 (x + 0.5) / width - 1) * tan(vfov / 2) * width / height, "
               "sy = (1 - 2 (y + 0.5) / height) * tan(vfov / 2)\"},\n",
            c->vfov_deg, rq->width, rq->height);
}

static void job_lights(FILE *f, const gib_scene *s)
{
    static const char *types[] = {"point", "spot", "directional"};
    fputs("  \"lights\": [", f);
    for (uint32_t i = 0; i < s->light_count; i++) {
        const gib_light *l = &s->lights[i];
        fprintf(f, "%s\n    {\"name\": ", i ? "," : "");
        json_str(f, l->name);
        fprintf(f, ", \"type\": \"%s\", \"position\": ", types[l->type % 3]);
        json_vec3(f, l->position);
        fputs(", \"direction\": ", f);
        json_vec3(f, l->direction);
        fputs(", \"intensity\": ", f);
        json_vec3(f, l->intensity);
        fprintf(f, ", \"units\": \"%s\"", l->type == GIB_LIGHT_DIRECTIONAL ? "W/m^2 (irradiance "
                "on a surface facing it; direction is where the light travels)" : "W/sr (radiance "
                "of a Lambertian surface: rho/pi I falloff cos / r^2)");
        if (l->type == GIB_LIGHT_SPOT)
            fprintf(f, ", \"spot_exponent\": %.9g, \"spot_outer_deg\": %.9g, \"falloff\": "
                       "\"cos^exponent(angle to direction) inside the outer half-angle, 0 outside\"",
                    l->spot_exponent, l->spot_outer_deg);
        fputc('}', f);
    }
    fputs("\n  ],\n", f);
}

static void job_materials(FILE *f, const gib_scene *s)
{
    static const char *spec[] = {"none", "mirror", "phong"};
    fputs("  \"materials\": [", f);
    for (uint32_t m = 0; m < s->material_count; m++) {
        const gib_material *mt = &s->materials[m];
        fprintf(f, "%s\n    {\"index\": %u, \"name\": ", m ? "," : "", m);
        json_str(f, mt->name);
        fputs(", \"albedo\": ", f);
        json_vec3(f, mt->albedo);
        fputs(", \"albedo_texture\": ", f);
        if (mt->albedo_tex >= 0)
            json_str(f, s->textures[mt->albedo_tex].path);
        else
            fputs("null", f);
        fputs(", \"alpha_texture\": ", f);
        if (mt->alpha_tex >= 0)
            json_str(f, s->textures[mt->alpha_tex].path);
        else
            fputs("null", f);
        fprintf(f, ", \"specular\": \"%s\", \"specular_albedo\": ", spec[mt->spec_type % 3]);
        json_vec3(f, mt->specular);
        fprintf(f, ", \"phong_n\": %.9g, \"two_sided\": %s}", mt->phong_n,
                mt->two_sided ? "true" : "false");
    }
    fputs("\n  ],\n", f);
}

/* What each component includes (ARCHITECTURE.md, "Light-transport components"). */
static const char *component_paths(unsigned bit)
{
    switch (bit) {
    case GIB_OUT_AO: return "(1/pi) integral of V(x,w) cos dw over the hemisphere of the first "
                            "visible point; V = 0 if a hit lies within dmax, else 1; with "
                            "obscurance, V = min(d/dmax, 1); the same value in R, G and B";
    case GIB_OUT_DIRECT: return "L D E and L S E: light from every light (and the sky) reflected "
                                "once, at the first visible point, with shadows";
    case GIB_OUT_INDIRECT: return "L D D E: light reflected diffusely twice";
    case GIB_OUT_GLOSSY: return "L D S E: light reflected diffusely, then specularly at the "
                                "visible point";
    case GIB_OUT_CAUSTIC: return "L S+ D E: light reflected by mirrors, then diffusely";
    default: return "";
    }
}

static void job_components(FILE *f, const gib_external_request *rq, const char *dir)
{
    const gib_technique *t = &rq->x->technique;
    int first = 1;
    fputs("  \"components\": [", f);
    for (unsigned bit = 1; bit <= GIB_OUT_CAUSTIC; bit <<= 1) {
        if (!(t->components & bit))
            continue;
        char out[2200];
        snprintf(out, sizeof out, "%s/%s.exr", dir, gib_output_name(bit));
        fprintf(f, "%s\n    {\"name\": \"%s\", \"paths\": ", first ? "" : ",",
                gib_output_name(bit));
        json_str(f, component_paths(bit));
        fputs(", \"output\": ", f);
        json_str(f, out);
        if (bit == GIB_OUT_AO) {
            fputs(", \"dmax\": ", f);
            json_num(f, gib_param_float(t, rq->params, "dmax"));
            fprintf(f, ", \"obscurance\": %d", gib_param_int(t, rq->params, "obscurance"));
        }
        fputc('}', f);
        first = 0;
    }
    fputs("\n  ],\n", f);
}

static void job_scene(FILE *f, const gib_external_request *rq)
{
    const gib_scene *s = rq->scene;
    char feats[256];
    gib_features_str(s->features, feats, sizeof feats);
    fputs("  \"scene\": {\"name\": ", f);
    json_str(f, rq->scene_name);
    fputs(", \"description\": ", f);
    json_str(f, s->description);
    fprintf(f, ", \"features\": \"%s\", \"exposure\": %.9g, \"sky\": ", feats, s->exposure);
    json_vec3(f, s->sky);
    fprintf(f, ",\n    \"gltf\": \"scene.gltf\", \"vertices\": %u, \"triangles\": %u, "
               "\"units\": \"linear RGB radiance; metres\"},\n",
            s->vertex_count, s->triangle_count);
}

int gib_external_write_job(const gib_external_request *rq, const char *dir, gib_error *err)
{
    if (write_gltf(dir, rq, err) < 0)
        return -1;
    char path[2048];
    snprintf(path, sizeof path, "%s/job.json", dir);
    FILE *f = fopen(path, "w");
    if (!f)
        return gib_fail(err, "cannot write %s", path);
    fprintf(f, "{\n  \"gibench_job\": 1,\n  \"technique\": ");
    json_str(f, rq->x->tech_name);
    fputs(", \"version\": ", f);
    json_str(f, rq->x->version);
    fprintf(f, ",\n  \"time\": %.9g,\n  \"frames\": {\"warmup\": %d, \"timed\": %d},\n",
            rq->time, rq->warmup, rq->frames);
    job_scene(f, rq);
    job_camera(f, rq);
    job_lights(f, rq->scene);
    job_materials(f, rq->scene);
    job_components(f, rq, dir);
    fputs("  \"directory\": ", f);
    json_str(f, dir);
    fputs(",\n  \"timings\": ", f);
    snprintf(path, sizeof path, "%s/timings.json", dir);
    json_str(f, path);
    fputs("\n}\n", f);
    if (fclose(f) != 0)
        return gib_fail(err, "cannot write %s/job.json", dir);
    return 0;
}

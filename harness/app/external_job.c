/* gibench — an external technique's job (external.h): the scene at the row's instant as a JSON
 * description beside a glTF 2.0 file of its geometry, and the outputs expected back. The format is
 * documented in examples/external_renderer/README.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "external.h"

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

static void json_vec3(FILE *f, const float *v)
{
    fputc('[', f);
    for (int i = 0; i < 3; i++) {
        json_num(f, v[i]);
        fputs(i < 2 ? ", " : "]", f);
    }
}

/* ---- the glTF: one shared vertex buffer, one mesh (one primitive) per material ---- */

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

/* scene.bin: positions, normals, uvs (vertex_count each), then the grouped indices. */
static int write_bin(const char *path, const gib_scene *s, const uint32_t *idx, gib_error *err)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return gib_fail(err, "cannot write %s", path);
    size_t nv = s->vertex_count, ni = (size_t)s->triangle_count * 3;
    int ok = fwrite(s->positions, 12, nv, f) == nv && fwrite(s->normals, 12, nv, f) == nv;
    for (size_t v = 0; ok && v < nv; v++) { /* uvs, zero where the scene has none */
        const float zero[2] = {0, 0};
        ok = fwrite(s->uvs ? s->uvs + 2 * v : zero, 8, 1, f) == 1;
    }
    ok = ok && fwrite(idx, 4, ni, f) == ni;
    if (fclose(f) != 0 || !ok)
        return gib_fail(err, "cannot write %s", path);
    return 0;
}

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
        fprintf(f, ",\n    {\"bufferView\": 3, \"byteOffset\": %zu, \"componentType\": 5125, "
                   "\"count\": %u, \"type\": \"SCALAR\"}", (size_t)first[m] * 4, count[m]);
    fputs("\n  ],\n", f);
}

/* Materials as glTF's metallic-roughness (albedo as the base colour, not metallic, rough), the
 * exact gibench material in extras.gibench; textures by absolute file URI. */
static void gltf_materials(FILE *f, const gib_scene *s)
{
    fputs("  \"materials\": [", f);
    for (uint32_t m = 0; m < s->material_count; m++) {
        const gib_material *mt = &s->materials[m];
        fprintf(f, "%s\n    {\"name\": ", m ? "," : "");
        json_str(f, mt->name);
        fputs(", \"doubleSided\": ", f);
        fputs(mt->two_sided ? "true" : "false", f);
        fprintf(f, ", \"pbrMetallicRoughness\": {\"baseColorFactor\": [%.9g, %.9g, %.9g, 1], "
                   "\"metallicFactor\": 0, \"roughnessFactor\": 1",
                mt->albedo[0], mt->albedo[1], mt->albedo[2]);
        if (mt->albedo_tex >= 0)
            fprintf(f, ", \"baseColorTexture\": {\"index\": %d}", mt->albedo_tex);
        fprintf(f, "}, \"extras\": {\"gibench_material\": %u}}", m);
    }
    fputs("\n  ],\n  \"images\": [", f);
    for (uint32_t t = 0; t < s->texture_count; t++) {
        fprintf(f, "%s\n    {\"uri\": ", t ? "," : "");
        char uri[600];
        snprintf(uri, sizeof uri, "file://%s", s->textures[t].path);
        json_str(f, uri);
        fputc('}', f);
    }
    fputs("\n  ],\n  \"textures\": [", f);
    for (uint32_t t = 0; t < s->texture_count; t++)
        fprintf(f, "%s\n    {\"source\": %u}", t ? "," : "", t);
    fputs("\n  ],\n", f);
}

static int write_gltf(const char *dir, const gib_scene *s, gib_error *err)
{
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
        size_t bytes = (size_t)s->vertex_count * 32 + (size_t)s->triangle_count * 12;
        fprintf(f, "{\n  \"asset\": {\"version\": \"2.0\", \"generator\": \"gibench\"},\n"
                   "  \"scene\": 0,\n  \"scenes\": [{\"nodes\": [0]}],\n"
                   "  \"nodes\": [{\"name\": \"world\", \"children\": [");
        for (uint32_t m = 0; m < s->material_count; m++)
            fprintf(f, "%s%u", m ? ", " : "", m + 1);
        fputs("]}", f);
        for (uint32_t m = 0; m < s->material_count; m++)
            fprintf(f, ",\n    {\"mesh\": %u}", m);
        fputs("],\n  \"meshes\": [", f);
        for (uint32_t m = 0; m < s->material_count; m++)
            fprintf(f, "%s\n    {\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1, "
                       "\"TEXCOORD_0\": 2}, \"indices\": %u, \"material\": %u, \"mode\": 4}]}",
                    m ? "," : "", m + 3, m);
        fputs("\n  ],\n", f);
        gltf_materials(f, s);
        gltf_accessors(f, s, first, count);
        fprintf(f, "  \"buffers\": [{\"uri\": \"scene.bin\", \"byteLength\": %zu}]\n}\n", bytes);
        if (fclose(f) != 0)
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
    if (write_gltf(dir, rq->scene, err) < 0)
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

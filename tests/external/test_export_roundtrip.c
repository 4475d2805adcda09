/* The external job's glTF read back (harness/app/external_job.c; scenes/gltf_scene.c,
 * gltf_nodes.c; scenes/FORMAT.md, "glTF scenes"): a scene written as an external row gets it
 * (gib_external_write_job), then loaded through a .scene that names the glTF with camera, lights
 * and materials = gltf (and states the sky, exposure and closedness glTF does not hold), is the
 * same scene:
 *  (a) cornell (built-in: a spot, three diffuse materials), through the lossless path (extras);
 *  (b) a scene written here with what core glTF cannot carry exactly: a Phong lobe whose
 *      specular is not proportional to its albedo, a single-sided mirror, a spot of exponent 5
 *      and outer angle 120 degrees, a point and a directional light, a sky; its second camera;
 *  (c) hard_thin_wall (built-in: diffuse, two point lights) with every extras member stripped:
 *      there core glTF alone is exact;
 *  (d) the file of (a) edited after export (a base colour, a light's intensity): the stale
 *      extras are not used, and the load lists them as ignored;
 *  (e) textures: a glTF written here with one image inside its buffer (exported as a PNG
 *      beside the glTF) and one PNG file (exported by its path), each with rows of different
 *      colours, so that a flipped v shows: the texels read back equal, and so do the references.
 * (a)-(c) field by field: the camera's eye and field of view exact, its basis within float
 * rounding (the node's rotation is a quaternion computed in double); the lights' positions,
 * intensities, exponents and angles exact, directions within float rounding; the materials
 * exact. Then the references (direct: deterministic; full: 64 spp) of the original and the read
 * back scene at 64x64 agree within the references' own noise. */
#define _GNU_SOURCE
#include <ftw.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "harness/app/external.h"
#include "harness/imaging/image.h"
#include "harness/imaging/oiio_shim.h"
#include "reference/reference.h"
#include "scenes/scene.h"
#include "tests/common/check.h"
#include "tests/scenes/gltf_writer.h"

static int failures;
static char root[256]; /* every exported folder lies under it */

/* ------------------------------------------------------------------ export and read back */

/* Writes scene s's job for camera `camera` into root/name, as an external row gets it. */
static int export_scene(const gib_scene *s, const char *scene_name, int camera, const char *name)
{
    gib_external x;
    gib_params p;
    gib_error err = {0};
    char dir[512];
    memset(&x, 0, sizeof x);
    snprintf(x.name, sizeof x.name, "roundtrip");
    snprintf(dir, sizeof dir, "%s/%s", root, name);
    if (mkdir(dir, 0777) || gib_external_set(&x, "command", "true", &err) ||
        gib_external_set(&x, "components", "direct", &err) || gib_external_finish(&x, ".", &err))
        return CHECK_TRUE("export: set up", 0, err.msg), -1;
    gib_params_default(&x.technique, &p);
    const gib_external_request rq = {.x = &x, .scene = s, .scene_name = scene_name, .params = &p,
                                     .camera = camera, .width = 64, .height = 64, .frames = 1};
    const int rc = gib_external_write_job(&rq, dir, &err);
    CHECK(rc == 0, "export %s: %s", name, err.msg);
    return rc;
}

/* Loads root/name/scene.gltf through a .scene beside it that takes camera, lights and materials
 * from it and states what glTF does not hold (the glTF's scene extras record them too). */
static int read_back(const gib_scene *orig, const char *name, gib_scene *out)
{
    char path[600];
    snprintf(path, sizeof path, "%s/%s/back.scene", root, name);
    FILE *f = fopen(path, "w");
    if (!f)
        return CHECK_TRUE("read back: write the .scene", 0, path), -1;
    fprintf(f, "[scene]\ngltf = %s/%s/scene.gltf\ncamera = gltf\nlights = gltf\n"
               "materials = gltf\nexposure = %.9g\n", root, name, orig->exposure);
    if (orig->features & GIB_FEAT_SKY)
        fprintf(f, "sky = %.9g %.9g %.9g\n", orig->sky[0], orig->sky[1], orig->sky[2]);
    if (orig->features & GIB_FEAT_CLOSED)
        fputs("closed = 1\n", f);
    fclose(f);
    gib_error err = {0};
    const int rc = gib_scene_load(path, out, &err);
    CHECK(rc == 0, "read back %s: %s", name, err.msg);
    return rc;
}

/* Every "extras" member (key, object and the comma before it) taken out of root/name/scene.gltf.
 * The exporter's extras are objects; the strings of the scenes stripped here hold no braces. */
static void strip_extras(const char *name)
{
    char path[600];
    snprintf(path, sizeof path, "%s/%s/scene.gltf", root, name);
    FILE *f = fopen(path, "rb");
    char *js = calloc(1 << 20, 1);
    size_t n = f && js ? fread(js, 1, (1 << 20) - 1, f) : 0;
    if (f)
        fclose(f);
    for (char *k; n && (k = strstr(js, "\"extras\"")) != NULL;) {
        char *e = strchr(k, '{'), *c = k;
        for (int depth = 0; e && *e && (e == strchr(k, '{') || depth > 0); e++)
            depth += *e == '{' ? 1 : *e == '}' ? -1 : 0;
        while (c > js && c[-1] != ',')
            c--;
        memmove(c - 1, e, strlen(e) + 1);
    }
    f = fopen(path, "wb");
    if (f && js)
        fputs(js, f), fclose(f);
    CHECK(js && n && !strstr(js, "extras") && !strstr(js, "gibench\":"),
          "strip %s: extras remain", name);
    free(js);
}

/* ------------------------------------------------------------------ field by field */

static int same3(const float *a, const float *b, double tol)
{
    return fabs(a[0] - b[0]) <= tol && fabs(a[1] - b[1]) <= tol && fabs(a[2] - b[2]) <= tol;
}

static void compare_camera(const char *what, const gib_camera *a, const gib_camera *b)
{
    char d[256];
    float ra[3], ua[3], fa[3], rb[3], ub[3], fb[3];
    gib_camera_basis(a, ra, ua, fa);
    gib_camera_basis(b, rb, ub, fb);
    snprintf(d, sizeof d, "%s: eye (%.9g %.9g %.9g), fov %.9g -> fov %.9g", what, a->eye[0],
             a->eye[1], a->eye[2], a->vfov_deg, b->vfov_deg);
    CHECK_TRUE("camera: eye and vertical fov exact", same3(a->eye, b->eye, 0) &&
               a->vfov_deg == b->vfov_deg && !strcmp(a->name, b->name), d);
    snprintf(d, sizeof d, "%s: forward (%.9g %.9g %.9g) -> (%.9g %.9g %.9g); 4e-7: a few float "
             "ulps of the unit basis (eye + forward rounds in float)", what, fa[0], fa[1], fa[2],
             fb[0], fb[1], fb[2]);
    CHECK_TRUE("camera: basis within float rounding",
               same3(ra, rb, 4e-7) && same3(ua, ub, 4e-7) && same3(fa, fb, 4e-7), d);
}

static void compare_light(const char *what, const gib_light *a, const gib_light *b)
{
    char d[384];
    const int dir = a->type != GIB_LIGHT_POINT;
    snprintf(d, sizeof d, "%s: '%s' type %d I (%.9g %.9g %.9g) -> '%s' type %d I (%.9g %.9g "
             "%.9g), e %.9g -> %.9g, outer %.9g -> %.9g", what, a->name, a->type,
             a->intensity[0], a->intensity[1], a->intensity[2], b->name, b->type,
             b->intensity[0], b->intensity[1], b->intensity[2], a->spot_exponent,
             b->spot_exponent, a->spot_outer_deg, b->spot_outer_deg);
    CHECK_TRUE("light: type, position, intensity, cone exact",
               !strcmp(a->name, b->name) && a->type == b->type &&
                   (a->type == GIB_LIGHT_DIRECTIONAL || same3(a->position, b->position, 0)) &&
                   same3(a->intensity, b->intensity, 0) &&
                   (a->type != GIB_LIGHT_SPOT || (a->spot_exponent == b->spot_exponent &&
                                                  a->spot_outer_deg == b->spot_outer_deg)), d);
    snprintf(d, sizeof d, "%s: '%s' (%.9g %.9g %.9g) -> (%.9g %.9g %.9g); 4e-7: float "
             "rounding of a unit vector through a quaternion", what, a->name, a->direction[0],
             a->direction[1], a->direction[2], b->direction[0], b->direction[1],
             b->direction[2]);
    CHECK_TRUE("light: direction within float rounding",
               !dir || same3(a->direction, b->direction, 4e-7), d);
}

static void compare_material(const char *what, const gib_material *a, const gib_scene *back)
{
    const gib_material *b = NULL;
    for (uint32_t i = 0; i < back->material_count && !b; i++)
        b = strcmp(back->materials[i].name, a->name) ? NULL : &back->materials[i];
    char d[384];
    snprintf(d, sizeof d, "%s: '%s' albedo (%.9g %.9g %.9g) spec %d (%.9g %.9g %.9g) n %.9g "
             "two-sided %d -> %s", what, a->name, a->albedo[0], a->albedo[1], a->albedo[2],
             a->spec_type, a->specular[0], a->specular[1], a->specular[2], a->phong_n,
             a->two_sided, b ? "found" : "missing");
    CHECK_TRUE("material: albedo, lobe, two-sidedness exact",
               b && same3(a->albedo, b->albedo, 0) && a->spec_type == b->spec_type &&
                   (a->spec_type == GIB_SPEC_NONE || same3(a->specular, b->specular, 0)) &&
                   (a->spec_type != GIB_SPEC_PHONG || a->phong_n == b->phong_n) &&
                   a->two_sided == b->two_sided && (a->albedo_tex >= 0) == (b->albedo_tex >= 0),
               d);
}

static void compare_fields(const char *what, const gib_scene *a, int camera, const gib_scene *b)
{
    char d[256];
    snprintf(d, sizeof d, "%s: %u -> %u triangles, %u -> %u lights, %u -> %u materials, "
             "features %#x -> %#x", what, a->triangle_count, b->triangle_count, a->light_count,
             b->light_count, a->material_count, b->material_count, a->features, b->features);
    CHECK_TRUE("scene: triangles, lights, materials, features", a->triangle_count ==
               b->triangle_count && a->light_count == b->light_count && a->material_count ==
               b->material_count && a->features == b->features && b->camera_count >= 1, d);
    if (b->camera_count >= 1)
        compare_camera(what, &a->cameras[camera], &b->cameras[0]);
    for (uint32_t i = 0; i < a->light_count && i < b->light_count; i++)
        compare_light(what, &a->lights[i], &b->lights[i]);
    for (uint32_t i = 0; i < a->material_count; i++)
        compare_material(what, &a->materials[i], b);
}

/* ------------------------------------------------------------------ the references */

static int render(const gib_scene *s, int component, int camera, gib_image *img,
                  gib_ref_stats *st)
{
    gib_ref_params rp;
    gib_error err = {0};
    memset(&rp, 0, sizeof rp);
    rp.component = component;
    rp.width = rp.height = 64;
    rp.spp = 64;
    rp.seed = 1;
    rp.quiet = 1;
    rp.camera = camera;
    const int rc = gib_reference_render(s, &rp, img, NULL, st, &err);
    CHECK(rc == 0, "reference of '%s': %s", s->name, err.msg);
    return rc;
}

/* Both references of one component: their means, their noise, the RMSE between them. Both use
 * the same seed and samples, so where the scenes are one the images are one; the bound is the
 * noise two independent references would differ by, sqrt(noise_a^2 + noise_b^2), and where
 * there is none (direct is deterministic) 1e-5 of the mean: the camera's basis read back from
 * the node's quaternion differs by float rounding (~1e-7), which moves each pixel's value about
 * as much relatively, a hundredth of the bound; a mapping error (683 lm/W, an axis, a cone)
 * moves it by percents. */
static void compare_refs(const char *what, const gib_scene *a, int camera, const gib_scene *b,
                         int component)
{
    gib_image ia, ib;
    gib_ref_stats sa, sb;
    if (render(a, component, camera, &ia, &sa) || render(b, component, 0, &ib, &sb))
        return;
    double se = 0;
    const size_t n = (size_t)ia.width * ia.height * 3;
    for (size_t i = 0; i < n; i++)
        se += ((double)ia.px[i] - ib.px[i]) * ((double)ia.px[i] - ib.px[i]);
    const double rmse = sqrt(se / (double)n);
    const double bound = fmax(hypot(sa.noise_rmse, sb.noise_rmse), 1e-5 * sa.mean);
    char w[160];
    printf("%s %s: means %.6g and %.6g, noise RMSE %.3g and %.3g, RMSE between them %.3g "
           "(%.2f s + %.2f s)\n", what, gib_component_name(component), sa.mean, sb.mean,
           sa.noise_rmse, sb.noise_rmse, rmse, sa.seconds, sb.seconds);
    snprintf(w, sizeof w, "%s %s: RMSE between the references", what,
             gib_component_name(component));
    CHECK_AT_MOST(w, rmse, bound, "the references' own noise, sqrt(na^2 + nb^2), or 1e-5 of "
                                  "the mean where they have none: float rounding of the camera");
    gib_image_free(&ia);
    gib_image_free(&ib);
}

/* ------------------------------------------------------------------ the cases */

/* Loads scene `src` (a name or a .scene path), exports it, reads it back and compares. */
static void round_trip(const char *what, const char *src, int camera, int strip)
{
    gib_scene a, b;
    gib_error err = {0};
    if (gib_scene_load(src, &a, &err)) {
        CHECK_TRUE("load the original", 0, err.msg);
        return;
    }
    if (export_scene(&a, src, camera, what) == 0) {
        if (strip)
            strip_extras(what);
        if (read_back(&a, what, &b) == 0) {
            compare_fields(what, &a, camera, &b);
            compare_refs(what, &a, camera, &b, GIB_COMP_DIRECT);
            compare_refs(what, &a, camera, &b, GIB_COMP_FULL);
            gib_scene_free(&b);
        }
    }
    gib_scene_free(&a);
}

static const char glossy_scene[] =
    "[scene]\ndescription = glossy round trip\nexposure = 2\nsky = 0.2 0.22 0.25\n"
    "[mesh.ground_and_box]\nprocedural = plane_box\n"
    "[material.ground]\nalbedo = 0.4 0.4 0.4\nspecular = 0.3 0.25 0.2\nphong_n = 40\n"
    "[material.box]\nalbedo = 0.1 0.05 0.05\nspecular = 0.8 0.8 0.8\nmirror = 1\n"
    "two_sided = 0\n"
    "[light.bulb]\ntype = point\nposition = 1 2 1\nintensity = 3 2 1\n"
    "[light.key]\ntype = spot\nposition = -3 4 1.5\ntarget = 0 0 0\nintensity = 80 70 60\n"
    "exponent = 5\nouter_angle = 120\n"
    "[light.sun]\ntype = directional\ndirection = -0.3 -1 -0.2\nintensity = 1 0.9 0.8\n"
    "[camera.front]\neye = 0.5 2.8 5.5\ntarget = 0 0.4 0\n"
    "[camera.side]\neye = 4 2 -3\ntarget = 0 0.3 0\nfov = 50\n";

/* (d): the file of (a) with red's base colour and the spot's intensity changed after export. */
static void stale_extras(void)
{
    char path[600], scene[600];
    snprintf(path, sizeof path, "%s/cornell/scene.gltf", root);
    FILE *f = fopen(path, "rb");
    char *js = calloc(1 << 20, 1), *r, *i;
    const size_t n = f && js ? fread(js, 1, (1 << 20) - 1, f) : 0;
    if (f)
        fclose(f);
    r = n ? strstr(js, "\"baseColorFactor\": [0.629999995") : NULL;
    i = n ? strstr(js, "\"intensity\": 341.5") : NULL;
    CHECK(r && i, "(d) the export lacks red's base colour or the spot's 341.5 cd");
    if (r && i) {
        memcpy(r + 20, "0.500000000", 11);
        memcpy(i + 13, "683.0", 5);
        snprintf(path, sizeof path, "%s/cornell/edited.gltf", root);
        f = fopen(path, "wb");
        fputs(js, f), fclose(f);
        snprintf(scene, sizeof scene, "%s/cornell/edited.scene", root);
        f = fopen(scene, "wb");
        fprintf(f, "[scene]\ngltf = %s\ncamera = gltf\nlights = gltf\nmaterials = gltf\n",
                path), fclose(f);
        gib_scene s;
        gib_error err = {0};
        if (gib_scene_load(scene, &s, &err) == 0) {
            const gib_material *red = NULL;
            for (uint32_t k = 0; k < s.material_count; k++)
                red = strcmp(s.materials[k].name, "red") ? red : &s.materials[k];
            CHECK_NEAR("(d) edited red: the file's base colour", 0.5, red ? red->albedo[0] : -1,
                       0, "baseColorFactor 0.5, metallic 0: albedo 0.5 exactly");
            CHECK_NEAR("(d) edited spot: the file's 683 cd", 1.0, s.lights[0].intensity[0], 0,
                       "683 cd x colour 1 / 683 lm/W");
            CHECK_TRUE("(d) stale extras listed as ignored",
                       strstr(s.ignored, "materials edited") && strstr(s.ignored, "lights edited"),
                       s.ignored);
            gib_scene_free(&s);
        } else {
            CHECK_TRUE("(d) load the edited file", 0, err.msg);
        }
    }
    free(js);
}

/* (e): two textured quads from a .gltf written here, lit by a point light, seen from above. */
static void write_textured(char *scene, size_t n)
{
    const unsigned char px[12] = {200, 30, 0, 200, 30, 0, 0, 100, 180, 0, 100, 180};
    char png[600], gltf[600], eb[512];
    snprintf(png, sizeof png, "%s/e_tex.png", root);
    CHECK(gib_oiio_write_png8(png, 2, 2, 3, px, eb, (int)sizeof eb) == 0, "(e) PNG: %s", eb);
    unsigned char bytes[4096];
    FILE *f = fopen(png, "rb");
    const size_t len = f ? fread(bytes, 1, sizeof bytes, f) : 0;
    if (f)
        fclose(f);
    gw_prim p[2];
    memset(p, 0, sizeof p);
    gw_quad(&p[0], -1.1f, 0, 0, 2);
    gw_quad(&p[1], 1.1f, 0, 0, 2);
    p[0].material = 0, p[1].material = 1;
    snprintf(gltf, sizeof gltf, "%s/e.gltf", root);
    gw_write(gltf, 0, p, 2, "", "",
             "\"images\":[{\"bufferView\":6,\"mimeType\":\"image/png\"},{\"uri\":\"e_tex.png\"}],"
             "\"textures\":[{\"source\":0},{\"source\":1}],\"materials\":["
             "{\"name\":\"inside\",\"doubleSided\":true,\"pbrMetallicRoughness\":{"
             "\"baseColorTexture\":{\"index\":0},\"metallicFactor\":0}},"
             "{\"name\":\"beside\",\"doubleSided\":true,\"pbrMetallicRoughness\":{"
             "\"baseColorTexture\":{\"index\":1},\"metallicFactor\":0}}],",
             bytes, len);
    gw_prim_free(&p[0]);
    gw_prim_free(&p[1]);
    snprintf(scene, n, "%s/textured.scene", root);
    if ((f = fopen(scene, "w")) != NULL)
        fprintf(f, "[scene]\ngltf = %s\nmaterials = gltf\n[light.l]\ntype = point\n"
                   "position = 0 3 0.5\nintensity = 5 5 5\n[camera.top]\neye = 0 4 0.01\n"
                   "target = 0 0 0\nfov = 60\n", gltf), fclose(f);
}

/* (e): each texture of the original and of the scene read back, texel by texel. */
static void compare_textures(const gib_scene *a, const gib_scene *b)
{
    for (uint32_t i = 0; i < a->material_count; i++) {
        const gib_material *ma = &a->materials[i], *mb = NULL;
        for (uint32_t k = 0; k < b->material_count; k++)
            mb = strcmp(b->materials[k].name, ma->name) ? mb : &b->materials[k];
        const gib_texture *ta = ma->albedo_tex >= 0 ? &a->textures[ma->albedo_tex] : NULL;
        const gib_texture *tb = mb && mb->albedo_tex >= 0 ? &b->textures[mb->albedo_tex] : NULL;
        int same = ta && tb && ta->width == tb->width && ta->height == tb->height;
        for (int t = 0; same && t < ta->width * ta->height * 4; t++)
            same = ta->rgba[t] == tb->rgba[t];
        char d[1200];
        snprintf(d, sizeof d, "'%s': %s -> %s", ma->name, ta ? ta->path : "none",
                 tb ? tb->path : "none");
        CHECK_TRUE("(e) texture read back texel for texel", same, d);
    }
}

static void textured(void)
{
    char scene[600];
    write_textured(scene, sizeof scene);
    gib_scene a, b;
    gib_error err = {0};
    if (gib_scene_load(scene, &a, &err)) {
        CHECK_TRUE("(e) load the textured scene", 0, err.msg);
        return;
    }
    if (export_scene(&a, scene, 0, "textured") == 0 && read_back(&a, "textured", &b) == 0) {
        char png[600];
        snprintf(png, sizeof png, "%s/textured/texture0.png", root);
        FILE *f = fopen(png, "rb");
        CHECK_TRUE("(e) the buffer's image written beside the glTF", f != NULL, png);
        if (f)
            fclose(f);
        compare_fields("textured", &a, 0, &b);
        compare_textures(&a, &b);
        compare_refs("textured", &a, 0, &b, GIB_COMP_DIRECT);
        gib_scene_free(&b);
    }
    gib_scene_free(&a);
}

static int remove_entry(const char *p, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb, (void)flag, (void)ftw;
    return remove(p);
}

/* With an argument, round-trips that scene too (e.g. sponza, with the shared data). */
int main(int argc, char **argv)
{
    snprintf(root, sizeof root, "/tmp/gib_export_rt_XXXXXX");
    if (!mkdtemp(root))
        return CHECK_TRUE("mkdtemp", 0, root), 1;
    if (!gib_scene_data_root()) /* a .scene's gltf = /absolute/path needs a data root */
        setenv("GIBENCH_SCENES", root, 1);
    char glossy[600];
    snprintf(glossy, sizeof glossy, "%s/glossy.scene", root);
    FILE *f = fopen(glossy, "w");
    if (f)
        fputs(glossy_scene, f), fclose(f);
    round_trip("cornell", "cornell", 0, 0);
    round_trip("glossy", glossy, 1, 0);
    round_trip("hard_thin_wall", "hard_thin_wall", 0, 1);
    stale_extras();
    textured();
    if (argc > 1)
        round_trip("extra", argv[1], 0, 0);
    nftw(root, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
    printf("%s: %d failure(s)\n", failures ? "FAILED" : "passed", failures);
    return failures ? 1 : 0;
}

/* glTF scenes whose buffer and images are files beside the .gltf (scenes/FORMAT.md, "glTF
 * scenes"; scenes/gltf_file.h, gltf_scene.c), as `gibench export` writes them and as most tools
 * do, not data: URIs:
 *  (f) a .gltf with its buffer in f.bin and its base colour texture in f_tex.png loads, with the
 *      texture read from that file (a texel's sRGB value decoded) and oriented as glTF says;
 *  (g) its buffer file missing: the load fails naming the missing file and the glTF;
 *  (h) its image file missing: the same, whether the .scene takes the materials or not (assimp
 *      reads them then). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/imaging/oiio_shim.h"
#include "scene_test.h"
#include "scenes/scene_internal.h"
#include "tests/scenes/gltf_writer.h"

/* A 2x2 RGB PNG beside the glTFs: top row red (sRGB code 200), bottom row green (100). */
static void write_png(const char *name)
{
    const unsigned char px[12] = {200, 0, 0, 200, 0, 0, 0, 100, 0, 0, 100, 0};
    char path[512], eb[512];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    CHECK(gib_oiio_write_png8(path, 2, 2, 3, px, eb, (int)sizeof eb) == 0, "PNG %s: %s", path,
          eb);
}

/* name.gltf: one textured quad, its buffer in bin_file, its image file `image`. */
static void write_gltf(const char *name, const char *bin_file, const char *image)
{
    gw_prim p;
    memset(&p, 0, sizeof p);
    gw_quad(&p, 0, 0, 0, 2);
    p.material = 0;
    char path[512], extra[1024];
    snprintf(path, sizeof path, "%s/%s.gltf", tmpdir, name);
    snprintf(extra, sizeof extra,
             "\"images\":[{\"uri\":\"%s\"}],\"textures\":[{\"source\":0}],"
             "\"materials\":[{\"name\":\"tex\",\"pbrMetallicRoughness\":{\"baseColorFactor\":"
             "[0.5,0.5,0.5,1],\"baseColorTexture\":{\"index\":0},\"metallicFactor\":0}}],",
             image);
    gw_write_bin(path, 0, &p, 1, "", "", extra, NULL, 0, bin_file);
    gw_prim_free(&p);
}

static int load(const char *gltf, int materials, gib_scene *s, gib_error *err, char *path,
                size_t n)
{
    static int k;
    char name[64], text[512];
    snprintf(name, sizeof name, "f%03d.scene", k++);
    snprintf(text, sizeof text, "[scene]\ngltf = %s\n%s[camera.c]\neye = 0 2 0.1\n"
             "target = 0 0 0\n", gltf, materials ? "materials = gltf\n" : "");
    write_file(name, text, path, n);
    err->msg[0] = '\0';
    return gib_scene_load(path, s, err);
}

/* (f) */
static void test_files(void)
{
    write_png("f_tex.png");
    write_gltf("f", "f.bin", "f_tex.png");
    gib_scene s;
    gib_error err;
    char sp[512];
    int rc = load("f.gltf", 1, &s, &err, sp, sizeof sp);
    CHECK_TRUE("(f) a .gltf with f.bin and f_tex.png loads", rc == 0, err.msg);
    if (rc)
        return;
    const gib_material *m = s.material_count == 1 ? &s.materials[0] : NULL;
    const gib_texture *t = m && m->albedo_tex >= 0 ? &s.textures[m->albedo_tex] : NULL;
    CHECK_TRUE("(f) its texture is the file beside it", t && strstr(t->path, "f_tex.png") &&
               t->width == 2 && t->height == 2, t ? t->path : "no texture");
    if (t) {
        CHECK_NEAR("(f) texel (0, 0): sRGB 200 decoded", gib_srgb_to_linear(200.0f / 255.0f),
                   t->rgba[0], 1e-6, "8-bit sRGB decoded to linear in float");
        CHECK_NEAR("(f) texel (0, 1): sRGB 100 decoded", gib_srgb_to_linear(100.0f / 255.0f),
                   t->rgba[4 * 2 + 1], 1e-6, "8-bit sRGB decoded to linear in float");
        CHECK_NEAR("(f) albedo factor: baseColor 0.5, metallic 0", 0.5, m->albedo[0], 1e-7,
                   "0.5 is exact in float");
    }
    int rows_ok = s.uvs != NULL && s.vertex_count > 0;
    for (uint32_t v = 0; rows_ok && t && v < s.vertex_count; v++) { /* glTF v = 0 at -z: row 0 */
        const float row = (1.0f - s.uvs[2 * v + 1]) * (float)t->height;
        rows_ok = (s.positions[3 * v + 2] < 0) == (row < 1.0f);
    }
    CHECK_TRUE("(f) the corner at glTF uv (0, 0) reads the image's top row", rows_ok, "");
    gib_scene_free(&s);
}

/* A load expected to fail naming `missing` and the glTF file `gltf`. */
static void expect_missing(const char *what, const char *gltf, int materials, const char *missing)
{
    gib_scene s;
    gib_error err;
    char sp[512], detail[sizeof err.msg + 16];
    int rc = load(gltf, materials, &s, &err, sp, sizeof sp);
    if (rc == 0)
        gib_scene_free(&s);
    snprintf(detail, sizeof detail, "rc %d: %s", rc, err.msg);
    CHECK_TRUE(what, rc != 0 && strstr(err.msg, missing) && strstr(err.msg, gltf) &&
               strstr(err.msg, "missing") && strstr(err.msg, sp), detail);
}

/* (g), (h) */
static void test_missing(void)
{
    write_gltf("g", "missing_g.bin", "f_tex.png");
    expect_missing("(g) a missing .bin is named, with its glTF", "g.gltf", 1, "'missing_g.bin'");
    expect_missing("(g) ... without materials = gltf too", "g.gltf", 0, "'missing_g.bin'");
    write_gltf("h", "h.bin", "gone.png");
    expect_missing("(h) a missing image is named, with its glTF", "h.gltf", 1, "'gone.png'");
    expect_missing("(h) ... without materials = gltf too", "h.gltf", 0, "'gone.png'");
}

int main(void)
{
    if (scene_test_begin("gib_gltf_files"))
        return 1;
    setenv("GIBENCH_SCENES", tmpdir, 1);
    test_files();
    test_missing();
    return scene_test_end();
}

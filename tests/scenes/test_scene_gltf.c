/* glTF scenes (scenes/FORMAT.md, "glTF scenes"; scenes/gltf_scene.c): a .scene that names a glTF
 * 2.0 file and takes its cameras, KHR_lights_punctual lights and materials.
 *  (a) a .gltf written here (base64 buffer): two cameras (one under a parent node), a point, a
 *      spot and a directional light, four materials -> the loaded gib_scene's cameras (eye,
 *      direction, fov), lights (positions, directions, intensities at 683 lm/W, the spot's outer
 *      angle and power-matched exponent), materials (albedo, specular, Phong exponent, mirror,
 *      two-sidedness) and which triangles carry which material (assimp's material order);
 *  (c) the mapping's numbers: rough metal's Phong exponent, the clamps, the spot exponent;
 *  (d) what gibench cannot model refused naming the file and the feature;
 *  (e) a .glb with an embedded PNG: its texture loaded (sRGB decoded), oriented as glTF says, and
 *      its normal map listed as ignored.
 * The furnace (b) is test_scene_gltf_furnace.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/imaging/oiio_shim.h"
#include "scene_test.h"
#include "scenes/scene_internal.h"
#include "tests/scenes/gltf_writer.h"

static const gib_material *mat_named(const gib_scene *s, const char *name)
{
    for (uint32_t i = 0; i < s->material_count; i++)
        if (strcmp(s->materials[i].name, name) == 0)
            return &s->materials[i];
    return NULL;
}

static int load(const char *scene_text, gib_scene *s, gib_error *err)
{
    static int n;
    char name[64], path[512];
    snprintf(name, sizeof name, "g%03d.scene", n++);
    write_file(name, scene_text, path, sizeof path);
    err->msg[0] = '\0';
    return gib_scene_load(path, s, err);
}

/* ------------------------------------------------------------------ (a) */

static const char *const a_nodes =
    /* 1: camera "Cam" at (1,2,3) turned 90 degrees about +y: looks down -x */
    "{\"name\":\"CamNode\",\"camera\":0,\"translation\":[1,2,3],"
    "\"rotation\":[0,0.70710678,0,0.70710678]},"
    /* 2: a parent at (0,10,0) with 3: camera "Top" turned -90 degrees about x: looks down -y */
    "{\"translation\":[0,10,0],\"children\":[3]},"
    "{\"name\":\"TopNode\",\"camera\":1,\"rotation\":[-0.70710678,0,0,0.70710678]},"
    /* 4: the point light, 5: the spot (pointing down), 6: the directional light (down -z) */
    "{\"translation\":[0,3,0],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
    "{\"translation\":[2,3,0],\"rotation\":[-0.70710678,0,0,0.70710678],"
    "\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
    "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}}";

static const char *const a_extra =
    "\"extensionsUsed\":[\"KHR_lights_punctual\"],"
    "\"cameras\":[{\"name\":\"Cam\",\"type\":\"perspective\",\"perspective\":{\"yfov\":0.6,"
    "\"znear\":0.1,\"aspectRatio\":1.5}},"
    "{\"name\":\"Top\",\"type\":\"perspective\",\"perspective\":{\"yfov\":1.0,\"znear\":0.1}}],"
    "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":["
    "{\"name\":\"bulb\",\"type\":\"point\",\"color\":[1,0.5,0.25],\"intensity\":1366,"
    "\"range\":20},"
    "{\"name\":\"spot\",\"type\":\"spot\",\"intensity\":1366,\"spot\":{\"innerConeAngle\":0.2,"
    "\"outerConeAngle\":0.5}},"
    "{\"name\":\"sun\",\"type\":\"directional\",\"intensity\":683}]}},"
    "\"materials\":["
    "{\"name\":\"white\",\"doubleSided\":true,\"pbrMetallicRoughness\":{\"baseColorFactor\":"
    "[0.8,0.8,0.8,1],\"metallicFactor\":0}},"
    "{\"name\":\"metal\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.9,0.6,0.3,1],"
    "\"metallicFactor\":1,\"roughnessFactor\":0.5}},"
    "{\"name\":\"half\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.5,0.5,1],"
    "\"metallicFactor\":0.5,\"roughnessFactor\":0.3}},"
    "{\"name\":\"mirror\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.95,0.95,0.95,1],"
    "\"metallicFactor\":1,\"roughnessFactor\":0.05}}],";

/* Quad k at x = 10 k carries material order[k]: the primitives' order differs from the
 * materials', so a mix-up of assimp's material indices shows. */
static const int a_order[4] = {2, 0, 3, 1};
static const char *const a_names[4] = {"white", "metal", "half", "mirror"};

static void write_a(void)
{
    gw_prim p[4];
    memset(p, 0, sizeof p);
    for (int k = 0; k < 4; k++) {
        gw_quad(&p[k], 10.0f * (float)k, 0.0f, 0.0f, 4.0f);
        p[k].material = a_order[k];
    }
    char path[512];
    snprintf(path, sizeof path, "%s/a.gltf", tmpdir);
    gw_write(path, 0, p, 4, a_nodes, ",1,2,4,5,6", a_extra, NULL, 0);
    for (int k = 0; k < 4; k++)
        gw_prim_free(&p[k]);
}

static void check_vec(const char *what, const float *got, double x, double y, double z, double tol)
{
    CHECK(fabs(got[0] - x) <= tol && fabs(got[1] - y) <= tol && fabs(got[2] - z) <= tol,
          "%s = (%g, %g, %g), want (%g, %g, %g) +- %g", what, (double)got[0], (double)got[1],
          (double)got[2], x, y, z, tol);
}

static void test_a(void)
{
    write_a();
    gib_scene s;
    gib_error err;
    int rc = load("[scene]\ngltf = a.gltf\ncamera = gltf\nlights = gltf\nmaterials = gltf\n", &s,
                  &err);
    CHECK(rc == 0, "(a) load: %s", err.msg);
    if (rc)
        return;
    /* cameras: both, in node order */
    CHECK(s.camera_count == 2, "(a) cameras: %u, want 2", s.camera_count);
    const gib_camera *c = &s.cameras[0];
    CHECK(strcmp(c->name, "Cam") == 0, "(a) camera 0 is '%s', want 'Cam'", c->name);
    check_vec("(a) Cam eye", c->eye, 1, 2, 3, 1e-6);
    float d0[3], d1[3], r[3], u[3]; /* the view direction: the target lies along it */
    gib_camera_basis(c, r, u, d0);
    check_vec("(a) Cam direction (node -Z turned 90 about +y)", d0, -1, 0, 0, 1e-6);
    check_vec("(a) Cam up", c->up, 0, 1, 0, 1e-6);
    NEAR(c->vfov_deg, 0.6 * 180.0 / M_PI, 1e-4, "yfov 0.6 rad in degrees");
    if (s.camera_count == 2) {
        c = &s.cameras[1];
        check_vec("(a) Top eye (parent's translation)", c->eye, 0, 10, 0, 1e-6);
        gib_camera_basis(c, r, u, d1);
        check_vec("(a) Top direction (down)", d1, 0, -1, 0, 1e-6);
        check_vec("(a) Top up", c->up, 0, 0, -1, 1e-6);
    }
    /* lights, in gibench's units: 1366 cd = 2 W/sr at 683 lm/W */
    CHECK(s.light_count == 3, "(a) lights: %u, want 3", s.light_count);
    if (s.light_count == 3) {
        const gib_light *l = &s.lights[0];
        CHECK(l->type == GIB_LIGHT_POINT && strcmp(l->name, "bulb") == 0, "(a) light 0 '%s' "
              "type %d, want the point light 'bulb'", l->name, l->type);
        check_vec("(a) point position", l->position, 0, 3, 0, 1e-6);
        check_vec("(a) point intensity (W/sr = cd color / 683)", l->intensity, 2, 1, 0.5, 1e-5);
        l = &s.lights[1];
        CHECK(l->type == GIB_LIGHT_SPOT, "(a) light 1 type %d, want spot", l->type);
        check_vec("(a) spot position", l->position, 2, 3, 0, 1e-6);
        check_vec("(a) spot direction (node -Z turned down)", l->direction, 0, -1, 0, 1e-6);
        check_vec("(a) spot intensity on the axis", l->intensity, 2, 2, 2, 1e-5);
        NEAR(l->spot_outer_deg, 0.5 * 180.0 / M_PI, 1e-4, "outerConeAngle in degrees");
        /* the same power within the outer cone as glTF's smooth falloff */
        const double ci = cos(0.2), co = cos(0.5), e = l->spot_exponent;
        const double want = (1 - ci) + (ci - co) / 3, got = (1 - pow(co, e + 1)) / (e + 1);
        NEAR(got, want, 1e-6 * want, "cos^e power = glTF spot power (FORMAT.md)");
        CHECK(e > 1.0 && e < 100.0, "(a) spot exponent %g out of the plausible range", e);
        l = &s.lights[2];
        CHECK(l->type == GIB_LIGHT_DIRECTIONAL, "(a) light 2 type %d, want directional",
              l->type);
        check_vec("(a) directional direction (-Z)", l->direction, 0, 0, -1, 1e-6);
        check_vec("(a) directional irradiance (W/m^2 = lux / 683)", l->intensity, 1, 1, 1, 1e-6);
    }
    /* materials: rho_d = base (1 - metallic), rho_s = base metallic, n = 2/alpha^2 - 2 */
    const gib_material *m = mat_named(&s, "white");
    CHECK(m && m->spec_type == GIB_SPEC_NONE && fabsf(m->albedo[0] - 0.8f) < 1e-6f &&
              m->two_sided == 1, "(a) 'white': want albedo 0.8, no lobe, two-sided");
    m = mat_named(&s, "metal");
    CHECK(m && m->spec_type == GIB_SPEC_PHONG, "(a) 'metal' must be Phong");
    if (m) {
        check_vec("(a) metal albedo", m->albedo, 0, 0, 0, 1e-7);
        check_vec("(a) metal specular = baseColor", m->specular, 0.9, 0.6, 0.3, 1e-6);
        NEAR(m->phong_n, 30.0, 1e-3, "roughness 0.5: alpha 0.25, n = 2/0.0625 - 2");
        CHECK(m->two_sided == 0, "(a) 'metal' is single-sided in the file");
    }
    m = mat_named(&s, "half");
    CHECK(m && m->spec_type == GIB_SPEC_PHONG, "(a) 'half' must be Phong");
    if (m) {
        check_vec("(a) half albedo", m->albedo, 0.25, 0.25, 0.25, 1e-6);
        check_vec("(a) half specular", m->specular, 0.25, 0.25, 0.25, 1e-6);
        NEAR(m->phong_n, 2.0 / (0.09 * 0.09) - 2.0, 1e-2, "roughness 0.3");
    }
    m = mat_named(&s, "mirror");
    CHECK(m && m->spec_type == GIB_SPEC_MIRROR, "(a) 'mirror' (roughness 0.05) must be a mirror");
    /* each quad's triangles carry the material its primitive names */
    int wrong = 0;
    for (uint32_t t = 0; t < s.triangle_count; t++) {
        float x = 0;
        for (int k = 0; k < 3; k++)
            x += s.positions[3 * s.indices[3 * t + k]] / 3.0f;
        int q = (int)lrintf(x / 10.0f);
        wrong += q < 0 || q > 3 ||
                 strcmp(s.materials[s.tri_material[t]].name, a_names[a_order[q]]) != 0;
    }
    CHECK(s.triangle_count == 8 && wrong == 0, "(a) %d of %u triangles carry the wrong material",
          wrong, s.triangle_count);
    const unsigned want_f = GIB_FEAT_SPECULAR | GIB_FEAT_MIRROR | GIB_FEAT_POINT_LIGHT |
                            GIB_FEAT_SPOT_LIGHT | GIB_FEAT_DIR_LIGHT;
    CHECK((s.features & want_f) == want_f, "(a) features 0x%x lack 0x%x", s.features, want_f);
    CHECK(strstr(s.ignored, "light range") != NULL, "(a) ignored '%s' lacks the light range",
          s.ignored);
    printf("ok   (a) cameras, lights, materials; ignored: %s\n", s.ignored);
    gib_scene_free(&s);

    /* camera = gltf:NAME by the node's name, with [light] sections kept before the file's */
    rc = load("[scene]\ngltf = a.gltf\ncamera = gltf:TopNode\n[light.key]\ntype = point\n"
              "position = 0 1 0\nintensity = 1 1 1\n", &s, &err);
    CHECK(rc == 0, "(a) gltf:TopNode: %s", err.msg);
    if (rc == 0) {
        CHECK(s.camera_count == 1 && fabsf(s.cameras[0].eye[1] - 10.0f) < 1e-6f,
              "(a) gltf:TopNode: %u cameras, eye y %g", s.camera_count,
              (double)s.cameras[0].eye[1]);
        CHECK(s.light_count == 1, "(a) lights not requested: %u lights, want the section's 1",
              s.light_count);
        CHECK(strstr(s.ignored, "lights (lights = gltf") != NULL, "(a) lights not requested "
              "must be listed as ignored: '%s'", s.ignored);
        gib_scene_free(&s);
    }
    /* the file's cameras not requested: listed; its mesh needs a [camera] section */
    rc = load("[scene]\ngltf = a.gltf\n[camera.c]\neye = 0 5 5\ntarget = 0 0 0\n", &s, &err);
    CHECK(rc == 0, "(a) geometry only: %s", err.msg);
    if (rc == 0) {
        CHECK(s.camera_count == 1 && strstr(s.ignored, "cameras (camera = gltf") != NULL,
              "(a) geometry only: %u cameras, ignored '%s'", s.camera_count, s.ignored);
        gib_scene_free(&s);
    }
}

/* Unnamed materials used in the reverse of their order: assimp lists them by first use, so only
 * their factors tell them apart (gib_gltf_match). */
static void test_a_unnamed(void)
{
    gw_prim p[2];
    memset(p, 0, sizeof p);
    gw_quad(&p[0], 0, 0, 0, 1);
    p[0].material = 1;
    gw_quad(&p[1], 10, 0, 0, 1);
    p[1].material = 0;
    char path[512];
    snprintf(path, sizeof path, "%s/u.gltf", tmpdir);
    gw_write(path, 0, p, 2, "", "",
             "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.2,0.2,0.2,1],"
             "\"metallicFactor\":0}},{\"pbrMetallicRoughness\":{\"baseColorFactor\":"
             "[0.7,0.7,0.7,1],\"metallicFactor\":0}}],", NULL, 0);
    gw_prim_free(&p[0]);
    gw_prim_free(&p[1]);
    gib_scene s;
    gib_error err;
    int rc = load("[scene]\ngltf = u.gltf\nmaterials = gltf\n[camera.c]\neye = 0 1 1\n"
                  "target = 0 0 0\n", &s, &err);
    CHECK(rc == 0, "(a) unnamed: %s", err.msg);
    if (rc)
        return;
    int wrong = 0;
    for (uint32_t t = 0; t < s.triangle_count; t++) {
        const float x = s.positions[3 * s.indices[3 * t]];
        const gib_material *m = &s.materials[s.tri_material[t]];
        wrong += fabsf(m->albedo[0] - (x < 5.0f ? 0.7f : 0.2f)) > 1e-6f;
    }
    CHECK(s.triangle_count == 4 && wrong == 0, "(a) unnamed: %d of %u triangles carry the wrong "
          "material", wrong, s.triangle_count);
    printf("ok   (a) unnamed materials matched by their factors\n");
    gib_scene_free(&s);
}

/* ------------------------------------------------------------------ (c) */

static void test_c(void)
{
    NEAR(gib_gltf_phong_n(0.5f), 30.0, 1e-4, "rough metal: alpha = 0.25, n = 2/alpha^2 - 2");
    NEAR(gib_gltf_phong_n(0.7f), 2.0 / pow(0.49, 2) - 2.0, 1e-3, "roughness 0.7");
    NEAR(gib_gltf_phong_n(1.0f), 1.0, 0, "roughness 1: n = 0 clamped to 1");
    CHECK(isinf(gib_gltf_phong_n(0.1f)), "roughness 0.1 (n = 19998 >= %g) must be a mirror",
          (double)GIB_GLTF_PHONG_MAX);
    CHECK(isfinite(gib_gltf_phong_n(0.13f)) && gib_gltf_phong_n(0.13f) < GIB_GLTF_PHONG_MAX,
          "roughness 0.13 (n = 6999) must stay Phong");
    NEAR(gib_gltf_spot_exponent(0.4, 0.4), 0.0, 0, "a hard cone (inner = outer): cos^0");
    const double e = gib_gltf_spot_exponent(0.0, M_PI / 4), co = cos(M_PI / 4);
    NEAR((1 - pow(co, e + 1)) / (e + 1), (1 - co) / 3, 1e-6, "inner 0: power (1 - cos o) / 3");
    printf("ok   (c) phong_n(0.5) = %g, spot exponent (0, 45 deg) = %g\n",
           (double)gib_gltf_phong_n(0.5f), e);
}

/* ------------------------------------------------------------------ (d) */

/* Writes d<k>.gltf (one quad, material 0 unless material < 0) with the given nodes and top-level
 * JSON, loads `keys` on top of gltf = d<k>.gltf and expects an error naming the file and phrase. */
static void refuse(const char *what, const char *nodes, const char *scene_nodes, const char *extra,
                   int material, const char *keys, const char *phrase)
{
    static int k;
    char file[64], path[512], text[1024];
    snprintf(file, sizeof file, "d%d.gltf", k++);
    snprintf(path, sizeof path, "%s/%s", tmpdir, file);
    gw_prim p;
    memset(&p, 0, sizeof p);
    gw_quad(&p, 0, 0, 0, 1);
    p.material = material;
    gw_write(path, 0, &p, 1, nodes, scene_nodes, extra, NULL, 0);
    gw_prim_free(&p);
    snprintf(text, sizeof text, "[scene]\ngltf = %s\n%s[camera.c]\neye = 0 1 1\ntarget = 0 0 0\n",
             file, keys);
    gib_scene s;
    gib_error err;
    int rc = load(text, &s, &err);
    CHECK(rc != 0, "(d) %s: loaded, want refused", what);
    if (rc == 0) {
        gib_scene_free(&s);
        return;
    }
    CHECK(strstr(err.msg, file) != NULL, "(d) %s: message does not name %s: %s", what, file,
          err.msg);
    CHECK(strstr(err.msg, phrase) != NULL, "(d) %s: message lacks '%s': %s", what, phrase,
          err.msg);
    printf("ok   (d) %-22s %s\n", what, err.msg);
}

static void test_d(void)
{
    refuse("emissive", "", "", "\"materials\":[{\"name\":\"glow\",\"emissiveFactor\":[1,0.5,0]}],",
           0, "materials = gltf\n", "emissive");
    refuse("transmission", "", "",
           "\"extensionsUsed\":[\"KHR_materials_transmission\"],\"materials\":[{\"extensions\":"
           "{\"KHR_materials_transmission\":{\"transmissionFactor\":1}}}],",
           0, "materials = gltf\n", "KHR_materials_transmission");
    refuse("transmission (no list)", "", "",
           "\"materials\":[{\"name\":\"glass\",\"extensions\":"
           "{\"KHR_materials_transmission\":{\"transmissionFactor\":1}}}],",
           0, "materials = gltf\n", "transmission");
    refuse("unknown light type",
           "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}", ",1",
           "\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{\"KHR_lights_punctual\":"
           "{\"lights\":[{\"type\":\"area\",\"intensity\":10}]}},",
           -1, "lights = gltf\n", "type 'area'");
    refuse("skin", "{\"name\":\"bone\"}", ",1", "\"skins\":[{\"joints\":[1]}],", -1, "", "skin");
    refuse("alpha blend", "", "",
           "\"materials\":[{\"alphaMode\":\"BLEND\"}],", 0, "materials = gltf\n", "BLEND");
    refuse("orthographic camera", "{\"camera\":0}", ",1",
           "\"cameras\":[{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":1,\"ymag\":1,"
           "\"znear\":0.1,\"zfar\":10}}],", -1, "camera = gltf\n", "orthographic");
    refuse("unknown extension", "", "", "\"extensionsUsed\":[\"EXT_made_up\"],", -1, "",
           "EXT_made_up");
    refuse("camera name", "", "", "", -1, "camera = gltf:Nope\n", "no camera named 'Nope'");
    refuse("animation", "", "",
           "\"animations\":[{\"channels\":[],\"samplers\":[]}],", -1, "", "animations");
    scene_expect_load("lights = gltf without gltf",
                      "[scene]\nlights = gltf\n[mesh.m]\nprocedural = plane_box\n[camera.c]\n"
                      "eye = 0 1 1\ntarget = 0 0 0\n",
                      -1, 2, "gltf = FILE", NULL);
    scene_expect_load("camera = other", "[scene]\ncamera = main\n", -1, 2, "gltf:NAME", NULL);
}

/* ------------------------------------------------------------------ (e) */

static void test_e(void)
{
    /* a 2x2 RGBA PNG: top row red (code 200), bottom row green (code 100), all opaque but the
     * bottom right texel (alpha 0; the image reader premultiplies, so its colour reads 0) */
    const unsigned char px[16] = {200, 0, 0, 255, 200, 0, 0, 255, 0, 100, 0, 255, 0, 100, 0, 0};
    char png[512], eb[512];
    snprintf(png, sizeof png, "%s/t.png", tmpdir);
    CHECK(gib_oiio_write_png8(png, 2, 2, 4, px, eb, (int)sizeof eb) == 0, "(e) PNG: %s", eb);
    FILE *fp = fopen(png, "rb");
    unsigned char bytes[4096];
    size_t n = fp ? fread(bytes, 1, sizeof bytes, fp) : 0;
    if (fp)
        fclose(fp);
    CHECK(n > 0 && n < sizeof bytes, "(e) PNG of %zu bytes", n);
    gw_prim p[2];
    memset(p, 0, sizeof p);
    gw_quad(&p[0], 0, 0, 0, 2);
    p[0].material = 0;
    gw_quad(&p[1], 10, 0, 0, 2); /* the same texture as an alpha mask (cutoff 0.25) */
    p[1].material = 1;
    char path[512];
    snprintf(path, sizeof path, "%s/e.glb", tmpdir);
    gw_write(path, 1, p, 2, "", "",
             "\"images\":[{\"bufferView\":6,\"mimeType\":\"image/png\"}],"
             "\"textures\":[{\"source\":0}],"
             "\"materials\":[{\"name\":\"tex\",\"normalTexture\":{\"index\":0},"
             "\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.5,0.5,1],"
             "\"baseColorTexture\":{\"index\":0},\"metallicFactor\":0}},"
             "{\"name\":\"cut\",\"alphaMode\":\"MASK\",\"alphaCutoff\":0.25,"
             "\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},"
             "\"metallicFactor\":0}}],",
             bytes, n);
    gw_prim_free(&p[0]);
    gw_prim_free(&p[1]);
    gib_scene s;
    gib_error err;
    int rc = load("[scene]\ngltf = e.glb\nmaterials = gltf\n[camera.c]\neye = 0 2 0.1\n"
                  "target = 0 0 0\n", &s, &err);
    CHECK(rc == 0, "(e) load: %s", err.msg);
    if (rc)
        return;
    const gib_material *m = mat_named(&s, "tex");
    CHECK(m && m->albedo_tex >= 0 && (uint32_t)m->albedo_tex < s.texture_count,
          "(e) 'tex' has no texture");
    if (m && m->albedo_tex >= 0) {
        const gib_texture *t = &s.textures[m->albedo_tex];
        NEAR(m->albedo[0], 0.5, 1e-7, "baseColorFactor times the texture");
        CHECK(t->width == 2 && t->height == 2 && strstr(t->path, "e.glb#image0"),
              "(e) texture %dx%d '%s'", t->width, t->height, t->path);
        NEAR(t->rgba[0], gib_srgb_to_linear(200.0f / 255.0f), 1e-6, "top row: sRGB 200 decoded");
        NEAR(t->rgba[4 * 2 + 1], gib_srgb_to_linear(100.0f / 255.0f), 1e-6,
             "bottom row: sRGB 100");
        /* orientation: the corner with glTF uv (0,0) must read the image's top row */
        int checked = 0;
        for (uint32_t v = 0; v < s.vertex_count; v++) {
            const float *q = s.positions + 3 * v, *uv = s.uvs + 2 * v;
            if (q[0] > 5.0f)
                continue; /* the masked quad */
            const float gv = q[2] < 0 ? 0.0f : 1.0f; /* gw_quad: glTF v = 0 at -z */
            const int row = (int)fminf(fmaxf((1.0f - uv[1]) * (float)t->height, 0.0f),
                                       (float)t->height - 1.0f);
            checked++;
            CHECK(row == (gv == 0.0f ? 0 : 1), "(e) vertex %u (glTF v %g) reads row %d", v,
                  (double)gv, row);
        }
        CHECK(checked > 0, "(e) no vertices");
    }
    CHECK(s.features & GIB_FEAT_TEXTURES, "(e) features lack textures");
    /* MASK: kept where alpha x factor.a >= cutoff, i.e. where alpha x 0.5 / 0.25 >= 0.5 */
    m = mat_named(&s, "cut");
    CHECK(m && m->alpha_tex >= 0 && (uint32_t)m->alpha_tex < s.texture_count,
          "(e) 'cut' has no alpha mask");
    if (m && m->alpha_tex >= 0) {
        const gib_texture *t = &s.textures[m->alpha_tex];
        NEAR(t->rgba[0], 1.0, 1e-6, "opaque: alpha 1 x 0.5 / cutoff 0.25 = 2, at most 1");
        NEAR(t->rgba[4 * 3], 0.0, 1e-7, "transparent texel: a hole");
        CHECK(m->albedo_tex >= 0 && m->albedo_tex != m->alpha_tex,
              "(e) 'cut' keeps its colour texture apart from its mask");
    }
    CHECK(s.features & GIB_FEAT_ALPHA_MASK, "(e) features lack alpha_mask");
    CHECK(strstr(s.ignored, "normal maps") != NULL, "(e) ignored '%s' lacks normal maps",
          s.ignored);
    printf("ok   (e) embedded PNG texture; ignored: %s\n", s.ignored);
    gib_scene_free(&s);
}

int main(void)
{
    if (scene_test_begin("gib_gltf"))
        return 1;
    setenv("GIBENCH_SCENES", tmpdir, 1);
    test_a();
    test_a_unnamed();
    test_c();
    test_d();
    test_e();
    return scene_test_end();
}

/* Loading scenes: the Cornell box against its published measurements, the camera and light
 * definitions both renderers share, mesh files (OBJ+MTL with a texture named in the wrong case,
 * gzipped PLY with a degenerate triangle), transforms, and the shared-data scenes, available or
 * reported unavailable. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <zlib.h>

#include "harness/imaging/oiio_shim.h"
#include "scenes/scene.h"
#include "tests/scenes/scene_test.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double dot3(const float *a, const float *b)
{
    return (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
}

/* Invariants every loaded scene must satisfy, whatever it is. */
static void check_invariants(const gib_scene *s)
{
    uint32_t bad_n = 0;
    for (uint32_t v = 0; v < s->vertex_count; v++) {
        const float *n = s->normals + 3 * (size_t)v;
        double l = sqrt(dot3(n, n));
        if (!isfinite(l) || fabs(l - 1.0) > 1e-4)
            bad_n++;
        for (int k = 0; k < 3; k++)
            if (!isfinite(s->positions[3 * (size_t)v + (size_t)k]))
                bad_n++;
    }
    CHECK(bad_n == 0, "%s: %u vertices with a non-finite position or a non-unit normal", s->name,
          bad_n);
    uint32_t covered = 0, bad_range = 0, bad_idx = 0;
    for (uint32_t r = 0; r < s->range_count; r++) {
        const gib_draw_range *R = &s->ranges[r];
        if (R->first_index % 3 || R->index_count % 3 || R->first_index != covered ||
            R->material >= s->material_count)
            bad_range++;
        for (uint32_t t = R->first_index / 3; t < (R->first_index + R->index_count) / 3; t++)
            if (s->tri_material[t] != R->material)
                bad_range++;
        covered += R->index_count;
    }
    CHECK(bad_range == 0 && covered == 3 * s->triangle_count,
          "%s: draw ranges do not tile the triangles by material", s->name);
    for (uint32_t i = 0; i < 3 * s->triangle_count; i++)
        bad_idx += s->indices[i] >= s->vertex_count;
    CHECK(bad_idx == 0, "%s: %u indices out of range", s->name, bad_idx);
    CHECK(s->camera_count >= 1, "%s: no camera", s->name);
    for (uint32_t m = 0; m < s->material_count; m++) {
        const gib_material *M = &s->materials[m];
        for (int c = 0; c < 3; c++)
            CHECK(M->albedo[c] + M->specular[c] <= 1.0f + 1e-6f,
                  "%s: material %s breaks "
                  "rho_d + rho_s <= 1",
                  s->name, M->name);
        CHECK(M->albedo_tex < (int)s->texture_count && M->alpha_tex < (int)s->texture_count,
              "%s: material %s has a texture index out of range", s->name, M->name);
    }
    for (int k = 0; k < 3; k++)
        CHECK(s->bounds_min[k] <= s->bounds_max[k], "%s: empty bounds", s->name);
}

/* For meshes whose vertex normals are face normals (procedural ones), the winding must agree with
 * the stored normal, also after mirroring transforms. Returns the number of disagreeing
 * triangles. */
static int winding_mismatches(const gib_scene *s)
{
    int bad = 0;
    for (uint32_t t = 0; t < s->triangle_count; t++) {
        const uint32_t *i = s->indices + 3 * (size_t)t;
        const float *a = s->positions + 3 * (size_t)i[0], *b = s->positions + 3 * (size_t)i[1],
                    *c = s->positions + 3 * (size_t)i[2];
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        float g[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                      e1[0] * e2[1] - e1[1] * e2[0]};
        double l = sqrt(dot3(g, g));
        if (dot3(g, s->normals + 3 * (size_t)i[0]) < 0.9999 * l)
            bad++;
    }
    return bad;
}

static int find_material(const gib_scene *s, const char *name)
{
    for (uint32_t m = 0; m < s->material_count; m++)
        if (strcmp(s->materials[m].name, name) == 0)
            return (int)m;
    return -1;
}

static void test_cornell(void)
{
    gib_scene s;
    gib_error err;
    int rc = gib_scene_load("cornell", &s, &err);
    CHECK(rc == 0, "cornell: %s", err.msg);
    if (rc)
        return;
    check_invariants(&s);
    /* 5 walls + 5 faces for each block, two triangles each, three vertices per triangle. */
    CHECK(s.triangle_count == 30, "cornell: %u triangles, want 30", s.triangle_count);
    CHECK(s.vertex_count == 90, "cornell: %u vertices, want 90", s.vertex_count);
    const char *tol = "published mm coordinates converted to float metres";
    NEAR(s.bounds_min[0], 0.0, 1e-6, tol);
    NEAR(s.bounds_min[1], 0.0, 1e-6, tol);
    NEAR(s.bounds_min[2], 0.0, 1e-6, tol);
    NEAR(s.bounds_max[0], 0.556, 1e-6, tol);
    NEAR(s.bounds_max[1], 0.5488, 1e-6, tol);
    NEAR(s.bounds_max[2], 0.5592, 1e-6, tol);
    CHECK(s.material_count == 3, "cornell: %u materials, want 3", s.material_count);
    int w = find_material(&s, "white"), r = find_material(&s, "red"),
        g = find_material(&s, "green");
    CHECK(w >= 0 && r >= 0 && g >= 0, "cornell: materials white, red, green missing");
    if (w >= 0 && r >= 0 && g >= 0) {
        NEAR(s.materials[r].albedo[0], 0.63, 1e-7, "exact constant");
        NEAR(s.materials[g].albedo[1], 0.45, 1e-7, "exact constant");
        NEAR(s.materials[w].albedo[2], 0.68, 1e-7, "exact constant");
        CHECK(s.materials[w].two_sided && s.materials[w].spec_type == GIB_SPEC_NONE &&
                  s.materials[w].albedo_tex < 0,
              "cornell: white must be two-sided Lambertian");
    }
    CHECK(winding_mismatches(&s) == 0, "cornell: winding disagrees with the face normals");
    CHECK(s.light_count == 1 && s.lights[0].type == GIB_LIGHT_SPOT, "cornell: want 1 spot light");
    if (s.light_count == 1) {
        const gib_light *l = &s.lights[0];
        NEAR(l->direction[1], -1.0, 1e-7, "points straight down, unit length");
        NEAR(l->spot_exponent, 1.0, 0, "cosine falloff");
        NEAR(l->spot_outer_deg, 90.0, 0, "as stated in cornell.scene");
        CHECK(l->position[1] < 0.5488f && l->position[1] > 0.5f, "spot is not just under the "
                                                                 "ceiling");
    }
    CHECK(s.features == GIB_FEAT_SPOT_LIGHT, "cornell: features 0x%x, want spot_light only",
          s.features);
    NEAR(s.cameras[0].vfov_deg, 39.31, 0.005, "2 atan(12.5/35) = 39.3077 deg");
    NEAR(s.cameras[0].eye[2], -0.8, 1e-7, "published eye at z = -800 mm");
    CHECK(s.content_hash != 0, "cornell: no content hash");

    gib_scene s2;
    if (gib_scene_load("cornell", &s2, &err) == 0) {
        CHECK(s2.content_hash == s.content_hash, "cornell: content hash differs between loads");
        gib_scene_free(&s2);
    }
    gib_scene_free(&s);
}

static void test_camera(void)
{
    gib_camera c = {.eye = {1, 2, 3}, .target = {1, 2, 10}, .up = {0, 1, 0}, .vfov_deg = 39.31f};
    float right[3], up[3], fwd[3], o[3], d[3];
    gib_camera_basis(&c, right, up, fwd);
    NEAR(fwd[2], 1.0, 1e-7, "looks along +z");
    NEAR(right[0], -1.0, 1e-7, "right = forward x up: -x when looking along +z with y up");
    NEAR(up[1], 1.0, 1e-7, "orthonormal");
    /* Even size: the centre lies between pixels; odd size: it is the centre of pixel 320. */
    gib_camera_ray(&c, 640, 480, 320.0f, 240.0f, o, d);
    NEAR(d[0], fwd[0], 1e-7, "centre ray = forward");
    NEAR(d[1], fwd[1], 1e-7, "centre ray = forward");
    NEAR(d[2], fwd[2], 1e-7, "centre ray = forward");
    NEAR(o[1], 2.0, 0, "origin = eye");
    gib_camera_ray(&c, 641, 481, 320 + 0.5f, 240 + 0.5f, o, d);
    NEAR(dot3(d, fwd), 1.0, 1e-7, "pixel-centre ray of an odd-sized image");
    /* The top edge of the image (py = 0) is vfov/2 above the axis; row 0 is the top row. */
    gib_camera_ray(&c, 640, 480, 320.0f, 0.0f, o, d);
    NEAR(acos(dot3(d, fwd)) * 180.0 / M_PI, 39.31 / 2, 1e-3, "float acos near 20 deg");
    CHECK(dot3(d, up) > 0, "py = 0 must point up (row 0 on top)");
    gib_camera_ray(&c, 640, 480, 0.0f, 240.0f, o, d);
    CHECK(dot3(d, right) < 0, "px = 0 must point left");
    /* Horizontal half-angle follows the aspect: tan(h) = aspect * tan(v/2). */
    NEAR(dot3(d, right) / dot3(d, fwd), -(640.0 / 480.0) * tan(39.31 / 2 * M_PI / 180), 1e-6,
         "float rounding");
}

static void test_lights(void)
{
    gib_light spot = {.type = GIB_LIGHT_SPOT,
                      .position = {0, 3, 0},
                      .direction = {0, -1, 0},
                      .intensity = {4, 4, 4},
                      .spot_exponent = 1,
                      .spot_outer_deg = 70};
    const float axis[3] = {0, -1, 0};
    const double k = M_PI / 180;
    float at60[3] = {(float)sin(60 * k), (float)-cos(60 * k), 0};
    float at80[3] = {(float)sin(80 * k), (float)-cos(80 * k), 0};
    NEAR(gib_spot_falloff(&spot, axis), 1.0, 1e-7, "cos^1(0) = 1");
    NEAR(gib_spot_falloff(&spot, at60), 0.5, 1e-6, "cos^1(60 deg) = 0.5, float trig");
    NEAR(gib_spot_falloff(&spot, at80), 0.0, 0, "outside the 70 deg outer angle");
    float scaled[3] = {at60[0] * 5, at60[1] * 5, 0};
    NEAR(gib_spot_falloff(&spot, scaled), 0.5, 1e-6, "direction need not be unit length");
    spot.spot_exponent = 2;
    NEAR(gib_spot_falloff(&spot, at60), 0.25, 1e-6, "cos^2(60 deg)");
    spot.spot_exponent = 1;

    /* Inverse square law: E = I / r^2 on the axis. */
    gib_light point = spot;
    point.type = GIB_LIGHT_POINT;
    float wi[3], dist, E[3];
    const float p1[3] = {0, 1, 0}, p2[3] = {0, -1, 0};
    CHECK(gib_light_eval(&point, p1, wi, &dist, E) == 1, "point light reaches p1");
    NEAR(E[0], 1.0, 1e-6, "4 / 2^2");
    NEAR(dist, 2.0, 1e-6, "distance");
    NEAR(wi[1], 1.0, 1e-7, "wi points from p to the light");
    gib_light_eval(&point, p2, wi, &dist, E);
    NEAR(E[1], 0.25, 1e-7, "4 / 4^2: quadrupled distance, a sixteenth");
    /* Spot off axis: I cos(theta) / r^2. p is 45 deg off the axis at r = 2 sqrt 2. */
    const float p3[3] = {2, 1, 0};
    CHECK(gib_light_eval(&spot, p3, wi, &dist, E) == 1, "45 deg is inside the spot");
    NEAR(E[2], 4 * cos(45 * k) / 8, 1e-6, "I cos(45) / r^2");
    const float p4[3] = {10, 2, 0}; /* about 84 deg off axis */
    CHECK(gib_light_eval(&spot, p4, wi, &dist, E) == 0 && E[0] == 0, "outside the spot: 0");
    /* A point exactly at the light gets nothing rather than infinity. */
    CHECK(gib_light_eval(&point, point.position, wi, &dist, E) == 0 && isfinite(E[0]) &&
              isfinite(wi[0]),
          "light touching the point must give finite zero");
    gib_light sun = {
        .type = GIB_LIGHT_DIRECTIONAL, .direction = {0, -1, 0}, .intensity = {3, 2, 1}};
    CHECK(gib_light_eval(&sun, p1, wi, &dist, E) == 1, "directional reaches everything");
    NEAR(E[0], 3.0, 0, "irradiance unchanged by distance");
    NEAR(wi[1], 1.0, 0, "wi = -direction");
    CHECK(isinf(dist), "directional distance is infinite");

    char f[128];
    gib_features_str(GIB_FEAT_TEXTURES | GIB_FEAT_SPOT_LIGHT, f, sizeof f);
    CHECK(strcmp(f, "textures,spot_light") == 0, "features string '%s'", f);
}

/* Transforms: rotate 90 about y maps (x, z) to (z, -x); mirroring keeps windings consistent. */
static void test_transforms(void)
{
    char path[512];
    write_file("rotated.scene",
               "[scene]\n[mesh.box]\nprocedural = cornell_box\nrotate = 0 90 0\n"
               "translate = 1 2 3\n[camera.c]\neye = 0 0 5\ntarget = 0 0 0\n",
               path, sizeof path);
    gib_scene s;
    gib_error err;
    if (gib_scene_load(path, &s, &err) == 0) {
        const char *why = "float rotation of metre-sized coordinates";
        NEAR(s.bounds_min[0], 1.0, 1e-6, why);
        NEAR(s.bounds_max[0], 1.5592, 1e-6, why);
        NEAR(s.bounds_min[2], 3.0 - 0.556, 1e-6, why);
        NEAR(s.bounds_max[2], 3.0, 1e-6, why);
        NEAR(s.bounds_max[1], 2.5488, 1e-6, why);
        CHECK(winding_mismatches(&s) == 0, "rotated cornell: winding disagrees with normals");
        gib_scene_free(&s);
    } else {
        CHECK(0, "rotated: %s", err.msg);
    }
    write_file("mirrored.scene",
               "[scene]\n[mesh.box]\nprocedural = cornell_box\nscale = -2 1 0.5\n"
               "rotate = 30 20 10\n[camera.c]\neye = 0 0 5\ntarget = 0 0 0\n",
               path, sizeof path);
    if (gib_scene_load(path, &s, &err) == 0) {
        check_invariants(&s);
        CHECK(winding_mismatches(&s) == 0, "mirrored cornell: winding disagrees with normals");
        gib_scene_free(&s);
    } else {
        CHECK(0, "mirrored: %s", err.msg);
    }
}

/* Mesh files: an OBJ whose MTL names its texture in the wrong case, and a gzipped PLY with a
 * degenerate triangle, placed in a room. */
static void test_mesh_files(void)
{
    char path[512], err_buf[512];
    /* 2x2 texture: top-left texel red, the rest sRGB 128 (linear 0.21586). */
    unsigned char px[2 * 2 * 3] = {255, 0, 0, 128, 128, 128, 128, 128, 128, 128, 128, 128};
    snprintf(path, sizeof path, "%s/Checker.PNG", tmpdir);
    if (gib_oiio_write_png8(path, 2, 2, 3, px, err_buf, sizeof err_buf)) {
        CHECK(0, "cannot write the test texture: %s", err_buf);
        return;
    }
    write_file("quad.obj",
               "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
               "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl painted\nf 1/1 2/2 3/3 4/4\n",
               path, sizeof path);
    write_file("quad.mtl",
               "newmtl painted\nKd 0 0 0\nKs 0.2 0.2 0.2\nNs 50\n"
               "map_Kd checker.png\nmap_d checker.png\n",
               path, sizeof path);

    const char *ply = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\n"
                      "property float y\nproperty float z\nelement face 3\n"
                      "property list uchar int vertex_indices\nend_header\n"
                      "0 0 0\n1 0 0\n0 0 1\n2 0 0\n0 1 0\n"
                      "3 0 2 1\n3 0 1 3\n3 0 4 2\n"; /* the second triangle has zero area */
    snprintf(path, sizeof path, "%s/tri.ply.gz", tmpdir);
    gzFile gz = gzopen(path, "wb");
    CHECK(gz != NULL, "cannot write %s", path);
    if (gz) {
        gzputs(gz, ply);
        gzclose(gz);
    }
    write_file("files.scene",
               "[scene]\n"
               "[mesh.room]\nprocedural = room\nsize = 4 3 4\n"
               "[mesh.quad]\nfile = quad.obj\ntranslate = 0 0.5 0\n"
               "[mesh.tri]\nfile = tri.ply.gz\nscale = 2\n"
               "[material.room_floor]\nalbedo = 0.5 0.5 0.5\n"
               "[light.l]\ntype = point\nposition = 0 2 0\nintensity = 1 1 1\n"
               "[camera.c]\neye = 0 1.5 1.5\ntarget = 0 1 0\n",
               path, sizeof path);
    gib_scene s;
    gib_error err;
    int rc = gib_scene_load(path, &s, &err);
    CHECK(rc == 0, "files.scene: %s", err.msg);
    if (rc)
        return;
    check_invariants(&s);
    CHECK(s.triangle_count == 12 + 2 + 3, "files: %u triangles, want 17 (degenerate kept)",
          s.triangle_count);
    int m = find_material(&s, "painted");
    CHECK(m >= 0, "files: material 'painted' missing");
    if (m >= 0) {
        const gib_material *M = &s.materials[m];
        CHECK(M->albedo_tex >= 0 && M->alpha_tex >= 0 && M->albedo_tex != M->alpha_tex,
              "painted: colour and mask are two decodings of one file");
        CHECK(M->spec_type == GIB_SPEC_PHONG && M->phong_n == 50, "painted: Ks/Ns -> Phong 50");
        /* Kd 0 with a texture reads as 1; 1 + 0.2 > 1 is scaled down together. */
        NEAR(M->albedo[0], 1.0 / 1.2, 1e-6, "Kd 1 and Ks 0.2 scaled by 1/1.2");
        NEAR(M->specular[0], 0.2 / 1.2, 1e-6, "Kd 1 and Ks 0.2 scaled by 1/1.2");
        if (M->albedo_tex >= 0 && M->alpha_tex >= 0) {
            const gib_texture *T = &s.textures[M->albedo_tex], *A = &s.textures[M->alpha_tex];
            CHECK(T->width == 2 && T->height == 2, "texture size %dx%d", T->width, T->height);
            NEAR(T->rgba[0], 1.0, 1e-6, "row 0 is the top row: top-left texel is red");
            NEAR(T->rgba[1], 0.0, 1e-6, "top-left texel is red");
            NEAR(T->rgba[4], 0.2158605, 1e-6, "sRGB 128/255 decodes to 0.2158605");
            NEAR(A->rgba[4], 128.0 / 255.0, 1e-6, "masks are not linearised");
            CHECK(strstr(T->path, "Checker.PNG") != NULL, "texture resolved ignoring case: %s",
                  T->path);
        }
    }
    CHECK((s.features & (GIB_FEAT_TEXTURES | GIB_FEAT_ALPHA_MASK | GIB_FEAT_SPECULAR |
                         GIB_FEAT_POINT_LIGHT | GIB_FEAT_CLOSED)) ==
              (GIB_FEAT_TEXTURES | GIB_FEAT_ALPHA_MASK | GIB_FEAT_SPECULAR | GIB_FEAT_POINT_LIGHT |
               GIB_FEAT_CLOSED),
          "files: features 0x%x", s.features);
    int f = find_material(&s, "room_floor"), d = find_material(&s, "default");
    CHECK(f >= 0 && s.materials[f].albedo[0] == 0.5f, "room_floor override not applied");
    CHECK(d >= 0 && s.materials[d].spec_type == GIB_SPEC_NONE, "PLY gets a diffuse 'default'");
    NEAR(s.bounds_max[1], 3.0, 1e-6, "room height");
    gib_scene_free(&s);
}

static void test_shared_data(void)
{
    char empty[300];
    snprintf(empty, sizeof empty, "%s/empty_root", tmpdir);
    mkdir(empty, 0700);
    setenv("GIBENCH_SCENES", empty, 1);
    gib_scene s;
    gib_error err;
    int rc = gib_scene_load("sponza", &s, &err);
    CHECK(rc == GIB_SCENE_UNAVAILABLE, "sponza with an empty data root: rc %d (%s)", rc, err.msg);
    if (rc == 0)
        gib_scene_free(&s);
    CHECK(strstr(err.msg, "sponza.scene:") && strstr(err.msg, "sponza-crytek") &&
              strstr(err.msg, "GIBENCH_SCENES") && strstr(err.msg, "McGuire"),
          "unavailable message must name the file, the folder, GIBENCH_SCENES and where to get "
          "the data: %s",
          err.msg);
    printf("ok   unavailable: %s\n", err.msg);

    gib_scene_info *info;
    int n;
    CHECK(gib_scene_list(&info, &n, &err) == 0, "list: %s", err.msg);
    int saw_cornell = 0, saw_sponza = 0;
    for (int i = 0; i < n; i++) {
        if (!strcmp(info[i].name, "cornell"))
            saw_cornell = info[i].available;
        if (!strcmp(info[i].name, "sponza"))
            saw_sponza = 1 + info[i].available;
    }
    CHECK(saw_cornell && saw_sponza == 1, "list: cornell available, sponza listed unavailable");
    free(info);
    rmdir(empty);

    unsetenv("GIBENCH_SCENES");
    const char *root = gib_scene_data_root();
    char dir[600];
    snprintf(dir, sizeof dir, "%s/sponza-crytek", root ? root : "");
    if (!root || access(dir, R_OK) != 0) {
        printf("skip shared-data scenes: no data root with sponza-crytek (%s)\n",
               root ? root : "none");
        return;
    }
    static const struct {
        const char *name;
        uint32_t tris;
        unsigned feats;
    } want[] = {
        {"sponza", 262267, GIB_FEAT_TEXTURES | GIB_FEAT_ALPHA_MASK | GIB_FEAT_SPOT_LIGHT},
        {"sponza_sun", 262267, GIB_FEAT_TEXTURES | GIB_FEAT_ALPHA_MASK | GIB_FEAT_DIR_LIGHT},
        {"sponza_dabrovic", 66450, GIB_FEAT_TEXTURES | GIB_FEAT_SPOT_LIGHT},
        {"sibenik", 75284, GIB_FEAT_TEXTURES | GIB_FEAT_SPOT_LIGHT},
        {"bunny", 69451 + 12, GIB_FEAT_SPOT_LIGHT | GIB_FEAT_CLOSED},
        {"dragon", 202520 + 12, GIB_FEAT_SPOT_LIGHT | GIB_FEAT_CLOSED},
    };
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
        double t0 = now();
        rc = gib_scene_load(want[i].name, &s, &err);
        double dt = now() - t0;
        CHECK(rc == 0, "%s: %s", want[i].name, err.msg);
        if (rc)
            continue;
        check_invariants(&s);
        CHECK(s.triangle_count == want[i].tris, "%s: %u triangles, want %u (README)", want[i].name,
              s.triangle_count, want[i].tris);
        CHECK((s.features & want[i].feats) == want[i].feats, "%s: features 0x%x lack 0x%x",
              want[i].name, s.features, want[i].feats);
        if (!strcmp(want[i].name, "sponza")) {
            CHECK(s.triangle_count > 200000, "sponza: more than 200000 triangles");
            CHECK(s.texture_count >= 25, "sponza: %u textures", s.texture_count);
            /* Seconds, not minutes; generous for sanitizer builds and slow disks. */
            CHECK(dt < 60.0, "sponza took %.1f s to load", dt);
        }
        printf("ok   %-16s %7u triangles %7u vertices %3u materials %3u textures  %.2f s\n",
               want[i].name, s.triangle_count, s.vertex_count, s.material_count, s.texture_count,
               dt);
        gib_scene_free(&s);
    }
}

int main(void)
{
    if (scene_test_begin("gib_scene_load") < 0)
        return 1;
    test_cornell();
    test_camera();
    test_lights();
    test_transforms();
    setenv("GIBENCH_SCENES", tmpdir, 1); /* mesh files of test_mesh_files live there */
    test_mesh_files();
    test_shared_data();
    return scene_test_end();
}

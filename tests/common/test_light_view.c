/* The light views' reflective shadow map (techniques/common/light_view.*) conserves energy: inside
 * a closed sphere (albedo 0.5, two-sided) every watt a light emits reaches a wall, so the flux of
 * all texels must add up to 0.5 x the emitted power, per colour channel:
 *   point light of intensity I:                 4 pi I
 *   spot, cos^e falloff inside half-angle a:    2 pi I (1 - cos^(e+1) a) / (e + 1)
 *   directional light of irradiance E (the sphere seen from outside): E pi R^2.
 * Tolerance 1% (the bound): what is left is the texels' point-sampled solid angles and
 * areas (O(1/res^2)) and the tessellated sphere (20 x 4^5 flat faces: its outline is within 2e-4
 * of the circle's area). Each case also checks where the flux is: a spot's texels carry flux only
 * inside its cone. A last case checks the z-buffer resolves a sheet 1 cm above the ground 25 m from
 * the light. */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness/gl/timers.h"
#include "techniques/common/light_view.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures;

static const char *sphere =
    "[scene]\ndescription = light-view energy test\nclosed = 1\n"
    "[mesh.sphere]\nprocedural = sphere_interior\nradius = 1.0\nsubdivisions = 5\n"
    "[material.sphere_wall]\nalbedo = 0.5 0.5 0.5\n"
    "[camera.c]\neye = 0 0 -0.6\ntarget = 1 0 -0.6\nup = 0 1 0\nfov = 60\n";

/* A scene's light views rendered once: the fixture, the views and what they were made with. */
typedef struct rendered_views {
    gib_gl_fixture fx;
    gib_ledger ledger;
    gib_timers timers;
    gib_light_views lv;
} rendered_views;

/* Opens the scene text, renders its light views at res with the attributes asked for; 0, or -1
 * (a failure counted and printed). */
static int render_views(rendered_views *v, const char *dir, const char *name, const char *text,
                        int res, unsigned attributes)
{
    if (gib_fixture_open_text(&v->fx, dir, name, text) < 0) {
        failures++;
        return -1;
    }
    gib_ledger_init(&v->ledger);
    gib_timers_init(&v->timers);
    gib_error err;
    if (gib_light_views_create(&v->lv, &v->fx.gpu, res, attributes, "lv", &v->ledger, &err) < 0) {
        CHECK(0, "%s: %s", name, err.msg);
        gib_fixture_close(&v->fx);
        return -1;
    }
    gib_timers_frame_begin(&v->timers, 1);
    gib_light_views_render(&v->lv, &v->fx.gpu, &v->timers, "light_view");
    gib_timers_frame_end(&v->timers);
    return 0;
}

/* Attribute a of every face, RGBA floats (malloc'd). */
static float *read_attribute(const rendered_views *v, int a, int res)
{
    size_t n = (size_t)res * res * v->lv.face_count * 4;
    float *px = malloc(n * sizeof *px);
    glGetTextureImage(v->lv.textures[a], 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * sizeof *px), px);
    return px;
}

static void close_views(rendered_views *v)
{
    gib_light_views_destroy(&v->lv, &v->ledger);
    gib_timers_destroy(&v->timers);
    gib_ledger_release_all(&v->ledger);
    gib_fixture_close(&v->fx);
}

static void check_case(const char *dir, const char *name, const char *light, int res,
                       const double expected[3], double cone_cos)
{
    char text[4096];
    snprintf(text, sizeof text, "%s[light.l]\n%s", sphere, light);
    rendered_views v;
    if (render_views(&v, dir, name, text, res, GIB_LV_FLUX | GIB_LV_POSITION) < 0)
        return;
    size_t n = (size_t)res * res * v.lv.face_count * 4;
    float *flux = read_attribute(&v, 3, res), *pos = read_attribute(&v, 1, res);
    double sum[3] = {0, 0, 0};
    long outside = 0;
    const gib_light *l = &v.fx.scene.lights[0];
    for (size_t i = 0; i < n; i += 4) {
        for (int c = 0; c < 3; c++)
            sum[c] += flux[i + c];
        if (cone_cos > -2 && flux[i] > 0) { /* a spot: flux only inside the cone */
            double d[3], len = 0, c = 0;
            for (int k = 0; k < 3; k++) {
                d[k] = pos[i + k] - l->position[k];
                len += d[k] * d[k];
            }
            for (int k = 0; k < 3; k++)
                c += d[k] * l->direction[k] / sqrt(len);
            outside += c < cone_cos - 1e-4;
        }
    }
    for (int c = 0; c < 3; c++) {
        char what[160];
        snprintf(what, sizeof what,
                 "%s res %d faces %d channel %d: texels' flux %.6f over the expected %.6f", name,
                 res, v.lv.face_count, c, sum[c], expected[c]);
        CHECK_NEAR(what, 1, sum[c] / expected[c], 0.01,
                   "the issue's bound: point-sampled solid angles, areas, the tessellated sphere");
    }
    CHECK(!outside, "%s: %ld texels outside the spot's cone carry flux", name, outside);
    free(flux);
    free(pos);
    close_views(&v);
}

/* A spot of intensity (1, 2, 3) with cos^e falloff inside `deg` degrees. */
static void check_spot(const char *dir, const char *name, const char *placement, int e, double deg)
{
    const double I[3] = {1, 2, 3}, a = deg * M_PI / 180;
    double expected[3];
    for (int c = 0; c < 3; c++)
        expected[c] = 0.5 * 2 * M_PI * I[c] * (1 - pow(cos(a), e + 1)) / (e + 1);
    char light[256];
    snprintf(light, sizeof light,
             "type = spot\n%sintensity = 1 2 3\nexponent = %d\nouter_angle = %g\n", placement, e,
             deg);
    check_case(dir, name, light, 128, expected, cos(a));
}

/* Depth precision: a 4 x 4 m sheet 1 cm above a 40 x 40 m ground, lit from 25 m above by a spot:
 * every texel of the light view inside the sheet's footprint must see the sheet (its position 1 cm
 * up), none the ground under it. With a 24-bit z-buffer and the near plane at far / 1e5 the depth
 * resolved ~7 cm there and the ground took every texel (Sponza's pools lost half their photons so);
 * the float z-buffer with reversed depth resolves ~1e-6 of the distance. Bound: no texel but those
 * on the sheet's border (its outline crosses at most 4 x res texels of the map). */
static void check_depth_precision(const char *dir)
{
    const char *text =
        "[scene]\ndescription = light-view depth precision\n"
        "[mesh.sheet]\nprocedural = quad\nsize = 4 4\ntranslate = 0 0.01 0\n"
        "[mesh.ground]\nprocedural = quad\nsize = 40 40\n"
        "[light.l]\ntype = spot\nposition = 0 25 0\ndirection = 0 -1 0\nintensity = 1 1 1\n"
        "outer_angle = 10\n"
        "[camera.c]\neye = 0 5 10\ntarget = 0 0 0\nup = 0 1 0\nfov = 60\n";
    const int res = 512;
    rendered_views v;
    if (render_views(&v, dir, "depth_precision", text, res, GIB_LV_POSITION) < 0)
        return;
    size_t n = (size_t)res * res * v.lv.face_count * 4;
    float *pos = read_attribute(&v, 1, res);
    long inside = 0, ground = 0;
    for (size_t i = 0; i < n; i += 4)
        if (fabsf(pos[i]) < 2 && fabsf(pos[i + 2]) < 2) {
            inside++;
            ground += pos[i + 1] < 0.01f;
        }
    char what[128];
    snprintf(what, sizeof what, "%ld texels over the sheet", inside);
    CHECK_TRUE("depth_precision: more than 1000 texels over the sheet", inside > 1000, what);
    snprintf(what, sizeof what, "depth_precision: of %ld, texels seeing the ground 1 cm under",
             inside);
    CHECK_AT_MOST(what, ground, 4 * res,
                  "the sheet's border: its outline crosses at most 4 x res texels of the map");
    free(pos);
    close_views(&v);
}

int main(void)
{
    char dir[] = "/tmp/gib_light_view_XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp");
        return 1;
    }
    const double pi = M_PI, rho = 0.5;
    const double I[3] = {1, 2, 3};
    double e[3];
    for (int c = 0; c < 3; c++)
        e[c] = rho * 4 * pi * I[c];
    check_case(dir, "point_centre", "type = point\nposition = 0 0 0\nintensity = 1 2 3\n", 64, e,
               -3);
    /* Off centre: the walls are nearer on one side, the total the same. */
    check_case(dir, "point_off_centre", "type = point\nposition = 0.3 0.2 -0.4\nintensity = 1 2 3\n",
               64, e, -3);
    /* A narrow spot: one perspective view over its cone; a wide one: the cube. */
    check_spot(dir, "spot_30", "position = 0.1 0 0\ndirection = 0 1 0\n", 1, 30);
    check_spot(dir, "spot_70", "position = 0 -0.2 0\ndirection = 0.6 0.8 0\n", 2, 70);
    /* Directional, from outside: the sphere's cross-section pi R^2. */
    for (int c = 0; c < 3; c++)
        e[c] = rho * I[c] * pi;
    check_case(dir, "directional",
               "type = directional\ndirection = 0.3 -1 0.2\nintensity = 1 2 3\n", 512, e, -3);
    check_depth_precision(dir);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        printf("note: could not remove %s\n", dir);
    printf("%s\n", failures ? "FAILED" : "all light-view energy checks passed");
    return failures ? 1 : 0;
}

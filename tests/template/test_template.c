/* What is particular to the template (techniques/template/), beyond the tests every technique
 * gets (test_registry, test_contract_gl, test_closed_form), run as the harness runs it:
 *  1. its counter counts the surface pixels: every pixel in the furnace, so W x H;
 *  2. its parameter is read: strength = 2 doubles the image (up to float rounding, 1e-6);
 *  3. its status: a closed room whose light has no power gives `no_light`, not a black image to
 *     score.
 * Runtime: under a second. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "harness/app/runner.h"
#include "harness/gl/context.h"
#include "tests/common/gl_fixture.h"

static int failures;
#include "tests/common/check.h"

#define W 32
#define H 24

/* The furnace's sphere and camera with a point light of no power. */
static const char *DARK_ROOM =
    "[scene]\ndescription = the furnace with a dark light (tests/template/test_template.c)\n"
    "closed = 1\n[mesh.sphere]\nprocedural = sphere_interior\nradius = 1.0\nsubdivisions = 2\n"
    "[material.wall]\nalbedo = 0.5 0.5 0.5\n[light.centre]\ntype = point\nposition = 0 0 0\n"
    "intensity = 0 0 0\n[camera.inside]\neye = 0 0 -0.6\ntarget = 1 0 -0.6\nup = 0 1 0\n"
    "fov = 60\n";

static const gib_technique *the_template(void)
{
    int n = 0;
    const gib_technique *const *tests = gib_techniques_test_only(&n);
    for (int i = 0; i < n; i++)
        if (!strcmp(tests[i]->name, "template"))
            return tests[i];
    return NULL;
}

/* Runs the template with strength `strength` and returns its image mean (-1 on failure). */
static double run(const gib_gpu_scene *gpu, const gib_technique *t, const char *strength,
                  gib_run_result *r)
{
    gib_params p;
    gib_error err;
    gib_params_default(t, &p);
    if (gib_param_set(t, &p, "strength", strength, &err) < 0) {
        CHECK(0, "%s", err.msg);
        return -1;
    }
    gib_run_technique(gpu, t, &p, 0, W, H, 0, 1, r);
    if (!r->ok)
        return -1;
    double sum = 0;
    for (long i = 0; i < (long)W * H * 3; i++)
        sum += r->images[0].px[i];
    return sum / ((double)W * H * 3);
}

static void lit_room(const gib_gl_fixture *fx, const gib_technique *t)
{
    gib_run_result r1, r2;
    double m1 = run(&fx->gpu, t, "1", &r1), m2 = run(&fx->gpu, t, "2", &r2);
    char want[32];
    snprintf(want, sizeof want, "pixels=%d", W * H);
    CHECK(r1.ok && !strcmp(r1.counters, want), "counters '%s' (status %s), expected '%s'",
          r1.counters, r1.status, want);
    CHECK(m1 > 0 && fabs(m2 / m1 - 2) < 1e-6, "strength 2 gives mean %.7f, strength 1 %.7f", m2,
          m1);
    printf("furnace: counters '%s', mean %.6f at strength 1, %.6f at 2\n", r1.counters, m1, m2);
    gib_run_result_free(&r1);
    gib_run_result_free(&r2);
}

static void dark_room(const gib_technique *t, const char *dir)
{
    char path[512];
    snprintf(path, sizeof path, "%s/template_dark_room.scene", dir);
    FILE *f = fopen(path, "w");
    CHECK(f, "cannot write %s", path);
    if (!f)
        return;
    fputs(DARK_ROOM, f);
    fclose(f);
    gib_scene scene;
    gib_gpu_scene gpu;
    gib_error err;
    if (gib_scene_load(path, &scene, &err) < 0 || gib_gpu_scene_upload(&scene, &gpu, &err) < 0) {
        CHECK(0, "dark room: %s", err.msg);
        return;
    }
    gib_run_result r;
    run(&gpu, t, "1", &r);
    CHECK(!strcmp(r.status, "no_light"), "dark room: status '%s', expected no_light", r.status);
    printf("dark room: status %s (%s)\n", r.status, r.err.msg);
    gib_run_result_free(&r);
    gib_gpu_scene_free(&gpu);
    gib_scene_free(&scene);
}

int main(int argc, char **argv)
{
    const gib_technique *t = the_template();
    if (!t) {
        CHECK(0, "no test-only technique named 'template'");
        return 1;
    }
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "furnace") < 0)
        return 1;
    lit_room(&fx, t);
    dark_room(t, argc > 1 ? argv[1] : ".");
    gib_fixture_close(&fx);
    printf("%s: the template's counter, parameter and status\n", failures ? "FAIL" : "PASS");
    return failures ? 1 : 0;
}

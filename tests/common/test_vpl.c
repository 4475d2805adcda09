/* The VPLs shared by rsm_gather and multires_ir (techniques/common/vpl.h, vpl_gather.glsl).
 *
 * 1. The gather (vpl_irradiance, through its probe) of ONE VPL put by hand against the closed form
 *    E = Phi cos_l cos_x / (pi max(d^2, eps^2)) in double, at points of a plane under the VPL,
 *    including points the VPL must not light: behind the VPL's own surface (cos_l < 0) and on the
 *    back of the receiver (cos_x < 0), where the text's |n.v| would light them, and points nearer
 *    than eps. Tolerance 1e-5 relative (float arithmetic on O(1) numbers; the text's formula, the
 *    unnormalised v or a missing 1/pi are off by factors, not 1e-5).
 * 2. The VPLs' fluxes add up to the light views' total reflected flux (the FLUX texels summed in
 *    double) within 1e-5 relative (float sums of ~10^3 texels a thread), for a 40-degree spot (one
 *    perspective view: the circle pattern, Voronoi regions) and a point light in the Cornell box (a
 *    cube: the grid, 256 VPLs in rows of 6-7 over 6 faces), at two VPL counts each, and a
 *    directional light (the grid on its orthographic view); each VPL
 *    with flux stands on a surface. A VPL weighted by its sample texel's flux times the texels per
 *    VPL instead (the uniform-density assumption the circle pattern breaks) misses by percents.
 * 3. Fewer VPLs than light-view faces is refused, naming vpl_count. */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "techniques/common/light_view.h"
#include "techniques/common/vpl.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

static const char *spot_scene =
    "[scene]\ndescription = furnace sphere lit by a 40-degree spot (circle pattern)\nclosed = 1\n"
    "[mesh.sphere]\nprocedural = sphere_interior\nradius = 1.0\nsubdivisions = 4\n"
    "[material.sphere_wall]\nalbedo = 0.5 0.4 0.3\n"
    "[light.centre]\ntype = spot\nposition = 0.1 0 0\ndirection = 0.3 -0.2 -1\nintensity = 1 2 3\n"
    "exponent = 2\nouter_angle = 40\n"
    "[camera.inside]\neye = 0 0 0.6\ntarget = 0 0 -1\nup = 0 1 0\nfov = 60\n";

static const char *point_scene =
    "[scene]\ndescription = Cornell box with a point light (grid pattern on a cube)\n"
    "[mesh.box]\nprocedural = cornell_box\n"
    "[light.bulb]\ntype = point\nposition = 0.3 0.4 0.25\nintensity = 0.5 0.5 0.5\n"
    "[camera.published]\neye = 0.278 0.273 -0.800\ntarget = 0.278 0.273 0.0\nup = 0 1 0\n"
    "fov = 39.3077\n";

static const char *sun_scene =
    "[scene]\ndescription = Cornell box under a directional light (grid pattern on the ortho view)\n"
    "[mesh.box]\nprocedural = cornell_box\n"
    "[light.sun]\ntype = directional\ndirection = 0.3 -1 0.4\nintensity = 2 2 2\n"
    "[camera.published]\neye = 0.278 0.273 -0.800\ntarget = 0.278 0.273 0.0\nup = 0 1 0\n"
    "fov = 39.3077\n";

/* Fewer VPLs than faces is refused with a message naming the parameter. */
static int count_test(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open_text(&fx, "/tmp", "ir_vpl_point", point_scene) < 0)
        return 0;
    gib_light_views lv;
    gib_vpls v;
    gib_ledger ledger;
    gib_error err;
    gib_ledger_init(&ledger);
    int ok = 0;
    if (gib_light_views_create(&lv, &fx.gpu, 16, GIB_LV_POSITION | GIB_LV_NORMAL | GIB_LV_FLUX,
                               "rsm", &ledger, &err) == 0) {
        ok = gib_vpls_create(&v, &lv, 5, 1, "vpl", &ledger, &err) < 0 &&
             strstr(err.msg, "vpl_count") != NULL;
        snprintf(check_msg, sizeof check_msg,
                 "5 VPLs for a cube's 6 faces: %.400s",
                 ok ? err.msg : "accepted");
        CHECK_TRUE(check_msg, ok, "");
        if (!ok)
            gib_vpls_destroy(&v, &ledger);
        gib_light_views_destroy(&lv, &ledger);
    }
    gib_fixture_close(&fx);
    return ok;
}

static int probe_test(gib_gl_fixture *fx)
{
    gib_light_views lv;
    gib_vpls v;
    gib_ledger ledger;
    gib_error err;
    gib_ledger_init(&ledger);
    if (gib_light_views_create(&lv, &fx->gpu, 16, GIB_LV_POSITION | GIB_LV_NORMAL | GIB_LV_FLUX,
                               "rsm", &ledger, &err) < 0 ||
        gib_vpls_create(&v, &lv, 1, 1, "vpl", &ledger, &err) < 0) {
        CHECK(0, "probe set-up: %s", err.msg);
        return 0;
    }
    /* One VPL at the origin facing +y (a floor patch), flux (2, 1, 0.5) W. */
    const float vpl[GIB_VPL_FLOATS] = {0, 0, 0, 1, 0, 1, 0, 0, 2, 1, 0.5f, 0};
    gib_vpls_write(&v, vpl, 1);
    const float eps = 0.05f;
    /* Receivers: a wall x = 1 facing -x, points over y in (-0.5, 1.5), z in (-1, 1); plus the
     * wall's back (normal +x), and points near the VPL. */
    enum { NY = 9, NZ = 5, N = NY * NZ * 2 + 3 };
    float in[8 * N], out[4 * N], nx[N][3], px[N][3];
    int k = 0;
    for (int back = 0; back < 2; back++)
        for (int i = 0; i < NY; i++)
            for (int j = 0; j < NZ; j++, k++) {
                px[k][0] = 1;
                px[k][1] = -0.5f + 2.0f * i / (NY - 1);
                px[k][2] = -1 + 2.0f * j / (NZ - 1);
                nx[k][0] = back ? 1.0f : -1.0f;
                nx[k][1] = nx[k][2] = 0;
            }
    const float near[3][6] = {{0.03f, 0.02f, 0, -0.6f, 0.8f, 0}, /* nearer than eps */
                              {0.1f, 0.3f, 0.2f, 0, -1, 0},      /* ceiling-like, above */
                              {0.2f, -0.3f, 0, 0, 1, 0}};        /* under the floor */
    for (int q = 0; q < 3; q++, k++)
        for (int c = 0; c < 3; c++) {
            px[k][c] = near[q][c];
            nx[k][c] = near[q][3 + c];
        }
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 4; c++) {
            in[8 * i + c] = c < 3 ? px[i][c] : 0;
            in[8 * i + 4 + c] = c < 3 ? nx[i][c] : 0;
        }
    if (gib_vpls_probe(&v, eps, in, N, out, &err) < 0) {
        CHECK(0, "probe: %s", err.msg);
        return 0;
    }
    double worst = 0;
    int lit = 0, ok = 1;
    for (int i = 0; i < N; i++) {
        double d[3], d2 = 0;
        for (int c = 0; c < 3; c++) {
            d[c] = (double)vpl[c] - px[i][c];
            d2 += d[c] * d[c];
        }
        double len = sqrt(d2), cx = 0, cl = 0;
        for (int c = 0; c < 3; c++) {
            cx += nx[i][c] * d[c] / len;
            cl -= vpl[4 + c] * d[c] / len;
        }
        double g = cx > 0 && cl > 0 ? cx * cl / (M_PI * fmax(d2, (double)eps * eps)) : 0;
        lit += g > 0;
        for (int c = 0; c < 3; c++) {
            double want = vpl[8 + c] * g, got = out[4 * i + c];
            double e = fabs(got - want) / fmax(fabs(want), 1e-6);
            if (e > worst)
                worst = e;
            if (e > 1e-5 && fabs(got - want) > 1e-9) {
                if (ok)
                    printf("  point %d (%g %g %g) n (%g %g %g): E %g, closed form %g\n", i, px[i][0],
                           px[i][1], px[i][2], nx[i][0], nx[i][1], nx[i][2], got, want);
                ok = 0;
            }
        }
    }
    snprintf(check_msg, sizeof check_msg,
             "one VPL's irradiance at %d points (%d lit) against Phi cos_l cos_x / (pi max(d^2, "
             "eps^2)): worst relative error %.2g (tolerance 1e-5)",
             N, lit, worst);
    CHECK_TRUE(check_msg, ok, "");
    gib_vpls_destroy(&v, &ledger);
    gib_light_views_destroy(&lv, &ledger);
    return ok;
}

static int flux_test(const char *name, const char *text, int count)
{
    gib_gl_fixture fx;
    if (gib_fixture_open_text(&fx, "/tmp", name, text) < 0)
        return 0;
    gib_light_views lv;
    gib_vpls v;
    gib_ledger ledger;
    gib_error err;
    gib_timers timers;
    gib_ledger_init(&ledger);
    gib_timers_init(&timers);
    int res = 64, ok = 1;
    if (gib_light_views_create(&lv, &fx.gpu, res, GIB_LV_POSITION | GIB_LV_NORMAL | GIB_LV_FLUX,
                               "rsm", &ledger, &err) < 0 ||
        gib_vpls_create(&v, &lv, count, 7, "vpl", &ledger, &err) < 0) {
        CHECK(0, "%s: set-up: %s", name, err.msg);
        return 0;
    }
    gib_light_views_render(&lv, &fx.gpu, &timers, "rsm");
    gib_vpls_update(&v, &lv, &timers, "rsm");
    size_t texels = (size_t)res * res * lv.face_count;
    float *flux = malloc(texels * 16), *vp = malloc((size_t)count * GIB_VPL_FLOATS * 4);
    glGetTextureImage(lv.textures[3], 0, GL_RGBA, GL_FLOAT, (GLsizei)(texels * 16), flux);
    gib_vpls_read(&v, vp);
    double want[3] = {0, 0, 0}, got[3] = {0, 0, 0};
    for (size_t i = 0; i < texels; i++)
        for (int c = 0; c < 3; c++)
            want[c] += flux[4 * i + c];
    int on_surface = 1, valid = 0;
    for (int i = 0; i < count; i++) {
        const float *p = vp + GIB_VPL_FLOATS * i;
        for (int c = 0; c < 3; c++)
            got[c] += p[8 + c];
        valid += p[3] > 0.5f;
        if (p[3] < 0.5f && p[8] + p[9] + p[10] > 0)
            on_surface = 0;
    }
    for (int c = 0; c < 3; c++) {
        CHECK(want[c] > 0, "%s channel %d: the light views reflect %.7g W", name, c, want[c]);
        snprintf(check_msg, sizeof check_msg,
                 "%s (%d faces, %d VPLs, %d valid) channel %d: VPL flux %.7g W over the light "
                 "views' reflected %.7g W",
                 name, lv.face_count, count, valid, c, got[c], want[c]);
        CHECK_NEAR(check_msg, 1, got[c] / want[c], 1e-5, "float sums of ~10^3 texels a thread");
    }
    if (!on_surface) {
        CHECK(0, "%s: a VPL carries flux without a surface", name);
        ok = 0;
    }
    if (v.count != count) {
        CHECK(0, "%s: %d VPLs, asked for %d", name, v.count, count);
        ok = 0;
    }
    free(flux);
    free(vp);
    gib_vpls_destroy(&v, &ledger);
    gib_light_views_destroy(&lv, &ledger);
    gib_timers_destroy(&timers);
    gib_fixture_close(&fx);
    return ok;
}

int main(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open_text(&fx, "/tmp", "ir_vpl_spot", spot_scene) < 0)
        return 1;
    printf("renderer %s\n", fx.info.renderer);
    failures += !(probe_test(&fx));
    gib_fixture_close(&fx);
    failures += !(flux_test("ir_vpl_spot", spot_scene, 256));
    failures += !(flux_test("ir_vpl_spot", spot_scene, 37));
    failures += !(flux_test("ir_vpl_point", point_scene, 256));
    failures += !(flux_test("ir_vpl_point", point_scene, 6 * 16));
    failures += !(flux_test("ir_vpl_sun", sun_scene, 256));
    failures += !(count_test());
    printf("%s: VPL gather and flux\n", failures ? "FAIL" : "PASS");
    return failures != 0;
}

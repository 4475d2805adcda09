/* Scenes that move: the GL side and the reference render the same instant.
 *
 * usage: test_motion SCENE T. On a moving scene, at t = 0 and at t = T:
 *  1. Primary hits: the G-buffer's positions after gib_gpu_scene_set_time(t), as view depth,
 *     against the reference's `depth` image at time t (Embree built from the posed vertices),
 *     pixel centres both. Tolerances as tests/gl/test_camera.c, for the same reasons: depths
 *     within 1e-4 x the scene diagonal except on silhouettes (at most 2% of the pixels), hit/miss
 *     agreeing on 99%.
 *  2. `direct` run over two frames, at 0 then at T (dt = T), its image against the reference
 *     `direct` at T: relative RMSE below 0.08 (the bound of tests/direct/test_direct_cornell.c, same
 *     technique and light: shadow-map edges are what is left) and the median per-pixel relative
 *     error over lit pixels below 1e-3 (same visible point, same falloff: G-buffer rounding).
 * And that the test can tell the instants apart: the scene must move enough that the hits at T
 * against the reference at 0 disagree on more than 2% of the pixels, and the image at T must fail
 * one of the two image bounds against the reference at 0 — so a GL side or a technique that kept
 * t = 0 data fails check 1 or 2. */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "harness/gl/gpu_scene.h"
#include "harness/app/runner.h"
#include "harness/gl/view.h"
#include "harness/imaging/metrics.h"
#include "reference/reference.h"
#include "techniques/common/gbuffer.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

#define W 96
#define H 64
#define REL_RMSE_MAX 0.08
#define MEDIAN_MAX 1e-3

static int reference(const gib_scene *s, int comp, double t, gib_image *out)
{
    gib_ref_params rp = {.component = comp, .width = W, .height = H, .spp = 1, .seed = 1,
                         .quiet = 1, .time = (float)t};
    gib_error err;
    gib_ref_stats st;
    if (gib_reference_render(s, &rp, out, NULL, &st, &err) < 0) {
        CHECK(0, "reference at t = %g: %s", t, err.msg);
        return -1;
    }
    return 0;
}

/* GL view depth per pixel (row 0 on top), -1 for a miss, with the GPU scene posed at t. */
static int gl_depth(gib_gl_fixture *fx, double t, float *depth)
{
    gib_error err;
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    gib_gbuffer g;
    gib_timers timers;
    gib_timers_init(&timers);
    if (gib_gpu_scene_set_time(&fx->gpu, t, &err) < 0 ||
        gib_gbuffer_create(&g, W, H, &ledger, &err) < 0) {
        CHECK(0, "%s", err.msg);
        return -1;
    }
    /* The GL side works in the scene's frame (scene.h, gib_scene_frame): its camera there. */
    const gib_camera *cam = &fx->gpu.scene->cameras[0];
    gib_view view;
    gib_view_make(fx->gpu.scene, cam, W, H, (float)t, &view);
    gib_timers_frame_begin(&timers, 0);
    gib_gbuffer_render(&g, &fx->gpu, &view, &timers, "gbuffer");
    gib_timers_frame_end(&timers);
    float *pos = malloc(sizeof(float) * 4 * W * H);
    glGetTextureImage(g.position, 0, GL_RGBA, GL_FLOAT, W * H * 16, pos);
    float right[3], up[3], fwd[3];
    gib_camera_basis(cam, right, up, fwd);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const float *p = pos + ((size_t)(H - 1 - y) * W + x) * 4; /* GL rows are bottom up */
            float d = 0;
            for (int k = 0; k < 3; k++)
                d += (p[k] - cam->eye[k]) * fwd[k];
            depth[y * W + x] = p[3] > 0.5f ? d : -1.0f;
        }
    free(pos);
    gib_gbuffer_destroy(&g, &ledger);
    gib_timers_destroy(&timers);
    return 0;
}

typedef struct hit_cmp {
    int both, hitmiss, far_off;
} hit_cmp;

static hit_cmp compare_hits(const float *gl, const gib_image *ref, float tol)
{
    hit_cmp c = {0, 0, 0};
    for (int i = 0; i < W * H; i++) {
        const float r = ref->px[3 * i];
        const int rt_hit = r > 0.0f, gl_hit = gl[i] >= 0.0f;
        if (rt_hit != gl_hit)
            c.hitmiss++;
        else if (rt_hit) {
            c.both++;
            c.far_off += fabsf(gl[i] - r) > tol;
        }
    }
    return c;
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* Relative RMSE and the median per-pixel relative error over pixels lit in the reference. */
static void image_errors(const gib_scene *s, const gib_image *ref, const gib_image *img,
                         double *rel_rmse, double *median)
{
    gib_metrics m;
    gib_error err;
    gib_metrics_compute(ref, img, s->exposure, &m, &err);
    *rel_rmse = m.nonfinite ? INFINITY : m.rel_rmse;
    float *rel = malloc(sizeof(float) * W * H);
    int n = 0;
    for (int i = 0; i < W * H; i++) {
        double a = 0, b = 0;
        for (int c = 0; c < 3; c++) {
            a += ref->px[i * 3 + c];
            b += img->px[i * 3 + c];
        }
        if (a > 1e-6)
            rel[n++] = (float)(fabs(b - a) / a);
    }
    qsort(rel, (size_t)n, sizeof(float), cmp_float);
    *median = n ? rel[n / 2] : 1.0;
    free(rel);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: test_motion SCENE T\n");
        return 2;
    }
    const double T = atof(argv[2]);
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, argv[1]) < 0)
        return 1;
    gib_scene *s = &fx.scene;
    if (!s->motion_count) {
        CHECK(0, "scene '%s' does not move", s->name);
        gib_fixture_close(&fx);
        return 1;
    }
    const float tol = 1e-4f * gib_fixture_diagonal(s);
    const int n = W * H;

    /* 1. Primary hits at 0 and T, and the hits at T against the reference at 0. */
    float *gl = malloc(sizeof(float) * n);
    gib_image ref_depth[2] = {{0}};
    const double times[2] = {0.0, T};
    int setup_ok = 1; /* the parts that do not depend on the GL side rendering right */
    for (int i = 0; i < 2 && setup_ok; i++)
        setup_ok = reference(s, GIB_COMP_DEPTH, times[i], &ref_depth[i]) == 0;
    for (int i = 0; i < 2 && setup_ok; i++) {
        if (gl_depth(&fx, times[i], gl) < 0) {
            setup_ok = 0;
            break;
        }
        hit_cmp c = compare_hits(gl, &ref_depth[i], tol);
        const int pass = c.both > n / 4 && c.hitmiss <= n / 100 && c.far_off <= n / 50;
        snprintf(check_msg, sizeof check_msg,
                 "%s t = %g: GL hits vs the reference's: both hit %d of %d, hit/miss disagree %d "
                 "(%.2f%%, max 1%%), farther than 1e-4 diag %d (%.2f%%, max 2%%)",
                 s->name, times[i], c.both, n, c.hitmiss, 100.0 * c.hitmiss / n, c.far_off,
                 100.0 * c.far_off / n);
        CHECK_TRUE(check_msg, pass, "");
        if (i == 1) {
            for (int k = 0; k < n; k++) /* the reference's hits at T, as the GL array */
                gl[k] = ref_depth[1].px[3 * k] > 0.0f ? ref_depth[1].px[3 * k] : -1.0f;
            hit_cmp st = compare_hits(gl, &ref_depth[0], tol);
            const double moved = (double)(st.hitmiss + st.far_off) / n;
            snprintf(check_msg, sizeof check_msg,
                     "the reference's hits at t = %g and at t = 0 differ on %.2f%% of the pixels "
                     "(must be > 2%%: the scene moves enough to tell the instants apart)",
                     T, 100.0 * moved);
            CHECK_TRUE(check_msg, moved > 0.02, "");
            setup_ok &= moved > 0.02;
        }
    }

    /* 2. `direct` over frames at 0 and T against the reference at T (and at 0: must differ). */
    const gib_technique *tech = gib_technique_find("direct");
    gib_params p;
    gib_params_default(tech, &p);
    gib_run_result r;
    memset(&r, 0, sizeof r);
    gib_image ref_direct[2] = {{0}};
    if (setup_ok) {
        gib_run(&(gib_run_request){.scene = &fx.gpu, .technique = tech, .params = &p, .width = W,
                                   .height = H, .warmup = 1, .frames = 1, .time = T, .dt = T},
                &r);
        if (!r.ok) {
            CHECK(0, "direct: %s: %s", r.status, r.err.msg);
            setup_ok = 0;
        }
        for (int i = 0; i < 2 && setup_ok; i++)
            setup_ok = reference(s, GIB_COMP_DIRECT, times[i], &ref_direct[i]) == 0;
    }
    failures += !setup_ok;
    if (setup_ok) {
        double rel[2], med[2];
        for (int i = 0; i < 2; i++)
            image_errors(s, &ref_direct[i], &r.images[0], &rel[i], &med[i]);
        const int pass = rel[1] < REL_RMSE_MAX && med[1] < MEDIAN_MAX;
        snprintf(check_msg, sizeof check_msg,
                 "direct at t = %g (frames at 0 and %g) vs the reference at t = %g: rel_rmse %.4g "
                 "(max %.2g), median per-pixel rel error %.3g (max %.0e)",
                 T, T, T, rel[1], REL_RMSE_MAX, med[1], MEDIAN_MAX);
        CHECK_TRUE(check_msg, pass, "");
        const int differs = !(rel[0] < REL_RMSE_MAX && med[0] < MEDIAN_MAX);
        snprintf(check_msg, sizeof check_msg,
                 "the same image vs the reference at t = 0: rel_rmse %.4g, median %.3g (must fail "
                 "a bound: an image of t = 0 would be told apart)",
                 rel[0], med[0]);
        CHECK_TRUE(check_msg, differs, "");
        if (getenv("GIB_TEST_OUT")) {
            char path[1024];
            gib_error err;
            snprintf(path, sizeof path, "%s/motion_%s_t%g.png", getenv("GIB_TEST_OUT"), s->name, T);
            gib_png_write_preview(path, &r.images[0], s->exposure, &err);
            snprintf(path, sizeof path, "%s/motion_%s_t%g_ref.png", getenv("GIB_TEST_OUT"), s->name,
                     T);
            gib_png_write_preview(path, &ref_direct[1], s->exposure, &err);
        }
    }
    if (r.output_count)
        gib_run_result_free(&r);
    for (int i = 0; i < 2; i++) {
        gib_image_free(&ref_depth[i]);
        gib_image_free(&ref_direct[i]);
    }
    free(gl);
    gib_fixture_close(&fx);
    printf("%s\n", failures ? "FAIL" : "PASS");
    return failures != 0;
}

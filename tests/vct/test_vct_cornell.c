/* vct (Crassin et al. 2011 as Sugihara et al. 2014 Sec. 6 ran it) against one diffuse bounce
 * (L D D E), at 64x64 pixels, voxel_res 64, inject_res 128 (seconds on llvmpipe).
 *
 * VCT is a coarse, biased estimate and these bounds are what this build of the method gets, with
 * their reasons; each fails when a bug is put back (noted):
 *  - the furnace (scenes/furnace.scene: inside a closed sphere, albedo 0.5, I = 1 W/sr at the
 *    centre; one bounce = 0.25 / pi = 0.079577 everywhere): the mean within FURNACE_LO..HI of the
 *    closed form, and the direct light within DIRECT_TOL of 0.5 / pi (no occluder between the
 *    light and any wall: a shadow cone that meets its own wall fails; measured 8.9e-5).
 *    Measured 0.63: the sphere's shell is one voxel thick, so a coarse cell that holds it is
 *    mostly empty and pre-integrates to a fraction of its opacity and radiance, and the cone then
 *    leaves the sphere through it with the rest (VCT's thin-shell loss). It measured 0.71 while the
 *    cones read beyond the grid, where the edge-clamped textures repeated the sphere's wall (the
 *    grid's margin and the cone's exit, vct_trace.glsl): light that the honest loss now lacks, so
 *    the band's floor moved from 0.65 to 0.55 with it. Radiance injected without its 1/pi (x3.1)
 *    or the cone weights not summing to 1 fall outside;
 *  - the Cornell box against the `indirect` reference (REF_SPP): the mean of each channel within
 *    15% of the reference's (MEAN_LO..HI; measured 1.03-1.06; the paper's level measured
 *    0.82: its samples read the receiver's own cells, vct_trace.glsl), 8x8-block relative
 *    RMSE below BLOCK_TOL (measured 0.26-0.37; 0.81-1.03 at the paper's level), and the colour
 *    bleeding on the right sides: the left third (red wall) redder than the right third (green
 *    wall), as in the reference (mirrored anisotropic directions fail this). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "harness/app/runner.h"
#include "harness/gl/context.h"
#include "reference/reference.h"
#include "tests/common/block_stats.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

#define W 64
#define H 64
#define BLOCK 8
#define REF_SPP 1024
#define MEAN_LO 0.85
#define MEAN_HI 1.15
#define BLOCK_TOL 0.6
#define FURNACE 0.079577
#define FURNACE_LO 0.55
#define FURNACE_HI 1.0
#define DIRECT_TOL 5e-4

/* Runs vct at the test's settings on the open fixture. */
static int run_vct(gib_gl_fixture *fx, gib_run_result *r)
{
    gib_error err;
    const gib_technique *t = gib_technique_find("vct");
    gib_params p;
    gib_params_default(t, &p);
    if (gib_param_set(t, &p, "voxel_res", "64", &err) < 0 ||
        gib_param_set(t, &p, "inject_res", "128", &err) < 0) {
        CHECK(0, "%s", err.msg);
        return -1;
    }
    gib_run_technique(&fx->gpu, t, &p, 0, W, H, 0, 1, r);
    if (!r->ok) {
        CHECK(0, "vct: %s: %s", r->status, r->err.msg);
        return -1;
    }
    long nonfinite = 0;
    for (int i = 0; i < r->output_count; i++)
        nonfinite += gib_image_count_nonfinite(&r->images[i]);
    if (nonfinite || r->output_count != 3 || r->output_components[1] != GIB_OUT_INDIRECT) {
        CHECK(0, "%ld non-finite pixels, or outputs out of order", nonfinite);
        return -1;
    }
    return 0;
}

/* Mean of channel c over the columns x0 <= x < x1. */
static double mean_of(const float *px, int c, int x0, int x1)
{
    double s = 0;
    for (int y = 0; y < H; y++)
        for (int x = x0; x < x1; x++)
            s += px[(y * W + x) * 3 + c];
    return s / ((double)H * (x1 - x0));
}

static int furnace(void)
{
    gib_gl_fixture fx;
    gib_run_result r;
    if (gib_fixture_open(&fx, "furnace") < 0 || run_vct(&fx, &r) < 0)
        return 0;
    double ind = 0, dmax = 0;
    for (int c = 0; c < 3; c++)
        ind += mean_of(r.images[1].px, c, 0, W) / 3;
    for (long i = 0; i < (long)W * H * 3; i++) {
        double e = fabs(r.images[0].px[i] - 0.5 / M_PI);
        dmax = e > dmax ? e : dmax;
    }
    int before = failures;
    snprintf(check_msg, sizeof check_msg, "furnace: indirect mean (closed form %.6f)", FURNACE);
    CHECK_AT_LEAST(check_msg, ind, FURNACE_LO * FURNACE,
                   "VCT's thin-shell loss: a one-voxel shell leaks through coarse cells; "
                   "measured 0.63 of the closed form");
    CHECK_AT_MOST(check_msg, ind, FURNACE_HI * FURNACE,
                  "one bounce's closed form; radiance without its 1/pi (x3.1) or cone weights "
                  "not summing to 1 fall outside");
    CHECK_AT_MOST("furnace: direct, largest error from 0.5 / pi", dmax, DIRECT_TOL,
                  "no occluder between the light and any wall; measured 8.9e-5");
    int good = failures == before;
    gib_run_result_free(&r);
    gib_fixture_close(&fx);
    return good;
}

int main(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "cornell") < 0)
        return 1;
    gib_run_result r;
    if (run_vct(&fx, &r) < 0)
        return 1;
    gib_image ref;
    gib_ref_stats st;
    if (gib_fixture_reference(&fx, GIB_COMP_INDIRECT, W, H, REF_SPP, &ref, &st) < 0)
        return 1;
    const gib_image *ind = &r.images[1]; /* direct, indirect, glossy */
    printf("renderer %s: vct on cornell %dx%d (reference %d spp, noise %.2f%% of its mean)\n",
           fx.info.renderer, W, H, st.spp, 100 * st.noise_rmse / st.mean);
    static const char *const channel[3] = {"red", "green", "blue"};
    for (int c = 0; c < 3; c++) {
        double block, mean;
        gib_block_error(ref.px, ind->px, W, H, BLOCK, c, &block, &mean);
        snprintf(check_msg, sizeof check_msg, "%s: mean, ratio to the reference's", channel[c]);
        CHECK_AT_LEAST(check_msg, mean, MEAN_LO, "within 15% of the reference; measured 1.03-1.06");
        CHECK_AT_MOST(check_msg, mean, MEAN_HI, "within 15% of the reference; measured 1.03-1.06");
        snprintf(check_msg, sizeof check_msg, "%s: %dx%d-block relative RMSE", channel[c], BLOCK,
                 BLOCK);
        CHECK_AT_MOST(check_msg, block, BLOCK_TOL,
                      "VCT is coarse and biased; measured 0.26-0.37 (0.81-1.03 at the paper's "
                      "level)");
    }
    /* Red/green of the left and right thirds, ours and the reference's. */
    double rl = mean_of(ind->px, 0, 0, W / 3) / mean_of(ind->px, 1, 0, W / 3),
           rr = mean_of(ind->px, 0, W - W / 3, W) / mean_of(ind->px, 1, W - W / 3, W),
           fl = mean_of(ref.px, 0, 0, W / 3) / mean_of(ref.px, 1, 0, W / 3),
           fr = mean_of(ref.px, 0, W - W / 3, W) / mean_of(ref.px, 1, W - W / 3, W);
    int bleed = rl > rr && fl > fr;
    snprintf(check_msg, sizeof check_msg,
             "colour bleeding: red/green left third %.3f, right third %.3f (reference %.3f, %.3f)",
             rl, rr, fl, fr);
    CHECK_TRUE(check_msg, bleed, "");
    failures += !(furnace());
    printf("%s: vct against the Cornell box's indirect reference and the furnace\n",
           failures ? "FAIL" : "PASS");
    gib_image_free(&ref);
    gib_run_result_free(&r);
    gib_fixture_close(&fx);
    return failures != 0;
}

/* vct (Crassin et al. 2011 as Sugihara et al. 2014 Sec. 6 ran it) on the Cornell box against the
 * reference `indirect` component (one diffuse bounce, L D D E) at 64x64 pixels, voxel_res 64 and
 * inject_res 128 (small: seconds on llvmpipe). Cone tracing is a coarse, biased estimate (60-degree
 * cones through 1/64-of-the-box voxels), so the bounds are on what the method gets right at this
 * size, each on all three channels:
 *  - the image mean within MEAN_TOL of the reference's: the injection conserves the reflected flux
 *    (vct_inject.vert) and the cone weights are the cosine-weighted shares, so the overall level
 *    is right up to the cones' coarse occlusion;
 *  - the relative RMSE of 8x8-pixel block means below BLOCK_TOL (red and green bleeding in the
 *    right places: with the anisotropic textures' front/back swapped, or no injection normal
 *    test, the blocks fail).
 * Measured values and the tolerances' reasons are printed with the result. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "harness/app/runner.h"
#include "harness/gl/context.h"
#include "reference/reference.h"
#include "tests/common/gl_fixture.h"

#define W 64
#define H 64
#define BLOCK 8
#define REF_SPP 1024
#define MEAN_TOL 0.25
#define BLOCK_TOL 0.40

static void block_error(const float *ref, const float *img, int c, double *block_rel,
                        double *mean_ratio)
{
    double se = 0, mref = 0, mimg = 0;
    int nb = 0;
    for (int by = 0; by < H; by += BLOCK)
        for (int bx = 0; bx < W; bx += BLOCK) {
            double a = 0, b = 0;
            for (int y = by; y < by + BLOCK; y++)
                for (int x = bx; x < bx + BLOCK; x++) {
                    a += ref[(y * W + x) * 3 + c];
                    b += img[(y * W + x) * 3 + c];
                }
            a /= BLOCK * BLOCK;
            b /= BLOCK * BLOCK;
            se += (b - a) * (b - a);
            mref += a;
            mimg += b;
            nb++;
        }
    mref /= nb;
    mimg /= nb;
    *block_rel = sqrt(se / nb) / mref;
    *mean_ratio = mimg / mref;
}

int main(void)
{
    gib_error err;
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "cornell") < 0)
        return 1;
    const gib_technique *t = gib_technique_find("vct");
    gib_params p;
    gib_params_default(t, &p);
    if (gib_param_set(t, &p, "voxel_res", "64", &err) < 0 ||
        gib_param_set(t, &p, "inject_res", "128", &err) < 0) {
        printf("FAIL: %s\n", err.msg);
        return 1;
    }
    gib_run_result r;
    gib_run_technique(&fx.gpu, t, &p, 0, W, H, 0, 1, &r);
    if (!r.ok) {
        printf("FAIL: vct: %s: %s\n", r.status, r.err.msg);
        return 1;
    }
    gib_ref_params rp = {.component = GIB_COMP_INDIRECT, .width = W, .height = H, .spp = REF_SPP,
                         .seed = 1, .quiet = 1};
    gib_image ref;
    gib_ref_stats st;
    if (gib_reference_render(&fx.scene, &rp, &ref, NULL, &st, &err) < 0) {
        printf("FAIL: reference: %s\n", err.msg);
        return 1;
    }
    int ok = 1;
    const gib_image *ind = &r.images[1]; /* direct, indirect, glossy */
    long nonfinite = 0;
    for (int i = 0; i < r.output_count; i++)
        nonfinite += gib_image_count_nonfinite(&r.images[i]);
    printf("renderer %s: vct on cornell %dx%d (reference %d spp, noise %.2f%% of its mean), %ld "
           "non-finite\n", fx.info.renderer, W, H, st.spp, 100 * st.noise_rmse / st.mean, nonfinite);
    if (nonfinite || r.output_components[1] != GIB_OUT_INDIRECT) {
        printf("FAIL: %ld non-finite pixels, or outputs out of order\n", nonfinite);
        ok = 0;
    }
    static const char *const channel[3] = {"red", "green", "blue"};
    for (int c = 0; c < 3; c++) {
        double block, mean;
        block_error(ref.px, ind->px, c, &block, &mean);
        int good = fabs(mean - 1) <= MEAN_TOL && block <= BLOCK_TOL;
        printf("%s %s: mean %.4f of the reference's (tolerance %.2f), %dx%d-block relative RMSE "
               "%.4f (bound %.2f)\n", good ? "PASS" : "FAIL", channel[c], mean, MEAN_TOL, BLOCK,
               BLOCK, block, BLOCK_TOL);
        ok &= good;
    }
    printf("%s: vct against the Cornell box's indirect reference\n", ok ? "PASS" : "FAIL");
    gib_image_free(&ref);
    gib_run_result_free(&r);
    gib_fixture_close(&fx);
    return ok ? 0 : 1;
}

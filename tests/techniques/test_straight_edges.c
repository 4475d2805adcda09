/* Straight edges that the reference does not have: the facets and seams a light view's faces or a
 * voxel grid's cells print on smooth indirect light, and the stripes and rings shadow cones print
 * on smooth direct light. Instantiated over the voxel techniques (lrsm,
 * vct) with rsm_gather (VPLs, no grid, no faces) as the control, on the Cornell box (its spot
 * light's hemisphere is a cube of six light-view faces) and on cornell_spot45 (one perspective
 * view), `indirect` at 128x128 against a 1024-spp reference.
 *
 * The measure (straight_edges): among neighbouring pixel pairs where the reference is smooth
 * (its 5x5 box-filtered luminance changes by under SMOOTH = 5%, and is above 5% of its mean, so
 * that the path tracer's noise and the geometry's own edges are not counted), the share that
 * jump by over JUMP = 20% in the image AND lie on an axis-aligned run of at least RUN = 6 such
 * jumps: a straight edge across the image, not the ragged border of a blotch. Measured at the
 * defaults on the Cornell box: lrsm 0.0076 (0.014 with Algorithm 1's sample, hits = 0), vct
 * 0.006 (0.013 while both levels a fetch blends were lifted by the coarser one's cells),
 * rsm_gather 0.008; on cornell_spot45: lrsm 0.011 (0.032 with hits = 0: the straight borders of
 * the dark blotches Eq. 12's window and Eq. 8's axis left on the back wall), vct 0.012 (0.020 with
 * the one lift), rsm_gather 0.004. The bound STRAIGHT_MAX = 0.018 holds every technique at its
 * defaults on both scenes and fails lrsm's literal reading (hits = 0, seams = 0: Algorithm 1's
 * sample from the face holding its centre only; 0.022 on the Cornell box's cube of faces, 0.037
 * under the spot), which is asserted too, so that the measure keeps its power to see them.
 *
 * The same measure on the voxel techniques' `direct` (shadow cones) against the path tracer's
 * exact direct light, on the Cornell box at voxel_res 64 and 256, bounded by DIRECT_MAX = 0.012:
 * measured lrsm 0.0084 / 0.0054, vct 0.0085 / 0.0057. It sees the stripes a cone toward the light
 * at grazing prints on the turned tall box when it reads its own receiver's voxels (lrsm before
 * its lift 0.024 at 256^3; vct's `clearance` 0, which shrinks the samples instead of lifting
 * them, is the control that must exceed the bound) and the rings of a cone that stops too near a
 * light hung under the ceiling (lrsm 0.016 at 64^3). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "harness/app/runner.h"
#include "reference/reference.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures; /* every check (check.h); the cases also return their own count */

#define W 128
#define H 128
#define REF_SPP 1024
#define SMOOTH 0.05
#define JUMP 0.2
#define RUN 6
#define STRAIGHT_MAX 0.018
#define DIRECT_MAX 0.012

/* The mean of the three channels, one value a pixel. */
static double *luminance(const gib_image *im)
{
    double *l = malloc(sizeof *l * W * H);
    for (long i = 0; i < (long)W * H; i++)
        l[i] = (im->px[i * im->channels] + im->px[i * im->channels + 1] +
                im->px[i * im->channels + 2]) / 3;
    return l;
}

/* A 5x5 box filter, the border clamped. */
static double *box5(const double *l)
{
    double *b = malloc(sizeof *b * W * H);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double s = 0;
            for (int dy = -2; dy <= 2; dy++)
                for (int dx = -2; dx <= 2; dx++) {
                    int u = x + dx < 0 ? 0 : x + dx >= W ? W - 1 : x + dx;
                    int v = y + dy < 0 ? 0 : y + dy >= H ? H - 1 : y + dy;
                    s += l[v * W + u];
                }
            b[y * W + x] = s / 25;
        }
    return b;
}

static double rel_change(double a, double b)
{
    double m = fmax(a, b);
    return m > 0 ? fabs(a - b) / m : 0;
}

/* The share of smooth pairs on straight runs of jumps (see the header). Pairs (p, p + step) for
 * step along one axis; runs are counted along the other axis (a jump between rows y and y + 1 at
 * consecutive x is a horizontal edge). */
static double straight_edges(const double *img, const double *ref_blur, double ref_mean)
{
    long smooth = 0, straight = 0;
    for (int axis = 0; axis < 2; axis++) {
        int outer = axis == 0 ? H - 1 : W - 1, inner = axis == 0 ? W : H;
        for (int a = 0; a < outer; a++) {
            int run = 0;
            for (int b = 0; b <= inner; b++) {
                int bad = 0;
                if (b < inner) {
                    int x = axis == 0 ? b : a, y = axis == 0 ? a : b;
                    int p = y * W + x, q = axis == 0 ? p + W : p + 1;
                    int flat = rel_change(ref_blur[p], ref_blur[q]) < SMOOTH &&
                               fmax(ref_blur[p], ref_blur[q]) > 0.05 * ref_mean;
                    smooth += flat;
                    bad = flat && rel_change(img[p], img[q]) > JUMP;
                }
                if (bad) {
                    run++;
                } else {
                    if (run >= RUN)
                        straight += run;
                    run = 0;
                }
            }
        }
    }
    return smooth ? (double)straight / (double)smooth : 0;
}

/* The measure of the technique's image of component `comp` (GIB_OUT_*) with the parameters
 * params (name, value, ..., NULL), or -1 on failure. */
static double measure(gib_gl_fixture *fx, const char *name, const char *const *params, unsigned comp,
                      const double *ref_blur, double ref_mean)
{
    const gib_technique *t = gib_technique_find(name);
    gib_params p;
    gib_error err;
    gib_params_default(t, &p);
    for (int i = 0; params && params[i]; i += 2)
        if (gib_param_set(t, &p, params[i], params[i + 1], &err) < 0) {
            CHECK(0, "%s", err.msg);
            return -1;
        }
    gib_run_result r;
    gib_run_technique(&fx->gpu, t, &p, 0, W, H, 0, 1, &r);
    if (!r.ok) {
        CHECK(0, "%s: %s: %s", name, r.status, r.err.msg);
        return -1;
    }
    double m = -1;
    for (int o = 0; o < r.output_count; o++)
        if (r.output_components[o] == comp && !gib_image_count_nonfinite(&r.images[o])) {
            double *l = luminance(&r.images[o]);
            m = straight_edges(l, ref_blur, ref_mean);
            free(l);
        }
    gib_run_result_free(&r);
    if (m < 0)
        CHECK(0, "%s gave no finite image of the component asked", name);
    return m;
}

struct edge_case {
    const char *technique;
    const char *params[5];   /* name, value, ..., NULL */
    int bounded;   /* 1: at most the bound; -1: above it (the artefact must be seen); 0: printed */
};

static const struct edge_case indirect_cases[] = {{"lrsm", {NULL}, 1},
                                                  {"vct", {NULL}, 1},
                                                  {"rsm_gather", {NULL}, 1},
                                                  {"lrsm", {"hits", "0", "seams", "0", NULL}, -1}};

static const struct edge_case direct_cases[] = {
    {"lrsm", {"voxel_res", "64", NULL}, 1},
    {"lrsm", {"voxel_res", "256", NULL}, 1},
    {"vct", {"voxel_res", "64", NULL}, 1},
    {"vct", {"voxel_res", "256", NULL}, 1},
    {"vct", {"voxel_res", "256", "clearance", "0", NULL}, -1}};

/* The cases' measures on `scene`'s component `comp` against its reference (REF_SPP), each
 * held to `bound` where `assert_bounds`; returns the failures. */
static int run_scene(const char *scene, unsigned comp, const struct edge_case *cases, size_t count,
                     double bound, int assert_bounds)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, scene) < 0)
        return 1;
    gib_image ref;
    int is_direct = comp == GIB_OUT_DIRECT;
    if (gib_fixture_reference(&fx, is_direct ? GIB_COMP_DIRECT : GIB_COMP_INDIRECT, W, H, REF_SPP,
                              &ref, NULL) < 0)
        return 1;
    double *rl = luminance(&ref), *rb = box5(rl), mean = 0;
    for (long i = 0; i < (long)W * H; i++)
        mean += rl[i] / ((double)W * H);
    int failures = 0;
    for (size_t k = 0; k < count; k++) {
        const struct edge_case *c = &cases[k];
        if (!assert_bounds && c->bounded < 0)
            continue;
        double m = measure(&fx, c->technique, c->params, comp, rb, mean);
        int want = assert_bounds ? c->bounded : 0;
        int ok = m >= 0 && (want == 0 || (want > 0 ? m <= bound : m > bound));
        failures += !ok;
        printf("%s %s %s %s", ok ? (want ? "PASS" : "INFO") : "FAIL", scene,
               is_direct ? "direct" : "indirect", c->technique);
        for (int i = 0; c->params[i]; i += 2)
            printf(" %s=%s", c->params[i], c->params[i + 1]);
        printf(": straight edges %.4f of the smooth pairs (%s %.3f)\n", m,
               want > 0 ? "at most" : want < 0 ? "must exceed" : "printed, not bounded; cornell's bound",
               bound);
    }
    free(rl);
    free(rb);
    gib_image_free(&ref);
    gib_fixture_close(&fx);
    return failures;
}

int main(void)
{
    size_t ni = sizeof indirect_cases / sizeof indirect_cases[0];
    size_t nd = sizeof direct_cases / sizeof direct_cases[0];
    failures += run_scene("cornell", GIB_OUT_INDIRECT, indirect_cases, ni, STRAIGHT_MAX, 1) +
                   run_scene("cornell_spot45", GIB_OUT_INDIRECT, indirect_cases, ni, STRAIGHT_MAX, 1) +
                   run_scene("cornell", GIB_OUT_DIRECT, direct_cases, nd, DIRECT_MAX, 1);
    printf("%s: straight edges on smooth light\n", failures ? "FAIL" : "PASS");
    return failures ? 1 : 0;
}

/* What a vct cone reads over open ground and under a roof (techniques/vct/vct_trace.glsl through
 * vct_probe.comp), on synthetic volumes written straight into the base voxels (grid of side 1 at
 * the origin): solid ground for y < 1/4, its top facing +y; "roof" adds a slab 2 voxels thick
 * 12 voxels above the ground. Cones start at the ground's top at the grid's centre in x and z,
 * with the diffuse set's directions (one along +y, tilted ones 60 degrees from it) and aperture
 * (60 degrees), over the whole grid.
 *  - Open ground, at the default sample level, voxel_res 64 and 128: nothing above the ground, so
 *    a cone's occlusion is what it reads of the ground it leaves: below 0.1 for the central cone
 *    and 0.22 for the tilted ones. Their lower edge grazes the ground, and a sample of diameter
 *    d = 2 t tan(30) is wider than the cone's inscribed sphere (radius t sin 30): its centre is
 *    0.87 of its radius above the ground, so ~1.3% of its volume lies below it, 2.6% of a step's
 *    opacity, ~15% over the ~6 samples to the grid's edge; the trilinear footprint adds a little
 *    (measured 0.197-0.201). 0.22 is that floor with 10% of room; the 0.2 first asked for sits on
 *    it. The paper's literal level (sample_level 0: cells as wide as the sample, a trilinear
 *    footprint twice that) is printed beside: it reads 0.6-0.9 there, which is why the default
 *    departs from it.
 *  - Roof: the central cone is blocked (occlusion above 0.85): the finer level must not make a
 *    two-voxel slab transparent. The slab, 10 voxels from the cone's start, is read at level ~2.5
 *    (cells ~6 voxels wide, the slab a third of one): measured 0.90. Two levels finer than the
 *    paper's, the samples' footprints leave gaps along the cone and read 0.78, which fails. */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tests/vct/vct_probe.h"
#include "tests/common/check.h"

#define CONES 3 /* central, tilted toward +x, tilted toward -z */
#define CENTRAL_MAX 0.1
#define TILTED_MAX 0.22
#define ROOF_MIN 0.85

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

/* Ground below y = res / 4 (unlit: radiance 0, alpha 1, normal +y); with `roof`, a slab 2 voxels
 * thick 12 voxels above it. */
static void fill(vct_volume *v, int res, int roof)
{
    size_t n = (size_t)res * res * res * 4;
    float *rad = calloc(n, sizeof *rad), *nrm = calloc(n, sizeof *nrm);
    int ground = res / 4;
    for (int z = 0; z < res; z++)
        for (int y = 0; y < res; y++)
            for (int x = 0; x < res; x++) {
                if (!(y < ground || (roof && y >= ground + 12 && y < ground + 14)))
                    continue;
                size_t i = (((size_t)z * res + y) * res + x) * 4;
                rad[i + 3] = 1;
                nrm[i + 1] = y < ground ? 1.0f : -1.0f;
                nrm[i + 3] = 1;
            }
    vct_probe_upload(v, res, rad, nrm);
}

/* The occlusion of the CONES cones from the ground's top at the centre, at `sample_level`. */
static int trace(unsigned prog, const vct_volume *v, int sample_level, float occlusion[CONES])
{
    const float tilt = (float)(60.0 * M_PI / 180.0), tan_half = (float)tan(30.0 * M_PI / 180.0);
    const float dirs[CONES][3] = {{0, 1, 0},
                                  {sinf(tilt), cosf(tilt), 0},
                                  {0, cosf(tilt), -sinf(tilt)}};
    float in[CONES * 3][4], out[CONES][4];
    for (int i = 0; i < CONES; i++) {
        const float p[4] = {0.5f, 0.25f, 0.5f, tan_half}, nrm[4] = {0, 1, 0, 1.0f};
        for (int c = 0; c < 4; c++) {
            in[3 * i][c] = p[c];
            in[3 * i + 1][c] = nrm[c];
            in[3 * i + 2][c] = c < 3 ? dirs[i][c] : 0;
        }
    }
    const vct_cone_settings cones = {1.0f, 1.5f, sample_level, 0, 0};
    if (vct_probe_run(prog, v, &cones, (const float(*)[4])in, CONES, out) < 0)
        return -1;
    for (int i = 0; i < CONES; i++)
        occlusion[i] = out[i][3];
    return 0;
}

static void open_ground(unsigned prog, int res, gib_ledger *ledger)
{
    const float origin[3] = {0, 0, 0};
    vct_volume v;
    gib_error err;
    if (vct_volume_create(&v, origin, 1.0f, res, false, ledger, &err) < 0) {
        CHECK(0, "%s", err.msg);
        return;
    }
    fill(&v, res, 0);
    float ours[CONES], paper[CONES];
    if (trace(prog, &v, 1, ours) < 0 || trace(prog, &v, 0, paper) < 0) {
        CHECK(0, "the vct probe did not run");
    } else {
        for (int i = 0; i < CONES; i++) {
            double bound = i == 0 ? CENTRAL_MAX : TILTED_MAX;
            int good = ours[i] < bound;
            snprintf(check_msg, sizeof check_msg,
                     "open ground, voxel_res %d, %s cone %d: occlusion %.3f (bound %.2f; the "
                     "paper's level reads %.3f)",
                     res, i ? "tilted" : "central", i, ours[i], bound, paper[i]);
            CHECK_TRUE(check_msg, good, "");
        }
    }
    fill(&v, res, 1);
    if (trace(prog, &v, 1, ours) == 0 && trace(prog, &v, 0, paper) == 0) {
        int good = ours[0] > ROOF_MIN;
        snprintf(check_msg, sizeof check_msg,
                 "roof, voxel_res %d: the central cone's occlusion %.3f (bound > %.2f; the paper's "
                 "level reads %.3f)",
                 res, ours[0], ROOF_MIN, paper[0]);
        CHECK_TRUE(check_msg, good, "");
    }
    vct_volume_destroy(&v, ledger);
}

int main(void)
{
    gib_gl_fixture fx;
    unsigned prog;
    if (vct_probe_open(&fx, &prog) < 0)
        return 1;
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    open_ground(prog, 64, &ledger);
    open_ground(prog, 128, &ledger);
    glDeleteProgram(prog);
    gib_fixture_close(&fx);
    printf("%s: vct cones over open ground and under a roof\n", failures ? "FAIL" : "PASS");
    return failures ? 1 : 0;
}

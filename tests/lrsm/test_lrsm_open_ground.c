/* What an lrsm diffuse cone reads of the occlusion voxels over open ground and under a roof
 * (lrsm_march.glsl through lrsm_cone_probe.comp, with lrsm's defaults: opacity as a density read a
 * level finer, start offset 1.5 voxels, step 1, 60-degree cones over the whole grid). The scene:
 * an 8 x 8 m floor at y = 0 and a 2 x 0.2 x 2 m roof slab 0.5 m above its corner (x, z > 1.5).
 *  - Open ground, from (-2, 0, -2), the central cone (along +y) and three cones tilted 60 degrees
 *    away from the roof: nothing lies above the floor there, so a cone's occlusion is what it reads
 *    of the floor it leaves, at most CENTRAL_MAX and TILTED_MAX at voxel_res 64, 128 and 256
 *    (measured 0 and 0 / 0.023 / 0.027). The tilted cones' lower edge grazes the floor: without
 *    the bound that keeps a sample in front of the receiver's plane their samples read it from
 *    ~20 voxels on, more of it the finer the voxels (measured 0.20 / 0.42 / 0.59: fails).
 *  - Roof: the central cone from under the slab's centre is blocked, occlusion above ROOF_MIN
 *    (measured 0.98): the bound must not let a cone through what is above it. */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness/gl/bindings.h"
#include "techniques/common/shader.h"
#include "techniques/common/voxels.h"
#include "techniques/lrsm/lrsm_slots.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

#define CONES 5 /* central, three tilted, the roof's central */
#define CENTRAL_MAX 0.1
#define TILTED_MAX 0.2
#define ROOF_MIN 0.8

static const char *scene_text =
    "[scene]\ndescription = lrsm open ground: a floor and a roof slab over its corner\n"
    "[mesh.floor]\nprocedural = quad\nsize = 8 8\n"
    "[mesh.roof]\nprocedural = box\nsize = 2 0.2 2\ntranslate = 2.5 0.6 2.5\n"
    "[camera.c]\neye = 0 3 6\ntarget = 0 0 0\nup = 0 1 0\nfov = 60\n"
    "[light.l]\ntype = point\nposition = 0 3 0\nintensity = 1 1 1\n";

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

/* The occlusion of the CONES cones at voxel_res `res`; 0 on success. */
static int trace(gib_gl_fixture *fx, unsigned prog, int res, float occlusion[CONES])
{
    const float tilt = (float)(60.0 * M_PI / 180.0), aperture = (float)(60.0 * M_PI / 180.0);
    const float s = sinf(tilt), c = cosf(tilt), h = s / sqrtf(2.0f);
    const float dirs[CONES][3] = {{0, 1, 0}, {-s, c, 0}, {0, c, -s}, {-h, c, -h}, {0, 1, 0}};
    float in[CONES * 3][4];
    for (int i = 0; i < CONES; i++) {
        const float x[3] = {i < 4 ? -2.0f : 2.5f, 0, i < 4 ? -2.0f : 2.5f};
        for (int k = 0; k < 3; k++) {
            in[3 * i][k] = x[k];
            in[3 * i + 1][k] = k == 1 ? 1.0f : 0.0f;
            in[3 * i + 2][k] = dirs[i][k];
        }
        in[3 * i][3] = aperture;
        in[3 * i + 1][3] = in[3 * i + 2][3] = 0;
    }
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    gib_voxels v;
    gib_error err;
    if (gib_voxels_create(&v, &fx->gpu, res, "voxels", &ledger, &err) < 0) {
        CHECK(0, "%s", err.msg);
        return -1;
    }
    gib_voxels_build(&v, &fx->gpu, NULL, "voxelization");
    GLuint buf[2];
    glCreateBuffers(2, buf);
    glNamedBufferStorage(buf[0], sizeof in, in, 0);
    glNamedBufferStorage(buf[1], sizeof(float) * CONES, NULL, 0);
    glUseProgram(prog);
    gib_voxels_bind(&v);
    glUniform1i(GIB_LOC_VOXEL_DENSITY, 1);
    glUniform1f(LRSM_CONE_LOC_START_OFFSET, 1.5f);
    glUniform1f(LRSM_CONE_LOC_STEP_FACTOR, 1.0f);
    glUniform1f(LRSM_CONE_LOC_MAX_DISTANCE, 1.0f);
    glUniform1i(LRSM_CONE_PROBE_LOC_COUNT, CONES);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LRSM_CONE_PROBE_SSBO_IN, buf[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LRSM_CONE_PROBE_SSBO_OUT, buf[1]);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buf[1], 0, sizeof(float) * CONES, occlusion);
    glDeleteBuffers(2, buf);
    gib_voxels_destroy(&v, &ledger);
    return gib_gl_check("lrsm cone probe", &err);
}

/* CHECK_TRUE with the occlusion and its bound, at the caller's file:line. */
#define CHECK_OCCLUSION(ok, what, res, got, bound)                                                 \
    do {                                                                                           \
        snprintf(check_msg, sizeof check_msg, "%s, voxel_res %d: occlusion %.3f (bound %s %.2f)",  \
                 what, res, (double)(got), strstr(what, "roof") ? ">" : "<", (double)(bound));    \
        CHECK_TRUE(check_msg, ok, "");                                                            \
    } while (0)

int main(void)
{
    char dir[] = "/tmp/gib_lrsm_open_ground_XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "cannot make a temporary folder");
        return 1;
    }
    gib_gl_fixture fx;
    if (gib_fixture_open_text(&fx, dir, "open_ground", scene_text) < 0)
        return 1;
    gib_error err;
    const char *files[] = {"lrsm/lrsm_cone_probe.comp"};
    unsigned prog = gib_program(files, 1, NULL, &err);
    if (!prog) {
        CHECK(0, "%s", err.msg);
        return 1;
    }
    const int resolutions[] = {64, 128, 256};
    for (int r = 0; r < 3; r++) {
        float occ[CONES];
        if (trace(&fx, prog, resolutions[r], occ) < 0) {
            failures++;
            continue;
        }
        CHECK_OCCLUSION(occ[0] < CENTRAL_MAX, "open ground, central cone", resolutions[r], occ[0],
                        CENTRAL_MAX);
        for (int i = 1; i < 4; i++)
            CHECK_OCCLUSION(occ[i] < TILTED_MAX, "open ground, tilted cone", resolutions[r], occ[i],
                            TILTED_MAX);
        CHECK_OCCLUSION(occ[4] > ROOF_MIN, "under the roof, central cone", resolutions[r], occ[4], ROOF_MIN);
    }
    glDeleteProgram(prog);
    gib_fixture_close(&fx);
    printf("%s: lrsm cones over open ground and under a roof\n", failures ? "FAIL" : "PASS");
    return failures ? 1 : 0;
}

/* vct's anisotropic mips (techniques/vct/vct_aniso.comp; Crassin et al. 2011, Sec. 4) on a
 * synthetic 64^3 volume written straight into the base voxels (radiance + occlusion, normal):
 *  A. two one-voxel walls side by side: x = 0 red facing -x, x = 1 green facing +x, over all y, z.
 *     Level 0 (x cell 0) seen travelling +x: the red wall in front, its lit side facing the cone:
 *     (red, alpha 1); travelling -x: green in front: (green, 1). Swapping front and back, or
 *     showing a wall's radiance from behind, gives the other colour.
 *  B. one red wall at x = 5 facing -x, only for y < 32. Level 0 (x cell 2, y cell 0): travelling
 *     +x it is behind an empty voxel: (red, 1); travelling +y the pairs along y at x = 4 are empty
 *     and at x = 5 red in front of red, edge-on (shown): (red / 2, 1 / 2). Level 1 (x cell 1,
 *     y cell 0) travelling +y: per line, level-0 (red/2, 1/2) in front of (red/2, 1/2) composites
 *     to (3/4 red, 3/4) (Eq. 1); with the empty lines at x cell 3, (3/8 red, 3/8): a plain average
 *     would give 1/2 and 1/4 for the alpha. Values are RGBA16F: tolerance 2e-3 (half-float
 *     rounding of values <= 1 is below 5e-4). */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "techniques/vct/vct.h"
#include "tests/common/check.h"
#include "tests/common/gl_fixture.h"

#define RES 64
#define TOL 2e-3

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

/* got against want channel by channel, to TOL; one PASS/FAIL line with both (check.h), at the
 * caller's line. */
#define check(what, got, want) check_at(__FILE__, __LINE__, what, got, want)
static int check_at(const char *file, int line, const char *what, const float *got,
                    const float want[4])
{
    int good = 1;
    for (int c = 0; c < 4; c++)
        good &= fabsf(got[c] - want[c]) <= TOL;
    char detail[160];
    snprintf(detail, sizeof detail, "(%.4f %.4f %.4f %.4f), expected (%.4f %.4f %.4f %.4f) tol %g "
             "(half-float rounding)", got[0], got[1], got[2], got[3], want[0], want[1], want[2],
             want[3], TOL);
    failures += gib_check_report(file, line, good, what, detail);
    return good;
}

static float *level(const vct_volume *v, int d, int lvl)
{
    int s = (RES / 2) >> lvl;
    size_t n = (size_t)s * s * s * 4;
    float *px = malloc(n * sizeof *px);
    glGetTextureImage(v->aniso[d], lvl, GL_RGBA, GL_FLOAT, (GLsizei)(n * sizeof *px), px);
    return px;
}

static const float *at(const float *px, int lvl, int x, int y, int z)
{
    int s = (RES / 2) >> lvl;
    return px + (((size_t)z * s + y) * s + x) * 4;
}

int main(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "cornell") < 0)
        return 1;
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    gib_error err;
    vct_volume v;
    const float origin[3] = {0, 0, 0};
    if (vct_volume_create(&v, origin, 1.0f, RES, false, &ledger, &err) < 0) {
        CHECK(0, "%s", err.msg);
        return 1;
    }
    size_t n = (size_t)RES * RES * RES * 4;
    float *rad = calloc(n, sizeof *rad), *nrm = calloc(n, sizeof *nrm);
    const float red[3] = {1, 0, 0}, green[3] = {0, 1, 0};
    for (int z = 0; z < RES; z++)
        for (int y = 0; y < RES; y++)
            for (int x = 0; x < RES; x++) {
                const float *c = NULL;
                float nx = 0;
                if (x == 0)
                    c = red, nx = -1;
                else if (x == 1)
                    c = green, nx = 1;
                else if (x == 5 && y < 32)
                    c = red, nx = -1;
                if (!c)
                    continue;
                size_t i = (((size_t)z * RES + y) * RES + x) * 4;
                rad[i] = c[0], rad[i + 1] = c[1], rad[i + 2] = c[2], rad[i + 3] = 1;
                nrm[i] = nx, nrm[i + 3] = 1;
            }
    glTextureSubImage3D(v.radiance, 0, 0, 0, 0, RES, RES, RES, GL_RGBA, GL_FLOAT, rad);
    glTextureSubImage3D(v.normal, 0, 0, 0, 0, RES, RES, RES, GL_RGBA, GL_FLOAT, nrm);
    vct_volume_mips(&v);
    glFinish();

    int ok = 1;
    float *px0 = level(&v, VCT_PX, 0), *nx0 = level(&v, VCT_NX, 0), *py0 = level(&v, VCT_PY, 0),
          *py1 = level(&v, VCT_PY, 1);
    const float w_red[4] = {1, 0, 0, 1}, w_green[4] = {0, 1, 0, 1}, half[4] = {0.5f, 0, 0, 0.5f},
                l1[4] = {0.375f, 0, 0, 0.375f};
    ok &= check("A: level 0 travelling +x sees the red wall's front", at(px0, 0, 0, 7, 7), w_red);
    ok &= check("A: level 0 travelling -x sees the green wall's front", at(nx0, 0, 0, 7, 7), w_green);
    ok &= check("B: level 0 travelling +x, wall behind an empty voxel", at(px0, 0, 2, 3, 3), w_red);
    ok &= check("B: level 0 travelling +y, wall edge-on in half the lines", at(py0, 0, 2, 3, 3), half);
    ok &= check("B: level 1 travelling +y, composited front to back", at(py1, 1, 1, 3, 3), l1);
    snprintf(check_msg, sizeof check_msg,
             "vct anisotropic mips");
    CHECK_TRUE(check_msg, ok, "");
    free(px0), free(nx0), free(py0), free(py1), free(rad), free(nrm);
    vct_volume_destroy(&v, &ledger);
    gib_fixture_close(&fx);
    return failures != 0;
}

/* What a vct cone reads of a lit floor that fills its whole cap (techniques/vct/vct_trace.glsl
 * through vct_probe.comp), on synthetic volumes written straight into the base voxels (grid of side
 * 1 at the origin, 256^3 as the paper's Sponza rows): a lit layer one voxel thick at y = 64
 * (radiance 1, normal +y), alone ("thin": a floor that is one polygon) or on an unlit solid
 * ("solid": a floor, wall or column thicker than a voxel). A 60-degree cone starts H voxels above
 * it, 8 voxels in from the -x face, its axis phi below the horizontal toward +x; its apex sits on a
 * receiver whose normal is the axis ("facing", nothing else in the grid) or horizontal, +x
 * ("wall": an unlit wall behind the apex, a banner or a wall whose tilted cones look down at the
 * floor). Every geometry run keeps the whole cap on the floor inside
 * the grid, so the truth is radiance 1 and occlusion 1.
 *
 * What a cone reads there is below the truth, and the rows are the energy audit's control for
 * vct's cones over Sponza's lit floor (with --csv PATH they are written there; make
 * vct-floor-control). The sphere samples step over the layer: a thin layer is met by the trilinear
 * footprints of a sample or two that hold it as a fraction of their cells, and the cone passes
 * through the rest (occlusion = radiance < 1); on a solid floor the footprints that reach under
 * the lit layer read the unlit voxels beneath it (occlusion 1, radiance below it). The paper's
 * level (sample_level 0, printed beside) reads less on a floor the cone faces.
 *
 * Asserted, what must hold whatever the sampling: the mips and Eq. 1 keep a lit surface's light
 * per unit of opacity (thin floor: radiance / occlusion within 0.02 of 1: half floats and the step
 * correction's rounding), a solid floor stops every cone (occlusion >= 0.97: 0.995 ends the march,
 * and the last step's opacity may stop short of it), and no cone reads more than the floor's
 * light (radiance <= 1.02). */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/vct/vct_probe.h"
#include "tests/common/check.h"

static int failures; /* check.h's CHECK counts here; the exit status is decided as before (by the cases' own counts) */
static char check_msg[512]; /* what a CHECK_TRUE line says */

#define RES 256
#define FLOOR_Y 64
#define START_X 8
#define MAX_CONES 128
#define LIGHT_PER_OPACITY_TOL 0.02
#define SOLID_OCCLUSION_MIN 0.97

static const int heights[] = {4, 8, 16, 32, 64};
static const int tilts[] = {45, 60, 75, 90};

static const int apertures[] = {60, 10}; /* vct's diffuse and specular cones, degrees */

typedef struct cone_case {
    int aperture, height, tilt, wall;
} cone_case;

/* The lit layer at FLOOR_Y, with `solid` an unlit solid under it, with `wall` the receivers' wall:
 * unlit voxels at x <= START_X - 2 (the one holding the apex's receiver point, 1.5 voxels behind
 * the apex, and all behind it) facing +x, above the floor. */
static void fill(vct_volume *v, int solid, int wall)
{
    size_t n = (size_t)RES * RES * RES * 4;
    float *rad = calloc(n, sizeof *rad), *nrm = calloc(n, sizeof *nrm);
    for (int z = 0; z < RES; z++)
        for (int y = 0; y < RES; y++)
            for (int x = 0; x < RES; x++) {
                int floor = y == FLOOR_Y || (solid && y < FLOOR_Y);
                if (!floor && !(wall && y > FLOOR_Y && x <= START_X - 2))
                    continue;
                size_t i = (((size_t)z * RES + y) * RES + x) * 4;
                float lit = y == FLOOR_Y ? 1.0f : 0.0f;
                rad[i] = rad[i + 1] = rad[i + 2] = lit;
                rad[i + 3] = 1;
                nrm[i] = floor ? 0.0f : 1.0f;
                nrm[i + 1] = floor ? 1.0f : 0.0f;
                nrm[i + 3] = 1;
            }
    vct_probe_upload(v, RES, rad, nrm);
}

/* Whether the cap's upper edge (phi - aperture / 2 below the horizontal) meets the floor inside
 * the grid along +x from a start `height` voxels above it. */
static int cap_on_floor(int aperture, int height, int tilt)
{
    double edge = tilt - aperture / 2.0;
    if (edge <= 0)
        return 0;
    double reach = height / tan(edge * M_PI / 180.0);
    return START_X + reach < RES - 8;
}

static int cases(cone_case *c)
{
    int n = 0;
    for (size_t a = 0; a < sizeof apertures / sizeof *apertures; a++)
        for (int w = 0; w < 2; w++)
            for (size_t t = 0; t < sizeof tilts / sizeof *tilts; t++)
                for (size_t h = 0; h < sizeof heights / sizeof *heights; h++)
                    if (cap_on_floor(apertures[a], heights[h], tilts[t]) && !(w && tilts[t] == 90))
                        c[n++] = (cone_case){apertures[a], heights[h], tilts[t], w};
    return n;
}

/* vct_cone's (radiance, occlusion) for each case at `sample_level`. */
static int trace(unsigned prog, const vct_volume *v, int sample_level, const cone_case *c, int n,
                 float out[][4])
{
    const float vs = 1.0f / RES;
    float in[MAX_CONES * 3][4];
    for (int i = 0; i < n; i++) {
        float phi = (float)(c[i].tilt * M_PI / 180.0), D[3] = {cosf(phi), -sinf(phi), 0};
        /* The apex: H voxels above the floor's top after start_offset's 1.5 voxels along n. */
        float nrm[3] = {c[i].wall ? 1.0f : D[0], c[i].wall ? 0.0f : D[1], 0};
        float p[3] = {START_X * vs, (FLOOR_Y + 1 + c[i].height) * vs, 0.5f};
        for (int k = 0; k < 3; k++)
            p[k] -= 1.5f * vs * nrm[k];
        float tan_half = (float)tan(c[i].aperture * M_PI / 360.0);
        memcpy(in[3 * i], (float[4]){p[0], p[1], p[2], tan_half}, sizeof in[0]);
        memcpy(in[3 * i + 1], (float[4]){nrm[0], nrm[1], nrm[2], 1.0f}, sizeof in[0]);
        memcpy(in[3 * i + 2], (float[4]){D[0], D[1], D[2], 0}, sizeof in[0]);
    }
    const vct_cone_settings cones = {1.0f, 1.5f, sample_level, 1, 0};
    return vct_probe_run(prog, v, &cones, (const float(*)[4])in, n, out);
}

/* Fills the volume (solid floor or thin, with the receivers' wall or not), traces the cases of
 * that receiver at the default and the paper's sample level, prints and checks them; the failures. */
static int run_volume(unsigned prog, vct_volume *v, int solid, int wall, const cone_case *all,
                      int n_all, FILE *csv)
{
    cone_case c[MAX_CONES];
    int n = 0, failures = 0;
    for (int i = 0; i < n_all; i++)
        if (all[i].wall == wall)
            c[n++] = all[i];
    fill(v, solid, wall);
    float ours[MAX_CONES][4], paper[MAX_CONES][4];
    if (trace(prog, v, 1, c, n, ours) < 0 || trace(prog, v, 0, c, n, paper) < 0) {
        CHECK(0, "the vct probe did not run");
        return 1;
    }
    const char *floor = solid ? "solid" : "thin", *receiver = wall ? "wall" : "facing";
    for (int i = 0; i < n; i++) {
        float rad = ours[i][0], occ = ours[i][3];
        int n_msg = snprintf(check_msg, sizeof check_msg,
                             "%2d-degree cone, %s floor, %s receiver, %d deg down, %2d voxels up "
                             "(radiance %.3f, occlusion %.3f; the paper's level %.3f, %.3f): ",
                             c[i].aperture, floor, receiver, c[i].tilt, c[i].height, rad, occ,
                             paper[i][0], paper[i][3]);
        char *tail = check_msg + n_msg;
        size_t room = sizeof check_msg - (size_t)n_msg;
        snprintf(tail, room, "radiance");
        CHECK_AT_MOST(check_msg, rad, 1.0f + LIGHT_PER_OPACITY_TOL,
                      "no cone reads more than the floor's light 1, to 0.02: half floats and the "
                      "step correction's rounding");
        if (solid) {
            snprintf(tail, room, "occlusion");
            CHECK_AT_LEAST(check_msg, occ, SOLID_OCCLUSION_MIN,
                           "a solid floor stops every cone: 0.995 ends the march, and the last "
                           "step's opacity may stop short of it");
        } else {
            snprintf(tail, room, "|radiance - occlusion|");
            CHECK_AT_MOST(check_msg, fabsf(rad - occ), LIGHT_PER_OPACITY_TOL * occ,
                          "light per unit of opacity kept, within 0.02 of 1: half floats and the "
                          "step correction's rounding");
        }
        if (csv)
            fprintf(csv, "%d,%s,%s,%d,%d,%.4f,%.4f,%.4f,%.4f\n", c[i].aperture, floor, receiver,
                    c[i].tilt, c[i].height, rad, occ, paper[i][0], paper[i][3]);
    }
    return failures;
}

int main(int argc, char **argv)
{
    const char *csv_path = argc == 3 && strcmp(argv[1], "--csv") == 0 ? argv[2] : NULL;
    gib_gl_fixture fx;
    unsigned prog;
    if (vct_probe_open(&fx, &prog) < 0)
        return 1;
    gib_error err;
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    vct_volume v;
    const float origin[3] = {0, 0, 0};
    if (vct_volume_create(&v, origin, 1.0f, RES, false, &ledger, &err) < 0) {
        CHECK(0, "%s", err.msg);
        return 1;
    }
    FILE *csv = csv_path ? fopen(csv_path, "w") : NULL;
    if (csv_path && !csv) {
        CHECK(0, "cannot write %s", csv_path);
        return 1;
    }
    if (csv)
        fprintf(csv, "aperture_deg,floor,receiver,tilt_deg,height_voxels,radiance,occlusion,"
                     "radiance_paper_level,occlusion_paper_level\n");
    cone_case c[MAX_CONES];
    int n = cases(c), failures = 0;
    for (int solid = 0; solid < 2; solid++)
        for (int wall = 0; wall < 2; wall++)
            failures += run_volume(prog, &v, solid, wall, c, n, csv);
    if (csv)
        fclose(csv);
    vct_volume_destroy(&v, &ledger);
    glDeleteProgram(prog);
    gib_fixture_close(&fx);
    printf("%s: vct cones over a lit floor that fills their cap\n", failures ? "FAIL" : "PASS");
    return failures ? 1 : 0;
}

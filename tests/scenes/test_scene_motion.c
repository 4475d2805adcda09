/* Scenes that move (scenes/FORMAT.md, "Motion"): the motion keys' errors name file:line, and the
 * poses are what the format says. Poses are checked against the formulas computed here
 * independently (rotation matrices, wave sums in double); tolerances are float rounding of
 * coordinates of order 1 (1e-5), except where stated. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes/scene.h"
#include "tests/scenes/scene_test.h"

/* A scene file that must fail at `line` with `phrase` in its message. */
static void expect_error(const char *what, const char *text, int line, const char *phrase)
{
    scene_expect_load(what, text, -1, line, phrase, NULL);
}

#define HEAD "[scene]\n[camera.c]\neye = 0 1 5\ntarget = 0 0 0\n[mesh.m]\n" /* mesh at line 5 */

static void errors(void)
{
    expect_error("keys not increasing", HEAD "procedural = box\nkeys = 0 2 1\n", 7,
                 "must increase");
    expect_error("key_rotate count",
                 HEAD "procedural = box\nkeys = 0 1\nkey_rotate = 0 0 0, 0 90 0, 0 0 1\n", 8,
                 "3 per key");
    expect_error("key_translate not by 3",
                 HEAD "procedural = box\nkeys = 0 1\nkey_translate = 0 0 0 1\n",
                 8, "3 numbers per key");
    expect_error("values without keys", HEAD "procedural = box\nkey_rotate = 0 0 0\n", 7,
                 "keyframes need 'keys");
    expect_error("keys without values", HEAD "procedural = box\nkeys = 0 1\n", 7,
                 "needs 'key_rotate' and/or 'key_translate'");
    expect_error("loop with one key",
                 HEAD "procedural = box\nkeys = 0\nkey_translate = 1 0 0\nloop = 1\n", 9,
                 "at least 2 keys");
    expect_error("loop not a bool", HEAD "procedural = box\nloop = maybe\n", 7, "expects 0 or 1");
    expect_error("waves on a box", HEAD "procedural = box\nwaves = 0.1 1 0 1\n", 7,
                 "only to 'procedural = water'");
    expect_error("water without waves", HEAD "procedural = water\n", 6, "needs 'waves");
    expect_error("waves not by 4", HEAD "procedural = water\nwaves = 0.1 1 0 1 2\n", 7,
                 "4 numbers per wave");
    expect_error("zero wavelength", HEAD "procedural = water\nwaves = 0.1 1 0 1, 0.1 0 0 1\n", 7,
                 "wave 2");
    expect_error("keys on water",
                 HEAD "procedural = water\nwaves = 0.1 1 0 1\nkeys = 0 1\n"
                      "key_translate = 0 0 0, 1 0 0\n",
                 8, "moves by its waves");
    expect_error("water too fine", HEAD "procedural = water\nwaves = 0.1 1 0 1\nsegments = 5000\n",
                 8, "'segments' must be from 1 to 2896");
    expect_error("too many keys",
                 HEAD "procedural = box\nkeys = 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16\n", 7,
                 "expects 1 to 16 numbers");
}

static void rot_y(double deg, const double v[3], double out[3])
{
    const double a = deg * M_PI / 180.0, c = cos(a), s = sin(a);
    out[0] = c * v[0] + s * v[2];
    out[1] = v[1];
    out[2] = -s * v[0] + c * v[2];
}

/* A box turning 0 -> 180 degrees about y (through a pivot) while moving 1 m along x over 2 s. */
static void rigid(void)
{
    char path[512];
    write_file("rigid.scene",
               HEAD "procedural = box\nsize = 1 1 1\ntranslate = 3 0 0\n"
                    "keys = 0 2\nkey_rotate = 0 0 0, 0 180 0\nkey_translate = 0 0 0, 1 0 0\n"
                    "pivot = 3 0.5 0\n"
                    "[mesh.floor]\nprocedural = quad\nsize = 10 10\n",
               path, sizeof path);
    gib_scene s;
    gib_error err;
    if (gib_scene_load(path, &s, &err) < 0) {
        CHECK(0, "rigid scene: %s", err.msg);
        return;
    }
    CHECK(s.motion_count == 1 && s.motions[0].kind == GIB_MOTION_RIGID &&
              s.motions[0].vertex_count == 36 && s.motions[0].first_vertex == 0,
          "one rigid motion over the box's 36 vertices (count %u)", s.motion_count);
    const gib_motion *m = &s.motions[0];
    float *pos = malloc(sizeof(float) * 3 * m->vertex_count * 2), *nrm = pos + 3 * m->vertex_count;
    const double times[] = {0.0, 0.5, 1.0, 2.0, 7.0, -3.0};
    const double deg_at[] = {0.0, 45.0, 90.0, 180.0, 180.0, 0.0}; /* no loop: ends hold */
    double worst = 0, worst_n = 0;
    for (int k = 0; k < 6; k++) {
        gib_motion_pose(m, times[k], pos, nrm);
        const double frac = deg_at[k] / 180.0;
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            const float *r = m->rest_positions + 3 * v, *rn = m->rest_normals + 3 * v;
            const double d[3] = {r[0] - 3.0, r[1] - 0.5, r[2]}, n0[3] = {rn[0], rn[1], rn[2]};
            double q[3], qn[3];
            rot_y(deg_at[k], d, q);
            rot_y(deg_at[k], n0, qn);
            const double want[3] = {q[0] + 3.0 + frac, q[1] + 0.5, q[2]};
            for (int c = 0; c < 3; c++) {
                worst = fmax(worst, fabs(pos[3 * v + c] - want[c]));
                worst_n = fmax(worst_n, fabs(nrm[3 * v + c] - qn[c]));
            }
        }
    }
    NEAR(worst, 0.0, 1e-5, "rigid pose against R_y(angle)(p - pivot) + pivot + T, float rounding");
    NEAR(worst_n, 0.0, 1e-6, "normals rotated with the mesh");
    /* As loaded, the arrays hold t = 0; gib_scene_posed leaves the scene as it is. */
    gib_motion_pose(m, 0.0, pos, nrm);
    CHECK(!memcmp(pos, s.positions, sizeof(float) * 3 * m->vertex_count), "loaded = pose at t = 0");
    gib_scene posed;
    CHECK(gib_scene_posed(&s, 1.0, &posed, &err) == 0, "posed copy: %s", err.msg);
    gib_motion_pose(m, 1.0, pos, nrm);
    CHECK(!memcmp(pos, posed.positions, sizeof(float) * 3 * m->vertex_count) &&
              posed.positions != s.positions && posed.time == 1.0f,
          "the posed copy holds t = 1 in its own arrays");
    CHECK(!memcmp(posed.positions + 3 * 36, s.positions + 3 * 36, sizeof(float) * 3 * 6),
          "the static floor is copied as it is");
    gib_motion_pose(m, 0.0, pos, nrm);
    CHECK(!memcmp(pos, s.positions, sizeof(float) * 3 * m->vertex_count) && s.time == 0.0f,
          "the scene itself still holds t = 0");
    gib_scene_posed_free(&posed);
    /* Bounds hold every instant (sampled finely over the motion and beyond). */
    int outside = 0;
    for (int k = 0; k <= 200; k++) {
        gib_motion_pose(m, -0.5 + 3.0 * k / 200.0, pos, nrm);
        for (uint32_t v = 0; v < 3 * m->vertex_count; v++)
            outside += pos[v] < s.bounds_min[v % 3] || pos[v] > s.bounds_max[v % 3];
    }
    CHECK(outside == 0, "%d posed coordinates outside the scene bounds", outside);
    free(pos);
    gib_scene_free(&s);
}

/* A loop: the pose repeats every span; between keys it is linear. */
static void looping(void)
{
    char path[512];
    write_file("loop.scene",
               HEAD "procedural = box\nkeys = 1 2 3\n"
                    "key_translate = 0 0 0, 0 2 0, 0 0 0\nloop = 1\n",
               path, sizeof path);
    gib_scene s;
    gib_error err;
    if (gib_scene_load(path, &s, &err) < 0) {
        CHECK(0, "loop scene: %s", err.msg);
        return;
    }
    const gib_motion *m = &s.motions[0];
    float a[3 * 36 * 2], b[3 * 36 * 2];
    const double t[] = {0.25, 1.5, 2.75, -4.1};
    const double y[] = {1.5, 1.0, 0.5, 1.8}; /* wrapped into [1, 3]: 2.25, 1.5, 2.75, 1.9 */
    for (int k = 0; k < 4; k++) {
        gib_motion_pose(m, t[k], a, a + 3 * 36);
        gib_motion_pose(m, t[k] + 2.0 * 7, b, b + 3 * 36);
        double d = 0;
        for (int i = 0; i < 3 * 36; i++)
            d = fmax(d, fabs(a[i] - b[i]));
        NEAR(d, 0.0, 1e-5, "a loop repeats after its span (2 s), float rounding of the phase");
        NEAR(a[1] - m->rest_positions[1], y[k], 1e-5, "linear between keys, wrapped time");
    }
    gib_scene_free(&s);
}

/* Water: heights are the sum of the file's waves and normals the surface's own (against the
 * grid's finite differences). */
static void water(void)
{
    char path[512];
    write_file("water.scene",
               HEAD "procedural = water\nsize = 4 2\nsegments = 200\n"
                    "waves = 0.05 1.5 30 1.2, 0.02 0.7 -60 0.8\ntranslate = 1 2 3\n",
               path, sizeof path);
    gib_scene s;
    gib_error err;
    if (gib_scene_load(path, &s, &err) < 0) {
        CHECK(0, "water scene: %s", err.msg);
        return;
    }
    CHECK(s.motion_count == 1 && s.motions[0].kind == GIB_MOTION_WATER &&
              s.vertex_count == 201 * 201 && s.triangle_count == 2 * 200 * 200,
          "a 200 x 200 water grid (%u vertices, %u triangles)", s.vertex_count, s.triangle_count);
    const gib_motion *m = &s.motions[0];
    const double wv[2][4] = {{0.05, 1.5, 30, 1.2}, {0.02, 0.7, -60, 0.8}};
    float *pos = malloc(sizeof(float) * 6 * m->vertex_count), *nrm = pos + 3 * m->vertex_count;
    double worst_h = 0, worst_xz = 0, worst_angle = 0;
    int outside = 0;
    for (int k = 0; k < 3; k++) {
        const double t = k * 1.7;
        gib_motion_pose(m, t, pos, nrm);
        for (uint32_t j = 0; j <= 200; j++)
            for (uint32_t i = 0; i <= 200; i++) {
                const uint32_t v = j * 201 + i;
                const double x = (i / 200.0 - 0.5) * 4.0, z = (j / 200.0 - 0.5) * 2.0;
                double h = 0;
                for (int w = 0; w < 2; w++) {
                    const double kk = 2 * M_PI / wv[w][1], d = wv[w][2] * M_PI / 180.0;
                    h += wv[w][0] * sin(kk * cos(d) * x + kk * sin(d) * z - kk * wv[w][3] * t);
                }
                worst_h = fmax(worst_h, fabs(pos[3 * v + 1] - (h + 2.0)));
                worst_xz = fmax(worst_xz, fmax(fabs(pos[3 * v] - (x + 1)),
                                               fabs(pos[3 * v + 2] - (z + 3))));
                for (int c = 0; c < 3; c++)
                    outside += pos[3 * v + c] < s.bounds_min[c] || pos[3 * v + c] > s.bounds_max[c];
                if (i == 0 || j == 0 || i == 200 || j == 200)
                    continue;
                /* Central differences along the grid: their cross product is the surface normal
                 * to O(h^2) (cells of 2 cm and 1 cm against wavelengths of 70 cm or more). */
                const float *px0 = pos + 3 * (v - 1), *px1 = pos + 3 * (v + 1);
                const float *pz0 = pos + 3 * (v - 201), *pz1 = pos + 3 * (v + 201);
                const double ex[3] = {px1[0] - px0[0], px1[1] - px0[1], px1[2] - px0[2]};
                const double ez[3] = {pz1[0] - pz0[0], pz1[1] - pz0[1], pz1[2] - pz0[2]};
                double n[3] = {ez[1] * ex[2] - ez[2] * ex[1], ez[2] * ex[0] - ez[0] * ex[2],
                               ez[0] * ex[1] - ez[1] * ex[0]};
                const double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                const double dot =
                    (n[0] * nrm[3 * v] + n[1] * nrm[3 * v + 1] + n[2] * nrm[3 * v + 2]) / l;
                worst_angle = fmax(worst_angle, acos(fmin(1.0, dot)));
            }
    }
    NEAR(worst_h, 0.0, 1e-5, "height = sum of the waves, float rounding at y = 2");
    NEAR(worst_xz, 0.0, 1e-5, "a height field: x and z stay on the grid");
    /* Finite differences over 2 cells: curvature error ~ (k h)^2 / 6 of the slope, ~1e-3 rad. */
    CHECK(worst_angle < 5e-3, "analytic normals off the grid's by up to %.3g rad (want < 5e-3)",
          worst_angle);
    CHECK(outside == 0, "%d posed coordinates outside the scene bounds", outside);
    free(pos);
    gib_scene_free(&s);
}

int main(void)
{
    if (scene_test_begin("gib_scene_motion") < 0)
        return 1;
    errors();
    rigid();
    looping();
    water();
    return scene_test_end();
}

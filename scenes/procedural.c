/* gibench — scenes built in C: the Cornell box from its published measurements, a plane with a box
 * on it, and a closed room to put scanned models in.
 *
 * Every flat face gets its own vertices carrying the face's geometric normal, so the shading normal
 * equals the geometric normal and the GL side and the path tracer cannot disagree about it. All
 * materials are Lambertian and two-sided: the faces are single-sided quads (walls without
 * thickness), and a technique that culls or flips by winding must not change what they reflect. */
#include <math.h>
#include <string.h>

#include "../harness/base/hash.h"
#include "scene_internal.h"

static const char *const generator_names[] = {"cornell_box", "plane_box", "room"};

int gib_procedural_known(const char *name)
{
    for (size_t i = 0; i < sizeof generator_names / sizeof generator_names[0]; i++)
        if (strcmp(name, generator_names[i]) == 0)
            return 1;
    return 0;
}

int gib_procedural_takes_size(const char *name)
{
    return strcmp(name, "room") == 0;
}

const char *gib_procedural_names(void)
{
    return "cornell_box, plane_box, room";
}

/* Geometric normal of triangle (a, b, c), right-handed (counter-clockwise seen from the front). */
static void tri_normal(const float a[3], const float b[3], const float c[3], float n[3])
{
    const float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    n[0] /= len;
    n[1] /= len;
    n[2] /= len;
}

/* Adds quad q (4 corners in order around the face, any winding) as two triangles (0,1,2) and
 * (0,2,3), each with its own three vertices and face normal. The winding is chosen so the normal
 * points toward `toward` when facing = +1, away from it when facing = -1. Quad texture
 * coordinates are the unit square, for techniques that want some. */
static void add_quad(gib_geom *g, float q[4][3], const float toward[3], int facing,
                     uint32_t material)
{
    float n[3];
    tri_normal(q[0], q[1], q[2], n);
    const float centre[3] = {(q[0][0] + q[1][0] + q[2][0] + q[3][0]) * 0.25f,
                             (q[0][1] + q[1][1] + q[2][1] + q[3][1]) * 0.25f,
                             (q[0][2] + q[1][2] + q[2][2] + q[3][2]) * 0.25f};
    const float d = n[0] * (toward[0] - centre[0]) + n[1] * (toward[1] - centre[1]) +
                    n[2] * (toward[2] - centre[2]);
    if ((d > 0.0f) != (facing > 0)) { /* reverse the winding: swap corners 1 and 3 */
        for (int k = 0; k < 3; k++) {
            float t = q[1][k];
            q[1][k] = q[3][k];
            q[3][k] = t;
        }
    }
    static const float quv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int t = 0; t < 2; t++) {
        const float *a = q[tri[t][0]], *b = q[tri[t][1]], *c = q[tri[t][2]];
        tri_normal(a, b, c, n);
        uint32_t i0 = gib_geom_vertex(g, a, n, quv[tri[t][0]]);
        uint32_t i1 = gib_geom_vertex(g, b, n, quv[tri[t][1]]);
        uint32_t i2 = gib_geom_vertex(g, c, n, quv[tri[t][2]]);
        gib_geom_triangle(g, i0, i1, i2, material);
    }
}

/* The Cornell box, from "Cornell Box data", Cornell University Program of Computer Graphics
 * (www.graphics.cornell.edu/online/box/data.html), coordinates in millimetres, converted to
 * metres. The walls enclose x in [0, 556], y in [0, 548.8], z in [0, 559.2]; the camera looks
 * along +z from z = -800, so x = 0 (the green wall) appears on the right.
 *
 * The published data is not quite a box: the red wall's bottom edge runs from x = 552.8 to 549.6
 * while its top edge is at x = 556, so that quad is twisted out of plane by about 3 mm, and the
 * floor and back wall are trapezoids. We keep the published coordinates as they are and split
 * every quad into two triangles with their own vertices and geometric normals, so each triangle is
 * exactly planar and shading normals equal geometric normals (no smoothing across the twist).
 *
 * The published scene's area light is not built: scenes/cornell.scene replaces it with a spot
 * light (the techniques under test take point-like lights). The blocks have no bottom faces, as
 * in the published data. Albedos are the RGB values used by common renderers (Mitsuba's and
 * pbrt-v3's cornell-box scenes, converted from the published spectral reflectances): white
 * 0.725 0.71 0.68, red 0.63 0.065 0.05, green 0.14 0.45 0.091. */
/* clang-format off */
static const float cornell_quads[][4][3] = {
    /* 0 floor (white) */
    {{552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}},
    /* 1 ceiling (white) */
    {{556, 548.8f, 0}, {556, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}},
    /* 2 back wall (white) */
    {{549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556, 548.8f, 559.2f}},
    /* 3 right wall (green) */
    {{0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}},
    /* 4 left wall (red) */
    {{552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556, 548.8f, 559.2f}, {556, 548.8f, 0}},
    /* 5-9 short block (white) */
    {{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}},
    {{290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}},
    {{130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}},
    {{82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}},
    {{240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}},
    /* 10-14 tall block (white) */
    {{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}},
    {{423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}},
    {{472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}},
    {{314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}},
    {{265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}},
};
/* clang-format on */

static int build_cornell(gib_geom *g, gib_error *err)
{
    const int nq = (int)(sizeof cornell_quads / sizeof cornell_quads[0]);
    gib_mat_desc white = gib_mat_desc_diffuse("white", 0.725f, 0.71f, 0.68f);
    gib_mat_desc red = gib_mat_desc_diffuse("red", 0.63f, 0.065f, 0.05f);
    gib_mat_desc green = gib_mat_desc_diffuse("green", 0.14f, 0.45f, 0.091f);
    int mw = gib_geom_material(g, &white, err);
    int mr = mw < 0 ? -1 : gib_geom_material(g, &red, err);
    int mg = mr < 0 ? -1 : gib_geom_material(g, &green, err);
    if (mg < 0 || gib_geom_reserve(g, (uint32_t)nq * 6, (uint32_t)nq * 2, err))
        return -1;
    /* Walls face the inside of the box; block faces face away from the block's centre. */
    const float room_centre[3] = {0.278f, 0.2744f, 0.2796f};
    const float short_centre[3] = {0.186f, 0.0825f, 0.169f};
    const float tall_centre[3] = {0.3685f, 0.165f, 0.35125f};
    for (int i = 0; i < nq; i++) {
        float q[4][3];
        for (int k = 0; k < 4; k++)
            for (int c = 0; c < 3; c++)
                q[k][c] = cornell_quads[i][k][c] * 0.001f; /* mm -> m */
        uint32_t m = (uint32_t)(i == 3 ? mg : i == 4 ? mr : mw);
        if (i < 5)
            add_quad(g, q, room_centre, +1, m);
        else
            add_quad(g, q, i < 10 ? short_centre : tall_centre, -1, m);
    }
    return 0;
}

/* An axis-aligned box [lo, hi]; faces point outward (inward = 0) or inward (inward = 1). Face
 * order: -x, +x, -y, +y, -z, +z; skip_mask bit i leaves face i out; mats[i] is face i's
 * material. */
static void add_box(gib_geom *g, const float lo[3], const float hi[3], int inward,
                    unsigned skip_mask, const uint32_t mats[6])
{
    const float centre[3] = {(lo[0] + hi[0]) * 0.5f, (lo[1] + hi[1]) * 0.5f,
                             (lo[2] + hi[2]) * 0.5f};
    for (int f = 0; f < 6; f++) {
        if (skip_mask & (1u << f))
            continue;
        const int axis = f / 2;
        const float v = (f & 1) ? hi[axis] : lo[axis];
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        float q[4][3];
        const float su[4] = {lo[u], hi[u], hi[u], lo[u]};
        const float sw[4] = {lo[w], lo[w], hi[w], hi[w]};
        for (int k = 0; k < 4; k++) {
            q[k][axis] = v;
            q[k][u] = su[k];
            q[k][w] = sw[k];
        }
        add_quad(g, q, centre, inward ? +1 : -1, mats[f]);
    }
}

/* An 8 m x 8 m ground plane at y = 0 centred on the origin, and a 1 m cube standing on it at the
 * origin (no bottom face: it would coincide with the ground). The box is orange so that its
 * indirect light on the ground is told apart from the ground's own colour. */
static int build_plane_box(gib_geom *g, gib_error *err)
{
    gib_mat_desc ground = gib_mat_desc_diffuse("ground", 0.7f, 0.7f, 0.7f);
    gib_mat_desc box = gib_mat_desc_diffuse("box", 0.7f, 0.35f, 0.15f);
    int mg = gib_geom_material(g, &ground, err);
    int mb = mg < 0 ? -1 : gib_geom_material(g, &box, err);
    if (mb < 0 || gib_geom_reserve(g, 6 + 5 * 6, 2 + 5 * 2, err))
        return -1;
    float q[4][3] = {{-4, 0, -4}, {4, 0, -4}, {4, 0, 4}, {-4, 0, 4}};
    const float above[3] = {0, 1, 0};
    add_quad(g, q, above, +1, (uint32_t)mg);
    const float lo[3] = {-0.5f, 0.0f, -0.5f}, hi[3] = {0.5f, 1.0f, 0.5f};
    const uint32_t mats[6] = {(uint32_t)mb, (uint32_t)mb, (uint32_t)mb,
                              (uint32_t)mb, (uint32_t)mb, (uint32_t)mb};
    add_box(g, lo, hi, 0, 1u << 2 /* no -y face */, mats);
    return 0;
}

/* The inside of a closed box, floor at y = 0, centred on x and z, all faces facing inward. Each
 * face has its own material (room_floor, room_ceiling, room_wall_xneg/xpos/zneg/zpos, all 0.7
 * grey) so that a scene file can colour single walls. */
static int build_room(gib_geom *g, const gib_proc_params *p, gib_error *err)
{
    float size[3] = {4.0f, 3.0f, 4.0f};
    if (p && p->has_size)
        memcpy(size, p->size, sizeof size);
    for (int i = 0; i < 3; i++)
        if (!(size[i] > 0.0f) || !isfinite(size[i]))
            return gib_fail(err,
                            "room: 'size' must be three positive numbers (width height "
                            "depth), got %g %g %g",
                            size[0], size[1], size[2]);
    static const char *names[6] = {"room_wall_xneg", "room_wall_xpos", "room_floor",
                                   "room_ceiling",   "room_wall_zneg", "room_wall_zpos"};
    uint32_t mats[6];
    for (int f = 0; f < 6; f++) {
        gib_mat_desc d = gib_mat_desc_diffuse(names[f], 0.7f, 0.7f, 0.7f);
        int m = gib_geom_material(g, &d, err);
        if (m < 0)
            return -1;
        mats[f] = (uint32_t)m;
    }
    if (gib_geom_reserve(g, 6 * 6, 6 * 2, err))
        return -1;
    const float lo[3] = {-0.5f * size[0], 0.0f, -0.5f * size[2]};
    const float hi[3] = {0.5f * size[0], size[1], 0.5f * size[2]};
    add_box(g, lo, hi, 1, 0, mats);
    return 0;
}

int gib_procedural_build(const char *name, const gib_proc_params *p, gib_geom *out, uint64_t *hash,
                         gib_error *err)
{
    *hash = gib_hash_str(*hash, "procedural");
    *hash = gib_hash_str(*hash, name);
    if (p && p->has_size)
        for (int i = 0; i < 3; i++)
            *hash = gib_hash_f32(*hash, p->size[i]);
    if (strcmp(name, "cornell_box") == 0)
        return build_cornell(out, err);
    if (strcmp(name, "plane_box") == 0)
        return build_plane_box(out, err);
    if (strcmp(name, "room") == 0)
        return build_room(out, p, err);
    return gib_fail(err, "unknown procedural generator '%s' (known: %s)", name,
                    gib_procedural_names());
}

/* gibench — the `ring` generator: an upright ring (a thick-walled open cylinder, the "caustic
 * ring" of the thesis' test scenes, Le 2014 Sec. 4.1) standing on y = 0, centred on the y axis.
 * Inner wall (normals toward the axis), outer wall (normals away from it) and the top rim (flat,
 * +y); no bottom face: the ring stands on a surface it would coincide with, as plane_box's box.
 * 6 x segments triangles.
 *
 * The walls have SMOOTH (radial) normals: the thesis' ring is a curved mirror of ~200 triangles,
 * and its caustic (the cardioid inside the ring) comes from the curvature; flat facets would
 * reflect parallel bundles and give no caustic at all. Both renderers shade with the interpolated
 * normal, so they reflect off the same smooth surface. The rim is flat (its own vertices). */
#include <math.h>

#include "scene_internal.h"

int gib_gen_ring(gib_geom *g, const gib_proc_params *p, gib_error *err)
{
    const double r0 = gib_proc_get(p, GIB_PK_RADIUS, 0, GIB_RING_RADIUS);
    const double t = gib_proc_get(p, GIB_PK_THICKNESS, 0, GIB_RING_THICKNESS * r0);
    const double h = gib_proc_get(p, GIB_PK_HEIGHT, 0, GIB_RING_HEIGHT * r0);
    const uint32_t n = (uint32_t)gib_proc_get(p, GIB_PK_SEGMENTS, 0, GIB_RING_SEGMENTS);
    const double r1 = r0 + t;
    gib_mat_desc md = gib_mat_desc_diffuse("ring", 0.7f, 0.7f, 0.7f);
    const int m = gib_geom_material(g, &md, err);
    /* Walls: 2 rows of n + 1 vertices each (seam duplicated for the uvs); rim: 4 per segment. */
    if (m < 0 || gib_geom_reserve(g, 2 * 2 * (n + 1) + 4 * n, 6 * n, err))
        return -1;
    const double two_pi = 6.283185307179586;
    for (int wall = 0; wall < 2; wall++) {
        const double r = wall ? r1 : r0, s = wall ? 1.0 : -1.0; /* normal sign: out / in */
        const uint32_t base = g->vcount;
        for (uint32_t i = 0; i <= n; i++) {
            const double a = two_pi * (double)(i % n) / (double)n;
            const float c = (float)cos(a), sn = (float)sin(a);
            const float nrm[3] = {(float)s * c, 0.0f, (float)s * sn};
            for (int k = 0; k < 2; k++) {
                const float pos[3] = {(float)r * c, k ? (float)h : 0.0f, (float)r * sn};
                const float uv[2] = {(float)i / (float)n, (float)k};
                gib_geom_vertex(g, pos, nrm, uv);
            }
        }
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t a = base + 2 * i, b = a + 1, c = a + 2, d = a + 3; /* a,c bottom */
            /* Angle grows from +x toward +z; (a, b, c) winds outward (normal along +r). */
            if (wall) {
                gib_geom_triangle(g, a, b, c, (uint32_t)m);
                gib_geom_triangle(g, c, b, d, (uint32_t)m);
            } else {
                gib_geom_triangle(g, a, c, b, (uint32_t)m);
                gib_geom_triangle(g, c, d, b, (uint32_t)m);
            }
        }
    }
    const float up[3] = {0.0f, 1.0f, 0.0f};
    for (uint32_t i = 0; i < n; i++) {
        const double a0 = two_pi * (double)i / (double)n, a1 = two_pi * (double)(i + 1) / (double)n;
        const float q[4][3] = {{(float)(r0 * cos(a0)), (float)h, (float)(r0 * sin(a0))},
                               {(float)(r1 * cos(a0)), (float)h, (float)(r1 * sin(a0))},
                               {(float)(r1 * cos(a1)), (float)h, (float)(r1 * sin(a1))},
                               {(float)(r0 * cos(a1)), (float)h, (float)(r0 * sin(a1))}};
        uint32_t v[4];
        for (int k = 0; k < 4; k++) {
            const float uv[2] = {(float)(k == 1 || k == 2), (float)(k >= 2)};
            v[k] = gib_geom_vertex(g, q[k], up, uv);
        }
        /* Seen from +y, angle growing from +x toward +z turns clockwise: (0, 3, 1) faces +y. */
        gib_geom_triangle(g, v[0], v[3], v[1], (uint32_t)m);
        gib_geom_triangle(g, v[1], v[3], v[2], (uint32_t)m);
    }
    return 0;
}

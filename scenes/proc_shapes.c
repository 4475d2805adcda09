/* gibench — simple procedural shapes for small and hard-case scenes: a quad, a box, a square made
 * of sliver and degenerate triangles, and a closed sphere seen from inside (the furnace test).
 * Every triangle has its own vertices carrying its geometric normal (except that degenerate
 * triangles, which have none, carry the normal of the plane they lie in), so the GL side and the
 * path tracer cannot disagree about shading normals. Materials are Lambertian and two-sided. */
#include <math.h>
#include <string.h>

#include "scene_internal.h"

static int one_material(gib_geom *g, const char *name, float albedo, gib_error *err)
{
    gib_mat_desc d = gib_mat_desc_diffuse(name, albedo, albedo, albedo);
    return gib_geom_material(g, &d, err);
}

/* A w x d rectangle (size = w d, default 1 1) in the xz plane at y = 0, centred on the origin,
 * facing +y. Place it with rotate / translate. */
int gib_gen_quad(gib_geom *g, const gib_proc_params *p, gib_error *err)
{
    const float w = (float)gib_proc_get(p, GIB_PK_SIZE, 0, 1.0);
    const float d = (float)gib_proc_get(p, GIB_PK_SIZE, 1, 1.0);
    int m = one_material(g, "quad", 0.7f, err);
    if (m < 0 || gib_geom_reserve(g, 6, 2, err))
        return -1;
    float q[4][3] = {{-0.5f * w, 0, -0.5f * d},
                     {0.5f * w, 0, -0.5f * d},
                     {0.5f * w, 0, 0.5f * d},
                     {-0.5f * w, 0, 0.5f * d}};
    const float above[3] = {0, 1, 0};
    gib_geom_add_quad(g, q, above, +1, (uint32_t)m);
    return 0;
}

/* An axis-aligned w x h x d box (size = w h d, default 1 1 1) standing on y = 0, centred on x and
 * z, all six faces facing outward. */
int gib_gen_box(gib_geom *g, const gib_proc_params *p, gib_error *err)
{
    const float w = (float)gib_proc_get(p, GIB_PK_SIZE, 0, 1.0);
    const float h = (float)gib_proc_get(p, GIB_PK_SIZE, 1, 1.0);
    const float d = (float)gib_proc_get(p, GIB_PK_SIZE, 2, 1.0);
    int m = one_material(g, "box", 0.7f, err);
    if (m < 0 || gib_geom_reserve(g, 6 * 6, 6 * 2, err))
        return -1;
    const float lo[3] = {-0.5f * w, 0.0f, -0.5f * d}, hi[3] = {0.5f * w, h, 0.5f * d};
    const uint32_t mats[6] = {(uint32_t)m, (uint32_t)m, (uint32_t)m,
                              (uint32_t)m, (uint32_t)m, (uint32_t)m};
    gib_geom_add_box(g, lo, hi, 0, 0, mats);
    return 0;
}

/* Appends triangle (a, b, c) lying in the plane y = 0 with normal +y, reordering b and c so that
 * the winding agrees with +y when the triangle has an area. uv = position / size + 0.5. */
static void flat_triangle(gib_geom *g, const double a[3], const double b[3], const double c[3],
                          double w, double d, uint32_t m)
{
    const double cross_y = (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]);
    const double *v[3] = {a, cross_y < 0 ? c : b, cross_y < 0 ? b : c};
    const float n[3] = {0.0f, 1.0f, 0.0f};
    uint32_t idx[3];
    for (int k = 0; k < 3; k++) {
        const float pos[3] = {(float)v[k][0], (float)v[k][1], (float)v[k][2]};
        const float uv[2] = {(float)(v[k][0] / w + 0.5), (float)(v[k][2] / d + 0.5)};
        idx[k] = gib_geom_vertex(g, pos, n, uv);
    }
    gib_geom_triangle(g, idx[0], idx[1], idx[2], m);
}

/* A w x d rectangle (size = w d, default 4 4) at y = 0, centred, facing +y, made only of slivers
 * and degenerate triangles: a fan of `segments` (default 1024) triangles from the corner
 * (-w/2, -d/2) to points spaced evenly along the two far edges (x = +w/2, then z = +d/2), so every
 * fan triangle is about diag x (w + d) / segments (aspect ratio ~ segments / 2), all sharing one
 * vertex. After each fan triangle comes a zero-area one, cycling through three kinds: two equal
 * corners, three collinear corners (the corner, the midpoint and the far end of a fan edge), all
 * three corners equal. Triangles: 2 x segments, half of them degenerate; each carries +y. */
int gib_gen_slivers(gib_geom *g, const gib_proc_params *p, gib_error *err)
{
    const double w = gib_proc_get(p, GIB_PK_SIZE, 0, 4.0);
    const double d = gib_proc_get(p, GIB_PK_SIZE, 1, 4.0);
    const uint32_t n = (uint32_t)gib_proc_get(p, GIB_PK_SEGMENTS, 0, 1024.0);
    int m = one_material(g, "slivers", 0.7f, err);
    if (m < 0 || gib_geom_reserve(g, 6 * n, 2 * n, err))
        return -1;
    /* Pieces on the first far edge (x = +w/2), in proportion to its length, at least one. */
    uint32_t n1 = (uint32_t)floor((double)n * d / (w + d) + 0.5);
    n1 = n1 < 1 ? 1 : n1 > n - 1 ? n - 1 : n1;
    const uint32_t n2 = n - n1;
    const double c0[3] = {-0.5 * w, 0.0, -0.5 * d};
    double prev[3] = {0.5 * w, 0.0, -0.5 * d};
    for (uint32_t i = 1; i <= n; i++) {
        double cur[3] = {0.5 * w, 0.0, 0.5 * d};
        if (i < n1)
            cur[2] = -0.5 * d + d * (double)i / (double)n1;
        else if (i > n1)
            cur[0] = 0.5 * w - w * (double)(i - n1) / (double)n2;
        flat_triangle(g, c0, prev, cur, w, d, (uint32_t)m);
        const double mid[3] = {0.5 * (c0[0] + cur[0]), 0.0, 0.5 * (c0[2] + cur[2])};
        switch (i % 3) {
        case 0: flat_triangle(g, c0, cur, cur, w, d, (uint32_t)m); break;
        case 1: flat_triangle(g, c0, mid, cur, w, d, (uint32_t)m); break;
        default: flat_triangle(g, cur, cur, cur, w, d, (uint32_t)m); break;
        }
        memcpy(prev, cur, sizeof prev);
    }
    return 0;
}

/* ------------------------------------------------------------------ sphere_interior */

static void norm3(double v[3])
{
    const double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
}

static void midpoint(const double a[3], const double b[3], double out[3])
{
    out[0] = a[0] + b[0]; /* a + b == b + a exactly: both faces of an edge get one midpoint */
    out[1] = a[1] + b[1];
    out[2] = a[2] + b[2];
    norm3(out);
}

/* Emits a unit-sphere triangle scaled by r, wound so its normal points at the centre. */
static void sphere_face(gib_geom *g, const double a[3], const double b[3], const double c[3],
                        double r, uint32_t m)
{
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    norm3(n);
    const int flip = n[0] * (a[0] + b[0] + c[0]) + n[1] * (a[1] + b[1] + c[1]) +
                         n[2] * (a[2] + b[2] + c[2]) >
                     0.0;
    if (flip)
        n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
    const double *v[3] = {a, flip ? c : b, flip ? b : c};
    const float fn[3] = {(float)n[0], (float)n[1], (float)n[2]};
    uint32_t idx[3];
    for (int k = 0; k < 3; k++) {
        const float pos[3] = {(float)(r * v[k][0]), (float)(r * v[k][1]), (float)(r * v[k][2])};
        /* Equirectangular uv, for techniques that want some. */
        const float uv[2] = {(float)(0.5 + atan2(v[k][0], v[k][2]) / (2.0 * M_PI)),
                             (float)(0.5 + asin(v[k][1] < -1 ? -1 : v[k][1] > 1 ? 1 : v[k][1]) /
                                               M_PI)};
        idx[k] = gib_geom_vertex(g, pos, fn, uv);
    }
    gib_geom_triangle(g, idx[0], idx[1], idx[2], m);
}

static void subdivide(gib_geom *g, const double a[3], const double b[3], const double c[3],
                      int level, double r, uint32_t m)
{
    if (level == 0) {
        sphere_face(g, a, b, c, r, m);
        return;
    }
    double ab[3], bc[3], ca[3];
    midpoint(a, b, ab);
    midpoint(b, c, bc);
    midpoint(c, a, ca);
    subdivide(g, a, ab, ca, level - 1, r, m);
    subdivide(g, ab, b, bc, level - 1, r, m);
    subdivide(g, ca, bc, c, level - 1, r, m);
    subdivide(g, ab, bc, ca, level - 1, r, m);
}

/* A closed sphere of radius `radius` (default 1) about the origin, seen from inside: an icosahedron
 * whose faces are split in four `subdivisions` times (default 5), new vertices pushed out onto the
 * sphere. 20 x 4^subdivisions triangles, flat, their normals pointing into the sphere (each
 * triangle's normal passes through the centre, which projects onto its circumcentre). All vertices
 * lie on the sphere; from one subdivision on, the six points (+-R, 0, 0), ... are vertices, so the
 * bounds are exactly +-R. Material `sphere_wall`, albedo 0.5. */
int gib_gen_sphere_interior(gib_geom *g, const gib_proc_params *p, gib_error *err)
{
    const double r = gib_proc_get(p, GIB_PK_RADIUS, 0, 1.0);
    const int levels = (int)gib_proc_get(p, GIB_PK_SUBDIVISIONS, 0, 5.0);
    const uint32_t faces = 20u << (2 * levels);
    int m = one_material(g, "sphere_wall", 0.5f, err);
    if (m < 0 || gib_geom_reserve(g, 3 * faces, faces, err))
        return -1;
    const double t = (1.0 + sqrt(5.0)) / 2.0;
    double v[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    static const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int i = 0; i < 12; i++)
        norm3(v[i]);
    for (int i = 0; i < 20; i++)
        subdivide(g, v[f[i][0]], v[f[i][1]], v[f[i][2]], levels, r, (uint32_t)m);
    return 0;
}

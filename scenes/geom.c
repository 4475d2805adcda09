/* gibench — the growable triangle soup that generators and mesh importers fill before the scene is
 * flattened (scene_internal.h), and the flat-face building blocks the generators share. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

static int grow(void **p, uint32_t *cap, uint32_t need, size_t elem, gib_error *err)
{
    if (need <= *cap)
        return 0;
    uint64_t c = *cap ? *cap : 64;
    while (c < need)
        c *= 2;
    if (c > UINT32_MAX)
        return gib_fail(err, "mesh too large: more than 2^32 vertices or triangles");
    void *q = gib_realloc_array(*p, (size_t)c, elem, err);
    if (!q)
        return -1;
    *p = q;
    *cap = (uint32_t)c;
    return 0;
}

int gib_geom_reserve(gib_geom *g, uint32_t verts, uint32_t tris, gib_error *err)
{
    if ((uint64_t)g->vcount + verts > UINT32_MAX || (uint64_t)g->tcount + tris > UINT32_MAX)
        return gib_fail(err, "mesh too large: more than 2^32 vertices or triangles");
    uint32_t nv = g->vcount + verts, nt = g->tcount + tris;
    if (nv > g->vcap) {
        /* The three vertex arrays grow together; reuse one capacity for all of them. */
        uint32_t cap = g->vcap;
        if (grow((void **)&g->pos, &cap, nv, 3 * sizeof(float), err))
            return -1;
        uint32_t c2 = g->vcap;
        if (grow((void **)&g->nrm, &c2, nv, 3 * sizeof(float), err))
            return -1;
        c2 = g->vcap;
        if (grow((void **)&g->uv, &c2, nv, 2 * sizeof(float), err))
            return -1;
        g->vcap = cap;
    }
    if (nt > g->tcap) {
        uint32_t cap = g->tcap;
        if (grow((void **)&g->idx, &cap, nt, 3 * sizeof(uint32_t), err))
            return -1;
        uint32_t c2 = g->tcap;
        if (grow((void **)&g->mat, &c2, nt, sizeof(uint32_t), err))
            return -1;
        g->tcap = cap;
    }
    return 0;
}

uint32_t gib_geom_vertex(gib_geom *g, const float p[3], const float n[3], const float uv[2])
{
    uint32_t i = g->vcount++;
    memcpy(g->pos + 3 * (size_t)i, p, 3 * sizeof(float));
    memcpy(g->nrm + 3 * (size_t)i, n, 3 * sizeof(float));
    g->uv[2 * (size_t)i] = uv ? uv[0] : 0.0f;
    g->uv[2 * (size_t)i + 1] = uv ? uv[1] : 0.0f;
    return i;
}

void gib_geom_triangle(gib_geom *g, uint32_t a, uint32_t b, uint32_t c, uint32_t material)
{
    uint32_t t = g->tcount++;
    g->idx[3 * (size_t)t] = a;
    g->idx[3 * (size_t)t + 1] = b;
    g->idx[3 * (size_t)t + 2] = c;
    g->mat[t] = material;
}

int gib_geom_material(gib_geom *g, const gib_mat_desc *m, gib_error *err)
{
    if (grow((void **)&g->mats, &g->mcap, g->mcount + 1, sizeof *g->mats, err))
        return -1;
    g->mats[g->mcount] = *m;
    return (int)g->mcount++;
}

void gib_geom_free(gib_geom *g)
{
    free(g->pos);
    free(g->nrm);
    free(g->uv);
    free(g->idx);
    free(g->mat);
    free(g->mats);
    memset(g, 0, sizeof *g);
}

gib_mat_desc gib_mat_desc_diffuse(const char *name, float r, float g, float b)
{
    gib_mat_desc d;
    memset(&d, 0, sizeof d);
    snprintf(d.m.name, sizeof d.m.name, "%s", name);
    d.m.albedo[0] = r;
    d.m.albedo[1] = g;
    d.m.albedo[2] = b;
    d.m.albedo_tex = -1;
    d.m.alpha_tex = -1;
    d.m.spec_type = GIB_SPEC_NONE;
    d.m.phong_n = 1.0f;
    d.m.two_sided = 1;
    d.mesh_index = -1;
    return d;
}

/* ------------------------------------------------------------------ flat faces */

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
void gib_geom_add_quad(gib_geom *g, float q[4][3], const float toward[3], int facing,
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

/* An axis-aligned box [lo, hi]; faces point outward (inward = 0) or inward (inward = 1). Face
 * order: -x, +x, -y, +y, -z, +z; skip_mask bit i leaves face i out; mats[i] is face i's
 * material. */
void gib_geom_add_box(gib_geom *g, const float lo[3], const float hi[3], int inward,
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
        gib_geom_add_quad(g, q, centre, inward ? +1 : -1, mats[f]);
    }
}

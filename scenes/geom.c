/* gibench — the growable triangle soup that generators and mesh importers fill before the scene is
 * flattened (scene_internal.h). */
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

/* gibench — the `water` generator: a w x d grid of segments x segments cells in the xz plane at
 * y = 0, centred, facing +y, smooth normals (+y at rest). Its heights and normals at time t come
 * from the mesh's waves (motion.c); the grid here is the surface at rest, in the mesh's frame. */
#include "scene_internal.h"

int gib_gen_water(gib_geom *g, const gib_proc_params *p, gib_error *err)
{
    const float w = (float)gib_proc_get(p, GIB_PK_SIZE, 0, GIB_WATER_SIZE);
    const float d = (float)gib_proc_get(p, GIB_PK_SIZE, 1, GIB_WATER_SIZE);
    const uint32_t n = (uint32_t)gib_proc_get(p, GIB_PK_SEGMENTS, 0, GIB_WATER_SEGMENTS);
    gib_mat_desc md = gib_mat_desc_diffuse("water", 0.25f, 0.45f, 0.6f);
    const int m = gib_geom_material(g, &md, err);
    if (m < 0 || gib_geom_reserve(g, (n + 1) * (n + 1), 2 * n * n, err))
        return -1;
    const uint32_t base = g->vcount;
    const float up[3] = {0.0f, 1.0f, 0.0f};
    for (uint32_t j = 0; j <= n; j++)
        for (uint32_t i = 0; i <= n; i++) {
            const float u = (float)i / (float)n, v = (float)j / (float)n;
            const float pos[3] = {(u - 0.5f) * w, 0.0f, (v - 0.5f) * d}, uv[2] = {u, v};
            gib_geom_vertex(g, pos, up, uv);
        }
    /* (x0,z0), (x0,z1), (x1,z0) winds toward +y. */
    for (uint32_t j = 0; j < n; j++)
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t a = base + j * (n + 1) + i, b = a + (n + 1), c = a + 1, e = b + 1;
            gib_geom_triangle(g, a, b, c, (uint32_t)m);
            gib_geom_triangle(g, c, b, e, (uint32_t)m);
        }
    return 0;
}

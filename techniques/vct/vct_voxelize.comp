#include "gl/bindings.h"
// Occupancy: alpha = 1 in every voxel a triangle overlaps (exact triangle/box test by separating
// axes, Akenine-Moeller 2001), one invocation per triangle. For each column of voxels along the
// triangle's dominant normal axis only the few voxels the plane crosses are tested. Mesa has no
// conservative rasterisation; this misses no voxel a triangle touches (faces touching count).
layout(local_size_x = 64) in;
layout(location = GIB_LOC_VOXEL_FIRST + 0) uniform vec3 u_origin;
layout(location = GIB_LOC_VOXEL_FIRST + 1) uniform float u_size;
layout(location = GIB_LOC_VOXEL_FIRST + 2) uniform int u_res;
layout(location = 3) uniform uint u_triangles;
layout(std430, binding = GIB_SSBO_OWN_FIRST + 0) readonly buffer Positions { float pos[]; };
layout(std430, binding = GIB_SSBO_OWN_FIRST + 1) readonly buffer Indices { uint idx[]; };
layout(binding = 0, rgba16f) uniform image3D u_radiance;

vec3 vertex(uint i)
{
    uint v = idx[i];
    return (vec3(pos[3u * v], pos[3u * v + 1u], pos[3u * v + 2u]) - u_origin) / u_size *
           float(u_res);
}

// Triangle a b c (voxel units) against the box centre +- h.
bool overlaps(vec3 a, vec3 b, vec3 c, vec3 centre, float h)
{
    a -= centre;
    b -= centre;
    c -= centre;
    if (any(greaterThan(min(a, min(b, c)), vec3(h))) || any(lessThan(max(a, max(b, c)), vec3(-h))))
        return false;
    vec3 e[3] = vec3[3](b - a, c - b, a - c);
    vec3 n = cross(e[0], e[1]);
    if (abs(dot(n, a)) > h * (abs(n.x) + abs(n.y) + abs(n.z)))
        return false;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            vec3 u = vec3(0.0);
            u[j] = 1.0;
            vec3 ax = cross(u, e[i]);
            float pa = dot(a, ax), pb = dot(b, ax), pc = dot(c, ax);
            float r = h * (abs(ax.x) + abs(ax.y) + abs(ax.z));
            if (min(pa, min(pb, pc)) > r || max(pa, max(pb, pc)) < -r)
                return false;
        }
    return true;
}

void main()
{
    uint t = gl_GlobalInvocationID.x;
    if (t >= u_triangles)
        return;
    vec3 a = vertex(3u * t), b = vertex(3u * t + 1u), c = vertex(3u * t + 2u);
    vec3 n = cross(b - a, c - a);
    vec3 an = abs(n);
    if (!(an.x + an.y + an.z > 0.0))
        return; // degenerate: no area
    int k = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    int u = (k + 1) % 3, v = (k + 2) % 3;
    ivec3 lo = max(ivec3(floor(min(a, min(b, c)))), ivec3(0));
    ivec3 hi = min(ivec3(floor(max(a, max(b, c)))), ivec3(u_res - 1));
    float d = dot(n, a);
    const float h = 0.5 * (1.0 + 1e-4); // touching counts, with float slack
    for (int i = lo[u]; i <= hi[u]; i++)
        for (int j = lo[v]; j <= hi[v]; j++) {
            // The plane's coordinate along k over the column's square, at its 4 corners.
            float w0 = 1e30, w1 = -1e30;
            for (int q = 0; q < 4; q++) {
                float x = float(i + (q & 1)), y = float(j + (q >> 1));
                float w = (d - n[u] * x - n[v] * y) / n[k];
                w0 = min(w0, w);
                w1 = max(w1, w);
            }
            int m0 = max(int(floor(w0)) - 1, lo[k]), m1 = min(int(floor(w1)) + 1, hi[k]);
            for (int m = m0; m <= m1; m++) {
                ivec3 p;
                p[u] = i;
                p[v] = j;
                p[k] = m;
                if (overlaps(a, b, c, vec3(p) + 0.5, h)) {
                    vec4 r = imageLoad(u_radiance, p);
                    imageStore(u_radiance, p, vec4(r.rgb, 1.0)); // every writer writes the same
                }
            }
        }
}

// Occlusion voxels (techniques/common/voxels.h): writes 1 into every voxel a triangle touches.
// Exact triangle/box overlap by the separating axis theorem (Akenine-Moller 2001, "Fast 3D
// triangle-box overlap testing": the 3 box normals, the triangle's normal and the 9 edge x box-normal
// axes), against a box dilated by EPS voxel on each side so that float rounding can only add voxels,
// never miss one. Work per triangle: only the voxel columns along the triangle's dominant normal axis
// w inside its bounding box; in each column the plane crosses at most 3 voxels (|n_w| is the largest
// component), so the 13 axes split into the column's 2D test in the (u, v) projection (axes u, v and
// the 3 edge x w), once per column, and the w extent, plane and 6 other edge axes per voxel.
// Triangles with more than LARGE_COLUMNS columns are listed by the first pass (SMALL) and done by a
// second pass (LARGE) with one 64-wide work group per triangle, so one invocation never walks a
// floor's million columns alone. Every writer stores 1: no atomics on the texture (paper, Sec. 5).
#include "gl/bindings.h"
layout(local_size_x = 64) in;

layout(std430, binding = GIB_SSBO_OWN_FIRST + 0) readonly buffer Positions { float positions[]; };
layout(std430, binding = GIB_SSBO_OWN_FIRST + 1) readonly buffer Indices { uint indices[]; };
// work[0..2]: the LARGE pass's indirect dispatch (groups, 1, 1); work[3]: large-triangle count;
// work[4..]: their indices.
layout(std430, binding = GIB_SSBO_OWN_FIRST + 2) buffer Work { uint work[]; };
layout(r8, binding = 0) writeonly uniform image3D u_vox;

layout(location = GIB_LOC_OWN_FIRST + 0) uniform vec3 u_grid_origin;
layout(location = GIB_LOC_OWN_FIRST + 1) uniform float u_inv_voxel;   // res / side
layout(location = GIB_LOC_OWN_FIRST + 2) uniform int u_res;
layout(location = GIB_LOC_OWN_FIRST + 3) uniform uint u_triangle_count;

const float EPS = 1e-3;        // dilation in voxels: float error of voxel coordinates up to 512
const float H = 0.5 + EPS;     // half side of the tested box
const int LARGE_COLUMNS = 64;
const uint MAX_GROUPS = 65535u;

vec3 vertex(uint i)
{
    vec3 p = vec3(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]);
    return (p - u_grid_origin) * u_inv_voxel;
}

// A triangle in voxel units with its coordinates permuted so that w (.z) is its normal's dominant
// axis: p = (u, v, w) = (x_{(d+1)%3}, x_{(d+2)%3}, x_d).
struct Tri {
    vec3 v0, v1, v2, e0, e1, e2, n;
    int d;
    ivec2 lo, hi;   // the columns (u, v) of the bounding box, clamped to the grid
    vec2 w_range;   // the triangle's extent along w
    bool ok;
};

vec3 perm(vec3 p, int d)
{
    return d == 0 ? p.yzx : d == 1 ? p.zxy : p;
}

Tri setup(uint t)
{
    Tri r;
    vec3 a = vertex(indices[3u * t]), b = vertex(indices[3u * t + 1u]), c = vertex(indices[3u * t + 2u]);
    vec3 n = cross(b - a, c - a), an = abs(n);
    r.d = an.x >= an.y && an.x >= an.z ? 0 : an.y >= an.z ? 1 : 2;
    r.v0 = perm(a, r.d); r.v1 = perm(b, r.d); r.v2 = perm(c, r.d);
    r.e0 = r.v1 - r.v0; r.e1 = r.v2 - r.v1; r.e2 = r.v0 - r.v2;
    r.n = perm(n, r.d);
    vec3 mn = min(r.v0, min(r.v1, r.v2)), mx = max(r.v0, max(r.v1, r.v2));
    // Voxel i spans [i, i + 1]: it can touch [mn, mx] when i + 1 + EPS >= mn and i - EPS <= mx.
    r.lo = max(ivec2(ceil(mn.xy - 1.0 - EPS)), ivec2(0));
    r.hi = min(ivec2(floor(mx.xy + EPS)), ivec2(u_res - 1));
    r.w_range = vec2(mn.z, mx.z);
    // Zero-area triangles cover nothing; NaN positions fail the comparison and are skipped too.
    r.ok = abs(r.n.z) > 1e-20 && all(lessThanEqual(r.lo, r.hi)) &&
           mx.z >= -1.0 - EPS && mn.z <= float(u_res) + EPS;
    return r;
}

// Separating-axis test on one 2D axis a: the triangle's projections [t0, t1] against the box
// centred at c (projection dot(c, a), radius H (|a.x| + |a.y|)). True when NOT separated.
bool axis2(vec2 a, vec2 c, float p0, float p1, float p2)
{
    float t0 = min(p0, min(p1, p2)), t1 = max(p0, max(p1, p2));
    float pc = dot(c, a), r = H * (abs(a.x) + abs(a.y));
    return pc - r <= t1 && pc + r >= t0;
}

// Edge e x axis, in the 2D projection (x, y) of a vector: a = (-e.y, e.x) up to sign.
bool edges2(vec2 c, vec2 v0, vec2 v1, vec2 v2, vec2 e0, vec2 e1, vec2 e2)
{
    vec2 a0 = vec2(-e0.y, e0.x), a1 = vec2(-e1.y, e1.x), a2 = vec2(-e2.y, e2.x);
    return axis2(a0, c, dot(v0, a0), dot(v1, a0), dot(v2, a0)) &&
           axis2(a1, c, dot(v0, a1), dot(v1, a1), dot(v2, a1)) &&
           axis2(a2, c, dot(v0, a2), dot(v1, a2), dot(v2, a2));
}

void column(Tri r, ivec2 col)
{
    vec2 c = vec2(col) + 0.5;
    // Axes e_i x w: the triangle's (u, v) projection against the column's square.
    if (!edges2(c, r.v0.xy, r.v1.xy, r.v2.xy, r.e0.xy, r.e1.xy, r.e2.xy))
        return;
    // The plane n.p = n.v0 over the square: w = wc +- dw. A voxel box (centre k + 0.5, half H)
    // meets the plane iff |k + 0.5 - wc| <= H + dw (the normal axis), and the triangle's w extent
    // iff |k + 0.5 - mid| <= H + half extent (the w axis).
    float wc = (dot(r.n, r.v0) - r.n.x * c.x - r.n.y * c.y) / r.n.z;
    float dw = H * (abs(r.n.x) + abs(r.n.y)) / abs(r.n.z);
    float k0 = max(ceil(wc - H - dw - 0.5), ceil(r.w_range.x - H - 0.5));
    float k1 = min(floor(wc + H + dw - 0.5), floor(r.w_range.y + H - 0.5));
    int ka = max(int(k0), 0), kb = min(int(k1), u_res - 1);
    for (int k = ka; k <= kb; k++) {
        vec3 b = vec3(c, float(k) + 0.5);
        // Axes e_i x u and e_i x v: the (v, w) and (w, u) projections against the box's faces.
        if (!edges2(b.yz, r.v0.yz, r.v1.yz, r.v2.yz, r.e0.yz, r.e1.yz, r.e2.yz) ||
            !edges2(b.zx, r.v0.zx, r.v1.zx, r.v2.zx, r.e0.zx, r.e1.zx, r.e2.zx))
            continue;
        ivec3 p;
        p[(r.d + 1) % 3] = col.x;
        p[(r.d + 2) % 3] = col.y;
        p[r.d] = k;
        imageStore(u_vox, p, vec4(1.0));
    }
}

void main()
{
#ifdef SMALL
    uint t = gl_GlobalInvocationID.x;
    if (t >= u_triangle_count)
        return;
    Tri r = setup(t);
    if (!r.ok)
        return;
    ivec2 span = r.hi - r.lo + 1;
    if (span.x * span.y > LARGE_COLUMNS) {
        uint i = atomicAdd(work[3], 1u);
        work[4u + i] = t;
        atomicMax(work[0], min(i + 1u, MAX_GROUPS));
        return;
    }
    for (int v = r.lo.y; v <= r.hi.y; v++)
        for (int u = r.lo.x; u <= r.hi.x; u++)
            column(r, ivec2(u, v));
#else
    // LARGE: work groups stride over the listed triangles, invocations over their columns.
    uint count = work[3];
    for (uint i = gl_WorkGroupID.x; i < count; i += gl_NumWorkGroups.x) {
        Tri r = setup(work[4u + i]);
        ivec2 span = r.hi - r.lo + 1;
        int columns = span.x * span.y;
        for (int j = int(gl_LocalInvocationIndex); j < columns; j += int(gl_WorkGroupSize.x))
            column(r, r.lo + ivec2(j % span.x, j / span.x));
    }
#endif
}

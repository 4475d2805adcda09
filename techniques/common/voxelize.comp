// Occlusion voxels (techniques/common/voxels.h): writes 1 into every voxel a triangle touches.
// Exact triangle/box overlap by the separating axis theorem (Akenine-Moller 2001, "Fast 3D
// triangle-box overlap testing": the 3 box normals, the triangle's normal and the 9 edge x
// box-normal axes), against a box dilated by EPS voxel on each side so that float rounding can only
// add voxels, never miss one. Work per triangle: only the voxel columns along the triangle's
// dominant normal axis w inside its bounding box; in each column the plane crosses at most 4 voxels
// (|n_w| is the largest component: the plane rises at most 2 voxels across a column), so the 13
// axes split into the column's 2D test in the (u, v) projection (axes u, v and the 3 edge x w),
// once per column, and the w extent, the plane and the 6 other edge axes per voxel.
// Alpha-masked materials (cut-outs: Sponza's plants and chains), as the G-buffer and the light
// views discard mask < 0.5: a voxel the triangle touches is set when the mask, filtered over one
// voxel's footprint on the triangle (the mip level of a voxel side in texels) at the point of the
// triangle nearest the voxel's centre, is at least 0.5, i.e. when most of the surface there is
// solid. Not conservative for these triangles only: a voxel with a thin solid part stays empty.
// Triangles with more than LARGE_COLUMNS columns are listed by the first pass (SMALL) and done by a
// second pass (LARGE) with one 64-wide work group per triangle, so one invocation never walks a
// floor's million columns alone. Every writer stores 1: no atomics on the texture (paper, Sec. 5).
#include "common/common_slots.h"
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_1D) in;

layout(std430, binding = GIB_VOXELIZE_SSBO_POSITIONS) readonly buffer Positions {
    float positions[];
};
layout(std430, binding = GIB_VOXELIZE_SSBO_INDICES) readonly buffer Indices { uint indices[]; };
// work[0..2]: the LARGE pass's indirect dispatch (groups, 1, 1); work[3]: large-triangle count;
// work[4 .. 4 + T): their indices; work[4 + T + t]: triangle t's alpha mask, 0 for none, else
// its id (1 + an index into gib_voxels.mask_tex; static, written at creation).
layout(std430, binding = GIB_VOXELIZE_SSBO_WORK) buffer Work { uint work[]; };
layout(std430, binding = GIB_VOXELIZE_SSBO_UVS) readonly buffer Uvs { float uvs[]; };
layout(r8, binding = GIB_VOXELIZE_IMAGE_VOXELS) writeonly uniform image3D u_vox;
#ifdef ALPHA
// The masks of this pass: scene textures u_mask_first .. u_mask_first + 5 (a pass per 6 masks).
layout(binding = GIB_VOXELIZE_UNIT_MASK_FIRST + 0) uniform sampler2D u_mask0;
layout(binding = GIB_VOXELIZE_UNIT_MASK_FIRST + 1) uniform sampler2D u_mask1;
layout(binding = GIB_VOXELIZE_UNIT_MASK_FIRST + 2) uniform sampler2D u_mask2;
layout(binding = GIB_VOXELIZE_UNIT_MASK_FIRST + 3) uniform sampler2D u_mask3;
layout(binding = GIB_VOXELIZE_UNIT_MASK_FIRST + 4) uniform sampler2D u_mask4;
layout(binding = GIB_VOXELIZE_UNIT_MASK_FIRST + 5) uniform sampler2D u_mask5;
#endif

layout(location = GIB_VOXELIZE_LOC_ORIGIN) uniform vec3 u_grid_origin;
layout(location = GIB_VOXELIZE_LOC_INV_VOXEL) uniform float u_inv_voxel;   // res / side
layout(location = GIB_VOXELIZE_LOC_RES) uniform int u_res;
layout(location = GIB_VOXELIZE_LOC_TRIANGLES) uniform uint u_triangle_count;
layout(location = GIB_VOXELIZE_LOC_MASK_FIRST) uniform int u_mask_first;  // ALPHA

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
    int slot;       // -1 unmasked, else the mask's sampler in this pass
    vec2 uv0, uv1, uv2;
    float lod;      // alpha-masked: the mask's mip level of one voxel side
    bool ok;
};

#ifdef ALPHA
vec4 mask_lookup(int slot, vec2 uv, float lod)
{
    switch (slot) {
    case 0: return textureLod(u_mask0, uv, lod);
    case 1: return textureLod(u_mask1, uv, lod);
    case 2: return textureLod(u_mask2, uv, lod);
    case 3: return textureLod(u_mask3, uv, lod);
    case 4: return textureLod(u_mask4, uv, lod);
    default: return textureLod(u_mask5, uv, lod);
    }
}

ivec2 mask_size(int slot)
{
    switch (slot) {
    case 0: return textureSize(u_mask0, 0);
    case 1: return textureSize(u_mask1, 0);
    case 2: return textureSize(u_mask2, 0);
    case 3: return textureSize(u_mask3, 0);
    case 4: return textureSize(u_mask4, 0);
    default: return textureSize(u_mask5, 0);
    }
}

#endif

// Whether triangle t belongs to this pass (without ALPHA: the triangles without a mask; with:
// those whose mask is bound), and its mask's sampler (-1 for none).
bool in_pass(uint t, out int slot)
{
    int m = int(work[4u + u_triangle_count + t]);
#ifdef ALPHA
    slot = m - 1 - u_mask_first;
    return m != 0 && slot >= 0 && slot < 6;
#else
    slot = -1;
    return m == 0;
#endif
}

vec3 perm(vec3 p, int d)
{
    return d == 0 ? p.yzx : d == 1 ? p.zxy : p;
}

Tri setup(uint t, int slot)
{
    Tri r;
    r.slot = slot;
    uint i0 = indices[3u * t], i1 = indices[3u * t + 1u], i2 = indices[3u * t + 2u];
    vec3 a = vertex(i0), b = vertex(i1), c = vertex(i2);
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
#ifdef ALPHA
    if (slot >= 0) {
        r.uv0 = vec2(uvs[2u * i0], uvs[2u * i0 + 1u]);
        r.uv1 = vec2(uvs[2u * i1], uvs[2u * i1 + 1u]);
        r.uv2 = vec2(uvs[2u * i2], uvs[2u * i2 + 1u]);
        vec2 f = r.uv1 - r.uv0, g = r.uv2 - r.uv0;
        float uv_area = abs(f.x * g.y - f.y * g.x), area = length(n);  // both doubled
        vec2 size = vec2(mask_size(slot));
        r.lod = 0.5 * log2(max(uv_area * size.x * size.y / max(area, 1e-30), 1.0));
    }
#endif
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

#ifdef ALPHA
// Alpha-masked triangles: the mask over the voxel's footprint at the triangle's point nearest the
// voxel centre b (projected on the plane, barycentrics clamped to the triangle).
bool solid(Tri r, vec3 b)
{
    vec3 q = b - r.n * (dot(r.n, b - r.v0) / dot(r.n, r.n));
    vec3 f = r.v1 - r.v0, g = r.v2 - r.v0, w = q - r.v0;
    float d00 = dot(f, f), d01 = dot(f, g), d11 = dot(g, g), d20 = dot(w, f), d21 = dot(w, g);
    float den = d00 * d11 - d01 * d01;
    vec3 l = vec3(0.0, (d11 * d20 - d01 * d21) / den, (d00 * d21 - d01 * d20) / den);
    l.x = 1.0 - l.y - l.z;
    l = max(l, 0.0);
    l /= l.x + l.y + l.z;
    vec2 uv = l.x * r.uv0 + l.y * r.uv1 + l.z * r.uv2;
    return mask_lookup(r.slot, uv, r.lod).r >= 0.5;
}
#endif

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
#ifdef ALPHA
        if (!solid(r, b))
            continue;
#endif
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
    int slot;
    if (t >= u_triangle_count || !in_pass(t, slot))
        return;
    Tri r = setup(t, slot);
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
        uint t = work[4u + i];
        int slot;
        in_pass(t, slot);
        Tri r = setup(t, slot);
        ivec2 span = r.hi - r.lo + 1;
        int columns = span.x * span.y;
        for (int j = int(gl_LocalInvocationIndex); j < columns; j += int(gl_WorkGroupSize.x))
            column(r, r.lo + ivec2(j % span.x, j / span.x));
    }
#endif
}

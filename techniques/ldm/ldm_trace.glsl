// The trace of Aalund et al. 2015, Sec. 3.1, in orthographic LDM i:
//   find map (the caller picks i: the LDM whose direction is +-d), find pixel (re-projection of x
//   into the map), find depth value (walk the pre-sorted list to z_x), compute intersection (the
//   neighbouring node: next for +v, previous for -v — "a single LDM can be queried both in the v and
//   -v direction").
// Returns the distance from x to the first surface along sgn*v beyond eps, or -1 when nothing is hit
// (or x projects outside the map). The walk stops at the first hit: the lists are sorted.
#include "ldm/ldm_common.glsl"
layout(std430, binding = GIB_SSBO_LDM_HEADS) readonly buffer Heads { uint heads[]; };
layout(std430, binding = GIB_SSBO_LDM_NODES) readonly buffer Nodes { uvec2 nodes[]; };

float ldm_trace(int i, vec3 x, float sgn, float eps)
{
    LdmInfo L = ldm_info[i];
    vec3 v = L.dir_extent.xyz;
    float e = L.dir_extent.w;
    int res = int(L.origin_res.w);
    vec3 t, b;
    ortho_basis(v, t, b);
    vec3 q = x - L.origin_res.xyz;
    ivec2 px = ivec2(floor((vec2(dot(q, t), dot(q, b)) / e * 0.5 + 0.5) * float(res)));
    if (any(lessThan(px, ivec2(0))) || any(greaterThanEqual(px, ivec2(res))))
        return -1.0;
    float z = dot(q, v);
    uint cur = heads[L.offsets.x + uint(px.y * res + px.x)];
    if (sgn > 0.0) {
        while (cur != LDM_END) {
            float d = uintBitsToFloat(nodes[cur].x);
            if (d > z + eps)
                return d - z;
            cur = nodes[cur].y;
        }
        return -1.0;
    }
    float hit = -1.0;
    while (cur != LDM_END) {
        float d = uintBitsToFloat(nodes[cur].x);
        if (d >= z - eps)
            break;
        hit = z - d;
        cur = nodes[cur].y;
    }
    return hit;
}

// Texel size of LDM i in world units.
float ldm_texel(int i)
{
    return 2.0 * ldm_info[i].dir_extent.w / ldm_info[i].origin_res.w;
}

// Depth tolerance for leaving a surface with normal n along +-v. The surface's own fragment in x's
// LDM pixel was rasterised at the pixel centre, at most ~0.71 texel sideways from x, so it lies
// within 0.71 texel * tan(theta) of x in depth (theta between n and v); a quarter texel more covers
// rasterisation rounding. Capped (at tan = 8) like a shadow-map bias: grazing samples weigh cos.
float ldm_eps(float texel, float abs_cos)
{
    float c = clamp(abs_cos, 1e-3, 1.0);
    return texel * (0.25 + 0.71 * min(sqrt(1.0 - c * c) / c, 8.0));
}

// Algorithm 3.5 at one fragment of a photon's line: walk the pixel's list for a surface the ray
// meets here. The thesis compares depths within an epsilon; we take the epsilon from the geometry
// instead of a scene-dependent constant: the ray crosses the node's tangent plane (the node's
// depth and normal) at t, and that crossing counts when it projects within u_slack pixels of this
// pixel's footprint (a 1-pixel line has one fragment per step of its major axis, so a crossing
// near this pixel may lie up to a pixel aside) and beyond the self-intersection distance t_min.
// The first hit is kept: atomicMin over the photon's t (positive floats order as their bits), in
// place of the thesis' row of hits per line.
#include "ispm_caustics/caustics.glsl"
#include "ispm_caustics/list_lookup.glsl"
layout(std430, binding = ISPM_SSBO_PHOTONS) readonly buffer Photons { Photon photons[]; };
layout(std430, binding = ISPM_SSBO_FIRST_HIT) buffer FirstHit { uint first_t[]; };
layout(location = ISPM_TRACE_LOC_TMAX) uniform float u_tmax;
layout(location = ISPM_TRACE_LOC_SLACK) uniform float u_slack;
flat in int v_photon;
void main()
{
    Photon p = photons[v_photon];
    ivec2 px = ivec2(gl_FragCoord.xy);
    float best = u_tmax;
    uint idx = heads[px.y * u_res + px.x];
    for (int i = 0; i < max_walk(); i++) {
        if (idx == LIST_END)
            break;
        Node nd = nodes[idx];
        idx = nd.next;
        vec3 n;
        float t = node_hit(px, nd, p.origin.xyz, p.dir.xyz, n);
        if (t > p.dir.w && t < best && pixel_distance(px, p.origin.xyz + t * p.dir.xyz) <= 0.5 + u_slack)
            best = t;
    }
    if (best < u_tmax)
        atomicMin(first_t[v_photon], floatBitsToUint(best));
}

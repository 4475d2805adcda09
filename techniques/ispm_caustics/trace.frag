// Algorithm 3.5 at one fragment of a photon's line: walk the pixel's list for a surface the ray
// meets here. The thesis compares depths within an epsilon; we take the epsilon from the geometry
// instead of a scene-dependent constant: the ray crosses the node's tangent plane (the node's
// depth and normal) at t, and that crossing counts when
// - it projects within u_slack pixels of this pixel's footprint (a 1-pixel line has one fragment
//   per step of its major axis, so a crossing near this pixel may lie up to a pixel aside);
// - its depth lies within u_depth pixel footprints of the node's (the thesis' depth epsilon, in
//   units of the pixel's own width at that depth). A node stands for its surface over one pixel,
//   and the plane alone stands for it over the whole pixel frustum: a face seen nearly edge-on
//   (the sides of Sponza's arcades, along the view) spans that frustum over metres of depth, and
//   photons passing far from the face would stop there. The bound takes a face to reach at most
//   u_depth footprints from its node: 4 holds a face up to ~83 degrees from the view over its
//   whole pixel (ring_occluded's slab, ~8 degrees above the camera's rays, needs 3.5, and leaks
//   its caustic below that); smaller values lose more of the edge-on faces' photons;
// - it lies beyond the self-intersection distance t_min.
// The first hit is kept: atomicMin over the photon's t (positive floats order as their bits), in
// place of the thesis' row of hits per line.
#include "ispm_caustics/caustics.glsl"
#include "ispm_caustics/list_lookup.glsl"
layout(std430, binding = ISPM_SSBO_PHOTONS) readonly buffer Photons { Photon photons[]; };
layout(std430, binding = ISPM_SSBO_FIRST_HIT) buffer FirstHit { uint first_t[]; };
layout(location = ISPM_TRACE_LOC_TMAX) uniform float u_tmax;
layout(location = ISPM_TRACE_LOC_SLACK) uniform float u_slack;
layout(location = ISPM_TRACE_LOC_DEPTH) uniform float u_depth; // pixel footprints (1e30: no bound)
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
        vec3 q = p.origin.xyz + t * p.dir.xyz;
        if (t > p.dir.w && t < best && pixel_distance(px, q) <= 0.5 + u_slack &&
            abs(view_depth(q) - abs(nd.depth)) <= u_depth * pixel_footprint(abs(nd.depth)))
            best = t;
    }
    if (best < u_tmax)
        atomicMin(first_t[v_photon], floatBitsToUint(best));
}

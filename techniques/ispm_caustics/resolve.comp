// After the trace: each photon's second hit (its first t), the receiver's normal from the list
// nodes there (the node of the 3x3 pixels around the hit whose tangent plane passes closest to
// it), and the splat radius (Sec. 3.3.2.3): h = C sqrt(A), A the area the photon stands for on the
// receiver. The thesis' h = C0 sqrt(A_scene / N) / sqrt(cos(theta) / d^2) mixes units (area x
// length); we carry the photon's own footprint along its unfolded path instead: the light-view
// solid angle it stands for times the path length squared (a point light seen in a plane mirror
// is a point light at that distance), over cos(theta) at the receiver; orthographic (directional)
// footprints keep their area. cos(theta) is clamped at 0.1 (grazing), h at a tenth of the scene's
// diagonal; both in the scene's units through the footprint.
#include "ispm_caustics/caustics.glsl"
#include "ispm_caustics/list_lookup.glsl"
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_1D) in;
layout(std430, binding = ISPM_SSBO_PHOTONS) buffer Photons { Photon photons[]; };
layout(std430, binding = ISPM_SSBO_FIRST_HIT) readonly buffer FirstHit { uint first_t[]; };
layout(std430, binding = ISPM_SSBO_COMMAND) readonly buffer Command { uint cmd[8]; };
layout(location = ISPM_TRACE_LOC_TMAX) uniform float u_tmax;
layout(location = ISPM_TRACE_LOC_CAPACITY) uniform uint u_capacity;
layout(location = ISPM_RESOLVE_LOC_SPLAT_SCALE) uniform float u_splat_scale;
layout(location = ISPM_RESOLVE_LOC_HMAX) uniform float u_hmax;
void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= min(cmd[1], u_capacity))
        return;
    Photon p = photons[i];
    uint tb = first_t[i];
    photons[i].hit = vec4(0.0);
    if (tb == 0xffffffffu)
        return;
    float t = uintBitsToFloat(tb);
    vec3 x = p.origin.xyz + t * p.dir.xyz;
    vec4 c = u_view_proj * vec4(x - u_origin, 1.0);
    if (c.w <= 0.0)
        return;
    ivec2 q = ivec2(floor((c.xy / c.w * 0.5 + 0.5) * float(u_res)));
    float best = 1e30;
    vec3 nbest = -p.dir.xyz;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            ivec2 px = q + ivec2(dx, dy);
            if (any(lessThan(px, ivec2(0))) || any(greaterThanEqual(px, ivec2(u_res))))
                continue;
            uint idx = heads[px.y * u_res + px.x];
            for (int k = 0; k < max_walk() && idx != LIST_END; k++) {
                Node nd = nodes[idx];
                idx = nd.next;
                vec3 n;
                if (node_hit(px, nd, p.origin.xyz, p.dir.xyz, n) < 0.0)
                    continue;
                float e = abs(dot(x - node_point(px, nd.depth), n));
                if (e < best) {
                    best = e;
                    nbest = n;
                }
            }
        }
    vec3 nf = dot(nbest, p.dir.xyz) < 0.0 ? nbest : -nbest;
    float cosi = dot(nf, -p.dir.xyz);
    float cc = max(cosi, 0.1);
    float area = p.flux.w >= 0.0 ? p.flux.w * (p.origin.w + t) * (p.origin.w + t) / cc
                                 : -p.flux.w / cc;
    float h = min(u_splat_scale * sqrt(area), u_hmax);
    photons[i].hit = vec4(x, h);
    photons[i].hit_n = vec4(nf, cosi);
}

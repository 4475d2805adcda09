// LDM construction (Aalund et al. 2015, Sec. 3; [LHL14]): every fragment, front or back face, is
// inserted into its pixel's list in depth order, so the lists are pre-sorted when the pass ends.
// Lock-free insertion: allocate a node with atomicAdd, find the predecessor by walking the sorted
// list, link with atomicCompSwap on the predecessor's `next`; if another fragment linked there first,
// walk on from the same predecessor.
#include "common/scene.glsl"
#include "ldm/ldm_common.glsl"
layout(std430, binding = GIB_SSBO_LDM_HEADS) coherent buffer Heads { uint heads[]; };
// x depth bits, y next
layout(std430, binding = GIB_SSBO_LDM_NODES) coherent buffer Nodes { uvec2 nodes[]; };
layout(std430, binding = GIB_SSBO_LDM_STATUS) buffer Status { uint overflow; uint contention; };
layout(std430, binding = GIB_SSBO_LDM_COUNTERS) buffer Counters { uint counters[]; };
layout(location = GIB_LOC_MATERIAL) uniform int u_material;
layout(binding = GIB_UNIT_ALPHA_TEX) uniform sampler2D u_alpha_tex;
in vec3 v_position;
in vec2 v_uv;
flat in int v_ldm;
void main()
{
    Material m = materials[u_material];
    if (m.flags.z != 0 && texture(u_alpha_tex, vec2(v_uv.x, 1.0 - v_uv.y)).r < 0.5)
        discard;
    LdmInfo L = ldm_info[v_ldm];
    float z = dot(v_position - L.origin_res.xyz, L.dir_extent.xyz);
    uint k = atomicAdd(counters[v_ldm], 1u);
    if (k >= L.offsets.z) {
        atomicAdd(overflow, 1u);
        return;
    }
    uint node = L.offsets.y + k;
    ivec2 px = ivec2(gl_FragCoord.xy);
    int res = int(L.origin_res.w);
    uint head = L.offsets.x + uint(px.y * res + px.x);
    nodes[node].x = floatBitsToUint(z);
    uint prev = LDM_END; // LDM_END as predecessor means "the head"
    for (int attempt = 0; attempt < 1024; attempt++) {
        uint cur = prev == LDM_END ? heads[head] : nodes[prev].y;
        while (cur != LDM_END && uintBitsToFloat(nodes[cur].x) < z) {
            prev = cur;
            cur = nodes[cur].y;
        }
        nodes[node].y = cur;
        memoryBarrierBuffer();
        uint seen = prev == LDM_END ? atomicCompSwap(heads[head], cur, node)
                                    : atomicCompSwap(nodes[prev].y, cur, node);
        if (seen == cur)
            return;
    }
    atomicAdd(contention, 1u);
}

// Algorithm 3.4: per-pixel linked lists of the scene seen from the camera at the ray resolution
// (Sec. 3.3.2.1; Ch. 4: the lists have the photon rays' resolution), every fragment kept (no depth
// test, no culling). The insertion takes a node with an atomic counter and swaps it in as the
// pixel's head (atomicExchange: lines 4-7 of the algorithm made safe between fragments); a node
// past the pool's capacity is not written and counted, and the run says `overflow`. The longest
// list's length bounds the walks of the trace.
#include "common/scene.glsl"
#include "ispm_caustics/caustics.glsl"
layout(std430, binding = ISPM_SSBO_HEADS) coherent buffer Heads { uint heads[]; };
layout(std430, binding = ISPM_SSBO_NODES) writeonly buffer Nodes { Node nodes[]; };
layout(std430, binding = ISPM_SSBO_STATUS) buffer Status {
    uint list_count, list_overflow, photon_overflow, list_longest;
};
layout(std430, binding = ISPM_SSBO_COUNTS) buffer Counts { uint counts[]; };
layout(location = GIB_LOC_MATERIAL) uniform int u_material;
layout(location = GIB_LOC_ORIGIN) uniform vec3 u_origin; // the eye
layout(location = ISPM_LOC_FORWARD) uniform vec3 u_forward;
layout(location = ISPM_LOC_RES) uniform int u_res;
layout(location = ISPM_LIST_LOC_CAPACITY) uniform uint u_capacity;
layout(binding = GIB_UNIT_ALPHA_TEX) uniform sampler2D u_alpha_tex;
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
void main()
{
    Material m = materials[u_material];
    if (m.flags.z != 0 && texture(u_alpha_tex, vec2(v_uv.x, 1.0 - v_uv.y)).r < 0.5)
        discard;
    uint k = atomicAdd(list_count, 1u);
    if (k >= u_capacity) {
        atomicAdd(list_overflow, 1u);
        return;
    }
    float z = dot(v_position - u_origin, u_forward);
    ivec2 px = ivec2(gl_FragCoord.xy);
    nodes[k].depth = m.flags.y != 0 ? z : -z;
    nodes[k].normal = oct_encode(normalize(v_normal));
    uint pixel = uint(px.y * u_res + px.x);
    nodes[k].next = atomicExchange(heads[pixel], k);
    atomicMax(list_longest, atomicAdd(counts[pixel], 1u) + 1u);
}

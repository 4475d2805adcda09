// The 4 peeled layers (peel.frag) as lists of at most 4 nodes, nearest first, so the trace
// (trace.frag, resolve.comp) reads them as it reads Algorithm 3.4's lists.
#include "ispm_caustics/caustics.glsl"
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_2D, local_size_y = GIB_GROUP_2D) in;
layout(std430, binding = ISPM_SSBO_HEADS) writeonly buffer Heads { uint heads[]; };
layout(std430, binding = ISPM_SSBO_NODES) writeonly buffer Nodes { Node nodes[]; };
layout(std430, binding = ISPM_SSBO_STATUS) buffer Status {
    uint list_count, list_overflow, photon_overflow, list_longest;
};
layout(binding = ISPM_UNIT_LAYER_FIRST + 0) uniform sampler2D u_layer0;
layout(binding = ISPM_UNIT_LAYER_FIRST + 1) uniform sampler2D u_layer1;
layout(binding = ISPM_UNIT_LAYER_FIRST + 2) uniform sampler2D u_layer2;
layout(binding = ISPM_UNIT_LAYER_FIRST + 3) uniform sampler2D u_layer3;
layout(location = ISPM_LOC_RES) uniform int u_res;
void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_res || px.y >= u_res)
        return;
    uint pixel = uint(px.y * u_res + px.x), pixels = uint(u_res * u_res);
    vec4 l[4] = vec4[4](texelFetch(u_layer0, px, 0), texelFetch(u_layer1, px, 0),
                        texelFetch(u_layer2, px, 0), texelFetch(u_layer3, px, 0));
    uint next = LIST_END;
    uint count = 0u;
    for (int k = 3; k >= 0; k--) {
        if (l[k].w < 0.5)
            continue;
        uint node = uint(k) * pixels + pixel;
        nodes[node].depth = l[k].x;
        nodes[node].normal = floatBitsToUint(l[k].y);
        nodes[node].next = next;
        next = node;
        count++;
    }
    heads[pixel] = next;
    atomicAdd(list_count, count);
    atomicMax(list_longest, count);
}

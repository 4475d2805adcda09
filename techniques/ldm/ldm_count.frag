// Counting pass (once, at create): fragments per LDM, to size the node buffers exactly.
#include "common/scene.glsl"
#include "ldm/ldm_common.glsl"
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
    atomicAdd(counters[v_ldm], 1u);
}

// Shared by every LDM shader: the per-LDM description; the map's basis is ortho_basis(v).
#include "common/basis.glsl"
#include "ldm/ldm_slots.h"
struct LdmInfo {
    vec4 dir_extent;  // xyz view direction v (depth grows along v), w half-width of the map
    vec4 origin_res;  // xyz origin of the map's plane (centre - v * radius), w resolution
    uvec4 offsets;    // x head base (in its page), y node base (in its page), z node capacity, w page
};
layout(std430, binding = GIB_SSBO_LDM_INFO) readonly buffer LdmInfos { LdmInfo ldm_info[]; };
const uint LDM_END = 0xffffffffu;

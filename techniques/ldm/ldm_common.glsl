// Shared by every LDM shader: the per-LDM description and the basis of an orthographic LDM.
struct LdmInfo {
    vec4 dir_extent;  // xyz view direction v (depth grows along v), w half-width of the map
    vec4 origin_res;  // xyz origin of the map's plane (centre - v * radius), w resolution
    uvec4 offsets;    // x head base (in its page), y node base (in its page), z node capacity, w page
};
layout(std430, binding = 3) readonly buffer LdmInfos { LdmInfo ldm_info[]; };
const uint LDM_END = 0xffffffffu;

// The same basis as ldm.c's ldm_basis(): independent of anything but v.
void ldm_basis(vec3 v, out vec3 t, out vec3 b)
{
    vec3 up = abs(v.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    t = normalize(cross(up, v));
    b = cross(v, t);
}

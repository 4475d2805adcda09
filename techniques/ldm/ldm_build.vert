// LDM construction: each instance renders the scene orthographically along one LDM direction.
#include "ldm/ldm_common.glsl"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = LDM_LOC_FIRST_LDM) uniform int u_first_ldm;
out vec3 v_position;
out vec2 v_uv;
flat out int v_ldm;
void main()
{
    int i = u_first_ldm + gl_InstanceID;
    LdmInfo L = ldm_info[i];
    vec3 q = a_position - L.origin_res.xyz;
    float e = L.dir_extent.w;
    vec3 t, b;
    ortho_basis(L.dir_extent.xyz, t, b);
    // Orthographic: x, y over [-e, e] to clip space; depth along v over [0, 2e].
    gl_Position = vec4(dot(q, t) / e, dot(q, b) / e, dot(q, L.dir_extent.xyz) / e - 1.0, 1.0);
    v_position = a_position;
    v_uv = a_uv;
    v_ldm = i;
}

#include "common/scene.glsl"
// Shadow maps store distances, not window depth, so the lookup compares world-space lengths:
// the distance to the light (point and spot lights, cube maps) or the depth along the light's
// direction from a plane behind the scene (directional lights).
layout(location = 0) uniform int u_material;
layout(location = 2) uniform vec3 u_light_pos;   // point/spot: light position; directional: plane origin
layout(location = 3) uniform vec3 u_light_dir;   // directional: travel direction
layout(location = 4) uniform int u_directional;
layout(binding = 1) uniform sampler2D u_alpha_tex;
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
layout(location = 0) out float o_distance;
void main()
{
    Material m = materials[u_material];
    if (m.flags.z != 0 && texture(u_alpha_tex, vec2(v_uv.x, 1.0 - v_uv.y)).r < 0.5)
        discard;
    o_distance = u_directional != 0 ? dot(v_position - u_light_pos, u_light_dir)
                                    : length(v_position - u_light_pos);
}

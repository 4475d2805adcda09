#include "common/scene.glsl"
#include "common/common_slots.h"
// G-buffer: world position, viewer-facing shading normal, albedo (rho_d x texture), specular.
// The path tracer makes the same choices at its primary hit (reference/): two-sided materials flip
// the normal toward the viewer; one-sided materials seen from behind reflect nothing.
layout(location = GIB_LOC_MATERIAL) uniform int u_material;
layout(location = GIB_GBUFFER_LOC_EYE) uniform vec3 u_eye;
layout(binding = GIB_UNIT_ALBEDO_TEX) uniform sampler2D u_albedo_tex;
layout(binding = GIB_UNIT_ALPHA_TEX) uniform sampler2D u_alpha_tex;
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
layout(location = 0) out vec4 o_position; // xyz, w = 1 where a surface was hit
layout(location = 1) out vec4 o_normal;   // xyz, w = material index
layout(location = 2) out vec4 o_albedo;   // rgb, w = spec type
layout(location = 3) out vec4 o_specular; // rgb rho_s, w = Phong n
void main()
{
    Material m = materials[u_material];
    // Texture rows are stored top first (scenes/scene.h), OBJ's v runs bottom up.
    vec2 st = vec2(v_uv.x, 1.0 - v_uv.y);
    if (m.flags.z != 0 && texture(u_alpha_tex, st).r < 0.5)
        discard;
    vec3 n = normalize(v_normal);
    vec3 wo = normalize(u_eye - v_position);
    bool back = dot(n, wo) < 0.0;
    if (back && m.flags.y != 0)
        n = -n;
    vec3 albedo = m.albedo.rgb;
    if (m.albedo.w > 0.5)
        albedo *= texture(u_albedo_tex, st).rgb;
    vec3 spec = m.specular.rgb;
    if (back && m.flags.y == 0) {
        albedo = vec3(0.0);
        spec = vec3(0.0);
    }
    o_position = vec4(v_position, 1.0);
    o_normal = vec4(n, float(u_material));
    o_albedo = vec4(albedo, float(m.flags.x));
    o_specular = vec4(spec, m.specular.w);
}

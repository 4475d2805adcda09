#include "common/scene.glsl"
#include "common/shadow_lookup.glsl"
#include "common/common_slots.h"
// Direct light (L D E and L S E) from every light of the scene, with PCF shadow maps, evaluated on
// the G-buffer: the same BRDF and light falloff as the reference's `direct` estimator.
layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position;
layout(binding = GIB_UNIT_GBUF_NORMAL) uniform sampler2D g_normal;
layout(binding = GIB_UNIT_GBUF_ALBEDO) uniform sampler2D g_albedo;
layout(binding = GIB_UNIT_GBUF_SPECULAR) uniform sampler2D g_specular;
layout(location = GIB_DIRECT_LOC_EYE) uniform vec3 u_eye;
layout(location = GIB_DIRECT_LOC_LIGHT_COUNT) uniform int u_light_count;
in vec2 v_texcoord;
layout(location = 0) out vec4 o_color;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(g_position, px, 0);
    if (pos.w < 0.5) {
        o_color = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    vec3 n = texelFetch(g_normal, px, 0).xyz;
    vec4 alb = texelFetch(g_albedo, px, 0);
    vec4 spec = texelFetch(g_specular, px, 0);
    vec3 wo = normalize(u_eye - pos.xyz);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < u_light_count; i++) {
        vec3 wi;
        float dist;
        vec3 E = light_eval(lights[i], pos.xyz, wi, dist);
        float cosi = dot(n, wi);
        if (cosi <= 0.0 || max(E.r, max(E.g, E.b)) <= 0.0)
            continue;
        float v = shadow_visibility(i, pos.xyz, n);
        sum += brdf(alb.rgb, spec, int(alb.w + 0.5), n, wo, wi) * E * (cosi * v);
    }
    o_color = vec4(sum, 1.0);
}

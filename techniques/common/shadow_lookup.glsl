// Shadow-map lookup with percentage-closer filtering, shared by every technique that needs direct
// visibility of the scene's lights (techniques/common/shadow_map.c builds the maps).
// Point and spot lights: one cube map per light in a cube-map array (layer = light's slot).
// Directional lights: one orthographic map per light in a 2D array.
#include "common/basis.glsl"
layout(binding = 4) uniform samplerCubeArray u_shadow_cube;
layout(binding = 5) uniform sampler2DArray u_shadow_ortho;
layout(location = 20) uniform int u_shadow_res;
layout(location = 21) uniform int u_pcf_radius;     // (2r+1)^2 taps
layout(location = 22) uniform float u_normal_offset; // in texels
layout(std430, binding = 2) readonly buffer ShadowSlots { vec4 shadow_slots[]; };
// shadow_slots[2i]: x = slot in its array, y = ortho half-width (world units);
// shadow_slots[2i+1]: xyz = origin of the ortho map's plane (directional lights). The ortho view basis
// is rebuilt from the light direction by ortho_basis(), as on the C side.

// Depth tolerance for a map of texel size `texel` seen at incidence cosine `cosi`: one texel, plus
// the depth a surface tilted by theta spans across a texel (texel * tan theta, capped at 8 texels
// so that grazing surfaces do not lose their contact shadows entirely).
float shadow_bias(float texel, float cosi)
{
    float c = clamp(cosi, 1e-3, 1.0);
    return texel * (1.0 + min(sqrt(1.0 - c * c) / c, 8.0));
}

// Visibility in [0,1] of light i from the surface point p with (viewer-facing) normal n.
float shadow_visibility(int i, vec3 p, vec3 n)
{
    Light l = lights[i];
    int type = int(l.position_type.w + 0.5);
    float slot = shadow_slots[2 * i].x;
    float taps = 0.0, lit = 0.0;
    if (type == 2) {
        vec3 d = l.direction_exponent.xyz;
        float extent = shadow_slots[2 * i].y;
        float texel = 2.0 * extent / float(u_shadow_res);
        vec3 q = p + n * (u_normal_offset * texel);
        vec3 t, b;
        ortho_basis(d, t, b);
        vec3 origin = shadow_slots[2 * i + 1].xyz;
        vec2 uv = vec2(dot(q - origin, t), dot(q - origin, b)) / (2.0 * extent) + 0.5;
        float depth = dot(q - origin, d);
        float bias = shadow_bias(texel, dot(n, -d));
        for (int y = -u_pcf_radius; y <= u_pcf_radius; y++)
            for (int x = -u_pcf_radius; x <= u_pcf_radius; x++) {
                vec2 o = vec2(x, y) / float(u_shadow_res);
                float stored = texture(u_shadow_ortho, vec3(uv + o, slot)).r;
                lit += stored + bias >= depth ? 1.0 : 0.0;
                taps += 1.0;
            }
        return lit / taps;
    }
    vec3 L0 = p - l.position_type.xyz;
    // A cube face spans 90 degrees over u_shadow_res texels: a texel at distance r is ~2r/res wide.
    float texel = 2.0 * length(L0) / float(u_shadow_res);
    vec3 q = p + n * (u_normal_offset * texel);
    vec3 L = q - l.position_type.xyz;
    float dist = length(L);
    float bias = shadow_bias(texel, dot(n, -L / dist));
    vec3 t, b;
    ortho_basis(L / dist, t, b);
    for (int y = -u_pcf_radius; y <= u_pcf_radius; y++)
        for (int x = -u_pcf_radius; x <= u_pcf_radius; x++) {
            vec3 dir = L + (float(x) * t + float(y) * b) * texel;
            float stored = texture(u_shadow_cube, vec4(dir, slot)).r;
            lit += stored + bias >= dist ? 1.0 : 0.0;
            taps += 1.0;
        }
    return lit / taps;
}

// Shadow-map lookup with percentage-closer filtering, shared by every technique that needs direct
// visibility of the scene's lights: the depth of the light views (techniques/common/light_view.*),
// distances from point and spot lights, depths along a directional light from the plane behind
// the scene.
#include "common/basis.glsl"
#include "common/light_view.glsl"
layout(binding = GIB_UNIT_LV_DEPTH) uniform sampler2DArray u_lv_depth;
layout(location = GIB_LOC_LV_PCF_RADIUS) uniform int u_pcf_radius;    // (2r+1)^2 taps
layout(location = GIB_LOC_LV_NORMAL_OFFSET) uniform float u_normal_offset; // in texels

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
    vec3 origin = lv_origin(i);
    float taps = 0.0, lit = 0.0;
    if (lv_kind(i) == GIB_LV_KIND_ORTHO) {
        int face = lv_first_face(i);
        vec3 d = lv_axis(face);
        float texel = lv_texel(i);
        vec3 q = p + n * (u_normal_offset * texel);
        vec3 uv = lv_project(face, q - origin);
        float depth = dot(q - origin, d);
        float bias = shadow_bias(texel, dot(n, -d));
        for (int y = -u_pcf_radius; y <= u_pcf_radius; y++)
            for (int x = -u_pcf_radius; x <= u_pcf_radius; x++) {
                vec2 o = vec2(x, y) / float(lv_res());
                float stored = texture(u_lv_depth, vec3(uv.xy + o, uv.z)).r;
                lit += stored + bias >= depth ? 1.0 : 0.0;
                taps += 1.0;
            }
        return lit / taps;
    }
    vec3 L0 = p - origin;
    // A texel at distance r from the light is about r * (its side at unit distance) wide.
    float texel = lv_texel(i) * length(L0);
    vec3 q = p + n * (u_normal_offset * texel);
    vec3 L = q - origin;
    float dist = length(L);
    float bias = shadow_bias(texel, dot(n, -L / dist));
    vec3 t, b;
    ortho_basis(L / dist, t, b);
    for (int y = -u_pcf_radius; y <= u_pcf_radius; y++)
        for (int x = -u_pcf_radius; x <= u_pcf_radius; x++) {
            vec3 dir = L + (float(x) * t + float(y) * b) * texel;
            vec3 uv = lv_project(lv_face(i, dir), dir);
            float stored = texture(u_lv_depth, uv).r;
            lit += stored + bias >= dist ? 1.0 : 0.0;
            taps += 1.0;
        }
    return lit / taps;
}

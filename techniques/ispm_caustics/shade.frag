// Output radiance L = rho_d / pi E (diffuse receivers: L S D E) from the splatted irradiance E.
// With splats at full resolution E is read at the pixel; at 1/k resolution it is upsampled
// bilaterally (Sec. 3.3.2.4): the 3x3 low-resolution texels around the pixel, weighted by a
// tent of radius 1.5 low-resolution texels (the text's "bilinear weight" over a 3x3 box), the
// normals' agreement max(n . n', 0)^8 and 1 / (1 + |d - d'| / (0.01 d)): the text's
// 1 / (1 + |d - d'|) measures depth in the scene's units; ours is relative, 1% of the pixel's depth
// halving the weight.
#include "ispm_caustics/ispm_caustics_slots.h"
layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position;
layout(binding = GIB_UNIT_GBUF_NORMAL) uniform sampler2D g_normal;
layout(binding = GIB_UNIT_GBUF_ALBEDO) uniform sampler2D g_albedo;
layout(binding = ISPM_SHADE_UNIT_IRRADIANCE) uniform sampler2D u_irradiance;
layout(binding = ISPM_SHADE_UNIT_LOW_POSITION) uniform sampler2D u_low_position;
layout(binding = ISPM_SHADE_UNIT_LOW_NORMAL) uniform sampler2D u_low_normal;
layout(location = ISPM_SHADE_LOC_DIVISOR) uniform int u_divisor;
layout(location = ISPM_SHADE_LOC_EYE) uniform vec3 u_eye;
layout(location = 0) out vec4 o_color;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(g_position, px, 0);
    if (pos.w < 0.5) {
        o_color = vec4(0.0);
        return;
    }
    vec3 albedo = texelFetch(g_albedo, px, 0).rgb;
    vec3 E;
    if (u_divisor == 1) {
        E = texelFetch(u_irradiance, px, 0).rgb;
    } else {
        vec3 n = texelFetch(g_normal, px, 0).xyz;
        float d = length(pos.xyz - u_eye);
        vec2 lp = (vec2(px) + 0.5) / float(u_divisor) - 0.5; // in low-resolution texel centres
        ivec2 c = ivec2(floor(lp + 0.5));
        ivec2 size = textureSize(u_irradiance, 0);
        vec3 sum = vec3(0.0);
        float wsum = 0.0;
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                ivec2 q = c + ivec2(dx, dy);
                if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
                    continue;
                vec4 lpos = texelFetch(u_low_position, q, 0);
                if (lpos.w < 0.5)
                    continue;
                vec2 off = abs(vec2(q) - lp);
                float wx = max(0.0, 1.0 - off.x / 1.5) * max(0.0, 1.0 - off.y / 1.5);
                float wn = pow(max(dot(n, texelFetch(u_low_normal, q, 0).xyz), 0.0), 8.0);
                float wd = 1.0 / (1.0 + abs(d - length(lpos.xyz - u_eye)) / (0.01 * d));
                float w = wx * wn * wd;
                sum += w * texelFetch(u_irradiance, q, 0).rgb;
                wsum += w;
            }
        E = wsum > 0.0 ? sum / wsum : vec3(0.0);
    }
    o_color = vec4(albedo / 3.14159265358979 * E, 1.0);
}

#define MR_READ_MIPS 1
#include "multires_ir/multires_common.glsl"
// Bottom-up interpolation (Algorithm 3.2), one level a pass from the coarsest: a region covered by
// its parent (continuous, parent continuous) takes the bilinear interpolation of the 2 x 2 regions
// of the coarser level nearest its centre that hold data (gathered there or interpolated in the
// previous pass), weights renormalised over those taps. The "interpolating weight" the text leaves
// open also drops a tap whose region is discontinuous with this one (its mean depth off by more
// than the depth threshold or its mean normal beyond the angle), so light does not bleed across
// an edge that falls on a region boundary; the parent itself is always kept (it contains this
// region and is continuous). RESOLVE: the last step, into the output at full resolution, where
// level-0 regions gathered themselves and every pixel's own albedo turns E into L = rho/pi E.
layout(binding = MULTIRES_UNIT_IRRADIANCE) uniform sampler2D mr_irradiance;
// the level written (k); data read from k + 1
layout(location = MULTIRES_LOC_LEVEL) uniform int u_level;
layout(location = MULTIRES_LOC_EYE) uniform vec3 u_eye;
#ifdef RESOLVE
layout(binding = GIB_UNIT_GBUF_ALBEDO) uniform sampler2D g_albedo;
#endif
layout(location = 0) out vec4 o_color;

float mr_depth(ivec2 a)
{
    return length(texelFetch(mr_mean, a, 0).xyz - u_eye);
}

vec3 mr_normal(ivec2 a)
{
    vec3 n = texelFetch(mr_nsum, a, 0).xyz;
    float len = length(n);
    return len > 0.0 ? n / len : vec3(0.0);
}

vec4 interpolate(int k, ivec2 region)
{
    ivec2 self = mr_texel(k, region);
    float d = mr_depth(self);
    vec3 n = mr_normal(self);
    float cos_t = 1.0 - 0.5 * u_normal_chord * u_normal_chord;  // cos(theta) from its chord
    ivec4 coarse = mr_rect(k + 1);
    ivec2 parent = region >> 1;
    // The coarse texel left of / below the fine centre and the bilinear fractions.
    ivec2 j0 = ivec2(floor((vec2(region) + 0.5) * 0.5 - 0.5));
    vec2 f = (vec2(region) + 0.5) * 0.5 - 0.5 - vec2(j0);
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int t = 0; t < 4; t++) {
        ivec2 o = ivec2(t & 1, t >> 1);
        ivec2 j = j0 + o;
        if (any(lessThan(j, ivec2(0))) || any(greaterThanEqual(j, coarse.zw)))
            continue;
        ivec2 a = coarse.xy + j;
        vec4 e = texelFetch(mr_irradiance, a, 0);
        if (e.w <= 0.0)
            continue;
        if (j != parent) {
            float dj = mr_depth(a);
            if (abs(dj - d) > u_depth_threshold * min(d, dj) || dot(mr_normal(a), n) < cos_t)
                continue;
        }
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        sum += w * e.rgb;
        wsum += w;
    }
    return wsum > 0.0 ? vec4(sum / wsum, 1.0) : vec4(0.0);
}

void main()
{
#ifdef RESOLVE
    ivec2 px = ivec2(gl_FragCoord.xy);
    o_color = vec4(0.0, 0.0, 0.0, 1.0);
    if (mr_empty(0, px))
        return;
    vec4 e = mr_valid(0, px) ? texelFetch(mr_irradiance, px, 0) : interpolate(0, px);
    o_color.rgb = texelFetch(g_albedo, px, 0).rgb * (1.0 / 3.14159265358979) * e.rgb;
#else
    ivec2 region = ivec2(gl_FragCoord.xy) - mr_rect(u_level).xy;
    if (!mr_covered(u_level, region))
        discard;
    o_color = interpolate(u_level, region);
#endif
}

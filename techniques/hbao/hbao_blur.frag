// One axis of the separable cross-bilateral blur that follows HBAO in Bavoil et al. 2008: it
// averages away the noise of the per-pixel direction rotation and step jitter without blurring
// across depth edges. Weights: a spatial Gaussian times a range term on the distance of the
// neighbour's surface point from the centre pixel's tangent plane, relative to the centre's depth
// (scale-free, so the same setting serves scenes in metres and in centimetres).
#include "hbao/hbao_slots.h"
layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position;
layout(binding = GIB_UNIT_GBUF_NORMAL) uniform sampler2D g_normal;
layout(binding = HBAO_BLUR_UNIT_AO) uniform sampler2D u_ao;
layout(location = HBAO_BLUR_LOC_EYE) uniform vec3 u_eye;
layout(location = HBAO_BLUR_LOC_FORWARD) uniform vec3 u_forward;
layout(location = HBAO_BLUR_LOC_AXIS) uniform ivec2 u_axis;
layout(location = HBAO_BLUR_LOC_RADIUS) uniform int u_radius;
// plane distance scale, as a fraction of depth
layout(location = HBAO_BLUR_LOC_TOLERANCE) uniform float u_tolerance;
layout(location = HBAO_BLUR_LOC_FINAL) uniform int u_final;
layout(location = 0) out vec4 o_ao;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(g_position, 0);
    vec4 pos = texelFetch(g_position, px, 0);
    if (pos.w < 0.5) {
        o_ao = u_final != 0 ? vec4(0.0, 0.0, 0.0, 1.0) : vec4(0.0);
        return;
    }
    vec3 N = normalize(texelFetch(g_normal, px, 0).xyz);
    float inv_tol = 1.0 / (u_tolerance * dot(pos.xyz - u_eye, u_forward));
    float sigma = 0.5 * float(u_radius) + 0.5;
    float inv_2s2 = 1.0 / (2.0 * sigma * sigma);
    float sum = 0.0, wsum = 0.0;
    for (int k = -u_radius; k <= u_radius; k++) {
        ivec2 q = px + k * u_axis;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
            continue;
        vec4 qp = texelFetch(g_position, q, 0);
        if (qp.w < 0.5)
            continue;
        // Symmetric: a receiver seen at a grazing angle has a tangent plane that nearly contains
        // the view rays next to it, so the surface behind it would pass a one-sided test.
        vec3 qn = texelFetch(g_normal, q, 0).xyz;
        vec3 e = qp.xyz - pos.xyz;
        float dz = max(abs(dot(N, e)), abs(dot(qn, e))) * inv_tol;
        float w = exp(-float(k * k) * inv_2s2 - dz * dz);
        sum += w * texelFetch(u_ao, q, 0).r;
        wsum += w;
    }
    float ao = sum / wsum; // wsum >= 1: the centre pixel always counts with weight 1
    o_ao = u_final != 0 ? vec4(ao, ao, ao, 1.0) : vec4(ao, 0.0, 0.0, 0.0);
}

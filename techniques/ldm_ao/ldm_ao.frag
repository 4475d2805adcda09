// Ambient occlusion and obscurance with LDMs (Aalund et al. 2015, Sec. 3.3, Eq. 1-3, and 4.1):
//   AO(x) ~ (2/N) sum_i V(x, w_i) cos(theta_i),  V = 0 when trace(x, w_i) hits within dmax, else 1;
//   obscurance (Sec. 3.3, [ZIK98]): V = rho(d) = min(d / dmax, 1), d the distance to the first hit
//   (the paper names no falloff; Zhukov's linear one is our choice, the reference uses the same).
// One LDM direction v serves the sample direction w = v or -v, whichever lies in the hemisphere of
// n. The pass runs once per node page (additive blending) over the LDMs stored in it.
// With LDM_SKY defined (technique ldm_env, the paper's Fig. 11) the same sum is the direct light of
// a uniform sky of radiance L: rho/pi * integral L V cos dw = rho * L * (2/N) sum V |cos|.
#include "ldm/ldm_trace.glsl"
#include "ldm_ao/ldm_ao_slots.h"
layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position;
layout(binding = GIB_UNIT_GBUF_NORMAL) uniform sampler2D g_normal;
layout(location = LDM_AO_LOC_FIRST) uniform int u_first;
layout(location = LDM_AO_LOC_COUNT) uniform int u_count;
layout(location = LDM_AO_LOC_WEIGHT) uniform float u_weight;        // 2 / N
layout(location = LDM_AO_LOC_DMAX) uniform float u_dmax;          // +inf for unbounded
layout(location = LDM_AO_LOC_OBSCURANCE) uniform int u_obscurance;
layout(location = LDM_AO_LOC_OFFSET) uniform float u_offset_texels;
#ifdef LDM_SKY
layout(binding = GIB_UNIT_GBUF_ALBEDO) uniform sampler2D g_albedo;
layout(location = LDM_AO_LOC_SKY) uniform vec3 u_sky;
#endif
layout(location = 0) out vec4 o_ao;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(g_position, px, 0);
    if (pos.w < 0.5) {
        o_ao = vec4(0.0);
        return;
    }
    vec3 n = texelFetch(g_normal, px, 0).xyz;
    float sum = 0.0;
    for (int i = u_first; i < u_first + u_count; i++) {
        vec3 v = ldm_info[i].dir_extent.xyz;
        float c = dot(n, v);
        if (abs(c) < 1e-6)
            continue;
        float texel = ldm_texel(i);
        vec3 x = pos.xyz + n * (u_offset_texels * texel);
        float d = ldm_trace(i, x, sign(c), ldm_eps(texel, abs(c)));
        float vis;
        if (d < 0.0)
            vis = 1.0;
        else if (u_obscurance != 0)
            vis = clamp(d / u_dmax, 0.0, 1.0);
        else
            vis = d <= u_dmax ? 0.0 : 1.0;
        sum += vis * abs(c);
    }
#ifdef LDM_SKY
    o_ao = vec4(texelFetch(g_albedo, px, 0).rgb * u_sky * (sum * u_weight), 0.0);
#else
    o_ao = vec4(vec3(sum * u_weight), 0.0);
#endif
}

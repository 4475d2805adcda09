#include "common/vpl_gather.glsl"
#include "rsm_gather/rsm_gather_slots.h"
// rsm_gather (Dachsbacher and Stamminger 2005, the thesis' baseline; Algorithm 2.1): every VPL
// gathered at every G-buffer pixel, L = rho_d / pi x E (vpl_gather.glsl), the diffuse part of the
// visible point only (the `indirect` component is L D D E).
layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position;
layout(binding = GIB_UNIT_GBUF_NORMAL) uniform sampler2D g_normal;
layout(binding = GIB_UNIT_GBUF_ALBEDO) uniform sampler2D g_albedo;
layout(location = RSM_GATHER_LOC_VPLS) uniform int u_vpls;
layout(location = RSM_GATHER_LOC_EPS) uniform float u_eps;
layout(location = 0) out vec4 o_color;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    o_color = vec4(0.0, 0.0, 0.0, 1.0);
    vec4 pos = texelFetch(g_position, px, 0);
    vec3 alb = texelFetch(g_albedo, px, 0).rgb;
    if (pos.w < 0.5 || max(alb.r, max(alb.g, alb.b)) <= 0.0)
        return;
    vec3 n = texelFetch(g_normal, px, 0).xyz;
    o_color.rgb = alb * (1.0 / 3.14159265358979) * vpl_irradiance(pos.xyz, n, u_vpls, u_eps);
}

#define MR_READ_MIPS 1
#include "multires_ir/multires_common.glsl"
#include "common/vpl_gather.glsl"
// Gathering (Sec. 3.2.2.2): over the flattened image with the stencil test (MASKED: the mask), so
// only valid regions are shaded: the irradiance of every VPL (vpl_gather.glsl, the formula of rsm_gather) at the
// region's mean position and normal. Irradiance, not radiance: the albedo varies inside a region
// (textures), so each pixel applies its own after interpolation. alpha 1 marks data.
#ifdef MASKED
layout(binding = MULTIRES_UNIT_VALID) uniform sampler2D mr_valid_mask;  // multires.h, stencil = 0
#endif
layout(location = MULTIRES_GATHER_LOC_VPLS) uniform int u_vpls;
layout(location = MULTIRES_GATHER_LOC_EPS) uniform float u_eps;
layout(location = 0) out vec4 o_irradiance;
void main()
{
#ifdef MASKED
    if (texelFetch(mr_valid_mask, ivec2(gl_FragCoord.xy), 0).r < 0.5)
        discard;
#endif
    ivec2 region;
    int k = mr_level(ivec2(gl_FragCoord.xy), region);
    ivec2 a = mr_texel(k, region);
    vec4 m = texelFetch(mr_mean, a, 0);
    vec3 n = texelFetch(mr_nsum, a, 0).xyz;
    float len = length(n);
    o_irradiance = vec4(vpl_irradiance(m.xyz, len > 0.0 ? n / len : vec3(0.0), u_vpls, u_eps), 1.0);
}

#include "multires_ir/multires_common.glsl"
// The min-max mips (Sec. 3.2.2.1) in the flattened image: level 0 from the G-buffer, level k from
// the up to 2 x 2 regions of level k - 1 it holds (regions past the image's edge are skipped).
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_2D, local_size_y = GIB_GROUP_2D) in;
layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position;
layout(binding = GIB_UNIT_GBUF_NORMAL) uniform sampler2D g_normal;
layout(binding = MULTIRES_IMAGE_LO, rgba32f) uniform image2D o_lo;
layout(binding = MULTIRES_IMAGE_HI, rgba32f) uniform image2D o_hi;
layout(binding = MULTIRES_IMAGE_MEAN, rgba32f) uniform image2D o_mean;
layout(binding = MULTIRES_IMAGE_NSUM, rgba32f) uniform image2D o_nsum;
layout(location = MULTIRES_LOC_LEVEL) uniform int u_level;
layout(location = MULTIRES_LOC_EYE) uniform vec3 u_eye;
void main()
{
    ivec2 r = ivec2(gl_GlobalInvocationID.xy);
    ivec4 rect = mr_rect(u_level);
    if (any(greaterThanEqual(r, rect.zw)))
        return;
    vec4 lo = vec4(1e30), hi = vec4(-1e30), mean = vec4(0.0), nsum = vec4(0.0);
    if (u_level == 0) {
        vec4 p = texelFetch(g_position, r, 0);
        if (p.w > 0.5) {
            vec3 n = texelFetch(g_normal, r, 0).xyz;
            float d = length(p.xyz - u_eye);
            lo = vec4(n, d);
            hi = lo;
            mean = vec4(p.xyz, 1.0);
            nsum = vec4(n, 0.0);
        } else {
            lo.w = MR_FAR;
            hi.w = MR_FAR;
        }
    } else {
        ivec4 child = mr_rect(u_level - 1);
        float count = 0.0;
        vec3 psum = vec3(0.0);
        for (int j = 0; j < 4; j++) {
            ivec2 c = 2 * r + ivec2(j & 1, j >> 1);
            if (any(greaterThanEqual(c, child.zw)))
                continue;
            ivec2 a = child.xy + c;
            vec4 clo = imageLoad(o_lo, a), chi = imageLoad(o_hi, a), cm = imageLoad(o_mean, a);
            lo = min(lo, clo);
            hi = max(hi, chi);
            psum += cm.xyz * cm.w;
            count += cm.w;
            nsum += imageLoad(o_nsum, a);
        }
        mean = vec4(count > 0.0 ? psum / count : vec3(0.0), count);
    }
    ivec2 a = rect.xy + r;
    imageStore(o_lo, a, lo);
    imageStore(o_hi, a, hi);
    imageStore(o_mean, a, mean);
    imageStore(o_nsum, a, nsum);
}

// Sec. 3.3.1.1, Fig. 3.5: the light view's specular mask and its mip chain. Level 0: 1 where the
// light sees a specular surface (NORMAL.w, the material's specular type, with rho_s > 0), else 0.
// Level k: the box mean of its 4 texels at level k - 1 (computed here: GL leaves
// glGenerateMipmap's filter to the driver), so a texel is exactly 1 iff all 4^k texels below are.
#include "ispm_caustics/ispm_caustics_slots.h"
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_2D, local_size_y = GIB_GROUP_2D) in;
layout(binding = GIB_UNIT_LV_POSITION) uniform sampler2DArray lv_position;
layout(binding = GIB_UNIT_LV_NORMAL) uniform sampler2DArray lv_normal;
layout(binding = GIB_UNIT_LV_SPECULAR) uniform sampler2DArray lv_specular;
layout(r32f, binding = ISPM_MIP_IMAGE_DST) uniform writeonly image2DArray u_dst;
layout(r32f, binding = ISPM_MIP_IMAGE_SRC) uniform readonly image2DArray u_src;
layout(location = ISPM_MIP_LOC_LEVEL) uniform int u_level;
layout(location = ISPM_MIP_LOC_RES) uniform int u_res; // of the level written
void main()
{
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (p.x >= u_res || p.y >= u_res)
        return;
    float v;
    if (u_level == 0) {
        vec3 s = texelFetch(lv_specular, p, 0).rgb;
        bool spec = texelFetch(lv_position, p, 0).w > 0.5 && texelFetch(lv_normal, p, 0).w > 0.5 &&
                    max(s.r, max(s.g, s.b)) > 0.0;
        v = spec ? 1.0 : 0.0;
    } else {
        ivec3 q = ivec3(2 * p.xy, p.z);
        v = 0.25 * (imageLoad(u_src, q).r + imageLoad(u_src, q + ivec3(1, 0, 0)).r +
                    imageLoad(u_src, q + ivec3(0, 1, 0)).r + imageLoad(u_src, q + ivec3(1, 1, 0)).r);
    }
    imageStore(u_dst, p, vec4(v));
}

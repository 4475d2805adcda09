#include "common/common_slots.h"
// VPL extraction (common/vpl.h): one work group per VPL sums the reflected flux of its region of
// light-view texels and takes position and normal from the texel under its sample point, or from
// the region's texel nearest to it that holds a surface (ties: the lower texel index).
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_1D) in;
struct Vpl {
    vec4 position;
    vec4 normal;
    vec4 flux;
};
layout(std430, binding = GIB_VPL_SSBO_VPLS) writeonly buffer Vpls { Vpl vpls[]; };
layout(std430, binding = GIB_VPL_SSBO_CELLS) readonly buffer Cells { ivec4 cells[]; };
layout(std430, binding = GIB_VPL_SSBO_TEXELS) readonly buffer Texels { int texels[]; };
layout(binding = GIB_UNIT_LV_POSITION) uniform sampler2DArray lv_position;
layout(binding = GIB_UNIT_LV_NORMAL) uniform sampler2DArray lv_normal;
layout(binding = GIB_UNIT_LV_FLUX) uniform sampler2DArray lv_flux;
layout(location = GIB_VPL_LOC_RES) uniform int u_res;
layout(location = GIB_VPL_LOC_COUNT) uniform int u_count;
shared vec3 s_flux[GIB_GROUP_1D];
shared int s_d2[GIB_GROUP_1D];
shared int s_texel[GIB_GROUP_1D];
void main()
{
    int id = int(gl_WorkGroupID.x);
    int t = int(gl_LocalInvocationID.x);
    ivec4 c = cells[min(id, u_count - 1)];
    ivec2 sp = ivec2(c.y % u_res, c.y / u_res);
    vec3 sum = vec3(0.0);
    int best = 0x7fffffff, best_texel = -1;
    for (int k = c.z + t; k < c.z + c.w; k += GIB_GROUP_1D) {
        int idx = texels[k];
        ivec3 q = ivec3(idx % u_res, idx / u_res, c.x);
        sum += texelFetch(lv_flux, q, 0).rgb;
        if (texelFetch(lv_position, q, 0).w > 0.5) {
            ivec2 dd = q.xy - sp;
            int d2 = dd.x * dd.x + dd.y * dd.y;
            if (d2 < best || (d2 == best && idx < best_texel)) {
                best = d2;
                best_texel = idx;
            }
        }
    }
    s_flux[t] = sum;
    s_d2[t] = best;
    s_texel[t] = best_texel;
    barrier();
    for (int s = GIB_GROUP_1D / 2; s > 0; s >>= 1) {
        if (t < s) {
            s_flux[t] += s_flux[t + s];
            int d2 = s_d2[t + s], tx = s_texel[t + s];
            if (tx >= 0 && (d2 < s_d2[t] || (d2 == s_d2[t] && (s_texel[t] < 0 || tx < s_texel[t])))) {
                s_d2[t] = d2;
                s_texel[t] = tx;
            }
        }
        barrier();
    }
    if (t != 0 || id >= u_count)
        return;
    int tx = s_texel[0];
    if (tx < 0) {
        vpls[id].position = vec4(0.0);
        vpls[id].normal = vec4(0.0);
        vpls[id].flux = vec4(s_flux[0], 0.0);
        return;
    }
    ivec3 q = ivec3(tx % u_res, tx / u_res, c.x);
    vpls[id].position = vec4(texelFetch(lv_position, q, 0).xyz, 1.0);
    vpls[id].normal = vec4(texelFetch(lv_normal, q, 0).xyz, 0.0);
    vpls[id].flux = vec4(s_flux[0], 0.0);
}

#include "common/vpl_gather.glsl"
// Test hook (common/vpl.h, gib_vpls_probe): vpl_irradiance() at given points and normals.
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_1D) in;
layout(std430, binding = GIB_VPL_PROBE_SSBO_IN) readonly buffer ProbeIn { vec4 probe_in[]; };
layout(std430, binding = GIB_VPL_PROBE_SSBO_OUT) writeonly buffer ProbeOut { vec4 probe_out[]; };
layout(location = GIB_VPL_PROBE_LOC_COUNT) uniform int u_count;
layout(location = GIB_VPL_PROBE_LOC_VPLS) uniform int u_vpls;
layout(location = GIB_VPL_PROBE_LOC_EPS) uniform float u_eps;
void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_count)
        return;
    probe_out[i] = vec4(vpl_irradiance(probe_in[2 * i].xyz, probe_in[2 * i + 1].xyz, u_vpls, u_eps),
                        0.0);
}

#include "vct/vct_trace.glsl"
// Test hook (tests/vct): vct_cone() from given points, so that tests check what a cone reads from
// the anisotropic mips apart from the G-buffer. In: (p, tan_half), (n, max_dist), (D, 0) per
// cone; out: vct_cone's (radiance, occlusion).
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_1D) in;
layout(std430, binding = VCT_PROBE_SSBO_IN) readonly buffer ProbeIn { vec4 probe_in[]; };
layout(std430, binding = VCT_PROBE_SSBO_OUT) writeonly buffer ProbeOut { vec4 probe_out[]; };
layout(location = VCT_PROBE_LOC_COUNT) uniform int u_count;
void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_count)
        return;
    vec4 p = probe_in[3 * i], n = probe_in[3 * i + 1], d = probe_in[3 * i + 2];
    probe_out[i] = vct_cone(p.xyz, n.xyz, normalize(d.xyz), p.w, n.w);
}

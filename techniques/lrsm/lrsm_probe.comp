#include "common/light_view.glsl"
#include "lrsm/lrsm_common.glsl"
#include "lrsm/lrsm_sample.glsl"
// Test hook (tests/lrsm): lrsm_sample() at given cone samples, so that tests check the LRSM's
// radiance lookup (Algorithm 1) apart from the voxels. In: (x_c, r_c) and (v_c, 0) per sample; out:
// (L, the lit coverage).
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_1D) in;
layout(std430, binding = LRSM_PROBE_SSBO_IN) readonly buffer ProbeIn { vec4 probe_in[]; };
layout(std430, binding = LRSM_PROBE_SSBO_OUT) writeonly buffer ProbeOut { vec4 probe_out[]; };
layout(location = LRSM_PROBE_LOC_COUNT) uniform int u_count;
void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_count)
        return;
    vec4 s = probe_in[2 * i], v = probe_in[2 * i + 1];
    probe_out[i] = lrsm_sample(s.xyz, s.w, v.xyz);
}

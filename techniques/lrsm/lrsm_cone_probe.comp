#include "common/voxel_cone.glsl"
#include "lrsm/lrsm_march.glsl"
// Test hook: the occlusion an lrsm diffuse cone gathers (lrsm_cone.frag's trace_cone without the
// radiance), for given cones. Per cone, in: (x, aperture in radians), (n, 0), (dir, 0); out: A.
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_1D) in;
layout(std430, binding = LRSM_CONE_PROBE_SSBO_IN) readonly buffer In { vec4 cones[]; };
layout(std430, binding = LRSM_CONE_PROBE_SSBO_OUT) writeonly buffer Out { float occlusion[]; };
layout(location = LRSM_CONE_PROBE_LOC_COUNT) uniform int u_count;
void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_count)
        return;
    LrsmCone k = lrsm_cone_start(cones[3 * i].xyz, cones[3 * i + 1].xyz, cones[3 * i + 2].xyz,
                                 cones[3 * i].w);
    vec3 c;
    float A = 0.0, d;
    for (int s = 0; s < 512 && A < 255.0 / 256.0 && lrsm_cone_sample(k, c, d); s++) {
        A += (1.0 - A) * voxel_step_alpha(c, d, u_step_factor);
        lrsm_cone_advance(k, d);
    }
    occlusion[i] = A;
}

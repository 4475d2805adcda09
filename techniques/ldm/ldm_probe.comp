// Validation kernel (tests/ldm): traces arbitrary rays along LDM directions, so the trace of Sec. 3.1
// can be checked against Embree on the same rays. ray.w = +-(i + 1): LDM i, direction sign.
#include "ldm/ldm_trace.glsl"
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_1D) in;
layout(std430, binding = LDM_PROBE_SSBO_RAYS) readonly buffer Rays { vec4 rays[]; };
layout(std430, binding = LDM_PROBE_SSBO_HITS) writeonly buffer Hits { float hits[]; };
layout(location = LDM_PROBE_LOC_COUNT) uniform int u_count;
layout(location = LDM_PROBE_LOC_FIRST) uniform int u_first; // LDMs of the bound page
layout(location = LDM_PROBE_LOC_PAGE_COUNT) uniform int u_page_count;
layout(location = LDM_PROBE_LOC_EPS) uniform float u_eps;
void main()
{
    int k = int(gl_GlobalInvocationID.x);
    if (k >= u_count)
        return;
    vec4 r = rays[k];
    int i = int(abs(r.w) + 0.5) - 1;
    if (i < u_first || i >= u_first + u_page_count)
        return;
    hits[k] = ldm_trace(i, r.xyz, sign(r.w), u_eps);
}

// Test probe (tests/ispm_caustics): the Phong sampler of caustics.glsl on given lobe axes and normals.
#include "ispm_caustics/caustics.glsl"
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_1D) in;
layout(std430, binding = ISPM_PROBE_SSBO_IN) readonly buffer In { vec4 xi[]; };       // xy xi1 xi2
// xyz d, w accepted
layout(std430, binding = ISPM_PROBE_SSBO_OUT) buffer Out { vec4 dirs[]; };
layout(location = ISPM_PROBE_LOC_R) uniform vec3 u_r;
layout(location = ISPM_PROBE_LOC_NORMAL) uniform vec3 u_normal;
layout(location = ISPM_PROBE_LOC_N) uniform float u_n;
layout(location = ISPM_PROBE_LOC_COUNT) uniform int u_count;
void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_count)
        return;
    vec3 d;
    float w;
    bool ok = sample_phong(u_r, u_normal, u_n, xi[i].x, xi[i].y, d, w);
    dirs[i] = vec4(d, ok ? 1.0 : 0.0);
}

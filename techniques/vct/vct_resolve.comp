#include "vct/vct_slots.h"
// The injection's sums to averages (vct_inject.vert): radiance = sum(w L) / sum(w), normal = the
// normalised sum of w n with w = 1 where light landed. Alpha (occlusion) = the occlusion voxels'
// occupancy at level 0 (common/voxels.h, the same grid: exact triangle/box overlap, alpha masks
// honoured), or 1 where light landed (a lit surface is there even if a float rounding put its
// texel in the neighbouring voxel).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = VCT_RESOLVE_UNIT_OCCUPANCY) uniform sampler3D u_occupancy;
layout(binding = VCT_RESOLVE_IMAGE_RADIANCE, rgba16f) uniform image3D u_radiance;
layout(binding = VCT_RESOLVE_IMAGE_NORMAL, rgba16f) uniform image3D u_normal;
void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, imageSize(u_radiance))))
        return;
    vec4 r = imageLoad(u_radiance, c);
    bool lit = r.a > 0.0;
    float occupied = lit || texelFetch(u_occupancy, c, 0).r > 0.5 ? 1.0 : 0.0;
    if (!lit) {
        imageStore(u_radiance, c, vec4(0.0, 0.0, 0.0, occupied));
        return;
    }
    vec3 n = imageLoad(u_normal, c).xyz;
    float len = length(n);
    imageStore(u_radiance, c, vec4(r.rgb / r.a, occupied));
    imageStore(u_normal, c, vec4(len > 0.0 ? n / len : vec3(0.0), 1.0));
}

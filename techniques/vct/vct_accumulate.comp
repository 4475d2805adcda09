#include "vct/vct_slots.h"
// Several lights (vct_volume_inject): one light's injected sums (rgb sum w L, a sum w, in the normal
// volume used as scratch) become its area-weighted average radiance, added to the radiance volume
// (rgb the lights' sum, a 1 where any light landed): averaged per light, so that a surface lit by
// two lights gets their sum, not their mean.
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_3D, local_size_y = GIB_GROUP_3D, local_size_z = GIB_GROUP_3D) in;
layout(binding = VCT_ACCUMULATE_IMAGE_SCRATCH, rgba16f) readonly uniform image3D u_scratch;
layout(binding = VCT_ACCUMULATE_IMAGE_RADIANCE, rgba16f) uniform image3D u_radiance;
void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, imageSize(u_radiance))))
        return;
    vec4 s = imageLoad(u_scratch, c);
    if (s.a > 0.0)
        imageStore(u_radiance, c, vec4(imageLoad(u_radiance, c).rgb + s.rgb / s.a, 1.0));
}

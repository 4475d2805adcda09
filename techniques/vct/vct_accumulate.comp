#include "vct/vct_slots.h"
// Several lights (vct_volume_inject): one light's injected sums (rgb sum w L, a sum w, in the normal
// volume used as scratch) become its area-weighted average radiance, added to the radiance volume
// (rgb the lights' sum, a 1 where any light landed). Averaging all lights' texels together instead
// gave a surface lit by two lights their mean radiance, not their sum.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
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

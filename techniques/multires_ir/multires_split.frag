#define MR_READ_MIPS 1
#include "multires_ir/multires_common.glsl"
// Region splitting (Algorithm 3.1): a full-screen pass over the flattened image; the texels of
// valid regions survive and set the stencil or the mask (multires.h), the others are discarded.
layout(location = 0) out vec4 o_mark;
void main()
{
    ivec2 region;
    int k = mr_level(ivec2(gl_FragCoord.xy), region);
    if (k < 0 || !mr_valid(k, region))
        discard;
    o_mark = vec4(1.0);
}

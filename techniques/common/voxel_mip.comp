// One level of the occlusion voxels' mip chain (techniques/common/voxels.h): each texel the mean
// of its 2x2x2 children one level below (a box filter; odd sizes drop the last child layer, as
// the level sizes do). The level below is read as an image, so the 8 values are the stored bytes
// and the mean is rounded once, to the nearest 1/255, by the R8 store.
#include "common/common_slots.h"
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_3D, local_size_y = GIB_GROUP_3D, local_size_z = GIB_GROUP_3D) in;
layout(r8, binding = GIB_VOXEL_MIP_IMAGE_DST) writeonly uniform image3D u_dst;
layout(r8, binding = GIB_VOXEL_MIP_IMAGE_SRC) readonly uniform image3D u_src;

void main()
{
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p, imageSize(u_dst))))
        return;
    ivec3 s = 2 * p;
    float sum = 0.0;
    for (int c = 0; c < 8; c++)
        sum += imageLoad(u_src, s + ivec3(c & 1, (c >> 1) & 1, c >> 2)).r;
    imageStore(u_dst, p, vec4(sum * 0.125));
}

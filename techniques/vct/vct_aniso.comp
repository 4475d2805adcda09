#include "vct/vct_slots.h"
// Anisotropic mips (Crassin et al. 2011, Sec. 4; Sugihara et al. 2014, Sec. 6): for each of the 6
// directions a cone can travel (+x -x +y -y +z -z), a voxel of level k+1 is its 8 children of level
// k seen along that direction: the 2 children on each line along it composited front to back,
//     C = C_front + (1 - a_front) C_back,   a = a_front + (1 - a_front) a_back
// (premultiplied radiance C, occlusion a; Eq. 1 over two samples), and the 4 lines averaged.
// FROM_BASE builds level 0 (res/2) from the base voxels, where a lit voxel hides its radiance from
// a direction's texture when its surface faces away from every direction that texture stands for:
// the D^2 weights of vct_trace.glsl make a texture dominant within 45 degrees of its axis, and all
// of those meet the surface from behind when its normal is within 45 degrees of the axis, dot(n,
// axis) > cos 45. The hidden voxel still occludes. The threshold is cos 45, not 0: a cone between
// two axes sees from the front surfaces that face slightly away from one axis (a wall with n =
// (0.5, -0.87, 0) and D = (0.7, 0.7, 0)), and that axis's texture carries half the cone's weight.
// A surface seen edge-on (dot = 0) is shown: voxelised, it is a voxel thick, its line along the
// axis is opaque, and a cone crossing a wall obliquely reads it through that sideways texture too;
// hidden, walls would be black occluders. This keeps the light of one side of a wall from its
// other side when the two sides are in different voxels; a wall thinner than a voxel lit on both
// sides has one averaged normal and leaks (stated in vct.h).
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_3D, local_size_y = GIB_GROUP_3D, local_size_z = GIB_GROUP_3D) in;
layout(location = VCT_ANISO_LOC_LEVEL) uniform int u_level; // level written
#ifdef FROM_BASE
layout(binding = VCT_ANISO_UNIT_RADIANCE) uniform sampler3D u_radiance;
layout(binding = VCT_ANISO_UNIT_NORMAL) uniform sampler3D u_normal;
#else
layout(binding = VCT_ANISO_UNIT_SRC_FIRST) uniform sampler3D u_src[6];
#endif
layout(binding = VCT_ANISO_IMAGE_DST_FIRST, rgba16f) writeonly uniform image3D u_dst[6];

const float HIDDEN_COS = 0.70710678; // cos 45 degrees
const vec3 DIRECTION[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0),
                                  vec3(0, 0, 1), vec3(0, 0, -1));

vec4 child(int d, ivec3 p)
{
#ifdef FROM_BASE
    vec4 r = texelFetch(u_radiance, p, 0); // rgb is premultiplied: 0 where empty, alpha 0 or 1
    vec4 n = texelFetch(u_normal, p, 0);
    if (n.w > 0.5 && dot(n.xyz, DIRECTION[d]) > HIDDEN_COS)
        r.rgb = vec3(0.0);
    return r;
#else
    return texelFetch(u_src[d], p, u_level - 1);
#endif
}

void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, imageSize(u_dst[0]))))
        return;
    for (int d = 0; d < 6; d++) {
        int axis = d / 2;
        int front = (d & 1) == 0 ? 0 : 1; // travelling +: the lower child is in front
        vec4 sum = vec4(0.0);
        for (int q = 0; q < 4; q++) {
            ivec3 o = ivec3(0);
            o[(axis + 1) % 3] = q & 1;
            o[(axis + 2) % 3] = q >> 1;
            ivec3 pf = 2 * c + o, pb = 2 * c + o;
            pf[axis] += front;
            pb[axis] += 1 - front;
            vec4 f = child(d, pf), b = child(d, pb);
            sum += vec4(f.rgb + (1.0 - f.a) * b.rgb, f.a + (1.0 - f.a) * b.a);
        }
        imageStore(u_dst[d], c, 0.25 * sum);
    }
}

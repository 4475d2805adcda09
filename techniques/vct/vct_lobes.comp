#include "vct/vct_slots.h"
// The emission lobes (vct's `front_faces`; vct_trace.glsl says why): for each of the 6 directions
// a surface can face (+x -x +y -y +z -z), a voxel of level k holds the luminance of the lit
// surfaces inside it that face that way, and the back-most plane that light leaves from:
//   Y = mean over the children of sum w Y_s  (Y_s a lit base voxel's luminance, premultiplied by
//                                             its occupancy)
//   P = Y b   (b the least centre coordinate along the axis, grid units [0, 1], of the children
//              with light in a + lobe, the greatest in a - lobe: every surface of the lobe lies in
//              front of b, so an apex in front of it may see some of them. A mean plane would hide
//              a floor's light from a receiver on it wherever a lit box top shares the cell.
//              Stored times Y so that filtering blends it by luminance.)
// A lit base voxel of normal n shares itself among the lobes by w = max(0, n . axis)^2 (summing
// to 1); a voxel no light reached adds nothing. Stored per axis k as (Y+, P+, Y-, P-) in one
// RGBA16F texture. FROM_BASE builds level 0 (res/2) from the base voxels; otherwise level k+1
// from level k. Plain averages, not composited along a direction: the lobes only say from which
// side of which plane a cell's light leaves; what a cone sees, and its occlusion, stay in the
// anisotropic mips (vct_aniso.comp).
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_3D, local_size_y = GIB_GROUP_3D, local_size_z = GIB_GROUP_3D) in;
layout(location = VCT_ANISO_LOC_LEVEL) uniform int u_level; // level written
#ifdef FROM_BASE
layout(binding = VCT_ANISO_UNIT_RADIANCE) uniform sampler3D u_radiance;
layout(binding = VCT_ANISO_UNIT_NORMAL) uniform sampler3D u_normal;
#else
layout(binding = VCT_LOBES_UNIT_SRC_FIRST) uniform sampler3D u_src[3];
#endif
layout(binding = VCT_LOBES_IMAGE_DST_FIRST, rgba16f) writeonly uniform image3D u_dst[3];

// A child's luminance y (+, - lobe) and the back-most plane of its light: the least coordinate
// of the + lobe's, the greatest of the - lobe's.
void add_child(inout vec4 axis, inout vec2 extreme, vec2 y, vec2 plane)
{
    axis += vec4(y.x, 0.0, y.y, 0.0);
    if (y.x > 0.0)
        extreme.x = min(extreme.x, plane.x);
    if (y.y > 0.0)
        extreme.y = max(extreme.y, plane.y);
}

void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, imageSize(u_dst[0]))))
        return;
    vec4 axis[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));   // luminance sums in x and z
    vec2 extreme[3] = vec2[3](vec2(1e9, -1e9), vec2(1e9, -1e9), vec2(1e9, -1e9));
    for (int q = 0; q < 8; q++) {
        ivec3 p = 2 * c + ivec3(q & 1, (q >> 1) & 1, q >> 2);
#ifdef FROM_BASE
        vec4 r = texelFetch(u_radiance, p, 0); // rgb premultiplied by the occupancy
        vec4 n = texelFetch(u_normal, p, 0);   // w = 1 where light landed
        float y = dot(r.rgb, vec3(0.2126, 0.7152, 0.0722));
        if (n.w < 0.5 || y <= 0.0)
            continue;
        vec3 centre = (vec3(p) + 0.5) / float(textureSize(u_radiance, 0).x);
        for (int k = 0; k < 3; k++) {
            vec2 w = vec2(max(n[k], 0.0), max(-n[k], 0.0));
            add_child(axis[k], extreme[k], w * w * y, vec2(centre[k]));
        }
#else
        for (int k = 0; k < 3; k++) {
            vec4 t = texelFetch(u_src[k], p, u_level - 1);
            vec2 y = t.xz;
            add_child(axis[k], extreme[k], y,
                      vec2(y.x > 0.0 ? t.y / y.x : 0.0, y.y > 0.0 ? t.w / y.y : 0.0));
        }
#endif
    }
    for (int k = 0; k < 3; k++) {
        vec2 y = 0.125 * vec2(axis[k].x, axis[k].z);
        imageStore(u_dst[k], c, vec4(y.x, y.x * extreme[k].x, y.y, y.y * extreme[k].y));
    }
}

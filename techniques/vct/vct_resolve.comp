#include "vct/vct_texel.glsl"
#include "vct/vct_slots.h"
// The injection's sums to averages (vct_inject.vert): radiance = sum(w L) / sum(w), normal = the
// normalised sum of w n with w = 1 where light landed. Alpha (occlusion) = the occlusion voxels'
// occupancy at level 0 (common/voxels.h, the same grid: exact triangle/box overlap, alpha masks
// honoured), or 1 where light landed (a lit surface is there even if a float rounding put its
// texel in the neighbouring voxel).
//
// The fill (u_lights > 0; vct's `fill`): an occupied voxel where no texel landed takes the
// radiance of the light-view texel its centre projects to, when that texel's surface is in the
// voxel: within 1.5 voxels of the centre along the light's ray, and its plane through the voxel's
// box (|(c - p).n| <= h (|n.x| + |n.y| + |n.z|) / 2 for a box of side h). The occupancy is
// conservative (any overlap) while texels are points: a surface crossing a voxel's corner occupies
// it but seldom sends it a texel, the more seldom the finer the grid for the same light views.
// Without the fill such voxels are black occluders inside lit surfaces. A voxel in shadow
// projects to its occluder, farther than 1.5 voxels, and stays black.
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_3D, local_size_y = GIB_GROUP_3D, local_size_z = GIB_GROUP_3D) in;
layout(location = GIB_LOC_VOXEL_ORIGIN) uniform vec3 u_origin;
layout(location = GIB_LOC_VOXEL_SIZE) uniform float u_size;
layout(location = GIB_LOC_VOXEL_RES) uniform int u_res;
layout(location = VCT_RESOLVE_LOC_LIGHTS) uniform int u_lights;
layout(location = VCT_RESOLVE_LOC_LV_RES) uniform int u_lv_res;
layout(binding = VCT_RESOLVE_UNIT_OCCUPANCY) uniform sampler3D u_occupancy;
layout(binding = GIB_UNIT_LV_POSITION) uniform sampler2DArray lv_position;
layout(binding = GIB_UNIT_LV_NORMAL) uniform sampler2DArray lv_normal;
layout(binding = GIB_UNIT_LV_FLUX) uniform sampler2DArray lv_flux;
layout(binding = VCT_RESOLVE_IMAGE_RADIANCE, rgba16f) uniform image3D u_radiance;
layout(binding = VCT_RESOLVE_IMAGE_NORMAL, rgba16f) uniform image3D u_normal;

// The radiance and normal of the lit surface in voxel c, from light `light`'s view; false if the
// light sees no surface in it.
bool fill_from_view(int light, ivec3 c, out vec3 radiance, out vec3 normal)
{
    float h = u_size / float(u_res);
    vec3 centre = u_origin + (vec3(c) + 0.5) * h;
    vec3 rel = centre - lv_origin(light);
    int face = lv_face(light, rel);
    vec3 uv = lv_project(face, rel);
    if (any(lessThan(uv.xy, vec2(0.0))) || any(greaterThanEqual(uv.xy, vec2(1.0))))
        return false;
    ivec3 tc = ivec3(ivec2(uv.xy * float(u_lv_res)), face);
    vec4 p = texelFetch(lv_position, tc, 0);
    normal = texelFetch(lv_normal, tc, 0).xyz;
    vec3 off = centre - p.xyz;
    vec3 an = abs(normal);
    if (p.w < 0.5 || length(off) > 1.5 * h || abs(dot(off, normal)) > 0.5 * h * (an.x + an.y + an.z))
        return false;
    radiance = texelFetch(lv_flux, tc, 0).rgb /
               (3.14159265358979 * lv_texel_area(light, face, p.xyz, normal));
    return true;
}

void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, imageSize(u_radiance))))
        return;
    vec4 r = imageLoad(u_radiance, c);
    bool lit = r.a > 0.0;
    bool occupied = lit || texelFetch(u_occupancy, c, 0).r > 0.5;
    if (lit) {
        vec3 n = imageLoad(u_normal, c).xyz;
        float len = length(n);
        imageStore(u_radiance, c, vec4(r.rgb / r.a, 1.0));
        imageStore(u_normal, c, vec4(len > 0.0 ? n / len : vec3(0.0), 1.0));
        return;
    }
    vec3 sum = vec3(0.0), nsum = vec3(0.0);
    int found = 0;
    for (int l = 0; occupied && l < u_lights; l++) {
        vec3 L, n;
        if (fill_from_view(l, c, L, n)) {
            sum += L;
            nsum += n;
            found++;
        }
    }
    if (found > 0) {
        imageStore(u_radiance, c, vec4(sum, 1.0));
        imageStore(u_normal, c, vec4(normalize(nsum), 1.0));
        return;
    }
    imageStore(u_radiance, c, vec4(0.0, 0.0, 0.0, occupied ? 1.0 : 0.0));
}

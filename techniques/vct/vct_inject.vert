#extension GL_ARB_shader_viewport_layer_array : require
#include "vct/vct_texel.glsl"
#include "vct/vct_slots.h"
// Injection (vct.h): one point per light-view texel, drawn into the voxel that holds the texel's
// position (layer = z), with the texel's radiance L = flux / (pi A) (vct_texel.glsl). Voxels
// average L weighted by area (w = A in voxel faces), so a voxel's radiance is its patches' total
// reflected flux over pi times their total area: the flux the surface reflects is what the voxels
// emit (sum w L = sum flux / (pi voxel^2)).
layout(location = GIB_LOC_VOXEL_ORIGIN) uniform vec3 u_origin;
layout(location = GIB_LOC_VOXEL_SIZE) uniform float u_size;
layout(location = GIB_LOC_VOXEL_RES) uniform int u_res;
layout(location = VCT_INJECT_LOC_LIGHT) uniform int u_light;
layout(location = VCT_INJECT_LOC_LV_RES) uniform int u_lv_res;
layout(location = VCT_INJECT_LOC_FACE) uniform int u_face;
layout(binding = GIB_UNIT_LV_POSITION) uniform sampler2DArray lv_position;
layout(binding = GIB_UNIT_LV_NORMAL) uniform sampler2DArray lv_normal;
layout(binding = GIB_UNIT_LV_FLUX) uniform sampler2DArray lv_flux;
out vec4 v_radiance;
out vec4 v_normal;
void main()
{
    ivec3 tc = ivec3(gl_VertexID % u_lv_res, gl_VertexID / u_lv_res, u_face);
    vec4 p = texelFetch(lv_position, tc, 0);
    vec3 g = (p.xyz - u_origin) / u_size * float(u_res);
    ivec3 vox = ivec3(floor(g));
    gl_PointSize = 1.0;
    v_radiance = vec4(0.0);
    v_normal = vec4(0.0);
    if (p.w < 0.5 || any(lessThan(vox, ivec3(0))) || any(greaterThanEqual(vox, ivec3(u_res)))) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the view: not drawn
        gl_Layer = 0;
        return;
    }
    vec3 n = texelFetch(lv_normal, tc, 0).xyz;
    vec3 flux = texelFetch(lv_flux, tc, 0).rgb;
    float area = lv_texel_area(u_light, u_face, p.xyz, n);
    float voxel = u_size / float(u_res);
    float w = area / (voxel * voxel);
    v_radiance = vec4(flux / (3.14159265358979 * voxel * voxel), w); // w L = flux / (pi voxel^2)
    v_normal = vec4(w * n, 0.0);
    gl_Position = vec4((vec2(vox.xy) + 0.5) / float(u_res) * 2.0 - 1.0, 0.0, 1.0);
    gl_Layer = vox.z;
}

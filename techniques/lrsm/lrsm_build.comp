#include "common/light_view.glsl"
#include "lrsm/lrsm_common.glsl"
// LRSM construction (Sec. 4.3, 5; Table 1): one invocation per 2x2 block of one light-view face.
// Each RSM texel goes to the layer of its depth partition (both layers inside an overlap band) and
// its <n.l> partition; the texels of the block that share a layer are merged into that layer's
// texel, every value premultiplied by the opacity alpha = members / 4 (lrsm_build_block() in
// lrsm_math.c is the CPU mirror). The radiance texel holds the members' radiance weighted by the
// area of surface each sees (u_jacobian 1: rgb = sum R w / 4, a = sum w / 4; lrsm_math.h's
// lrsm_area_weight), so that its mips average radiance over surface area, as Eq. 2 integrates it,
// not over the light's solid angle: Sec. 4.2 takes Eq. 3's Jacobian r^2 / <n.l> as constant and
// drops it, which lets a texel a light almost touches (a patch micrometres wide, its radiance at
// the half float's limit) outweigh metres of lit surface in every footprint that holds it
// (hard_light_touching). With u_jacobian 0 (the paper) w = 1 and a = alpha. Table 1 leaves the
// radiance texel's alpha free (opacity is in the normal and depth textures). Every layer texel of
// the block is written, empty ones as 0, so the arrays need no clear.
//
// The light view is the paper's RSM (light_view.h, GIB_LV_PACKED16): each texel's reflected
// radiance (Table 1: rho L_d <n.l> / pi) and depth, its normal and <n.l>.
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_2D, local_size_y = GIB_GROUP_2D) in;
layout(binding = GIB_UNIT_LV_PACKED0) uniform sampler2DArray u_lv_radiance_depth;
layout(binding = GIB_UNIT_LV_PACKED1) uniform sampler2DArray u_lv_normal_nl;
layout(binding = LRSM_IMAGE_RADIANCE, rgba16f) writeonly uniform image2DArray o_radiance;
layout(binding = LRSM_IMAGE_NORMAL, rgba16f) writeonly uniform image2DArray o_normal;
layout(binding = LRSM_IMAGE_DEPTH, rgba16) writeonly uniform image2DArray o_depth;
layout(location = LRSM_BUILD_LOC_FACE) uniform int u_face;
layout(location = LRSM_BUILD_LOC_LIGHT) uniform int u_light;
layout(location = LRSM_BUILD_LOC_HALF) uniform int u_half;  // layer side: light-view res / 2
layout(location = LRSM_BUILD_LOC_JACOBIAN) uniform int u_jacobian; // 1: texels weighted by area

const int MAX_LAYERS = 16;

// The texel's area weight (lrsm_area_weight): its direction's cosine to the face's axis from its
// place on the face (side 2 u_half texels of lv_texel at unit distance, centred on the axis).
float texel_area(ivec2 t, float z, float cosnl)
{
    vec2 p = (vec2(t) + 0.5 - float(u_half)) * lv_texel(u_light);
    float cos_face = inversesqrt(1.0 + dot(p, p));
    return lrsm_area_weight(lv_kind(u_light), z, lrsm_table[u_light].y, cos_face, cosnl);
}

void main()
{
    ivec2 b = ivec2(gl_GlobalInvocationID.xy);
    if (b.x >= u_half || b.y >= u_half)
        return;
    int layers = u_depth_parts * u_normal_parts;
    vec4 rad[MAX_LAYERS]; // sum of radiance x area weight, of area weights
    vec3 nrm[MAX_LAYERS];
    vec3 dep[MAX_LAYERS]; // sum of warped z, of warped z^2, member count
    for (int l = 0; l < layers; l++) {
        rad[l] = vec4(0.0);
        nrm[l] = vec3(0.0);
        dep[l] = vec3(0.0);
    }
    for (int i = 0; i < 4; i++) {
        ivec3 t = ivec3(2 * b + ivec2(i & 1, i >> 1), u_face);
        vec4 rz = texelFetch(u_lv_radiance_depth, t, 0);
        float z = rz.w;
        if (isinf(z))
            continue;
        vec4 nl = texelFetch(u_lv_normal_nl, t, 0);
        vec3 n = nl.xyz;
        int k = lrsm_normal_part(nl.w, u_normal_parts);
        if (k < 0)
            continue;
        float w = u_jacobian != 0 ? texel_area(t.xy, z, nl.w) : 1.0;
        vec4 r = vec4(rz.rgb * w, w);
        for (int d = 0; d < u_depth_parts; d++) {
            if (!lrsm_in_depth_layer(u_light, d, z))
                continue;
            float lo, hi;
            lrsm_layer_range(u_light, d, lo, hi);
            float zw = clamp((z - lo) / (hi - lo), 0.0, 1.0);
            int li = d * u_normal_parts + k;
            rad[li] += r;
            nrm[li] += n;
            dep[li] += vec3(zw, zw * zw, 1.0);
        }
    }
    for (int l = 0; l < layers; l++) {
        ivec3 o = ivec3(b, u_face * layers + l);
        float alpha = dep[l].z * 0.25;
        imageStore(o_radiance, o, rad[l] * 0.25);
        imageStore(o_normal, o, vec4(nrm[l] * 0.25, alpha));
        imageStore(o_depth, o, vec4(dep[l].xy * 0.25, alpha, 0.0));
    }
}

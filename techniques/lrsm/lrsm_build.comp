#include "common/light_view.glsl"
#include "lrsm/lrsm_common.glsl"
// LRSM construction (Sec. 4.3, 5; Table 1): one invocation per 2x2 block of one light-view face.
// Each RSM texel goes to the layer of its depth partition (both layers inside an overlap band) and
// its <n.l> partition; the texels of the block that share a layer are merged into that layer's
// texel, every value premultiplied by the opacity alpha = members / 4 (lrsm_build_block() in
// lrsm_math.c is the CPU mirror). Every layer texel of the block is written, empty ones as 0, so
// the arrays need no clear.
//
// Reflected radiance (Table 1: rho L_d <n.l> / pi) from the light view's FLUX, which is rho times
// the flux reaching the texel: that flux crosses the texel's area perpendicular to the light,
// A_perp = z^2 dw with dw = s^2 cos^3(theta) (perspective and cube faces, z the distance to the
// light, theta the angle from the view axis) or s^2 (orthographic), so the surface's irradiance is
// flux <n.l> / A_perp and its Lambertian radiance R = FLUX <n.l> / (pi A_perp).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = GIB_UNIT_LV_DEPTH) uniform sampler2DArray u_lv_depth;
layout(binding = GIB_UNIT_LV_NORMAL) uniform sampler2DArray u_lv_normal;
layout(binding = GIB_UNIT_LV_FLUX) uniform sampler2DArray u_lv_flux;
layout(binding = 0, rgba16f) writeonly uniform image2DArray o_radiance;
layout(binding = 1, rgba16f) writeonly uniform image2DArray o_normal;
layout(binding = 2, rgba16) writeonly uniform image2DArray o_depth;
layout(location = GIB_LOC_OWN_FIRST + 2) uniform int u_face;
layout(location = GIB_LOC_OWN_FIRST + 3) uniform int u_light;
layout(location = GIB_LOC_OWN_FIRST + 4) uniform int u_half;   // layer side: light-view res / 2

const float PI = 3.14159265358979;
const int MAX_LAYERS = 16;

void main()
{
    ivec2 b = ivec2(gl_GlobalInvocationID.xy);
    if (b.x >= u_half || b.y >= u_half)
        return;
    int layers = u_depth_parts * u_normal_parts;
    vec3 rad[MAX_LAYERS];
    vec3 nrm[MAX_LAYERS];
    vec3 dep[MAX_LAYERS]; // sum of warped z, of warped z^2, member count
    for (int l = 0; l < layers; l++) {
        rad[l] = vec3(0.0);
        nrm[l] = vec3(0.0);
        dep[l] = vec3(0.0);
    }
    int kind = lv_kind(u_light);
    float s = lv_texel(u_light);
    vec3 axis = lv_axis(u_face);
    mat4 inv = inverse(lv_view_proj(u_face));
    float res = float(2 * u_half);
    for (int i = 0; i < 4; i++) {
        ivec2 t = 2 * b + ivec2(i & 1, i >> 1);
        float z = texelFetch(u_lv_depth, ivec3(t, u_face), 0).r;
        vec4 flux = texelFetch(u_lv_flux, ivec3(t, u_face), 0);
        if (flux.w < 0.5 || isinf(z))
            continue;
        vec3 n = texelFetch(u_lv_normal, ivec3(t, u_face), 0).xyz;
        vec3 l;        // toward the light
        float a_perp;  // the texel's area perpendicular to the light
        if (kind == 2) {
            l = -axis;
            a_perp = s * s;
        } else {
            vec2 ndc = (vec2(t) + 0.5) / res * 2.0 - 1.0;
            vec4 p0 = inv * vec4(ndc, -1.0, 1.0), p1 = inv * vec4(ndc, 1.0, 1.0);
            vec3 dir = normalize(p1.xyz / p1.w - p0.xyz / p0.w);
            l = -dir;
            float c = dot(dir, axis);
            a_perp = z * z * s * s * c * c * c;
        }
        float cosnl = dot(n, l);
        int k = lrsm_normal_part(cosnl, u_normal_parts);
        if (k < 0)
            continue;
        vec3 r = flux.rgb * (cosnl / (PI * a_perp));
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
        imageStore(o_radiance, o, vec4(rad[l] * 0.25, alpha));
        imageStore(o_normal, o, vec4(nrm[l] * 0.25, alpha));
        imageStore(o_depth, o, vec4(dep[l].xy * 0.25, alpha, 0.0));
    }
}

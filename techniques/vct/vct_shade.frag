#include "common/scene.glsl"
#include "vct/vct_trace.glsl"
// The cone passes on the G-buffer (Sugihara et al. 2014, Sec. 3.1 and 6), one per output:
//  DIRECT:   every light with a shadow cone toward it (visibility 1 - occlusion), same BRDF and
//            falloff as the reference's `direct`;
//  INDIRECT: rho_d x sum_i w_i I_i over the 6 diffuse cones (common/voxel_cone.glsl: weights are
//            the cones' cosine-weighted shares, summing to 1): the cosine-weighted mean incoming
//            radiance times pi, times rho_d / pi (the reference's one diffuse bounce, L D D E);
//  GLOSSY:   one cone along the mirror direction on pixels with a specular lobe: rho_s I for a
//            mirror; rho_s I max(0, n.r) for normalised Phong (its lobe integrates cos to about
//            n.r), the reference's L D S E.
layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position;
layout(binding = GIB_UNIT_GBUF_NORMAL) uniform sampler2D g_normal;
layout(binding = GIB_UNIT_GBUF_ALBEDO) uniform sampler2D g_albedo;
layout(binding = GIB_UNIT_GBUF_SPECULAR) uniform sampler2D g_specular;
layout(location = VCT_SHADE_LOC_EYE) uniform vec3 u_eye;
layout(location = VCT_SHADE_LOC_LIGHT_COUNT) uniform int u_light_count;
layout(location = VCT_SHADE_LOC_TAN_HALF) uniform float u_tan_half;   // tan(aperture / 2)
layout(location = VCT_SHADE_LOC_MAX_DIST) uniform float u_max_dist;   // world units
in vec2 v_texcoord;
layout(location = 0) out vec4 o_color;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(g_position, px, 0);
    o_color = vec4(0.0, 0.0, 0.0, 1.0);
    if (pos.w < 0.5)
        return;
    vec3 n = texelFetch(g_normal, px, 0).xyz;
    vec4 alb = texelFetch(g_albedo, px, 0);
    vec4 spec = texelFetch(g_specular, px, 0);
    vec3 wo = normalize(u_eye - pos.xyz);
    vec3 sum = vec3(0.0);
#if defined(DIRECT)
    for (int i = 0; i < u_light_count; i++) {
        vec3 wi;
        float dist;
        vec3 E = light_eval(lights[i], pos.xyz, wi, dist);
        float cosi = dot(n, wi);
        if (cosi <= 0.0 || max(E.r, max(E.g, E.b)) <= 0.0)
            continue;
        bool local = dist < 1e30; // point and spot lights: the cone tapers toward the light
        float v = 1.0 - vct_cone_ex(pos.xyz, n, wi, u_tan_half, min(dist, u_max_dist), local).a;
        sum += brdf(alb.rgb, spec, int(alb.w + 0.5), n, wo, wi) * E * (cosi * v);
    }
#elif defined(INDIRECT)
    for (int i = 0; i < diffuse_cone_count(); i++)
        if (diffuse_cone_share(i) > 0.0)
            sum += diffuse_cone_share(i) * vct_cone(pos.xyz, n, diffuse_cone_dir(i, n), u_tan_half,
                                                    u_max_dist).rgb;
    sum *= alb.rgb;
#else
    int type = int(alb.w + 0.5);
    if (type == 0)
        return;
    vec3 r = reflect(-wo, n);
    sum = spec.rgb * vct_cone(pos.xyz, n, r, u_tan_half, u_max_dist).rgb;
    if (type == 2)
        sum *= max(dot(n, r), 0.0);
#endif
    o_color = vec4(sum, 1.0);
}

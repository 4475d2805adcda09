#include "common/scene.glsl"
#include "common/light_view.glsl"
#include "common/voxel_cone.glsl"
#include "lrsm/lrsm_common.glsl"
#include "lrsm/lrsm_sample.glsl"
#include "lrsm/lrsm_hits.glsl"
#include "lrsm/lrsm_march.glsl"
// The three cone passes of `lrsm` on the G-buffer (Sec. 3.1, 5, 6), one program each by define:
//  DIFFUSE:  6 cones over the hemisphere (voxel_cone.glsl's set), Eq. 1 front to back with alpha
//            from the occlusion voxels and L from the LRSM: a cone's integral of cos dw is pi
//            times its share w_i, so the pixel's indirect radiance is rho sum_i w_i I_i.
//  SPECULAR: one cone along the mirror direction r, on pixels with a specular lobe only: rho_s I
//            for a mirror, rho_s <n.r> I for a narrow normalised Phong lobe. The Phong exponent
//            does not set the aperture (Sec. 6: a 10-degree cone for every specular pixel).
//  SHADOW:   direct light of every light (scene.glsl's BRDF and falloff) times its shadow cone's
//            visibility (voxel_cone.glsl's shadow_cone_ex, tapered toward a point or spot light)
//            instead of a shadow map; its alpha follows `opacity` as the other cones'.
// Cone marching (Eq. 1), as shadow_cone: the samples of lrsm_march.glsl until the cone is opaque
// (A > 255/256), light from the LRSM (lrsm_hits, or lrsm_sample with hits 0), alpha from
// voxel_step_alpha. `opacity` 0 is the paper's reading (the mips' mean occupancy: a one-voxel wall
// in a sample d voxels wide reads ~1/d, so wide cones pass thin walls); 1 (default) reads it as a
// density over the step. Departures from the literal reading, each with its reason:
//  - A sample stays in front of the receiver's plane, its diameter at most its centre's height
//    above it: a tilted cone's samples otherwise reach the receiver's own voxels, and read as a
//    density that occupancy blocks open ground's own cones more the finer the voxels.
//  - `hits` 1 (default): a sample's light and alpha are the share of its rays that meet the lit
//    surfaces inside it (lrsm_hits.glsl: each layer a plane, Eq. 8 averaged over the cone's cap),
//    and the voxels' alpha beyond the lit coverage blocks as unlit surface by the share of rays
//    its own plane stops (occupancy_plane_hits). Eq. 1's isotropic alpha blocks a cone by a
//    surface's full coverage at any angle, and Eq. 8 on the axis culls the surfaces a cone runs
//    along (a wall's central cone beside a floor lit from above). hits 0 keeps Algorithm 1:
//  - `coverage` 1 (default with hits 0): L = sum A R V N / max(sum A V, alpha), since Eq. 5's
//    R V N already carries the lit share V and Eq. 1 multiplies it by the same coverage again
//    (coverage 0, the paper's reading). The floor alpha keeps a lit surface glimpsed by a Gaussian
//    tail from lending an unlit occluder its whole radiance.
// PERFORMANCE.md, "Quality behind the voxel techniques' defaults", has the measurements.
layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position;
layout(binding = GIB_UNIT_GBUF_NORMAL) uniform sampler2D g_normal;
layout(binding = GIB_UNIT_GBUF_ALBEDO) uniform sampler2D g_albedo;
layout(binding = GIB_UNIT_GBUF_SPECULAR) uniform sampler2D g_specular;
layout(location = LRSM_CONE_LOC_EYE) uniform vec3 u_eye;
layout(location = LRSM_CONE_LOC_APERTURE) uniform float u_aperture;     // radians, full angle
// 1: L normalised by the lit coverage
layout(location = LRSM_CONE_LOC_COVERAGE) uniform int u_coverage;
// 1: a sample's light and opacity are the share of its rays that meet the lit planes (lrsm_hits)
layout(location = LRSM_CONE_LOC_HITS) uniform int u_hits;
in vec2 v_texcoord;
layout(location = 0) out vec4 o_color;

// The share of a sample's rays (centre p, diameter d, cone along dir, t and b across it) that the
// occupancy's own plane stops within the step: the occupancy's variation across the sample
// (central differences of the mip voxel_step_alpha reads, half a sample apart) along the axis and
// across it gives the cosine between the axis and the plane's normal, and a plane through the
// centre at that tilt (lrsm_plane_hits at distance 0) is met by all of the rays when it faces the
// axis and by few when it lies along it. Uniform occupancy (no plane) stops all it covers.
float occupancy_plane_hits(vec3 p, float d, vec3 dir, vec3 t, vec3 b, float sin_half)
{
    float h = 0.5 * d, o = voxel_occlusion(p, h);
    vec3 v = vec3(0.0);
    for (int s = -1; s <= 1; s += 2) {
        v.x += abs(voxel_occlusion(p + float(s) * h * dir, h) - o);
        v.y += abs(voxel_occlusion(p + float(s) * h * t, h) - o);
        v.z += abs(voxel_occlusion(p + float(s) * h * b, h) - o);
    }
    float len = length(v);
    if (len < 1e-4)
        return 1.0;
    float ca = v.x / len;
    float E = lrsm_cap_cosine(ca, sqrt(max(1.0 - ca * ca, 0.0)), sin_half);
    return lrsm_plane_hits(0.0, E, h, u_step_factor, 0.0);
}

vec3 trace_cone(vec3 x, vec3 n, vec3 dir, float aperture)
{
    LrsmCone k = lrsm_cone_start(x, n, dir, aperture);
    float sin_half = sin(0.5 * aperture);
    vec3 across_t, across_b;   // the cone's basis, for occupancy_plane_hits
    ortho_basis(dir, across_t, across_b);
    vec3 I = vec3(0.0), c;
    float A = 0.0, d;
    for (int i = 0; i < 512 && A < 255.0 / 256.0 && lrsm_cone_sample(k, c, d); i++) {
        float a = voxel_step_alpha(c, d, u_step_factor);
        if (a > 0.0 && u_hits != 0) {
            // the lit planes' hits, at most all of the rays; the voxels' alpha beyond the lit
            // coverage blocks as unlit surface, by the share its own plane stops
            LrsmHits h = lrsm_hits(c, 0.5 * d, dir, sin_half, u_step_factor);
            float norm = max(h.hit, 1.0), hit = h.hit / norm;
            float stop = occupancy_plane_hits(c, d, dir, across_t, across_b, sin_half);
            float unlit = max(a - min(h.lit, a), 0.0) * stop;
            I += (1.0 - A) * h.light / norm;
            A += (1.0 - A) * (hit + (1.0 - hit) * unlit);
        } else if (a > 0.0) {
            vec4 s = lrsm_sample(c, 0.5 * d, -dir);
            vec3 L = u_coverage != 0 ? s.rgb / max(s.a, a) : s.rgb;
            I += (1.0 - A) * a * L;
            A += (1.0 - A) * a;
        }
        lrsm_cone_advance(k, d);
    }
    return I;
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(g_position, px, 0);
    o_color = vec4(0.0, 0.0, 0.0, 1.0);
    if (pos.w < 0.5)
        return;
    vec3 x = pos.xyz;
    vec3 n = texelFetch(g_normal, px, 0).xyz;
    vec4 alb = texelFetch(g_albedo, px, 0);
#if defined(DIFFUSE)
    if (max(alb.r, max(alb.g, alb.b)) <= 0.0)
        return;
    vec3 sum = vec3(0.0);
    for (int i = 0; i < diffuse_cone_count(); i++)
        if (diffuse_cone_share(i) > 0.0)
            sum += diffuse_cone_share(i) * trace_cone(x, n, diffuse_cone_dir(i, n), u_aperture);
    o_color.rgb = alb.rgb * sum;
#elif defined(SPECULAR)
    int type = int(alb.w + 0.5);
    vec4 spec = texelFetch(g_specular, px, 0);
    if (type == 0 || max(spec.r, max(spec.g, spec.b)) <= 0.0)
        return;
    vec3 wo = normalize(u_eye - x);
    vec3 r = reflect(-wo, n);
    float cosr = dot(n, r);
    if (cosr <= 0.0)
        return;
    vec3 I = trace_cone(x, n, r, u_aperture);
    o_color.rgb = spec.rgb * (type == 1 ? 1.0 : cosr) * I;
#else
    vec4 spec = texelFetch(g_specular, px, 0);
    vec3 wo = normalize(u_eye - x);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < u_lrsm_lights; i++) {
        vec3 wi;
        float dist;
        vec3 E = light_eval(lights[i], x, wi, dist);
        float cosi = dot(n, wi);
        if (cosi <= 0.0 || max(E.r, max(E.g, E.b)) <= 0.0)
            continue;
        // a point or spot light within the cone's length: the cone tapers toward it
        float cone_length = u_max_distance * u_voxel_size;
        float v = shadow_cone_ex(x, n, wi, min(dist, cone_length), u_aperture, u_step_factor,
                                 u_start_offset, dist <= cone_length);
        sum += brdf(alb.rgb, spec, int(alb.w + 0.5), n, wo, wi) * E * (cosi * v);
    }
    o_color.rgb = sum;
#endif
}

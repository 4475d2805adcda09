#include "common/scene.glsl"
#include "common/light_view.glsl"
#include "common/voxel_cone.glsl"
#include "lrsm/lrsm_common.glsl"
#include "lrsm/lrsm_sample.glsl"
#include "lrsm/lrsm_hits.glsl"
#include "lrsm/lrsm_march.glsl"
// The three cone passes of `lrsm` on the G-buffer (Sec. 3.1, 5, 6), one program each by define:
//  DIFFUSE:  6 cones over the hemisphere (voxel_cone.glsl's set), Eq. 1 front to back with alpha
//            from the occlusion voxels and L from the LRSM. L_o = rho/pi int L_in cos dw, and a
//            cone's integral of cos dw is pi times its cosine-weighted share w_i, so the pixel's
//            indirect radiance is rho sum_i w_i I_i.
//  SPECULAR: one cone along the mirror direction r, on pixels with a specular lobe only: a mirror
//            reflects rho_s I; a normalised Phong lobe rho_s (n+2)/(2 pi) cos^n integrates to
//            rho_s <n.r> over a narrow lobe, so rho_s <n.r> I. The Phong exponent does not set
//            the aperture (the paper's 10-degree cone for every specular pixel, Sec. 6).
//  SHADOW:   direct light of every light (the BRDF and falloff of scene.glsl), each times its
//            shadow cone's visibility (voxel_cone.glsl's shadow_cone_ex, tapering toward a point
//            or spot light) instead of a shadow map. Its alpha follows `opacity` as the other
//            cones': with the paper's mean occupancy a box's one-voxel shell reads alpha ~ 1/d in a
//            sample d voxels wide, and the Cornell box's tall box let 0.19 of the light through to
//            its umbra (0.01 with the density).
// Cone marching (Eq. 1), as voxel_cone.glsl's shadow_cone: the samples of lrsm_march.glsl, alpha
// corrected for the step as 1 - (1 - alpha)^step_factor, until the cone is opaque (A > 255/256).
// A sample is a sphere of radius d/2 at its centre; its light comes from the LRSM (lrsm_hits, or
// lrsm_sample with hits 0) and its alpha from voxel_cone.glsl's voxel_step_alpha. Parameter `opacity` 0 is the paper's reading (the
// mips' mean occupancy as the sample's alpha: a wall one voxel thick inside a sample d voxels wide
// reads alpha ~ 1/d, so wide cones pass thin walls nearly unweighted and the indirect level falls
// as 1/voxel_res in closed scenes); 1 (default) reads the occupancy as a density over the step.
// Three departures from the literal reading, each with its reason:
//  - A sample stays in front of the receiver's plane: its diameter at most its centre's height
//    above that plane. A 60-degree cone tilted 60 degrees from n grazes the plane, and its samples
//    (2 t tan 30 wide) and their trilinear footprints reach the receiver's own surface from ~20
//    voxels on; read as a density, the little occupancy they find there is multiplied by the
//    sample's width in voxels, so open ground blocks its own tilted cones more the finer the
//    voxels, and the indirect light falls with voxel_res (PERFORMANCE.md, "Quality behind the
//    voxel techniques' defaults"). At twice the height (only the trilinear footprint's centre
//    kept clear) the Cornell box's indirect light falls from 0.92 to 0.76 of the reference's
//    between 64^3 and 256^3.
//  - `hits` 1 (default): a sample's light and alpha are the share of its rays that meet the lit
//    surfaces inside it (lrsm_hits.glsl: each LRSM layer a plane, Eq. 8 averaged over the cone's
//    cap), and what is left of the voxels' alpha beyond the lit coverage blocks as unlit surface,
//    by the share of rays its own plane stops (occupancy_plane_hits). Eq. 1 with an isotropic
//    alpha lets a surface block a cone by its full coverage whatever the angle it is seen at, and
//    Eq. 8 on the axis culled the surfaces a cone runs along: in a box lit from above a wall's
//    central cone runs parallel to the lit floor, read exactly 0 where the path tracer's cone
//    reads 3-8% of the light, and was blocked whole by the unlit ceiling it grazes; the light came
//    in dark blotches with straight borders (PERFORMANCE.md, "lrsm: a cone sample as the share of
//    its rays that meet the lit planes", has the measurements). hits 0 keeps Algorithm 1's sample
//    with Eq. 1's alpha:
//  - `coverage` 1 (default with hits 0): a sample's radiance is the LRSM's over the coverage of the lit
//    surfaces inside it, L = sum A R V N / max(sum A V, alpha). Eq. 5's L = R V N already carries
//    the lit surfaces' share V of the footprint, and Eq. 1 multiplies it by the voxels' alpha, the
//    same surfaces' coverage counted a second time (the paper's reading, coverage 0, loses a
//    quarter of the Cornell box's indirect light and half the furnace's). The floor alpha
//    keeps a lit surface glimpsed by a Gaussian tail (V of a few percent behind an unlit
//    occluder) from lending the occluder its whole radiance.
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

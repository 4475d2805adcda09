// Photon tracing with photon differentials through LDMs (Aalund et al. 2015, Sec. 3.4 and 4.2):
// every texel of the light's view (a reflective-shadow-map face rendered by the shared G-buffer pass)
// is a primary photon from the point light, hitting x1. It is split into one secondary photon per
// LDM direction in the hemisphere of n1 (photon splitting instead of Russian roulette), each traced
// with the LDM (Sec. 3.1), discarded unless the camera sees where it lands, diffusely reflected (the
// directional differentials rotated by the quaternion taking d1 to d2), transferred to x2 (Igehy
// 1999), and stored for splatting. LDDE paths only: photons are absorbed after this bounce.
#include "common/scene.glsl"
#include "ldm/ldm_trace.glsl"
#include "ldm_indirect/photon.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D rsm_position;
layout(binding = 1) uniform sampler2D rsm_normal;
layout(binding = 2) uniform sampler2D rsm_albedo;
layout(binding = 3) uniform sampler2D g_position;
layout(binding = 4) uniform sampler2D g_normal;
layout(std430, binding = 8) writeonly buffer Photons { Photon photons[]; };
layout(std430, binding = 9) buffer Command { DrawCommand command; uint overflow; };
layout(location = 0) uniform int u_light;
layout(location = 1) uniform vec3 u_face_forward;
layout(location = 2) uniform vec3 u_face_right;
layout(location = 3) uniform vec3 u_face_up;
layout(location = 4) uniform int u_res;             // light-view photon resolution
layout(location = 5) uniform int u_first;           // LDMs of the bound page
layout(location = 6) uniform int u_count;
layout(location = 7) uniform float u_split_weight;  // 2/N: each direction stands for 2 pi / N sr
layout(location = 8) uniform mat4 u_camera_view_proj; // maps p - u_camera_origin
layout(location = 12) uniform vec3 u_camera_origin;
layout(location = 9) uniform ivec2 u_camera_size;
layout(location = 10) uniform float u_offset_texels;
layout(location = 11) uniform uint u_capacity;

vec3 rotate(vec4 q, vec3 v)
{
    vec3 t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

// Rotation quaternion taking unit vector a to unit vector b (alpha(w_i, w_o) of Sec. 3.4).
vec4 rotation_between(vec3 a, vec3 b)
{
    float c = dot(a, b);
    if (c < -0.999999) {
        vec3 axis = abs(a.x) < 0.9 ? cross(a, vec3(1, 0, 0)) : cross(a, vec3(0, 1, 0));
        return vec4(normalize(axis), 0.0);
    }
    return normalize(vec4(cross(a, b), 1.0 + c));
}

// Transfer of a positional differential along d over distance t onto the plane with normal n
// (Igehy 1999): D x' = D x + t D d + (D t) d, D t = -((D x + t D d) . n) / (d . n).
vec3 transfer(vec3 dx, vec3 dd, vec3 d, float t, vec3 n)
{
    vec3 a = dx + t * dd;
    return a - (dot(a, n) / dot(d, n)) * d;
}

// Deviation from Sec. 3.4, for numerical stability: the rotated directional differential can point
// against the positional one, and then the footprint focuses to a line at t2 = t1 and its irradiance
// (Eq. 4) diverges: a point light at height h over a floor focuses every photon that bounces
// straight up onto a ceiling at height 2h (measured on the Cornell box: single-pixel splats 40x
// the reference). A diffuse bounce spreads light and never focuses it, so each rotated differential
// takes the sign that makes it add to the transferred positional differential.
vec3 diverging(vec3 dx, vec3 dd, vec3 d, float t, vec3 n)
{
    vec3 p = transfer(dx, vec3(0.0), d, t, n);
    vec3 s = transfer(vec3(0.0), dd, d, t, n);
    return dot(p, s) < 0.0 ? -dd : dd;
}

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_res || px.y >= u_res)
        return;
    vec4 p1 = texelFetch(rsm_position, px, 0);
    if (p1.w < 0.5)
        return;
    vec3 x1 = p1.xyz;
    vec3 n1 = texelFetch(rsm_normal, px, 0).xyz;   // faces the light
    vec3 rho1 = texelFetch(rsm_albedo, px, 0).rgb;
    Light light = lights[u_light];
    vec3 lp = light.position_type.xyz;

    // Primary photon: direction through the texel centre and its flux I(d) * solid angle.
    float s = 2.0 / float(u_res);
    vec2 uv = (vec2(px) + 0.5) * s - 1.0;
    vec3 D = u_face_forward + uv.x * u_face_right + uv.y * u_face_up;
    float len = length(D);
    vec3 d1 = D / len;
    vec3 wi;
    float r1;
    vec3 E = light_eval(light, x1, wi, r1);     // I * falloff / r^2
    vec3 flux1 = E * r1 * r1 * (s * s / (len * len * len));
    if (max(flux1.r, max(flux1.g, flux1.b)) <= 0.0 || dot(n1, -d1) <= 0.0)
        return;
    // Directional differentials of d = D/|D| with D_u D = s * right (Igehy 1999, Eq. for normalised
    // directions), positional differentials at the point light are 0, then transfer to x1.
    vec3 ddu = (dot(D, D) * (s * u_face_right) - dot(D, s * u_face_right) * D) / (len * len * len);
    vec3 ddv = (dot(D, D) * (s * u_face_up) - dot(D, s * u_face_up) * D) / (len * len * len);
    float t1 = dot(x1 - lp, d1);
    vec3 dxu = transfer(vec3(0.0), ddu, d1, t1, n1);
    vec3 dxv = transfer(vec3(0.0), ddv, d1, t1, n1);

    for (int i = u_first; i < u_first + u_count; i++) {
        vec3 v = ldm_info[i].dir_extent.xyz;
        float c = dot(n1, v);
        if (abs(c) < 1e-4)
            continue;
        float sgn = sign(c);
        vec3 d2 = sgn * v;
        float texel = ldm_texel(i);
        vec3 x1o = x1 + n1 * (u_offset_texels * texel);
        float t2 = ldm_trace(i, x1o, sgn, ldm_eps(texel, abs(c)));
        if (t2 < 0.0)
            continue;
        vec3 x2 = x1o + t2 * d2;
        // Visible from the camera? The surface the G-buffer holds at x2's pixel must be the one the
        // photon landed on: x2 within two LDM texels of its tangent plane. (x2 comes from the LDM
        // node of x1's pixel, so it is off the true hit by up to ~0.7 texel sideways along d2: a
        // point-to-point test would reject grazing photons and lose their energy.)
        vec4 clip = u_camera_view_proj * vec4(x2 - u_camera_origin, 1.0);
        if (clip.w <= 0.0)
            continue;
        ivec2 cp = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * vec2(u_camera_size)));
        if (any(lessThan(cp, ivec2(0))) || any(greaterThanEqual(cp, u_camera_size)))
            continue;
        vec4 g = texelFetch(g_position, cp, 0);
        if (g.w < 0.5)
            continue;
        vec3 n2 = texelFetch(g_normal, cp, 0).xyz; // faces the camera
        float h = dot(x2 - g.xyz, n2);
        if (abs(h) > 2.0 * texel)
            continue;
        if (dot(n2, d2) >= 0.0)
            continue; // lands on the side the camera does not see
        x2 -= h * n2; // onto the receiving surface, where the splat's kernel is centred
        vec4 q = rotation_between(d1, d2);
        vec3 du2 = transfer(dxu, diverging(dxu, rotate(q, ddu), d2, t2, n2), d2, t2, n2);
        vec3 dv2 = transfer(dxv, diverging(dxv, rotate(q, ddv), d2, t2, n2), d2, t2, n2);
        // Split flux: Phi1 * (rho1/pi) * cos * (2 pi / N).
        vec3 flux2 = flux1 * rho1 * (abs(c) * u_split_weight);
        uint k = atomicAdd(command.count, 1u);
        if (k >= u_capacity) {
            atomicAdd(overflow, 1u);
            atomicAdd(command.count, 0xffffffffu); // undo: the draw must not read past the buffer
            continue;
        }
        photons[k] = Photon(vec4(x2, 1.0), vec4(du2, 0.0), vec4(dv2, 0.0), vec4(flux2, 0.0));
    }
}

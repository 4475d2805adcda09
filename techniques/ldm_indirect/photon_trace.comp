// Photon tracing with photon differentials through LDMs (Aalund et al. 2015, Sec. 3.4 and 4.2):
// every texel of a face of the light's view (the shared light views, techniques/common/light_view.*,
// a reflective shadow map with the flux each texel's surface reflects) is a primary photon from the
// point or spot light, hitting x1. It is split into one secondary photon per
// LDM direction in the hemisphere of n1 (photon splitting instead of Russian roulette), each traced
// with the LDM (Sec. 3.1), discarded unless the camera sees where it lands, diffusely reflected (the
// directional differentials rotated by the quaternion taking d1 to d2), transferred to x2 (Igehy
// 1999), and stored for splatting. LDDE paths only: photons are absorbed after this bounce.
#include "common/scene.glsl"
#include "common/light_view.glsl"
#include "ldm/ldm_trace.glsl"
#include "ldm_indirect/photon.glsl"
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_2D, local_size_y = GIB_GROUP_2D) in;
layout(binding = GIB_UNIT_LV_POSITION) uniform sampler2DArray lv_position;
layout(binding = GIB_UNIT_LV_NORMAL) uniform sampler2DArray lv_normal;
layout(binding = GIB_UNIT_LV_FLUX) uniform sampler2DArray lv_flux;
layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position;
layout(binding = GIB_UNIT_GBUF_NORMAL) uniform sampler2D g_normal;
layout(std430, binding = LDMI_SSBO_PHOTONS) writeonly buffer Photons { Photon photons[]; };
layout(std430, binding = LDMI_SSBO_COMMAND) buffer Command { DrawCommand command; uint overflow; };
layout(location = LDMI_TRACE_LOC_LIGHT) uniform int u_light;
layout(location = LDMI_TRACE_LOC_FACE) uniform int u_face;           // the light-view layer traced
layout(location = LDMI_TRACE_LOC_RES) uniform int u_res;            // light-view photon resolution
layout(location = LDMI_TRACE_LOC_FIRST) uniform int u_first;          // LDMs of the bound page
layout(location = LDMI_TRACE_LOC_COUNT) uniform int u_count;
// 2/N: each direction stands for 2 pi / N sr
layout(location = LDMI_TRACE_LOC_SPLIT_WEIGHT) uniform float u_split_weight;
// maps p - u_camera_origin
layout(location = LDMI_TRACE_LOC_VIEW_PROJ) uniform mat4 u_camera_view_proj;
layout(location = LDMI_TRACE_LOC_ORIGIN) uniform vec3 u_camera_origin;
layout(location = LDMI_TRACE_LOC_SIZE) uniform ivec2 u_camera_size;
layout(location = LDMI_TRACE_LOC_OFFSET) uniform float u_offset_texels;
layout(location = LDMI_TRACE_LOC_CAPACITY) uniform uint u_capacity;

// Flux audit (built with AUDIT defined, ldm_indirect.h): every invocation sums the flux of each
// fate below, the work group adds its sums, and work group g adds them to audit[g] (one slot
// per work group, accumulated over faces, lights and pages; the host clears and reads it).
#ifdef AUDIT
#include "ldm_indirect/audit.glsl"
layout(std430, binding = LDMI_SSBO_AUDIT) buffer Audit { vec4 audit[]; };
// 1 for the first LDM page: count the primary photon
layout(location = LDMI_TRACE_LOC_FIRST_PAGE) uniform int u_first_page;
vec3 acc[AUDIT_COUNT];
shared vec3 group_acc[AUDIT_COUNT][GIB_GROUP_2D * GIB_GROUP_2D];
#define TALLY(k, v) acc[k] += (v)
#else
#define TALLY(k, v)
#endif

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

// The trace of Sec. 3.1 (ldm/ldm_trace.glsl) from a surface point x1 with normal n1 into the
// hemisphere of n1, along sgn*v of LDM i. The generic trace leaves x1's own surface by skipping
// every node within a depth tolerance of x1 that grows with tan(n1, v) up to ~6 texels: that also
// skips every OTHER surface that close, i.e. the walls, curtains and column bases a grazing photon
// from the floor should land on. Here a node is x1's own surface when it lies on x1's tangent plane
// (height within a quarter texel: a node is the surface's depth at its pixel's centre, exact for a
// plane), and the hit is the first node beyond x1 that is above that plane. A ray into n1's
// hemisphere cannot hit anything below the plane, so nothing reachable is skipped but what lies
// within a quarter texel of the plane. Returns the distance along sgn*v, or -1.
float trace_from_surface(int i, vec3 x1, vec3 n1, float sgn, float texel)
{
    LdmInfo L = ldm_info[i];
    vec3 v = L.dir_extent.xyz;
    float e = L.dir_extent.w;
    int res = int(L.origin_res.w);
    vec3 t, b;
    ortho_basis(v, t, b);
    vec3 q = x1 - L.origin_res.xyz;
    vec2 st = vec2(dot(q, t), dot(q, b));
    ivec2 px = ivec2(floor((st / e * 0.5 + 0.5) * float(res)));
    if (any(lessThan(px, ivec2(0))) || any(greaterThanEqual(px, ivec2(res))))
        return -1.0;
    // The pixel centre's lateral offset from x1 and its height above x1's plane.
    vec2 centre = ((vec2(px) + 0.5) / float(res) * 2.0 - 1.0) * e;
    float h_lateral = dot((centre.x - st.x) * t + (centre.y - st.y) * b, n1);
    float nv = dot(n1, v);
    float z = dot(q, v);
    float tol = 0.25 * texel;
    uint cur = heads[L.offsets.x + uint(px.y * res + px.x)];
    float hit = -1.0;
    while (cur != LDM_END) {
        float d = uintBitsToFloat(nodes[cur].x);
        bool above = h_lateral + (d - z) * nv > tol; // the node's height above x1's plane
        if (sgn > 0.0) {
            if (d > z && above)
                return d - z;
        } else {
            if (d >= z)
                break;
            if (above)
                hit = z - d;
        }
        cur = nodes[cur].y;
    }
    return hit;
}

// Deviation from Sec. 3.4, for numerical stability: the rotated directional differential can point
// against the positional one, and then the footprint focuses to a line at t2 = t1 and its irradiance
// (Eq. 4) diverges: a point light at height h over a floor focuses every photon that bounces
// straight up onto a ceiling at height 2h, in single-pixel splats far too bright. A diffuse bounce
// spreads light and never focuses it, so each rotated differential takes the sign that makes it
// add to the transferred positional differential.
vec3 diverging(vec3 dx, vec3 dd, vec3 d, float t, vec3 n)
{
    vec3 p = transfer(dx, vec3(0.0), d, t, n);
    vec3 s = transfer(vec3(0.0), dd, d, t, n);
    return dot(p, s) < 0.0 ? -dd : dd;
}

void trace_texel(ivec2 px)
{
    Light light = lights[u_light];
    vec3 lp = light.position_type.xyz;
    // Primary photon: direction through the texel centre (texel side s on the plane at unit
    // distance) and its flux I(d) * solid angle.
    vec3 face_forward = lv_axis(u_face), face_right = lv_right(u_face), face_up = lv_up(u_face);
    float s = lv_texel(u_light);
    vec2 uv = (vec2(px) + 0.5 - 0.5 * float(u_res)) * s;
    vec3 D = face_forward + uv.x * face_right + uv.y * face_up;
    float len = length(D);
    vec3 d1 = D / len;
    float domega = s * s / (len * len * len);
    vec3 wi;
    float r1;
#ifdef AUDIT
    bool primary = u_first_page != 0;
    if (primary)
        TALLY(AUDIT_EMITTED, light_eval(light, lp + d1, wi, r1) * domega); // I(d1) at r = 1
#endif
    vec4 p1 = texelFetch(lv_position, ivec3(px, u_face), 0);
    if (p1.w < 0.5) {
#ifdef AUDIT
        if (primary)
            TALLY(AUDIT_NO_SURFACE, light_eval(light, lp + d1, wi, r1) * domega);
#endif
        return;
    }
    vec3 x1 = p1.xyz;
    vec3 n1 = texelFetch(lv_normal, ivec3(px, u_face), 0).xyz;   // faces the light
    vec3 reflected = texelFetch(lv_flux, ivec3(px, u_face), 0).rgb; // rho1 * flux1
    vec3 E = light_eval(light, x1, wi, r1);     // I * falloff / r^2
    vec3 flux1 = E * r1 * r1 * domega;
    if (max(flux1.r, max(flux1.g, flux1.b)) <= 0.0 || dot(n1, -d1) <= 0.0) {
#ifdef AUDIT
        if (primary)
            TALLY(AUDIT_BACK_FACING, flux1);
#endif
        return;
    }
#ifdef AUDIT
    if (primary)
        TALLY(AUDIT_REFLECTED, reflected);
#endif
    // Directional differentials of d = D/|D| with D_u D = s * right (Igehy 1999, Eq. for normalised
    // directions), positional differentials at the point light are 0, then transfer to x1.
    vec3 ddu = (dot(D, D) * (s * face_right) - dot(D, s * face_right) * D) / (len * len * len);
    vec3 ddv = (dot(D, D) * (s * face_up) - dot(D, s * face_up) * D) / (len * len * len);
    float t1 = dot(x1 - lp, d1);
    vec3 dxu = transfer(vec3(0.0), ddu, d1, t1, n1);
    vec3 dxv = transfer(vec3(0.0), ddv, d1, t1, n1);

    for (int i = u_first; i < u_first + u_count; i++) {
        vec3 v = ldm_info[i].dir_extent.xyz;
        float c = dot(n1, v);
        // Split flux: Phi1 * (rho1/pi) * cos * (2 pi / N).
        vec3 flux2 = reflected * (abs(c) * u_split_weight);
        TALLY(AUDIT_CARRIED, flux2);
        if (abs(c) < 1e-4) {
            TALLY(AUDIT_GRAZING, flux2);
            continue;
        }
        float sgn = sign(c);
        vec3 d2 = sgn * v;
        float texel = ldm_texel(i);
        vec3 x1o = x1 + n1 * (u_offset_texels * texel);
        float t2 = trace_from_surface(i, x1o, n1, sgn, texel);
        if (t2 < 0.0) {
            TALLY(AUDIT_MISS, flux2);
            continue;
        }
        vec3 x2 = x1o + t2 * d2;
        // Visible from the camera? The surface the G-buffer holds at x2's pixel must be the one the
        // photon landed on: x2 within two LDM texels of its tangent plane. (x2 comes from the LDM
        // node of x1's pixel, so it is off the true hit by up to ~0.7 texel sideways along d2: a
        // point-to-point test would reject grazing photons and lose their energy.)
        vec4 clip = u_camera_view_proj * vec4(x2 - u_camera_origin, 1.0);
        if (clip.w <= 0.0) {
            TALLY(AUDIT_BEHIND_CAMERA, flux2);
            continue;
        }
        ivec2 cp = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * vec2(u_camera_size)));
        if (any(lessThan(cp, ivec2(0))) || any(greaterThanEqual(cp, u_camera_size))) {
            TALLY(AUDIT_OFF_SCREEN, flux2);
            continue;
        }
        vec4 g = texelFetch(g_position, cp, 0);
        if (g.w < 0.5) {
            TALLY(AUDIT_ON_SKY, flux2);
            continue;
        }
        vec3 n2 = texelFetch(g_normal, cp, 0).xyz; // faces the camera
        float h = dot(x2 - g.xyz, n2);
        if (h < -2.0 * texel) {
            TALLY(AUDIT_OCCLUDED, flux2); // behind the surface the camera sees
            continue;
        }
        if (h > 2.0 * texel) {
            TALLY(AUDIT_IN_FRONT, flux2); // in front of it: no surface where the camera looks
            continue;
        }
        // The photon lands on the side of the receiving surface it comes from: x1 must lie in front
        // of that surface's plane (for x2 on the plane this is d2 . n2 < 0). Without it a photon
        // landing just behind a thin wall the camera sees is taken for one landing on the wall.
        if (dot(n2, d2) >= 0.0 || dot(x1 - g.xyz, n2) <= 0.0) {
            TALLY(AUDIT_BACK_SIDE, flux2); // lands on the side the camera does not see
            continue;
        }
        x2 -= h * n2; // onto the receiving surface, where the splat's kernel is centred
        vec4 q = rotation_between(d1, d2);
        vec3 du2 = transfer(dxu, diverging(dxu, rotate(q, ddu), d2, t2, n2), d2, t2, n2);
        vec3 dv2 = transfer(dxv, diverging(dxv, rotate(q, ddv), d2, t2, n2), d2, t2, n2);
        // A footprint that is not finite or has (nearly) no area has no irradiance to splat (Eq. 4):
        // E_p = Phi / A_p would overflow to inf and splat NaN.
        float l2 = length(du2) * length(dv2);
        float area2 = length(cross(du2, dv2));
        if (isinf(l2) || isnan(l2) || !(area2 > 1e-6 * l2)) {
            TALLY(AUDIT_DEGENERATE, flux2);
            continue;
        }
        uint k = atomicAdd(command.count, 1u);
        if (k >= u_capacity) {
            TALLY(AUDIT_OVERFLOW, flux2);
            atomicAdd(overflow, 1u);
            atomicAdd(command.count, 0xffffffffu); // undo: the draw must not read past the buffer
            continue;
        }
        TALLY(AUDIT_STORED, flux2);
        photons[k] = Photon(vec4(x2, 1.0), vec4(du2, 0.0), vec4(dv2, 0.0), vec4(flux2, 0.0));
    }
}

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
#ifdef AUDIT
    for (int k = 0; k < AUDIT_COUNT; k++)
        acc[k] = vec3(0.0);
#endif
    if (px.x < u_res && px.y < u_res)
        trace_texel(px);
#ifdef AUDIT
    uint li = gl_LocalInvocationIndex;
    for (int k = 0; k < AUDIT_COUNT; k++)
        group_acc[k][li] = acc[k];
    barrier();
    if (li < uint(AUDIT_COUNT)) {
        vec3 sum = vec3(0.0);
        for (int j = 0; j < GIB_GROUP_2D * GIB_GROUP_2D; j++)
            sum += group_acc[li][j];
        uint g = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
        audit[g * uint(AUDIT_COUNT) + li].rgb += sum;
    }
#endif
}

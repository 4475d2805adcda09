// Eq. 5-7: L_o(x) += f_s(x) E_p pi K(|M_p (x - x_p)|), Silverman's second-order kernel
// K(l) = (3/pi)(1 - l^2)^2 for l < 1 (Eq. 6), M_p (Eq. 7) mapping world to filter space. The third
// row a n_p penalises distance off the photon's plane (topological bias). Eq. 7 as printed makes
// a carry units of length; we scale it by the footprint, a_eff = a sqrt(|D_u x . (D_v x x n)|), so a
// is dimensionless: with a = 1 a point half a footprint off the plane gets l = 1. f_s = rho/pi
// (diffuse receivers: LDDE). Additive blending sums over photons.
#include "ldm_indirect/ldm_indirect_slots.h"
layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position;
layout(binding = GIB_UNIT_GBUF_NORMAL) uniform sampler2D g_normal;
layout(binding = GIB_UNIT_GBUF_ALBEDO) uniform sampler2D g_albedo;
layout(location = LDMI_SPLAT_LOC_TOPO_BIAS) uniform float u_topo_bias;
flat in vec3 f_position;
flat in vec3 f_du;
flat in vec3 f_dv;
flat in vec3 f_irradiance;
layout(location = 0) out vec4 o_color;
#ifdef AUDIT
// Audit (ldm_indirect.h): the flux the splat deposits on this pixel's patch of surface, irradiance
// times the patch's area: the pixel's solid angle (from the frustum's half-extents at distance 1
// and the image size) times dist^2 / cos.
layout(location = LDMI_SPLAT_LOC_EYE) uniform vec3 u_eye;
// xy: tan of the half-angles, zw: image size
layout(location = LDMI_SPLAT_LOC_TAN_SIZE) uniform vec4 u_tan_size;
#endif
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(g_position, px, 0);
    if (pos.w < 0.5)
        discard;
    vec3 n = texelFetch(g_normal, px, 0).xyz;
    // n_p: the receiver's normal at the photon, taken as the pixel's normal flipped to the
    // photon's plane side (the footprint lies in the plane spanned by du, dv).
    vec3 np = normalize(cross(f_du, f_dv));
    if (dot(np, n) < 0.0)
        np = -np;
    float det = dot(f_du, cross(f_dv, np));
    if (abs(det) < 1e-30)
        discard;
    vec3 d = pos.xyz - f_position;
    float a = u_topo_bias * sqrt(abs(det));
    vec3 f = (2.0 / det) * vec3(dot(cross(f_dv, np), d), dot(cross(np, f_du), d), a * dot(np, d));
    float l2 = dot(f, f);
    if (l2 >= 1.0)
        discard;
    float k = (3.0 / 3.14159265358979) * (1.0 - l2) * (1.0 - l2);
#ifdef AUDIT
    vec2 ndc = gl_FragCoord.xy / u_tan_size.zw * 2.0 - 1.0;
    vec3 dv = vec3(ndc * u_tan_size.xy, -1.0);
    float domega = (4.0 * u_tan_size.x * u_tan_size.y / (u_tan_size.z * u_tan_size.w)) /
                   pow(length(dv), 3.0);
    vec3 to_eye = u_eye - pos.xyz;
    float dist = length(to_eye);
    float area = domega * dist * dist / max(abs(dot(n, to_eye / dist)), 1e-3);
    o_color = vec4(f_irradiance * 3.14159265358979 * k * area, 0.0);
#else
    vec3 albedo = texelFetch(g_albedo, px, 0).rgb;
    o_color = vec4((albedo / 3.14159265358979) * f_irradiance * 3.14159265358979 * k, 0.0);
#endif
}

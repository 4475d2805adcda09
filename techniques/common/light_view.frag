#include "common/scene.glsl"
#include "common/common_slots.h"
#include "common/light_view_shared.h"
// One face of a light's view (techniques/common/light_view.c): what the light sees at each texel,
// as a reflective shadow map. Flux per texel: a point or spot light of intensity I sends
// I(w) dw into the texel's solid angle dw = s^2 cos^3(theta) (s: the texel's side on the plane at
// unit distance, theta: the angle from the view axis); a directional light of irradiance E sends
// E s^2 through a texel of side s. The surface there reflects rho_d times that flux diffusely.
layout(location = GIB_LOC_MATERIAL) uniform int u_material;
layout(location = GIB_LOC_ORIGIN) uniform vec3 u_origin;
layout(location = GIB_LV_LOC_FORWARD) uniform vec3 u_forward;
// enum gib_lv_kind: 0 cube, 1 perspective, 2 ortho
layout(location = GIB_LV_LOC_KIND) uniform int u_kind;
layout(location = GIB_LV_LOC_LIGHT) uniform int u_light;
layout(location = GIB_LV_LOC_TEXEL) uniform float u_texel;
layout(binding = GIB_UNIT_ALBEDO_TEX) uniform sampler2D u_albedo_tex;
layout(binding = GIB_UNIT_ALPHA_TEX) uniform sampler2D u_alpha_tex;
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
#ifdef PACKED16
// The LRSM paper's format (light_view.h, GIB_LV_PACKED16): the reflected radiance
// rho E <n.l> / pi with the depth, the normal with <n.l>. E <n.l> is the irradiance the flux per
// texel gives over the texel's area on the surface, so this is the radiance the LRSM's
// construction derived from FLUX before (Table 1).
layout(location = 0) out vec4 o_radiance_depth;
layout(location = 1) out vec4 o_normal_nl;
#else
layout(location = 0) out float o_depth;
layout(location = 1) out vec4 o_position;
layout(location = 2) out vec4 o_normal;
layout(location = 3) out vec4 o_flux;
layout(location = 4) out vec4 o_specular;
#endif
void main()
{
    Material m = materials[u_material];
    vec2 st = vec2(v_uv.x, 1.0 - v_uv.y); // texture rows top first, OBJ's v bottom up
    if (m.flags.z != 0 && texture(u_alpha_tex, st).r < 0.5)
        discard;
    // Corners collinear in the scene can round to a sliver of nonzero area in the view, whose
    // attributes, interpolated over almost no area, are not finite: such a fragment is left out, as
    // a true zero-area triangle is (one NaN texel turns every VPL or mip that reads it NaN).
    if (any(isnan(v_position)) || any(isinf(v_position)) || any(isnan(v_normal)) ||
        any(isinf(v_normal)) || dot(v_normal, v_normal) == 0.0)
        discard;
    vec3 rel = v_position - u_origin;
    vec3 flux_in;
    vec3 to_light;
    vec3 E;       // irradiance on a surface facing the light
    float depth;
    if (u_kind == GIB_LV_KIND_ORTHO) {
        depth = dot(rel, u_forward);
        to_light = -u_forward;
        E = lights[u_light].intensity_outer.rgb;
        flux_in = E * (u_texel * u_texel);
    } else {
        float dist = length(rel);
        depth = dist;
        to_light = -rel / max(dist, 1e-30);
        float c = dot(rel, u_forward) / max(dist, 1e-30);
        vec3 wi;
        float d;
        E = light_eval(lights[u_light], v_position, wi, d); // I(w) / d^2
        flux_in = E * (d * d) * (u_texel * u_texel * c * c * c);
    }
    // Facing as in the G-buffer with the light as the viewer: two-sided materials turn the normal
    // toward it, one-sided ones seen from behind reflect nothing.
    vec3 n = normalize(v_normal);
    bool back = dot(n, to_light) < 0.0;
    if (back && m.flags.y != 0)
        n = -n;
    vec3 albedo = m.albedo.rgb;
    if (m.albedo.w > 0.5)
        albedo *= texture(u_albedo_tex, st).rgb;
    vec3 spec = m.specular.rgb;
    if (back && m.flags.y == 0) {
        albedo = vec3(0.0);
        spec = vec3(0.0);
    }
#ifdef PACKED16
    float cosnl = dot(n, to_light);
    // Clamped to the half float's largest value: next to a light that touches a surface the
    // irradiance grows without bound (1e11 W/m^2 a micrometre away), and an overflow to +inf
    // would turn every filtered texel it reaches into NaN.
    o_radiance_depth = vec4(min(albedo * E * (max(cosnl, 0.0) / 3.14159265358979), vec3(65504.0)),
                            depth);
    o_normal_nl = vec4(n, cosnl);
#else
    o_depth = depth;
    o_position = vec4(v_position, 1.0);
    o_normal = vec4(n, float(m.flags.x));
    o_flux = vec4(albedo * flux_in, 1.0);
    o_specular = vec4(spec, m.specular.w);
#endif
}

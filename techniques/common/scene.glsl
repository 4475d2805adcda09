// gibench — the GLSL mirror of scenes/scene.h: materials, lights and the light falloff.
// gib_light_eval() and gib_spot_falloff() (scenes/camera_light.c, scenes/light_eval.h) are the
// definitions; these functions must compute the same numbers (tests/direct checks the images agree
// with the reference).
#include "gl/bindings.h"

struct Material {
    vec4 albedo;    // rgb = rho_d, w = albedo texture bound (1) or not (0)
    vec4 specular;  // rgb = rho_s, w = Phong exponent n
    ivec4 flags;    // x = spec type (0 none, 1 mirror, 2 Phong), y = two-sided, z = alpha mask bound
};
layout(std430, binding = GIB_SSBO_MATERIALS) readonly buffer Materials { Material materials[]; };

struct Light {
    vec4 position_type;      // xyz position, w = type (0 point, 1 spot, 2 directional)
    vec4 direction_exponent; // xyz unit axis / travel direction, w = spot exponent e
    vec4 intensity_outer;    // rgb intensity (W/sr) or irradiance, w = cos(outer half-angle)
};
layout(std430, binding = GIB_SSBO_LIGHTS) readonly buffer Lights { Light lights[]; };

const float PI = 3.14159265358979;

// Incident E at p such that a Lambertian surface reflects (rho/pi) * E * max(0, n.wi).
vec3 light_eval(Light l, vec3 p, out vec3 wi, out float dist)
{
    int type = int(l.position_type.w + 0.5);
    if (type == 2) {
        wi = -l.direction_exponent.xyz;
        dist = 3.0e38;
        return l.intensity_outer.rgb;
    }
    vec3 d = l.position_type.xyz - p;
    float r2 = max(dot(d, d), 1e-30);
    dist = sqrt(r2);
    wi = d / dist;
    float falloff = 1.0;
    if (type == 1) {
        float c = dot(-wi, l.direction_exponent.xyz);
        falloff = c >= l.intensity_outer.w ? (c > 0.0 ? pow(c, l.direction_exponent.w) : 0.0) : 0.0;
    }
    return l.intensity_outer.rgb * (falloff / r2);
}

// BRDF times pi-free Lambert term: rho_d/pi + normalised Phong rho_s (n+2)/(2 pi) max(0, r.wi)^n.
vec3 brdf(vec3 albedo, vec4 spec, int spec_type, vec3 n, vec3 wo, vec3 wi)
{
    vec3 f = albedo / PI;
    if (spec_type == 2) {
        vec3 r = reflect(-wo, n);
        f += spec.rgb * ((spec.w + 2.0) / (2.0 * PI)) * pow(max(dot(r, wi), 0.0), spec.w);
    }
    return f;
}

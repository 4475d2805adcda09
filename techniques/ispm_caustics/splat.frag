// Sec. 3.3.2.3: a photon's irradiance at the surface point x this pixel sees, when x lies on the
// photon's surface (within h/2 of its plane, facing the side the photon arrives from) and within
// h of its hit: Phi kappa(r) / K with the Gaussian kappa(r) = exp(-(r/h)^2 / (2 delta)) cut at
// r = h and K its integral over that disk, 2 pi delta h^2 (1 - exp(-1/(2 delta))): one photon's
// splat integrates to its flux on its plane (the thesis divides by pi h^2, right only for a
// constant kernel). Additive blending sums the photons.
#include "ispm_caustics/caustics.glsl"
layout(std430, binding = ISPM_SSBO_PHOTONS) readonly buffer Photons { Photon photons[]; };
layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position;
layout(binding = GIB_UNIT_GBUF_NORMAL) uniform sampler2D g_normal;
layout(location = ISPM_SPLAT_LOC_DELTA) uniform float u_delta;
flat in int f_photon;
layout(location = 0) out vec4 o_irradiance;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(g_position, px, 0);
    if (pos.w < 0.5)
        discard;
    vec3 nx = texelFetch(g_normal, px, 0).xyz;
    Photon p = photons[f_photon];
    vec3 n = p.hit_n.xyz;
    if (dot(nx, n) <= 0.0)
        discard; // the camera sees the other side
    float h = p.hit.w;
    vec3 dp = pos.xyz - p.hit.xyz;
    float dn = dot(dp, n);
    float r2 = dot(dp, dp) - dn * dn;
    if (abs(dn) > 0.5 * h || r2 >= h * h)
        discard;
    float u = r2 / (h * h);
    float K = 6.28318530717959 * u_delta * h * h * (1.0 - exp(-0.5 / u_delta));
    o_irradiance = vec4(p.flux.rgb * (exp(-0.5 * u / u_delta) / K), 0.0);
}

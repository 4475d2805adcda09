// The VPL gather (the thesis, Sec. 3.2.2; Dachsbacher and Stamminger 2005), shared by rsm_gather
// and multires_ir. A Lambertian VPL reflecting flux Phi emits I(theta) = Phi cos(theta) / pi, so
// the irradiance it gives a point x with normal n at distance d is
//     E = Phi cos_l cos_x / (pi max(d^2, eps^2)),   cos_l = <n_l, -w>, cos_x = <n, w>, w = v / |v|,
// v = VPL - x, both cosines one-sided (zero when negative). Departure from the text's
// E = Phi max(0, |n_x.v|) max(0, |n_l.v|) / (|v|^2 + eps): |.| lets a VPL light the back of a
// surface and a point behind the VPL's own surface, v unnormalised makes E scale as 1/d instead of
// 1/d^2, and the 1/pi of the VPL's intensity is missing; eps is a length in the scene's units (the
// technique's clamp_distance) under d, so the clamp scales with the scene. No visibility between
// VPL and x (as the thesis and RSM).
#include "common/common_slots.h"
struct Vpl {
    vec4 position;  // w: 1 valid
    vec4 normal;    // w: light index
    vec4 flux;      // rgb, W
};
layout(std430, binding = GIB_VPL_SSBO_VPLS) readonly buffer Vpls { Vpl vpls[]; };

vec3 vpl_irradiance(vec3 x, vec3 n, int count, float eps)
{
    const float pi = 3.14159265358979;
    float eps2 = eps * eps;
    vec3 E = vec3(0.0);
    for (int i = 0; i < count; i++) {
        Vpl l = vpls[i];
        if (l.position.w < 0.5)
            continue;
        vec3 v = l.position.xyz - x;
        float d2 = dot(v, v);
        if (!(d2 > 0.0))
            continue;
        vec3 w = v * inversesqrt(d2);
        float cx = dot(n, w), cl = -dot(l.normal.xyz, w);
        if (cx <= 0.0 || cl <= 0.0)
            continue;
        E += l.flux.rgb * (cx * cl / (pi * max(d2, eps2)));
    }
    return E;
}

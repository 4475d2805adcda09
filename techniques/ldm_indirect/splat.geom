// Expands a photon into the screen-space rectangle that bounds its footprint: the parallelogram
// x_p +- D_u x / 2 +- D_v x / 2, which contains the kernel's ellipse (M maps it to the unit disc).
#include "gl/bindings.h"
layout(points) in;
layout(triangle_strip, max_vertices = 4) out;
layout(location = GIB_LOC_VIEW_PROJ) uniform mat4 u_view_proj; // camera-relative: maps p - u_origin
layout(location = GIB_LOC_ORIGIN) uniform vec3 u_origin;
in vec3 v_position[];
in vec3 v_du[];
in vec3 v_dv[];
in vec3 v_irradiance[];
flat out vec3 f_position;
flat out vec3 f_du;
flat out vec3 f_dv;
flat out vec3 f_irradiance;
void main()
{
    if (max(v_irradiance[0].r, max(v_irradiance[0].g, v_irradiance[0].b)) <= 0.0)
        return;
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    bool behind = false;
    for (int k = 0; k < 4; k++) {
        vec3 c = v_position[0] + 0.5 * ((k & 1) != 0 ? v_du[0] : -v_du[0]) +
                 0.5 * ((k & 2) != 0 ? v_dv[0] : -v_dv[0]);
        vec4 clip = u_view_proj * vec4(c - u_origin, 1.0);
        if (clip.w <= 1e-6) {
            behind = true;
            break;
        }
        vec2 ndc = clip.xy / clip.w;
        lo = min(lo, ndc);
        hi = max(hi, ndc);
    }
    // A footprint reaching behind the camera covers an unknown part of the screen: cover all of it.
    if (behind) {
        lo = vec2(-1.0);
        hi = vec2(1.0);
    }
    lo = clamp(lo, -1.0, 1.0);
    hi = clamp(hi, -1.0, 1.0);
    if (any(greaterThanEqual(lo, hi)))
        return;
    for (int k = 0; k < 4; k++) {
        f_position = v_position[0];
        f_du = v_du[0];
        f_dv = v_dv[0];
        f_irradiance = v_irradiance[0];
        gl_Position = vec4((k & 1) != 0 ? hi.x : lo.x, (k & 2) != 0 ? hi.y : lo.y, 0.0, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}

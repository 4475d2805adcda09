// A light-view texel as a patch of a Lambertian surface (vct.h, injection): it reflects `flux` (W,
// rho_d x the flux reaching it, common/light_view.h) from the area
//     A = A_perp / cos(phi),
// A_perp its cross-section perpendicular to the light's rays (perspective: its solid angle
// s^2 cos^3(theta) times d^2; ortho: s^2) and phi the angle between the surface normal n and the
// direction to the light; its outgoing radiance is L = flux / (pi A). Grazing texels: the cosine
// is floored at 0.01 (their area is large but finite).
#include "common/light_view.glsl"
float lv_texel_area(int light, int face, vec3 p, vec3 n)
{
    float s = lv_texel(light);
    vec3 rel = p - lv_origin(light);
    float a_perp, cos_phi;
    if (lv_kind(light) == GIB_LV_KIND_ORTHO) {
        a_perp = s * s;
        cos_phi = dot(n, -lv_axis(face));
    } else {
        float d = length(rel);
        float ct = dot(rel, lv_axis(face)) / d;
        a_perp = s * s * ct * ct * ct * d * d;
        cos_phi = dot(n, -rel / d);
    }
    return a_perp / max(cos_phi, 0.01);
}

// A photon's disk of radius h in the receiver's plane, centred on its hit, as the quad bounding it
// (Sec. 3.3.2.3, Fig. 3.13(b): "a quad generated in the geometry shader"); GL clips it.
#include "ispm_caustics/caustics.glsl"
layout(points) in;
layout(triangle_strip, max_vertices = 4) out;
layout(std430, binding = ISPM_SSBO_PHOTONS) readonly buffer Photons { Photon photons[]; };
layout(location = GIB_LOC_VIEW_PROJ) uniform mat4 u_view_proj;
layout(location = GIB_LOC_ORIGIN) uniform vec3 u_origin;
flat out int f_photon;
void main()
{
    int i = gl_PrimitiveIDIn;
    Photon p = photons[i];
    float h = p.hit.w;
    if (!(h > 0.0) || p.hit_n.w <= 0.0)
        return;
    vec3 x, y;
    onb(p.hit_n.xyz, x, y);
    for (int k = 0; k < 4; k++) {
        vec3 c = p.hit.xyz + h * ((k & 1) != 0 ? x : -x) + h * ((k & 2) != 0 ? y : -y);
        f_photon = i;
        gl_Position = u_view_proj * vec4(c - u_origin, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}

// Photon splatting (Aalund et al. 2015, Sec. 4.2): the photon buffer is drawn as points; the vertex
// shader forms the irradiance estimate E_p = Phi_p / A_p (Eq. 4), A_p = pi/4 |D_u x x D_v x|.
#include "ldm_indirect/photon.glsl"
layout(std430, binding = LDMI_SSBO_PHOTONS) readonly buffer Photons { Photon photons[]; };
out vec3 v_position;
out vec3 v_du;
out vec3 v_dv;
out vec3 v_irradiance;
void main()
{
    Photon p = photons[gl_VertexID];
    float area = 0.25 * 3.14159265358979 * length(cross(p.du.xyz, p.dv.xyz));
    v_position = p.position.xyz;
    v_du = p.du.xyz;
    v_dv = p.dv.xyz;
    v_irradiance = area > 0.0 ? p.flux.rgb / area : vec3(0.0);
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}

// Sec. 3.3.2.2: each photon's ray drawn as a line (instance = photon, vertex 0/1 = its ends) in
// the camera's view at the ray resolution; GL clips it to the view frustum.
#include "ispm_caustics/caustics.glsl"
layout(std430, binding = ISPM_SSBO_PHOTONS) readonly buffer Photons { Photon photons[]; };
layout(location = GIB_LOC_VIEW_PROJ) uniform mat4 u_view_proj;
layout(location = GIB_LOC_ORIGIN) uniform vec3 u_origin;
layout(location = ISPM_TRACE_LOC_TMAX) uniform float u_tmax;
layout(location = ISPM_TRACE_LOC_CAPACITY) uniform uint u_capacity;
flat out int v_photon;
void main()
{
    v_photon = gl_InstanceID;
    if (uint(gl_InstanceID) >= u_capacity) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside: clipped
        return;
    }
    Photon p = photons[gl_InstanceID];
    float t = gl_VertexID == 0 ? p.dir.w : u_tmax;
    gl_Position = u_view_proj * vec4(p.origin.xyz + t * p.dir.xyz - u_origin, 1.0);
}

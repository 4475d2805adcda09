#include "gl/bindings.h"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
// maps p - u_origin (camera-relative: precision)
layout(location = GIB_LOC_VIEW_PROJ) uniform mat4 u_view_proj;
layout(location = GIB_LOC_ORIGIN) uniform vec3 u_origin;
out vec3 v_position;
out vec3 v_normal;
out vec2 v_uv;
void main()
{
    v_position = a_position;
    v_normal = a_normal;
    v_uv = a_uv;
    gl_Position = u_view_proj * vec4(a_position - u_origin, 1.0);
}

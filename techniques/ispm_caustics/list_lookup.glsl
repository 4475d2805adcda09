// The camera's lists at the ray resolution (list_build.frag) and what the trace asks of them.
layout(std430, binding = ISPM_SSBO_HEADS) readonly buffer Heads { uint heads[]; };
layout(std430, binding = ISPM_SSBO_NODES) readonly buffer Nodes { Node nodes[]; };
layout(location = GIB_LOC_VIEW_PROJ) uniform mat4 u_view_proj; // camera-relative: maps p - u_origin
layout(location = GIB_LOC_ORIGIN) uniform vec3 u_origin;    // the eye
layout(location = ISPM_LOC_FORWARD) uniform vec3 u_forward;
layout(location = ISPM_LOC_RES) uniform int u_res;
// camera right / P[0]: x_ndc 1's direction step
layout(location = ISPM_LOC_RIGHT_TAN) uniform vec3 u_right_tan;
layout(location = ISPM_LOC_UP_TAN) uniform vec3 u_up_tan;    // camera up / P[5]
layout(std430, binding = ISPM_SSBO_STATUS) readonly buffer Status {
    uint list_count, list_overflow, photon_overflow, list_longest;
};
// Walks stop after the longest list's length (llvmpipe runs a loop's lanes to its bound when the
// bound is a large constant, however early each list ends).
int max_walk() { return int(min(list_longest, 1u << 20)); }

// The point of node nd of pixel px: on the pixel centre's ray at the node's linear depth.
vec3 node_point(ivec2 px, float depth)
{
    vec2 c = (vec2(px) + 0.5) / float(u_res) * 2.0 - 1.0;
    return u_origin + abs(depth) * (u_forward + c.x * u_right_tan + c.y * u_up_tan);
}

// Ray parameter where o + t d crosses the node's tangent plane, or -1 when it runs parallel to it
// or (Sec. 3.3.2.2, Fig. 3.11) reaches a one-sided surface from behind: the thesis' rejection of
// self-intersections, which also keeps it from hitting the back faces of closed meshes.
float node_hit(ivec2 px, Node nd, vec3 o, vec3 d, out vec3 n)
{
    n = oct_decode(nd.normal);
    float dn = dot(d, n);
    if (abs(dn) < 1e-6 || (nd.depth < 0.0 && dn > 0.0))
        return -1.0;
    return dot(node_point(px, nd.depth) - o, n) / dn;
}

// The camera's linear depth of q (along its forward axis, as the nodes store it).
float view_depth(vec3 q) { return dot(q - u_origin, u_forward); }

// A ray-resolution pixel's width at linear depth z (along the camera's right axis).
float pixel_footprint(float z) { return z * 2.0 * length(u_right_tan) / float(u_res); }

// Distance in ray-resolution pixels (Chebyshev) from pixel px's centre to where point q projects.
float pixel_distance(ivec2 px, vec3 q)
{
    vec4 c = u_view_proj * vec4(q - u_origin, 1.0);
    if (c.w <= 0.0)
        return 1e30;
    vec2 w = (c.xy / c.w * 0.5 + 0.5) * float(u_res);
    vec2 dd = abs(w - (vec2(px) + 0.5));
    return max(dd.x, dd.y);
}

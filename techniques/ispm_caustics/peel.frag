// The 4-depth-layer variant the thesis compares its lists against (Sec. 3.3.2.2, Fig. 4.2(b)):
// depth peeling (Everitt 2001) from the camera at the ray resolution. Pass k keeps, with the depth
// test, the nearest fragment behind layer k - 1 (the previous layer's linear depth at this pixel,
// u_prev), so the 4 layers are the first 4 surfaces along each pixel's ray; what lies deeper is
// missing, which is the leak of Fig. 4.2(b). Output: the list node's fields (caustics.glsl).
#include "common/scene.glsl"
#include "ispm_caustics/caustics.glsl"
layout(location = GIB_LOC_MATERIAL) uniform int u_material;
layout(location = GIB_LOC_ORIGIN) uniform vec3 u_origin; // the eye
layout(location = ISPM_LOC_FORWARD) uniform vec3 u_forward;
layout(location = ISPM_PEEL_LOC_LAYER) uniform int u_layer;
layout(binding = GIB_UNIT_ALPHA_TEX) uniform sampler2D u_alpha_tex;
layout(binding = ISPM_UNIT_PREV_LAYER) uniform sampler2D u_prev;
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
layout(location = 0) out vec4 o_node; // x signed depth, y normal bits, z depth, w 1
void main()
{
    Material m = materials[u_material];
    if (m.flags.z != 0 && texture(u_alpha_tex, vec2(v_uv.x, 1.0 - v_uv.y)).r < 0.5)
        discard;
    float z = dot(v_position - u_origin, u_forward);
    if (u_layer > 0) {
        vec4 prev = texelFetch(u_prev, ivec2(gl_FragCoord.xy), 0);
        if (prev.w < 0.5 || z <= prev.z * (1.0 + 1e-5))
            discard;
    }
    o_node = vec4(m.flags.y != 0 ? z : -z, uintBitsToFloat(oct_encode(normalize(v_normal))), z, 1.0);
}

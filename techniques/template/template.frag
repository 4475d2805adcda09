// The template's one pass (techniques/template/template.c): the one-bounce ambient term, shaded
// on the G-buffer. Every surface pixel reflects a uniform irradiance E (computed once on the CPU
// from the scene's lights, albedos and area) diffusely: L = (rho_d / pi) E. A pixel where the
// camera sees nothing gets 0, as in every reference component.
//
// Slots by name only: the pass's own from its header, which includes the GL runtime's table of
// the shared ones; shader.c expands the #include lines from the files embedded at build time
// (cmake/gl.cmake embeds techniques/*/*_slots.h and harness/gl/bindings.h with the shaders).
#include "template/template_slots.h"

layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position; // xyz, w = 1 on a hit
layout(binding = GIB_UNIT_GBUF_ALBEDO) uniform sampler2D g_albedo;     // rho_d (texture included)
layout(std430, binding = TEMPLATE_SSBO_COUNTS) buffer Counts {
    uint shaded_pixels; // cleared by template.c before the pass, read back by its counters()
};
layout(location = TEMPLATE_LOC_IRRADIANCE) uniform vec3 u_irradiance;
layout(location = 0) out vec4 o_indirect;

const float PI = 3.14159265358979;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    if (texelFetch(g_position, px, 0).w < 0.5) { // the camera sees nothing here
        o_indirect = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    vec3 albedo = texelFetch(g_albedo, px, 0).rgb;
    o_indirect = vec4(albedo / PI * u_irradiance, 1.0);
    atomicAdd(shaded_pixels, 1u);
}

// gibench technique `template` — its own GL slots, one table for C (template.c) and GLSL
// (template.frag): only #define lines and // comments, valid in both languages, in the style of
// harness/gl/bindings.h, which holds the slots every pass shares (included here by the path C
// uses, which the shader embedding serves to GLSL too). A slot a pass owns gets a name
// here, never a bare number in the shader or the C file: the C side binds what the shader
// declares only if both read the same #define.
//
// Copying the template: rename the file to <name>_slots.h, the guard to <NAME>_SLOTS_H and the
// prefix TEMPLATE_ to <NAME>_. Own slots come from the ranges bindings.h marks "own";
// template.c checks at compile time that they stay there (_Static_assert).
#ifndef TEMPLATE_SLOTS_H
#define TEMPLATE_SLOTS_H

#include "harness/gl/bindings.h"

// Texture units. The pass reads the shared G-buffer at bindings.h's GIB_UNIT_GBUF_POSITION and
// GIB_UNIT_GBUF_ALBEDO (gib_gbuffer_bind puts it there); it has no texture of its own. One would
// take GIB_UNIT_OWN_FIRST (10) onwards:
//   #define TEMPLATE_UNIT_HISTORY (GIB_UNIT_OWN_FIRST + 0) // an own texture

// Shader storage buffers: the own range is GIB_SSBO_OWN_FIRST (8) to 15.
#define TEMPLATE_SSBO_COUNTS (GIB_SSBO_OWN_FIRST + 0) // uint: surface pixels shaded this frame

// Uniform locations of the ambient pass. It is a full-screen program (it draws no scene), so
// every location of 0..19 is free; own ones start at GIB_LOC_OWN_FIRST (2) by habit.
#define TEMPLATE_LOC_IRRADIANCE (GIB_LOC_OWN_FIRST + 0) // vec3: the ambient irradiance E, W/m^2

#endif

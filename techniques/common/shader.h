/* gibench — GLSL programs from the shaders embedded at build time (cmake/embed_shaders.cmake).
 * Shader files live next to their technique; paths are relative to techniques/ ("common/gbuffer.frag").
 * `#include "common/scene.glsl"` lines are expanded (one level deep is all gibench uses, but nested
 * includes work), and `#version 450 core` is prepended. */
#ifndef GIB_SHADER_H
#define GIB_SHADER_H

#include "harness/base/error.h"

/* Returns the embedded source or NULL (generated shaders.c). */
const char *gib_shader_source(const char *path);

/* Builds a program from up to 4 stage files, the stage taken from the extension (.vert .geom .frag
 * .comp). On failure err holds the file name and the compiler's log, and 0 is returned. `defines`
 * (may be NULL) is inserted after #version, e.g. "#define PCF 1\n". */
unsigned gib_program(const char *const *files, int count, const char *defines, gib_error *err);

#endif

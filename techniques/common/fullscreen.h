/* gibench — a full-screen pass written once: one triangle covering the viewport
 * (common/fullscreen.vert) shaded by a fragment shader, into a framebuffer. */
#ifndef GIB_FULLSCREEN_H
#define GIB_FULLSCREEN_H

#include "harness/base/error.h"
#include "techniques/common/pass_state.h"

typedef struct gib_fullscreen {
    unsigned program, vao;
} gib_fullscreen;

/* Builds common/fullscreen.vert with `fragment` (a path under techniques/; `defines` may be NULL). */
int gib_fullscreen_create(gib_fullscreen *fs, const char *fragment, const char *defines,
                          gib_error *err);
/* Binds `fbo` with a width x height viewport and the default pass state (common/pass_state.h: no
 * depth test, no stencil, colour written), blending off or additive (`additive`: GL_ONE, GL_ONE,
 * for passes that sum into the target), and uses the program: set its uniforms and textures after
 * this. */
void gib_fullscreen_begin(const gib_fullscreen *fs, unsigned fbo, int width, int height,
                          int additive);
/* The same with any pass state (a stencil test, a viewport inside the framebuffer). */
void gib_fullscreen_begin_pass(const gib_fullscreen *fs, const gib_pass_state *state);
/* Draws the triangle; may be called several times between begin and end. */
void gib_fullscreen_draw(const gib_fullscreen *fs);
/* Ends the pass: no VAO, the default pass state (gib_pass_end). */
void gib_fullscreen_end(void);
void gib_fullscreen_destroy(gib_fullscreen *fs);

#endif

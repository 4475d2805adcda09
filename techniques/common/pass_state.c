#include "techniques/common/pass_state.h"

#include <glad/gl.h>

static void apply_blend(gib_blend blend)
{
    if (blend == GIB_BLEND_ADD) {
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
    } else {
        glDisable(GL_BLEND);
    }
}

/* The depth write mask stays on in every case (GL's default): with the test off nothing is
 * written, and a depth clear, which the mask also gates, keeps working. */
static void apply_depth(gib_depth depth)
{
    glDepthMask(GL_TRUE);
    glClipControl(GL_LOWER_LEFT, depth == GIB_DEPTH_REVERSED ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
    if (depth == GIB_DEPTH_LESS || depth == GIB_DEPTH_REVERSED) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(depth == GIB_DEPTH_LESS ? GL_LESS : GL_GREATER);
    } else {
        glDisable(GL_DEPTH_TEST);
    }
}

static void apply_cull(gib_cull cull)
{
    if (cull == GIB_CULL_BACK) {
        glEnable(GL_CULL_FACE);
        glFrontFace(GL_CCW);
        glCullFace(GL_BACK);
    } else {
        glDisable(GL_CULL_FACE);
    }
}

/* Off and MARK write all stencil bits (GL's default mask, which stencil clears also obey);
 * EQUAL writes none. */
static void apply_stencil(gib_stencil stencil, int ref)
{
    switch (stencil) {
    case GIB_STENCIL_MARK:
        glEnable(GL_STENCIL_TEST);
        glStencilMask(0xff);
        glStencilFunc(GL_ALWAYS, ref, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        break;
    case GIB_STENCIL_EQUAL:
        glEnable(GL_STENCIL_TEST);
        glStencilMask(0);
        glStencilFunc(GL_EQUAL, ref, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        break;
    default:
        glDisable(GL_STENCIL_TEST);
        glStencilMask(0xff);
        break;
    }
}

static void apply_fixed(const gib_pass_state *s)
{
    glDisable(GL_SCISSOR_TEST);
    apply_blend(s->blend);
    apply_depth(s->depth);
    apply_cull(s->cull);
    apply_stencil(s->stencil, s->stencil_ref);
    const GLboolean c = s->no_color ? GL_FALSE : GL_TRUE;
    glColorMask(c, c, c, c);
}

void gib_pass_apply(const gib_pass_state *s)
{
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    glViewport(s->x, s->y, s->width, s->height);
    apply_fixed(s);
}

void gib_pass_end(void)
{
    const gib_pass_state defaults = {0};
    apply_fixed(&defaults);
}

#include "gbuffer.h"

#include <glad/gl.h>
#include <string.h>

#include "harness/gl/context.h"
#include "techniques/common/common_slots.h"
#include "techniques/common/pass_state.h"
#include "techniques/common/shader.h"

int gib_gbuffer_create(gib_gbuffer *g, int w, int h, gib_ledger *ledger, gib_error *err)
{
    memset(g, 0, sizeof *g);
    g->width = w;
    g->height = h;
    const char *files[] = {"common/gbuffer.vert", "common/gbuffer.frag"};
    if (!(g->program = gib_program(files, 2, NULL, err)))
        return -1;
    if (!(g->position = gib_gpu_texture(ledger, "gbuffer.position", GL_TEXTURE_2D, w, h, 1,
                                        GL_RGBA32F, 1, err)) ||
        !(g->normal = gib_gpu_texture(ledger, "gbuffer.normal", GL_TEXTURE_2D, w, h, 1, GL_RGBA32F,
                                      1, err)) ||
        !(g->albedo = gib_gpu_texture(ledger, "gbuffer.albedo", GL_TEXTURE_2D, w, h, 1, GL_RGBA32F,
                                      1, err)) ||
        !(g->specular = gib_gpu_texture(ledger, "gbuffer.specular", GL_TEXTURE_2D, w, h, 1,
                                        GL_RGBA16F, 1, err)) ||
        !(g->depth = gib_gpu_renderbuffer(ledger, "gbuffer.depth", GL_DEPTH_COMPONENT24, w, h, err)))
        return -1;
    glCreateFramebuffers(1, &g->fbo);
    const unsigned tex[4] = {g->position, g->normal, g->albedo, g->specular};
    for (int i = 0; i < 4; i++)
        glNamedFramebufferTexture(g->fbo, GL_COLOR_ATTACHMENT0 + i, tex[i], 0);
    glNamedFramebufferRenderbuffer(g->fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, g->depth);
    const GLenum bufs[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                            GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(g->fbo, 4, bufs);
    if (glCheckNamedFramebufferStatus(g->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return gib_fail(err, "G-buffer framebuffer incomplete");
    return gib_gl_check("G-buffer creation", err);
}

void gib_gbuffer_render(gib_gbuffer *g, const gib_gpu_scene *scene, const gib_view *view,
                        gib_timers *timers, const char *pass)
{
    gib_timer_begin(timers, pass);
    gib_pass_apply(&(gib_pass_state){.fbo = g->fbo, .width = g->width, .height = g->height,
                                     .depth = GIB_DEPTH_LESS});
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < 4; i++)
        glClearBufferfv(GL_COLOR, i, zero);
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    glUseProgram(g->program);
    glUniformMatrix4fv(GIB_LOC_VIEW_PROJ, 1, GL_FALSE, view->view_proj);
    glUniform3fv(GIB_LOC_ORIGIN, 1, view->origin);
    glUniform3fv(GIB_GBUFFER_LOC_EYE, 1, view->camera->eye);
    gib_gpu_scene_draw(scene);
    gib_pass_end();
    gib_timer_end(timers);
}

void gib_gbuffer_bind(const gib_gbuffer *g)
{
    glBindTextureUnit(GIB_UNIT_GBUF_POSITION, g->position);
    glBindTextureUnit(GIB_UNIT_GBUF_NORMAL, g->normal);
    glBindTextureUnit(GIB_UNIT_GBUF_ALBEDO, g->albedo);
    glBindTextureUnit(GIB_UNIT_GBUF_SPECULAR, g->specular);
}

void gib_gbuffer_destroy(gib_gbuffer *g, gib_ledger *ledger)
{
    if (g->fbo)
        glDeleteFramebuffers(1, &g->fbo);
    if (g->program)
        glDeleteProgram(g->program);
    const unsigned tex[4] = {g->position, g->normal, g->albedo, g->specular};
    for (int i = 0; i < 4; i++)
        if (tex[i])
            gib_gpu_free(ledger, tex[i], 1);
    if (g->depth)
        gib_gpu_free(ledger, g->depth, 2);
    memset(g, 0, sizeof *g);
}

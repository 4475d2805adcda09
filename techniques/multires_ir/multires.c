#include "techniques/multires_ir/multires.h"

#include <glad/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/bindings.h"
#include "techniques/common/shader.h"

void multires_rect(const multires *m, int k, int rect[4])
{
    if (k == 0) {
        rect[0] = rect[1] = 0;
        rect[2] = m->width;
        rect[3] = m->height;
        return;
    }
    int y = 0;
    for (int j = 1; j < k; j++)
        y += (m->height + (1 << j) - 1) >> j;
    rect[0] = m->width;
    rect[1] = y;
    rect[2] = (m->width + (1 << k) - 1) >> k;
    rect[3] = (m->height + (1 << k) - 1) >> k;
}

static unsigned fs_program(const char *frag, const char *defines, gib_error *err)
{
    const char *files[] = {"common/fullscreen.vert", frag};
    return gib_program(files, 2, defines, err);
}

int multires_create(multires *m, int width, int height, int levels, float depth_threshold,
                    float normal_deg, int use_stencil, int with_gather, gib_ledger *ledger,
                    gib_error *err)
{
    memset(m, 0, sizeof *m);
    m->use_stencil = use_stencil;
    m->width = width;
    m->height = height;
    m->levels = levels;
    m->depth_threshold = depth_threshold;
    m->normal_chord = 2.0f * sinf(0.5f * normal_deg * (float)M_PI / 180.0f);
    int r[4];
    m->atlas_w = width;
    m->atlas_h = height;
    int stack = 0;
    for (int k = 1; k < levels; k++) {
        multires_rect(m, k, r);
        if (k == 1)
            m->atlas_w = width + r[2];
        stack = r[1] + r[3];
    }
    if (stack > m->atlas_h)
        m->atlas_h = stack;
    /* The flattened image (Fig. 3.3(a)) is 1.5x the image wide: refused in our words, before GL
     * would refuse the texture (found by tests/hostile at 16384 wide). */
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (max_size > 0 && (m->atlas_w > max_size || m->atlas_h > max_size))
        return gib_fail(err, "multires_ir: an image of %dx%d needs a flattened multi-resolution "
                             "image of %dx%d, over this GL's GL_MAX_TEXTURE_SIZE %d",
                        width, height, m->atlas_w, m->atlas_h, max_size);
    const char *names[5] = {"mips.min", "mips.max", "mips.mean_position", "mips.normal_sum",
                            "mips.irradiance"};
    unsigned *tex[5] = {&m->lo, &m->hi, &m->mean, &m->nsum, &m->irradiance};
    for (int i = 0; i < 5; i++) {
        if (!(*tex[i] = gib_gpu_texture(ledger, names[i], GL_TEXTURE_2D, m->atlas_w, m->atlas_h, 1,
                                        GL_RGBA32F, 1, err)))
            return -1;
        glTextureParameteri(*tex[i], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(*tex[i], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glCreateFramebuffers(1, &m->fbo_color);
    glNamedFramebufferTexture(m->fbo_color, GL_COLOR_ATTACHMENT0, m->irradiance, 0);
    if (use_stencil) {
        if (!(m->stencil = gib_gpu_renderbuffer(ledger, "mips.stencil", GL_DEPTH24_STENCIL8,
                                                m->atlas_w, m->atlas_h, err)))
            return -1;
        glCreateFramebuffers(1, &m->fbo);
        glNamedFramebufferTexture(m->fbo, GL_COLOR_ATTACHMENT0, m->irradiance, 0);
        glNamedFramebufferRenderbuffer(m->fbo, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                       m->stencil);
    } else {
        if (!(m->mask = gib_gpu_texture(ledger, "mips.valid", GL_TEXTURE_2D, m->atlas_w,
                                        m->atlas_h, 1, GL_R8, 1, err)))
            return -1;
        glCreateFramebuffers(1, &m->fbo_mask);
        glNamedFramebufferTexture(m->fbo_mask, GL_COLOR_ATTACHMENT0, m->mask, 0);
    }
    const char *mips[] = {"multires_ir/multires_mips.comp"};
    if (!(m->mips_program = gib_program(mips, 1, NULL, err)) ||
        !(m->split_program = fs_program("multires_ir/multires_split.frag", NULL, err)))
        return -1;
    if (with_gather &&
        (!(m->gather_program = fs_program("multires_ir/multires_gather.frag",
                                          use_stencil ? NULL : "#define MASKED 1\n", err)) ||
         !(m->upsample_program = fs_program("multires_ir/multires_upsample.frag", NULL, err)) ||
         !(m->resolve_program =
               fs_program("multires_ir/multires_upsample.frag", "#define RESOLVE 1\n", err))))
        return -1;
    glCreateVertexArrays(1, &m->vao);
    return 0;
}

static void common_uniforms(const multires *m)
{
    glUniform2i(2, m->width, m->height);
    glUniform1i(3, m->levels);
    glUniform1f(4, m->depth_threshold);
    glUniform1f(5, m->normal_chord);
}

static void bind_mips(const multires *m)
{
    glBindTextureUnit(GIB_UNIT_OWN_FIRST + 0, m->lo);
    glBindTextureUnit(GIB_UNIT_OWN_FIRST + 1, m->hi);
    glBindTextureUnit(GIB_UNIT_OWN_FIRST + 2, m->mean);
    glBindTextureUnit(GIB_UNIT_OWN_FIRST + 3, m->nsum);
}

void multires_split(multires *m, unsigned position_tex, unsigned normal_tex, const float eye[3])
{
    glUseProgram(m->mips_program);
    common_uniforms(m);
    glUniform3fv(7, 1, eye);
    glBindTextureUnit(GIB_UNIT_GBUF_POSITION, position_tex);
    glBindTextureUnit(GIB_UNIT_GBUF_NORMAL, normal_tex);
    unsigned *tex[4] = {&m->lo, &m->hi, &m->mean, &m->nsum};
    for (int i = 0; i < 4; i++)
        glBindImageTexture((GLuint)i, *tex[i], 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    for (int k = 0; k < m->levels; k++) {
        int r[4];
        multires_rect(m, k, r);
        glUniform1i(6, k);
        glDispatchCompute((GLuint)(r[2] + 7) / 8, (GLuint)(r[3] + 7) / 8, 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    /* Marking: texels of invalid regions are discarded, the rest write stencil 1 (colour writes
     * off) or 1 into the mask (cleared to 0 first). */
    const float zero[4] = {0, 0, 0, 0};
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    if (m->use_stencil) {
        glBindFramebuffer(GL_FRAMEBUFFER, m->fbo);
        glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glEnable(GL_STENCIL_TEST);
        glStencilMask(0xff);
        glStencilFunc(GL_ALWAYS, 1, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    } else {
        glBindFramebuffer(GL_FRAMEBUFFER, m->fbo_mask);
        glClearBufferfv(GL_COLOR, 0, zero);
    }
    glViewport(0, 0, m->atlas_w, m->atlas_h);
    glUseProgram(m->split_program);
    common_uniforms(m);
    bind_mips(m);
    glBindVertexArray(m->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_STENCIL_TEST);
    glBindVertexArray(0);
}

void multires_gather(multires *m, int vpl_count, float eps)
{
    const float zero[4] = {0, 0, 0, 0};
    glClearTexImage(m->irradiance, 0, GL_RGBA, GL_FLOAT, zero);
    glBindFramebuffer(GL_FRAMEBUFFER, m->use_stencil ? m->fbo : m->fbo_color);
    glViewport(0, 0, m->atlas_w, m->atlas_h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    if (m->use_stencil) {
        glEnable(GL_STENCIL_TEST);
        glStencilMask(0);
        glStencilFunc(GL_EQUAL, 1, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    }
    glUseProgram(m->gather_program);
    common_uniforms(m);
    bind_mips(m);
    if (m->mask)
        glBindTextureUnit(GIB_UNIT_OWN_FIRST + 5, m->mask);
    glUniform1i(8, vpl_count);
    glUniform1f(9, eps);
    glBindVertexArray(m->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_STENCIL_TEST);
    glStencilMask(0xff);
    glBindVertexArray(0);
}

void multires_upsample(multires *m, unsigned fbo, const float eye[3])
{
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
    glBindVertexArray(m->vao);
    glUseProgram(m->upsample_program);
    common_uniforms(m);
    bind_mips(m);
    glUniform3fv(7, 1, eye);
    glBindTextureUnit(GIB_UNIT_OWN_FIRST + 4, m->irradiance);
    glBindFramebuffer(GL_FRAMEBUFFER, m->fbo_color);
    /* Each level reads only the next coarser level's texels and writes its own (disjoint), with a
     * texture barrier between levels (GL 4.5, 9.3.1). */
    for (int k = m->levels - 2; k >= 1; k--) {
        int r[4];
        multires_rect(m, k, r);
        glTextureBarrier();
        glViewport(r[0], r[1], r[2], r[3]);
        glUniform1i(6, k);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glTextureBarrier();
    glUseProgram(m->resolve_program);
    common_uniforms(m);
    glUniform3fv(7, 1, eye);
    glUniform1i(6, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, m->width, m->height);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}

void multires_read_valid(const multires *m, unsigned char *out)
{
    size_t n = (size_t)m->atlas_w * m->atlas_h;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (m->use_stencil) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, m->fbo);
        glReadPixels(0, 0, m->atlas_w, m->atlas_h, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, out);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    } else {
        glGetTextureImage(m->mask, 0, GL_RED, GL_UNSIGNED_BYTE, (GLsizei)n, out);
        for (size_t i = 0; i < n; i++)
            out[i] = out[i] > 127;
    }
}

long multires_count_valid(const multires *m, long *counts)
{
    unsigned char *s = malloc((size_t)m->atlas_w * m->atlas_h);
    if (!s)
        return -1;
    multires_read_valid(m, s);
    long total = 0;
    for (int k = 0; k < m->levels; k++) {
        int r[4];
        multires_rect(m, k, r);
        counts[k] = 0;
        for (int y = r[1]; y < r[1] + r[3]; y++)
            for (int x = r[0]; x < r[0] + r[2]; x++)
                counts[k] += s[(size_t)y * m->atlas_w + x] == 1;
        total += counts[k];
    }
    free(s);
    return total;
}

void multires_destroy(multires *m, gib_ledger *ledger)
{
    unsigned *prog[5] = {&m->mips_program, &m->split_program, &m->gather_program,
                         &m->upsample_program, &m->resolve_program};
    for (int i = 0; i < 5; i++)
        if (*prog[i])
            glDeleteProgram(*prog[i]);
    if (m->vao)
        glDeleteVertexArrays(1, &m->vao);
    unsigned *fbo[3] = {&m->fbo, &m->fbo_mask, &m->fbo_color};
    for (int i = 0; i < 3; i++)
        if (*fbo[i])
            glDeleteFramebuffers(1, fbo[i]);
    if (m->mask)
        gib_gpu_free(ledger, m->mask, 1);
    unsigned *tex[5] = {&m->lo, &m->hi, &m->mean, &m->nsum, &m->irradiance};
    for (int i = 0; i < 5; i++)
        if (*tex[i])
            gib_gpu_free(ledger, *tex[i], 1);
    if (m->stencil)
        gib_gpu_free(ledger, m->stencil, 2);
    memset(m, 0, sizeof *m);
}

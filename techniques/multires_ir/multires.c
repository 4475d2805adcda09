#include "techniques/multires_ir/multires.h"

#include <glad/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "techniques/common/compute.h"
#include "techniques/common/shader.h"
#include "techniques/multires_ir/multires_ir_slots.h"

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
        gib_fullscreen_create(&m->split, "multires_ir/multires_split.frag", NULL, err) < 0)
        return -1;
    if (with_gather &&
        (gib_fullscreen_create(&m->gather, "multires_ir/multires_gather.frag",
                               use_stencil ? NULL : "#define MASKED 1\n", err) < 0 ||
         gib_fullscreen_create(&m->upsample, "multires_ir/multires_upsample.frag", NULL, err) < 0 ||
         gib_fullscreen_create(&m->resolve, "multires_ir/multires_upsample.frag",
                               "#define RESOLVE 1\n", err) < 0))
        return -1;
    return 0;
}

static void common_uniforms(const multires *m)
{
    glUniform2i(MULTIRES_LOC_SIZE, m->width, m->height);
    glUniform1i(MULTIRES_LOC_LEVELS, m->levels);
    glUniform1f(MULTIRES_LOC_DEPTH_THRESHOLD, m->depth_threshold);
    glUniform1f(MULTIRES_LOC_NORMAL_CHORD, m->normal_chord);
}

static void bind_mips(const multires *m)
{
    glBindTextureUnit(MULTIRES_UNIT_LO, m->lo);
    glBindTextureUnit(MULTIRES_UNIT_HI, m->hi);
    glBindTextureUnit(MULTIRES_UNIT_MEAN, m->mean);
    glBindTextureUnit(MULTIRES_UNIT_NSUM, m->nsum);
}

/* Level k's rectangle of the flattened image (level 0: the image) in `fbo`, as a pass's state. */
static gib_pass_state level_pass(const multires *m, unsigned fbo, int k)
{
    int r[4];
    multires_rect(m, k, r);
    return (gib_pass_state){.fbo = fbo, .x = r[0], .y = r[1], .width = r[2], .height = r[3]};
}

void multires_split(multires *m, unsigned position_tex, unsigned normal_tex, const float eye[3])
{
    glUseProgram(m->mips_program);
    common_uniforms(m);
    glUniform3fv(MULTIRES_LOC_EYE, 1, eye);
    glBindTextureUnit(GIB_UNIT_GBUF_POSITION, position_tex);
    glBindTextureUnit(GIB_UNIT_GBUF_NORMAL, normal_tex);
    const unsigned image[4] = {MULTIRES_IMAGE_LO, MULTIRES_IMAGE_HI, MULTIRES_IMAGE_MEAN,
                               MULTIRES_IMAGE_NSUM};
    const unsigned tex[4] = {m->lo, m->hi, m->mean, m->nsum};
    for (int i = 0; i < 4; i++)
        glBindImageTexture(image[i], tex[i], 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    for (int k = 0; k < m->levels; k++) {
        int r[4];
        multires_rect(m, k, r);
        glUniform1i(MULTIRES_LOC_LEVEL, k);
        glDispatchCompute(gib_groups((unsigned)r[2], GIB_GROUP_2D),
                          gib_groups((unsigned)r[3], GIB_GROUP_2D), 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    /* Marking: texels of invalid regions are discarded, the rest write stencil 1 (colour writes
     * off) or 1 into the mask (cleared to 0 first). */
    gib_pass_state mark = {.fbo = m->fbo_mask, .width = m->atlas_w, .height = m->atlas_h};
    if (m->use_stencil) {
        mark.fbo = m->fbo;
        mark.stencil = GIB_STENCIL_MARK;
        mark.stencil_ref = 1;
        mark.no_color = 1;
    }
    gib_fullscreen_begin_pass(&m->split, &mark);
    const float zero[4] = {0, 0, 0, 0};
    if (m->use_stencil)
        glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    else
        glClearBufferfv(GL_COLOR, 0, zero);
    common_uniforms(m);
    bind_mips(m);
    gib_fullscreen_draw(&m->split);
    gib_fullscreen_end();
}

void multires_gather(multires *m, int vpl_count, float eps)
{
    const float zero[4] = {0, 0, 0, 0};
    glClearTexImage(m->irradiance, 0, GL_RGBA, GL_FLOAT, zero);
    gib_pass_state gather = {.fbo = m->fbo_color, .width = m->atlas_w, .height = m->atlas_h};
    if (m->use_stencil) {
        gather.fbo = m->fbo;
        gather.stencil = GIB_STENCIL_EQUAL;
        gather.stencil_ref = 1;
    }
    gib_fullscreen_begin_pass(&m->gather, &gather);
    common_uniforms(m);
    bind_mips(m);
    if (m->mask)
        glBindTextureUnit(MULTIRES_UNIT_VALID, m->mask);
    glUniform1i(MULTIRES_GATHER_LOC_VPLS, vpl_count);
    glUniform1f(MULTIRES_GATHER_LOC_EPS, eps);
    gib_fullscreen_draw(&m->gather);
    gib_fullscreen_end();
}

void multires_upsample(multires *m, unsigned fbo, const float eye[3])
{
    const gib_pass_state atlas = {.fbo = m->fbo_color, .width = m->atlas_w, .height = m->atlas_h};
    gib_fullscreen_begin_pass(&m->upsample, &atlas);
    common_uniforms(m);
    bind_mips(m);
    glUniform3fv(MULTIRES_LOC_EYE, 1, eye);
    glBindTextureUnit(MULTIRES_UNIT_IRRADIANCE, m->irradiance);
    /* Each level reads only the next coarser level's texels and writes its own (disjoint), with a
     * texture barrier between levels (GL 4.5, 9.3.1). */
    for (int k = m->levels - 2; k >= 1; k--) {
        const gib_pass_state level = level_pass(m, m->fbo_color, k);
        glTextureBarrier();
        gib_pass_apply(&level);
        glUniform1i(MULTIRES_LOC_LEVEL, k);
        gib_fullscreen_draw(&m->upsample);
    }
    glTextureBarrier();
    const gib_pass_state image = level_pass(m, fbo, 0);
    gib_fullscreen_begin_pass(&m->resolve, &image);
    common_uniforms(m);
    glUniform3fv(MULTIRES_LOC_EYE, 1, eye);
    glUniform1i(MULTIRES_LOC_LEVEL, 0);
    gib_fullscreen_draw(&m->resolve);
    gib_fullscreen_end();
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
    if (m->mips_program)
        glDeleteProgram(m->mips_program);
    gib_fullscreen *passes[4] = {&m->split, &m->gather, &m->upsample, &m->resolve};
    for (int i = 0; i < 4; i++)
        gib_fullscreen_destroy(passes[i]);
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

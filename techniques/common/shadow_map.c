#include "shadow_map.h"

#include <glad/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "techniques/common/shader.h"
#include "harness/gl/view.h"

static void bounding_sphere(const gib_scene *s, float c[3], float *r)
{
    float d2 = 0;
    for (int i = 0; i < 3; i++) {
        c[i] = 0.5f * (s->bounds_min[i] + s->bounds_max[i]);
        float e = s->bounds_max[i] - s->bounds_min[i];
        d2 += e * e;
    }
    *r = 0.5f * sqrtf(d2) * 1.01f + 1e-6f;
}

int gib_shadow_maps_create(gib_shadow_maps *sm, const gib_gpu_scene *gpu, int res,
                           gib_ledger *ledger, gib_error *err)
{
    memset(sm, 0, sizeof *sm);
    const gib_scene *s = gpu->scene;
    sm->res = res;
    const char *files[] = {"common/gbuffer.vert", "common/shadow.frag"};
    if (!(sm->program = gib_program(files, 2, NULL, err)))
        return -1;
    uint32_t n = s->light_count;
    float *slots = calloc(8 * (n ? n : 1), sizeof(float));
    sm->ortho_extent = calloc(n ? n : 1, sizeof(float));
    sm->ortho_origin = calloc(n ? n : 1, sizeof *sm->ortho_origin);
    if (!slots || !sm->ortho_extent || !sm->ortho_origin) {
        free(slots);
        return gib_fail(err, "out of memory");
    }
    float c[3], r;
    bounding_sphere(s, c, &r);
    for (uint32_t i = 0; i < n; i++) {
        const gib_light *l = &s->lights[i];
        if (l->type == GIB_LIGHT_DIRECTIONAL) {
            slots[8 * i] = (float)sm->ortho_count++;
            slots[8 * i + 1] = sm->ortho_extent[i] = r;
            for (int k = 0; k < 3; k++)
                slots[8 * i + 4 + k] = sm->ortho_origin[i][k] = c[k] - l->direction[k] * r;
        } else {
            slots[8 * i] = (float)sm->cube_count++;
        }
    }
    sm->slots = gib_gpu_buffer(ledger, "shadow.slots", 32 * (uint64_t)(n ? n : 1), slots, 0, err);
    free(slots);
    if (!sm->slots)
        return -1;
    /* Unused arrays still get one small layer so the samplers are complete. */
    int cube_res = sm->cube_count ? res : 1, ortho_res = sm->ortho_count ? res : 1;
    if (!(sm->cube_array = gib_gpu_texture(ledger, "shadow.cube", GL_TEXTURE_CUBE_MAP_ARRAY,
                                           cube_res, cube_res,
                                           6 * (sm->cube_count ? sm->cube_count : 1), GL_R32F, 1,
                                           err)) ||
        !(sm->ortho_array = gib_gpu_texture(ledger, "shadow.ortho", GL_TEXTURE_2D_ARRAY, ortho_res,
                                            ortho_res, sm->ortho_count ? sm->ortho_count : 1,
                                            GL_R32F, 1, err)) ||
        !(sm->depth = gib_gpu_renderbuffer(ledger, "shadow.depth", GL_DEPTH_COMPONENT24, res, res,
                                           err)))
        return -1;
    const unsigned tex[2] = {sm->cube_array, sm->ortho_array};
    for (int i = 0; i < 2; i++) {
        /* Nearest filtering: PCF filters the binary comparisons, not the distances. */
        glTextureParameteri(tex[i], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(tex[i], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(tex[i], GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(tex[i], GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    /* Outside the ortho map nothing occludes: clear value is +inf and lookups clamp. */
    glCreateFramebuffers(1, &sm->fbo);
    glNamedFramebufferRenderbuffer(sm->fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, sm->depth);
    return gib_gl_check("shadow map creation", err);
}

/* GL's cube-map face order and the up vectors that make a rendered face match its sampling
 * orientation. */
static const float face_dir[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const float face_up[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

static void draw_face(gib_shadow_maps *sm, const gib_gpu_scene *gpu, unsigned tex, int layer,
                      const float view_proj[16], const float origin[3])
{
    glNamedFramebufferTextureLayer(sm->fbo, GL_COLOR_ATTACHMENT0, tex, 0, layer);
    glBindFramebuffer(GL_FRAMEBUFFER, sm->fbo);
    const float far[4] = {INFINITY, INFINITY, INFINITY, INFINITY};
    glClearBufferfv(GL_COLOR, 0, far);
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    glUniformMatrix4fv(1, 1, GL_FALSE, view_proj);
    glUniform3fv(6, 1, origin); /* view_proj is relative to origin, as in gbuffer.vert */
    gib_gpu_scene_draw(gpu);
}

void gib_shadow_maps_render(gib_shadow_maps *sm, const gib_gpu_scene *gpu, gib_timers *timers)
{
    const gib_scene *s = gpu->scene;
    if (!s->light_count)
        return;
    gib_timer_begin(timers, "shadow");
    glViewport(0, 0, sm->res, sm->res);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glUseProgram(sm->program);
    float c[3], r;
    bounding_sphere(s, c, &r);
    for (uint32_t i = 0; i < s->light_count; i++) {
        const gib_light *l = &s->lights[i];
        float view[16], proj[16], vp[16];
        if (l->type == GIB_LIGHT_DIRECTIONAL) {
            int slot = 0;
            for (uint32_t k = 0; k < i; k++)
                slot += s->lights[k].type == GIB_LIGHT_DIRECTIONAL;
            float t[3], b[3];
            gib_ortho_basis(l->direction, t, b);
            const float zero[3] = {0, 0, 0};
            gib_mat4_view(t, b, l->direction, zero, view);
            float e = sm->ortho_extent[i];
            gib_mat4_ortho(-e, e, -e, e, 0, 2 * e, proj);
            gib_mat4_mul(proj, view, vp);
            glUniform3fv(2, 1, sm->ortho_origin[i]);
            glUniform3fv(3, 1, l->direction);
            glUniform1i(4, 1);
            draw_face(sm, gpu, sm->ortho_array, slot, vp, sm->ortho_origin[i]);
            continue;
        }
        int slot = 0;
        for (uint32_t k = 0; k < i; k++)
            slot += s->lights[k].type != GIB_LIGHT_DIRECTIONAL;
        float far = 0;
        for (int k = 0; k < 3; k++)
            far += (l->position[k] - c[k]) * (l->position[k] - c[k]);
        far = sqrtf(far) + r;
        gib_mat4_perspective((float)M_PI / 2, 1.0f, far * 1e-5f, far, proj);
        glUniform3fv(2, 1, l->position);
        glUniform1i(4, 0);
        for (int f = 0; f < 6; f++) {
            float right[3], up[3];
            const float *d = face_dir[f], *u = face_up[f];
            right[0] = d[1] * u[2] - d[2] * u[1];
            right[1] = d[2] * u[0] - d[0] * u[2];
            right[2] = d[0] * u[1] - d[1] * u[0];
            up[0] = right[1] * d[2] - right[2] * d[1];
            up[1] = right[2] * d[0] - right[0] * d[2];
            up[2] = right[0] * d[1] - right[1] * d[0];
            const float zero[3] = {0, 0, 0};
            gib_mat4_view(right, up, d, zero, view);
            gib_mat4_mul(proj, view, vp);
            draw_face(sm, gpu, sm->cube_array, slot * 6 + f, vp, l->position);
        }
    }
    gib_timer_end(timers);
}

void gib_shadow_maps_bind(const gib_shadow_maps *sm, int pcf_radius, float normal_offset)
{
    glBindTextureUnit(4, sm->cube_array);
    glBindTextureUnit(5, sm->ortho_array);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, sm->slots);
    glUniform1i(20, sm->res);
    glUniform1i(21, pcf_radius);
    glUniform1f(22, normal_offset);
}

void gib_shadow_maps_destroy(gib_shadow_maps *sm, gib_ledger *ledger)
{
    if (sm->fbo)
        glDeleteFramebuffers(1, &sm->fbo);
    if (sm->program)
        glDeleteProgram(sm->program);
    if (sm->cube_array)
        gib_gpu_free(ledger, sm->cube_array, 1);
    if (sm->ortho_array)
        gib_gpu_free(ledger, sm->ortho_array, 1);
    if (sm->depth)
        gib_gpu_free(ledger, sm->depth, 2);
    if (sm->slots)
        gib_gpu_free(ledger, sm->slots, 0);
    free(sm->ortho_extent);
    free(sm->ortho_origin);
    memset(sm, 0, sizeof *sm);
}

/* gibench technique `ldm_indirect` — single-bounce diffuse indirect light (LDDE) by photon
 * differentials traced through layered depth maps and splatted with Silverman's kernel
 * (Aalund, Frisvad, Bærentzen 2015, Sec. 3.4 Eq. 4-7 and 4.2).
 *
 *  1. LDMs for N directions (techniques/ldm, Sec. 3 and 3.2).
 *  2. Photon tracing (photon_trace.comp): each point or spot light renders its view (six cube faces:
 *     a spot's cone may be a hemisphere wide) at the photon resolution with the shared G-buffer pass,
 *     so every texel is a primary photon with its differentials; each is split over the N LDM
 *     directions of its hemisphere, traced, kept when the camera sees where it lands, and stored.
 *  3. Splatting (splat.*): the photon buffer drawn as points (glDrawArraysIndirect on the photon
 *     counter), expanded to the footprint's screen rectangle, Eq. 5 with additive blending.
 * Directional lights are not traced (the paper's emission is from point lights, Sec. 3.4/6).
 * Photon storage is bounded (a photon is 64 bytes; the buffer is capped at one SSBO); more photons
 * than fit is reported as status `overflow`, never dropped silently. */
#include <glad/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "harness/gl/ledger.h"
#include "techniques/common/shader.h"
#include "harness/gl/view.h"
#include "techniques/common/gbuffer.h"
#include "techniques/ldm/ldm.h"

extern const gib_technique gib_technique_ldm_indirect;

typedef struct ldm_indirect {
    const gib_gpu_scene *scene;
    gib_ledger *ledger;
    gib_gbuffer gbuffer, rsm;
    ldm_set ldms;
    unsigned trace_program, splat_program;
    unsigned photons, command, vao;
    uint32_t capacity;
    int photon_res;
    float offset, topo_bias;
    char status[32];
} ldm_indirect;

static const gib_param_spec ldm_indirect_params[] = {
    {"directions", GIB_PARAM_INT, 128, 1, 4096, "number of LDM directions N (Sec. 3.2)"},
    {"ldm_res", GIB_PARAM_INT, 128, 8, 2048, "LDM resolution (pixels per side)"},
    {"photon_res", GIB_PARAM_INT, 64, 4, 2048, "light-view photon resolution per cube face"},
    {"topo_bias", GIB_PARAM_FLOAT, 1.0, 0, 100,
     "topological-bias parameter a of Eq. 7 (in units of the footprint size)"},
    {"normal_offset", GIB_PARAM_FLOAT, 1.0, 0, 16, "ray origin offset along the normal, LDM texels"},
    {0},
};

static const float face_dir[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const float face_up[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

static void cross3(const float a[3], const float b[3], float o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static void ldm_indirect_destroy(void *self)
{
    ldm_indirect *a = self;
    if (!a)
        return;
    gib_gbuffer_destroy(&a->gbuffer, a->ledger);
    gib_gbuffer_destroy(&a->rsm, a->ledger);
    ldm_destroy(&a->ldms, a->ledger);
    if (a->trace_program)
        glDeleteProgram(a->trace_program);
    if (a->splat_program)
        glDeleteProgram(a->splat_program);
    if (a->vao)
        glDeleteVertexArrays(1, &a->vao);
    free(a);
}

static void *ldm_indirect_create(const gib_gpu_scene *scene, const gib_params *p, int w, int h,
                                 gib_ledger *ledger, gib_error *err)
{
    const gib_technique *t = &gib_technique_ldm_indirect;
    ldm_indirect *a = calloc(1, sizeof *a);
    if (!a) {
        gib_fail(err, "out of memory");
        return NULL;
    }
    a->scene = scene;
    a->ledger = ledger;
    a->photon_res = gib_param_int(t, p, "photon_res");
    a->offset = (float)gib_param_float(t, p, "normal_offset");
    a->topo_bias = (float)gib_param_float(t, p, "topo_bias");
    strcpy(a->status, "ok");
    const char *trace[] = {"ldm_indirect/photon_trace.comp"};
    const char *splat[] = {"ldm_indirect/splat.vert", "ldm_indirect/splat.geom",
                           "ldm_indirect/splat.frag"};
    int directions = gib_param_int(t, p, "directions");
    if (gib_gbuffer_create(&a->gbuffer, w, h, ledger, err) < 0 ||
        gib_gbuffer_create(&a->rsm, a->photon_res, a->photon_res, ledger, err) < 0 ||
        ldm_create(&a->ldms, scene, directions, gib_param_int(t, p, "ldm_res"), 1.0, ledger, err) < 0 ||
        !(a->trace_program = gib_program(trace, 1, NULL, err)) ||
        !(a->splat_program = gib_program(splat, 3, NULL, err)))
        goto fail;
    /* At most one secondary photon per LDM per primary photon (one of +-v per LDM). */
    uint32_t lights = 0;
    for (uint32_t i = 0; i < scene->scene->light_count; i++)
        lights += scene->scene->lights[i].type != GIB_LIGHT_DIRECTIONAL;
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    double want = 6.0 * a->photon_res * a->photon_res * (double)a->ldms.count * lights;
    double fit = (double)max_block / 64.0;
    a->capacity = (uint32_t)(want < fit ? (want > 1 ? want : 1) : fit);
    const uint32_t init[6] = {0, 1, 0, 0, 0, 0};
    if (!(a->photons = gib_gpu_buffer(ledger, "ldm_indirect.photons", 64ull * a->capacity, NULL, 0,
                                      err)) ||
        !(a->command = gib_gpu_buffer(ledger, "ldm_indirect.command", sizeof init, init,
                                      GL_DYNAMIC_STORAGE_BIT, err)))
        goto fail;
    glCreateVertexArrays(1, &a->vao);
    return a;
fail:
    ldm_indirect_destroy(a);
    return NULL;
}

static void trace_light(ldm_indirect *a, int li, const gib_view *view, gib_timers *timers)
{
    const gib_light *l = &a->scene->scene->lights[li];
    gib_camera light_cam = {.vfov_deg = 90};
    memcpy(light_cam.eye, l->position, sizeof light_cam.eye);
    for (int f = 0; f < 6; f++) {
        float right[3], up[3], vmat[16], proj[16];
        cross3(face_dir[f], face_up[f], right);
        cross3(right, face_dir[f], up);
        gib_view fv = {.camera = &light_cam, .width = a->photon_res, .height = a->photon_res};
        const float zero[3] = {0, 0, 0};
        gib_mat4_view(right, up, face_dir[f], zero, vmat);
        memcpy(fv.origin, l->position, sizeof fv.origin);
        float far = 0;
        for (int k = 0; k < 3; k++)
            far += (l->position[k] - a->ldms.center[k]) * (l->position[k] - a->ldms.center[k]);
        far = sqrtf(far) + a->ldms.radius;
        gib_mat4_perspective((float)M_PI / 2, 1.0f, far * 1e-5f, far, proj);
        gib_mat4_mul(proj, vmat, fv.view_proj);
        /* The light's view through the shared G-buffer pass: a reflective shadow map face whose
         * normals face the light. */
        gib_gbuffer_render(&a->rsm, a->scene, &fv, timers, "rsm");

        gib_timer_begin(timers, "photon_trace");
        glUseProgram(a->trace_program);
        gib_gpu_scene_bind(a->scene);
        glBindTextureUnit(0, a->rsm.position);
        glBindTextureUnit(1, a->rsm.normal);
        glBindTextureUnit(2, a->rsm.albedo);
        glBindTextureUnit(3, a->gbuffer.position);
        glBindTextureUnit(4, a->gbuffer.normal);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, a->photons);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, a->command);
        glUniform1i(0, li);
        glUniform3fv(1, 1, face_dir[f]);
        glUniform3fv(2, 1, right);
        glUniform3fv(3, 1, up);
        glUniform1i(4, a->photon_res);
        glUniform1f(7, 2.0f / (float)a->ldms.count);
        glUniformMatrix4fv(8, 1, GL_FALSE, view->view_proj);
        glUniform3fv(12, 1, view->origin);
        glUniform2i(9, view->width, view->height);
        glUniform1f(10, a->offset);
        glUniform1ui(11, a->capacity);
        int groups = (a->photon_res + 7) / 8;
        for (int p = 0; p < a->ldms.page_count; p++) {
            ldm_bind_page(&a->ldms, p);
            glUniform1i(5, a->ldms.pages[p].first);
            glUniform1i(6, a->ldms.pages[p].count);
            glDispatchCompute(groups, groups, 1);
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
        gib_timer_end(timers);
    }
}

static int ldm_indirect_render(void *self, const gib_view *view, gib_timers *timers,
                               const gib_image_target *targets, int target_count, gib_error *err)
{
    ldm_indirect *a = self;
    if (target_count != 1)
        return gib_fail(err, "ldm_indirect renders one component, was given %d targets",
                        target_count);
    const uint32_t init[6] = {0, 1, 0, 0, 0, 0};
    glNamedBufferSubData(a->command, 0, sizeof init, init);
    ldm_build(&a->ldms, a->scene, timers);
    gib_gbuffer_render(&a->gbuffer, a->scene, view, timers, "gbuffer");
    for (uint32_t li = 0; li < a->scene->scene->light_count; li++)
        if (a->scene->scene->lights[li].type != GIB_LIGHT_DIRECTIONAL)
            trace_light(a, (int)li, view, timers);

    gib_timer_begin(timers, "splat");
    glBindFramebuffer(GL_FRAMEBUFFER, targets[0].fbo);
    glViewport(0, 0, view->width, view->height);
    const float zero[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(a->splat_program);
    glUniformMatrix4fv(1, 1, GL_FALSE, view->view_proj);
    glUniform3fv(6, 1, view->origin);
    glUniform1f(2, a->topo_bias);
    glBindTextureUnit(0, a->gbuffer.position);
    glBindTextureUnit(1, a->gbuffer.normal);
    glBindTextureUnit(2, a->gbuffer.albedo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, a->photons);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, a->command);
    glBindVertexArray(a->vao);
    glDrawArraysIndirect(GL_POINTS, NULL);
    glBindVertexArray(0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glDisable(GL_BLEND);
    gib_timer_end(timers);
    return gib_gl_check("ldm_indirect", err);
}

static const char *ldm_indirect_status(void *self)
{
    ldm_indirect *a = self;
    const char *s = ldm_status(&a->ldms);
    if (strcmp(s, "ok"))
        return s;
    uint32_t cmd[5];
    glGetNamedBufferSubData(a->command, 0, sizeof cmd, cmd);
    if (cmd[4])
        strcpy(a->status, "overflow");
    return a->status;
}

const gib_technique gib_technique_ldm_indirect = {
    .name = "ldm_indirect",
    .source = "Aalund, Frisvad, Baerentzen 2015, Sec. 3.4, 4.2 (photon differentials through LDMs)",
    .components = GIB_OUT_INDIRECT,
    .params = ldm_indirect_params,
    .scene_needs_any = GIB_FEAT_POINT_LIGHT | GIB_FEAT_SPOT_LIGHT,
    .create = ldm_indirect_create,
    .render = ldm_indirect_render,
    .status = ldm_indirect_status,
    .destroy = ldm_indirect_destroy,
};

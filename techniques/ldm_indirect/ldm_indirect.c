/* gibench technique `ldm_indirect` — single-bounce diffuse indirect light (LDDE) by photon
 * differentials traced through layered depth maps and splatted with Silverman's kernel
 * (Aalund, Frisvad, Bærentzen 2015, Sec. 3.4 Eq. 4-7 and 4.2).
 *
 *  1. LDMs for N directions (techniques/ldm, Sec. 3 and 3.2).
 *  2. Photon tracing (photon_trace.comp): the shared light views (techniques/common/light_view.h:
 *     a cube for point lights and wide spots, one perspective view for a spot of at most 45
 *     degrees) at the photon resolution are a reflective shadow map whose texels are primary
 *     photons with their reflected flux and differentials; each is split over the N LDM
 *     directions of its hemisphere, traced, kept when the camera sees where it lands, and stored.
 *  3. Splatting (splat.*): the photon buffer drawn as points (glDrawArraysIndirect on the photon
 *     counter), expanded to the footprint's screen rectangle, Eq. 5 with additive blending.
 * Directional lights are not traced (the paper's emission is from point lights, Sec. 3.4/6).
 * Photon storage is bounded (a photon is 64 bytes; the buffer is capped at one SSBO): the LDM
 * directions are traced in batches whose photons fit it, each splatted before the next (a 90-degree
 * spot's six faces at photon_res 128 and 512 directions would store 50M); a light view larger than
 * the buffer alone still overflows, reported as status `overflow`, never dropped silently.
 * The flux audit (ldm_indirect.h) counts, per frame, where the light's flux goes: emitted, reflected,
 * carried by the secondary photons, discarded (by reason), stored and splatted. */
#include "techniques/ldm_indirect/ldm_indirect.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "techniques/common/compute.h"
#include "techniques/common/gbuffer.h"
#include "techniques/common/light_view.h"
#include "techniques/common/pass_state.h"
#include "techniques/common/shader.h"
#include "techniques/ldm/ldm.h"
#include "techniques/ldm_indirect/ldm_indirect_slots.h"

extern const gib_technique gib_technique_ldm_indirect;

typedef struct ldm_indirect {
    const gib_gpu_scene *scene;
    gib_ledger *ledger;
    gib_gbuffer gbuffer;
    gib_light_views views;   /* the RSM of the point and spot lights: one primary photon a texel */
    ldm_set ldms;
    unsigned trace_program, splat_program, audit_splat_program;
    unsigned photons, command, vao;
    uint32_t capacity;
    int photon_res;
    float offset, topo_bias;
    /* Flux audit (ldm_indirect.h): its own trace and splat programs, one slot of AUDIT_SHADER_FATES
     * vec4 per trace work group, and a float target the audit splat sums into. */
    int audit, audit_log;
    unsigned audit_buffer, audit_texture, audit_fbo;
    uint32_t audit_groups;
    int width, height;
    ldm_indirect_audit last;
} ldm_indirect;

#define AUDIT_SHADER_FATES LDM_AUDIT_SPLATTED /* the fates audit.glsl counts */

static int audit_requested;
static ldm_indirect_audit audit_last;

void ldm_indirect_audit_enable(int on)
{
    audit_requested = on;
}

int ldm_indirect_audit_last(ldm_indirect_audit *out)
{
    if (!audit_last.valid)
        return -1;
    *out = audit_last;
    return 0;
}

const char *ldm_indirect_audit_name(int fate)
{
    static const char *const names[LDM_AUDIT_FATES] = {
        "emitted", "no_surface", "back_facing", "reflected", "carried", "grazing", "miss",
        "behind_camera", "off_screen", "on_sky", "occluded", "in_front", "back_side", "degenerate",
        "overflow",
        "stored", "splatted"};
    return fate >= 0 && fate < LDM_AUDIT_FATES ? names[fate] : "?";
}

void ldm_indirect_audit_format(const ldm_indirect_audit *a, char *buf, size_t size)
{
    size_t n = 0;
    double e = (a->flux[LDM_AUDIT_EMITTED][0] + a->flux[LDM_AUDIT_EMITTED][1] +
                a->flux[LDM_AUDIT_EMITTED][2]) / 3;
    for (int k = 0; k < LDM_AUDIT_FATES && n < size; k++) {
        double v = (a->flux[k][0] + a->flux[k][1] + a->flux[k][2]) / 3;
        int w = snprintf(buf + n, size - n, "%s%s=%.6g W (%.4g%%)", k ? " " : "",
                         ldm_indirect_audit_name(k), v, e > 0 ? 100 * v / e : 0.0);
        if (w < 0)
            break;
        n += (size_t)w;
    }
}

static const gib_param_spec ldm_indirect_params[] = {
    {"directions", GIB_PARAM_INT, 128, 1, 4096, "number of LDM directions N (Sec. 3.2)"},
    {"ldm_res", GIB_PARAM_INT, 128, 8, 2048, "LDM resolution (pixels per side)"},
    {"photon_res", GIB_PARAM_INT, 64, 4, 2048, "photon resolution per light-view face (a cube face, or a narrow spot's view)"},
    {"topo_bias", GIB_PARAM_FLOAT, 1.0, 0, 100,
     "topological-bias parameter a of Eq. 7 (in units of the footprint size)"},
    {"normal_offset", GIB_PARAM_FLOAT, 1.0, 0, 16, "ray origin offset along the normal, LDM texels"},
    {"memory_budget_mb", GIB_PARAM_FLOAT, 0, 0, 1e7,
     "the most the LDMs may take, decimal MB (0: no limit); over it create ends out_of_memory with "
     "the plan recorded"},
    {0},
};

static void ldm_indirect_destroy(void *self)
{
    ldm_indirect *a = self;
    if (!a)
        return;
    gib_gbuffer_destroy(&a->gbuffer, a->ledger);
    gib_light_views_destroy(&a->views, a->ledger);
    ldm_destroy(&a->ldms, a->ledger);
    const unsigned bufs[3] = {a->photons, a->command, a->audit_buffer};
    for (int i = 0; i < 3; i++)
        if (bufs[i])
            gib_gpu_free(a->ledger, bufs[i], 0);
    if (a->audit_texture)
        gib_gpu_free(a->ledger, a->audit_texture, 1);
    if (a->trace_program)
        glDeleteProgram(a->trace_program);
    if (a->splat_program)
        glDeleteProgram(a->splat_program);
    if (a->audit_splat_program)
        glDeleteProgram(a->audit_splat_program);
    if (a->vao)
        glDeleteVertexArrays(1, &a->vao);
    if (a->audit_fbo)
        glDeleteFramebuffers(1, &a->audit_fbo);
    free(a);
}

static void *ldm_indirect_create(const gib_gpu_scene *scene, const gib_params *p, int w, int h,
                                 gib_ledger *ledger, gib_error *err)
{
    const gib_technique *t = &gib_technique_ldm_indirect;
    ldm_indirect *a = calloc(1, sizeof *a);
    if (!a) {
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    a->scene = scene;
    a->ledger = ledger;
    a->photon_res = gib_param_int(t, p, "photon_res");
    a->offset = (float)gib_param_float(t, p, "normal_offset");
    a->topo_bias = (float)gib_param_float(t, p, "topo_bias");
    a->width = w;
    a->height = h;
    const char *env = getenv("GIBENCH_LDM_AUDIT");
    a->audit_log = env && *env && strcmp(env, "0");
    a->audit = audit_requested || a->audit_log;
    const char *trace[] = {"ldm_indirect/photon_trace.comp"};
    const char *splat[] = {"ldm_indirect/splat.vert", "ldm_indirect/splat.geom",
                           "ldm_indirect/splat.frag"};
    int directions = gib_param_int(t, p, "directions");
    /* The LDMs first: a plan over the budget fails before anything else is allocated. */
    const uint64_t budget = (uint64_t)(gib_param_float(t, p, "memory_budget_mb") * 1e6);
    if (ldm_create(&a->ldms, scene, directions, gib_param_int(t, p, "ldm_res"), 1.0, budget, ledger,
                   err) < 0 ||
        gib_gbuffer_create(&a->gbuffer, w, h, ledger, err) < 0 ||
        gib_light_views_create(&a->views, scene, a->photon_res,
                               GIB_LV_POSITION | GIB_LV_NORMAL | GIB_LV_FLUX |
                                   GIB_LV_LOCAL_LIGHTS_ONLY,
                               "ldm_indirect.rsm", ledger, err) < 0 ||
        !(a->trace_program = gib_program(trace, 1, a->audit ? "#define AUDIT 1\n" : NULL, err)) ||
        !(a->splat_program = gib_program(splat, 3, NULL, err)))
        goto fail;
    if (a->audit) {
        a->audit_groups = gib_groups((unsigned)a->photon_res, GIB_GROUP_2D) *
                          gib_groups((unsigned)a->photon_res, GIB_GROUP_2D);
        if (!(a->audit_buffer = gib_gpu_buffer(ledger, "ldm_indirect.audit",
                                               16ull * AUDIT_SHADER_FATES * a->audit_groups, NULL,
                                               GL_DYNAMIC_STORAGE_BIT, err)) ||
            !(a->audit_texture = gib_gpu_texture(ledger, "ldm_indirect.audit_splat", GL_TEXTURE_2D,
                                                 w, h, 1, GL_RGBA32F, 1, err)) ||
            !(a->audit_splat_program = gib_program(splat, 3, "#define AUDIT 1\n", err)))
            goto fail;
        glCreateFramebuffers(1, &a->audit_fbo);
        glNamedFramebufferTexture(a->audit_fbo, GL_COLOR_ATTACHMENT0, a->audit_texture, 0);
    }
    /* At most one secondary photon per LDM per primary photon (one of +-v per LDM). */
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    double want = (double)a->views.face_count * a->photon_res * a->photon_res * (double)a->ldms.count;
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

/* The trace program's state for face f of light li (its light views rendered this frame). */
static void bind_trace(ldm_indirect *a, int li, int f, const gib_view *view)
{
    glUseProgram(a->trace_program);
    gib_gpu_scene_bind(a->scene);
    gib_light_views_bind(&a->views);
    glBindTextureUnit(GIB_UNIT_GBUF_POSITION, a->gbuffer.position);
    glBindTextureUnit(GIB_UNIT_GBUF_NORMAL, a->gbuffer.normal);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LDMI_SSBO_PHOTONS, a->photons);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LDMI_SSBO_COMMAND, a->command);
    glUniform1i(LDMI_TRACE_LOC_LIGHT, li);
    glUniform1i(LDMI_TRACE_LOC_FACE, f);
    glUniform1i(LDMI_TRACE_LOC_RES, a->photon_res);
    glUniform1f(LDMI_TRACE_LOC_SPLIT_WEIGHT, 2.0f / (float)a->ldms.count);
    glUniformMatrix4fv(LDMI_TRACE_LOC_VIEW_PROJ, 1, GL_FALSE, view->view_proj);
    glUniform3fv(LDMI_TRACE_LOC_ORIGIN, 1, view->origin);
    glUniform2i(LDMI_TRACE_LOC_SIZE, view->width, view->height);
    glUniform1f(LDMI_TRACE_LOC_OFFSET, a->offset);
    glUniform1ui(LDMI_TRACE_LOC_CAPACITY, a->capacity);
    if (a->audit)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LDMI_SSBO_AUDIT, a->audit_buffer);
}

/* The splat pass (splat.*): the photon buffer drawn as points into fbo, added with blending to
 * what earlier batches left there. The audit's program also gets what it needs to turn
 * irradiance into flux. */
static void draw_splats(ldm_indirect *a, unsigned program, unsigned fbo, const gib_view *view,
                        int audit)
{
    gib_pass_apply(&(gib_pass_state){.fbo = fbo, .width = view->width, .height = view->height,
                                     .blend = GIB_BLEND_ADD});
    glUseProgram(program);
    glUniformMatrix4fv(GIB_LOC_VIEW_PROJ, 1, GL_FALSE, view->view_proj);
    glUniform3fv(GIB_LOC_ORIGIN, 1, view->origin);
    glUniform1f(LDMI_SPLAT_LOC_TOPO_BIAS, a->topo_bias);
    if (audit) {
        glUniform3fv(LDMI_SPLAT_LOC_EYE, 1, view->origin);
        /* proj[0] = 1/tan(half horizontal angle), proj[5] = 1/tan(half vertical angle). */
        glUniform4f(LDMI_SPLAT_LOC_TAN_SIZE, 1.0f / view->proj[0], 1.0f / view->proj[5],
                    (float)view->width, (float)view->height);
    }
    glBindTextureUnit(GIB_UNIT_GBUF_POSITION, a->gbuffer.position);
    glBindTextureUnit(GIB_UNIT_GBUF_NORMAL, a->gbuffer.normal);
    glBindTextureUnit(GIB_UNIT_GBUF_ALBEDO, a->gbuffer.albedo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LDMI_SSBO_PHOTONS, a->photons);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, a->command);
    glBindVertexArray(a->vao);
    glDrawArraysIndirect(GL_POINTS, NULL);
    glBindVertexArray(0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    gib_pass_end();
}

/* LDMs a dispatch traces, so that a batch's photons always fit the buffer: a primary photon makes
 * at most one secondary photon per LDM (one of +-v). Only a light view larger than the buffer
 * itself can still overflow, which the status then says. */
static int ldms_per_batch(const ldm_indirect *a)
{
    uint64_t per_ldm = (uint64_t)a->photon_res * (uint64_t)a->photon_res;
    uint64_t n = a->capacity / per_ldm;
    return n > 0 ? (int)n : 1;
}

/* Traces LDMs [first, first + count) of the bound page from face f, splats what they stored onto
 * the target (and the audit's), and empties the photon buffer for the next batch; the overflow
 * count (the command's fifth word) is kept across batches. */
static void trace_batch(ldm_indirect *a, int first, int count, int primaries, unsigned fbo,
                        const gib_view *view, gib_timers *timers)
{
    const uint32_t empty[4] = {0, 1, 0, 0};
    glNamedBufferSubData(a->command, 0, sizeof empty, empty);
    gib_timer_begin(timers, "photon_trace");
    glUniform1i(LDMI_TRACE_LOC_FIRST, first);
    glUniform1i(LDMI_TRACE_LOC_COUNT, count);
    if (a->audit)
        glUniform1i(LDMI_TRACE_LOC_FIRST_PAGE, primaries);
    GLuint groups = gib_groups((unsigned)a->photon_res, GIB_GROUP_2D);
    glDispatchCompute(groups, groups, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    gib_timer_end(timers);
    gib_timer_begin(timers, "splat");
    draw_splats(a, a->splat_program, fbo, view, 0);
    gib_timer_end(timers);
    if (a->audit) {
        gib_timer_begin(timers, "audit");
        draw_splats(a, a->audit_splat_program, a->audit_fbo, view, 1);
        gib_timer_end(timers);
    }
}

/* Every light's faces, every LDM page, in batches that fit the photon buffer (Sec. 3.4: each
 * primary photon split over the N directions), splatted as they go. */
static void trace_and_splat(ldm_indirect *a, unsigned fbo, const gib_view *view, gib_timers *timers)
{
    const int per_batch = ldms_per_batch(a);
    for (int li = 0; li < (int)a->scene->scene->light_count; li++)
        for (int f = a->views.first_face[li]; f < a->views.first_face[li] + a->views.faces_of[li];
             f++)
            for (int p = 0; p < a->ldms.page_count; p++) {
                const ldm_page *page = &a->ldms.pages[p];
                for (int i = page->first; i < page->first + page->count; i += per_batch) {
                    int n = page->first + page->count - i;
                    /* bound for every batch: the splat pass before it changed the bindings */
                    ldm_bind_page(&a->ldms, p);
                    bind_trace(a, li, f, view);
                    trace_batch(a, i, n < per_batch ? n : per_batch, p == 0 && i == page->first,
                                fbo, view, timers);
                }
            }
}

/* The audit's sums, read back and added up in double (the splat passes drew its texture). */
static void audit_frame(ldm_indirect *a)
{
    ldm_indirect_audit au = {.valid = 1};
    size_t nslot = (size_t)AUDIT_SHADER_FATES * a->audit_groups;
    float *slots = malloc(16 * nslot);
    size_t npx = (size_t)a->width * a->height;
    float *px = malloc(16 * npx);
    if (!slots || !px) {
        free(slots);
        free(px);
        return;
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(a->audit_buffer, 0, (GLsizeiptr)(16 * nslot), slots);
    for (size_t g = 0; g < a->audit_groups; g++)
        for (int k = 0; k < AUDIT_SHADER_FATES; k++)
            for (int c = 0; c < 3; c++)
                au.flux[k][c] += slots[(g * AUDIT_SHADER_FATES + k) * 4 + c];
    glGetTextureImage(a->audit_texture, 0, GL_RGBA, GL_FLOAT, (GLsizei)(16 * npx), px);
    for (size_t i = 0; i < npx; i++)
        for (int c = 0; c < 3; c++)
            au.flux[LDM_AUDIT_SPLATTED][c] += px[4 * i + c];
    free(slots);
    free(px);
    a->last = au;
    audit_last = au;
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
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(targets[0].fbo, GL_COLOR, 0, zero);
    if (a->audit) {
        glClearNamedBufferData(a->audit_buffer, GL_RGBA32F, GL_RGBA, GL_FLOAT, NULL);
        glClearNamedFramebufferfv(a->audit_fbo, GL_COLOR, 0, zero);
    }
    ldm_build(&a->ldms, a->scene, timers);
    gib_gbuffer_render(&a->gbuffer, a->scene, view, timers, "gbuffer");
    gib_light_views_render(&a->views, a->scene, timers, "rsm");
    trace_and_splat(a, targets[0].fbo, view, timers);
    if (a->audit)
        audit_frame(a);
    return gib_gl_check("ldm_indirect", err);
}

static gib_status ldm_indirect_status(void *self)
{
    ldm_indirect *a = self;
    gib_status s = ldm_status(&a->ldms);
    if (s != GIB_STATUS_OK)
        return s;
    if (a->audit_log && a->last.valid) {
        char line[1024];
        ldm_indirect_audit_format(&a->last, line, sizeof line);
        fprintf(stderr, "ldm_indirect audit, last frame: %s\n", line);
    }
    uint32_t cmd[5];
    glGetNamedBufferSubData(a->command, 0, sizeof cmd, cmd);
    return cmd[4] ? GIB_STATUS_OVERFLOW : GIB_STATUS_OK;
}

static const char *const ldm_indirect_passes[] = {"gbuffer", "rsm", "ldm_build", "ldm_count",
    "photon_trace", "splat", "audit", NULL};

const gib_technique gib_technique_ldm_indirect = {
    .name = "ldm_indirect",
    .source = "Aalund, Frisvad, Baerentzen 2015, Sec. 3.4, 4.2 (photon differentials through LDMs)",
    .components = GIB_OUT_INDIRECT,
    .params = ldm_indirect_params,
    .passes = ldm_indirect_passes,
    .scene_needs_any = GIB_FEAT_POINT_LIGHT | GIB_FEAT_SPOT_LIGHT,
    .create = ldm_indirect_create,
    .render = ldm_indirect_render,
    .status = ldm_indirect_status,
    .destroy = ldm_indirect_destroy,
};

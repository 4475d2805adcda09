#include "runner.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "harness/gl/ledger.h"
#include "harness/gl/view.h"

const char *gib_output_name(unsigned bit)
{
    switch (bit) {
    case GIB_OUT_AO: return "ao";
    case GIB_OUT_DIRECT: return "direct";
    case GIB_OUT_INDIRECT: return "indirect";
    case GIB_OUT_GLOSSY: return "glossy";
    case GIB_OUT_CAUSTIC: return "caustic";
    default: return "unknown";
    }
}

static void set_status(gib_run_result *r, const char *status)
{
    snprintf(r->status, sizeof r->status, "%s", status);
    r->ok = !strcmp(status, "ok");
}

/* A failed step's status: the code its error carries (out_of_memory, shader_failed, ...), or the
 * step's own word when the failure has no code of its own. */
static void set_failure_status(gib_run_result *r, const char *step_status)
{
    const char *coded = gib_error_code_status(r->err.code);
    set_status(r, coded ? coded : step_status);
}

/* Reads an RGBA32F target into a 3-channel image with row 0 on top. */
static int read_target(unsigned texture, int w, int h, gib_image *img, gib_error *err)
{
    if (gib_image_alloc(img, w, h, 3, err) < 0)
        return -1;
    size_t n = (size_t)w * h;
    float *rgba = malloc(n * 16);
    if (!rgba)
        return gib_fail(err, "out of memory reading back a %dx%d image", w, h);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * 16), rgba);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++)
                img->px[((size_t)y * w + x) * 3 + c] = rgba[((size_t)(h - 1 - y) * w + x) * 4 + c];
    free(rgba);
    return gib_gl_check("reading back an image", err);
}

/* Available video memory in bytes from GL_NVX_gpu_memory_info (NVIDIA), or -1. llvmpipe and Mesa's
 * other drivers do not expose it (nor GL_ATI_meminfo): there the ledger is the only memory figure. */
static long long nvx_available_bytes(void)
{
    static int checked, has;
    if (!checked) {
        GLint n = 0;
        glGetIntegerv(GL_NUM_EXTENSIONS, &n);
        for (GLint i = 0; i < n && !has; i++)
            has = !strcmp((const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i), "GL_NVX_gpu_memory_info");
        checked = 1;
    }
    if (!has)
        return -1;
    GLint kb = 0;
    glGetIntegerv(0x9049 /* GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX */, &kb);
    return (long long)kb * 1024;
}

void gib_run_technique(const gib_gpu_scene *scene, const gib_technique *t, const gib_params *params,
                       int camera, int w, int h, int warmup, int frames, gib_run_result *r)
{
    gib_run_technique_at(scene, t, params, camera, w, h, warmup, frames, 0.0, 0.0, r);
}

/* The instant frame f of n is rendered at: the last at `time`, each earlier one dt before. */
static double frame_time(double time, double dt, int f, int n)
{
    return time - (double)(n - 1 - f) * dt;
}

void gib_run_technique_at(const gib_gpu_scene *scene, const gib_technique *t,
                          const gib_params *params, int camera, int w, int h, int warmup,
                          int frames, double time, double dt, gib_run_result *r)
{
    const int moves = scene->scene->motion_count > 0, nf = 1 + warmup + frames;
    memset(r, 0, sizeof *r);
    set_status(r, "ok");
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    /* Fault injection (tests/faults): a GPU memory budget for the technique's allocations. */
    const char *budget = getenv("GIBENCH_GPU_BUDGET_BYTES");
    if (budget && *budget)
        ledger.budget_bytes = strtoull(budget, NULL, 10);
    gib_timers timers;
    gib_timers_init(&timers);
    gib_image_target targets[GIB_MAX_OUTPUTS];
    unsigned fbos[GIB_MAX_OUTPUTS] = {0};
    int nt = 0;
    void *self = NULL;
    glGetError();

    /* Output targets belong to the harness: their memory is not the technique's. */
    gib_ledger out_ledger;
    gib_ledger_init(&out_ledger);
    unsigned depth = gib_gpu_renderbuffer(&out_ledger, "output.depth", GL_DEPTH_COMPONENT24, w, h,
                                          &r->err);
    for (unsigned bit = 1; bit && nt < GIB_MAX_OUTPUTS; bit <<= 1) {
        if (!(t->components & bit))
            continue;
        unsigned tex = gib_gpu_texture(&out_ledger, "output.color", GL_TEXTURE_2D, w, h, 1,
                                       GL_RGBA32F, 1, &r->err);
        if (!tex || !depth) {
            set_status(r, "alloc_failed");
            goto done;
        }
        glCreateFramebuffers(1, &fbos[nt]);
        glNamedFramebufferTexture(fbos[nt], GL_COLOR_ATTACHMENT0, tex, 0);
        glNamedFramebufferRenderbuffer(fbos[nt], GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
        const float zero[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(fbos[nt], GL_COLOR, 0, zero);
        targets[nt] = (gib_image_target){.component = bit, .fbo = fbos[nt], .texture = tex};
        r->output_components[nt] = bit;
        nt++;
    }
    r->output_count = nt;

    long long avail_before = nvx_available_bytes();
    r->driver_bytes = -1;
    /* create() sees the scene as the first frame will (a technique may measure it there). */
    if (moves && gib_gpu_scene_set_time(scene, frame_time(time, dt, 0, nf), &r->err) < 0) {
        set_status(r, "scene_update_failed");
        goto done;
    }
    const double create_start = gib_now_ms();
    self = t->create(scene, params, w, h, &ledger, &r->err);
    if (!self) {
        set_failure_status(r, "create_failed");
        goto done;
    }
    gib_view view;
    for (int f = 0; f < nf; f++) {
        const double tf = frame_time(time, dt, f, nf);
        gib_view_make(scene->scene, &scene->scene->cameras[camera], w, h, (float)tf, &view);
        gib_timers_frame_begin(&timers, f > warmup); /* f = 0 is the cold frame */
        /* A moving scene's vertices for this frame, in a pass of their own (static: no pass). */
        if (moves) {
            gib_timer_begin(&timers, "scene_update");
            int urc = gib_gpu_scene_set_time(scene, tf, &r->err);
            gib_timer_end(&timers);
            if (urc < 0) {
                gib_timers_frame_end(&timers);
                set_status(r, "scene_update_failed");
                goto done;
            }
        }
        int rc = t->render(self, &view, &timers, targets, nt, &r->err);
        gib_timers_frame_end(&timers);
        if (f == 0)
            r->first_frame_ms = gib_now_ms() - create_start;
        if (rc < 0) {
            set_failure_status(r, "render_failed");
            goto done;
        }
    }
    if (t->status) {
        const char *s = t->status(self);
        if (s && strcmp(s, "ok")) {
            set_status(r, s);
            snprintf(r->err.msg, sizeof r->err.msg, "technique '%s' reported '%s'", t->name, s);
        }
    }
    if (t->counters)
        t->counters(self, r->counters, sizeof r->counters);
    for (int i = 0; i < nt; i++)
        if (read_target(targets[i].texture, w, h, &r->images[i], &r->err) < 0) {
            set_status(r, "readback_failed");
            goto done;
        }
    r->frames = timers.frames;
    long long avail_after = nvx_available_bytes();
    if (avail_before >= 0 && avail_after >= 0)
        r->driver_bytes = avail_before - avail_after;
    r->pass_count = gib_timers_stats(&timers, r->passes, GIB_TIMER_MAX_PASSES, &r->gpu_total,
                                     &r->cpu_total);
done:
    r->technique_bytes = ledger.peak_bytes;
    gib_ledger_summary(&ledger, r->memory_by_label, sizeof r->memory_by_label);
    gib_ledger_structures(&ledger, r->memory_by_structure, sizeof r->memory_by_structure);
    gib_ledger_planned_structures(&ledger, r->planned_structures, sizeof r->planned_structures);
    if (self)
        t->destroy(self);
    gib_ledger_release_all(&ledger); /* whatever a technique forgot to free */
    for (int i = 0; i < nt; i++)
        glDeleteFramebuffers(1, &fbos[i]);
    gib_ledger_release_all(&out_ledger);
    gib_timers_destroy(&timers);
}

void gib_run_result_free(gib_run_result *r)
{
    for (int i = 0; i < r->output_count; i++)
        gib_image_free(&r->images[i]);
}

#include "runner.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/base/status.h"
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

static void set_status(gib_run_result *r, gib_status status)
{
    snprintf(r->status, sizeof r->status, "%s", gib_status_name(status));
    r->ok = status == GIB_STATUS_OK;
}

/* A failed step's status: the code its error carries (out_of_memory, shader_failed, ...), or the
 * step's own status when the failure has no code of its own. */
static void set_failure_status(gib_run_result *r, gib_status step_status)
{
    int coded = gib_error_code_status(r->err.code);
    set_status(r, coded >= 0 ? (gib_status)coded : step_status);
}

/* Reads an RGBA32F target into a 3-channel image with row 0 on top. */
static int read_target(unsigned texture, int w, int h, gib_image *img, gib_error *err)
{
    if (gib_image_alloc(img, w, h, 3, err) < 0)
        return -1;
    size_t n = (size_t)w * h;
    float *rgba = malloc(n * 16);
    if (!rgba)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "out of memory reading back a %dx%d image", w, h);
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
    gib_run(&(gib_run_request){.scene = scene, .technique = t, .params = params, .camera = camera,
                               .width = w, .height = h, .warmup = warmup, .frames = frames},
            r);
}

/* The instant frame f of n is rendered at: the last at `time`, each earlier one dt before. */
static double frame_time(const gib_run_request *rq, int f, int n)
{
    return rq->time - (double)(n - 1 - f) * rq->dt;
}

/* What one run holds while it runs: the technique's ledger and the harness's (output targets),
 * the timers, the targets, the technique's state. */
typedef struct run_state {
    gib_ledger ledger, out_ledger;
    gib_timers timers;
    gib_image_target targets[GIB_MAX_OUTPUTS];
    unsigned fbos[GIB_MAX_OUTPUTS];
    int target_count;
    void *self;
} run_state;

/* One RGBA32F target per output component, cleared, sharing one depth buffer. The targets belong
 * to the harness: their memory is not the technique's. */
static int make_targets(const gib_run_request *rq, run_state *st, gib_run_result *r)
{
    const int w = rq->width, h = rq->height;
    unsigned depth = gib_gpu_renderbuffer(&st->out_ledger, "output.depth", GL_DEPTH_COMPONENT24, w,
                                          h, &r->err);
    for (unsigned bit = 1; bit && st->target_count < GIB_MAX_OUTPUTS; bit <<= 1) {
        if (!(rq->technique->components & bit))
            continue;
        unsigned tex = gib_gpu_texture(&st->out_ledger, "output.color", GL_TEXTURE_2D, w, h, 1,
                                       GL_RGBA32F, 1, &r->err);
        if (!tex || !depth)
            return -1;
        const int i = st->target_count++;
        glCreateFramebuffers(1, &st->fbos[i]);
        glNamedFramebufferTexture(st->fbos[i], GL_COLOR_ATTACHMENT0, tex, 0);
        glNamedFramebufferRenderbuffer(st->fbos[i], GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
        const float zero[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(st->fbos[i], GL_COLOR, 0, zero);
        st->targets[i] = (gib_image_target){.component = bit, .fbo = st->fbos[i], .texture = tex};
        r->output_components[i] = bit;
    }
    r->output_count = st->target_count;
    return 0;
}

/* Whether the warm-up lasts until the time settles: asked for, and possible (the instants of the
 * frames do not depend on how many there are, and no sequence counts them). */
static int warmup_is_auto(const gib_run_request *rq)
{
    return rq->warmup == GIB_WARMUP_AUTO && rq->sequence < 2 &&
           (rq->dt == 0 || rq->scene->scene->motion_count == 0);
}

/* The warm-up frames: the request's, or more where a sequence needs more frames than it renders;
 * for an auto warm-up, the most it may take. */
static int warmup_frames(const gib_run_request *rq)
{
    if (warmup_is_auto(rq))
        return GIB_WARMUP_AUTO_MAX;
    const int warmup = rq->warmup < 0 ? GIB_WARMUP_FALLBACK : rq->warmup;
    const int need = rq->sequence - 1 - rq->frames;
    return warmup > need ? warmup : need;
}

/* An auto warm-up's frames after the counting one: settled once the last three GPU frame times lie
 * within 5% of their median, or after 2 s of warm-up. */
typedef struct warm_watch {
    double ms[3];
    int n;
    double start_ms;
} warm_watch;

static int warm_settled(warm_watch *w, double frame_ms)
{
    if (w->n == 0)
        w->start_ms = gib_now_ms();
    w->ms[w->n++ % 3] = frame_ms;
    if (w->n < 3)
        return 0;
    double lo = w->ms[0], hi = w->ms[0], sum = 0;
    for (int k = 0; k < 3; k++) {
        lo = w->ms[k] < lo ? w->ms[k] : lo;
        hi = w->ms[k] > hi ? w->ms[k] : hi;
        sum += w->ms[k];
    }
    const double median = sum - lo - hi;
    return hi - lo <= 0.05 * median || gib_now_ms() - w->start_ms > 2000.0;
}

/* With a sequence, frame f's images read back into their place in it (after its timing ends). */
static int read_sequence_frame(const gib_run_request *rq, run_state *st, gib_run_result *r, int f,
                               int nf)
{
    const int k = f - (nf - r->sequence);
    if (r->sequence < 2 || k < 0)
        return 0;
    for (int i = 0; i < st->target_count; i++)
        if (read_target(st->targets[i].texture, rq->width, rq->height, &r->seq_images[i][k],
                        &r->err) < 0) {
            set_status(r, GIB_STATUS_READBACK_FAILED);
            return -1;
        }
    return 0;
}

/* The cold frame, the warm-up and the timed frames (f = 0 is the cold one). A moving scene's
 * vertices are uploaded for each frame in a pass of their own. Returns -1 with the status set. */
static int render_frames(const gib_run_request *rq, run_state *st, gib_run_result *r,
                         double create_start)
{
    const gib_gpu_scene *scene = rq->scene;
    int warmup = warmup_frames(rq);
    const int moves = scene->scene->motion_count > 0, auto_warm = warmup_is_auto(rq);
    int nf = 1 + warmup + rq->frames;
    warm_watch watch = {0};
    gib_view view;
    for (int f = 0; f < nf; f++) {
        const double tf = frame_time(rq, f, nf);
        gib_view_make(scene->scene, &scene->scene->cameras[rq->camera], rq->width, rq->height,
                      (float)tf, &view);
        /* The work is counted in the first warm frame (the cold one where there is none). */
        st->timers.count_next = f == (warmup > 0);
        gib_timers_frame_begin(&st->timers, f > warmup);
        if (moves) {
            gib_timer_begin(&st->timers, GIB_SCENE_UPDATE_PASS);
            int urc = gib_gpu_scene_set_time(scene, tf, &r->err);
            gib_timer_end(&st->timers);
            if (urc < 0) {
                gib_timers_frame_end(&st->timers);
                set_status(r, GIB_STATUS_SCENE_UPDATE_FAILED);
                return -1;
            }
        }
        int rc = rq->technique->render(st->self, &view, &st->timers, st->targets,
                                       st->target_count, &r->err);
        gib_timers_frame_end(&st->timers);
        if (f == 0)
            r->first_frame_ms = gib_now_ms() - create_start;
        if (rc < 0) {
            set_failure_status(r, GIB_STATUS_RENDER_FAILED);
            return -1;
        }
        if (read_sequence_frame(rq, st, r, f, nf) < 0)
            return -1;
        if (auto_warm && f >= 2 && f <= warmup && warm_settled(&watch, st->timers.frame_ms)) {
            warmup = f;
            nf = 1 + warmup + rq->frames;
        }
    }
    r->warmup_frames = warmup;
    return 0;
}

/* The sequence's images, allocated before the frames (their pixels as each is read back). */
static int alloc_sequence(const gib_run_request *rq, run_state *st, gib_run_result *r)
{
    if (rq->sequence < 2)
        return 0;
    r->sequence = rq->sequence;
    for (int i = 0; i < st->target_count; i++)
        if (!(r->seq_images[i] = calloc((size_t)rq->sequence, sizeof(gib_image))))
            return gib_fail_code(&r->err, GIB_ERR_OUT_OF_MEMORY,
                                 "out of memory for a sequence of %d frames", rq->sequence);
    return 0;
}

/* After the frames: the technique's status word and counters, the images read back, the times. */
static int collect(const gib_run_request *rq, run_state *st, gib_run_result *r)
{
    const gib_technique *t = rq->technique;
    if (t->status) {
        gib_status s = t->status(st->self);
        if (s != GIB_STATUS_OK) {
            set_status(r, s);
            snprintf(r->err.msg, sizeof r->err.msg, "technique '%s' reported '%s' (%s)", t->name,
                     r->status, gib_status_doc(s) ? gib_status_doc(s) : "not a status");
        }
    }
    if (t->counters)
        t->counters(st->self, r->counters, sizeof r->counters);
    for (int i = 0; i < st->target_count; i++)
        if (read_target(st->targets[i].texture, rq->width, rq->height, &r->images[i], &r->err) <
            0) {
            set_status(r, GIB_STATUS_READBACK_FAILED);
            return -1;
        }
    r->frames = st->timers.frames;
    r->pass_count = gib_timers_stats(&st->timers, r->passes, GIB_TIMER_MAX_PASSES, &r->gpu_total,
                                     &r->cpu_total);
    return 0;
}

/* The memory columns, then everything released (whatever a technique forgot to free too). */
static void release(const gib_run_request *rq, run_state *st, gib_run_result *r)
{
    r->technique_bytes = st->ledger.peak_bytes;
    gib_ledger_summary(&st->ledger, r->memory_by_label, sizeof r->memory_by_label);
    gib_ledger_structures(&st->ledger, r->memory_by_structure, sizeof r->memory_by_structure);
    gib_ledger_planned_structures(&st->ledger, r->planned_structures,
                                  sizeof r->planned_structures);
    if (st->self)
        rq->technique->destroy(st->self);
    gib_ledger_release_all(&st->ledger);
    for (int i = 0; i < st->target_count; i++)
        glDeleteFramebuffers(1, &st->fbos[i]);
    gib_ledger_release_all(&st->out_ledger);
    gib_timers_destroy(&st->timers);
}

void gib_run(const gib_run_request *rq, gib_run_result *r)
{
    memset(r, 0, sizeof *r);
    set_status(r, GIB_STATUS_OK);
    r->driver_bytes = -1;
    /* Matrices and `render` refuse such values before loading a scene; a caller that builds its
     * own parameters gets the same refusal here, before anything is allocated. */
    if (gib_params_check(rq->technique, rq->params, &r->err) < 0) {
        set_failure_status(r, GIB_STATUS_CREATE_FAILED);
        return;
    }
    if (!rq->technique->create || !rq->technique->render) { /* an external's (gib_external_run) */
        gib_fail(&r->err, "technique '%s' has no create() or render()", rq->technique->name);
        set_status(r, GIB_STATUS_CREATE_FAILED);
        return;
    }
    run_state st;
    memset(&st, 0, sizeof st);
    gib_ledger_init(&st.ledger);
    gib_ledger_init(&st.out_ledger);
    /* Fault injection (tests/faults): a GPU memory budget for the technique's allocations. */
    const char *budget = getenv("GIBENCH_GPU_BUDGET_BYTES");
    if (budget && *budget)
        st.ledger.budget_bytes = strtoull(budget, NULL, 10);
    gib_timers_init(&st.timers);
    glGetError();
    if (make_targets(rq, &st, r) < 0 || alloc_sequence(rq, &st, r) < 0) {
        set_status(r, GIB_STATUS_ALLOC_FAILED);
        release(rq, &st, r);
        return;
    }
    const long long avail_before = nvx_available_bytes();
    /* create() sees the scene as the first frame will (a technique may measure it there). */
    const int moves = rq->scene->scene->motion_count > 0;
    const int nf = 1 + warmup_frames(rq) + rq->frames;
    if (moves && gib_gpu_scene_set_time(rq->scene, frame_time(rq, 0, nf), &r->err) < 0) {
        set_status(r, GIB_STATUS_SCENE_UPDATE_FAILED);
        release(rq, &st, r);
        return;
    }
    const double create_start = gib_now_ms();
    st.self = rq->technique->create(rq->scene, rq->params, rq->width, rq->height, &st.ledger,
                                    &r->err);
    if (!st.self)
        set_failure_status(r, GIB_STATUS_CREATE_FAILED);
    else if (render_frames(rq, &st, r, create_start) == 0 && collect(rq, &st, r) == 0) {
        const long long avail_after = nvx_available_bytes();
        if (avail_before >= 0 && avail_after >= 0)
            r->driver_bytes = avail_before - avail_after;
    }
    release(rq, &st, r);
}

void gib_run_result_free(gib_run_result *r)
{
    for (int i = 0; i < r->output_count; i++) {
        gib_image_free(&r->images[i]);
        for (int k = 0; r->seq_images[i] && k < r->sequence; k++)
            gib_image_free(&r->seq_images[i][k]);
        free(r->seq_images[i]);
        r->seq_images[i] = NULL;
    }
}

/* gibench — one run: a technique with validated parameters on an uploaded scene at one size.
 * create → the cold first frame → W warm-up frames → F timed frames → read back each component
 * image (ARCHITECTURE.md, data flow). The result carries everything a CSV row needs except the
 * metrics. */
#ifndef GIB_RUNNER_H
#define GIB_RUNNER_H

#include "techniques/technique.h"
#include "harness/imaging/image.h"
#include "harness/gl/gpu_scene.h"
#include "harness/gl/timers.h"

#define GIB_MAX_OUTPUTS 5

typedef struct gib_run_result {
    int ok;                         /* 0: see status and err */
    char status[32];                /* "ok", "create_failed", "render_failed", "overflow", ... */
    int output_count;
    unsigned output_components[GIB_MAX_OUTPUTS]; /* GIB_OUT_* bit of each image */
    gib_image images[GIB_MAX_OUTPUTS];
    int sequence;                   /* frames in seq_images (0: a single-frame run) */
    gib_image *seq_images[GIB_MAX_OUTPUTS]; /* per image, `sequence` frames, the last frame last */
    int pass_count;
    gib_pass_stats passes[GIB_TIMER_MAX_PASSES];
    gib_pass_stats gpu_total, cpu_total;
    int frames;
    int warmup_frames;              /* the warm-up frames rendered (auto: until the time settled) */
    double first_frame_ms;          /* wall time from create to the cold first frame's image
                                       (glFinish): compiles and first uses included */
    uint64_t technique_bytes;       /* peak bytes the technique's ledger held */
    long long driver_bytes;         /* what the driver says the run took (GL_NVX_gpu_memory_info:
                                       drop in available video memory from before create to after
                                       the last frame), -1 where the driver does not tell */
    char memory_by_label[1024];
    char memory_by_structure[256];  /* the same summed by structure (gib_ledger_structures) */
    char planned_structures[256];   /* what the technique planned, by structure, even when create()
                                       refused it (gib_ledger_planned_structures); "" if none */
    char counters[256];             /* the technique's counters of the last frame, or "" */
    char renderer[256];             /* an external technique's renderer (external.h), else "" */
    gib_error err;
} gib_run_result;

/* warmup GIB_WARMUP_AUTO: warm-up frames until three frames' GPU times agree within 5% of their
 * median (at least 3 after the first warm frame, at most GIB_WARMUP_AUTO_MAX frames or 2 s), for
 * a single-frame run of a scene standing still or at one instant; otherwise GIB_WARMUP_FALLBACK. */
#define GIB_WARMUP_AUTO (-2)
#define GIB_WARMUP_AUTO_MAX 60
#define GIB_WARMUP_FALLBACK 5

/* What to run: a technique with validated parameters on an uploaded scene, from `camera`, at
 * width x height: the cold first frame, then `warmup` warm-up frames, then `frames` timed frames
 * (warmup 0 still times no cold frame). The last frame (the image read back) shows instant `time`
 * (seconds), each frame before it, the cold one included, dt earlier (dt 0: all at `time`); for a
 * moving scene every frame first uploads its vertices in a timed pass "scene_update".
 * sequence above 1: the last `sequence` frames of the same technique instance are each read back
 * after their frame's timing ends (its state carries from frame to frame, as in an application);
 * when the run renders fewer frames, warm-up frames are added in front. */
typedef struct gib_run_request {
    const gib_gpu_scene *scene;
    const gib_technique *technique;
    const gib_params *params;
    int camera, width, height;
    int warmup, frames;
    double time, dt;
    int sequence; /* 0 or 1: only the last frame is read back */
} gib_run_request;

/* Never fails outright: problems are reported in result->status and result->err. */
void gib_run(const gib_run_request *request, gib_run_result *result);
/* gib_run at time 0 with dt 0, for tests that run a static scene. */
void gib_run_technique(const gib_gpu_scene *scene, const gib_technique *t, const gib_params *params,
                       int camera, int width, int height, int warmup, int frames,
                       gib_run_result *result);
void gib_run_result_free(gib_run_result *r);

/* Name of a GIB_OUT_* bit: "ao", "direct", ... (matching the reference's component names). */
const char *gib_output_name(unsigned bit);
/* The pass the runner times itself, around an animated scene's upload before a frame. */
#define GIB_SCENE_UPDATE_PASS "scene_update"

#endif

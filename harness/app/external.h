/* gibench — external techniques: a renderer outside gibench (Vulkan, D3D12, CUDA, any program)
 * declared in a matrix file and scored on the same references as a built-in technique
 * (README.md, "Bring your own renderer"; the job format: examples/external_renderer/README.md).
 *
 *   [external.myrenderer]
 *   command = python3 render.py   ; run by /bin/sh -c in the MATRIX FILE'S FOLDER, the job's path
 *                                 ; appended as its last argument (and in $GIBENCH_JOB)
 *   version = 1.0                 ; recorded in the rows (params: version=1.0)
 *   components = direct           ; ao, direct, indirect, glossy, caustic (comma-separated)
 *   timeout_s = 600               ; the command is killed (its process group) past it
 *
 * and `techniques = direct, myrenderer` (or `ext:myrenderer`). Its rows' technique is
 * `ext:myrenderer`, so they never mix with a built-in's; an external named like a built-in is
 * refused. With `ao` it takes the parameters dmax and obscurance ([params.myrenderer]), which set
 * its reference as they set ldm_ao's.
 *
 * Per row, gibench writes the scene at the row's instant into a temporary folder (job.json,
 * scene.gltf + scene.bin: external_job.c, format in examples/external_renderer/README.md), runs the
 * command, reads back one EXR per component and timings.json if present, and fills a run result
 * that is scored like a built-in's (run_score.c). */
#ifndef GIB_EXTERNAL_H
#define GIB_EXTERNAL_H

#include "runner.h"
#include "scenes/scene.h"
#include "techniques/technique.h"

#define GIB_EXTERNAL_PREFIX "ext:"
#define GIB_MAX_EXTERNALS 16

typedef struct gib_external {
    char name[64];          /* "myrenderer": the [external.NAME] section */
    char tech_name[72];     /* "ext:myrenderer": the rows' technique */
    char command[1024];
    char version[64];
    char workdir[1024];     /* the matrix file's folder: where the command runs */
    double timeout_s;
    gib_technique technique;  /* its descriptor (no create/render: the runner never calls them) */
    gib_param_spec params[3];
    gib_ref_binding reference[3];
    int line;               /* where its section starts, for errors */
} gib_external;

/* Sets key = value of [external.NAME] (name, command, version, components, timeout_s); errors
 * name the key and what it takes (the caller prefixes file and line). */
int gib_external_set(gib_external *x, const char *key, const char *value, gib_error *err);
/* Completes x after its keys: its descriptor and parameters; refuses a missing command or
 * components. matrix_path gives the folder the command runs in. */
int gib_external_finish(gib_external *x, const char *matrix_path, gib_error *err);

/* What a run of an external needs beyond the request: the warm-up and timed frames it is asked to
 * render (hints: it reports what it did in timings.json), the parameters key. */
typedef struct gib_external_request {
    const gib_external *x;
    const gib_scene *scene;
    const char *scene_name;
    const gib_params *params;
    int camera, width, height, warmup, frames;
    double time;
} gib_external_request;

/* Writes the job, runs the command and reads back its images and timings into r, which is then
 * scored as a built-in run's (never fails outright: r->status and r->err say why). */
void gib_external_run(const gib_external_request *rq, gib_run_result *r);

/* external_job.c: the job folder's files for request rq: job.json (outputs named
 * <dir>/<component>.exr and <dir>/timings.json), scene.gltf and scene.bin. */
int gib_external_write_job(const gib_external_request *rq, const char *dir, gib_error *err);

/* external_timings.c: timings.json into r's times, passes, memory, renderer and counters; 0, or
 * -1 with err naming what is malformed. */
int gib_external_read_timings(const char *path, gib_run_result *r, gib_error *err);

/* "version=1.0" after the parameters ("dmax=0.5;obscurance=0;version=1.0"): the rows' params. */
void gib_external_params_key(const gib_external *x, const gib_params *p, char *out, int len);

#endif

/* gibench tests — what every GL test sets up: a scene loaded and uploaded under a GL context, one
 * technique rendered on it, and
 * (for tests that compare with the path tracer's geometry) an Embree scene of the same triangles. */
#ifndef GIB_GL_FIXTURE_H
#define GIB_GL_FIXTURE_H

#include <embree3/rtcore.h>

#include "harness/gl/context.h"
#include "harness/gl/gpu_scene.h"
#include "harness/imaging/image.h"

typedef struct gib_gl_fixture {
    gib_scene scene;
    gib_gpu_scene gpu;
    gib_gl_info info;
    int gl_up;
} gib_gl_fixture;

/* Loads `scene_name`, creates a context (auto backend) and uploads the scene. On failure prints
 * "FAIL: set-up: ..." and returns -1. */
int gib_fixture_open(gib_gl_fixture *f, const char *scene_name);
/* Writes `text` to dir/name.scene and opens it as gib_fixture_open. On failure prints
 * "FAIL name: ..." and returns -1. */
int gib_fixture_open_text(gib_gl_fixture *f, const char *dir, const char *name, const char *text);
void gib_fixture_close(gib_gl_fixture *f);

/* The path tracer's image of `component` (GIB_COMP_*) of the fixture's scene at w x h with spp
 * samples (seed 1), and its statistics (st may be NULL). On failure prints "FAIL: reference: ..."
 * and returns -1. */
struct gib_ref_stats;
int gib_fixture_reference(const gib_gl_fixture *f, int component, int w, int h, int spp,
                          gib_image *out, struct gib_ref_stats *st);

/* Technique `name` at its defaults but `params` (NULL-terminated "key=value" strings) rendered once
 * from `camera` at w x h, its image of `component` (GIB_OUT_*) moved into out. On failure prints
 * "FAIL name: ..." and returns -1. */
int gib_fixture_render(gib_gl_fixture *f, const char *name, const char *const *params, int camera,
                       int w, int h, unsigned component, gib_image *out);
/* The mean over the RGB channels of that image, as gib_rgb_mean; -1 on failure (printed). */
double gib_fixture_render_mean(gib_gl_fixture *f, const char *name, const char *const *params,
                               int camera, int w, int h, unsigned component);

/* A committed Embree scene of the scene's triangles (release with rtcReleaseScene and
 * rtcReleaseDevice). */
RTCScene gib_fixture_embree(const gib_scene *scene, RTCDevice *device);
/* Distance to the first hit along o + t d, or -1 on a miss. */
float gib_fixture_trace(RTCScene s, const float o[3], const float d[3]);
/* The scene's bounding-box diagonal. */
float gib_fixture_diagonal(const gib_scene *scene);

#endif

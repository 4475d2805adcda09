/* gibench tests — what every GL test sets up: a scene loaded and uploaded under a GL context, and
 * (for tests that compare with the path tracer's geometry) an Embree scene of the same triangles. */
#ifndef GIB_GL_FIXTURE_H
#define GIB_GL_FIXTURE_H

#include <embree3/rtcore.h>

#include "harness/gl/context.h"
#include "harness/gl/gpu_scene.h"

typedef struct gib_gl_fixture {
    gib_scene scene;
    gib_gpu_scene gpu;
    gib_gl_info info;
    int gl_up;
} gib_gl_fixture;

/* Loads `scene_name`, creates a context (auto backend) and uploads the scene. On failure prints
 * "FAIL: set-up: ..." and returns -1. */
int gib_fixture_open(gib_gl_fixture *f, const char *scene_name);
void gib_fixture_close(gib_gl_fixture *f);

/* A committed Embree scene of the scene's triangles (release with rtcReleaseScene and
 * rtcReleaseDevice). */
RTCScene gib_fixture_embree(const gib_scene *scene, RTCDevice *device);
/* Distance to the first hit along o + t d, or -1 on a miss. */
float gib_fixture_trace(RTCScene s, const float o[3], const float d[3]);
/* The scene's bounding-box diagonal. */
float gib_fixture_diagonal(const gib_scene *scene);

#endif

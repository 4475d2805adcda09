/* gibench — the shared G-buffer pass: world position, viewer-facing shading normal, albedo and
 * specular parameters per pixel (techniques/common/gbuffer.frag). Position, normal and albedo are
 * RGBA32F: half floats would put an error of their own into every lit pixel of every technique,
 * the G-buffer's, not the technique's. */
#ifndef GIB_GBUFFER_H
#define GIB_GBUFFER_H

#include "harness/gl/gpu_scene.h"
#include "harness/gl/timers.h"
#include "techniques/technique.h"

typedef struct gib_gbuffer {
    int width, height;
    unsigned fbo, position, normal, albedo, specular, depth;
    unsigned program;
} gib_gbuffer;

int gib_gbuffer_create(gib_gbuffer *g, int width, int height, gib_ledger *ledger, gib_error *err);
/* Renders the scene into the G-buffer, timed as pass `pass` ("gbuffer" for the camera; "rsm" when
 * the view is a light's, which makes it a reflective shadow map whose normals face the light). */
void gib_gbuffer_render(gib_gbuffer *g, const gib_gpu_scene *scene, const gib_view *view,
                        gib_timers *timers, const char *pass);
/* Binds position, normal, albedo, specular to texture units 0..3. */
void gib_gbuffer_bind(const gib_gbuffer *g);
void gib_gbuffer_destroy(gib_gbuffer *g, gib_ledger *ledger);

#endif

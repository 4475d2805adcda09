/* gibench technique `direct` — rasterised direct light from every light of the scene with shadow
 * maps and percentage-closer filtering (Williams 1978; Reeves, Salesin and Cook 1987). It is the
 * direct-light baseline that indirect techniques add to, and the first check that the GL side and the
 * path tracer see the same world: without shadows it is exact up to float precision, so its error
 * against the reference `direct` is the shadow maps' error (resolution, PCF blur, bias). */
#include <glad/gl.h>
#include <stdlib.h>

#include "harness/gl/context.h"
#include "harness/gl/ledger.h"
#include "techniques/common/shader.h"
#include "techniques/common/gbuffer.h"
#include "techniques/common/shadow_map.h"

typedef struct direct {
    const gib_gpu_scene *scene;
    gib_ledger *ledger;
    gib_gbuffer gbuffer;
    gib_shadow_maps shadows;
    unsigned program, vao;
    int pcf_radius;
    float normal_offset;
} direct;

static const gib_param_spec direct_params[] = {
    {"shadow_res", GIB_PARAM_INT, 1024, 16, 8192, "shadow map resolution (cube face side, texels)"},
    {"pcf", GIB_PARAM_INT, 1, 0, 4, "PCF radius r: (2r+1)^2 shadow taps"},
    {"normal_offset", GIB_PARAM_FLOAT, 1.5, 0, 16, "shadow lookup offset along the normal, texels"},
    {0},
};

extern const gib_technique gib_technique_direct;
static void direct_destroy(void *self);

static void *direct_create(const gib_gpu_scene *scene, const gib_params *p, int width, int height,
                           gib_ledger *ledger, gib_error *err)
{
    direct *d = calloc(1, sizeof *d);
    if (!d) {
        gib_fail(err, "out of memory");
        return NULL;
    }
    d->scene = scene;
    d->ledger = ledger;
    const gib_technique *t = &gib_technique_direct;
    d->pcf_radius = gib_param_int(t, p, "pcf");
    d->normal_offset = (float)gib_param_float(t, p, "normal_offset");
    const char *files[] = {"common/fullscreen.vert", "direct/direct.frag"};
    if (gib_gbuffer_create(&d->gbuffer, width, height, ledger, err) < 0 ||
        gib_shadow_maps_create(&d->shadows, scene, gib_param_int(t, p, "shadow_res"), ledger,
                               err) < 0 ||
        !(d->program = gib_program(files, 2, NULL, err))) {
        direct_destroy(d);
        return NULL;
    }
    glCreateVertexArrays(1, &d->vao);
    return d;
}

static int direct_render(void *self, const gib_view *view, gib_timers *timers,
                         const gib_image_target *targets, int target_count, gib_error *err)
{
    direct *d = self;
    if (target_count != 1)
        return gib_fail(err, "direct renders one component, was given %d targets", target_count);
    gib_shadow_maps_render(&d->shadows, d->scene, timers);
    gib_gbuffer_render(&d->gbuffer, d->scene, view, timers, "gbuffer");

    gib_timer_begin(timers, "shade");
    glBindFramebuffer(GL_FRAMEBUFFER, targets[0].fbo);
    glViewport(0, 0, view->width, view->height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(d->program);
    gib_gpu_scene_bind(d->scene);
    gib_gbuffer_bind(&d->gbuffer);
    gib_shadow_maps_bind(&d->shadows, d->pcf_radius, d->normal_offset);
    glUniform3fv(2, 1, view->camera->eye);
    glUniform1i(3, (int)d->scene->scene->light_count);
    glBindVertexArray(d->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    gib_timer_end(timers);
    return gib_gl_check("direct", err);
}

static void direct_destroy(void *self)
{
    direct *d = self;
    if (!d)
        return;
    gib_gbuffer_destroy(&d->gbuffer, d->ledger);
    gib_shadow_maps_destroy(&d->shadows, d->ledger);
    if (d->program)
        glDeleteProgram(d->program);
    if (d->vao)
        glDeleteVertexArrays(1, &d->vao);
    free(d);
}

const gib_technique gib_technique_direct = {
    .name = "direct",
    .source = "rasterised direct light, shadow maps with PCF (Williams 1978; Reeves et al. 1987)",
    .components = GIB_OUT_DIRECT,
    .params = direct_params,
    .scene_needs = 0,
    .scene_needs_any = GIB_FEAT_POINT_LIGHT | GIB_FEAT_SPOT_LIGHT | GIB_FEAT_DIR_LIGHT,
    .create = direct_create,
    .render = direct_render,
    .status = NULL,
    .destroy = direct_destroy,
};

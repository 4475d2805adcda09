/* gibench technique `rsm_gather` — one diffuse bounce from virtual point lights gathered at every
 * pixel (Dachsbacher and Stamminger 2005; the thesis' baseline, Sec. 2.2.2, Algorithm 2.1, with the
 * VPL patterns of Sec. 3.2.1).
 *
 * Per frame (timer passes):
 *  gbuffer    the shared G-buffer;
 *  rsm        the shared light views (position, normal, flux at rsm_res; label "rsm"), then the
 *             VPLs extracted from them (techniques/common/vpl.h: vpl_count VPLs whose regions of
 *             texels partition the views, so their fluxes add up to the reflected flux);
 *  gathering  every VPL at every pixel: L = rho_d / pi x sum Phi cos_l cos_x / (pi max(d^2, eps^2))
 *             (vpl_gather.glsl, with the corrections of the text's formula), eps =
 *             clamp_distance in the scene's units. No visibility between VPL and pixel (as the
 *             thesis): light passes through occluders, so the blocks' indirect shadows are missing.
 * Output `indirect`. */
#include <glad/gl.h>
#include <stdlib.h>

#include "harness/gl/context.h"
#include "techniques/common/fullscreen.h"
#include "techniques/common/gbuffer.h"
#include "techniques/common/vpl.h"
#include "techniques/rsm_gather/rsm_gather.h"
#include "techniques/rsm_gather/rsm_gather_slots.h"

extern const gib_technique gib_technique_rsm_gather;

typedef struct rsm_gather {
    const gib_gpu_scene *scene;
    gib_ledger *ledger;
    gib_vpl_frame frame;     /* G-buffer, light views, VPLs */
    gib_fullscreen gather;
    float eps;
} rsm_gather;

static const gib_param_spec rsm_gather_params[] = {
    GIB_VPL_PARAMS,
    {0},
};

static void rsm_gather_destroy(void *self)
{
    rsm_gather *s = self;
    if (!s)
        return;
    gib_fullscreen_destroy(&s->gather);
    gib_vpl_frame_destroy(&s->frame, s->ledger);
    free(s);
}

static void *rsm_gather_create(const gib_gpu_scene *scene, const gib_params *p, int width,
                               int height, gib_ledger *ledger, gib_error *err)
{
    const gib_technique *t = &gib_technique_rsm_gather;
    rsm_gather *s = calloc(1, sizeof *s);
    if (!s) {
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    s->scene = scene;
    s->ledger = ledger;
    s->eps = (float)gib_param_float(t, p, "clamp_distance");
    if (gib_vpl_frame_create(&s->frame, scene, width, height, gib_param_int(t, p, "rsm_res"),
                             gib_param_int(t, p, "vpl_count"), ledger, err) < 0 ||
        gib_fullscreen_create(&s->gather, "rsm_gather/rsm_gather.frag", NULL, err) < 0 ||
        gib_gl_check("rsm_gather creation", err) < 0) {
        rsm_gather_destroy(s);
        return NULL;
    }
    return s;
}

void rsm_gather_render_vpls(void *self, const gib_view *view, gib_timers *timers)
{
    rsm_gather *s = self;
    gib_vpl_frame_render(&s->frame, s->scene, view, timers);
}

void rsm_gather_gather(void *self, const gib_view *view, gib_timers *timers, unsigned fbo)
{
    rsm_gather *s = self;
    gib_timer_begin(timers, "gathering");
    gib_fullscreen_begin(&s->gather, fbo, view->width, view->height, 0);
    gib_gbuffer_bind(&s->frame.gbuffer);
    gib_vpls_bind(&s->frame.vpls);
    glUniform1i(RSM_GATHER_LOC_VPLS, s->frame.vpls.count);
    glUniform1f(RSM_GATHER_LOC_EPS, s->eps);
    gib_fullscreen_draw(&s->gather);
    gib_fullscreen_end();
    gib_timer_end(timers);
}

static int rsm_gather_render(void *self, const gib_view *view, gib_timers *timers,
                             const gib_image_target *targets, int target_count, gib_error *err)
{
    rsm_gather_render_vpls(self, view, timers);
    for (int i = 0; i < target_count; i++)
        if (targets[i].component == GIB_OUT_INDIRECT)
            rsm_gather_gather(self, view, timers, targets[i].fbo);
    return gib_gl_check("rsm_gather", err);
}

static const char *const rsm_gather_passes[] = {"gbuffer", "rsm", "gathering", NULL};

const gib_technique gib_technique_rsm_gather = {
    .name = "rsm_gather",
    .source = "VPLs from reflective shadow maps gathered at every pixel (Dachsbacher and "
              "Stamminger 2005; thesis 004 Sec. 2.2.2, 3.2.1, Alg. 2.1)",
    .components = GIB_OUT_INDIRECT,
    .params = rsm_gather_params,
    .passes = rsm_gather_passes,
    .reference = NULL,
    .scene_needs = 0,
    .scene_needs_any = GIB_FEAT_POINT_LIGHT | GIB_FEAT_SPOT_LIGHT | GIB_FEAT_DIR_LIGHT,
    .create = rsm_gather_create,
    .render = rsm_gather_render,
    .status = NULL,
    .destroy = rsm_gather_destroy,
};

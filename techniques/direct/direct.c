/* gibench technique `direct` — rasterised direct light from every light of the scene with shadow
 * maps and percentage-closer filtering (Williams 1978; Reeves, Salesin and Cook 1987). It is the
 * direct-light baseline that indirect techniques add to, and the first check that the GL side and the
 * path tracer see the same world: without shadows it is exact up to float precision, so its error
 * against the reference `direct` is the shadow maps' error (resolution, PCF blur, bias). */
#include <stdlib.h>

#include "harness/gl/context.h"
#include "techniques/common/direct_light.h"

typedef struct direct {
    const gib_gpu_scene *scene;
    gib_ledger *ledger;
    gib_gbuffer gbuffer;
    gib_direct_light light;
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
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    d->scene = scene;
    d->ledger = ledger;
    const gib_technique *t = &gib_technique_direct;
    if (gib_gbuffer_create(&d->gbuffer, width, height, ledger, err) < 0 ||
        gib_direct_light_create(&d->light, scene, gib_param_int(t, p, "shadow_res"),
                                gib_param_int(t, p, "pcf"),
                                (float)gib_param_float(t, p, "normal_offset"), ledger, err) < 0) {
        direct_destroy(d);
        return NULL;
    }
    return d;
}

static int direct_render(void *self, const gib_view *view, gib_timers *timers,
                         const gib_image_target *targets, int target_count, gib_error *err)
{
    direct *d = self;
    if (target_count != 1)
        return gib_fail(err, "direct renders one component, was given %d targets", target_count);
    gib_direct_light_shadows(&d->light, d->scene, timers);
    gib_gbuffer_render(&d->gbuffer, d->scene, view, timers, "gbuffer");
    gib_direct_light_shade(&d->light, d->scene, &d->gbuffer, view, targets[0].fbo, timers);
    return gib_gl_check("direct", err);
}

static void direct_destroy(void *self)
{
    direct *d = self;
    if (!d)
        return;
    gib_gbuffer_destroy(&d->gbuffer, d->ledger);
    gib_direct_light_destroy(&d->light, d->ledger);
    free(d);
}

static const char *const direct_passes[] = {"gbuffer", "shadow", "shade", NULL};

const gib_technique gib_technique_direct = {
    .name = "direct",
    .source = "rasterised direct light, shadow maps with PCF (Williams 1978; Reeves et al. 1987)",
    .components = GIB_OUT_DIRECT,
    .params = direct_params,
    .passes = direct_passes,
    .scene_needs = 0,
    .scene_needs_any = GIB_FEAT_POINT_LIGHT | GIB_FEAT_SPOT_LIGHT | GIB_FEAT_DIR_LIGHT,
    .create = direct_create,
    .render = direct_render,
    .status = NULL,
    .destroy = direct_destroy,
};

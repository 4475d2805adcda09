#include "direct_light.h"

#include <glad/gl.h>
#include <string.h>

#include "techniques/common/common_slots.h"

int gib_direct_light_create(gib_direct_light *d, const gib_gpu_scene *scene, int shadow_res,
                            int pcf_radius, float normal_offset, gib_ledger *ledger,
                            gib_error *err)
{
    memset(d, 0, sizeof *d);
    d->pcf_radius = pcf_radius;
    d->normal_offset = normal_offset;
    if (gib_shadow_maps_create(&d->shadows, scene, shadow_res, ledger, err) < 0 ||
        gib_fullscreen_create(&d->pass, "common/direct_light.frag", NULL, err) < 0)
        return -1;
    return 0;
}

void gib_direct_light_shadows(gib_direct_light *d, const gib_gpu_scene *scene, gib_timers *timers)
{
    gib_shadow_maps_render(&d->shadows, scene, timers);
}

void gib_direct_light_shade(gib_direct_light *d, const gib_gpu_scene *scene,
                            const gib_gbuffer *gbuffer, const gib_view *view, unsigned fbo,
                            gib_timers *timers)
{
    gib_timer_begin(timers, "shade");
    gib_fullscreen_begin(&d->pass, fbo, view->width, view->height, 0);
    gib_gpu_scene_bind(scene);
    gib_gbuffer_bind(gbuffer);
    gib_shadow_maps_bind(&d->shadows, d->pcf_radius, d->normal_offset);
    glUniform3fv(GIB_DIRECT_LOC_EYE, 1, view->camera->eye);
    glUniform1i(GIB_DIRECT_LOC_LIGHT_COUNT, (int)scene->scene->light_count);
    gib_fullscreen_draw(&d->pass);
    gib_fullscreen_end();
    gib_timer_end(timers);
}

void gib_direct_light_destroy(gib_direct_light *d, gib_ledger *ledger)
{
    gib_shadow_maps_destroy(&d->shadows, ledger);
    gib_fullscreen_destroy(&d->pass);
}

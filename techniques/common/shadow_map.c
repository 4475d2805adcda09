#include "shadow_map.h"

#include <glad/gl.h>

#include "harness/gl/bindings.h"

int gib_shadow_maps_create(gib_shadow_maps *sm, const gib_gpu_scene *gpu, int res,
                           gib_ledger *ledger, gib_error *err)
{
    return gib_light_views_create(&sm->views, gpu, res, GIB_LV_DEPTH, "shadow", ledger, err);
}

void gib_shadow_maps_render(gib_shadow_maps *sm, const gib_gpu_scene *gpu, gib_timers *timers)
{
    gib_light_views_render(&sm->views, gpu, timers, "shadow");
}

void gib_shadow_maps_bind(const gib_shadow_maps *sm, int pcf_radius, float normal_offset)
{
    gib_light_views_bind(&sm->views);
    glUniform1i(GIB_LOC_LV_PCF_RADIUS, pcf_radius);
    glUniform1f(GIB_LOC_LV_NORMAL_OFFSET, normal_offset);
}

void gib_shadow_maps_destroy(gib_shadow_maps *sm, gib_ledger *ledger)
{
    gib_light_views_destroy(&sm->views, ledger);
}

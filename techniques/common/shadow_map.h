/* gibench — shadow maps for every light of the scene: the depth of the light views
 * (light_view.h), looked up by shadow_lookup.glsl with percentage-closer filtering over
 * (2r+1)^2 taps and a normal offset in texels. Shared by the techniques that need direct
 * visibility. */
#ifndef GIB_SHADOW_MAP_H
#define GIB_SHADOW_MAP_H

#include "techniques/common/light_view.h"

typedef struct gib_shadow_maps {
    gib_light_views views;
} gib_shadow_maps;

int gib_shadow_maps_create(gib_shadow_maps *sm, const gib_gpu_scene *scene, int res,
                           gib_ledger *ledger, gib_error *err);
/* Renders every light's map; timed as pass "shadow". Static scenes could skip this after the first
 * frame, but gibench times what a dynamic scene would pay, so it runs every frame. */
void gib_shadow_maps_render(gib_shadow_maps *sm, const gib_gpu_scene *scene, gib_timers *timers);
/* Binds the maps and the light-view table and sets the lookup uniforms of the program in use. */
void gib_shadow_maps_bind(const gib_shadow_maps *sm, int pcf_radius, float normal_offset_texels);
void gib_shadow_maps_destroy(gib_shadow_maps *sm, gib_ledger *ledger);

#endif

/* gibench — direct light (L D E and L S E) from every light of the scene on the G-buffer, with
 * shadow maps and percentage-closer filtering (Williams 1978; Reeves, Salesin and Cook 1987):
 * the pass of the `direct` technique, shared with the techniques that add to direct light. */
#ifndef GIB_DIRECT_LIGHT_H
#define GIB_DIRECT_LIGHT_H

#include "techniques/common/fullscreen.h"
#include "techniques/common/gbuffer.h"
#include "techniques/common/shadow_map.h"

typedef struct gib_direct_light {
    gib_shadow_maps shadows;
    gib_fullscreen pass;
    int pcf_radius;
    float normal_offset;
} gib_direct_light;

int gib_direct_light_create(gib_direct_light *d, const gib_gpu_scene *scene, int shadow_res,
                            int pcf_radius, float normal_offset_texels, gib_ledger *ledger,
                            gib_error *err);
/* The shadow maps of this frame (pass "shadow"). */
void gib_direct_light_shadows(gib_direct_light *d, const gib_gpu_scene *scene, gib_timers *timers);
/* Shades the G-buffer into `fbo` (pass "shade"), replacing what is there. */
void gib_direct_light_shade(gib_direct_light *d, const gib_gpu_scene *scene,
                            const gib_gbuffer *gbuffer, const gib_view *view, unsigned fbo,
                            gib_timers *timers);
void gib_direct_light_destroy(gib_direct_light *d, gib_ledger *ledger);

#endif

/* gibench — shadow maps for every light of the scene, shared by the techniques that need direct
 * visibility (DESIGN.md: shared passes live once in techniques/common/).
 *
 * Point and spot lights get a cube map of distances (one layer-face set in a cube-map array), since
 * a spot's cone may be as wide as a hemisphere (the Cornell spot is); directional lights get an
 * orthographic map over the scene's bounding sphere. Lookups: shadow_lookup.glsl, with
 * percentage-closer filtering over (2r+1)^2 taps and a normal offset in texels. */
#ifndef GIB_SHADOW_MAP_H
#define GIB_SHADOW_MAP_H

#include "harness/gl/gpu_scene.h"
#include "harness/gl/timers.h"
#include "techniques/technique.h"

typedef struct gib_shadow_maps {
    int res;
    int cube_count, ortho_count;
    unsigned cube_array, ortho_array; /* R32F distances */
    unsigned depth;                    /* depth renderbuffer, res x res */
    unsigned fbo, program, slots;      /* slots: SSBO binding 2 */
    float *ortho_extent;               /* per light */
    float (*ortho_origin)[3];
} gib_shadow_maps;

int gib_shadow_maps_create(gib_shadow_maps *sm, const gib_gpu_scene *scene, int res,
                           gib_ledger *ledger, gib_error *err);
/* Renders every light's map; timed as pass "shadow". Static scenes could skip this after the first
 * frame, but gibench times what a dynamic scene would pay, so it runs every frame. */
void gib_shadow_maps_render(gib_shadow_maps *sm, const gib_gpu_scene *scene, gib_timers *timers);
/* Binds the maps (units 4, 5), the slot SSBO (binding 2) and sets the lookup uniforms of the
 * program in use (locations 20-22 of shadow_lookup.glsl). */
void gib_shadow_maps_bind(const gib_shadow_maps *sm, int pcf_radius, float normal_offset_texels);
void gib_shadow_maps_destroy(gib_shadow_maps *sm, gib_ledger *ledger);

#endif

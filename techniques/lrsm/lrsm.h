/* gibench technique `lrsm` — layered reflective shadow maps with voxel cone tracing (Sugihara,
 * Rauwendaal, Salvi 2014). The layers are their own small module so that tests can build them from a
 * synthetic light view and count their bytes.
 *
 * Layout: one GL_TEXTURE_2D_ARRAY per attribute (Table 1: radiance RGBA16F, normal + opacity
 * RGBA16F, warped z, z^2 + opacity RGBA16 UNORM), at half the light view's side, full mip chains;
 * array layer face * D * N + d * N + k holds depth partition d and <n.l> partition k of light-view
 * face `face`. A point light or a wide spot (cube light view) has 6 faces, each with its own D x N
 * layers; a narrow spot and a directional light have one. */
#ifndef GIB_LRSM_H
#define GIB_LRSM_H

#include <stdint.h>

#include "techniques/common/light_view.h"

typedef struct lrsm_layers {
    int half;                 /* layer side: light-view res / 2 */
    int depth_parts, normal_parts, faces, lights;
    float overlap;            /* delta as a fraction of a depth partition */
    int jacobian;             /* 1: radiance filtered over surface area (lrsm_build.comp); 0 */
    unsigned radiance, normal, depth;  /* 2D arrays, full chains */
    unsigned table;           /* SSBO (GIB_SSBO_OWN_FIRST): per light (z0, z1, delta, 0) */
    float *table_data;
    unsigned program;
} lrsm_layers;

/* Bytes of the layers (the plan, exact): 24 B per texel, faces x layers x every level of the chain. */
uint64_t lrsm_layers_bytes(int rsm_res, int layers, int faces);

/* Allocates the layers for the views' faces through the ledger ("layers.radiance", "layers.normal",
 * "layers.depth"; the partition table, 16 bytes a light, as "rsm.partitions" so that the structure
 * `layers` is exactly Table 2's LRSM) and builds the construction program. */
int lrsm_layers_create(lrsm_layers *L, const gib_light_views *views, int depth_parts,
                       int normal_parts, float overlap, gib_ledger *ledger, gib_error *err);
/* The static depth partitions of each light: its view's depth range over the scene's bounds. */
void lrsm_layers_partition(lrsm_layers *L, const gib_light_views *views, const gib_scene *scene);
/* Sets light i's range by hand (tests). */
void lrsm_layers_set_range(lrsm_layers *L, int light, float z0, float z1);
/* The construction pass over every face (the views must be rendered), then the mip chains. */
void lrsm_layers_build(lrsm_layers *L, const gib_light_views *views);
/* Binds the arrays to GIB_UNIT_OWN_FIRST + 0..2 and the table, and sets D and N on the current
 * program (lrsm_common.glsl's uniforms). */
void lrsm_layers_bind(const lrsm_layers *L);
void lrsm_layers_destroy(lrsm_layers *L, gib_ledger *ledger);

/* Test hook: lrsm_sample() (lrsm_sample.glsl) at n cone samples, in[2i] = (x_c, r_c), in[2i + 1] =
 * (v_c, 0), out[i] = (L, the lit coverage sum A V): the LRSM's radiance lookup apart from the
 * voxels; `seams` as lrsm's parameter (1: every face a footprint overlaps). */
int lrsm_layers_probe(const lrsm_layers *L, const gib_light_views *views, float mip_clamp,
                      int seams, const float *in, int n, float *out, gib_error *err);

#endif

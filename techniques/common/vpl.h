/* gibench — virtual point lights from the shared light views (the thesis, Sec. 3.2.1; Dachsbacher
 * and Stamminger 2005), shared by `rsm_gather` and `multires_ir` so that the two differ only in
 * where they gather.
 *
 * Pattern, fixed at create from a seeded generator (the thesis samples "at loading time" and keeps
 * the pattern): vpl_count VPLs spread over the light views' faces (face f of F gets
 * floor(V(f+1)/F) - floor(Vf/F)); on a perspective face (a spot of at most 45 degrees) the circle
 * pattern u = 0.5 + 0.5 sqrt(xi1) cos(2 pi xi2), v = 0.5 + 0.5 sqrt(xi1) sin(2 pi xi2); on a cube
 * face (point lights, wider spots) or an orthographic face (directional) the jittered grid: n cells
 * in round(sqrt(n)) rows of equal height, row r split in equal cells (n = N^2 gives the N x N grid).
 *
 * Flux (the departure from the text): each VPL stands for a region of its face's texels,
 * its grid cell or, for the circle, its Voronoi cell (texels nearest to its sample point): the
 * regions partition the face, and each frame a compute pass (vpl_extract.comp) sums the FLUX of
 * the VPL's region, so the VPLs' fluxes add up to the light views' total reflected flux whatever
 * the pattern's density. The regions are lists of texels built once at create (CPU).
 * Position and normal: the texel under the sample point; where no surface is there, the texel of
 * the region nearest to it that holds one (a VPL whose region holds no surface has no flux and is
 * marked invalid). */
#ifndef GIB_VPL_H
#define GIB_VPL_H

#include "techniques/common/gbuffer.h"
#include "techniques/common/light_view.h"

/* One VPL in the SSBO (std430, 48 bytes): position.xyz (w: 1 valid, 0 none), normal.xyz (facing
 * the light; w: 0), flux.rgb (W, the diffusely reflected flux it stands for). */
#define GIB_VPL_FLOATS 12

typedef struct gib_vpls {
    int count;          /* VPLs in all (0 when the scene has no viewed light) */
    int res;            /* the light views' side */
    unsigned buffer;    /* the VPLs (GIB_VPL_FLOATS floats each) */
    unsigned cells;     /* per VPL: ivec4(face, sample texel y * res + x, first, count) */
    unsigned texels;    /* the regions' texels (y * res + x), grouped by VPL */
    unsigned program;
} gib_vpls;

/* Builds the pattern and the regions for the views' faces (the views need GIB_LV_POSITION,
 * GIB_LV_NORMAL and GIB_LV_FLUX) through the ledger ("<label>.buffer", "<label>.cells",
 * "<label>.regions"). Fails when count is below the views' face count (a face without a VPL would
 * lose its flux). */
int gib_vpls_create(gib_vpls *v, const gib_light_views *views, int count, unsigned seed,
                    const char *label, gib_ledger *ledger, gib_error *err);
/* Extracts the VPLs from the views rendered this frame (vpl_extract.comp), timed as `pass`. */
void gib_vpls_update(gib_vpls *v, const gib_light_views *views, gib_timers *timers, const char *pass);
/* Binds the VPL buffer to GIB_SSBO_OWN_FIRST (vpl_gather.glsl's `vpls`). */
void gib_vpls_bind(const gib_vpls *v);
/* Reads the VPLs back (count x GIB_VPL_FLOATS floats). */
int gib_vpls_read(const gib_vpls *v, float *out);
/* Replaces the VPLs by given ones (tests: a single VPL put by hand). */
void gib_vpls_write(gib_vpls *v, const float *in, int n);
void gib_vpls_destroy(gib_vpls *v, gib_ledger *ledger);

/* Test hook: vpl_irradiance() (vpl_gather.glsl) with the bound VPLs at n points: in[2i] = (x, 0),
 * in[2i + 1] = (n, 0); out[i] = (E, 0), irradiance in W/m^2. */
int gib_vpls_probe(const gib_vpls *v, float clamp_distance, const float *in, int n, float *out,
                   gib_error *err);

/* What every VPL technique sets up and renders each frame alike: the G-buffer, the light views
 * (position, normal, flux at rsm_res; label "rsm") and their VPLs (seed 1, label "vpl"). */
typedef struct gib_vpl_frame {
    gib_gbuffer gbuffer;
    gib_light_views views;
    gib_vpls vpls;
} gib_vpl_frame;

/* The parameters gib_vpl_frame_create reads, in every VPL technique's spec list. */
#define GIB_VPL_PARAMS                                                                            \
    {"rsm_res", GIB_PARAM_INT, 256, 16, 1024, "light view side, texels"},                         \
    {"vpl_count", GIB_PARAM_INT, 256, 1, 4096,                                                    \
     "VPLs over all light-view faces (at least one per face), fixed at create"},                  \
    {"clamp_distance", GIB_PARAM_LENGTH, 0.05, 0, 1e9,                                            \
     "eps under the VPL distance: 1 / max(d^2, eps^2), scene units"}

/* f must be zeroed; on failure what was made is left for gib_vpl_frame_destroy. */
int gib_vpl_frame_create(gib_vpl_frame *f, const gib_gpu_scene *scene, int width, int height,
                         int rsm_res, int vpl_count, gib_ledger *ledger, gib_error *err);
/* Passes "gbuffer" and "rsm" (the light views and the VPL extraction). */
void gib_vpl_frame_render(gib_vpl_frame *f, const gib_gpu_scene *scene, const gib_view *view,
                          gib_timers *timers);
void gib_vpl_frame_destroy(gib_vpl_frame *f, gib_ledger *ledger);

#endif

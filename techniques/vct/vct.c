/* gibench technique `vct` — dense voxel cone tracing (Crassin et al. 2011), the baseline of
 * Sugihara, Rauwendaal and Salvi 2014 (Sec. 3.1 and 6): per frame
 *  1. "voxelization": the occlusion voxels (common/voxels.h) for the occupancy, the light views
 *     (label "rsm": position, normal, reflected flux at inject_res) injected into the dense base
 *     voxels (radiance + occlusion, normal; RGBA16F), anisotropic mips in 6 directions
 *     (vct_volume.c);
 *  2. "gbuffer";
 *  3. "shadow_cone" -> direct, "diffuse_cones" -> indirect, "specular_cone" -> glossy
 *     (vct_shade.frag, vct_trace.glsl).
 * Memory is planned before anything is allocated; a plan over the budget fails create() with
 * "out of memory" (the row's status out_of_memory). A NaN reaching an output is found by the
 * harness (status nonfinite). */
#include "techniques/vct/vct.h"

#include <glad/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "techniques/common/fullscreen.h"
#include "techniques/common/gbuffer.h"
#include "techniques/common/light_view.h"
#include "techniques/common/voxels.h"
#include "techniques/vct/vct_slots.h"

extern const gib_technique gib_technique_vct;

static const gib_param_spec vct_params[] = {
    {"voxel_res", GIB_PARAM_INT, 128, 64, 512, "voxels per side of the dense grid"},
    {"diffuse_aperture", GIB_PARAM_FLOAT, 60, 1, 120, "full aperture of the 6 diffuse cones, degrees"},
    {"specular_aperture", GIB_PARAM_FLOAT, 10, 0.5, 120, "full aperture of the specular cone, degrees"},
    {"shadow_aperture", GIB_PARAM_FLOAT, 4, 0.5, 60, "full aperture of the shadow cones, degrees"},
    {"step_factor", GIB_PARAM_FLOAT, 1, 0.1, 4,
     "step between samples as a multiple of the current sample's diameter (1: spheres that "
     "touch, Fig. 4; as common/voxel_cone.glsl's shadow_cone)"},
    {"start_offset", GIB_PARAM_FLOAT, 1.5, 0, 8, "cone start offset along the normal, in voxels"},
    {"max_distance", GIB_PARAM_FLOAT, 1, 0.01, 2, "longest cone, as a fraction of the grid side"},
    {"sample_level", GIB_PARAM_INT, 1, 0, 2,
     "levels finer than the paper's log2(d) a sample of diameter d reads (0: the paper's "
     "mipLevel, whose trilinear footprint reaches the receiver's own cells; vct_trace.glsl)"},
    {"clearance", GIB_PARAM_INT, 1, 0, 1,
     "how a diffuse cone's sample is kept in front of the receiver's plane: 0 its diameter at most "
     "its height (a tilted cone narrowed to half its width), 1 its width kept and the sample lifted "
     "along the normal (vct_trace.glsl)"},
    {"cone", GIB_PARAM_INT, -1, -1, 5,
     "-1: indirect gathers all 6 diffuse cones; i: cone i alone, weight 1 (against `gibench "
     "reference --component indirect --cone i`: each cone's own error)"},
    {"front_faces", GIB_PARAM_INT, 1, 0, 1,
     "1: a cone sample's light is limited to the lit surfaces whose front faces the cone's apex "
     "(emission lobes, vct_lobes.comp); 0: the anisotropic mips' light alone (the paper), where "
     "a wall's lit face is seen edge-on from its dark side (vct_trace.glsl)"},
    {"inject_res", GIB_PARAM_INT, 512, 16, 4096, "light-view resolution for the injection"},
    {"fill", GIB_PARAM_INT, 1, 0, 1,
     "1: an occupied voxel no light-view texel landed in takes the light of the surface the light "
     "views see in it (0: point injection alone, whose misses are black occluders; "
     "vct_resolve.comp)"},
    {"memory_budget_mb", GIB_PARAM_FLOAT, 0, 0, 1e7,
     "memory budget for the voxels (decimal MB); 0 = the device's (NVX_gpu_memory_info, else "
     "half the physical memory)"},
    {GIB_PRESET_PARAM, GIB_PARAM_INT, 0, 0, 1,
     "default: the departures above; paper: Crassin et al.'s cone as the LRSM paper ran it"},
    {0},
};

/* The literal reading: the sample's mip level log2(d), point injection alone, the anisotropic
 * mips' light alone; the paper keeps no sample in front of the receiver's plane, and clearance 0
 * (the sample shrunk to its height above it) is the nearest the cone can take without reading the
 * receiver's own cells at every step. ARCHITECTURE.md, "LRSM and its VCT baseline", says what
 * each default repairs and on which scenes it was chosen. */
static const gib_preset vct_presets[] = {
    {"paper", "sample_level=0;fill=0;clearance=0;front_faces=0",
     "voxel cone tracing as published (Crassin et al. 2011; Sugihara et al. 2014, Sec. 6): a "
     "sample's trilinear footprint reaches the receiver's own cells, which darken it; clearance 0 "
     "stands for the plane the paper does not keep"},
    {0},
};

typedef struct vct {
    const gib_gpu_scene *scene;
    gib_ledger *ledger;
    gib_gbuffer gbuffer;
    gib_light_views views;
    gib_voxels occ;          /* the shared occlusion voxels: the occupancy (radiance alpha) */
    vct_volume vol;
    gib_fullscreen direct, indirect, glossy;
    int inject_res;
    bool fill;
    int cone;                /* the diffuse cone rendered alone, < 0 all */
    vct_cone_settings cones;
    float max_distance;
    float tan_diffuse, tan_specular, tan_shadow;
} vct;

static void vct_destroy(void *self)
{
    vct *a = self;
    if (!a)
        return;
    gib_fullscreen_destroy(&a->direct);
    gib_fullscreen_destroy(&a->indirect);
    gib_fullscreen_destroy(&a->glossy);
    vct_volume_destroy(&a->vol, a->ledger);
    gib_voxels_destroy(&a->occ, a->ledger);
    gib_light_views_destroy(&a->views, a->ledger);
    gib_gbuffer_destroy(&a->gbuffer, a->ledger);
    free(a);
}

static float tan_half_deg(double deg)
{
    return (float)tan(deg * M_PI / 360.0);
}

static void *vct_create(const gib_gpu_scene *scene, const gib_params *p, int w, int h,
                        gib_ledger *ledger, gib_error *err)
{
    const gib_technique *t = &gib_technique_vct;
    vct *a = calloc(1, sizeof *a);
    if (!a) {
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "vct: out of memory (host)");
        return NULL;
    }
    a->scene = scene;
    a->ledger = ledger;
    a->inject_res = gib_param_int(t, p, "inject_res");
    a->fill = gib_param_int(t, p, "fill") != 0;
    a->cone = gib_param_int(t, p, "cone");
    a->cones.step_factor = (float)gib_param_float(t, p, "step_factor");
    a->cones.start_offset = (float)gib_param_float(t, p, "start_offset");
    a->cones.sample_level = gib_param_int(t, p, "sample_level");
    a->cones.clearance = gib_param_int(t, p, "clearance");
    a->cones.front_faces = gib_param_int(t, p, "front_faces");
    a->max_distance = (float)gib_param_float(t, p, "max_distance");
    a->tan_diffuse = tan_half_deg(gib_param_float(t, p, "diffuse_aperture"));
    a->tan_specular = tan_half_deg(gib_param_float(t, p, "specular_aperture"));
    a->tan_shadow = tan_half_deg(gib_param_float(t, p, "shadow_aperture"));
    /* The plan is checked against the budget before anything is allocated. */
    int res = gib_param_int(t, p, "voxel_res");
    vct_plan plan;
    vct_plan_bytes(res, (long long)scene->scene->triangle_count, a->cones.front_faces != 0,
                   &plan);
    if (vct_plan_check(&plan, res, gib_param_float(t, p, "memory_budget_mb"), ledger, err) < 0) {
        free(a);
        return NULL;
    }
    /* Occupancy from the shared occlusion voxels (common/voxels.h), the radiance in a grid
     * placed as theirs: one exact voxeliser for LRSM and VCT, alpha masks honoured; its R8
     * texture is the "voxels" structure, beside the paper's VCT formats. */
    if (gib_voxels_create(&a->occ, scene, res, "voxels", ledger, err) < 0 ||
        vct_volume_create(&a->vol, a->occ.origin, a->occ.size, res, a->cones.front_faces != 0,
                          ledger, err) < 0 ||
        gib_light_views_create(&a->views, scene, a->inject_res,
                               GIB_LV_POSITION | GIB_LV_NORMAL | GIB_LV_FLUX, "rsm", ledger,
                               err) < 0 ||
        gib_gbuffer_create(&a->gbuffer, w, h, ledger, err) < 0 ||
        gib_fullscreen_create(&a->direct, "vct/vct_shade.frag", "#define DIRECT 1\n", err) < 0 ||
        gib_fullscreen_create(&a->indirect, "vct/vct_shade.frag", "#define INDIRECT 1\n", err) < 0 ||
        gib_fullscreen_create(&a->glossy, "vct/vct_shade.frag", "#define GLOSSY 1\n", err) < 0) {
        /* A driver's GL_OUT_OF_MEMORY anywhere carries its code (the ledger sets it): the row's
         * status is out_of_memory. */
        vct_destroy(a);
        return NULL;
    }
    return a;
}

static void cone_pass(vct *a, const gib_fullscreen *fs, const char *pass, unsigned fbo,
                      const gib_view *view, float tan_half, gib_timers *timers)
{
    gib_timer_begin(timers, pass);
    gib_fullscreen_begin(fs, fbo, view->width, view->height, 0);
    gib_gpu_scene_bind(a->scene);
    gib_gbuffer_bind(&a->gbuffer);
    vct_volume_bind_cones(&a->vol, &a->cones);
    glUniform3fv(VCT_SHADE_LOC_EYE, 1, view->camera->eye);
    glUniform1i(VCT_SHADE_LOC_LIGHT_COUNT, (int)a->scene->scene->light_count);
    glUniform1f(VCT_SHADE_LOC_TAN_HALF, tan_half);
    glUniform1f(VCT_SHADE_LOC_MAX_DIST, a->max_distance * a->vol.size);
    if (fs == &a->indirect)
        glUniform1i(GIB_LOC_VOXEL_CONE_ONLY, a->cone);
    gib_fullscreen_draw(fs);
    gib_fullscreen_end();
    gib_timer_end(timers);
}

static int vct_render(void *self, const gib_view *view, gib_timers *timers,
                      const gib_image_target *targets, int target_count, gib_error *err)
{
    vct *a = self;
    if (target_count != 3)
        return gib_fail(err, "vct renders 3 components, was given %d targets", target_count);
    gib_gbuffer_render(&a->gbuffer, a->scene, view, timers, "gbuffer");
    /* "voxelization": occupancy, light views, injection and mips (each call adds to the pass). */
    gib_voxels_build(&a->occ, a->scene, timers, "voxelization");
    gib_light_views_render(&a->views, a->scene, timers, "voxelization");
    gib_timer_begin(timers, "voxelization");
    gib_light_views_bind(&a->views);
    vct_volume_inject(&a->vol, a->occ.texture, a->inject_res, a->views.first_face,
                      a->views.faces_of, (int)a->scene->scene->light_count, a->fill);
    vct_volume_mips(&a->vol);
    gib_timer_end(timers);
    /* targets follow the component bits: direct, indirect, glossy. */
    cone_pass(a, &a->direct, "shadow_cone", targets[0].fbo, view, a->tan_shadow, timers);
    cone_pass(a, &a->indirect, "diffuse_cones", targets[1].fbo, view, a->tan_diffuse, timers);
    cone_pass(a, &a->glossy, "specular_cone", targets[2].fbo, view, a->tan_specular, timers);
    return gib_gl_check("vct", err);
}

static const char *const vct_passes[] = {"gbuffer", "voxelization", "shadow_cone", "diffuse_cones",
    "specular_cone", NULL};

const gib_technique gib_technique_vct = {
    .name = "vct",
    .source = "Crassin et al. 2011 voxel cone tracing, dense, as Sugihara et al. 2014 Sec. 6 ran it",
    .components = GIB_OUT_DIRECT | GIB_OUT_INDIRECT | GIB_OUT_GLOSSY,
    .params = vct_params,
    .passes = vct_passes,
    .presets = vct_presets,
    .create = vct_create,
    .render = vct_render,
    .destroy = vct_destroy,
};

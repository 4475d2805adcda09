/* gibench technique `lrsm` — layered reflective shadow maps for voxel-based indirect illumination
 * (Sugihara, Rauwendaal, Salvi 2014, Sec. 3-6, Eq. 1, 5-15, Table 1, Algorithm 1).
 *
 * Per frame (timer passes as Table 3):
 *  gbuffer            the shared G-buffer (techniques/common/gbuffer.h);
 *  voxelization       binary occlusion voxels with box-filtered mips (techniques/common/voxels.h);
 *  lrsm_construction  the shared light views (DEPTH, NORMAL, FLUX; label "rsm") at rsm_res, the
 *                     layers at rsm_res / 2 (lrsm_layers.c, lrsm_build.comp) and their mips;
 *  shadow_cone        `direct`: every light's direct light times a shadow cone's visibility;
 *  diffuse_cones      `indirect`: 6 cones over the hemisphere, Eq. 1 with the LRSM's radiance;
 *  specular_cone      `glossy`: one cone along the mirror direction on pixels with a specular lobe.
 * Spot lights (perspective view), directional lights (orthographic) and point lights and spots
 * wider than 45 degrees (the light views' cube: 6 faces, each with its own D x N layers, so such a
 * light costs 6 times the layers' memory; a cone sample is looked up in the face its centre falls
 * in). */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "techniques/common/fullscreen.h"
#include "techniques/common/gbuffer.h"
#include "techniques/common/voxels.h"
#include "techniques/lrsm/lrsm.h"
#include "techniques/lrsm/lrsm_slots.h"

extern const gib_technique gib_technique_lrsm;

enum { PASS_SHADOW, PASS_DIFFUSE, PASS_SPECULAR, PASSES };

typedef struct lrsm {
    const gib_gpu_scene *scene;
    gib_ledger *ledger;
    gib_gbuffer gbuffer;
    gib_voxels voxels;
    int voxels_up;
    gib_light_views views;
    lrsm_layers layers;
    gib_fullscreen pass[PASSES];
    float aperture[PASSES];      /* radians */
    float start_offset, step_factor, max_distance, mip_clamp;
    int opacity, backface, seams;   /* voxel_step_alpha's model; Eq. 8 as cosine or test; the
                                       faces a sample reads (lrsm_sample.glsl) */
    int coverage;                   /* a sample's L over its lit coverage (lrsm_cone.frag) */
    int hits;                       /* a sample as the share of rays meeting the lit planes */
    int visibility;                 /* Eq. 12's window: +-r_c or widened by 1/<n.l> */
    int cone;                       /* the diffuse cone rendered alone, < 0 all */
    int rebuild, built;             /* structures every frame, or only the first frame's */
} lrsm;

static const gib_param_spec lrsm_params[] = {
    {"voxel_res", GIB_PARAM_INT, 128, 64, 512, "occlusion voxels per side of the cubic grid"},
    {"diffuse_aperture", GIB_PARAM_FLOAT, 60, 1, 120, "diffuse cones' full aperture, degrees"},
    {"specular_aperture", GIB_PARAM_FLOAT, 10, 0.5, 90, "specular cone's full aperture, degrees"},
    {"shadow_aperture", GIB_PARAM_FLOAT, 4, 0.1, 60, "shadow cones' full aperture, degrees"},
    {"step_factor", GIB_PARAM_FLOAT, 1, 0.1, 4, "cone step = step_factor x the sample's diameter"},
    {"start_offset", GIB_PARAM_FLOAT, 1.5, 0, 8, "cone start along the normal, voxels"},
    {"max_distance", GIB_PARAM_FLOAT, 1, 0.05, 2, "cone length, fraction of the voxel grid's side"},
    {"rsm_res", GIB_PARAM_INT, 512, 64, 2048,
     "light view side, texels (even: the layers are at half its side, one texel per 2x2 block)",
     .multiple_of = 2},
    {"layers_depth", GIB_PARAM_INT, 2, 1, 4, "depth partitions D"},
    {"layers_normal", GIB_PARAM_INT, 2, 1, 4, "<n.l> partitions N"},
    {"overlap", GIB_PARAM_FLOAT, 0.1, 0, 0.5, "depth layers' overlap delta, fraction of a partition"},
    {"mip_clamp", GIB_PARAM_FLOAT, 0, 0, 12, "lowest LRSM mip level a cone sample reads"},
    {"opacity", GIB_PARAM_INT, 1, 0, 1,
     "voxel alpha: 0 mean occupancy per sample (paper), 1 occupancy as a density over the step",
     .choices = (const gib_param_choice[]){{"mean", 0}, {"density", 1}, {0}}},
    {"backface", GIB_PARAM_INT, 2, 0, 2,
     "Eq. 8: 0 the cosine <n.v> (paper); 1 a backface test only; 2 the cosine weighting each "
     "layer's radiance in the sample's mean, which keeps the lit coverage (lrsm_sample.glsl)",
     .choices = (const gib_param_choice[]){{"cosine", 0}, {"test", 1}, {"weighted", 2}, {0}}},
    {"coverage", GIB_PARAM_INT, 1, 0, 1,
     "1: a cone sample's radiance is the LRSM's over the coverage of the lit surfaces inside it "
     "(at least the voxels' alpha); 0: Eq. 5's R V N as it is, its coverage V counted again by "
     "the voxels' alpha in Eq. 1"},
    {"hits", GIB_PARAM_INT, 1, 0, 1,
     "1: a cone sample's light and opacity are the share of its rays that meet each lit layer's "
     "plane within its step, Eq. 8 averaged over the cone's cap, and the voxels' alpha beyond the "
     "lit coverage blocks as the plane of its occupancy would (lrsm_hits.glsl); 0: Algorithm 1's "
     "R V N with Eq. 1's alpha, as `backface` and `coverage` read them",
     .choices = (const gib_param_choice[]){{"algorithm1", 0}, {"planes", 1}, {0}}},
    {"seams", GIB_PARAM_INT, 1, 0, 1,
     "1: a sample reads every light-view face its footprint overlaps, weighted by the overlap; 0: "
     "the face of its centre only (the paper's one view per light; facets at a cube's seams)"},
    {"visibility", GIB_PARAM_INT, 1, 0, 1,
     "Eq. 12's depth window: 0 the sample's +-r_c (paper), 1 widened to +-r_c / <n.l>, the depth "
     "span a surface through the sample covers across its footprint"},
    {"jacobian", GIB_PARAM_INT, 1, 0, 1,
     "LRSM radiance filtered over: 1 the surface area each RSM texel sees (Eq. 3's Jacobian "
     "r^2/<n.l>), 0 the light's solid angle (paper, Sec. 4.2: the Jacobian taken as constant)"},
    {"cone", GIB_PARAM_INT, -1, -1, 5,
     "-1: indirect gathers all 6 diffuse cones; i: cone i alone, weight 1 (against `gibench "
     "reference --component indirect --cone i`: each cone's own error)"},
    {"rebuild", GIB_PARAM_INT, 1, 0, 1,
     "1: voxels, light views and layers rebuilt every frame (paper, Sec. 6); 0: the first frame's "
     "kept (a negative control: what a technique that misses the motion scores over time)"},
    {GIB_PRESET_PARAM, GIB_PARAM_INT, 0, 0, 1,
     "default: the departures above; paper: Algorithm 1 and Eq. 1, 5, 8, 12 as published"},
    {0},
};

/* The paper's literal reading: Algorithm 1's sample (Eq. 5's R V N times Eq. 1's alpha), the mean
 * occupancy as alpha, Eq. 8's cosine on the cone's axis, one light view per light, Eq. 12's window
 * of +-r_c and the Jacobian taken as constant (Sec. 4.2). ARCHITECTURE.md, "LRSM and its VCT
 * baseline", says what each breaks and on which scenes each default was chosen. */
static const gib_preset lrsm_presets[] = {
    {"paper", "opacity=0;hits=0;backface=0;coverage=0;seams=0;visibility=0;jacobian=0",
     "Algorithm 1 and Eq. 1, 5, 8, 12 as published (Sugihara et al. 2014, Sec. 4-5): the lit "
     "coverage counted twice (Eq. 5's V and Eq. 1's alpha) and Eq. 8 on the cone's axis leave "
     "the indirect light a few percent of the answer"},
    {0},
};

/* With hits = planes a sample's light is the share of its rays that meet the lit planes (Eq. 8
 * averaged over the cone's cap): `backface` and `coverage` choose among Algorithm 1's readings and
 * have nothing to act on, so they must keep their defaults. */
static int planes_alone(const gib_technique *t, const gib_params *p)
{
    return !gib_param_int(t, p, "hits") ||
           (gib_param_int(t, p, "backface") == 2 && gib_param_int(t, p, "coverage") == 1);
}

static const gib_param_rule lrsm_rules[] = {
    {"hits,backface,coverage",
     "backface and coverage act only with hits = algorithm1 (with hits = planes a sample's light "
     "is the share of its rays meeting the lit planes, Eq. 8 averaged over the cone's cap)",
     planes_alone},
    {0},
};

static void lrsm_destroy(void *self);

static void *lrsm_create(const gib_gpu_scene *scene, const gib_params *p, int width, int height,
                         gib_ledger *ledger, gib_error *err)
{
    const gib_technique *t = &gib_technique_lrsm;
    lrsm *s = calloc(1, sizeof *s);
    if (!s) {
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    s->scene = scene;
    s->ledger = ledger;
    const double deg = M_PI / 180;
    s->aperture[PASS_SHADOW] = (float)(gib_param_float(t, p, "shadow_aperture") * deg);
    s->aperture[PASS_DIFFUSE] = (float)(gib_param_float(t, p, "diffuse_aperture") * deg);
    s->aperture[PASS_SPECULAR] = (float)(gib_param_float(t, p, "specular_aperture") * deg);
    s->start_offset = (float)gib_param_float(t, p, "start_offset");
    s->step_factor = (float)gib_param_float(t, p, "step_factor");
    s->max_distance = (float)gib_param_float(t, p, "max_distance");
    s->mip_clamp = (float)gib_param_float(t, p, "mip_clamp");
    s->opacity = gib_param_int(t, p, "opacity");
    s->backface = gib_param_int(t, p, "backface");
    s->seams = gib_param_int(t, p, "seams");
    s->coverage = gib_param_int(t, p, "coverage");
    s->visibility = gib_param_int(t, p, "visibility");
    s->hits = gib_param_int(t, p, "hits");
    s->rebuild = gib_param_int(t, p, "rebuild");
    s->cone = gib_param_int(t, p, "cone");
    static const char *const define[PASSES] = {"#define SHADOW 1\n", "#define DIFFUSE 1\n",
                                               "#define SPECULAR 1\n"};
    if (gib_gbuffer_create(&s->gbuffer, width, height, ledger, err) < 0)
        goto fail;
    if (gib_voxels_create(&s->voxels, scene, gib_param_int(t, p, "voxel_res"), "voxels", ledger,
                          err) < 0)
        goto fail;
    s->voxels_up = 1;
    if (gib_light_views_create(&s->views, scene, gib_param_int(t, p, "rsm_res"), GIB_LV_PACKED16,
                               "rsm", ledger, err) < 0)
        goto fail;
    if (lrsm_layers_create(&s->layers, &s->views, gib_param_int(t, p, "layers_depth"),
                           gib_param_int(t, p, "layers_normal"),
                           (float)gib_param_float(t, p, "overlap"), ledger, err) < 0)
        goto fail;
    s->layers.jacobian = gib_param_int(t, p, "jacobian");
    lrsm_layers_partition(&s->layers, &s->views, scene->scene);
    for (int i = 0; i < PASSES; i++)
        if (gib_fullscreen_create(&s->pass[i], "lrsm/lrsm_cone.frag", define[i], err) < 0)
            goto fail;
    if (gib_gl_check("lrsm creation", err) < 0)
        goto fail;
    return s;
fail:
    lrsm_destroy(s);
    return NULL;
}

/* One cone pass into `fbo`, timed as `name`. */
static void cone_pass(lrsm *s, int which, const char *name, const gib_view *view, unsigned fbo,
                      gib_timers *timers)
{
    gib_timer_begin(timers, name);
    gib_fullscreen_begin(&s->pass[which], fbo, view->width, view->height, 0);
    gib_gpu_scene_bind(s->scene);
    gib_gbuffer_bind(&s->gbuffer);
    gib_light_views_bind(&s->views);
    lrsm_layers_bind(&s->layers);
    gib_voxels_bind(&s->voxels);
    glUniform1f(LRSM_LOC_MIP_CLAMP, s->mip_clamp);
    glUniform1i(LRSM_LOC_LIGHTS, (int)s->scene->scene->light_count);
    glUniform3fv(LRSM_CONE_LOC_EYE, 1, view->camera->eye);
    glUniform1f(LRSM_CONE_LOC_APERTURE, s->aperture[which]);
    glUniform1f(LRSM_CONE_LOC_START_OFFSET, s->start_offset);
    glUniform1f(LRSM_CONE_LOC_STEP_FACTOR, s->step_factor);
    glUniform1f(LRSM_CONE_LOC_MAX_DISTANCE, s->max_distance);
    glUniform1i(LRSM_LOC_BACKFACE, s->backface);
    glUniform1i(LRSM_LOC_SEAMS, s->seams);
    glUniform1i(LRSM_CONE_LOC_COVERAGE, s->coverage);
    glUniform1i(LRSM_CONE_LOC_HITS, s->hits);
    glUniform1i(LRSM_LOC_VISIBILITY, s->visibility);
    glUniform1i(GIB_LOC_VOXEL_DENSITY, s->opacity);
    if (which == PASS_DIFFUSE)
        glUniform1i(GIB_LOC_VOXEL_CONE_ONLY, s->cone);
    gib_fullscreen_draw(&s->pass[which]);
    gib_fullscreen_end();
    gib_timer_end(timers);
}

static int lrsm_render(void *self, const gib_view *view, gib_timers *timers,
                       const gib_image_target *targets, int target_count, gib_error *err)
{
    lrsm *s = self;
    gib_gbuffer_render(&s->gbuffer, s->scene, view, timers, "gbuffer");
    if (s->rebuild || !s->built) {
        gib_voxels_build(&s->voxels, s->scene, timers, "voxelization");
        /* Light views, then layers and mips: two brackets of the same pass (timers accumulate). */
        gib_light_views_render(&s->views, s->scene, timers, "lrsm_construction");
        gib_timer_begin(timers, "lrsm_construction");
        lrsm_layers_build(&s->layers, &s->views);
        gib_timer_end(timers);
        s->built = 1;
    }
    for (int i = 0; i < target_count; i++) {
        unsigned c = targets[i].component;
        if (c == GIB_OUT_DIRECT)
            cone_pass(s, PASS_SHADOW, "shadow_cone", view, targets[i].fbo, timers);
        else if (c == GIB_OUT_INDIRECT)
            cone_pass(s, PASS_DIFFUSE, "diffuse_cones", view, targets[i].fbo, timers);
        else if (c == GIB_OUT_GLOSSY)
            cone_pass(s, PASS_SPECULAR, "specular_cone", view, targets[i].fbo, timers);
    }
    return gib_gl_check("lrsm", err);
}

static void lrsm_destroy(void *self)
{
    lrsm *s = self;
    if (!s)
        return;
    for (int i = 0; i < PASSES; i++)
        gib_fullscreen_destroy(&s->pass[i]);
    lrsm_layers_destroy(&s->layers, s->ledger);
    gib_light_views_destroy(&s->views, s->ledger);
    if (s->voxels_up)
        gib_voxels_destroy(&s->voxels, s->ledger);
    gib_gbuffer_destroy(&s->gbuffer, s->ledger);
    free(s);
}

static const char *const lrsm_passes[] = {"gbuffer", "voxelization", "lrsm_construction",
    "shadow_cone", "diffuse_cones", "specular_cone", NULL};

const gib_technique gib_technique_lrsm = {
    .name = "lrsm",
    .source = "layered reflective shadow maps with voxel cone tracing (Sugihara, Rauwendaal, Salvi "
              "2014, Sec. 3-6, Eq. 1, 5-15, Alg. 1)",
    .components = GIB_OUT_DIRECT | GIB_OUT_INDIRECT | GIB_OUT_GLOSSY,
    .params = lrsm_params,
    .rules = lrsm_rules,
    .passes = lrsm_passes,
    .presets = lrsm_presets,
    .reference = NULL,
    .scene_needs = 0,
    .scene_needs_any = GIB_FEAT_POINT_LIGHT | GIB_FEAT_SPOT_LIGHT | GIB_FEAT_DIR_LIGHT,
    .create = lrsm_create,
    .render = lrsm_render,
    .destroy = lrsm_destroy,
};

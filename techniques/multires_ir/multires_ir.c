/* gibench technique `multires_ir` — one diffuse bounce from the same VPLs as `rsm_gather`,
 * gathered by multi-resolution splatting (the thesis, Sec. 3.2.2, Algorithms 3.1 and 3.2; Nichols
 * and Wyman 2009, Nichols, Shopf and Wyman 2009): the two differ only in where they gather.
 *
 * Per frame (timer passes):
 *  gbuffer     the shared G-buffer;
 *  rsm         the shared light views and the VPLs (techniques/common/vpl.h), as rsm_gather;
 *  splitting   min-max mips of depth (distance to the camera) and normal over `levels`
 *              resolutions (regions of 1, 2, ..., 2^(levels-1) pixels), then Algorithm 3.1 marks
 *              the valid regions in the stencil of one flattened image of all levels, or in a mask
 *              image (parameter `stencil`, multires.h: same regions; llvmpipe's timers
 *              under-count passes into a framebuffer with a stencil); the rules for the coarsest
 *              and finest levels in multires_common.glsl;
 *  gathering   every VPL at each valid region's mean position and normal (stencil test or mask),
 *              the irradiance of vpl_gather.glsl;
 *  upsampling  Algorithm 3.2: from the coarsest level down, regions inside a valid coarser one take
 *              the bilinear interpolation of the coarser level's data; at full resolution each
 *              pixel's albedo gives L = rho/pi E.
 * Output `indirect`. */
#include <glad/gl.h>
#include <stdlib.h>

#include "harness/gl/context.h"
#include "techniques/common/gbuffer.h"
#include "techniques/common/vpl.h"
#include "techniques/multires_ir/multires.h"

extern const gib_technique gib_technique_multires_ir;

typedef struct multires_ir {
    const gib_gpu_scene *scene;
    gib_ledger *ledger;
    gib_vpl_frame frame;     /* G-buffer, light views, VPLs */
    multires mr;
    float eps;
} multires_ir;

static const gib_param_spec multires_ir_params[] = {
    GIB_VPL_PARAMS,
    {"levels", GIB_PARAM_INT, 4, 1, 8,
     "resolutions: regions of 1 to 2^(levels-1) pixels a side (1: every pixel, as rsm_gather)"},
    {"depth_threshold", GIB_PARAM_FLOAT, 0.05, 0, 10,
     "a region splits where its depth range exceeds this fraction of its nearest depth"},
    {"normal_threshold", GIB_PARAM_FLOAT, 20, 0, 180,
     "a region splits where a normal component's range exceeds the chord of this angle, degrees"},
    {"stencil", GIB_PARAM_INT, 0, 0, 1,
     "valid regions marked in: 1 the stencil (the thesis), 0 a mask image (same regions; "
     "llvmpipe's timers under-count stencil-buffer passes)",
     .choices = (const gib_param_choice[]){{"mask", 0}, {"stencil", 1}, {0}}},
    {0},
};

static void multires_ir_destroy(void *self)
{
    multires_ir *s = self;
    if (!s)
        return;
    multires_destroy(&s->mr, s->ledger);
    gib_vpl_frame_destroy(&s->frame, s->ledger);
    free(s);
}

static void *multires_ir_create(const gib_gpu_scene *scene, const gib_params *p, int width,
                                int height, gib_ledger *ledger, gib_error *err)
{
    const gib_technique *t = &gib_technique_multires_ir;
    multires_ir *s = calloc(1, sizeof *s);
    if (!s) {
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    s->scene = scene;
    s->ledger = ledger;
    s->eps = (float)gib_param_float(t, p, "clamp_distance");
    if (gib_vpl_frame_create(&s->frame, scene, width, height, gib_param_int(t, p, "rsm_res"),
                             gib_param_int(t, p, "vpl_count"), ledger, err) < 0 ||
        multires_create(&s->mr, width, height, gib_param_int(t, p, "levels"),
                        (float)gib_param_float(t, p, "depth_threshold"),
                        (float)gib_param_float(t, p, "normal_threshold"),
                        gib_param_int(t, p, "stencil"), 1, ledger, err) < 0 ||
        gib_gl_check("multires_ir creation", err) < 0) {
        multires_ir_destroy(s);
        return NULL;
    }
    return s;
}

static int multires_ir_render(void *self, const gib_view *view, gib_timers *timers,
                              const gib_image_target *targets, int target_count, gib_error *err)
{
    multires_ir *s = self;
    gib_vpl_frame_render(&s->frame, s->scene, view, timers);
    const float *eye = view->camera->eye;
    for (int i = 0; i < target_count; i++) {
        if (targets[i].component != GIB_OUT_INDIRECT)
            continue;
        gib_timer_begin(timers, "splitting");
        multires_split(&s->mr, s->frame.gbuffer.position, s->frame.gbuffer.normal, eye);
        gib_timer_end(timers);
        gib_timer_begin(timers, "gathering");
        gib_vpls_bind(&s->frame.vpls);
        multires_gather(&s->mr, s->frame.vpls.count, s->eps);
        gib_timer_end(timers);
        gib_timer_begin(timers, "upsampling");
        gib_gbuffer_bind(&s->frame.gbuffer);
        multires_upsample(&s->mr, targets[i].fbo, eye);
        gib_timer_end(timers);
    }
    return gib_gl_check("multires_ir", err);
}

static const char *const multires_ir_passes[] = {"gbuffer", "rsm", "splitting", "gathering",
    "upsampling", NULL};

const gib_technique gib_technique_multires_ir = {
    .name = "multires_ir",
    .source = "VPLs gathered by multi-resolution splatting over min-max mips and stencil-marked "
              "regions (thesis 004 Sec. 3.2, Alg. 3.1, 3.2; Nichols et al. 2009)",
    .components = GIB_OUT_INDIRECT,
    .params = multires_ir_params,
    .passes = multires_ir_passes,
    .reference = NULL,
    .scene_needs = 0,
    .scene_needs_any = GIB_FEAT_POINT_LIGHT | GIB_FEAT_SPOT_LIGHT | GIB_FEAT_DIR_LIGHT,
    .create = multires_ir_create,
    .render = multires_ir_render,
    .status = NULL,
    .destroy = multires_ir_destroy,
};

/* gibench technique `ldm_ao` — ambient occlusion and obscurance traced through layered depth maps
 * (Aalund, Frisvad, Bærentzen 2015: Sec. 3.1 trace, 3.2 deterministic directions, 3.3 Eq. 1-3,
 * 4.1 implementation). Output component `ao`, scored against the reference `ao` with the same dmax
 * (and obscurance). Deterministic: no random numbers anywhere, so two frames are bit-identical. */
#include <glad/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "harness/gl/ledger.h"
#include "techniques/common/fullscreen.h"
#include "techniques/common/gbuffer.h"
#include "techniques/ldm/ldm.h"
#include "techniques/ldm_ao/ldm_ao_slots.h"

extern const gib_technique gib_technique_ldm_ao;

typedef struct ldm_ao {
    const gib_gpu_scene *scene;
    gib_ledger *ledger;
    gib_gbuffer gbuffer;
    ldm_set ldms;
    gib_fullscreen trace;
    float dmax, offset;
    int obscurance;
} ldm_ao;

static const gib_param_spec ldm_ao_params[] = {
    {"directions", GIB_PARAM_INT, 128, 1, 4096, "number of LDM directions N (Sec. 3.2)"},
    {"ldm_res", GIB_PARAM_INT, 128, 8, 2048, "LDM resolution (pixels per side)"},
    {"dmax", GIB_PARAM_LENGTH, INFINITY, 0, INFINITY,
     "maximum occluder distance, world units (inf: unattenuated AO)"},
    {"obscurance", GIB_PARAM_INT, 0, 0, 1, "1: obscurance rho(d) = min(d/dmax, 1) (needs finite dmax)"},
    {"normal_offset", GIB_PARAM_FLOAT, 1.0, 0, 16, "ray origin offset along the normal, LDM texels"},
    {"node_budget", GIB_PARAM_FLOAT, 1.0, 0.01, 1.0,
     "LDM nodes allocated, as a fraction of the fragments counted at create (<1: overflow reported)"},
    {"memory_budget_mb", GIB_PARAM_FLOAT, 0, 0, 1e7,
     "the most the LDMs may take, decimal MB (0: no limit); over it create ends out_of_memory with "
     "the plan recorded"},
    {0},
};

/* Obscurance weighs an occluder at distance d by rho(d) = min(d/dmax, 1), defined for a finite
 * dmax > 0 only. */
static int obscurance_range(const gib_technique *t, const gib_params *p)
{
    const double dmax = gib_param_float(t, p, "dmax");
    return !gib_param_int(t, p, "obscurance") || (isfinite(dmax) && dmax > 0);
}

static const gib_param_rule ldm_ao_rules[] = {
    {"obscurance,dmax", "obscurance = 1 needs a finite dmax > 0 (rho(d) = min(d/dmax, 1))",
     obscurance_range},
    {0},
};

static void ldm_ao_destroy(void *self)
{
    ldm_ao *a = self;
    if (!a)
        return;
    gib_gbuffer_destroy(&a->gbuffer, a->ledger);
    ldm_destroy(&a->ldms, a->ledger);
    gib_fullscreen_destroy(&a->trace);
    free(a);
}

static void *ldm_ao_create(const gib_gpu_scene *scene, const gib_params *p, int w, int h,
                           gib_ledger *ledger, gib_error *err)
{
    const gib_technique *t = &gib_technique_ldm_ao;
    ldm_ao *a = calloc(1, sizeof *a);
    if (!a) {
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    a->scene = scene;
    a->ledger = ledger;
    a->dmax = (float)gib_param_float(t, p, "dmax");
    a->obscurance = gib_param_int(t, p, "obscurance");
    a->offset = (float)gib_param_float(t, p, "normal_offset");
    /* The LDMs first: a plan over the budget fails before anything else is allocated. */
    const uint64_t budget = (uint64_t)(gib_param_float(t, p, "memory_budget_mb") * 1e6);
    if (ldm_create(&a->ldms, scene, gib_param_int(t, p, "directions"),
                   gib_param_int(t, p, "ldm_res"), gib_param_float(t, p, "node_budget"), budget,
                   ledger, err) < 0 ||
        gib_gbuffer_create(&a->gbuffer, w, h, ledger, err) < 0 ||
        gib_fullscreen_create(&a->trace, "ldm_ao/ldm_ao.frag", NULL, err) < 0) {
        ldm_ao_destroy(a);
        return NULL;
    }
    return a;
}

static int ldm_ao_render(void *self, const gib_view *view, gib_timers *timers,
                         const gib_image_target *targets, int target_count, gib_error *err)
{
    ldm_ao *a = self;
    if (target_count != 1)
        return gib_fail(err, "ldm_ao renders one component, was given %d targets", target_count);
    ldm_build(&a->ldms, a->scene, timers);
    gib_gbuffer_render(&a->gbuffer, a->scene, view, timers, "gbuffer");

    gib_timer_begin(timers, "ldm_trace");
    /* Additive: pages add their LDMs' share of Eq. 2. */
    gib_fullscreen_begin(&a->trace, targets[0].fbo, view->width, view->height, 1);
    const float zero[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    gib_gbuffer_bind(&a->gbuffer);
    glUniform1f(LDM_AO_LOC_WEIGHT, 2.0f / (float)a->ldms.count);
    glUniform1f(LDM_AO_LOC_DMAX, a->dmax);
    glUniform1i(LDM_AO_LOC_OBSCURANCE, a->obscurance);
    glUniform1f(LDM_AO_LOC_OFFSET, a->offset);
    for (int p = 0; p < a->ldms.page_count; p++) {
        ldm_bind_page(&a->ldms, p);
        glUniform1i(LDM_AO_LOC_FIRST, a->ldms.pages[p].first);
        glUniform1i(LDM_AO_LOC_COUNT, a->ldms.pages[p].count);
        gib_fullscreen_draw(&a->trace);
    }
    gib_fullscreen_end();
    gib_timer_end(timers);
    return gib_gl_check("ldm_ao", err);
}

static gib_status ldm_ao_status(void *self) { return ldm_status(&((ldm_ao *)self)->ldms); }

static const gib_ref_binding ldm_ao_reference[] = {
    {GIB_OUT_AO, GIB_REF_AO_DMAX, "dmax"},
    {GIB_OUT_AO, GIB_REF_AO_OBSCURANCE, "obscurance"},
    {0},
};

static const char *const ldm_ao_passes[] = {"gbuffer", "ldm_build", "ldm_trace", NULL};

const gib_technique gib_technique_ldm_ao = {
    .name = "ldm_ao",
    .source = "Aalund, Frisvad, Baerentzen 2015, Sec. 3.1-3.3, 4.1 (layered depth maps)",
    .components = GIB_OUT_AO,
    .params = ldm_ao_params,
    .rules = ldm_ao_rules,
    .passes = ldm_ao_passes,
    .reference = ldm_ao_reference,
    .create = ldm_ao_create,
    .render = ldm_ao_render,
    .status = ldm_ao_status,
    .destroy = ldm_ao_destroy,
};

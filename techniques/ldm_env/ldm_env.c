/* gibench technique `ldm_env` — direct light from the scene's lights (shadow maps, as `direct`)
 * plus direct environment light from a uniform sky traced through layered depth maps: the LDM
 * paper's Figure 11 (Aalund, Frisvad, Bærentzen 2015, Sec. 5.2 and Fig. 11: "direct environment
 * light ... traced using LDMs"). For a uniform sky of radiance L the sky's share of the direct
 * radiance is rho * L * (2/N) sum_i V(x, w_i) |n . v_i| (Eq. 2 with unbounded visibility), so the
 * LDM pass is ldm_ao.frag with LDM_SKY defined, added onto the shaded lights. Output component
 * `direct`; only for scenes with a sky (GIB_FEAT_SKY). The sky's glossy reflection (a Phong lobe
 * seeing the sky, which the reference includes) is not rendered: Lambertian receivers only, as the
 * paper's Eq. 2; on a sky scene with Phong materials that shows up as this technique's error. */
#include <glad/gl.h>
#include <math.h>
#include <stdlib.h>

#include "harness/gl/context.h"
#include "techniques/common/direct_light.h"
#include "techniques/ldm/ldm.h"
#include "techniques/ldm_ao/ldm_ao_slots.h"

extern const gib_technique gib_technique_ldm_env;

typedef struct ldm_env {
    const gib_gpu_scene *scene;
    gib_ledger *ledger;
    gib_gbuffer gbuffer;
    gib_direct_light light;
    ldm_set ldms;
    gib_fullscreen sky;
    float ldm_offset;
} ldm_env;

static const gib_param_spec ldm_env_params[] = {
    {"directions", GIB_PARAM_INT, 128, 1, 4096, "number of LDM directions N for the sky (Sec. 3.2)"},
    {"ldm_res", GIB_PARAM_INT, 128, 8, 2048, "LDM resolution (pixels per side)"},
    {"ldm_offset", GIB_PARAM_FLOAT, 1.0, 0, 16, "sky ray origin offset along the normal, LDM texels"},
    {"shadow_res", GIB_PARAM_INT, 1024, 16, 8192, "shadow map resolution for the lights"},
    {"pcf", GIB_PARAM_INT, 1, 0, 4, "PCF radius r: (2r+1)^2 shadow taps"},
    {"normal_offset", GIB_PARAM_FLOAT, 1.5, 0, 16, "shadow lookup offset along the normal, texels"},
    {0},
};

static void ldm_env_destroy(void *self)
{
    ldm_env *e = self;
    if (!e)
        return;
    gib_gbuffer_destroy(&e->gbuffer, e->ledger);
    gib_direct_light_destroy(&e->light, e->ledger);
    ldm_destroy(&e->ldms, e->ledger);
    gib_fullscreen_destroy(&e->sky);
    free(e);
}

static void *ldm_env_create(const gib_gpu_scene *scene, const gib_params *p, int w, int h,
                            gib_ledger *ledger, gib_error *err)
{
    const gib_technique *t = &gib_technique_ldm_env;
    ldm_env *e = calloc(1, sizeof *e);
    if (!e) {
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    e->scene = scene;
    e->ledger = ledger;
    e->ldm_offset = (float)gib_param_float(t, p, "ldm_offset");
    if (gib_gbuffer_create(&e->gbuffer, w, h, ledger, err) < 0 ||
        gib_direct_light_create(&e->light, scene, gib_param_int(t, p, "shadow_res"),
                                gib_param_int(t, p, "pcf"),
                                (float)gib_param_float(t, p, "normal_offset"), ledger, err) < 0 ||
        ldm_create(&e->ldms, scene, gib_param_int(t, p, "directions"), gib_param_int(t, p, "ldm_res"),
                   1.0, 0, ledger, err) < 0 ||
        gib_fullscreen_create(&e->sky, "ldm_ao/ldm_ao.frag", "#define LDM_SKY 1\n", err) < 0) {
        ldm_env_destroy(e);
        return NULL;
    }
    return e;
}

static int ldm_env_render(void *self, const gib_view *view, gib_timers *timers,
                          const gib_image_target *targets, int target_count, gib_error *err)
{
    ldm_env *e = self;
    if (target_count != 1)
        return gib_fail(err, "ldm_env renders one component, was given %d targets", target_count);
    gib_direct_light_shadows(&e->light, e->scene, timers);
    ldm_build(&e->ldms, e->scene, timers);
    gib_gbuffer_render(&e->gbuffer, e->scene, view, timers, "gbuffer");
    gib_direct_light_shade(&e->light, e->scene, &e->gbuffer, view, targets[0].fbo, timers);

    gib_timer_begin(timers, "ldm_sky");
    gib_fullscreen_begin(&e->sky, targets[0].fbo, view->width, view->height, 1);
    gib_gbuffer_bind(&e->gbuffer);
    glUniform1f(LDM_AO_LOC_WEIGHT, 2.0f / (float)e->ldms.count);
    glUniform1f(LDM_AO_LOC_DMAX, INFINITY); /* unbounded: the sky is seen wherever nothing is hit */
    glUniform1i(LDM_AO_LOC_OBSCURANCE, 0);
    glUniform1f(LDM_AO_LOC_OFFSET, e->ldm_offset);
    glUniform3fv(LDM_AO_LOC_SKY, 1, e->scene->scene->sky);
    for (int p = 0; p < e->ldms.page_count; p++) {
        ldm_bind_page(&e->ldms, p);
        glUniform1i(LDM_AO_LOC_FIRST, e->ldms.pages[p].first);
        glUniform1i(LDM_AO_LOC_COUNT, e->ldms.pages[p].count);
        gib_fullscreen_draw(&e->sky);
    }
    gib_fullscreen_end();
    gib_timer_end(timers);
    return gib_gl_check("ldm_env", err);
}

static gib_status ldm_env_status(void *self) { return ldm_status(&((ldm_env *)self)->ldms); }

static const char *const ldm_env_passes[] = {"gbuffer", "ldm_build", "ldm_sky", "shadow", "shade",
    NULL};

const gib_technique gib_technique_ldm_env = {
    .name = "ldm_env",
    .source = "Aalund, Frisvad, Baerentzen 2015, Fig. 11 (uniform sky through LDMs) + shadow maps",
    .components = GIB_OUT_DIRECT,
    .params = ldm_env_params,
    .passes = ldm_env_passes,
    .scene_needs = GIB_FEAT_SKY,
    .create = ldm_env_create,
    .render = ldm_env_render,
    .status = ldm_env_status,
    .destroy = ldm_env_destroy,
};

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
#include "harness/gl/ledger.h"
#include "techniques/common/shader.h"
#include "techniques/common/gbuffer.h"
#include "techniques/common/shadow_map.h"
#include "techniques/ldm/ldm.h"

extern const gib_technique gib_technique_ldm_env;

typedef struct ldm_env {
    const gib_gpu_scene *scene;
    gib_ledger *ledger;
    gib_gbuffer gbuffer;
    gib_shadow_maps shadows;
    ldm_set ldms;
    unsigned shade_program, sky_program, vao;
    int pcf;
    float normal_offset, ldm_offset;
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
    gib_shadow_maps_destroy(&e->shadows, e->ledger);
    ldm_destroy(&e->ldms, e->ledger);
    if (e->shade_program)
        glDeleteProgram(e->shade_program);
    if (e->sky_program)
        glDeleteProgram(e->sky_program);
    if (e->vao)
        glDeleteVertexArrays(1, &e->vao);
    free(e);
}

static void *ldm_env_create(const gib_gpu_scene *scene, const gib_params *p, int w, int h,
                            gib_ledger *ledger, gib_error *err)
{
    const gib_technique *t = &gib_technique_ldm_env;
    ldm_env *e = calloc(1, sizeof *e);
    if (!e) {
        gib_fail(err, "out of memory");
        return NULL;
    }
    e->scene = scene;
    e->ledger = ledger;
    e->pcf = gib_param_int(t, p, "pcf");
    e->normal_offset = (float)gib_param_float(t, p, "normal_offset");
    e->ldm_offset = (float)gib_param_float(t, p, "ldm_offset");
    const char *shade[] = {"common/fullscreen.vert", "direct/direct.frag"};
    const char *sky[] = {"common/fullscreen.vert", "ldm_ao/ldm_ao.frag"};
    if (gib_gbuffer_create(&e->gbuffer, w, h, ledger, err) < 0 ||
        gib_shadow_maps_create(&e->shadows, scene, gib_param_int(t, p, "shadow_res"), ledger, err) < 0 ||
        ldm_create(&e->ldms, scene, gib_param_int(t, p, "directions"), gib_param_int(t, p, "ldm_res"),
                   1.0, ledger, err) < 0 ||
        !(e->shade_program = gib_program(shade, 2, NULL, err)) ||
        !(e->sky_program = gib_program(sky, 2, "#define LDM_SKY 1\n", err))) {
        ldm_env_destroy(e);
        return NULL;
    }
    glCreateVertexArrays(1, &e->vao);
    return e;
}

static int ldm_env_render(void *self, const gib_view *view, gib_timers *timers,
                          const gib_image_target *targets, int target_count, gib_error *err)
{
    ldm_env *e = self;
    if (target_count != 1)
        return gib_fail(err, "ldm_env renders one component, was given %d targets", target_count);
    gib_shadow_maps_render(&e->shadows, e->scene, timers);
    ldm_build(&e->ldms, e->scene, timers);
    gib_gbuffer_render(&e->gbuffer, e->scene, view, timers, "gbuffer");

    gib_timer_begin(timers, "shade");
    glBindFramebuffer(GL_FRAMEBUFFER, targets[0].fbo);
    glViewport(0, 0, view->width, view->height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(e->shade_program);
    gib_gpu_scene_bind(e->scene);
    gib_gbuffer_bind(&e->gbuffer);
    gib_shadow_maps_bind(&e->shadows, e->pcf, e->normal_offset);
    glUniform3fv(2, 1, view->camera->eye);
    glUniform1i(3, (int)e->scene->scene->light_count);
    glBindVertexArray(e->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    gib_timer_end(timers);

    gib_timer_begin(timers, "ldm_sky");
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(e->sky_program);
    gib_gbuffer_bind(&e->gbuffer);
    glUniform1f(7, 2.0f / (float)e->ldms.count);
    glUniform1f(8, INFINITY); /* unbounded: the sky is seen wherever nothing is hit */
    glUniform1i(9, 0);
    glUniform1f(10, e->ldm_offset);
    glUniform3fv(11, 1, e->scene->scene->sky);
    for (int p = 0; p < e->ldms.page_count; p++) {
        ldm_bind_page(&e->ldms, p);
        glUniform1i(5, e->ldms.pages[p].first);
        glUniform1i(6, e->ldms.pages[p].count);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glDisable(GL_BLEND);
    glBindVertexArray(0);
    gib_timer_end(timers);
    return gib_gl_check("ldm_env", err);
}

static const char *ldm_env_status(void *self) { return ldm_status(&((ldm_env *)self)->ldms); }

const gib_technique gib_technique_ldm_env = {
    .name = "ldm_env",
    .source = "Aalund, Frisvad, Baerentzen 2015, Fig. 11 (uniform sky through LDMs) + shadow maps",
    .components = GIB_OUT_DIRECT,
    .params = ldm_env_params,
    .scene_needs = GIB_FEAT_SKY,
    .create = ldm_env_create,
    .render = ldm_env_render,
    .status = ldm_env_status,
    .destroy = ldm_env_destroy,
};

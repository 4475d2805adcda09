/* gibench technique `hbao` — image-space horizon-based ambient occlusion (Bavoil, Sainz and
 * Dimitrov 2008, "Image-Space Horizon-Based Ambient Occlusion", SIGGRAPH 2008 talk; the same
 * authors' chapter in ShaderX7), the screen-space baseline of the LDM paper (Aalund, Frisvad and
 * Baerentzen 2015, Sec. 2.2 and Sec. 5.1, Fig. 8: "HBAO" with its kernel radius equal to d_max).
 *
 * Passes: the shared G-buffer ("gbuffer"), the horizon search ("hbao", techniques/hbao/hbao.frag),
 * and, when blur_radius > 0, the talk's cross-bilateral blur as two separable passes ("blur").
 *
 * What it estimates, and how that differs from the reference `ao` (ARCHITECTURE.md): the reference is
 * the cosine-weighted visible fraction (1/pi) int V cos, with V = 0 when a hit lies within d_max.
 * HBAO integrates the occluded SOLID ANGLE between the tangent plane and the horizon found in the
 * depth buffer, uniformly weighted (no cosine) and, by default, attenuated by W(r) = 1 - r^2/R^2;
 * it sees only the front-most layer and nothing off screen. Those are the method's approximations
 * and are what the benchmark measures; falloff = 0 replaces W by the reference's hard cut-off.
 * R = d_max must be finite: the kernel is the projection of R at each pixel. */
#include <glad/gl.h>
#include <math.h>
#include <stdlib.h>

#include "harness/gl/context.h"
#include "harness/gl/ledger.h"
#include "techniques/common/fullscreen.h"
#include "techniques/common/gbuffer.h"
#include "techniques/hbao/hbao_slots.h"

typedef struct hbao {
    gib_ledger *ledger;
    const gib_gpu_scene *scene;
    gib_gbuffer gbuffer;
    gib_fullscreen ao, blur;
    unsigned ao_tex[2], ao_fbo[2]; /* raw AO and the blur's intermediate (blur_radius > 0 only) */
    float radius, bias_rad, max_radius_px;
    int dirs, steps, falloff, blur_radius;
} hbao;

/* Relative plane-distance tolerance of the blur: 1% of the view depth. Neighbours on the centre's
 * tangent plane (and on gently curved surfaces) blend; a surface separated in depth by a few
 * percent (the Cornell blocks in front of the walls, Sponza's columns before the galleries)
 * gets a weight below exp(-4). */
#define HBAO_BLUR_TOLERANCE 0.01f

/* Defaults. directions = steps = 8 is a mid-range setting: more of each lowers the error at a
 * cost that grows with their product. The falloff W(r) = 1 - r^2/R^2 is Bavoil et al.'s.
 * The angle bias of 10 degrees is the value public ports of NVIDIA's HBAO samples set
 * (TanAngleBias = tan(10 deg)); NVIDIA's 2008 DX10 sample shipped with 30, which hides more of the
 * low-tessellation creases the bias is for but also more real contact occlusion. The blur radius 2
 * gives the lowest error on the Cornell box, at the price of a little detail on Sponza
 * (PERFORMANCE.md, "Measurements moved out of the sources"). */
static const gib_param_spec hbao_params[] = {
    {"dmax", GIB_PARAM_LENGTH, 1.0, 1e-6, 1e9,
     "occlusion radius R = d_max in scene units (Crytek Sponza is in cm); must be finite: "
     "screen-space AO marches the projection of R, so an unbounded d_max (inf) is not possible"},
    {"directions", GIB_PARAM_INT, 8, 1, 64, "N_d: screen directions per pixel (rotated per pixel)"},
    {"steps", GIB_PARAM_INT, 8, 1, 64, "N_s: ray-marching steps per direction (jittered)"},
    {"angle_bias", GIB_PARAM_FLOAT, 10, 0, 60,
     "tangent angle bias, degrees: ignores occluders less than this above the tangent plane"},
    {"falloff", GIB_PARAM_INT, 1, 0, 1,
     "attenuation W(r): 1 = 1 - r^2/R^2 (Bavoil et al. 2008), 0 = 1 inside R (hard cut-off)"},
    {"max_radius_px", GIB_PARAM_FLOAT, 0, 0, 1e6,
     "clamp on the projected radius in pixels, 0 = none (the LDM paper's HBAO grows with d_max)"},
    {"blur_radius", GIB_PARAM_INT, 2, 0, 32,
     "cross-bilateral blur radius in pixels (separable, 2r+1 taps per axis), 0 = off"},
    {0},
};

extern const gib_technique gib_technique_hbao;
static void hbao_destroy(void *self);

static void *hbao_create(const gib_gpu_scene *scene, const gib_params *p, int width, int height,
                         gib_ledger *ledger, gib_error *err)
{
    hbao *h = calloc(1, sizeof *h);
    if (!h) {
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    const gib_technique *t = &gib_technique_hbao;
    h->ledger = ledger;
    h->scene = scene;
    h->radius = (float)gib_param_float(t, p, "dmax");
    h->dirs = gib_param_int(t, p, "directions");
    h->steps = gib_param_int(t, p, "steps");
    h->bias_rad = (float)(gib_param_float(t, p, "angle_bias") * M_PI / 180.0);
    h->falloff = gib_param_int(t, p, "falloff");
    h->max_radius_px = (float)gib_param_float(t, p, "max_radius_px");
    h->blur_radius = gib_param_int(t, p, "blur_radius");
    if (gib_gbuffer_create(&h->gbuffer, width, height, ledger, err) < 0 ||
        gib_fullscreen_create(&h->ao, "hbao/hbao.frag", NULL, err) < 0)
        goto fail;
    if (h->blur_radius > 0) {
        static const char *labels[2] = {"hbao.ao", "hbao.blur"};
        if (gib_fullscreen_create(&h->blur, "hbao/hbao_blur.frag", NULL, err) < 0)
            goto fail;
        for (int i = 0; i < 2; i++) {
            if (!(h->ao_tex[i] = gib_gpu_texture(ledger, labels[i], GL_TEXTURE_2D, width, height,
                                                 1, GL_R32F, 1, err)))
                goto fail;
            glCreateFramebuffers(1, &h->ao_fbo[i]);
            glNamedFramebufferTexture(h->ao_fbo[i], GL_COLOR_ATTACHMENT0, h->ao_tex[i], 0);
            if (glCheckNamedFramebufferStatus(h->ao_fbo[i], GL_FRAMEBUFFER) !=
                GL_FRAMEBUFFER_COMPLETE) {
                gib_fail(err, "hbao: AO framebuffer incomplete");
                goto fail;
            }
        }
    }
    if (gib_gl_check("hbao create", err) < 0)
        goto fail;
    return h;
fail:
    hbao_destroy(h);
    return NULL;
}

/* Camera axes in world space, from the rows of the (rigid) view matrix. */
static void view_axes(const gib_view *v, float right[3], float up[3], float forward[3])
{
    for (int i = 0; i < 3; i++) {
        right[i] = v->view[i * 4 + 0];
        up[i] = v->view[i * 4 + 1];
        forward[i] = -v->view[i * 4 + 2];
    }
}

static int hbao_render(void *self, const gib_view *view, gib_timers *timers,
                       const gib_image_target *targets, int target_count, gib_error *err)
{
    hbao *h = self;
    if (target_count != 1)
        return gib_fail(err, "hbao renders one component, was given %d targets", target_count);
    gib_gbuffer_render(&h->gbuffer, h->scene, view, timers, "gbuffer");

    float right[3], up[3], forward[3];
    view_axes(view, right, up, forward);
    const int blur = h->blur_radius > 0;
    gib_gbuffer_bind(&h->gbuffer);

    gib_timer_begin(timers, "hbao");
    gib_fullscreen_begin(&h->ao, blur ? h->ao_fbo[0] : targets[0].fbo, view->width, view->height,
                         0);
    glUniform3fv(HBAO_LOC_EYE, 1, view->camera->eye);
    glUniform3fv(HBAO_LOC_RIGHT, 1, right);
    glUniform3fv(HBAO_LOC_UP, 1, up);
    glUniform3fv(HBAO_LOC_FORWARD, 1, forward);
    /* proj[5] = cot(fov_y / 2): lateral offset / depth -> NDC; times height/2 -> pixels (square
     * pixels, so the same factor holds along x). */
    glUniform1f(HBAO_LOC_FOCAL_PX, view->proj[5] * 0.5f * (float)view->height);
    glUniform1f(HBAO_LOC_RADIUS, h->radius);
    glUniform1i(HBAO_LOC_DIRS, h->dirs);
    glUniform1i(HBAO_LOC_STEPS, h->steps);
    glUniform1f(HBAO_LOC_BIAS, h->bias_rad);
    glUniform1i(HBAO_LOC_FALLOFF, h->falloff);
    glUniform1f(HBAO_LOC_MAX_RADIUS_PX, h->max_radius_px);
    glUniform1i(HBAO_LOC_FINAL, !blur);
    gib_fullscreen_draw(&h->ao);
    gib_fullscreen_end();
    gib_timer_end(timers);

    if (blur) {
        gib_timer_begin(timers, "blur");
        for (int pass = 0; pass < 2; pass++) {
            gib_fullscreen_begin(&h->blur, pass == 0 ? h->ao_fbo[1] : targets[0].fbo, view->width,
                                 view->height, 0);
            if (pass == 0) {
                glUniform3fv(HBAO_BLUR_LOC_EYE, 1, view->camera->eye);
                glUniform3fv(HBAO_BLUR_LOC_FORWARD, 1, forward);
                glUniform1i(HBAO_BLUR_LOC_RADIUS, h->blur_radius);
                glUniform1f(HBAO_BLUR_LOC_TOLERANCE, HBAO_BLUR_TOLERANCE);
            }
            glBindTextureUnit(HBAO_BLUR_UNIT_AO, h->ao_tex[pass]);
            glUniform2i(HBAO_BLUR_LOC_AXIS, pass == 0, pass == 1);
            glUniform1i(HBAO_BLUR_LOC_FINAL, pass == 1);
            gib_fullscreen_draw(&h->blur);
        }
        gib_fullscreen_end();
        gib_timer_end(timers);
    }
    return gib_gl_check("hbao", err);
}

static void hbao_destroy(void *self)
{
    hbao *h = self;
    if (!h)
        return;
    gib_gbuffer_destroy(&h->gbuffer, h->ledger);
    for (int i = 0; i < 2; i++) {
        if (h->ao_fbo[i])
            glDeleteFramebuffers(1, &h->ao_fbo[i]);
        if (h->ao_tex[i])
            gib_gpu_free(h->ledger, h->ao_tex[i], 1);
    }
    gib_fullscreen_destroy(&h->ao);
    gib_fullscreen_destroy(&h->blur);
    free(h);
}

static const gib_ref_binding hbao_reference[] = {
    {GIB_OUT_AO, GIB_REF_AO_DMAX, "dmax"},
    {0},
};

static const char *const hbao_passes[] = {"gbuffer", "hbao", "blur", NULL};

const gib_technique gib_technique_hbao = {
    .name = "hbao",
    .source = "image-space horizon-based AO (Bavoil, Sainz and Dimitrov 2008); LDM paper Sec. 5.1",
    .components = GIB_OUT_AO,
    .params = hbao_params,
    .passes = hbao_passes,
    .reference = hbao_reference,
    .scene_needs = 0,
    .scene_needs_any = 0,
    .create = hbao_create,
    .render = hbao_render,
    .status = NULL,
    .destroy = hbao_destroy,
};

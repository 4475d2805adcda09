/* gibench technique `template` — the technique a new one is copied from (ARCHITECTURE.md, "Adding
 * a technique"). It is compiled with the others and tested like them, but it is not in the
 * registry's list: `gibench list` and matrices never see it; tests reach it through
 * gib_techniques_test_only() (techniques/registry.c).
 *
 * What it estimates: the `indirect` component (one diffuse bounce, L D D E) by the ambient term of
 * a closed scene, an energy balance: the one-bounce term of the ambient term of progressive
 * radiosity (Cohen, Chen, Wallace and Greenberg 1988, which sums every bounce with 1/(1 - rho)).
 * In a closed scene all the power Phi the lights emit lands on the surfaces; after one diffuse
 * reflection the surfaces give back rho_avg Phi, rho_avg their area-weighted mean albedo. Spread
 * evenly over the area A, that is the irradiance E = rho_avg Phi / A at every point, and a
 * Lambertian point reflects
 *     L = (rho_d / pi) E.
 * It ignores where the light falls and what sees what, so it is right only where those do not
 * matter: inside a sphere of uniform albedo with lights anywhere inside (the form factor between
 * two patches of a sphere's inside does not depend on where they are). There it is exact: the
 * furnace (scenes/furnace.scene: R = 1 m, rho = 0.5, I = 1 W/sr) gives E = 0.5 x 4 pi I / 4 pi R^2
 * and L = 0.25 / pi = 0.079577 (its facets: x 1.0003). tests/techniques/test_closed_form.c checks
 * that, with every other technique that outputs a component the furnace has a closed form for;
 * tests/template/test_template.c checks its counter, its parameter and its status.
 *
 * The pieces every technique has, in the order a newcomer meets them below:
 *  1. its state: what create() allocates, render() uses and destroy() frees;
 *  2. its parameters: name, type, default, range, help (checked before create is called);
 *  3. create(): every GPU allocation through the ledger (the CSV's memory columns), shaders built;
 *  4. render(): each pass between gib_timer_begin/end (the CSV's per-pass times);
 *  5. status() and counters(): what the frame found, read after the last frame;
 *  6. destroy();
 *  7. reference bindings and the descriptor itself.
 * Its GL slots are named in template_slots.h, which template.frag includes too. */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "harness/gl/bindings.h"
#include "harness/gl/context.h"
#include "techniques/common/fullscreen.h"
#include "techniques/common/gbuffer.h"
#include "techniques/template/template_slots.h"

/* The own slots stay in the ranges bindings.h leaves to a pass; a shared slot taken by mistake
 * would be overwritten (or overwrite) without any GL error. */
_Static_assert(TEMPLATE_SSBO_COUNTS >= GIB_SSBO_OWN_FIRST && TEMPLATE_SSBO_COUNTS <= 15,
               "TEMPLATE_SSBO_COUNTS must be one of bindings.h's own SSBO bindings (8..15)");
_Static_assert(TEMPLATE_LOC_IRRADIANCE >= 0 && TEMPLATE_LOC_IRRADIANCE < GIB_LOC_LV_FIRST,
               "a full-screen pass's own uniforms use locations 0..19");

/* ---- 1. state ---- */

typedef struct template_state {
    const gib_gpu_scene *scene; /* the scene on the GPU: the harness owns it, it outlives us */
    gib_ledger *ledger;         /* where every allocation is counted (and freed from) */
    gib_gbuffer gbuffer;        /* the shared G-buffer pass (techniques/common/gbuffer.h) */
    gib_fullscreen ambient;     /* the pass of template.frag */
    unsigned counts;            /* SSBO at TEMPLATE_SSBO_COUNTS: one uint, pixels shaded */
    float irradiance[3];        /* E, RGB, W/m^2: fixed for the scene, computed in create */
    unsigned shaded_pixels;     /* what the last frame counted (read back by counters) */
} template_state;

/* ---- 2. parameters ----
 * One line per parameter: the name the CLI (--param strength=2), matrices and the CSV use, its
 * type (GIB_PARAM_INT, GIB_PARAM_FLOAT, or GIB_PARAM_LENGTH for a distance a matrix's scene_scale
 * scales), the default, the inclusive range (a value outside is refused before create is called)
 * and a help text `gibench list` prints. An int would read, e.g.:
 *     {"samples", GIB_PARAM_INT, 16, 1, 1024, "samples per pixel"},
 * Read them in create with gib_param_float/gib_param_int by name; a name not declared here stops
 * the process with a message naming it. */
static const gib_param_spec template_params[] = {
    {"strength", GIB_PARAM_FLOAT, 1.0, 0.0, 16.0,
     "scale on the ambient irradiance rho_avg Phi / A (1: the energy balance of a closed scene)"},
    {0},
};

/* The descriptor is at the end of the file; create needs it for the parameter look-ups. */
extern const gib_technique gib_technique_template;
static void template_destroy(void *self);

/* What create computes: the irradiance E the pass spreads. First the power of one light in
 * channel c, W. Point: I over the sphere, 4 pi I. Spot: I cos^e(theta) over its cone,
 * 2 pi I (1 - cos^(e+1) theta_o) / (e + 1), the cosine clamped at 0 as gib_spot_falloff clamps
 * it (with e = 0 the falloff is 1 out to theta_o, beyond 90 degrees too).
 * A directional light has no finite power in a closed scene: 0 (scene_needs_any below leaves
 * scenes lit only by one out). */
static double light_power(const gib_light *l, int c)
{
    const double I = l->intensity[c];
    if (l->type == GIB_LIGHT_POINT)
        return 4.0 * M_PI * I;
    if (l->type != GIB_LIGHT_SPOT)
        return 0.0;
    const double e = l->spot_exponent, cos_o = cos(l->spot_outer_deg * M_PI / 180.0);
    if (e == 0.0)
        return 2.0 * M_PI * I * (1.0 - cos_o);
    return 2.0 * M_PI * I * (1.0 - pow(fmax(cos_o, 0.0), e + 1.0)) / (e + 1.0);
}

static double triangle_area(const gib_scene *s, uint32_t t)
{
    const float *p[3];
    for (int k = 0; k < 3; k++)
        p[k] = s->positions + 3 * (size_t)s->indices[3 * (size_t)t + k];
    double u[3], v[3];
    for (int k = 0; k < 3; k++) {
        u[k] = (double)p[1][k] - p[0][k];
        v[k] = (double)p[2][k] - p[0][k];
    }
    const double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2],
                 cz = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
}

/* E = strength x rho_avg Phi / A, per channel. rho_avg weighs each triangle's material albedo by
 * its area (textures are left out: their mean is not known here). A moving scene is measured as
 * loaded. All on the CPU, once: the pass only reads the result. */
static void ambient_irradiance(const gib_scene *s, double strength, float E[3])
{
    double area = 0, reflected[3] = {0, 0, 0}, power[3] = {0, 0, 0};
    for (uint32_t t = 0; t < s->triangle_count; t++) {
        const double a = triangle_area(s, t);
        const gib_material *m = &s->materials[s->tri_material[t]];
        area += a;
        for (int c = 0; c < 3; c++)
            reflected[c] += a * m->albedo[c];
    }
    for (uint32_t i = 0; i < s->light_count; i++)
        for (int c = 0; c < 3; c++)
            power[c] += light_power(&s->lights[i], c);
    for (int c = 0; c < 3; c++)
        E[c] = area > 0 ? (float)(strength * (reflected[c] / area) * power[c] / area) : 0.0f;
}

/* ---- 3. create ----
 * Everything a frame needs, for images of width x height: textures and buffers through the
 * ledger (gib_gpu_texture, gib_gpu_buffer, gib_gpu_renderbuffer; label "<structure>.<what>", the
 * part before the '.' is the CSV's memory-by-structure key), programs from the embedded shaders.
 * On failure: set err, free what was made (destroy copes with a half-built state), return NULL.
 * No printing, no files, no context: the harness owns those. */
static void *template_create(const gib_gpu_scene *scene, const gib_params *p, int width,
                             int height, gib_ledger *ledger, gib_error *err)
{
    template_state *s = calloc(1, sizeof *s);
    if (!s) {
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    s->scene = scene;
    s->ledger = ledger;
    const gib_technique *t = &gib_technique_template;
    ambient_irradiance(scene->scene, gib_param_float(t, p, "strength"), s->irradiance);
    if (gib_gbuffer_create(&s->gbuffer, width, height, ledger, err) < 0 ||
        gib_fullscreen_create(&s->ambient, "template/template.frag", NULL, err) < 0 ||
        !(s->counts = gib_gpu_buffer(ledger, "template.counts", sizeof(unsigned), NULL,
                                     GL_DYNAMIC_STORAGE_BIT, err)) ||
        gib_gl_check("template create", err) < 0) {
        template_destroy(s);
        return NULL;
    }
    return s;
}

/* ---- 4. render ----
 * One frame into targets[]: one per set bit of .components, in bit order (here one, `indirect`).
 * The target's FBO has a colour texture (RGBA32F) and a depth buffer; rows are GL's, bottom up.
 * Every pass sits between gib_timer_begin(timers, "<pass>") and gib_timer_end: those names are
 * the CSV's passes. gib_gbuffer_render times itself as "gbuffer". Returns 0, or -1 with err set. */
static int template_render(void *self, const gib_view *view, gib_timers *timers,
                           const gib_image_target *targets, int target_count, gib_error *err)
{
    template_state *s = self;
    if (target_count != 1)
        return gib_fail(err, "template renders one component, was given %d targets",
                        target_count);
    gib_gbuffer_render(&s->gbuffer, s->scene, view, timers, "gbuffer");

    gib_timer_begin(timers, "ambient");
    const unsigned zero = 0;
    glClearNamedBufferData(s->counts, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    gib_gbuffer_bind(&s->gbuffer); /* position, normal, albedo, specular at GIB_UNIT_GBUF_* */
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEMPLATE_SSBO_COUNTS, s->counts);
    gib_fullscreen_begin(&s->ambient, targets[0].fbo, view->width, view->height, 0);
    glUniform3fv(TEMPLATE_LOC_IRRADIANCE, 1, s->irradiance);
    gib_fullscreen_draw(&s->ambient);
    gib_fullscreen_end();
    gib_timer_end(timers);
    return gib_gl_check("template", err);
}

/* ---- 5. status and counters ----
 * Both are optional (NULL in the descriptor) and are called once, after the last frame.
 * status: GIB_STATUS_OK when the image is an answer; otherwise one of harness/base/status.h's
 * (GIB_STATUS_OVERFLOW, GIB_STATUS_NO_PHOTONS, ...), which becomes the row's status instead of
 * scores, for a condition that makes the image no estimate at all (NaN is the runner's to find). Here: lights that give no power (E = 0) leave a black image that would
 * score as if it were the technique's answer.
 * counters: what the last frame counted, "name=value" pairs joined by ';', written to the row's
 * `counters` column. Here the pixels the pass shaded, read back from the SSBO. */
static gib_status template_status(void *self)
{
    const template_state *s = self;
    const int lit = s->irradiance[0] > 0 || s->irradiance[1] > 0 || s->irradiance[2] > 0;
    return lit ? GIB_STATUS_OK : GIB_STATUS_NO_LIGHT;
}

static void template_counters(void *self, char *buf, size_t len)
{
    template_state *s = self;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); /* the shader's atomics, before the read */
    glGetNamedBufferSubData(s->counts, 0, sizeof s->shaded_pixels, &s->shaded_pixels);
    snprintf(buf, len, "pixels=%u", s->shaded_pixels);
}

/* ---- 6. destroy ----
 * Frees everything create made, through the ledger (gib_gpu_free), also when create stopped
 * half-way (members still 0 are skipped). The harness checks nothing is left: tests/techniques/
 * test_contract_gl.c fails a technique whose ledger is not empty after destroy. */
static void template_destroy(void *self)
{
    template_state *s = self;
    if (!s)
        return;
    gib_gbuffer_destroy(&s->gbuffer, s->ledger);
    gib_fullscreen_destroy(&s->ambient);
    if (s->counts)
        gib_gpu_free(s->ledger, s->counts, 0);
    free(s);
}

/* ---- 7. reference bindings and the descriptor ----
 * Each output component is scored against the path tracer's component of the same name. Where
 * that reference has settings, the technique says which of its parameters gives each one: an
 * `ao` technique binds its range, {GIB_OUT_AO, GIB_REF_AO_DMAX, "dmax"} (and may bind
 * GIB_REF_AO_OBSCURANCE). `indirect` has no settings: the list holds only its terminator. */
static const gib_ref_binding template_reference[] = {
    {0},
};

static const char *const template_passes[] = {"gbuffer", "ambient", NULL};

const gib_technique gib_technique_template = {
    .name = "template",
    .source = "the technique template: ambient term of a closed scene (after Cohen et al. 1988)",
    .components = GIB_OUT_INDIRECT,
    .params = template_params,
    .passes = template_passes,
    .reference = template_reference,
    /* The estimate needs a closed scene (all light lands on its surfaces) and a point or spot
     * light (a finite power): other scenes are skipped, with the reason, by matrices and tests. */
    .scene_needs = GIB_FEAT_CLOSED,
    .scene_needs_any = GIB_FEAT_POINT_LIGHT | GIB_FEAT_SPOT_LIGHT,
    .create = template_create,
    .render = template_render,
    .status = template_status,
    .counters = template_counters,
    .destroy = template_destroy,
};

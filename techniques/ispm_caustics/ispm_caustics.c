/* gibench technique `ispm_caustics` — caustics by photons from the light view traced through the
 * camera's per-pixel linked lists and splatted (Le Hoang Quyen 2014, thesis 004, Sec. 3.3,
 * Algorithms 3.3-3.5, Ch. 4). Output: `caustic` (L S D E: one specular bounce, as the thesis).
 *
 *  1. Light view (common/light_view.h, pass "rsm") with position, normal (w: specular mask),
 *     flux (rho_d x flux) and specular part.
 *  2. "list_build": the scene from the camera at ray_res^2 into per-pixel linked lists
 *     (list_build.frag, Algorithm 3.4), a pool of list_capacity nodes per pixel on average; a full
 *     pool is status `overflow`.
 *  3. "photon_tracing": the specular mask's mip chain (mask_mip.comp), one photon per fully
 *     specular texel of level mask_level (emit.comp: roulette, mirror or Phong reflection with
 *     random numbers generated once at create), their rays drawn as lines at ray_res^2 against the
 *     lists (trace.*, Algorithm 3.5), then each photon's hit, normal and splat radius
 *     (resolve.comp). One draw traces every photon: the first hit of each goes to its own slot
 *     (atomicMin) instead of a texture row, so the thesis' repeated passes (rows run out) are one.
 *     Hits outside the camera's frustum are not found (the thesis' lists are perspective too).
 *     The thesis' per-pixel min/max depth for skipping empty space is not kept: the walk's bound
 *     is the longest list instead (list_lookup.glsl).
 *  4. "splatting": Gaussian disks into an irradiance target at 1/splat_res_divisor of the image.
 *  5. "upsampling": radiance rho_d / pi E, with bilateral upsampling when the splats were smaller.
 * layers = 4: the lists are replaced by 4 depth-peeled layers (peel.frag, 4 passes) turned into
 * lists of at most 4 nodes (layers.comp), the thesis' comparison: surfaces deeper than the 4th
 * along a camera ray are missing (Fig. 4.2(b)). */
#include <glad/gl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "techniques/common/compute.h"
#include "techniques/common/fullscreen.h"
#include "techniques/common/gbuffer.h"
#include "techniques/common/light_view.h"
#include "techniques/common/shader.h"
#include "techniques/common/pass_state.h"
#include "techniques/ispm_caustics/ispm_caustics.h"
#include "techniques/ispm_caustics/ispm_caustics_slots.h"

extern const gib_technique gib_technique_ispm_caustics;

#define PHOTON_BYTES 80u
#define NODE_BYTES 12u

typedef struct caustics {
    const gib_gpu_scene *scene;
    gib_ledger *ledger;
    int width, height, ray_res, level, res_l, divisor, splat_w, splat_h;
    float splat_scale, delta, slack, hit_depth, diag;
    gib_gbuffer gbuffer, low;      /* low: the splats' G-buffer when divisor > 1 */
    gib_light_views views;
    unsigned mask;                 /* R32F 2D array, levels 0..mask_level */
    unsigned heads, nodes, counts, status_buf, photons, random, first_t, command;
    unsigned irradiance, splat_fbo, list_fbo, vao;
    unsigned mip_prog, emit_prog, list_prog, trace_prog, resolve_prog, splat_prog;
    int layers;                    /* 0: lists; 4: depth-peeled layers */
    unsigned layer_tex[ISPM_LAYERS], layer_depth, layer_fbo, peel_prog, layers_prog;
    gib_fullscreen shade;
    uint32_t node_capacity, photon_capacity;
    int redraw, frames_rendered;   /* random numbers drawn anew each frame after the first */
    uint64_t rng;                  /* the PCG32 state the numbers continue from */
    float *rnd;                    /* with redraw: the CPU copy refilled each frame */
} caustics;

static const gib_param_spec caustics_params[] = {
    {"rsm_res", GIB_PARAM_INT, 256, 16, 4096, "light-view resolution per face (the RSM, Ch. 4: 512)"},
    {"mask_level", GIB_PARAM_INT, 2, 0, 10,
     "mip level of the specular mask photons are emitted from (Sec. 3.3.1.1): ~4x fewer a level"},
    {"ray_res", GIB_PARAM_INT, 128, 16, 2048,
     "side of the camera's linked lists and of the photon lines (Ch. 4: 128 or 256)"},
    {"list_capacity", GIB_PARAM_FLOAT, 8, 0.01, 1024,
     "list nodes per ray_res pixel on average (the pool; Ch. 4: 20 MB)"},
    {"splat_scale", GIB_PARAM_FLOAT, 3.0, 0.01, 100,
     "C: splat radius h = C sqrt(area the photon stands for on the receiver)"},
    {"splat_res_divisor", GIB_PARAM_INT, 1, 1, 8,
     "splats at 1/k of the image side; k > 1 upsampled bilaterally (Sec. 3.3.2.4: 2)"},
    {"layers", GIB_PARAM_INT, 0, 0, ISPM_LAYERS,
     "0: per-pixel linked lists; 4: 4 depth-peeled layers (the thesis' comparison, Fig. 4.2(b))",
     .choices = (const gib_param_choice[]){{"lists", 0}, {"peeled", ISPM_LAYERS}, {0}}},
    {"kernel_delta", GIB_PARAM_FLOAT, 0.25, 0.01, 10,
     "delta of the Gaussian splat kernel exp(-(r/h)^2 / (2 delta)), cut at r = h"},
    {"hit_slack", GIB_PARAM_FLOAT, 0.5, 0, 4,
     "pixels around a line fragment where a crossing of a list node's plane counts as a hit"},
    {"hit_depth", GIB_PARAM_FLOAT, 4, 0, 64,
     "how far in depth a crossing may lie from its list node, in pixel footprints at the node's "
     "depth (Algorithm 3.5's depth epsilon); 0: no bound, the node's tangent plane alone"},
    {"seed", GIB_PARAM_INT, 1, 0, 1e9, "seed of the pre-generated random numbers"},
    {"redraw", GIB_PARAM_INT, 0, 0, 1,
     "0: the pre-generated random numbers reused every frame (thesis, Ch. 4: temporal coherence); "
     "1: drawn anew every frame (the same stream, continued)"},
    {0},
};

/* Photons are emitted from mip mask_level of the rsm_res^2 specular mask, which must exist. */
static int mask_level_exists(const gib_technique *t, const gib_params *p)
{
    return (gib_param_int(t, p, "rsm_res") >> gib_param_int(t, p, "mask_level")) >= 1;
}

static const gib_param_rule caustics_rules[] = {
    {"rsm_res,mask_level",
     "mask_level must be a mip of the light view: rsm_res >> mask_level >= 1", mask_level_exists},
    {0},
};

static void caustics_destroy(void *self)
{
    caustics *c = self;
    if (!c)
        return;
    gib_gbuffer_destroy(&c->gbuffer, c->ledger);
    if (c->low.fbo)
        gib_gbuffer_destroy(&c->low, c->ledger);
    gib_light_views_destroy(&c->views, c->ledger);
    const unsigned bufs[] = {c->heads, c->nodes, c->counts, c->status_buf, c->photons, c->random, c->first_t,
                             c->command};
    for (size_t i = 0; i < sizeof bufs / sizeof bufs[0]; i++)
        if (bufs[i])
            gib_gpu_free(c->ledger, bufs[i], 0);
    if (c->mask)
        gib_gpu_free(c->ledger, c->mask, 1);
    if (c->irradiance)
        gib_gpu_free(c->ledger, c->irradiance, 1);
    const unsigned progs[] = {c->mip_prog, c->emit_prog, c->list_prog, c->trace_prog,
                              c->resolve_prog, c->splat_prog};
    for (size_t i = 0; i < sizeof progs / sizeof progs[0]; i++)
        if (progs[i])
            glDeleteProgram(progs[i]);
    gib_fullscreen_destroy(&c->shade);
    for (int k = 0; k < ISPM_LAYERS; k++)
        if (c->layer_tex[k])
            gib_gpu_free(c->ledger, c->layer_tex[k], 1);
    if (c->layer_depth)
        gib_gpu_free(c->ledger, c->layer_depth, 2);
    if (c->layer_fbo)
        glDeleteFramebuffers(1, &c->layer_fbo);
    if (c->peel_prog)
        glDeleteProgram(c->peel_prog);
    if (c->layers_prog)
        glDeleteProgram(c->layers_prog);
    if (c->splat_fbo)
        glDeleteFramebuffers(1, &c->splat_fbo);
    free(c->rnd);
    if (c->list_fbo)
        glDeleteFramebuffers(1, &c->list_fbo);
    if (c->vao)
        glDeleteVertexArrays(1, &c->vao);
    free(c);
}

/* PCG32 (O'Neill 2014) for the random numbers generated once at create. */
static uint32_t pcg32(uint64_t *s)
{
    uint64_t old = *s;
    *s = old * 6364136223846793005ull + 1442695040888963407ull;
    uint32_t x = (uint32_t)(((old >> 18u) ^ old) >> 27u), r = (uint32_t)(old >> 59u);
    return (x >> r) | (x << ((32 - r) & 31));
}

/* The photons' indirect draw command as emission starts (emit.comp counts into it): the lines of
 * the tracing {2 vertices, N instances, 0, 0} and the points of the splatting {N, 1 instance, 0,
 * 0}, N = 0. Written at create and before every frame's emission. */
static const uint32_t COMMAND_RESET[8] = {2, 0, 0, 0, 0, 1, 0, 0};

/* The parameters (checked against the descriptor's rules before any scene is loaded) and the
 * sizes that follow from them. */
static void read_params(caustics *c, const gib_params *p, int *rsm_res)
{
    const gib_technique *t = &gib_technique_ispm_caustics;
    *rsm_res = gib_param_int(t, p, "rsm_res");
    c->level = gib_param_int(t, p, "mask_level");
    c->ray_res = gib_param_int(t, p, "ray_res");
    c->divisor = gib_param_int(t, p, "splat_res_divisor");
    c->splat_scale = (float)gib_param_float(t, p, "splat_scale");
    c->delta = (float)gib_param_float(t, p, "kernel_delta");
    c->slack = (float)gib_param_float(t, p, "hit_slack");
    c->hit_depth = (float)gib_param_float(t, p, "hit_depth");
    c->layers = gib_param_int(t, p, "layers");
    c->res_l = *rsm_res >> c->level;
    const gib_scene *s = c->scene->scene;
    c->diag = 0;
    for (int k = 0; k < 3; k++)
        c->diag += (s->bounds_max[k] - s->bounds_min[k]) * (s->bounds_max[k] - s->bounds_min[k]);
    c->diag = sqrtf(c->diag);
    c->splat_w = (c->width + c->divisor - 1) / c->divisor;
    c->splat_h = (c->height + c->divisor - 1) / c->divisor;
}

/* The G-buffers, the light views and every program. */
static int create_passes(caustics *c, int rsm_res, gib_error *err)
{
    const char *mip[] = {"ispm_caustics/mask_mip.comp"};
    const char *emit[] = {"ispm_caustics/emit.comp"};
    const char *list[] = {"common/gbuffer.vert", "ispm_caustics/list_build.frag"};
    const char *trace[] = {"ispm_caustics/trace.vert", "ispm_caustics/trace.frag"};
    const char *resolve[] = {"ispm_caustics/resolve.comp"};
    const char *splat[] = {"ispm_caustics/splat.vert", "ispm_caustics/splat.geom",
                           "ispm_caustics/splat.frag"};
    const unsigned lv = GIB_LV_POSITION | GIB_LV_NORMAL | GIB_LV_FLUX | GIB_LV_SPECULAR;
    if (gib_gbuffer_create(&c->gbuffer, c->width, c->height, c->ledger, err) < 0 ||
        (c->divisor > 1 &&
         gib_gbuffer_create(&c->low, c->splat_w, c->splat_h, c->ledger, err) < 0) ||
        gib_light_views_create(&c->views, c->scene, rsm_res, lv, "rsm", c->ledger, err) < 0 ||
        !(c->mip_prog = gib_program(mip, 1, NULL, err)) ||
        !(c->emit_prog = gib_program(emit, 1, NULL, err)) ||
        !(c->list_prog = gib_program(list, 2, NULL, err)) ||
        !(c->trace_prog = gib_program(trace, 2, NULL, err)) ||
        !(c->resolve_prog = gib_program(resolve, 1, NULL, err)) ||
        !(c->splat_prog = gib_program(splat, 3, NULL, err)) ||
        gib_fullscreen_create(&c->shade, "ispm_caustics/shade.frag", NULL, err) < 0)
        return -1;
    return 0;
}

/* The pool of list nodes: list_capacity per ray_res pixel on average, within one storage buffer
 * (4 a pixel with the layers). */
static int size_pool(caustics *c, const gib_params *p, gib_error *err)
{
    uint64_t pixels = (uint64_t)c->ray_res * (uint64_t)c->ray_res;
    double per_pixel = gib_param_float(&gib_technique_ispm_caustics, p, "list_capacity");
    uint64_t nodes = (uint64_t)ceil((double)pixels * per_pixel);
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    if (nodes * NODE_BYTES > (uint64_t)max_block)
        return gib_fail(err, "ispm_caustics: list_capacity %g x %d^2 nodes of %u bytes exceed one "
                             "storage buffer (%lld bytes)", per_pixel, c->ray_res, NODE_BYTES,
                        (long long)max_block);
    c->node_capacity = (uint32_t)(c->layers ? ISPM_LAYERS * pixels : nodes);
    return 0;
}

/* The next n random numbers of the stream, uniform in [0, 1). */
static void fill_random(uint64_t *state, float *rnd, size_t n)
{
    for (size_t i = 0; i < n; i++)
        rnd[i] = (float)(pcg32(state) >> 8) * (1.0f / 16777216.0f);
}

/* 8 random numbers a photon, generated once from the seed (with redraw the buffer is refilled from
 * the same stream every frame after the first, and its CPU copy kept). */
static int create_random(caustics *c, const gib_params *p, gib_error *err)
{
    size_t nrand = (size_t)c->photon_capacity * 8;
    float *rnd = malloc(nrand * sizeof *rnd);
    if (!rnd)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    uint64_t seed = (uint64_t)gib_param_int(&gib_technique_ispm_caustics, p, "seed");
    c->rng = 0x853c49e6748fea9bull ^ (seed << 1);
    c->redraw = gib_param_int(&gib_technique_ispm_caustics, p, "redraw");
    fill_random(&c->rng, rnd, nrand);
    c->random = gib_gpu_buffer(c->ledger, "photons.random", nrand * sizeof *rnd, rnd,
                               c->redraw ? GL_DYNAMIC_STORAGE_BIT : 0, err);
    if (c->redraw)
        c->rnd = rnd;
    else
        free(rnd);
    return c->random ? 0 : -1;
}

/* With redraw, every frame after the first draws its photons' random numbers anew (timed as
 * "random_redraw": generating and uploading them is the cost of not reusing them). */
static void redraw_random(caustics *c, gib_timers *timers)
{
    if (!c->redraw || c->frames_rendered++ == 0)
        return;
    gib_timer_begin(timers, "random_redraw");
    size_t nrand = (size_t)c->photon_capacity * 8;
    fill_random(&c->rng, c->rnd, nrand);
    glNamedBufferSubData(c->random, 0, (GLsizeiptr)(nrand * sizeof *c->rnd), c->rnd);
    gib_timer_end(timers);
}

/* The mask, the lists, the photons and the splats' target, as the ledger names them. */
static int create_buffers(caustics *c, int rsm_res, int faces, gib_error *err)
{
    gib_ledger *L = c->ledger;
    const uint64_t pixels = (uint64_t)c->ray_res * (uint64_t)c->ray_res;
    const unsigned dyn = GL_DYNAMIC_STORAGE_BIT;
    if (!(c->mask = gib_gpu_texture(L, "mips.mask", GL_TEXTURE_2D_ARRAY, rsm_res, rsm_res, faces,
                                    GL_R32F, c->level + 1, err)) ||
        !(c->heads = gib_gpu_buffer(L, "lists.heads", 4 * pixels, NULL, dyn, err)) ||
        !(c->counts = gib_gpu_buffer(L, "lists.counts", 4 * pixels, NULL, dyn, err)) ||
        !(c->nodes = gib_gpu_buffer(L, "lists.nodes", (uint64_t)NODE_BYTES * c->node_capacity,
                                    NULL, 0, err)) ||
        !(c->status_buf = gib_gpu_buffer(L, "lists.status", 16, NULL, dyn, err)) ||
        !(c->photons = gib_gpu_buffer(L, "photons.buffer",
                                      (uint64_t)PHOTON_BYTES * c->photon_capacity, NULL, 0, err)) ||
        !(c->first_t = gib_gpu_buffer(L, "photons.first_hit", 4ull * c->photon_capacity, NULL,
                                      dyn, err)) ||
        !(c->command = gib_gpu_buffer(L, "photons.command", sizeof COMMAND_RESET, COMMAND_RESET,
                                      dyn, err)) ||
        !(c->irradiance = gib_gpu_texture(L, "splat.irradiance", GL_TEXTURE_2D, c->splat_w,
                                          c->splat_h, 1, GL_RGBA32F, 1, err)))
        return -1;
    return 0;
}

/* The framebuffers: the splats' target, an attachment-less one at ray_res (lists and lines write
 * buffers only), and with layers = 4 the peeling's programs, depth and layer textures. */
static int create_targets(caustics *c, gib_error *err)
{
    glCreateFramebuffers(1, &c->splat_fbo);
    glNamedFramebufferTexture(c->splat_fbo, GL_COLOR_ATTACHMENT0, c->irradiance, 0);
    glCreateFramebuffers(1, &c->list_fbo);
    glNamedFramebufferParameteri(c->list_fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, c->ray_res);
    glNamedFramebufferParameteri(c->list_fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, c->ray_res);
    glCreateVertexArrays(1, &c->vao);
    if (!c->layers)
        return 0;
    const char *peel[] = {"common/gbuffer.vert", "ispm_caustics/peel.frag"};
    const char *lay[] = {"ispm_caustics/layers.comp"};
    if (!(c->peel_prog = gib_program(peel, 2, NULL, err)) ||
        !(c->layers_prog = gib_program(lay, 1, NULL, err)) ||
        !(c->layer_depth = gib_gpu_renderbuffer(c->ledger, "layers.zbuffer",
                                                GL_DEPTH_COMPONENT32F, c->ray_res, c->ray_res,
                                                err)))
        return -1;
    for (int k = 0; k < ISPM_LAYERS; k++)
        if (!(c->layer_tex[k] = gib_gpu_texture(c->ledger, "layers.depth_normal", GL_TEXTURE_2D,
                                                c->ray_res, c->ray_res, 1, GL_RGBA32F, 1, err)))
            return -1;
    glCreateFramebuffers(1, &c->layer_fbo);
    glNamedFramebufferRenderbuffer(c->layer_fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                   c->layer_depth);
    return 0;
}

static void *caustics_create(const gib_gpu_scene *scene, const gib_params *p, int w, int h,
                             gib_ledger *ledger, gib_error *err)
{
    caustics *c = calloc(1, sizeof *c);
    if (!c) {
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    c->scene = scene;
    c->ledger = ledger;
    c->width = w;
    c->height = h;
    int rsm_res = 0;
    read_params(c, p, &rsm_res);
    if (create_passes(c, rsm_res, err) < 0 || size_pool(c, p, err) < 0)
        goto fail;
    int faces = c->views.face_count > 0 ? c->views.face_count : 1;
    c->photon_capacity = (uint32_t)((uint64_t)faces * c->res_l * c->res_l);
    if (create_random(c, p, err) < 0 || create_buffers(c, rsm_res, faces, err) < 0 ||
        create_targets(c, err) < 0 || gib_gl_check("ispm_caustics create", err) < 0)
        goto fail;
    return c;
fail:
    caustics_destroy(c);
    return NULL;
}

/* The camera's axes scaled for list_lookup.glsl and the ray-resolution uniforms every list user
 * takes. */
static void list_uniforms(const caustics *c, const gib_view *v)
{
    const float *V = v->view, *P = v->proj;
    const float right[3] = {V[0] / P[0], V[4] / P[0], V[8] / P[0]};
    const float up[3] = {V[1] / P[5], V[5] / P[5], V[9] / P[5]};
    const float fwd[3] = {-V[2], -V[6], -V[10]};
    glUniformMatrix4fv(GIB_LOC_VIEW_PROJ, 1, GL_FALSE, v->view_proj);
    glUniform3fv(GIB_LOC_ORIGIN, 1, v->origin);
    glUniform3fv(ISPM_LOC_FORWARD, 1, fwd);
    glUniform1i(ISPM_LOC_RES, c->ray_res);
    glUniform3fv(ISPM_LOC_RIGHT_TAN, 1, right);
    glUniform3fv(ISPM_LOC_UP_TAN, 1, up);
}

/* What both list builders share: the status cleared, the scene rasterised from the camera at the
 * ray resolution with `prog` into `fbo`, every face kept (no culling, no blending). */
static void camera_pass_begin(caustics *c, const gib_view *view, const float fwd[3], unsigned fbo,
                              unsigned prog, gib_depth depth)
{
    const uint32_t zero = 0;
    glClearNamedBufferData(c->status_buf, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    gib_pass_apply(&(gib_pass_state){.fbo = fbo, .width = c->ray_res, .height = c->ray_res,
                                     .depth = depth});
    glUseProgram(prog);
    gib_gpu_scene_bind(c->scene);
    glUniformMatrix4fv(GIB_LOC_VIEW_PROJ, 1, GL_FALSE, view->view_proj);
    glUniform3fv(GIB_LOC_ORIGIN, 1, view->origin);
    glUniform3fv(ISPM_LOC_FORWARD, 1, fwd);
}

/* Algorithm 3.4: every fragment of the scene seen from the camera into its pixel's list. */
static void build_lists(caustics *c, const gib_view *view, const float fwd[3])
{
    const uint32_t ones = 0xffffffffu, zero = 0;
    glClearNamedBufferData(c->heads, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &ones);
    glClearNamedBufferData(c->counts, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    camera_pass_begin(c, view, fwd, c->list_fbo, c->list_prog, GIB_DEPTH_OFF);
    glUniform1i(ISPM_LOC_RES, c->ray_res);
    glUniform1ui(ISPM_LIST_LOC_CAPACITY, c->node_capacity);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_HEADS, c->heads);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_NODES, c->nodes);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_STATUS, c->status_buf);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_COUNTS, c->counts);
    gib_gpu_scene_draw(c->scene);
    gib_pass_end();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

/* The 4-layer variant: 4 peeling passes, then the layers as lists of at most 4 nodes. */
static void build_layers(caustics *c, const gib_view *view, const float fwd[3])
{
    camera_pass_begin(c, view, fwd, c->layer_fbo, c->peel_prog, GIB_DEPTH_LESS);
    const float none[4] = {0, 0, 0, 0};
    for (int k = 0; k < ISPM_LAYERS; k++) {
        glNamedFramebufferTexture(c->layer_fbo, GL_COLOR_ATTACHMENT0, c->layer_tex[k], 0);
        glClearBufferfv(GL_COLOR, 0, none);
        glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
        glUniform1i(ISPM_PEEL_LOC_LAYER, k);
        glBindTextureUnit(ISPM_UNIT_PREV_LAYER, c->layer_tex[k > 0 ? k - 1 : 0]);
        gib_gpu_scene_draw(c->scene);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    }
    gib_pass_end();
    glUseProgram(c->layers_prog);
    for (int k = 0; k < ISPM_LAYERS; k++)
        glBindTextureUnit(ISPM_UNIT_LAYER_FIRST + k, c->layer_tex[k]);
    glUniform1i(ISPM_LOC_RES, c->ray_res);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_HEADS, c->heads);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_NODES, c->nodes);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_STATUS, c->status_buf);
    glDispatchCompute(gib_groups((unsigned)c->ray_res, GIB_GROUP_2D),
                      gib_groups((unsigned)c->ray_res, GIB_GROUP_2D), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

/* The specular mask and its mips (Fig. 3.5), from the bound light views. */
static void build_mask(caustics *c)
{
    glUseProgram(c->mip_prog);
    int faces = c->views.face_count;
    for (int l = 0; l <= c->level && faces > 0; l++) {
        int res = c->views.res >> l;
        glBindImageTexture(ISPM_MIP_IMAGE_DST, c->mask, l, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
        glBindImageTexture(ISPM_MIP_IMAGE_SRC, c->mask, l > 0 ? l - 1 : 0, GL_TRUE, 0,
                           GL_READ_ONLY, GL_R32F);
        glUniform1i(ISPM_MIP_LOC_LEVEL, l);
        glUniform1i(ISPM_MIP_LOC_RES, res);
        glDispatchCompute(gib_groups((unsigned)res, GIB_GROUP_2D),
                          gib_groups((unsigned)res, GIB_GROUP_2D), (unsigned)faces);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
}

/* Emission (Sec. 3.3.1): a photon per fully specular texel of the mask's level, counted into the
 * draw command. */
static void emit_photons(caustics *c, const gib_view *view, const float fwd[3])
{
    const uint32_t ones = 0xffffffffu;
    glNamedBufferSubData(c->command, 0, sizeof COMMAND_RESET, COMMAND_RESET);
    glClearNamedBufferData(c->first_t, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &ones);
    glUseProgram(c->emit_prog);
    gib_gpu_scene_bind(c->scene);
    glBindTextureUnit(ISPM_EMIT_UNIT_MASK, c->mask);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_PHOTONS, c->photons);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_RANDOM, c->random);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_COMMAND, c->command);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_STATUS, c->status_buf);
    glUniform1i(ISPM_EMIT_LOC_LEVEL, c->level);
    glUniform1i(ISPM_EMIT_LOC_RES, c->res_l);
    glUniform1ui(ISPM_EMIT_LOC_CAPACITY, c->photon_capacity);
    glUniform3fv(ISPM_EMIT_LOC_EYE, 1, view->origin);
    glUniform3fv(ISPM_EMIT_LOC_FORWARD, 1, fwd);
    glUniform1f(ISPM_EMIT_LOC_PIXEL_SCALE, 2.0f / ((float)c->ray_res * view->proj[5]));
    glUniform1f(ISPM_EMIT_LOC_TMIN_FLOOR, 1e-4f * c->diag);
    if (c->views.face_count > 0)
        glDispatchCompute(gib_groups((unsigned)c->res_l, GIB_GROUP_2D),
                          gib_groups((unsigned)c->res_l, GIB_GROUP_2D),
                          (unsigned)c->views.face_count);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

/* Algorithm 3.5: the photons' lines against the lists, then each photon's hit, normal and splat
 * radius (resolve.comp). */
static void trace_photons(caustics *c, const gib_view *view)
{
    const float tmax = 2.0f * c->diag;
    gib_pass_apply(&(gib_pass_state){.fbo = c->list_fbo, .width = c->ray_res,
                                     .height = c->ray_res});
    glUseProgram(c->trace_prog);
    list_uniforms(c, view);
    glUniform1f(ISPM_TRACE_LOC_TMAX, tmax);
    glUniform1ui(ISPM_TRACE_LOC_CAPACITY, c->photon_capacity);
    glUniform1f(ISPM_TRACE_LOC_SLACK, c->slack);
    glUniform1f(ISPM_TRACE_LOC_DEPTH, c->hit_depth > 0.0f ? c->hit_depth : 1e30f);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_HEADS, c->heads);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_NODES, c->nodes);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_PHOTONS, c->photons);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_FIRST_HIT, c->first_t);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, c->command);
    glBindVertexArray(c->vao);
    glDrawArraysIndirect(GL_LINES, NULL);
    gib_pass_end();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(c->resolve_prog);
    list_uniforms(c, view);
    glUniform1f(ISPM_TRACE_LOC_TMAX, tmax);
    glUniform1ui(ISPM_TRACE_LOC_CAPACITY, c->photon_capacity);
    glUniform1f(ISPM_RESOLVE_LOC_SPLAT_SCALE, c->splat_scale);
    glUniform1f(ISPM_RESOLVE_LOC_HMAX, 0.1f * c->diag);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_COMMAND, c->command);
    glDispatchCompute(gib_groups(c->photon_capacity, GIB_GROUP_1D), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

/* Splatting (Sec. 3.3.2.3): Gaussian disks summed into the irradiance target over `sg`. */
static void splat_photons(caustics *c, const gib_view *view, const gib_gbuffer *sg)
{
    gib_pass_apply(&(gib_pass_state){.fbo = c->splat_fbo, .width = c->splat_w,
                                     .height = c->splat_h, .blend = GIB_BLEND_ADD});
    const float black[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, black);
    glUseProgram(c->splat_prog);
    glUniformMatrix4fv(GIB_LOC_VIEW_PROJ, 1, GL_FALSE, view->view_proj);
    glUniform3fv(GIB_LOC_ORIGIN, 1, view->origin);
    glUniform1f(ISPM_SPLAT_LOC_DELTA, c->delta);
    glBindTextureUnit(GIB_UNIT_GBUF_POSITION, sg->position);
    glBindTextureUnit(GIB_UNIT_GBUF_NORMAL, sg->normal);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ISPM_SSBO_PHOTONS, c->photons);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, c->command);
    glBindVertexArray(c->vao);
    glDrawArraysIndirect(GL_POINTS, (const void *)(uintptr_t)(4 * sizeof(uint32_t)));
    glBindVertexArray(0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    gib_pass_end();
}

/* Radiance rho_d / pi E into `fbo`, upsampled bilaterally when the splats were smaller. */
static void shade(caustics *c, const gib_view *view, unsigned fbo, const gib_gbuffer *sg)
{
    gib_fullscreen_begin(&c->shade, fbo, c->width, c->height, 0);
    gib_gbuffer_bind(&c->gbuffer);
    glBindTextureUnit(ISPM_SHADE_UNIT_IRRADIANCE, c->irradiance);
    glBindTextureUnit(ISPM_SHADE_UNIT_LOW_POSITION, sg->position);
    glBindTextureUnit(ISPM_SHADE_UNIT_LOW_NORMAL, sg->normal);
    glUniform1i(ISPM_SHADE_LOC_DIVISOR, c->divisor);
    glUniform3fv(ISPM_SHADE_LOC_EYE, 1, view->origin);
    gib_fullscreen_draw(&c->shade);
    gib_fullscreen_end();
}

static int caustics_render(void *self, const gib_view *view, gib_timers *timers,
                           const gib_image_target *targets, int target_count, gib_error *err)
{
    caustics *c = self;
    if (target_count != 1)
        return gib_fail(err, "ispm_caustics renders one component, was given %d targets",
                        target_count);
    const float *V = view->view;
    const float fwd[3] = {-V[2], -V[6], -V[10]};
    gib_gbuffer_render(&c->gbuffer, c->scene, view, timers, "gbuffer");
    if (c->divisor > 1) {
        gib_view lv = *view;
        lv.width = c->splat_w;
        lv.height = c->splat_h;
        gib_gbuffer_render(&c->low, c->scene, &lv, timers, "gbuffer");
    }
    gib_light_views_render(&c->views, c->scene, timers, "rsm");
    redraw_random(c, timers);

    gib_timer_begin(timers, "list_build");
    if (c->layers)
        build_layers(c, view, fwd);
    else
        build_lists(c, view, fwd);
    gib_timer_end(timers);

    gib_timer_begin(timers, "photon_tracing");
    gib_light_views_bind(&c->views);
    build_mask(c);
    emit_photons(c, view, fwd);
    trace_photons(c, view);
    gib_timer_end(timers);

    const gib_gbuffer *sg = c->divisor > 1 ? &c->low : &c->gbuffer;
    gib_timer_begin(timers, "splatting");
    splat_photons(c, view, sg);
    gib_timer_end(timers);

    gib_timer_begin(timers, "upsampling");
    shade(c, view, targets[0].fbo, sg);
    gib_timer_end(timers);
    return gib_gl_check("ispm_caustics", err);
}

int ispm_caustics_read_photons(void *self, ispm_photon **out)
{
    caustics *c = self;
    uint32_t cmd[8];
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(c->command, 0, sizeof cmd, cmd);
    uint32_t n = cmd[1] < c->photon_capacity ? cmd[1] : c->photon_capacity;
    *out = malloc(sizeof **out * (n ? n : 1));
    if (!*out)
        return -1;
    if (n)
        glGetNamedBufferSubData(c->photons, 0, (GLsizeiptr)(sizeof **out * n), *out);
    return (int)n;
}

/* photons: how many the mask's mip level emitted this frame (Algorithm 3.3), the count the
 * thesis' Tables 4.1-4.5 are indexed by. */
static void caustics_counters(void *self, char *buf, size_t len)
{
    caustics *c = self;
    uint32_t cmd[8];
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(c->command, 0, sizeof cmd, cmd);
    snprintf(buf, len, "photons=%u", cmd[1]);
}

/* `overflow` when the lists' pool ran out; `no_photons` when the mask's level emitted none (no
 * specular texel whose 4^level texels below are all specular): the caustic image is then black by
 * construction, a status of its own rather than an error score. */
static gib_status caustics_status(void *self)
{
    caustics *c = self;
    uint32_t st[3], cmd[8];
    glGetNamedBufferSubData(c->status_buf, 0, sizeof st, st);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(c->command, 0, sizeof cmd, cmd);
    if (st[1] || st[2])
        return GIB_STATUS_OVERFLOW;
    return cmd[1] == 0 ? GIB_STATUS_NO_PHOTONS : GIB_STATUS_OK;
}

static const char *const caustics_passes[] = {"gbuffer", "rsm", "list_build", "photon_tracing",
    "random_redraw", "splatting", "upsampling", NULL};

const gib_technique gib_technique_ispm_caustics = {
    .name = "ispm_caustics",
    .source = "Le Hoang Quyen 2014 (thesis), Sec. 3.3, Algorithms 3.3-3.5 (caustic photons "
              "through per-pixel linked lists)",
    .components = GIB_OUT_CAUSTIC,
    .params = caustics_params,
    .rules = caustics_rules,
    .passes = caustics_passes,
    .scene_needs_any = GIB_FEAT_SPECULAR | GIB_FEAT_MIRROR,
    .create = caustics_create,
    .render = caustics_render,
    .status = caustics_status,
    .counters = caustics_counters,
    .destroy = caustics_destroy,
};

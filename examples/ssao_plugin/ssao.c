/* An example gibench technique built outside gibench's repository, as a plugin: `ssao`, plain
 * screen-space ambient occlusion against the depth buffer of the shared G-buffer pass.
 *
 * Per pixel: the G-buffer's world position P and viewer-facing normal N; `samples` directions
 * drawn cosine-weighted over the hemisphere around N (a per-pixel hash rotates the set), each
 * marched in `steps` points out to d_max. A point that projects into the image BEHIND the surface
 * the G-buffer holds there (deeper along the view axis than that surface, by less than d_max) is
 * taken as a hit: the direction is occluded. AO = the unoccluded fraction, which for a
 * cosine-weighted set estimates the reference `ao` (1/pi) int V cos, V = 0 when a hit lies within
 * d_max (ARCHITECTURE.md, "The technique contract": a technique outputting `ao` binds its range
 * to the reference's dmax). What it cannot see: anything off screen or behind the front-most
 * layer. Pixels where nothing was hit get 0, as the reference.
 *
 * Build it against an installed gibench (docs/adding-a-technique.md, "As a plugin"):
 *   cmake -S . -B build -DCMAKE_PREFIX_PATH=<prefix> && cmake --build build
 *   gibench --plugin build/ssao.so check-technique ssao
 * It links nothing: the gib_* functions and glad's GL pointers resolve in the gibench executable. */
#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>

#include "harness/gl/bindings.h"
#include "harness/gl/context.h"
#include "techniques/common/gbuffer.h"
#include "techniques/common/pass_state.h"
#include "techniques/technique.h"

/* The version of the contract this plugin reports; GIB_CONTRACT_VERSION_OVERRIDE builds a plugin
 * that claims another one (tests/plugins/: gibench must refuse it). */
#ifdef GIB_CONTRACT_VERSION_OVERRIDE
#define SSAO_CONTRACT_VERSION GIB_CONTRACT_VERSION_OVERRIDE
#else
#define SSAO_CONTRACT_VERSION GIB_CONTRACT_VERSION
#endif
/* The technique's name; tests/plugins/ builds one named after a built-in, which gibench refuses. */
#ifndef SSAO_NAME
#define SSAO_NAME "ssao"
#endif

/* Uniform locations of the AO pass. */
enum { LOC_EYE = 0, LOC_FORWARD, LOC_VIEW_PROJ, LOC_DMAX, LOC_SAMPLES, LOC_STEPS };

static const char vertex_glsl[] =
    "#version 450 core\n"
    "void main() {\n" /* one triangle covering the viewport */
    "    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
    "    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
    "}\n";

/* After "#version 450 core" and the units' defines. */
static const char fragment_glsl[] =
    "layout(binding = UNIT_POSITION) uniform sampler2D g_position;\n"
    "layout(binding = UNIT_NORMAL) uniform sampler2D g_normal;\n"
    "layout(location = 0) uniform vec3 u_eye;\n"
    "layout(location = 1) uniform vec3 u_forward;\n"
    "layout(location = 2) uniform mat4 u_view_proj;\n" /* relative to u_eye */
    "layout(location = 3) uniform float u_dmax;\n"
    "layout(location = 4) uniform int u_samples;\n"
    "layout(location = 5) uniform int u_steps;\n"
    "layout(location = 0) out vec4 o_ao;\n"
    "uint pcg(uint v) {\n" /* Jarzynski and Olano 2020: the same image every frame */
    "    uint s = v * 747796405u + 2891336453u;\n"
    "    uint w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;\n"
    "    return (w >> 22u) ^ w;\n"
    "}\n"
    "float unit(inout uint h) { h = pcg(h); return float(h >> 8) / 16777216.0; }\n"
    "void main() {\n"
    "    ivec2 px = ivec2(gl_FragCoord.xy);\n"
    "    vec4 pos = texelFetch(g_position, px, 0);\n"
    "    if (pos.w < 0.5) { o_ao = vec4(0.0, 0.0, 0.0, 1.0); return; }\n"
    "    vec3 N = normalize(texelFetch(g_normal, px, 0).xyz);\n"
    "    vec3 T = normalize(abs(N.x) > 0.5 ? cross(N, vec3(0, 1, 0)) : cross(N, vec3(1, 0, 0)));\n"
    "    vec3 B = cross(N, T);\n"
    "    ivec2 size = textureSize(g_position, 0);\n"
    "    uint h = pcg(uint(px.x) + 65536u * uint(px.y));\n"
    "    vec3 origin = pos.xyz + N * (1e-3 * u_dmax);\n"
    "    float open = 0.0;\n"
    "    for (int i = 0; i < u_samples; i++) {\n"
    "        float r = sqrt((float(i) + unit(h)) / float(u_samples));\n" /* stratified, cosine */
    "        float phi = 6.28318530718 * unit(h);\n"
    "        vec3 dir = T * (r * cos(phi)) + B * (r * sin(phi)) + N * sqrt(max(1.0 - r * r, 0.0));\n"
    "        float hit = 0.0;\n"
    "        float jitter = unit(h);\n"
    "        for (int k = 0; k < u_steps && hit == 0.0; k++) {\n"
    "            vec3 s = origin + dir * (u_dmax * (float(k) + jitter) / float(u_steps));\n"
    "            vec4 clip = u_view_proj * vec4(s - u_eye, 1.0);\n"
    "            if (clip.w <= 0.0) break;\n"
    "            vec2 uv = clip.xy / clip.w * 0.5 + 0.5;\n"
    "            if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) break;\n"
    "            vec4 q = texelFetch(g_position, ivec2(uv * vec2(size)), 0);\n"
    "            if (q.w < 0.5) continue;\n"
    "            float ds = dot(s - u_eye, u_forward), dq = dot(q.xyz - u_eye, u_forward);\n"
    "            if (ds > dq + 1e-3 * u_dmax && ds - dq < u_dmax) hit = 1.0;\n"
    "        }\n"
    "        open += 1.0 - hit;\n"
    "    }\n"
    "    float ao = open / float(u_samples);\n"
    "    o_ao = vec4(ao, ao, ao, 1.0);\n"
    "}\n";

typedef struct ssao {
    gib_ledger *ledger;
    const gib_gpu_scene *scene;
    gib_gbuffer gbuffer;
    unsigned program, vao;
    float dmax;
    int samples, steps;
} ssao;

static const gib_param_spec ssao_params[] = {
    {"dmax", GIB_PARAM_LENGTH, 0.1, 1e-6, 1e9,
     "occluder range d_max in scene units; finite: the search marches out to it on screen"},
    {"samples", GIB_PARAM_INT, 16, 1, 256, "hemisphere directions per pixel (cosine-weighted)"},
    {"steps", GIB_PARAM_INT, 4, 1, 64, "points marched along each direction out to d_max"},
    {0},
};

extern const gib_technique ssao_technique;
static void ssao_destroy(void *self);

static unsigned compile(unsigned stage, const char *const *parts, int count, gib_error *err)
{
    unsigned s = glCreateShader(stage);
    glShaderSource(s, count, parts, NULL);
    glCompileShader(s);
    int ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        glDeleteShader(s);
        gib_fail(err, "ssao: shader does not compile: %s", log);
        return 0;
    }
    return s;
}

static unsigned build_program(gib_error *err)
{
    char header[160];
    snprintf(header, sizeof header,
             "#version 450 core\n#define UNIT_POSITION %d\n#define UNIT_NORMAL %d\n",
             GIB_UNIT_GBUF_POSITION, GIB_UNIT_GBUF_NORMAL);
    const char *vs_parts[] = {vertex_glsl};
    const char *fs_parts[] = {header, fragment_glsl};
    unsigned vs = compile(GL_VERTEX_SHADER, vs_parts, 1, err);
    unsigned fs = vs ? compile(GL_FRAGMENT_SHADER, fs_parts, 2, err) : 0;
    if (!fs) {
        if (vs)
            glDeleteShader(vs);
        return 0;
    }
    unsigned p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    int ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        glGetProgramInfoLog(p, sizeof log, NULL, log);
        glDeleteProgram(p);
        gib_fail(err, "ssao: program does not link: %s", log);
        return 0;
    }
    return p;
}

static void *ssao_create(const gib_gpu_scene *scene, const gib_params *p, int width, int height,
                         gib_ledger *ledger, gib_error *err)
{
    ssao *s = calloc(1, sizeof *s);
    if (!s) {
        gib_fail(err, "ssao: out of memory");
        return NULL;
    }
    s->ledger = ledger;
    s->scene = scene;
    s->dmax = (float)gib_param_float(&ssao_technique, p, "dmax");
    s->samples = gib_param_int(&ssao_technique, p, "samples");
    s->steps = gib_param_int(&ssao_technique, p, "steps");
    if (gib_gbuffer_create(&s->gbuffer, width, height, ledger, err) < 0 ||
        !(s->program = build_program(err))) {
        ssao_destroy(s);
        return NULL;
    }
    glCreateVertexArrays(1, &s->vao);
    return s;
}

static int ssao_render(void *self, const gib_view *view, gib_timers *timers,
                       const gib_image_target *targets, int target_count, gib_error *err)
{
    ssao *s = self;
    if (target_count != 1)
        return gib_fail(err, "ssao renders one component, was given %d targets", target_count);
    gib_gbuffer_render(&s->gbuffer, s->scene, view, timers, "gbuffer");

    gib_timer_begin(timers, "ssao");
    gib_pass_apply(&(gib_pass_state){.fbo = targets[0].fbo, .width = view->width,
                                     .height = view->height});
    gib_gbuffer_bind(&s->gbuffer);
    glUseProgram(s->program);
    /* view->view's third row is minus the viewing direction (GL looks down -z) */
    const float forward[3] = {-view->view[2], -view->view[6], -view->view[10]};
    glUniform3fv(LOC_EYE, 1, view->origin);
    glUniform3fv(LOC_FORWARD, 1, forward);
    glUniformMatrix4fv(LOC_VIEW_PROJ, 1, GL_FALSE, view->view_proj);
    glUniform1f(LOC_DMAX, s->dmax);
    glUniform1i(LOC_SAMPLES, s->samples);
    glUniform1i(LOC_STEPS, s->steps);
    glBindVertexArray(s->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
    gib_pass_end();
    gib_timer_end(timers);
    return gib_gl_check("ssao", err);
}

static void ssao_destroy(void *self)
{
    ssao *s = self;
    if (!s)
        return;
    gib_gbuffer_destroy(&s->gbuffer, s->ledger);
    if (s->program)
        glDeleteProgram(s->program);
    if (s->vao)
        glDeleteVertexArrays(1, &s->vao);
    free(s);
}

static const gib_ref_binding ssao_reference[] = {
    {GIB_OUT_AO, GIB_REF_AO_DMAX, "dmax"},
    {0},
};

static const char *const ssao_passes[] = {"gbuffer", "ssao", NULL};

const gib_technique ssao_technique = {
    .name = SSAO_NAME,
    .source = "example plugin: screen-space AO, cosine-weighted hemisphere rays marched against "
              "the G-buffer's depth (examples/ssao_plugin)",
    .components = GIB_OUT_AO,
    .params = ssao_params,
    .passes = ssao_passes,
    .reference = ssao_reference,
    .create = ssao_create,
    .render = ssao_render,
    .destroy = ssao_destroy,
};

/* The plugin's one entry point (techniques/technique.h, gib_plugin_entry_fn). */
GIB_PLUGIN_EXPORT const gib_technique *const *gib_plugin_techniques(int *count,
                                                                    int *contract_version)
{
    static const gib_technique *const list[] = {&ssao_technique};
    *count = 1;
    *contract_version = SSAO_CONTRACT_VERSION;
    return list;
}

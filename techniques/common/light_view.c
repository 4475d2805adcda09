#include "light_view.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "techniques/common/common_slots.h"
#include "techniques/common/pass_state.h"
#include "techniques/common/shader.h"

/* GL's cube-map face order, with up vectors giving each face a right-handed view. */
static const float face_dir[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const float face_up[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

static const char *const packed_name[2] = {"radiance_depth", "normal_nl"};

static const struct {
    unsigned bit, format;
    const char *name;
} attribute[GIB_LV_ATTRIBUTE_COUNT] = {
    {GIB_LV_DEPTH, GL_R32F, "depth"},       {GIB_LV_POSITION, GL_RGBA32F, "position"},
    {GIB_LV_NORMAL, GL_RGBA32F, "normal"},  {GIB_LV_FLUX, GL_RGBA32F, "flux"},
    {GIB_LV_SPECULAR, GL_RGBA32F, "specular"},
};

int gib_light_view_kind(const gib_light *l)
{
    if (l->type == GIB_LIGHT_DIRECTIONAL)
        return GIB_LV_ORTHO;
    if (l->type == GIB_LIGHT_SPOT && l->spot_outer_deg <= 45.0f)
        return GIB_LV_PERSPECTIVE;
    return GIB_LV_CUBE;
}

static void cross3(const float a[3], const float b[3], float o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* Sets every face's view and each light's texel size from the lights and the scene's bounds. */
static void set_up_views(gib_light_views *lv, const gib_scene *s)
{
    float c[3], r;
    gib_view_bounding_sphere(s, c, &r);
    int f = 0;
    for (uint32_t i = 0; i < s->light_count; i++) {
        const gib_light *l = &s->lights[i];
        int kind = gib_light_view_kind(l);
        lv->first_face[i] = f;
        if (!lv->faces_of[i])
            continue;
        float view[16], proj[16];
        if (kind == GIB_LV_ORTHO) {
            gib_lv_face *face = &lv->faces[f++];
            face->light = (int)i;
            face->kind = kind;
            float t[3], b[3];
            gib_ortho_basis(l->direction, t, b);
            const float zero[3] = {0, 0, 0};
            gib_mat4_view(t, b, l->direction, zero, view);
            gib_mat4_ortho_reversed(-r, r, -r, r, 0, 2 * r, proj);
            gib_mat4_mul(proj, view, face->view_proj);
            for (int k = 0; k < 3; k++) {
                face->origin[k] = c[k] - l->direction[k] * r;
                face->forward[k] = l->direction[k];
                face->right[k] = t[k];
                face->up[k] = b[k];
            }
            lv->texel[i] = 2 * r / (float)lv->res;
            continue;
        }
        float far = 0;
        for (int k = 0; k < 3; k++)
            far += (l->position[k] - c[k]) * (l->position[k] - c[k]);
        far = sqrtf(far) + r;
        float half = kind == GIB_LV_CUBE ? (float)M_PI / 4 : l->spot_outer_deg * (float)M_PI / 180;
        gib_mat4_perspective_reversed(2 * half, 1.0f, far * 1e-5f, far, proj);
        lv->texel[i] = 2 * tanf(half) / (float)lv->res;
        for (int k = 0; k < (kind == GIB_LV_CUBE ? 6 : 1); k++) {
            gib_lv_face *face = &lv->faces[f++];
            face->light = (int)i;
            face->kind = kind;
            float right[3], up[3];
            const float *d = kind == GIB_LV_CUBE ? face_dir[k] : l->direction;
            if (kind == GIB_LV_CUBE) {
                cross3(d, face_up[k], right);
                cross3(right, d, up);
            } else {
                gib_ortho_basis(d, right, up);
            }
            const float zero[3] = {0, 0, 0};
            gib_mat4_view(right, up, d, zero, view);
            gib_mat4_mul(proj, view, face->view_proj);
            memcpy(face->origin, l->position, sizeof face->origin);
            memcpy(face->forward, d, sizeof face->forward);
            memcpy(face->right, right, sizeof face->right);
            memcpy(face->up, up, sizeof face->up);
        }
    }
    /* The table light_view.glsl reads: a header, 2 vec4 per light, 7 vec4 per face. */
    float *t = lv->table_data;
    int n = (int)s->light_count;
    t[0] = (float)n;
    t[1] = (float)lv->face_count;
    t[2] = (float)lv->res;
    t[3] = 0;
    for (int i = 0; i < n; i++) {
        float *e = t + 4 + 8 * i;
        memset(e, 0, 8 * sizeof(float));
        e[0] = (float)lv->first_face[i];
        e[1] = GIB_LV_KIND_NONE;
        if (!lv->faces_of[i])
            continue;
        const gib_lv_face *first = &lv->faces[lv->first_face[i]];
        e[1] = (float)first->kind;
        e[2] = lv->texel[i];
        memcpy(e + 4, first->origin, 3 * sizeof(float));
    }
    for (int k = 0; k < lv->face_count; k++) {
        float *e = t + 4 + 8 * n + 28 * k;
        memcpy(e, lv->faces[k].view_proj, 16 * sizeof(float));
        memcpy(e + 16, lv->faces[k].forward, 3 * sizeof(float));
        memcpy(e + 20, lv->faces[k].right, 3 * sizeof(float));
        memcpy(e + 24, lv->faces[k].up, 3 * sizeof(float));
        e[19] = e[23] = e[27] = 0;
    }
}

int gib_light_views_create(gib_light_views *lv, const gib_gpu_scene *gpu, int res,
                           unsigned attributes, const char *label, gib_ledger *ledger,
                           gib_error *err)
{
    memset(lv, 0, sizeof *lv);
    const gib_scene *s = gpu->scene;
    lv->res = res;
    lv->packed = (attributes & GIB_LV_PACKED16) != 0;
    lv->attributes = lv->packed ? 0 : (attributes | GIB_LV_DEPTH) & ((1u << GIB_LV_ATTRIBUTE_COUNT) - 1);
    uint32_t n = s->light_count;
    lv->first_face = calloc(n ? n : 1, sizeof *lv->first_face);
    lv->faces_of = calloc(n ? n : 1, sizeof *lv->faces_of);
    if (!lv->first_face || !lv->faces_of)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    for (uint32_t i = 0; i < n; i++) {
        int kind = gib_light_view_kind(&s->lights[i]);
        if (kind == GIB_LV_ORTHO && (attributes & GIB_LV_LOCAL_LIGHTS_ONLY))
            continue;
        lv->faces_of[i] = kind == GIB_LV_CUBE ? 6 : 1;
        lv->face_count += lv->faces_of[i];
    }
    lv->table_floats = 4 + 8 * (int)n + 28 * lv->face_count;
    lv->faces = calloc(lv->face_count ? lv->face_count : 1, sizeof *lv->faces);
    lv->texel = calloc(n ? n : 1, sizeof *lv->texel);
    lv->table_data = calloc((size_t)lv->table_floats, sizeof(float));
    if (!lv->faces || !lv->texel || !lv->table_data)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    const char *files[] = {"common/gbuffer.vert", "common/light_view.frag"};
    if (!(lv->program = gib_program(files, 2, lv->packed ? "#define PACKED16 1\n" : NULL, err)))
        return -1;
    char name[96];
    snprintf(name, sizeof name, "%s.table", label);
    set_up_views(lv, s);
    if (!(lv->table = gib_gpu_buffer(ledger, name, sizeof(float) * (uint64_t)lv->table_floats,
                                     lv->table_data, GL_DYNAMIC_STORAGE_BIT, err)))
        return -1;
    /* Without a light, one small layer keeps the samplers complete. */
    int layers = lv->face_count ? lv->face_count : 1, side = lv->face_count ? res : 1;
    GLenum draw[GIB_LV_ATTRIBUTE_COUNT];
    glCreateFramebuffers(1, &lv->fbo);
    for (int a = 0; a < GIB_LV_ATTRIBUTE_COUNT; a++) {
        draw[a] = GL_NONE;
        if (lv->packed ? a >= 2 : !(lv->attributes & attribute[a].bit))
            continue;
        snprintf(name, sizeof name, "%s.%s", label, lv->packed ? packed_name[a] : attribute[a].name);
        if (!(lv->textures[a] = gib_gpu_texture(ledger, name, GL_TEXTURE_2D_ARRAY, side, side, layers,
                                                lv->packed ? GL_RGBA16F : attribute[a].format,
                                                lv->packed ? 0 : 1, err)))
            return -1;
        /* Nearest: shadow lookups filter binary comparisons (PCF), and RSM texels are samples. */
        glTextureParameteri(lv->textures[a], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(lv->textures[a], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(lv->textures[a], GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(lv->textures[a], GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        draw[a] = GL_COLOR_ATTACHMENT0 + (GLenum)a;
    }
    glNamedFramebufferDrawBuffers(lv->fbo, GIB_LV_ATTRIBUTE_COUNT, draw);
    snprintf(name, sizeof name, lv->packed ? "%s_raster.zbuffer" : "%s.zbuffer", label);
    if (!(lv->depth = gib_gpu_renderbuffer(ledger, name, GL_DEPTH_COMPONENT32F, res, res, err)))
        return -1;
    glNamedFramebufferRenderbuffer(lv->fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, lv->depth);
    return gib_gl_check("light view creation", err);
}

void gib_light_views_render(gib_light_views *lv, const gib_gpu_scene *gpu, gib_timers *timers,
                            const char *pass)
{
    if (!lv->face_count)
        return;
    gib_timer_begin(timers, pass);
    set_up_views(lv, gpu->scene);
    glNamedBufferSubData(lv->table, 0, sizeof(float) * (GLsizeiptr)lv->table_floats,
                         lv->table_data);
    gib_pass_apply(&(gib_pass_state){.fbo = lv->fbo, .width = lv->res, .height = lv->res,
                                     .depth = GIB_DEPTH_REVERSED});
    glUseProgram(lv->program);
    gib_gpu_scene_bind(gpu);
    /* Empty texels: depth +inf (the first attribute, or the packed depth in w), the rest 0. */
    const float far[4] = {INFINITY, INFINITY, INFINITY, INFINITY}, zero[4] = {0, 0, 0, 0},
                far_packed[4] = {0, 0, 0, INFINITY};
    for (int f = 0; f < lv->face_count; f++) {
        const gib_lv_face *face = &lv->faces[f];
        for (int a = 0; a < GIB_LV_ATTRIBUTE_COUNT; a++)
            if (lv->textures[a])
                glNamedFramebufferTextureLayer(lv->fbo, GL_COLOR_ATTACHMENT0 + (GLenum)a,
                                               lv->textures[a], 0, f);
        for (int a = 0; a < GIB_LV_ATTRIBUTE_COUNT; a++)
            if (lv->textures[a])
                glClearBufferfv(GL_COLOR, a, a > 0 ? zero : lv->packed ? far_packed : far);
        const float farthest = 0; /* reversed depth (pass_state.h): 0 is the far plane */
        glClearBufferfv(GL_DEPTH, 0, &farthest);
        glUniformMatrix4fv(GIB_LOC_VIEW_PROJ, 1, GL_FALSE, face->view_proj);
        glUniform3fv(GIB_LOC_ORIGIN, 1, face->origin);
        glUniform3fv(GIB_LV_LOC_FORWARD, 1, face->forward);
        glUniform1i(GIB_LV_LOC_KIND, face->kind);
        glUniform1i(GIB_LV_LOC_LIGHT, face->light);
        glUniform1f(GIB_LV_LOC_TEXEL, lv->texel[face->light]);
        gib_gpu_scene_draw(gpu);
    }
    gib_pass_end();
    gib_timer_end(timers);
}

void gib_light_views_bind(const gib_light_views *lv)
{
    for (int a = 0; a < GIB_LV_ATTRIBUTE_COUNT; a++)
        if (lv->textures[a])
            glBindTextureUnit(GIB_UNIT_LV_DEPTH + a, lv->textures[a]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_SSBO_LIGHT_VIEWS, lv->table);
}

void gib_light_views_destroy(gib_light_views *lv, gib_ledger *ledger)
{
    if (lv->fbo)
        glDeleteFramebuffers(1, &lv->fbo);
    if (lv->program)
        glDeleteProgram(lv->program);
    for (int a = 0; a < GIB_LV_ATTRIBUTE_COUNT; a++)
        if (lv->textures[a])
            gib_gpu_free(ledger, lv->textures[a], 1);
    if (lv->depth)
        gib_gpu_free(ledger, lv->depth, 2);
    if (lv->table)
        gib_gpu_free(ledger, lv->table, 0);
    free(lv->faces);
    free(lv->first_face);
    free(lv->faces_of);
    free(lv->texel);
    free(lv->table_data);
    memset(lv, 0, sizeof *lv);
}

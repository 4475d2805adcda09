#include "gpu_scene.h"

#include <glad/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness/imaging/image.h"
#include "context.h"

/* Textures are linear floats in the scene model; on the GPU they are sRGB8 (the 8-bit data they came
 * from), decoded by the sampler, so filtering happens on linear values as in the path tracer. */
static unsigned upload_texture(gib_gpu_scene *gpu, const gib_texture *t, int srgb, gib_error *err)
{
    size_t n = (size_t)t->width * t->height;
    unsigned char *bytes = malloc(n * 4);
    if (!bytes) {
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory uploading texture '%s'", t->path);
        return 0;
    }
    for (size_t i = 0; i < n * 4; i++) {
        float v = t->rgba[i];
        if (srgb && (i & 3) != 3)
            v = gib_srgb_encode(v);
        v = v < 0 ? 0 : v > 1 ? 1 : v;
        bytes[i] = (unsigned char)lrintf(v * 255.0f);
    }
    unsigned tex = gib_gpu_texture(&gpu->ledger, "scene.textures", GL_TEXTURE_2D, t->width,
                                   t->height, 1, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, 0, err);
    if (tex) {
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTextureSubImage2D(tex, 0, 0, 0, t->width, t->height, GL_RGBA, GL_UNSIGNED_BYTE, bytes);
        glGenerateTextureMipmap(tex);
        glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
    }
    free(bytes);
    return tex;
}

static unsigned upload_array(gib_gpu_scene *gpu, const char *label, const void *data, size_t bytes,
                             gib_error *err)
{
    return gib_gpu_buffer(&gpu->ledger, label, bytes, data, 0, err);
}

/* Vertices of the largest moving mesh, twice (positions, normals); a 1-float placeholder for a
 * static scene. */
static float *pose_room(const gib_scene *s, gib_error *err)
{
    size_t most = 0;
    for (uint32_t i = 0; i < s->motion_count; i++)
        most = s->motions[i].vertex_count > most ? s->motions[i].vertex_count : most;
    return gib_calloc(most ? 6 * most : 1, sizeof(float), err);
}

/* Vertex and index buffers, and the vertex array that reads them. */
static int upload_geometry(gib_gpu_scene *gpu, const gib_scene *s, gib_error *err)
{
    size_t nv = s->vertex_count;
    /* A moving scene rewrites positions and normals every frame (gib_gpu_scene_set_time). */
    const unsigned vflags = s->motion_count ? GL_DYNAMIC_STORAGE_BIT : 0;
    if (!(gpu->positions = gib_gpu_buffer(&gpu->ledger, "scene.positions", nv * 12, s->positions,
                                          vflags, err)) ||
        !(gpu->normals = gib_gpu_buffer(&gpu->ledger, "scene.normals", nv * 12, s->normals, vflags,
                                        err)) ||
        !(gpu->uvs = upload_array(gpu, "scene.uvs", s->uvs, nv * 8, err)) ||
        !(gpu->pose = pose_room(s, err)) ||
        !(gpu->indices = upload_array(gpu, "scene.indices", s->indices,
                                      (size_t)s->triangle_count * 12, err)))
        return -1;
    glCreateVertexArrays(1, &gpu->vao);
    const unsigned bufs[3] = {gpu->positions, gpu->normals, gpu->uvs};
    const int comps[3] = {3, 3, 2};
    for (int i = 0; i < 3; i++) {
        glVertexArrayVertexBuffer(gpu->vao, i, bufs[i], 0, comps[i] * 4);
        glVertexArrayAttribFormat(gpu->vao, i, comps[i], GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(gpu->vao, i, i);
        glEnableVertexArrayAttrib(gpu->vao, i);
    }
    glVertexArrayElementBuffer(gpu->vao, gpu->indices);
    return 0;
}

/* The materials' SSBO: std430 struct Material { vec4 albedo; vec4 specular; ivec4 flags; } = 48
 * bytes. */
static int upload_materials(gib_gpu_scene *gpu, const gib_scene *s, gib_error *err)
{
    struct { float albedo[4], specular[4]; int flags[4]; } *mats =
        calloc(s->material_count ? s->material_count : 1, sizeof *mats);
    if (!mats)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    for (uint32_t i = 0; i < s->material_count; i++) {
        const gib_material *m = &s->materials[i];
        memcpy(mats[i].albedo, m->albedo, 12);
        mats[i].albedo[3] = m->albedo_tex >= 0 ? 1.0f : 0.0f;
        memcpy(mats[i].specular, m->specular, 12);
        mats[i].specular[3] = m->phong_n;
        mats[i].flags[0] = m->spec_type;
        mats[i].flags[1] = m->two_sided;
        mats[i].flags[2] = m->alpha_tex >= 0;
    }
    gpu->materials = upload_array(gpu, "scene.materials", mats,
                                  sizeof *mats * (s->material_count ? s->material_count : 1), err);
    free(mats);
    return gpu->materials ? 0 : -1;
}

/* The lights' SSBO: std430 struct Light { vec4 position_type; vec4 direction_exponent;
 * vec4 intensity_outer; } */
static int upload_lights(gib_gpu_scene *gpu, const gib_scene *s, gib_error *err)
{
    float *lights = calloc(s->light_count ? s->light_count : 1, 48);
    if (!lights)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    for (uint32_t i = 0; i < s->light_count; i++) {
        const gib_light *l = &s->lights[i];
        float *o = lights + i * 12;
        memcpy(o, l->position, 12);
        o[3] = (float)l->type;
        memcpy(o + 4, l->direction, 12);
        o[7] = l->spot_exponent;
        memcpy(o + 8, l->intensity, 12);
        o[11] = l->type == GIB_LIGHT_SPOT ? gib_spot_cos_outer(l) : -2.0f; /* as the reference */
    }
    gpu->lights = upload_array(gpu, "scene.lights", lights,
                               48 * (size_t)(s->light_count ? s->light_count : 1), err);
    free(lights);
    return gpu->lights ? 0 : -1;
}

/* The scene's textures, and the white one that stands in for none. */
static int upload_textures(gib_gpu_scene *gpu, const gib_scene *s, gib_error *err)
{
    gpu->textures = calloc(s->texture_count ? s->texture_count : 1, sizeof *gpu->textures);
    if (!gpu->textures)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    /* A texture used as an alpha mask keeps its bytes linear; colour textures are sRGB. */
    for (uint32_t i = 0; i < s->texture_count; i++) {
        int srgb = 1;
        for (uint32_t m = 0; m < s->material_count; m++)
            if (s->materials[m].alpha_tex == (int)i)
                srgb = 0;
        if (!(gpu->textures[i] = upload_texture(gpu, &s->textures[i], srgb, err)))
            return -1;
    }
    gib_texture white = {.width = 1, .height = 1, .rgba = (float[4]){1, 1, 1, 1}};
    strcpy(white.path, "white");
    if (!(gpu->white = upload_texture(gpu, &white, 0, err)))
        return -1;
    return 0;
}

int gib_gpu_scene_upload(const gib_scene *scene, gib_gpu_scene *gpu, gib_error *err)
{
    memset(gpu, 0, sizeof *gpu);
    gib_ledger_init(&gpu->ledger);
    /* The techniques see the scene in its frame (gib_scene_frame), as the path tracer does: a
     * scene far from the origin is moved next to it, so G-buffer positions, shadow-map distances,
     * LDM depths and photon positions keep the precision of the scene's size. */
    if (!(gpu->frame = gib_calloc(1, sizeof *gpu->frame, err)) ||
        gib_scene_frame_make(scene, gpu->frame, err) < 0) {
        free(gpu->frame);
        gpu->frame = NULL;
        return gib_error_prefix(err, "scene '%s' upload", scene->name);
    }
    const gib_scene *s = gpu->scene = &gpu->frame->scene;
    if (upload_geometry(gpu, s, err) < 0 || upload_materials(gpu, s, err) < 0 ||
        upload_lights(gpu, s, err) < 0 || upload_textures(gpu, s, err) < 0) {
        gib_error_prefix(err, "scene '%s' upload", s->name);
        gib_gpu_scene_free(gpu);
        return -1;
    }
    return gib_gl_check("uploading the scene", err);
}

int gib_gpu_scene_set_time(const gib_gpu_scene *gpu, double t, gib_error *err)
{
    const gib_scene *s = gpu->scene;
    for (uint32_t i = 0; i < s->motion_count; i++) {
        const gib_motion *m = &s->motions[i];
        float *pos = gpu->pose, *nrm = gpu->pose + 3 * (size_t)m->vertex_count;
        gib_motion_pose(m, t, pos, nrm);
        if (gpu->frame && gpu->frame->moved) /* into the frame the upload used, as it rounds */
            for (size_t i = 0; i < 3 * (size_t)m->vertex_count; i++)
                pos[i] = (float)((double)pos[i] - (double)gpu->frame->origin[i % 3]);
        const GLintptr at = (GLintptr)m->first_vertex * 12;
        const GLsizeiptr bytes = (GLsizeiptr)m->vertex_count * 12;
        glNamedBufferSubData(gpu->positions, at, bytes, pos);
        glNamedBufferSubData(gpu->normals, at, bytes, nrm);
    }
    return gib_gl_check("uploading the scene's vertices for the frame", err);
}

void gib_gpu_scene_free(gib_gpu_scene *gpu)
{
    if (gpu->vao)
        glDeleteVertexArrays(1, &gpu->vao);
    gib_ledger_release_all(&gpu->ledger);
    free(gpu->textures);
    free(gpu->pose);
    if (gpu->frame)
        gib_scene_frame_free(gpu->frame);
    free(gpu->frame);
    memset(gpu, 0, sizeof *gpu);
}

void gib_gpu_scene_bind(const gib_gpu_scene *gpu)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, gpu->materials);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, gpu->lights);
}

void gib_gpu_scene_draw(const gib_gpu_scene *gpu) { gib_gpu_scene_draw_instanced(gpu, 1); }

void gib_gpu_scene_draw_instanced(const gib_gpu_scene *gpu, int instances)
{
    const gib_scene *s = gpu->scene;
    glBindVertexArray(gpu->vao);
    gib_gpu_scene_bind(gpu);
    for (uint32_t r = 0; r < s->range_count; r++) {
        const gib_draw_range *dr = &s->ranges[r];
        const gib_material *m = &s->materials[dr->material];
        glUniform1i(0, (int)dr->material);
        glBindTextureUnit(0, m->albedo_tex >= 0 ? gpu->textures[m->albedo_tex] : gpu->white);
        glBindTextureUnit(1, m->alpha_tex >= 0 ? gpu->textures[m->alpha_tex] : gpu->white);
        glDrawElementsInstanced(GL_TRIANGLES, (GLsizei)dr->index_count, GL_UNSIGNED_INT,
                                (const void *)((size_t)dr->first_index * 4), instances);
    }
    glBindVertexArray(0);
}

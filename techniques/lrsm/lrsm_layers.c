/* gibench technique `lrsm` — the layers of the LRSM (Sec. 4.3, 5; Table 1): allocation, static
 * partitions, the construction pass (lrsm_build.comp) and the mip chains. */
#include "techniques/lrsm/lrsm.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "techniques/common/compute.h"
#include "techniques/common/shader.h"
#include "techniques/lrsm/lrsm_slots.h"

static const unsigned layer_format[3] = {GL_RGBA16F, GL_RGBA16F, GL_RGBA16};

uint64_t lrsm_layers_bytes(int rsm_res, int layers, int faces)
{
    uint64_t bytes = 0;
    for (int a = 0; a < 3; a++)
        bytes += gib_texture_bytes(GL_TEXTURE_2D_ARRAY, rsm_res / 2, rsm_res / 2, layers * faces,
                                   layer_format[a], 0);
    return bytes;
}

int lrsm_layers_create(lrsm_layers *L, const gib_light_views *views, int depth_parts,
                       int normal_parts, float overlap, gib_ledger *ledger, gib_error *err)
{
    memset(L, 0, sizeof *L);
    L->half = views->res / 2;
    L->depth_parts = depth_parts;
    L->normal_parts = normal_parts;
    L->overlap = overlap;
    L->faces = views->face_count;
    /* The lights in the light views' table: every light of the scene (unviewed ones are skipped). */
    int n = views->table_data ? (int)views->table_data[0] : 0;
    L->lights = n;
    L->table_data = calloc((size_t)(n ? n : 1) * 4, sizeof(float));
    if (!L->table_data)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    if (!(L->table = gib_gpu_buffer(ledger, "rsm.partitions", sizeof(float) * 4 * (uint64_t)(n ? n : 1),
                                    L->table_data, GL_DYNAMIC_STORAGE_BIT, err)))
        return -1;
    /* Without a viewed light one 1x1 layer keeps the samplers complete (nothing samples it). */
    int layers = L->faces ? L->faces * depth_parts * normal_parts : 1, side = L->faces ? L->half : 1;
    static const char *const name[3] = {"layers.radiance", "layers.normal", "layers.depth"};
    unsigned *tex[3] = {&L->radiance, &L->normal, &L->depth};
    for (int a = 0; a < 3; a++) {
        if (!(*tex[a] = gib_gpu_texture(ledger, name[a], GL_TEXTURE_2D_ARRAY, side, side, layers,
                                        layer_format[a], 0, err)))
            return -1;
        glTextureParameteri(*tex[a], GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(*tex[a], GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(*tex[a], GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(*tex[a], GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        const float zero[4] = {0, 0, 0, 0};
        glClearTexImage(*tex[a], 0, GL_RGBA, GL_FLOAT, zero);
    }
    const char *files[] = {"lrsm/lrsm_build.comp"};
    if (!(L->program = gib_program(files, 1, NULL, err)))
        return -1;
    return 0;
}

void lrsm_layers_set_range(lrsm_layers *L, int light, float z0, float z1)
{
    float *e = L->table_data + 4 * light;
    e[0] = z0;
    e[1] = z1;
    e[2] = L->overlap * (z1 - z0) / (float)L->depth_parts;
    e[3] = 0;
    glNamedBufferSubData(L->table, 0, sizeof(float) * 4 * (GLsizeiptr)L->lights, L->table_data);
}

/* Depth is what the light view stores: the distance to a point or spot light, or the depth along a
 * directional light from the plane behind the scene. The range over the 8 corners of the scene's
 * bounds (which cover every instant of a moving scene) holds every surface the light can see. */
void lrsm_layers_partition(lrsm_layers *L, const gib_light_views *views, const gib_scene *scene)
{
    for (int i = 0; i < L->lights; i++) {
        if (!views->faces_of[i])
            continue;
        const gib_lv_face *f = &views->faces[views->first_face[i]];
        float z0 = INFINITY, z1 = 0;
        if (f->kind == GIB_LV_ORTHO) {
            for (int c = 0; c < 8; c++) {
                float z = 0;
                for (int k = 0; k < 3; k++) {
                    float p = (c >> k) & 1 ? scene->bounds_max[k] : scene->bounds_min[k];
                    z += (p - f->origin[k]) * f->forward[k];
                }
                z0 = fminf(z0, z);
                z1 = fmaxf(z1, z);
            }
        } else {
            float near2 = 0, far2 = 0;
            for (int k = 0; k < 3; k++) {
                float lo = scene->bounds_min[k] - f->origin[k], hi = scene->bounds_max[k] - f->origin[k];
                float out = lo > 0 ? lo : hi < 0 ? -hi : 0;   /* distance to the box along k */
                near2 += out * out;
                far2 += fmaxf(lo * lo, hi * hi);
            }
            z0 = sqrtf(near2);
            z1 = sqrtf(far2);
        }
        if (!(z1 > z0))
            z1 = z0 + 1e-6f * fmaxf(1.0f, z0);
        float *e = L->table_data + 4 * i;
        e[0] = z0;
        e[1] = z1;
        e[2] = L->overlap * (z1 - z0) / (float)L->depth_parts;
        e[3] = 0;
    }
    glNamedBufferSubData(L->table, 0, sizeof(float) * 4 * (GLsizeiptr)(L->lights ? L->lights : 1),
                         L->table_data);
}

void lrsm_layers_bind(const lrsm_layers *L)
{
    glBindTextureUnit(LRSM_UNIT_RADIANCE, L->radiance);
    glBindTextureUnit(LRSM_UNIT_NORMAL, L->normal);
    glBindTextureUnit(LRSM_UNIT_DEPTH, L->depth);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LRSM_SSBO_TABLE, L->table);
    glUniform1i(LRSM_LOC_DEPTH_PARTS, L->depth_parts);
    glUniform1i(LRSM_LOC_NORMAL_PARTS, L->normal_parts);
}

void lrsm_layers_build(lrsm_layers *L, const gib_light_views *views)
{
    if (!L->faces)
        return;
    glUseProgram(L->program);
    gib_light_views_bind(views);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LRSM_SSBO_TABLE, L->table);
    glUniform1i(LRSM_LOC_DEPTH_PARTS, L->depth_parts);
    glUniform1i(LRSM_LOC_NORMAL_PARTS, L->normal_parts);
    glUniform1i(LRSM_BUILD_LOC_HALF, L->half);
    glUniform1i(LRSM_BUILD_LOC_JACOBIAN, L->jacobian);
    glBindImageTexture(LRSM_IMAGE_RADIANCE, L->radiance, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(LRSM_IMAGE_NORMAL, L->normal, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(LRSM_IMAGE_DEPTH, L->depth, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16);
    GLuint groups = gib_groups((unsigned)L->half, GIB_GROUP_2D);
    for (int f = 0; f < L->faces; f++) {
        glUniform1i(LRSM_BUILD_LOC_FACE, f);
        glUniform1i(LRSM_BUILD_LOC_LIGHT, views->faces[f].light);
        glDispatchCompute(groups, groups, 1);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    /* Sec. 4.2: pre-filtering is a box-filtered mip chain of each layer. */
    glGenerateTextureMipmap(L->radiance);
    glGenerateTextureMipmap(L->normal);
    glGenerateTextureMipmap(L->depth);
    for (int u = 0; u < LRSM_IMAGES; u++)
        glBindImageTexture(LRSM_IMAGE_RADIANCE + (GLuint)u, 0, 0, GL_FALSE, 0, GL_READ_ONLY,
                           GL_RGBA8);
}

void lrsm_layers_destroy(lrsm_layers *L, gib_ledger *ledger)
{
    if (L->program)
        glDeleteProgram(L->program);
    unsigned tex[3] = {L->radiance, L->normal, L->depth};
    for (int a = 0; a < 3; a++)
        if (tex[a])
            gib_gpu_free(ledger, tex[a], 1);
    if (L->table)
        gib_gpu_free(ledger, L->table, 0);
    free(L->table_data);
    memset(L, 0, sizeof *L);
}

int lrsm_layers_probe(const lrsm_layers *L, const gib_light_views *views, float mip_clamp,
                      int seams, const float *in, int n, float *out, gib_error *err)
{
    const char *files[] = {"lrsm/lrsm_probe.comp"};
    unsigned program = gib_program(files, 1, NULL, err);
    if (!program)
        return -1;
    GLuint buf[2];
    glCreateBuffers(2, buf);
    glNamedBufferStorage(buf[0], (GLsizeiptr)(sizeof(float) * 8 * (size_t)n), in, 0);
    glNamedBufferStorage(buf[1], (GLsizeiptr)(sizeof(float) * 4 * (size_t)n), NULL, 0);
    glUseProgram(program);
    gib_light_views_bind(views);
    lrsm_layers_bind(L);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LRSM_PROBE_SSBO_IN, buf[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LRSM_PROBE_SSBO_OUT, buf[1]);
    glUniform1f(LRSM_LOC_MIP_CLAMP, mip_clamp);
    glUniform1i(LRSM_LOC_LIGHTS, L->lights);
    glUniform1i(LRSM_PROBE_LOC_COUNT, n);
    glUniform1i(LRSM_LOC_SEAMS, seams);
    glDispatchCompute(gib_groups((unsigned)n, GIB_GROUP_1D), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buf[1], 0, (GLsizeiptr)(sizeof(float) * 4 * (size_t)n), out);
    glDeleteBuffers(2, buf);
    glDeleteProgram(program);
    return 0;
}

#include "voxels.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "techniques/common/common_slots.h"
#include "techniques/common/compute.h"
#include "techniques/common/shader.h"

uint64_t gib_voxels_bytes(int res)
{
    return gib_texture_bytes(GL_TEXTURE_3D, res, res, res, GL_R8, 0);
}

/* A cube centred on the scene's bounds with 1.5 + floor(res / 64) voxels of margin on each side
 * (2.5 at 64^3, 3.5 at 128^3, 5.5 at 256^3). The half voxel puts faces on the bounds along the
 * longest axis (Sponza's floor, a room's walls) in the middle of a voxel layer rather than on the
 * boundary between two, which would set both (and make the result depend on the margin's parity).
 * The whole voxels keep the walls on the bounds off the grid's outer cells, where the cones'
 * trilinear fetches blend them with what lies beyond the grid (vct's transparent border, or its
 * edge repeated), so cones leaving through an open side (the Cornell box's front) do not read
 * them there. A margin growing with res keeps the coarse levels' outer cells empty as well; res/64
 * gives results the most even in voxel_res (PERFORMANCE.md, "The voxel grid's margin"). A scene
 * with no extent (no triangles, or one point) gets a unit cube. */
static void fit_grid(gib_voxels *v, const gib_scene *s)
{
    float ext = 0, c[3];
    for (int k = 0; k < 3; k++) {
        float lo = s->bounds_min[k], hi = s->bounds_max[k];
        int ok = isfinite(lo) && isfinite(hi) && hi >= lo;
        c[k] = ok ? 0.5f * (lo + hi) : 0.0f;
        if (ok && hi - lo > ext)
            ext = hi - lo;
    }
    if (!(ext > 0))
        ext = 1;
    const int margin_voxels = 3 + 2 * (v->res / 64); /* both sides */
    v->size = ext * (float)v->res / (float)(v->res - margin_voxels);
    for (int k = 0; k < 3; k++)
        v->origin[k] = c[k] - 0.5f * v->size;
}

/* The work buffer (voxelize.comp): a header, room for the large-triangle list, and each
 * triangle's alpha mask as a compact id (1..mask_count, 0 for none; v->mask_tex maps ids to scene
 * textures). */
static int make_work(gib_voxels *v, const gib_scene *s, const char *label, gib_ledger *ledger,
                     gib_error *err)
{
    const size_t t = v->triangle_count;
    uint32_t *data = gib_calloc(4 + 2 * t, sizeof *data, err);
    if (!data || !(v->mask_tex = gib_calloc(s->texture_count + 1, sizeof *v->mask_tex, err))) {
        free(data);
        return -1;
    }
    for (uint32_t r = 0; r < s->range_count; r++) {
        const int tex = s->materials[s->ranges[r].material].alpha_tex;
        if (tex < 0)
            continue;
        int id = 0;
        while (id < v->mask_count && v->mask_tex[id] != tex)
            id++;
        if (id == v->mask_count)
            v->mask_tex[v->mask_count++] = tex;
        const uint32_t first = s->ranges[r].first_index / 3, n = s->ranges[r].index_count / 3;
        for (uint32_t i = first; i < first + n && i < t; i++)
            data[4 + t + i] = (uint32_t)id + 1;
    }
    char name[96];
    snprintf(name, sizeof name, "%s_work.triangles", label);
    v->work = gib_gpu_buffer(ledger, name, 4 * (4 + 2 * (uint64_t)t), data, GL_DYNAMIC_STORAGE_BIT,
                             err);
    free(data);
    return v->work ? 0 : -1;
}

int gib_voxels_create(gib_voxels *v, const gib_gpu_scene *scene, int res, const char *label,
                      gib_ledger *ledger, gib_error *err)
{
    memset(v, 0, sizeof *v);
    if (res < GIB_VOXELS_MIN_RES || res > GIB_VOXELS_MAX_RES)
        return gib_fail(err, "voxel_res = %d is out of range (%d..%d)", res, GIB_VOXELS_MIN_RES,
                        GIB_VOXELS_MAX_RES);
    v->res = res;
    v->triangle_count = scene->scene->triangle_count;
    fit_grid(v, scene->scene);
    const char *file[1] = {"common/voxelize.comp"}, *mip_file[1] = {"common/voxel_mip.comp"};
    char name[96];
    snprintf(name, sizeof name, "%s.occupancy", label);
    if (!(v->program[0] = gib_program(file, 1, "#define SMALL 1\n", err)) ||
        !(v->program[1] = gib_program(file, 1, NULL, err)) ||
        !(v->program[2] = gib_program(file, 1, "#define SMALL 1\n#define ALPHA 1\n", err)) ||
        !(v->program[3] = gib_program(file, 1, "#define ALPHA 1\n", err)) ||
        !(v->program_mip = gib_program(mip_file, 1, NULL, err)) ||
        !(v->texture = gib_gpu_texture(ledger, name, GL_TEXTURE_3D, res, res, res, GL_R8, 0, err)))
        goto fail;
    if (make_work(v, scene->scene, label, ledger, err) < 0)
        goto fail;
    /* Outside the grid is empty: cones leaving it see no occlusion. */
    glTextureParameteri(v->texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(v->texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    const GLenum wraps[3] = {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R};
    for (int k = 0; k < 3; k++)
        glTextureParameteri(v->texture, wraps[k], GL_CLAMP_TO_BORDER);
    const float border[4] = {0, 0, 0, 0};
    glTextureParameterfv(v->texture, GL_TEXTURE_BORDER_COLOR, border);
    if (gib_gl_check("creating the occlusion voxels", err) < 0)
        goto fail;
    return 0;
fail:
    gib_error_prefix(err, "occlusion voxels '%s' at %d^3", label, res);
    gib_voxels_destroy(v, ledger);
    return -1;
}

/* Box-filtered averages of the 1/0 occupancy (voxel_mip.comp), level by level. R8 UNORM: Mesa
 * cannot mipmap integer formats. Not glGenerateMipmap: GL leaves its filter to the implementation
 * (a box filter is only recommended), and Mesa's rounds three times (texels up to 1.4/255 off the
 * mean); the cone's alpha is the mean occupancy (Sec. 3.1). Same time as Mesa's on llvmpipe. */
void gib_voxels_mips(gib_voxels *v)
{
    glUseProgram(v->program_mip);
    const int levels = gib_mip_levels(v->res, v->res, v->res);
    for (int l = 1; l < levels; l++) {
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glBindImageTexture(GIB_VOXEL_MIP_IMAGE_DST, v->texture, l, GL_TRUE, 0, GL_WRITE_ONLY,
                           GL_R8);
        glBindImageTexture(GIB_VOXEL_MIP_IMAGE_SRC, v->texture, l - 1, GL_TRUE, 0, GL_READ_ONLY,
                           GL_R8);
        const GLuint n = gib_groups((unsigned)(v->res >> l), GIB_GROUP_3D);
        glDispatchCompute(n, n, n);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    glUseProgram(0);
    glBindImageTexture(GIB_VOXEL_MIP_IMAGE_DST, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8);
    glBindImageTexture(GIB_VOXEL_MIP_IMAGE_SRC, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
}

void gib_voxels_build(gib_voxels *v, const gib_gpu_scene *scene, gib_timers *timers,
                      const char *pass)
{
    if (timers)
        gib_timer_begin(timers, pass);
    const unsigned char zero = 0;
    glClearTexImage(v->texture, 0, GL_RED, GL_UNSIGNED_BYTE, &zero);
    if (v->triangle_count) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_VOXELIZE_SSBO_POSITIONS,
                         scene->positions);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_VOXELIZE_SSBO_INDICES, scene->indices);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_VOXELIZE_SSBO_WORK, v->work);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_VOXELIZE_SSBO_UVS, scene->uvs);
        glBindImageTexture(GIB_VOXELIZE_IMAGE_VOXELS, v->texture, 0, GL_TRUE, 0, GL_WRITE_ONLY,
                           GL_R8);
        /* A pass for the triangles without a mask, then one per 6 alpha masks (the samplers one
         * pass binds): separate programs, as sampling code in the loop slows llvmpipe down
         * even where no triangle takes it. */
        for (int first = -GIB_VOXELIZE_MASKS; first < v->mask_count; first += GIB_VOXELIZE_MASKS) {
            const unsigned *programs = v->program + (first < 0 ? 0 : 2);
            for (int j = 0; j < GIB_VOXELIZE_MASKS; j++)
                glBindTextureUnit(GIB_VOXELIZE_UNIT_MASK_FIRST + j,
                                  first >= 0 && first + j < v->mask_count
                                      ? scene->textures[v->mask_tex[first + j]] : scene->white);
            const uint32_t reset[4] = {0, 1, 1, 0};
            glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                            GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            glNamedBufferSubData(v->work, 0, sizeof reset, reset);
            for (int i = 0; i < 2; i++) {
                glUseProgram(programs[i]);
                glUniform3fv(GIB_VOXELIZE_LOC_ORIGIN, 1, v->origin);
                glUniform1f(GIB_VOXELIZE_LOC_INV_VOXEL, (float)v->res / v->size);
                glUniform1i(GIB_VOXELIZE_LOC_RES, v->res);
                glUniform1ui(GIB_VOXELIZE_LOC_TRIANGLES, v->triangle_count);
                glUniform1i(GIB_VOXELIZE_LOC_MASK_FIRST, first);
                if (i == 0) {
                    glDispatchCompute(gib_groups(v->triangle_count, GIB_GROUP_1D), 1, 1);
                    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
                } else {
                    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, v->work);
                    glDispatchComputeIndirect(0);
                    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
                }
            }
        }
        glUseProgram(0);
        for (int j = 0; j < GIB_VOXELIZE_MASKS; j++)
            glBindTextureUnit(GIB_VOXELIZE_UNIT_MASK_FIRST + j, 0);
        glBindImageTexture(GIB_VOXELIZE_IMAGE_VOXELS, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    gib_voxels_mips(v);
    if (timers)
        gib_timer_end(timers);
}

void gib_voxels_bind(const gib_voxels *v)
{
    glBindTextureUnit(GIB_UNIT_VOXELS, v->texture);
    glUniform3fv(GIB_LOC_VOXEL_ORIGIN, 1, v->origin);
    glUniform1f(GIB_LOC_VOXEL_SIZE, v->size);
    glUniform1i(GIB_LOC_VOXEL_RES, v->res);
}

void gib_voxels_destroy(gib_voxels *v, gib_ledger *ledger)
{
    if (v->texture)
        gib_gpu_free(ledger, v->texture, 1);
    if (v->work)
        gib_gpu_free(ledger, v->work, 0);
    free(v->mask_tex);
    for (int i = 0; i < 4; i++)
        if (v->program[i])
            glDeleteProgram(v->program[i]);
    if (v->program_mip)
        glDeleteProgram(v->program_mip);
    memset(v, 0, sizeof *v);
}

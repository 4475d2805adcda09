/* gibench `vct`: the dense voxel volume (vct.h) — memory plan, injection, occupancy and the
 * anisotropic mips. */
#include "techniques/vct/vct.h"

#include <glad/gl.h>
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "harness/gl/context.h"
#include "techniques/common/compute.h"
#include "techniques/common/pass_state.h"
#include "techniques/common/shader.h"
#include "techniques/common/voxels.h"
#include "techniques/vct/vct_slots.h"

static const char *const dir_label[VCT_DIRECTIONS] = {"aniso.px", "aniso.nx", "aniso.py",
                                                      "aniso.ny", "aniso.pz", "aniso.nz"};

void vct_plan_bytes(int res, long long triangles, bool lobes, vct_plan *p)
{
    /* What gib_gpu_texture will count (the ledger's plan): RGBA16F base levels, and 6 RGBA16F
     * textures of (res/2)^3 with full chains. */
    p->radiance = gib_texture_bytes(GL_TEXTURE_3D, res, res, res, GL_RGBA16F, 1);
    p->normal = gib_texture_bytes(GL_TEXTURE_3D, res, res, res, GL_RGBA16F, 1);
    p->aniso = VCT_DIRECTIONS * gib_texture_bytes(GL_TEXTURE_3D, res / 2, res / 2, res / 2,
                                                  GL_RGBA16F, 0);
    p->voxels = triangles < 0 ? 0 : gib_voxels_bytes(res) + 16 + 8 * (uint64_t)triangles;
    p->lobes = lobes ? 3 * gib_texture_bytes(GL_TEXTURE_3D, res / 2, res / 2, res / 2, GL_RGBA16F, 0)
                     : 0;
    p->total = p->radiance + p->normal + p->aniso + p->lobes + p->voxels;
}

int vct_plan_check(const vct_plan *plan, int res, double budget_mb, gib_ledger *ledger,
                   gib_error *err)
{
    gib_ledger_plan(ledger, "radiance", plan->radiance);
    gib_ledger_plan(ledger, "normal", plan->normal);
    gib_ledger_plan(ledger, "aniso", plan->aniso);
    if (plan->lobes)
        gib_ledger_plan(ledger, "lobes", plan->lobes);
    gib_ledger_plan(ledger, "voxels", plan->voxels);
    const char *what = "";
    uint64_t budget = vct_budget_bytes(budget_mb, &what);
    if (plan->total <= budget)
        return 0;
    return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                    "vct: out of memory: voxel_res %d plans %llu bytes (radiance %llu, normal %llu, "
                    "aniso %llu, lobes %llu, voxels %llu), over the %llu bytes available (%s); "
                    "nothing allocated",
                    res, (unsigned long long)plan->total, (unsigned long long)plan->radiance,
                    (unsigned long long)plan->normal, (unsigned long long)plan->aniso,
                    (unsigned long long)plan->lobes, (unsigned long long)plan->voxels, (unsigned long long)budget, what);
}

#define GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX 0x9049

uint64_t vct_budget_bytes(double budget_mb, const char **what)
{
    if (budget_mb > 0) {
        *what = "memory_budget_mb";
        return (uint64_t)(budget_mb * 1e6);
    }
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++) {
        const char *e = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (e && !strcmp(e, "GL_NVX_gpu_memory_info")) {
            GLint kb = 0;
            glGetIntegerv(GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, &kb);
            *what = "the device's available memory (GL_NVX_gpu_memory_info)";
            return (uint64_t)kb * 1024;
        }
    }
    *what = "half the physical memory (no GL_NVX_gpu_memory_info)";
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    return pages > 0 && page > 0 ? (uint64_t)pages * (uint64_t)page / 2 : 0;
}

/* A driver's GL_OUT_OF_MEMORY (its code set by the ledger) is said against the plan. */
static int alloc_failed(gib_error *err, const vct_plan *plan)
{
    if (err->code == GIB_ERR_OUT_OF_MEMORY)
        gib_error_prefix(err, "vct: out of memory allocating the voxels (planned %llu bytes)",
                         (unsigned long long)plan->total);
    return -1;
}

int vct_volume_create(vct_volume *v, const float origin[3], float size, int res, bool lobes,
                      gib_ledger *ledger, gib_error *err)
{
    memset(v, 0, sizeof *v);
    v->res = res;
    memcpy(v->origin, origin, sizeof v->origin);
    v->size = size;
    vct_plan plan;
    vct_plan_bytes(res, -1, lobes, &plan);
    const char *inject[] = {"vct/vct_inject.vert", "vct/vct_inject.frag"};
    const char *resolve[] = {"vct/vct_resolve.comp"};
    const char *accumulate[] = {"vct/vct_accumulate.comp"};
    const char *mip[] = {"vct/vct_aniso.comp"};
    const char *lobe_mip[] = {"vct/vct_lobes.comp"};
    if (!(v->inject_program = gib_program(inject, 2, NULL, err)) ||
        !(v->resolve_program = gib_program(resolve, 1, NULL, err)) ||
        !(v->accumulate_program = gib_program(accumulate, 1, NULL, err)) ||
        !(v->mip_base_program = gib_program(mip, 1, "#define FROM_BASE 1\n", err)) ||
        !(v->mip_program = gib_program(mip, 1, NULL, err)) ||
        !(v->lobe_base_program = gib_program(lobe_mip, 1, "#define FROM_BASE 1\n", err)) ||
        !(v->lobe_program = gib_program(lobe_mip, 1, NULL, err)))
        return -1;
    int half = res / 2;
    v->aniso_levels = gib_mip_levels(half, half, half);
    if (!(v->radiance = gib_gpu_texture(ledger, "radiance.base", GL_TEXTURE_3D, res, res, res,
                                        GL_RGBA16F, 1, err)) ||
        !(v->normal = gib_gpu_texture(ledger, "normal.base", GL_TEXTURE_3D, res, res, res,
                                      GL_RGBA16F, 1, err)))
        return alloc_failed(err, &plan);
    for (int d = 0; d < VCT_DIRECTIONS; d++)
        if (!(v->aniso[d] = gib_gpu_texture(ledger, dir_label[d], GL_TEXTURE_3D, half, half, half,
                                            GL_RGBA16F, 0, err)))
            return alloc_failed(err, &plan);
    for (int k = 0; lobes && k < 3; k++)
        if (!(v->lobe[k] = gib_gpu_texture(ledger, "lobes", GL_TEXTURE_3D, half, half, half,
                                           GL_RGBA16F, 0, err)))
            return alloc_failed(err, &plan);
    enum { ALL = 2 + VCT_DIRECTIONS + 3 };
    const unsigned all[ALL] = {v->radiance, v->normal,   v->aniso[0], v->aniso[1],
                               v->aniso[2], v->aniso[3], v->aniso[4], v->aniso[5],
                               v->lobe[0],  v->lobe[1],  v->lobe[2]};
    for (int i = 0; i < ALL && all[i]; i++) {
        /* Trilinear within and between levels. Outside the grid is empty: a transparent border
         * (the default border colour, 0). The grid's margin keeps walls off its outer cells, so
         * the border dilutes none; clamped to the edge, the outer cells repeated beyond the grid
         * (vct_trace.glsl). */
        glTextureParameteri(all[i], GL_TEXTURE_MIN_FILTER,
                            i < 2 ? GL_LINEAR : GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(all[i], GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        const GLenum wrap[3] = {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R};
        for (int k = 0; k < 3; k++)
            glTextureParameteri(all[i], wrap[k], GL_CLAMP_TO_BORDER);
    }
    glCreateFramebuffers(1, &v->fbo);
    glNamedFramebufferTexture(v->fbo, GL_COLOR_ATTACHMENT0, v->radiance, 0);
    glNamedFramebufferTexture(v->fbo, GL_COLOR_ATTACHMENT1, v->normal, 0);
    const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(v->fbo, 2, bufs);
    glCreateFramebuffers(1, &v->scratch_fbo);
    glNamedFramebufferTexture(v->scratch_fbo, GL_COLOR_ATTACHMENT0, v->normal, 0);
    glNamedFramebufferDrawBuffer(v->scratch_fbo, GL_COLOR_ATTACHMENT0);
    if (glCheckNamedFramebufferStatus(v->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
        glCheckNamedFramebufferStatus(v->scratch_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return gib_fail(err, "vct: the layered injection framebuffer is incomplete");
    glCreateVertexArrays(1, &v->vao);
    if (gib_gl_check("vct volume", err) < 0)
        return alloc_failed(err, &plan);
    return 0;
}

static void grid_uniforms(const vct_volume *v)
{
    glUniform3fv(GIB_LOC_VOXEL_ORIGIN, 1, v->origin);
    glUniform1f(GIB_LOC_VOXEL_SIZE, v->size);
    glUniform1i(GIB_LOC_VOXEL_RES, v->res);
}

/* Draws the texels of lights [first, last) as points into `fbo` (vct_inject.vert): radiance
 * (rgb: w L, a: w) to its first attachment unless `normals_only`, normal (rgb: w n) to its second
 * if it has one. */
static void inject_points(vct_volume *v, unsigned fbo, int lv_res, const int *first_face,
                          const int *faces_of, int first, int last, bool normals_only)
{
    gib_pass_apply(&(gib_pass_state){.fbo = fbo, .width = v->res, .height = v->res,
                                     .blend = GIB_BLEND_ADD});
    if (normals_only)
        glColorMaski(0, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glUseProgram(v->inject_program);
    grid_uniforms(v);
    glUniform1i(VCT_INJECT_LOC_LV_RES, lv_res);
    glBindVertexArray(v->vao);
    for (int l = first; l < last; l++)
        for (int f = first_face[l]; f < first_face[l] + faces_of[l]; f++) {
            glUniform1i(VCT_INJECT_LOC_LIGHT, l);
            glUniform1i(VCT_INJECT_LOC_FACE, f);
            glDrawArrays(GL_POINTS, 0, lv_res * lv_res);
        }
    glBindVertexArray(0);
    if (normals_only)
        glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gib_pass_end();
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

/* Several lights: each light's texels averaged apart (in the normal volume) and added to the
 * radiance volume (vct_accumulate.comp), then every light's normals injected with the radiance
 * volume write-masked; the radiance's alpha is 1 where light landed, so the resolve's division
 * leaves the sum. */
static void inject_lights_apart(vct_volume *v, int lv_res, const int *first_face,
                                const int *faces_of, int lights)
{
    const float zero[4] = {0, 0, 0, 0};
    int g = (int)gib_groups((unsigned)v->res, GIB_GROUP_3D);
    for (int l = 0; l < lights; l++) {
        glClearTexImage(v->normal, 0, GL_RGBA, GL_FLOAT, zero);
        inject_points(v, v->scratch_fbo, lv_res, first_face, faces_of, l, l + 1, false);
        glUseProgram(v->accumulate_program);
        glBindImageTexture(VCT_ACCUMULATE_IMAGE_SCRATCH, v->normal, 0, GL_TRUE, 0, GL_READ_ONLY,
                           GL_RGBA16F);
        glBindImageTexture(VCT_ACCUMULATE_IMAGE_RADIANCE, v->radiance, 0, GL_TRUE, 0,
                           GL_READ_WRITE, GL_RGBA16F);
        glDispatchCompute(g, g, g);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    glClearTexImage(v->normal, 0, GL_RGBA, GL_FLOAT, zero);
    inject_points(v, v->fbo, lv_res, first_face, faces_of, 0, lights, true);
}

void vct_volume_inject(vct_volume *v, unsigned occupancy, int lv_res, const int *first_face,
                       const int *faces_of, int lights, bool fill)
{
    const float zero[4] = {0, 0, 0, 0};
    glClearTexImage(v->radiance, 0, GL_RGBA, GL_FLOAT, zero);
    glClearTexImage(v->normal, 0, GL_RGBA, GL_FLOAT, zero);
    /* Injection: every light-view texel drawn as a point into the voxel holding its position,
     * summed by additive blending, w the texel's area in voxel faces. The injection framebuffer
     * stays bound after: llvmpipe loses the begin of a GL_TIME_ELAPSED query started while
     * framebuffer 0 (none, surfaceless) is bound, and the next pass's time. */
    if (lights > 1)
        inject_lights_apart(v, lv_res, first_face, faces_of, lights);
    else
        inject_points(v, v->fbo, lv_res, first_face, faces_of, 0, lights, false);

    /* Resolve: sums to area-weighted averages; alpha = occupancy (the occlusion voxels', or
     * where light landed); with `fill`, occupied voxels no texel reached from the light views. */
    int g = (int)gib_groups((unsigned)v->res, GIB_GROUP_3D);
    glUseProgram(v->resolve_program);
    grid_uniforms(v);
    glUniform1i(VCT_RESOLVE_LOC_LIGHTS, fill ? lights : 0);
    glUniform1i(VCT_RESOLVE_LOC_LV_RES, lv_res);
    glBindTextureUnit(VCT_RESOLVE_UNIT_OCCUPANCY, occupancy);
    glBindImageTexture(VCT_RESOLVE_IMAGE_RADIANCE, v->radiance, 0, GL_TRUE, 0, GL_READ_WRITE,
                       GL_RGBA16F);
    glBindImageTexture(VCT_RESOLVE_IMAGE_NORMAL, v->normal, 0, GL_TRUE, 0, GL_READ_WRITE,
                       GL_RGBA16F);
    glDispatchCompute(g, g, g);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

/* A chain of `count` RGBA16F 3D textures, level by level: level 0 by `base_program` from the base
 * voxels (radiance, normal), level k+1 by `program` from level k (bound from unit `src_first`),
 * each level written through images from `dst_first`. */
static void build_levels(const vct_volume *v, unsigned base_program, unsigned program,
                         const unsigned *tex, int count, GLuint src_first, GLuint dst_first)
{
    for (int level = 0; level < v->aniso_levels; level++) {
        int side = (v->res / 2) >> level;
        glUseProgram(level == 0 ? base_program : program);
        glUniform1i(VCT_ANISO_LOC_LEVEL, level);
        if (level == 0) {
            glBindTextureUnit(VCT_ANISO_UNIT_RADIANCE, v->radiance);
            glBindTextureUnit(VCT_ANISO_UNIT_NORMAL, v->normal);
        } else {
            for (int i = 0; i < count; i++)
                glBindTextureUnit(src_first + (GLuint)i, tex[i]);
        }
        for (int i = 0; i < count; i++)
            glBindImageTexture(dst_first + (GLuint)i, tex[i], level, GL_TRUE, 0, GL_WRITE_ONLY,
                               GL_RGBA16F);
        int g = (int)gib_groups((unsigned)side, GIB_GROUP_3D);
        glDispatchCompute(g, g, g);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    for (int i = 0; i < count; i++)
        glBindTextureUnit(src_first + (GLuint)i, 0);
}

void vct_volume_mips(vct_volume *v)
{
    build_levels(v, v->mip_base_program, v->mip_program, v->aniso, VCT_DIRECTIONS,
                 VCT_ANISO_UNIT_SRC_FIRST, VCT_ANISO_IMAGE_DST_FIRST);
    if (v->lobe[0]) /* the emission lobes (vct_lobes.comp), for front_faces */
        build_levels(v, v->lobe_base_program, v->lobe_program, v->lobe, 3,
                     VCT_LOBES_UNIT_SRC_FIRST, VCT_LOBES_IMAGE_DST_FIRST);
}

void vct_volume_bind_cones(const vct_volume *v, const vct_cone_settings *c)
{
    glBindTextureUnit(GIB_UNIT_VOXELS, v->radiance);
    for (int d = 0; d < VCT_DIRECTIONS; d++)
        glBindTextureUnit(VCT_UNIT_ANISO_FIRST + d, v->aniso[d]);
    for (int k = 0; k < 3; k++)
        glBindTextureUnit(VCT_UNIT_LOBE_FIRST + k, v->lobe[k]);
    grid_uniforms(v);
    glUniform1f(VCT_LOC_STEP_FACTOR, c->step_factor);
    glUniform1f(VCT_LOC_START_OFFSET, c->start_offset);
    glUniform1f(VCT_LOC_LEVEL_BIAS, (float)c->sample_level);
    glUniform1i(VCT_LOC_CLEARANCE, c->clearance);
    glUniform1i(VCT_LOC_FRONT_FACES, c->front_faces);
}

void vct_volume_destroy(vct_volume *v, gib_ledger *ledger)
{
    const unsigned progs[] = {v->mip_base_program, v->inject_program, v->resolve_program,
                              v->accumulate_program, v->mip_program, v->lobe_base_program,
                              v->lobe_program};
    for (int i = 0; i < 7; i++)
        if (progs[i])
            glDeleteProgram(progs[i]);
    if (v->fbo)
        glDeleteFramebuffers(1, &v->fbo);
    if (v->scratch_fbo)
        glDeleteFramebuffers(1, &v->scratch_fbo);
    if (v->vao)
        glDeleteVertexArrays(1, &v->vao);
    if (v->radiance)
        gib_gpu_free(ledger, v->radiance, 1);
    if (v->normal)
        gib_gpu_free(ledger, v->normal, 1);
    for (int d = 0; d < VCT_DIRECTIONS; d++)
        if (v->aniso[d])
            gib_gpu_free(ledger, v->aniso[d], 1);
    for (int k = 0; k < 3; k++)
        if (v->lobe[k])
            gib_gpu_free(ledger, v->lobe[k], 1);
    memset(v, 0, sizeof *v);
}

#include "ldm.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "harness/gl/ledger.h"
#include "techniques/common/compute.h"
#include "techniques/common/pass_state.h"
#include "techniques/common/shader.h"
#include "harness/gl/view.h"
#include "eqsp.h"
#include "techniques/ldm/ldm_slots.h"

/* std430 struct LdmInfo in ldm_common.glsl. */
typedef struct ldm_info_gpu {
    float dir_extent[4];
    float origin_res[4];
    uint32_t offsets[4];
} ldm_info_gpu;

static void draw_all(const gib_gpu_scene *scene, unsigned program, int first, int count)
{
    glUseProgram(program);
    glUniform1i(LDM_LOC_FIRST_LDM, first);
    gib_gpu_scene_draw_instanced(scene, count);
}

static int upload_info(ldm_set *l, gib_ledger *ledger, const uint64_t *counts, gib_error *err)
{
    ldm_info_gpu *info = calloc(l->count, sizeof *info);
    if (!info)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    for (int i = 0; i < l->count; i++) {
        for (int k = 0; k < 3; k++) {
            info[i].dir_extent[k] = l->dirs[3 * i + k];
            info[i].origin_res[k] = l->center[k] - l->dirs[3 * i + k] * l->radius;
        }
        info[i].dir_extent[3] = l->radius;
        info[i].origin_res[3] = (float)l->res;
    }
    /* Offsets within each page (filled when the pages are laid out). */
    for (int p = 0; p < l->page_count; p++) {
        uint64_t node_base = 0;
        for (int j = 0; j < l->pages[p].count; j++) {
            int i = l->pages[p].first + j;
            info[i].offsets[0] = (uint32_t)((uint64_t)j * l->res * l->res);
            info[i].offsets[1] = (uint32_t)node_base;
            info[i].offsets[2] = counts ? (uint32_t)counts[i] : 0;
            info[i].offsets[3] = (uint32_t)p;
            node_base += counts ? counts[i] : 0;
        }
    }
    if (l->info)
        glNamedBufferSubData(l->info, 0, sizeof *info * l->count, info);
    else
        l->info = gib_gpu_buffer(ledger, "ldm.info", sizeof *info * l->count, info,
                                 GL_DYNAMIC_STORAGE_BIT, err);
    free(info);
    return l->info ? 0 : -1;
}

static void begin_pass(ldm_set *l)
{
    /* No depth test and no culling: front and back faces all go into the lists. */
    gib_pass_apply(&(gib_pass_state){.fbo = l->fbo, .width = l->res, .height = l->res});
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_SSBO_LDM_INFO, l->info);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_SSBO_LDM_STATUS, l->status);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_SSBO_LDM_COUNTERS, l->counters);
}

/* Counting pass: fragments per LDM of the geometry as the GPU scene holds it now, into counts. */
static void count_fragments(ldm_set *l, const gib_gpu_scene *scene, uint32_t *counts)
{
    const uint32_t zero = 0;
    glClearNamedBufferData(l->counters, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    begin_pass(l);
    draw_all(scene, l->count_program, 0, l->count);
    gib_pass_end();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(l->counters, 0, 4 * (GLsizeiptr)l->count, counts);
}

/* The page that starts at LDM i: consecutive LDMs while their heads and nodes (capacity[k] nodes
 * for LDM k) both fit one buffer of `limit` bytes. Sets *count (0: LDM i alone is too large) and
 * *nodes. */
static void next_page(const ldm_set *l, const uint64_t *capacity, uint64_t limit, int i, int *count,
                      uint64_t *nodes)
{
    const uint64_t heads_per_ldm = 4ull * l->res * l->res;
    *count = 0;
    *nodes = 0;
    while (i + *count < l->count && (uint64_t)(*count + 1) * heads_per_ldm <= limit &&
           (*nodes + capacity[i + *count]) * 8 <= limit) {
        *nodes += capacity[i + *count];
        (*count)++;
    }
}

static uint64_t max_block_bytes(void)
{
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    return (uint64_t)max_block;
}

void ldm_plan_bytes(const ldm_set *l, const uint64_t *capacity, uint64_t limit, ldm_plan *p)
{
    memset(p, 0, sizeof *p);
    p->heads = 4ull * l->res * l->res * (uint64_t)l->count;
    for (int i = 0; i < l->count;) {
        int n;
        uint64_t nodes;
        next_page(l, capacity, limit, i, &n, &nodes);
        if (!n) { /* one LDM larger than a buffer: lay_out_pages refuses it; planned all the same */
            n = 1;
            nodes = capacity[i];
        }
        p->nodes += 8 * (nodes ? nodes : 1); /* an empty page still holds one node */
        i += n;
    }
    p->info = sizeof(ldm_info_gpu) * (uint64_t)l->count;
    p->counters = 4 * (uint64_t)l->count;
    p->status = 16;
    p->total = p->heads + p->nodes + p->info + p->counters + p->status;
}

/* Pages: consecutive LDMs while heads and nodes (capacity[i] nodes for LDM i) both fit one SSBO;
 * allocates them and uploads the per-LDM info. */
static int lay_out_pages(ldm_set *l, const uint64_t *capacity, gib_ledger *ledger, gib_error *err)
{
    const uint64_t limit = max_block_bytes();
    const uint64_t heads_per_ldm = 4ull * l->res * l->res;
    l->page_count = 0;
    for (int i = 0; i < l->count;) {
        if (l->page_count == LDM_MAX_PAGES)
            return gib_fail(err, "ldm: %d LDMs of %dx%d need more than %d buffers of %llu bytes",
                            l->count, l->res, l->res, LDM_MAX_PAGES, (unsigned long long)limit);
        ldm_page *pg = &l->pages[l->page_count++];
        memset(pg, 0, sizeof *pg); /* page 0 was borrowed by the counting pass */
        pg->first = i;
        uint64_t nodes;
        next_page(l, capacity, limit, i, &pg->count, &nodes);
        if (!pg->count)
            return gib_fail(err, "ldm: one %dx%d LDM needs %llu nodes, more than one buffer of "
                            "%llu bytes holds", l->res, l->res,
                            (unsigned long long)capacity[i], (unsigned long long)limit);
        i += pg->count;
        pg->node_capacity = nodes;
        if (!(pg->heads = gib_gpu_buffer(ledger, "ldm.heads", heads_per_ldm * pg->count, NULL,
                                         GL_DYNAMIC_STORAGE_BIT, err)) ||
            !(pg->nodes = gib_gpu_buffer(ledger, "ldm.nodes", 8 * (nodes ? nodes : 1), NULL, 0,
                                         err)))
            return -1;
    }
    memcpy(l->capacity, capacity, sizeof *capacity * (size_t)l->count);
    return upload_info(l, ledger, capacity, err);
}

/* Records the plan in the ledger (structure "ldm") and holds it against budget_bytes (0: none). */
static int plan_check(ldm_set *l, const uint64_t *capacity, uint64_t budget_bytes,
                      gib_ledger *ledger, gib_error *err)
{
    ldm_plan_bytes(l, capacity, max_block_bytes(), &l->plan);
    const ldm_plan *p = &l->plan;
    gib_ledger_plan(ledger, "ldm.heads", p->heads);
    gib_ledger_plan(ledger, "ldm.nodes", p->nodes);
    gib_ledger_plan(ledger, "ldm.info", p->info);
    gib_ledger_plan(ledger, "ldm.counters", p->counters);
    gib_ledger_plan(ledger, "ldm.status", p->status);
    if (!budget_bytes || p->total <= budget_bytes)
        return 0;
    return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                         "ldm: out of memory: %d LDMs of %dx%d plan %llu bytes (heads %llu, "
                         "nodes %llu for %llu fragments), over the %llu bytes of "
                         "memory_budget_mb; only the counting pass's buffers allocated",
                         l->count, l->res, l->res, (unsigned long long)p->total,
                         (unsigned long long)p->heads, (unsigned long long)p->nodes,
                         (unsigned long long)l->fragments, (unsigned long long)budget_bytes);
}

static void free_pages(ldm_set *l, gib_ledger *ledger)
{
    for (int p = 0; p < l->page_count; p++) {
        if (l->pages[p].heads)
            gib_gpu_free(ledger, l->pages[p].heads, 0);
        if (l->pages[p].nodes)
            gib_gpu_free(ledger, l->pages[p].nodes, 0);
    }
    l->page_count = 0;
}

int ldm_create(ldm_set *l, const gib_gpu_scene *scene, int directions, int res, double node_budget,
               uint64_t budget_bytes, gib_ledger *ledger, gib_error *err)
{
    memset(l, 0, sizeof *l);
    l->state = GIB_STATUS_OK;
    l->res = res;
    l->node_budget = node_budget;
    l->ledger = ledger;
    l->moving = scene->scene->motion_count > 0;
    int max = directions * 2 + 8;
    l->dirs = calloc((size_t)max * 3, sizeof(float));
    if (!l->dirs)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    l->count = ldm_directions(directions, l->dirs, max);
    if (l->count <= 0)
        return gib_fail(err, "ldm: no direction set for %d directions", directions);
    /* A moving scene's bounds cover every instant (scene.h), so the sphere holds at every frame. */
    gib_view_bounding_sphere(scene->scene, l->center, &l->radius);

    const char *build[] = {"ldm/ldm_build.vert", "ldm/ldm_build.frag"};
    const char *count[] = {"ldm/ldm_build.vert", "ldm/ldm_count.frag"};
    if (!(l->build_program = gib_program(build, 2, NULL, err)) ||
        !(l->count_program = gib_program(count, 2, NULL, err)))
        return -1;
    glCreateFramebuffers(1, &l->fbo);
    glNamedFramebufferParameteri(l->fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, res);
    glNamedFramebufferParameteri(l->fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, res);
    if (!(l->counters = gib_gpu_buffer(ledger, "ldm.counters", 4 * (uint64_t)l->count, NULL,
                                       GL_DYNAMIC_STORAGE_BIT, err)) ||
        !(l->status = gib_gpu_buffer(ledger, "ldm.status", 16, NULL, GL_DYNAMIC_STORAGE_BIT, err)))
        return -1;
    const uint32_t zeros[4] = {0, 0, 0, 0};
    glNamedBufferSubData(l->status, 0, 16, zeros);
    /* One page holds everything for the counting pass's info upload. */
    l->page_count = 1;
    l->pages[0].first = 0;
    l->pages[0].count = l->count;
    if (upload_info(l, ledger, NULL, err) < 0)
        return -1;

    uint32_t *counts32 = calloc(l->count, sizeof *counts32);
    uint64_t *counts = calloc(l->count, sizeof *counts);
    l->capacity = calloc(l->count, sizeof *l->capacity);
    if (!counts32 || !counts || !l->capacity) {
        free(counts32);
        free(counts);
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    }
    count_fragments(l, scene, counts32);
    for (int i = 0; i < l->count; i++) {
        l->fragments += counts32[i];
        counts[i] = (uint64_t)((double)counts32[i] * node_budget);
    }
    free(counts32);
    l->mean_depth_complexity = (double)l->fragments / ((double)l->count * res * res);
    int rc = plan_check(l, counts, budget_bytes, ledger, err);
    if (rc == 0)
        rc = lay_out_pages(l, counts, ledger, err);
    free(counts);
    return rc < 0 ? rc : gib_gl_check("ldm create", err);
}

/* A moving scene's fragment counts change every frame: they are counted again (pass
 * "ldm_count"), and when an LDM would need more nodes than it has, the pages are laid out anew
 * with a quarter more room than this frame needs (capacities never shrink, so a periodic motion
 * settles). An allocation that fails leaves status "alloc_failed". */
static void recount(ldm_set *l, const gib_gpu_scene *scene, gib_timers *timers)
{
    gib_timer_begin(timers, "ldm_count");
    uint32_t *counts32 = calloc(l->count, sizeof *counts32);
    uint64_t *cap = calloc(l->count, sizeof *cap);
    int grow = 0;
    if (counts32 && cap) {
        count_fragments(l, scene, counts32);
        for (int i = 0; i < l->count; i++) {
            const uint64_t need = (uint64_t)((double)counts32[i] * l->node_budget);
            cap[i] = l->capacity[i];
            if (need > cap[i]) {
                cap[i] = need + need / 4;
                grow = 1;
            }
        }
    }
    gib_error err;
    if (!counts32 || !cap || (grow && (free_pages(l, l->ledger),
                                       lay_out_pages(l, cap, l->ledger, &err) < 0)))
        l->state = GIB_STATUS_ALLOC_FAILED;
    free(counts32);
    free(cap);
    gib_timer_end(timers);
}

void ldm_build(ldm_set *l, const gib_gpu_scene *scene, gib_timers *timers)
{
    if (l->moving)
        recount(l, scene, timers);
    if (!l->page_count)
        return; /* alloc_failed: nothing to build into */
    gib_timer_begin(timers, "ldm_build");
    const uint32_t zero = 0, end = 0xffffffffu;
    glClearNamedBufferData(l->counters, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    begin_pass(l);
    for (int p = 0; p < l->page_count; p++) {
        glClearNamedBufferData(l->pages[p].heads, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &end);
        ldm_bind_page(l, p);
        draw_all(scene, l->build_program, l->pages[p].first, l->pages[p].count);
    }
    gib_pass_end();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    gib_timer_end(timers);
}

void ldm_bind_page(const ldm_set *l, int page)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_SSBO_LDM_INFO, l->info);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_SSBO_LDM_HEADS, l->pages[page].heads);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_SSBO_LDM_NODES, l->pages[page].nodes);
}

gib_status ldm_status(ldm_set *l)
{
    uint32_t st[2] = {0, 0};
    glGetNamedBufferSubData(l->status, 0, 8, st);
    if (st[0])
        l->state = GIB_STATUS_OVERFLOW;
    else if (st[1])
        l->state = GIB_STATUS_CONTENTION;
    return l->state;
}

void ldm_destroy(ldm_set *l, gib_ledger *ledger)
{
    free_pages(l, ledger);
    free(l->capacity);
    const unsigned bufs[3] = {l->info, l->status, l->counters};
    for (int i = 0; i < 3; i++)
        if (bufs[i])
            gib_gpu_free(ledger, bufs[i], 0);
    if (l->fbo)
        glDeleteFramebuffers(1, &l->fbo);
    if (l->build_program)
        glDeleteProgram(l->build_program);
    if (l->count_program)
        glDeleteProgram(l->count_program);
    free(l->dirs);
    memset(l, 0, sizeof *l);
}

int ldm_snap(const ldm_set *l, int i, const float p[3], float out[3])
{
    const float *v = l->dirs + 3 * i;
    float t[3], b[3], o[3], q[3];
    gib_ortho_basis(v, t, b);
    for (int k = 0; k < 3; k++) {
        o[k] = l->center[k] - v[k] * l->radius;
        q[k] = p[k] - o[k];
    }
    float x = q[0] * t[0] + q[1] * t[1] + q[2] * t[2];
    float y = q[0] * b[0] + q[1] * b[1] + q[2] * b[2];
    float z = q[0] * v[0] + q[1] * v[1] + q[2] * v[2];
    float fx = (x / l->radius * 0.5f + 0.5f) * l->res, fy = (y / l->radius * 0.5f + 0.5f) * l->res;
    if (fx < 0 || fy < 0 || fx >= l->res || fy >= l->res)
        return 0;
    float cx = ((floorf(fx) + 0.5f) / l->res - 0.5f) * 2.0f * l->radius;
    float cy = ((floorf(fy) + 0.5f) / l->res - 0.5f) * 2.0f * l->radius;
    for (int k = 0; k < 3; k++)
        out[k] = o[k] + cx * t[k] + cy * b[k] + z * v[k];
    return 1;
}

int ldm_probe(ldm_set *l, const float *rays, int n, float eps, float *dist, gib_ledger *ledger,
              gib_error *err)
{
    const char *files[] = {"ldm/ldm_probe.comp"};
    unsigned prog = gib_program(files, 1, NULL, err);
    if (!prog)
        return -1;
    unsigned rb = gib_gpu_buffer(ledger, "ldm.probe_rays", 16ull * n, rays, 0, err);
    unsigned hb = rb ? gib_gpu_buffer(ledger, "ldm.probe_hits", 4ull * n, NULL,
                                      GL_DYNAMIC_STORAGE_BIT, err) : 0;
    if (!hb) {
        glDeleteProgram(prog);
        return -1;
    }
    glUseProgram(prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LDM_PROBE_SSBO_RAYS, rb);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LDM_PROBE_SSBO_HITS, hb);
    glUniform1i(LDM_PROBE_LOC_COUNT, n);
    glUniform1f(LDM_PROBE_LOC_EPS, eps);
    for (int p = 0; p < l->page_count; p++) {
        ldm_bind_page(l, p);
        glUniform1i(LDM_PROBE_LOC_FIRST, l->pages[p].first);
        glUniform1i(LDM_PROBE_LOC_PAGE_COUNT, l->pages[p].count);
        glDispatchCompute(gib_groups((unsigned)n, GIB_GROUP_1D), 1, 1);
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(hb, 0, 4 * (GLsizeiptr)n, dist);
    gib_gpu_free(ledger, rb, 0);
    gib_gpu_free(ledger, hb, 0);
    glDeleteProgram(prog);
    return gib_gl_check("ldm probe", err);
}

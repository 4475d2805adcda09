#include "techniques/common/vpl.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "techniques/common/common_slots.h"
#include "techniques/common/compute.h"
#include "techniques/common/shader.h"

/* A small deterministic generator (splitmix64): the pattern depends on the seed only. */
static double next_uniform(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

/* Sample points (u, v in [0, 1)^2) of the n VPLs of one face and each texel's owner (0..n-1). */
static void face_pattern(int kind, int n, int res, uint64_t *rng, double *u, double *v, int *owner)
{
    if (kind == GIB_LV_PERSPECTIVE) {
        /* Circle pattern (Sec. 3.2.1); regions: Voronoi cells in texel space. */
        for (int i = 0; i < n; i++) {
            double x1 = next_uniform(rng), x2 = next_uniform(rng);
            double r = 0.5 * sqrt(x1), a = 2 * M_PI * x2;
            u[i] = 0.5 + r * cos(a);
            v[i] = 0.5 + r * sin(a);
        }
        /* Nearest sample by buckets: a G x G grid over the square, searched ring by ring until
         * the ring lies farther than the best sample found (exact; ties to the lower index). */
        int G = (int)ceil(sqrt((double)n));
        int *head = malloc((size_t)G * G * sizeof *head), *next = malloc((size_t)n * sizeof *next);
        if (!head || !next) {
            free(head), free(next);
            for (int k = 0; k < res * res; k++)
                owner[k] = 0;
            return;
        }
        for (int b = 0; b < G * G; b++)
            head[b] = -1;
        for (int i = n - 1; i >= 0; i--) {
            int bx = (int)(u[i] * G), by = (int)(v[i] * G);
            bx = bx < 0 ? 0 : bx >= G ? G - 1 : bx;
            by = by < 0 ? 0 : by >= G ? G - 1 : by;
            next[i] = head[by * G + bx];
            head[by * G + bx] = i;
        }
        for (int y = 0; y < res; y++)
            for (int x = 0; x < res; x++) {
                double cu = (x + 0.5) / res, cv = (y + 0.5) / res, best = INFINITY;
                int b = 0, bx = (int)(cu * G), by = (int)(cv * G);
                for (int ring = 0; ring <= G; ring++) {
                    double reach = (ring - 1) / (double)G; /* nearest a ring's cells can be */
                    if (ring > 1 && reach * reach > best)
                        break;
                    for (int gy = by - ring; gy <= by + ring; gy++)
                        for (int gx = bx - ring; gx <= bx + ring; gx++) {
                            if (gx < 0 || gy < 0 || gx >= G || gy >= G ||
                                (abs(gx - bx) != ring && abs(gy - by) != ring))
                                continue;
                            for (int i = head[gy * G + gx]; i >= 0; i = next[i]) {
                                double d = (cu - u[i]) * (cu - u[i]) + (cv - v[i]) * (cv - v[i]);
                                if (d < best || (d == best && i < b)) {
                                    best = d;
                                    b = i;
                                }
                            }
                        }
                }
                owner[y * res + x] = b;
            }
        free(head), free(next);
        return;
    }
    /* Jittered grid: round(sqrt(n)) rows, row r with floor(n(r+1)/R) - floor(nr/R) cells. */
    int rows = (int)lround(sqrt((double)n));
    if (rows < 1)
        rows = 1;
    for (int r = 0, i = 0; r < rows; r++) {
        int first = (int)((long)n * r / rows), cols = (int)((long)n * (r + 1) / rows) - first;
        for (int j = 0; j < cols; j++, i++) {
            u[i] = (j + next_uniform(rng)) / cols;
            v[i] = (r + next_uniform(rng)) / rows;
        }
    }
    for (int y = 0; y < res; y++) {
        int r = (int)((y + 0.5) / res * rows);
        int first = (int)((long)n * r / rows), cols = (int)((long)n * (r + 1) / rows) - first;
        for (int x = 0; x < res; x++)
            owner[y * res + x] = first + (int)((x + 0.5) / res * cols);
    }
}

int gib_vpls_create(gib_vpls *v, const gib_light_views *views, int count, unsigned seed,
                    const char *label, gib_ledger *ledger, gib_error *err)
{
    memset(v, 0, sizeof *v);
    int F = views->face_count, res = views->res;
    const unsigned need = GIB_LV_POSITION | GIB_LV_NORMAL | GIB_LV_FLUX;
    if ((views->attributes & need) != need)
        return gib_fail(err, "VPLs need the light views' position, normal and flux");
    if (F && count < F)
        return gib_fail(err, "parameter 'vpl_count' = %d is below the light views' %d faces (a "
                        "face without a VPL would lose its flux)", count, F);
    v->count = F ? count : 0;
    v->res = res;
    int n_alloc = v->count ? v->count : 1;
    int *cells = calloc((size_t)n_alloc * 4, sizeof *cells);
    int *texels = calloc((size_t)(F ? F : 1) * res * res, sizeof *texels);
    int *owner = malloc((size_t)res * res * sizeof *owner);
    int *fill = malloc((size_t)n_alloc * sizeof *fill);
    double *u = malloc((size_t)n_alloc * sizeof *u), *w = malloc((size_t)n_alloc * sizeof *w);
    if (!cells || !texels || !owner || !fill || !u || !w) {
        free(cells), free(texels), free(owner), free(fill), free(u), free(w);
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    }
    uint64_t rng = seed;
    int base = 0, list = 0;
    for (int f = 0; f < F; f++) {
        int n = (int)((long)count * (f + 1) / F) - (int)((long)count * f / F);
        face_pattern(views->faces[f].kind, n, res, &rng, u, w, owner);
        for (int i = 0; i < n; i++) {
            int sx = (int)(u[i] * res), sy = (int)(w[i] * res);
            sx = sx < 0 ? 0 : sx >= res ? res - 1 : sx;
            sy = sy < 0 ? 0 : sy >= res ? res - 1 : sy;
            int *c = cells + 4 * (base + i);
            c[0] = f;
            c[1] = sy * res + sx;
            c[3] = 0;
            fill[i] = 0;
        }
        for (int k = 0; k < res * res; k++)
            cells[4 * (base + owner[k]) + 3]++;
        for (int i = 0; i < n; i++) {
            cells[4 * (base + i) + 2] = list;
            list += cells[4 * (base + i) + 3];
        }
        for (int k = 0; k < res * res; k++) {
            int o = owner[k];
            texels[cells[4 * (base + o) + 2] + fill[o]++] = k;
        }
        base += n;
    }
    free(owner), free(fill), free(u), free(w);
    char name[96];
    snprintf(name, sizeof name, "%s.buffer", label);
    if (!(v->buffer = gib_gpu_buffer(ledger, name, 4ull * GIB_VPL_FLOATS * n_alloc, NULL,
                                     GL_DYNAMIC_STORAGE_BIT, err)))
        goto fail;
    snprintf(name, sizeof name, "%s.cells", label);
    if (!(v->cells = gib_gpu_buffer(ledger, name, 16ull * n_alloc, cells, 0, err)))
        goto fail;
    snprintf(name, sizeof name, "%s.regions", label);
    if (!(v->texels = gib_gpu_buffer(ledger, name, 4ull * (list ? list : 1), texels, 0, err)))
        goto fail;
    free(cells), free(texels);
    const float zero = 0;
    glClearNamedBufferData(v->buffer, GL_R32F, GL_RED, GL_FLOAT, &zero);
    const char *files[] = {"common/vpl_extract.comp"};
    if (!(v->program = gib_program(files, 1, NULL, err)))
        return -1;
    return gib_gl_check("VPL creation", err);
fail:
    free(cells), free(texels);
    return -1;
}

void gib_vpls_update(gib_vpls *v, const gib_light_views *views, gib_timers *timers, const char *pass)
{
    if (!v->count)
        return;
    gib_timer_begin(timers, pass);
    glUseProgram(v->program);
    gib_light_views_bind(views);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_VPL_SSBO_VPLS, v->buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_VPL_SSBO_CELLS, v->cells);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_VPL_SSBO_TEXELS, v->texels);
    glUniform1i(GIB_VPL_LOC_RES, v->res);
    glUniform1i(GIB_VPL_LOC_COUNT, v->count);
    glDispatchCompute((GLuint)v->count, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    gib_timer_end(timers);
}

void gib_vpls_bind(const gib_vpls *v)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_VPL_SSBO_VPLS, v->buffer);
}

int gib_vpls_read(const gib_vpls *v, float *out)
{
    if (!v->count)
        return 0;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(v->buffer, 0, (GLsizeiptr)(4ull * GIB_VPL_FLOATS * v->count), out);
    return 0;
}

void gib_vpls_write(gib_vpls *v, const float *in, int n)
{
    if (n > v->count)
        n = v->count;
    glNamedBufferSubData(v->buffer, 0, (GLsizeiptr)(4ull * GIB_VPL_FLOATS * n), in);
}

int gib_vpls_probe(const gib_vpls *v, float clamp_distance, const float *in, int n, float *out,
                   gib_error *err)
{
    const char *files[] = {"common/vpl_probe.comp"};
    unsigned prog = gib_program(files, 1, NULL, err);
    if (!prog)
        return -1;
    unsigned buf[2];
    glCreateBuffers(2, buf);
    glNamedBufferStorage(buf[0], (GLsizeiptr)(32ull * n), in, 0);
    glNamedBufferStorage(buf[1], (GLsizeiptr)(16ull * n), NULL, GL_DYNAMIC_STORAGE_BIT);
    glUseProgram(prog);
    gib_vpls_bind(v);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_VPL_PROBE_SSBO_IN, buf[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_VPL_PROBE_SSBO_OUT, buf[1]);
    glUniform1i(GIB_VPL_PROBE_LOC_COUNT, n);
    glUniform1i(GIB_VPL_PROBE_LOC_VPLS, v->count);
    glUniform1f(GIB_VPL_PROBE_LOC_EPS, clamp_distance);
    glDispatchCompute(gib_groups((unsigned)n, GIB_GROUP_1D), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buf[1], 0, (GLsizeiptr)(16ull * n), out);
    glDeleteBuffers(2, buf);
    glDeleteProgram(prog);
    return gib_gl_check("VPL probe", err);
}

void gib_vpls_destroy(gib_vpls *v, gib_ledger *ledger)
{
    if (v->program)
        glDeleteProgram(v->program);
    if (v->buffer)
        gib_gpu_free(ledger, v->buffer, 0);
    if (v->cells)
        gib_gpu_free(ledger, v->cells, 0);
    if (v->texels)
        gib_gpu_free(ledger, v->texels, 0);
    memset(v, 0, sizeof *v);
}

int gib_vpl_frame_create(gib_vpl_frame *f, const gib_gpu_scene *scene, int width, int height,
                         int rsm_res, int vpl_count, gib_ledger *ledger, gib_error *err)
{
    if (gib_gbuffer_create(&f->gbuffer, width, height, ledger, err) < 0 ||
        gib_light_views_create(&f->views, scene, rsm_res,
                               GIB_LV_POSITION | GIB_LV_NORMAL | GIB_LV_FLUX, "rsm", ledger,
                               err) < 0 ||
        gib_vpls_create(&f->vpls, &f->views, vpl_count, 1, "vpl", ledger, err) < 0)
        return -1;
    return 0;
}

void gib_vpl_frame_render(gib_vpl_frame *f, const gib_gpu_scene *scene, const gib_view *view,
                          gib_timers *timers)
{
    gib_gbuffer_render(&f->gbuffer, scene, view, timers, "gbuffer");
    gib_light_views_render(&f->views, scene, timers, "rsm");
    gib_vpls_update(&f->vpls, &f->views, timers, "rsm");
}

void gib_vpl_frame_destroy(gib_vpl_frame *f, gib_ledger *ledger)
{
    gib_vpls_destroy(&f->vpls, ledger);
    gib_light_views_destroy(&f->views, ledger);
    gib_gbuffer_destroy(&f->gbuffer, ledger);
}

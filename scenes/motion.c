/* gibench — scenes that move (FORMAT.md, "Motion"): rigid meshes posed by keyframes, water
 * surfaces as sums of travelling waves. One function, gib_motion_pose, says where every moving
 * vertex is at time t; the GL side uploads what it writes, the path tracer builds its BVH from it,
 * so both render the same instant. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

/* The keyframe segment holding t and the weight of its second key (loop: t wraps over the keys'
 * span; otherwise the first and last values hold outside it, as glTF and USD do). */
static void find_segment(const gib_motion *m, double t, int *i0, double *w)
{
    const int n = m->key_count;
    const double t0 = m->key_time[0], t1 = m->key_time[n - 1];
    if (m->loop && n >= 2) {
        const double span = t1 - t0;
        t = t0 + (t - t0) - span * floor((t - t0) / span);
    }
    if (n == 1 || t <= t0) {
        *i0 = 0;
        *w = 0.0;
        return;
    }
    if (t >= t1) {
        *i0 = n - 2;
        *w = 1.0;
        return;
    }
    int i = 0;
    while (i + 2 < n && t >= m->key_time[i + 1])
        i++;
    *i0 = i;
    *w = (t - m->key_time[i]) / ((double)m->key_time[i + 1] - m->key_time[i]);
}

/* Rotation and translation of a rigid motion at time t. */
static void rigid_at(const gib_motion *m, double t, float r[3][3], float tr[3])
{
    int i;
    double w;
    find_segment(m, t, &i, &w);
    const int j = m->key_count > 1 ? i + 1 : i;
    float deg[3];
    for (int k = 0; k < 3; k++) {
        deg[k] = (float)((1.0 - w) * m->key_rotate[i][k] + w * m->key_rotate[j][k]);
        tr[k] = (float)((1.0 - w) * m->key_translate[i][k] + w * m->key_translate[j][k]);
    }
    gib_euler_rotation(deg, r);
}

static void mul3(const float m[3][3], const float v[3], float out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
}

static void normalize3(float v[3])
{
    const float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0.0f && isfinite(l))
        for (int i = 0; i < 3; i++)
            v[i] /= l;
}

void gib_motion_pose(const gib_motion *m, double t, float *pos, float *nrm)
{
    if (m->kind == GIB_MOTION_RIGID) {
        float r[3][3], tr[3];
        rigid_at(m, t, r, tr);
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            const float *p = m->rest_positions + 3 * (size_t)v;
            const float d[3] = {p[0] - m->pivot[0], p[1] - m->pivot[1], p[2] - m->pivot[2]};
            float q[3];
            mul3(r, d, q);
            for (int k = 0; k < 3; k++)
                pos[3 * (size_t)v + k] = q[k] + m->pivot[k] + tr[k];
            mul3(r, m->rest_normals + 3 * (size_t)v, nrm + 3 * (size_t)v);
        }
        return;
    }
    /* Water: height and slope of the sum of waves in the mesh's frame (double: the phase k.x - wt
     * grows with t and with the surface's size), then the mesh's placement. */
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *p = m->rest_positions + 3 * (size_t)v;
        double h = 0.0, dx = 0.0, dz = 0.0;
        for (int i = 0; i < m->wave_count; i++) {
            const gib_wave *wv = &m->waves[i];
            const double ph = (double)wv->k[0] * p[0] + (double)wv->k[1] * p[2] - wv->omega * t;
            const double c = cos(ph);
            h += wv->amplitude * sin(ph);
            dx += wv->amplitude * wv->k[0] * c;
            dz += wv->amplitude * wv->k[1] * c;
        }
        const float local[3] = {p[0], (float)h, p[2]};
        const float ln[3] = {(float)-dx, 1.0f, (float)-dz};
        float q[3];
        mul3(m->m, local, q);
        for (int k = 0; k < 3; k++)
            pos[3 * (size_t)v + k] = q[k] + m->translate[k];
        float *n = nrm + 3 * (size_t)v;
        mul3(m->nm, ln, n);
        normalize3(n);
    }
}

void gib_scene_set_time(gib_scene *s, double t)
{
    for (uint32_t i = 0; i < s->motion_count; i++) {
        const gib_motion *m = &s->motions[i];
        gib_motion_pose(m, t, s->positions + 3 * (size_t)m->first_vertex,
                        s->normals + 3 * (size_t)m->first_vertex);
    }
    if (s->motion_count)
        s->time = (float)t;
}

int gib_scene_posed(const gib_scene *s, double t, gib_scene *out, gib_error *err)
{
    *out = *s;
    if (!s->motion_count)
        return 0;
    const size_t n = 3 * (size_t)s->vertex_count;
    out->positions = gib_calloc(n, sizeof(float), err);
    out->normals = gib_calloc(n, sizeof(float), err);
    if (!out->positions || !out->normals) {
        free(out->positions);
        free(out->normals);
        memset(out, 0, sizeof *out);
        return -1;
    }
    memcpy(out->positions, s->positions, n * sizeof(float));
    memcpy(out->normals, s->normals, n * sizeof(float));
    gib_scene_set_time(out, t);
    return 0;
}

void gib_scene_posed_free(gib_scene *posed)
{
    if (posed->motion_count) {
        free(posed->positions);
        free(posed->normals);
    }
    memset(posed, 0, sizeof *posed);
}

/* ------------------------------------------------------------------ building */

static void grow_box(float lo[3], float hi[3], const float p[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = fminf(lo[k], p[k]);
        hi[k] = fmaxf(hi[k], p[k]);
    }
}

/* A box holding motion m's vertices at every instant. Rigid: the translation moves within the
 * keys' box (linear interpolation), and a rotation keeps each vertex at its distance from the
 * pivot, so the rotated mesh lies in the pivot's ball of the largest such distance (or exactly in
 * the one rotated box when every key has the same rotation). Water: the grid's box with heights
 * within +-sum of amplitudes, its 8 corners placed. */
static void motion_bounds(const gib_motion *m, float lo[3], float hi[3])
{
    if (m->kind == GIB_MOTION_WATER) {
        float a = 0.0f, blo[3] = {INFINITY, INFINITY, INFINITY}, bhi[3] = {-INFINITY, -INFINITY,
                                                                          -INFINITY};
        for (int i = 0; i < m->wave_count; i++)
            a += m->waves[i].amplitude;
        for (uint32_t v = 0; v < m->vertex_count; v++)
            grow_box(blo, bhi, m->rest_positions + 3 * (size_t)v);
        blo[1] = -a;
        bhi[1] = a;
        for (int c = 0; c < 8; c++) {
            const float p[3] = {c & 1 ? bhi[0] : blo[0], c & 2 ? bhi[1] : blo[1],
                                c & 4 ? bhi[2] : blo[2]};
            float q[3];
            mul3(m->m, p, q);
            for (int k = 0; k < 3; k++)
                q[k] += m->translate[k];
            grow_box(lo, hi, q);
        }
        return;
    }
    float tlo[3] = {INFINITY, INFINITY, INFINITY}, thi[3] = {-INFINITY, -INFINITY, -INFINITY};
    int same_rotation = 1;
    for (int i = 0; i < m->key_count; i++) {
        grow_box(tlo, thi, m->key_translate[i]);
        same_rotation &= !memcmp(m->key_rotate[i], m->key_rotate[0], sizeof m->key_rotate[0]);
    }
    float r[3][3];
    gib_euler_rotation(m->key_rotate[0], r);
    float rlo[3] = {INFINITY, INFINITY, INFINITY}, rhi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double r2 = 0.0;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *p = m->rest_positions + 3 * (size_t)v;
        const float d[3] = {p[0] - m->pivot[0], p[1] - m->pivot[1], p[2] - m->pivot[2]};
        float q[3];
        mul3(r, d, q);
        grow_box(rlo, rhi, q);
        r2 = fmax(r2, (double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
    }
    const float rad = (float)sqrt(r2) * (1.0f + 1e-6f);
    for (int k = 0; k < 3; k++) {
        const float a = same_rotation ? rlo[k] : -rad, b = same_rotation ? rhi[k] : rad;
        lo[k] = fminf(lo[k], m->pivot[k] + a + tlo[k]);
        hi[k] = fmaxf(hi[k], m->pivot[k] + b + thi[k]);
    }
}

int gib_scene_build_motion(const gib_scene_spec *s, const uint32_t *vbegin, gib_scene *sc,
                           gib_error *err)
{
    int n = 0;
    for (int i = 0; i < s->mesh_count; i++)
        n += s->meshes[i].keys_line || s->meshes[i].wave_count;
    if (!n)
        return 0;
    if (!(sc->motions = gib_calloc((size_t)n, sizeof *sc->motions, err)))
        return -1;
    for (int i = 0; i < s->mesh_count; i++) {
        const gib_mesh_spec *ms = &s->meshes[i];
        if (!ms->keys_line && !ms->wave_count)
            continue;
        gib_motion *m = &sc->motions[sc->motion_count++];
        snprintf(m->mesh, sizeof m->mesh, "%s", ms->name);
        m->first_vertex = vbegin[i];
        m->vertex_count = vbegin[i + 1] - vbegin[i];
        const size_t nf = 3 * (size_t)m->vertex_count;
        if (!(m->rest_positions = gib_calloc(nf + 1, sizeof(float), err)))
            return -1;
        memcpy(m->rest_positions, sc->positions + 3 * (size_t)m->first_vertex, nf * sizeof(float));
        if (ms->wave_count) {
            m->kind = GIB_MOTION_WATER;
            /* The placed grid back in the mesh's frame: the generator built it at y = 0 there. */
            float r[3][3];
            gib_euler_rotation(ms->rotate_deg, r);
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++) {
                    m->m[a][b] = r[a][b] * ms->scale[b];
                    m->nm[a][b] = r[a][b] / ms->scale[b];
                }
            /* [scene] shift moved the placed grid: the placement's translation includes it. */
            for (int k = 0; k < 3; k++)
                m->translate[k] = (float)((double)ms->translate[k] + s->shift[k]);
            for (uint32_t v = 0; v < m->vertex_count; v++) {
                float *p = m->rest_positions + 3 * (size_t)v;
                const float d[3] = {p[0] - m->translate[0], p[1] - m->translate[1],
                                    p[2] - m->translate[2]};
                for (int b = 0; b < 3; b++)
                    p[b] = (r[0][b] * d[0] + r[1][b] * d[1] + r[2][b] * d[2]) / ms->scale[b];
                p[1] = 0.0f;
            }
            m->wave_count = ms->wave_count;
            for (int w = 0; w < ms->wave_count; w++) {
                const double k = 2.0 * M_PI / ms->waves[w][1], dir = ms->waves[w][2] * M_PI / 180.0;
                m->waves[w].amplitude = ms->waves[w][0];
                m->waves[w].k[0] = (float)(k * cos(dir));
                m->waves[w].k[1] = (float)(k * sin(dir));
                m->waves[w].omega = (float)(k * ms->waves[w][3]);
            }
        } else {
            m->kind = GIB_MOTION_RIGID;
            if (!(m->rest_normals = gib_calloc(nf + 1, sizeof(float), err)))
                return -1;
            memcpy(m->rest_normals, sc->normals + 3 * (size_t)m->first_vertex, nf * sizeof(float));
            m->key_count = ms->key_count;
            m->loop = ms->loop;
            memcpy(m->key_time, ms->key_time, sizeof m->key_time);
            memcpy(m->key_rotate, ms->key_rotate, sizeof m->key_rotate);
            memcpy(m->key_translate, ms->key_translate, sizeof m->key_translate);
            for (int k = 0; k < 3; k++) /* a world point: [scene] shift moves it too */
                m->pivot[k] = (float)((double)ms->pivot[k] + s->shift[k]);
        }
    }
    gib_scene_set_time(sc, 0.0);
    /* Bounds: the static vertices as they are, each motion's box over every instant. */
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    uint32_t next = 0;
    for (uint32_t mi = 0; mi <= sc->motion_count; mi++) {
        const uint32_t end =
            mi < sc->motion_count ? sc->motions[mi].first_vertex : sc->vertex_count;
        for (uint32_t v = next; v < end; v++)
            grow_box(lo, hi, sc->positions + 3 * (size_t)v);
        if (mi < sc->motion_count) {
            motion_bounds(&sc->motions[mi], lo, hi);
            next = end + sc->motions[mi].vertex_count;
        }
    }
    memcpy(sc->bounds_min, lo, sizeof lo);
    memcpy(sc->bounds_max, hi, sizeof hi);
    return 0;
}

void gib_scene_free_motion(gib_scene *sc)
{
    for (uint32_t i = 0; i < sc->motion_count; i++) {
        free(sc->motions[i].rest_positions);
        free(sc->motions[i].rest_normals);
    }
    free(sc->motions);
    sc->motions = NULL;
    sc->motion_count = 0;
}

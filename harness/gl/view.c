#include "view.h"

#include <math.h>
#include <string.h>

void gib_mat4_mul(const float a[16], const float b[16], float out[16])
{
    float r[16];
    for (int c = 0; c < 4; c++)
        for (int rr = 0; rr < 4; rr++) {
            float s = 0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + rr] * b[c * 4 + k];
            r[c * 4 + rr] = s;
        }
    memcpy(out, r, sizeof r);
}

void gib_mat4_view(const float right[3], const float up[3], const float forward[3],
                   const float eye[3], float out[16])
{
    /* Rows: right, up, -forward (GL looks down -z). */
    float m[16] = {0};
    for (int i = 0; i < 3; i++) {
        m[i * 4 + 0] = right[i];
        m[i * 4 + 1] = up[i];
        m[i * 4 + 2] = -forward[i];
    }
    m[12] = -(right[0] * eye[0] + right[1] * eye[1] + right[2] * eye[2]);
    m[13] = -(up[0] * eye[0] + up[1] * eye[1] + up[2] * eye[2]);
    m[14] = forward[0] * eye[0] + forward[1] * eye[1] + forward[2] * eye[2];
    m[15] = 1;
    memcpy(out, m, sizeof m);
}

void gib_ortho_basis(const float d[3], float t[3], float b[3])
{
    float up[3] = {0, 1, 0};
    if (fabsf(d[1]) >= 0.99f) {
        up[0] = 1;
        up[1] = 0;
    }
    t[0] = up[1] * d[2] - up[2] * d[1];
    t[1] = up[2] * d[0] - up[0] * d[2];
    t[2] = up[0] * d[1] - up[1] * d[0];
    float n = sqrtf(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int i = 0; i < 3; i++)
        t[i] /= n;
    b[0] = d[1] * t[2] - d[2] * t[1];
    b[1] = d[2] * t[0] - d[0] * t[2];
    b[2] = d[0] * t[1] - d[1] * t[0];
}

void gib_mat4_perspective(float vfov, float aspect, float n, float f, float out[16])
{
    float t = 1.0f / tanf(vfov * 0.5f);
    memset(out, 0, 16 * sizeof(float));
    out[0] = t / aspect;
    out[5] = t;
    out[10] = (f + n) / (n - f);
    out[11] = -1;
    out[14] = 2 * f * n / (n - f);
}

void gib_mat4_perspective_reversed(float vfov, float aspect, float n, float f, float out[16])
{
    float t = 1.0f / tanf(vfov * 0.5f);
    memset(out, 0, 16 * sizeof(float));
    out[0] = t / aspect;
    out[5] = t;
    out[10] = n / (f - n);
    out[11] = -1;
    out[14] = f * n / (f - n);
}

void gib_mat4_ortho_reversed(float l, float r, float b, float t, float n, float f, float out[16])
{
    gib_mat4_ortho(l, r, b, t, n, f, out);
    out[10] = 1 / (f - n);
    out[14] = f / (f - n);
}

void gib_mat4_ortho(float l, float r, float b, float t, float n, float f, float out[16])
{
    memset(out, 0, 16 * sizeof(float));
    out[0] = 2 / (r - l);
    out[5] = 2 / (t - b);
    out[10] = -2 / (f - n);
    out[12] = -(r + l) / (r - l);
    out[13] = -(t + b) / (t - b);
    out[14] = -(f + n) / (f - n);
    out[15] = 1;
}

void gib_view_make(const gib_scene *s, const gib_camera *cam, int w, int h, float time,
                   gib_view *v)
{
    memset(v, 0, sizeof *v);
    v->camera = cam;
    v->width = w;
    v->height = h;
    v->time = time;
    float right[3], up[3], fwd[3];
    gib_camera_basis(cam, right, up, fwd);
    const float zero[3] = {0, 0, 0};
    gib_mat4_view(right, up, fwd, zero, v->view);
    memcpy(v->origin, cam->eye, sizeof v->origin);
    /* Far plane beyond the farthest bounding-box corner; near plane a small fraction of it (a 24-bit
     * depth buffer keeps ~1e-4 relative precision at the far plane with this ratio). */
    float far = 0;
    for (int c = 0; c < 8; c++) {
        float p[3] = {c & 1 ? s->bounds_max[0] : s->bounds_min[0],
                      c & 2 ? s->bounds_max[1] : s->bounds_min[1],
                      c & 4 ? s->bounds_max[2] : s->bounds_min[2]};
        float d = sqrtf((p[0] - cam->eye[0]) * (p[0] - cam->eye[0]) +
                        (p[1] - cam->eye[1]) * (p[1] - cam->eye[1]) +
                        (p[2] - cam->eye[2]) * (p[2] - cam->eye[2]));
        if (d > far)
            far = d;
    }
    far = far * 1.01f + 1e-3f;
    gib_mat4_perspective(cam->vfov_deg * (float)M_PI / 180.0f, (float)w / (float)h, far * 1e-4f,
                         far, v->proj);
    gib_mat4_mul(v->proj, v->view, v->view_proj);
}

void gib_view_bounding_sphere(const gib_scene *s, float c[3], float *r)
{
    float d2 = 0;
    for (int i = 0; i < 3; i++) {
        c[i] = 0.5f * (s->bounds_min[i] + s->bounds_max[i]);
        float e = s->bounds_max[i] - s->bounds_min[i];
        d2 += e * e;
    }
    /* the margin relative to the scene's size (an absolute one fits no single scale: hard_tiny
     * is millimetres across); a point-sized scene still gets a map */
    *r = 0.5f * sqrtf(d2) * 1.01f;
    if (!(*r > 0.0f))
        *r = 1e-6f;
}

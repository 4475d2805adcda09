/* The diffuse cone set on the C side (cone_set.h). */
#include "harness/base/cone_set.h"

#include <math.h>

static void cross3(const float a[3], const float b[3], float o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static void normalize3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        v[k] /= l;
}

void gib_cone_basis(const float d[3], float t[3], float b[3])
{
    const float up[3] = {fabsf(d[1]) < 0.99f ? 0.0f : 1.0f, fabsf(d[1]) < 0.99f ? 1.0f : 0.0f, 0.0f};
    cross3(up, d, t);
    normalize3(t);
    cross3(d, t, b);
}

void gib_diffuse_cone_dir(int i, const float n[3], float dir[3])
{
    if (i == 0) {
        for (int k = 0; k < 3; k++)
            dir[k] = n[k];
        return;
    }
    const float tilt = 1.0471976f, phi = (float)(i - 1) * 1.2566371f; /* 60, 72 degrees */
    float t[3], b[3];
    gib_cone_basis(n, t, b);
    for (int k = 0; k < 3; k++)
        dir[k] = cosf(tilt) * n[k] + sinf(tilt) * (cosf(phi) * t[k] + sinf(phi) * b[k]);
    normalize3(dir);
}

float gib_diffuse_cone_weight(int i)
{
    return i == 0 ? 2.0f / 7.0f : 1.0f / 7.0f;
}

void gib_cone_cap_sample(const float axis[3], float half, float u1, float u2, float d[3])
{
    float t[3], b[3];
    gib_cone_basis(axis, t, b);
    float cos_t = 1.0f - u1 * (1.0f - cosf(half));
    float sin_t = sqrtf(fmaxf(0.0f, 1.0f - cos_t * cos_t));
    float phi = 6.2831853f * u2;
    for (int k = 0; k < 3; k++)
        d[k] = cos_t * axis[k] + sin_t * (cosf(phi) * t[k] + sinf(phi) * b[k]);
}

/* gibench — THE camera and light definitions (DESIGN.md, "One scene model for both sides").
 *
 * The path tracer calls these functions and the GL shaders mirror them line by line
 * (techniques/common/scene.glsl), so they are kept as plain as possible: every formula here is one
 * that can be written identically in GLSL, in single precision, with no special cases that only
 * one side would have. */
#include <math.h>
#include <stdio.h>

#include "scene.h"

static float dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const float a[3], const float b[3], float out[3])
{
    float x = a[1] * b[2] - a[2] * b[1];
    float y = a[2] * b[0] - a[0] * b[2];
    float z = a[0] * b[1] - a[1] * b[0];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

static void normalize3(float v[3])
{
    float len = sqrtf(dot3(v, v));
    if (len > 0.0f) {
        v[0] /= len;
        v[1] /= len;
        v[2] /= len;
    }
}

void gib_camera_basis(const gib_camera *cam, float right[3], float up[3], float forward[3])
{
    forward[0] = cam->target[0] - cam->eye[0];
    forward[1] = cam->target[1] - cam->eye[1];
    forward[2] = cam->target[2] - cam->eye[2];
    normalize3(forward);
    cross3(forward, cam->up, right);
    normalize3(right);
    /* right and forward are orthonormal, so this is unit length without normalising. */
    cross3(right, forward, up);
}

void gib_camera_ray(const gib_camera *cam, int width, int height, float px, float py,
                    float origin[3], float dir[3])
{
    float right[3], up[3], forward[3];
    gib_camera_basis(cam, right, up, forward);
    const float tan_half = tanf(0.5f * cam->vfov_deg * (float)(M_PI / 180.0));
    const float aspect = (float)width / (float)height;
    /* Row 0 is the top of the image: py grows downward, so y = +tan_half at py = 0. */
    const float x = (2.0f * px / (float)width - 1.0f) * aspect * tan_half;
    const float y = (1.0f - 2.0f * py / (float)height) * tan_half;
    for (int i = 0; i < 3; i++) {
        origin[i] = cam->eye[i];
        dir[i] = forward[i] + x * right[i] + y * up[i];
    }
    normalize3(dir);
}

float gib_spot_cos_outer(const gib_light *l)
{
    return cosf(l->spot_outer_deg * (float)(M_PI / 180.0));
}

float gib_spot_falloff(const gib_light *l, const float dir_from_light[3])
{
    return gib_spot_falloff_cos(l, gib_spot_cos_outer(l), dir_from_light);
}

float gib_spot_falloff_cos(const gib_light *l, float cos_outer, const float dir_from_light[3])
{
    /* Compare cosines instead of angles: no acos, and theta == outer counts as inside on both
     * sides. dir_from_light need not be unit length; the axis is (the loader normalises it). */
    const float len = sqrtf(dot3(dir_from_light, dir_from_light));
    if (!(len > 0.0f))
        return 0.0f;
    const float cos_theta = dot3(dir_from_light, l->direction) / len;
    if (cos_theta < cos_outer)
        return 0.0f;
    /* Clamped so an outer angle beyond 90 degrees never takes pow() of a negative number. */
    float c = fmaxf(cos_theta, 0.0f);
    /* Cosine falloff (e = 1, the Cornell and Sponza spots) is common and powf is ~5% of the path
     * tracer's time on Sponza: the shortcut gives the identical value. */
    return l->spot_exponent == 1.0f ? c : powf(c, l->spot_exponent);
}

int gib_light_eval(const gib_light *l, const float p[3], float wi[3], float *dist, float E[3])
{
    return gib_light_eval_cos(l, l->type == GIB_LIGHT_SPOT ? gib_spot_cos_outer(l) : -1.0f, p, wi,
                              dist, E);
}

int gib_light_eval_cos(const gib_light *l, float cos_outer, const float p[3], float wi[3],
                       float *dist, float E[3])
{
    if (l->type == GIB_LIGHT_DIRECTIONAL) {
        wi[0] = -l->direction[0];
        wi[1] = -l->direction[1];
        wi[2] = -l->direction[2];
        *dist = INFINITY;
        E[0] = l->intensity[0];
        E[1] = l->intensity[1];
        E[2] = l->intensity[2];
        return 1;
    }
    float d[3] = {l->position[0] - p[0], l->position[1] - p[1], l->position[2] - p[2]};
    const float r2 = dot3(d, d);
    /* A point exactly at the light receives nothing rather than an infinity (hard case "light
     * touching a surface"): finite output is required of every estimator. */
    if (!(r2 > 0.0f)) {
        wi[0] = 0.0f;
        wi[1] = 1.0f;
        wi[2] = 0.0f;
        *dist = 0.0f;
        E[0] = E[1] = E[2] = 0.0f;
        return 0;
    }
    const float r = sqrtf(r2);
    wi[0] = d[0] / r;
    wi[1] = d[1] / r;
    wi[2] = d[2] / r;
    *dist = r;
    float falloff = 1.0f;
    if (l->type == GIB_LIGHT_SPOT) {
        const float from_light[3] = {-wi[0], -wi[1], -wi[2]};
        falloff = gib_spot_falloff_cos(l, cos_outer, from_light);
        if (falloff <= 0.0f) {
            E[0] = E[1] = E[2] = 0.0f;
            return 0;
        }
    }
    E[0] = l->intensity[0] * falloff / r2;
    E[1] = l->intensity[1] * falloff / r2;
    E[2] = l->intensity[2] * falloff / r2;
    return 1;
}

void gib_features_str(unsigned features, char *out, int out_len)
{
    static const char *names[] = {"textures",   "specular",  "mirror",     "point_light",
                                  "spot_light", "dir_light", "alpha_mask", "closed", "sky"};
    if (!out || out_len <= 0)
        return;
    out[0] = '\0';
    int used = 0;
    for (unsigned i = 0; i < sizeof names / sizeof names[0]; i++) {
        if (!(features & (1u << i)))
            continue;
        int n = snprintf(out + used, (size_t)(out_len - used), "%s%s", used ? "," : "", names[i]);
        if (n < 0 || n >= out_len - used)
            break; /* truncated: out is still NUL-terminated */
        used += n;
    }
}

/* gibench — THE camera and light definitions (ARCHITECTURE.md, "One scene model for both sides").
 *
 * The path tracer calls these functions and the GL shaders mirror them line by line
 * (techniques/common/scene.glsl), so they are kept as plain as possible: every formula here is one
 * that can be written identically in GLSL, in single precision, with no special cases that only
 * one side would have. The light evaluation itself is in light_eval.h, static inline, so that the
 * path tracer's next-event estimation inlines it. */
#include <math.h>
#include <stdio.h>

#include "scene.h"

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
    float len = sqrtf(gib_dot3(v, v));
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

int gib_light_eval(const gib_light *l, const float p[3], float wi[3], float *dist, float E[3])
{
    return gib_light_eval_cos(l, l->type == GIB_LIGHT_SPOT ? gib_spot_cos_outer(l) : -1.0f, p, wi,
                              dist, E);
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

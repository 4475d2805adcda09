/* gibench — the reference renderer's estimators, one per light-transport component (DESIGN.md,
 * "Light-transport components"). Each evaluates one sample at a visible surface point that the
 * render loop found through a pixel centre. */
#include <math.h>

#include "ref_internal.h"

#define REF_PI 3.14159265358979323846f

/* rho_d: the material's albedo times its texture (already linear, scene.h). */
static void ref_albedo(const gib_scene *gs, const ref_hit *h, float a[3])
{
    const gib_material *m = h->mat;
    a[0] = m->albedo[0];
    a[1] = m->albedo[1];
    a[2] = m->albedo[2];
    if (m->albedo_tex >= 0) {
        float t[4];
        ref_tex_sample(&gs->textures[m->albedo_tex], h->uv[0], h->uv[1], t);
        a[0] *= t[0];
        a[1] *= t[1];
        a[2] *= t[2];
    }
}

/* Direct light, L D E and L S E with shadows: for every light, f(wo, wi) E max(0, n.wi), with
 * f = rho_d / pi + rho_s (n + 2) / (2 pi) max(0, r.wi)^n (normalised Phong, r the mirror direction
 * of wo about n). A mirror lobe adds nothing here: a delta lobe meets a point, spot or directional
 * light (a delta in direction) with probability zero, so only its diffuse part is lit directly;
 * the light seen in a mirror belongs to caustic/full paths, not to `direct`.
 * No random numbers: with delta lights the estimator is exact, so 1 spp is the converged image. */
void ref_est_direct(const ref_world *w, const ref_hit *h, const float wo[3], float out[3],
                    long long *rays)
{
    const gib_scene *gs = w->gs;
    out[0] = out[1] = out[2] = 0.0f;
    if (h->back)
        return;
    float albedo[3];
    ref_albedo(gs, h, albedo);
    const gib_material *m = h->mat;
    int phong = m->spec_type == GIB_SPEC_PHONG;
    float r[3] = {0.0f, 0.0f, 0.0f};
    if (phong) {
        float nw = 2.0f * ref_dot(h->n, wo);
        for (int k = 0; k < 3; k++)
            r[k] = nw * h->n[k] - wo[k];
    }
    for (uint32_t i = 0; i < gs->light_count; i++) {
        float wi[3], dist, E[3];
        if (!gib_light_eval(&gs->lights[i], h->p, wi, &dist, E))
            continue;
        float cosn = ref_dot(h->n, wi);
        if (!(cosn > 0.0f) || (E[0] == 0.0f && E[1] == 0.0f && E[2] == 0.0f))
            continue;
        float f[3];
        for (int k = 0; k < 3; k++)
            f[k] = albedo[k] * (1.0f / REF_PI);
        if (phong) {
            float rw = ref_dot(r, wi);
            if (rw > 0.0f) {
                float lobe = (m->phong_n + 2.0f) * (0.5f / REF_PI) * powf(rw, m->phong_n);
                for (int k = 0; k < 3; k++)
                    f[k] += m->specular[k] * lobe;
            }
        }
        /* The shadow ray stops eps short of the light: a light resting on a surface is not
         * shadowed by that surface (DESIGN.md, "Hard cases": a light touching a surface). */
        float o[3];
        ref_offset_origin(w, h, wi, o);
        float tfar = isinf(dist) ? INFINITY : dist - w->eps;
        if (tfar > 0.0f) {
            ++*rays;
            if (ref_occluded(w, o, wi, tfar))
                continue;
        }
        for (int k = 0; k < 3; k++)
            out[k] += f[k] * E[k] * cosn;
    }
}

/* Orthonormal basis around a unit vector (Duff et al. 2017, "Building an Orthonormal Basis,
 * Revisited"): branch-free and continuous except across n.z = 0's sign. */
static void ref_basis(const float n[3], float t[3], float b[3])
{
    float sign = copysignf(1.0f, n[2]);
    float a = -1.0f / (sign + n[2]);
    float c = n[0] * n[1] * a;
    t[0] = 1.0f + sign * n[0] * n[0] * a;
    t[1] = sign * c;
    t[2] = -sign * n[0];
    b[0] = c;
    b[1] = sign + n[1] * n[1] * a;
    b[2] = -n[1];
}

/* Ambient occlusion, (1/pi) integral V cos dw about the viewer-facing shading normal. Directions
 * are cosine-distributed (pdf cos/pi), so the integrand over the pdf is V itself: each sample is
 * 0 or 1 and the pixel's mean is the unoccluded fraction, unbiased. Exactly two random numbers
 * per sample, drawn in a fixed order. */
float ref_est_ao(const ref_world *w, const ref_hit *h, float dmax, ref_pcg32 *rng, long long *rays)
{
    if (h->back)
        return 0.0f;
    float u1 = ref_pcg32_float(rng), u2 = ref_pcg32_float(rng);
    float phi = 2.0f * REF_PI * u1, r = sqrtf(u2);
    float lx = r * cosf(phi), ly = r * sinf(phi), lz = sqrtf(fmaxf(0.0f, 1.0f - u2));
    float t[3], b[3], d[3];
    ref_basis(h->n, t, b);
    for (int k = 0; k < 3; k++)
        d[k] = lx * t[k] + ly * b[k] + lz * h->n[k];
    float o[3];
    ref_offset_origin(w, h, d, o);
    float tfar = (dmax > 0.0f && isfinite(dmax)) ? dmax : INFINITY;
    ++*rays;
    return ref_occluded(w, o, d, tfar) ? 0.0f : 1.0f;
}

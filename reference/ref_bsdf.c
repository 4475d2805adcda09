/* gibench — the reference renderer's material model (scene.h): Lambertian rho_d / pi plus an
 * optional specular lobe, normalised Phong rho_s (n + 2) / (2 pi) max(0, r . wi)^n or a mirror
 * (a delta lobe of reflectance rho_s). Next-event estimation toward the scene's delta lights and
 * toward its sky, and importance sampling of each lobe. */
#include <math.h>
#include <string.h>

#include "ref_internal.h"

void ref_albedo(const ref_world *w, const ref_hit *h, float a[3])
{
    if (h->has_kd) {
        a[0] = h->kd[0], a[1] = h->kd[1], a[2] = h->kd[2];
        return;
    }
    const gib_material *m = h->mat;
    a[0] = m->albedo[0];
    a[1] = m->albedo[1];
    a[2] = m->albedo[2];
    if (m->albedo_tex >= 0) {
        float t[4];
        const ref_mip *mip = w->mips ? &w->mips[m->albedo_tex] : NULL;
        if (mip && mip->levels > 0)
            ref_mip_sample(mip, h->uv[0], h->uv[1], h->has_duv ? h->duv : NULL, t);
        else
            ref_tex_sample(&w->gs->textures[m->albedo_tex], h->uv[0], h->uv[1], t);
        a[0] *= t[0];
        a[1] *= t[1];
        a[2] *= t[2];
    }
}

void ref_material(const ref_world *w, const ref_hit *h, ref_mat *m)
{
    ref_albedo(w, h, m->kd);
    ref_material_specular(h, m);
}

void ref_material_specular(const ref_hit *h, ref_mat *m)
{
    const gib_material *g = h->mat;
    m->spec = g->spec_type;
    m->phong_n = g->phong_n;
    for (int k = 0; k < 3; k++)
        m->ks[k] = g->spec_type == GIB_SPEC_NONE ? 0.0f : g->specular[k];
    if (m->ks[0] <= 0.0f && m->ks[1] <= 0.0f && m->ks[2] <= 0.0f)
        m->spec = GIB_SPEC_NONE;
}

/* The shadow ray stops eps short of the light: a light resting on a surface is not shadowed by
 * that surface (ARCHITECTURE.md, "Hard cases": a light touching a surface). */
void ref_nee_visible(const ref_world *w, const ref_hit *h, const float wo[3], int want_d,
                     int want_s, float phong_n, uint32_t first, ref_nee_vis *v, long long *rays)
{
    const gib_scene *gs = w->gs;
    v->n = 0;
    if (h->back || (!want_d && !want_s))
        return;
    float r[3] = {0.0f, 0.0f, 0.0f};
    if (want_s)
        ref_reflect(wo, h->n, r);
    uint32_t end = gs->light_count - first < REF_NEE_LIGHTS ? gs->light_count
                                                             : first + REF_NEE_LIGHTS;
    for (uint32_t i = first; i < end; i++) {
        float wi[3], dist, E[3];
        if (!gib_light_eval_cos(&gs->lights[i], w->spot_cos[i], h->p, wi, &dist, E))
            continue;
        float cosn = ref_dot(h->n, wi);
        if (!(cosn > 0.0f) || (E[0] == 0.0f && E[1] == 0.0f && E[2] == 0.0f))
            continue;
        float lobe = 0.0f;
        if (want_s) {
            float rw = ref_dot(r, wi);
            if (rw > 0.0f)
                lobe = (phong_n + 2.0f) * (0.5f / REF_PI) * powf(rw, phong_n);
        }
        if (!want_d && !(lobe > 0.0f))
            continue;
        float o[3];
        ref_offset_origin(w, h, wi, o);
        float tfar = isinf(dist) ? INFINITY : dist - w->eps;
        if (tfar > 0.0f) {
            ++*rays;
            if (ref_occluded(w, o, wi, tfar))
                continue;
        }
        memcpy(v->e[v->n], E, sizeof E);
        v->cosn[v->n] = cosn;
        v->pb[v->n] = ref_lv_density(w, i, wi, dist, h->ng);
        v->wd[v->n] = 1.0f;
        v->lobe[v->n++] = lobe;
    }
}

void ref_nee_shade(const ref_nee_vis *v, const ref_mat *m, float dif[3], float spec[3])
{
    for (int i = 0; i < v->n; i++)
        for (int k = 0; k < 3; k++) {
            dif[k] += m->kd[k] * (1.0f / REF_PI) * v->e[i][k] * v->cosn[i] * v->wd[i];
            if (spec)
                spec[k] += m->ks[k] * v->lobe[i] * v->e[i][k] * v->cosn[i];
        }
}

void ref_nee(const ref_world *w, const ref_hit *h, const ref_mat *m, const float wo[3],
             float dif[3], float spec[3], long long *rays)
{
    ref_nee_weighed(w, h, m, wo, dif, spec, rays, NULL, NULL);
}

void ref_nee_weighed(const ref_world *w, const ref_hit *h, const ref_mat *m, const float wo[3],
                     float dif[3], float spec[3], long long *rays,
                     void (*weigh)(const void *arg, struct ref_nee_vis *v), const void *arg)
{
    dif[0] = dif[1] = dif[2] = 0.0f;
    if (spec)
        spec[0] = spec[1] = spec[2] = 0.0f;
    int want_d = m->kd[0] > 0.0f || m->kd[1] > 0.0f || m->kd[2] > 0.0f;
    int want_s = spec && m->spec == GIB_SPEC_PHONG;
    for (uint32_t first = 0; first < w->gs->light_count; first += REF_NEE_LIGHTS) {
        ref_nee_vis v;
        ref_nee_visible(w, h, wo, want_d, want_s, m->phong_n, first, &v, rays);
        if (weigh)
            weigh(arg, &v);
        ref_nee_shade(&v, m, dif, want_s ? spec : NULL);
    }
}

/* 1 when the ray leaving h along d (d . n_g > 0) escapes the scene and sees the sky. */
static int ref_sees_sky(const ref_world *w, const ref_hit *h, const float d[3], long long *rays)
{
    if (!(ref_dot(d, h->ng) > 0.0f))
        return 0;
    float o[3];
    ref_offset_origin(w, h, d, o);
    ++*rays;
    return !ref_occluded(w, o, d, INFINITY);
}

/* The sky is a light like the others (L in Heckbert notation), but not a delta: every non-delta
 * lobe is sampled by its own importance sampling (for a uniform sky of radiance L the integrand
 * of the diffuse lobe is rho_d / pi L V cos, and cosine-weighted directions make its weight
 * rho_d L V, 0 or rho_d L; the Phong lobe's weight is rho_s (n + 2) / (n + 1) cos L V, as in
 * ref_sample_phong), and the mirror lobe by its one direction. */
void ref_nee_sky(const ref_world *w, const ref_hit *h, const ref_mat *m, const float wo[3],
                 ref_rng *rng, float dif[3], float spec[3], long long *rays)
{
    const float *L = w->gs->sky;
    if (!ref_has_sky(w->gs))
        return;
    float u1, u2, u3, u4;
    ref_rng_2d(rng, &u1, &u2);
    ref_rng_2d(rng, &u3, &u4);
    if (h->back)
        return;
    float d[3];
    if (m->kd[0] > 0.0f || m->kd[1] > 0.0f || m->kd[2] > 0.0f) {
        ref_sample_cosine(h->n, u1, u2, d);
        if (ref_sees_sky(w, h, d, rays))
            for (int k = 0; k < 3; k++)
                dif[k] += m->kd[k] * L[k];
    }
    if (!spec || m->spec == GIB_SPEC_NONE)
        return;
    float r[3], wgt = 1.0f;
    ref_reflect(wo, h->n, r);
    if (m->spec == GIB_SPEC_PHONG)
        wgt = ref_sample_phong(r, m->phong_n, h->n, u3, u4, d);
    else
        d[0] = r[0], d[1] = r[1], d[2] = r[2];
    if (wgt > 0.0f && ref_sees_sky(w, h, d, rays))
        for (int k = 0; k < 3; k++)
            spec[k] += m->ks[k] * wgt * L[k];
}

/* Duff et al. 2017, "Building an Orthonormal Basis, Revisited": branch-free and continuous except
 * across n.z = 0's sign. */
void ref_basis(const float n[3], float t[3], float b[3])
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

/* Malley's method: a uniform point on the unit disk lifted to the hemisphere. */
void ref_sample_cosine(const float n[3], float u1, float u2, float d[3])
{
    float phi = 2.0f * REF_PI * u1, r = sqrtf(u2);
    float lx = r * cosf(phi), ly = r * sinf(phi), lz = sqrtf(ref_fmaxf(0.0f, 1.0f - u2));
    float t[3], b[3];
    ref_basis(n, t, b);
    for (int k = 0; k < 3; k++)
        d[k] = lx * t[k] + ly * b[k] + lz * n[k];
}

void ref_reflect(const float wo[3], const float n[3], float r[3])
{
    float nw = 2.0f * ref_dot(n, wo);
    for (int k = 0; k < 3; k++)
        r[k] = nw * n[k] - wo[k];
}

/* cos alpha = u1^(1 / (n + 1)) gives the pdf (n + 1) / (2 pi) cos^n alpha about r; with the BRDF
 * (n + 2) / (2 pi) cos^n alpha the weight f cos / pdf is (n + 2) / (n + 1) cos theta. */
float ref_sample_phong(const float r[3], float n_exp, const float ns[3], float u1, float u2,
                       float d[3])
{
    float ca = powf(u1, 1.0f / (n_exp + 1.0f));
    float sa = sqrtf(ref_fmaxf(0.0f, 1.0f - ca * ca));
    float phi = 2.0f * REF_PI * u2;
    float t[3], b[3];
    ref_basis(r, t, b);
    float lx = sa * cosf(phi), ly = sa * sinf(phi);
    for (int k = 0; k < 3; k++)
        d[k] = lx * t[k] + ly * b[k] + ca * r[k];
    float c = ref_dot(ns, d);
    return c > 0.0f ? (n_exp + 2.0f) / (n_exp + 1.0f) * c : 0.0f;
}

/* gibench — the reference renderer's per-pixel estimators of the short path classes (ARCHITECTURE.md,
 * "Light-transport components"): direct, ao / obscurance, indirect, glossy, and the auxiliary
 * images. Each evaluates one sample at the visible point the render loop found through a pixel
 * centre; ref_path.c has full/higher and the camera part of caustic, ref_light.c the light-traced
 * parts.
 *
 * Every sampled reflection that would leave through the geometric surface (d . n_g <= 0, possible
 * with interpolated normals) contributes 0: a reflected ray cannot enter the surface it leaves.
 * The same rule holds in ref_path.c and ref_light.c, so the components add up.
 *
 * The sky (scenes with one): every path whose light is the sky is found by next-event estimation
 * toward the sky at its light-side vertex (ref_nee_sky), in every component alike, and a sampled
 * bounce or continuation ray that escapes adds nothing, so each such path is counted once and by
 * the same strategy everywhere. */
#include <math.h>

#include "harness/base/cone_set.h"
#include "ref_internal.h"

/* Direct light, L D E and L S E with shadows: for every light, f(wo, wi) E max(0, n.wi), with
 * f = rho_d / pi + rho_s (n + 2) / (2 pi) max(0, r.wi)^n (normalised Phong, r the mirror direction
 * of wo about n). A mirror lobe adds nothing from the delta lights: a delta lobe meets a point,
 * spot or directional light (a delta in direction) with probability zero (that zero-measure path,
 * a light seen in a mirror, is counted by no component, reference.h).
 * The sky (scenes with one) is a light too: integral f L_sky V cos dw over the hemisphere, one
 * importance-sampled direction per lobe and sample (ref_nee_sky): rho_d L V from a cosine-
 * weighted direction, the Phong lobe's share from a Phong-sampled one, and a mirror's rho_s L V
 * from its mirror direction (the sky has area, so the sky seen in a mirror at the visible point,
 * L S E, is a path of positive measure and belongs here).
 * Without a sky no random numbers are used: with delta lights the estimator is exact, so 1 spp is
 * the converged image; with a sky it is random and needs spp >= 2 like the others. */
void ref_est_direct(const ref_world *w, const ref_hit *h, const float wo[3], ref_rng *rng,
                    float out[3], long long *rays)
{
    out[0] = out[1] = out[2] = 0.0f;
    if (h->back)
        return;
    ref_mat m;
    ref_material(w, h, &m);
    float dif[3], spec[3];
    ref_nee(w, h, &m, wo, dif, spec, rays);
    ref_nee_sky(w, h, &m, wo, rng, dif, spec, rays);
    for (int k = 0; k < 3; k++)
        out[k] = dif[k] + spec[k];
}

/* Ambient occlusion, (1/pi) integral V cos dw about the viewer-facing shading normal. Directions
 * are cosine-distributed (pdf cos/pi), so the integrand over the pdf is V itself: each sample is
 * 0 or 1 and the pixel's mean is the unoccluded fraction, unbiased. Exactly two random numbers
 * per sample, drawn in a fixed order.
 *
 * Obscurance (Zhukov, Iones and Kronin 1998, "An ambient light illumination model"; the LDM paper,
 * Aalund et al. 2015 Sec. 3.3, generalises V to V(x, w, d), d the distance to the first occluder,
 * but gives no falloff): we use Zhukov's linear rho(d) = min(d / dmax, 1), so an occluder at the
 * surface blocks fully, one at dmax or beyond not at all; the sample's value is rho(d), 1 on a
 * miss. d is measured from the ray origin (the point moved off the surface by the ray offset). */
void ref_ao_ray(const ref_world *w, const ref_hit *h, ref_rng *rng, float o[3], float d[3])
{
    float u1, u2;
    ref_rng_2d(rng, &u1, &u2);
    ref_sample_cosine(h->n, u1, u2, d);
    ref_offset_origin(w, h, d, o);
}

float ref_ao_value(float t, float dmax, int obscurance)
{
    int bounded = dmax > 0.0f && isfinite(dmax);
    if (obscurance && bounded)
        return t >= dmax ? 1.0f : t / dmax;
    return t <= (bounded ? dmax : INFINITY) && t < INFINITY ? 0.0f : 1.0f;
}

float ref_est_ao(const ref_world *w, const ref_hit *h, float dmax, int obscurance, ref_rng *rng,
                 long long *rays)
{
    if (h->back)
        return 0.0f;
    float d[3], o[3];
    ref_ao_ray(w, h, rng, o, d);
    int bounded = dmax > 0.0f && isfinite(dmax);
    ++*rays;
    if (obscurance && bounded)
        return ref_ao_value(ref_hit_distance(w, o, d, dmax), dmax, 1);
    return ref_occluded(w, o, d, bounded ? dmax : INFINITY) ? 0.0f : 1.0f;
}

/* A bounce from the visible point in two halves, so that a pixel's batch of samples casts every
 * bounce ray before it shades any hit: each hit's triangle record and albedo texel, prefetched
 * when its ray returns, arrive while the other rays are traced. Each sample keeps its own stream
 * and arithmetic, so the values are those of the samples taken one at a time. */
typedef struct ref_bounce {
    ref_pending pq;
    float scale[3]; /* what the bounce's light is multiplied by: rho_d, or rho_s x the lobe weight */
    int live;       /* the ray was cast and met a surface */
} ref_bounce;

static void ref_bounce_cast(const ref_world *w, const ref_hit *h, const float d[3],
                            ref_bounce *b, long long *rays)
{
    b->live = 0;
    if (!(ref_dot(d, h->ng) > 0.0f))
        return;
    float o[3];
    ref_offset_origin(w, h, d, o);
    ++*rays;
    b->live = ref_trace_start(w, o, d, &b->pq);
}

/* The diffuse-only direct light leaving the bounce's hit y back along the ray (the D vertex next
 * to the light in L D D E and L D S E), the sky's included. Returns 0 when the ray escaped or met
 * a one-sided back: such a sample adds nothing (an escaping ray's path, L_sky D E or L_sky S E, is
 * one vertex long and `direct` counts it, by its own sky sampling). */
static int ref_bounce_light(const ref_world *w, const ref_bounce *b, ref_rng *rng, float L[3],
                            long long *rays)
{
    L[0] = L[1] = L[2] = 0.0f;
    ref_hit y;
    if (!b->live)
        return 0;
    ref_trace_finish(w, &b->pq, &y);
    if (y.back)
        return 0;
    ref_mat m;
    const float wo[3] = {-b->pq.d[0], -b->pq.d[1], -b->pq.d[2]};
    int want_d = ref_diffuse_known(w, w->tris[y.prim].mat);
    if (want_d >= 0 && w->gs->light_count <= REF_NEE_LIGHTS && !ref_has_sky(w->gs)) {
        /* ref_nee's shadow rays first, the albedo's texel only where light arrives: the same
         * rays and sums, without the texel's cache miss at points in shadow */
        ref_nee_vis v;
        ref_nee_visible(w, &y, wo, want_d, 0, 0.0f, 0, &v, rays);
        if (v.n == 0)
            return 1;
        ref_material(w, &y, &m);
        ref_nee_shade(&v, &m, L, NULL);
        return 1;
    }
    ref_material(w, &y, &m);
    ref_nee(w, &y, &m, wo, L, NULL, rays);
    ref_nee_sky(w, &y, &m, wo, rng, L, NULL, rays);
    return 1;
}

/* Indirect, L D D E: a cosine-weighted bounce from the visible point's diffuse lobe
 * (f cos / pdf = rho_d), then the diffuse lobe of the bounce point lit by next-event estimation.
 * Specular lobes at either vertex belong to glossy (x1) and caustic (x2). cone >= 1: only diffuse
 * cone cone - 1 of the cone set, the cap of half-angle cone_half (radians), sampled uniformly:
 * rho_d times the cap's mean radiance. The bounce's direction d and weight; 0 when the sample
 * adds nothing. */
static int ref_indirect_bounce(const ref_world *w, const ref_hit *h, int cone, float cone_half,
                               ref_rng *rng, float d[3], float scale[3])
{
    float u1, u2;
    ref_rng_2d(rng, &u1, &u2);
    if (h->back)
        return 0;
    ref_albedo(w, h, scale);
    if (scale[0] <= 0.0f && scale[1] <= 0.0f && scale[2] <= 0.0f)
        return 0;
    if (cone > 0) { /* f cos / pdf becomes rho_d x L's cap mean: each direction weighs 1 / n */
        float axis[3];
        gib_diffuse_cone_dir(cone - 1, h->n, axis);
        gib_cone_cap_sample(axis, cone_half, u1, u2, d);
    } else {
        ref_sample_cosine(h->n, u1, u2, d);
    }
    return 1;
}

/* Glossy, L D S E: the visible point's specular lobe (Phong, importance-sampled; or the mirror
 * direction) sees a diffuse surface lit by next-event estimation. The bounce's direction d and
 * weight; 0 when the sample adds nothing. */
static int ref_glossy_bounce(const ref_world *w, const ref_hit *h, const float wo[3],
                             ref_rng *rng, float d[3], float scale[3])
{
    float u1, u2;
    ref_rng_2d(rng, &u1, &u2);
    if (h->back)
        return 0;
    ref_mat m;
    ref_material(w, h, &m);
    if (m.spec == GIB_SPEC_NONE)
        return 0;
    float r[3], wgt = 1.0f;
    ref_reflect(wo, h->n, r);
    if (m.spec == GIB_SPEC_PHONG)
        wgt = ref_sample_phong(r, m.phong_n, h->n, u1, u2, d);
    else
        d[0] = r[0], d[1] = r[1], d[2] = r[2];
    if (!(wgt > 0.0f))
        return 0;
    for (int k = 0; k < 3; k++)
        scale[k] = m.ks[k] * wgt;
    return 1;
}

/* n <= REF_PATH_BATCH samples of indirect or glossy: every bounce cast, then every hit shaded. */
static void ref_sample_bounces(const ref_ctx *c, const ref_hit *h, const float wo[3], int n,
                               ref_rng *rng, float (*out)[3], long long *rays)
{
    ref_bounce b[REF_PATH_BATCH];
    const float cone_half = 0.5f * c->p.cone_aperture * 0.017453293f;
    for (int i = 0; i < n; i++) {
        float d[3];
        out[i][0] = out[i][1] = out[i][2] = 0.0f;
        b[i].live = 0;
        if (c->p.component == GIB_COMP_INDIRECT
                ? ref_indirect_bounce(c->w, h, c->p.cone, cone_half, &rng[i], d, b[i].scale)
                : ref_glossy_bounce(c->w, h, wo, &rng[i], d, b[i].scale))
            ref_bounce_cast(c->w, h, d, &b[i], rays);
    }
    for (int i = 0; i < n; i++) {
        float L[3];
        if (ref_bounce_light(c->w, &b[i], &rng[i], L, rays))
            for (int k = 0; k < 3; k++)
                out[i][k] = b[i].scale[k] * L[k];
    }
}

/* Auxiliary images of the visible point. albedo: rho_d, filtered like the GL G-buffer's (0 on the
 * back of a one-sided surface, which shades to 0); normal: the shading normal as shaded, i.e.
 * facing the viewer (on a one-sided back, the surface's own normal, pointing away); depth: the
 * view-space depth, (p - eye) . forward, in scene units. Misses are 0 in all three. */
void ref_est_aux(const ref_ctx *c, const ref_hit *h, float out[3])
{
    switch (c->p.component) {
    case GIB_COMP_ALBEDO:
        if (h->back)
            out[0] = out[1] = out[2] = 0.0f;
        else
            ref_albedo(c->w, h, out);
        break;
    case GIB_COMP_NORMAL:
        out[0] = h->n[0], out[1] = h->n[1], out[2] = h->n[2];
        break;
    default: {
        float v[3] = {h->p[0] - c->cam->eye[0], h->p[1] - c->cam->eye[1],
                      h->p[2] - c->cam->eye[2]};
        out[0] = out[1] = out[2] = ref_dot(v, c->fwd);
    }
    }
}

static void ref_sample_one(const ref_ctx *c, const ref_hit *h, const float wo[3], ref_rng *rng,
                           float out[3], long long *rays)
{
    switch (c->p.component) {
    case GIB_COMP_AO:
        out[0] = out[1] = out[2] =
            ref_est_ao(c->w, h, c->p.dmax, c->p.obscurance, rng, rays);
        break;
    case GIB_COMP_DIRECT:
        ref_est_direct(c->w, h, wo, rng, out, rays);
        break;
    case GIB_COMP_ALBEDO:
    case GIB_COMP_NORMAL:
    case GIB_COMP_DEPTH:
        ref_est_aux(c, h, out);
        break;
    default:
        ref_est_caustic(c, h, rng, out, rays);
    }
}

void ref_sample_camera(const ref_ctx *c, const ref_hit *h, const float wo[3], int n,
                       ref_rng *rng, float (*out)[3], long long *rays)
{
    if (c->p.component == GIB_COMP_FULL || c->p.component == GIB_COMP_HIGHER) {
        ref_est_paths(c, h, wo, c->p.component == GIB_COMP_HIGHER, n, rng, out, rays);
        return;
    }
    if (c->p.component == GIB_COMP_INDIRECT || c->p.component == GIB_COMP_GLOSSY) {
        ref_sample_bounces(c, h, wo, n, rng, out, rays);
        return;
    }
    for (int i = 0; i < n; i++)
        ref_sample_one(c, h, wo, &rng[i], out[i], rays);
}

/* gibench — light tracing: the paths whose vertex next to the light is a mirror, for `caustic`
 * (L S_mirror S* D E) and for `full` / `higher` (every such path).
 *
 * Why light tracing: the scene's lights are points, spots and directional lights, deltas in
 * position or direction. A camera path that meets a mirror (a delta lobe) continues in exactly one
 * direction, which hits a point light with probability zero, and next-event estimation cannot
 * aim through a mirror either: a delta light seen through a delta lobe is invisible to camera
 * paths (ARCHITECTURE.md, "Light-transport components"). Particles leaving the light follow the mirror
 * (and then glossy) lobes naturally, and the diffuse surface they land on is connected to the
 * pinhole camera by a visibility ray: the particle is splatted into the pixel its point projects
 * to. Paths whose light-side vertex is Phong are left to camera paths (next-event estimation
 * through the Phong lobe finds them), so that every class has one footprint in every component.
 *
 * What a splat measures: the pixel's radiance AVERAGED OVER ITS AREA (a point projects into a
 * pixel, not onto its centre), while the camera-side components take the radiance through the
 * pixel centre. The two agree on smooth images; at sharp edges they differ by the variation within
 * the pixel. This is inherent to splatting and stated in reference.h and the EXR header.
 *
 * Estimator (Veach 1997, Sec. 10.2; pbrt's light tracing): a particle carries flux beta; at a
 * surface point y reached from direction wl (toward the light), its splat into pixel j is
 *     beta f(wl, wc) |n_s . wl| |n_g . wc| / (|n_g . wl| d^2 cos^3(theta) A_pix N),
 * wc toward the eye at distance d, theta the angle of wc to the camera axis, A_pix the pixel's
 * area on the image plane at distance 1, N the particles of the pass; |n_s . wl| / |n_g . wl| is
 * Veach's adjoint correction for shading normals (Sec. 5.3), and scattering multiplies beta by
 * f |n_s . wl| |n_g . wo| / (pdf |n_g . wl|). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ref_internal.h"

/* The light's selection weight: its power (luminance), or an upper bound for spots. */
static float ref_light_weight(const ref_ctx *c, const gib_light *l)
{
    return ref_light_power(c->w, l);
}

/* Emits one particle: origin o, direction d, flux beta. Returns 0 when nothing is emitted. */
static int ref_emit(const ref_ctx *c, ref_pcg32 *rng, float o[3], float d[3], float beta[3])
{
    const gib_scene *gs = c->w->gs;
    float u0 = ref_pcg32_float(rng), u1 = ref_pcg32_float(rng), u2 = ref_pcg32_float(rng);
    float total = 0.0f;
    for (uint32_t i = 0; i < gs->light_count; i++)
        total += ref_light_weight(c, &gs->lights[i]);
    if (!(total > 0.0f))
        return 0;
    const gib_light *l = NULL;
    float acc = 0.0f, psel = 0.0f, target = u0 * total;
    for (uint32_t i = 0; i < gs->light_count; i++) {
        float wl = ref_light_weight(c, &gs->lights[i]);
        if (wl > 0.0f) {
            l = &gs->lights[i];
            psel = wl / total;
        }
        acc += wl;
        if (target < acc && wl > 0.0f)
            break;
    }
    if (!l)
        return 0;
    float scale; /* 1 / (pdf * psel) */
    if (l->type == GIB_LIGHT_DIRECTIONAL) {
        /* A disk across the scene's bounding sphere, facing the light: pdf 1 / (pi R^2) in area,
         * and the irradiance E is flux per unit area. */
        float t[3], b[3], R = c->w->bradius, r = R * sqrtf(u1), phi = 2.0f * REF_PI * u2;
        ref_basis(l->direction, t, b);
        for (int k = 0; k < 3; k++) {
            d[k] = l->direction[k];
            o[k] = c->w->bcentre[k] - R * d[k] + r * cosf(phi) * t[k] + r * sinf(phi) * b[k];
        }
        scale = REF_PI * R * R / psel;
        for (int k = 0; k < 3; k++)
            beta[k] = l->intensity[k] * scale;
        return 1;
    }
    float ct, axis[3] = {0.0f, 0.0f, 1.0f};
    if (l->type == GIB_LIGHT_SPOT) { /* uniform in solid angle over the cone */
        float co = cosf(l->spot_outer_deg * (REF_PI / 180.0f));
        ct = 1.0f - u1 * (1.0f - co);
        memcpy(axis, l->direction, sizeof axis);
        scale = 2.0f * REF_PI * (1.0f - co) / psel;
    } else { /* uniform over the sphere */
        ct = 1.0f - 2.0f * u1;
        scale = 4.0f * REF_PI / psel;
    }
    float st = sqrtf(ref_fmaxf(0.0f, 1.0f - ct * ct)), phi = 2.0f * REF_PI * u2, t[3], b[3];
    ref_basis(axis, t, b);
    for (int k = 0; k < 3; k++) {
        d[k] = st * cosf(phi) * t[k] + st * sinf(phi) * b[k] + ct * axis[k];
        o[k] = l->position[k];
    }
    float falloff = l->type == GIB_LIGHT_SPOT ? gib_spot_falloff(l, d) : 1.0f;
    for (int k = 0; k < 3; k++)
        beta[k] = l->intensity[k] * falloff * scale;
    return falloff > 0.0f;
}

static void ref_splat_add(ref_splats *out, uint32_t pix, const float v[3])
{
    if (out->n == out->cap) {
        size_t cap = out->cap ? 2 * out->cap : 256;
        ref_splat *s = realloc(out->s, cap * sizeof *s);
        if (!s) {
            out->oom = 1;
            return;
        }
        out->s = s;
        out->cap = cap;
    }
    out->s[out->n].pix = pix;
    memcpy(out->s[out->n].v, v, sizeof out->s[out->n].v);
    out->n++;
}

/* Connects y (reached by a particle travelling along din with flux beta) to the camera through
 * its diffuse lobe (dif) and/or Phong lobe (spec), and splats into the pixel y projects to. */
static void ref_connect(const ref_ctx *c, const ref_hit *y, const ref_mat *m, const float din[3],
                        const float beta[3], int dif, int spec, ref_splats *out, long long *rays)
{
    const float wl[3] = {-din[0], -din[1], -din[2]};
    float q[3], wc[3];
    for (int k = 0; k < 3; k++)
        q[k] = y->p[k] - c->cam->eye[k];
    float z = ref_dot(q, c->fwd), dist = sqrtf(ref_dot(q, q));
    float cos_l = ref_dot(y->n, wl), cos_gl = ref_dot(y->ng, wl);
    if (!(z > 0.0f) || !(dist > 0.0f) || !(cos_l > 0.0f) || !(cos_gl > 0.0f))
        return;
    for (int k = 0; k < 3; k++)
        wc[k] = -q[k] / dist;
    float cos_gc = ref_dot(y->ng, wc);
    if (!(cos_gc > 0.0f)) /* the camera looks at the other side */
        return;
    const int W = c->p.width, H = c->p.height;
    float px = (ref_dot(q, c->right) / z / (c->aspect * c->tan_half) + 1.0f) * 0.5f * (float)W;
    float py = (1.0f - ref_dot(q, c->up) / z / c->tan_half) * 0.5f * (float)H;
    if (!(px >= 0.0f && px < (float)W && py >= 0.0f && py < (float)H))
        return;
    float f[3] = {0.0f, 0.0f, 0.0f};
    if (dif)
        for (int k = 0; k < 3; k++)
            f[k] = m->kd[k] * (1.0f / REF_PI);
    if (spec && m->spec == GIB_SPEC_PHONG) {
        float r[3];
        ref_reflect(wc, y->n, r);
        float rw = ref_dot(r, wl);
        if (rw > 0.0f) {
            float lobe = (m->phong_n + 2.0f) * (0.5f / REF_PI) * powf(rw, m->phong_n);
            for (int k = 0; k < 3; k++)
                f[k] += m->ks[k] * lobe;
        }
    }
    if (f[0] <= 0.0f && f[1] <= 0.0f && f[2] <= 0.0f)
        return;
    float o[3];
    ref_offset_origin(c->w, y, wc, o);
    ++*rays;
    if (ref_occluded(c->w, o, wc, dist))
        return;
    float cz = z / dist;
    float pix_side = 2.0f * c->tan_half / (float)H;
    float g = cos_l * cos_gc /
              (cos_gl * dist * dist * cz * cz * cz * pix_side * pix_side *
               (float)ref_light_particles(c));
    float v[3];
    for (int k = 0; k < 3; k++)
        v[k] = beta[k] * f[k] * g;
    int ix = (int)px, iy = (int)py;
    if (ix >= W)
        ix = W - 1;
    if (iy >= H)
        iy = H - 1;
    ref_splat_add(out, (uint32_t)iy * (uint32_t)W + (uint32_t)ix, v);
}

/* Scatters the particle at y into a new direction through one lobe (0 diffuse, 1 specular);
 * multiplies beta by the adjoint weight. Returns 0 when the particle dies. */
static int ref_scatter(const ref_hit *y, const ref_mat *m, int lobe_s, float prob, float u1,
                       float u2, float din[3], float beta[3])
{
    const float wl[3] = {-din[0], -din[1], -din[2]};
    float d[3], fw[3]; /* f cos_s(d) / pdf */
    float cs = ref_dot(y->n, wl), cg = ref_dot(y->ng, wl);
    if (!(cs > 0.0f) || !(cg > 0.0f))
        return 0;
    if (!lobe_s) {
        ref_sample_cosine(y->n, u1, u2, d);
        for (int k = 0; k < 3; k++)
            fw[k] = m->kd[k];
    } else {
        float r[3], wgt = 1.0f;
        ref_reflect(wl, y->n, r);
        if (m->spec == GIB_SPEC_PHONG)
            wgt = ref_sample_phong(r, m->phong_n, y->n, u1, u2, d);
        else
            memcpy(d, r, sizeof d);
        if (!(wgt > 0.0f))
            return 0;
        for (int k = 0; k < 3; k++)
            fw[k] = m->ks[k] * wgt;
    }
    float dg = ref_dot(d, y->ng), ds = ref_dot(d, y->n);
    if (!(dg > 0.0f) || !(ds > 0.0f))
        return 0;
    /* f cos_s(d) / pdf  ->  f |n_s.wl| |n_g.d| / (pdf |n_g.wl|) */
    float corr = cs * dg / (ds * cg);
    for (int k = 0; k < 3; k++)
        beta[k] *= fw[k] * corr / prob;
    memcpy(din, d, sizeof d);
    return 1;
}

static void ref_particle(const ref_ctx *c, ref_pcg32 *rng, ref_splats *out, long long *rays)
{
    const ref_world *w = c->w;
    const int caustic = c->p.component == GIB_COMP_CAUSTIC;
    const int higher = c->p.component == GIB_COMP_HIGHER;
    const int maxs = c->p.max_specular, maxd = c->p.max_depth, mind = c->p.min_depth;
    float o[3], d[3], beta[3];
    if (!ref_emit(c, rng, o, d, beta))
        return;
    int all_s = 1; /* every vertex so far left through a specular lobe */
    for (int verts = 1;; verts++) {
        ref_hit y;
        ++*rays;
        /* every path here starts at a mirror: a first ray that meets none ends the particle as
         * its trace through the whole scene would, for a fraction of the work */
        if ((verts == 1 && !ref_may_hit_mirror(w, o, d)) || !ref_trace(w, o, d, &y) || y.back)
            return;
        ref_mat m;
        ref_material(w, &y, &m);
        float u0 = ref_pcg32_float(rng), u1 = ref_pcg32_float(rng), u2 = ref_pcg32_float(rng);
        if (caustic) {
            /* L S_mirror S* D E: the first vertex a mirror; splat the diffuse lobe once a specular
             * vertex lies behind, continue through the specular lobe while fewer than
             * max_specular were used. */
            if (verts == 1 && m.spec != GIB_SPEC_MIRROR)
                return;
            if (verts > 1)
                ref_connect(c, &y, &m, d, beta, 1, 0, out, rays);
            if (verts > maxs || m.spec == GIB_SPEC_NONE ||
                !ref_scatter(&y, &m, 1, 1.0f, u1, u2, d, beta))
                return;
        } else {
            /* full / higher: only paths whose light-side vertex is a mirror (the rest come from
             * camera paths). y is the eye-side vertex x1 of a path of `verts` vertices. */
            if (verts == 1) {
                if (m.spec != GIB_SPEC_MIRROR || !ref_scatter(&y, &m, 1, 1.0f, u1, u2, d, beta))
                    return;
            } else {
                int keep_d = !higher || !ref_basic_class(verts, 0, all_s, maxs);
                int keep_s = !higher || !ref_basic_class(verts, 1, all_s, maxs);
                if (keep_d || keep_s)
                    ref_connect(c, &y, &m, d, beta, keep_d, keep_s, out, rays);
                if (verts >= maxd)
                    return;
                float pd = ref_lum(m.kd), ps = m.spec != GIB_SPEC_NONE ? ref_lum(m.ks) : 0.0f;
                if (!(pd + ps > 0.0f))
                    return;
                int lobe_s = u0 * (pd + ps) >= pd;
                if (!ref_scatter(&y, &m, lobe_s, (lobe_s ? ps : pd) / (pd + ps), u1, u2, d, beta))
                    return;
                all_s = all_s && lobe_s;
                if (verts >= mind) {
                    float q = ref_fminf(1.0f, ref_fmaxf(beta[0], ref_fmaxf(beta[1], beta[2])));
                    if (!(ref_pcg32_float(rng) < q))
                        return;
                    for (int k = 0; k < 3; k++)
                        beta[k] /= q;
                }
            }
        }
        ref_offset_origin(w, &y, d, o);
    }
}

void ref_light_chunk(const ref_ctx *c, uint64_t pass, uint32_t chunk, int count,
                     ref_splats *out, long long *rays)
{
    for (int i = 0; i < count; i++) {
        uint64_t particle = (uint64_t)chunk * REF_LIGHT_CHUNK + (uint64_t)i;
        ref_pcg32 rng;
        ref_pcg32_seed_sample(&rng, REF_LIGHT_STREAM | particle, pass, c->p.seed, c->p.component);
        ref_particle(c, &rng, out, rays);
    }
}

/* gibench — `full` and `higher`: camera paths with next-event estimation (DESIGN.md,
 * "Light-transport components": full is everything up to a maximum depth).
 *
 * A path of k surface vertices x1 (visible) .. xk (next to the light). At every vertex the light
 * is connected by next-event estimation through the non-delta lobes (diffuse and Phong); the path
 * is continued by sampling one lobe (diffuse, Phong or mirror, chosen in proportion to the
 * lobes' reflectances). Point, spot and directional lights are deltas that a sampled direction
 * never hits, so every path class is found by exactly one strategy and no MIS is needed — except
 * the classes whose light-side vertex is a mirror: next-event estimation cannot go through a delta
 * lobe, so those come from light tracing (ref_light.c, run by the render loop for scenes with
 * mirrors). Camera paths through mirrors are followed (a mirror seen from the camera shows the
 * diffuse surfaces behind it, lit by next-event estimation there).
 *
 * The sky (scenes with one) is not a delta: a continuation can escape and see it. Such escapes
 * add nothing; the sky is reached only by next-event estimation at every vertex, one sampled
 * direction per lobe (ref_nee_sky: diffuse, Phong, and the mirror direction of a mirror), so
 * again one strategy per path class and no MIS. Sky paths through mirrors are all found this way
 * (the sky seen through a mirror is not a delta light seen through a delta lobe), so no sky path
 * needs light tracing and none is missing.
 *
 * Russian roulette from min_depth on: a path that has reached vertex d >= min_depth continues
 * with probability q = min(1, max channel of its throughput after this bounce, estimated from the
 * material's untextured reflectances), and the survivors' throughput is divided by q, which keeps
 * the estimator unbiased (Arvo and Kirk 1990). max_depth cuts paths off: `full` is exactly the
 * sum of all classes of at most max_depth vertices.
 *
 * `higher` runs the same paths and keeps only the contributions whose class none of direct,
 * indirect, glossy and caustic counts (ref_basic_class).
 *
 * The camera part of `caustic` is here too: L S+ D E whose vertex next to the light is Phong,
 * found like full's paths (diffuse bounce from the visible point, specular continuations,
 * next-event estimation through the Phong lobe). Its mirror-first paths come from light tracing
 * (ref_light.c), as full's do — except those whose light is the sky: L_sky S+ D E, Phong or
 * mirror next to the sky, comes from these camera paths by the sky's next-event estimation
 * through the specular lobe (mirror: its one direction). */
#include <math.h>
#include <string.h>

#include "ref_internal.h"

int ref_basic_class(int verts, int s1, int all_s_rest, int max_specular)
{
    if (verts <= 1)
        return 1;                  /* L D E, L S E: direct */
    if (verts == 2)
        return !(s1 && all_s_rest); /* L D D E, L D S E, L S D E; L S S E is higher */
    return !s1 && all_s_rest && verts - 1 <= max_specular; /* L S+ D E: caustic */
}

/* The order of work at each vertex hides memory latency: the continuation ray is traced (its
 * hit's triangle record prefetched) BEFORE this vertex's textured material and next-event
 * estimation are evaluated, and the next hit's albedo texel is prefetched before the next
 * continuation is traced, so the two cache misses of a hit overlap Embree's work instead of
 * stalling on it. That is why the lobe and the roulette are chosen from the material's constant
 * reflectances (any positive selection probabilities keep the estimator unbiased, as long as the
 * weight divides by the same ones); the sample's weight then uses the textured values. */
void ref_est_path(const ref_ctx *c, const ref_hit *h, const float wo[3], int higher_only,
                  ref_pcg32 *rng, float out[3], long long *rays)
{
    const ref_world *w = c->w;
    const int maxd = c->p.max_depth, mind = c->p.min_depth, maxs = c->p.max_specular;
    out[0] = out[1] = out[2] = 0.0f;
    if (h->back)
        return;
    ref_hit cur = *h, next;
    float wcur[3] = {wo[0], wo[1], wo[2]};
    float beta[3] = {1.0f, 1.0f, 1.0f};
    int s1 = 0, all_s_rest = 1; /* lobes of the vertices before the current one */
    for (int depth = 1;; depth++) {
        /* 1. choose the continuation from the material's constants, and trace it */
        const gib_material *gm = cur.mat;
        int spec = gm->spec_type != GIB_SPEC_NONE;
        float pd = ref_lum(gm->albedo), ps = spec ? ref_lum(gm->specular) : 0.0f;
        int cont = depth < maxd && pd + ps > 0.0f, lobe_s = 0, hit = 0;
        float d[3], f = 1.0f, q = 1.0f, prob = 1.0f;
        ref_pending pend;
        if (cont) {
            float u0 = ref_pcg32_float(rng), u1 = ref_pcg32_float(rng), u2 = ref_pcg32_float(rng);
            lobe_s = u0 * (pd + ps) >= pd;
            prob = (lobe_s ? ps : pd) / (pd + ps);
            if (!lobe_s) {
                ref_sample_cosine(cur.n, u1, u2, d);
            } else {
                float r[3];
                ref_reflect(wcur, cur.n, r);
                if (gm->spec_type == GIB_SPEC_PHONG)
                    f = ref_sample_phong(r, gm->phong_n, cur.n, u1, u2, d);
                else
                    memcpy(d, r, sizeof d);
            }
            cont = f > 0.0f && ref_dot(d, cur.ng) > 0.0f;
            if (cont && depth >= mind) { /* roulette on the untextured throughput estimate */
                const float *refl = lobe_s ? gm->specular : gm->albedo;
                float est = 0.0f;
                for (int k = 0; k < 3; k++)
                    est = fmaxf(est, beta[k] * refl[k] * f / prob);
                q = fminf(1.0f, est);
                cont = ref_pcg32_float(rng) < q;
            }
            if (cont) {
                float o[3];
                ref_offset_origin(w, &cur, d, o);
                ++*rays;
                hit = ref_trace_start(w, o, d, &pend);
            }
        }

        /* 2. this vertex: textured material, next-event estimation (diffuse and Phong parts are
         * different classes; `higher` skips the parts whose class is basic) */
        ref_mat m;
        ref_material(w, &cur, &m);
        int keep[2];
        for (int lobe = 0; lobe < 2; lobe++) {
            int c1 = depth == 1 ? lobe : s1, rest = depth == 1 ? 1 : (all_s_rest && lobe);
            keep[lobe] = !higher_only || !ref_basic_class(depth, c1, rest, maxs);
        }
        if (keep[0] || keep[1]) {
            ref_mat mn = m;
            if (!keep[0])
                mn.kd[0] = mn.kd[1] = mn.kd[2] = 0.0f;
            float dif[3], sp[3];
            if (cur.has_nee && keep[0] && keep[1]) { /* the pixel's own, computed once */
                memcpy(dif, cur.nee_dif, sizeof dif);
                memcpy(sp, cur.nee_spec, sizeof sp);
            } else {
                ref_nee(w, &cur, &mn, wcur, dif, keep[1] ? sp : NULL, rays);
            }
            ref_nee_sky(w, &cur, &mn, wcur, rng, dif, keep[1] ? sp : NULL, rays);
            for (int k = 0; k < 3; k++)
                out[k] += beta[k] * (dif[k] + (keep[1] ? sp[k] : 0.0f));
        }
        if (!hit)
            break;

        /* 3. the continuation's weight with the textured reflectances; the next vertex */
        const float *refl = lobe_s ? m.ks : m.kd;
        for (int k = 0; k < 3; k++)
            beta[k] *= refl[k] * f / (prob * q);
        if (depth == 1)
            s1 = lobe_s;
        else
            all_s_rest = all_s_rest && lobe_s;
        ref_trace_finish(w, &pend, &next);
        if (next.back || (beta[0] <= 0.0f && beta[1] <= 0.0f && beta[2] <= 0.0f))
            break;
        cur = next;
        wcur[0] = -d[0], wcur[1] = -d[1], wcur[2] = -d[2];
    }
}

void ref_est_caustic(const ref_ctx *c, const ref_hit *h, ref_pcg32 *rng, float out[3],
                     long long *rays)
{
    const ref_world *w = c->w;
    out[0] = out[1] = out[2] = 0.0f;
    float u1 = ref_pcg32_float(rng), u2 = ref_pcg32_float(rng);
    if (h->back || !w->has_specular)
        return;
    float beta[3], d[3];
    ref_albedo(w, h, beta);
    if (beta[0] <= 0.0f && beta[1] <= 0.0f && beta[2] <= 0.0f)
        return;
    ref_sample_cosine(h->n, u1, u2, d); /* f cos / pdf = rho_d */
    ref_hit cur = *h;
    for (int verts = 2; verts <= c->p.max_specular + 1; verts++) {
        if (!(ref_dot(d, cur.ng) > 0.0f))
            return;
        float o[3];
        ref_offset_origin(w, &cur, d, o);
        ++*rays;
        if (!ref_trace(w, o, d, &cur) || cur.back)
            return;
        ref_mat m;
        ref_material(w, &cur, &m);
        if (m.spec == GIB_SPEC_NONE)
            return;
        const float wo[3] = {-d[0], -d[1], -d[2]};
        /* x_verts next to the light, through its specular lobe: the delta lights through a Phong
         * lobe, the sky through a Phong lobe or a mirror */
        ref_mat ms = m;
        ms.kd[0] = ms.kd[1] = ms.kd[2] = 0.0f;
        float dif[3], spec[3];
        ref_nee(w, &cur, &ms, wo, dif, spec, rays);
        ref_nee_sky(w, &cur, &ms, wo, rng, dif, spec, rays);
        for (int k = 0; k < 3; k++)
            out[k] += beta[k] * spec[k];
        if (verts == c->p.max_specular + 1)
            return;
        float r[3], f = 1.0f;
        ref_reflect(wo, cur.n, r);
        if (m.spec == GIB_SPEC_PHONG)
            f = ref_sample_phong(r, m.phong_n, cur.n, ref_pcg32_float(rng), ref_pcg32_float(rng),
                                 d);
        else
            d[0] = r[0], d[1] = r[1], d[2] = r[2];
        if (!(f > 0.0f))
            return;
        for (int k = 0; k < 3; k++)
            beta[k] *= m.ks[k] * f;
    }
}

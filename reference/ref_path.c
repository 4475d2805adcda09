/* gibench — `full` and `higher`: camera paths with next-event estimation (ARCHITECTURE.md,
 * "Light-transport components": full is everything up to a maximum depth).
 *
 * A path of k surface vertices x1 (visible) .. xk (next to the light). At every vertex the light
 * is connected by next-event estimation through the non-delta lobes (diffuse and Phong); the path
 * is continued by sampling one lobe (diffuse, Phong or mirror, chosen in proportion to the
 * lobes' reflectances). Point, spot and directional lights are deltas that a sampled direction
 * never hits, so a sampled direction never finds a light itself. The classes whose light-side
 * vertex is a mirror come from light tracing (ref_light.c, run by the render loop for scenes with
 * mirrors): next-event estimation cannot go through a delta lobe. Camera paths through mirrors
 * are followed (a mirror seen from the camera shows the diffuse surfaces behind it, lit by
 * next-event estimation there).
 *
 * Light vertices (ref_connect.c; chosen per image by ref_pilot.c): each sample also draws a light
 * vertex y (a ray from a light) and connects it to every camera vertex x below max_depth through
 * both diffuse lobes; L y x ... E is also the camera path's diffuse bounce from x to y with
 * next-event estimation at y, and the balance heuristic weighs the two (ref_path_weights), so each
 * path counts once in expectation. The connection ends on a camera vertex, never on the camera.
 *
 * The sky is reached only by next-event estimation at every vertex (escapes add nothing).
 * Russian roulette from min_depth on: a path that has reached vertex d >= min_depth continues
 * with probability q = min(1, max channel of its throughput after this bounce, estimated from the
 * material's untextured reflectances; doubled with light vertices, REF_RR_LV), and the survivors'
 * throughput is divided by q, which keeps the estimator unbiased (Arvo and Kirk 1990). max_depth
 * cuts paths off: `full` is exactly the sum of all classes of at most max_depth vertices.
 *
 * `higher` keeps only the contributions whose class none of direct, indirect, glossy and caustic
 * counts (ref_basic_class). The camera part of `caustic` is here too: L S+ D E whose vertex next
 * to the light is Phong (or whose light is the sky); its mirror-first paths come from light
 * tracing (ref_light.c). */
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

/* With light vertices, Russian roulette keeps paths longer: survival min(1, 2 x the throughput
 * estimate) instead of min(1, it). Each vertex's connection estimates its bounce's light with
 * little noise, so a path killed early loses a well-estimated tail, and the roulette's 1/q
 * became the larger part of the noise. On the closed room (reference/PERFORMANCE.md) the
 * variance x rays fell 1.28x with 2; 2.5 and 3.3 gave 1.34x, 1.4 gave 1.15x, no roulette 1.0x. */
#define REF_RR_LV 2.0f

/* The order of work hides memory latency. Paths run in batches (the samples of one pixel, which
 * share its visible point), depth by depth: first every live path chooses its continuation and
 * traces it (its hit's triangle record prefetched), then every path evaluates its current vertex
 * (textured material, next-event estimation) and only then fills its next hit from the record and
 * prefetches that hit's albedo texel. Between a texel's prefetch and its load lie the batch's
 * other continuation rays, and the batch's misses are in flight together instead of one at a time
 * (Sponza: bounce hits land anywhere in 137 MB of textures and 17 MB of triangle records, ~180 ns
 * a miss on this machine). Each path keeps its own random stream and does exactly the arithmetic
 * of a path traced alone, so the image does not depend on the batching. That is also why the lobe
 * and the roulette are chosen from the material's constant reflectances (any positive selection
 * probabilities keep the estimator unbiased, as long as the weight divides by the same ones); the
 * sample's weight then uses the textured values. */
typedef struct ref_path_state {
    ref_hit cur;             /* the current vertex */
    ref_pending pend;        /* its continuation, traced */
    ref_rng *rng;
    float *out;
    float wcur[3], beta[3], d[3], f, q, prob;
    int depth, s1, all_s_rest; /* lobes of the vertices before the current one */
    int lobe_s, hit, live;
    int keep[2];             /* the vertex's diffuse and Phong parts count (`higher` drops some) */
    int nee_cast, nee_want_s; /* vis holds the vertex's next-event shadow rays, cast */
    ref_nee_vis vis;
    ref_lvert lv;            /* the sample's light vertex (ref_connect.c) */
    float cont_pa;           /* the continuation's probability of its diffuse lobe (selection
                              * and roulette); 0: not diffuse, or no light vertices */
    float arr_x[3], arr_n[3], arr_pa; /* the vertex before cur, its shading normal and the
                              * cont_pa of the bounce that reached cur */
    float conn[3];           /* the light vertex's connection to cur, before beta and rho_d */
    int conn_on;
} ref_path_state;

/* The vertex's diffuse and Phong parts are different classes; `higher` keeps only those whose
 * class is not basic. */
static void ref_path_keep(const ref_ctx *c, int higher_only, ref_path_state *ps)
{
    for (int lobe = 0; lobe < 2; lobe++) {
        int c1 = ps->depth == 1 ? lobe : ps->s1,
            rest = ps->depth == 1 ? 1 : (ps->all_s_rest && lobe);
        ps->keep[lobe] = !higher_only || !ref_basic_class(ps->depth, c1, rest, c->p.max_specular);
    }
}

static int ref_any_positive(const float v[3])
{
    return v[0] > 0.0f || v[1] > 0.0f || v[2] > 0.0f;
}

/* The continuation's survival probability: 1 before min_depth, then min(1, the largest channel
 * of the throughput it would carry, from the material's untextured reflectance refl, the lobe's
 * weight f and its selection probability prob), that throughput doubled with light vertices
 * (REF_RR_LV). */
static float ref_path_survival(const ref_ctx *c, const ref_path_state *ps, const float refl[3],
                               float f, float prob)
{
    if (ps->depth < c->p.min_depth)
        return 1.0f;
    float est = 0.0f;
    for (int k = 0; k < 3; k++)
        est = ref_fmaxf(est, ps->beta[k] * refl[k] * f / prob);
    return ref_fminf(1.0f, c->lv_on ? est * REF_RR_LV : est);
}

/* The MIS weights of next-event estimation's diffuse part at cur when a diffuse bounce reached
 * it: the same paths are light vertices connected to the vertex before (ref_connect.c). */
static void ref_path_weights(const ref_path_state *ps, ref_nee_vis *v)
{
    if (!(ps->arr_pa > 0.0f))
        return;
    float pa = ref_camera_density(ps->arr_x, ps->arr_n, ps->arr_pa, ps->cur.p, ps->cur.ng);
    for (int i = 0; i < v->n; i++)
        if (v->pb[i] > 0.0f)
            v->wd[i] = ref_mis_weight(pa, v->pb[i]);
}

static void ref_path_weigh(const void *ps, ref_nee_vis *v)
{
    ref_path_weights(ps, v);
}

/* Next-event estimation at cur toward every light with the MIS weights: scenes with more lights
 * than one ref_nee_vis holds. */
static void ref_path_nee_all(const ref_ctx *c, const ref_path_state *ps, const ref_mat *m,
                             float dif[3], float spec[3], long long *rays)
{
    ref_nee_weighed(c->w, &ps->cur, m, ps->wcur, dif, spec, rays, ref_path_weigh, ps);
}

/* The light vertex's connection to cur through cur's diffuse lobe, a path one vertex longer than
 * cur's own (so only below max_depth, and in `higher` only when its class is not basic), weighted
 * against the diffuse bounce the camera path would take here (its selection and roulette). */
static void ref_path_connect(const ref_ctx *c, int higher_only, ref_path_state *ps,
                             long long *rays)
{
    const gib_material *gm = ps->cur.mat;
    ps->conn_on = 0;
    if (!c->lv_on || !ps->lv.ok || ps->depth >= c->p.max_depth || ps->cur.back)
        return;
    if (higher_only && ref_basic_class(ps->depth + 1, ps->depth == 1 ? 0 : ps->s1, 0,
                                       c->p.max_specular))
        return;
    float pd = ref_lum(gm->albedo);
    float psp = gm->spec_type != GIB_SPEC_NONE ? ref_lum(gm->specular) : 0.0f;
    if (!(pd > 0.0f))
        return;
    float prob = pd / (pd + psp), pa = prob * ref_path_survival(c, ps, gm->albedo, 1.0f, prob);
    ps->conn_on = ref_lv_connect(c->w, &ps->cur, &ps->lv, pa, ps->conn, rays);
}

/* The vertex's shadow rays toward the delta lights, cast before its texel is read: the light's
 * part does not depend on the texel (a texel of 0 only makes a ray unnecessary), and a last
 * vertex that no light reaches then needs no texel at all. Scenes with more lights than one
 * ref_nee_vis holds take ref_nee whole at the vertex instead. */
static void ref_path_shadow_rays(const ref_ctx *c, ref_path_state *ps, long long *rays)
{
    const ref_hit *cur = &ps->cur;
    const gib_material *gm = cur->mat;
    ps->nee_cast = 0;
    if (!(ps->keep[0] || ps->keep[1]) || (cur->has_nee && ps->keep[0] && ps->keep[1]) ||
        c->w->gs->light_count > REF_NEE_LIGHTS)
        return;
    int want_d = ps->keep[0] && ref_any_positive(gm->albedo);
    ps->nee_want_s = ps->keep[1] && gm->spec_type == GIB_SPEC_PHONG &&
                     ref_any_positive(gm->specular);
    ref_nee_visible(c->w, cur, ps->wcur, want_d, ps->nee_want_s, gm->phong_n, 0, &ps->vis, rays);
    ref_path_weights(ps, &ps->vis);
    ps->nee_cast = 1;
}

/* choose the continuation from the material's constants, and trace it */
static void ref_path_trace_continuation(const ref_ctx *c, ref_path_state *ps, long long *rays)
{
    const ref_world *w = c->w;
    const gib_material *gm = ps->cur.mat;
    int spec = gm->spec_type != GIB_SPEC_NONE;
    float pd = ref_lum(gm->albedo), psp = spec ? ref_lum(gm->specular) : 0.0f;
    int cont = ps->depth < c->p.max_depth && pd + psp > 0.0f;
    ps->lobe_s = 0, ps->hit = 0, ps->f = 1.0f, ps->q = 1.0f, ps->prob = 1.0f;
    ps->cont_pa = 0.0f;
    if (!cont)
        return;
    float u0 = ref_rng_1d(ps->rng), u1, u2;
    ref_rng_2d(ps->rng, &u1, &u2);
    ps->lobe_s = u0 * (pd + psp) >= pd;
    ps->prob = (ps->lobe_s ? psp : pd) / (pd + psp);
    if (!ps->lobe_s) {
        ref_sample_cosine(ps->cur.n, u1, u2, ps->d);
    } else {
        float r[3];
        ref_reflect(ps->wcur, ps->cur.n, r);
        if (gm->spec_type == GIB_SPEC_PHONG)
            ps->f = ref_sample_phong(r, gm->phong_n, ps->cur.n, u1, u2, ps->d);
        else
            memcpy(ps->d, r, sizeof ps->d);
    }
    cont = ps->f > 0.0f && ref_dot(ps->d, ps->cur.ng) > 0.0f;
    if (cont && ps->depth >= c->p.min_depth) { /* roulette on the untextured throughput estimate */
        ps->q = ref_path_survival(c, ps, ps->lobe_s ? gm->specular : gm->albedo, ps->f, ps->prob);
        cont = ref_rng_1d(ps->rng) < ps->q;
    }
    if (cont) {
        if (!ps->lobe_s && c->lv_on)
            ps->cont_pa = ps->prob * ps->q;
        float o[3];
        ref_offset_origin(w, &ps->cur, ps->d, o);
        ++*rays;
        ps->hit = ref_trace_start(w, o, ps->d, &ps->pend);
    }
}

/* 1. the continuation, then the vertex's shadow rays (from the same point: Embree finds the two
 * close together in its tree) */
static void ref_path_continue(const ref_ctx *c, int higher_only, ref_path_state *ps,
                              long long *rays)
{
    ref_path_keep(c, higher_only, ps);
    ref_path_trace_continuation(c, ps, rays);
    ref_path_shadow_rays(c, ps, rays);
    ref_path_connect(c, higher_only, ps, rays);
}

/* 2. this vertex: textured material, next-event estimation (diffuse and Phong parts are different
 * classes; `higher` skips the parts whose class is basic); 3. the continuation's weight with the
 * textured reflectances, and the next vertex. Clears live when the path ends here. */
static void ref_path_vertex(const ref_ctx *c, ref_path_state *ps, long long *rays)
{
    const ref_world *w = c->w;
    const ref_hit *cur = &ps->cur;
    const int depth = ps->depth;
    const int *keep = ps->keep;
    ps->live = 0;
    /* a last vertex that adds nothing (no part kept, or no light reaches it and there is no sky)
     * reads no texel: out += beta * 0 would leave out exactly as it is */
    if (!ps->hit && !ps->conn_on &&
        (!(keep[0] || keep[1]) || (ps->nee_cast && ps->vis.n == 0 && !ref_has_sky(w->gs))))
        return;
    ref_mat m;
    ref_material(w, cur, &m);
    if (keep[0] || keep[1]) {
        ref_mat mn; /* m with the diffuse part dropped when it is not kept */
        const ref_mat *mk = &m;
        if (!keep[0]) {
            mn = m;
            mn.kd[0] = mn.kd[1] = mn.kd[2] = 0.0f;
            mk = &mn;
        }
        float dif[3], sp[3];
        if (cur->has_nee && keep[0] && keep[1]) { /* the pixel's own, computed once */
            memcpy(dif, cur->nee_dif, sizeof dif);
            memcpy(sp, cur->nee_spec, sizeof sp);
        } else if (ps->nee_cast) {
            dif[0] = dif[1] = dif[2] = sp[0] = sp[1] = sp[2] = 0.0f;
            ref_nee_shade(&ps->vis, mk, dif, ps->nee_want_s ? sp : NULL);
        } else {
            ref_path_nee_all(c, ps, mk, dif, keep[1] ? sp : NULL, rays);
        }
        if (ref_has_sky(w->gs))
            ref_nee_sky(w, cur, mk, ps->wcur, ps->rng, dif, keep[1] ? sp : NULL, rays);
        for (int k = 0; k < 3; k++)
            ps->out[k] += ps->beta[k] * (dif[k] + (keep[1] ? sp[k] : 0.0f));
    }
    if (ps->conn_on)
        for (int k = 0; k < 3; k++)
            ps->out[k] += ps->beta[k] * m.kd[k] * ps->conn[k];
    if (!ps->hit)
        return;

    const float *refl = ps->lobe_s ? m.ks : m.kd;
    for (int k = 0; k < 3; k++)
        ps->beta[k] *= refl[k] * ps->f / (ps->prob * ps->q);
    if (depth == 1)
        ps->s1 = ps->lobe_s;
    else
        ps->all_s_rest = ps->all_s_rest && ps->lobe_s;
    for (int k = 0; k < 3; k++)
        ps->arr_x[k] = cur->p[k], ps->arr_n[k] = cur->n[k];
    ps->arr_pa = ps->cont_pa;
    ref_trace_finish(w, &ps->pend, &ps->cur);
    if (ps->cur.back || (ps->beta[0] <= 0.0f && ps->beta[1] <= 0.0f && ps->beta[2] <= 0.0f))
        return;
    ps->wcur[0] = -ps->d[0], ps->wcur[1] = -ps->d[1], ps->wcur[2] = -ps->d[2];
    ps->depth++;
    ps->live = 1;
}

void ref_est_paths(const ref_ctx *c, const ref_hit *h, const float wo[3], int higher_only,
                   int n, ref_rng *rng, float (*out)[3], long long *rays)
{
    ref_path_state ps[REF_PATH_BATCH];
    int live = 0;
    n = n < REF_PATH_BATCH ? n : REF_PATH_BATCH;
    for (int i = 0; i < n; i++) {
        ref_path_state *p = &ps[i];
        p->rng = &rng[i];
        p->out = out[i];
        p->out[0] = p->out[1] = p->out[2] = 0.0f;
        p->live = !h->back;
        live += p->live;
        if (!p->live)
            continue;
        p->cur = *h;
        memcpy(p->wcur, wo, sizeof p->wcur);
        p->beta[0] = p->beta[1] = p->beta[2] = 1.0f;
        p->depth = 1;
        p->s1 = 0;
        p->all_s_rest = 1;
        p->arr_pa = 0.0f;
        p->lv.ok = 0;
        if (c->lv_on)
            ref_lv_sample(c->w, p->rng, &p->lv, rays);
    }
    while (live > 0) {
        for (int i = 0; i < n; i++)
            if (ps[i].live)
                ref_path_continue(c, higher_only, &ps[i], rays);
        live = 0;
        for (int i = 0; i < n; i++)
            if (ps[i].live) {
                ref_path_vertex(c, &ps[i], rays);
                live += ps[i].live;
            }
    }
}

void ref_est_caustic(const ref_ctx *c, const ref_hit *h, ref_rng *rng, float out[3],
                     long long *rays)
{
    const ref_world *w = c->w;
    out[0] = out[1] = out[2] = 0.0f;
    float u1, u2;
    ref_rng_2d(rng, &u1, &u2);
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
        ++*rays; /* a ray that meets no specular triangle ends here as its whole trace would */
        if (!ref_may_hit_specular(w, o, d) || !ref_trace(w, o, d, &cur) || cur.back)
            return;
        ref_mat m; /* the specular lobe alone: this vertex's diffuse lobe is not caustic's */
        m.kd[0] = m.kd[1] = m.kd[2] = 0.0f;
        ref_material_specular(&cur, &m);
        if (m.spec == GIB_SPEC_NONE)
            return;
        const float wo[3] = {-d[0], -d[1], -d[2]};
        /* x_verts next to the light, through its specular lobe: the delta lights through a Phong
         * lobe, the sky through a Phong lobe or a mirror */
        const ref_mat ms = m;
        float dif[3], spec[3];
        ref_nee(w, &cur, &ms, wo, dif, spec, rays);
        ref_nee_sky(w, &cur, &ms, wo, rng, dif, spec, rays);
        for (int k = 0; k < 3; k++)
            out[k] += beta[k] * spec[k];
        if (verts == c->p.max_specular + 1)
            return;
        float r[3], f = 1.0f;
        ref_reflect(wo, cur.n, r);
        if (m.spec == GIB_SPEC_PHONG) {
            float v1, v2;
            ref_rng_2d(rng, &v1, &v2);
            f = ref_sample_phong(r, m.phong_n, cur.n, v1, v2, d);
        }
        else
            d[0] = r[0], d[1] = r[1], d[2] = r[2];
        if (!(f > 0.0f))
            return;
        for (int k = 0; k < 3; k++)
            beta[k] *= m.ks[k] * f;
    }
}

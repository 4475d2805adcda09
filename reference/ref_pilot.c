/* gibench — the pilot that chooses full and higher's strategies (GIB_REF_STRATEGIES_AUTO).
 *
 * Light vertices (ref_connect.c) cost a ray per sample and a shadow ray per camera vertex. Where
 * a light lights a nearby surface brightly (a lamp under a ceiling) they cut the noise several
 * times over; where the light is spread thin (a spot over an open floor) they cut it by a few
 * percent and the rays are wasted. Which one a scene is cannot be told from its description, so
 * the render measures it: before the first round, every REF_PILOT_STRIDE-th pixel in x and y takes
 * REF_PILOT_SPP independent samples (PCG32, its own seeds) of the image's estimator, once with
 * light vertices and once without; each way's variance is the sum of the pixels' sample
 * variances scaled to the whole image, its cost its rays (a shadow ray weighted REF_PILOT_SHADOW
 * of a closest-hit one), and the gain (variance x cost without) / (variance x cost with) decides
 * (light vertices above 1). The light-tracing part of scenes with mirrors is the same either way
 * but adds to both sides' variance and cost (a sixteenth of a pass estimates them): where it
 * dominates, halving the camera part's noise is not worth twice its rays.
 *
 * The choice is a function of the scene, camera and parameters alone (seed included, spp not):
 * the same request always renders the same way, whatever the threads, and a --target-noise run
 * makes it once, before its first round, as a plain run does. Its cost: 2 x 16 samples for one
 * pixel in 16 (two samples a pixel) and a sixteenth of a light pass, about 1% of a 256-spp
 * render, 10% of a 16-spp one. Being independent samples, it measures Monte Carlo efficiency;
 * the Sobol points of the render gain as much or more with light vertices as without (closed
 * room 2.8x against 1.3x in variance, Cornell box 2.2x against 1.6x, furnace 2.8x against 3.3x),
 * so where it errs it mostly errs toward camera paths alone (the Cornell box: 0.98 measured by
 * the pilot, 1.4-1.7 with Sobol points). */
#include <math.h>
#include <stdlib.h>

#include "ref_internal.h"

#define REF_PILOT_STRIDE 4
#define REF_PILOT_SPP REF_PATH_BATCH
/* A shadow ray's cost in closest-hit rays, shading included: on the closed room of
 * reference/PERFORMANCE.md, light vertices' extra rays (nearly all shadow rays) took 0.55 of the
 * time a ray of camera paths took. */
#define REF_PILOT_SHADOW 0.5
#define REF_PILOT_SALT 0x7069c07e5eedull
#define REF_PILOT_PASS 0xffffffffull /* the light pilot's pass: past any render's (max_spp) */

typedef struct ref_pilot {
    ref_ctx c;               /* the image's context; lv_on set per pass */
    int x0, y0, rows;
    double *var, *cost;      /* per pilot row */
} ref_pilot;

/* The summed sample variance (three channels) of one pilot pixel; its rays to *closest and
 * *shadow. */
static double ref_pilot_pixel(const ref_ctx *c, int x, int y, long long *closest,
                              long long *shadow)
{
    ref_hit h;
    float wo[3];
    long long rays = 0;
    if (!ref_pixel_hit(c, x, y, &h, wo, &rays))
        return 0.0;
    uint64_t pix = (uint64_t)y * (uint64_t)c->p.width + (uint64_t)x;
    ref_rng rng[REF_PILOT_SPP];
    float v[REF_PILOT_SPP][3];
    for (int i = 0; i < REF_PILOT_SPP; i++)
        ref_rng_seed_sample(&rng[i], GIB_REF_SAMPLER_RANDOM, pix, (uint64_t)i,
                            c->p.seed ^ REF_PILOT_SALT, c->p.component);
    long long s0 = ref_shadow_rays();
    rays = 0;
    ref_sample_camera(c, &h, wo, REF_PILOT_SPP, rng, v, &rays);
    long long sh = ref_shadow_rays() - s0;
    *shadow += sh;
    *closest += rays - sh;
    double var = 0.0;
    for (int k = 0; k < 3; k++) {
        double m = 0.0, m2 = 0.0;
        for (int i = 0; i < REF_PILOT_SPP; i++)
            m += v[i][k];
        m /= REF_PILOT_SPP;
        for (int i = 0; i < REF_PILOT_SPP; i++)
            m2 += ((double)v[i][k] - m) * ((double)v[i][k] - m);
        var += m2 / (REF_PILOT_SPP - 1);
    }
    return var;
}

static void ref_pilot_row(void *ctx, int row)
{
    ref_pilot *pl = ctx;
    const int y = pl->y0 + row * REF_PILOT_STRIDE;
    long long closest = 0, shadow = 0;
    double var = 0.0;
    for (int x = pl->x0; x < pl->c.p.width; x += REF_PILOT_STRIDE)
        var += ref_pilot_pixel(&pl->c, x, y, &closest, &shadow);
    pl->var[row] = var;
    pl->cost[row] = (double)closest + REF_PILOT_SHADOW * (double)shadow;
}

/* One pass of the camera pilot, lv_on as asked: the variance of a one-sample-per-pixel image
 * summed over all pixels (*var) and its cost per sample per pixel over all pixels (*cost),
 * scaled from the pilot pixels (sums in row order). */
static void ref_pilot_camera(ref_pilot *pl, int lv_on, int nthreads, double *var, double *cost)
{
    pl->c.lv_on = lv_on;
    ref_parallel(nthreads, pl->rows, ref_pilot_row, pl, NULL);
    double v = 0.0, k = 0.0;
    for (int r = 0; r < pl->rows; r++)
        v += pl->var[r], k += pl->cost[r];
    const int cols = (pl->c.p.width - pl->x0 + REF_PILOT_STRIDE - 1) / REF_PILOT_STRIDE;
    const double scale = (double)pl->c.p.width * pl->c.p.height / ((double)cols * pl->rows);
    *var = v * scale;
    *cost = k * scale / REF_PILOT_SPP;
}

typedef struct ref_pilot_lt {
    const ref_ctx *c;
    int count;               /* particles in all */
    double *var, *cost;      /* per chunk */
} ref_pilot_lt;

static void ref_pilot_chunk(void *ctx, int chunk)
{
    ref_pilot_lt *lt = ctx;
    int first = chunk * REF_LIGHT_CHUNK;
    int n = lt->count - first < REF_LIGHT_CHUNK ? lt->count - first : REF_LIGHT_CHUNK;
    ref_splats sp = {0};
    long long rays = 0, s0 = ref_shadow_rays();
    ref_light_chunk(lt->c, REF_PILOT_PASS, (uint32_t)chunk, n, &sp, &rays);
    long long sh = ref_shadow_rays() - s0;
    double v = 0.0;
    for (size_t i = 0; i < sp.n; i++)
        for (int k = 0; k < 3; k++)
            v += (double)sp.s[i].v[k] * sp.s[i].v[k];
    free(sp.s);
    lt->var[chunk] = v;
    lt->cost[chunk] = (double)(rays - sh) + REF_PILOT_SHADOW * (double)sh;
}

/* The light-tracing part (scenes with mirrors), the same whichever the strategies: one pass's
 * variance summed over pixels, sum_j Var(pass_j) ~ P E[sum of a particle's squared splats] for
 * the P independent particles of a pass (splats already divided by P), and its cost, both
 * estimated from a sixteenth of a pass (its own pass index). */
static void ref_pilot_light(const ref_ctx *c, int nthreads, double *var, double *cost)
{
    const long long P = ref_light_particles(c);
    long long n = P / (REF_PILOT_STRIDE * REF_PILOT_STRIDE);
    n = n < 1 ? 1 : n;
    int chunks = (int)((n + REF_LIGHT_CHUNK - 1) / REF_LIGHT_CHUNK);
    ref_pilot_lt lt = {.c = c, .count = (int)n};
    lt.var = calloc((size_t)chunks, sizeof *lt.var);
    lt.cost = calloc((size_t)chunks, sizeof *lt.cost);
    *var = *cost = 0.0;
    if (lt.var && lt.cost) {
        ref_parallel(nthreads, chunks, ref_pilot_chunk, &lt, NULL);
        for (int i = 0; i < chunks; i++)
            *var += lt.var[i], *cost += lt.cost[i];
        *var *= (double)P / (double)n;
        *cost *= (double)P / (double)n;
    }
    free(lt.var);
    free(lt.cost);
}

double ref_pilot_gain(const ref_ctx *c, int nthreads)
{
    ref_pilot pl = {.c = *c};
    const int W = c->p.width, H = c->p.height;
    pl.x0 = W >= REF_PILOT_STRIDE ? REF_PILOT_STRIDE / 2 : 0;
    pl.y0 = H >= REF_PILOT_STRIDE ? REF_PILOT_STRIDE / 2 : 0;
    pl.rows = (H - pl.y0 + REF_PILOT_STRIDE - 1) / REF_PILOT_STRIDE;
    pl.var = calloc((size_t)pl.rows, sizeof *pl.var);
    pl.cost = calloc((size_t)pl.rows, sizeof *pl.cost);
    double gain = 0.0, vc, cc, vl, cl, vt = 0.0, ct = 0.0;
    if (pl.var && pl.cost) {
        ref_pilot_camera(&pl, 0, nthreads, &vc, &cc);
        ref_pilot_camera(&pl, 1, nthreads, &vl, &cl);
        if (c->light_part)
            ref_pilot_light(c, nthreads, &vt, &ct);
        double cam = (vc + vt) * (cc + ct), lv = (vl + vt) * (cl + ct);
        gain = cam > 0.0 ? (lv > 0.0 ? cam / lv : INFINITY) : 0.0;
    }
    free(pl.var);
    free(pl.cost);
    return gain;
}

/* Reference renderer: several components of one view rendered together (gib_reference_render_set,
 * reference/ref_set.c) give each component's render alone, bit for bit, and the cache stores
 * them as the entries single requests find (gib_reference_get_set, harness/app/refcache.c).
 *
 * Scene: ref_determinism's (a floor, an alpha-masked two-sided Phong board, a mirror wall, a
 * point light): every estimator runs on it, light tracing included. Checks:
 *  - every component (ao, direct, indirect, glossy, caustic, full, higher, albedo, normal,
 *    depth) in one set, each with its own spp, two toward a target noise (their own rounds), with
 *    two more AO images (bounded, obscurance: the set shares their rays) and indirect at another
 *    size (a second view of the world), against each rendered alone: the same image and
 *    standard-error bits, and the same spp, rounds, mean, noise, rays, target reached and
 *    strategies; on 1 thread as on all;
 *  - the set's components add up: with max_depth 2, full = direct + indirect + glossy + caustic
 *    + higher in expectation (tests/reference/ref_sum.c, there from separate renders): image
 *    means within 4 standard errors of their difference per channel (the renders' own errors in
 *    quadrature; independent samples, each component on its own streams), every 4x4 block's
 *    within 4.5 (64 blocks x 3 channels); a negative control, the sum without higher, must part
 *    by more than 4, else the check could not see a component missing;
 *  - a set of more components than it holds is refused;
 *  - through the cache: the set's entries are found by single requests, with the set's pixels,
 *    and a second set finds them all. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness/app/app.h"
#include "ref_test_util.h"

enum { W = 32, H = 32, NB = 4 };
/* The sum rule's samples per pixel: the negative control parts by 12 standard errors. The whole
 * test takes ~1.5 s in release, ~3 s under AddressSanitizer: no smaller count is needed there. */
enum { SPP = 1024 };

static int same_bits(const gib_image *a, const gib_image *b)
{
    return a->width == b->width && a->height == b->height && a->channels == b->channels &&
           !memcmp(a->px, b->px, (size_t)a->width * a->height * a->channels * sizeof *a->px);
}

/* Every component together against each alone, and three more: AO within 0.5 m and obscurance
 * within 1 m (whose rays the set shares with the unbounded AO's), indirect at another size. */
enum { NSET = GIB_COMP_COUNT + 3 };
static void check_bits(const gib_scene *s, int threads)
{
    gib_ref_params p[NSET];
    static const int spp[NSET] = {16, 1, 16, 24, 32, 16, 8, 1, 1, 1, 16, 24, 16};
    for (int c = 0; c < NSET; c++) {
        static const int extra[3] = {GIB_COMP_AO, GIB_COMP_AO, GIB_COMP_INDIRECT};
        p[c] = rt_params(c < GIB_COMP_COUNT ? c : extra[c - GIB_COMP_COUNT], W, H, spp[c]);
        p[c].max_depth = 4;
        p[c].threads = threads;
    }
    p[GIB_COMP_COUNT].dmax = 0.5f;
    p[GIB_COMP_COUNT + 1].dmax = 1.0f;
    p[GIB_COMP_COUNT + 1].obscurance = 1;
    p[GIB_COMP_COUNT + 2].width = W / 2;
    p[GIB_COMP_COUNT + 2].height = H - 8;
    p[GIB_COMP_INDIRECT].target_noise = 0.3; /* rounds of its own: 16, 64, ... */
    p[GIB_COMP_INDIRECT].max_spp = 256;
    p[GIB_COMP_HIGHER].target_noise = 0.5;
    p[GIB_COMP_HIGHER].max_spp = 64;
    gib_image img[NSET], sd[NSET];
    gib_ref_stats st[NSET];
    gib_error err;
    int rc = gib_reference_render_set(s, p, NSET, img, sd, st, &err);
    CHECK(rc == 0, "the set failed: %s", err.msg);
    if (rc < 0)
        return;
    int rounds_differ = 0;
    for (int c = 0; c < NSET; c++) {
        gib_image a, asd;
        gib_ref_stats as;
        rt_render(s, &p[c], &a, &asd, &as);
        const gib_ref_stats *b = &st[c];
        const char *name = gib_component_name(p[c].component);
        printf("  %-8s %2dx%2d dmax %-3g threads %d: %3d spp, %d rounds, mean %.6g noise %.4g "
               "rays %lld\n", name, p[c].width, p[c].height, (double)p[c].dmax, threads, b->spp,
               b->rounds, b->mean, b->noise_rmse, b->rays);
        CHECK(same_bits(&a, &img[c]) && same_bits(&asd, &sd[c]),
              "%s %d: the set's image or standard error differs from its render alone", name, c);
        CHECK(as.spp == b->spp && as.rounds == b->rounds && as.mean == b->mean &&
                  as.noise_rmse == b->noise_rmse && as.rays == b->rays &&
                  as.target_reached == b->target_reached &&
                  as.light_vertices == b->light_vertices && as.pilot_gain == b->pilot_gain,
              "%s: the set's statistics differ from its render alone (spp %d/%d, rounds %d/%d, "
              "rays %lld/%lld)", name, b->spp, as.spp, b->rounds, as.rounds, b->rays, as.rays);
        rounds_differ |= b->rounds != st[0].rounds;
        gib_image_free(&a), gib_image_free(&asd);
        gib_image_free(&img[c]), gib_image_free(&sd[c]);
    }
    CHECK(rounds_differ, "every component took the same rounds: the test asked for own rounds");
}

typedef struct planes { /* per channel: pixel values and variances of the mean */
    double v[3 * W * H], var[3 * W * H];
} planes;

/* Adds an image and its variances into acc. */
static void accumulate(planes *acc, const gib_image *img, const gib_image *sd)
{
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++) {
            acc->v[c * W * H + i] += (double)img->px[3 * i + c];
            acc->var[c * W * H + i] += (double)sd->px[3 * i + c] * sd->px[3 * i + c];
        }
}

/* full = direct + indirect + glossy + caustic + higher (max_depth 2), all from one set. */
static void check_sum(const gib_scene *s)
{
    static const int comps[] = {GIB_COMP_FULL, GIB_COMP_DIRECT, GIB_COMP_INDIRECT,
                                GIB_COMP_GLOSSY, GIB_COMP_CAUSTIC, GIB_COMP_HIGHER};
    enum { N = sizeof comps / sizeof comps[0] };
    gib_ref_params p[N];
    for (int k = 0; k < N; k++) {
        p[k] = rt_params(comps[k], W, H, SPP);
        p[k].max_depth = 2;
        p[k].sampler = GIB_REF_SAMPLER_RANDOM; /* independent samples: normal block means */
    }
    gib_image img[N], sd[N];
    gib_ref_stats st[N];
    gib_error err;
    if (gib_reference_render_set(s, p, N, img, sd, st, &err) < 0) {
        CHECK(0, "the set failed: %s", err.msg);
        return;
    }
    planes *full = calloc(1, sizeof *full), *sum = calloc(1, sizeof *sum),
           *control = calloc(1, sizeof *control);
    if (!full || !sum || !control) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    for (int k = 0; k < N; k++) {
        accumulate(k == 0 ? full : sum, &img[k], &sd[k]);
        if (k > 0 && comps[k] != GIB_COMP_HIGHER)
            accumulate(control, &img[k], &sd[k]);
        printf("  %-8s %d spp: mean %.6g noise %.4g\n", gib_component_name(comps[k]), st[k].spp,
               st[k].mean, st[k].noise_rmse);
    }
    double zm, zb, cm, cb;
    rt_z_diff(full->v, full->var, sum->v, sum->var, W, H, NB, &zm, &zb);
    rt_z_diff(full->v, full->var, control->v, control->var, W, H, NB, &cm, &cb);
    zm = fabs(zm), cm = fabs(cm);
    printf("  full - (direct + indirect + glossy + caustic + higher): image means %.2f sigma, "
           "worst 4x4 block %.2f; without higher %.2f\n", zm, zb, cm);
    CHECK_AT_MOST("set sum rule: image means (standard errors)", zm, 4.0,
                  "the six renders' own errors in quadrature, per channel");
    CHECK_AT_MOST("set sum rule: worst 4x4 block (standard errors)", zb, 4.5,
                  "64 blocks x 3 channels of 16 pixels each");
    CHECK(cm > 4.0, "negative control: the sum without higher parts by %.2f sigma only: the "
                    "check has no power", cm);
    for (int k = 0; k < N; k++)
        gib_image_free(&img[k]), gib_image_free(&sd[k]);
    free(full);
    free(sum);
    free(control);
}

static void check_refused(const gib_scene *s)
{
    gib_ref_params p[GIB_REF_SET_MAX + 1];
    for (int k = 0; k <= GIB_REF_SET_MAX; k++)
        p[k] = rt_params(GIB_COMP_DIRECT, W, H, 1);
    gib_image img[GIB_REF_SET_MAX + 1];
    gib_error err = {0};
    int rc = gib_reference_render_set(s, p, GIB_REF_SET_MAX + 1, img, NULL, NULL, &err);
    CHECK(rc < 0 && strstr(err.msg, "a set holds"), "%d components in one set: rc %d, '%s'",
          GIB_REF_SET_MAX + 1, rc, err.msg);
}

/* Through the cache: a set's entries serve single requests, then a second set. */
static void check_cache(const gib_scene *s)
{
    char dir[] = "/tmp/gib_ref_set_XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "no temporary folder");
    static const int comps[3] = {GIB_COMP_INDIRECT, GIB_COMP_GLOSSY, GIB_COMP_CAUSTIC};
    gib_ref_request rq[3];
    gib_ref_result res[3], again[3];
    gib_error err;
    for (int k = 0; k < 3; k++)
        rq[k] = (gib_ref_request){.scene = s, .width = W, .height = H, .component = comps[k],
                                  .spp = 16, .cache_dir = dir, .quiet = 1};
    int rc = gib_reference_get_set(rq, 3, res, &err);
    CHECK(rc == 0, "the set through the cache failed: %s", rc < 0 ? err.msg : "");
    for (int k = 0; rc == 0 && k < 3; k++) {
        gib_ref_result one;
        int grc = gib_reference_get(&rq[k], &one, &err);
        CHECK(grc == 0 && one.from_cache && !res[k].from_cache &&
                  !strcmp(one.path, res[k].path) && same_bits(&one.image, &res[k].image),
              "%s: the set's cache entry does not serve the request alone",
              gib_component_name(comps[k]));
        gib_image_free(&one.image);
    }
    rc = rc == 0 ? gib_reference_get_set(rq, 3, again, &err) : -1;
    for (int k = 0; rc == 0 && k < 3; k++) {
        CHECK(again[k].from_cache && same_bits(&again[k].image, &res[k].image),
              "%s: a second set did not find the entry", gib_component_name(comps[k]));
        gib_image_free(&again[k].image);
        unlink(res[k].path);
        gib_image_free(&res[k].image);
    }
    rmdir(dir);
}

int main(void)
{
    gib_scene s;
    rt_scene_mixed(&s);
    printf("every component together against each alone:\n");
    check_bits(&s, 0);
    check_bits(&s, 1);
    printf("the set's components add up (max_depth 2, %d spp):\n", SPP);
    check_sum(&s);
    check_refused(&s);
    check_cache(&s);
    rt_scene_free(&s);
    printf("%s\n", failures ? "FAIL" : "PASS");
    return failures != 0;
}

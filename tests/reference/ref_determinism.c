/* Reference renderer, determinism (ARCHITECTURE.md, "Reference renderer": a rerun gives the same image
 * bit for bit) and sampling toward a target noise.
 *
 * Expected:
 *  - every component (the light-traced ones too) rendered with 1, 2, 3 and 7 threads gives
 *    bit-identical images, standard-error images and statistics (mean, noise_rmse, rays): each
 *    sample has its own seeded generator, pixels accumulate their samples in order, light-tracing
 *    chunks are merged in chunk order, image-wide sums are taken in pixel order;
 *  - a different seed changes a random component's image (else the seed is ignored);
 *  - --target-noise: the rounds stop once noise_rmse / mean <= target (or at max_spp, then
 *    target_reached = 0), and the image of a run that stopped at N samples is bit-identical to a
 *    plain N-sample render (sample N is the same number whether drawn in round 1 or round 3);
 *    the header's `stop` says which;
 *  - an interrupt (gib_ref_interrupt) requested before the first round ends the render after it;
 *    one requested during round 2 abandons that round (or stops after it, if it had finished),
 *    and the rounds kept are bit-identical to a plain render of their spp.
 * The scene has an alpha-masked occluder (Embree filter callbacks run concurrently), a Phong
 * object and a mirror (so glossy, caustic and the light-traced part of full/higher run); all of it
 * runs again with a sky (the sky's sampling in every estimator; `direct` then random, so its
 * seed must matter and its target noise be reachable). No tolerance: equality of bytes, and the
 * target inequality itself. */
#include <pthread.h>
#include <string.h>
#include <time.h>

#include "ref_test_util.h"

static int same(const gib_image *a, const gib_image *b)
{
    return a->width == b->width && a->height == b->height &&
           memcmp(a->px, b->px, (size_t)a->width * a->height * 3 * sizeof(float)) == 0;
}

static void test_threads(const gib_scene *s)
{
    const int W = 40, H = 37; /* odd height: rows do not split evenly over the threads */
    const int threads[4] = {1, 2, 3, 7};
    for (int comp = 0; comp < GIB_COMP_COUNT; comp++) {
        gib_image base = {0}, base_sd = {0};
        gib_ref_stats base_st = {0};
        gib_ref_params p = rt_params(comp, W, H, comp == GIB_COMP_AO ? 32 : 4);
        p.dmax = 1.0f;
        p.max_depth = 4;
        p.min_depth = 2; /* Russian roulette on */
        p.max_specular = 2;
        for (int i = 0; i < 4; i++) {
            gib_image img, sd;
            gib_ref_stats st;
            p.threads = threads[i];
            rt_render(s, &p, &img, &sd, &st);
            if (i == 0) {
                base = img;
                base_sd = sd;
                base_st = st;
                continue;
            }
            CHECK(same(&img, &base), "%s: %d threads: image differs from 1",
                  gib_component_name(comp), threads[i]);
            CHECK(same(&sd, &base_sd), "%s: %d threads: stderr differs from 1",
                  gib_component_name(comp), threads[i]);
            CHECK(st.mean == base_st.mean && st.noise_rmse == base_st.noise_rmse &&
                      st.rays == base_st.rays,
                  "%s: %d threads: statistics differ", gib_component_name(comp), threads[i]);
            gib_image_free(&img);
            gib_image_free(&sd);
        }
        if (!gib_component_deterministic(s, comp)) {
            gib_image img;
            p.seed = 2;
            rt_render(s, &p, &img, NULL, NULL);
            CHECK(!same(&img, &base), "%s: seed 2 gives the seed-1 image",
                  gib_component_name(comp));
            gib_image_free(&img);
        }
        printf("%-8s threads 1, 2, 3, 7 bit-identical (image, stderr, stats); mean %.6f "
               "noise_rmse %.6f rays %lld\n",
               gib_component_name(comp), base_st.mean, base_st.noise_rmse, base_st.rays);
        gib_image_free(&base);
        gib_image_free(&base_sd);
    }
}

/* 1 when img, its standard error sd and its noise (st) are those of a plain render of st->spp
 * samples at img's size (max_depth 3, as every test here). */
static int same_as_plain(const gib_scene *s, int comp, const gib_image *img, const gib_image *sd,
                         const gib_ref_stats *st)
{
    gib_ref_params q = rt_params(comp, img->width, img->height, st->spp);
    q.max_depth = 3;
    gib_image img2, sd2;
    gib_ref_stats st2;
    rt_render(s, &q, &img2, &sd2, &st2);
    int ok = same(img, &img2) && same(sd, &sd2) && st->noise_rmse == st2.noise_rmse;
    gib_image_free(&img2);
    gib_image_free(&sd2);
    return ok;
}

/* The header's `stop` for a render of p that ended with st. */
static const char *header_stop(const gib_scene *s, const gib_ref_params *p,
                               const gib_ref_stats *st, gib_kv kv[GIB_REF_ATTR_COUNT])
{
    int nkv = gib_reference_attrs(s, p, st, kv, GIB_REF_ATTR_COUNT);
    const char *stop = gib_kv_get(kv, nkv, "stop");
    return stop ? stop : "(missing)";
}

static void test_target(const gib_scene *s, int comp, double target, int max_spp, int reach)
{
    const int W = 24, H = 20;
    gib_ref_params p = rt_params(comp, W, H, 4);
    p.target_noise = target;
    p.max_spp = max_spp;
    p.max_depth = 3;
    gib_image img, sd;
    gib_ref_stats st;
    rt_render(s, &p, &img, &sd, &st);
    double rel = st.noise_rmse / st.mean;
    if (reach) {
        CHECK(st.target_reached && rel <= target && st.rounds > 1 && st.spp <= max_spp,
              "%s: target %.3g: reached %d, noise/mean %.4g, %d rounds, %d spp",
              gib_component_name(comp), target, st.target_reached, rel, st.rounds, st.spp);
    } else {
        CHECK(!st.target_reached && st.spp == max_spp && rel > target,
              "%s: unreachable target %.3g: reached %d, %d spp (max %d)",
              gib_component_name(comp), target, st.target_reached, st.spp, max_spp);
    }
    /* the header says why sampling stopped */
    gib_kv kv[GIB_REF_ATTR_COUNT];
    const char *stop = header_stop(s, &p, &st, kv);
    CHECK(!strcmp(stop, reach ? "target" : "max_spp"), "%s: header stop '%s', want %s",
          gib_component_name(comp), stop, reach ? "target" : "max_spp");
    CHECK(same_as_plain(s, comp, &img, &sd, &st),
          "%s: the %d-round run (%d spp) differs from a plain %d spp render",
          gib_component_name(comp), st.rounds, st.spp, st.spp);
    printf("%-8s target %.3g%s: %d rounds, %d spp, noise/mean %.4f, %s; bit-identical to a "
           "plain %d spp render\n",
           gib_component_name(comp), target, reach ? "" : " (max_spp too low)", st.rounds,
           st.spp, rel, st.target_reached ? "reached" : "not reached", st.spp);
    gib_image_free(&img);
    gib_image_free(&sd);
}

/* An interrupt requested before the render starts: the first round completes and is the result
 * (a plain render of its spp, bit for bit), marked interrupted; the renderer counted the round. */
static void test_interrupt(const gib_scene *s)
{
    gib_ref_params p = rt_params(GIB_COMP_FULL, 24, 20, 4);
    p.target_noise = 1e-9;
    p.max_depth = 3;
    gib_ref_interrupt stop;
    atomic_init(&stop.requested, 1);
    atomic_init(&stop.rounds_done, 0);
    p.interrupt = &stop;
    gib_image img, sd;
    gib_ref_stats st;
    rt_render(s, &p, &img, &sd, &st);
    CHECK(st.interrupted && !st.target_reached && st.rounds == 1 && st.spp == 4 &&
              atomic_load(&stop.rounds_done) == 1,
          "interrupt: interrupted %d, reached %d, %d rounds, %d spp, rounds_done %d",
          st.interrupted, st.target_reached, st.rounds, st.spp, atomic_load(&stop.rounds_done));
    gib_kv kv[GIB_REF_ATTR_COUNT];
    const char *why = header_stop(s, &p, &st, kv);
    CHECK(!strcmp(why, "interrupted"), "interrupt: header stop '%s'", why);
    CHECK(same_as_plain(s, GIB_COMP_FULL, &img, &sd, &st),
          "interrupt: the round kept differs from a plain 4 spp render");
    printf("interrupted before round 1 ended: 1 round, 4 spp, bit-identical to a plain render\n");
    gib_image_free(&img);
    gib_image_free(&sd);
}

/* Sets the interrupt as soon as the first round is finished, as a Ctrl-C handler would. */
static void *interrupt_after_round_1(void *arg)
{
    gib_ref_interrupt *stop = arg;
    while (atomic_load(&stop->rounds_done) < 1) {
        struct timespec nap = {0, 100 * 1000};
        nanosleep(&nap, NULL);
    }
    atomic_store(&stop->requested, 1);
    return NULL;
}

/* An interrupt during round 2: the round is abandoned and the result is round 1's, bit for bit
 * (or, when round 2 finished before its threads saw the request, rounds 1 and 2). */
static void test_interrupt_mid_round(const gib_scene *s)
{
    gib_ref_params p = rt_params(GIB_COMP_FULL, 24, 20, 4);
    p.target_noise = 1e-9;
    p.max_spp = 1 << 20;
    p.max_depth = 3;
    gib_ref_interrupt stop;
    atomic_init(&stop.requested, 0);
    atomic_init(&stop.rounds_done, 0);
    p.interrupt = &stop;
    pthread_t th;
    CHECK(pthread_create(&th, NULL, interrupt_after_round_1, &stop) == 0, "pthread_create");
    gib_image img, sd;
    gib_ref_stats st;
    rt_render(s, &p, &img, &sd, &st);
    pthread_join(th, NULL);
    CHECK(st.interrupted && ((st.spp == 4 && st.rounds == 1) || (st.spp == 16 && st.rounds == 2)),
          "interrupt in round 2: interrupted %d, %d rounds, %d spp (want 1 round of 4 or 2 "
          "rounds, 16)", st.interrupted, st.rounds, st.spp);
    CHECK(same_as_plain(s, GIB_COMP_FULL, &img, &sd, &st),
          "interrupt in round 2: the %d spp kept differ from a plain render", st.spp);
    printf("interrupted in round 2: %s, %d spp kept, bit-identical to a plain render\n",
           st.rounds == 1 ? "round 2 abandoned" : "round 2 had finished", st.spp);
    gib_image_free(&img);
    gib_image_free(&sd);
}

int main(void)
{
    gib_scene s;
    rt_scene_mixed(&s);
    test_threads(&s);
    test_target(&s, GIB_COMP_INDIRECT, 0.25, 4096, 1);
    test_target(&s, GIB_COMP_FULL, 0.05, 4096, 1); /* camera and light-traced parts */
    test_target(&s, GIB_COMP_AO, 1e-4, 16, 0);
    test_interrupt(&s);
    test_interrupt_mid_round(&s);
    /* the same scene under a sky: direct is random then, and every estimator samples the sky */
    printf("with a sky:\n");
    rt_sky(&s, 0.3f, 0.35f, 0.4f);
    CHECK(!gib_component_deterministic(&s, GIB_COMP_DIRECT), "direct with a sky is random");
    test_threads(&s);
    test_target(&s, GIB_COMP_DIRECT, 0.02, 4096, 1);
    rt_scene_free(&s);
    return failures ? 1 : 0;
}

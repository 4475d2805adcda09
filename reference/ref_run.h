/* gibench — one component's render in progress (reference.c), shared with the set render
 * (ref_set.c) that drives several at once: its per-pixel statistics, light passes and rounds.
 * Internal to reference/. */
#ifndef GIB_REF_RUN_H
#define GIB_REF_RUN_H

#include "ref_internal.h"

typedef struct ref_run {
    ref_ctx c;
    ref_progress *prog;
    double *cm, *cm2;         /* camera part: per pixel and channel, mean and Welford's M2 */
    double *cb;               /* sobol: per pixel, channel and batch (innermost), the batch's sum */
    double *lm, *lm2;         /* light part */
    int s0, s1;               /* this round's samples */
    /* light passes in flight: passes g0 .. g0+gn-1, chunks per pass, their splats and images */
    int g0, gn, chunks, group;
    ref_splats *splats;       /* gn * chunks */
    double *pass_img;         /* gn * W*H*3 */
    int oom;
    /* Interrupts (gib_ref_interrupt): the statistics as the last finished round left them, so a
     * round in progress can be abandoned at once (its tasks skip their work) and undone. */
    const gib_ref_interrupt *stop;
    double *saved;            /* cm, cm2, lm, lm2 of the last finished round; NULL: none kept */
    int can_abandon;          /* a finished round is saved */
    double pilot_gain;        /* ref_choose_strategies: the pilot's figure, 0 without one */
    atomic_int abandoned;     /* a task of this round skipped its work */
} ref_run;

/* How a render's rounds went, and when it began. */
typedef struct ref_tally {
    int n, rounds, reached, interrupted; /* n: the samples per pixel the image holds */
    double mean, noise;
    double t0;   /* ref_now() at the start */
    uint64_t k0; /* ref_ticks() at the start (with w->time_embree) */
} ref_tally;

/* Sets up r for params p on world w (normalised context, progress counters into prog, the
 * strategies of full and higher chosen, statistics allocated). 0, or -1 with err (free r with
 * ref_run_free either way). */
int ref_run_setup(ref_run *r, const ref_world *w, const gib_scene *scene, const gib_ref_params *p,
                  ref_progress *prog, double t0, int nthreads, gib_error *err);
void ref_run_free(ref_run *r);
/* The samples r->s0 .. r->s1 - 1 of pixel pix at its visible point h, accumulated in sample
 * order into r's statistics. */
void ref_pixel_samples(ref_run *r, size_t pix, const ref_hit *h, const float wo[3],
                       long long *rays);
/* Sample s's value v of pixel pix into r's statistics (samples in order). */
void ref_pixel_add(ref_run *r, size_t pix, int s, const float v[3]);
/* The primary ray of pixel (x, y) and its footprint (ref_pixel_hit without the component's own
 * part): 0 on a miss. Differentials and albedo are skipped on a back face unless keep_back. */
int ref_primary_hit(const ref_ctx *c, int x, int y, int keep_back, ref_hit *h, float wo[3],
                    long long *rays);
/* The component's own part of a visible point from ref_primary_hit: 0 when it samples nothing
 * there (the back of a one-sided surface for a shaded component); full's next-event estimation
 * at x1. */
int ref_pixel_ready(const ref_ctx *c, ref_hit *h, const float wo[3], long long *rays);
/* This round's light passes (r->s0 .. r->s1 - 1); -1 when out of memory for splats. */
int ref_light_round(ref_run *r, int nthreads);
/* After a round that took the image to `goal` samples: its summary into t, the progress line,
 * and the next round's goal in *goal. Returns 1 when the render is done (no target, the target
 * reached, or max_spp), else 0. */
int ref_round_end(ref_run *r, ref_tally *t, int *goal);
/* The image (camera and light parts summed) and, when asked, each pixel's standard error. */
void ref_write_images(const ref_run *r, int n, gib_image *out, gib_image *stderr_img);
void ref_fill_stats(gib_ref_stats *stats, const ref_run *r, const gib_scene *scene,
                    const gib_ref_params *p, const ref_tally *t);
int ref_thread_count(const gib_ref_params *p);

#endif

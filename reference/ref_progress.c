/* gibench — the reference renderer's thread pool and progress report.
 *
 * Progress: on a terminal, one line redrawn four times a second (samples per pixel done, rays per
 * second, estimated time left, the noise of the last round against the target); elsewhere (a log
 * file, ctest, the matrix runner's captured stderr) plain lines, one per finished round of a
 * render that took over a second and one every 30 s during long rounds. */
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

#include "ref_internal.h"

double ref_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct ref_pool {
    ref_task_fn fn;
    void *ctx;
    int ntasks;
    atomic_int next;
    atomic_int done;
} ref_pool;

static void *ref_pool_worker(void *arg)
{
    ref_pool *pl = arg;
#if defined(__x86_64__) || defined(__i386__)
    /* Flush denormals to zero, as Embree recommends for speed; every worker sets the same mode,
     * so results stay independent of the thread count. */
    unsigned csr = _mm_getcsr();
    _mm_setcsr(csr | 0x8040);
#endif
    for (;;) {
        int t = atomic_fetch_add(&pl->next, 1);
        if (t >= pl->ntasks)
            break;
        pl->fn(pl->ctx, t);
        atomic_fetch_add(&pl->done, 1);
    }
#if defined(__x86_64__) || defined(__i386__)
    _mm_setcsr(csr); /* the caller's thread may run this too: give its FP mode back */
#endif
    return NULL;
}

void ref_parallel(int nthreads, int ntasks, ref_task_fn fn, void *ctx, ref_progress *prog)
{
    if (ntasks <= 0)
        return;
    ref_pool pl = {.fn = fn, .ctx = ctx, .ntasks = ntasks};
    atomic_init(&pl.next, 0);
    atomic_init(&pl.done, 0);
    pthread_t tid[256];
    int want = nthreads < ntasks ? nthreads : ntasks, started = 0;
    if (want > 256)
        want = 256;
    for (int i = 0; i < want; i++) {
        if (pthread_create(&tid[i], NULL, ref_pool_worker, &pl) != 0)
            break; /* fewer threads is slower, not wrong */
        started++;
    }
    if (prog && (started > 0 ? started : 1) > prog->threads_used)
        prog->threads_used = started > 0 ? started : 1;
    if (started == 0) {
        ref_pool_worker(&pl);
    } else if (prog && prog->enabled) {
        while (atomic_load(&pl.done) < ntasks) {
            struct timespec nap = {0, 20 * 1000 * 1000};
            nanosleep(&nap, NULL);
            ref_progress_tick(prog, 0);
        }
    }
    for (int i = 0; i < started; i++)
        pthread_join(tid[i], NULL);
}

static void ref_progress_print(ref_progress *p, double now, int final)
{
    long long units = atomic_load(&p->units), rays = atomic_load(&p->rays);
    double el = now - p->t0;
    double spp = p->units_per_spp > 0 ? (double)units / (double)p->units_per_spp : 0.0;
    char left[48] = "?", noise[64] = "";
    if (units > 0 && p->units_target > units && !final)
        snprintf(left, sizeof left, "%.0f s left%s",
                 el * (double)(p->units_target - units) / (double)units,
                 p->target > 0.0 ? " in this round" : "");
    else if (final || units >= p->units_target)
        snprintf(left, sizeof left, "%.1f s", el);
    if (p->noise_rel >= 0.0)
        snprintf(noise, sizeof noise, ", noise %.3g%% of mean", 100.0 * p->noise_rel);
    if (p->noise_rel >= 0.0 && p->target > 0.0)
        snprintf(noise + strlen(noise), sizeof noise - strlen(noise), " (target %.3g%%)",
                 100.0 * p->target);
    fprintf(stderr, "%sreference %s: %.1f/%d spp (round %d), %.2f Mrays/s, %s%s%s",
            p->tty ? "\r" : "", p->what, spp, p->spp_goal, p->round,
            el > 0.0 ? (double)rays / el * 1e-6 : 0.0, left, noise, p->tty ? "   " : "\n");
    fflush(stderr);
    p->printed = 1;
}

void ref_progress_tick(ref_progress *p, int force)
{
    if (!p || !p->enabled)
        return;
    double now = ref_now();
    if (p->tty) {
        /* the first line after 0.25 s: short renders stay silent */
        if (force || (now - p->t0 >= 0.25 && now - p->last_print >= 0.25)) {
            ref_progress_print(p, now, 0);
            p->last_print = now;
        }
    } else if (force || now - (p->last_print > 0.0 ? p->last_print : p->t0) >= 30.0) {
        ref_progress_print(p, now, 0);
        p->last_print = now;
    }
}

void ref_progress_round(ref_progress *p, int spp_done, double noise_rel)
{
    if (!p || !p->enabled)
        return;
    p->noise_rel = noise_rel;
    p->spp_goal = spp_done;
    double now = ref_now();
    if (p->tty ? p->printed : (now - p->t0 >= 1.0 || p->target > 0.0)) {
        ref_progress_print(p, now, 1);
        p->last_print = now;
    }
}

void ref_progress_end(ref_progress *p)
{
    if (p && p->enabled && p->tty && p->printed) /* leave the line for the caller's log line */
        fprintf(stderr, "\n");
}

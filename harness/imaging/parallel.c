/* gibench — the scoring threads (parallel.h). A team's workers sleep on a condition variable
 * between runs; each run hands its items out through an atomic counter, the caller working too. */
#include "parallel.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#define MAX_THREADS 1024

static atomic_int threads_set; /* 0: not set */

void gib_score_threads_set(int threads)
{
    atomic_store(&threads_set, threads > 0 ? (threads < MAX_THREADS ? threads : MAX_THREADS) : 0);
}

/* GIBENCH_SCORE_THREADS when it holds a count in range, else 0 (a bad value is reported once). */
static int threads_from_env(void)
{
    static atomic_int warned;
    const char *v = getenv("GIBENCH_SCORE_THREADS");
    if (!v || !*v)
        return 0;
    char *end;
    long n = strtol(v, &end, 10);
    if (*end == '\0' && n >= 1 && n <= MAX_THREADS)
        return (int)n;
    if (!atomic_exchange(&warned, 1))
        fprintf(stderr, "gibench: GIBENCH_SCORE_THREADS='%s' is not a count from 1 to %d: "
                        "scoring on every core\n", v, MAX_THREADS);
    return 0;
}

int gib_score_threads(void)
{
    int n = atomic_load(&threads_set);
    if (n > 0)
        return n;
    n = threads_from_env();
    if (n > 0)
        return n;
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    return cores < 1 ? 1 : cores > MAX_THREADS ? MAX_THREADS : (int)cores;
}

struct gib_team {
    pthread_mutex_t mu;
    pthread_cond_t go, done;
    unsigned long generation; /* one per run; a worker runs each generation once */
    int quit, busy;           /* busy: workers still in the current run */
    int n;                    /* the current run's items */
    atomic_int next;
    gib_item_fn fn;
    void *ctx;
    int workers; /* started, the caller not counted */
    pthread_t thread[];
};

/* Takes items until none is left. */
static void take_items(gib_team *t)
{
    for (int i = atomic_fetch_add(&t->next, 1); i < t->n; i = atomic_fetch_add(&t->next, 1))
        t->fn(t->ctx, i);
}

static void *worker(void *arg)
{
    gib_team *t = arg;
    unsigned long seen = 0;
    pthread_mutex_lock(&t->mu);
    for (;;) {
        while (t->generation == seen && !t->quit)
            pthread_cond_wait(&t->go, &t->mu);
        if (t->quit)
            break;
        seen = t->generation;
        pthread_mutex_unlock(&t->mu);
        take_items(t);
        pthread_mutex_lock(&t->mu);
        if (--t->busy == 0)
            pthread_cond_signal(&t->done);
    }
    pthread_mutex_unlock(&t->mu);
    return NULL;
}

gib_team *gib_team_start(int threads)
{
    if (threads <= 0)
        threads = gib_score_threads();
    if (threads > MAX_THREADS)
        threads = MAX_THREADS;
    if (threads < 2)
        return NULL;
    gib_team *t = calloc(1, sizeof *t + (size_t)(threads - 1) * sizeof(pthread_t));
    if (!t)
        return NULL;
    pthread_mutex_init(&t->mu, NULL);
    pthread_cond_init(&t->go, NULL);
    pthread_cond_init(&t->done, NULL);
    /* Fewer workers than asked when the system refuses more: the items still all run. */
    while (t->workers < threads - 1 &&
           pthread_create(&t->thread[t->workers], NULL, worker, t) == 0)
        t->workers++;
    if (t->workers == 0) {
        gib_team_stop(t);
        return NULL;
    }
    return t;
}

void gib_team_run(gib_team *t, int n, gib_item_fn fn, void *ctx)
{
    if (!t || n < 2) {
        for (int i = 0; i < n; i++)
            fn(ctx, i);
        return;
    }
    pthread_mutex_lock(&t->mu);
    t->fn = fn;
    t->ctx = ctx;
    t->n = n;
    atomic_store(&t->next, 0);
    t->busy = t->workers;
    t->generation++;
    pthread_cond_broadcast(&t->go);
    pthread_mutex_unlock(&t->mu);
    take_items(t);
    pthread_mutex_lock(&t->mu);
    while (t->busy > 0)
        pthread_cond_wait(&t->done, &t->mu);
    pthread_mutex_unlock(&t->mu);
}

int gib_team_size(const gib_team *t)
{
    return t ? t->workers + 1 : 1;
}

void gib_team_stop(gib_team *t)
{
    if (!t)
        return;
    pthread_mutex_lock(&t->mu);
    t->quit = 1;
    pthread_cond_broadcast(&t->go);
    pthread_mutex_unlock(&t->mu);
    for (int i = 0; i < t->workers; i++)
        pthread_join(t->thread[i], NULL);
    pthread_cond_destroy(&t->go);
    pthread_cond_destroy(&t->done);
    pthread_mutex_destroy(&t->mu);
    free(t);
}

void gib_parallel(int threads, int n, gib_item_fn fn, void *ctx)
{
    if (threads <= 0)
        threads = gib_score_threads();
    gib_team *t = n > 1 ? gib_team_start(threads < n ? threads : n) : NULL;
    gib_team_run(t, n, fn, ctx);
    gib_team_stop(t);
}

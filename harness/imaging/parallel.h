/* gibench — the scoring threads: a team of threads that runs numbered items of work, for the image
 * metrics (SSIM, FLIP) and the images a row writes.
 *
 * Items are handed out one at a time in any order, so an item must write only its own outputs;
 * sums are reduced by the caller afterwards in item order, which makes every result independent of
 * the thread count (tests/imaging/test_score_threads.c checks 1, 2, 3 and 7 threads bit for bit). */
#ifndef GIB_PARALLEL_H
#define GIB_PARALLEL_H

/* How many threads scoring uses: gib_score_threads_set's value when one was set, else the
 * environment's GIBENCH_SCORE_THREADS (1 to 1024), else the online cores. */
int gib_score_threads(void);

/* Sets the thread count scoring uses from now on (0: back to the environment and the cores).
 * Not for use while scoring runs. */
void gib_score_threads_set(int threads);

typedef struct gib_team gib_team;
typedef void (*gib_item_fn)(void *ctx, int item);

/* A team of up to `threads` threads, the caller one of them (threads <= 0: gib_score_threads()).
 * NULL when only one thread is asked for or none could be started: gib_team_run then runs the
 * items on the caller's thread. */
gib_team *gib_team_start(int threads);

/* fn(ctx, i) for every i in [0, n), returning when all are done. Not reentrant: an item must not
 * run the team it runs on. */
void gib_team_run(gib_team *team, int n, gib_item_fn fn, void *ctx);

/* The team's thread count (1 for NULL). */
int gib_team_size(const gib_team *team);

void gib_team_stop(gib_team *team);

/* A team started, the items run and the team stopped: for a single parallel step. */
void gib_parallel(int threads, int n, gib_item_fn fn, void *ctx);

#endif

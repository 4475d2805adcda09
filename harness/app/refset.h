/* gibench — the references a matrix's runs ask for, and a view's rendered together
 * (harness/app/refset.c). */
#ifndef GIB_REFSET_H
#define GIB_REFSET_H

#include "app.h"
#include "matrix.h"

/* 1 when technique t can run on scene s (the features it needs); else 0, and why in why (NULL:
 * not wanted). */
int gib_scene_wanted(const gib_scene *s, const gib_technique *t, char *why, size_t len);

/* The reference request of output `bit` (a GIB_OUT_* bit) of run mr at the matrix's spp, what its
 * scoring asks first (a reference too noisy to rank the row is asked again deeper, refrank.h).
 * Returns the reference component, -1 when there is no estimator for it. */
int gib_matrix_ref_request(const gib_matrix *m, const char *cache, const gib_scene *scene,
                           const gib_matrix_run *mr, unsigned bit, gib_ref_request *rq);

/* The distinct requests (one per cache key) of the runs j of scene `scene` with want[j] set
 * (want NULL: every run of the scene named scene->name), every output each run scores; at most
 * max into out. Returns the count. */
int gib_matrix_ref_requests(const gib_matrix *m, const char *cache, const gib_scene *scene,
                            const char *want, gib_ref_request *out, int max);

/* Worlds: requests are grouped by the scene they render and its instant (a moving scene's time;
 * a static scene has one), what one world serves; world[i] gets request i's group, groups
 * numbered from 0 in order of first appearance. Returns the group count. */
int gib_ref_worlds(const gib_ref_request *rq, int n, int *world);

/* fn(ctx, set, k) for each world g < groups in turn: its requests (world[i] == g; a request of
 * world < 0 is left out) in order, in sets of at most GIB_REF_SET_MAX requests and 1 GiB of
 * their statistics. Stops at the first nonzero return, which it returns; else 0. */
typedef int (*gib_ref_set_fn)(void *ctx, const gib_ref_request *set, int k);
int gib_ref_each_set(const gib_ref_request *rq, int n, const int *world, int groups,
                     gib_ref_set_fn fn, void *ctx);

/* Renders what the cache lacks of the requests, each world's together (gib_reference_get_set, at
 * most GIB_REF_SET_MAX a set; a key asked twice once), each stored as its own entry under the key
 * its request alone has and with the pixels its render alone gives; a later gib_reference_get
 * finds it. A world with one request is left to it. 0, or -1 / GIB_REF_WRITE_FAILED with err. */
int gib_reference_prefetch(const gib_ref_request *rq, int n, gib_error *err);

/* gibench bench references (harness/app/bench_refset.c): argv[0] is "references". */
int gib_bench_references(int argc, char **argv);

#endif

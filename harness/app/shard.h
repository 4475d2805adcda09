/* gibench — matrices split into shards (`gibench run M --shard i/N`) and the manifests that let
 * `gibench merge` put the shards' CSVs back together (docs/scale-out.md).
 *
 * The split depends only on the expanded matrix (never on the machine or on which scenes are
 * present), so every shard computes the same assignment on its own. A shard writes, beside its
 * DIR/<matrix>.csv, the manifest DIR/<matrix>.shard (written to a temporary name and renamed when
 * the shard's runs are done, so a shard that did not finish has none):
 *
 *   gibench-shard 1
 *   matrix NAME          profile P          revision R          fingerprint HEX (the expansion)
 *   shard I/N            runs TOTAL
 *   run J ORDINAL STATE  one per run of this shard: J its index in the expansion, ORDINAL its place
 *                        in the order an unsharded run executes, STATE expect | skipped | failed
 *   row KEY              the CSV identity key of each row the run writes (after its `run` line)
 *
 * Fields are separated by one tab (keys hold spaces in no field today, but parameters may). */
#ifndef GIB_SHARD_H
#define GIB_SHARD_H

#include <stdint.h>

#include "harness/base/error.h"
#include "matrix.h"

typedef struct gib_shard {
    int index, count; /* 1 <= index <= count; count 0 = the whole matrix */
} gib_shard;

#define GIB_SHARD_MAX 4096

/* "I/N" with 1 <= I <= N <= GIB_SHARD_MAX; errors name the option. */
int gib_shard_parse(const char *opt, const char *s, gib_shard *out, gib_error *err);

/* owner[j] in 1..count for every run j of m: a deterministic, balanced split (shard.c says how). */
void gib_shard_assign(const gib_matrix *m, int count, int *owner);

/* ordinal[j]: run j's place in the order an unsharded `gibench run` executes the runs (scene by
 * scene in order of first appearance, runs in matrix order within a scene). */
void gib_shard_order(const gib_matrix *m, int *ordinal);

/* A hash of everything that decides the matrix's rows: profile, camera, frames, warmup, dt,
 * reference samples, and every run's scene, technique, parameters, size and instant. */
uint64_t gib_matrix_fingerprint(const gib_matrix *m);

#endif

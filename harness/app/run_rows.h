/* gibench run — what the matrix driver (cmd_run.c) and the scoring of a run (run_score.c) share: a
 * results row being filled, the run's context, a row's identity and its append (run_rows.c), and
 * the scoring cmd_run.c calls (run_score.c). cmd_run.c -> run_score.c -> run_rows.c: no cycle.
 * Internal to `gibench run`. */
#ifndef GIB_RUN_ROWS_H
#define GIB_RUN_ROWS_H

#include "app.h"
#include "csv.h"
#include "history.h"
#include "matrix.h"
#include "progress.h"
#include "runner.h"
#include "schema.h"
#include "shard.h"
#include "scenes/scene.h"

/* A row of either table, its cells by column index (harness/app/schema.h). */
typedef struct gib_row {
    char v[GIB_TABLE_MAX_COLS][512]; /* a cell: params, the longest, is up to 511 characters */
    const char *ptr[GIB_TABLE_MAX_COLS];
} gib_row;

void gib_row_set(gib_row *r, int col, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* A runs row's identity key: its GIB_KEY_ROW columns joined by '|' (as gib_csv keys rows). */
void gib_row_key(const gib_row *r, char *key, size_t len);
/* A number as the tables write it: %.9g, nan, inf, -inf. */
void gib_row_num(gib_row *r, int col, double v);

typedef struct gib_run_ctx {
    const gib_matrix *m;
    const gib_table_layout *cols;
    gib_csv *csv, *passes;
    const char *out, *cache;
    int images;
    int timing_only; /* --timing-only: no references, scores or images; NaN/Inf still checked */
    gib_gl_info info;
    gib_history *hist;     /* NULL: --no-history, or recording failed (reported once) */
    const gib_history_machine *machine;
    long long hist_run;    /* the history's run of this matrix; 0 until its first gib_row */
    int hist_failed;
    int rows_written, rows_failed, rows_out_of_memory, runs_skipped;
    int write_failed; /* a table could not be written (a full disk): the run stops there */
    gib_shard shard;
    const gib_matrix *later; /* the run's matrices after this one (nlater): their references of a
                              * scene are rendered with this one's (cmd_run.c) */
    int nlater;
    const int *owner; /* with --shard: each run's shard (shard.h) */
    char *state;      /* with --shard: 'e' rows expected, 's' skipped, 'f' failed; 0 not ours */
    gib_progress progress;
} gib_run_ctx;

/* A table could not be written (a full disk): the run stops there. */
void gib_run_write_failed(gib_run_ctx *ctx, const gib_error *err);
/* The identity part of a row (the run, its settings and the machine). */
void gib_run_row_identity(gib_row *r, const gib_run_ctx *ctx, const gib_matrix_run *mr,
                          unsigned comp);
/* Appends a finished row to the table (and the history). */
void gib_run_append_row(gib_run_ctx *ctx, gib_row *r);
/* run_score.c: a run's passes, then a row per output component, each scored against its
 * reference (a sequence's frames and temporal error too). */
void gib_run_score(gib_run_ctx *ctx, const gib_scene *scene, const gib_gpu_scene *gpu,
                   const gib_matrix_run *mr, gib_run_result *res);

#endif

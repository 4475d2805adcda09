/* gibench — results history: every `gibench run` row kept in a SQLite database across runs
 * (docs/history.md).
 *
 * Schema (one file, default DIR/history.sqlite beside the CSVs):
 *   machine(id, renderer, gl_version, backend, cpu, cores, gpu)   one row per distinct machine
 *   run(id, machine_id, revision, started, matrix, profile, host)  one row per matrix per run
 *   result(id, run_id, matrix, profile, scene, camera, technique, component, params, width,
 *          height, time, gpu_ms_median, cpu_ms, mem_bytes, rmse, rel_rmse, ssim, ref_noise_rmse,
 *          status, revision, timestamp, row_json)
 * row_json holds the whole CSV row (numbers as JSON numbers), so a column added later (flip, ...)
 * is kept and queried (json_extract) without a schema change; the typed columns are the ones the
 * queries filter on. Writers serialise on SQLite's own lock: each batch is one BEGIN IMMEDIATE
 * transaction, and a busy database is waited for (busy_timeout), so concurrent runs or shards
 * writing one file lose no row. */
#ifndef GIB_HISTORY_H
#define GIB_HISTORY_H

#include <stdio.h>

#include "harness/base/error.h"

typedef struct gib_history gib_history;

typedef struct gib_history_machine {
    char renderer[256], gl_version[256], backend[32];
    char cpu[256];  /* /proc/cpuinfo "model name" ("unknown" where absent) */
    int cores;      /* online processors */
    char gpu[256];  /* GL_RENDERER when it is a GPU; empty for software rasterisers (llvmpipe) */
} gib_history_machine;

/* The machine this process runs on, given the GL context's renderer, version and backend. */
void gib_history_machine_detect(gib_history_machine *m, const char *renderer,
                                const char *gl_version, const char *backend);

/* Opens (creating it and its tables when absent) the history at path. */
int gib_history_open(gib_history **h, const char *path, gib_error *err);
/* Opens an existing history read-only, for queries: a copy without write permission, or one
 * another process is writing, is read as it is. */
int gib_history_open_readonly(gib_history **h, const char *path, gib_error *err);
void gib_history_close(gib_history *h);

/* Records a run (one matrix of one `gibench run`) and returns its id. */
int gib_history_begin_run(gib_history *h, const gib_history_machine *m, const char *revision,
                          const char *matrix, const char *profile, long long *run_id,
                          gib_error *err);

/* Writer batches: rows added between begin and commit land together or not at all. */
int gib_history_begin(gib_history *h, gib_error *err);
int gib_history_commit(gib_history *h, gib_error *err);
/* Adds one CSV row: n column names and values (NULL or "" = empty, left out of row_json). */
int gib_history_add_row(gib_history *h, long long run_id, const char *const *names,
                        const char *const *values, int n, gib_error *err);

/* Prints the machine table (id, renderer, GL version, backend, CPU, cores, GPU, runs). */
int gib_history_print_machines(gib_history *h, FILE *f, gib_error *err);

/* --- queries --- */
typedef struct gib_history_filter {
    const char *matrix, *scene, *technique, *component, *params; /* NULL: any */
    const char *renderer; /* substring of the machine's renderer; NULL: any */
    int width, height;    /* 0: any */
    long long machine;    /* 0: any */
} gib_history_filter;

typedef struct gib_history_point {
    char revision[64];
    char started[32];  /* the first run of this revision in the series (UTC, ISO 8601) */
    double value;      /* median over the revision's ok rows */
    int rows;
} gib_history_point;

/* One (matrix, scene, camera, technique, component, params, size, instant) row on one machine,
 * its metric by revision in the order the revisions were first run. */
typedef struct gib_history_series {
    char matrix[128], scene[128], technique[64], component[32], params[1024];
    int camera, width, height;
    double time;
    long long machine;
    char renderer[256];
    gib_history_point *points;
    int count;
} gib_history_series;

/* The series of every row the filter matches, for metric (a column name: rmse, ssim,
 * gpu_ms_median, flip, ...; read from row_json, so any numeric column). Only rows with status ok
 * and a finite value count. */
int gib_history_query(gib_history *h, const gib_history_filter *f, const char *metric,
                      gib_history_series **out, int *count, gib_error *err);
void gib_history_series_free(gib_history_series *s, int count);

/* Whether a larger value of metric is better (ssim, psnr) or worse (errors, times, memory). */
int gib_history_higher_is_better(const char *metric);

/* The first point whose value is worse than the best of the points before it by more than
 * rel_tol of that best plus abs_tol (the noise allowed); -1 when none is. */
int gib_history_find_worse(const gib_history_series *s, int higher_is_better, double rel_tol,
                           double abs_tol);

/* The GL_RENDERER substrings that name a software rasteriser (Mesa's), NULL-terminated: such a
 * renderer names no GPU (gib_machine.gpu stays empty). `gibench schema` exports the list. */
extern const char *const gib_software_renderers[];
/* Whether GL_RENDERER `renderer` is a software rasteriser (one of gib_software_renderers in it). */
int gib_is_software_renderer(const char *renderer);

#endif

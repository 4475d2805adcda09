/* gibench — where a matrix run is: runs done of the total, time elapsed and an estimate of the time
 * left, as `[k/N]` on the log lines and, when stderr is a terminal, as a live line under them.
 *
 * The estimate weights each run by its work: its pixels times its frames (the cold one and the
 * warm-up included), plus, for each reference it is the first to need (scene, size, instant,
 * component), its pixels times the reference's samples per pixel over REF_SAMPLES_PER_FRAME (one
 * traced sample per pixel costs about a fifth of a rasterised frame's pixel on llvmpipe: a rough
 * prior, and a cached reference costs nothing, so the estimate says "about"). Time left = elapsed
 * x (work left / work done). */
#ifndef GIB_PROGRESS_H
#define GIB_PROGRESS_H

#include "harness/app/matrix.h"

typedef struct gib_progress {
    int runs_total, runs_done;
    double work_total, work_done;
    double start_ms;
    int live;          /* stderr is a terminal: keep a live line */
    int line_shown;    /* a live line is on the terminal now */
    double *run_work;  /* per run of the matrix; 0 for runs not to do */
} gib_progress;

/* The runs to do are those todo[j] != 0 marks. Returns -1 only when out of memory. */
int gib_progress_start(gib_progress *p, const gib_matrix *m, const char *todo);
/* Run j finished (whatever its status). */
void gib_progress_run_done(gib_progress *p, int j);
/* "[k/N]" of the run being done now (k = runs done + 1), for log lines. */
void gib_progress_tag(const gib_progress *p, char *out, size_t len);
/* Clears the live line before other output goes to the terminal (no-op without one). */
void gib_progress_clear(gib_progress *p);
/* Prints the progress: the live line on a terminal, else a log line on stdout. */
void gib_progress_report(gib_progress *p);
void gib_progress_free(gib_progress *p);
/* "1h02m", "3m05s", "12s". */
void gib_format_duration(double seconds, char *out, size_t len);

#endif

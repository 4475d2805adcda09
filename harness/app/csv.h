/* gibench — tidy CSV results (ARCHITECTURE.md, "Matrices, CSV and reproduction").
 *
 * One row per (run, output component), appended and flushed as each run finishes, so an
 * interrupted matrix keeps what it did; a rerun skips runs whose rows are all present. The
 * columns and the identity key are the caller's (for gibench run: harness/app/schema.h, the base
 * columns plus the parameters the matrix names). A second file holds per-pass timings. */
#ifndef GIB_CSV_H
#define GIB_CSV_H

#include <stdio.h>

#include "harness/base/error.h"

typedef struct gib_csv {
    FILE *f;
    char path[1024];
    int ncols;
    char **keys;      /* identity keys of rows already present (for resume) */
    int nkeys;
    int key_cols[16]; /* the columns that make a row's identity key (none: every row is new) */
    int nkey;
    int lock_fd;      /* PATH.lock, flock'ed while the table is open */
    int moved_aside;  /* the file had other columns and went to PATH.old: its rows are gone */
} gib_csv;

/* Opens for appending. An existing file with the same header is kept (its rows' identity keys are
 * loaded, and an unfinished last line, left by a process killed mid-write, is cut off); one with a
 * different header is moved aside to PATH.old and a fresh file started (moved_aside). */
int gib_csv_open(gib_csv *c, const char *path, const char *const *columns, int ncols,
                 const int *key_columns, int nkey_columns, gib_error *err);
/* Moves PATH aside to PATH.old (replacing an older one); nothing to do when PATH is absent. */
int gib_csv_move_aside(const char *path, gib_error *err);
/* Appends one row (ncols values, NULL = empty), quoted as RFC 4180 needs, and flushes it in one
 * write. A row whose identity key the file already holds is not written again (a run redone after
 * an interruption re-appends only what is missing): every row is in the file exactly once.
 * Returns 1 when written, 0 when the row was there already, -1 on a write error. */
int gib_csv_append(gib_csv *c, const char *const *values, gib_error *err);
/* Whether a row with this identity key (key columns joined by '|') is present. */
int gib_csv_has(const gib_csv *c, const char *key);
void gib_csv_close(gib_csv *c);

#endif

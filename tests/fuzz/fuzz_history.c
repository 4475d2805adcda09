/* Fuzz target: the results history's inputs (harness/app/history.c, cmd_history.c). The input has
 * three parts separated by "####\n":
 *   1. a CSV row as `gibench run` records it: a line of column names and a line of values, both
 *      tab-separated (any byte but tab, newline and NUL: quotes, backslashes, control characters,
 *      invalid UTF-8, nan, huge numbers);
 *   2. SQL run on the history file afterwards: an edited, damaged or foreign history (NULLs where
 *      the schema says NOT NULL, text where numbers belong, tables dropped or redefined), which a
 *      later `gibench run` then records into;
 *   3. `gibench history` options, one a line (--db is this file; --plot is not run: gnuplot).
 * Each input starts from a fresh history. Checked beyond "no crash": every recorded row's
 * row_json is valid JSON that gives back each value exactly (a number as the same number, text as
 * the same bytes), so the JSON the history stores never garbles a row. */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <sqlite3.h>

#include "harness/app/app.h"
#include "harness/app/history.h"
#include "tests/fuzz/fuzz_common.h"

#define MAX_COLS 64

static char db_path[512];

/* Splits [p, end) at tabs into at most MAX_COLS NUL-terminated copies in buf. */
static int split_tabs(const char *p, const char *end, char *buf, char **field)
{
    int n = 0;
    field[n++] = buf;
    for (; p < end; p++) {
        if (*p == '\t') {
            *buf++ = 0;
            if (n == MAX_COLS)
                break;
            field[n++] = buf;
        } else if (*p) {
            *buf++ = *p;
        }
    }
    *buf = 0;
    return n;
}

/* The edits run with the limits of an untrusted script: no other files, no pragmas, bounded; and
 * data only: no views or triggers, which are code that gibench's own statements would run (a
 * recursive view makes any reader loop; that is the file's doing, not a bug of ours). */
static int deny_outside(void *u, int action, const char *a, const char *b, const char *c,
                        const char *d)
{
    (void)u, (void)a, (void)b, (void)c, (void)d;
    switch (action) {
    case SQLITE_ATTACH: case SQLITE_DETACH: case SQLITE_PRAGMA:
    case SQLITE_CREATE_VIEW: case SQLITE_CREATE_TEMP_VIEW:
    case SQLITE_CREATE_TRIGGER: case SQLITE_CREATE_TEMP_TRIGGER:
        return SQLITE_DENY;
    default:
        return SQLITE_OK;
    }
}

static int stop_long(void *u)
{
    return ++*(int *)u > 2000; /* 2000 x 1000 VM steps */
}

static int same_number(const char *text, double stored)
{
    double want = strtod(text, NULL);
    if (!isfinite(want)) /* "1e999": JSON holds it, SQLite reads it as infinity */
        return !isfinite(stored) || fabs(stored) > 1.7e308;
    return stored == want || fabs(stored - want) <= 1e-15 * fabs(want);
}

/* Every value of the row the history stored comes back from row_json as written. */
static void check_row_json(sqlite3 *db, char **names, char **values, int n)
{
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(db, "SELECT json_valid(row_json), row_json FROM result ORDER BY id DESC"
                               " LIMIT 1", -1, &st, NULL) != SQLITE_OK)
        abort();
    if (sqlite3_step(st) != SQLITE_ROW || sqlite3_column_int(st, 0) != 1) {
        fprintf(stderr, "fuzz_history: row_json is not valid JSON: %s\n",
                (const char *)sqlite3_column_text(st, 1));
        abort();
    }
    sqlite3_finalize(st);
    for (int i = 0; i < n; i++) {
        if (!values[i][0])
            continue; /* empty values are left out */
        int dup = 0;
        for (int k = 0; k < n; k++)
            dup |= k != i && values[k][0] && !strcmp(names[k], names[i]);
        if (dup)
            continue; /* a repeated column name: JSON keeps both; which one is not ours to say */
        if (sqlite3_prepare_v2(db, "SELECT j.type, j.atom FROM result r, json_each(r.row_json) j"
                                   " WHERE r.id = (SELECT max(id) FROM result) AND j.key = ?1",
                               -1, &st, NULL) != SQLITE_OK)
            abort();
        sqlite3_bind_text(st, 1, names[i], -1, SQLITE_STATIC);
        int ok = sqlite3_step(st) == SQLITE_ROW;
        const char *type = ok ? (const char *)sqlite3_column_text(st, 0) : "missing";
        if (ok && (!strcmp(type, "integer") || !strcmp(type, "real")))
            ok = same_number(values[i], sqlite3_column_double(st, 1));
        else if (ok && !strcmp(type, "text"))
            ok = sqlite3_column_bytes(st, 1) == (int)strlen(values[i]) &&
                 !memcmp(sqlite3_column_text(st, 1), values[i], strlen(values[i]));
        else
            ok = 0;
        if (!ok) {
            fprintf(stderr, "fuzz_history: column '%s' = '%s' comes back from row_json as %s\n",
                    names[i], values[i], type);
            abort();
        }
        sqlite3_finalize(st);
    }
}

static void remove_db(void)
{
    unlink(db_path);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!db_path[0]) {
        const char *tmp = getenv("TMPDIR");
        snprintf(db_path, sizeof db_path, "%s/gibench-fuzz-history-%ld.sqlite",
                 tmp && *tmp ? tmp : "/tmp", (long)getpid());
        atexit(remove_db);
    }
    const char *p = (const char *)data, *end = p + size;
    size_t len;
    const char *row = fuzz_next_part(&p, end, &len), *row_end = row + len;
    const char *nl = memchr(row, '\n', len);
    const char *sql = fuzz_next_part(&p, end, &len);
    char *script = strndup(sql, len);
    const char *opts = fuzz_next_part(&p, end, &len), *opts_end = opts + len;

    unlink(db_path);
    gib_history *h;
    gib_error err;
    if (gib_history_open(&h, db_path, &err) < 0)
        abort(); /* a fresh file in $TMPDIR must open */
    gib_history_machine m = {.renderer = "llvmpipe (fuzz)", .gl_version = "4.5", .backend = "egl",
                             .cpu = "fuzz", .cores = 2};
    long long run_id;
    if (gib_history_begin_run(h, &m, "0123abcd", "fuzz", "quick", &run_id, &err) < 0)
        abort();
    static char nbuf[1 << 16], vbuf[1 << 16];
    char *names[MAX_COLS], *values[MAX_COLS];
    int nn = split_tabs(row, nl ? nl : row_end, nbuf, names);
    int nv = nl ? split_tabs(nl + 1, row_end, vbuf, values) : 0;
    int n = nn < nv ? nn : nv;
    if (n && gib_history_begin(h, &err) == 0) {
        if (gib_history_add_row(h, run_id, (const char *const *)names,
                                (const char *const *)values, n, &err) < 0)
            abort(); /* any text is a value the history must take */
        gib_history_commit(h, &err);
    }
    gib_history_close(h);

    sqlite3 *db;
    if (sqlite3_open_v2(db_path, &db, SQLITE_OPEN_READWRITE, NULL) != SQLITE_OK)
        abort();
    if (n)
        check_row_json(db, names, values, n);
    int steps = 0;
    sqlite3_set_authorizer(db, deny_outside, NULL);
    sqlite3_progress_handler(db, 1000, stop_long, &steps);
    sqlite3_limit(db, SQLITE_LIMIT_LENGTH, 1 << 20);
    if (script[0])
        sqlite3_exec(db, script, NULL, NULL, NULL);
    sqlite3_close(db);
    free(script);

    /* A later `gibench run` recording into the edited file: any step may refuse with a message
     * (the run then goes on without its history); none may crash. */
    if (gib_history_open(&h, db_path, &err) == 0) {
        if (gib_history_begin_run(h, &m, "4567cdef", "fuzz", "quick", &run_id, &err) == 0 && n &&
            gib_history_begin(h, &err) == 0 &&
            gib_history_add_row(h, run_id, (const char *const *)names,
                                (const char *const *)values, n, &err) == 0)
            gib_history_commit(h, &err);
        gib_history_close(h);
    }

    /* The option lines; --plot (gnuplot) and --db (this file) are dropped with their values. */
    char *argv[40], obuf[4096];
    int argc = 0, skip = 0;
    size_t o = 0;
    argv[argc++] = "history";
    while (opts < opts_end && argc < 36) {
        const char *e = memchr(opts, '\n', (size_t)(opts_end - opts)), *line = opts;
        size_t k = (size_t)((e ? e : opts_end) - line);
        opts = e ? e + 1 : opts_end;
        if (skip) {
            skip = 0;
            continue;
        }
        if (k + 1 > sizeof obuf - o)
            break;
        memcpy(obuf + o, line, k);
        obuf[o + k] = 0;
        if (!strcmp(obuf + o, "--plot") || !strcmp(obuf + o, "--db")) {
            skip = 1;
            continue;
        }
        argv[argc++] = obuf + o;
        o += k + 1;
    }
    argv[argc++] = "--db";
    argv[argc++] = db_path;
    argv[argc] = NULL;
    gib_cmd_history(argc, argv);
    return 0;
}

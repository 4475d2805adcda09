/* Results history (harness/app/history.c) on stores built here, no GL:
 *  - queries: series per row and machine, a revision's median, the renderer filter, a column the
 *    schema does not name (read from row_json), rows not `ok` left out;
 *  - find: the first revision worse than the best before it beyond the tolerance, in both
 *    directions (rmse lower is better, ssim higher);
 *  - two writers at once (two processes, one transaction per row, as `gibench run` writes): every
 *    row is present.
 * Values are exact (they are stored and read back, medians of constructed numbers), so equality
 * is checked to 1e-12, the round trip of a %.9g-formatted double through text and JSON. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <sqlite3.h>

#include "harness/app/history.h"

static int failures;
#include "tests/common/check.h"

static const char *names[] = {"matrix", "profile", "scene", "camera", "technique", "component",
                              "params", "width", "height", "time", "gpu_ms_median", "rmse",
                              "ssim", "status", "message", "renderer", "git_revision", "flip"};
#define NCOL ((int)(sizeof names / sizeof names[0]))

static void machine(gib_history_machine *m, const char *renderer)
{
    gib_history_machine_detect(m, renderer, "4.5 test", "egl");
}

/* Adds one row of scene `scene` (technique direct, 32x32) at revision rev. */
static void add(gib_history *h, long long run, const char *scene, const char *rev, double rmse,
                double ssim, double flip, const char *status, const char *message)
{
    char r[32], s[32], f[32], ms[32];
    snprintf(r, sizeof r, "%.9g", rmse);
    snprintf(s, sizeof s, "%.9g", ssim);
    snprintf(f, sizeof f, "%.9g", flip);
    snprintf(ms, sizeof ms, "%.9g", 10 * rmse);
    const char *v[NCOL] = {"m", "quick", scene, "0", "direct", "direct", "pcf=1", "32", "32", "0",
                           ms, r, s, status, message, "r", rev, f};
    gib_error err;
    int rc = gib_history_begin(h, &err) < 0 || gib_history_add_row(h, run, names, v, NCOL, &err) < 0 ||
             gib_history_commit(h, &err) < 0;
    CHECK(!rc, "adding a row: %s", err.msg);
}

static void test_queries(const char *dir)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/q.sqlite", dir);
    gib_history *h;
    gib_error err;
    if (gib_history_open(&h, path, &err) < 0) {
        CHECK(0, "open: %s", err.msg);
        return;
    }
    gib_history_machine ma, mb;
    machine(&ma, "llvmpipe (LLVM 15)");
    machine(&mb, "NVIDIA H100/PCIe/SSE2");
    CHECK(ma.gpu[0] == 0, "llvmpipe is not a GPU, got '%s'", ma.gpu);
    CHECK(!strcmp(mb.gpu, "NVIDIA H100/PCIe/SSE2"), "a GPU renderer names the GPU, got '%s'", mb.gpu);
    CHECK(ma.cores > 0, "cores %d", ma.cores);
    /* Five revisions on machine a: r2 is within 2% of r1 (noise), r4 is 30% worse than the best. */
    const char *revs[] = {"r1", "r2", "r3", "r4", "r5"};
    const double rmse[] = {0.10, 0.101, 0.099, 0.13, 0.129};
    const double ssim[] = {0.90, 0.90, 0.80, 0.80, 0.95};
    for (int i = 0; i < 5; i++) {
        long long run;
        CHECK(gib_history_begin_run(h, &ma, revs[i], "m", "quick", &run, &err) == 0, "%s", err.msg);
        add(h, run, "cornell", revs[i], rmse[i], ssim[i], 0.5 + i, "ok", "");
        if (i == 2) /* a second run of r3: its point is the median of 0.099, 0.2 and 0.05 */
            add(h, run, "cornell", revs[i], 0.2, ssim[i], 0.5 + i, "ok", "");
        if (i == 2)
            add(h, run, "cornell", revs[i], 0.05, ssim[i], 0.5 + i, "ok", "");
        /* not ok: left out of every series, its nan kept as text in row_json */
        add(h, run, "cornell", revs[i], NAN, NAN, NAN, "nonfinite", "12 NaN/Inf \"values\"\n");
    }
    long long runb;
    CHECK(gib_history_begin_run(h, &mb, "r5", "m", "quick", &runb, &err) == 0, "%s", err.msg);
    add(h, runb, "cornell", "r5", 0.02, 0.99, 0.1, "ok", "");
    add(h, runb, "sponza", "r5", 0.03, 0.98, 0.1, "ok", "");

    gib_history_filter all = {0};
    gib_history_series *s;
    int n;
    CHECK(gib_history_query(h, &all, "rmse", &s, &n, &err) == 0, "%s", err.msg);
    /* series: (cornell, machine a), (cornell, machine b), (sponza, machine b) */
    CHECK(n == 3, "3 series (row x machine), got %d", n);
    if (n == 3) {
        CHECK(!strcmp(s[0].scene, "cornell") && s[0].count == 5, "cornell on a: %s %d points",
              s[0].scene, s[0].count);
        for (int i = 0; i < 5 && s[0].count == 5; i++) {
            double want = i == 2 ? 0.099 : rmse[i];
            CHECK(!strcmp(s[0].points[i].revision, revs[i]), "point %d is %s", i,
                  s[0].points[i].revision);
            CHECK(fabs(s[0].points[i].value - want) < 1e-12, "point %d: %.9g, want %.9g", i,
                  s[0].points[i].value, want);
            CHECK(s[0].points[i].rows == (i == 2 ? 3 : 1), "point %d rows %d", i,
                  s[0].points[i].rows);
        }
        CHECK(gib_history_find_worse(&s[0], 0, 0.02, 1e-6) == 3, "rmse worse at r4 (index 3), got %d",
              gib_history_find_worse(&s[0], 0, 0.02, 1e-6));
        CHECK(gib_history_find_worse(&s[0], 0, 0.5, 1e-6) == -1, "within 50%%: no regression");
        CHECK(gib_history_find_worse(&s[1], 0, 0.02, 1e-6) == -1, "one point: no regression");
        /* Held to the best so far, not the first point: 0.10, 0.05, then 0.06 is a regression. */
        gib_history_point p3[3] = {{.value = 0.10}, {.value = 0.05}, {.value = 0.06}};
        gib_history_series c = {.points = p3, .count = 3};
        CHECK(gib_history_find_worse(&c, 0, 0.02, 1e-6) == 2, "worse than the best so far at 2");
        p3[2].value = 0.0505; /* 1% above the best: noise */
        CHECK(gib_history_find_worse(&c, 0, 0.02, 1e-6) == -1, "1%% above the best is noise");
    }
    gib_history_series_free(s, n);

    CHECK(gib_history_query(h, &all, "ssim", &s, &n, &err) == 0, "%s", err.msg);
    if (n >= 1)
        CHECK(gib_history_find_worse(&s[0], gib_history_higher_is_better("ssim"), 0.02, 1e-6) == 2,
              "ssim worse (lower) at r3 (index 2)");
    gib_history_series_free(s, n);

    gib_history_filter gpu = {.renderer = "NVIDIA", .scene = "cornell"};
    CHECK(gib_history_query(h, &gpu, "rmse", &s, &n, &err) == 0, "%s", err.msg);
    CHECK(n == 1 && s[0].count == 1 && fabs(s[0].points[0].value - 0.02) < 1e-12,
          "renderer filter: 1 series of the H100's one point, got %d", n);
    gib_history_series_free(s, n);

    /* flip is no typed column: read from row_json */
    gib_history_filter llvm = {.renderer = "llvmpipe"};
    CHECK(gib_history_query(h, &llvm, "flip", &s, &n, &err) == 0, "%s", err.msg);
    CHECK(n == 1 && s[0].count == 5 && fabs(s[0].points[4].value - 4.5) < 1e-12,
          "flip from row_json: %d series", n);
    gib_history_series_free(s, n);

    CHECK(gib_history_query(h, &all, "rmse; DROP TABLE result", &s, &n, &err) < 0,
          "a metric that is no column name is refused");
    CHECK(strstr(err.msg, "metric"), "the error names the metric: %s", err.msg);
    gib_history_close(h);

    /* Stored as written: the not-ok rows have NULL rmse, valid JSON with the message escaped. */
    sqlite3 *db;
    sqlite3_open(path, &db);
    sqlite3_stmt *st;
    sqlite3_prepare_v2(db,
                       "SELECT count(*), sum(rmse IS NULL), sum(json_valid(row_json)),"
                       " sum(json_extract(row_json, '$.message') = '12 NaN/Inf \"values\"' || char(10)),"
                       " sum(json_extract(row_json, '$.rmse') = 'nan')"
                       " FROM result WHERE status = 'nonfinite'", -1, &st, NULL);
    if (sqlite3_step(st) == SQLITE_ROW)
        for (int c = 1; c < 5; c++)
            CHECK(sqlite3_column_int(st, c) == 5, "nonfinite rows, check %d: %d of 5", c,
                  sqlite3_column_int(st, c));
    sqlite3_finalize(st);
    sqlite3_close(db);
}

/* Two processes write one history at once; every row must be there. */
static void test_two_writers(const char *dir)
{
    enum { ROWS = 200 };
    char path[1024];
    snprintf(path, sizeof path, "%s/w.sqlite", dir);
    pid_t pid[2];
    for (int w = 0; w < 2; w++) {
        pid[w] = fork();
        if (pid[w] == 0) {
            gib_history *h;
            gib_error err;
            gib_history_machine m;
            long long run;
            machine(&m, "llvmpipe");
            if (gib_history_open(&h, path, &err) < 0 ||
                gib_history_begin_run(h, &m, w ? "b" : "a", "m", "quick", &run, &err) < 0) {
                printf("writer %d: %s\n", w, err.msg);
                _exit(1);
            }
            for (int i = 0; i < ROWS; i++) {
                char scene[32];
                snprintf(scene, sizeof scene, "s%d", i);
                int before = failures;
                add(h, run, scene, w ? "b" : "a", 0.1, 0.9, 0.1, "ok", "");
                if (failures != before)
                    _exit(1);
            }
            gib_history_close(h);
            _exit(0);
        }
    }
    for (int w = 0; w < 2; w++) {
        int st = 0;
        waitpid(pid[w], &st, 0);
        CHECK(WIFEXITED(st) && WEXITSTATUS(st) == 0, "writer %d failed", w);
    }
    sqlite3 *db;
    sqlite3_open(path, &db);
    sqlite3_stmt *st;
    sqlite3_prepare_v2(db, "SELECT count(*), count(DISTINCT run_id) FROM result", -1, &st, NULL);
    int rows = -1, runs = -1;
    if (sqlite3_step(st) == SQLITE_ROW) {
        rows = sqlite3_column_int(st, 0);
        runs = sqlite3_column_int(st, 1);
    }
    sqlite3_finalize(st);
    sqlite3_close(db);
    CHECK(rows == 2 * ROWS && runs == 2, "two writers: %d rows of %d, %d runs", rows, 2 * ROWS, runs);
    printf("two writers at once: %d rows of %d\n", rows, 2 * ROWS);
}

int main(int argc, char **argv)
{
    char dir[] = "/tmp/gib_history_XXXXXX";
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    (void)argc, (void)argv;
    test_queries(dir);
    test_two_writers(dir);
    char cmd[1100];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        printf("could not remove %s\n", dir);
    printf(failures ? "%d failures\n" : "all history checks passed\n", failures);
    return failures ? 1 : 0;
}

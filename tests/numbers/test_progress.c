/* A matrix run's progress (harness/app/progress.h) on a constructed matrix: the runs counted are
 * the ones marked to do, each weighted by its pixels times its frames plus the references it is
 * the first to need; the estimate of the time left is elapsed x work left / work done; durations
 * read as a person writes them. No GL. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "harness/app/progress.h"
#include "techniques/technique.h"

static int failures;
#include "tests/common/check.h"

int main(void)
{
    const gib_technique *direct = gib_technique_find("direct");
    gib_matrix_run runs[3] = {
        {.scene = "cornell", .technique = direct, .width = 10, .height = 10},
        {.scene = "cornell", .technique = direct, .width = 10, .height = 10}, /* same reference */
        {.scene = "cornell", .technique = direct, .width = 20, .height = 10}, /* a new one */
    };
    gib_matrix m = {.frames = 5, .warmup = 2, .runs = runs, .run_count = 3};
    const int direct_component = 1; /* GIB_COMP_DIRECT */
    m.ref_spp[direct_component] = 50;
    const char todo[3] = {1, 1, 1};
    gib_progress p;
    CHECK(gib_progress_start(&p, &m, todo) == 0, "start");
    /* frames: 100 px x 8 frames; reference: 100 px x 50 spp / 5 = 1000 (first run only). */
    CHECK(fabs(p.run_work[0] - 1800) < 1e-9 && fabs(p.run_work[1] - 800) < 1e-9 &&
              fabs(p.run_work[2] - 3600) < 1e-9,
          "work per run %g %g %g, want 1800 800 3600", p.run_work[0], p.run_work[1],
          p.run_work[2]);
    char tag[32];
    gib_progress_tag(&p, tag, sizeof tag);
    CHECK(!strcmp(tag, "[1/3]"), "tag before the first run '%s'", tag);
    gib_progress_run_done(&p, 0);
    gib_progress_tag(&p, tag, sizeof tag);
    CHECK(!strcmp(tag, "[2/3]") && p.runs_done == 1 && fabs(p.work_done - 1800) < 1e-9,
          "after one run: '%s', done %d, work %g", tag, p.runs_done, p.work_done);
    gib_progress_free(&p);

    const char some[3] = {0, 1, 0}; /* a resumed run: only run 1 is left */
    CHECK(gib_progress_start(&p, &m, some) == 0 && p.runs_total == 1 &&
              fabs(p.work_total - 800) < 1e-9,
          "resumed: %d runs, work %g (want 1, 800: its reference is counted by run 0's)",
          p.runs_total, p.work_total);
    gib_progress_free(&p);

    char d[32];
    gib_format_duration(12.4, d, sizeof d);
    CHECK(!strcmp(d, "12s"), "12.4 s -> '%s'", d);
    gib_format_duration(185, d, sizeof d);
    CHECK(!strcmp(d, "3m05s"), "185 s -> '%s'", d);
    gib_format_duration(3720, d, sizeof d);
    CHECK(!strcmp(d, "1h02m"), "3720 s -> '%s'", d);
    printf("%s: progress (%d failure(s))\n", failures ? "FAIL" : "PASS", failures);
    return failures ? 1 : 0;
}

#include "progress.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness/app/app.h"
#include "harness/app/runner.h"
#include "harness/gl/timers.h"
#include "reference/reference.h"

#define REF_SAMPLES_PER_FRAME 5.0

/* The work of run j of m: its frames, and the references no earlier run of m needs (same scene,
 * size, instant and component), at the matrix's samples per pixel (64 where it names none, as
 * the runner). */
static double run_work(const gib_matrix *m, int j)
{
    const gib_matrix_run *r = &m->runs[j];
    const double pixels = (double)r->width * r->height;
    double work = pixels * (m->frames + m->warmup + 1);
    for (unsigned bit = 1; bit <= GIB_OUT_CAUSTIC; bit <<= 1) {
        if (!(r->technique->components & bit))
            continue;
        const int c = gib_component_parse(gib_output_name(bit));
        int first = 1;
        for (int i = 0; i < j && first; i++) {
            const gib_matrix_run *q = &m->runs[i];
            first = !((q->technique->components & bit) && !strcmp(q->scene, r->scene) &&
                      q->width == r->width && q->height == r->height && q->time == r->time);
        }
        const int spp = c >= 0 && c < GIB_MATRIX_MAX_COMPONENTS && m->ref_spp[c] ? m->ref_spp[c]
                                                                                  : 64;
        if (first)
            work += pixels * spp / REF_SAMPLES_PER_FRAME;
    }
    return work;
}

int gib_progress_start(gib_progress *p, const gib_matrix *m, const char *todo)
{
    memset(p, 0, sizeof *p);
    p->run_work = calloc(m->run_count ? (size_t)m->run_count : 1, sizeof *p->run_work);
    if (!p->run_work)
        return -1;
    for (int j = 0; j < m->run_count; j++) {
        if (!todo[j])
            continue;
        p->run_work[j] = run_work(m, j);
        p->work_total += p->run_work[j];
        p->runs_total++;
    }
    p->start_ms = gib_now_ms();
    p->live = isatty(STDERR_FILENO);
    return 0;
}

void gib_progress_run_done(gib_progress *p, int j)
{
    p->runs_done++;
    p->work_done += p->run_work[j];
}

void gib_progress_tag(const gib_progress *p, char *out, size_t len)
{
    snprintf(out, len, "[%d/%d]", p->runs_done + 1 > p->runs_total ? p->runs_total
                                                                     : p->runs_done + 1,
             p->runs_total);
}

void gib_format_duration(double s, char *out, size_t len)
{
    const long t = (long)llround(s > 0 ? s : 0);
    if (t >= 3600)
        snprintf(out, len, "%ldh%02ldm", t / 3600, t / 60 % 60);
    else if (t >= 60)
        snprintf(out, len, "%ldm%02lds", t / 60, t % 60);
    else
        snprintf(out, len, "%lds", t);
}

void gib_progress_clear(gib_progress *p)
{
    if (p->line_shown) {
        fputs("\r\033[K", stderr);
        fflush(stderr);
        p->line_shown = 0;
    }
}

void gib_progress_report(gib_progress *p)
{
    const double elapsed = (gib_now_ms() - p->start_ms) / 1000.0;
    char el[32], left[48] = "";
    gib_format_duration(elapsed, el, sizeof el);
    if (p->work_done > 0 && p->runs_done < p->runs_total) {
        char d[32];
        gib_format_duration(elapsed * (p->work_total - p->work_done) / p->work_done, d, sizeof d);
        snprintf(left, sizeof left, ", about %s left", d);
    }
    const double pct = p->work_total > 0 ? 100.0 * p->work_done / p->work_total : 100.0;
    fflush(stdout);
    if (p->live) {
        fprintf(stderr, "\r\033[K[%d/%d] %.0f%% of the work, %s elapsed%s", p->runs_done,
                p->runs_total, pct, el, left);
        fflush(stderr);
        p->line_shown = 1;
    } else {
        printf("[%d/%d] %.0f%% of the work, %s elapsed%s\n", p->runs_done, p->runs_total, pct, el,
               left);
    }
}

void gib_progress_free(gib_progress *p)
{
    gib_progress_clear(p);
    free(p->run_work);
    p->run_work = NULL;
}

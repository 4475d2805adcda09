#include "timers.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

double gib_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

void gib_timers_init(gib_timers *t)
{
    memset(t, 0, sizeof *t);
    t->active = -1;
}

void gib_timers_destroy(gib_timers *t)
{
    for (int i = 0; i < t->pass_count; i++) {
        if (t->queries[i])
            glDeleteQueries(1, &t->queries[i]);
        if (t->work_queries[i][0])
            glDeleteQueries(GIB_WORK_COUNT, t->work_queries[i]);
    }
    t->pass_count = 0;
}

/* The statistics counted, in the order of GIB_WORK_*. */
static const GLenum work_targets[GIB_WORK_COUNT] = {
    GL_VERTICES_SUBMITTED, GL_PRIMITIVES_SUBMITTED, GL_FRAGMENT_SHADER_INVOCATIONS,
    GL_COMPUTE_SHADER_INVOCATIONS};

int gib_timers_can_count(void)
{
    return GLAD_GL_ARB_pipeline_statistics_query;
}

static void work_begin(gib_timers *t, int i)
{
    if (!t->work_queries[i][0])
        glGenQueries(GIB_WORK_COUNT, t->work_queries[i]);
    for (int k = 0; k < GIB_WORK_COUNT; k++)
        glBeginQuery(work_targets[k], t->work_queries[i][k]);
}

/* Ends pass i's statistics queries and adds their counts (a pass may run twice in a frame). */
static void work_end(gib_timers *t, int i)
{
    for (int k = 0; k < GIB_WORK_COUNT; k++)
        glEndQuery(work_targets[k]);
    for (int k = 0; k < GIB_WORK_COUNT; k++) {
        GLuint64 n = 0;
        glGetQueryObjectui64v(t->work_queries[i][k], GL_QUERY_RESULT, &n);
        t->work[i][k] += n;
    }
    t->counted[i] = 1;
}

static int pass_index(gib_timers *t, const char *name)
{
    for (int i = 0; i < t->pass_count; i++)
        if (!strcmp(t->names[i], name))
            return i;
    if (t->pass_count >= GIB_TIMER_MAX_PASSES)
        return -1;
    int i = t->pass_count++;
    strncpy(t->names[i], name, sizeof t->names[i] - 1);
    glGenQueries(1, &t->queries[i]);
    return i;
}

void gib_timer_begin(gib_timers *t, const char *pass)
{
    if (t->active >= 0)
        gib_timer_end(t);
    int i = pass_index(t, pass);
    if (i < 0)
        return;
    t->active = i;
    if (t->counting)
        work_begin(t, i);
    glBeginQuery(GL_TIME_ELAPSED, t->queries[i]);
}

void gib_timer_end(gib_timers *t)
{
    if (t->active < 0)
        return;
    glEndQuery(GL_TIME_ELAPSED);
    if (t->counting)
        work_end(t, t->active);
    /* Read back at once: a pass may run twice in a frame (several lights), and one query object per
     * pass can only hold one result. The wait costs CPU time, not GPU time. */
    GLuint64 ns = 0;
    glGetQueryObjectui64v(t->queries[t->active], GL_QUERY_RESULT, &ns);
    t->frame_ms += ns * 1e-6;
    if (t->cold)
        t->first_ms[t->active] += ns * 1e-6;
    if (t->recording && t->frames < GIB_TIMER_MAX_FRAMES) {
        t->ms[t->active][t->frames] += ns * 1e-6;
        t->used_in_frame[t->active] = 1;
    }
    t->active = -1;
}

void gib_timers_frame_begin(gib_timers *t, int record)
{
    t->cold = t->begun++ == 0;
    t->recording = !t->cold && record && t->frames < GIB_TIMER_MAX_FRAMES;
    t->counting = t->count_next && gib_timers_can_count();
    t->count_next = 0;
    t->frame_ms = 0;
    if (t->recording)
        for (int i = 0; i < GIB_TIMER_MAX_PASSES; i++)
            t->ms[i][t->frames] = 0;
    t->frame_cpu_start = gib_now_ms();
}

void gib_timers_frame_end(gib_timers *t)
{
    if (t->active >= 0)
        gib_timer_end(t);
    glFinish();
    t->counting = 0;
    if (t->cold) {
        t->first_cpu_ms = gib_now_ms() - t->frame_cpu_start;
        for (int i = 0; i < t->pass_count; i++)
            t->first_total_ms += t->first_ms[i];
        t->cold = 0;
    }
    if (!t->recording)
        return;
    double total = 0;
    for (int i = 0; i < t->pass_count; i++)
        total += t->ms[i][t->frames];
    t->total_ms[t->frames] = total;
    t->cpu_ms[t->frames] = gib_now_ms() - t->frame_cpu_start;
    t->frames++;
    t->recording = 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void gib_stats_median(const double *v, int n, double *median, double *min, double *max)
{
    double *s = malloc(sizeof(double) * (n > 0 ? n : 1));
    if (!s || n <= 0) {
        *median = *min = *max = 0;
        free(s);
        return;
    }
    memcpy(s, v, sizeof(double) * n);
    qsort(s, n, sizeof(double), cmp_double);
    *median = n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
    *min = s[0];
    *max = s[n - 1];
    free(s);
}

double gib_stats_quantile(const double *v, int n, double q)
{
    double *s = n > 0 ? malloc(sizeof(double) * n) : NULL;
    if (!s)
        return 0;
    memcpy(s, v, sizeof(double) * n);
    qsort(s, n, sizeof(double), cmp_double);
    double h = q * (n - 1);
    int lo = (int)h;
    double x = lo + 1 < n ? s[lo] + (h - lo) * (s[lo + 1] - s[lo]) : s[n - 1];
    free(s);
    return x;
}

/* Median, spread and extremes of n timed values, and the cold frame's value beside them. */
static void fill_stats(gib_pass_stats *st, const char *name, const double *v, int n, double first)
{
    memset(st, 0, sizeof *st);
    snprintf(st->name, sizeof st->name, "%s", name);
    gib_stats_median(v, n, &st->median_ms, &st->min_ms, &st->max_ms);
    st->iqr_ms = gib_stats_quantile(v, n, 0.75) - gib_stats_quantile(v, n, 0.25);
    st->first_ms = first;
}

int gib_timers_stats(const gib_timers *t, gib_pass_stats *stats, int max, gib_pass_stats *gpu_total,
                     gib_pass_stats *cpu_total)
{
    int n = t->pass_count < max ? t->pass_count : max;
    for (int i = 0; i < n; i++) {
        fill_stats(&stats[i], t->names[i], t->ms[i], t->frames, t->first_ms[i]);
        stats[i].counted = t->counted[i];
        memcpy(stats[i].work, t->work[i], sizeof stats[i].work);
    }
    if (gpu_total)
        fill_stats(gpu_total, "total", t->total_ms, t->frames, t->first_total_ms);
    if (cpu_total)
        fill_stats(cpu_total, "cpu", t->cpu_ms, t->frames, t->first_cpu_ms);
    return n;
}

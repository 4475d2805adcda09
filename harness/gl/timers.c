#include "timers.h"

#include <glad/gl.h>
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
    for (int i = 0; i < t->pass_count; i++)
        if (t->queries[i])
            glDeleteQueries(1, &t->queries[i]);
    t->pass_count = 0;
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
    glBeginQuery(GL_TIME_ELAPSED, t->queries[i]);
}

void gib_timer_end(gib_timers *t)
{
    if (t->active < 0)
        return;
    glEndQuery(GL_TIME_ELAPSED);
    /* Read back at once: a pass may run twice in a frame (several lights), and one query object per
     * pass can only hold one result. The wait costs CPU time, not GPU time. */
    GLuint64 ns = 0;
    glGetQueryObjectui64v(t->queries[t->active], GL_QUERY_RESULT, &ns);
    if (t->recording && t->frames < GIB_TIMER_MAX_FRAMES) {
        t->ms[t->active][t->frames] += ns * 1e-6;
        t->used_in_frame[t->active] = 1;
    }
    t->active = -1;
}

void gib_timers_frame_begin(gib_timers *t, int record)
{
    t->recording = record && t->frames < GIB_TIMER_MAX_FRAMES;
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

int gib_timers_stats(const gib_timers *t, gib_pass_stats *stats, int max, gib_pass_stats *gpu_total,
                     gib_pass_stats *cpu_total)
{
    int n = t->pass_count < max ? t->pass_count : max;
    for (int i = 0; i < n; i++) {
        strcpy(stats[i].name, t->names[i]);
        gib_stats_median(t->ms[i], t->frames, &stats[i].median_ms, &stats[i].min_ms,
                         &stats[i].max_ms);
    }
    if (gpu_total) {
        strcpy(gpu_total->name, "total");
        gib_stats_median(t->total_ms, t->frames, &gpu_total->median_ms, &gpu_total->min_ms,
                         &gpu_total->max_ms);
    }
    if (cpu_total) {
        strcpy(cpu_total->name, "cpu");
        gib_stats_median(t->cpu_ms, t->frames, &cpu_total->median_ms, &cpu_total->min_ms,
                         &cpu_total->max_ms);
    }
    return n;
}

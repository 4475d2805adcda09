/* gibench — named per-pass GPU timers (GL_TIME_ELAPSED queries) and CPU frame time.
 *
 * A technique brackets each pass with gib_timer_begin/end. The harness marks frames; results are
 * collected after each frame (queries are read back then, so they never overlap: TIME_ELAPSED
 * queries cannot nest). The first frame (shader JIT, first use of every resource) is kept apart as
 * the cold frame; statistics are over the timed frames only, warm-up frames are discarded. */
#ifndef GIB_TIMERS_H
#define GIB_TIMERS_H

/* Pipeline statistics: the harness sets count_next before one frame (a warm one: the last
 * warm-up frame) and every pass of that frame also counts its work. The counting queries never
 * bracket a timed frame, so they cannot change its times. */

#define GIB_TIMER_MAX_PASSES 16
#define GIB_TIMER_MAX_FRAMES 256

/* The work a pass did in the counting frame (GL_ARB_pipeline_statistics_query): vertices and
 * primitives submitted, fragment and compute shader invocations. */
enum { GIB_WORK_VERTICES, GIB_WORK_PRIMITIVES, GIB_WORK_FRAGMENTS, GIB_WORK_COMPUTE, GIB_WORK_COUNT };

typedef struct gib_pass_stats {
    char name[48];
    double median_ms, min_ms, max_ms; /* over the timed frames */
    double iqr_ms;                    /* their interquartile range (quartiles interpolated) */
    double first_ms;                  /* the cold first frame: never among the timed ones */
    int counted;                      /* 1: work[] holds the counting frame's pipeline statistics */
    unsigned long long work[GIB_WORK_COUNT];
} gib_pass_stats;

struct gib_timers {
    int pass_count;
    char names[GIB_TIMER_MAX_PASSES][48];
    unsigned queries[GIB_TIMER_MAX_PASSES];
    unsigned work_queries[GIB_TIMER_MAX_PASSES][GIB_WORK_COUNT];
    unsigned long long work[GIB_TIMER_MAX_PASSES][GIB_WORK_COUNT];
    int counted[GIB_TIMER_MAX_PASSES];
    int count_next;                /* set by the harness: count the work of the next frame begun */
    int counting;                  /* 1 during that frame, when the driver has the statistics */
    double frame_ms;               /* GPU ms of the frame being rendered or last ended, any frame */
    int used_in_frame[GIB_TIMER_MAX_PASSES];
    int active;                    /* pass index with an open query, -1 when none */
    int frames;                    /* recorded (timed) frames */
    int recording;                 /* 0 during warm-up */
    int begun;                     /* frames begun, the cold one included */
    int cold;                      /* 1 during the first frame */
    double first_ms[GIB_TIMER_MAX_PASSES], first_total_ms, first_cpu_ms;
    double ms[GIB_TIMER_MAX_PASSES][GIB_TIMER_MAX_FRAMES];
    double total_ms[GIB_TIMER_MAX_FRAMES];
    double cpu_ms[GIB_TIMER_MAX_FRAMES];
    double frame_cpu_start;
};
typedef struct gib_timers gib_timers;

void gib_timers_init(gib_timers *t);
void gib_timers_destroy(gib_timers *t);

/* Used by techniques. Passes are identified by name; the same name in one frame accumulates. */
void gib_timer_begin(gib_timers *t, const char *pass);
void gib_timer_end(gib_timers *t);

/* Whether the driver counts pipeline statistics (GL_ARB_pipeline_statistics_query). */
int gib_timers_can_count(void);

/* Used by the harness around each render() call. `record` = 0 for warm-up frames; the first frame
 * begun is the cold one and is never recorded as timed. frame_end waits for the GPU (glFinish), so
 * the CPU time is the full frame's wall time. */
void gib_timers_frame_begin(gib_timers *t, int record);
void gib_timers_frame_end(gib_timers *t);

/* Per-pass statistics (stats[i] for pass i, up to max) and totals. Returns the pass count. */
int gib_timers_stats(const gib_timers *t, gib_pass_stats *stats, int max, gib_pass_stats *gpu_total,
                     gib_pass_stats *cpu_total);

/* Median, min, max of n values (n >= 1). */
void gib_stats_median(const double *v, int n, double *median, double *min, double *max);
/* Quantile q in [0, 1] of n values, linearly interpolated between order statistics (Hyndman and
 * Fan's type 7, numpy's default); 0 for n < 1. */
double gib_stats_quantile(const double *v, int n, double q);

double gib_now_ms(void);

#endif

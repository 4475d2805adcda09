/* gibench history — questions asked of the results history (history.h), as airspeed velocity
 * answers them for Python benchmarks: how a row's error or time changed across revisions, on
 * which machine; which revision made it worse; as a table or a gnuplot plot. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "history.h"
#include "options.h"

static const gib_command_doc doc = {
    "history", "[filters] [--find [--tol REL] [--abs A] | --plot FILE.png | --machines]",
    "Reads the results history `gibench run` records (default results/history.sqlite). Every\n"
    "(matrix, scene, camera, technique, component, params, size, instant) row on one machine is a\n"
    "series; each revision is a point, the median of its `ok` rows' metric (default rmse; any\n"
    "numeric CSV column: ssim, gpu_ms_median, cpu_ms, mem_bytes, flip, ...), in the order the\n"
    "revisions were first run.\n"
    "  (default)    a table per series: revision, first run, rows, value, change\n"
    "  --find       per series, the first revision worse than the best before it by more than\n"
    "               REL of that best plus A (defaults: 0.02 for errors, as the quality gate;\n"
    "               0.10 for times and memory, llvmpipe's run-to-run spread; A = 1e-6)\n"
    "  --plot F.png the metric by revision, a line per series (gnuplot)\n"
    "  --machines   the machines in the history (ids for --machine)\n"
    "--renderer keeps machines whose GL renderer contains TEXT. Exit status 1 when --find finds a\n"
    "regression, 2 for bad options, 3 when nothing matches.\n"};

static int is_time_metric(const char *m)
{
    return strstr(m, "_ms") || strstr(m, "mem") || strstr(m, "bytes");
}

/* The revisions of every series in the order they were first run (ISO times sort as text). */
static int revision_order(const gib_history_series *s, int n, char (**revs)[64], int *nrev)
{
    int cap = 0, count = 0;
    char (*r)[64] = NULL;
    char(*first)[32] = NULL;
    for (int i = 0; i < n; i++)
        for (int p = 0; p < s[i].count; p++) {
            int k = 0;
            while (k < count && strcmp(r[k], s[i].points[p].revision))
                k++;
            if (k < count) {
                if (strcmp(s[i].points[p].started, first[k]) < 0)
                    memcpy(first[k], s[i].points[p].started, 32);
                continue;
            }
            if (count == cap) {
                cap = cap ? 2 * cap : 16;
                void *a = realloc(r, cap * sizeof *r), *b = a ? realloc(first, cap * sizeof *first)
                                                              : NULL;
                if (a)
                    r = a;
                if (!a || !b) {
                    free(r);
                    free(b ? b : first);
                    return -1;
                }
                first = b;
            }
            memcpy(r[count], s[i].points[p].revision, 64);
            memcpy(first[count], s[i].points[p].started, 32);
            count++;
        }
    for (int i = 1; i < count; i++) /* insertion sort by first run: few revisions */
        for (int j = i; j > 0 && strcmp(first[j], first[j - 1]) < 0; j--) {
            char t[64], u[32];
            memcpy(t, r[j], 64), memcpy(r[j], r[j - 1], 64), memcpy(r[j - 1], t, 64);
            memcpy(u, first[j], 32), memcpy(first[j], first[j - 1], 32), memcpy(first[j - 1], u, 32);
        }
    free(first);
    *revs = r;
    *nrev = count;
    return 0;
}

static void series_title(const gib_history_series *s, char *out, size_t len)
{
    snprintf(out, len, "%s: %s %s %s [%s] %dx%d", s->matrix, s->scene, s->technique,
             s->component, s->params, s->width, s->height);
    if (s->time != 0.0 || s->camera != 0)
        snprintf(out + strlen(out), len - strlen(out), " camera %d t %g", s->camera, s->time);
}

/* Text from the history (revisions, scenes, parameters) and the user (the PNG's path) goes into
 * gnuplot's script only as a single-quoted string: a quote doubled, a line break a space, so a
 * damaged or foreign history can neither break the script nor run commands through it. */
static void gnuplot_string(FILE *g, const char *s, size_t max)
{
    fputc('\'', g);
    for (size_t i = 0; s[i] && i < max; i++) {
        if (s[i] == '\'')
            fputc('\'', g);
        fputc(s[i] == '\n' || s[i] == '\r' ? ' ' : s[i], g);
    }
    fputc('\'', g);
}

static int plot(const char *png, const char *metric, const gib_history_series *s, int n)
{
    char (*revs)[64];
    int nrev;
    if (revision_order(s, n, &revs, &nrev) < 0) {
        fprintf(stderr, "gibench history: out of memory\n");
        return 1;
    }
    char dat[] = "/tmp/gibench_history_XXXXXX";
    int fd = mkstemp(dat);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f) {
        fprintf(stderr, "gibench history: --plot: cannot write a temporary file\n");
        free(revs);
        return 1;
    }
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < nrev; k++)
            for (int p = 0; p < s[i].count; p++)
                if (!strcmp(s[i].points[p].revision, revs[k]))
                    fprintf(f, "%d %.9g\n", k, s[i].points[p].value);
        fprintf(f, "\n\n");
    }
    fclose(f);
    FILE *g = popen("gnuplot", "w");
    if (!g) {
        fprintf(stderr, "gibench history: --plot: cannot run gnuplot (Debian gnuplot-nox)\n");
        unlink(dat);
        free(revs);
        return 1;
    }
    /* The key below the plot, one line per series: room grows with the series count. */
    fprintf(g, "set terminal pngcairo size 1200,%d noenhanced font ',10'\nset output ", 560 + 18 * n);
    gnuplot_string(g, png, SIZE_MAX);
    fprintf(g, "\nset title 'gibench history: %s by revision'\nset ylabel '%s'\n", metric, metric);
    fprintf(g, "set xlabel 'revision (in the order first run)'\nset grid\nset key outside below Left reverse\n");
    fprintf(g, "set xrange [-0.5:%d.5]\nset xtics rotate by -45 (", nrev - 1);
    for (int k = 0; k < nrev; k++) {
        fputs(k ? ", " : "", g);
        gnuplot_string(g, revs[k], 24);
        fprintf(g, " %d", k);
    }
    fprintf(g, ")\nplot ");
    for (int i = 0; i < n; i++) {
        char t[1400];
        series_title(&s[i], t, sizeof t);
        if (strlen(t) > 110) /* long parameter lists: the table has them whole */
            strcpy(t + 104, " ...]");
        snprintf(t + strlen(t), sizeof t - strlen(t), " [machine %lld]", s[i].machine);
        fprintf(g, "%s'%s' index %d using 1:2 with linespoints title ", i ? ", " : "", dat, i);
        gnuplot_string(g, t, SIZE_MAX);
    }
    fprintf(g, "\n");
    int rc = pclose(g);
    unlink(dat);
    free(revs);
    if (rc != 0) {
        fprintf(stderr, "gibench history: gnuplot failed writing %s (status %d)\n", png, rc);
        return 1;
    }
    printf("gibench history: wrote %s (%d series, %d revisions)\n", png, n, nrev);
    return 0;
}

/* What the command line asks for. */
typedef struct history_opts {
    const char *db, *metric, *png;
    gib_history_filter f;
    int find, machines, have_tol;
    double tol, abs_tol;
} history_opts;

/* history_parse_args, history_load: go on (else the exit status) */
#define PROCEED GIB_OPTIONS_PROCEED

static int parse_plot(const gib_option *o, const char *v, gib_error *err)
{
    *(const char **)o->dest = v;
    return gib_check_output(o->name, v, ".png", err);
}

static int parse_size(const gib_option *o, const char *v, gib_error *err)
{
    gib_history_filter *f = o->dest;
    return gib_parse_size(o->name, v, &f->width, &f->height, err);
}

static int parse_machine(const gib_option *o, const char *v, gib_error *err)
{
    long id;
    if (gib_parse_int(o->name, v, 1, 1L << 40, &id, err) < 0)
        return -1;
    ((gib_history_filter *)o->dest)->machine = id;
    return 0;
}

static int parse_tol(const gib_option *o, const char *v, gib_error *err)
{
    history_opts *h = o->dest;
    h->have_tol = 1;
    return gib_parse_float(o->name, v, 0, 1e6, &h->tol, err);
}

static int history_parse_args(int argc, char **argv, history_opts *o)
{
    gib_history_filter *f = &o->f;
    const gib_option opts[] = {
        GIB_OPTION_TEXT("--db", &o->db, "PATH", "the history (default results/history.sqlite)"),
        GIB_OPTION_TEXT("--metric", &o->metric, "M", "a numeric column (default rmse)"),
        GIB_OPTION_TEXT("--matrix", &f->matrix, "M", "only this matrix's series"),
        GIB_OPTION_TEXT("--scene", &f->scene, "S", "only this scene's"),
        GIB_OPTION_TEXT("--technique", &f->technique, "T", "only this technique's"),
        GIB_OPTION_TEXT("--component", &f->component, "C", "only this component's"),
        GIB_OPTION_TEXT("--params", &f->params, "P", "only these parameters'"),
        GIB_OPTION_CUSTOM("--size", f, parse_size, "WxH", "only this size's"),
        GIB_OPTION_TEXT("--renderer", &f->renderer, "TEXT", "machines whose renderer holds TEXT"),
        GIB_OPTION_CUSTOM("--machine", f, parse_machine, "ID", "one machine (--machines lists)"),
        GIB_OPTION_FLAG("--find", &o->find, "the first regression of each series"),
        GIB_OPTION_CUSTOM("--tol", o, parse_tol, "REL", "--find's relative tolerance"),
        GIB_OPTION_FLOAT("--abs", &o->abs_tol, 0, 1e30, "A", "--find's absolute tolerance"),
        GIB_OPTION_CUSTOM("--plot", &o->png, parse_plot, "FILE.png", "plot the metric by revision"),
        GIB_OPTION_FLAG("--machines", &o->machines, "the machines in the history"),
        {0}};
    return gib_options_parse(&doc, opts, argc, argv, NULL, NULL, 0);
}

/* The matching series from the history (or, with --machines, the machines printed). Returns
 * PROCEED with at least one series in *s, or the exit status. */
static int history_load(const history_opts *o, gib_history_series **s, int *n)
{
    gib_error err;
    if (access(o->db, R_OK) != 0) {
        fprintf(stderr, "gibench history: no history at %s (`gibench run` records one; --db PATH)\n",
                o->db);
        return 3;
    }
    gib_history *h;
    if (gib_history_open_readonly(&h, o->db, &err) < 0) {
        fprintf(stderr, "gibench history: %s\n", err.msg);
        return 1;
    }
    if (o->machines) {
        int rc = gib_history_print_machines(h, stdout, &err);
        if (rc < 0)
            fprintf(stderr, "gibench history: %s\n", err.msg);
        gib_history_close(h);
        return rc < 0 ? 1 : 0;
    }
    if (gib_history_query(h, &o->f, o->metric, s, n, &err) < 0) {
        fprintf(stderr, "gibench history: %s\n", err.msg);
        gib_history_close(h);
        return 2;
    }
    gib_history_close(h);
    if (!*n) {
        fprintf(stderr, "gibench history: no `ok` row with a numeric %s matches in %s\n",
                o->metric, o->db);
        return 3;
    }
    return PROCEED;
}

/* --find on one series: its first revision worse than the best before it, printed. Returns 1
 * when there is one. */
static int print_worse(const history_opts *o, const gib_history_series *s, int higher,
                       const char *title)
{
    int w = gib_history_find_worse(s, higher, o->tol, o->abs_tol);
    if (w < 0)
        return 0;
    double best = s->points[0].value;
    for (int p = 1; p < w; p++)
        if (higher ? s->points[p].value > best : s->points[p].value < best)
            best = s->points[p].value;
    const gib_history_point *last = &s->points[s->count - 1];
    printf("%s on machine %lld (%s)\n  %s worse at revision %s (first run %s): %.6g, best "
           "before %.6g (%+.1f%%, allowed %.1f%% + %g); latest %s: %.6g\n",
           title, s->machine, s->renderer, o->metric, s->points[w].revision,
           s->points[w].started, s->points[w].value, best,
           best ? 100.0 * (s->points[w].value / best - 1) : 0.0, 100 * o->tol, o->abs_tol,
           last->revision, last->value);
    return 1;
}

/* One series as a table: revision, first run, rows, value, change. */
static void print_table(const history_opts *o, const gib_history_series *s, const char *title)
{
    printf("%s on machine %lld (%s)\n  %-20s %-20s %4s %14s %9s\n", title, s->machine,
           s->renderer, "revision", "first run", "rows", o->metric, "change");
    for (int p = 0; p < s->count; p++) {
        const gib_history_point *q = &s->points[p];
        char ch[32] = "";
        if (p && s->points[p - 1].value)
            snprintf(ch, sizeof ch, "%+.2f%%", 100 * (q->value / s->points[p - 1].value - 1));
        printf("  %-20s %-20s %4d %14.6g %9s\n", q->revision, q->started, q->rows, q->value, ch);
    }
}

int gib_cmd_history(int argc, char **argv)
{
    history_opts o = {.db = GIB_PROJECT_ROOT "/results/history.sqlite", .metric = "rmse",
                      .abs_tol = 1e-6};
    int rc = history_parse_args(argc, argv, &o);
    if (rc != PROCEED)
        return rc;
    gib_history_series *s;
    int n;
    rc = history_load(&o, &s, &n);
    if (rc != PROCEED)
        return rc;
    if (!o.have_tol)
        o.tol = is_time_metric(o.metric) ? 0.10 : 0.02;
    int higher = gib_history_higher_is_better(o.metric), status = 0, worse_count = 0;
    if (o.png) {
        if (n > 24)
            fprintf(stderr, "gibench history: --plot: %d series match; filter to 24 or fewer\n", n);
        status = n > 24 ? 2 : plot(o.png, o.metric, s, n);
    }
    for (int i = 0; i < n && !o.png; i++) {
        char t[1400];
        series_title(&s[i], t, sizeof t);
        if (o.find)
            worse_count += print_worse(&o, &s[i], higher, t);
        else
            print_table(&o, &s[i], t);
    }
    if (o.find) {
        printf("gibench history: %d of %d series got worse in %s (tolerance %g relative + %g)\n",
               worse_count, n, o.metric, o.tol, o.abs_tol);
        status = worse_count ? 1 : status;
    }
    gib_history_series_free(s, n);
    return status;
}

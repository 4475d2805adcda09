/* gibench bench reference — the reference renderer's ray throughput against raw Embree
 * (reference/ref_bench.c), and with --efficiency its sampling efficiency by sampler (how fast its
 * error falls per second), printed and written to CSV with the machine it ran on. Performance is
 * measured and reported here, never asserted by a test. `bench scoring` is bench_scoring.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <embree3/rtcore_config.h>
#include <sys/utsname.h>
#include <unistd.h>

#include "app.h"
#include "bench_scoring.h"
#include "options.h"
#include "refset.h"

static const gib_command_doc doc = {
    "bench", "reference [--efficiency] [options]",
    "Measures, on one scene and BVH: raw Embree throughput on random incoherent rays\n"
    "(rtcIntersect1; from the bounding box, and Aila and Laine's diffuse rays from the visible\n"
    "surfaces), the path tracer's own rays replayed with each ray API (single rays,\n"
    "rtcIntersect1M streams, 4/8/16-wide packets), and the path tracer's throughput (rays per\n"
    "second including sampling and shading); for component full on scenes without a sky or\n"
    "mirrors, also a lean tracer (the same kind of paths with almost no other work, its own\n"
    "rays replayed with each API: what a renderer doing little but tracing reaches on this\n"
    "machine and scene; rows lean_* are paired with the lean tracer's own replay). A list of\n"
    "scenes runs each in turn into one CSV, skipping those whose data is absent. Defaults:\n"
    "scene sponza (cornell when its data is absent), 256x256, component full, 16 spp, all\n"
    "cores. --repeat N rounds (default 3, at most 100) each run every measure once; each row\n"
    "has the best, median and worst time, and its paired ratio: its rays/s over the fastest\n"
    "replay's in the same round, whose median is the figure to quote on a shared machine\n"
    "(both sides of a pair ran under the same load).\n"
    "\n"
    "--efficiency: per scene and component, a truth image (Sobol, --truth-spp, default 2048,\n"
    "seed 1000), then per sampler and spp --repeat renders (seeds 1..N); each render's actual\n"
    "error is its mean squared difference from the truth less the truth's own reported variance\n"
    "(independent renders: variances add). efficiency = 1 / (relative variance x seconds), the\n"
    "relative variance that error over the truth's squared mean, the seconds those of sampling\n"
    "(the BVH build left out); beside it the efficiency the renderer's own noise estimate\n"
    "predicts, and their ratio (an honest estimate gives ~1). Defaults: scenes cornell,sibenik,\n"
    "sponza, components full,indirect, 128x128, spp 16,64, samplers random,sobol, 3 repeats.\n"};

void gib_bench_machine_name(char *out, size_t len)
{
    snprintf(out, len, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512];
    while (f && fgets(line, sizeof line, f)) {
        if (!strncmp(line, "model name", 10)) {
            char *c = strchr(line, ':');
            if (c) {
                c++;
                while (*c == ' ' || *c == '\t')
                    c++;
                c[strcspn(c, "\n")] = 0;
                snprintf(out, len, "%s", c);
            }
            break;
        }
    }
    if (f)
        fclose(f);
    struct utsname u;
    if (uname(&u) == 0)
        snprintf(out + strlen(out), len - strlen(out), " / %s %s", u.sysname, u.machine);
    for (char *p = out; *p; p++) /* CSV-safe */
        if (*p == ',' || *p == '"')
            *p = ' ';
}

/* The path tracer's figures of one scene, for the summary of a multi-scene run. */
typedef struct bench_summary {
    char scene[64];
    unsigned triangles;
    double mrays, paired_median, paired_min, paired_max;
    double embree_inside; /* path_tracer_embree's paired median */
    double lean;          /* lean_tracer's paired median (0: not run) */
} bench_summary;

/* One scene's rows and what they are read against: the raw figures and the fastest replays. */
typedef struct bench_table {
    const gib_scene *scene;
    const gib_ref_params *p;
    const char *comp;
    long cores;
    char machine[256];
    const gib_ref_bench_row *rows;
    int n;
    double raw_random, raw_diffuse, raw_best, lean_best; /* Mrays/s */
    const char *best_api;                                /* the fastest raw_replay's */
} bench_table;

/* Loads scene `name` (bench_scene's fallback and in_list). Returns 0, 3 when its data is absent,
 * 1 on another error. */
static int bench_load_scene(const char *name, int fallback, int in_list, gib_scene *scene)
{
    gib_error err = {0};
    int rc = gib_scene_load(name, scene, &err);
    if (rc == GIB_SCENE_UNAVAILABLE && fallback) {
        fprintf(stderr, "gibench bench: sponza unavailable (%s); using cornell\n", err.msg);
        rc = gib_scene_load("cornell", scene, &err);
    }
    if (rc < 0) {
        if (rc == GIB_SCENE_UNAVAILABLE && in_list)
            fprintf(stderr, "gibench bench: skipping scene '%s': %s\n", name, err.msg);
        else
            fprintf(stderr, "gibench bench: %s\n", err.msg);
        return rc == GIB_SCENE_UNAVAILABLE ? 3 : 1;
    }
    return 0;
}

/* The raw figures and the fastest replays among the rows. */
static void bench_find_yardsticks(bench_table *t)
{
    t->raw_random = t->raw_diffuse = t->raw_best = t->lean_best = 0.0;
    t->best_api = "";
    for (int i = 0; i < t->n; i++) {
        const gib_ref_bench_row *r = &t->rows[i];
        if (!strcmp(r->measure, "raw_random"))
            t->raw_random = r->mrays_per_s;
        if (!strcmp(r->measure, "raw_diffuse"))
            t->raw_diffuse = r->mrays_per_s;
        if (!strcmp(r->measure, "raw_replay") && r->mrays_per_s > t->raw_best) {
            t->raw_best = r->mrays_per_s;
            t->best_api = r->api;
        }
        if (!strcmp(r->measure, "lean_replay") && r->mrays_per_s > t->lean_best)
            t->lean_best = r->mrays_per_s;
    }
}

/* Every row printed, and written to f when there is one. */
static void bench_print_rows(const bench_table *t, FILE *f)
{
    const gib_scene *scene = t->scene;
    const gib_ref_params *p = t->p;
    printf("scene %s (%u triangles), %s %dx%d at %d spp, %ld cores, %s\n", scene->name,
           scene->triangle_count, t->comp, p->width, p->height, p->spp, t->cores, t->machine);
    for (int i = 0; i < t->n; i++) {
        const gib_ref_bench_row *r = &t->rows[i];
        double a = t->raw_random > 0 ? r->mrays_per_s / t->raw_random : 0.0;
        /* best replay: the lean tracer's rows against the replay of its own rays */
        double best = strncmp(r->measure, "lean_", 5) ? t->raw_best : t->lean_best;
        double b = best > 0 ? r->mrays_per_s / best : 0.0;
        double c = t->raw_diffuse > 0 ? r->mrays_per_s / t->raw_diffuse : 0.0;
        printf("  %-18s %-15s %11lld rays %8.3f s %8.2f Mrays/s  %5.2fx raw random  %5.2fx best "
               "replay  paired %.3f [%.3f, %.3f]\n",
               r->measure, r->api, r->rays, r->seconds, r->mrays_per_s, a, b, r->paired_median,
               r->paired_min, r->paired_max);
        if (f)
            fprintf(f,
                    "%s,%u,%s,%d,%d,%d,%ld,%s,%d.%d.%d,%s,%s,%lld,%.6f,%.4f,%.4f,%.4f,%.4f,%d,"
                    "%.6f,%.6f,%.4f,%.4f,%.4f\n",
                    scene->name, scene->triangle_count, t->comp, p->width, p->height, p->spp,
                    t->cores, t->machine, RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH,
                    r->measure, r->api, r->rays, r->seconds, r->mrays_per_s, a, c, b, r->repeats,
                    r->seconds_median, r->seconds_max, r->paired_median, r->paired_min,
                    r->paired_max);
    }
    if (f)
        fflush(f);
    printf("fastest API on the replayed path-tracer rays: %s\n", t->best_api);
}

/* The path tracer's row read against the others, and kept in *sum (when given). */
static void bench_print_path_tracer(const bench_table *t, bench_summary *sum)
{
    double embree_inside = 0.0, lean = 0.0;
    for (int i = 0; i < t->n; i++) {
        if (!strcmp(t->rows[i].measure, "path_tracer_embree"))
            embree_inside = t->rows[i].paired_median;
        if (!strcmp(t->rows[i].measure, "lean_tracer"))
            lean = t->rows[i].paired_median;
    }
    for (int i = 0; i < t->n; i++) {
        const gib_ref_bench_row *r = &t->rows[i];
        if (strcmp(r->measure, "path_tracer"))
            continue;
        printf("path tracer against the fastest replay: %.3f, the median of %d paired repeats "
               "(range %.3f to %.3f); best against best %.3f; against diffuse rays %.3f, "
               "bounding-box rays %.3f\n",
               r->paired_median, r->repeats, r->paired_min, r->paired_max,
               t->raw_best > 0 ? r->mrays_per_s / t->raw_best : 0.0,
               t->raw_diffuse > 0 ? r->mrays_per_s / t->raw_diffuse : 0.0,
               t->raw_random > 0 ? r->mrays_per_s / t->raw_random : 0.0);
        printf("Embree inside the path tracer runs at %.3f of its speed alone on the same rays "
               "(paired median)\n", embree_inside);
        if (lean > 0.0)
            printf("lean tracer (the same kind of paths, almost no other work) against the replay "
                   "of its own rays: %.3f (paired median); the path tracer reaches %.2f of it\n",
                   lean, r->paired_median / lean);
        else
            printf("lean tracer: not run (it traces `full`'s paths on scenes without a sky or "
                   "mirrors only)\n");
        if (sum) {
            sum->embree_inside = embree_inside;
            sum->lean = lean;
            snprintf(sum->scene, sizeof sum->scene, "%s", t->scene->name);
            sum->triangles = t->scene->triangle_count;
            sum->mrays = r->mrays_per_s;
            sum->paired_median = r->paired_median;
            sum->paired_min = r->paired_min;
            sum->paired_max = r->paired_max;
        }
    }
}

/* Benchmarks one scene and writes its rows to f (NULL: print only). fallback: an absent sponza
 * is replaced by the built-in cornell (the default scene); in_list: an absent scene is skipped
 * with a message. Returns 0, 3 when the scene's data is absent, 1 on another error. */
static int bench_scene(const char *name, int fallback, int in_list, const gib_ref_params *p,
                       const char *comp, int repeat, FILE *f, bench_summary *sum)
{
    gib_error err = {0};
    gib_scene scene;
    int rc = bench_load_scene(name, fallback, in_list, &scene);
    if (rc)
        return rc;
    gib_ref_bench_row rows[24];
    int n = gib_reference_bench(&scene, p, repeat, stderr, rows, 24, &err);
    if (n < 0) {
        /* the library's own messages begin "bench: "; the renderer's "reference: " */
        fprintf(stderr, "gibench %s%s\n", strncmp(err.msg, "bench: ", 7) ? "bench: " : "",
                err.msg);
        gib_scene_free(&scene);
        return 1;
    }
    bench_table t = {.scene = &scene, .p = p, .comp = comp, .rows = rows, .n = n};
    gib_bench_machine_name(t.machine, sizeof t.machine);
    t.cores = p->threads > 0 ? p->threads : sysconf(_SC_NPROCESSORS_ONLN);
    bench_find_yardsticks(&t);
    bench_print_rows(&t, f);
    bench_print_path_tracer(&t, sum);
    gib_scene_free(&scene);
    return 0;
}

/* ---- --efficiency: error per second, by sampler ---- */

typedef struct eff_opts {
    int w, h, truth_spp, repeat, threads;
    int spp[8], nspp;
    int sampler[2], nsampler;
    int comp[GIB_COMP_COUNT], ncomp;
} eff_opts;

static int eff_render(const gib_scene *sc, int comp, int spp, int sampler, uint64_t seed,
                      const eff_opts *o, gib_image *img, gib_ref_stats *st)
{
    gib_error err = {0};
    gib_ref_params p = {.component = comp, .width = o->w, .height = o->h, .spp = spp,
                        .seed = seed, .sampler = sampler, .threads = o->threads, .quiet = 1};
    if (gib_reference_render(sc, &p, img, NULL, st, &err) < 0) {
        fprintf(stderr, "gibench bench: %s %s: %s\n", sc->name, gib_component_name(comp), err.msg);
        return -1;
    }
    return 0;
}

static int eff_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* One scene and component: its truth and where the rows go. */
typedef struct eff_case {
    const gib_scene *sc;
    int comp;
    const eff_opts *o;
    gib_image truth;
    gib_ref_stats ts;
    FILE *f;
    const char *machine;
    long cores;
} eff_case;

/* Each sampler's renders at one spp: their mean squared error, their reported noise, their
 * seconds and the spp they reached. */
typedef struct eff_renders {
    double secs[2][GIB_REF_BENCH_MAX_REPEATS], err2[2], pred2[2];
    int spp_done[2];
} eff_renders;

/* The samplers' repeats at spp, alternating, so both ran under the machine's same load. */
static int eff_render_all(const eff_case *c, int spp, eff_renders *er)
{
    const eff_opts *o = c->o;
    const size_t n = (size_t)o->w * o->h * 3;
    memset(er, 0, sizeof *er);
    for (int r = 0; r < o->repeat; r++)
        for (int si = 0; si < o->nsampler; si++) {
            gib_image img;
            gib_ref_stats st;
            if (eff_render(c->sc, c->comp, spp, o->sampler[si], (uint64_t)r + 1, o, &img, &st) < 0)
                return -1;
            double e2 = 0.0;
            for (size_t i = 0; i < n; i++) {
                double d = (double)img.px[i] - c->truth.px[i];
                e2 += d * d;
            }
            er->err2[si] += e2 / (double)n / o->repeat;
            er->pred2[si] += st.noise_rmse * st.noise_rmse / o->repeat;
            er->secs[si][r] = st.render_seconds;
            er->spp_done[si] = st.spp;
            gib_image_free(&img);
        }
    return 0;
}

/* Each sampler's row at one spp: printed, and written to f when there is one. */
static void eff_rows(const eff_case *c, eff_renders *er)
{
    const eff_opts *o = c->o;
    const double tvar = c->ts.noise_rmse * c->ts.noise_rmse, m2 = c->ts.mean * c->ts.mean;
    double eff_random = 0.0;
    for (int si = 0; si < o->nsampler; si++) {
        const int smp = o->sampler[si];
        double *sv = er->secs[si], pred2 = er->pred2[si];
        qsort(sv, (size_t)o->repeat, sizeof *sv, eff_cmp);
        double t = o->repeat % 2 ? sv[o->repeat / 2]
                                 : 0.5 * (sv[o->repeat / 2 - 1] + sv[o->repeat / 2]);
        double var = er->err2[si] - tvar; /* the truth's own noise removed */
        double rel = m2 > 0.0 ? var / m2 : var;
        double prel = m2 > 0.0 ? pred2 / m2 : pred2;
        double eff = var > 0.0 && t > 0.0 ? 1.0 / (rel * t) : INFINITY;
        double peff = pred2 > 0.0 && t > 0.0 ? 1.0 / (prel * t) : INFINITY;
        double honest = var > 0.0 ? sqrt(pred2 / var) : INFINITY;
        if (smp == GIB_REF_SAMPLER_RANDOM)
            eff_random = eff;
        double vs = eff_random > 0.0 ? eff / eff_random : 0.0;
        printf("  %-6s %5d spp: %.3f s (median of %d), relative RMSE %.4g, efficiency "
               "%.4g /s (reported noise's: %.4g, reported/actual error %.3f)%s",
               gib_ref_sampler_name(smp), er->spp_done[si], t, o->repeat,
               sqrt(fmax(rel, 0.0)), eff, peff, honest,
               vs > 0.0 && smp != GIB_REF_SAMPLER_RANDOM ? "" : "\n");
        if (vs > 0.0 && smp != GIB_REF_SAMPLER_RANDOM)
            printf("; %.2fx random's\n", vs);
        if (c->f)
            fprintf(c->f,
                    "%s,%u,%s,%d,%d,%d,%d,%ld,%s,%s,%d,%.6f,%.6f,%.9g,%.9g,%.9g,%.6f,"
                    "%.6g,%.6g,%.4f\n",
                    c->sc->name, c->sc->triangle_count, gib_component_name(c->comp), o->w, o->h,
                    er->spp_done[si], c->ts.spp, c->cores, c->machine, gib_ref_sampler_name(smp),
                    o->repeat, t, sv[o->repeat - 1], c->ts.mean, sqrt(fmax(rel, 0.0)),
                    sqrt(prel), honest, eff, peff, vs);
    }
}

/* One component: its truth, then every sampler and spp. Returns 0, or -1 after a message. */
static int eff_component(eff_case *c)
{
    const eff_opts *o = c->o;
    if (eff_render(c->sc, c->comp, o->truth_spp, GIB_REF_SAMPLER_SOBOL, 1000, o, &c->truth,
                   &c->ts) < 0)
        return -1;
    printf("%s %s %dx%d: truth %d spp (sobol) in %.1f s, mean %.6g, its noise %.3g\n",
           c->sc->name, gib_component_name(c->comp), o->w, o->h, c->ts.spp, c->ts.render_seconds,
           c->ts.mean, c->ts.noise_rmse);
    for (int k = 0; k < o->nspp; k++) {
        eff_renders er;
        if (eff_render_all(c, o->spp[k], &er) < 0) {
            gib_image_free(&c->truth);
            return -1;
        }
        eff_rows(c, &er);
    }
    if (c->f)
        fflush(c->f);
    gib_image_free(&c->truth);
    return 0;
}

/* One scene: every component, sampler and spp; rows to f. Returns 0, 3 (data absent), 1. */
static int eff_scene(const char *name, const eff_opts *o, FILE *f, const char *machine)
{
    gib_error err = {0};
    gib_scene sc;
    int rc = gib_scene_load(name, &sc, &err);
    if (rc < 0) {
        fprintf(stderr, "gibench bench: %s scene '%s': %s\n",
                rc == GIB_SCENE_UNAVAILABLE ? "skipping" : "cannot load", name, err.msg);
        return rc == GIB_SCENE_UNAVAILABLE ? 3 : 1;
    }
    long cores = o->threads > 0 ? o->threads : sysconf(_SC_NPROCESSORS_ONLN);
    for (int ci = 0; ci < o->ncomp; ci++) {
        eff_case c = {.sc = &sc, .comp = o->comp[ci], .o = o, .f = f, .machine = machine,
                      .cores = cores};
        if (eff_component(&c) < 0) {
            gib_scene_free(&sc);
            return 1;
        }
    }
    gib_scene_free(&sc);
    return 0;
}

/* Splits a comma list into ints parsed by parse(); returns the count or -1. */
static int eff_list(const char *opt, const char *v, int *out, int max, int (*parse)(const char *))
{
    char buf[256];
    int n = 0;
    if (snprintf(buf, sizeof buf, "%s", v) >= (int)sizeof buf)
        return -1;
    for (char *save = NULL, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        int x = parse(t);
        if (x < 0 || n >= max) {
            fprintf(stderr, "gibench bench: %s: '%s' %s\n", opt, t,
                    x < 0 ? "not understood" : "one too many");
            return -1;
        }
        out[n++] = x;
    }
    if (n == 0)
        fprintf(stderr, "gibench bench: %s: empty list\n", opt);
    return n > 0 ? n : -1;
}

static int eff_parse_spp(const char *t)
{
    char *end;
    long v = strtol(t, &end, 10);
    return *end || v < 2 || v > (1 << 20) ? -1 : (int)v;
}

/* The CSV of a bench is written to OUT.part and renamed over OUT once a scene has its rows: a run
 * where no scene could be measured leaves an earlier file of that name as it was. Opens it with
 * its header line into *f (NULL without --out); returns 0, or the exit status after a message. */
static int part_open(const char *out, char *part, size_t cap, const char *header, FILE **f)
{
    *f = NULL;
    if (!out)
        return 0;
    if (snprintf(part, cap, "%s.part", out) >= (int)cap) {
        fprintf(stderr, "gibench bench: --out path too long (%zu characters)\n", strlen(out));
        return 2;
    }
    if (!(*f = fopen(part, "w"))) {
        fprintf(stderr, "gibench bench: cannot write %s\n", part);
        return 1;
    }
    fputs(header, *f);
    return 0;
}

/* Closes f and renames part over out when ran > 0 scenes gave rows (else removes it). Returns 0,
 * or -1 after a message when writing or renaming failed. */
static int part_finish(FILE *f, const char *part, const char *out, int ran)
{
    int werr = ferror(f);
    if (fclose(f) != 0 || werr) {
        fprintf(stderr, "gibench bench: writing %s failed\n", part);
        remove(part);
        return -1;
    }
    if (ran == 0) {
        remove(part);
        return 0;
    }
    if (rename(part, out) != 0) {
        fprintf(stderr, "gibench bench: cannot rename %s to %s\n", part, out);
        return -1;
    }
    printf("-> %s\n", out);
    return 0;
}

static int eff_run(const char *scenes, const eff_opts *o, const char *out)
{
    char machine[256], list[1024], part[4096];
    gib_bench_machine_name(machine, sizeof machine);
    snprintf(list, sizeof list, "%s", scenes);
    FILE *f;
    int st = part_open(out, part, sizeof part,
                       "scene,triangles,component,width,height,spp,truth_spp,cores,machine,"
                       "sampler,repeats,seconds_median,seconds_max,truth_mean,rel_rmse_actual,"
                       "rel_noise_reported,reported_over_actual,efficiency,efficiency_reported,"
                       "efficiency_vs_random\n", &f);
    if (st)
        return st;
    int ran = 0, failed = 0;
    for (char *save = NULL, *name = strtok_r(list, ",", &save); name;
         name = strtok_r(NULL, ",", &save)) {
        int rc = eff_scene(name, o, f, machine);
        ran += rc == 0;
        failed += rc == 1;
    }
    if (f && part_finish(f, part, out, ran) < 0)
        return 1;
    if (f && ran == 0)
        return 3;
    return failed ? 1 : ran ? 0 : 3;
}

/* What the command line asks for (NULL: the mode's default). */
typedef struct bench_opts {
    const char *scene_name, *size, *out, *comp, *samplers, *spps;
    long spp, threads, repeat, truth_spp;
    int efficiency;
} bench_opts;

#define PROCEED GIB_OPTIONS_PROCEED /* bench_parse_args: go on (else the exit status) */

/* The options after `reference`. */
static int bench_parse_args(int argc, char **argv, bench_opts *o)
{
    const gib_option opts[] = {
        GIB_OPTION_FLAG("--efficiency", &o->efficiency, "efficiency against a truth image"),
        GIB_OPTION_TEXT("--scene", &o->scene_name, "S[,S...]", "the scenes"),
        GIB_OPTION_TEXT("--size", &o->size, "WxH", "the image size"),
        GIB_OPTION_TEXT("--component", &o->comp, "C[,C...]", "the components"),
        GIB_OPTION_TEXT("--spp", &o->spps, "N[,N...]", "samples per pixel"),
        GIB_OPTION_TEXT("--sampler", &o->samplers, "random,sobol", "--efficiency's samplers"),
        GIB_OPTION_INT("--truth-spp", &o->truth_spp, 2, 1 << 20, "N", "the truth image's samples"),
        GIB_OPTION_INT("--threads", &o->threads, 0, 1024, "N", "0: every core"),
        GIB_OPTION_INT("--repeat", &o->repeat, 1, 100, "N", "rounds (default 3)"),
        GIB_OPTION_TEXT("--out", &o->out, "F.csv", "write the rows here"),
        {0}};
    return gib_options_parse(&doc, opts, argc - 1, argv + 1, NULL, NULL, 0);
}

/* --efficiency: its lists, then its scenes. Returns the exit status. */
static int bench_efficiency(const bench_opts *b)
{
    gib_error err = {0};
    eff_opts o = {.truth_spp = (int)b->truth_spp, .repeat = (int)b->repeat,
                  .threads = (int)b->threads};
    if (gib_parse_size("--size", b->size ? b->size : "128x128", &o.w, &o.h, &err) < 0) {
        fprintf(stderr, "gibench bench: %s\n", err.msg);
        return 2;
    }
    if ((o.nspp = eff_list("--spp", b->spps ? b->spps : "16,64", o.spp, 8, eff_parse_spp)) < 0 ||
        (o.nsampler = eff_list("--sampler", b->samplers, o.sampler, 2, gib_ref_sampler_parse)) <
            0 ||
        (o.ncomp = eff_list("--component", b->comp ? b->comp : "full,indirect", o.comp,
                            GIB_COMP_COUNT, gib_component_parse)) < 0)
        return 2;
    return eff_run(b->scene_name ? b->scene_name : "cornell,sibenik,sponza", &o, b->out);
}

/* The throughput run's parameters and scene list from the options. Returns PROCEED or the exit
 * status. */
static int bench_throughput_args(const bench_opts *o, gib_ref_params *p, char *list, size_t cap)
{
    gib_error err = {0};
    const char *size = o->size ? o->size : "256x256", *comp = o->comp ? o->comp : "full";
    long spp = o->spp;
    if (o->spps && gib_parse_int("--spp", o->spps, 2, 1 << 20, &spp, &err) < 0) {
        fprintf(stderr, "gibench bench: %s\n", err.msg);
        return 2;
    }
    if (strcmp(o->samplers, "random,sobol") != 0) {
        fprintf(stderr, "gibench bench: --sampler goes with --efficiency\n");
        return 2;
    }
    int w, h, component = gib_component_parse(comp);
    if (component < 0) {
        fprintf(stderr, "gibench bench: unknown component '%s'\n", comp);
        return 2;
    }
    if (gib_parse_size("--size", size, &w, &h, &err) < 0) {
        fprintf(stderr, "gibench bench: %s\n", err.msg);
        return 2;
    }
    const char *sn = o->scene_name;
    if (sn && (strlen(sn) >= cap || !sn[strspn(sn, ",")])) {
        fprintf(stderr, "gibench bench: --scene '%.60s%s': %s\n", sn, strlen(sn) > 60 ? "..." : "",
                strlen(sn) >= cap ? "list too long" : "names no scene");
        return 2;
    }
    snprintf(list, cap, "%s", sn ? sn : "sponza");
    *p = (gib_ref_params){.component = component, .width = w, .height = h, .spp = (int)spp,
                          .seed = 1, .threads = (int)o->threads, .quiet = 1};
    return PROCEED;
}

/* The table of a multi-scene run: each scene's path tracer against its replay. */
static void bench_print_summary(const bench_summary *sum, int nsum)
{
    printf("path tracer against the fastest replay of its own rays, by scene (paired "
           "median [least, greatest]; Embree's speed inside it; the lean tracer's ratio):\n");
    for (int i = 0; i < nsum; i++) {
        char lean[16] = "n/a";
        if (sum[i].lean > 0.0)
            snprintf(lean, sizeof lean, "%.3f", sum[i].lean);
        printf("  %-12s %9u triangles  %6.2f Mrays/s  %.3f [%.3f, %.3f]  Embree %.3f  "
               "lean %s\n",
               sum[i].scene, sum[i].triangles, sum[i].mrays, sum[i].paired_median,
               sum[i].paired_min, sum[i].paired_max, sum[i].embree_inside, lean);
    }
}

/* The throughput benchmark over the scene list. Returns the exit status. */
static int bench_throughput(const bench_opts *o)
{
    char list[1024];
    gib_ref_params p;
    int st = bench_throughput_args(o, &p, list, sizeof list);
    if (st != PROCEED)
        return st;
    const char *comp = o->comp ? o->comp : "full";
    char part[4096];
    FILE *f;
    st = part_open(o->out, part, sizeof part,
                   "scene,triangles,component,width,height,spp,cores,machine,embree,measure,"
                   "api,rays,seconds,mrays_per_s,vs_raw_random,vs_raw_diffuse,"
                   "vs_raw_replay_best,repeats,seconds_median,seconds_max,"
                   "vs_replay_paired_median,vs_replay_paired_min,vs_replay_paired_max\n", &f);
    if (st)
        return st;
    /* Scenes one after another, each row written as soon as its scene is done: a scene that
     * fails keeps the others' rows. In a list, a scene whose data is absent is skipped. */
    int nlist = 1, ran = 0, failed = 0, unavailable = 0;
    for (const char *c = list; *c; c++)
        nlist += *c == ',';
    bench_summary sum[64];
    int nsum = 0;
    for (char *save = NULL, *name = strtok_r(list, ",", &save); name;
         name = strtok_r(NULL, ",", &save)) {
        int rc = bench_scene(name, !o->scene_name, nlist > 1, &p, comp, (int)o->repeat, f,
                             nsum < 64 ? &sum[nsum] : NULL);
        if (rc == 0) {
            ran++;
            nsum += nsum < 64;
        } else if (rc == 3) {
            unavailable++;
        } else {
            failed++;
        }
    }
    if (f && part_finish(f, part, o->out, ran) < 0)
        return 1;
    if (nsum > 1)
        bench_print_summary(sum, nsum);
    if (failed > 0)
        return 1;
    if (ran == 0)
        return unavailable > 0 ? 3 : 1;
    return 0;
}

int gib_cmd_bench(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "scoring") == 0)
        return gib_bench_scoring(argc - 1, argv + 1);
    if (argc >= 2 && strcmp(argv[1], "references") == 0)
        return gib_bench_references(argc - 1, argv + 1);
    if (argc < 2 || strcmp(argv[1], "reference") != 0) {
        if (argc >= 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
            gib_options_usage(stdout, &doc, NULL);
            puts("\ngibench bench scoring --help: the scoring of a row, by thread count.");
            puts("gibench bench references --help: a profile's references, one at a time and "
                 "each view's together.");
            return 0;
        }
        fputs("gibench bench: what to measure? ('reference' or 'scoring')\n", stderr);
        gib_options_usage(stderr, &doc, NULL);
        return 2;
    }
    bench_opts o = {.samplers = "random,sobol", .spp = 16, .repeat = 3, .truth_spp = 2048};
    int rc = bench_parse_args(argc, argv, &o);
    if (rc != PROCEED)
        return rc;
    return o.efficiency ? bench_efficiency(&o) : bench_throughput(&o);
}

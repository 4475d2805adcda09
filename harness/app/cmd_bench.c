/* gibench bench reference — the reference renderer's ray throughput against raw Embree
 * (reference/ref_bench.c), printed and written to CSV with the machine it ran on. Performance is
 * measured and reported here, never asserted by a test. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <embree3/rtcore_config.h>
#include <sys/utsname.h>
#include <unistd.h>

#include "app.h"

static const char help[] =
    "usage: gibench bench reference [--scene S[,S...]] [--size WxH] [--component C] [--spp N]\n"
    "                               [--threads N] [--repeat N] [--out F.csv]\n"
    "\n"
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
    "(both sides of a pair ran under the same load).\n";

static void machine_name(char *out, size_t len)
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

/* Benchmarks one scene and writes its rows to f (NULL: print only). fallback: an absent sponza
 * is replaced by the built-in cornell (the default scene); in_list: an absent scene is skipped
 * with a message. Returns 0, 3 when the scene's data is absent, 1 on another error. */
static int bench_scene(const char *name, int fallback, int in_list, const gib_ref_params *p,
                       const char *comp, int repeat, FILE *f, bench_summary *sum)
{
    gib_error err = {{0}};
    gib_scene scene;
    int rc = gib_scene_load(name, &scene, &err);
    if (rc == GIB_SCENE_UNAVAILABLE && fallback) {
        fprintf(stderr, "gibench bench: sponza unavailable (%s); using cornell\n", err.msg);
        rc = gib_scene_load("cornell", &scene, &err);
    }
    if (rc < 0) {
        if (rc == GIB_SCENE_UNAVAILABLE && in_list)
            fprintf(stderr, "gibench bench: skipping scene '%s': %s\n", name, err.msg);
        else
            fprintf(stderr, "gibench bench: %s\n", err.msg);
        return rc == GIB_SCENE_UNAVAILABLE ? 3 : 1;
    }
    gib_ref_bench_row rows[24];
    int n = gib_reference_bench(&scene, p, repeat, stderr, rows, 24, &err);
    if (n < 0) {
        /* the library's own messages begin "bench: "; the renderer's "reference: " */
        fprintf(stderr, "gibench %s%s\n", strncmp(err.msg, "bench: ", 7) ? "bench: " : "",
                err.msg);
        gib_scene_free(&scene);
        return 1;
    }
    char machine[256];
    machine_name(machine, sizeof machine);
    long cores = p->threads > 0 ? p->threads : sysconf(_SC_NPROCESSORS_ONLN);
    double raw_random = 0.0, raw_diffuse = 0.0, raw_best = 0.0, lean_best = 0.0;
    const char *best_api = "";
    for (int i = 0; i < n; i++) {
        if (!strcmp(rows[i].measure, "raw_random"))
            raw_random = rows[i].mrays_per_s;
        if (!strcmp(rows[i].measure, "raw_diffuse"))
            raw_diffuse = rows[i].mrays_per_s;
        if (!strcmp(rows[i].measure, "raw_replay") && rows[i].mrays_per_s > raw_best) {
            raw_best = rows[i].mrays_per_s;
            best_api = rows[i].api;
        }
        if (!strcmp(rows[i].measure, "lean_replay") && rows[i].mrays_per_s > lean_best)
            lean_best = rows[i].mrays_per_s;
    }
    printf("scene %s (%u triangles), %s %dx%d at %d spp, %ld cores, %s\n", scene.name,
           scene.triangle_count, comp, p->width, p->height, p->spp, cores, machine);
    for (int i = 0; i < n; i++) {
        const gib_ref_bench_row *r = &rows[i];
        double a = raw_random > 0 ? r->mrays_per_s / raw_random : 0.0;
        /* best replay: the lean tracer's rows against the replay of its own rays */
        double best = strncmp(r->measure, "lean_", 5) ? raw_best : lean_best;
        double b = best > 0 ? r->mrays_per_s / best : 0.0;
        double c = raw_diffuse > 0 ? r->mrays_per_s / raw_diffuse : 0.0;
        printf("  %-18s %-15s %11lld rays %8.3f s %8.2f Mrays/s  %5.2fx raw random  %5.2fx best "
               "replay  paired %.3f [%.3f, %.3f]\n",
               r->measure, r->api, r->rays, r->seconds, r->mrays_per_s, a, b, r->paired_median,
               r->paired_min, r->paired_max);
        if (f)
            fprintf(f,
                    "%s,%u,%s,%d,%d,%d,%ld,%s,%d.%d.%d,%s,%s,%lld,%.6f,%.4f,%.4f,%.4f,%.4f,%d,"
                    "%.6f,%.6f,%.4f,%.4f,%.4f\n",
                    scene.name, scene.triangle_count, comp, p->width, p->height, p->spp, cores,
                    machine, RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH, r->measure,
                    r->api, r->rays, r->seconds, r->mrays_per_s, a, c, b, r->repeats,
                    r->seconds_median, r->seconds_max, r->paired_median, r->paired_min,
                    r->paired_max);
    }
    if (f)
        fflush(f);
    printf("fastest API on the replayed path-tracer rays: %s\n", best_api);
    double embree_inside = 0.0, lean = 0.0;
    for (int i = 0; i < n; i++) {
        if (!strcmp(rows[i].measure, "path_tracer_embree"))
            embree_inside = rows[i].paired_median;
        if (!strcmp(rows[i].measure, "lean_tracer"))
            lean = rows[i].paired_median;
    }
    for (int i = 0; i < n; i++) {
        if (strcmp(rows[i].measure, "path_tracer"))
            continue;
        printf("path tracer against the fastest replay: %.3f, the median of %d paired repeats "
               "(range %.3f to %.3f); best against best %.3f; against diffuse rays %.3f, "
               "bounding-box rays %.3f\n",
               rows[i].paired_median, rows[i].repeats, rows[i].paired_min, rows[i].paired_max,
               raw_best > 0 ? rows[i].mrays_per_s / raw_best : 0.0,
               raw_diffuse > 0 ? rows[i].mrays_per_s / raw_diffuse : 0.0,
               raw_random > 0 ? rows[i].mrays_per_s / raw_random : 0.0);
        printf("Embree inside the path tracer runs at %.3f of its speed alone on the same rays "
               "(paired median)\n", embree_inside);
        if (lean > 0.0)
            printf("lean tracer (the same kind of paths, almost no other work) against the replay "
                   "of its own rays: %.3f (paired median); the path tracer reaches %.2f of it\n",
                   lean, rows[i].paired_median / lean);
        else
            printf("lean tracer: not run (it traces `full`'s paths on scenes without a sky or "
                   "mirrors only)\n");
        if (sum) {
            sum->embree_inside = embree_inside;
            sum->lean = lean;
            snprintf(sum->scene, sizeof sum->scene, "%s", scene.name);
            sum->triangles = scene.triangle_count;
            sum->mrays = rows[i].mrays_per_s;
            sum->paired_median = rows[i].paired_median;
            sum->paired_min = rows[i].paired_min;
            sum->paired_max = rows[i].paired_max;
        }
    }
    gib_scene_free(&scene);
    return 0;
}

int gib_cmd_bench(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "reference") != 0) {
        if (argc >= 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
            fputs(help, stdout);
            return 0;
        }
        fprintf(stderr, "gibench bench: what to measure? ('reference')\n%s", help);
        return 2;
    }
    const char *scene_name = NULL, *size = "256x256", *out = NULL, *comp = "full";
    long spp = 16, threads = 0, repeat = 3;
    gib_error err = {{0}};
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(help, stdout);
            return 0;
        }
        if (!v) {
            fprintf(stderr, "gibench bench: option %s needs a value\n%s", a, help);
            return 2;
        }
        i++;
        int rc = 0;
        if (!strcmp(a, "--scene")) scene_name = v;
        else if (!strcmp(a, "--size")) size = v;
        else if (!strcmp(a, "--out")) out = v;
        else if (!strcmp(a, "--component")) comp = v;
        else if (!strcmp(a, "--spp")) rc = gib_parse_int(a, v, 2, 1 << 20, &spp, &err);
        else if (!strcmp(a, "--threads")) rc = gib_parse_int(a, v, 0, 1024, &threads, &err);
        else if (!strcmp(a, "--repeat")) rc = gib_parse_int(a, v, 1, 100, &repeat, &err);
        else {
            fprintf(stderr, "gibench bench: unknown option '%s'\n%s", a, help);
            return 2;
        }
        if (rc < 0) {
            fprintf(stderr, "gibench bench: %s\n", err.msg);
            return 2;
        }
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
    char list[1024];
    if (scene_name && (strlen(scene_name) >= sizeof list || !scene_name[strspn(scene_name, ",")])) {
        fprintf(stderr, "gibench bench: --scene '%.60s%s': %s\n", scene_name,
                strlen(scene_name) > 60 ? "..." : "",
                strlen(scene_name) >= sizeof list ? "list too long" : "names no scene");
        return 2;
    }
    snprintf(list, sizeof list, "%s", scene_name ? scene_name : "sponza");
    gib_ref_params p = {.component = component, .width = w, .height = h, .spp = (int)spp,
                        .seed = 1, .threads = (int)threads, .quiet = 1};
    /* Written beside --out and renamed over it once a scene has its rows: a run where no scene
     * could be measured leaves an earlier file of that name as it was. */
    char part[4096];
    if (snprintf(part, sizeof part, "%s.part", out ? out : "") >= (int)sizeof part) {
        fprintf(stderr, "gibench bench: --out path too long (%zu characters)\n", strlen(out));
        return 2;
    }
    FILE *f = out ? fopen(part, "w") : NULL;
    if (out && !f) {
        fprintf(stderr, "gibench bench: cannot write %s\n", part);
        return 1;
    }
    if (f)
        fprintf(f, "scene,triangles,component,width,height,spp,cores,machine,embree,measure,api,"
                   "rays,seconds,mrays_per_s,vs_raw_random,vs_raw_diffuse,vs_raw_replay_best,"
                   "repeats,seconds_median,seconds_max,vs_replay_paired_median,"
                   "vs_replay_paired_min,vs_replay_paired_max\n");
    /* Scenes one after another, each row written as soon as its scene is done: a scene that
     * fails keeps the others' rows. In a list, a scene whose data is absent is skipped. */
    int nlist = 1, ran = 0, failed = 0, unavailable = 0;
    for (const char *c = list; *c; c++)
        nlist += *c == ',';
    bench_summary sum[64];
    int nsum = 0;
    for (char *save = NULL, *name = strtok_r(list, ",", &save); name;
         name = strtok_r(NULL, ",", &save)) {
        int rc = bench_scene(name, !scene_name, nlist > 1, &p, comp, (int)repeat, f,
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
    if (f) {
        int werr = ferror(f);
        if (fclose(f) != 0 || werr) {
            fprintf(stderr, "gibench bench: writing %s failed\n", part);
            remove(part);
            return 1;
        }
        if (ran == 0) {
            remove(part);
        } else if (rename(part, out) != 0) {
            fprintf(stderr, "gibench bench: cannot rename %s to %s\n", part, out);
            return 1;
        } else {
            printf("-> %s\n", out);
        }
    }
    if (nsum > 1) {
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
    if (failed > 0)
        return 1;
    if (ran == 0)
        return unavailable > 0 ? 3 : 1;
    return 0;
}

/* gibench bench references — what a matrix profile's references cost rendered one request at a
 * time (gib_reference_render each, as runs asked before) against each world's requests together
 * (gib_reference_render_set, as `gibench run` now renders a scene's references when it first
 * loads it, for that matrix and the later ones of the run: refset.h, cmd_run.c). The requests are
 * those the runs ask first (each output at its matrix's spp, one per cache key), gathered per
 * scene over every matrix and grouped by instant (one world); a set of one request is rendered
 * once and counted on both sides. One CSV row per set and a total row: seconds each way (the least
 * of --repeat rounds, the world's build included), the noise RMSE each way, and whether every
 * image came out bit for bit the same. Performance is measured here, never asserted by a test. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "app.h"
#include "bench_scoring.h"
#include "options.h"
#include "refset.h"

static const gib_command_doc doc = {
    "bench", "references MATRIX... [--profile P] [--out F.csv] [options]",
    "Renders the references the matrices' runs ask for first (profile P, default quick) two ways:\n"
    "one request at a time, and each scene's requests at one instant together (one world, one\n"
    "primary ray a pixel of each view; each image the same bits). Scenes whose data is absent are skipped. --repeat N\n"
    "rounds (default 1) keep each side's least time; --threads N (default every core).\n"};

#define BR_MAX_REQUESTS 1024

typedef struct br_total {
    char machine[256];
    long cores;
    int repeat, threads, sets, requests, differ;
    double each, together;
    FILE *csv;
} br_total;

static double br_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The images' pixels are the same bits. */
static int br_same(const gib_image *a, const gib_image *b)
{
    size_t n = (size_t)a->width * a->height * a->channels;
    return a->width == b->width && a->height == b->height && a->channels == b->channels &&
           memcmp(a->px, b->px, n * sizeof *a->px) == 0;
}

/* One set's requests both ways, its CSV row. 0, or -1 with err. */
static int br_set(br_total *t, const char *matrix, const gib_scene *scene,
                   const gib_ref_request *rq, int n, gib_error *err)
{
    gib_ref_params p[GIB_REF_SET_MAX];
    gib_image one[GIB_REF_SET_MAX] = {{0}}, set[GIB_REF_SET_MAX] = {{0}};
    gib_ref_stats st1[GIB_REF_SET_MAX], sts[GIB_REF_SET_MAX];
    double each = 1e300, together = 1e300;
    int rc = 0, same = 1;
    char comps[1024] = "";
    for (int k = 0; k < n; k++) {
        p[k] = gib_ref_request_params(&rq[k]);
        p[k].quiet = 1;
        p[k].threads = t->threads;
        snprintf(comps + strlen(comps), sizeof comps - strlen(comps), "%s%s:%d@%dx%d",
                 k ? "+" : "", gib_component_name(p[k].component), p[k].spp, p[k].width,
                 p[k].height);
    }
    for (int r = 0; r < t->repeat && rc == 0; r++) {
        double t0 = br_now();
        for (int k = 0; k < n && rc == 0; k++) {
            gib_image_free(&one[k]);
            rc = gib_reference_render(scene, &p[k], &one[k], NULL, &st1[k], err);
        }
        double t1 = br_now();
        for (int k = 0; k < n; k++)
            gib_image_free(&set[k]);
        if (rc == 0 && n > 1)
            rc = gib_reference_render_set(scene, p, n, set, NULL, sts, err);
        double t2 = br_now();
        each = t1 - t0 < each ? t1 - t0 : each;
        together = n > 1 ? (t2 - t1 < together ? t2 - t1 : together) : each;
    }
    double noise1 = 0.0, noises = 0.0; /* the largest of the set's images */
    for (int k = 0; rc == 0 && k < n; k++) {
        const gib_ref_stats *s = n > 1 ? &sts[k] : &st1[k];
        same = same && (n == 1 || br_same(&one[k], &set[k]));
        noise1 = st1[k].noise_rmse > noise1 ? st1[k].noise_rmse : noise1;
        noises = s->noise_rmse > noises ? s->noise_rmse : noises;
    }
    for (int k = 0; k < n; k++)
        gib_image_free(&one[k]), gib_image_free(&set[k]);
    if (rc < 0)
        return gib_error_prefix(err, "%s %s %s", matrix, scene->name, comps);
    t->sets++;
    t->requests += n;
    t->differ += !same;
    t->each += each;
    t->together += together;
    printf("%-40s %-15s t=%-4g each %7.2f s  together %7.2f s  %s  %s\n", matrix, scene->name,
           (double)p[0].time, each, together, same ? "same bits" : "IMAGES DIFFER", comps);
    fprintf(t->csv, "%s,%s,%ld,%d,%s,%s,%d,%g,%s,%d,%.4f,%.4f,%.4f,%.6g,%.6g,%d\n",
            gib_git_revision(), t->machine, t->cores, t->threads, matrix, scene->name,
            p[0].camera, (double)p[0].time, comps, n, each, together, each / together, noise1,
            noises, same);
    return 0;
}

typedef struct br_scene_ctx {
    br_total *t;
    const char *names;
    const gib_scene *scene;
    gib_error *err;
} br_scene_ctx;

/* gib_ref_each_set's step: one set both ways. */
static int br_each(void *ctx, const gib_ref_request *set, int k)
{
    br_scene_ctx *sc = ctx;
    return br_set(sc->t, sc->names, sc->scene, set, k, sc->err);
}

/* One scene: the requests of its runs in every matrix (the first to load it renders them all,
 * as `gibench run` does), one per key, world by world. */
static int br_scene(br_total *t, const gib_matrix *ms, int nm, const char *sname, gib_error *err)
{
    gib_scene scene;
    gib_error serr;
    if (gib_scene_load(sname, &scene, &serr) < 0) {
        printf("scene %s skipped: %s\n", sname, serr.msg);
        return 0;
    }
    int most = 1, n = 0, rc = 0;
    for (int i = 0; i < nm; i++)
        most = ms[i].run_count > most ? ms[i].run_count : most;
    char *want = calloc((size_t)most, 1), names[256] = "";
    gib_ref_request *rq = malloc(BR_MAX_REQUESTS * sizeof *rq);
    int *world = malloc(BR_MAX_REQUESTS * sizeof *world);
    uint64_t *key = malloc(BR_MAX_REQUESTS * sizeof *key);
    if (!want || !rq || !world || !key)
        rc = gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "bench references: out of memory");
    for (int i = 0; rc == 0 && i < nm; i++) {
        int before = n, got;
        for (int j = 0; j < ms[i].run_count; j++)
            want[j] = !strcmp(ms[i].runs[j].scene, sname) &&
                      gib_scene_wanted(&scene, ms[i].runs[j].technique, NULL, 0);
        got = gib_matrix_ref_requests(&ms[i], NULL, &scene, want, rq + n, BR_MAX_REQUESTS - n);
        for (int k = n; k < n + got; k++) { /* a key asked before is in the cache */
            gib_ref_params p = gib_ref_request_params(&rq[k]);
            uint64_t kk = gib_reference_cache_key(&scene, &p);
            int dup = 0;
            for (int j = 0; j < before && !dup; j++)
                dup = key[j] == kk;
            if (!dup)
                key[before] = kk, rq[before++] = rq[k];
        }
        if (before > n)
            snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s",
                     names[0] ? "+" : "", ms[i].name);
        n = before;
    }
    br_scene_ctx sc = {.t = t, .names = names, .scene = &scene, .err = err};
    if (rc == 0)
        rc = gib_ref_each_set(rq, n, world, gib_ref_worlds(rq, n, world), br_each, &sc);
    free(key);
    free(world);
    free(rq);
    free(want);
    gib_scene_free(&scene);
    return rc;
}

int gib_bench_references(int argc, char **argv)
{
    const char *profile = "quick", *out = NULL;
    long repeat = 1, threads = 0;
    const gib_option opts[] = {
        GIB_OPTION_TEXT("--profile", &profile, "P", "the matrices' profile (default quick)"),
        GIB_OPTION_TEXT("--out", &out, "F.csv", "write the rows here"),
        GIB_OPTION_INT("--repeat", &repeat, 1, 100, "N", "rounds (default 1)"),
        GIB_OPTION_INT("--threads", &threads, 0, 1024, "N", "0: every core"),
        {0}};
    const char *files[256];
    int nfiles = 0;
    int rc = gib_options_parse(&doc, opts, argc, argv, files, &nfiles, 256);
    if (rc != GIB_OPTIONS_PROCEED)
        return rc;
    if (nfiles == 0) {
        fputs("gibench bench references: name the matrices (harness/matrices/*.matrix)\n", stderr);
        return 2;
    }
    br_total t = {.repeat = (int)repeat, .threads = (int)threads};
    gib_bench_machine_name(t.machine, sizeof t.machine);
    t.cores = threads > 0 ? threads : sysconf(_SC_NPROCESSORS_ONLN);
    t.csv = out ? fopen(out, "w") : stdout;
    if (!t.csv) {
        perror(out);
        return 1;
    }
    fputs("revision,machine,cores,threads,matrices,scene,camera,time,components,"
          "requests,seconds_each,seconds_together,speedup,noise_each,noise_together,"
          "same_bits\n", t.csv);
    gib_matrix *ms = calloc((size_t)nfiles, sizeof *ms);
    gib_error err = {0};
    int nm = 0;
    rc = ms ? 0 : 1;
    while (rc == 0 && nm < nfiles)
        if (gib_matrix_load(files[nm], profile, &ms[nm], &err) < 0)
            rc = 1;
        else
            nm++;
    for (int i = 0; rc == 0 && i < nm; i++) /* each scene at its first run, as a run meets it */
        for (int j = 0; rc == 0 && j < ms[i].run_count; j++) {
            const char *sname = ms[i].runs[j].scene;
            int first = 1;
            for (int a = 0; a <= i && first; a++)
                for (int b = 0; b < (a < i ? ms[a].run_count : j) && first; b++)
                    first = strcmp(ms[a].runs[b].scene, sname) != 0;
            if (first && br_scene(&t, ms, nm, sname, &err) < 0)
                rc = 1;
        }
    for (int i = 0; i < nm; i++)
        gib_matrix_free(&ms[i]);
    free(ms);
    if (rc == 1)
        fprintf(stderr, "gibench bench references: %s\n", err.msg);
    fprintf(t.csv, "%s,%s,%ld,%d,all,all,0,0,%d sets,%d,%.4f,%.4f,%.4f,,,%d\n",
            gib_git_revision(), t.machine, t.cores, t.threads, t.sets, t.requests, t.each,
            t.together, t.together > 0 ? t.each / t.together : 0.0, t.differ == 0);
    printf("all: %d requests in %d sets: one at a time %.2f s, together %.2f s (%.2fx); %s\n",
           t.requests, t.sets, t.each, t.together, t.together > 0 ? t.each / t.together : 0.0,
           t.differ ? "SOME IMAGES DIFFER" : "every image the same bits");
    if (out)
        fclose(t.csv);
    return rc == 1 ? 1 : t.differ ? 1 : 0;
}

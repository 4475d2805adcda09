/* gibench bench references — what a matrix profile's references cost rendered one request at a
 * time (gib_reference_render each, as runs asked before) against each world's requests together
 * (gib_reference_render_set, as `gibench run` prefetches them now: refset.h). The requests are
 * those a run of the matrices asks first (each output at the matrix's spp, one per cache key, a
 * key an earlier matrix already asked for left out, as the cache would), grouped by scene and
 * instant (one world); a set of one request is rendered once and counted on both sides. One CSV
 * row per set and a total row: seconds each way (the least of --repeat rounds, the world's build included),
 * the noise RMSE each way, and whether every image came out bit for bit the same. Performance is
 * measured here, never asserted by a test. */
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
    printf("%-21s %-15s t=%-4g each %7.2f s  together %7.2f s  %s  %s\n", matrix, scene->name,
           (double)p[0].time, each, together, same ? "same bits" : "IMAGES DIFFER", comps);
    fprintf(t->csv, "%s,%s,%ld,%d,%s,%s,%d,%g,%s,%d,%.4f,%.4f,%.4f,%.6g,%.6g,%d\n",
            gib_git_revision(), t->machine, t->cores, t->threads, matrix, scene->name,
            p[0].camera, (double)p[0].time, comps, n, each, together, each / together, noise1,
            noises, same);
    return 0;
}

/* One matrix: its scenes' requests not asked before (keys in seen), world by world. */
static int br_matrix(br_total *t, const char *path, const char *profile, uint64_t *seen,
                     int *nseen, gib_error *err)
{
    gib_matrix m;
    if (gib_matrix_load(path, profile, &m, err) < 0)
        return -1;
    char *want = calloc((size_t)m.run_count + 1, 1);
    gib_ref_request *rq = malloc(BR_MAX_REQUESTS * sizeof *rq);
    int *world = malloc(BR_MAX_REQUESTS * sizeof *world), rc = want && rq && world ? 0 : -1;
    for (int i = 0; rc == 0 && i < m.run_count; i++) {
        int first = 1;
        for (int j = 0; j < i && first; j++)
            first = strcmp(m.runs[j].scene, m.runs[i].scene) != 0;
        gib_scene scene;
        gib_error serr;
        if (!first || gib_scene_load(m.runs[i].scene, &scene, &serr) < 0) {
            if (first)
                printf("%s: scene %s skipped: %s\n", m.name, m.runs[i].scene, serr.msg);
            continue;
        }
        for (int j = 0; j < m.run_count; j++)
            want[j] = !strcmp(m.runs[j].scene, m.runs[i].scene) &&
                      gib_scene_wanted(&scene, m.runs[j].technique, NULL, 0);
        int n = gib_matrix_ref_requests(&m, NULL, &scene, want, rq, BR_MAX_REQUESTS), kept = 0;
        for (int k = 0; k < n; k++) { /* what an earlier matrix asked for is in the cache */
            gib_ref_params p = gib_ref_request_params(&rq[k]);
            uint64_t key = gib_reference_cache_key(&scene, &p);
            int dup = 0;
            for (int s = 0; s < *nseen && !dup; s++)
                dup = seen[s] == key;
            if (!dup && *nseen < 4 * BR_MAX_REQUESTS)
                seen[(*nseen)++] = key, rq[kept++] = rq[k];
        }
        int groups = gib_ref_worlds(rq, kept, world);
        for (int g = 0; g < groups && rc == 0; g++) {
            gib_ref_request set[GIB_REF_SET_MAX];
            int k = 0;
            for (int r = 0; r < kept && k < GIB_REF_SET_MAX; r++)
                if (world[r] == g)
                    set[k++] = rq[r];
            rc = br_set(t, m.name, &scene, set, k, err);
        }
        gib_scene_free(&scene);
    }
    if (!(want && rq && world) && rc < 0)
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "bench references: out of memory");
    free(world);
    free(rq);
    free(want);
    gib_matrix_free(&m);
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
    fputs("revision,machine,cores,threads,matrix,scene,camera,time,components,"
          "requests,seconds_each,seconds_together,speedup,noise_each,noise_together,"
          "same_bits\n", t.csv);
    uint64_t *seen = malloc(4 * BR_MAX_REQUESTS * sizeof *seen);
    int nseen = 0;
    gib_error err = {0};
    rc = seen ? 0 : 1;
    for (int i = 0; i < nfiles && rc == 0; i++)
        if (br_matrix(&t, files[i], profile, seen, &nseen, &err) < 0)
            rc = 1;
    free(seen);
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

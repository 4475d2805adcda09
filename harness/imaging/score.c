/* gibench — a row's metrics, FLIP means and images (score.h). The images that do not depend on
 * the metrics (EXR, preview, error map) are written by threads of their own while the team
 * computes the metrics; the FLIP map's PNG follows LDR-FLIP. */
#include "score.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

#include "flip.h"

enum { W_FLIP, W_EXR, W_PREVIEW, W_ERROR, W_COUNT }; /* the images, in the order errors report */

typedef struct image_writes {
    const gib_image *ref, *img;
    const float *map; /* the LDR-FLIP map */
    float exposure;
    const char *dir, *name;
    int rc[W_COUNT];
    gib_error err[W_COUNT];
    pthread_t thread[W_COUNT];
    int started[W_COUNT];
} image_writes;

typedef struct write_job {
    image_writes *w;
    int which;
} write_job;

static void write_one(image_writes *w, int which)
{
    char path[4096];
    static const char *const suffix[W_COUNT] = {"_flip.png", ".exr", ".png", "_error.png"};
    snprintf(path, sizeof path, "%s/%s%s", w->dir, w->name, suffix[which]);
    gib_error *err = &w->err[which];
    switch (which) {
    case W_FLIP:
        w->rc[which] = gib_flip_write_png(path, w->map, w->img->width, w->img->height, err);
        break;
    case W_EXR: w->rc[which] = gib_exr_write(path, w->img, NULL, 0, err); break;
    case W_PREVIEW: w->rc[which] = gib_png_write_preview(path, w->img, w->exposure, err); break;
    case W_ERROR: w->rc[which] = gib_png_write_error_map(path, w->ref, w->img, 0.0f, err); break;
    }
}

static void *write_thread(void *arg)
{
    write_job *j = arg;
    write_one(j->w, j->which);
    return NULL;
}

/* Starts the writes that need no metric, each on a thread of its own where there are threads to
 * spare; those not started run in writes_finish. */
static void writes_start(image_writes *w, write_job jobs[W_COUNT], int threads)
{
    for (int k = W_EXR; k < W_COUNT && threads > 1; k++) {
        jobs[k] = (write_job){w, k};
        w->started[k] = pthread_create(&w->thread[k], NULL, write_thread, &jobs[k]) == 0;
    }
}

/* Waits for the writes, runs those not started (when run_rest), and returns the first failure in
 * the order of the enumeration (0 when all were written), its message in *err. */
static int writes_finish(image_writes *w, int run_rest, gib_error *err)
{
    for (int k = W_EXR; k < W_COUNT; k++) {
        if (w->started[k])
            pthread_join(w->thread[k], NULL);
        else if (run_rest)
            write_one(w, k);
    }
    for (int k = 0; k < W_COUNT; k++)
        if (w->rc[k] < 0) {
            *err = w->err[k];
            return GIB_SCORE_WRITE_FAILED;
        }
    return 0;
}

/* The metrics and FLIP means on a team of `threads`; map: the LDR-FLIP map or NULL. */
static int score_metrics(const gib_image *ref, const gib_image *img, float exposure, int threads,
                         float *map, gib_metrics *m, gib_error *err)
{
    gib_team *team = gib_team_start(threads);
    int rc = gib_metrics_compute_on(team, ref, img, exposure, m, err);
    if (rc == 0)
        rc = gib_flip_pair_on(team, ref, img, exposure, map, &m->flip, &m->hdrflip, err);
    gib_team_stop(team);
    return rc;
}

int gib_score_pair(const gib_image *ref, const gib_image *img, float exposure, const char *dir,
                   const char *name, gib_metrics *m, gib_error *err)
{
    if (gib_metrics_check(ref, img, err) < 0)
        return -1;
    const int threads = gib_score_threads();
    const size_t n = (size_t)ref->width * ref->height;
    float *map = dir ? malloc(n * sizeof(float)) : NULL;
    if (dir && !map)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "FLIP: out of memory for a %dx%d map", ref->width, ref->height);
    image_writes w = {.ref = ref, .img = img, .map = map, .exposure = exposure, .dir = dir,
                      .name = name};
    write_job jobs[W_COUNT];
    if (dir)
        writes_start(&w, jobs, threads);
    int rc = score_metrics(ref, img, exposure, threads, map, m, err);
    if (dir && rc == 0 && !isnan(m->flip))
        write_one(&w, W_FLIP);
    free(map);
    if (!dir)
        return rc;
    gib_error werr;
    int wrc = writes_finish(&w, rc == 0, &werr);
    if (rc == 0 && wrc != 0)
        *err = werr;
    return rc != 0 ? rc : wrc;
}

/* gibench run — scoring one run: its passes table rows, then per output component the reference
 * (deeper where needed to rank the row), the metrics, the images, and for a sequence every frame's
 * score and the temporal error (ARCHITECTURE.md, "Data flow of a matrix row"). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "run_rows.h"
#include "harness/base/status.h"
#include "harness/imaging/temporal.h"
#include "refrank.h"
#include "refset.h"

/* The row's error beside what a black image scores and with the reference's noise taken out
 * (metrics.h, gib_rmse_interval). */
static void set_error_scale(gib_row *r, const gib_metrics *m, const gib_rmse_bounds *b)
{
    gib_row_num(r, GIB_C_BLACK_RMSE, m->black_rmse);
    gib_row_num(r, GIB_C_OVER_BLACK, m->black_rmse > 0 ? m->rmse / m->black_rmse
                                                   : m->rmse > 0 ? INFINITY : 0.0);
    gib_row_num(r, GIB_C_RMSE_DENOISED, b->denoised);
    gib_row_num(r, GIB_C_RMSE_LO, b->lo);
    gib_row_num(r, GIB_C_RMSE_HI, b->hi);
}

/* What a pass ran, from its counted work: raster (vertices and fragments), compute, both, or none
 * (a copy or clear). Empty where the driver counts nothing. */
static void pass_work(gib_row *r, const gib_pass_stats *ps)
{
    if (!ps->counted)
        return;
    static const int cols[GIB_WORK_COUNT] = {GIB_P_VERTICES, GIB_P_PRIMITIVES, GIB_P_FRAGMENTS,
                                             GIB_P_COMPUTE};
    for (int k = 0; k < GIB_WORK_COUNT; k++)
        gib_row_set(r, cols[k], "%llu", ps->work[k]);
    const int raster = ps->work[GIB_WORK_PRIMITIVES] > 0 || ps->work[GIB_WORK_FRAGMENTS] > 0;
    const int compute = ps->work[GIB_WORK_COMPUTE] > 0;
    gib_row_set(r, GIB_P_KIND, "%s", raster && compute ? "both" : raster ? "raster"
                                     : compute ? "compute" : "none");
}

/* The run's passes, before its rows: a run whose rows are all in the CSV (run_done) then has its
 * passes too, whenever the process is stopped. Returns -1 when the table cannot be written. */
static int write_passes(gib_run_ctx *ctx, const gib_matrix_run *mr, const gib_run_result *res)
{
    for (int p = 0; res->ok && p < res->pass_count; p++) {
        gib_row r;
        const gib_pass_stats *ps = &res->passes[p];
        memset(r.ptr, 0, sizeof r.ptr);
        gib_row_set(&r, GIB_P_MATRIX, "%s", ctx->m->name);
        gib_row_set(&r, GIB_P_PROFILE, "%s", ctx->m->profile);
        gib_row_set(&r, GIB_P_SCENE, "%s", mr->scene);
        gib_row_set(&r, GIB_P_TECHNIQUE, "%s", mr->technique->name);
        gib_row_set(&r, GIB_P_PARAMS, "%s", mr->params_key);
        gib_row_set(&r, GIB_P_WIDTH, "%d", mr->width);
        gib_row_set(&r, GIB_P_HEIGHT, "%d", mr->height);
        gib_row_set(&r, GIB_P_TIME, "%.9g", mr->time);
        gib_row_set(&r, GIB_P_PASS, "%s", ps->name);
        gib_row_set(&r, GIB_P_MEDIAN, "%.6g", ps->median_ms);
        gib_row_set(&r, GIB_P_MIN, "%.6g", ps->min_ms);
        gib_row_set(&r, GIB_P_MAX, "%.6g", ps->max_ms);
        gib_row_set(&r, GIB_P_IQR, "%.6g", ps->iqr_ms);
        gib_row_set(&r, GIB_P_FIRST, "%.6g", ps->first_ms);
        pass_work(&r, ps);
        gib_row_set(&r, GIB_P_RENDERER, "%s",
                    res->renderer[0] ? res->renderer : ctx->info.renderer);
        gib_row_set(&r, GIB_P_GIT, "%s", gib_git_revision());
        gib_error err;
        if (gib_csv_append(ctx->passes, r.ptr, &err) < 0) {
            gib_run_write_failed(ctx, &err);
            return -1;
        }
    }
    return 0;
}

/* What every row of a run holds, ok or not: memory and counters; its times when it rendered. */
static void row_run_result(gib_row *r, const gib_gpu_scene *gpu, const gib_run_result *res)
{
    gib_row_set(r, GIB_C_SCENE_MEM, "%llu", (unsigned long long)gpu->ledger.peak_bytes);
    gib_row_set(r, GIB_C_MEM, "%llu", (unsigned long long)res->technique_bytes);
    gib_row_set(r, GIB_C_MEM_STRUCT, "%s", res->memory_by_structure);
    /* What the technique planned, filled when the runner reports it (empty until then). */
    gib_row_set(r, GIB_C_MEM_PLANNED, "%s", res->planned_structures);
    gib_row_set(r, GIB_C_COUNTERS, "%s", res->counters);
    if (res->renderer[0]) /* an external's (external.h), as it reports itself */
        gib_row_set(r, GIB_C_RENDERER, "%s", res->renderer);
    if (res->ok)
        gib_row_set(r, GIB_C_WARMUP, "%d", res->warmup_frames);
    if (res->driver_bytes >= 0)
        gib_row_set(r, GIB_C_DRIVER_MEM, "%lld", res->driver_bytes);
    if (!res->ok) {
        gib_row_set(r, GIB_C_STATUS, "%s", res->status);
        gib_row_set(r, GIB_C_MESSAGE, "%s", res->err.msg);
        return;
    }
    gib_row_num(r, GIB_C_GPU_MED, res->gpu_total.median_ms);
    gib_row_num(r, GIB_C_GPU_MIN, res->gpu_total.min_ms);
    gib_row_num(r, GIB_C_GPU_MAX, res->gpu_total.max_ms);
    gib_row_num(r, GIB_C_GPU_IQR, res->gpu_total.iqr_ms);
    gib_row_num(r, GIB_C_CPU, res->cpu_total.median_ms);
    gib_row_num(r, GIB_C_CPU_IQR, res->cpu_total.iqr_ms);
    gib_row_num(r, GIB_C_FIRST_FRAME, res->first_frame_ms);
    gib_row_num(r, GIB_C_FIRST_GPU, res->gpu_total.first_ms);
}

/* The reference's preview beside the technique images, once per (scene, component, size, dmax),
 * and the row's image names, relative to DIR/images/<matrix>/ (the report reads them). */
static void row_images(gib_row *r, const char *img_dir, const char *name, const gib_ref_result *ref,
                       float exposure)
{
    char ref_png[4096];
    const char *slash = strrchr(ref->path, '/');
    snprintf(ref_png, sizeof ref_png, "%s/reference_%s", img_dir, slash ? slash + 1 : ref->path);
    char *dot = strrchr(ref_png, '.');
    if (dot)
        strcpy(dot, ".png");
    gib_error err;
    if (access(ref_png, F_OK) != 0 &&
        gib_png_write_preview(ref_png, &ref->image, exposure, &err) < 0)
        fprintf(stderr, "gibench run: %s\n", err.msg);
    gib_row_set(r, GIB_C_IMAGE, "%s", name);
    gib_row_set(r, GIB_C_REF_IMAGE, "%s", strrchr(ref_png, '/') + 1);
}

static void row_metrics(gib_row *r, const gib_score *s, const gib_ref_result *ref)
{
    const gib_metrics *m = &s->m;
    gib_row_num(r, GIB_C_RMSE, m->rmse);
    gib_row_num(r, GIB_C_REL_RMSE, m->rel_rmse);
    gib_row_num(r, GIB_C_MEAN_RATIO, m->mean_ratio);
    set_error_scale(r, m, &s->rmse);
    gib_row_num(r, GIB_C_PSNR, m->psnr);
    gib_row_num(r, GIB_C_SSIM, m->ssim);
    gib_row_num(r, GIB_C_FLIP, m->flip);
    gib_row_num(r, GIB_C_HDRFLIP, m->hdrflip);
    gib_row_set(r, GIB_C_NONFINITE, "%ld", m->nonfinite);
    /* A reference noisier than a fifth of the error cannot rank techniques. */
    gib_row_set(r, GIB_C_REF_NOISY, "%d", ref->noise_rmse > 0.2 * m->rmse);
    gib_row_set(r, GIB_C_STATUS, "%s",
            gib_status_name(m->nonfinite ? GIB_STATUS_NONFINITE : GIB_STATUS_OK));
    if (m->nonfinite)
        gib_row_set(r, GIB_C_MESSAGE, "%ld NaN/Inf values in the image", m->nonfinite);
}

/* ---- sequences: each frame against the reference at its instant, and what changes ---- */

/* A sequence column's cell (its index follows the base columns). */
#define SEQ_COL(id) (GIB_C_COUNT + GIB_S_##id)

/* What a sequence scores: the references of its frames and each frame's metrics. */
typedef struct seq_scores {
    gib_image refs[GIB_MATRIX_MAX_SEQUENCE];
    double rmse[GIB_MATRIX_MAX_SEQUENCE], denoised[GIB_MATRIX_MAX_SEQUENCE];
    double noise2; /* sum over frames of the reference's noise variance */
    int n, have;   /* frames; references obtained */
} seq_scores;

/* The references of the frames, at the spp the row's last frame was ranked at (rq), and each
 * frame's error. Returns 0, -1 (err set), or GIB_REF_WRITE_FAILED. */
static int seq_references(const gib_run_ctx *ctx, const gib_matrix_run *mr, const gib_image *frames,
                          gib_ref_request rq, seq_scores *sc, gib_error *err)
{
    for (int k = 0; k < sc->n; k++) {
        rq.time = (float)(mr->time - (double)(sc->n - 1 - k) * ctx->m->dt);
        gib_ref_result ref;
        int grc = gib_reference_get(&rq, &ref, err);
        if (grc < 0)
            return grc;
        sc->refs[sc->have++] = ref.image;
        sc->noise2 += ref.noise_rmse * ref.noise_rmse;
        gib_metrics m; /* the RMSE alone: a frame's SSIM and FLIP are not reported */
        if (gib_metrics_errors(&ref.image, &frames[k], &m, err) < 0)
            return -1;
        gib_rmse_bounds b;
        gib_rmse_interval(m.rmse, ref.noise_rmse, (long)mr->width * mr->height, &b);
        sc->rmse[k] = m.rmse;
        sc->denoised[k] = b.denoised;
    }
    return 0;
}

/* Per frame: the technique's preview, the reference's, and an error map on one scale for the whole
 * sequence (twice the worst frame's RMSE), as <name>_f<k>{,_ref,_error}.png in img_dir/seq/. */
static int seq_images(const char *img_dir, const char *name, const gib_image *frames,
                      const seq_scores *sc, double worst, float exposure, gib_error *err)
{
    char dir[2100], path[4200];
    snprintf(dir, sizeof dir, "%s/seq", img_dir);
    if (gib_mkdirs(dir, err) < 0)
        return -1;
    for (int k = 0; k < sc->n; k++) {
        snprintf(path, sizeof path, "%s/%s_f%02d.png", dir, name, k);
        if (gib_png_write_preview(path, &frames[k], exposure, err) < 0)
            return -1;
        snprintf(path, sizeof path, "%s/%s_f%02d_ref.png", dir, name, k);
        if (gib_png_write_preview(path, &sc->refs[k], exposure, err) < 0)
            return -1;
        snprintf(path, sizeof path, "%s/%s_f%02d_error.png", dir, name, k);
        if (gib_png_write_error_map(path, &sc->refs[k], &frames[k], (float)(2.0 * worst), err) < 0)
            return -1;
    }
    return 0;
}

/* The sequence columns from the frames' scores and the temporal error. */
static int seq_columns(gib_row *r, const seq_scores *sc, const gib_image *frames, float exposure,
                       double *worst, gib_error *err)
{
    double sum = 0, sum_dn = 0;
    int wk = 0;
    for (int k = 0; k < sc->n; k++) {
        sum += sc->rmse[k];
        sum_dn += sc->denoised[k];
        if (sc->rmse[k] > sc->rmse[wk])
            wk = k;
    }
    *worst = sc->rmse[wk];
    gib_temporal t;
    const double noise = sqrt(sc->noise2 / sc->n);
    if (gib_temporal_compute(sc->refs, frames, sc->n, noise, exposure, 1, &t, err) < 0)
        return -1;
    gib_row_set(r, SEQ_COL(SEQUENCE), "%d", sc->n);
    gib_row_num(r, SEQ_COL(SEQ_RMSE_MEAN), sum / sc->n);
    gib_row_num(r, SEQ_COL(SEQ_RMSE_WORST), sc->rmse[wk]);
    gib_row_set(r, SEQ_COL(SEQ_WORST_FRAME), "%d", wk);
    gib_row_num(r, SEQ_COL(SEQ_DENOISED_MEAN), sum_dn / sc->n);
    gib_row_num(r, SEQ_COL(T_RMSE), t.rmse);
    gib_row_num(r, SEQ_COL(T_DENOISED), t.rmse_denoised);
    gib_row_num(r, SEQ_COL(T_PEAK), t.peak);
    gib_row_num(r, SEQ_COL(T_FROZEN), t.frozen);
    gib_row_num(r, SEQ_COL(T_FLIP), t.flip);
    gib_row_num(r, SEQ_COL(T_REF_NOISE), noise);
    return 0;
}

/* A sequence run's row (its image i) gets the sequence columns; a failure to score them makes the
 * row's status sequence_failed. Returns -1 only when a table or image cannot be written. */
static int score_sequence(gib_run_ctx *ctx, const gib_scene *scene, const gib_matrix_run *mr,
                          const gib_run_result *res, int i, const gib_ref_request *rq,
                          const char *img_dir, const char *name, gib_row *r)
{
    if (res->sequence < 2)
        return 0;
    static seq_scores sc; /* the references of up to 64 frames: not on the stack */
    memset(&sc, 0, sizeof sc);
    sc.n = res->sequence;
    const gib_image *frames = res->seq_images[i];
    gib_error err;
    double worst = 0;
    int rc = seq_references(ctx, mr, frames, *rq, &sc, &err);
    if (rc == 0)
        rc = seq_columns(r, &sc, frames, scene->exposure, &worst, &err);
    if (rc == 0 && ctx->images &&
        seq_images(img_dir, name, frames, &sc, worst, scene->exposure, &err) < 0)
        rc = GIB_REF_WRITE_FAILED;
    if (rc == GIB_REF_WRITE_FAILED)
        gib_run_write_failed(ctx, &err);
    else if (rc < 0) {
        gib_row_set(r, GIB_C_STATUS, "%s", gib_status_name(GIB_STATUS_SEQUENCE_FAILED));
        gib_row_set(r, GIB_C_MESSAGE, "%s", err.msg);
    }
    for (int k = 0; k < sc.have; k++)
        gib_image_free(&sc.refs[k]);
    return rc == GIB_REF_WRITE_FAILED ? -1 : 0;
}

/* Scores image img (component bit of run mr) against its reference into row r and appends it. */
static void score_component(gib_run_ctx *ctx, const gib_scene *scene, const gib_matrix_run *mr,
                            const gib_run_result *res, unsigned bit, int index,
                            const char *img_dir, gib_row *r)
{
    gib_error err;
    gib_ref_request rq;
    const gib_image *img = &res->images[index];
    int component = gib_matrix_ref_request(ctx->m, ctx->cache, scene, mr, bit, &rq);
    gib_ref_result ref;
    int grc = component < 0 ? -1
                            : gib_reference_to_rank(&rq, img, scene->exposure,
                                                    ctx->m->ref_spp_growth, &ref, &err);
    if (grc == GIB_REF_WRITE_FAILED) { /* no row (a rerun redoes this run) */
        gib_run_write_failed(ctx, &err);
        return;
    }
    if (grc < 0) {
        gib_row_set(r, GIB_C_STATUS, "%s", gib_status_name(GIB_STATUS_REFERENCE_FAILED));
        gib_row_set(r, GIB_C_MESSAGE, "%s",
                    component < 0 ? "no reference estimator for this component" : err.msg);
        gib_run_append_row(ctx, r);
        return;
    }
    char name[512];
    gib_image_name(mr->scene, mr->technique->name, mr->params_key, mr->width, mr->height, mr->time,
                   gib_output_name(bit), name, sizeof name);
    if (ctx->images)
        row_images(r, img_dir, name, &ref, scene->exposure);
    gib_score s;
    int src = gib_score_image(&ref.image, ref.noise_rmse, img, scene->exposure,
                              ctx->images ? img_dir : NULL, name, &s, &err);
    if (src == GIB_IMAGE_WRITE_FAILED) {
        gib_run_write_failed(ctx, &err);
        gib_image_free(&ref.image);
        return;
    }
    if (src < 0) {
        gib_row_set(r, GIB_C_STATUS, "%s", gib_status_name(GIB_STATUS_SCORING_FAILED));
        gib_row_set(r, GIB_C_MESSAGE, "%s", err.msg);
    } else {
        row_metrics(r, &s, &ref);
    }
    gib_row_set(r, GIB_C_REF_SPP, "%d", ref.spp);
    gib_row_num(r, GIB_C_REF_NOISE, ref.noise_rmse);
    if (src == 0 && score_sequence(ctx, scene, mr, res, index, &rq, img_dir, name, r) < 0) {
        gib_image_free(&ref.image);
        return;
    }
    gib_run_append_row(ctx, r);
    char tag[32];
    gib_progress_tag(&ctx->progress, tag, sizeof tag);
    gib_progress_clear(&ctx->progress);
    printf("%s %-10s %-8s %-36s %4dx%-4d t %-5g gpu %8.3f ms  rmse %.4g  ssim %.4f  flip %.4f  %s\n",
           tag, mr->scene, mr->technique->name, mr->params_key, mr->width, mr->height, mr->time,
           res->gpu_total.median_ms, s.m.rmse, s.m.ssim, s.m.flip, r->v[GIB_C_STATUS]);
    gib_image_free(&ref.image);
}

/* A timed row without a reference (--timing-only): its image is only checked for NaN/Inf, which
 * would make its times those of a broken frame. */
static void time_component(gib_run_ctx *ctx, const gib_matrix_run *mr, const gib_run_result *res,
                           int index, gib_row *r)
{
    const gib_image *img = &res->images[index];
    long nonfinite = 0;
    for (size_t k = 0; k < (size_t)img->width * img->height * img->channels; k++)
        nonfinite += !isfinite(img->px[k]);
    gib_row_set(r, GIB_C_NONFINITE, "%ld", nonfinite);
    gib_row_set(r, GIB_C_STATUS, "%s",
            gib_status_name(nonfinite ? GIB_STATUS_NONFINITE : GIB_STATUS_OK));
    if (nonfinite)
        gib_row_set(r, GIB_C_MESSAGE, "%ld NaN/Inf values in the image (timing only)", nonfinite);
    else
        gib_row_set(r, GIB_C_MESSAGE, "timing only: not scored");
    gib_run_append_row(ctx, r);
    char tag[32];
    gib_progress_tag(&ctx->progress, tag, sizeof tag);
    gib_progress_clear(&ctx->progress);
    printf("%s %-10s %-8s %-36s %4dx%-4d t %-5g gpu %8.3f ms (IQR %.3f, warm-up %d)  %s\n", tag,
           mr->scene, mr->technique->name, mr->params_key, mr->width, mr->height, mr->time,
           res->gpu_total.median_ms, res->gpu_total.iqr_ms, res->warmup_frames,
           r->v[GIB_C_STATUS]);
}

/* A run's passes, then a row per output component. */
void gib_run_score(gib_run_ctx *ctx, const gib_scene *scene, const gib_gpu_scene *gpu,
                   const gib_matrix_run *mr, gib_run_result *res)
{
    gib_progress_clear(&ctx->progress); /* references may report their own progress */
    char img_dir[2048];
    snprintf(img_dir, sizeof img_dir, "%s/images/%s", ctx->out, ctx->m->name);
    gib_error err;
    if (ctx->images && gib_mkdirs(img_dir, &err) < 0) {
        fprintf(stderr, "gibench run: %s\n", err.msg);
        ctx->images = 0;
    }
    if (write_passes(ctx, mr, res) < 0)
        return;
    for (unsigned bit = 1, i = 0; bit <= GIB_OUT_CAUSTIC && !ctx->write_failed; bit <<= 1) {
        if (!(mr->technique->components & bit))
            continue;
        gib_row r;
        gib_run_row_identity(&r, ctx, mr, bit);
        row_run_result(&r, gpu, res);
        if (!res->ok)
            gib_run_append_row(ctx, &r);
        else if (ctx->timing_only)
            time_component(ctx, mr, res, (int)i++, &r);
        else
            score_component(ctx, scene, mr, res, bit, (int)i++, img_dir, &r);
    }
}

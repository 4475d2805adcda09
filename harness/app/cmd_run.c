/* gibench run — runs matrix files: every (scene, technique, parameters, size) of the chosen
 * profile, each scored against its cached reference, one CSV row per output component appended as
 * it finishes (ARCHITECTURE.md, "Data flow of a matrix row" and "Matrices, CSV and reproduction"). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "runner.h"
#include "app.h"
#include "csv.h"
#include "history.h"
#include "harness/base/hash.h"
#include "matrix.h"
#include "refrank.h"
#include "shard.h"

static const char help[] =
    "usage: gibench run MATRIX... [--profile quick|paper] [--out DIR] [--cache DIR]\n"
    "                   [--backend egl|osmesa|auto] [--no-images] [--shard I/N]\n"
    "                   [--history PATH | --no-history] [--warmup W] [--frames F]\n"
    "\n"
    "Expands each matrix (scenes x techniques x parameter lists x sizes), validates it, then runs\n"
    "it: DIR/<matrix>.csv gets one row per run and component, DIR/<matrix>_passes.csv the per-pass\n"
    "GPU times, DIR/images/<matrix>/ the images, previews and error maps. Rows are appended as\n"
    "runs finish; a rerun skips the runs already in the CSV. References come from --cache\n"
    "(default results/cache), rendered when missing or stale. Scenes whose data is absent are\n"
    "skipped with a message. Exit status 1 when any row is not `ok` or the history could not\n"
    "be written.\n"
    "\n"
    "Every row is also recorded in the results history, a SQLite file (--history, default\n"
    "DIR/history.sqlite; `gibench history` queries it), with the machine and revision.\n"
    "\n"
    "--shard I/N runs share I of N of each matrix's runs (with the references they need): a\n"
    "deterministic, balanced split by scene, size and instant that every shard computes alike.\n"
    "Each shard writes into its own DIR, plus DIR/<matrix>.shard, the manifest `gibench merge`\n"
    "checks when it combines the shards' CSVs into the table one run would write.\n"
    "\n"
    "Timing: every run renders a cold first frame (its time to the first image, compiles\n"
    "included, is the column first_frame_ms), then the profile's warm-up frames, then its timed\n"
    "frames: median, interquartile range, min and max. --warmup W and --frames F replace the\n"
    "profile's counts (the timing benchmark's longer warm-up, harness/bench_timing.py).\n";

enum { C_MATRIX, C_PROFILE, C_SCENE, C_CAMERA, C_TECHNIQUE, C_COMPONENT, C_PARAMS, C_WIDTH,
       C_HEIGHT, C_INSTANT, C_WARMUP, C_FRAMES, C_DT, C_GPU_MED, C_GPU_MIN, C_GPU_MAX, C_GPU_IQR,
       C_CPU, C_CPU_IQR, C_FIRST_FRAME, C_FIRST_GPU, C_MEM, C_MEM_STRUCT, C_MEM_PLANNED, C_SCENE_MEM,
       C_DRIVER_MEM, C_RMSE, C_REL_RMSE, C_MEAN_RATIO, C_BLACK_RMSE, C_OVER_BLACK, C_RMSE_DENOISED, C_RMSE_LO,
       C_RMSE_HI, C_PSNR, C_SSIM, C_FLIP, C_HDRFLIP, C_NONFINITE, C_REF_SPP,
       C_REF_NOISE, C_REF_NOISY,
       C_STATUS, C_MESSAGE, C_COUNTERS, C_IMAGE, C_REF_IMAGE, C_BACKEND, C_RENDERER, C_GL_VERSION, C_GIT, C_TIME, C_BASE_COUNT };

static const char *const base_columns[C_BASE_COUNT] = {
    "matrix", "profile", "scene", "camera", "technique", "component", "params", "width", "height",
    "time", "warmup", "frames", "dt", "gpu_ms_median", "gpu_ms_min", "gpu_ms_max", "gpu_ms_iqr",
    "cpu_ms", "cpu_ms_iqr", "first_frame_ms", "first_frame_gpu_ms", "mem_bytes", "mem_by_structure",
    "mem_planned_by_structure", "scene_mem_bytes", "driver_mem_bytes", "rmse", "rel_rmse", "mean_ratio", "black_rmse", "rmse_over_black",
    "rmse_denoised", "rmse_lo", "rmse_hi", "psnr", "ssim", "flip", "hdrflip",
    "nonfinite", "ref_spp",
    "ref_noise_rmse", "ref_noisy", "status", "message", "counters", "image", "ref_image", "backend", "renderer", "gl_version",
    "git_revision", "timestamp"};
static const int key_columns[] = {C_PROFILE, C_SCENE, C_CAMERA, C_TECHNIQUE, C_COMPONENT, C_PARAMS,
                                  C_WIDTH, C_HEIGHT, C_INSTANT};
#define NKEY ((int)(sizeof key_columns / sizeof key_columns[0]))
/* profile, scene, technique, params, width, height, time, pass: a pass row's identity. */
static const int pass_key_columns[] = {1, 2, 3, 4, 5, 6, 7, 8};

static const char *const pass_columns[] = {"matrix", "profile", "scene", "technique", "params",
                                           "width", "height", "time", "pass", "ms_median", "ms_min",
                                           "ms_max", "ms_iqr", "ms_first", "renderer",
                                           "git_revision"};
#define PASS_COLUMNS ((int)(sizeof pass_columns / sizeof pass_columns[0]))

#define MAX_COLS 128
typedef struct columns {
    const char *names[MAX_COLS];
    int count;
} columns;

/* Base columns, then every parameter name of every technique once, in registry order. A name that
 * does not fit is an error, never a column dropped without a word. */
static int make_columns(columns *c, gib_error *err)
{
    c->count = 0;
    for (int i = 0; i < C_BASE_COUNT; i++)
        c->names[c->count++] = base_columns[i];
    int n;
    const gib_technique *const *all = gib_techniques(&n);
    for (int t = 0; t < n; t++)
        for (int p = 0; all[t]->params && all[t]->params[p].name; p++) {
            int seen = 0;
            for (int k = C_BASE_COUNT; k < c->count; k++)
                seen |= !strcmp(c->names[k], all[t]->params[p].name);
            if (seen)
                continue;
            if (c->count == MAX_COLS)
                return gib_fail(err, "technique '%s' parameter '%s': the results table holds %d "
                                "columns at most (MAX_COLS in harness/app/cmd_run.c)", all[t]->name,
                                all[t]->params[p].name, MAX_COLS);
            c->names[c->count++] = all[t]->params[p].name;
        }
    return 0;
}

typedef struct row {
    char v[MAX_COLS][256];
    const char *ptr[MAX_COLS];
} row;

static void row_set(row *r, int col, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void row_set(row *r, int col, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->v[col], sizeof r->v[col], fmt, ap);
    va_end(ap);
    r->ptr[col] = r->v[col];
}

static void row_key(const row *r, char *key, size_t len)
{
    key[0] = 0;
    for (int k = 0; k < NKEY; k++) {
        strncat(key, k ? "|" : "", len - strlen(key) - 1);
        strncat(key, r->v[key_columns[k]], len - strlen(key) - 1);
    }
}

static void fmt_num(row *r, int col, double v)
{
    if (isnan(v))
        row_set(r, col, "nan");
    else if (isinf(v))
        row_set(r, col, v > 0 ? "inf" : "-inf");
    else
        row_set(r, col, "%.9g", v);
}

typedef struct run_ctx {
    const gib_matrix *m;
    const columns *cols;
    gib_csv *csv, *passes;
    const char *out, *cache;
    int images;
    gib_gl_info info;
    gib_history *hist;     /* NULL: --no-history, or recording failed (reported once) */
    const gib_history_machine *machine;
    long long hist_run;    /* the history's run of this matrix; 0 until its first row */
    int hist_failed;
    int rows_written, rows_failed, rows_out_of_memory, runs_skipped;
    int write_failed; /* a table could not be written (a full disk): the run stops there */
    gib_shard shard;
    const int *owner; /* with --shard: each run's shard (shard.h) */
    char *state;      /* with --shard: 'e' rows expected, 's' skipped, 'f' failed; 0 not ours */
} run_ctx;

/* Whether run j is this process's to do: every run, or with --shard this shard's share. */
static int run_mine(const run_ctx *ctx, int j)
{
    return !ctx->shard.count || ctx->owner[j] == ctx->shard.index;
}

static void run_state(run_ctx *ctx, int j, char state)
{
    if (ctx->state)
        ctx->state[j] = state;
}

/* The identity part of a row: what makes it this run. */
static void row_identity(row *r, const run_ctx *ctx, const gib_matrix_run *mr, unsigned comp)
{
    memset(r->ptr, 0, sizeof r->ptr);
    row_set(r, C_MATRIX, "%s", ctx->m->name);
    row_set(r, C_PROFILE, "%s", ctx->m->profile);
    row_set(r, C_SCENE, "%s", mr->scene);
    row_set(r, C_CAMERA, "%d", ctx->m->camera);
    row_set(r, C_TECHNIQUE, "%s", mr->technique->name);
    row_set(r, C_COMPONENT, "%s", gib_output_name(comp));
    row_set(r, C_PARAMS, "%s", mr->params_key);
    row_set(r, C_WIDTH, "%d", mr->width);
    row_set(r, C_HEIGHT, "%d", mr->height);
    row_set(r, C_INSTANT, "%.9g", mr->time);
    row_set(r, C_DT, "%.9g", ctx->m->dt);
    row_set(r, C_WARMUP, "%d", ctx->m->warmup);
    row_set(r, C_FRAMES, "%d", ctx->m->frames);
    row_set(r, C_BACKEND, "%s", ctx->info.backend);
    row_set(r, C_RENDERER, "%s", ctx->info.renderer);
    row_set(r, C_GL_VERSION, "%s", ctx->info.version);
    row_set(r, C_GIT, "%s", gib_git_revision());
    time_t now = time(NULL);
    strftime(r->v[C_TIME], sizeof r->v[C_TIME], "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    r->ptr[C_TIME] = r->v[C_TIME];
    const gib_technique *t = mr->technique;
    for (int p = 0; t->params && t->params[p].name; p++)
        for (int k = C_BASE_COUNT; k < ctx->cols->count; k++)
            if (!strcmp(ctx->cols->names[k], t->params[p].name))
                fmt_num(r, k, mr->params.values[p]);
}

static int run_done(const run_ctx *ctx, const gib_matrix_run *mr)
{
    for (unsigned bit = 1; bit <= GIB_OUT_CAUSTIC; bit <<= 1) {
        if (!(mr->technique->components & bit))
            continue;
        row r;
        char key[4096];
        row_identity(&r, ctx, mr, bit);
        row_key(&r, key, sizeof key);
        if (!gib_csv_has(ctx->csv, key))
            return 0;
    }
    return 1;
}

/* Stops recording after the first failure, which makes the run's exit status 1. */
static void history_failed(run_ctx *ctx, const gib_error *err)
{
    fprintf(stderr, "gibench run: results history not recorded from here on: %s\n", err->msg);
    gib_history_close(ctx->hist);
    ctx->hist = NULL;
    ctx->hist_failed = 1;
}

static void append_row(run_ctx *ctx, row *r)
{
    gib_error err;
    int w = gib_csv_append(ctx->csv, r->ptr, &err);
    if (w < 0) {
        fprintf(stderr, "gibench run: %s: stopping (the rows before it are intact; a rerun "
                        "resumes)\n", err.msg);
        ctx->write_failed = 1;
        return;
    }
    if (w == 0) /* written before an interruption: the row is there once (and in
                 * the history, unless the run was killed between the two writes) */
        return;
    if (ctx->hist && !ctx->hist_run &&
        gib_history_begin_run(ctx->hist, ctx->machine, gib_git_revision(), ctx->m->name,
                              ctx->m->profile, &ctx->hist_run, &err) < 0)
        history_failed(ctx, &err);
    /* One transaction per row: short, so concurrent runs writing the same history wait for each
     * other only milliseconds (history.h). */
    if (ctx->hist && (gib_history_begin(ctx->hist, &err) < 0 ||
                      gib_history_add_row(ctx->hist, ctx->hist_run, ctx->cols->names, r->ptr,
                                          ctx->cols->count, &err) < 0 ||
                      gib_history_commit(ctx->hist, &err) < 0))
        history_failed(ctx, &err);
    ctx->rows_written++;
    /* out_of_memory is a result (the plan exceeds the device), not a failure of the run. */
    if (!strcmp(r->v[C_STATUS], "out_of_memory"))
        ctx->rows_out_of_memory++;
    else if (strcmp(r->v[C_STATUS], "ok"))
        ctx->rows_failed++;
}

/* The reference request of a row (component GIB_OUT_* bit `bit` of run mr), at the matrix's spp.
 * Returns the reference component, -1 when there is no estimator for it. */
static int row_request(const run_ctx *ctx, const gib_scene *scene, const gib_matrix_run *mr,
                       unsigned bit, gib_ref_request *rq)
{
    int component = gib_component_parse(gib_output_name(bit));
    *rq = (gib_ref_request){.scene = scene, .camera = ctx->m->camera, .width = mr->width,
                            .height = mr->height, .time = (float)mr->time, .component = component,
                            .spp = component >= 0 && ctx->m->ref_spp[component]
                                       ? ctx->m->ref_spp[component] : 64,
                            .cache_dir = ctx->cache};
    gib_ref_request_match(rq, mr->technique, &mr->params, bit);
    return component;
}

/* The reference a row is scored against (refrank.h): the matrix's, or where its noise is over a
 * fifth of the row's error, one with more samples. Returns what gib_reference_get returns. */
static int reference_to_rank(const run_ctx *ctx, gib_ref_request *rq, const gib_image *img,
                             float exposure, gib_ref_result *ref, gib_error *err)
{
    int grc = gib_reference_get(rq, ref, err);
    gib_metrics m;
    if (grc < 0 || gib_metrics_compute(&ref->image, img, exposure, &m, err) < 0 || m.nonfinite)
        return grc;
    int spp = gib_ref_spp_to_rank(rq->spp, ref->noise_rmse, m.rmse, (long)rq->width * rq->height,
                                  ctx->m->ref_spp_growth);
    if (spp == rq->spp)
        return grc;
    printf("    reference %s %dx%d: noise %.3g at %d spp is over a fifth of the row's error %.3g: "
           "scored at %d spp\n", gib_component_name(rq->component), rq->width, rq->height,
           ref->noise_rmse, rq->spp, m.rmse, spp);
    gib_image_free(&ref->image);
    rq->spp = spp;
    return gib_reference_get(rq, ref, err);
}

/* The row's error beside what a black image scores and with the reference's noise taken out
 * (metrics.h, gib_rmse_interval). */
static void set_error_scale(row *r, const gib_metrics *m, double noise_rmse, long pixels)
{
    gib_rmse_bounds b;
    gib_rmse_interval(m->rmse, noise_rmse, pixels, &b);
    fmt_num(r, C_BLACK_RMSE, m->black_rmse);
    fmt_num(r, C_OVER_BLACK, m->black_rmse > 0 ? m->rmse / m->black_rmse
                                               : m->rmse > 0 ? INFINITY : 0.0);
    fmt_num(r, C_RMSE_DENOISED, b.denoised);
    fmt_num(r, C_RMSE_LO, b.lo);
    fmt_num(r, C_RMSE_HI, b.hi);
}

static void score_run(run_ctx *ctx, const gib_scene *scene, const gib_gpu_scene *gpu,
                      const gib_matrix_run *mr, gib_run_result *res)
{
    const gib_technique *t = mr->technique;
    char img_dir[2048];
    snprintf(img_dir, sizeof img_dir, "%s/images/%s", ctx->out, ctx->m->name);
    gib_error err;
    if (ctx->images && gib_mkdirs(img_dir, &err) < 0) {
        fprintf(stderr, "gibench run: %s\n", err.msg);
        ctx->images = 0;
    }
    /* The passes first: a run whose rows are all in the CSV (run_done) then has its passes too,
     * whenever the process is stopped. */
    for (int p = 0; res->ok && p < res->pass_count; p++) {
        char v[PASS_COLUMNS][256];
        const char *ptr[PASS_COLUMNS];
        snprintf(v[0], 256, "%s", ctx->m->name);
        snprintf(v[1], 256, "%s", ctx->m->profile);
        snprintf(v[2], 256, "%s", mr->scene);
        snprintf(v[3], 256, "%s", t->name);
        snprintf(v[4], 256, "%s", mr->params_key);
        snprintf(v[5], 256, "%d", mr->width);
        snprintf(v[6], 256, "%d", mr->height);
        snprintf(v[7], 256, "%.9g", mr->time);
        snprintf(v[8], 256, "%s", res->passes[p].name);
        snprintf(v[9], 256, "%.6g", res->passes[p].median_ms);
        snprintf(v[10], 256, "%.6g", res->passes[p].min_ms);
        snprintf(v[11], 256, "%.6g", res->passes[p].max_ms);
        snprintf(v[12], 256, "%.6g", res->passes[p].iqr_ms);
        snprintf(v[13], 256, "%.6g", res->passes[p].first_ms);
        snprintf(v[14], 256, "%s", ctx->info.renderer);
        snprintf(v[15], 256, "%s", gib_git_revision());
        for (int k = 0; k < PASS_COLUMNS; k++)
            ptr[k] = v[k];
        if (gib_csv_append(ctx->passes, ptr, &err) < 0) {
            fprintf(stderr, "gibench run: %s: stopping (the rows before it are intact; a rerun "
                            "resumes)\n", err.msg);
            ctx->write_failed = 1;
            return;
        }
    }
    for (unsigned bit = 1, i = 0; bit <= GIB_OUT_CAUSTIC; bit <<= 1) {
        if (!(t->components & bit))
            continue;
        row r;
        row_identity(&r, ctx, mr, bit);
        row_set(&r, C_SCENE_MEM, "%llu", (unsigned long long)gpu->ledger.peak_bytes);
        row_set(&r, C_MEM, "%llu", (unsigned long long)res->technique_bytes);
        row_set(&r, C_MEM_STRUCT, "%s", res->memory_by_structure);
        row_set(&r, C_MEM_PLANNED, "%s", res->planned_structures);
        row_set(&r, C_COUNTERS, "%s", res->counters);
        if (res->driver_bytes >= 0)
            row_set(&r, C_DRIVER_MEM, "%lld", res->driver_bytes);
        if (!res->ok) {
            row_set(&r, C_STATUS, "%s", res->status);
            row_set(&r, C_MESSAGE, "%s", res->err.msg);
            append_row(ctx, &r);
            continue;
        }
        fmt_num(&r, C_GPU_MED, res->gpu_total.median_ms);
        fmt_num(&r, C_GPU_MIN, res->gpu_total.min_ms);
        fmt_num(&r, C_GPU_MAX, res->gpu_total.max_ms);
        fmt_num(&r, C_GPU_IQR, res->gpu_total.iqr_ms);
        fmt_num(&r, C_CPU, res->cpu_total.median_ms);
        fmt_num(&r, C_CPU_IQR, res->cpu_total.iqr_ms);
        fmt_num(&r, C_FIRST_FRAME, res->first_frame_ms);
        fmt_num(&r, C_FIRST_GPU, res->gpu_total.first_ms);
        const gib_image *img = &res->images[i++];
        const char *comp = gib_output_name(bit);
        gib_ref_request rq;
        int component = row_request(ctx, scene, mr, bit, &rq);
        gib_ref_result ref;
        int grc = component < 0 ? -1 : reference_to_rank(ctx, &rq, img, scene->exposure, &ref, &err);
        if (grc == GIB_REF_WRITE_FAILED) {
            /* The disk is full: no row (a rerun redoes this run), the run stops as for a table. */
            fprintf(stderr, "gibench run: %s: stopping (the rows before it are intact; a rerun "
                            "resumes)\n", err.msg);
            ctx->write_failed = 1;
            return;
        }
        if (grc < 0) {
            row_set(&r, C_STATUS, "reference_failed");
            row_set(&r, C_MESSAGE, "%s", component < 0 ? "no reference estimator for this component"
                                                       : err.msg);
            append_row(ctx, &r);
            continue;
        }
        char name[512];
        char at[48] = "";
        if (mr->time != 0.0) /* names of runs at t = 0 stay what they were */
            snprintf(at, sizeof at, "_t%g", mr->time);
        snprintf(name, sizeof name, "%s_%s_%s_%dx%d%s_%s", mr->scene, t->name, mr->params_key,
                 mr->width, mr->height, at, comp);
        for (char *p = name; *p; p++)
            if (*p == ';' || *p == '=')
                *p = *p == ';' ? '_' : '-';
        /* File names stop at 255 bytes: a long parameter list (lrsm has 15) becomes its hash. */
        if (strlen(name) + strlen("_error.png") + 16 > 240) {
            char hex[17];
            gib_hash_hex(gib_hash_str(GIB_HASH_INIT, mr->params_key), hex);
            snprintf(name, sizeof name, "%s_%s_p%s_%dx%d%s_%s", mr->scene, t->name, hex, mr->width,
                     mr->height, at, comp);
        }
        if (ctx->images) {
            /* The reference beside the technique images, once per (scene, component, size, dmax). */
            char ref_png[4096];
            const char *slash = strrchr(ref.path, '/');
            snprintf(ref_png, sizeof ref_png, "%s/reference_%s", img_dir, slash ? slash + 1 : ref.path);
            char *dot = strrchr(ref_png, '.');
            if (dot)
                strcpy(dot, ".png");
            if (access(ref_png, F_OK) != 0 && gib_png_write_preview(ref_png, &ref.image, scene->exposure, &err) < 0)
                fprintf(stderr, "gibench run: %s\n", err.msg);
            /* The row's images by name, relative to DIR/images/<matrix>/ (the report reads them). */
            row_set(&r, C_IMAGE, "%s", name);
            row_set(&r, C_REF_IMAGE, "%s", strrchr(ref_png, '/') + 1);
        }
        gib_metrics m;
        int src = gib_score_and_save(&ref.image, img, scene->exposure, ctx->images ? img_dir : NULL,
                                     name, &m, &err);
        if (src == GIB_IMAGE_WRITE_FAILED) {
            fprintf(stderr, "gibench run: %s: stopping (the rows before it are intact; a rerun "
                            "resumes)\n", err.msg);
            ctx->write_failed = 1;
            gib_image_free(&ref.image);
            return;
        }
        if (src < 0) {
            row_set(&r, C_STATUS, "scoring_failed");
            row_set(&r, C_MESSAGE, "%s", err.msg);
        } else {
            fmt_num(&r, C_RMSE, m.rmse);
            fmt_num(&r, C_REL_RMSE, m.rel_rmse);
            fmt_num(&r, C_MEAN_RATIO, m.mean_ratio);
            set_error_scale(&r, &m, ref.noise_rmse, (long)mr->width * mr->height);
            fmt_num(&r, C_PSNR, m.psnr);
            fmt_num(&r, C_SSIM, m.ssim);
            fmt_num(&r, C_FLIP, m.flip);
            fmt_num(&r, C_HDRFLIP, m.hdrflip);
            row_set(&r, C_NONFINITE, "%ld", m.nonfinite);
            /* A reference noisier than a fifth of the error cannot rank techniques. */
            row_set(&r, C_REF_NOISY, "%d", ref.noise_rmse > 0.2 * m.rmse);
            row_set(&r, C_STATUS, "%s", m.nonfinite ? "nonfinite" : "ok");
            if (m.nonfinite)
                row_set(&r, C_MESSAGE, "%ld NaN/Inf values in the image", m.nonfinite);
        }
        row_set(&r, C_REF_SPP, "%d", ref.spp);
        fmt_num(&r, C_REF_NOISE, ref.noise_rmse);
        append_row(ctx, &r);
        printf("  %-10s %-8s %-36s %4dx%-4d t %-5g gpu %8.3f ms  rmse %.4g  ssim %.4f  flip %.4f"
               "  %s\n",
               mr->scene, t->name, mr->params_key, mr->width, mr->height, mr->time,
               res->gpu_total.median_ms, m.rmse, m.ssim, m.flip, r.v[C_STATUS]);
        gib_image_free(&ref.image);
    }
}

static int scene_wanted(const gib_scene *s, const gib_technique *t, char *why, size_t len)
{
    if ((s->features & t->scene_needs) != t->scene_needs) {
        char f[256];
        gib_features_str(t->scene_needs & ~s->features, f, sizeof f);
        snprintf(why, len, "scene lacks %s", f);
        return 0;
    }
    if (t->scene_needs_any && !(s->features & t->scene_needs_any)) {
        char f[256];
        gib_features_str(t->scene_needs_any, f, sizeof f);
        snprintf(why, len, "scene has none of %s", f);
        return 0;
    }
    return 1;
}

static void run_matrix(run_ctx *ctx)
{
    const gib_matrix *m = ctx->m;
    char *done_scene = calloc(m->run_count, 1);
    for (int i = 0; done_scene && i < m->run_count && !ctx->write_failed; i++) {
        if (done_scene[i])
            continue;
        const char *sname = m->runs[i].scene;
        int pending = 0, mine = 0;
        for (int j = i; j < m->run_count; j++)
            if (!strcmp(m->runs[j].scene, sname) && run_mine(ctx, j)) {
                mine++;
                pending += !run_done(ctx, &m->runs[j]);
            }
        for (int j = i; j < m->run_count; j++)
            if (!strcmp(m->runs[j].scene, sname))
                done_scene[j] = 1;
        if (!mine) /* another shard's scene */
            continue;
        if (!pending) {
            printf("%s: every run already in %s\n", sname, ctx->csv->path);
            continue;
        }
        gib_scene scene;
        gib_gpu_scene gpu;
        gib_error err;
        int rc = gib_scene_load(sname, &scene, &err);
        if (rc == GIB_SCENE_UNAVAILABLE) {
            printf("%s: skipped (%d runs): %s\n", sname, pending, err.msg);
            ctx->runs_skipped += pending;
            for (int j = i; j < m->run_count; j++)
                if (!strcmp(m->runs[j].scene, sname) && run_mine(ctx, j) && !run_done(ctx, &m->runs[j]))
                    run_state(ctx, j, 's');
            continue;
        }
        if (rc < 0 || gib_gpu_scene_upload(&scene, &gpu, &err) < 0) {
            fprintf(stderr, "gibench run: scene '%s': %s\n", sname, err.msg);
            if (rc == 0)
                gib_scene_free(&scene);
            ctx->rows_failed += pending;
            for (int j = i; j < m->run_count; j++)
                if (!strcmp(m->runs[j].scene, sname) && run_mine(ctx, j) && !run_done(ctx, &m->runs[j]))
                    run_state(ctx, j, 'f');
            continue;
        }
        printf("%s: %u triangles, %d runs to do\n", sname, scene.triangle_count, pending);
        for (int j = i; j < m->run_count && !ctx->write_failed; j++) {
            const gib_matrix_run *mr = &m->runs[j];
            if (strcmp(mr->scene, sname) || !run_mine(ctx, j) || run_done(ctx, mr))
                continue;
            char why[512];
            if (!scene_wanted(&scene, mr->technique, why, sizeof why)) {
                printf("  %s on %s skipped: %s\n", mr->technique->name, sname, why);
                ctx->runs_skipped++;
                run_state(ctx, j, 's');
                continue;
            }
            gib_run_result res;
            gib_run_technique_at(&gpu, mr->technique, &mr->params, m->camera, mr->width,
                                 mr->height, m->warmup, m->frames, mr->time, m->dt, &res);
            if (!res.ok)
                fprintf(stderr, "gibench run: %s on %s (%s): %s: %s\n", mr->technique->name, sname,
                        mr->params_key, res.status, res.err.msg);
            score_run(ctx, &scene, &gpu, mr, &res);
            gib_run_result_free(&res);
        }
        gib_gpu_scene_free(&gpu);
        gib_scene_free(&scene);
    }
    free(done_scene);
}

/* DIR/<matrix>.shard (shard.h): this shard's runs, their state and the keys of the rows each
 * writes, written under a temporary name and renamed once the runs are done. */
static int write_manifest(const run_ctx *ctx, gib_error *err)
{
    const gib_matrix *m = ctx->m;
    char path[2048], tmp[2100], hex[17];
    snprintf(path, sizeof path, "%s/%s.shard", ctx->out, m->name);
    snprintf(tmp, sizeof tmp, "%s.tmp%d", path, (int)getpid());
    int *ordinal = malloc((size_t)m->run_count * sizeof *ordinal);
    FILE *f = ordinal ? fopen(tmp, "w") : NULL;
    if (!f) {
        free(ordinal);
        return gib_fail(err, "cannot write the shard manifest %s", tmp);
    }
    gib_shard_order(m, ordinal);
    gib_hash_hex(gib_matrix_fingerprint(m), hex);
    fprintf(f, "gibench-shard\t1\nmatrix\t%s\nprofile\t%s\nrevision\t%s\nfingerprint\t%s\n"
               "shard\t%d/%d\nruns\t%d\n",
            m->name, m->profile, gib_git_revision(), hex, ctx->shard.index, ctx->shard.count,
            m->run_count);
    for (int j = 0; j < m->run_count; j++) {
        if (!run_mine(ctx, j))
            continue;
        char st = ctx->state[j];
        fprintf(f, "run\t%d\t%d\t%s\n", j, ordinal[j],
                st == 's' ? "skipped" : st == 'f' ? "failed" : "expect");
        for (unsigned bit = 1; bit <= GIB_OUT_CAUSTIC; bit <<= 1) {
            if (!(m->runs[j].technique->components & bit))
                continue;
            row r;
            char key[4096];
            row_identity(&r, ctx, &m->runs[j], bit);
            row_key(&r, key, sizeof key);
            fprintf(f, "row\t%s\n", key);
        }
    }
    free(ordinal);
    if (fclose(f) != 0 || rename(tmp, path) != 0) {
        unlink(tmp);
        return gib_fail(err, "cannot write the shard manifest %s", path);
    }
    printf("shard %d/%d of %s: manifest %s\n", ctx->shard.index, ctx->shard.count, m->name, path);
    return 0;
}

int gib_cmd_run(int argc, char **argv)
{
    const char *profile = "quick", *out = GIB_PROJECT_ROOT "/results", *cache = NULL;
    const char *history = NULL;
    int no_history = 0;
    const char *files[64];
    int nfiles = 0, backend = GIB_BACKEND_AUTO, images = 1;
    gib_shard shard = {0, 0};
    long warmup = -1, frames = -1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(help, stdout);
            return 0;
        }
        if (!strcmp(a, "--no-images")) {
            images = 0;
            continue;
        }
        if (!strcmp(a, "--no-history")) {
            no_history = 1;
            continue;
        }
        if (a[0] != '-') {
            if (nfiles < 64)
                files[nfiles++] = a;
            continue;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "gibench run: option %s needs a value\n%s", a, help);
            return 2;
        }
        const char *v = argv[++i];
        if (!strcmp(a, "--profile")) profile = v;
        else if (!strcmp(a, "--out")) out = v;
        else if (!strcmp(a, "--cache")) cache = v;
        else if (!strcmp(a, "--shard")) {
            gib_error serr;
            if (gib_shard_parse("--shard", v, &shard, &serr) < 0) {
                fprintf(stderr, "gibench run: %s\n", serr.msg);
                return 2;
            }
        }
        else if (!strcmp(a, "--history")) history = v;
        else if (!strcmp(a, "--warmup") || !strcmp(a, "--frames")) {
            gib_error verr;
            int warm = !strcmp(a, "--warmup");
            if (gib_parse_int(a, v, warm ? 0 : 1, warm ? 100 : GIB_TIMER_MAX_FRAMES,
                              warm ? &warmup : &frames, &verr) < 0) {
                fprintf(stderr, "gibench run: %s\n", verr.msg);
                return 2;
            }
        }
        else if (!strcmp(a, "--backend")) {
            if ((backend = gib_backend_parse(v)) < 0) {
                fprintf(stderr, "gibench run: --backend expects egl, osmesa or auto, got '%s'\n", v);
                return 2;
            }
        } else {
            fprintf(stderr, "gibench run: unknown option '%s'\n%s", a, help);
            return 2;
        }
    }
    if (!nfiles) {
        fprintf(stderr, "gibench run: no matrix file given\n%s", help);
        return 2;
    }
    gib_error err;
    columns cols;
    if (make_columns(&cols, &err) < 0) {
        fprintf(stderr, "gibench run: %s\n", err.msg);
        return 1;
    }
    /* Every matrix is expanded and validated before anything renders. */
    gib_matrix *ms = calloc(nfiles, sizeof *ms);
    int total = 0;
    for (int i = 0; i < nfiles; i++) {
        if (gib_matrix_load(files[i], profile, &ms[i], &err) < 0) {
            fprintf(stderr, "gibench run: %s\n", err.msg);
            for (int k = 0; k < i; k++)
                gib_matrix_free(&ms[k]);
            free(ms);
            return 2;
        }
        total += ms[i].run_count;
        if (warmup >= 0)
            ms[i].warmup = (int)warmup;
        if (frames >= 0)
            ms[i].frames = (int)frames;
    }
    char cache_dir[2048];
    snprintf(cache_dir, sizeof cache_dir, "%s", cache ? cache : GIB_PROJECT_ROOT "/results/cache");
    run_ctx ctx = {.out = out, .cache = cache_dir, .images = images, .shard = shard};
    if (gib_mkdirs(out, &err) < 0 || gib_gl_init(backend, &ctx.info, &err) < 0) {
        fprintf(stderr, "gibench run: %s\n", err.msg);
        for (int k = 0; k < nfiles; k++)
            gib_matrix_free(&ms[k]);
        free(ms);
        return 1;
    }
    printf("gibench run: %d matrices, %d runs, profile %s, on %s (%s, %s)\n", nfiles, total,
           profile, ctx.info.renderer, ctx.info.backend, ctx.info.version);
    char hist_path[2048];
    snprintf(hist_path, sizeof hist_path, "%s", history ? history : "");
    if (!history)
        snprintf(hist_path, sizeof hist_path, "%s/history.sqlite", out);
    gib_history_machine machine;
    gib_history_machine_detect(&machine, ctx.info.renderer, ctx.info.version, ctx.info.backend);
    if (!no_history && gib_history_open(&ctx.hist, hist_path, &err) < 0) {
        fprintf(stderr, "gibench run: --history: %s\n", err.msg);
        gib_gl_shutdown();
        for (int k = 0; k < nfiles; k++)
            gib_matrix_free(&ms[k]);
        free(ms);
        return 1;
    }
    int status = 0;
    for (int i = 0; i < nfiles && !ctx.write_failed; i++) {
        gib_csv csv = {.lock_fd = -1}, passes = {.lock_fd = -1};
        char path[2048], ppath[2048];
        snprintf(path, sizeof path, "%s/%s.csv", out, ms[i].name);
        snprintf(ppath, sizeof ppath, "%s/%s_passes.csv", out, ms[i].name);
        /* A table restarted for new columns restarts its passes too: their rows belong to runs
         * that are gone, and would stand in (same key) for the passes of the runs redone. */
        if (gib_csv_open(&csv, path, cols.names, cols.count, key_columns, NKEY, &err) < 0 ||
            (csv.moved_aside && gib_csv_move_aside(ppath, &err) < 0) ||
            gib_csv_open(&passes, ppath, pass_columns, PASS_COLUMNS, pass_key_columns, 8, &err) < 0) {
            fprintf(stderr, "gibench run: %s\n", err.msg);
            gib_csv_close(&csv);
            gib_csv_close(&passes);
            status = 1;
            continue;
        }
        printf("matrix %s (%d runs): %s\n", ms[i].name, ms[i].run_count, ms[i].description);
        ctx.machine = &machine;
        ctx.hist_run = 0; /* a history run is recorded with the matrix's first new row */
        ctx.m = &ms[i];
        ctx.cols = &cols;
        ctx.csv = &csv;
        ctx.passes = &passes;
        int *owner = NULL;
        if (shard.count) {
            owner = malloc((size_t)ms[i].run_count * sizeof *owner);
            ctx.state = calloc((size_t)ms[i].run_count + 1, 1);
            if (!owner || !ctx.state) {
                fprintf(stderr, "gibench run: out of memory splitting %s into shards\n", ms[i].name);
                free(owner), free(ctx.state), ctx.state = NULL;
                gib_csv_close(&csv), gib_csv_close(&passes);
                status = 1;
                continue;
            }
            gib_shard_assign(&ms[i], shard.count, owner);
            int mine = 0;
            for (int j = 0; j < ms[i].run_count; j++)
                if (owner[j] == shard.index) {
                    ctx.state[j] = 'e';
                    mine++;
                }
            printf("shard %d/%d: %d of the %d runs\n", shard.index, shard.count, mine,
                   ms[i].run_count);
            ctx.owner = owner;
        }
        run_matrix(&ctx);
        if (shard.count && !ctx.write_failed && write_manifest(&ctx, &err) < 0) {
            fprintf(stderr, "gibench run: %s\n", err.msg);
            status = 1;
        }
        free(owner);
        free(ctx.state);
        ctx.owner = NULL;
        ctx.state = NULL;
        gib_csv_close(&csv);
        gib_csv_close(&passes);
    }
    printf("gibench run: %d rows written (%d not ok, %d out of memory), %d runs skipped\n",
           ctx.rows_written, ctx.rows_failed, ctx.rows_out_of_memory, ctx.runs_skipped);
    if (ctx.hist)
        printf("gibench run: rows recorded in %s\n", hist_path);
    if (ctx.rows_failed || ctx.hist_failed || ctx.write_failed)
        status = 1;
    gib_history_close(ctx.hist);
    gib_gl_shutdown();
    for (int k = 0; k < nfiles; k++)
        gib_matrix_free(&ms[k]);
    free(ms);
    return status;
}

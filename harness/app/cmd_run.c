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
#include "refset.h"
#include "history.h"
#include "harness/base/status.h"
#include "harness/base/hash.h"
#include "matrix.h"
#include "progress.h"
#include "schema.h"
#include "options.h"
#include "run_rows.h"
#include "shard.h"

static const gib_command_doc doc = {
    "run", "MATRIX... [options]",
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
    "profile's counts (the timing benchmark's longer warm-up, harness/reporting/bench_timing.py).\n"
    "--warmup auto renders warm-up frames until three frames' GPU times agree within 5%\n"
    "(at most 60 frames or 2 s); the rows' warmup column says how many it took.\n"
    "\n"
    "--timing-only times and measures memory only: no references, no scores, no images (the\n"
    "rows' metric columns stay empty; each image is still checked for NaN/Inf). For a lent GPU,\n"
    "whose minutes go to frames (harness/device/run_on_nvidia.sh).\n"
    "\n"
    "Every pass row counts its work in the first warm frame (GL pipeline statistics: vertices,\n"
    "primitives, fragment and compute invocations) and says whether it ran raster or compute.\n"};

/* Whether run j is this process's to do: every run, or with --shard this shard's share. */
static int run_mine(const gib_run_ctx *ctx, int j)
{
    return !ctx->shard.count || ctx->owner[j] == ctx->shard.index;
}

static void run_state(gib_run_ctx *ctx, int j, char state)
{
    if (ctx->state)
        ctx->state[j] = state;
}

static int run_done(const gib_run_ctx *ctx, const gib_matrix_run *mr)
{
    for (unsigned bit = 1; bit <= GIB_OUT_CAUSTIC; bit <<= 1) {
        if (!(mr->technique->components & bit))
            continue;
        gib_row r;
        char key[4096];
        gib_run_row_identity(&r, ctx, mr, bit);
        gib_row_key(&r, key, sizeof key);
        if (!gib_csv_has(ctx->csv, key))
            return 0;
    }
    return 1;
}

/* Marks this process's unfinished runs of scene sname (from run `from` on) with state; they
 * count as done for the progress. */
static void mark_scene_runs(gib_run_ctx *ctx, int from, const char *sname, char state)
{
    const gib_matrix *m = ctx->m;
    for (int j = from; j < m->run_count; j++)
        if (!strcmp(m->runs[j].scene, sname) && run_mine(ctx, j) && !run_done(ctx, &m->runs[j])) {
            run_state(ctx, j, state);
            gib_progress_run_done(&ctx->progress, j);
        }
    gib_progress_report(&ctx->progress);
}

/* Which runs of matrix m are of the scene and can run on it (want[j]); with `mine`, only this
 * process's unfinished ones (ctx's matrix). */
static void scene_runs(const gib_run_ctx *ctx, const gib_matrix *m, const gib_scene *scene,
                       const char *sname, int mine, char *want)
{
    for (int j = 0; j < m->run_count; j++) {
        const gib_matrix_run *mr = &m->runs[j];
        want[j] = !strcmp(mr->scene, sname) && gib_scene_wanted(scene, mr->technique, NULL, 0) &&
                  (!mine || (run_mine(ctx, j) && !run_done(ctx, mr)));
    }
}

/* The references this process's unfinished runs of the scene ask for first, and without --shard
 * those of the runs of the scene in the run's later matrices whose tables do not exist yet
 * (fresh: every run to do), each world's rendered together (refset.h: the same pixels and keys
 * as one at a time, the scene's world built once an instant instead of once a request and
 * matrix): the runs then find them in the cache. A failure here is left to the runs, which ask
 * again and report their own. */
static void prefetch_scene_refs(gib_run_ctx *ctx, int from, const gib_scene *scene)
{
    const gib_matrix *m = ctx->m;
    enum { MAX_REQUESTS = 1024 };
    int most = m->run_count;
    for (int k = 0; k < ctx->nlater; k++)
        most = ctx->later[k].run_count > most ? ctx->later[k].run_count : most;
    char *want = ctx->timing_only ? NULL : calloc((size_t)most + 1, 1);
    gib_ref_request *rq = want ? malloc(MAX_REQUESTS * sizeof *rq) : NULL;
    int n = 0;
    if (rq) {
        scene_runs(ctx, m, scene, m->runs[from].scene, 1, want);
        n = gib_matrix_ref_requests(m, ctx->cache, scene, want, rq, MAX_REQUESTS);
    }
    for (int k = 0; rq && !ctx->shard.count && k < ctx->nlater; k++) {
        const gib_matrix *l = &ctx->later[k];
        char table[2048];
        snprintf(table, sizeof table, "%s/%s.csv", ctx->out, l->name);
        if (access(table, F_OK) == 0)
            continue; /* a table to resume: its done runs need no reference */
        scene_runs(ctx, l, scene, m->runs[from].scene, 0, want);
        n += gib_matrix_ref_requests(l, ctx->cache, scene, want, rq + n, MAX_REQUESTS - n);
    }
    gib_error err;
    if (n > 1 && gib_reference_prefetch(rq, n, &err) < 0)
        fprintf(stderr, "gibench run: %s's references, rendered together: %s (each run asks "
                        "again)\n", scene->name, err.msg);
    free(rq);
    free(want);
}

/* Runs this process's unfinished runs of an uploaded scene (from run `from` on). */
static void run_scene_runs(gib_run_ctx *ctx, int from, const gib_scene *scene,
                           const gib_gpu_scene *gpu)
{
    const gib_matrix *m = ctx->m;
    const char *sname = m->runs[from].scene;
    prefetch_scene_refs(ctx, from, scene);
    for (int j = from; j < m->run_count && !ctx->write_failed; j++) {
        const gib_matrix_run *mr = &m->runs[j];
        if (strcmp(mr->scene, sname) || !run_mine(ctx, j) || run_done(ctx, mr))
            continue;
        char why[512];
        if (!gib_scene_wanted(scene, mr->technique, why, sizeof why)) {
            gib_progress_clear(&ctx->progress);
            printf("  %s on %s skipped: %s\n", mr->technique->name, sname, why);
            ctx->runs_skipped++;
            run_state(ctx, j, 's');
            gib_progress_run_done(&ctx->progress, j);
            continue;
        }
        gib_run_result res;
        const gib_external *x = gib_matrix_external(m, mr->technique);
        if (x)
            gib_external_run(&(gib_external_request){.x = x, .scene = scene, .scene_name = sname,
                                                     .params = &mr->params, .camera = m->camera,
                                                     .width = mr->width, .height = mr->height,
                                                     .warmup = m->warmup < 0 ? GIB_WARMUP_FALLBACK
                                                                             : m->warmup,
                                                     .frames = m->frames, .time = mr->time},
                             &res);
        else
            gib_run(&(gib_run_request){.scene = gpu, .technique = mr->technique,
                                       .params = &mr->params, .camera = m->camera,
                                       .width = mr->width, .height = mr->height,
                                       .warmup = m->warmup, .frames = m->frames, .time = mr->time,
                                       .dt = m->dt, .sequence = m->sequence},
                    &res);
        if (!res.ok)
            fprintf(stderr, "gibench run: %s on %s (%s): %s: %s\n", mr->technique->name, sname,
                    mr->params_key, res.status, res.err.msg);
        gib_run_score(ctx, scene, gpu, mr, &res);
        gib_run_result_free(&res);
        gib_progress_run_done(&ctx->progress, j);
        gib_progress_report(&ctx->progress);
    }
}

/* The runs of the scene of run i (i its first): loads and uploads it once for them all. */
static void run_scene(gib_run_ctx *ctx, int i, int pending)
{
    const char *sname = ctx->m->runs[i].scene;
    gib_scene scene;
    gib_gpu_scene gpu;
    gib_error err;
    int rc = gib_scene_load(sname, &scene, &err);
    if (rc == GIB_SCENE_UNAVAILABLE) {
        printf("%s: skipped (%d runs): %s\n", sname, pending, err.msg);
        ctx->runs_skipped += pending;
        mark_scene_runs(ctx, i, sname, 's');
        return;
    }
    if (rc < 0 || gib_gpu_scene_upload(&scene, &gpu, &err) < 0) {
        fprintf(stderr, "gibench run: scene '%s': %s\n", sname, err.msg);
        if (rc == 0)
            gib_scene_free(&scene);
        ctx->rows_failed += pending;
        mark_scene_runs(ctx, i, sname, 'f');
        return;
    }
    gib_progress_clear(&ctx->progress);
    printf("%s: %u triangles, %d runs to do\n", sname, scene.triangle_count, pending);
    run_scene_runs(ctx, i, &scene, &gpu);
    gib_gpu_scene_free(&gpu);
    gib_scene_free(&scene);
}

/* Which runs this process will do (its share, not yet in the table), for the progress. */
static int start_progress(gib_run_ctx *ctx)
{
    const gib_matrix *m = ctx->m;
    char *todo = calloc(m->run_count ? (size_t)m->run_count : 1, 1);
    if (!todo)
        return -1;
    for (int j = 0; j < m->run_count; j++)
        todo[j] = run_mine(ctx, j) && !run_done(ctx, &m->runs[j]);
    int rc = gib_progress_start(&ctx->progress, m, todo);
    free(todo);
    return rc;
}

static void run_matrix(gib_run_ctx *ctx)
{
    const gib_matrix *m = ctx->m;
    if (start_progress(ctx) < 0) {
        fprintf(stderr, "gibench run: out of memory\n");
        ctx->write_failed = 1;
        return;
    }
    char *done_scene = calloc(m->run_count, 1);
    for (int i = 0; done_scene && i < m->run_count && !ctx->write_failed; i++) {
        if (done_scene[i])
            continue;
        const char *sname = m->runs[i].scene;
        int pending = 0, mine = 0;
        for (int j = i; j < m->run_count; j++)
            if (!strcmp(m->runs[j].scene, sname)) {
                done_scene[j] = 1;
                if (run_mine(ctx, j)) {
                    mine++;
                    pending += !run_done(ctx, &m->runs[j]);
                }
            }
        if (!mine) /* another shard's scene */
            continue;
        if (!pending)
            printf("%s: every run already in %s\n", sname, ctx->csv->path);
        else
            run_scene(ctx, i, pending);
    }
    free(done_scene);
    gib_progress_free(&ctx->progress);
}

/* DIR/<matrix>.shard (shard.h): this shard's runs, their state and the keys of the rows each
 * writes, written under a temporary name and renamed once the runs are done. */
static int write_manifest(const gib_run_ctx *ctx, gib_error *err)
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
            gib_row r;
            char key[4096];
            gib_run_row_identity(&r, ctx, &m->runs[j], bit);
            gib_row_key(&r, key, sizeof key);
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

/* ---- the command ---- */

typedef struct run_opts {
    const char *profile, *out, *cache, *history;
    const char *files[64];
    int nfiles, backend, images, no_images, no_history, timing_only;
    gib_shard shard;
    long warmup, frames;
} run_opts;

static int parse_shard(const gib_option *o, const char *v, gib_error *err)
{
    return gib_shard_parse(o->name, v, o->dest, err);
}

/* --warmup W, or auto: until three frames' GPU times agree. */
static int parse_warmup(const gib_option *o, const char *v, gib_error *err)
{
    if (!strcmp(v, "auto")) {
        *(long *)o->dest = GIB_WARMUP_AUTO;
        return 0;
    }
    return gib_parse_int(o->name, v, 0, 100, o->dest, err);
}

/* Returns -1 to go on, 0 after --help, 2 on bad usage. */
static int parse_options(int argc, char **argv, run_opts *o)
{
    *o = (run_opts){.profile = "quick", .out = GIB_PROJECT_ROOT "/results",
                    .backend = GIB_BACKEND_AUTO, .warmup = -1, .frames = -1};
    const gib_option opts[] = {
        GIB_OPTION_TEXT("--profile", &o->profile, "P", "the matrices' profile (quick, paper, ...)"),
        GIB_OPTION_TEXT("--out", &o->out, "DIR", "the tables and images (default results)"),
        GIB_OPTION_TEXT("--cache", &o->cache, "DIR", "the references (default results/cache)"),
        GIB_OPTION_BACKEND("--backend", &o->backend),
        GIB_OPTION_FLAG("--no-images", &o->no_images, "write no images"),
        GIB_OPTION_CUSTOM("--shard", &o->shard, parse_shard, "I/N", "run share I of N"),
        GIB_OPTION_TEXT("--history", &o->history, "PATH", "the results history"),
        GIB_OPTION_FLAG("--no-history", &o->no_history, "record no history"),
        GIB_OPTION_CUSTOM("--warmup", &o->warmup, parse_warmup, "W|auto",
                          "warm-up frames instead of the profile's"),
        GIB_OPTION_INT("--frames", &o->frames, 1, GIB_TIMER_MAX_FRAMES, "F",
                       "timed frames instead of the profile's"),
        GIB_OPTION_FLAG("--timing-only", &o->timing_only, "times and memory only, no scores"),
        {0}};
    int rc = gib_options_parse(&doc, opts, argc, argv, o->files, &o->nfiles, 64);
    if (rc != GIB_OPTIONS_PROCEED)
        return rc;
    o->images = !o->no_images;
    if (!o->nfiles) {
        fputs("gibench run: no matrix file given\n", stderr);
        gib_options_usage(stderr, &doc, opts);
        return 2;
    }
    return -1;
}

static void free_matrices(gib_matrix *ms, int n)
{
    for (int k = 0; ms && k < n; k++)
        gib_matrix_free(&ms[k]);
    free(ms);
}

/* Every matrix expanded and validated before anything renders, with its table's layout. */
static int load_matrices(const run_opts *o, gib_matrix **out, gib_table_layout **layouts,
                         int *total)
{
    gib_matrix *ms = calloc(o->nfiles, sizeof *ms);
    gib_table_layout *ls = calloc(o->nfiles, sizeof *ls);
    gib_error err;
    *total = 0;
    for (int i = 0; ms && ls && i < o->nfiles; i++) {
        if (gib_matrix_load(o->files[i], o->profile, &ms[i], &err) < 0 ||
            gib_table_layout_of(&ms[i], &ls[i], &err) < 0) {
            fprintf(stderr, "gibench run: %s\n", err.msg);
            free_matrices(ms, i + 1);
            free(ls);
            return -1;
        }
        *total += ms[i].run_count;
        if (o->warmup >= 0 || o->warmup == GIB_WARMUP_AUTO)
            ms[i].warmup = (int)o->warmup;
        if (o->frames >= 0)
            ms[i].frames = (int)o->frames;
    }
    if (!ms || !ls) {
        fprintf(stderr, "gibench run: out of memory\n");
        free(ms), free(ls);
        return -1;
    }
    *out = ms;
    *layouts = ls;
    return 0;
}

/* Opens DIR/<matrix>.csv and its passes table. A table restarted for new columns restarts its
 * passes too: their rows belong to runs that are gone, and would stand in (same key) for the
 * passes of the runs redone. */
static int open_tables(const char *out, const gib_matrix *m, const gib_table_layout *l,
                       gib_csv *csv, gib_csv *passes, gib_error *err)
{
    char path[2048], ppath[2048];
    int key[GIB_C_COUNT], pkey[GIB_P_COUNT];
    int nkey = gib_schema_key(gib_run_columns, GIB_C_COUNT, GIB_KEY_ROW, key, GIB_C_COUNT);
    int npkey = gib_schema_key(gib_pass_columns, GIB_P_COUNT, GIB_KEY_ROW, pkey, GIB_P_COUNT);
    const char *pnames[GIB_P_COUNT];
    for (int k = 0; k < GIB_P_COUNT; k++)
        pnames[k] = gib_pass_columns[k].name;
    snprintf(path, sizeof path, "%s/%s.csv", out, m->name);
    snprintf(ppath, sizeof ppath, "%s/%s_passes.csv", out, m->name);
    if (gib_csv_open(csv, path, l->names, l->count, key, nkey, err) < 0 ||
        (csv->moved_aside && gib_csv_move_aside(ppath, err) < 0) ||
        gib_csv_open(passes, ppath, pnames, GIB_P_COUNT, pkey, npkey, err) < 0)
        return -1;
    return 0;
}

/* With --shard: which runs are this shard's (ctx->owner, ctx->state). */
static int assign_shard(gib_run_ctx *ctx, int **owner)
{
    const gib_matrix *m = ctx->m;
    *owner = malloc((size_t)m->run_count * sizeof **owner);
    ctx->state = calloc((size_t)m->run_count + 1, 1);
    if (!*owner || !ctx->state) {
        fprintf(stderr, "gibench run: out of memory splitting %s into shards\n", m->name);
        free(*owner), free(ctx->state);
        *owner = NULL, ctx->state = NULL;
        return -1;
    }
    gib_shard_assign(m, ctx->shard.count, *owner);
    int mine = 0;
    for (int j = 0; j < m->run_count; j++)
        if ((*owner)[j] == ctx->shard.index) {
            ctx->state[j] = 'e';
            mine++;
        }
    printf("shard %d/%d: %d of the %d runs\n", ctx->shard.index, ctx->shard.count, mine,
           m->run_count);
    ctx->owner = *owner;
    return 0;
}

/* One matrix into its tables. Returns 1 when it could not run or write its manifest. */
static int run_one_matrix(gib_run_ctx *ctx, const gib_matrix *m, const gib_table_layout *l)
{
    gib_csv csv = {.lock_fd = -1}, passes = {.lock_fd = -1};
    gib_error err;
    int status = 0, *owner = NULL;
    if (open_tables(ctx->out, m, l, &csv, &passes, &err) < 0) {
        fprintf(stderr, "gibench run: %s\n", err.msg);
        gib_csv_close(&csv);
        gib_csv_close(&passes);
        return 1;
    }
    printf("matrix %s (%d runs): %s\n", m->name, m->run_count, m->description);
    ctx->hist_run = 0; /* a history run is recorded with the matrix's first new gib_row */
    ctx->m = m;
    ctx->cols = l;
    ctx->csv = &csv;
    ctx->passes = &passes;
    if (ctx->shard.count && assign_shard(ctx, &owner) < 0) {
        status = 1;
    } else {
        run_matrix(ctx);
        if (ctx->shard.count && !ctx->write_failed && write_manifest(ctx, &err) < 0) {
            fprintf(stderr, "gibench run: %s\n", err.msg);
            status = 1;
        }
    }
    free(owner);
    free(ctx->state);
    ctx->owner = NULL;
    ctx->state = NULL;
    gib_csv_close(&csv);
    gib_csv_close(&passes);
    return status;
}

/* The GL context and the results history. Returns 0, or 1 (reported). */
static int start_run(gib_run_ctx *ctx, const run_opts *o, char *hist_path, size_t len,
                     gib_history_machine *machine)
{
    gib_error err;
    if (gib_mkdirs(o->out, &err) < 0 || gib_gl_init(o->backend, &ctx->info, &err) < 0) {
        fprintf(stderr, "gibench run: %s\n", err.msg);
        return 1;
    }
    snprintf(hist_path, len, "%s", o->history ? o->history : "");
    if (!o->history)
        snprintf(hist_path, len, "%s/history.sqlite", o->out);
    gib_history_machine_detect(machine, ctx->info.renderer, ctx->info.version, ctx->info.backend);
    ctx->machine = machine;
    if (!o->no_history && gib_history_open(&ctx->hist, hist_path, &err) < 0) {
        fprintf(stderr, "gibench run: --history: %s\n", err.msg);
        gib_gl_shutdown();
        return 1;
    }
    return 0;
}

int gib_cmd_run(int argc, char **argv)
{
    run_opts o;
    int rc = parse_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    gib_matrix *ms;
    gib_table_layout *layouts;
    int total;
    if (load_matrices(&o, &ms, &layouts, &total) < 0)
        return 2;
    char cache_dir[2048], hist_path[2048];
    snprintf(cache_dir, sizeof cache_dir, "%s",
             o.cache ? o.cache : GIB_PROJECT_ROOT "/results/cache");
    gib_run_ctx ctx = {.out = o.out, .cache = cache_dir, .images = o.images && !o.timing_only,
                   .timing_only = o.timing_only, .shard = o.shard};
    gib_history_machine machine;
    if (start_run(&ctx, &o, hist_path, sizeof hist_path, &machine)) {
        free_matrices(ms, o.nfiles);
        free(layouts);
        return 1;
    }
    printf("gibench run: %d matrices, %d runs, profile %s, on %s (%s, %s)\n", o.nfiles, total,
           o.profile, ctx.info.renderer, ctx.info.backend, ctx.info.version);
    if (ctx.info.device[0])
        printf("gibench run: EGL %s\n", ctx.info.device);
    int status = 0;
    for (int i = 0; i < o.nfiles && !ctx.write_failed; i++) {
        ctx.later = &ms[i + 1];
        ctx.nlater = o.nfiles - i - 1;
        status |= run_one_matrix(&ctx, &ms[i], &layouts[i]);
    }
    printf("gibench run: %d rows written (%d not ok, %d out of memory), %d runs skipped\n",
           ctx.rows_written, ctx.rows_failed, ctx.rows_out_of_memory, ctx.runs_skipped);
    if (ctx.hist)
        printf("gibench run: rows recorded in %s\n", hist_path);
    if (ctx.rows_failed || ctx.hist_failed || ctx.write_failed)
        status = 1;
    gib_history_close(ctx.hist);
    gib_gl_shutdown();
    free_matrices(ms, o.nfiles);
    free(layouts);
    return status;
}

/* gibench run — a results row: filled cell by cell, its identity, appended to the table and the
 * history (run_rows.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "run_rows.h"
#include "harness/base/status.h"
#include "harness/base/hash.h"

void gib_row_set(gib_row *r, int col, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->v[col], sizeof r->v[col], fmt, ap);
    va_end(ap);
    r->ptr[col] = r->v[col];
}

/* A runs row's identity key: its GIB_KEY_ROW columns joined by '|' (as gib_csv keys rows). */
void gib_row_key(const gib_row *r, char *key, size_t len)
{
    int cols[GIB_C_COUNT];
    int n = gib_schema_key(gib_run_columns, GIB_C_COUNT, GIB_KEY_ROW, cols, GIB_C_COUNT);
    key[0] = 0;
    for (int k = 0; k < n; k++) {
        strncat(key, k ? "|" : "", len - strlen(key) - 1);
        strncat(key, r->v[cols[k]], len - strlen(key) - 1);
    }
}

void gib_row_num(gib_row *r, int col, double v)
{
    if (isnan(v))
        gib_row_set(r, col, "nan");
    else if (isinf(v))
        gib_row_set(r, col, v > 0 ? "inf" : "-inf");
    else
        gib_row_set(r, col, "%.9g", v);
}

/* A table could not be written (a full disk): the run stops there. */
void gib_run_write_failed(gib_run_ctx *ctx, const gib_error *err)
{
    fprintf(stderr, "gibench run: %s: stopping (the rows before it are intact; a rerun resumes)\n",
            err->msg);
    ctx->write_failed = 1;
}

/* The identity part of a row: what makes it this run, and the run's settings and machine. */
void gib_run_row_identity(gib_row *r, const gib_run_ctx *ctx, const gib_matrix_run *mr,
                          unsigned comp)
{
    memset(r->ptr, 0, sizeof r->ptr);
    gib_row_set(r, GIB_C_MATRIX, "%s", ctx->m->name);
    gib_row_set(r, GIB_C_PROFILE, "%s", ctx->m->profile);
    gib_row_set(r, GIB_C_SCENE, "%s", mr->scene);
    gib_row_set(r, GIB_C_CAMERA, "%d", ctx->m->camera);
    gib_row_set(r, GIB_C_TECHNIQUE, "%s", mr->technique->name);
    gib_row_set(r, GIB_C_COMPONENT, "%s", gib_output_name(comp));
    gib_row_set(r, GIB_C_PARAMS, "%s", mr->params_key);
    gib_row_set(r, GIB_C_WIDTH, "%d", mr->width);
    gib_row_set(r, GIB_C_HEIGHT, "%d", mr->height);
    gib_row_set(r, GIB_C_TIME, "%.9g", mr->time);
    gib_row_set(r, GIB_C_DT, "%.9g", ctx->m->dt);
    /* The warm-up the runner renders: more where a sequence needs more frames (runner.h); a run
     * that rendered sets the count it took (an auto warm-up's). */
    const int seq_warmup = ctx->m->sequence - 1 - ctx->m->frames;
    const int warmup = ctx->m->warmup < 0 ? GIB_WARMUP_FALLBACK : ctx->m->warmup;
    gib_row_set(r, GIB_C_WARMUP, "%d", warmup > seq_warmup ? warmup : seq_warmup);
    gib_row_set(r, GIB_C_FRAMES, "%d", ctx->m->frames);
    gib_row_set(r, GIB_C_BACKEND, "%s", ctx->info.backend);
    gib_row_set(r, GIB_C_RENDERER, "%s", ctx->info.renderer);
    gib_row_set(r, GIB_C_GL_VERSION, "%s", ctx->info.version);
    gib_row_set(r, GIB_C_GIT, "%s", gib_git_revision());
    gib_row_set(r, GIB_C_TECH_HASH, "%s", gib_technique_source_hash(mr->technique->name));
    const gib_external *x = gib_matrix_external(ctx->m, mr->technique);
    if (x) { /* an external's: its version for the GL version, a hash of command and version */
        char hex[17];
        gib_row_set(r, GIB_C_BACKEND, "external");
        gib_row_set(r, GIB_C_RENDERER, "%s %s", x->name, x->version);
        gib_row_set(r, GIB_C_GL_VERSION, "%s", x->version);
        gib_hash_hex(gib_hash_str(gib_hash_str(GIB_HASH_INIT, x->command), x->version), hex);
        gib_row_set(r, GIB_C_TECH_HASH, "%s", hex);
        gib_row_set(r, GIB_C_MESSAGE, "external command: %s", x->command); /* failures replace it */
    }
    time_t now = time(NULL);
    strftime(r->v[GIB_C_TIMESTAMP], sizeof r->v[GIB_C_TIMESTAMP], "%Y-%m-%dT%H:%M:%SZ",
             gmtime(&now));
    r->ptr[GIB_C_TIMESTAMP] = r->v[GIB_C_TIMESTAMP];
    /* The parameters the matrix names have columns of their own; all of them are in params. */
    const gib_technique *t = mr->technique;
    for (int p = 0; t->params && t->params[p].name; p++)
        for (int k = GIB_C_COUNT; k < ctx->cols->count; k++)
            if (strcmp(ctx->cols->names[k], t->params[p].name))
                continue;
            else if (!strcmp(t->params[p].name, GIB_PRESET_PARAM))
                gib_row_set(r, k, "%s", gib_params_preset_name(t, &mr->params));
            else
                gib_row_num(r, k, mr->params.values[p]);
}

/* Stops recording after the first failure, which makes the run's exit status 1. */
static void history_failed(gib_run_ctx *ctx, const gib_error *err)
{
    fprintf(stderr, "gibench run: results history not recorded from here on: %s\n", err->msg);
    gib_history_close(ctx->hist);
    ctx->hist = NULL;
    ctx->hist_failed = 1;
}

static void record_history(gib_run_ctx *ctx, const gib_row *r)
{
    gib_error err;
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
}

void gib_run_append_row(gib_run_ctx *ctx, gib_row *r)
{
    gib_error err;
    int w = gib_csv_append(ctx->csv, r->ptr, &err);
    if (w < 0) {
        gib_run_write_failed(ctx, &err);
        return;
    }
    if (w == 0) /* written before an interruption: the row is there once (and in
                 * the history, unless the run was killed between the two writes) */
        return;
    record_history(ctx, r);
    ctx->rows_written++;
    /* out_of_memory is a result (the plan exceeds the device), not a failure of the run. */
    if (gib_status_find(r->v[GIB_C_STATUS]) == GIB_STATUS_OUT_OF_MEMORY)
        ctx->rows_out_of_memory++;
    else if (gib_status_find(r->v[GIB_C_STATUS]) != GIB_STATUS_OK)
        ctx->rows_failed++;
}


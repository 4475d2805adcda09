/* gibench — results history in SQLite (history.h). */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <sqlite3.h>

#include "history.h"

struct gib_history {
    sqlite3 *db;
    sqlite3_stmt *insert;
    char path[1024];
};

/* A writer waits this long for another writer's transaction; runs commit one technique run at a
 * time (milliseconds), so only a stuck process makes a writer give up, with an error naming the
 * file. */
#define BUSY_TIMEOUT_MS 120000

static const char schema[] =
    "CREATE TABLE IF NOT EXISTS machine(id INTEGER PRIMARY KEY, renderer TEXT NOT NULL,"
    " gl_version TEXT NOT NULL, backend TEXT NOT NULL, cpu TEXT NOT NULL, cores INTEGER NOT NULL,"
    " gpu TEXT NOT NULL, UNIQUE(renderer, gl_version, backend, cpu, cores, gpu));"
    "CREATE TABLE IF NOT EXISTS run(id INTEGER PRIMARY KEY,"
    " machine_id INTEGER NOT NULL REFERENCES machine(id), revision TEXT NOT NULL,"
    " started TEXT NOT NULL, matrix TEXT NOT NULL, profile TEXT NOT NULL, host TEXT NOT NULL);"
    "CREATE TABLE IF NOT EXISTS result(id INTEGER PRIMARY KEY,"
    " run_id INTEGER NOT NULL REFERENCES run(id), matrix TEXT, profile TEXT, scene TEXT,"
    " camera INTEGER, technique TEXT, component TEXT, params TEXT, width INTEGER, height INTEGER,"
    " time REAL, gpu_ms_median REAL, cpu_ms REAL, mem_bytes INTEGER, rmse REAL, rel_rmse REAL,"
    " ssim REAL, ref_noise_rmse REAL, status TEXT, revision TEXT, timestamp TEXT,"
    " row_json TEXT NOT NULL);"
    "CREATE INDEX IF NOT EXISTS result_key ON result(scene, technique, component, params, width,"
    " height);"
    "CREATE INDEX IF NOT EXISTS result_run ON result(run_id);";

/* The typed columns of `result` filled from the CSV row's column of the same name, in the order
 * of the INSERT below (after run_id and before row_json). */
enum { T_TEXT, T_INT, T_REAL };
static const struct {
    const char *name, *csv;
    int type;
} typed[] = {
    {"matrix", "matrix", T_TEXT},         {"profile", "profile", T_TEXT},
    {"scene", "scene", T_TEXT},           {"camera", "camera", T_INT},
    {"technique", "technique", T_TEXT},   {"component", "component", T_TEXT},
    {"params", "params", T_TEXT},         {"width", "width", T_INT},
    {"height", "height", T_INT},          {"time", "time", T_REAL},
    {"gpu_ms_median", "gpu_ms_median", T_REAL}, {"cpu_ms", "cpu_ms", T_REAL},
    {"mem_bytes", "mem_bytes", T_INT},    {"rmse", "rmse", T_REAL},
    {"rel_rmse", "rel_rmse", T_REAL},     {"ssim", "ssim", T_REAL},
    {"ref_noise_rmse", "ref_noise_rmse", T_REAL}, {"status", "status", T_TEXT},
    {"revision", "git_revision", T_TEXT}, {"timestamp", "timestamp", T_TEXT},
};
#define NTYPED ((int)(sizeof typed / sizeof typed[0]))

static int db_fail(gib_history *h, gib_error *err, const char *what)
{
    return gib_fail(err, "history %s: %s: %s", h->path, what, sqlite3_errmsg(h->db));
}

static int exec(gib_history *h, const char *sql, gib_error *err)
{
    char *msg = NULL;
    if (sqlite3_exec(h->db, sql, NULL, NULL, &msg) != SQLITE_OK) {
        gib_fail(err, "history %s: %.40s...: %s", h->path, sql, msg ? msg : "error");
        sqlite3_free(msg);
        return -1;
    }
    return 0;
}

void gib_history_machine_detect(gib_history_machine *m, const char *renderer,
                                const char *gl_version, const char *backend)
{
    memset(m, 0, sizeof *m);
    snprintf(m->renderer, sizeof m->renderer, "%s", renderer ? renderer : "");
    snprintf(m->gl_version, sizeof m->gl_version, "%s", gl_version ? gl_version : "");
    snprintf(m->backend, sizeof m->backend, "%s", backend ? backend : "");
    snprintf(m->cpu, sizeof m->cpu, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512];
    while (f && fgets(line, sizeof line, f)) {
        if (strncmp(line, "model name", 10))
            continue;
        const char *c = strchr(line, ':');
        if (c) {
            c++;
            while (*c == ' ' || *c == '\t')
                c++;
            snprintf(m->cpu, sizeof m->cpu, "%s", c);
            m->cpu[strcspn(m->cpu, "\r\n")] = 0;
        }
        break;
    }
    if (f)
        fclose(f);
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    m->cores = n > 0 ? (int)n : 0;
    /* Mesa's software rasterisers name no GPU; any other GL_RENDERER is the device itself. */
    if (!gib_is_software_renderer(m->renderer))
        snprintf(m->gpu, sizeof m->gpu, "%s", m->renderer);
}

const char *const gib_software_renderers[] = {"llvmpipe", "softpipe", "swrast", "Software Rasterizer",
                                              "lavapipe", "SwiftShader", NULL};

int gib_is_software_renderer(const char *renderer)
{
    for (int i = 0; gib_software_renderers[i]; i++)
        if (strstr(renderer, gib_software_renderers[i]))
            return 1;
    return 0;
}

static int history_open(gib_history **out, const char *path, int readonly, gib_error *err)
{
    *out = NULL;
    gib_history *h = gib_calloc(1, sizeof *h, err);
    if (!h)
        return -1;
    snprintf(h->path, sizeof h->path, "%s", path);
    int flags = readonly ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
    if (sqlite3_open_v2(path, &h->db, flags, NULL) != SQLITE_OK) {
        gib_fail(err, "history %s: cannot open: %s", path,
                 h->db ? sqlite3_errmsg(h->db) : "out of memory");
        sqlite3_close(h->db);
        free(h);
        return -1;
    }
    sqlite3_busy_timeout(h->db, BUSY_TIMEOUT_MS);
    if (readonly) {
        /* A file that is not a history says so here, naming it. */
        sqlite3_stmt *st;
        if (sqlite3_prepare_v2(h->db, "SELECT count(*) FROM result JOIN run JOIN machine", -1, &st,
                               NULL) != SQLITE_OK) {
            gib_fail(err, "history %s: not a gibench history: %s", path, sqlite3_errmsg(h->db));
            gib_history_close(h);
            return -1;
        }
        sqlite3_finalize(st);
        *out = h;
        return 0;
    }
    /* The default rollback journal, not WAL: WAL needs shared memory, which a history on a
     * cluster's network file system does not have. The schema is created in a write transaction
     * so two first writers do not race. */
    if (exec(h, "BEGIN IMMEDIATE", err) < 0 || exec(h, schema, err) < 0 ||
        exec(h, "COMMIT", err) < 0) {
        gib_history_close(h);
        return -1;
    }
    char sql[1024] = "INSERT INTO result(run_id";
    for (int i = 0; i < NTYPED; i++)
        snprintf(sql + strlen(sql), sizeof sql - strlen(sql), ", %s", typed[i].name);
    strncat(sql, ", row_json) VALUES(?", sizeof sql - strlen(sql) - 1);
    for (int i = 0; i <= NTYPED; i++)
        strncat(sql, ", ?", sizeof sql - strlen(sql) - 1);
    strncat(sql, ")", sizeof sql - strlen(sql) - 1);
    if (sqlite3_prepare_v2(h->db, sql, -1, &h->insert, NULL) != SQLITE_OK) {
        db_fail(h, err, "preparing the insert");
        gib_history_close(h);
        return -1;
    }
    *out = h;
    return 0;
}

int gib_history_open(gib_history **out, const char *path, gib_error *err)
{
    return history_open(out, path, 0, err);
}

int gib_history_open_readonly(gib_history **out, const char *path, gib_error *err)
{
    return history_open(out, path, 1, err);
}

void gib_history_close(gib_history *h)
{
    if (!h)
        return;
    sqlite3_finalize(h->insert);
    if (!sqlite3_get_autocommit(h->db))
        sqlite3_exec(h->db, "ROLLBACK", NULL, NULL, NULL);
    sqlite3_close(h->db);
    free(h);
}

int gib_history_begin(gib_history *h, gib_error *err)
{
    /* IMMEDIATE takes the write lock now, so two writers never both hold a read lock and
     * deadlock when upgrading (SQLITE_BUSY that busy_timeout cannot resolve). */
    return exec(h, "BEGIN IMMEDIATE", err);
}

int gib_history_commit(gib_history *h, gib_error *err)
{
    return exec(h, "COMMIT", err);
}

static long long machine_id(gib_history *h, const gib_history_machine *m, gib_error *err)
{
    const char *sql[2] = {
        "INSERT OR IGNORE INTO machine(renderer, gl_version, backend, cpu, cores, gpu)"
        " VALUES(?1, ?2, ?3, ?4, ?5, ?6)",
        "SELECT id FROM machine WHERE renderer = ?1 AND gl_version = ?2 AND backend = ?3 AND"
        " cpu = ?4 AND cores = ?5 AND gpu = ?6"};
    long long id = -1;
    for (int k = 0; k < 2; k++) {
        sqlite3_stmt *st;
        if (sqlite3_prepare_v2(h->db, sql[k], -1, &st, NULL) != SQLITE_OK)
            return db_fail(h, err, "machine");
        sqlite3_bind_text(st, 1, m->renderer, -1, SQLITE_STATIC);
        sqlite3_bind_text(st, 2, m->gl_version, -1, SQLITE_STATIC);
        sqlite3_bind_text(st, 3, m->backend, -1, SQLITE_STATIC);
        sqlite3_bind_text(st, 4, m->cpu, -1, SQLITE_STATIC);
        sqlite3_bind_int(st, 5, m->cores);
        sqlite3_bind_text(st, 6, m->gpu, -1, SQLITE_STATIC);
        int rc = sqlite3_step(st);
        if (k == 1 && rc == SQLITE_ROW)
            id = sqlite3_column_int64(st, 0);
        sqlite3_finalize(st);
        if (rc != SQLITE_DONE && rc != SQLITE_ROW)
            return db_fail(h, err, "machine");
    }
    if (id < 0)
        return gib_fail(err, "history %s: machine row missing after insert", h->path);
    return id;
}

int gib_history_begin_run(gib_history *h, const gib_history_machine *m, const char *revision,
                          const char *matrix, const char *profile, long long *run_id,
                          gib_error *err)
{
    if (gib_history_begin(h, err) < 0)
        return -1;
    long long mid = machine_id(h, m, err);
    if (mid < 0) {
        exec(h, "ROLLBACK", NULL);
        return -1;
    }
    char started[32], host[256] = "";
    time_t now = time(NULL);
    strftime(started, sizeof started, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    gethostname(host, sizeof host - 1);
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(h->db,
                           "INSERT INTO run(machine_id, revision, started, matrix, profile, host)"
                           " VALUES(?, ?, ?, ?, ?, ?)", -1, &st, NULL) != SQLITE_OK) {
        db_fail(h, err, "run");
        exec(h, "ROLLBACK", NULL);
        return -1;
    }
    sqlite3_bind_int64(st, 1, mid);
    sqlite3_bind_text(st, 2, revision, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 3, started, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 4, matrix, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 5, profile, -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 6, host, -1, SQLITE_STATIC);
    int rc = sqlite3_step(st);
    sqlite3_finalize(st);
    if (rc != SQLITE_DONE) {
        db_fail(h, err, "run");
        exec(h, "ROLLBACK", NULL);
        return -1;
    }
    *run_id = sqlite3_last_insert_rowid(h->db);
    return gib_history_commit(h, err);
}

/* Whether s is a JSON number as written (RFC 8259): then it goes into row_json unquoted. */
static int json_number(const char *s)
{
    if (*s == '-')
        s++;
    if (*s == '0')
        s++;
    else if (isdigit((unsigned char)*s))
        while (isdigit((unsigned char)*s))
            s++;
    else
        return 0;
    if (*s == '.') {
        if (!isdigit((unsigned char)*++s))
            return 0;
        while (isdigit((unsigned char)*s))
            s++;
    }
    if (*s == 'e' || *s == 'E') {
        s++;
        if (*s == '+' || *s == '-')
            s++;
        if (!isdigit((unsigned char)*s))
            return 0;
        while (isdigit((unsigned char)*s))
            s++;
    }
    return *s == 0;
}

typedef struct sbuf {
    char *p;
    size_t len, cap;
    int oom;
} sbuf;

static void sb_put(sbuf *b, const char *s, size_t n)
{
    if (b->oom)
        return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = (b->cap ? b->cap * 2 : 1024) + n;
        char *p = realloc(b->p, cap);
        if (!p) {
            b->oom = 1;
            return;
        }
        b->p = p;
        b->cap = cap;
    }
    memcpy(b->p + b->len, s, n);
    b->len += n;
    b->p[b->len] = 0;
}

static void sb_json_string(sbuf *b, const char *s)
{
    sb_put(b, "\"", 1);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        char esc[8];
        if (c == '"' || c == '\\') {
            esc[0] = '\\';
            esc[1] = (char)c;
            sb_put(b, esc, 2);
        } else if (c < 0x20) {
            snprintf(esc, sizeof esc, "\\u%04x", c);
            sb_put(b, esc, 6);
        } else {
            sb_put(b, s, 1);
        }
    }
    sb_put(b, "\"", 1);
}

int gib_history_add_row(gib_history *h, long long run_id, const char *const *names,
                        const char *const *values, int n, gib_error *err)
{
    sbuf js = {0};
    sb_put(&js, "{", 1);
    int first = 1;
    for (int i = 0; i < n; i++) {
        if (!values[i] || !values[i][0])
            continue;
        if (!first)
            sb_put(&js, ",", 1);
        first = 0;
        sb_json_string(&js, names[i]);
        sb_put(&js, ":", 1);
        if (json_number(values[i]))
            sb_put(&js, values[i], strlen(values[i]));
        else
            sb_json_string(&js, values[i]); /* text, and nan / inf, which JSON cannot hold */
    }
    sb_put(&js, "}", 1);
    if (js.oom) {
        free(js.p);
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "history %s: out of memory building a row", h->path);
    }
    sqlite3_stmt *st = h->insert;
    sqlite3_reset(st);
    sqlite3_clear_bindings(st);
    sqlite3_bind_int64(st, 1, run_id);
    for (int t = 0; t < NTYPED; t++) {
        const char *v = NULL;
        for (int i = 0; i < n && !v; i++)
            if (!strcmp(names[i], typed[t].csv))
                v = values[i];
        if (!v || !v[0])
            continue; /* NULL */
        char *end;
        if (typed[t].type == T_TEXT) {
            sqlite3_bind_text(st, 2 + t, v, -1, SQLITE_TRANSIENT);
        } else if (typed[t].type == T_INT) {
            long long x = strtoll(v, &end, 10);
            if (!*end)
                sqlite3_bind_int64(st, 2 + t, x);
        } else {
            double x = strtod(v, &end);
            if (!*end && isfinite(x)) /* nan stays NULL here; row_json and status say why */
                sqlite3_bind_double(st, 2 + t, x);
        }
    }
    sqlite3_bind_text(st, 2 + NTYPED, js.p, (int)js.len, SQLITE_TRANSIENT);
    int rc = sqlite3_step(st);
    free(js.p);
    sqlite3_reset(st);
    if (rc != SQLITE_DONE)
        return db_fail(h, err, "adding a row");
    return 0;
}

/* --- queries --- */

/* A column as text, "" for NULL: a damaged or foreign history may hold NULL anywhere, whatever
 * the schema says (--machines crashed on a NULL gpu: tests/fuzz/regressions/fuzz_history). */
static const char *col_text(sqlite3_stmt *st, int i)
{
    const unsigned char *t = sqlite3_column_text(st, i);
    return t ? (const char *)t : "";
}

int gib_history_print_machines(gib_history *h, FILE *f, gib_error *err)
{
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(h->db,
                           "SELECT m.id, m.renderer, m.gl_version, m.backend, m.cpu, m.cores, m.gpu,"
                           " (SELECT count(*) FROM run WHERE machine_id = m.id),"
                           " (SELECT count(*) FROM result r JOIN run ru ON r.run_id = ru.id"
                           "  WHERE ru.machine_id = m.id) FROM machine m ORDER BY m.id",
                           -1, &st, NULL) != SQLITE_OK)
        return db_fail(h, err, "machines");
    int rc;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW)
        fprintf(f, "machine %lld: %s | %s | %s | cpu %s x %d | gpu %s | %d runs, %d rows\n",
                (long long)sqlite3_column_int64(st, 0), col_text(st, 1), col_text(st, 2),
                col_text(st, 3), col_text(st, 4), sqlite3_column_int(st, 5),
                col_text(st, 6)[0] ? col_text(st, 6) : "none", sqlite3_column_int(st, 7),
                sqlite3_column_int(st, 8));
    sqlite3_finalize(st);
    return rc == SQLITE_DONE ? 0 : db_fail(h, err, "machines");
}

int gib_history_higher_is_better(const char *metric)
{
    return !strcmp(metric, "ssim") || !strcmp(metric, "psnr");
}

int gib_history_find_worse(const gib_history_series *s, int higher_is_better, double rel_tol,
                           double abs_tol)
{
    if (s->count < 2)
        return -1;
    double best = s->points[0].value;
    for (int i = 1; i < s->count; i++) {
        double v = s->points[i].value;
        double allowed = fabs(best) * rel_tol + abs_tol;
        if (higher_is_better ? v < best - allowed : v > best + allowed)
            return i;
        if (higher_is_better ? v > best : v < best)
            best = v;
    }
    return -1;
}

static int metric_ok(const char *m)
{
    if (!*m || strlen(m) > 64)
        return 0;
    for (; *m; m++)
        if (!isalnum((unsigned char)*m) && *m != '_')
            return 0;
    return 1;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Values gathered per point before the median is taken. */
typedef struct vals {
    double *v;
    int n, cap;
} vals;

/* The series gathered so far, with each point's values before the median is taken. */
typedef struct gather {
    gib_history_series *ser;
    vals **pv; /* per series, per point */
    int ns, caps;
    gib_error *err;
} gather;

/* The query of a metric's `ok` rows through the filter, ordered by series. */
static int prepare_query(gib_history *h, const gib_history_filter *f, const char *metric,
                         sqlite3_stmt **out, gib_error *err)
{
    static const char sql[] =
        "SELECT r.matrix, r.scene, r.camera, r.technique, r.component, r.params, r.width,"
        " r.height, r.time, ru.machine_id, m.renderer, r.revision, ru.started, r.run_id,"
        " json_extract(r.row_json, '$.' || ?1) AS v"
        " FROM result r JOIN run ru ON r.run_id = ru.id JOIN machine m ON ru.machine_id = m.id"
        " WHERE r.status = 'ok' AND typeof(v) IN ('integer', 'real')"
        " AND (?2 IS NULL OR r.matrix = ?2) AND (?3 IS NULL OR r.scene = ?3)"
        " AND (?4 IS NULL OR r.technique = ?4) AND (?5 IS NULL OR r.component = ?5)"
        " AND (?6 IS NULL OR r.params = ?6) AND (?7 IS NULL OR instr(m.renderer, ?7) > 0)"
        " AND (?8 = 0 OR r.width = ?8) AND (?9 = 0 OR r.height = ?9)"
        " AND (?10 = 0 OR ru.machine_id = ?10)"
        " ORDER BY r.matrix, r.scene, r.camera, r.technique, r.component, r.params, r.width,"
        " r.height, r.time, ru.machine_id, r.id";
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(h->db, sql, -1, &st, NULL) != SQLITE_OK)
        return db_fail(h, err, "query");
    sqlite3_bind_text(st, 1, metric, -1, SQLITE_STATIC);
    const char *txt[] = {f->matrix, f->scene, f->technique, f->component, f->params, f->renderer};
    for (int i = 0; i < 6; i++)
        if (txt[i])
            sqlite3_bind_text(st, 2 + i, txt[i], -1, SQLITE_STATIC);
    sqlite3_bind_int(st, 8, f->width);
    sqlite3_bind_int(st, 9, f->height);
    sqlite3_bind_int64(st, 10, f->machine);
    *out = st;
    return 0;
}

/* The series a query row belongs to (no points). */
static void row_key(sqlite3_stmt *st, gib_history_series *key)
{
    memset(key, 0, sizeof *key);
    snprintf(key->matrix, sizeof key->matrix, "%s", col_text(st, 0));
    snprintf(key->scene, sizeof key->scene, "%s", col_text(st, 1));
    key->camera = sqlite3_column_int(st, 2);
    snprintf(key->technique, sizeof key->technique, "%s", col_text(st, 3));
    snprintf(key->component, sizeof key->component, "%s", col_text(st, 4));
    snprintf(key->params, sizeof key->params, "%s", col_text(st, 5));
    key->width = sqlite3_column_int(st, 6);
    key->height = sqlite3_column_int(st, 7);
    key->time = sqlite3_column_double(st, 8);
    key->machine = sqlite3_column_int64(st, 9);
    snprintf(key->renderer, sizeof key->renderer, "%s", col_text(st, 10));
}

static int same_series(const gib_history_series *s, const gib_history_series *key)
{
    return !strcmp(s->matrix, key->matrix) && !strcmp(s->scene, key->scene) &&
           s->camera == key->camera && !strcmp(s->technique, key->technique) &&
           !strcmp(s->component, key->component) && !strcmp(s->params, key->params) &&
           s->width == key->width && s->height == key->height && s->time == key->time &&
           s->machine == key->machine;
}

/* The series of key: the last one when it is the same (rows come ordered by series), else a new
 * one. NULL when out of memory. */
static gib_history_series *gather_series(gather *g, const gib_history_series *key)
{
    gib_history_series *s = g->ns ? &g->ser[g->ns - 1] : NULL;
    if (s && same_series(s, key))
        return s;
    if (g->ns == g->caps) {
        g->caps = g->caps ? 2 * g->caps : 16;
        gib_history_series *a = gib_realloc_array(g->ser, g->caps, sizeof *g->ser, g->err);
        vals **b = a ? gib_realloc_array(g->pv, g->caps, sizeof *g->pv, g->err) : NULL;
        if (a)
            g->ser = a;
        if (!a || !b)
            return NULL;
        g->pv = b;
    }
    g->ser[g->ns] = *key;
    g->pv[g->ns] = NULL;
    return &g->ser[g->ns++];
}

/* The last series' point of revision rev, added when new. Its index, or -1 when out of
 * memory. */
static int gather_point(gather *g, const char *rev, const char *started)
{
    gib_history_series *s = &g->ser[g->ns - 1];
    int p = 0;
    while (p < s->count && strcmp(s->points[p].revision, rev))
        p++;
    if (p < s->count)
        return p;
    gib_history_point *a = gib_realloc_array(s->points, s->count + 1, sizeof *a, g->err);
    vals *b = a ? gib_realloc_array(g->pv[g->ns - 1], s->count + 1, sizeof *b, g->err) : NULL;
    if (a)
        s->points = a;
    if (!a || !b)
        return -1;
    g->pv[g->ns - 1] = b;
    memset(&s->points[p], 0, sizeof s->points[p]);
    memset(&b[p], 0, sizeof b[p]);
    snprintf(s->points[p].revision, sizeof s->points[p].revision, "%s", rev);
    snprintf(s->points[p].started, sizeof s->points[p].started, "%s", started);
    s->count++;
    return p;
}

static int vals_add(vals *x, double v, gib_error *err)
{
    if (x->n == x->cap) {
        int cap = x->cap ? 2 * x->cap : 4;
        double *d = gib_realloc_array(x->v, cap, sizeof *d, err);
        if (!d)
            return -1;
        x->v = d;
        x->cap = cap;
    }
    x->v[x->n++] = v;
    return 0;
}

/* Every row of the query into its series and point. 0, or -1 when out of memory. */
static int gather_rows(gather *g, sqlite3_stmt *st, int *rc)
{
    while ((*rc = sqlite3_step(st)) == SQLITE_ROW) {
        gib_history_series key;
        row_key(st, &key);
        double v = sqlite3_column_double(st, 14);
        if (!isfinite(v))
            continue;
        if (!gather_series(g, &key))
            return -1;
        int p = gather_point(g, col_text(st, 11), col_text(st, 12));
        if (p < 0 || vals_add(&g->pv[g->ns - 1][p], v, g->err) < 0)
            return -1;
    }
    return 0;
}

/* Each point's value: the median of its rows'; the gathered values freed. */
static void take_medians(gather *g)
{
    for (int i = 0; i < g->ns; i++) {
        for (int p = 0; p < g->ser[i].count; p++) {
            vals *x = &g->pv[i][p];
            if (x->n) {
                qsort(x->v, x->n, sizeof *x->v, cmp_double);
                g->ser[i].points[p].value =
                    x->n % 2 ? x->v[x->n / 2] : 0.5 * (x->v[x->n / 2 - 1] + x->v[x->n / 2]);
            }
            g->ser[i].points[p].rows = x->n;
            free(x->v);
        }
        free(g->pv[i]);
    }
    free(g->pv);
    g->pv = NULL;
}

int gib_history_query(gib_history *h, const gib_history_filter *f, const char *metric,
                      gib_history_series **out, int *count, gib_error *err)
{
    *out = NULL;
    *count = 0;
    if (!metric_ok(metric))
        return gib_fail(err, "history: metric '%s' is not a column name", metric);
    sqlite3_stmt *st = NULL;
    if (prepare_query(h, f, metric, &st, err) < 0)
        return -1;
    gather g = {.err = err};
    int rc, failed = gather_rows(&g, st, &rc) < 0;
    if (!failed && rc != SQLITE_DONE) {
        db_fail(h, err, "query");
        failed = 1;
    }
    sqlite3_finalize(st);
    take_medians(&g);
    if (failed) {
        gib_history_series_free(g.ser, g.ns);
        return -1;
    }
    *out = g.ser;
    *count = g.ns;
    return 0;
}

void gib_history_series_free(gib_history_series *s, int count)
{
    for (int i = 0; s && i < count; i++)
        free(s[i].points);
    free(s);
}

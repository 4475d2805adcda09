/* gibench merge — combines the CSVs of a matrix's shards (`gibench run M --shard I/N`, each into
 * its own folder) into the table one unsharded run would write: the same header, the same rows in
 * the same order. It trusts nothing it cannot check: the shards' manifests (shard.h) must agree on
 * the matrix, its expansion, the profile and the revision, name every shard once and every run
 * once, and every row a manifest expects must be in its shard's CSV, once, with no row beside. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <unistd.h>

#include "app.h"
#include "schema.h"
#include "options.h"
#include "shard.h"

static const gib_command_doc doc = {
    "merge", "SHARD_DIR... --out DIR [--matrix NAME]...",
    "Combines the shards of each matrix found in the SHARD_DIRs (the --out folders of\n"
    "`gibench run M --shard I/N`, one per shard) into DIR/<matrix>.csv and DIR/<matrix>_passes.csv,\n"
    "row for row what one unsharded run writes. Refuses (exit 1, that matrix not written) shards of\n"
    "different matrices, matrix expansions, profiles or revisions, a missing or repeated shard, and\n"
    "rows that are missing, duplicated or not the shard's. Refuses to overwrite an existing\n"
    "DIR/<matrix>.csv. --matrix limits the merge to the named matrices. The shards' images\n"
    "(SHARD_DIR/images/<matrix>/) are gathered into DIR/images/<matrix>/, hard-linked or copied.\n"};

typedef struct lines {
    char *buf;
    char **line;  /* line[0] is the header */
    int count;
} lines;

static int read_lines(const char *path, lines *l, gib_error *err)
{
    memset(l, 0, sizeof *l);
    FILE *f = fopen(path, "rb");
    if (!f)
        return gib_fail(err, "cannot read %s", path);
    long n = fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1;
    if (n < 0 || fseek(f, 0, SEEK_SET) != 0 || !(l->buf = malloc((size_t)n + 1)) ||
        fread(l->buf, 1, (size_t)n, f) != (size_t)n) {
        fclose(f);
        return gib_fail(err, "cannot read %s", path);
    }
    fclose(f);
    l->buf[n] = 0;
    const char *nul = memchr(l->buf, 0, (size_t)n);
    if (nul) { /* the lines below are C strings: a NUL would end one early */
        int line = 1;
        for (const char *c = l->buf; c < nul; c++)
            line += *c == '\n';
        return gib_fail(err, "%s:%d: a NUL byte: not a text file (not a gibench CSV or manifest)",
                        path, line);
    }
    if (n && l->buf[n - 1] != '\n')
        return gib_fail(err, "%s: the last line is cut off (was the shard killed while writing?)",
                        path);
    int cap = 0;
    for (char *p = l->buf; *p;) {
        char *e = strchr(p, '\n');
        *e = 0;
        if (e > p && e[-1] == '\r')
            e[-1] = 0;
        if (*p) {
            if (l->count == cap) {
                cap = cap ? 2 * cap : 256;
                char **nl = realloc(l->line, (size_t)cap * sizeof *nl);
                if (!nl)
                    return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
                l->line = nl;
            }
            l->line[l->count++] = p;
        }
        p = e + 1;
    }
    if (!l->count)
        return gib_fail(err, "%s is empty (no header)", path);
    return 0;
}

static void free_lines(lines *l)
{
    free(l->buf);
    free(l->line);
    memset(l, 0, sizeof *l);
}

/* Field `want` of a CSV line (RFC 4180 quoting, one line per record as gibench writes), unquoted
 * into out. Returns the line's field count. */
static int csv_field(const char *p, int want, char *out, size_t len)
{
    int n = 0;
    size_t o = 0;
    if (len)
        out[0] = 0;
    for (;;) {
        int take = n == want;
        if (*p == '"') {
            for (p++; *p; p++) {
                if (*p == '"' && p[1] == '"')
                    p++;
                else if (*p == '"') {
                    p++;
                    break;
                }
                if (take && o + 1 < len)
                    out[o++] = *p;
            }
        }
        for (; *p && *p != ','; p++)
            if (take && o + 1 < len)
                out[o++] = *p;
        if (take && len)
            out[o] = 0;
        n++;
        if (*p != ',')
            return n;
        p++;
    }
}

static int column_of(const char *header, const char *name)
{
    char f[256];
    int n = csv_field(header, 0, f, sizeof f);
    for (int i = 0; i < n; i++) {
        csv_field(header, i, f, sizeof f);
        if (!strcmp(f, name))
            return i;
    }
    return -1;
}

typedef struct mrow {
    char key[1024];
    int run;         /* index in the expansion */
    int ordinal;     /* place in the unsharded order */
    int sub;         /* place among its run's rows */
    const char *line;
} mrow;

typedef struct manifest {
    char dir[1024], matrix[64], profile[32], revision[64], fingerprint[32];
    int index, count, runs;
    int *run_idx, *run_ord;
    char *run_state; /* 'e' expect, 's' skipped, 'f' failed */
    int nruns;
    mrow *rows;
    int nrows;
} manifest;

static void free_manifest(manifest *m)
{
    free(m->run_idx), free(m->run_ord), free(m->run_state), free(m->rows);
    memset(m, 0, sizeof *m);
}

static int read_manifest(const char *dir, const char *file, manifest *m, gib_error *err)
{
    memset(m, 0, sizeof *m);
    snprintf(m->dir, sizeof m->dir, "%s", dir);
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    lines l;
    if (read_lines(path, &l, err) < 0) {
        free_lines(&l);
        return -1;
    }
    int ok = !strcmp(l.line[0], "gibench-shard\t1");
    m->run_idx = malloc((size_t)l.count * sizeof *m->run_idx);
    m->run_ord = malloc((size_t)l.count * sizeof *m->run_ord);
    m->run_state = malloc((size_t)l.count);
    m->rows = calloc((size_t)l.count, sizeof *m->rows);
    int bad_line = ok ? 0 : 1;
    for (int i = 1; ok && i < l.count && m->rows; i++) {
        char *s = l.line[i], *tab = strchr(s, '\t');
        if (!tab) {
            bad_line = i + 1;
            break;
        }
        *tab = 0;
        const char *v = tab + 1;
        char st[16];
        if (!strcmp(s, "matrix")) snprintf(m->matrix, sizeof m->matrix, "%s", v);
        else if (!strcmp(s, "profile")) snprintf(m->profile, sizeof m->profile, "%s", v);
        else if (!strcmp(s, "revision")) snprintf(m->revision, sizeof m->revision, "%s", v);
        else if (!strcmp(s, "fingerprint")) snprintf(m->fingerprint, sizeof m->fingerprint, "%s", v);
        else if (!strcmp(s, "shard") && sscanf(v, "%d/%d", &m->index, &m->count) == 2) {}
        else if (!strcmp(s, "runs") && sscanf(v, "%d", &m->runs) == 1) {}
        else if (!strcmp(s, "run") && sscanf(v, "%d\t%d\t%15s", &m->run_idx[m->nruns],
                                             &m->run_ord[m->nruns], st) == 3 &&
                 (!strcmp(st, "expect") || !strcmp(st, "skipped") || !strcmp(st, "failed")))
            m->run_state[m->nruns++] = st[0];
        else if (!strcmp(s, "row") && m->nruns) {
            mrow *r = &m->rows[m->nrows];
            snprintf(r->key, sizeof r->key, "%s", v);
            r->run = m->run_idx[m->nruns - 1];
            r->ordinal = m->run_ord[m->nruns - 1];
            r->sub = m->nrows && m->rows[m->nrows - 1].run == r->run ? m->rows[m->nrows - 1].sub + 1 : 0;
            m->nrows++;
        } else {
            bad_line = i + 1;
            break;
        }
    }
    free_lines(&l);
    if (!m->rows)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    if (bad_line)
        return gib_fail(err, "%s:%d: not a gibench shard manifest line (written by another version?)",
                        path, bad_line);
    if (!m->matrix[0] || !m->count || m->index < 1 || m->index > m->count || m->runs < 1)
        return gib_fail(err, "%s: the manifest lacks its matrix, shard I/N or run count", path);
    return 0;
}

static int by_order(const void *pa, const void *pb)
{
    const mrow *a = pa, *b = pb;
    if (a->ordinal != b->ordinal)
        return a->ordinal - b->ordinal;
    return a->sub - b->sub;
}

/* The fields `cols` of a CSV line joined by '|', as gib_csv keys a row. */
static void line_key(const char *line, const int *cols, int n, char *key, size_t len)
{
    char f[512];
    key[0] = 0;
    for (int k = 0; k < n; k++) {
        csv_field(line, cols[k], f, sizeof f);
        strncat(key, k ? "|" : "", len - strlen(key) - 1);
        strncat(key, f, len - strlen(key) - 1);
    }
}

/* The run key of a row's identity key (its GIB_KEY_ROW fields joined by '|', schema.h): the
 * fields of the columns that are GIB_KEY_RUN too, the key by which a passes row names its run. */
static void run_key_of(const char *key, char *out, size_t len)
{
    int rk[GIB_C_COUNT];
    int nrk = gib_schema_key(gib_run_columns, GIB_C_COUNT, GIB_KEY_ROW, rk, GIB_C_COUNT);
    const char *p = key;
    int first = 1;
    out[0] = 0;
    for (int k = 0; k < nrk && p; k++) {
        const char *e = strchr(p, '|');
        size_t n = e ? (size_t)(e - p) : strlen(p);
        if (gib_run_columns[rk[k]].key & GIB_KEY_RUN) {
            size_t used = strlen(out);
            snprintf(out + used, len - used, "%s%.*s", first ? "" : "|", (int)n, p);
            first = 0;
        }
        p = e ? e + 1 : NULL;
    }
}

/* The columns of header named as the runs table's columns with key flag `flag`, in run_key_of's
 * order (a passes table names its run by the same names). Returns their count, or -1. */
static int key_columns_of(const char *header, const char *path, unsigned flag, int *cols,
                          gib_error *err)
{
    int rk[GIB_C_COUNT], n = 0;
    int nrk = gib_schema_key(gib_run_columns, GIB_C_COUNT, GIB_KEY_ROW, rk, GIB_C_COUNT);
    for (int k = 0; k < nrk; k++) {
        const char *name = gib_run_columns[rk[k]].name;
        if (!(gib_run_columns[rk[k]].key & flag))
            continue;
        if ((cols[n++] = column_of(header, name)) < 0)
            return gib_fail(err, "%s: no column '%s'", path, name);
    }
    return n;
}

/* Gathers the shards' DIR/images/<matrix>/ into OUT/images/<matrix>/: hard links where the folders
 * share a file system, copies elsewhere. A name already there (the references every shard of a
 * scene writes, or a second merge) is kept. Returns the number of files gathered, or -1. */
static int gather_images(const char *dir, const char *out, const char *name, gib_error *err)
{
    char src[2048], dst[2048];
    snprintf(src, sizeof src, "%s/images/%s", dir, name);
    DIR *dp = opendir(src);
    if (!dp)
        return 0; /* the shard ran with --no-images */
    snprintf(dst, sizeof dst, "%s/images/%s", out, name);
    if (gib_mkdirs(dst, err) < 0) {
        closedir(dp);
        return -1;
    }
    int n = 0;
    struct dirent *e;
    while ((e = readdir(dp))) {
        if (e->d_name[0] == '.')
            continue;
        char from[4096], to[4096];
        snprintf(from, sizeof from, "%s/%s", src, e->d_name);
        snprintf(to, sizeof to, "%s/%s", dst, e->d_name);
        if (access(to, F_OK) == 0)
            continue;
        if (link(from, to) != 0) {
            FILE *fi = fopen(from, "rb"), *fo = fi ? fopen(to, "wb") : NULL;
            char buf[65536];
            size_t k;
            int ok = fi && fo;
            while (ok && (k = fread(buf, 1, sizeof buf, fi)) > 0)
                ok = fwrite(buf, 1, k, fo) == k;
            ok = ok && !ferror(fi);
            if (fi)
                fclose(fi);
            if (fo && fclose(fo) != 0)
                ok = 0;
            if (!ok) {
                unlink(to);
                closedir(dp);
                return gib_fail(err, "cannot copy %s to %s", from, to);
            }
        }
        n++;
    }
    closedir(dp);
    return n;
}

static int write_atomic(const char *path, const char *header, mrow *rows, int n, gib_error *err)
{
    char tmp[2100];
    snprintf(tmp, sizeof tmp, "%s.tmp%d", path, (int)getpid());
    FILE *f = fopen(tmp, "w");
    if (!f)
        return gib_fail(err, "cannot write %s", tmp);
    fprintf(f, "%s\n", header);
    for (int i = 0; i < n; i++)
        fprintf(f, "%s\n", rows[i].line);
    if (fclose(f) != 0 || rename(tmp, path) != 0) {
        unlink(tmp);
        return gib_fail(err, "cannot write %s", path);
    }
    return 0;
}

/* The shards of one matrix agree on its profile, revision, expansion and split, and name each
 * shard once, none missing. */
static int check_shards(const manifest *sh, int n, gib_error *err)
{
    const manifest *a = &sh[0];
    const char *name = a->matrix;
    for (int i = 1; i < n; i++) {
        const manifest *b = &sh[i];
        if (strcmp(a->profile, b->profile))
            return gib_fail(err, "%s: shards of different profiles: %s (%s) and %s (%s)", name,
                            a->profile, a->dir, b->profile, b->dir);
        if (strcmp(a->revision, b->revision))
            return gib_fail(err, "%s: shards of different revisions: %s (%s) and %s (%s)", name,
                            a->revision, a->dir, b->revision, b->dir);
        if (strcmp(a->fingerprint, b->fingerprint) || a->runs != b->runs)
            return gib_fail(err, "%s: shards of different matrix expansions (%s in %s, %s in %s): "
                                 "the matrix file changed between shards", name, a->fingerprint,
                            a->dir, b->fingerprint, b->dir);
        if (a->count != b->count)
            return gib_fail(err, "%s: shards of different splits: %d/%d (%s) and %d/%d (%s)", name,
                            a->index, a->count, a->dir, b->index, b->count, b->dir);
        for (int k = 0; k < i; k++)
            if (sh[k].index == b->index)
                return gib_fail(err, "%s: shard %d/%d twice: %s and %s", name, b->index, b->count,
                                sh[k].dir, b->dir);
    }
    for (int s = 1; s <= a->count; s++) {
        int found = 0;
        for (int i = 0; i < n; i++)
            found |= sh[i].index == s;
        if (!found)
            return gib_fail(err, "%s: shard %d/%d is missing (no %s.shard among the folders given: "
                                 "it did not finish, or its folder was not named)", name, s,
                            a->count, name);
    }
    return 0;
}

/* Every run of the expansion in exactly one shard; a count beyond the shards' runs is refused
 * before anything of its size is allocated (a damaged manifest may claim billions). */
static int check_run_owners(const manifest *sh, int n, gib_error *err)
{
    const manifest *a = &sh[0];
    const char *name = a->matrix;
    int listed = 0;
    for (int i = 0; i < n; i++)
        listed += sh[i].nruns;
    if (a->runs > listed)
        return gib_fail(err, "%s: %d runs in the matrix but %d in its shards' manifests: runs are "
                             "missing", name, a->runs, listed);
    int *owner = calloc((size_t)a->runs, sizeof *owner);
    if (!owner)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    int rc = 0;
    for (int i = 0; i < n && !rc; i++)
        for (int r = 0; r < sh[i].nruns && !rc; r++) {
            int j = sh[i].run_idx[r];
            if (j < 0 || j >= a->runs)
                rc = gib_fail(err, "%s/%s.shard: run %d out of range", sh[i].dir, name, j);
            else if (owner[j])
                rc = gib_fail(err, "%s: run %d is in shard %d and in shard %d", name, j, owner[j],
                              sh[i].index);
            else
                owner[j] = sh[i].index;
        }
    for (int j = 0; j < a->runs && !rc; j++)
        if (!owner[j])
            rc = gib_fail(err, "%s: run %d of %d is in no shard", name, j, a->runs);
    free(owner);
    return rc;
}

/* One matrix's merge: the shards' tables as read, and the rows taken from them. */
typedef struct merge_state {
    const char *name;
    lines *csv, *pcsv;  /* each shard's runs and passes tables */
    mrow *all, *passes; /* the rows and passes rows, in the unsharded order once sorted */
    int nall, npass, pcap;
    int kcol[GIB_C_COUNT], nkcol, mcol, gcol;
} merge_state;

/* Row li of shard m's runs table (read from path): one of the manifest's rows, once, of this
 * matrix and revision. */
static int take_row(merge_state *st, const manifest *m, const lines *csv, int li, const char *path,
                    char *used, gib_error *err)
{
    const char *line = csv->line[li];
    int ncols = csv_field(csv->line[0], 0, NULL, 0);
    char key[1024], f[512];
    if (csv_field(line, 0, NULL, 0) != ncols)
        return gib_fail(err, "%s:%d: %d fields where the header has %d", path, li + 1,
                        csv_field(line, 0, NULL, 0), ncols);
    line_key(line, st->kcol, st->nkcol, key, sizeof key);
    if (st->mcol >= 0 && (csv_field(line, st->mcol, f, sizeof f), strcmp(f, st->name)))
        return gib_fail(err, "%s:%d: a row of matrix '%s' in %s's CSV", path, li + 1, f, st->name);
    if (st->gcol >= 0 && (csv_field(line, st->gcol, f, sizeof f), strcmp(f, m->revision)))
        return gib_fail(err, "%s:%d: a row of revision %s in a shard of revision %s (a resumed "
                             "CSV from another revision: rerun the shard into an empty folder)",
                        path, li + 1, f, m->revision);
    int r = 0;
    while (r < m->nrows && strcmp(m->rows[r].key, key))
        r++;
    if (r == m->nrows)
        return gib_fail(err, "%s:%d: row %s is not one of shard %d/%d's", path, li + 1, key,
                        m->index, m->count);
    if (used[r])
        return gib_fail(err, "%s:%d: row %s twice in shard %d/%d", path, li + 1, key, m->index,
                        m->count);
    used[r] = 1;
    st->all[st->nall] = m->rows[r];
    st->all[st->nall++].line = line;
    return 0;
}

/* Every row shard m's manifest expects is in its table, unless the shard skipped its run. */
static int check_rows_present(const merge_state *st, const manifest *m, const char *path,
                              const char *used, gib_error *err)
{
    for (int r = 0; r < m->nrows; r++) {
        if (used[r])
            continue;
        int ri = 0;
        while (m->run_idx[ri] != m->rows[r].run)
            ri++;
        if (m->run_state[ri] == 's')
            continue; /* the shard skipped the run (scene data absent, scene lacks a feature) */
        return gib_fail(err, "%s: row %s missing from %s (shard %d/%d%s)", st->name, m->rows[r].key,
                        path, m->index, m->count,
                        m->run_state[ri] == 'f' ? ": the shard could not load the scene" : "");
    }
    return 0;
}

/* Shard i's runs table: the same header as the first shard's, every row taken. */
static int take_shard_rows(merge_state *st, const manifest *m, int i, gib_error *err)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/%s.csv", m->dir, st->name);
    if (read_lines(path, &st->csv[i], err) < 0)
        return -1;
    const char *header = st->csv[i].line[0];
    if (i && strcmp(header, st->csv[0].line[0]))
        return gib_fail(err, "%s: the shards' CSVs have different columns (%s and %s.csv of the "
                             "first shard): built from different sources", st->name, path, st->name);
    if (i == 0) {
        if ((st->nkcol = key_columns_of(header, path, GIB_KEY_ROW, st->kcol, err)) < 0)
            return -1;
        st->mcol = column_of(header, gib_run_columns[GIB_C_MATRIX].name);
        st->gcol = column_of(header, gib_run_columns[GIB_C_GIT].name);
    }
    char *used = calloc((size_t)m->nrows + 1, 1);
    if (!used)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
    int rc = 0;
    for (int li = 1; li < st->csv[i].count && !rc; li++)
        rc = take_row(st, m, &st->csv[i], li, path, used, err);
    if (!rc)
        rc = check_rows_present(st, m, path, used, err);
    free(used);
    return rc;
}

/* Shard i's passes rows, each placed at its run's place in the unsharded order. */
static int take_shard_passes(merge_state *st, const manifest *sh, int i, gib_error *err)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/%s_passes.csv", sh[i].dir, st->name);
    if (access(path, F_OK) != 0)
        return 0;
    if (read_lines(path, &st->pcsv[i], err) < 0)
        return -1;
    const lines *p = &st->pcsv[i];
    for (int k = 0; k < i; k++)
        if (st->pcsv[k].count && strcmp(st->pcsv[k].line[0], p->line[0]))
            return gib_fail(err, "%s: the shards' passes CSVs have different columns (%s and %s)",
                            st->name, path, sh[k].dir);
    int pk[GIB_C_COUNT];
    int npk = key_columns_of(p->line[0], path, GIB_KEY_RUN, pk, err);
    if (npk < 0)
        return -1;
    for (int li = 1; li < p->count; li++) {
        char key[1024], rk[1024];
        line_key(p->line[li], pk, npk, key, sizeof key);
        int ord = -1;
        for (int r = 0; r < sh[i].nrows && ord < 0; r++) {
            run_key_of(sh[i].rows[r].key, rk, sizeof rk);
            if (!strcmp(rk, key))
                ord = sh[i].rows[r].ordinal;
        }
        if (ord < 0)
            return gib_fail(err, "%s:%d: passes of run %s, not one of shard %d/%d's", path, li + 1,
                            key, sh[i].index, sh[i].count);
        if (st->npass == st->pcap) {
            st->pcap = st->pcap ? 2 * st->pcap : 256;
            mrow *np = realloc(st->passes, (size_t)st->pcap * sizeof *np);
            if (!np)
                return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
            st->passes = np;
        }
        st->passes[st->npass] = (mrow){.ordinal = ord, .sub = st->npass, .line = p->line[li]};
        st->npass++;
    }
    return 0;
}

/* OUT/<matrix>.csv, its passes and the shards' images. */
static int write_merged(merge_state *st, const manifest *sh, int n, const char *out,
                        gib_error *err)
{
    char path[2048];
    if (gib_mkdirs(out, err) < 0)
        return -1;
    snprintf(path, sizeof path, "%s/%s.csv", out, st->name);
    if (write_atomic(path, st->csv[0].line[0], st->all, st->nall, err) < 0)
        return -1;
    for (int i = 0; i < n; i++)
        if (st->pcsv[i].count) {
            snprintf(path, sizeof path, "%s/%s_passes.csv", out, st->name);
            if (write_atomic(path, st->pcsv[i].line[0], st->passes, st->npass, err) < 0)
                return -1;
            break;
        }
    int nimages = 0;
    for (int i = 0; i < n; i++) {
        int k = gather_images(sh[i].dir, out, st->name, err);
        if (k < 0)
            return -1;
        nimages += k;
    }
    printf("%s: %d shards, %d runs, %d rows -> %s/%s.csv", st->name, sh[0].count, sh[0].runs,
           st->nall, out, st->name);
    if (nimages)
        printf(", %d images -> %s/images/%s/", nimages, out, st->name);
    printf("\n");
    return 0;
}

/* The shards' rows and passes in the unsharded order, into out (never over an existing table). */
static int merge_tables(merge_state *st, const manifest *sh, int n, const char *out,
                        gib_error *err)
{
    for (int i = 0; i < n; i++)
        if (take_shard_rows(st, &sh[i], i, err) < 0)
            return -1;
    qsort(st->all, (size_t)st->nall, sizeof *st->all, by_order);
    char path[2048];
    snprintf(path, sizeof path, "%s/%s.csv", out, st->name);
    if (access(path, F_OK) == 0)
        return gib_fail(err, "%s exists: merge writes a fresh table (remove it or choose another "
                             "--out)", path);
    for (int i = 0; i < n; i++)
        if (take_shard_passes(st, sh, i, err) < 0)
            return -1;
    if (st->npass) /* qsort of NULL, even with no element, is undefined */
        qsort(st->passes, (size_t)st->npass, sizeof *st->passes, by_order);
    return write_merged(st, sh, n, out, err);
}

/* Merges one matrix's shards (sh[0..n), from read_manifest) into out. */
static int merge_matrix(manifest *sh, int n, const char *out, gib_error *err)
{
    if (check_shards(sh, n, err) < 0 || check_run_owners(sh, n, err) < 0)
        return -1;
    int total = 0;
    for (int i = 0; i < n; i++)
        total += sh[i].nrows;
    merge_state st = {.name = sh[0].matrix, .mcol = -1, .gcol = -1};
    st.all = calloc((size_t)total + 1, sizeof *st.all);
    st.csv = calloc((size_t)n, sizeof *st.csv);
    st.pcsv = calloc((size_t)n, sizeof *st.pcsv);
    int rc = st.all && st.csv && st.pcsv ? merge_tables(&st, sh, n, out, err)
                                         : gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                                                         "out of memory");
    for (int i = 0; st.csv && st.pcsv && i < n; i++)
        free_lines(&st.csv[i]), free_lines(&st.pcsv[i]);
    free(st.csv), free(st.pcsv), free(st.all), free(st.passes);
    return rc;
}

/* ---- the command ---- */

typedef struct merge_opts {
    const char *out, *dirs[GIB_SHARD_MAX], *only[64];
    int ndirs, nonly;
} merge_opts;

/* Returns -1 to go on, 0 after --help, 2 on bad usage. */
static int parse_merge_options(int argc, char **argv, merge_opts *o)
{
    memset(o, 0, sizeof *o);
    const gib_option opts[] = {
        GIB_OPTION_TEXT("--out", &o->out, "DIR", "where the merged tables go (required)"),
        GIB_OPTION_LIST("--matrix", o->only, 64, &o->nonly, "NAME",
                        "merge only this matrix (repeatable)"),
        {0}};
    int rc = gib_options_parse(&doc, opts, argc, argv, o->dirs, &o->ndirs, GIB_SHARD_MAX);
    if (rc != GIB_OPTIONS_PROCEED)
        return rc;
    if (!o->ndirs || !o->out) {
        fprintf(stderr, "gibench merge: %s\n",
                !o->ndirs ? "no shard folder given" : "--out DIR missing");
        gib_options_usage(stderr, &doc, opts);
        return 2;
    }
    return -1;
}

/* Every manifest found, and the names of their matrices. */
typedef struct manifests {
    manifest *sh;
    int nsh, cap;
    char names[64][64];
    int nnames;
} manifests;

static int wanted_matrix(const merge_opts *o, const char *name)
{
    int wanted = !o->nonly;
    for (int k = 0; k < o->nonly; k++)
        wanted |= !strcmp(o->only[k], name);
    return wanted;
}

/* Reads DIR/FILE (a *.shard of matrix mname) into all. Returns 0, or -1 (reported). */
static int add_manifest(manifests *all, const char *dir, const char *file, const char *mname)
{
    gib_error err;
    if (all->nsh == all->cap) {
        all->cap = all->cap ? 2 * all->cap : 16;
        manifest *ns = realloc(all->sh, (size_t)all->cap * sizeof *ns);
        if (!ns)
            return -1;
        all->sh = ns;
    }
    manifest *m = &all->sh[all->nsh];
    if (read_manifest(dir, file, m, &err) < 0) {
        fprintf(stderr, "gibench merge: %s\n", err.msg);
        free_manifest(m);
        return -1;
    }
    if (strcmp(m->matrix, mname)) {
        fprintf(stderr, "gibench merge: %s/%s names matrix '%s'\n", dir, file, m->matrix);
        free_manifest(m);
        return -1;
    }
    int known = 0;
    for (int k = 0; k < all->nnames; k++)
        known |= !strcmp(all->names[k], mname);
    if (!known && all->nnames < 64)
        snprintf(all->names[all->nnames++], sizeof all->names[0], "%s", mname);
    all->nsh++;
    return 0;
}

/* The wanted manifests of folder dir. Returns 0, or 1 (reported). */
static int read_folder(const merge_opts *o, const char *dir, manifests *all)
{
    DIR *dp = opendir(dir);
    if (!dp) {
        fprintf(stderr, "gibench merge: cannot open the shard folder %s\n", dir);
        return 1;
    }
    int here = 0, status = 0;
    struct dirent *e;
    while (!status && (e = readdir(dp))) {
        size_t len = strlen(e->d_name);
        if (len < 7 || strcmp(e->d_name + len - 6, ".shard"))
            continue;
        char mname[64];
        snprintf(mname, sizeof mname, "%.*s", (int)(len - 6), e->d_name);
        if (!wanted_matrix(o, mname))
            continue;
        if (add_manifest(all, dir, e->d_name, mname) < 0)
            status = 1;
        else
            here++;
    }
    closedir(dp);
    if (!status && !here) {
        fprintf(stderr, "gibench merge: %s holds no shard manifest (*.shard)%s\n", dir,
                o->nonly ? " of the matrices named" : ": not a `gibench run --shard` folder");
        status = 1;
    }
    return status;
}

/* Every folder must hold a shard of every matrix: a folder of another matrix is refused. */
static int check_folders(const merge_opts *o, const manifests *all)
{
    for (int k = 0; k < all->nnames; k++)
        for (int d = 0; d < o->ndirs; d++) {
            int has = 0;
            for (int i = 0; i < all->nsh; i++)
                has |= !strcmp(all->sh[i].matrix, all->names[k]) && !strcmp(all->sh[i].dir, o->dirs[d]);
            if (!has) {
                fprintf(stderr, "gibench merge: %s holds no shard of matrix '%s' that the other "
                                "folders hold: shards of different matrices\n", o->dirs[d],
                        all->names[k]);
                return 1;
            }
        }
    return 0;
}

int gib_cmd_merge(int argc, char **argv)
{
    merge_opts o;
    int rc = parse_merge_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    manifests all = {0};
    int status = 0;
    for (int d = 0; d < o.ndirs && !status; d++)
        status = read_folder(&o, o.dirs[d], &all);
    if (!status)
        status = check_folders(&o, &all);
    gib_error err;
    for (int k = 0; !status && k < all.nnames; k++) {
        manifest *group = malloc((size_t)all.nsh * sizeof *group);
        int ng = 0;
        for (int i = 0; group && i < all.nsh; i++)
            if (!strcmp(all.sh[i].matrix, all.names[k]))
                group[ng++] = all.sh[i];
        if (!group || merge_matrix(group, ng, o.out, &err) < 0) {
            fprintf(stderr, "gibench merge: %s\n", group ? err.msg : "out of memory");
            status = 1;
        }
        free(group);
    }
    for (int i = 0; i < all.nsh; i++)
        free_manifest(&all.sh[i]);
    free(all.sh);
    return status;
}

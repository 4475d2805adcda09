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
#include "shard.h"

static const char help[] =
    "usage: gibench merge SHARD_DIR... --out DIR [--matrix NAME]...\n"
    "\n"
    "Combines the shards of each matrix found in the SHARD_DIRs (the --out folders of\n"
    "`gibench run M --shard I/N`, one per shard) into DIR/<matrix>.csv and DIR/<matrix>_passes.csv,\n"
    "row for row what one unsharded run writes. Refuses (exit 1, that matrix not written) shards of\n"
    "different matrices, matrix expansions, profiles or revisions, a missing or repeated shard, and\n"
    "rows that are missing, duplicated or not the shard's. Refuses to overwrite an existing\n"
    "DIR/<matrix>.csv. --matrix limits the merge to the named matrices. The shards' images\n"
    "(SHARD_DIR/images/<matrix>/) are gathered into DIR/images/<matrix>/, hard-linked or copied.\n";

/* The CSV identity key's columns, in cmd_run.c's order (key_columns there). */
static const char *const key_names[] = {"profile", "scene", "camera", "technique", "component",
                                        "params", "width", "height", "time"};
#define NKEY 9
/* The passes CSV's run columns, by which its rows find their run. */
static const char *const pass_key_names[] = {"scene", "technique", "params", "width", "height",
                                             "time"};

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
                    return gib_fail(err, "%s: out of memory", path);
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
        return gib_fail(err, "%s: out of memory", path);
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

/* The run key of a CSV identity key (profile|scene|camera|technique|component|params|w|h|time):
 * scene|technique|params|w|h|time, as the passes CSV names its run. */
static void run_key_of(const char *key, char *out, size_t len)
{
    char f[NKEY][256];
    int n = 0;
    const char *p = key;
    while (n < NKEY) {
        const char *e = strchr(p, '|');
        size_t k = e ? (size_t)(e - p) : strlen(p);
        snprintf(f[n++], sizeof f[0], "%.*s", (int)(k < 255 ? k : 255), p);
        if (!e)
            break;
        p = e + 1;
    }
    while (n < NKEY)
        f[n++][0] = 0;
    snprintf(out, len, "%.160s|%.160s|%.255s|%.32s|%.32s|%.64s", f[1], f[3], f[5], f[6], f[7], f[8]);
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

/* Merges one matrix's shards (sh[0..n), from read_manifest) into out. */
static int merge_matrix(manifest *sh, int n, const char *out, gib_error *err)
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
    /* Every run of the expansion in exactly one shard; a count beyond the shards' runs is refused
     * before anything of its size is allocated (a damaged manifest may claim billions). */
    int listed = 0;
    for (int i = 0; i < n; i++)
        listed += sh[i].nruns;
    if (a->runs > listed)
        return gib_fail(err, "%s: %d runs in the matrix but %d in its shards' manifests: runs are "
                             "missing", name, a->runs, listed);
    int *owner = calloc((size_t)a->runs, sizeof *owner);
    if (!owner)
        return gib_fail(err, "out of memory");
    for (int i = 0; i < n; i++)
        for (int r = 0; r < sh[i].nruns; r++) {
            int j = sh[i].run_idx[r];
            if (j < 0 || j >= a->runs) {
                free(owner);
                return gib_fail(err, "%s/%s.shard: run %d out of range", sh[i].dir, name, j);
            }
            if (owner[j]) {
                int first = owner[j];
                free(owner);
                return gib_fail(err, "%s: run %d is in shard %d and in shard %d", name, j, first,
                                sh[i].index);
            }
            owner[j] = sh[i].index;
        }
    for (int j = 0; j < a->runs; j++)
        if (!owner[j]) {
            free(owner);
            return gib_fail(err, "%s: run %d of %d is in no shard", name, j, a->runs);
        }
    free(owner);

    int total = 0;
    for (int i = 0; i < n; i++)
        total += sh[i].nrows;
    mrow *all = calloc((size_t)total + 1, sizeof *all);
    lines *csv = calloc((size_t)n, sizeof *csv), *pcsv = calloc((size_t)n, sizeof *pcsv);
    int nall = 0, rc = -1;
    char path[2048];
    if (!all || !csv || !pcsv) {
        gib_fail(err, "out of memory");
        goto done;
    }
    int kcol[NKEY], mcol = -1, gcol = -1;
    for (int i = 0; i < n; i++) {
        const manifest *m = &sh[i];
        snprintf(path, sizeof path, "%s/%s.csv", m->dir, name);
        if (read_lines(path, &csv[i], err) < 0)
            goto done;
        if (strcmp(csv[i].line[0], csv[0].line[0])) {
            gib_fail(err, "%s: the shards' CSVs have different columns (%s and %s/%s.csv): "
                          "built from different sources", name, path, sh[0].dir, name);
            goto done;
        }
        if (i == 0) {
            for (int k = 0; k < NKEY; k++)
                if ((kcol[k] = column_of(csv[0].line[0], key_names[k])) < 0) {
                    gib_fail(err, "%s: no column '%s'", path, key_names[k]);
                    goto done;
                }
            mcol = column_of(csv[0].line[0], "matrix");
            gcol = column_of(csv[0].line[0], "git_revision");
        }
        int ncols = csv_field(csv[i].line[0], 0, NULL, 0);
        char *used = calloc((size_t)m->nrows + 1, 1);
        if (!used) {
            gib_fail(err, "out of memory");
            goto done;
        }
        for (int li = 1; li < csv[i].count; li++) {
            const char *line = csv[i].line[li];
            char key[1024] = "", f[512];
            if (csv_field(line, 0, NULL, 0) != ncols) {
                gib_fail(err, "%s:%d: %d fields where the header has %d", path, li + 1,
                         csv_field(line, 0, NULL, 0), ncols);
                free(used);
                goto done;
            }
            for (int k = 0; k < NKEY; k++) {
                csv_field(line, kcol[k], f, sizeof f);
                strncat(key, k ? "|" : "", sizeof key - strlen(key) - 1);
                strncat(key, f, sizeof key - strlen(key) - 1);
            }
            if (mcol >= 0 && (csv_field(line, mcol, f, sizeof f), strcmp(f, name))) {
                gib_fail(err, "%s:%d: a row of matrix '%s' in %s's CSV", path, li + 1, f, name);
                free(used);
                goto done;
            }
            if (gcol >= 0 && (csv_field(line, gcol, f, sizeof f), strcmp(f, m->revision))) {
                gib_fail(err, "%s:%d: a row of revision %s in a shard of revision %s (a resumed "
                              "CSV from another revision: rerun the shard into an empty folder)",
                         path, li + 1, f, m->revision);
                free(used);
                goto done;
            }
            int r = 0;
            while (r < m->nrows && strcmp(m->rows[r].key, key))
                r++;
            if (r == m->nrows) {
                gib_fail(err, "%s:%d: row %s is not one of shard %d/%d's", path, li + 1, key,
                         m->index, m->count);
                free(used);
                goto done;
            }
            if (used[r]) {
                gib_fail(err, "%s:%d: row %s twice in shard %d/%d", path, li + 1, key, m->index,
                         m->count);
                free(used);
                goto done;
            }
            used[r] = 1;
            all[nall] = m->rows[r];
            all[nall++].line = line;
        }
        for (int r = 0; r < m->nrows; r++) {
            if (used[r])
                continue;
            int ri = 0;
            while (sh[i].run_idx[ri] != m->rows[r].run)
                ri++;
            if (m->run_state[ri] == 's')
                continue; /* the shard skipped the run (scene data absent, scene lacks a feature) */
            gib_fail(err, "%s: row %s missing from %s (shard %d/%d%s)", name, m->rows[r].key, path,
                     m->index, m->count,
                     m->run_state[ri] == 'f' ? ": the shard could not load the scene" : "");
            free(used);
            goto done;
        }
        free(used);
    }
    qsort(all, (size_t)nall, sizeof *all, by_order);
    snprintf(path, sizeof path, "%s/%s.csv", out, name);
    if (access(path, F_OK) == 0) {
        gib_fail(err, "%s exists: merge writes a fresh table (remove it or choose another --out)",
                 path);
        goto done;
    }

    /* The passes: each shard's rows, ordered by their run's place in the unsharded order. */
    int npass = 0, pcap = 0;
    mrow *passes = NULL;
    for (int i = 0; i < n; i++) {
        snprintf(path, sizeof path, "%s/%s_passes.csv", sh[i].dir, name);
        if (access(path, F_OK) != 0)
            continue;
        if (read_lines(path, &pcsv[i], err) < 0)
            goto done_passes;
        for (int k = 0; k < i; k++)
            if (pcsv[k].count && strcmp(pcsv[k].line[0], pcsv[i].line[0])) {
                gib_fail(err, "%s: the shards' passes CSVs have different columns (%s and %s)",
                         name, path, sh[k].dir);
                goto done_passes;
            }
        int pk[6];
        for (int k = 0; k < 6; k++)
            if ((pk[k] = column_of(pcsv[i].line[0], pass_key_names[k])) < 0) {
                gib_fail(err, "%s: no column '%s'", path, pass_key_names[k]);
                goto done_passes;
            }
        for (int li = 1; li < pcsv[i].count; li++) {
            char key[1024] = "", f[512], rk[1024];
            for (int k = 0; k < 6; k++) {
                csv_field(pcsv[i].line[li], pk[k], f, sizeof f);
                strncat(key, k ? "|" : "", sizeof key - strlen(key) - 1);
                strncat(key, f, sizeof key - strlen(key) - 1);
            }
            int ord = -1;
            for (int r = 0; r < sh[i].nrows && ord < 0; r++) {
                run_key_of(sh[i].rows[r].key, rk, sizeof rk);
                if (!strcmp(rk, key))
                    ord = sh[i].rows[r].ordinal;
            }
            if (ord < 0) {
                gib_fail(err, "%s:%d: passes of run %s, not one of shard %d/%d's", path, li + 1,
                         key, sh[i].index, sh[i].count);
                goto done_passes;
            }
            if (npass == pcap) {
                pcap = pcap ? 2 * pcap : 256;
                mrow *np = realloc(passes, (size_t)pcap * sizeof *np);
                if (!np) {
                    gib_fail(err, "out of memory");
                    goto done_passes;
                }
                passes = np;
            }
            passes[npass] = (mrow){.ordinal = ord, .sub = npass, .line = pcsv[i].line[li]};
            npass++;
        }
    }
    if (npass) /* qsort of NULL, even with no element, is undefined */
        qsort(passes, (size_t)npass, sizeof *passes, by_order);
    if (gib_mkdirs(out, err) < 0)
        goto done_passes;
    snprintf(path, sizeof path, "%s/%s.csv", out, name);
    if (write_atomic(path, csv[0].line[0], all, nall, err) < 0)
        goto done_passes;
    for (int i = 0; i < n; i++)
        if (pcsv[i].count) {
            snprintf(path, sizeof path, "%s/%s_passes.csv", out, name);
            if (write_atomic(path, pcsv[i].line[0], passes, npass, err) < 0)
                goto done_passes;
            break;
        }
    int nimages = 0;
    for (int i = 0; i < n; i++) {
        int k = gather_images(sh[i].dir, out, name, err);
        if (k < 0)
            goto done_passes;
        nimages += k;
    }
    printf("%s: %d shards, %d runs, %d rows -> %s/%s.csv", name, a->count, a->runs, nall, out, name);
    if (nimages)
        printf(", %d images -> %s/images/%s/", nimages, out, name);
    printf("\n");
    rc = 0;
done_passes:
    free(passes);
done:
    for (int i = 0; csv && pcsv && i < n; i++)
        free_lines(&csv[i]), free_lines(&pcsv[i]);
    free(csv), free(pcsv), free(all);
    return rc;
}

int gib_cmd_merge(int argc, char **argv)
{
    const char *out = NULL, *dirs[GIB_SHARD_MAX], *only[64];
    int ndirs = 0, nonly = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(help, stdout);
            return 0;
        }
        if (a[0] != '-') {
            if (ndirs == GIB_SHARD_MAX) {
                fprintf(stderr, "gibench merge: more than %d folders\n", GIB_SHARD_MAX);
                return 2;
            }
            dirs[ndirs++] = a;
            continue;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "gibench merge: option %s needs a value\n%s", a, help);
            return 2;
        }
        const char *v = argv[++i];
        if (!strcmp(a, "--out"))
            out = v;
        else if (!strcmp(a, "--matrix") && nonly < 64)
            only[nonly++] = v;
        else {
            fprintf(stderr, "gibench merge: unknown option '%s'\n%s", a, help);
            return 2;
        }
    }
    if (!ndirs || !out) {
        fprintf(stderr, "gibench merge: %s\n%s", !ndirs ? "no shard folder given" : "--out DIR missing",
                help);
        return 2;
    }
    /* Every manifest in every folder, grouped by matrix below. */
    manifest *sh = NULL;
    int nsh = 0, cap = 0, status = 0;
    gib_error err;
    char names[64][64];
    int nnames = 0;
    for (int d = 0; d < ndirs && !status; d++) {
        DIR *dp = opendir(dirs[d]);
        if (!dp) {
            fprintf(stderr, "gibench merge: cannot open the shard folder %s\n", dirs[d]);
            status = 1;
            break;
        }
        int here = 0;
        struct dirent *e;
        while ((e = readdir(dp))) {
            size_t len = strlen(e->d_name);
            if (len < 7 || strcmp(e->d_name + len - 6, ".shard"))
                continue;
            char mname[64];
            snprintf(mname, sizeof mname, "%.*s", (int)(len - 6), e->d_name);
            int wanted = !nonly;
            for (int k = 0; k < nonly; k++)
                wanted |= !strcmp(only[k], mname);
            if (!wanted)
                continue;
            if (nsh == cap) {
                cap = cap ? 2 * cap : 16;
                manifest *ns = realloc(sh, (size_t)cap * sizeof *ns);
                if (!ns) {
                    status = 1;
                    break;
                }
                sh = ns;
            }
            if (read_manifest(dirs[d], e->d_name, &sh[nsh], &err) < 0) {
                fprintf(stderr, "gibench merge: %s\n", err.msg);
                free_manifest(&sh[nsh]);
                status = 1;
                break;
            }
            if (strcmp(sh[nsh].matrix, mname)) {
                fprintf(stderr, "gibench merge: %s/%s names matrix '%s'\n", dirs[d], e->d_name,
                        sh[nsh].matrix);
                free_manifest(&sh[nsh]);
                status = 1;
                break;
            }
            int known = 0;
            for (int k = 0; k < nnames; k++)
                known |= !strcmp(names[k], mname);
            if (!known && nnames < 64)
                snprintf(names[nnames++], sizeof names[0], "%s", mname);
            nsh++;
            here++;
        }
        closedir(dp);
        if (!status && !here) {
            fprintf(stderr, "gibench merge: %s holds no shard manifest (*.shard)%s\n", dirs[d],
                    nonly ? " of the matrices named" : ": not a `gibench run --shard` folder");
            status = 1;
        }
    }
    /* Every folder must hold a shard of every matrix: a folder of another matrix is refused. */
    for (int k = 0; !status && k < nnames; k++)
        for (int d = 0; d < ndirs && !status; d++) {
            int has = 0;
            for (int i = 0; i < nsh; i++)
                has |= !strcmp(sh[i].matrix, names[k]) && !strcmp(sh[i].dir, dirs[d]);
            if (!has) {
                fprintf(stderr, "gibench merge: %s holds no shard of matrix '%s' that the other "
                                "folders hold: shards of different matrices\n", dirs[d], names[k]);
                status = 1;
            }
        }
    for (int k = 0; !status && k < nnames; k++) {
        manifest *group = malloc((size_t)nsh * sizeof *group);
        int ng = 0;
        for (int i = 0; group && i < nsh; i++)
            if (!strcmp(sh[i].matrix, names[k]))
                group[ng++] = sh[i];
        if (!group || merge_matrix(group, ng, out, &err) < 0) {
            fprintf(stderr, "gibench merge: %s\n", group ? err.msg : "out of memory");
            status = 1;
        }
        free(group);
    }
    for (int i = 0; i < nsh; i++)
        free_manifest(&sh[i]);
    free(sh);
    return status;
}

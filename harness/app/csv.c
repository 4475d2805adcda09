#include "csv.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

/* Splits one CSV line (RFC 4180 quoting, no embedded newlines: gibench never writes them) into
 * fields, in place. Returns the field count. */
static int split_csv(char *line, char **fields, int max)
{
    int n = 0;
    char *p = line;
    while (n < max) {
        char *out = p;
        fields[n++] = out;
        if (*p == '"') {
            p++;
            for (;;) {
                if (*p == '"' && p[1] == '"') {
                    *out++ = '"';
                    p += 2;
                } else if (*p == '"') {
                    p++;
                    break;
                } else if (!*p) {
                    break;
                } else {
                    *out++ = *p++;
                }
            }
            while (*p && *p != ',')
                p++;
        } else {
            while (*p && *p != ',')
                *out++ = *p++;
        }
        int more = *p == ',';
        *out = 0;
        if (!more)
            break;
        p++;
    }
    return n;
}

static void write_field(FILE *f, const char *v)
{
    if (!v)
        return;
    if (!strpbrk(v, ",\"\n\r")) {
        fputs(v, f);
        return;
    }
    fputc('"', f);
    for (; *v; v++) {
        if (*v == '"')
            fputc('"', f);
        fputc(*v == '\n' || *v == '\r' ? ' ' : *v, f);
    }
    fputc('"', f);
}

static void header_line(const char *const *columns, int ncols, char *out, size_t len)
{
    out[0] = 0;
    for (int i = 0; i < ncols; i++) {
        strncat(out, i ? "," : "", len - strlen(out) - 1);
        strncat(out, columns[i], len - strlen(out) - 1);
    }
}

/* A process killed while appending leaves a last line without its newline: cut it off, so that the
 * next row starts on a line of its own and the file parses. */
static int cut_unfinished_line(const char *path, gib_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return gib_fail(err, "cannot reopen %s", path);
    long size = fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1, keep = size;
    int c = EOF;
    while (keep > 0 && fseek(f, keep - 1, SEEK_SET) == 0 && (c = fgetc(f)) != '\n')
        keep--;
    fclose(f);
    if (size < 0)
        return gib_fail(err, "cannot read %s", path);
    if (keep == size)
        return 0;
    if (keep == 0) {
        /* No newline at all: the file is the header alone (the caller matched it whole), written
         * by a run killed before its newline. Finish the line; cutting it would lose the header
         * (found by tests/fuzz/fuzz_resume). */
        FILE *a = fopen(path, "ab");
        int ok = a && fputc('\n', a) != EOF;
        if (a && fclose(a) != 0)
            ok = 0;
        return ok ? 0 : gib_fail(err, "%s: cannot finish its header line", path);
    }
    if (truncate(path, keep) != 0)
        return gib_fail(err, "%s ends in an unfinished line that cannot be cut off", path);
    fprintf(stderr, "gibench: %s: cut off an unfinished last line (%ld bytes) left by an "
                    "interrupted run\n", path, size - keep);
    return 0;
}

static void row_key(const gib_csv *c, char *const *fields, char *key, size_t len)
{
    key[0] = 0;
    for (int k = 0; k < c->nkey; k++) {
        strncat(key, k ? "|" : "", len - strlen(key) - 1);
        strncat(key, fields[c->key_cols[k]] ? fields[c->key_cols[k]] : "", len - strlen(key) - 1);
    }
}

static int add_key(gib_csv *c, const char *key)
{
    char **nk = realloc(c->keys, sizeof(char *) * (c->nkeys + 1));
    if (!nk)
        return -1;
    c->keys = nk;
    if (!(c->keys[c->nkeys] = strdup(key)))
        return -1;
    for (char *p = c->keys[c->nkeys]; *p; p++)
        if (*p == '\n' || *p == '\r')
            *p = ' '; /* as the row is written (write_field) */
    c->nkeys++;
    return 0;
}

/* PATH.lock, flock'ed: one writer a table. A second run of the same matrix into the same folder
 * refuses before it reads or cuts anything, rather than append the same rows. The lock is kept
 * open until gib_csv_close, so it goes with the process, even when that is killed. */
static int lock_table(gib_csv *c, const char *path, gib_error *err)
{
    char lock[1100];
    snprintf(lock, sizeof lock, "%s.lock", path);
    c->lock_fd = open(lock, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (c->lock_fd < 0)
        return gib_fail(err, "cannot create the lock file %s", lock);
    if (flock(c->lock_fd, LOCK_EX | LOCK_NB) != 0) {
        int busy = errno == EWOULDBLOCK;
        close(c->lock_fd);
        c->lock_fd = -1;
        return gib_fail(err, "%s: %s", path, busy ? "another gibench run is writing this table (one "
                                                    "run a matrix and output folder at a time)"
                                                  : "cannot lock it");
    }
    return 0;
}

/* The identity keys of the rows after the header of `old` (a file whose header is the table's). */
static void load_keys(gib_csv *c, FILE *old, char **line, size_t *cap)
{
    char **fields = malloc(sizeof(char *) * (c->ncols + 1));
    ssize_t len;
    while (fields && (len = getline(line, cap, old)) > 0) {
        char *l = *line;
        /* A last line without its newline was left by a killed run and is cut off by the caller:
         * its key must not count, or its row would never be written again (found by
         * tests/fuzz/fuzz_resume: a row cut inside its last field). */
        if (l[len - 1] != '\n')
            break;
        l[strcspn(l, "\r\n")] = 0;
        if (!l[0])
            continue;
        /* A damaged line with too few or too many fields is no row. */
        if (split_csv(l, fields, c->ncols + 1) != c->ncols)
            continue;
        if (!c->nkey)
            continue;
        char key[4096];
        row_key(c, fields, key, sizeof key);
        if (add_key(c, key) < 0)
            break;
    }
    free(fields);
}

/* Whether PATH holds this header (its rows' keys then loaded). Returns 1 when it does, 0 when it has
 * other columns (or none), -1 when it cannot be opened (absent). */
static int keep_existing(gib_csv *c, const char *path, const char *header)
{
    FILE *old = fopen(path, "r");
    if (!old)
        return -1;
    char *line = NULL;
    size_t cap = 0;
    int same = 0;
    if (getline(&line, &cap, old) > 0) {
        line[strcspn(line, "\r\n")] = 0;
        if ((same = !strcmp(line, header)))
            load_keys(c, old, &line, &cap);
    }
    free(line);
    fclose(old);
    return same;
}

int gib_csv_open(gib_csv *c, const char *path, const char *const *columns, int ncols,
                 const int *key_cols, int nkey, gib_error *err)
{
    memset(c, 0, sizeof *c);
    snprintf(c->path, sizeof c->path, "%s", path);
    c->ncols = ncols;
    c->lock_fd = -1;
    if (lock_table(c, path, err) < 0)
        return -1;
    if (nkey < 0 || nkey > (int)(sizeof c->key_cols / sizeof c->key_cols[0]))
        return gib_fail(err, "%s: %d key columns, at most 16", path, nkey);
    for (int k = 0; k < nkey; k++)
        c->key_cols[k] = key_cols[k];
    c->nkey = nkey;
    char header[8192];
    header_line(columns, ncols, header, sizeof header);
    int kept = keep_existing(c, path, header), fresh = kept != 1;
    if (!fresh && cut_unfinished_line(path, err) < 0)
        return -1;
    if (kept == 0) {
        if (gib_csv_move_aside(path, err) < 0)
            return -1;
        c->moved_aside = 1;
        fprintf(stderr, "gibench: %s had different columns; moved it to %s.old\n", path, path);
    }
    c->f = fopen(path, "a");
    if (!c->f)
        return gib_fail(err, "cannot open %s for appending", path);
    setvbuf(c->f, NULL, _IOFBF, 1 << 16); /* a row leaves in one write(2) */
    if (fresh) {
        fprintf(c->f, "%s\n", header);
        fflush(c->f);
    }
    return 0;
}

int gib_csv_move_aside(const char *path, gib_error *err)
{
    char aside[1100];
    snprintf(aside, sizeof aside, "%s.old", path);
    if (rename(path, aside) != 0 && errno != ENOENT)
        return gib_fail(err, "%s cannot be moved aside to %s: %s", path, aside, strerror(errno));
    return 0;
}

int gib_csv_append(gib_csv *c, const char *const *values, gib_error *err)
{
    char key[4096];
    if (c->nkey) {
        row_key(c, (char *const *)values, key, sizeof key);
        if (gib_csv_has(c, key))
            return 0;
    }
    for (int i = 0; i < c->ncols; i++) {
        if (i)
            fputc(',', c->f);
        write_field(c->f, values[i]);
    }
    fputc('\n', c->f);
    if (fflush(c->f) != 0 || ferror(c->f))
        return gib_fail(err, "writing %s failed: %s", c->path, strerror(errno));
    if (c->nkey && add_key(c, key) < 0)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "out of memory keeping the keys of %s", c->path);
    return 1;
}

/* Whether a key read back from the file equals a row's key before writing: write_field turns a
 * value's line breaks into spaces, so they compare as spaces (else a resumed run would not know
 * such a row and write it twice; found by tests/fuzz/fuzz_resume). */
static int same_key(const char *stored, const char *key)
{
    for (;; stored++, key++) {
        char k = *key == '\n' || *key == '\r' ? ' ' : *key;
        if (*stored != k)
            return 0;
        if (!k)
            return 1;
    }
}

int gib_csv_has(const gib_csv *c, const char *key)
{
    for (int i = 0; i < c->nkeys; i++)
        if (same_key(c->keys[i], key))
            return 1;
    return 0;
}

void gib_csv_close(gib_csv *c)
{
    if (c->f)
        fclose(c->f);
    if (c->lock_fd >= 0)
        close(c->lock_fd); /* releases the lock */
    for (int i = 0; i < c->nkeys; i++)
        free(c->keys[i]);
    free(c->keys);
    memset(c, 0, sizeof *c);
    c->lock_fd = -1;
}

#include "csv.h"

#include <stdlib.h>
#include <string.h>

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

int gib_csv_open(gib_csv *c, const char *path, const char *const *columns, int ncols,
                 const int *key_cols, int nkey, gib_error *err)
{
    memset(c, 0, sizeof *c);
    snprintf(c->path, sizeof c->path, "%s", path);
    c->ncols = ncols;
    char header[8192];
    header_line(columns, ncols, header, sizeof header);
    FILE *old = fopen(path, "r");
    int fresh = 1;
    if (old) {
        static char line[65536];
        if (fgets(line, sizeof line, old)) {
            line[strcspn(line, "\r\n")] = 0;
            if (!strcmp(line, header)) {
                fresh = 0;
                char **fields = malloc(sizeof(char *) * ncols);
                while (fields && fgets(line, sizeof line, old)) {
                    line[strcspn(line, "\r\n")] = 0;
                    if (!line[0])
                        continue;
                    /* A truncated last line (killed mid-write) has too few fields: not finished. */
                    if (split_csv(line, fields, ncols) != ncols)
                        continue;
                    char key[4096] = "";
                    for (int k = 0; k < nkey; k++) {
                        strncat(key, k ? "|" : "", sizeof key - strlen(key) - 1);
                        strncat(key, fields[key_cols[k]], sizeof key - strlen(key) - 1);
                    }
                    char **nk = realloc(c->keys, sizeof(char *) * (c->nkeys + 1));
                    if (!nk)
                        break;
                    c->keys = nk;
                    c->keys[c->nkeys++] = strdup(key);
                }
                free(fields);
            }
        }
        fclose(old);
        if (fresh) {
            char aside[1100];
            snprintf(aside, sizeof aside, "%s.old", path);
            if (rename(path, aside) != 0)
                return gib_fail(err, "%s has different columns and cannot be moved aside", path);
            fprintf(stderr, "gibench: %s had different columns; moved it to %s\n", path, aside);
        }
    }
    c->f = fopen(path, "a");
    if (!c->f)
        return gib_fail(err, "cannot open %s for appending", path);
    if (fresh) {
        fprintf(c->f, "%s\n", header);
        fflush(c->f);
    }
    return 0;
}

int gib_csv_append(gib_csv *c, const char *const *values, gib_error *err)
{
    for (int i = 0; i < c->ncols; i++) {
        if (i)
            fputc(',', c->f);
        write_field(c->f, values[i]);
    }
    fputc('\n', c->f);
    if (fflush(c->f) != 0 || ferror(c->f))
        return gib_fail(err, "writing %s failed", c->path);
    return 0;
}

int gib_csv_has(const gib_csv *c, const char *key)
{
    for (int i = 0; i < c->nkeys; i++)
        if (!strcmp(c->keys[i], key))
            return 1;
    return 0;
}

void gib_csv_close(gib_csv *c)
{
    if (c->f)
        fclose(c->f);
    for (int i = 0; i < c->nkeys; i++)
        free(c->keys[i]);
    free(c->keys);
    memset(c, 0, sizeof *c);
}

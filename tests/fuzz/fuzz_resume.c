/* Fuzz target: a results table as `gibench run` finds it when resuming (harness/app/csv.c): the
 * input's first part (up to "####\n") is the table file in the output folder, whatever a killed
 * run, a full disk or an editor left there; the second is a row to append, its four values
 * separated by tabs (line breaks, quotes and commas allowed). gib_csv_open must keep, cut or move
 * the file aside, never crash; and every row exactly once holds: after the append, a reopened
 * table knows the row, appending it again writes nothing, and the file ends in a newline. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness/app/csv.h"
#include "tests/fuzz/fuzz_common.h"

static char path[512], lock[600], old[600];

static void remove_files(void)
{
    unlink(path), unlink(lock), unlink(old);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!path[0]) {
        const char *tmp = getenv("TMPDIR");
        snprintf(path, sizeof path, "%s/gibench-fuzz-resume-%ld.csv", tmp && *tmp ? tmp : "/tmp",
                 (long)getpid());
        snprintf(lock, sizeof lock, "%s.lock", path);
        snprintf(old, sizeof old, "%s.old", path);
        atexit(remove_files);
    }
    const char *p = (const char *)data, *end = p + size;
    size_t len;
    const char *table = fuzz_next_part(&p, end, &len);
    remove_files();
    FILE *f = fopen(path, "wb");
    if (!f)
        return 0;
    fwrite(table, 1, len, f);
    fclose(f);
    /* The row: four values, tab-separated, NUL bytes dropped (values are C strings). */
    static char buf[1 << 15];
    char *vals[4] = {buf, "", "", ""};
    size_t o = 0;
    int nv = 1;
    for (const char *q = p ? p : end; q < end && o + 1 < sizeof buf; q++) {
        if (*q == '\t' && nv < 4) {
            buf[o++] = 0;
            vals[nv++] = buf + o;
        } else if (*q) {
            buf[o++] = *q;
        }
    }
    buf[o] = 0;

    static const char *const cols[] = {"profile", "scene", "params", "rmse"};
    static const int keys[] = {0, 1, 2};
    gib_csv c;
    gib_error err;
    if (gib_csv_open(&c, path, cols, 4, keys, 3, &err) < 0) {
        gib_csv_close(&c);
        return 0; /* a refusal with a message is fine */
    }
    int rc = gib_csv_append(&c, (const char *const *)vals, &err);
    gib_csv_close(&c);
    if (rc < 0)
        abort(); /* the disk is not full here */
    if (gib_csv_open(&c, path, cols, 4, keys, 3, &err) < 0)
        abort(); /* the table just written must reopen */
    int again = gib_csv_append(&c, (const char *const *)vals, &err);
    gib_csv_close(&c);
    if (again != 0) {
        fprintf(stderr, "fuzz_resume: a row appended and found again was written twice (%d)\n",
                again);
        abort();
    }
    f = fopen(path, "rb");
    int last = EOF, ch;
    while (f && (ch = fgetc(f)) != EOF)
        last = ch;
    if (f)
        fclose(f);
    if (last != '\n') {
        fprintf(stderr, "fuzz_resume: the table does not end in a newline\n");
        abort();
    }
    return 0;
}

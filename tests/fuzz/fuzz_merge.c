/* Fuzz target: `gibench merge` (harness/app/cmd_merge.c) over two shard folders whose files come
 * from the input: parts separated by "####\n", in the order a/m.shard, a/m.csv, a/m_passes.csv,
 * b/m.shard, b/m.csv, b/m_passes.csv (a part not there: that file absent; a folder with no
 * manifest part is not named). Merge reads the manifests and CSVs as a user's shard folders: it
 * must refuse what it cannot trust with a message, never crash. When it does merge, the merged
 * table must hold every row of the shards' CSVs exactly once (checked here: a merge that drops or
 * repeats a row is a bug even without a crash). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "harness/app/app.h"
#include "tests/fuzz/fuzz_common.h"

static char base[512];

static const char *const files[6] = {"a/m.shard", "a/m.csv", "a/m_passes.csv",
                                     "b/m.shard", "b/m.csv", "b/m_passes.csv"};

/* The data lines of a CSV part as merge counts them: non-empty once a trailing '\r' is dropped. */
static int data_lines(const char *p, size_t n)
{
    int lines = 0, first = 1;
    const char *end = p + n;
    while (p < end) {
        const char *e = memchr(p, '\n', (size_t)(end - p));
        size_t len = (size_t)((e ? e : end) - p);
        if (len && p[len - 1] == '\r')
            len--;
        if (len) {
            if (!first)
                lines++;
            first = 0;
        }
        p = e ? e + 1 : end;
    }
    return lines;
}

static void path_of(char *out, size_t cap, const char *name)
{
    snprintf(out, cap, "%s/%s", base, name);
}

static void remove_folders(void)
{
    char p[600];
    for (int i = 0; i < 6; i++)
        path_of(p, sizeof p, files[i]), unlink(p);
    const char *const dirs[] = {"out/m.csv", "out/m_passes.csv", "out", "a", "b", ""};
    for (int i = 0; i < 6; i++) {
        path_of(p, sizeof p, dirs[i]);
        if (unlink(p) != 0)
            rmdir(p);
    }
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    const char *tmp = getenv("TMPDIR");
    snprintf(base, sizeof base, "%s/gibench-fuzz-merge-%ld", tmp && *tmp ? tmp : "/tmp",
             (long)getpid());
    char p[600];
    mkdir(base, 0755);
    path_of(p, sizeof p, "a"), mkdir(p, 0755);
    path_of(p, sizeof p, "b"), mkdir(p, 0755);
    atexit(remove_folders);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!base[0])
        LLVMFuzzerInitialize(NULL, NULL);
    const char *p = (const char *)data, *end = p + size;
    const char *part[6] = {0};
    size_t len[6] = {0};
    int nparts = 0;
    while (nparts < 6 && p) {
        part[nparts] = fuzz_next_part(&p, end, &len[nparts]);
        nparts++;
    }
    char path[600];
    int csv_rows = 0;
    for (int i = 0; i < 6; i++) {
        path_of(path, sizeof path, files[i]);
        unlink(path);
        if (i >= nparts)
            continue;
        FILE *f = fopen(path, "wb");
        if (!f)
            return 0;
        fwrite(part[i], 1, len[i], f);
        fclose(f);
        if (i == 1 || i == 4)
            csv_rows += data_lines(part[i], len[i]);
    }
    char out[600], dir_a[600], dir_b[600], merged[700];
    path_of(out, sizeof out, "out");
    path_of(dir_a, sizeof dir_a, "a");
    path_of(dir_b, sizeof dir_b, "b");
    snprintf(merged, sizeof merged, "%s/m.csv", out);
    unlink(merged);
    char *argv[6] = {"merge", dir_a, dir_b, "--out", out, NULL};
    int argc = 5;
    if (nparts <= 3) { /* only folder a has a manifest */
        argv[2] = "--out", argv[3] = out, argv[4] = NULL;
        argc = 4;
    }
    if (gib_cmd_merge(argc, argv) == 0) {
        FILE *f = fopen(merged, "rb");
        if (!f) {
            fprintf(stderr, "fuzz_merge: merge succeeded but wrote no %s\n", merged);
            abort();
        }
        static char buf[1 << 17];
        size_t n = fread(buf, 1, sizeof buf, f);
        fclose(f);
        int rows = data_lines(buf, n);
        if (rows != csv_rows) {
            fprintf(stderr, "fuzz_merge: merged %d rows from shards holding %d\n", rows, csv_rows);
            abort();
        }
    }
    unlink(merged);
    snprintf(merged, sizeof merged, "%s/m_passes.csv", out);
    unlink(merged);
    return 0;
}

#include "scene_test.h"

#include <dirent.h>
#include <stdlib.h>
#include <unistd.h>

int failures;
char tmpdir[256];

int scene_test_begin(const char *name)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/%s_XXXXXX", name);
    if (!mkdtemp(tmpdir)) {
        printf("FAIL: mkdtemp %s\n", tmpdir);
        return -1;
    }
    return 0;
}

void write_file(const char *name, const char *text, char *out, size_t n)
{
    snprintf(out, n, "%s/%s", tmpdir, name);
    FILE *f = fopen(out, "wb");
    if (!f) {
        printf("FAIL: cannot write %s\n", out);
        exit(1);
    }
    fputs(text, f);
    fclose(f);
}

int scene_test_end(void)
{
    DIR *d = opendir(tmpdir);
    if (d) {
        struct dirent *e;
        char p[600];
        while ((e = readdir(d)) != NULL) {
            if (e->d_name[0] == '.')
                continue;
            snprintf(p, sizeof p, "%s/%s", tmpdir, e->d_name);
            unlink(p);
        }
        closedir(d);
    }
    rmdir(tmpdir);
    printf("%s: %d failure(s)\n", failures ? "FAILED" : "passed", failures);
    return failures ? 1 : 0;
}

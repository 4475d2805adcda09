#include "scene_test.h"

#include "scenes/scene.h"
#include "tests/common/check.h"

#include <dirent.h>
#include <string.h>
#include <stdlib.h>
#include <unistd.h>

int failures;
char tmpdir[256];

int scene_test_begin(const char *name)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/%s_XXXXXX", name);
    if (!mkdtemp(tmpdir)) {
        CHECK(0, "mkdtemp %s", tmpdir);
        return -1;
    }
    return 0;
}

void write_file(const char *name, const char *text, char *out, size_t n)
{
    snprintf(out, n, "%s/%s", tmpdir, name);
    FILE *f = fopen(out, "wb");
    if (!f) {
        CHECK(0, "cannot write %s", out);
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

/* Loads `text` as a scene file and expects return code `want_rc`, and a message that names the
 * file, `:line:` and contains `phrase` (and `phrase2` when non-NULL). */
void scene_expect_load(const char *what, const char *text, int want_rc, int line, const char *phrase,
                   const char *phrase2)
{
    static int n;
    char name[64], path[512];
    snprintf(name, sizeof name, "case%03d.scene", n++);
    write_file(name, text, path, sizeof path);
    gib_scene s;
    gib_error err;
    err.msg[0] = '\0';
    int rc = gib_scene_load(path, &s, &err);
    CHECK(rc == want_rc, "%s: rc = %d, want %d (message: %s)", what, rc, want_rc, err.msg);
    if (rc == 0) {
        gib_scene_free(&s);
        return;
    }
    char at[32];
    snprintf(at, sizeof at, ":%d:", line);
    CHECK(strstr(err.msg, path) != NULL, "%s: message does not name the file %s: %s", what, path,
          err.msg);
    CHECK(strstr(err.msg, at) != NULL, "%s: message does not name line %d: %s", what, line,
          err.msg);
    CHECK(strstr(err.msg, phrase) != NULL, "%s: message lacks '%s': %s", what, phrase, err.msg);
    if (phrase2)
        CHECK(strstr(err.msg, phrase2) != NULL, "%s: message lacks '%s': %s", what, phrase2,
              err.msg);
    printf("ok   %-28s %s\n", what, err.msg);
}

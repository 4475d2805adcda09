/* gibench scene tests — gib_obj_check (scenes/obj_check.c), the OBJ element check that keeps
 * assimp off the inputs it reads past its buffer on: the four reference forms accepted, relative
 * and continued lines as assimp reads them; every malformed reference refused naming the file and
 * line; and every OBJ of the shared data (GIBENCH_SCENES, when present) accepted, so the check
 * refuses nothing a real scene holds. */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "scenes/scene_internal.h"
#include "tests/common/check.h"

static int failures;

static void expect_ok(const char *text)
{
    gib_error err = {0};
    int rc = gib_obj_check(text, strlen(text), "t.obj", &err);
    CHECK(rc == 0, "accepted: %s (%s)", text, err.msg);
}

static void expect_refused(const char *text, const char *where, const char *phrase)
{
    gib_error err = {0};
    int rc = gib_obj_check(text, strlen(text), "t.obj", &err);
    CHECK(rc < 0 && strstr(err.msg, where) && strstr(err.msg, phrase),
          "refused naming '%s' and '%s': %s -> rc %d '%s'", where, phrase, text, rc, err.msg);
}

/* Every .obj under dir (recursively) passes the check. Returns the number checked. */
static int check_tree(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue;
        char p[2048];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        struct stat st;
        if (stat(p, &st) != 0)
            continue;
        if (S_ISDIR(st.st_mode)) {
            n += check_tree(p);
            continue;
        }
        size_t len = strlen(p);
        if (len < 4 || strcmp(p + len - 4, ".obj"))
            continue;
        FILE *f = fopen(p, "rb");
        char *buf = malloc((size_t)st.st_size + 1);
        size_t got = f && buf ? fread(buf, 1, (size_t)st.st_size, f) : 0;
        if (f)
            fclose(f);
        gib_error err = {0};
        CHECK(got == (size_t)st.st_size && gib_obj_check(buf, got, p, &err) == 0,
              "shared OBJ %s accepted: %s", p, err.msg);
        free(buf);
        n++;
    }
    closedir(d);
    return n;
}

int main(void)
{
    const char *tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n";
    char buf[512];
    snprintf(buf, sizeof buf, "%sf 1 2 3\nf 1/1 2/2 3/3\nf 1//1 2//1 3//1\nf 1/1/1 2/2/1 3/3/1\n",
             tri);
    expect_ok(buf);
    snprintf(buf, sizeof buf, "%sf -3 -2 -1\n# f 0 0 0\nl 1 2\np 3\ng x\nusemtl m\n", tri);
    expect_ok(buf);
    snprintf(buf, sizeof buf, "%sf 1 2 \\\n 3\r\n", tri); /* continued, CRLF */
    expect_ok(buf);
    expect_ok("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"); /* forward references: assimp takes them */

    /* The fuzzer's input: a fourth index on the last line (assimp read past its buffer). */
    expect_refused("f 2/ 1//1 1///1\n", "t.obj':1:", "refers to a v that is not in the file");
    snprintf(buf, sizeof buf, "%sf 1 2 1///1\n", tri);
    expect_refused(buf, "t.obj':8:", "'1///1' in 'f' is not v, v/vt, v//vn or v/vt/vn");
    /* Statements after the seven vertex lines (so on line 8), each refused naming its fault. */
    static const struct {
        const char *statement, *phrase;
    } bad[] = {
        {"f 1/1/1/1 2 3", "'1/1/1/1'"},
        {"f 0 1 2", "refers to a v that is not in the file"}, /* indices start at 1 */
        {"f 1 2 4", "refers to a v that is not in the file"},
        {"f 1/4 2/1 3/1", "refers to a vt"},
        {"f 1//2 2//1 3//1", "refers to a vn"},
        {"f 1/ 2 3", "'1/'"},
        {"f a b c", "'a'"},
        {"f 1x 2 3", "'1x'"},
        {"f", "with no vertex"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(buf, sizeof buf, "%s%s\n", tri, bad[i].statement);
        expect_refused(buf, "t.obj':8:", bad[i].phrase);
    }
    /* Lines end where assimp ends them: a CR-only file's faces are checked too. */
    expect_ok("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r");
    expect_refused("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 4\r", "t.obj':4:", "refers to a v");
    expect_refused("v 0 0 0\fv 1 0 0\fv 0 1 0\ff 1 2 \v3\n", "t.obj':1:", "'\v3'");
    /* The fuzzer's second input: a NUL hid the face from the check, and assimp's strtol ran on
     * over vertical tabs past its buffer. */
    static const char nul_face[] = "\0f 0/\v\v\v\n";
    gib_error err = {0};
    int rc = gib_obj_check(nul_face, sizeof nul_face - 1, "t.obj", &err);
    CHECK(rc < 0 && strstr(err.msg, "t.obj':1: a NUL byte"), "a NUL byte refused: %s", err.msg);
    snprintf(buf, sizeof buf, "f -1 1 2\n%s", tri); /* relative before any vertex */
    expect_refused(buf, "t.obj':1:", "refers to a v");
    snprintf(buf, sizeof buf, "%sf 1 2 \\\n 3/1/1/1\nf 1 2 3\n", tri); /* the line counts both */
    expect_refused(buf, "t.obj':9:", "'3/1/1/1'");

    const char *root = gib_scene_data_root();
    int n = root ? check_tree(root) : 0;
    printf("%d shared-data OBJ files checked%s\n", n, n ? "" : " (no shared data here)");
    if (failures)
        CHECK(0, "ED: %d", failures);
    else
        printf("passed\n");
    return failures != 0;
}

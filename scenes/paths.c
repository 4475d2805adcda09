/* gibench — where scene files and shared scene data live, and resolving the file names that mesh
 * and material files contain.
 *
 * Archives made on Windows name files with the wrong case and with backslashes (Crytek and
 * Dabrovic Sponza say "SP_LUK.JPG" for sp_luk.JPG), so names are matched per path component,
 * exactly first and case-insensitively when the exact name is absent. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "scene_internal.h"

#ifndef GIB_PROJECT_ROOT
#define GIB_PROJECT_ROOT "."
#endif

int gib_path_is_dir(const char *path)
{
    struct stat st;
    return path && stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

int gib_path_is_file(const char *path)
{
    struct stat st;
    return path && stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

const char *gib_scene_data_root(void)
{
    /* Recomputed on every call (the environment may change, e.g. in tests); the static buffer
     * keeps the returned pointer valid until the next call. */
    static char root[GIB_PATH_MAX];
    const char *env = getenv("GIBENCH_SCENES");
    if (env && env[0]) {
        snprintf(root, sizeof root, "%s", env);
        return root;
    }
    snprintf(root, sizeof root, "%s", GIB_PROJECT_ROOT "/../shared/scenes");
    return gib_path_is_dir(root) ? root : NULL;
}

const char *gib_scene_dir(void)
{
    static char dir[GIB_PATH_MAX];
    const char *env = getenv("GIBENCH_ROOT");
    snprintf(dir, sizeof dir, "%s/scenes", env && env[0] ? env : GIB_PROJECT_ROOT);
    return dir;
}

void gib_path_dirname(const char *path, char *out, size_t out_len)
{
    const char *slash = strrchr(path, '/');
    if (!slash) {
        snprintf(out, out_len, ".");
        return;
    }
    size_t n = (size_t)(slash - path);
    if (n == 0)
        n = 1; /* "/file" -> "/" */
    if (n >= out_len)
        n = out_len - 1;
    memcpy(out, path, n);
    out[n] = '\0';
}

int gib_path_join(const char *dir, const char *rel, char *out, size_t out_len)
{
    int n;
    if (rel[0] == '/' || !dir || !dir[0])
        n = snprintf(out, out_len, "%s", rel);
    else if (dir[strlen(dir) - 1] == '/')
        n = snprintf(out, out_len, "%s%s", dir, rel);
    else
        n = snprintf(out, out_len, "%s/%s", dir, rel);
    return (n < 0 || (size_t)n >= out_len) ? -1 : 0;
}

/* Finds `name` in folder `dir` ignoring case; writes the name on disk into out. */
static int find_ci(const char *dir, const char *name, char *out, size_t out_len)
{
    DIR *d = opendir(dir[0] ? dir : ".");
    if (!d)
        return -1;
    int found = -1;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcasecmp(e->d_name, name) == 0 && strlen(e->d_name) < out_len) {
            snprintf(out, out_len, "%s", e->d_name);
            found = 0;
            break;
        }
    }
    closedir(d);
    return found;
}

int gib_path_resolve_ci(const char *path, char *out, size_t out_len)
{
    char p[GIB_PATH_MAX];
    if (snprintf(p, sizeof p, "%s", path) >= (int)sizeof p)
        return -1;
    for (char *c = p; *c; c++)
        if (*c == '\\')
            *c = '/';
    struct stat st;
    if (stat(p, &st) == 0) { /* the common case costs one stat */
        if (strlen(p) >= out_len)
            return -1;
        snprintf(out, out_len, "%s", p);
        return 0;
    }

    char cur[GIB_PATH_MAX];
    size_t len = 0;
    cur[0] = '\0';
    if (p[0] == '/') {
        cur[0] = '/';
        cur[1] = '\0';
        len = 1;
    }
    char *save = NULL;
    for (char *comp = strtok_r(p, "/", &save); comp; comp = strtok_r(NULL, "/", &save)) {
        if (strcmp(comp, ".") == 0)
            continue;
        char cand[GIB_PATH_MAX];
        const char *sep = (len == 0 || cur[len - 1] == '/') ? "" : "/";
        if (snprintf(cand, sizeof cand, "%s%s%s", cur, sep, comp) >= (int)sizeof cand)
            return -1;
        if (strcmp(comp, "..") != 0 && stat(cand, &st) != 0) {
            char real[256];
            if (find_ci(cur, comp, real, sizeof real) != 0)
                return -1;
            if (snprintf(cand, sizeof cand, "%s%s%s", cur, sep, real) >= (int)sizeof cand)
                return -1;
        }
        snprintf(cur, sizeof cur, "%s", cand);
        len = strlen(cur);
    }
    if (len == 0 || len >= out_len || stat(cur, &st) != 0)
        return -1;
    snprintf(out, out_len, "%s", cur);
    return 0;
}

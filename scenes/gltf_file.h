/* gibench — a glTF 2.0 file opened for what a .scene takes from it (gltf_scene.c, gltf_nodes.c):
 * the file's bytes, a GLB's BIN chunk, its JSON (gltf_bounds.c's reader), and small readers of
 * that JSON shared by both files. */
#ifndef GIB_GLTF_FILE_H
#define GIB_GLTF_FILE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"


typedef struct gfile {
    const char *path;
    char *data;            /* the whole file */
    size_t len;
    const char *bin;       /* a GLB's BIN chunk */
    size_t bin_len;
    int glb;
    gib_json *j;
} gfile;

static inline void gfile_close(gfile *f)
{
    gib_json_free(f->j);
    free(f->data);
    memset(f, 0, sizeof *f);
}

static inline int read_all(const char *path, char **out, size_t *len, gib_error *err)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return gib_fail(err, "glTF '%s': cannot open it", path);
    long size = fseek(fp, 0, SEEK_END) == 0 ? ftell(fp) : -1;
    char *buf = size >= 0 ? malloc((size_t)size + 1) : NULL;
    int ok = buf && fseek(fp, 0, SEEK_SET) == 0 && fread(buf, 1, (size_t)size, fp) == (size_t)size;
    fclose(fp);
    if (!ok) {
        free(buf);
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "glTF '%s': cannot read it", path);
    }
    *out = buf;
    *len = (size_t)size;
    return 0;
}

/* The file a relative URI of the glTF at `path` names, beside it (an absolute one as it is):
 * joined, and found on disk (names matched ignoring case); -1 when it is not there. */
static inline int beside(const char *path, const char *rel, char joined[GIB_PATH_MAX],
                         char found[GIB_PATH_MAX])
{
    char dir[GIB_PATH_MAX];
    gib_path_dirname(path, dir, GIB_PATH_MAX);
    if (gib_path_join(dir, rel, joined, GIB_PATH_MAX))
        return snprintf(joined, GIB_PATH_MAX, "%s", rel), -1;
    return gib_path_resolve_ci(joined, found, GIB_PATH_MAX) || !gib_path_is_file(found) ? -1 : 0;
}

/* The file a buffer's or image's `uri` names is there ("data:" URIs aside): else an error naming
 * the file, where it was looked for and the glTF that names it. */
static inline int uri_file_there(const char *path, const gib_json *j, int uri, const char *what,
                                 int i, gib_error *err)
{
    const char *s;
    size_t n;
    char rel[GIB_PATH_MAX], joined[GIB_PATH_MAX], found[GIB_PATH_MAX];
    if (gib_json_span(j, uri, &s, &n) || (n >= 5 && memcmp(s, "data:", 5) == 0) ||
        gib_json_str(j, uri, rel, sizeof rel) || beside(path, rel, joined, found) == 0)
        return 0;
    return gib_fail(err, "glTF '%s': %s %d's file '%s' is missing (looked for '%s'%s)", path,
                    what, i, rel, joined,
                    strchr(rel, '%') ? "; percent-encoded URIs are not decoded" : "");
}

/* Every buffer file the glTF names is there, so that a missing one is named as missing (not as
 * a buffer of 0 bytes by gib_gltf_bounds). */
static inline int buffer_files(const char *path, const gib_json *j, gib_error *err)
{
    int i = 0;
    for (int b = -1; (b = gib_json_child(j, gib_json_get(j, 0, "buffers"), b)) >= 0; i++)
        if (uri_file_there(path, j, gib_json_get(j, b, "uri"), "buffer", i, err))
            return -1;
    return 0;
}

/* Reads and checks (gib_gltf_bounds) the file, splits a GLB and parses the JSON; a missing
 * buffer file is reported before the bounds' checks. */
static inline int gfile_open(const char *path, gfile *f, gib_error *err)
{
    memset(f, 0, sizeof *f);
    f->path = path;
    size_t pl = strlen(path);
    f->glb = pl > 4 && (strcmp(path + pl - 4, ".glb") == 0 || strcmp(path + pl - 4, ".GLB") == 0);
    if (read_all(path, &f->data, &f->len, err))
        return -1;
    const char *json = f->data;
    size_t jlen = f->len;
    if (f->glb && gib_glb_split(f->data, f->len, path, &json, &jlen, &f->bin, &f->bin_len, err))
        return gfile_close(f), -1;
    int rc = gib_json_parse(json, jlen, &f->j);
    if ((rc == 0 && buffer_files(path, f->j, err)) ||
        gib_gltf_bounds(f->data, f->len, path, f->glb, err))
        return gfile_close(f), -1;
    if (rc)
        return gfile_close(f), rc == -2 ? gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                                                        "glTF '%s': out of memory", path)
                                        : gib_fail(err, "glTF '%s': its JSON is not one object",
                                                   path);
    return 0;
}

/* ------------------------------------------------------------------ small readers */

static inline int top(const gfile *f, const char *key, int i)
{
    int a = gib_json_get(f->j, 0, key), k = -1;
    for (int n = 0; (k = gib_json_child(f->j, a, k)) >= 0; n++)
        if (n == i)
            return k;
    return -1;
}

static inline int count(const gfile *f, int arr)
{
    int n = 0;
    for (int k = -1; (k = gib_json_child(f->j, arr, k)) >= 0;)
        n++;
    return gib_json_type(f->j, arr) == 'a' ? n : 0;
}

/* Member `key` of o as a number (dflt when absent); -1 when present but not a number. */
static inline int num(const gfile *f, int o, const char *key, double dflt, double *out)
{
    int v = gib_json_get(f->j, o, key);
    *out = dflt;
    return v < 0 ? 0 : gib_json_num(f->j, v, out);
}

/* Up to n numbers of array member `key` of o (dflt kept where absent). */
static inline int nums(const gfile *f, int o, const char *key, double *out, int n)
{
    int a = gib_json_get(f->j, o, key), i = 0;
    if (a < 0)
        return 0;
    if (gib_json_type(f->j, a) != 'a')
        return -1;
    for (int k = -1; (k = gib_json_child(f->j, a, k)) >= 0 && i < n; i++)
        if (gib_json_num(f->j, k, &out[i]))
            return -1;
    return i == n ? 0 : -1;
}

static inline int index_of(const gfile *f, int o, const char *key, int *out)
{
    double v;
    int t = gib_json_get(f->j, o, key);
    *out = -1;
    if (t < 0)
        return 0;
    if (gib_json_num(f->j, t, &v) || v < 0 || v > 1e9 || v != floor(v))
        return -1;
    *out = (int)v;
    return 0;
}

/* A JSON literal true (doubleSided, extras' flags). */
static inline int is_true(const gfile *f, int tok)
{
    const char *s;
    size_t n;
    return tok >= 0 && gib_json_span(f->j, tok, &s, &n) == 0 && n == 4 && memcmp(s, "true", 4) == 0;
}

static inline void note(char *ignored, size_t cap, const char *what)
{
    if (strstr(ignored, what))
        return;
    size_t n = strlen(ignored);
    snprintf(ignored + n, cap - n, "%s%s", n ? ", " : "", what);
}

/* Whether extras.gibench at token g still describes the file (gltf_scene.c): its "core", what the
 * exporter wrote as the file's own values, equals have[0..n-1]; extras without one count as
 * current. */
int gib_gltf_extras_current(const gfile *f, int g, const double *have, int n);

/* The cameras and lights of the nodes' trees, as `want` asks (gltf_nodes.c). */
int gib_gltf_read_nodes(const gfile *f, unsigned want, gib_gltf_info *out, gib_error *err);

#endif

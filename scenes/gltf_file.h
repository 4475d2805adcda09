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

/* Reads and checks (gib_gltf_bounds) the file, splits a GLB and parses the JSON. */
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
    if (gib_gltf_bounds(f->data, f->len, path, f->glb, err) ||
        (f->glb && gib_glb_split(f->data, f->len, path, &json, &jlen, &f->bin, &f->bin_len, err)))
        return gfile_close(f), -1;
    int rc = gib_json_parse(json, jlen, &f->j);
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

static inline void note(char *ignored, size_t cap, const char *what)
{
    if (strstr(ignored, what))
        return;
    size_t n = strlen(ignored);
    snprintf(ignored + n, cap - n, "%s%s", n ? ", " : "", what);
}

/* The cameras and lights of the nodes' trees, as `want` asks (gltf_nodes.c). */
int gib_gltf_read_nodes(const gfile *f, unsigned want, gib_gltf_info *out, gib_error *err);

#endif

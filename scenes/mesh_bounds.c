/* gibench — the mesh formats gibench reads, and what a file declares held to what its bytes hold.
 *
 * gibench reads OBJ, PLY, OFF, STL, glTF 2.0 and GLB (and .ply.gz, .off.gz, .stl.gz, .glb.gz),
 * nothing else assimp reads: each format here is documented (scenes/FORMAT.md) and tested
 * (tests/scenes/test_mesh_bounds.c). Before assimp sees a file, the counts it declares are held
 * to its size, so that reading it costs memory and time proportional to the file, whatever it
 * says (assimp allocates what the header declares: a 309-byte OFF declaring 3.5e9 vertices took
 * 97 s and 15.9 GB before assimp refused it). A declaration the bytes cannot hold is an error
 * naming the file, what it declared and its size. Per format:
 *  - OFF (Geomview, "OFF files", and assimp 5.2's OFFLoader): `[ST][C][N][4][n]OFF`, for nOFF a
 *    dimension, then the vertex, face and edge counts; each vertex is a line of at least its
 *    dimension's numbers (2 bytes each: a digit and a separator), each face a line of at least
 *    2 bytes.
 *  - STL (3D Systems, "StereoLithography Interface Specification", 1989): binary is an 80-byte
 *    header, a uint32 triangle count n, and n 50-byte records: exactly 84 + 50 n bytes. ASCII
 *    (`solid`) declares no count.
 *  - PLY: gib_ply_check (ply_check.c) holds each element count to the body's bytes.
 *  - OBJ: declares no counts; gib_obj_check (obj_check.c) reads it line by line.
 *  - glTF / GLB: gib_gltf_bounds (gltf_bounds.c). */
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "scene_internal.h"

static const char *const formats[] = {"obj", "ply", "off", "stl", "gltf", "glb", NULL};
/* gzipped: only self-contained formats (an OBJ's MTL, a glTF's .bin sit beside the file). */
static const char *const gz_formats[] = {"ply", "off", "stl", "glb", NULL};

const char *gib_mesh_formats_text(void)
{
    return ".obj, .ply, .off, .stl, .gltf, .glb (and gzipped .ply.gz, .off.gz, .stl.gz, .glb.gz)";
}

static int in_list(const char *const *list, const char *ext)
{
    for (int i = 0; list[i]; i++)
        if (strcasecmp(list[i], ext) == 0)
            return 1;
    return 0;
}

/* The extension before position end of path (the text after the last '.' of the file name). */
static void ext_before(const char *path, size_t end, char *out, size_t cap)
{
    size_t dot = end;
    while (dot > 0 && path[dot - 1] != '.' && path[dot - 1] != '/')
        dot--;
    out[0] = '\0';
    if (dot > 0 && path[dot - 1] == '.' && end - dot < cap) {
        memcpy(out, path + dot, end - dot);
        out[end - dot] = '\0';
        for (char *c = out; *c; c++)
            *c = (char)(*c >= 'A' && *c <= 'Z' ? *c + 32 : *c);
    }
}

int gib_mesh_format(const char *path, char fmt[8], int *gz, gib_error *err)
{
    size_t n = strlen(path);
    char ext[8];
    ext_before(path, n, ext, sizeof ext);
    *gz = strcmp(ext, "gz") == 0;
    if (*gz)
        ext_before(path, n - 3, ext, sizeof ext);
    if (*gz ? in_list(gz_formats, ext) : in_list(formats, ext)) {
        snprintf(fmt, 8, "%s", ext);
        return 0;
    }
    if (*gz && in_list(formats, ext))
        return gib_fail(err, "mesh '%s': gzipped meshes must be self-contained; decompress .%s "
                             "files, whose companions (MTL, .bin) sit beside them", path, ext);
    return gib_fail(err, "mesh '%s': not a supported mesh format; gibench reads %s", path,
                    gib_mesh_formats_text());
}

/* ------------------------------------------------------------------ OFF */

/* The next whitespace-separated token of [*p, end): its start, its length in *n. */
static const char *token(const char **p, const char *end, size_t *n)
{
    const char *s = *p;
    while (s < end && (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n' || *s == '\f'))
        s++;
    const char *e = s;
    while (e < end && !(*e == ' ' || *e == '\t' || *e == '\r' || *e == '\n' || *e == '\f'))
        e++;
    *p = e;
    *n = (size_t)(e - s);
    return s;
}

/* A token made of digits only, saturating at UINT64_MAX. */
static int count_value(const char *s, size_t n, uint64_t *v)
{
    *v = 0;
    if (n == 0)
        return 0;
    for (size_t i = 0; i < n; i++) {
        if (s[i] < '0' || s[i] > '9')
            return 0;
        unsigned d = (unsigned)(s[i] - '0');
        *v = *v > (UINT64_MAX - d) / 10 ? UINT64_MAX : *v * 10 + d;
    }
    return 1;
}

/* The OFF keyword with its optional prefixes ST, C, N, 4, n; sets *ndim for nOFF. 1 if it is. */
static int off_keyword(const char *s, size_t n, int *ndim)
{
    size_t i = 0;
    if (n - i >= 2 && s[i] == 'S' && s[i + 1] == 'T')
        i += 2;
    for (const char *flags = "CN4"; *flags; flags++)
        if (i < n && s[i] == *flags)
            i++;
    *ndim = i < n && s[i] == 'n';
    i += (size_t)*ndim;
    return n - i == 3 && memcmp(s + i, "OFF", 3) == 0;
}

static int off_bounds(const char *data, size_t len, const char *path, gib_error *err)
{
    const char *p = data, *end = data + len;
    size_t n;
    const char *t = token(&p, end, &n);
    int ndim = 0;
    uint64_t dims = 3, c[3];
    if (off_keyword(t, n, &ndim)) {
        t = token(&p, end, &n);
        if (ndim && (!count_value(t, n, &dims) || dims < 1 || dims > 3))
            return gib_fail(err, "mesh '%s': nOFF's dimension must be 1 to 3", path);
        if (ndim)
            t = token(&p, end, &n);
    }
    for (int i = 0; i < 3; i++, t = i < 3 ? token(&p, end, &n) : t)
        if (!count_value(t, n, &c[i]))
            return gib_fail(err, "mesh '%s': expected an OFF header and its vertex, face and edge "
                                 "counts (whole numbers)", path);
    /* Each vertex line holds dims numbers, each a digit and a separator; each face line 2 bytes
     * at least (its corner count and a line end). +1: the last line may lack its line end. */
    const uint64_t rest = (uint64_t)(end - p) + 1, vmin = 2 * dims;
    if (c[0] > rest / vmin)
        return gib_fail(err, "mesh '%s': declares %llu vertices, its %zu bytes hold at most %llu",
                        path, (unsigned long long)c[0], len, (unsigned long long)(rest / vmin));
    const uint64_t left = rest - c[0] * vmin;
    if (c[1] > left / 2)
        return gib_fail(err, "mesh '%s': declares %llu faces after %llu vertices, its %zu bytes "
                             "hold at most %llu", path, (unsigned long long)c[1],
                        (unsigned long long)c[0], len, (unsigned long long)(left / 2));
    return 0;
}

/* ------------------------------------------------------------------ STL */

static int stl_bounds(const char *data, size_t len, const char *path, gib_error *err)
{
    uint32_t n = 0;
    if (len >= 84) {
        const unsigned char *b = (const unsigned char *)data + 80;
        n = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
        if (84 + 50 * (uint64_t)n == len)
            return 0; /* binary, as assimp decides first */
    }
    const char *s = data, *end = data + len;
    while (s < end && (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n'))
        s++;
    if (end - s > 5 && memcmp(s, "solid", 5) == 0)
        return 0; /* ASCII: no declared count; assimp reads facet by facet */
    if (len < 84)
        return gib_fail(err, "mesh '%s': neither ASCII STL ('solid') nor binary STL (84 bytes "
                             "at least): %zu bytes", path, len);
    if (84 + 50 * (uint64_t)n > len)
        return gib_fail(err, "mesh '%s': declares %u triangles, its %zu bytes hold at most %zu",
                        path, n, len, (len - 84) / 50);
    return gib_fail(err, "mesh '%s': declares %u triangles (84 + 50 x %u = %llu bytes) but is "
                         "%zu bytes long", path, n, n, 84 + 50 * (unsigned long long)n, len);
}

/* ------------------------------------------------------------------ every format */

int gib_mesh_bounds(const char *data, size_t len, const char *path, const char *fmt,
                    gib_error *err)
{
    if (strcmp(fmt, "obj") == 0)
        return gib_obj_check(data, len, path, err);
    if (strcmp(fmt, "ply") == 0)
        return gib_ply_check(data, len, path, err);
    if (strcmp(fmt, "off") == 0)
        return off_bounds(data, len, path, err);
    if (strcmp(fmt, "stl") == 0)
        return stl_bounds(data, len, path, err);
    if (strcmp(fmt, "gltf") == 0 || strcmp(fmt, "glb") == 0)
        return gib_gltf_bounds(data, len, path, strcmp(fmt, "glb") == 0, err);
    return gib_fail(err, "mesh '%s': not a supported mesh format; gibench reads %s", path,
                    gib_mesh_formats_text());
}

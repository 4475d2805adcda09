/* gibench — a PLY file checked before assimp sees it.
 *
 * assimp 5.2's PLY reader loops forever on a header that never reaches `end_header`, aborts in
 * its triangulation on a garbled face list, and crashes in post-processing on garbled ASCII values
 * (all found by tests/fuzz/fuzz_mesh). So the whole file is checked here, as the PLY format
 * defines it (Turk 1994, "The PLY Polygon File Format"): the header (a first line `ply`,
 * `format ascii|binary_little_endian|binary_big_endian 1.0`, `comment`/`obj_info` lines,
 * `element NAME COUNT`, `property TYPE NAME` or `property list COUNT_TYPE ITEM_TYPE NAME` under an
 * element, `end_header`, within GIB_PLY_HEADER_MAX bytes), then the body: every element's values,
 * one element a line in ASCII, numbers of their types, list lengths up to GIB_PLY_LIST_MAX, face
 * indices within the vertices, and a binary body exactly as long as the header says. Anything else
 * is an error naming the file and the line (or byte offset). Before the body is read, every
 * element count is held to the bytes that can hold it (check_counts), so a header declaring
 * billions of vertices in a small file is refused at once, naming the count and the size. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

#define GIB_PLY_LIST_MAX 1024
#define MAX_ELEMENTS 16
#define MAX_PROPS 32

typedef struct ply_prop {
    int list;             /* 1: property list */
    int count_type, type; /* index into types[] */
    int index_list;       /* a face's vertex_indices / vertex_index */
} ply_prop;

typedef struct ply_element {
    char name[32];
    unsigned long count;
    ply_prop props[MAX_PROPS];
    int nprops;
} ply_element;

typedef struct ply_layout {
    int format; /* 0 ascii, 1 binary little endian, 2 binary big endian */
    ply_element el[MAX_ELEMENTS];
    int nel;
    unsigned long vertices;
    size_t body; /* offset of the body */
    int body_line;
} ply_layout;

static const char *const types[] = {"char", "uchar", "short", "ushort", "int", "uint", "float",
                                    "double", "int8", "uint8", "int16", "uint16", "int32",
                                    "uint32", "float32", "float64", NULL};
static const int type_size[] = {1, 1, 2, 2, 4, 4, 4, 8, 1, 1, 2, 2, 4, 4, 4, 8};
static const int type_float[] = {0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 1, 1};

static int type_of(const char *t)
{
    for (int i = 0; types[i]; i++)
        if (strcmp(t, types[i]) == 0)
            return i;
    return -1;
}

/* Splits a line (already NUL-terminated, no line end) into at most 6 words. */
static int words(char *line, char *w[6])
{
    int n = 0;
    for (char *tok = strtok(line, " \t"); tok && n < 6; tok = strtok(NULL, " \t"))
        w[n++] = tok;
    return strtok(NULL, " \t") ? 7 : n;
}

static int parse_header(const char *data, size_t len, const char *path, ply_layout *L,
                        gib_error *err)
{
    size_t limit = len < GIB_PLY_HEADER_MAX ? len : GIB_PLY_HEADER_MAX;
    int line_no = 0, have_format = 0;
    size_t pos = 0;
    memset(L, 0, sizeof *L);
    while (pos < limit) {
        size_t end = pos;
        while (end < limit && data[end] != '\n')
            end++;
        if (end == limit)
            break; /* no complete line left in the header's reach */
        line_no++;
        size_t n = end - pos;
        if (n > 0 && data[pos + n - 1] == '\r')
            n--;
        char line[256];
        if (n >= sizeof line)
            return gib_fail(err, "'%s' line %d: a PLY header line longer than %zu bytes", path,
                            line_no, sizeof line - 1);
        memcpy(line, data + pos, n);
        line[n] = '\0';
        if (memchr(line, '\0', n))
            return gib_fail(err, "'%s' line %d: a NUL byte in the PLY header", path, line_no);
        pos = end + 1;
        char *w[6];
        int nw = words(line, w);
        if (line_no == 1) {
            if (nw != 1 || strcmp(w[0], "ply"))
                return gib_fail(err, "'%s' line 1: not a PLY file (its first line must be 'ply')",
                                path);
            continue;
        }
        if (nw == 0)
            return gib_fail(err, "'%s' line %d: an empty line in the PLY header", path, line_no);
        if (!strcmp(w[0], "comment") || !strcmp(w[0], "obj_info"))
            continue;
        if (!strcmp(w[0], "end_header")) {
            if (nw != 1 || !have_format)
                return gib_fail(err, "'%s' line %d: end_header %s", path, line_no,
                                nw != 1 ? "followed by more words" : "before any format line");
            L->body = pos;
            L->body_line = line_no + 1;
            return 0;
        }
        if (!strcmp(w[0], "format")) {
            int f = nw != 3 ? -1 : !strcmp(w[1], "ascii") ? 0
                                : !strcmp(w[1], "binary_little_endian") ? 1
                                : !strcmp(w[1], "binary_big_endian") ? 2 : -1;
            if (f < 0 || strcmp(w[2], "1.0") || have_format)
                return gib_fail(err, "'%s' line %d: expected one 'format ascii|binary_little_endian|"
                                     "binary_big_endian 1.0' line", path, line_no);
            L->format = f;
            have_format = 1;
            continue;
        }
        if (!strcmp(w[0], "element")) {
            char *e = NULL;
            if (nw != 3 || !w[2][0] || w[2][0] == '-' || strtoul(w[2], &e, 10) > 0x7fffffffUL || *e)
                return gib_fail(err, "'%s' line %d: expected 'element NAME COUNT' with a count "
                                     "below 2^31", path, line_no);
            if (L->nel == MAX_ELEMENTS)
                return gib_fail(err, "'%s' line %d: more than %d elements", path, line_no,
                                MAX_ELEMENTS);
            ply_element *el = &L->el[L->nel++];
            snprintf(el->name, sizeof el->name, "%s", w[1]);
            el->count = strtoul(w[2], NULL, 10);
            if (!strcmp(w[1], "vertex"))
                L->vertices = el->count;
            continue;
        }
        if (!strcmp(w[0], "property")) {
            ply_element *el = L->nel ? &L->el[L->nel - 1] : NULL;
            ply_prop p = {0};
            int ok = el && el->nprops < MAX_PROPS;
            if (ok && nw == 3 && (p.type = type_of(w[1])) >= 0) {
                p.list = 0;
            } else if (ok && nw == 5 && !strcmp(w[1], "list") && (p.count_type = type_of(w[2])) >= 0 &&
                       !type_float[p.count_type] && (p.type = type_of(w[3])) >= 0) {
                p.list = 1;
                p.index_list = !strcmp(el->name, "face") &&
                               (!strcmp(w[4], "vertex_indices") || !strcmp(w[4], "vertex_index"));
            } else {
                return gib_fail(err, "'%s' line %d: expected 'property TYPE NAME' or 'property list "
                                     "COUNT_TYPE TYPE NAME' (an integer count type) after an "
                                     "element line, at most %d a element", path, line_no, MAX_PROPS);
            }
            el->props[el->nprops++] = p;
            continue;
        }
        return gib_fail(err, "'%s' line %d: '%s' is not a PLY header keyword", path, line_no, w[0]);
    }
    return gib_fail(err, "'%s': no end_header line in the first %zu bytes: not a complete PLY "
                         "header", path, limit);
}

/* One ASCII value of type t: the whole token a number of that kind. */
static int ascii_value(const char *tok, int t, double *v)
{
    char *e = NULL;
    errno = 0;
    if (type_float[t]) {
        *v = strtod(tok, &e);
        return *e == '\0' && e != tok && isfinite(*v) && errno != ERANGE;
    }
    long long x = strtoll(tok, &e, 10);
    *v = (double)x;
    return *e == '\0' && e != tok && errno != ERANGE;
}

static int check_ascii(const char *data, size_t len, const char *path, const ply_layout *L,
                       gib_error *err)
{
    size_t pos = L->body;
    int line_no = L->body_line - 1;
    char line[4096];
    for (int e = 0; e < L->nel; e++) {
        const ply_element *el = &L->el[e];
        for (unsigned long i = 0; i < el->count; i++) {
            line_no++;
            if (pos >= len)
                return gib_fail(err, "'%s' line %d: the file ends before %s %lu of %lu", path,
                                line_no, el->name, i, el->count);
            size_t end = pos;
            while (end < len && data[end] != '\n')
                end++;
            size_t n = end - pos;
            if (n >= sizeof line || memchr(data + pos, '\0', n))
                return gib_fail(err, "'%s' line %d: %s", path, line_no,
                                n >= sizeof line ? "a line too long for a PLY element"
                                                 : "a NUL byte in an ASCII PLY body");
            memcpy(line, data + pos, n);
            line[n] = '\0';
            pos = end + 1;
            char *save = NULL, *tok = strtok_r(line, " \t\r", &save);
            for (int p = 0; p < el->nprops; p++) {
                const ply_prop *pr = &el->props[p];
                double v;
                long items = 1;
                if (pr->list) {
                    if (!tok || !ascii_value(tok, pr->count_type, &v) || v < 0 || v > GIB_PLY_LIST_MAX)
                        return gib_fail(err, "'%s' line %d: %s %lu: a list length from 0 to %d "
                                             "expected", path, line_no, el->name, i, GIB_PLY_LIST_MAX);
                    items = (long)v;
                    tok = strtok_r(NULL, " \t\r", &save);
                }
                for (long k = 0; k < items; k++) {
                    if (!tok || !ascii_value(tok, pr->type, &v))
                        return gib_fail(err, "'%s' line %d: %s %lu: %s where a %s value belongs",
                                        path, line_no, el->name, i, tok ? "a bad value" : "nothing",
                                        types[pr->type]);
                    if (pr->index_list && (v < 0 || v >= (double)L->vertices))
                        return gib_fail(err, "'%s' line %d: face %lu refers to vertex %.0f of %lu",
                                        path, line_no, i, v, L->vertices);
                    tok = strtok_r(NULL, " \t\r", &save);
                }
            }
            if (tok)
                return gib_fail(err, "'%s' line %d: %s %lu has more values than its %d properties",
                                path, line_no, el->name, i, el->nprops);
        }
    }
    return 0;
}

static double binary_value(const unsigned char *p, int t, int big)
{
    unsigned char b[8];
    int n = type_size[t];
    for (int i = 0; i < n; i++)
        b[i] = big ? p[n - 1 - i] : p[i];
    switch (t % 8) {
    case 0: { int8_t v; memcpy(&v, b, 1); return v; }
    case 1: { uint8_t v; memcpy(&v, b, 1); return v; }
    case 2: { int16_t v; memcpy(&v, b, 2); return v; }
    case 3: { uint16_t v; memcpy(&v, b, 2); return v; }
    case 4: { int32_t v; memcpy(&v, b, 4); return v; }
    case 5: { uint32_t v; memcpy(&v, b, 4); return v; }
    case 6: { float v; memcpy(&v, b, 4); return v; }
    default: { double v; memcpy(&v, b, 8); return v; }
    }
}

static int check_binary(const char *data, size_t len, const char *path, const ply_layout *L,
                        gib_error *err)
{
    const unsigned char *d = (const unsigned char *)data;
    size_t pos = L->body;
    int big = L->format == 2;
    for (int e = 0; e < L->nel; e++) {
        const ply_element *el = &L->el[e];
        for (unsigned long i = 0; i < el->count; i++)
            for (int p = 0; p < el->nprops; p++) {
                const ply_prop *pr = &el->props[p];
                double items = 1;
                if (pr->list) {
                    if (len - pos < (size_t)type_size[pr->count_type] ||
                        !((items = binary_value(d + pos, pr->count_type, big)) >= 0) ||
                        items > GIB_PLY_LIST_MAX)
                        return gib_fail(err, "'%s' byte %zu: %s %lu: %s", path, pos, el->name, i,
                                        len - pos < (size_t)type_size[pr->count_type]
                                            ? "the file ends inside the body"
                                            : "a list length outside 0 to 1024");
                    pos += (size_t)type_size[pr->count_type];
                }
                for (long k = 0; k < (long)items; k++) {
                    if (len - pos < (size_t)type_size[pr->type])
                        return gib_fail(err, "'%s' byte %zu: the file ends inside %s %lu of %lu",
                                        path, pos, el->name, i, el->count);
                    double v = binary_value(d + pos, pr->type, big);
                    if (pr->index_list && !(v >= 0 && v < (double)L->vertices))
                        return gib_fail(err, "'%s' byte %zu: face %lu refers to vertex %.0f of %lu",
                                        path, pos, i, v, L->vertices);
                    if (type_float[pr->type] && !isfinite(v))
                        return gib_fail(err, "'%s' byte %zu: %s %lu: a NaN or infinite value",
                                        path, pos, el->name, i);
                    pos += (size_t)type_size[pr->type];
                }
            }
    }
    return 0;
}

/* The fewest bytes one instance of el takes: in ASCII a token (a digit and a separator) per
 * property, a list's being its length; in binary each property's size, a list's its count's. An
 * instance of no property still takes a byte (an ASCII line end), so no count is free. */
static size_t min_instance_bytes(const ply_element *el, int format)
{
    size_t n = 0;
    for (int p = 0; p < el->nprops; p++)
        n += format == 0 ? 2
                         : (size_t)type_size[el->props[p].list ? el->props[p].count_type
                                                               : el->props[p].type];
    return n ? n : 1;
}

/* Every element count held to the body's bytes before the body is read (scenes/FORMAT.md,
 * "Declared counts"), so that a header declaring billions of elements is refused at once. */
static int check_counts(size_t len, const char *path, const ply_layout *L, gib_error *err)
{
    size_t avail = len - L->body + (L->format == 0); /* the last ASCII line may lack its end */
    for (int e = 0; e < L->nel; e++) {
        const ply_element *el = &L->el[e];
        size_t min = min_instance_bytes(el, L->format);
        if (el->count > avail / min)
            return gib_fail(err, "mesh '%s': declares %lu '%s' elements, its %zu bytes hold at "
                                 "most %zu", path, el->count, el->name, len, avail / min);
        avail -= el->count * min;
    }
    return 0;
}

int gib_ply_check(const char *data, size_t len, const char *path, gib_error *err)
{
    ply_layout L;
    if (parse_header(data, len, path, &L, err) < 0 || check_counts(len, path, &L, err) < 0)
        return -1;
    return L.format == 0 ? check_ascii(data, len, path, &L, err)
                         : check_binary(data, len, path, &L, err);
}

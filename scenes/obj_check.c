/* gibench — an OBJ file's element statements checked before assimp sees them.
 *
 * assimp 5.2's OBJ parser reads past the end of its buffer when the file's last line is a face
 * with a token it reports as an error (a fourth index, as in `f 1///1`): it skips the line, then
 * steps on past the end (found by tests/fuzz/fuzz_mesh, ASan heap-buffer-overflow in strtol). So
 * every element statement (`f`, `l`, `p`) is checked here against the OBJ format (Wavefront,
 * "Object Files (.obj)", Appendix B1 of the Advanced Visualizer manual): each vertex reference is
 * `v`, `v/vt`, `v//vn` or `v/vt/vn`, integers that are not 0, a positive one at most the file's
 * count of that kind, a negative one at most the count defined before it (relative indices).
 * Lines end where assimp ends them ('\n', '\r', '\f'), and those ending in a backslash continue
 * on the next; a NUL byte is refused (assimp's parser read past its buffer on one: fuzz_mesh).
 * A statement is an element statement when its first letter is f, l or p, as assimp dispatches
 * on that letter alone (`f`2/ 1//1 1///1`, found by fuzz_mesh, was a face to assimp and none to
 * this check). Other statements are assimp's to read. An error names the file and the line. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

enum { KIND_V, KIND_VT, KIND_VN, NKINDS };

/* The next logical line of [*p, end), split where assimp splits lines (IsLineEnd: '\n', '\r',
 * '\f'; a NUL is refused before) and joined where one ends in '\'. Its text is copied into line
 * (cap bytes, truncated: element statements beyond that are refused below), and *lines counts
 * the lines read ("\r\n", a lone '\r' and '\n' one each). Returns 0 at the end of the data. */
static int next_line(const char **p, const char *end, char *line, size_t cap, size_t *len,
                     int *lines)
{
    if (*p >= end)
        return 0;
    size_t n = 0;
    int truncated = 0;
    for (;;) {
        const char *q = *p;
        while (q < end && *q != '\n' && *q != '\r' && *q != '\f')
            q++;
        size_t k = (size_t)(q - *p);
        int cont = k && (*p)[k - 1] == '\\';
        if (cont)
            k--;
        if (n + k >= cap) {
            k = n < cap - 1 ? cap - 1 - n : 0;
            truncated = 1;
        }
        memcpy(line + n, *p, k);
        n += k;
        if (q < end) {
            *lines += *q != '\f';
            q += *q == '\r' && q + 1 < end && q[1] == '\n' ? 2 : 1;
        } else {
            (*lines)++;
        }
        *p = q;
        if (!cont || *p >= end)
            break;
        if (n < cap - 1)
            line[n++] = ' ';
    }
    line[n] = 0;
    *len = truncated ? cap : n;
    return 1;
}

/* The statement's keyword, or -1 for a line that is blank or a comment. */
static int keyword(const char *s, char *kw, size_t cap)
{
    while (*s == ' ' || *s == '\t')
        s++;
    size_t n = 0;
    while (s[n] && s[n] != ' ' && s[n] != '\t' && n + 1 < cap) {
        kw[n] = s[n];
        n++;
    }
    kw[n] = 0;
    return n && kw[0] != '#' ? (int)n : -1;
}

/* One index of a reference: an optionally signed integer, not 0. Returns the characters read, 0
 * when there is no integer there, -1 for an index out of range. */
static int index_ok(const char *s, long count_all, long count_before)
{
    char *e;
    long v = strtol(s, &e, 10);
    if (e == s || !(isdigit((unsigned char)*s) || *s == '-' || *s == '+'))
        return 0;
    if (v == 0 || (v > 0 && v > count_all) || (v < 0 && -v > count_before))
        return -1;
    return (int)(e - s);
}

/* gib_obj_check with a line buffer of cap bytes. */
static int check_lines(const char *data, size_t len, const char *path, char *line, size_t cap,
                       gib_error *err)
{
    long total[NKINDS] = {0}, before[NKINDS] = {0};
    const char *const kinds[NKINDS] = {"v", "vt", "vn"};
    char kw[16];
    size_t n;
    int lines = 0;
    const char *nul = memchr(data, 0, len);
    if (nul) { /* OBJ is text; assimp reads on past a NUL as if it were a line end */
        int at = 1;
        for (const char *c = data; c < nul; c++)
            at += *c == '\n';
        return gib_fail(err, "'%s':%d: a NUL byte: not a text OBJ file", path, at);
    }
    /* First the counts of the whole file: assimp resolves positive indices after reading it. */
    for (const char *p = data, *end = data + len; next_line(&p, end, line, cap, &n, &lines);)
        if (keyword(line, kw, sizeof kw) > 0)
            for (int k = 0; k < NKINDS; k++)
                total[k] += !strcmp(kw, kinds[k]);
    lines = 0;
    for (const char *p = data, *end = data + len; next_line(&p, end, line, cap, &n, &lines);) {
        int at = lines;
        if (keyword(line, kw, sizeof kw) < 0)
            continue;
        for (int k = 0; k < NKINDS; k++)
            before[k] += !strcmp(kw, kinds[k]);
        if (kw[0] != 'f' && kw[0] != 'l' && kw[0] != 'p')
            continue; /* assimp reads a line by its first letter: `f`2/` is a face (fuzz_mesh) */
        if (n >= cap)
            return gib_fail(err, "'%s':%d: an element statement over %zu bytes", path, at,
                            cap - 1);
        const char *s = strstr(line, kw) + strlen(kw);
        int refs = 0;
        for (;;) {
            while (*s == ' ' || *s == '\t')
                s++;
            if (!*s)
                break;
            const char *tok = s;
            int part = 0, bad = 0;
            for (; part < NKINDS && !bad; part++) {
                int r = index_ok(s, total[part], before[part]);
                if (r < 0)
                    return gib_fail(err, "'%s':%d: '%s' refers to a %s that is not in the file "
                                         "(%ld; the file declares %ld)", path, at, kw, kinds[part],
                                    strtol(s, NULL, 10), total[part]);
                if (r == 0 && !(part == KIND_VT && *s == '/'))
                    bad = 1; /* only the texture index may be empty (v//vn) */
                s += r;
                if (*s != '/')
                    break;
                s++;
                if (part == KIND_VN)
                    bad = 1; /* a fourth index */
            }
            if (bad || (*s && *s != ' ' && *s != '\t')) {
                const char *e = tok;
                while (*e && *e != ' ' && *e != '\t')
                    e++;
                return gib_fail(err, "'%s':%d: '%.*s' in '%s' is not v, v/vt, v//vn or v/vt/vn "
                                     "(non-zero integers)", path, at, (int)(e - tok > 40 ? 40 : e - tok),
                                tok, kw);
            }
            refs++;
        }
        if (!refs)
            return gib_fail(err, "'%s':%d: '%s' with no vertex", path, at, kw);
    }
    return 0;
}

int gib_obj_check(const char *data, size_t len, const char *path, gib_error *err)
{
    const size_t cap = 1 << 16; /* a logical line; longer element statements are refused */
    char *line = malloc(cap);
    if (!line)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "'%s': out of memory checking it", path);
    int rc = check_lines(data, len, path, line, cap, err);
    free(line);
    return rc;
}

/* gibench — a PLY header checked before assimp sees it.
 *
 * assimp 5.2's PLY reader loops forever on a header that never reaches `end_header` (found by
 * tests/fuzz/fuzz_mesh: its line reader retries the end of the file), and reads past a malformed
 * one. So the header is checked here, as the PLY format defines it (Turk 1994, "The PLY Polygon
 * File Format"): a first line `ply`, then `format ascii|binary_little_endian|binary_big_endian 1.0`,
 * `comment`/`obj_info` lines, `element NAME COUNT` with a decimal count, `property TYPE NAME` or
 * `property list COUNT_TYPE ITEM_TYPE NAME` under an element, and `end_header`, all within the
 * first GIB_PLY_HEADER_MAX bytes. Anything else is an error naming the file and the line. */
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

static int is_type(const char *t)
{
    static const char *const types[] = {"char", "uchar", "short", "ushort", "int", "uint", "float",
                                        "double", "int8", "uint8", "int16", "uint16", "int32",
                                        "uint32", "float32", "float64", NULL};
    for (int i = 0; types[i]; i++)
        if (strcmp(t, types[i]) == 0)
            return 1;
    return 0;
}

/* Splits a line (already NUL-terminated, no line end) into at most 6 words. */
static int words(char *line, char *w[6])
{
    int n = 0;
    for (char *tok = strtok(line, " \t"); tok && n < 6; tok = strtok(NULL, " \t"))
        w[n++] = tok;
    return strtok(NULL, " \t") ? 7 : n;
}

int gib_ply_check_header(const char *data, size_t len, const char *path, gib_error *err)
{
    size_t limit = len < GIB_PLY_HEADER_MAX ? len : GIB_PLY_HEADER_MAX;
    int line_no = 0, have_format = 0, have_element = 0;
    size_t pos = 0;
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
            return 0;
        }
        if (!strcmp(w[0], "format")) {
            int known = nw == 3 && (!strcmp(w[1], "ascii") || !strcmp(w[1], "binary_little_endian") ||
                                    !strcmp(w[1], "binary_big_endian"));
            if (!known || strcmp(w[2], "1.0") || have_format)
                return gib_fail(err, "'%s' line %d: expected one 'format ascii|binary_little_endian|"
                                     "binary_big_endian 1.0' line", path, line_no);
            have_format = 1;
            continue;
        }
        if (!strcmp(w[0], "element")) {
            char *e = NULL;
            if (nw != 3 || !w[2][0] || strtoul(w[2], &e, 10) > 0x7fffffffUL || *e || w[2][0] == '-')
                return gib_fail(err, "'%s' line %d: expected 'element NAME COUNT' with a count "
                                     "below 2^31", path, line_no);
            have_element = 1;
            continue;
        }
        if (!strcmp(w[0], "property")) {
            int ok = have_element && ((nw == 3 && is_type(w[1])) ||
                                      (nw == 5 && !strcmp(w[1], "list") && is_type(w[2]) &&
                                       is_type(w[3])));
            if (!ok)
                return gib_fail(err, "'%s' line %d: expected 'property TYPE NAME' or 'property list "
                                     "COUNT_TYPE TYPE NAME' after an element line", path, line_no);
            continue;
        }
        return gib_fail(err, "'%s' line %d: '%s' is not a PLY header keyword", path, line_no, w[0]);
    }
    return gib_fail(err, "'%s': no end_header line in the first %zu bytes: not a complete PLY "
                         "header", path, limit);
}

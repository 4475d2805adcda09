/* gibench — a glTF 2.0 or GLB file's declarations held to its bytes before assimp reads it.
 *
 * As the glTF 2.0 specification defines them (Khronos, "glTF 2.0 Specification", sections 3.6
 * "Binary Data Storage" and 4.4 "GLB File Format"): a GLB is a 12-byte header (magic "glTF",
 * version 2, total length) then chunks of (length, type, data): the JSON chunk first, an optional
 * BIN chunk. The JSON's `buffers` have a byteLength held by their source: the GLB's BIN chunk
 * (a buffer without uri), a base64 data: URI, or a file beside the glTF; `bufferViews` lie within
 * their buffer (byteOffset + byteLength); `accessors` read count elements of type x componentType
 * bytes, byteStride apart, within their bufferView (an accessor without one, all zeros, within
 * the size of the input); sparse ones too. assimp 5.2 allocates what these declare before
 * checking them (a sparse accessor's count, a primitive's attributes), so each is checked here.
 * Then what assimp builds from them: every mesh's primitives' accessors, once per mesh and once
 * per instance in the scenes' node trees (PreTransformVertices copies each instance), may total
 * at most GLTF_EXPANSION times the input's bytes plus GLTF_EXPANSION_FLOOR; nodes form trees
 * (one parent each, no cycle). Only glTF 2.x is read (asset.version). An error names the file,
 * what it declared and the bytes that hold it. The JSON is tokenized once (depth at most
 * GLTF_DEPTH), in time and memory proportional to its size. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "scene_internal.h"

#define GLTF_DEPTH 64
#define GLTF_EXPANSION 64u
#define GLTF_EXPANSION_FLOOR (64ull << 20)

/* ------------------------------------------------------------------ JSON tokens */

enum { J_OBJ, J_ARR, J_STR, J_PRIM };

typedef struct jtok {
    int type;
    size_t start, end;   /* a string's text without its quotes */
    uint32_t next;       /* the token after this one's subtree */
} jtok;

typedef struct jdoc {
    const char *s;
    jtok *t;
    uint32_t n, cap;
} jdoc;

static int jpush(jdoc *d, int type, size_t start)
{
    if (d->n == d->cap) {
        uint32_t cap = d->cap ? d->cap * 2 : 256;
        jtok *t = realloc(d->t, cap * sizeof *t);
        if (!t)
            return -1;
        d->t = t;
        d->cap = cap;
    }
    d->t[d->n] = (jtok){type, start, start, d->n + 1};
    return (int)d->n++;
}

/* A string's end (the closing quote) from just after its opening one, or 0. */
static size_t jstring_end(const char *s, size_t i, size_t len)
{
    for (; i < len; i++) {
        if (s[i] == '"')
            return i;
        if (s[i] == '\\')
            i++;
        else if ((unsigned char)s[i] < 0x20)
            return 0;
    }
    return 0;
}

static size_t jprim_end(const char *s, size_t i, size_t len)
{
    while (i < len && (s[i] == '-' || s[i] == '+' || s[i] == '.' || (s[i] >= '0' && s[i] <= '9') ||
                       (s[i] >= 'a' && s[i] <= 'z') || (s[i] >= 'A' && s[i] <= 'Z')))
        i++;
    return i;
}

/* Tokenizes s as JSON: one value, containers nested at most GLTF_DEPTH deep. 0 or -1 (bad JSON,
 * *at its byte), -2 (out of memory). State `want`: 0 a value, 1 a key or '}', 2 ':', 3 ',' or a
 * close. */
static int jparse(jdoc *d, size_t len, size_t *at)
{
    const char *s = d->s;
    int stack[GLTF_DEPTH], depth = 0, want = 0, done = 0;
    size_t i = 0;
    for (; i < len; i++) {
        char c = s[i];
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n')
            continue;
        if (done)
            break;
        int top = depth ? d->t[stack[depth - 1]].type : -1;
        if (want == 2) {
            if (c != ':')
                break;
            want = 0;
        } else if (want == 3 || (want == 1 && c == '}') || (want == 0 && c == ']' && top == J_ARR &&
                                                              d->t[stack[depth - 1]].next == d->n)) {
            if (c == ',' && want == 3) {
                want = top == J_OBJ ? 1 : 0;
                continue;
            }
            if ((c == '}' && top != J_OBJ) || (c == ']' && top != J_ARR) || (c != '}' && c != ']'))
                break;
            jtok *t = &d->t[stack[--depth]];
            t->end = i + 1;
            t->next = d->n;
            want = 3;
            done = depth == 0;
        } else if (c == '"') {
            size_t e = jstring_end(s, i + 1, len);
            int k = e ? jpush(d, J_STR, i + 1) : -1;
            if (!e)
                break;
            if (k < 0)
                return -2;
            d->t[k].end = e;
            i = e;
            want = want == 1 ? 2 : 3;
            done = depth == 0;
        } else if (want == 1) {
            break;
        } else if (c == '{' || c == '[') {
            int k = jpush(d, c == '{' ? J_OBJ : J_ARR, i);
            if (k < 0)
                return -2;
            if (depth == GLTF_DEPTH)
                break;
            stack[depth++] = k;
            want = c == '{' ? 1 : 0;
        } else {
            size_t e = jprim_end(s, i, len);
            if (e == i)
                break;
            int k = jpush(d, J_PRIM, i);
            if (k < 0)
                return -2;
            d->t[k].end = e;
            i = e - 1;
            want = 3;
            done = depth == 0;
        }
    }
    while (i < len && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r' || s[i] == '\n'))
        i++;
    *at = i;
    return done && i == len ? 0 : -1;
}

/* The value of member `key` of object o, or -1. */
static int jget(const jdoc *d, int o, const char *key)
{
    if (o < 0 || d->t[o].type != J_OBJ)
        return -1;
    size_t kl = strlen(key);
    for (uint32_t k = (uint32_t)o + 1; k < d->t[o].next; k = d->t[k + 1].next) {
        const jtok *t = &d->t[k];
        if (t->end - t->start == kl && memcmp(d->s + t->start, key, kl) == 0)
            return (int)k + 1;
    }
    return -1;
}

/* The elements of array a (token indices, malloc'd) and their count; *n = 0 when a is absent. */
static int jitems(const jdoc *d, int a, uint32_t **out, uint32_t *n)
{
    *out = NULL;
    *n = 0;
    if (a < 0 || d->t[a].type != J_ARR)
        return 0;
    for (uint32_t k = (uint32_t)a + 1; k < d->t[a].next; k = d->t[k].next)
        (*n)++;
    *out = malloc((*n + 1) * sizeof **out);
    if (!*out)
        return -1;
    uint32_t i = 0;
    for (uint32_t k = (uint32_t)a + 1; k < d->t[a].next; k = d->t[k].next)
        (*out)[i++] = k;
    return 0;
}

/* Token v as a whole number from 0 to 2^53; dflt when v < 0 (absent). 0 or -1. */
static int juint(const jdoc *d, int v, uint64_t dflt, uint64_t *out)
{
    *out = dflt;
    if (v < 0)
        return 0;
    const jtok *t = &d->t[v];
    char buf[40];
    size_t n = t->end - t->start;
    if (t->type != J_PRIM || n == 0 || n >= sizeof buf)
        return -1;
    memcpy(buf, d->s + t->start, n);
    buf[n] = '\0';
    char *e;
    double x = strtod(buf, &e);
    if (*e || !(x >= 0 && x <= 9007199254740992.0) || x != floor(x))
        return -1;
    *out = (uint64_t)x;
    return 0;
}

static int jstreq(const jdoc *d, int v, const char *s)
{
    return v >= 0 && d->t[v].type == J_STR && d->t[v].end - d->t[v].start == strlen(s) &&
           memcmp(d->s + d->t[v].start, s, strlen(s)) == 0;
}

/* ------------------------------------------------------------------ the glTF's arrays */

typedef struct gltf {
    const char *path, *bin; /* bin: the GLB's BIN chunk, or NULL */
    uint64_t bin_len, input; /* input: the bytes read (file and buffers), the expansion's base */
    jdoc d;
    uint32_t *buf, *view, *acc, *mesh, *node, *scene, *skin, *anim;
    uint32_t nbuf, nview, nacc, nmesh, nnode, nscene, nskin, nanim;
    uint64_t *buf_len, *view_len, *acc_bytes, *mesh_bytes;
} gltf;

static int bad(gltf *g, gib_error *err, const char *what, uint32_t i, const char *key)
{
    return gib_fail(err, "mesh '%s': %s %u: '%s' missing or not a valid index or size", g->path,
                    what, i, key);
}

/* The decoded size of a base64 data: URI's payload. */
static uint64_t data_uri_bytes(const char *s, size_t n)
{
    const char *b = NULL;
    for (size_t i = 0; i + 8 <= n && !b; i++)
        b = memcmp(s + i, ";base64,", 8) == 0 ? s + i : NULL;
    if (!b)
        return 0;
    size_t k = n - (size_t)(b + 8 - s);
    uint64_t bytes = k / 4 * 3;
    for (size_t i = 0; i < 2 && i < k && s[n - 1 - i] == '='; i++)
        bytes--;
    return bytes;
}

/* The bytes that hold buffer i: the BIN chunk, a data: URI, or the file beside the glTF. */
static int buffer_source(gltf *g, uint32_t i, char *what, size_t cap, uint64_t *have, gib_error *err)
{
    int u = jget(&g->d, (int)g->buf[i], "uri");
    if (u < 0) {
        snprintf(what, cap, "%s", g->bin ? "BIN chunk" : "missing BIN chunk");
        *have = i == 0 && g->bin ? g->bin_len : 0;
        return 0;
    }
    const jtok *t = &g->d.t[u];
    const char *s = g->d.s + t->start;
    size_t n = t->end - t->start;
    if (t->type != J_STR)
        return bad(g, err, "buffer", i, "uri");
    if (n >= 5 && memcmp(s, "data:", 5) == 0) {
        snprintf(what, cap, "data: URI");
        *have = data_uri_bytes(s, n);
        return 0;
    }
    char rel[GIB_PATH_MAX], dir[GIB_PATH_MAX], joined[GIB_PATH_MAX], found[GIB_PATH_MAX];
    struct stat st;
    snprintf(rel, sizeof rel, "%.*s", (int)(n < sizeof rel ? n : sizeof rel - 1), s);
    gib_path_dirname(g->path, dir, sizeof dir);
    snprintf(what, cap, "file '%s'", rel);
    *have = 0;
    if (gib_path_join(dir, rel, joined, sizeof joined) == 0 &&
        gib_path_resolve_ci(joined, found, sizeof found) == 0 && stat(found, &st) == 0 &&
        S_ISREG(st.st_mode))
        *have = (uint64_t)st.st_size;
    return 0;
}

static int check_buffers(gltf *g, gib_error *err)
{
    g->buf_len = calloc(g->nbuf + 1, sizeof *g->buf_len);
    if (!g->buf_len)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory", g->path);
    for (uint32_t i = 0; i < g->nbuf; i++) {
        char what[GIB_PATH_MAX + 16];
        uint64_t have = 0;
        if (juint(&g->d, jget(&g->d, (int)g->buf[i], "byteLength"), UINT64_MAX, &g->buf_len[i]) ||
            g->buf_len[i] == UINT64_MAX)
            return bad(g, err, "buffer", i, "byteLength");
        if (buffer_source(g, i, what, sizeof what, &have, err))
            return -1;
        if (g->buf_len[i] > have)
            return gib_fail(err, "mesh '%s': buffer %u declares %llu bytes, its %s holds %llu",
                            g->path, i, (unsigned long long)g->buf_len[i], what,
                            (unsigned long long)have);
        g->input += strncmp(what, "file", 4) == 0 ? g->buf_len[i] : 0;
    }
    return 0;
}

static int check_views(gltf *g, gib_error *err)
{
    g->view_len = calloc(g->nview + 1, sizeof *g->view_len);
    if (!g->view_len)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory", g->path);
    for (uint32_t i = 0; i < g->nview; i++) {
        int v = (int)g->view[i];
        uint64_t b, off, stride;
        if (juint(&g->d, jget(&g->d, v, "buffer"), UINT64_MAX, &b) || b >= g->nbuf)
            return bad(g, err, "bufferView", i, "buffer");
        if (juint(&g->d, jget(&g->d, v, "byteLength"), UINT64_MAX, &g->view_len[i]) ||
            g->view_len[i] == UINT64_MAX || juint(&g->d, jget(&g->d, v, "byteOffset"), 0, &off) ||
            juint(&g->d, jget(&g->d, v, "byteStride"), 4, &stride) || stride < 4 || stride > 252)
            return bad(g, err, "bufferView", i, "byteLength, byteOffset or byteStride");
        if (off > g->buf_len[b] || g->view_len[i] > g->buf_len[b] - off)
            return gib_fail(err, "mesh '%s': bufferView %u declares bytes %llu to %llu of buffer "
                                 "%llu, which holds %llu", g->path, i, (unsigned long long)off,
                            (unsigned long long)(off + g->view_len[i]), (unsigned long long)b,
                            (unsigned long long)g->buf_len[b]);
    }
    return 0;
}

/* An accessor's element size from its type and componentType; 0 when either is unknown. */
static uint64_t elem_size(const jdoc *d, int a, uint64_t ctype)
{
    static const char *const types[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
    static const int comps[] = {1, 2, 3, 4, 4, 9, 16};
    int k = -1;
    for (int i = 0; i < 7 && k < 0; i++)
        k = jstreq(d, jget(d, a, "type"), types[i]) ? i : -1;
    int cs = ctype == 5120 || ctype == 5121 ? 1 : ctype == 5122 || ctype == 5123 ? 2
           : ctype == 5125 || ctype == 5126 ? 4 : 0;
    return k < 0 ? 0 : (uint64_t)comps[k] * (uint64_t)cs;
}

/* count elements of esize bytes, stride apart from offset, within bufferView `view`. */
static int within_view(gltf *g, const char *what, uint32_t i, int viewtok, uint64_t offset,
                       uint64_t count, uint64_t esize, gib_error *err)
{
    uint64_t v, stride;
    if (juint(&g->d, viewtok, UINT64_MAX, &v) || v >= g->nview)
        return bad(g, err, what, i, "bufferView");
    juint(&g->d, jget(&g->d, (int)g->view[v], "byteStride"), esize, &stride);
    const uint64_t len = g->view_len[v];
    uint64_t most = len < offset || len - offset < esize ? 0 : (len - offset - esize) / stride + 1;
    if (count > most)
        return gib_fail(err, "mesh '%s': %s %u declares %llu elements of %llu bytes, its "
                             "bufferView %llu of %llu bytes holds at most %llu", g->path, what, i,
                        (unsigned long long)count, (unsigned long long)esize,
                        (unsigned long long)v, (unsigned long long)len, (unsigned long long)most);
    return 0;
}

static int check_sparse(gltf *g, uint32_t i, int sp, uint64_t count, uint64_t esize, gib_error *err)
{
    uint64_t n, off, ct;
    int idx = jget(&g->d, sp, "indices"), val = jget(&g->d, sp, "values");
    if (juint(&g->d, jget(&g->d, sp, "count"), UINT64_MAX, &n) || n > count || idx < 0 || val < 0 ||
        juint(&g->d, jget(&g->d, idx, "componentType"), 0, &ct) ||
        (ct != 5121 && ct != 5123 && ct != 5125))
        return bad(g, err, "sparse accessor", i, "count, indices or values");
    if (juint(&g->d, jget(&g->d, idx, "byteOffset"), 0, &off) ||
        within_view(g, "sparse indices of accessor", i, jget(&g->d, idx, "bufferView"), off, n,
                    ct == 5121 ? 1 : ct == 5123 ? 2 : 4, err))
        return -1;
    if (juint(&g->d, jget(&g->d, val, "byteOffset"), 0, &off) ||
        within_view(g, "sparse values of accessor", i, jget(&g->d, val, "bufferView"), off, n,
                    esize, err))
        return -1;
    return 0;
}

static int check_accessors(gltf *g, gib_error *err)
{
    g->acc_bytes = calloc(g->nacc + 1, sizeof *g->acc_bytes);
    if (!g->acc_bytes)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory", g->path);
    for (uint32_t i = 0; i < g->nacc; i++) {
        int a = (int)g->acc[i];
        uint64_t count, ctype, off, esize;
        if (juint(&g->d, jget(&g->d, a, "count"), UINT64_MAX, &count) || count == UINT64_MAX ||
            juint(&g->d, jget(&g->d, a, "componentType"), 0, &ctype) ||
            juint(&g->d, jget(&g->d, a, "byteOffset"), 0, &off) ||
            (esize = elem_size(&g->d, a, ctype)) == 0)
            return bad(g, err, "accessor", i, "count, componentType, type or byteOffset");
        int view = jget(&g->d, a, "bufferView"), sp = jget(&g->d, a, "sparse");
        if (view >= 0 && within_view(g, "accessor", i, view, off, count, esize, err))
            return -1;
        if (view < 0 && count > g->input / esize) /* zeros: no more than the input's bytes */
            return gib_fail(err, "mesh '%s': accessor %u declares %llu elements of %llu bytes "
                                 "without a bufferView, its %llu bytes hold at most %llu", g->path,
                            i, (unsigned long long)count, (unsigned long long)esize,
                            (unsigned long long)g->input, (unsigned long long)(g->input / esize));
        if (sp >= 0 && check_sparse(g, i, sp, count, esize, err))
            return -1;
        g->acc_bytes[i] = count * esize;
    }
    return 0;
}

/* ------------------------------------------------------------------ what assimp builds */

static uint64_t sat_add(uint64_t a, uint64_t b)
{
    return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

/* Adds the bytes of accessor token v (an index) to *sum. */
static int add_accessor(gltf *g, int v, const char *what, uint32_t i, uint64_t *sum, gib_error *err)
{
    uint64_t a;
    if (v < 0)
        return 0;
    if (juint(&g->d, v, UINT64_MAX, &a) || a >= g->nacc)
        return bad(g, err, what, i, "accessor");
    *sum = sat_add(*sum, g->acc_bytes[a]);
    return 0;
}

/* Adds every accessor an object's members name (a primitive's attributes, a morph target). */
static int add_members(gltf *g, int o, uint32_t i, uint64_t *sum, gib_error *err)
{
    if (o < 0 || g->d.t[o].type != J_OBJ)
        return 0;
    for (uint32_t k = (uint32_t)o + 1; k < g->d.t[o].next; k = g->d.t[k + 1].next)
        if (add_accessor(g, (int)k + 1, "mesh", i, sum, err))
            return -1;
    return 0;
}

static int mesh_sizes(gltf *g, gib_error *err)
{
    g->mesh_bytes = calloc(g->nmesh + 1, sizeof *g->mesh_bytes);
    if (!g->mesh_bytes)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory", g->path);
    for (uint32_t i = 0; i < g->nmesh; i++) {
        uint32_t *prims, np;
        if (jitems(&g->d, jget(&g->d, (int)g->mesh[i], "primitives"), &prims, &np))
            return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory", g->path);
        int rc = 0;
        for (uint32_t p = 0; p < np && rc == 0; p++) {
            int pr = (int)prims[p], targets = jget(&g->d, pr, "targets");
            rc = add_members(g, jget(&g->d, pr, "attributes"), i, &g->mesh_bytes[i], err) ||
                 add_accessor(g, jget(&g->d, pr, "indices"), "mesh", i, &g->mesh_bytes[i], err);
            if (rc == 0 && targets >= 0 && g->d.t[targets].type == J_ARR)
                for (uint32_t k = (uint32_t)targets + 1; k < g->d.t[targets].next && rc == 0;
                     k = g->d.t[k].next)
                    rc = add_members(g, (int)k, i, &g->mesh_bytes[i], err);
        }
        free(prims);
        if (rc)
            return -1;
    }
    return 0;
}

/* The bytes assimp extracts once: every mesh, skins' matrices, animations' samplers. */
static int extracted_once(gltf *g, uint64_t *sum, gib_error *err)
{
    for (uint32_t i = 0; i < g->nmesh; i++)
        *sum = sat_add(*sum, g->mesh_bytes[i]);
    for (uint32_t i = 0; i < g->nskin; i++)
        if (add_accessor(g, jget(&g->d, (int)g->skin[i], "inverseBindMatrices"), "skin", i, sum,
                         err))
            return -1;
    for (uint32_t i = 0; i < g->nanim; i++) {
        int s = jget(&g->d, (int)g->anim[i], "samplers");
        for (uint32_t k = s >= 0 && g->d.t[s].type == J_ARR ? (uint32_t)s + 1 : 0;
             k && k < g->d.t[s].next; k = g->d.t[k].next)
            if (add_accessor(g, jget(&g->d, (int)k, "input"), "animation", i, sum, err) ||
                add_accessor(g, jget(&g->d, (int)k, "output"), "animation", i, sum, err))
                return -1;
    }
    return 0;
}

/* Nodes form trees: each child index in range, one parent each, no cycle (else assimp recurses
 * without end or copies a subtree once per path to it). sub[n]: the mesh bytes of n's subtree. */
static int node_trees(gltf *g, uint64_t *sub, uint32_t *parent, uint32_t *order, gib_error *err)
{
    uint32_t head = 0, tail = 0;
    for (uint32_t i = 0; i < g->nnode; i++)
        parent[i] = UINT32_MAX;
    for (uint32_t i = 0; i < g->nnode; i++) {
        int ch = jget(&g->d, (int)g->node[i], "children");
        uint64_t m, c;
        if (juint(&g->d, jget(&g->d, (int)g->node[i], "mesh"), UINT64_MAX, &m) ||
            (m != UINT64_MAX && m >= g->nmesh))
            return bad(g, err, "node", i, "mesh");
        sub[i] = m == UINT64_MAX ? 0 : g->mesh_bytes[m];
        for (uint32_t k = ch >= 0 && g->d.t[ch].type == J_ARR ? (uint32_t)ch + 1 : 0;
             k && k < g->d.t[ch].next; k = g->d.t[k].next) {
            if (juint(&g->d, (int)k, UINT64_MAX, &c) || c >= g->nnode || c == i)
                return bad(g, err, "node", i, "children");
            if (parent[c] != UINT32_MAX)
                return gib_fail(err, "mesh '%s': node %llu is a child of nodes %u and %u: nodes "
                                     "must form trees", g->path, (unsigned long long)c,
                                parent[c], i);
            parent[c] = i;
        }
    }
    for (uint32_t i = 0; i < g->nnode; i++)
        if (parent[i] == UINT32_MAX)
            order[tail++] = i;
    for (; head < tail; head++) { /* breadth first from the roots */
        int ch = jget(&g->d, (int)g->node[order[head]], "children");
        uint64_t c;
        for (uint32_t k = ch >= 0 && g->d.t[ch].type == J_ARR ? (uint32_t)ch + 1 : 0;
             k && k < g->d.t[ch].next;
             k = g->d.t[k].next)
            if (juint(&g->d, (int)k, 0, &c) == 0)
                order[tail++] = (uint32_t)c;
    }
    if (tail < g->nnode)
        return gib_fail(err, "mesh '%s': its nodes' children form a cycle: nodes must form trees",
                        g->path);
    for (uint32_t k = g->nnode; k-- > 0;)
        if (parent[order[k]] != UINT32_MAX)
            sub[parent[order[k]]] = sat_add(sub[parent[order[k]]], sub[order[k]]);
    return 0;
}

/* The mesh bytes of every scene's node instances (PreTransformVertices copies each). */
static int instanced(gltf *g, uint64_t *sum, gib_error *err)
{
    uint64_t *sub = calloc(g->nnode + 1, sizeof *sub);
    uint32_t *parent = calloc(g->nnode + 1, sizeof *parent);
    uint32_t *order = calloc(g->nnode + 1, sizeof *order);
    int rc = sub && parent && order ? node_trees(g, sub, parent, order, err)
                                    : gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                                                    "mesh '%s': out of memory", g->path);
    for (uint32_t i = 0; i < g->nscene && rc == 0; i++) {
        int ns = jget(&g->d, (int)g->scene[i], "nodes");
        uint64_t n;
        for (uint32_t k = ns >= 0 && g->d.t[ns].type == J_ARR ? (uint32_t)ns + 1 : 0;
             k && k < g->d.t[ns].next && rc == 0; k = g->d.t[k].next)
            if (juint(&g->d, (int)k, UINT64_MAX, &n) || n >= g->nnode)
                rc = bad(g, err, "scene", i, "nodes");
            else
                *sum = sat_add(*sum, sub[n]);
    }
    free(sub);
    free(parent);
    free(order);
    return rc;
}

static int expansion(gltf *g, gib_error *err)
{
    uint64_t once = 0, inst = 0;
    if (mesh_sizes(g, err) || extracted_once(g, &once, err) || instanced(g, &inst, err))
        return -1;
    const uint64_t most = GLTF_EXPANSION * g->input + GLTF_EXPANSION_FLOOR, total = sat_add(once, inst);
    if (total > most)
        return gib_fail(err, "mesh '%s': declares %llu bytes of mesh data (%llu in its meshes, "
                             "%llu in their node instances), its %llu bytes hold at most %llu "
                             "(%u x its size + %llu MiB)", g->path, (unsigned long long)total,
                        (unsigned long long)once, (unsigned long long)inst,
                        (unsigned long long)g->input, (unsigned long long)most, GLTF_EXPANSION,
                        GLTF_EXPANSION_FLOOR >> 20);
    return 0;
}

/* ------------------------------------------------------------------ the file */

static uint32_t le32(const char *p)
{
    const unsigned char *b = (const unsigned char *)p;
    return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

/* A GLB's header and chunks (spec 4.4): the JSON chunk in *json, the BIN chunk in g->bin. */
static int glb_chunks(gltf *g, const char *d, size_t len, const char **json, size_t *jlen,
                      gib_error *err)
{
    if (len < 20 || memcmp(d, "glTF", 4) != 0)
        return gib_fail(err, "mesh '%s': not a GLB file (no 'glTF' header and JSON chunk)", g->path);
    if (le32(d + 4) != 2)
        return gib_fail(err, "mesh '%s': GLB version %u; gibench reads version 2 (glTF 2.0)",
                        g->path, le32(d + 4));
    if (le32(d + 8) > len)
        return gib_fail(err, "mesh '%s': declares %u bytes, its file is %zu bytes", g->path,
                        le32(d + 8), len);
    const size_t end = le32(d + 8);
    const uint32_t jl = le32(d + 12);
    if (end < 20 || le32(d + 16) != 0x4E4F534Au || jl > end - 20)
        return gib_fail(err, "mesh '%s': declares a JSON chunk of %u bytes, its %zu bytes hold at "
                             "most %zu", g->path, jl, len, end < 20 ? 0 : end - 20);
    *json = d + 20;
    *jlen = jl;
    size_t at = 20 + (size_t)jl;
    if (end - at >= 8 && le32(d + at + 4) == 0x004E4942u) {
        if (le32(d + at) > end - at - 8)
            return gib_fail(err, "mesh '%s': declares a BIN chunk of %u bytes, its %zu bytes hold "
                                 "at most %zu", g->path, le32(d + at), len, end - at - 8);
        g->bin = d + at + 8;
        g->bin_len = le32(d + at);
    }
    return 0;
}

static int top_array(gltf *g, const char *key, uint32_t **items, uint32_t *n, gib_error *err)
{
    if (jitems(&g->d, jget(&g->d, 0, key), items, n))
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory", g->path);
    return 0;
}

static int check_json(gltf *g, const char *json, size_t jlen, gib_error *err)
{
    size_t at = 0;
    if (jlen >= 3 && memcmp(json, "\xEF\xBB\xBF", 3) == 0) /* a UTF-8 byte order mark */
        json += 3, jlen -= 3;
    g->d.s = json;
    int rc = jparse(&g->d, jlen, &at);
    if (rc == -2)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "mesh '%s': out of memory", g->path);
    if (rc < 0 || g->d.t[0].type != J_OBJ)
        return gib_fail(err, "mesh '%s': its JSON is not one object (byte %zu; at most %d levels "
                             "deep)", g->path, at, GLTF_DEPTH);
    int ver = jget(&g->d, jget(&g->d, 0, "asset"), "version");
    if (ver < 0 || g->d.t[ver].type != J_STR || g->d.t[ver].end - g->d.t[ver].start < 2 ||
        memcmp(json + g->d.t[ver].start, "2.", 2) != 0)
        return gib_fail(err, "mesh '%s': asset.version is not 2.x; gibench reads glTF 2.0 only",
                        g->path);
    if (top_array(g, "buffers", &g->buf, &g->nbuf, err) ||
        top_array(g, "bufferViews", &g->view, &g->nview, err) ||
        top_array(g, "accessors", &g->acc, &g->nacc, err) ||
        top_array(g, "meshes", &g->mesh, &g->nmesh, err) ||
        top_array(g, "nodes", &g->node, &g->nnode, err) ||
        top_array(g, "scenes", &g->scene, &g->nscene, err) ||
        top_array(g, "skins", &g->skin, &g->nskin, err) ||
        top_array(g, "animations", &g->anim, &g->nanim, err))
        return -1;
    return check_buffers(g, err) || check_views(g, err) || check_accessors(g, err) ||
                   expansion(g, err) ? -1 : 0;
}

int gib_gltf_bounds(const char *data, size_t len, const char *path, int glb, gib_error *err)
{
    gltf g;
    memset(&g, 0, sizeof g);
    g.path = path;
    g.input = len;
    const char *json = data;
    size_t jlen = len;
    int rc = glb ? glb_chunks(&g, data, len, &json, &jlen, err) : 0;
    if (rc == 0)
        rc = check_json(&g, json, jlen, err);
    free(g.d.t);
    free(g.buf), free(g.view), free(g.acc), free(g.mesh), free(g.node), free(g.scene);
    free(g.skin), free(g.anim), free(g.buf_len), free(g.view_len), free(g.acc_bytes);
    free(g.mesh_bytes);
    return rc;
}

/* ------------------------------------------------------------------ the JSON reader, for gltf_scene.c
 * (scene_internal.h, "glTF JSON"): the same tokenizer, handed out read-only. */

struct gib_json {
    jdoc d;
};

int gib_json_parse(const char *text, size_t len, gib_json **out)
{
    *out = calloc(1, sizeof **out);
    if (!*out)
        return -2;
    size_t at = 0;
    if (len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0)
        text += 3, len -= 3;
    (*out)->d.s = text;
    int rc = jparse(&(*out)->d, len, &at);
    if (rc == 0 && (*out)->d.t[0].type != J_OBJ)
        rc = -1;
    if (rc) {
        gib_json_free(*out);
        *out = NULL;
    }
    return rc;
}

void gib_json_free(gib_json *j)
{
    if (j)
        free(j->d.t);
    free(j);
}

int gib_json_get(const gib_json *j, int obj, const char *key)
{
    return jget(&j->d, obj, key);
}

int gib_json_type(const gib_json *j, int tok)
{
    if (tok < 0)
        return -1;
    static const char types[] = {'o', 'a', 's', 'p'};
    return types[j->d.t[tok].type];
}

int gib_json_child(const gib_json *j, int container, int prev)
{
    if (container < 0 || (j->d.t[container].type != J_ARR && j->d.t[container].type != J_OBJ))
        return -1;
    uint32_t k;
    if (prev < 0)
        k = (uint32_t)container + 1;
    else if (j->d.t[container].type == J_OBJ)
        k = j->d.t[prev + 1].next; /* prev is a key: skip its value */
    else
        k = j->d.t[prev].next;
    return k < j->d.t[container].next ? (int)k : -1;
}

int gib_json_num(const gib_json *j, int tok, double *out)
{
    if (tok < 0 || j->d.t[tok].type != J_PRIM)
        return -1;
    char buf[64];
    size_t n = j->d.t[tok].end - j->d.t[tok].start;
    if (n == 0 || n >= sizeof buf)
        return -1;
    memcpy(buf, j->d.s + j->d.t[tok].start, n);
    buf[n] = '\0';
    char *e;
    double x = strtod(buf, &e);
    if (*e || !isfinite(x))
        return -1;
    *out = x;
    return 0;
}

int gib_json_str(const gib_json *j, int tok, char *out, size_t cap)
{
    if (tok < 0 || j->d.t[tok].type != J_STR || cap == 0)
        return -1;
    size_t n = j->d.t[tok].end - j->d.t[tok].start;
    snprintf(out, cap, "%.*s", (int)(n < cap ? n : cap - 1), j->d.s + j->d.t[tok].start);
    return 0;
}

int gib_json_span(const gib_json *j, int tok, const char **s, size_t *n)
{
    if (tok < 0)
        return -1;
    *s = j->d.s + j->d.t[tok].start;
    *n = j->d.t[tok].end - j->d.t[tok].start;
    return 0;
}

int gib_json_streq(const gib_json *j, int tok, const char *s)
{
    return jstreq(&j->d, tok, s);
}

int gib_glb_split(const char *data, size_t len, const char *path, const char **json, size_t *jlen,
                  const char **bin, size_t *blen, gib_error *err)
{
    gltf g;
    memset(&g, 0, sizeof g);
    g.path = path;
    if (glb_chunks(&g, data, len, json, jlen, err))
        return -1;
    *bin = g.bin;
    *blen = (size_t)g.bin_len;
    return 0;
}

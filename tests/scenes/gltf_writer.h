/* gibench scene tests — a small glTF 2.0 writer for test_scene_gltf*.c: flat-shaded triangles
 * (one primitive per material), a buffer as a base64 data: URI or a file beside it (.gltf) or a
 * GLB's BIN chunk, an optional image in the buffer, and the test's own JSON for everything else
 * (nodes, cameras, lights, materials, images by URI). Header-only: static functions. */
#ifndef GIB_TEST_GLTF_WRITER_H
#define GIB_TEST_GLTF_WRITER_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct gw_buf {
    unsigned char *d;
    size_t n, cap;
} gw_buf;

static inline void gw_put(gw_buf *b, const void *p, size_t n)
{
    if (b->n + n + 1 > b->cap) {
        b->cap = (b->n + n + 1) * 2;
        b->d = realloc(b->d, b->cap);
        if (!b->d)
            abort();
    }
    memcpy(b->d + b->n, p, n);
    b->n += n;
}

static inline void gw_str(gw_buf *b, const char *s)
{
    gw_put(b, s, strlen(s));
}

static inline void gw_pad(gw_buf *b, unsigned char c)
{
    while (b->n % 4)
        gw_put(b, &c, 1);
}

/* One primitive: n triangles (9 floats of positions, 6 of glTF uvs each: v down), flat normals
 * from the winding (counter-clockwise = front), material index (-1: none). */
typedef struct gw_prim {
    float *pos, *uv;
    int ntri, cap, material;
} gw_prim;

static inline void gw_tri(gw_prim *p, const float a[3], const float b[3], const float c[3],
                   const float uv[6])
{
    if (p->ntri == p->cap) {
        p->cap = p->cap ? 2 * p->cap : 16;
        p->pos = realloc(p->pos, sizeof(float) * 9 * (size_t)p->cap);
        p->uv = realloc(p->uv, sizeof(float) * 6 * (size_t)p->cap);
        if (!p->pos || !p->uv)
            abort();
    }
    memcpy(p->pos + 9 * p->ntri, a, 12);
    memcpy(p->pos + 9 * p->ntri + 3, b, 12);
    memcpy(p->pos + 9 * p->ntri + 6, c, 12);
    static const float zero[6] = {0};
    memcpy(p->uv + 6 * p->ntri, uv ? uv : zero, 24);
    p->ntri++;
}

/* A square of side s in the plane y = y0 centred on (cx, cz), facing +y; glTF uv (0,0) at the
 * corner (-x, -z), (1,1) at (+x, +z). */
static inline void gw_quad(gw_prim *p, float cx, float y0, float cz, float s)
{
    const float h = 0.5f * s;
    const float a[3] = {cx - h, y0, cz - h}, b[3] = {cx - h, y0, cz + h}, c[3] = {cx + h, y0, cz + h},
                d[3] = {cx + h, y0, cz - h};
    const float uv1[6] = {0, 0, 0, 1, 1, 1}, uv2[6] = {0, 0, 1, 1, 1, 0};
    gw_tri(p, a, b, c, uv1);
    gw_tri(p, a, c, d, uv2);
}

/* An icosahedron of radius r about the origin split `levels` times, faces toward the centre. */
static inline void gw_icosphere(gw_prim *p, float r, int levels)
{
    const double g = (1.0 + sqrt(5.0)) / 2.0;
    double v[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                       {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    static const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    int n = 20;
    double *t = malloc(sizeof(double) * 9 * 20);
    for (int i = 0; i < 20; i++)
        for (int k = 0; k < 3; k++) {
            const double *q = v[f[i][k]];
            const double l = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
            for (int j = 0; j < 3; j++)
                t[9 * i + 3 * k + j] = q[j] / l;
        }
    for (int l = 0; l < levels; l++) {
        double *o = malloc(sizeof(double) * 9 * 4 * (size_t)n);
        for (int i = 0; i < n; i++) {
            const double *a = t + 9 * i, *b = a + 3, *c = a + 6;
            double m[3][3];
            for (int e = 0; e < 3; e++) {
                const double *x = e == 0 ? a : e == 1 ? b : c, *y = e == 0 ? b : e == 1 ? c : a;
                double s = 0;
                for (int j = 0; j < 3; j++)
                    m[e][j] = x[j] + y[j], s += m[e][j] * m[e][j];
                for (int j = 0; j < 3; j++)
                    m[e][j] /= sqrt(s);
            }
            const double *parts[4][3] = {{a, m[0], m[2]}, {m[0], b, m[1]}, {m[2], m[1], c},
                                         {m[0], m[1], m[2]}};
            for (int q = 0; q < 4; q++)
                for (int k = 0; k < 3; k++)
                    memcpy(o + 9 * (4 * i + q) + 3 * k, parts[q][k], 3 * sizeof(double));
        }
        free(t);
        t = o;
        n *= 4;
    }
    for (int i = 0; i < n; i++) {
        float a[3], b[3], c[3];
        for (int j = 0; j < 3; j++) {
            a[j] = (float)(r * t[9 * i + j]);
            b[j] = (float)(r * t[9 * i + 3 + j]);
            c[j] = (float)(r * t[9 * i + 6 + j]);
        }
        gw_tri(p, a, c, b, NULL); /* the icosahedron's faces wind outward: reversed, inward */
    }
    free(t);
}

static inline void gw_base64(gw_buf *out, const unsigned char *d, size_t n)
{
    static const char *k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)d[i] << 16 | (i + 1 < n ? (unsigned)d[i + 1] << 8 : 0) |
                     (i + 2 < n ? d[i + 2] : 0);
        char q[4] = {k[v >> 18 & 63], k[v >> 12 & 63], i + 1 < n ? k[v >> 6 & 63] : '=',
                     i + 2 < n ? k[v & 63] : '='};
        gw_put(out, q, 4);
    }
}

/* Writes path: prims (mesh 0 on node 0), the image's bytes as bufferView 3 x nprim when given,
 * `nodes` (JSON objects after node 0, comma-separated, may be ""), `scene_nodes` (the scene's
 * root list after 0, e.g. ",1,2"), `extra` (top-level members, each followed by a comma).
 * glb = 1 writes a GLB; bin_file (a .gltf's) not NULL: the buffer is that file beside path (not
 * written when it starts with "missing"), its uri bin_file. */
static inline void gw_write_bin(const char *path, int glb, const gw_prim *prims, int nprim,
                                const char *nodes, const char *scene_nodes, const char *extra,
                                const unsigned char *image, size_t image_len, const char *bin_file)
{
    gw_buf bin = {0}, js = {0};
    char tmp[1024];
    size_t *off = calloc((size_t)nprim * 3 + 2, sizeof *off);
    for (int p = 0; p < nprim; p++) {
        const gw_prim *g = &prims[p];
        off[3 * p] = bin.n;
        gw_put(&bin, g->pos, sizeof(float) * 9 * (size_t)g->ntri);
        off[3 * p + 1] = bin.n;
        for (int t = 0; t < g->ntri; t++) {
            const float *a = g->pos + 9 * t, *b = a + 3, *c = a + 6;
            float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            float nn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                           e1[0] * e2[1] - e1[1] * e2[0]};
            float l = sqrtf(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
            for (int j = 0; j < 3; j++)
                nn[j] /= l;
            for (int k = 0; k < 3; k++)
                gw_put(&bin, nn, 12);
        }
        off[3 * p + 2] = bin.n;
        gw_put(&bin, g->uv, sizeof(float) * 6 * (size_t)g->ntri);
    }
    off[3 * nprim] = bin.n;
    if (image)
        gw_put(&bin, image, image_len);
    gw_pad(&bin, 0);

    gw_str(&js, "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0");
    gw_str(&js, scene_nodes);
    gw_str(&js, "]}],\"nodes\":[{\"mesh\":0}");
    if (nodes[0]) {
        gw_str(&js, ",");
        gw_str(&js, nodes);
    }
    gw_str(&js, "],\"meshes\":[{\"primitives\":[");
    for (int p = 0; p < nprim; p++) {
        if (prims[p].material >= 0)
            snprintf(tmp, sizeof tmp, "%s{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d,"
                     "\"TEXCOORD_0\":%d},\"material\":%d}", p ? "," : "", 3 * p, 3 * p + 1,
                     3 * p + 2, prims[p].material);
        else
            snprintf(tmp, sizeof tmp, "%s{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d,"
                     "\"TEXCOORD_0\":%d}}", p ? "," : "", 3 * p, 3 * p + 1, 3 * p + 2);
        gw_str(&js, tmp);
    }
    gw_str(&js, "]}],");
    gw_str(&js, extra);
    gw_str(&js, "\"bufferViews\":[");
    for (int p = 0; p < nprim; p++)
        for (int k = 0; k < 3; k++) {
            snprintf(tmp, sizeof tmp, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}",
                     p || k ? "," : "", off[3 * p + k], off[3 * p + k + 1] - off[3 * p + k]);
            gw_str(&js, tmp);
        }
    if (image) {
        snprintf(tmp, sizeof tmp, ",{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}",
                 off[3 * nprim], image_len);
        gw_str(&js, tmp);
    }
    gw_str(&js, "],\"accessors\":[");
    for (int p = 0; p < nprim; p++) {
        float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int i = 0; i < 3 * prims[p].ntri; i++)
            for (int j = 0; j < 3; j++) {
                lo[j] = fminf(lo[j], prims[p].pos[3 * i + j]);
                hi[j] = fmaxf(hi[j], prims[p].pos[3 * i + j]);
            }
        const int n = 3 * prims[p].ntri;
        snprintf(tmp, sizeof tmp,
                 "%s{\"bufferView\":%d,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\","
                 "\"min\":[%.9g,%.9g,%.9g],\"max\":[%.9g,%.9g,%.9g]},"
                 "{\"bufferView\":%d,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
                 "{\"bufferView\":%d,\"componentType\":5126,\"count\":%d,\"type\":\"VEC2\"}",
                 p ? "," : "", 3 * p, n, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], 3 * p + 1, n,
                 3 * p + 2, n);
        gw_str(&js, tmp);
    }
    snprintf(tmp, sizeof tmp, "],\"buffers\":[{\"byteLength\":%zu", bin.n);
    gw_str(&js, tmp);
    if (!glb && bin_file) {
        gw_str(&js, ",\"uri\":\"");
        gw_str(&js, bin_file);
        gw_str(&js, "\"");
        const char *slash = strrchr(path, '/');
        snprintf(tmp, sizeof tmp, "%.*s%s", (int)(slash ? slash - path + 1 : 0), path, bin_file);
        FILE *bf = strncmp(bin_file, "missing", 7) ? fopen(tmp, "wb") : NULL;
        if (bf)
            fwrite(bin.d, 1, bin.n, bf), fclose(bf);
    } else if (!glb) {
        gw_str(&js, ",\"uri\":\"data:application/octet-stream;base64,");
        gw_base64(&js, bin.d, bin.n);
        gw_str(&js, "\"");
    }
    gw_str(&js, "}]}");
    FILE *fp = fopen(path, "wb");
    if (!fp)
        abort();
    if (glb) {
        gw_pad(&js, ' ');
        uint32_t h[5] = {0x46546C67u, 2, (uint32_t)(12 + 8 + js.n + 8 + bin.n), (uint32_t)js.n,
                         0x4E4F534Au};
        uint32_t bh[2] = {(uint32_t)bin.n, 0x004E4942u};
        fwrite(h, 4, 5, fp);
        fwrite(js.d, 1, js.n, fp);
        fwrite(bh, 4, 2, fp);
        fwrite(bin.d, 1, bin.n, fp);
    } else {
        fwrite(js.d, 1, js.n, fp);
    }
    fclose(fp);
    free(bin.d);
    free(js.d);
    free(off);
}

/* gw_write_bin with the buffer inside the file (a data: URI, or a GLB's BIN chunk). */
static inline void gw_write(const char *path, int glb, const gw_prim *prims, int nprim,
                            const char *nodes, const char *scene_nodes, const char *extra,
                            const unsigned char *image, size_t image_len)
{
    gw_write_bin(path, glb, prims, nprim, nodes, scene_nodes, extra, image, image_len, NULL);
}

static inline void gw_prim_free(gw_prim *p)
{
    free(p->pos);
    free(p->uv);
    memset(p, 0, sizeof *p);
}

#endif

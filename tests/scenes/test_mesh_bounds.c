/* gibench scene tests — what a mesh file declares held to its size before assimp reads it
 * (scenes/mesh_bounds.c, gltf_bounds.c, ply_check.c; scenes/FORMAT.md, "Meshes"). For every
 * format gibench reads, a tiny hostile file (written here into a temporary folder) declaring far
 * more than its bytes hold is refused through gib_mesh_import with the file and the declared
 * count in the message — our message, so assimp never saw it (assimp's would be "assimp cannot
 * read ..."), among them the 309-byte OFF declaring 3.5e9 vertices that took assimp 97 s and
 * 15.9 GB; a valid small file of each format still loads; a format outside the list is refused
 * naming it and the list. No wall-clock time is asserted. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#include "scenes/scene_internal.h"
#include "tests/common/check.h"

static int failures;
static char dir[256];

/* Writes len bytes (len 0: strlen) to dir/name; returns the path (static, one of 4). */
static const char *put(const char *name, const void *data, size_t len)
{
    static char paths[4][512];
    static int k;
    char *p = paths[k++ % 4];
    snprintf(p, 512, "%s/%s", dir, name);
    FILE *f = fopen(p, "wb");
    size_t n = len ? len : strlen(data);
    CHECK(f && fwrite(data, 1, n, f) == n && fclose(f) == 0, "wrote %s", p);
    return p;
}

static const char *put_gz(const char *name, const char *text)
{
    static char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    gzFile z = gzopen(p, "wb");
    CHECK(z && gzwrite(z, text, (unsigned)strlen(text)) == (int)strlen(text) && gzclose(z) == Z_OK,
          "wrote %s", p);
    return p;
}

/* The file loads with `tris` triangles. */
static void loads(const char *what, const char *path, uint32_t tris)
{
    gib_geom g;
    memset(&g, 0, sizeof g);
    uint64_t hash = 0;
    gib_error err = {0};
    int rc = gib_mesh_import(path, 60.0f, &g, &hash, &err);
    char detail[2600];
    snprintf(detail, sizeof detail, "rc %d, %u triangles (want %u) %s", rc, g.tcount, tris, err.msg);
    failures += gib_check_report(__FILE__, __LINE__, rc == 0 && g.tcount == tris, what, detail);
    gib_geom_free(&g);
}

/* The file is refused by our check: the message names it and holds `declared`. */
static void refused(const char *what, const char *path, const char *declared)
{
    gib_geom g;
    memset(&g, 0, sizeof g);
    uint64_t hash = 0;
    gib_error err = {0};
    int rc = gib_mesh_import(path, 60.0f, &g, &hash, &err);
    int ok = rc != 0 && strstr(err.msg, path) && strstr(err.msg, declared) &&
             !strstr(err.msg, "assimp");
    char detail[2600];
    snprintf(detail, sizeof detail, "'%s' in: %s", declared, err.msg);
    failures += gib_check_report(__FILE__, __LINE__, ok, what, detail);
    gib_geom_free(&g);
}

static const float tri_pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};

static void base64(const unsigned char *in, size_t n, char *out)
{
    static const char a[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t o = 0;
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)in[i] << 16 | (i + 1 < n ? (uint32_t)in[i + 1] << 8 : 0) |
                     (i + 2 < n ? in[i + 2] : 0);
        out[o++] = a[v >> 18 & 63];
        out[o++] = a[v >> 12 & 63];
        out[o++] = i + 1 < n ? a[v >> 6 & 63] : '=';
        out[o++] = i + 2 < n ? a[v & 63] : '=';
    }
    out[o] = '\0';
}

/* A glTF 2.0 of one triangle: buffer `buf` (uri member or ""), an accessor of `count` VEC3 floats
 * (extra: more accessor members), one mesh in one node of one scene. */
static void gltf_text(char *out, size_t cap, const char *buf, const char *count, const char *extra)
{
    snprintf(out, cap,
             "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{%s\"byteLength\":36}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
             "\"accessors\":[{%s\"componentType\":5126,\"count\":%s,\"type\":\"VEC3\","
             "\"min\":[0,0,0],\"max\":[1,1,0]}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
             "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}",
             buf, extra, count);
}

/* A GLB around json (padded to 4 bytes) with a BIN chunk of bin_len bytes declared bin_decl. */
static size_t glb(unsigned char *out, const char *json, const void *bin, uint32_t bin_len,
                  uint32_t bin_decl)
{
    uint32_t jl = (uint32_t)(strlen(json) + 3) / 4 * 4, total = 12 + 8 + jl + 8 + bin_len;
    uint32_t h[5] = {0x46546C67u, 2, total, jl, 0x4E4F534Au};
    memcpy(out, h, 20);
    memset(out + 20, ' ', jl);
    memcpy(out + 20, json, strlen(json));
    uint32_t c[2] = {bin_decl, 0x004E4942u};
    memcpy(out + 20 + jl, c, 8);
    memcpy(out + 28 + jl, bin, bin_len);
    return total;
}

static void off_and_stl(void)
{
    /* The reported file: 309 bytes declaring 3.5e9 vertices. */
    char off[400] = "OFF\n3500000000 1 0\n";
    while (strlen(off) + 6 <= 309)
        strcat(off, "0 0 0\n");
    while (strlen(off) < 309)
        strcat(off, " ");
    CHECK(strlen(off) == 309, "the OFF is 309 bytes: %zu", strlen(off));
    refused("OFF: 309 bytes declaring 3.5e9 vertices", put("huge.off", off, 0), "3500000000");
    refused("OFF: 4e9 faces", put("faces.off", "OFF\n3 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 0),
            "4000000000");
    refused("OFF.gz: 3.5e9 vertices", put_gz("huge.off.gz", off), "3500000000");
    const char *tri_off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    loads("OFF: a triangle loads", put("tri.off", tri_off, 0), 1);
    loads("OFF.gz: a triangle loads", put_gz("tri.off.gz", tri_off), 1);

    unsigned char stl[84 + 50] = {0};
    memcpy(stl, "binary", 6);
    uint32_t n = 4000000000u;
    memcpy(stl + 80, &n, 4);
    refused("STL: 4e9 triangles in 134 bytes", put("huge.stl", stl, sizeof stl), "4000000000");
    n = 1;
    memcpy(stl + 80, &n, 4);
    memcpy(stl + 84 + 12, tri_pos, sizeof tri_pos);
    loads("STL: a binary triangle loads", put("tri.stl", stl, sizeof stl), 1);
    loads("STL: an ASCII triangle loads",
          put("tri_ascii.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                               "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n", 0), 1);
}

static void ply_and_obj(void)
{
    const char *head = "ply\nformat ascii 1.0\nelement vertex %s\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                       "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    char ply[512];
    snprintf(ply, sizeof ply, head, "2000000000");
    refused("PLY: 2e9 vertices", put("huge.ply", ply, 0), "2000000000");
    refused("PLY.gz: 2e9 vertices", put_gz("huge.ply.gz", ply), "2000000000");
    const char *bin = "ply\nformat binary_little_endian 1.0\nelement vertex 1500000000\n"
                      "property float x\nproperty float y\nproperty float z\nend_header\n";
    refused("PLY binary: 1.5e9 vertices", put("huge_bin.ply", bin, 0), "1500000000");
    snprintf(ply, sizeof ply, head, "3");
    loads("PLY: a triangle loads", put("tri.ply", ply, 0), 1);

    /* OBJ declares no counts: a face index is what it claims, against the vertices it holds. */
    refused("OBJ: a face on vertex 1e9 of 3",
            put("huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1000000000\n", 0), "1000000000");
    loads("OBJ: a triangle loads", put("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 0), 1);
}

static void gltf_and_glb(void)
{
    char uri[128] = "\"uri\":\"data:application/octet-stream;base64,", json[2048];
    base64((const unsigned char *)tri_pos, sizeof tri_pos, uri + strlen(uri));
    strcat(uri, "\",");
    gltf_text(json, sizeof json, uri, "3", "\"bufferView\":0,");
    loads("glTF: a triangle (data: URI) loads", put("tri.gltf", json, 0), 1);
    gltf_text(json, sizeof json, uri, "3000000000", "\"bufferView\":0,");
    refused("glTF: accessor of 3e9 VEC3 in 36 bytes", put("huge.gltf", json, 0), "3000000000");
    gltf_text(json, sizeof json, uri, "4000000000",
              "\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":0,\"componentType\":5125},"
              "\"values\":{\"bufferView\":0}},");
    refused("glTF: sparse accessor of 4e9 without a bufferView", put("sparse.gltf", json, 0),
            "4000000000");

    put("tri.bin", tri_pos, sizeof tri_pos);
    gltf_text(json, sizeof json, "\"uri\":\"tri.bin\",", "3", "\"bufferView\":0,");
    loads("glTF: a triangle (.bin beside it) loads", put("tri_bin.gltf", json, 0), 1);
    char *bl = strstr(json, "\"byteLength\":36");
    memmove(bl + 23, bl + 15, strlen(bl + 15) + 1);
    memcpy(bl, "\"byteLength\":1000000000", 23);
    refused("glTF: buffer of 1e9 bytes, its .bin 36", put("huge_bin.gltf", json, 0), "1000000000");

    gltf_text(json, sizeof json, uri, "3", "\"bufferView\":0,");
    char *nodes = strstr(json, "\"nodes\":[{\"mesh\":0}]");
    char cyc[2048];
    snprintf(cyc, sizeof cyc, "%.*s\"nodes\":[{\"mesh\":0,\"children\":[1]},{\"children\":[0]}]%s",
             (int)(nodes - json), json, nodes + strlen("\"nodes\":[{\"mesh\":0}]"));
    refused("glTF: nodes in a cycle", put("cycle.gltf", cyc, 0), "cycle");

    static unsigned char g[4096];
    gltf_text(json, sizeof json, "", "3", "\"bufferView\":0,");
    loads("GLB: a triangle loads", put("tri.glb", g, glb(g, json, tri_pos, 36, 36)), 1);
    size_t n = glb(g, json, tri_pos, 36, 2000000000u);
    refused("GLB: BIN chunk of 2e9 bytes", put("huge_chunk.glb", g, n), "2000000000");
    gltf_text(json, sizeof json, "", "2500000000", "\"bufferView\":0,");
    refused("GLB: accessor of 2.5e9 VEC3", put("huge.glb", g, glb(g, json, tri_pos, 36, 36)),
            "2500000000");
}

int main(void)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/gibench-mesh-bounds-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        printf("FAIL: cannot make a temporary folder\n");
        return 1;
    }
    off_and_stl();
    ply_and_obj();
    gltf_and_glb();
    refused("a format outside the list", put("tri.fbx", "v 0 0 0\n", 0), ".gltf, .glb");
    refused("a gzipped OBJ", put_gz("tri.obj.gz", "v 0 0 0\n"), "self-contained");
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        printf("note: could not remove %s\n", dir);
    if (failures)
        CHECK(0, "%d checks failed", failures);
    else
        printf("passed\n");
    return failures != 0;
}

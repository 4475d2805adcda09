/* gibench — mesh files through assimp 5.2's C API: OBJ with its MTL, PLY, OFF, STL, glTF 2.0, GLB,
 * gzipped PLY, OFF, STL and GLB; nothing else (mesh_bounds.c), each checked before assimp reads it.
 *
 * Post-processing flags, and why:
 *  - ValidateDataStructure: assimp's own check of indices and counts before the other steps.
 *  - Triangulate: OBJ faces may be quads or n-gons (Dabrovic Sponza); not for PLY (see below).
 *  - SortByPType + AI_CONFIG_PP_SBP_REMOVE: drop point and line primitives, which neither side
 *    renders, instead of carrying vertices nothing uses.
 *  - GenSmoothNormals: only runs for meshes without normals (Sibenik, Dabrovic Sponza, the PLY
 *    scans). Its smoothing angle is limited (smooth_angle, 60 degrees by default) so that the
 *    right-angled edges of architecture stay hard; scans can ask for 180.
 *  - JoinIdenticalVertices: the OBJ importer emits one vertex per face corner; joining (after the
 *    normals are made) shrinks Sponza's vertex arrays about 4x, which matters because vertex work
 *    is nearly single-threaded on llvmpipe.
 *  - PreTransformVertices: bakes node transforms into the vertices and merges meshes that share a
 *    material, so what we read is already in the file's coordinates.
 * Not used: FindDegenerates (degenerate triangles are kept, ARCHITECTURE.md hard cases), FlipUVs (we keep
 * OBJ's v-up convention; gib_texture documents t = 1 - v), FixInfacingNormals (guesses wrong on
 * open architecture).
 *
 * A custom aiFileIO opens every file assimp asks for: it resolves names case-insensitively (an MTL
 * named in the wrong case still loads) and records each file read, whose bytes then go into the
 * content hash (the MTL changes the image as much as the OBJ does). */
#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <zlib.h>

#include "harness/base/hash.h"
#include "scene_internal.h"

/* ------------------------------------------------------------------ file access for assimp */

#define MAX_OPENED 32

typedef struct io_state {
    char opened[MAX_OPENED][GIB_PATH_MAX];
    int count;
} io_state;

static size_t f_read(struct aiFile *f, char *buf, size_t size, size_t count)
{
    return fread(buf, size, count, (FILE *)f->UserData);
}

static size_t f_write(struct aiFile *f, const char *buf, size_t size, size_t count)
{
    (void)f;
    (void)buf;
    (void)size;
    (void)count;
    return 0; /* read-only */
}

static size_t f_tell(struct aiFile *f)
{
    long p = ftell((FILE *)f->UserData);
    return p < 0 ? 0 : (size_t)p;
}

static size_t f_size(struct aiFile *f)
{
    struct stat st;
    if (fstat(fileno((FILE *)f->UserData), &st) != 0)
        return 0;
    return (size_t)st.st_size;
}

static enum aiReturn f_seek(struct aiFile *f, size_t off, enum aiOrigin origin)
{
    int whence = origin == aiOrigin_SET ? SEEK_SET : origin == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
    return fseek((FILE *)f->UserData, (long)off, whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
}

static void f_flush(struct aiFile *f)
{
    (void)f;
}

static struct aiFile *io_open(struct aiFileIO *io, const char *name, const char *mode)
{
    if (!mode || mode[0] != 'r')
        return NULL;
    io_state *st = (io_state *)io->UserData;
    char path[GIB_PATH_MAX];
    if (gib_path_resolve_ci(name, path, sizeof path) != 0 || !gib_path_is_file(path))
        return NULL;
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return NULL;
    struct aiFile *f = calloc(1, sizeof *f);
    if (!f) {
        fclose(fp);
        return NULL;
    }
    f->ReadProc = f_read;
    f->WriteProc = f_write;
    f->TellProc = f_tell;
    f->FileSizeProc = f_size;
    f->SeekProc = f_seek;
    f->FlushProc = f_flush;
    f->UserData = (aiUserData)fp;
    int known = 0;
    for (int i = 0; i < st->count && !known; i++)
        known = strcmp(st->opened[i], path) == 0;
    if (!known && st->count < MAX_OPENED)
        snprintf(st->opened[st->count++], GIB_PATH_MAX, "%s", path);
    return f;
}

static void io_close(struct aiFileIO *io, struct aiFile *f)
{
    (void)io;
    if (f) {
        fclose((FILE *)f->UserData);
        free(f);
    }
}

/* ------------------------------------------------------------------ gzip */

static int read_gz(const char *path, unsigned char **out, size_t *out_len, uint64_t *hash,
                   gib_error *err)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return gib_fail(err, "cannot open '%s'", path);
    struct stat st;
    if (fstat(fileno(fp), &st) != 0 || st.st_size <= 0) {
        fclose(fp);
        return gib_fail(err, "'%s' is empty or unreadable", path);
    }
    size_t in_len = (size_t)st.st_size;
    unsigned char *in = malloc(in_len);
    if (!in) {
        fclose(fp);
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory reading '%s'", path);
    }
    size_t got = fread(in, 1, in_len, fp);
    fclose(fp);
    if (got != in_len) {
        free(in);
        return gib_fail(err, "cannot read '%s'", path);
    }
    *hash = gib_hash_bytes(*hash, in, in_len);

    z_stream zs;
    memset(&zs, 0, sizeof zs);
    if (inflateInit2(&zs, 15 + 32) != Z_OK) { /* +32: accept gzip or zlib headers */
        free(in);
        return gib_fail(err, "zlib cannot start inflating '%s'", path);
    }
    size_t cap = in_len * 4 + 1024, len = 0;
    unsigned char *buf = malloc(cap);
    int zrc = Z_OK;
    while (buf) {
        zs.next_in = in + zs.total_in;
        zs.avail_in = (uInt)(in_len - zs.total_in);
        zs.next_out = buf + len;
        zs.avail_out = (uInt)(cap - len);
        zrc = inflate(&zs, Z_NO_FLUSH);
        len = zs.total_out;
        if (zrc == Z_STREAM_END || (zrc != Z_OK && zrc != Z_BUF_ERROR))
            break;
        if (zs.avail_out == 0) {
            unsigned char *nb = realloc(buf, cap * 2);
            if (!nb) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = nb;
            cap *= 2;
        } else if (zs.avail_in == 0) {
            zrc = Z_DATA_ERROR; /* input ended before the stream did */
            break;
        }
    }
    inflateEnd(&zs);
    free(in);
    if (!buf)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory decompressing '%s'", path);
    if (zrc != Z_STREAM_END) {
        free(buf);
        return gib_fail(err, "'%s' is not a complete gzip file (zlib: %s)", path,
                        zs.msg ? zs.msg : "truncated");
    }
    *out = buf;
    *out_len = len;
    return 0;
}

/* ------------------------------------------------------------------ materials */

static int texture_path(const struct aiMaterial *am, enum aiTextureType type, const char *dir,
                        char *out, size_t out_len, const char *mesh_path, gib_error *err)
{
    out[0] = '\0';
    if (aiGetMaterialTextureCount(am, type) == 0)
        return 0;
    struct aiString s;
    if (aiGetMaterialTexture(am, type, 0, &s, NULL, NULL, NULL, NULL, NULL, NULL) !=
        aiReturn_SUCCESS)
        return 0;
    if (s.length == 0)
        return 0;
    if (s.data[0] == '*')
        return gib_fail(err, "'%s': embedded textures are not supported ('%s')", mesh_path, s.data);
    for (char *c = s.data; *c; c++)
        if (*c == '\\')
            *c = '/';
    if (gib_path_join(dir, s.data, out, out_len))
        return gib_fail(err, "'%s': texture path too long: '%s'", mesh_path, s.data);
    return 0;
}

/* MTL to the scene model: Kd -> rho_d, Ks/Ns -> normalised Phong. MTL's Phong is not normalised
 * and exporters rarely keep Kd + Ks <= 1, so both are scaled down together when a channel's sum
 * exceeds 1 (energy conservation, ARCHITECTURE.md). Ks = 0 stays purely diffuse whatever Ns says
 * (Sponza's MTL has Ns 7.8 with Ks 0 everywhere). map_Kd multiplies Kd; a zero Kd with a texture is
 * read as 1, since an exporter that wrote 0 did not mean a black surface. */
static int read_material(const struct aiMaterial *am, const char *dir, const char *mesh_path,
                         unsigned flags, gib_mat_desc *d, gib_error *err)
{
    struct aiString name;
    if (aiGetMaterialString(am, AI_MATKEY_NAME, &name) != aiReturn_SUCCESS || name.length == 0) {
        /* Formats without materials (PLY): assimp invents one with a grey specular lobe of
         * exponent 1, which is nothing the file said. Use a plain diffuse material instead, named
         * "default" so that a [material.default] section (or the mesh's `material` key) can
         * replace it. */
        *d = gib_mat_desc_diffuse("default", 0.8f, 0.8f, 0.8f);
        return 0;
    }
    *d = gib_mat_desc_diffuse(name.data, 0.8f, 0.8f, 0.8f);

    struct aiColor4D kd = {0.8f, 0.8f, 0.8f, 1.0f}, ks = {0.0f, 0.0f, 0.0f, 1.0f};
    aiGetMaterialColor(am, AI_MATKEY_COLOR_DIFFUSE, &kd);
    aiGetMaterialColor(am, AI_MATKEY_COLOR_SPECULAR, &ks);
    ai_real ns = 1;
    unsigned int one = 1;
    aiGetMaterialFloatArray(am, AI_MATKEY_SHININESS, &ns, &one);

    if (!(flags & GIB_IMPORT_NO_TEXTURES) &&
        (texture_path(am, aiTextureType_DIFFUSE, dir, d->albedo_path, sizeof d->albedo_path,
                      mesh_path, err) ||
         texture_path(am, aiTextureType_OPACITY, dir, d->alpha_path, sizeof d->alpha_path,
                      mesh_path, err)))
        return -1;

    float a[3] = {(float)kd.r, (float)kd.g, (float)kd.b};
    float s[3] = {(float)ks.r, (float)ks.g, (float)ks.b};
    for (int c = 0; c < 3; c++) {
        a[c] = isfinite(a[c]) ? fmaxf(a[c], 0.0f) : 0.0f;
        s[c] = isfinite(s[c]) ? fmaxf(s[c], 0.0f) : 0.0f;
    }
    if (d->albedo_path[0] && a[0] == 0.0f && a[1] == 0.0f && a[2] == 0.0f)
        a[0] = a[1] = a[2] = 1.0f;
    float worst = 0.0f;
    for (int c = 0; c < 3; c++)
        worst = fmaxf(worst, a[c] + s[c]);
    const float k = worst > 1.0f ? 1.0f / worst : 1.0f;
    for (int c = 0; c < 3; c++) {
        d->m.albedo[c] = a[c] * k;
        d->m.specular[c] = s[c] * k;
    }
    if (s[0] > 0.0f || s[1] > 0.0f || s[2] > 0.0f) {
        d->m.spec_type = GIB_SPEC_PHONG;
        d->m.phong_n = (isfinite((float)ns) && ns > 0) ? (float)ns : 1.0f;
    } else {
        d->m.specular[0] = d->m.specular[1] = d->m.specular[2] = 0.0f;
    }
    return 0;
}

/* What assimp read of a glTF material (PBR factors, name, texture, sidedness), for gltf_scene.c
 * to find which of the file's materials it is (gib_gltf_match). */
static void source_pbr(const struct aiMaterial *am, gib_mat_desc *d)
{
    struct aiColor4D bc = {1, 1, 1, 1};
    ai_real v = 1;
    unsigned int one = 1;
    int two = 0;
    struct aiString name;
    aiGetMaterialColor(am, AI_MATKEY_BASE_COLOR, &bc);
    d->src_pbr[0] = (float)bc.r;
    d->src_pbr[1] = (float)bc.g;
    d->src_pbr[2] = (float)bc.b;
    d->src_pbr[3] = (float)bc.a;
    d->src_pbr[4] = aiGetMaterialFloatArray(am, AI_MATKEY_METALLIC_FACTOR, &v, &one) ==
                            aiReturn_SUCCESS ? (float)v : 1.0f;
    v = 1;
    one = 1;
    d->src_pbr[5] = aiGetMaterialFloatArray(am, AI_MATKEY_ROUGHNESS_FACTOR, &v, &one) ==
                            aiReturn_SUCCESS ? (float)v : 1.0f;
    one = 1;
    d->src_flags = 0;
    if (aiGetMaterialString(am, AI_MATKEY_NAME, &name) == aiReturn_SUCCESS && name.length > 0)
        d->src_flags |= GIB_SRC_NAMED;
    if (aiGetMaterialTextureCount(am, aiTextureType_BASE_COLOR) > 0 ||
        aiGetMaterialTextureCount(am, aiTextureType_DIFFUSE) > 0)
        d->src_flags |= GIB_SRC_BASE_TEX;
    if (aiGetMaterialIntegerArray(am, AI_MATKEY_TWOSIDED, &two, &one) == aiReturn_SUCCESS && two)
        d->src_flags |= GIB_SRC_TWO_SIDED;
}

/* ------------------------------------------------------------------ geometry */

static int append_scene(const struct aiScene *sc, const char *dir, const char *mesh_path,
                        unsigned flags, gib_geom *out, gib_error *err)
{
    int *mat_map = gib_calloc(sc->mNumMaterials ? sc->mNumMaterials : 1, sizeof *mat_map, err);
    if (!mat_map)
        return -1;
    for (unsigned i = 0; i < sc->mNumMaterials; i++)
        mat_map[i] = -1;
    int rc = 0;
    uint32_t tris_total = 0;
    for (unsigned mi = 0; mi < sc->mNumMeshes && rc == 0; mi++) {
        const struct aiMesh *m = sc->mMeshes[mi];
        if (!(m->mPrimitiveTypes & (aiPrimitiveType_TRIANGLE | aiPrimitiveType_POLYGON)))
            continue;
        /* Polygons (PLY, imported without assimp's triangulation) become fans; faces under 3
         * corners are dropped; an index past the mesh's vertices is an error, never a read. */
        unsigned ntri = 0;
        for (unsigned f = 0; f < m->mNumFaces && rc == 0; f++) {
            const struct aiFace *face = &m->mFaces[f];
            for (unsigned k = 0; k < face->mNumIndices && rc == 0; k++)
                if (face->mIndices[k] >= m->mNumVertices)
                    rc = gib_fail(err, "'%s': face %u refers to vertex %u of %u", mesh_path, f,
                                  face->mIndices[k], m->mNumVertices);
            ntri += face->mNumIndices >= 3 ? face->mNumIndices - 2 : 0;
        }
        if (rc != 0)
            break;
        if (ntri == 0)
            continue;
        unsigned am = m->mMaterialIndex < sc->mNumMaterials ? m->mMaterialIndex : 0;
        if (sc->mNumMaterials == 0) {
            rc = gib_fail(err, "'%s': mesh without any material", mesh_path);
            break;
        }
        if (mat_map[am] < 0) {
            gib_mat_desc d;
            if ((rc = read_material(sc->mMaterials[am], dir, mesh_path, flags, &d, err)) != 0)
                break;
            d.source_index = (int)am;
            source_pbr(sc->mMaterials[am], &d);
            if (am + 1 == sc->mNumMaterials)
                d.src_flags |= GIB_SRC_LAST;
            if ((mat_map[am] = gib_geom_material(out, &d, err)) < 0) {
                rc = -1;
                break;
            }
        }
        if ((rc = gib_geom_reserve(out, m->mNumVertices, ntri, err)) != 0)
            break;
        const uint32_t base = out->vcount;
        const struct aiVector3D *uvs = m->mTextureCoords[0];
        for (unsigned v = 0; v < m->mNumVertices; v++) {
            const float p[3] = {(float)m->mVertices[v].x, (float)m->mVertices[v].y,
                                (float)m->mVertices[v].z};
            /* Missing normals are left zero; scene_build repairs every invalid normal. */
            float n[3] = {0.0f, 0.0f, 0.0f};
            if (m->mNormals) {
                n[0] = (float)m->mNormals[v].x;
                n[1] = (float)m->mNormals[v].y;
                n[2] = (float)m->mNormals[v].z;
            }
            float uv[2] = {0.0f, 0.0f};
            if (uvs) {
                uv[0] = (float)uvs[v].x;
                uv[1] = (float)uvs[v].y;
            }
            gib_geom_vertex(out, p, n, uv);
        }
        for (unsigned f = 0; f < m->mNumFaces; f++) {
            const struct aiFace *face = &m->mFaces[f];
            for (unsigned k = 2; k < face->mNumIndices; k++)
                gib_geom_triangle(out, base + face->mIndices[0], base + face->mIndices[k - 1],
                                  base + face->mIndices[k], (uint32_t)mat_map[am]);
        }
        tris_total += ntri;
    }
    free(mat_map);
    if (rc == 0 && tris_total == 0)
        rc = gib_fail(err, "'%s' contains no triangles", mesh_path);
    return rc;
}

/* A mesh file on disk, read whole and checked (gib_mesh_bounds: what it declares against its
 * size, and the format's own checks) before assimp reads it. */
static int file_check(const char *path, const char *fmt, gib_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return gib_fail(err, "cannot open '%s'", path);
    long size = fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1;
    char *buf = size >= 0 ? malloc((size_t)size + 1) : NULL;
    int rc;
    if (!buf || fseek(f, 0, SEEK_SET) != 0 || fread(buf, 1, (size_t)size, f) != (size_t)size)
        rc = gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                           "cannot read '%s'%s", path, buf ? "" : " (out of memory)");
    else
        rc = gib_mesh_bounds(buf, (size_t)size, path, fmt, err);
    fclose(f);
    free(buf);
    return rc;
}

int gib_mesh_import(const char *path, float smooth_angle_deg, gib_geom *out, uint64_t *hash,
                    gib_error *err)
{
    return gib_mesh_import_ex(path, smooth_angle_deg, 0, out, hash, err);
}

int gib_mesh_import_ex(const char *path, float smooth_angle_deg, unsigned import_flags,
                       gib_geom *out, uint64_t *hash, gib_error *err)
{
    /* Only the formats FORMAT.md documents (mesh_bounds.c), each checked before assimp. */
    char fmt[8];
    int gz = 0;
    if (gib_mesh_format(path, fmt, &gz, err) != 0)
        return -1;
    /* PLY without aiProcess_Triangulate: its assertion aborts the process on malformed face
     * lists (found by tests/fuzz/fuzz_mesh), and append_scene makes fans of PLY's polygons. */
    const int is_ply = strcmp(fmt, "ply") == 0;
    const unsigned flags = aiProcess_ValidateDataStructure | (is_ply ? 0u : aiProcess_Triangulate) |
                           aiProcess_SortByPType | aiProcess_GenSmoothNormals |
                           aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices;
    struct aiPropertyStore *props = aiCreatePropertyStore();
    if (!props)
        return gib_fail(err, "assimp: cannot create a property store");
    aiSetImportPropertyFloat(props, AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE,
                             (ai_real)smooth_angle_deg);
    aiSetImportPropertyInteger(props, AI_CONFIG_PP_SBP_REMOVE,
                               aiPrimitiveType_POINT | aiPrimitiveType_LINE);

    char dir[GIB_PATH_MAX];
    gib_path_dirname(path, dir, sizeof dir);
    const struct aiScene *sc = NULL;
    int rc = 0;
    if (gz) {
        /* assimp picks the importer by extension, so the inner one is passed as a hint. Only
         * self-contained formats work this way (gib_mesh_format): the data comes from memory. */
        unsigned char *buf = NULL;
        size_t len = 0;
        rc = read_gz(path, &buf, &len, hash, err);
        if (rc == 0 && len > 0xffffffffu)
            rc = gib_fail(err, "'%s' decompresses to more than 4 GiB", path);
        if (rc == 0)
            rc = gib_mesh_bounds((const char *)buf, len, path, fmt, err);
        if (rc == 0)
            sc = aiImportFileFromMemoryWithProperties((const char *)buf, (unsigned)len, flags, fmt,
                                                      props);
        free(buf);
    } else if ((rc = file_check(path, fmt, err)) != 0) {
        /* refused before assimp reads it */
    } else {
        io_state st;
        st.count = 0;
        struct aiFileIO io = {io_open, io_close, (aiUserData)&st};
        sc = aiImportFileExWithProperties(path, flags, &io, props);
        for (int i = 0; i < st.count && sc; i++)
            if (gib_hash_file(hash, st.opened[i]) != 0)
                rc = gib_fail(err, "cannot read '%s' to hash it", st.opened[i]);
    }
    aiReleasePropertyStore(props);
    if (rc == 0 && !sc)
        rc = gib_fail(err, "assimp cannot read '%s': %s", path, aiGetErrorString());
    if (rc == 0)
        rc = append_scene(sc, dir, path, import_flags, out, err);
    if (sc)
        aiReleaseImport(sc);
    return rc;
}

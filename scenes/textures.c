/* gibench — texture files for materials: read through the OpenImageIO shim, colour textures
 * decoded from sRGB to linear (ARCHITECTURE.md: albedo textures are linear in the scene model), alpha
 * masks kept as stored. Each (file, decoding) pair is loaded once per scene however many
 * materials use it.
 *
 * Crytek Sponza has about 25 textures of 1024^2; decoding JPEGs dominates its load time, so
 * gib_tex_cache_get_many decodes them on several threads (the shim opens an independent
 * ImageInput per call, so concurrent calls are safe). */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness/base/hash.h"
#include "harness/imaging/oiio_shim.h"
#include "scene_internal.h"

float gib_srgb_to_linear(float c)
{
    if (c <= 0.04045f)
        return c / 12.92f;
    return powf((c + 0.055f) / 1.055f, 2.4f);
}

/* Most textures are 8-bit: their values are exactly k/255 after the shim's conversion, so a table
 * gives the same result as powf at a fraction of the cost. Other values take the formula. */
static float lut8[256];
static pthread_once_t lut_once = PTHREAD_ONCE_INIT;

static void lut_init(void)
{
    for (int k = 0; k < 256; k++)
        lut8[k] = gib_srgb_to_linear((float)k / 255.0f);
}

static void decode_srgb(float *rgba, size_t texels)
{
    pthread_once(&lut_once, lut_init);
    for (size_t i = 0; i < texels; i++) {
        for (int c = 0; c < 3; c++) {
            float v = rgba[4 * i + (size_t)c];
            float k = rintf(v * 255.0f);
            if (k >= 0.0f && k <= 255.0f && v == k / 255.0f)
                rgba[4 * i + (size_t)c] = lut8[(int)k];
            else
                rgba[4 * i + (size_t)c] = gib_srgb_to_linear(fminf(fmaxf(v, 0.0f), 1.0f));
        }
    }
}

static int find(const gib_tex_cache *c, const char *path, int srgb)
{
    for (uint32_t i = 0; i < c->count; i++)
        if (c->srgb[i] == srgb && strcmp(c->tex[i].path, path) == 0)
            return (int)i;
    return -1;
}

typedef struct load_job {
    const char *path;
    int srgb;
    int width, height;
    float *rgba;
    char errbuf[1024];
    int rc;
    uint64_t file_hash; /* hash of the file's bytes alone, combined in order afterwards */
} load_job;

/* An image embedded in a glTF ("<file>#image<N>", gltf_scene.c): its bytes go through a
 * temporary file, since the image reader takes paths; the hash covers the bytes. */
static void run_embedded(load_job *j)
{
    unsigned char *bytes = NULL;
    size_t len = 0;
    char ext[8], tmp[512];
    float mask = 0.0f;
    j->file_hash = GIB_HASH_INIT;
    j->rc = gib_gltf_image_bytes(j->path, &bytes, &len, ext, &mask, j->errbuf,
                                 (int)sizeof j->errbuf);
    if (j->rc == 0) {
        const char *dir = getenv("TMPDIR");
        snprintf(tmp, sizeof tmp, "%s/gibench_gltf_XXXXXX%s", dir && dir[0] ? dir : "/tmp", ext);
        int fd = mkstemps(tmp, (int)strlen(ext));
        FILE *fp = fd >= 0 ? fdopen(fd, "wb") : NULL;
        int ok = fp && fwrite(bytes, 1, len, fp) == len;
        if (fp)
            ok = (fclose(fp) == 0) && ok;
        else if (fd >= 0)
            close(fd);
        if (!ok) {
            snprintf(j->errbuf, sizeof j->errbuf, "cannot write texture '%s' to a temporary file",
                     j->path);
            j->rc = -1;
        } else {
            j->rc = gib_oiio_read_rgba(tmp, &j->width, &j->height, &j->rgba, j->errbuf,
                                       (int)sizeof j->errbuf);
            if (j->rc != 0)
                snprintf(j->errbuf, sizeof j->errbuf, "texture '%s': cannot decode its image",
                         j->path);
        }
        if (fd >= 0)
            unlink(tmp);
        j->file_hash = gib_hash_bytes(j->file_hash, bytes, len);
        j->file_hash = gib_hash_u64(j->file_hash, (uint64_t)(mask * 1e9f));
    }
    free(bytes);
    /* a glTF alpha mask: alpha x scale (at most 1) in the first channels, where the mask is read */
    for (size_t i = 0; j->rc == 0 && mask > 0.0f && i < (size_t)j->width * (size_t)j->height; i++)
        j->rgba[4 * i] = j->rgba[4 * i + 1] = j->rgba[4 * i + 2] =
            fminf(j->rgba[4 * i + 3] * mask, 1.0f);
    if (j->rc == 0 && j->srgb)
        decode_srgb(j->rgba, (size_t)j->width * (size_t)j->height);
}

static void run_job(load_job *j)
{
    if (gib_gltf_image_ref(j->path)) {
        run_embedded(j);
        return;
    }
    j->rc = gib_oiio_read_rgba(j->path, &j->width, &j->height, &j->rgba, j->errbuf,
                               (int)sizeof j->errbuf);
    if (j->rc == 0 && j->srgb)
        decode_srgb(j->rgba, (size_t)j->width * (size_t)j->height);
    j->file_hash = GIB_HASH_INIT;
    if (j->rc == 0 && gib_hash_file(&j->file_hash, j->path) != 0) {
        snprintf(j->errbuf, sizeof j->errbuf, "cannot read texture '%s' to hash it", j->path);
        j->rc = -1;
    }
}

typedef struct job_queue {
    load_job *jobs;
    int n;
    int next;
    pthread_mutex_t lock;
} job_queue;

static void *worker(void *arg)
{
    job_queue *q = arg;
    for (;;) {
        pthread_mutex_lock(&q->lock);
        int i = q->next < q->n ? q->next++ : -1;
        pthread_mutex_unlock(&q->lock);
        if (i < 0)
            return NULL;
        run_job(&q->jobs[i]);
    }
}

static int cache_add(gib_tex_cache *c, load_job *j, uint64_t *hash, gib_error *err)
{
    if (c->count == c->cap) {
        uint32_t cap = c->cap ? 2 * c->cap : 16;
        gib_texture *t = gib_realloc_array(c->tex, cap, sizeof *t, err);
        if (!t)
            return -1;
        c->tex = t;
        int *s = gib_realloc_array(c->srgb, cap, sizeof *s, err);
        if (!s)
            return -1;
        c->srgb = s;
        c->cap = cap;
    }
    gib_texture *t = &c->tex[c->count];
    memset(t, 0, sizeof *t);
    snprintf(t->path, sizeof t->path, "%s", j->path);
    t->width = j->width;
    t->height = j->height;
    t->rgba = j->rgba;
    j->rgba = NULL;
    c->srgb[c->count] = j->srgb;
    /* Combine per-file hashes in a fixed order (the order of first use) so that the scene hash
     * does not depend on which thread finished first. */
    *hash = gib_hash_str(*hash, j->srgb ? "srgb" : "linear");
    *hash = gib_hash_u64(*hash, j->file_hash);
    return (int)c->count++;
}

int gib_tex_cache_get_many(gib_tex_cache *c, const char *const *paths, const int *srgb, int n,
                           int *out_index, uint64_t *hash, gib_error *err)
{
    load_job *jobs = gib_calloc((size_t)(n > 0 ? n : 1), sizeof *jobs, err);
    if (!jobs)
        return -1;
    /* One job per distinct (path, decoding) not yet cached. */
    int nj = 0;
    for (int i = 0; i < n; i++) {
        out_index[i] = find(c, paths[i], srgb[i]);
        if (out_index[i] >= 0)
            continue;
        int dup = 0;
        for (int k = 0; k < nj && !dup; k++)
            dup = jobs[k].srgb == srgb[i] && strcmp(jobs[k].path, paths[i]) == 0;
        if (!dup) {
            jobs[nj].path = paths[i];
            jobs[nj].srgb = srgb[i];
            nj++;
        }
    }

    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    int nthreads = (int)(ncpu < 1 ? 1 : ncpu > 8 ? 8 : ncpu);
    if (nthreads > nj)
        nthreads = nj;
    job_queue q = {.jobs = jobs, .n = nj, .next = 0};
    pthread_mutex_init(&q.lock, NULL);
    pthread_t threads[8];
    int started = 0;
    for (int t = 1; t < nthreads; t++) /* this thread is worker 0 */
        if (pthread_create(&threads[started], NULL, worker, &q) == 0)
            started++;
    worker(&q);
    for (int t = 0; t < started; t++)
        pthread_join(threads[t], NULL);
    pthread_mutex_destroy(&q.lock);

    int rc = 0;
    for (int k = 0; k < nj; k++) {
        if (rc == 0 && jobs[k].rc != 0)
            rc = gib_fail(err, "%s", jobs[k].errbuf);
        if (rc == 0 && cache_add(c, &jobs[k], hash, err) < 0)
            rc = -1;
        free(jobs[k].rgba); /* NULL once moved into the cache */
    }
    free(jobs);
    if (rc)
        return -1;
    for (int i = 0; i < n; i++)
        if (out_index[i] < 0)
            out_index[i] = find(c, paths[i], srgb[i]);
    return 0;
}

int gib_tex_cache_get(gib_tex_cache *c, const char *resolved_path, int srgb, uint64_t *hash,
                      gib_error *err)
{
    int idx;
    if (gib_tex_cache_get_many(c, &resolved_path, &srgb, 1, &idx, hash, err))
        return -1;
    return idx;
}

void gib_tex_cache_release(gib_tex_cache *c)
{
    free(c->srgb);
    c->srgb = NULL;
    /* c->tex is handed to the scene by the caller. */
    c->tex = NULL;
    c->count = c->cap = 0;
}

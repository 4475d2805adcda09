/* gibench — the reference cache (ARCHITECTURE.md, "Reference renderer").
 *
 * An entry is an EXR named by gib_reference_cache_key(): a hash of everything that changes the
 * image — the scene's content hash (scene file, meshes, textures), the camera, size, component and
 * all its parameters (normalised, so that equal images share a key), spp or the target noise, seed
 * and the renderer version. Its header repeats those facts and carries a seal (gib_ref_seal: a
 * hash of the pixels and of every other attribute); an entry that cannot be read, whose header's
 * key, renderer version, scene hash, component or size do not match the request, whose seal does
 * not match its pixels and header (edited or corrupted since it was written: a wrong spp or noise
 * figure would go into every results table), or that holds NaN or Inf, is rendered again and
 * overwritten, never used. A new entry is read back and held to the same tests right after it is
 * written: one that fails them (an EXR writer that corrupted a chunk) is an error naming the file,
 * not an entry that every later request would silently render again. */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness/base/hash.h"
#include "app.h"

gib_ref_params gib_ref_request_params(const gib_ref_request *rq)
{
    gib_ref_params p = {.component = rq->component, .width = rq->width, .height = rq->height,
                        .spp = rq->spp, .dmax = rq->dmax, .obscurance = rq->obscurance,
                        .max_depth = rq->max_depth, .min_depth = rq->min_depth,
                        .max_specular = rq->max_specular, .cone = rq->cone,
                        .cone_aperture = rq->cone_aperture, .target_noise = rq->target_noise,
                        .max_spp = rq->max_spp, .seed = 1, .threads = rq->threads,
                        .camera = rq->camera, .time = rq->time, .quiet = rq->quiet,
                        .interrupt = rq->interrupt};
    return p;
}

#define GIB_SEAL_KEY "content_hash"

/* The hash of the pixels and of want's keys with their values in got, or 0 when got lacks one. */
static uint64_t seal_hash(const gib_image *img, const gib_kv *want, int nwant, const gib_kv *got,
                          int ngot)
{
    uint64_t h = gib_hash_u64(GIB_HASH_INIT, (uint64_t)img->width << 32 | (uint32_t)img->height);
    h = gib_hash_u64(h, (uint64_t)img->channels);
    h = gib_hash_bytes(h, img->px,
                       (size_t)img->width * (size_t)img->height * (size_t)img->channels *
                           sizeof *img->px);
    for (int i = 0; i < nwant; i++) {
        if (!strcmp(want[i].key, GIB_SEAL_KEY))
            continue;
        const char *v = gib_kv_get(got, ngot, want[i].key);
        if (!v)
            return 0;
        h = gib_hash_str(gib_hash_str(h, want[i].key), v);
    }
    return h ? h : 1;
}

int gib_ref_seal(const gib_image *img, gib_kv *attrs, int n, int max)
{
    if (n >= max)
        return n;
    char hex[17];
    gib_hash_hex(seal_hash(img, attrs, n, attrs, n), hex);
    snprintf(attrs[n].key, sizeof attrs[n].key, "%s", GIB_SEAL_KEY);
    snprintf(attrs[n].value, sizeof attrs[n].value, "%s", hex);
    return n + 1;
}

int gib_ref_seal_ok(const gib_image *img, const gib_kv *want, int nwant, const gib_kv *got,
                    int ngot)
{
    const char *seal = gib_kv_get(got, ngot, GIB_SEAL_KEY);
    uint64_t h = seal_hash(img, want, nwant, got, ngot);
    char hex[17];
    gib_hash_hex(h, hex);
    return seal && h && !strcmp(seal, hex);
}

static int attr_is(const gib_kv *attrs, int n, const char *key, const char *want)
{
    const char *v = gib_kv_get(attrs, n, key);
    return v && !strcmp(v, want);
}

/* Why an entry's header and pixels do not serve the request (a phrase completing "does not
 * match ..."), or NULL when they do. */
static const char *entry_mismatch(const gib_ref_request *rq, const char *key_hex,
                                  const gib_image *img, const gib_kv *attrs, int n)
{
    char scene_hex[17], num[32];
    gib_hash_hex(rq->scene->content_hash, scene_hex);
    snprintf(num, sizeof num, "%d", rq->width);
    gib_ref_params p = gib_ref_request_params(rq);
    gib_kv want[GIB_REF_ATTR_COUNT];
    if (!attr_is(attrs, n, "cache_key", key_hex))
        return "its key";
    if (!attr_is(attrs, n, "renderer_version", GIB_REFERENCE_VERSION))
        return "the renderer version";
    if (!attr_is(attrs, n, "scene_hash", scene_hex))
        return "the scene";
    if (!attr_is(attrs, n, "component", gib_component_name(rq->component)))
        return "the component";
    if (!attr_is(attrs, n, "width", num) || img->width != rq->width || img->height != rq->height)
        return "the image size";
    if (!gib_kv_get(attrs, n, "noise_rmse") || !gib_kv_get(attrs, n, "spp"))
        return "its header (no noise_rmse or spp)";
    if (attr_is(attrs, n, "stop", "interrupted"))
        return "a finished render (it holds the rounds done of an interrupted one)";
    int want_n = gib_reference_attrs(rq->scene, &p, NULL, want, GIB_REF_ATTR_COUNT);
    if (!gib_ref_seal_ok(img, want, want_n, attrs, n))
        return "its seal (pixels or header changed since it was written, or written before seals)";
    if (gib_image_count_nonfinite(img) != 0)
        return "finite pixels (it holds NaN or Inf)";
    return NULL;
}

/* Reads the entry at path into img and out's figures when it serves the request; otherwise says
 * why on stderr (the caller renders again) and returns 0. */
static int entry_valid(const char *path, const gib_ref_request *rq, const char *key_hex,
                       gib_image *img, gib_ref_result *out)
{
    if (access(path, R_OK) != 0)
        return 0;
    gib_kv *attrs = NULL;
    int n = 0;
    gib_error e;
    if (gib_exr_read(path, img, &attrs, &n, &e) < 0) {
        fprintf(stderr, "gibench: reference cache entry %s is unreadable (%s); rendering again\n",
                path, e.msg);
        return 0;
    }
    const char *why = entry_mismatch(rq, key_hex, img, attrs, n);
    if (!why) {
        const char *secs = gib_kv_get(attrs, n, "seconds");
        out->noise_rmse = strtod(gib_kv_get(attrs, n, "noise_rmse"), NULL);
        out->spp = (int)strtol(gib_kv_get(attrs, n, "spp"), NULL, 10);
        out->seconds = secs ? strtod(secs, NULL) : 0;
    } else {
        fprintf(stderr, "gibench: reference cache entry %s does not match %s; rendering again\n",
                path, why);
        gib_image_free(img);
    }
    free(attrs);
    return !why;
}

/* The pid of a writer's temporary for the entry named `base` (EXR cache names), or 0 if `name` is
 * none: our own "<base>.tmp<pid>" and the one OpenEXR writes it through, "tmp.<pid><base>.tmp<pid>"
 * (EXR_INTERMEDIATE_TEMP_FILE). */
static long temp_writer_pid(const char *name, const char *base)
{
    size_t nb = strlen(base);
    if (strncmp(name, "tmp.", 4) == 0) { /* OpenEXR's: skip "tmp.<pid>" to our own name */
        const char *p = name + 4;
        while (*p >= '0' && *p <= '9')
            p++;
        if (p == name + 4)
            return 0;
        name = p;
    }
    if (strncmp(name, base, nb) != 0 || strncmp(name + nb, ".tmp", 4) != 0)
        return 0;
    char *end;
    long pid = strtol(name + nb + 4, &end, 10);
    return *end == '\0' && pid > 0 ? pid : 0;
}

/* Removes what writers of the entry at `path` that died mid-write (SIGKILL, power loss) left: the
 * temporaries of processes no longer running on this machine. A live writer's are kept. */
static void remove_dead_writers_temps(const char *path)
{
    const char *slash = strrchr(path, '/');
    char dir[1100];
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) : 1, slash ? path : ".");
    const char *base = slash ? slash + 1 : path;
    DIR *dp = opendir(dir);
    if (!dp)
        return;
    struct dirent *e;
    while ((e = readdir(dp))) {
        long pid = temp_writer_pid(e->d_name, base);
        if (pid <= 0 || pid == (long)getpid() || !(kill((pid_t)pid, 0) < 0 && errno == ESRCH))
            continue;
        char stale[2200];
        snprintf(stale, sizeof stale, "%s/%s", dir, e->d_name);
        unlink(stale);
    }
    closedir(dp);
}

/* Reads back the entry just written to path and holds it to what a later request will: an entry
 * that would be refused (a writer that corrupts pixels, say) is an error naming the file, not an
 * entry every later request renders again. The file is left for inspection. */
static int entry_check_written(const char *path, const gib_ref_request *rq, const char *key_hex,
                               gib_error *err)
{
    gib_image img;
    gib_kv *attrs = NULL;
    int n = 0;
    gib_error e;
    if (gib_exr_read(path, &img, &attrs, &n, &e) < 0)
        return gib_fail(err, "reference cache entry %s does not read back right after it was "
                             "written: %s", path, e.msg);
    const char *why = entry_mismatch(rq, key_hex, &img, attrs, n);
    gib_image_free(&img);
    free(attrs);
    if (why)
        return gib_fail(err, "reference cache entry %s does not match %s right after it was "
                             "written: no request could use it", path, why);
    return 0;
}

/* The entry's key and path in out->path; 0, or -1 with err. */
static int entry_prepare(const gib_ref_request *rq, gib_ref_result *out, char key_hex[17],
                         gib_error *err)
{
    memset(out, 0, sizeof *out);
    if (rq->camera < 0 || (uint32_t)rq->camera >= rq->scene->camera_count)
        return gib_fail(err, "reference %s: camera %d of %u", rq->scene->name, rq->camera,
                        rq->scene->camera_count);
    gib_ref_params p = gib_ref_request_params(rq);
    gib_hash_hex(gib_reference_cache_key(rq->scene, &p), key_hex);
    if (gib_mkdirs(rq->cache_dir, err) < 0)
        return -1;
    snprintf(out->path, sizeof out->path, "%s/%s_%s_%dx%d_%s.exr", rq->cache_dir, rq->scene->name,
             gib_component_name(rq->component), rq->width, rq->height, key_hex);
    return 0;
}

/* A fresh render (out->image, its stats st) stored as the request's entry: written under a
 * temporary name, renamed, read back and checked. An interrupted render's rounds go beside the
 * entry instead (an error). 0, -1 or GIB_REF_WRITE_FAILED with err; out->image is freed on
 * error. */
static int entry_store(const gib_ref_request *rq, const char *key_hex, const gib_ref_stats *st,
                       gib_ref_result *out, gib_error *err)
{
    gib_ref_params p = gib_ref_request_params(rq);
    gib_kv attrs[GIB_REF_ATTR_COUNT + 1];
    int n = gib_reference_attrs(rq->scene, &p, st, attrs, GIB_REF_ATTR_COUNT);
    n = gib_ref_seal(&out->image, attrs, n, GIB_REF_ATTR_COUNT + 1);
    if (st->interrupted) { /* the rounds done missed the entry's target: kept beside it, not as it */
        out->interrupted = 1;
        char kept[1100];
        snprintf(kept, sizeof kept, "%.*s.interrupted.exr", (int)strlen(out->path) - 4, out->path);
        int wrc = gib_exr_write(kept, &out->image, attrs, n, err);
        gib_image_free(&out->image);
        if (wrc < 0)
            return gib_error_prefix(err, "interrupted, and writing the rounds done to %s", kept);
        return gib_fail(err, "interrupted after %d spp (noise RMSE %.3g, target not reached): "
                             "the rounds done are in %s; no cache entry was written",
                        st->spp, st->noise_rmse, kept);
    }
    /* Write to a temporary name and rename, so an interrupted write never leaves a valid-looking
     * entry behind. */
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s.tmp%d", out->path, (int)getpid());
    if (gib_exr_write(tmp, &out->image, attrs, n, err) < 0 || rename(tmp, out->path) != 0) {
        unlink(tmp);
        gib_image_free(&out->image);
        gib_error_prefix(err, "writing reference cache entry %s", out->path);
        return GIB_REF_WRITE_FAILED;
    }
    remove_dead_writers_temps(out->path);
    if (entry_check_written(out->path, rq, key_hex, err) < 0) {
        gib_image_free(&out->image);
        return -1;
    }
    out->spp = st->spp;
    out->noise_rmse = st->noise_rmse;
    out->seconds = st->seconds;
    if (!rq->quiet)
        fprintf(stderr, "gibench: reference %s %dx%d done in %.1f s, %d spp, noise RMSE %.3g\n",
                gib_component_name(rq->component), rq->width, rq->height, st->seconds, st->spp,
                st->noise_rmse);
    return 0;
}

int gib_reference_get(const gib_ref_request *rq, gib_ref_result *out, gib_error *err)
{
    char key_hex[17];
    if (entry_prepare(rq, out, key_hex, err) < 0)
        return -1;
    if (!rq->force && entry_valid(out->path, rq, key_hex, &out->image, out)) {
        out->from_cache = 1;
        return 0;
    }
    gib_ref_stats st;
    if (!rq->quiet)
        fprintf(stderr, "gibench: rendering reference %s/%s %dx%d at %d spp%s\n", rq->scene->name,
                gib_component_name(rq->component), rq->width, rq->height, rq->spp,
                rq->target_noise > 0 ? " per round, toward the target noise" : "");
    gib_ref_params p = gib_ref_request_params(rq);
    if (gib_reference_render(rq->scene, &p, &out->image, NULL, &st, err) < 0)
        return gib_error_prefix(err, "reference %s/%s", rq->scene->name,
                                gib_component_name(rq->component));
    return entry_store(rq, key_hex, &st, out, err);
}

int gib_reference_get_set(const gib_ref_request *rq, int n, gib_ref_result *out, gib_error *err)
{
    char key_hex[GIB_REF_SET_MAX][17];
    gib_ref_params p[GIB_REF_SET_MAX];
    gib_image img[GIB_REF_SET_MAX] = {{0}};
    gib_ref_stats st[GIB_REF_SET_MAX];
    int miss[GIB_REF_SET_MAX], nmiss = 0, rc = 0;
    if (n < 1 || n > GIB_REF_SET_MAX)
        return gib_fail(err, "reference: a set holds 1 to %d requests, got %d", GIB_REF_SET_MAX,
                        n);
    for (int i = 0; i < n; i++)
        memset(&out[i], 0, sizeof out[i]);
    for (int i = 0; i < n && rc == 0; i++) {
        if (entry_prepare(&rq[i], &out[i], key_hex[i], err) < 0)
            rc = -1;
        else if (!rq[i].force && entry_valid(out[i].path, &rq[i], key_hex[i], &out[i].image,
                                             &out[i]))
            out[i].from_cache = 1;
        else
            p[nmiss] = gib_ref_request_params(&rq[i]), miss[nmiss++] = i;
    }
    if (rc == 0 && nmiss > 0) {
        if (!rq[0].quiet)
            fprintf(stderr, "gibench: rendering %d references of %s together\n", nmiss,
                    rq[0].scene->name);
        p[0].interrupt = NULL; /* a set is not interrupted (reference.h) */
        rc = gib_reference_render_set(rq[0].scene, p, nmiss, img, NULL, st, err);
        if (rc < 0)
            gib_error_prefix(err, "references of %s", rq[0].scene->name);
        for (int k = 0; k < nmiss; k++) {
            out[miss[k]].image = img[k];
            if (rc == 0)
                rc = entry_store(&rq[miss[k]], key_hex[miss[k]], &st[k], &out[miss[k]], err);
        }
    }
    if (rc < 0)
        for (int i = 0; i < n; i++)
            gib_image_free(&out[i].image);
    return rc;
}

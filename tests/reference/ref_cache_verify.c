/* The reference cache reads back each entry right after writing it (harness/app/refcache.c,
 * entry_check_written): an entry whose seal fails then is an error naming the file, so the run's
 * row becomes reference_failed with that message, never an entry that every later request
 * silently renders again. The EXR writer is replaced at link time (-Wl,--wrap=gib_exr_write) by
 * one that can change a pixel on its way to the file, as a writer that corrupts a chunk would.
 * Usage: ref_cache_verify WORKDIR. */
#include "harness/app/app.h"
#include "tests/common/check.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int failures;

static int corrupt_writes; /* 1: the next writes change pixel 0 */

int __real_gib_exr_write(const char *path, const gib_image *img, const gib_kv *attrs, int nattrs,
                         gib_error *err);

/* Writes img, or a copy with pixel 0 changed (the header, seal included, is the original's). */
int __wrap_gib_exr_write(const char *path, const gib_image *img, const gib_kv *attrs, int nattrs,
                         gib_error *err)
{
    if (!corrupt_writes)
        return __real_gib_exr_write(path, img, attrs, nattrs, err);
    size_t n = (size_t)img->width * img->height * img->channels;
    gib_image bad = *img;
    bad.px = malloc(n * sizeof *bad.px);
    memcpy(bad.px, img->px, n * sizeof *bad.px);
    bad.px[0] += 1.0f;
    int rc = __real_gib_exr_write(path, &bad, attrs, nattrs, err);
    free(bad.px);
    return rc;
}

static int get(const gib_ref_request *rq, gib_ref_result *res, gib_error *err)
{
    memset(err, 0, sizeof *err);
    return gib_reference_get(rq, res, err);
}

int main(int argc, char **argv)
{
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/ref_cache_verify_cache", argc > 1 ? argv[1] : ".");
    gib_scene scene;
    gib_error err;
    if (gib_scene_load("cornell", &scene, &err) < 0) {
        CHECK(0, "cannot load cornell: %s", err.msg);
        return 1;
    }
    gib_ref_request rq = {.scene = &scene, .width = 16, .height = 12, .component = GIB_COMP_AO,
                          .spp = 4, .cache_dir = dir, .force = 1, .quiet = 1};
    gib_ref_result res;

    /* A written entry that does not read back as written: an error naming it, not a write
     * failure (that stops a run) and not a success. */
    corrupt_writes = 1;
    int rc = get(&rq, &res, &err);
    CHECK(rc == -1, "a corrupted entry: gib_reference_get returned %d, not -1", rc);
    CHECK(strstr(err.msg, res.path) && strstr(err.msg, "right after it was written") &&
              strstr(err.msg, "its seal"),
          "the error names the entry %s and its seal: '%s'", res.path, err.msg);
    CHECK(res.image.px == NULL, "no image is handed back with the error");
    struct stat st;
    CHECK(stat(res.path, &st) == 0, "the entry %s is left for inspection", res.path);
    printf("corrupted entry: %s\n", err.msg);

    /* A good writer: the request renders over it, and the next reads the entry. */
    corrupt_writes = 0;
    rq.force = 0;
    rc = get(&rq, &res, &err);
    CHECK(rc == 0 && !res.from_cache, "after it, a request renders again (rc %d, '%s')", rc,
          err.msg);
    gib_image_free(&res.image);
    rc = get(&rq, &res, &err);
    CHECK(rc == 0 && res.from_cache, "an entry written well is read from the cache (rc %d, '%s')",
          rc, err.msg);
    gib_image_free(&res.image);

    gib_scene_free(&scene);
    printf("%s\n", failures ? "FAILED" : "ok: an entry that fails its seal when written is an error");
    return failures != 0;
}

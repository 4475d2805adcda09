/* gibench — the reference cache (DESIGN.md, "Reference renderer").
 *
 * An entry is an EXR named by a hash of everything that changes the image: the scene's content hash
 * (scene file, meshes, textures), the camera, size, component, its parameters, spp and the renderer
 * version. Its header repeats those facts; an entry whose header does not match its key, or that
 * cannot be read, is rendered again and overwritten, never used. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../base/hash.h"
#include "app.h"

static uint64_t request_key(const gib_ref_request *rq)
{
    const gib_camera *c = &rq->scene->cameras[rq->camera];
    uint64_t h = gib_hash_str(GIB_HASH_INIT, GIB_REFERENCE_VERSION);
    h = gib_hash_u64(h, rq->scene->content_hash);
    h = gib_hash_bytes(h, c->eye, sizeof c->eye);
    h = gib_hash_bytes(h, c->target, sizeof c->target);
    h = gib_hash_bytes(h, c->up, sizeof c->up);
    h = gib_hash_f32(h, c->vfov_deg);
    h = gib_hash_u64(h, (uint64_t)rq->width << 32 | (uint64_t)rq->height);
    h = gib_hash_u64(h, (uint64_t)rq->component);
    h = gib_hash_u64(h, (uint64_t)rq->spp);
    /* dmax <= 0 and infinity both mean unbounded: one key for the one image. */
    if (rq->component == GIB_COMP_AO)
        h = gib_hash_f32(h, rq->dmax > 0 && isfinite(rq->dmax) ? rq->dmax : INFINITY);
    return h;
}

static int entry_valid(const char *path, const char *key_hex, gib_image *img, gib_ref_result *out)
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
    const char *key = gib_kv_get(attrs, n, "cache_key");
    const char *ver = gib_kv_get(attrs, n, "renderer_version");
    const char *noise = gib_kv_get(attrs, n, "noise_rmse");
    const char *spp = gib_kv_get(attrs, n, "spp");
    const char *secs = gib_kv_get(attrs, n, "seconds");
    int ok = key && ver && noise && spp && !strcmp(key, key_hex) &&
             !strcmp(ver, GIB_REFERENCE_VERSION) && gib_image_count_nonfinite(img) == 0;
    if (ok) {
        out->noise_rmse = strtod(noise, NULL);
        out->spp = (int)strtol(spp, NULL, 10);
        out->seconds = secs ? strtod(secs, NULL) : 0;
    } else {
        fprintf(stderr, "gibench: reference cache entry %s does not match its key; rendering again\n",
                path);
        gib_image_free(img);
    }
    free(attrs);
    return ok;
}

int gib_reference_get(const gib_ref_request *rq, gib_ref_result *out, gib_error *err)
{
    memset(out, 0, sizeof *out);
    char key_hex[17];
    gib_hash_hex(request_key(rq), key_hex);
    if (gib_mkdirs(rq->cache_dir, err) < 0)
        return -1;
    snprintf(out->path, sizeof out->path, "%s/%s_%s_%dx%d_%s.exr", rq->cache_dir, rq->scene->name,
             gib_component_name(rq->component), rq->width, rq->height, key_hex);
    if (!rq->force && entry_valid(out->path, key_hex, &out->image, out)) {
        out->from_cache = 1;
        return 0;
    }
    gib_ref_params p = {.component = rq->component, .width = rq->width, .height = rq->height,
                        .spp = rq->spp, .dmax = rq->dmax, .seed = 1, .threads = 0,
                        .camera = rq->camera, .quiet = 0};
    gib_ref_stats st;
    fprintf(stderr, "gibench: rendering reference %s/%s %dx%d at %d spp\n", rq->scene->name,
            gib_component_name(rq->component), rq->width, rq->height, rq->spp);
    if (gib_reference_render(rq->scene, &p, &out->image, NULL, &st, err) < 0)
        return gib_error_prefix(err, "reference %s/%s", rq->scene->name,
                                gib_component_name(rq->component));
    gib_kv attrs[32];
    int n = gib_reference_attrs(rq->scene, &p, &st, attrs, 31);
    snprintf(attrs[n].key, sizeof attrs[n].key, "cache_key");
    snprintf(attrs[n].value, sizeof attrs[n].value, "%s", key_hex);
    n++;
    /* Write to a temporary name and rename, so an interrupted write never leaves a valid-looking
     * entry behind. */
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s.tmp%d", out->path, (int)getpid());
    if (gib_exr_write(tmp, &out->image, attrs, n, err) < 0 || rename(tmp, out->path) != 0) {
        unlink(tmp);
        return gib_error_prefix(err, "writing reference cache entry %s", out->path);
    }
    out->spp = rq->spp;
    out->noise_rmse = st.noise_rmse;
    out->seconds = st.seconds;
    fprintf(stderr, "gibench: reference done in %.1f s, noise RMSE %.3g\n", st.seconds,
            st.noise_rmse);
    return 0;
}

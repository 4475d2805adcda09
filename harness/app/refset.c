/* gibench — the references a matrix's runs ask for, and each world's rendered together: the
 * requests of one scene at one instant (direct, indirect and glossy of `lrsm` and `vct`; indirect
 * and caustic of the thesis' techniques; each at every size of the profile) are rendered by one
 * gib_reference_render_set, which builds the scene's world once and traces each view's primary
 * rays once, instead of one render per request. Each image is what its render alone gives, bit
 * for bit, stored under the key its request alone has, so prefetching changes no pixel and no
 * key: only the time a run spends on its references. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "refset.h"

int gib_scene_wanted(const gib_scene *s, const gib_technique *t, char *why, size_t len)
{
    if ((s->features & t->scene_needs) != t->scene_needs) {
        char f[256];
        gib_features_str(t->scene_needs & ~s->features, f, sizeof f);
        if (why)
            snprintf(why, len, "scene lacks %s", f);
        return 0;
    }
    if (t->scene_needs_any && !(s->features & t->scene_needs_any)) {
        char f[256];
        gib_features_str(t->scene_needs_any, f, sizeof f);
        if (why)
            snprintf(why, len, "scene has none of %s", f);
        return 0;
    }
    return 1;
}

int gib_matrix_ref_request(const gib_matrix *m, const char *cache, const gib_scene *scene,
                           const gib_matrix_run *mr, unsigned bit, gib_ref_request *rq)
{
    int component = gib_component_parse(gib_output_name(bit));
    *rq = (gib_ref_request){.scene = scene, .camera = m->camera, .width = mr->width,
                            .height = mr->height, .time = (float)mr->time, .component = component,
                            .spp = component >= 0 && m->ref_spp[component]
                                       ? m->ref_spp[component] : 64,
                            .cache_dir = cache};
    gib_ref_request_match(rq, mr->technique, &mr->params, bit);
    return component;
}

int gib_matrix_ref_requests(const gib_matrix *m, const char *cache, const gib_scene *scene,
                            const char *want, gib_ref_request *out, int max)
{
    int n = 0;
    uint64_t keys[1024];
    for (int j = 0; j < m->run_count; j++) {
        const gib_matrix_run *mr = &m->runs[j];
        if (want ? !want[j] : strcmp(mr->scene, scene->name) != 0)
            continue;
        for (unsigned bit = 1; bit <= GIB_OUT_CAUSTIC; bit <<= 1) {
            gib_ref_request rq;
            if (!(mr->technique->components & bit) ||
                gib_matrix_ref_request(m, cache, scene, mr, bit, &rq) < 0)
                continue;
            gib_ref_params p = gib_ref_request_params(&rq);
            uint64_t key = gib_reference_cache_key(scene, &p);
            int seen = 0;
            for (int i = 0; i < n && !seen; i++)
                seen = keys[i] == key;
            if (!seen && n < max && n < (int)(sizeof keys / sizeof keys[0]))
                keys[n] = key, out[n++] = rq;
        }
    }
    return n;
}

int gib_ref_worlds(const gib_ref_request *rq, int n, int *world)
{
    int groups = 0;
    for (int i = 0; i < n; i++) {
        gib_ref_params pi = gib_ref_request_params(&rq[i]), qi;
        gib_reference_normalize(rq[i].scene, &pi, &qi); /* a static scene's instants are one */
        world[i] = -1;
        for (int j = 0; j < i && world[i] < 0; j++) {
            gib_ref_params pj = gib_ref_request_params(&rq[j]), qj;
            gib_reference_normalize(rq[j].scene, &pj, &qj);
            if (rq[j].scene == rq[i].scene && qj.time == qi.time)
                world[i] = world[j];
        }
        if (world[i] < 0)
            world[i] = groups++;
    }
    return groups;
}

/* A set's statistics live together: at most this many bytes of them a set (a 1280x720 image
 * holds ~0.3 GB: per pixel and channel a mean, M2, 8 Sobol batch sums and the light part's). */
#define REFSET_MAX_BYTES (1ull << 30)

/* An upper bound of a request's statistics in bytes. */
static unsigned long long request_bytes(const gib_ref_request *rq)
{
    return (unsigned long long)rq->width * (unsigned long long)rq->height * 3ull * 8ull *
           (4ull + GIB_REF_SOBOL_BATCHES);
}

int gib_ref_each_set(const gib_ref_request *rq, int n, const int *world, int groups,
                     gib_ref_set_fn fn, void *ctx)
{
    int rc = 0;
    for (int g = 0; g < groups && rc == 0; g++) {
        gib_ref_request set[GIB_REF_SET_MAX];
        unsigned long long bytes = 0;
        int k = 0;
        for (int i = 0; i <= n && rc == 0; i++) {
            int in = i < n && world[i] == g;
            if (in && k > 0 && bytes + request_bytes(&rq[i]) > REFSET_MAX_BYTES) {
                rc = fn(ctx, set, k); /* full: this one starts the next set */
                k = 0, bytes = 0;
            }
            if (in && rc == 0)
                set[k++] = rq[i], bytes += request_bytes(&rq[i]);
            if (rc == 0 && k > 0 && (k == GIB_REF_SET_MAX || i == n)) {
                rc = fn(ctx, set, k);
                k = 0, bytes = 0;
            }
        }
    }
    return rc;
}

/* gib_ref_each_set's step of the prefetch: a set of two or more through the cache. */
static int prefetch_set(void *ctx, const gib_ref_request *set, int k)
{
    if (k < 2) /* one request: left to its run */
        return 0;
    gib_ref_result res[GIB_REF_SET_MAX];
    int rc = gib_reference_get_set(set, k, res, ctx);
    for (int j = 0; rc == 0 && j < k; j++)
        gib_image_free(&res[j].image);
    return rc;
}

int gib_reference_prefetch(const gib_ref_request *rq, int n, gib_error *err)
{
    int *world = malloc((size_t)(n > 0 ? n : 1) * sizeof *world);
    uint64_t *key = malloc((size_t)(n > 0 ? n : 1) * sizeof *key);
    if (!world || !key) {
        free(world), free(key);
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "reference prefetch: out of memory");
    }
    int groups = gib_ref_worlds(rq, n, world), rc = 0;
    for (int i = 0; i < n; i++) { /* a key asked twice (two matrices) is rendered once */
        gib_ref_params p = gib_ref_request_params(&rq[i]);
        key[i] = gib_reference_cache_key(rq[i].scene, &p);
        for (int j = 0; j < i && world[i] >= 0; j++)
            if (key[j] == key[i] && world[j] >= 0)
                world[i] = -1;
    }
    rc = gib_ref_each_set(rq, n, world, groups, prefetch_set, err);
    free(key);
    free(world);
    return rc;
}

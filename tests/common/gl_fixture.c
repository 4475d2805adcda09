#include "gl_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "block_stats.h"
#include "harness/app/app.h"
#include "harness/app/runner.h"
#include "reference/reference.h"

int gib_fixture_open(gib_gl_fixture *f, const char *scene_name)
{
    memset(f, 0, sizeof *f);
    gib_error err;
    if (gib_scene_load(scene_name, &f->scene, &err) < 0) {
        fprintf(stderr, "FAIL: set-up: %s\n", err.msg);
        return -1;
    }
    if (gib_gl_init(GIB_BACKEND_AUTO, &f->info, &err) < 0 ||
        gib_gpu_scene_upload(&f->scene, &f->gpu, &err) < 0) {
        fprintf(stderr, "FAIL: set-up: %s\n", err.msg);
        gib_scene_free(&f->scene);
        return -1;
    }
    f->gl_up = 1;
    return 0;
}

int gib_fixture_open_text(gib_gl_fixture *f, const char *dir, const char *name, const char *text)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s.scene", dir, name);
    FILE *file = fopen(path, "w");
    if (!file) {
        printf("FAIL %s: cannot write %s\n", name, path);
        return -1;
    }
    fputs(text, file);
    fclose(file);
    return gib_fixture_open(f, path);
}

/* The references several tests ask for alike come from the harness's reference cache
 * (harness/app/refcache.c) in the folder ctest names in GIB_TEST_REF_CACHE for them; the test
 * fixture_ref_cache_reset empties it before each ctest run, so an entry is this build's. The
 * first test to ask renders and stores the image, the others read it: the pixels a render gives,
 * bit for bit (the render is deterministic for its seed). Without the variable (a test run by
 * hand) every test renders its own. */
static int fixture_cached_reference(const gib_gl_fixture *f, const char *dir,
                                    const gib_ref_params *rp, gib_image *out, gib_ref_stats *st)
{
    gib_ref_request rq = {.scene = &f->scene, .width = rp->width, .height = rp->height,
                          .component = rp->component, .spp = rp->spp, .cache_dir = dir,
                          .quiet = 1};
    gib_ref_result res;
    gib_error err;
    if (gib_reference_get(&rq, &res, &err) < 0) {
        printf("FAIL: reference: %s\n", err.msg);
        return -1;
    }
    if (res.from_cache)
        printf("reference %s %dx%d %d spp (component %d): shared, rendered by another test\n",
               f->scene.name, rp->width, rp->height, rp->spp, rp->component);
    *out = res.image;
    *st = (gib_ref_stats){.spp = res.spp, .noise_rmse = res.noise_rmse,
                          .seconds = res.seconds, .mean = gib_rgb_mean(out)};
    return 0;
}

int gib_fixture_reference(const gib_gl_fixture *f, int component, int w, int h, int spp,
                          gib_image *out, gib_ref_stats *st)
{
    gib_ref_params rp = {.component = component, .width = w, .height = h, .spp = spp, .seed = 1,
                         .quiet = 1};
    gib_ref_stats own;
    if (!st)
        st = &own;
    const char *dir = getenv("GIB_TEST_REF_CACHE");
    if (dir && dir[0])
        return fixture_cached_reference(f, dir, &rp, out, st);
    gib_error err;
    if (gib_reference_render(&f->scene, &rp, out, NULL, st, &err) < 0) {
        printf("FAIL: reference: %s\n", err.msg);
        return -1;
    }
    return 0;
}

int gib_fixture_render(gib_gl_fixture *f, const char *name, const char *const *params, int camera,
                       int w, int h, unsigned component, gib_image *out)
{
    const gib_technique *t = gib_technique_find(name);
    gib_params p;
    gib_error err;
    if (!t) {
        printf("FAIL %s: no such technique\n", name);
        return -1;
    }
    gib_params_default(t, &p);
    for (int i = 0; params && params[i]; i++) {
        char key[64];
        const char *eq = strchr(params[i], '=');
        snprintf(key, sizeof key, "%.*s", eq ? (int)(eq - params[i]) : 0, params[i]);
        if (!eq || gib_param_set(t, &p, key, eq + 1, &err) < 0) {
            printf("FAIL %s: parameter '%s': %s\n", name, params[i], eq ? err.msg : "no '='");
            return -1;
        }
    }
    gib_run_result r;
    gib_run_technique(&f->gpu, t, &p, camera, w, h, 0, 1, &r);
    int rc = -1;
    if (!r.ok)
        printf("FAIL %s: %s: %s\n", name, r.status, r.err.msg);
    for (int o = 0; r.ok && o < r.output_count; o++)
        if (r.output_components[o] == component) { /* taken out of the result */
            *out = r.images[o];
            r.images[o] = (gib_image){0};
            rc = 0;
        }
    if (r.ok && rc < 0)
        printf("FAIL %s: no image of component %u\n", name, component);
    gib_run_result_free(&r);
    return rc;
}

double gib_fixture_render_mean(gib_gl_fixture *f, const char *name, const char *const *params,
                               int camera, int w, int h, unsigned component)
{
    gib_image im;
    if (gib_fixture_render(f, name, params, camera, w, h, component, &im) < 0)
        return -1;
    double m = gib_rgb_mean(&im);
    gib_image_free(&im);
    return m;
}

void gib_fixture_close(gib_gl_fixture *f)
{
    if (f->gl_up) {
        gib_gpu_scene_free(&f->gpu);
        gib_gl_shutdown();
        gib_scene_free(&f->scene);
    }
    f->gl_up = 0;
}

RTCScene gib_fixture_embree(const gib_scene *scene, RTCDevice *device)
{
    *device = rtcNewDevice(NULL);
    RTCScene rs = rtcNewScene(*device);
    RTCGeometry geo = rtcNewGeometry(*device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(geo, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, scene->positions, 0,
                               12, scene->vertex_count);
    rtcSetSharedGeometryBuffer(geo, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, scene->indices, 0, 12,
                               scene->triangle_count);
    rtcCommitGeometry(geo);
    rtcAttachGeometry(rs, geo);
    rtcReleaseGeometry(geo);
    rtcCommitScene(rs);
    return rs;
}

float gib_fixture_trace(RTCScene s, const float o[3], const float d[3])
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = o[0], rh.ray.org_y = o[1], rh.ray.org_z = o[2];
    rh.ray.dir_x = d[0], rh.ray.dir_y = d[1], rh.ray.dir_z = d[2];
    rh.ray.tfar = INFINITY;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(s, &ctx, &rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1.0f : rh.ray.tfar;
}

float gib_fixture_diagonal(const gib_scene *scene)
{
    float d = 0;
    for (int k = 0; k < 3; k++)
        d += (scene->bounds_max[k] - scene->bounds_min[k]) * (scene->bounds_max[k] - scene->bounds_min[k]);
    return sqrtf(d);
}

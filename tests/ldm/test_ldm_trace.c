/* The LDM trace (Aalund et al. 2015, Sec. 3.1) against Embree on the same rays, on the Cornell box.
 *
 * Rays start at random points inside the box and run along +-v of every LDM. An LDM answers for the
 * pixel the origin falls in, i.e. for the ray through that pixel's centre at the origin's depth; so
 * Embree traces from that snapped origin (ldm_snap) and the two must agree to the LDM's depth
 * resolution: depths are float world distances interpolated at pixel centres, exact to ~1e-6 of the
 * scene size; we allow 1e-4 of the diagonal. Rays whose snapped pixel centre lies within float
 * rounding of a triangle edge can see different triangles (rasterisation's tie rules against
 * Embree's watertight test): at most 0.5% of the rays may disagree, and the test prints how many do.
 * Without the snap the error is the LDM's lateral resolution; that is reported, not asserted. */
#include <embree3/rtcore.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "harness/gl/gpu_scene.h"
#include "techniques/ldm/ldm.h"

static uint32_t rng_state = 12345;
static float rnd(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (rng_state >> 8) * (1.0f / 16777216.0f);
}

static float embree_trace(RTCScene s, const float o[3], const float d[3])
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh = {0};
    rh.ray.org_x = o[0], rh.ray.org_y = o[1], rh.ray.org_z = o[2];
    rh.ray.dir_x = d[0], rh.ray.dir_y = d[1], rh.ray.dir_z = d[2];
    rh.ray.tfar = INFINITY;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(s, &ctx, &rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1.0f : rh.ray.tfar;
}

int main(void)
{
    gib_error err;
    gib_gl_info info;
    gib_scene scene;
    gib_gpu_scene gpu;
    if (gib_scene_load("cornell", &scene, &err) < 0 || gib_gl_init(GIB_BACKEND_AUTO, &info, &err) < 0 ||
        gib_gpu_scene_upload(&scene, &gpu, &err) < 0) {
        fprintf(stderr, "FAIL: set-up: %s\n", err.msg);
        return 1;
    }
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    gib_timers timers;
    gib_timers_init(&timers);
    ldm_set l;
    const int N = 32, RES = 256, PER = 200;
    if (ldm_create(&l, &gpu, N, RES, &ledger, &err) < 0) {
        fprintf(stderr, "FAIL: ldm_create: %s\n", err.msg);
        return 1;
    }
    gib_timers_frame_begin(&timers, 0);
    ldm_build(&l, &gpu, &timers);
    gib_timers_frame_end(&timers);
    printf("renderer %s: %d LDMs of %dx%d, %llu nodes (mean depth complexity %.2f), status %s\n",
           info.renderer, l.count, RES, RES, (unsigned long long)l.fragments,
           l.mean_depth_complexity, ldm_status(&l));

    RTCDevice dev = rtcNewDevice(NULL);
    RTCScene rs = rtcNewScene(dev);
    RTCGeometry geo = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(geo, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, scene.positions, 0,
                               12, scene.vertex_count);
    rtcSetSharedGeometryBuffer(geo, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, scene.indices, 0, 12,
                               scene.triangle_count);
    rtcCommitGeometry(geo);
    rtcAttachGeometry(rs, geo);
    rtcReleaseGeometry(geo);
    rtcCommitScene(rs);

    int n = l.count * PER * 2;
    float *rays = malloc(sizeof(float) * 4 * n), *dist = malloc(sizeof(float) * n);
    float *snapped = malloc(sizeof(float) * 3 * n);
    float diag = 0;
    for (int k = 0; k < 3; k++)
        diag += (scene.bounds_max[k] - scene.bounds_min[k]) * (scene.bounds_max[k] - scene.bounds_min[k]);
    diag = sqrtf(diag);
    int m = 0;
    for (int i = 0; i < l.count; i++)
        for (int j = 0; j < PER; j++)
            for (int s = -1; s <= 1; s += 2) {
                float p[3];
                for (int k = 0; k < 3; k++)
                    p[k] = scene.bounds_min[k] + (0.02f + 0.96f * rnd()) * (scene.bounds_max[k] - scene.bounds_min[k]);
                if (!ldm_snap(&l, i, p, snapped + 3 * m))
                    continue;
                rays[4 * m] = p[0], rays[4 * m + 1] = p[1], rays[4 * m + 2] = p[2];
                rays[4 * m + 3] = (float)(s * (i + 1));
                m++;
            }
    if (ldm_probe(&l, rays, m, 0.0f, dist, &ledger, &err) < 0) {
        fprintf(stderr, "FAIL: probe: %s\n", err.msg);
        return 1;
    }
    int agree = 0, hits = 0, lateral_close = 0;
    double texel = 2.0 * l.radius / RES, worst = 0;
    for (int k = 0; k < m; k++) {
        int i = (int)fabsf(rays[4 * k + 3]) - 1;
        float sgn = rays[4 * k + 3] > 0 ? 1.0f : -1.0f;
        float d[3] = {sgn * l.dirs[3 * i], sgn * l.dirs[3 * i + 1], sgn * l.dirs[3 * i + 2]};
        float te = embree_trace(rs, snapped + 3 * k, d);
        float tu = embree_trace(rs, rays + 4 * k, d);
        int ok = (te < 0 && dist[k] < 0) || (te >= 0 && dist[k] >= 0 && fabsf(te - dist[k]) <= 1e-4f * diag);
        agree += ok;
        hits += te >= 0;
        if (ok && te >= 0 && fabs(te - dist[k]) > worst)
            worst = fabs(te - dist[k]);
        lateral_close += (tu < 0 && dist[k] < 0) || (tu >= 0 && dist[k] >= 0 && fabsf(tu - dist[k]) <= 2 * texel);
    }
    double frac = (double)agree / m;
    printf("%d rays (%d hit): %d agree with Embree from the snapped origin (%.3f%%, worst agreeing "
           "difference %.3g = %.2g of the diagonal); from the unsnapped origin %.2f%% are within "
           "2 texels (%.4g)\n", m, hits, agree, 100 * frac, worst, worst / diag,
           100.0 * lateral_close / m, 2 * texel);
    int pass = frac >= 0.995 && hits > m / 2 && !strcmp(ldm_status(&l), "ok");
    printf("%s: LDM trace vs Embree (expect >= 99.5%% agreement to 1e-4 of the diagonal)\n",
           pass ? "PASS" : "FAIL");
    free(rays);
    free(dist);
    free(snapped);
    rtcReleaseScene(rs);
    rtcReleaseDevice(dev);
    ldm_destroy(&l, &ledger);
    gib_timers_destroy(&timers);
    gib_gpu_scene_free(&gpu);
    gib_gl_shutdown();
    gib_scene_free(&scene);
    return pass ? 0 : 1;
}

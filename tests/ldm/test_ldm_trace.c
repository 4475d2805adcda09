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
#include "tests/common/gl_fixture.h"
#include "harness/gl/gpu_scene.h"
#include "techniques/ldm/ldm.h"
#include "tests/common/check.h"

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

static uint32_t rng_state = 12345;
static float rnd(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (rng_state >> 8) * (1.0f / 16777216.0f);
}

int main(void)
{
    gib_error err;
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "cornell") < 0)
        return 1;
    gib_scene *scene_p = &fx.scene;
    gib_gpu_scene *gpu_p = &fx.gpu;
    const gib_gl_info *info_p = &fx.info;
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    gib_timers timers;
    gib_timers_init(&timers);
    ldm_set l;
    const int N = 32, RES = 256, PER = 200;
    if (ldm_create(&l, gpu_p, N, RES, 1.0, 0, &ledger, &err) < 0) {
        CHECK(0, "ldm_create: %s", err.msg);
        return 1;
    }
    gib_timers_frame_begin(&timers, 0);
    ldm_build(&l, gpu_p, &timers);
    gib_timers_frame_end(&timers);
    printf("renderer %s: %d LDMs of %dx%d, %llu nodes (mean depth complexity %.2f), status %s\n",
           info_p->renderer, l.count, RES, RES, (unsigned long long)l.fragments,
           l.mean_depth_complexity, gib_status_name(ldm_status(&l)));

    RTCDevice dev;
    RTCScene rs = gib_fixture_embree(scene_p, &dev);

    int n = l.count * PER * 2;
    float *rays = malloc(sizeof(float) * 4 * n), *dist = malloc(sizeof(float) * n);
    float *snapped = malloc(sizeof(float) * 3 * n);
    float diag = gib_fixture_diagonal(scene_p);
    int m = 0;
    for (int i = 0; i < l.count; i++)
        for (int j = 0; j < PER; j++)
            for (int s = -1; s <= 1; s += 2) {
                float p[3];
                for (int k = 0; k < 3; k++)
                    p[k] = scene_p->bounds_min[k] + (0.02f + 0.96f * rnd()) * (scene_p->bounds_max[k] - scene_p->bounds_min[k]);
                if (!ldm_snap(&l, i, p, snapped + 3 * m))
                    continue;
                rays[4 * m] = p[0], rays[4 * m + 1] = p[1], rays[4 * m + 2] = p[2];
                rays[4 * m + 3] = (float)(s * (i + 1));
                m++;
            }
    if (ldm_probe(&l, rays, m, 0.0f, dist, &ledger, &err) < 0) {
        CHECK(0, "probe: %s", err.msg);
        return 1;
    }
    int agree = 0, hits = 0, lateral_close = 0;
    double texel = 2.0 * l.radius / RES, worst = 0;
    for (int k = 0; k < m; k++) {
        int i = (int)fabsf(rays[4 * k + 3]) - 1;
        float sgn = rays[4 * k + 3] > 0 ? 1.0f : -1.0f;
        float d[3] = {sgn * l.dirs[3 * i], sgn * l.dirs[3 * i + 1], sgn * l.dirs[3 * i + 2]};
        float te = gib_fixture_trace(rs, snapped + 3 * k, d);
        float tu = gib_fixture_trace(rs, rays + 4 * k, d);
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
    CHECK_AT_LEAST("LDM trace vs Embree: share agreeing to 1e-4 of diag.", frac, 0.995,
                   "rays snapped within float rounding of a triangle edge may see another "
                   "triangle (rasterisation's tie rules vs Embree's watertight test)");
    snprintf(check_msg, sizeof check_msg, "%d of %d rays hit, ldm status %d", hits, m,
             (int)ldm_status(&l));
    CHECK_TRUE("LDM trace: more than half the rays hit, status ok",
               hits > m / 2 && ldm_status(&l) == GIB_STATUS_OK, check_msg);
    free(rays);
    free(dist);
    free(snapped);
    rtcReleaseScene(rs);
    rtcReleaseDevice(dev);
    ldm_destroy(&l, &ledger);
    gib_timers_destroy(&timers);
    gib_fixture_close(&fx);
    return failures != 0;
}

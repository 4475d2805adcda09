#include "refrank.h"

#include <math.h>
#include <stdio.h>

#include "harness/imaging/metrics.h"

int gib_ref_spp_to_rank(int spp, double noise_rmse, double rmse, long pixels, int growth)
{
    if (!(noise_rmse > 0.2 * rmse) || !isfinite(rmse))
        return spp;
    gib_rmse_bounds b;
    gib_rmse_interval(rmse, noise_rmse, pixels, &b);
    const double target = GIB_REF_RANK_FRACTION * b.denoised;
    const double factor = target > 0 ? (noise_rmse / target) * (noise_rmse / target) : INFINITY;
    int k = 2;
    while (k < growth && k < factor)
        k *= 2;
    return spp * (k < growth ? k : growth);
}

int gib_reference_to_rank(gib_ref_request *rq, const gib_image *img, float exposure, int growth,
                          gib_ref_result *ref, gib_error *err)
{
    (void)exposure; /* SSIM's alone: the ranking reads the RMSE */
    int grc = gib_reference_get(rq, ref, err);
    gib_metrics m;
    if (grc < 0 || gib_metrics_errors(&ref->image, img, &m, err) < 0 || m.nonfinite)
        return grc;
    int spp = gib_ref_spp_to_rank(rq->spp, ref->noise_rmse, m.rmse, (long)rq->width * rq->height,
                                  growth);
    if (spp == rq->spp)
        return grc;
    printf("    reference %s %dx%d: noise %.3g at %d spp is over a fifth of the row's error %.3g: "
           "scored at %d spp\n", gib_component_name(rq->component), rq->width, rq->height,
           ref->noise_rmse, rq->spp, m.rmse, spp);
    gib_image_free(&ref->image);
    rq->spp = spp;
    return gib_reference_get(rq, ref, err);
}

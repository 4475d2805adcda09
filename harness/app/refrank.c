#include "refrank.h"

#include <math.h>

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

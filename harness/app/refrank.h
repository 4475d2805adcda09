/* gibench — references that can rank their rows: the samples per pixel of the reference a row is
 * scored against, chosen so that the reference's noise is at most a fifth of the row's error
 * (ARCHITECTURE.md, "Data flow of a matrix row").
 *
 * A reference's noise adds its square to the row's expected squared error (metrics.h,
 * gib_rmse_interval), so two rows whose errors differ by less than the noise cannot be ordered by
 * it. A row is scored against the matrix's spp first; where that reference's noise exceeds a fifth
 * of the row's error it asks for more samples: noise falls as 1/sqrt(spp), so spp x
 * (noise / target)^2, rounded up to a power of two times the matrix's spp (so that other rows and
 * matrices asking the same find it cached), at most ref_spp_growth times it. The choice depends on
 * the row's own image and the matrix's reference only, so a row scores the same whichever other
 * rows ran beside it, failed, or were resumed. */
#ifndef GIB_REFRANK_H
#define GIB_REFRANK_H

#include "app.h"

/* How many times the requested samples a reference may grow to rank a row: a matrix's
 * ref_spp_growth when it names none, and gibench render's. */
#define GIB_REF_SPP_GROWTH_DEFAULT 16

/* The noise a reference may have: this fraction of the row's de-noised error, below the fifth (0.2)
 * that ref_noisy tests, because the de-noised error is itself an estimate. */
#define GIB_REF_RANK_FRACTION 0.18

/* The spp to score a row against, given its RMSE against a reference of `spp` samples and noise
 * `noise_rmse` over `pixels` pixels: spp itself when the noise is at most a fifth of the RMSE,
 * else spp x 2^k as above, k >= 1, at most spp x growth. */
int gib_ref_spp_to_rank(int spp, double noise_rmse, double rmse, long pixels, int growth);

/* The reference image img is scored against: rq's, or where its noise is over a fifth of img's
 * error against it, one with more samples (gib_ref_spp_to_rank; rq->spp is set to the samples
 * used, and a line says so). Returns what gib_reference_get returns. */
int gib_reference_to_rank(gib_ref_request *rq, const gib_image *img, float exposure, int growth,
                          gib_ref_result *ref, gib_error *err);

#endif

/* gibench — everything a row reports of a technique image against its reference, computed once:
 * the metrics (metrics.h), LDR-FLIP and HDR-FLIP (flip.h), and the images a row keeps, over the
 * scoring threads (parallel.h). */
#ifndef GIB_SCORE_H
#define GIB_SCORE_H

#include "metrics.h"

/* Returned by gib_score_pair when the metrics are computed but an image cannot be written (a full
 * disk): the caller stops rather than record a row. */
#define GIB_SCORE_WRITE_FAILED (-2)

/* Scores img against ref into *m (gib_metrics_compute, then gib_flip_pair_on's means in m->flip
 * and m->hdrflip) and, where dir is set, writes DIR/NAME_flip.png (the LDR-FLIP map in FLIP's
 * magma, when LDR-FLIP is defined), NAME.exr, NAME.png (the preview at `exposure`) and
 * NAME_error.png. With more than one scoring thread the images are written while the metrics are
 * computed; the numbers are the same whatever the thread count. Returns 0, -1 (err set) when the
 * pair cannot be scored, or GIB_SCORE_WRITE_FAILED (err names the first image, in the order
 * above, that could not be written). */
int gib_score_pair(const gib_image *ref, const gib_image *img, float exposure, const char *dir,
                   const char *name, gib_metrics *m, gib_error *err);

#endif

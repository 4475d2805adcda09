/* The LRSM of a test fixture's scene, for the probe tests (lrsm_layers_probe): the light views at
 * `res` texels, 2 x 2 layers with an overlap of 0.1 (the technique's defaults), partitioned over
 * the scene's bounds, rendered and built. */
#ifndef GIB_TESTS_LRSM_SETUP_H
#define GIB_TESTS_LRSM_SETUP_H

#include <stdio.h>

#include "techniques/lrsm/lrsm.h"
#include "tests/common/gl_fixture.h"

typedef struct lrsm_setup {
    gib_ledger ledger;
    gib_light_views lv;
    lrsm_layers L;
    gib_timers timers;
} lrsm_setup;

/* Prints "FAIL: set-up: ..." and returns -1 on failure. */
static inline int lrsm_setup_build(lrsm_setup *s, gib_gl_fixture *fx, int res)
{
    gib_error err;
    gib_ledger_init(&s->ledger);
    gib_timers_init(&s->timers);
    if (gib_light_views_create(&s->lv, &fx->gpu, res, GIB_LV_PACKED16, "rsm", &s->ledger, &err) < 0 ||
        lrsm_layers_create(&s->L, &s->lv, 2, 2, 0.1f, &s->ledger, &err) < 0) {
        printf("FAIL: set-up: %s\n", err.msg);
        return -1;
    }
    lrsm_layers_partition(&s->L, &s->lv, fx->gpu.scene);
    gib_timers_frame_begin(&s->timers, 0);
    gib_light_views_render(&s->lv, &fx->gpu, &s->timers, "rsm");
    gib_timers_frame_end(&s->timers);
    lrsm_layers_build(&s->L, &s->lv);
    return 0;
}

static inline void lrsm_setup_destroy(lrsm_setup *s)
{
    lrsm_layers_destroy(&s->L, &s->ledger);
    gib_light_views_destroy(&s->lv, &s->ledger);
    gib_timers_destroy(&s->timers);
}

#endif

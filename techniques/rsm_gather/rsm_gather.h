/* gibench technique `rsm_gather` — the frame split in its two halves. */
#ifndef GIB_RSM_GATHER_H
#define GIB_RSM_GATHER_H

#include "techniques/common/vpl.h"

/* G-buffer, light views and VPL extraction. */
void rsm_gather_render_vpls(void *self, const gib_view *view, gib_timers *timers);
/* The gathering pass into `fbo` (view->width x view->height). */
void rsm_gather_gather(void *self, const gib_view *view, gib_timers *timers, unsigned fbo);

#endif

/* gibench technique `multires_ir` — the multi-resolution machinery (the thesis, Sec. 3.2.2,
 * Algorithms 3.1 and 3.2; Nichols, Shopf and Wyman 2009), apart from the VPLs so that tests can
 * run the splitting on a synthetic depth and normal image.
 *
 * One flattened image of all levels (multires_common.glsl: level 0 W x H, level k at x = W,
 * stacked): min-max mips of depth and normal plus the regions' mean position and normal (four
 * RGBA32F images, "mips.*"), a depth-stencil buffer whose stencil marks the valid regions, and the
 * irradiance of every level ("mips.irradiance"). The marking of the valid regions, two ways that
 * give the same regions (one function decides, mr_valid; tests/multires_ir compares both):
 *  stencil = 1, the thesis': a full-screen pass over the flattened image discards the texels of
 *    invalid regions, the rest set stencil 1 ("mips.stencil"); the gathering pass runs with the
 *    stencil test;
 *  stencil = 0: the same pass writes 1 into a mask image ("mips.valid", R8) instead, and the
 *    gathering shader discards where the mask is 0. The default, because llvmpipe's
 *    GL_TIME_ELAPSED queries under-count draws into a framebuffer with a depth-stencil
 *    attachment (a gathering pass reported at a seventh of its wall time: PERFORMANCE.md), so the
 *    stencil path's per-pass times cannot be reported on this machine; on a GPU both are timed.
 * Interpolation always draws into colour-only framebuffers. */
#ifndef GIB_MULTIRES_H
#define GIB_MULTIRES_H

#include "harness/gl/ledger.h"
#include "techniques/common/fullscreen.h"

typedef struct multires {
    int width, height, levels;
    int atlas_w, atlas_h;
    float depth_threshold, normal_chord;
    int use_stencil;
    unsigned lo, hi, mean, nsum, irradiance, stencil, mask, fbo, fbo_mask, fbo_color;
    unsigned mips_program;
    gib_fullscreen split, gather, upsample, resolve; /* passes over the flattened image */
} multires;

/* depth_threshold: relative depth range that splits; normal_deg: the angle whose chord bounds a
 * normal component's range. `gather_defines` builds the gathering program (NULL: no gathering, for
 * tests of the splitting alone). */
int multires_create(multires *m, int width, int height, int levels, float depth_threshold,
                    float normal_deg, int use_stencil, int with_gather, gib_ledger *ledger,
                    gib_error *err);
/* Atlas rectangle of level k: x, y, w, h (regions). */
void multires_rect(const multires *m, int k, int rect[4]);
/* Min-max mips from the G-buffer textures (position: xyz, w = 1 on a surface; normal: xyz) seen
 * from `eye`, then the stencil marking of the valid regions. */
void multires_split(multires *m, unsigned position_tex, unsigned normal_tex, const float eye[3]);
/* The gathering pass over the valid regions (the VPLs and their count bound by the caller). */
void multires_gather(multires *m, int vpl_count, float eps);
/* Interpolation from the coarsest level to level 1, then the resolve into `fbo` (W x H) with the
 * G-buffer's albedo on GIB_UNIT_GBUF_ALBEDO: L = rho/pi E. */
void multires_upsample(multires *m, unsigned fbo, const float eye[3]);
/* The marks of the flattened image, stencil or mask (atlas_w x atlas_h bytes, 1 where valid, row 0
 * at the bottom). */
void multires_read_valid(const multires *m, unsigned char *out);
/* Valid regions per level counted from the marks (counts[levels]); returns the total. */
long multires_count_valid(const multires *m, long *counts);
void multires_destroy(multires *m, gib_ledger *ledger);

#endif

/* gibench — matrix files: scenes x techniques x parameter lists x sizes, with profiles.
 *
 *   [matrix]
 *   description = what this matrix reproduces
 *   scenes = cornell, plane_box
 *   techniques = direct
 *   sizes = 256x256, 512x512
 *   camera = 0
 *   frames = 10            ; timed frames per run
 *   warmup = 3
 *   times = 0, 0.5         ; instants (s) the images show, for scenes that move (default 0)
 *   dt = 0.0167            ; frames before the last are dt apart (default 0: all at the instant)
 *   sequence = 8           ; score the last 8 frames of one run, each against the reference at its
 *                          ; instant, and what changes between them (default 1: the last frame)
 *   ref_spp_direct = 4     ; reference samples per pixel, per component (ref_spp_<component>)
 *   ref_spp_ao = 256
 *   ref_spp_growth = 16    ; a reference too noisy to rank its rows gets up to 16x those samples
 *   [params.direct]        ; comma-separated lists; the cross product is run
 *   shadow_res = 512, 1024
 *   [scene_scale]          ; optional: a scene's length parameters (dmax: GIB_PARAM_LENGTH)
 *   hard_tiny = 0.0018     ; are the lists' values times this, so a scaled twin runs the same test
 *   [profile.quick]        ; overrides for --profile quick: any [matrix] key, and TECH.PARAM lists
 *   sizes = 128x128
 *   direct.shadow_res = 256
 *   [external.myrenderer]  ; another program as a technique (external.h: command, version,
 *   command = ./render.sh  ; components, timeout_s); its rows are ext:myrenderer
 *
 * Parsing expands and validates everything (names, parameter ranges, sizes) before any rendering;
 * errors name the file and line. */
#ifndef GIB_MATRIX_H
#define GIB_MATRIX_H

#include "techniques/technique.h"
#include "external.h"

#define GIB_MATRIX_MAX_LIST 32
#define GIB_MATRIX_MAX_COMPONENTS 16
#define GIB_MATRIX_MAX_SEQUENCE 64

typedef struct gib_matrix_run {
    char scene[64];
    const gib_technique *technique;
    gib_params params;
    char params_key[512];   /* "pcf=1;shadow_res=512" in spec order: identifies the run in CSV */
    int width, height;
    double time;            /* the instant the image shows (seconds) */
} gib_matrix_run;

typedef struct gib_matrix {
    char name[64];          /* file name without .matrix */
    char path[1024];
    char profile[32];
    char description[512];
    int camera, frames, warmup;
    double dt;              /* seconds between frames (the last at the run's time) */
    int sequence;           /* frames read back and scored, the last at the run's time (1: only
                               the last; above 1 the runs table has the sequence columns) */
    int ref_spp[GIB_MATRIX_MAX_COMPONENTS]; /* by enum gib_component; 0 = not set */
    int ref_spp_growth;     /* the most a reference's spp is multiplied by so that its noise is at
                               most a fifth of the smallest error it scores (1: never) */
    gib_matrix_run *runs;
    int run_count;
    gib_external *externals;   /* its [external.NAME] sections; runs point at their descriptors */
    int external_count;
} gib_matrix;

/* The external technique whose descriptor t is, or NULL for a built-in or a plugin's. */
const gib_external *gib_matrix_external(const gib_matrix *m, const gib_technique *t);

int gib_matrix_load(const char *path, const char *profile, gib_matrix *m, gib_error *err);
void gib_matrix_free(gib_matrix *m);

/* "name=value;..." of a parameter set, in spec order. */
void gib_params_key(const gib_technique *t, const gib_params *p, char *out, int out_len);

#endif

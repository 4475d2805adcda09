/* gibench — the results schema, defined once (ARCHITECTURE.md, "Matrices, CSV and reproduction"):
 * the columns of a matrix's runs table (DIR/<matrix>.csv) and passes table
 * (DIR/<matrix>_passes.csv), which of them make a row's identity and a run's, and the names of a
 * row's images. `gibench run` writes its rows from these tables, `gibench merge` finds its keys
 * by them, and `gibench schema` exports them as JSON (the build writes it to build/schema.json),
 * which harness/reporting/schema.py reads for every report script.
 *
 * A runs table holds the base columns below, then one column per technique parameter that the
 * matrix file names ([params.T] keys, [profile.P] T.key overrides), in registry order; every
 * parameter of the run is in `params` ("name=value;..." in the technique's spec order) whatever
 * the wide columns, so a parameter added to a technique changes no existing matrix's header. */
#ifndef GIB_SCHEMA_H
#define GIB_SCHEMA_H

#include <stddef.h>
#include <stdio.h>

#include "harness/base/error.h"
#include "matrix.h"

#define GIB_KEY_ROW 1u /* part of a row's identity: a table holds each identity once (resume) */
#define GIB_KEY_RUN 2u /* part of a run's identity: a run's rows (one a component) and its passes */
#define GIB_KEY_RR (GIB_KEY_ROW | GIB_KEY_RUN)

/* X(id, name, kind, key flags, what the column holds). Kinds: text, int, real. */
#define GIB_RUN_COLUMNS(X)                                                                         \
    X(MATRIX, "matrix", "text", 0, "the matrix file's name")                                       \
    X(PROFILE, "profile", "text", GIB_KEY_RR, "the matrix profile run (quick, paper)")             \
    X(SCENE, "scene", "text", GIB_KEY_RR, "the scene")                                             \
    X(CAMERA, "camera", "int", GIB_KEY_ROW, "the scene camera's index")                            \
    X(TECHNIQUE, "technique", "text", GIB_KEY_RR, "the technique")                                 \
    X(COMPONENT, "component", "text", GIB_KEY_ROW, "the output component scored (ao, direct...)")  \
    X(PARAMS, "params", "text", GIB_KEY_RR, "every parameter, name=value;... in spec order")       \
    X(WIDTH, "width", "int", GIB_KEY_RR, "image width")                                            \
    X(HEIGHT, "height", "int", GIB_KEY_RR, "image height")                                         \
    X(TIME, "time", "real", GIB_KEY_RR, "the instant the image shows (s)")                         \
    X(WARMUP, "warmup", "int", 0, "warm-up frames")                                                \
    X(FRAMES, "frames", "int", 0, "timed frames")                                                  \
    X(DT, "dt", "real", 0, "seconds between frames")                                               \
    X(GPU_MED, "gpu_ms_median", "real", 0, "GPU ms a frame, median of the timed frames")           \
    X(GPU_MIN, "gpu_ms_min", "real", 0, "GPU ms, least")                                           \
    X(GPU_MAX, "gpu_ms_max", "real", 0, "GPU ms, greatest")                                        \
    X(GPU_IQR, "gpu_ms_iqr", "real", 0, "GPU ms, interquartile range")                             \
    X(CPU, "cpu_ms", "real", 0, "CPU ms a frame, median")                                          \
    X(CPU_IQR, "cpu_ms_iqr", "real", 0, "CPU ms, interquartile range")                             \
    X(FIRST_FRAME, "first_frame_ms", "real", 0, "wall ms from create to the first image")          \
    X(FIRST_GPU, "first_frame_gpu_ms", "real", 0, "GPU ms of the cold first frame")                \
    X(MEM, "mem_bytes", "int", 0, "peak bytes of the technique's ledger")                          \
    X(MEM_STRUCT, "mem_by_structure", "text", 0, "structure=bytes;... allocated")                  \
    X(MEM_PLANNED, "mem_planned_by_structure", "text", 0,                                          \
      "structure=bytes;... planned, filled even when create() failed for lack of memory")          \
    X(SCENE_MEM, "scene_mem_bytes", "int", 0, "peak bytes of the scene's ledger")                  \
    X(DRIVER_MEM, "driver_mem_bytes", "int", 0, "what the driver says the run took")               \
    X(RMSE, "rmse", "real", 0, "RMSE against the reference")                                       \
    X(REL_RMSE, "rel_rmse", "real", 0, "RMSE over the reference's mean")                           \
    X(MEAN_RATIO, "mean_ratio", "real", 0, "the image's mean over the reference's")                \
    X(BLACK_RMSE, "black_rmse", "real", 0, "what an all-black image scores")                       \
    X(OVER_BLACK, "rmse_over_black", "real", 0, "rmse / black_rmse")                               \
    X(RMSE_DENOISED, "rmse_denoised", "real", 0, "RMSE with the reference's noise taken out")      \
    X(RMSE_LO, "rmse_lo", "real", 0, "its 95% interval, low end")                                  \
    X(RMSE_HI, "rmse_hi", "real", 0, "its 95% interval, high end")                                 \
    X(PSNR, "psnr", "real", 0, "PSNR (dB)")                                                        \
    X(SSIM, "ssim", "real", 0, "SSIM")                                                             \
    X(FLIP, "flip", "real", 0, "mean FLIP")                                                        \
    X(HDRFLIP, "hdrflip", "real", 0, "mean HDR-FLIP")                                              \
    X(NONFINITE, "nonfinite", "int", 0, "NaN/Inf values in the image")                             \
    X(REF_SPP, "ref_spp", "int", 0, "the reference's samples per pixel")                           \
    X(REF_NOISE, "ref_noise_rmse", "real", 0, "the reference's own noise (RMSE)")                  \
    X(REF_NOISY, "ref_noisy", "int", 0, "1: the reference's noise is over a fifth of the error")   \
    X(STATUS, "status", "text", 0, "ok, out_of_memory, create_failed, ...")                        \
    X(MESSAGE, "message", "text", 0, "why a row is not ok")                                        \
    X(COUNTERS, "counters", "text", 0, "the technique's counters, name=value;...")                 \
    X(IMAGE, "image", "text", 0, "the row's image name in DIR/images/<matrix>/ (image_name)")      \
    X(REF_IMAGE, "ref_image", "text", 0, "the reference's preview beside it")                      \
    X(BACKEND, "backend", "text", 0, "egl or osmesa")                                              \
    X(RENDERER, "renderer", "text", 0, "the GL renderer string")                                   \
    X(GL_VERSION, "gl_version", "text", 0, "the GL version string")                                \
    X(GIT, "git_revision", "text", 0, "the source revision built")                                 \
    X(TECH_HASH, "technique_hash", "text", 0, "hash of the technique's sources (source_hash.py)")  \
    X(TIMESTAMP, "timestamp", "text", 0, "when the row was written (UTC)")

/* The sequence columns: after the base columns, only in the table of a matrix with `sequence` above
 * 1 (so no other table's header changes). The row's base metrics are its last frame's; these
 * score the whole sequence (ARCHITECTURE.md, "Metrics": "Temporal error"). */
#define GIB_SEQ_COLUMNS(X)                                                                         \
    X(SEQUENCE, "sequence", "int", 0, "frames scored, the last at time, dt apart")                 \
    X(SEQ_RMSE_MEAN, "seq_rmse_mean", "real", 0, "RMSE of each frame against its instant's "       \
      "reference, mean over the frames")                                                           \
    X(SEQ_RMSE_WORST, "seq_rmse_worst", "real", 0, "that RMSE at the worst frame")                 \
    X(SEQ_WORST_FRAME, "seq_worst_frame", "int", 0, "the worst frame's index (0: the first)")      \
    X(SEQ_DENOISED_MEAN, "seq_rmse_denoised_mean", "real", 0, "rmse_denoised, mean over frames")   \
    X(T_RMSE, "temporal_rmse", "real", 0, "RMSE of the frame-to-frame differences against the "    \
      "reference's")                                                                               \
    X(T_DENOISED, "temporal_rmse_denoised", "real", 0, "temporal_rmse with the references' noise " \
      "taken out (twice a frame's noise variance)")                                                \
    X(T_PEAK, "temporal_peak", "real", 0, "the worst pixel's temporal RMSE")                       \
    X(T_FROZEN, "temporal_frozen", "real", 0, "what a sequence that never changes scores")         \
    X(T_FLIP, "temporal_flip", "real", 0, "mean over frame pairs of |FLIP(T_k,T_k+1) - "           \
      "FLIP(R_k,R_k+1)|")                                                                          \
    X(T_REF_NOISE, "seq_ref_noise_rmse", "real", 0, "the references' noise, RMS over the frames")

#define GIB_PASS_COLUMNS(X)                                                                        \
    X(MATRIX, "matrix", "text", 0, "the matrix file's name")                                       \
    X(PROFILE, "profile", "text", GIB_KEY_RR, "the matrix profile run")                            \
    X(SCENE, "scene", "text", GIB_KEY_RR, "the scene")                                             \
    X(TECHNIQUE, "technique", "text", GIB_KEY_RR, "the technique")                                 \
    X(PARAMS, "params", "text", GIB_KEY_RR, "every parameter, name=value;...")                     \
    X(WIDTH, "width", "int", GIB_KEY_RR, "image width")                                            \
    X(HEIGHT, "height", "int", GIB_KEY_RR, "image height")                                         \
    X(TIME, "time", "real", GIB_KEY_RR, "the instant the image shows (s)")                         \
    X(PASS, "pass", "text", GIB_KEY_ROW, "the pass's name")                                        \
    X(MEDIAN, "ms_median", "real", 0, "GPU ms of the pass, median of the timed frames")            \
    X(MIN, "ms_min", "real", 0, "least")                                                           \
    X(MAX, "ms_max", "real", 0, "greatest")                                                        \
    X(IQR, "ms_iqr", "real", 0, "interquartile range")                                             \
    X(FIRST, "ms_first", "real", 0, "the cold first frame's")                                      \
    X(KIND, "kind", "text", 0, "raster, compute, both or none: what its counted work ran")         \
    X(VERTICES, "vertices", "int", 0, "vertices submitted in the counting frame")                  \
    X(PRIMITIVES, "primitives", "int", 0, "primitives submitted in the counting frame")            \
    X(FRAGMENTS, "fragment_invocations", "int", 0, "fragment shader invocations, counting frame")  \
    X(COMPUTE, "compute_invocations", "int", 0, "compute shader invocations, counting frame")      \
    X(RENDERER, "renderer", "text", 0, "the GL renderer string")                                   \
    X(GIT, "git_revision", "text", 0, "the source revision built")

#define GIB_COL_ENUM(id, name, kind, key, doc) GIB_C_##id,
enum gib_run_column { GIB_RUN_COLUMNS(GIB_COL_ENUM) GIB_C_COUNT };
#undef GIB_COL_ENUM
#define GIB_COL_ENUM(id, name, kind, key, doc) GIB_P_##id,
enum gib_pass_column { GIB_PASS_COLUMNS(GIB_COL_ENUM) GIB_P_COUNT };
#undef GIB_COL_ENUM
/* A sequence column's index in its table is GIB_C_COUNT + GIB_S_*. */
#define GIB_COL_ENUM(id, name, kind, key, doc) GIB_S_##id,
enum gib_seq_column { GIB_SEQ_COLUMNS(GIB_COL_ENUM) GIB_S_COUNT };
#undef GIB_COL_ENUM

typedef struct gib_column {
    const char *name, *kind;
    unsigned key; /* GIB_KEY_* */
    const char *doc;
} gib_column;

extern const gib_column gib_run_columns[GIB_C_COUNT];
extern const gib_column gib_pass_columns[GIB_P_COUNT];
extern const gib_column gib_seq_columns[GIB_S_COUNT];

/* The indices of the columns whose key has `flag`, in table order; returns their count. */
int gib_schema_key(const gib_column *cols, int ncols, unsigned flag, int *out, int max);

/* A matrix's runs table: the base columns, the sequence columns where the matrix scores sequences,
 * then the parameters the matrix file names. */
#define GIB_TABLE_MAX_COLS 128
typedef struct gib_table_layout {
    const char *names[GIB_TABLE_MAX_COLS];
    int count;
} gib_table_layout;

/* The layout of m's table (m from gib_matrix_load: its file is read again for the parameter
 * names it gives). A layout over GIB_TABLE_MAX_COLS is an error naming the parameter that does
 * not fit, never a column dropped. */
int gib_table_layout_of(const gib_matrix *m, gib_table_layout *l, gib_error *err);

/* The name (no extension) of a row's images in DIR/images/<matrix>/: the short template, or the
 * long one (its parameters as their hash) where the name would pass file-name limits. */
void gib_image_name(const char *scene, const char *technique, const char *params, int width,
                    int height, double time, const char *component, char *out, size_t len);

/* The schema as one JSON object (harness/reporting/schema.py reads it). */
void gib_schema_write_json(FILE *f);
int gib_cmd_schema(int argc, char **argv);

#endif

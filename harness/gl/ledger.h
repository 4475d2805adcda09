/* gibench — the GPU memory ledger. Every buffer and texture a technique (or a shared pass)
 * allocates goes through these helpers, so the memory column of a result row is the sum of what was
 * really allocated, by label, with exact mip-chain sizes (ARCHITECTURE.md, "The technique contract"). */
#ifndef GIB_LEDGER_H
#define GIB_LEDGER_H

#include <stdint.h>

#include "harness/base/error.h"

#define GIB_LEDGER_MAX 128
#define GIB_LEDGER_PLAN_MAX 16

typedef struct gib_ledger_entry {
    char label[64];
    unsigned name;       /* GL object name */
    int is_texture;
    uint64_t bytes;
} gib_ledger_entry;

typedef struct gib_ledger {
    gib_ledger_entry entries[GIB_LEDGER_MAX];
    int count;
    uint64_t current_bytes, peak_bytes;
    /* > 0: an allocation that would take current_bytes over it is refused with an "out of memory"
     * error, as a driver's GL_OUT_OF_MEMORY would be: the runner sets it from the environment's
     * GIBENCH_GPU_BUDGET_BYTES, so tests can exhaust "GPU memory" on any machine. */
    uint64_t budget_bytes;
    /* What a technique planned before allocating (gib_ledger_plan): kept whether or not the
     * allocations then succeed, so a row refused for memory still says what it would have taken. */
    gib_ledger_entry planned[GIB_LEDGER_PLAN_MAX];
    int planned_count;
} gib_ledger;

void gib_ledger_init(gib_ledger *l);

/* glCreateBuffers + glNamedBufferStorage(bytes, data, flags). Returns the buffer name or 0 with
 * err set (GL_OUT_OF_MEMORY, or a full ledger). */
unsigned gib_gpu_buffer(gib_ledger *l, const char *label, uint64_t bytes, const void *data,
                        unsigned flags, gib_error *err);

/* glCreateTextures(target) + glTextureStorage{2D,3D}: width x height x layers (layers = 1 for
 * GL_TEXTURE_2D, 6 for GL_TEXTURE_CUBE_MAP) with `levels` mip levels (0 = the full chain). The
 * ledger counts every level's exact size. */
unsigned gib_gpu_texture(gib_ledger *l, const char *label, unsigned target, int width, int height,
                         int layers, unsigned internal_format, int levels, gib_error *err);
/* The bytes gib_gpu_texture counts for these arguments, without allocating anything: the plan a
 * technique checks against a memory budget before it allocates (and Table 2's exact figures). */
uint64_t gib_texture_bytes(unsigned target, int width, int height, int layers,
                           unsigned internal_format, int levels);
/* A renderbuffer (depth attachments). */
unsigned gib_gpu_renderbuffer(gib_ledger *l, const char *label, unsigned internal_format, int width,
                              int height, gib_error *err);

/* Records that the technique plans `bytes` for `label` (nothing is allocated): the plan a technique
 * checks against a memory budget, reported in the row even when the check refuses it. A label
 * planned again replaces its bytes; past GIB_LEDGER_PLAN_MAX labels the rest are summed under
 * "other". */
void gib_ledger_plan(gib_ledger *l, const char *label, uint64_t bytes);

/* Deletes the GL object and removes its entry. */
void gib_gpu_free(gib_ledger *l, unsigned name, int is_texture);
/* Deletes everything still in the ledger. */
void gib_ledger_release_all(gib_ledger *l);

/* Bytes per texel of the internal formats gibench uses; 0 for an unknown format. */
unsigned gib_format_bytes(unsigned internal_format);
/* Full mip chain length for a size. */
int gib_mip_levels(int width, int height, int depth);

/* "label=bytes;label=bytes" summed by label, for the CSV. */
void gib_ledger_summary(const gib_ledger *l, char *out, int out_len);
/* The same summed by structure, the part of a label before its first '.' ("voxels=...;rsm=..."):
 * the CSV's mem_by_structure (the LRSM paper's Table 2 is per structure). */
void gib_ledger_structures(const gib_ledger *l, char *out, int out_len);
/* The plan (gib_ledger_plan) summed by structure, as gib_ledger_structures: the CSV's
 * mem_planned_by_structure; "" when nothing was planned. */
void gib_ledger_planned_structures(const gib_ledger *l, char *out, int out_len);

#endif

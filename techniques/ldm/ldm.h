/* gibench — layered depth maps (LDMs) as pre-sorted per-pixel singly linked lists, one orthographic
 * LDM per deterministic direction (Aalund, Frisvad, Bærentzen 2015, Sec. 3 and 3.2; construction as
 * in [LHL14]: insertion into depth order during a single pass over the geometry, with the atomics of
 * core GL 4.5 — atomicAdd for node allocation, atomicCompSwap to link). Shared by ldm_ao and
 * ldm_indirect; the trace of Sec. 3.1 is techniques/ldm/ldm_trace.glsl.
 *
 * Memory: per LDM, res^2 heads (uint) and one node (depth, next: 8 bytes) per fragment. The node
 * counts are measured at create by a counting pass over the same geometry (and again every frame
 * when the scene moves, growing the pages when needed: ldm_build's pass "ldm_count"); each
 * frame's construction checks every allocation against that capacity, and an
 * overflow is reported through ldm_status() — the row's status — never rendered silently wrong.
 * Nodes are split over "pages" (SSBOs) no larger than GL_MAX_SHADER_STORAGE_BLOCK_SIZE (128 MiB on
 * llvmpipe); a pass that traces LDMs runs once per page.
 * The plan: once the counting pass has measured the node counts, and before any page is allocated,
 * ldm_create records what the LDMs will take in the ledger (gib_ledger_plan, structure "ldm":
 * heads, nodes, info, counters, status, exactly what the ledger then counts) and holds it against
 * a budget; over it, create fails with GIB_ERR_OUT_OF_MEMORY having allocated only the counting
 * pass's own info, counters and status (part of the plan, freed by ldm_destroy). */
#ifndef LDM_H
#define LDM_H

#include "harness/gl/gpu_scene.h"
#include "harness/gl/timers.h"
#include "techniques/technique.h"

#define LDM_MAX_PAGES 64

typedef struct ldm_page {
    int first, count;        /* LDMs [first, first+count) live in this page */
    unsigned heads, nodes;   /* SSBOs, bound to 4 and 5 while this page is used */
    uint64_t node_capacity;
} ldm_page;

/* Bytes of each LDM buffer, as the ledger counts them once allocated. */
typedef struct ldm_plan {
    uint64_t heads, nodes, info, counters, status, total;
} ldm_plan;

typedef struct ldm_set {
    int count;               /* number of LDMs (directions) */
    int res;                 /* each LDM is res x res */
    float *dirs;             /* 3 per LDM: the view direction v (depth grows along v) */
    float center[3], radius; /* bounding sphere the maps cover */
    unsigned info;           /* SSBO binding 3: per-LDM basis, origin, offsets, capacity */
    unsigned status;         /* SSBO binding 6: [0] overflowing fragments, [1] contended inserts */
    unsigned counters;       /* SSBO binding 7: per-LDM node allocation counters */
    unsigned fbo, build_program, count_program;
    int page_count;
    ldm_page pages[LDM_MAX_PAGES];
    uint64_t *capacity;      /* nodes per LDM the pages hold */
    int moving;              /* the scene moves: counts are measured again every frame */
    double node_budget;
    gib_ledger *ledger;      /* where pages are reallocated when a moving scene needs more */
    uint64_t fragments;      /* total nodes (measured at create) */
    double mean_depth_complexity;
    ldm_plan plan;           /* what create planned (and, within the budget, allocated) */
    gib_status state;         /* GIB_STATUS_OK, or ALLOC_FAILED from the last build */
} ldm_set;

/* Builds the direction set, measures node counts, plans, allocates heads and nodes through the
 * ledger (labels "ldm.heads", "ldm.nodes"). node_budget scales the measured node counts into the
 * capacity (1: exact; below 1 caps memory, and the fragments that do not fit are reported as
 * status `overflow`). budget_bytes > 0: a plan over it fails with GIB_ERR_OUT_OF_MEMORY before
 * any page is allocated (0: no limit but the driver's). */
int ldm_create(ldm_set *l, const gib_gpu_scene *scene, int directions, int res, double node_budget,
               uint64_t budget_bytes, gib_ledger *ledger, gib_error *err);
/* The plan of l's LDMs with capacity[i] nodes for LDM i, in pages of at most `limit` bytes (what
 * ldm_create allocates with GL_MAX_SHADER_STORAGE_BLOCK_SIZE as the limit). */
void ldm_plan_bytes(const ldm_set *l, const uint64_t *capacity, uint64_t limit, ldm_plan *plan);
/* Constructs every LDM for this frame (pass "ldm_build"). */
void ldm_build(ldm_set *l, const gib_gpu_scene *scene, gib_timers *timers);
/* Binds page p's heads and nodes (bindings 4, 5) and the info SSBO (3). */
void ldm_bind_page(const ldm_set *l, int page);
/* "ok", "overflow" or "contention", read back from the GPU (call after rendering). */
gib_status ldm_status(ldm_set *l);
void ldm_destroy(ldm_set *l, gib_ledger *ledger);

/* Validation: traces n rays (4 floats each: origin xyz, w = +-(LDM index + 1) for direction +-v)
 * through the built LDMs; dist[k] = distance to the first surface beyond eps, or -1. */
int ldm_probe(ldm_set *l, const float *rays, int n, float eps, float *dist, gib_ledger *ledger,
              gib_error *err);
/* The LDM's pixel-centre snap of a point: the origin a ray from p along LDM i really starts from
 * (same depth, lateral position moved to the centre of p's LDM pixel). Returns 0 outside the map. */
int ldm_snap(const ldm_set *l, int i, const float p[3], float out[3]);
#endif

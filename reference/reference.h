/* gibench — the reference renderer: an Embree 3 path tracer with one estimator per
 * light-transport component (ao, direct, indirect, glossy, caustic, full, higher, and the auxiliary
 * albedo, normal and depth images), deterministic, reporting its own noise. What each component
 * counts, the strategies and pixel footprints, the sky, determinism, noise and texture filtering:
 * ARCHITECTURE.md, "Reference renderer". */
#ifndef GIB_REFERENCE_H
#define GIB_REFERENCE_H

#include <stdatomic.h>
#include <stdio.h>
#include "harness/imaging/image.h"
#include "scenes/scene.h"

/* Bumped whenever an estimator, the sampling or the seeding changes (the cache keys on it). A
 * change confined to some components is keyed for those alone instead, so that every other
 * image keeps its key (the cached references and the committed rows' reference names): full and
 * higher's light vertices hash their strategies into their keys (gib_reference_params_hash; camera
 * paths alone hash as before) and write `strategies` into the EXR header. */
#define GIB_REFERENCE_VERSION "gibench-ref-6" /* 6: Owen-scrambled Sobol camera samples, noise from
                                                * independently scrambled batches */

enum gib_component {
    GIB_COMP_AO = 0,
    GIB_COMP_DIRECT = 1,
    GIB_COMP_INDIRECT = 2,
    GIB_COMP_GLOSSY = 3,
    GIB_COMP_CAUSTIC = 4,
    GIB_COMP_FULL = 5,
    GIB_COMP_HIGHER = 6,
    GIB_COMP_ALBEDO = 7,  /* rho_d at the visible point (filtered texture times albedo) */
    GIB_COMP_NORMAL = 8,  /* viewer-facing shading normal, world space, components in [-1, 1] */
    GIB_COMP_DEPTH = 9,   /* view-space depth (distance along the camera's forward axis) */
    GIB_COMP_COUNT
};

const char *gib_component_name(int component);
/* Returns the enum value, or -1 for an unknown name. */
int gib_component_parse(const char *name);
/* 1 when the component's estimator uses no random numbers for this scene (direct with its delta
 * lights in a scene without a sky, the auxiliary images, and components that are identically 0 in
 * the scene, e.g. glossy without specular materials): its standard error is exactly 0 and one
 * sample is the answer. With a sky, direct samples the sky at random and needs spp >= 2. */
int gib_component_deterministic(const gib_scene *scene, int component);

/* Parameter defaults, used where a field is 0. */
#define GIB_REF_DEFAULT_MAX_DEPTH 8
#define GIB_REF_DEFAULT_MIN_DEPTH 3
#define GIB_REF_DEFAULT_MAX_SPECULAR 1
#define GIB_REF_DEFAULT_MAX_SPP 65536

/* The camera samples' numbers (reference/sampler.h). SOBOL, the default: Owen-scrambled Sobol
 * points (Burley 2020), each pixel's samples dealt round-robin into GIB_REF_SOBOL_BATCHES batches
 * with independent scrambles. The noise reported (noise_rmse, the standard-error image) is then
 * the spread of the batch means: sqrt(sum_b (m_b - m)^2 / (B (B - 1))) per pixel and channel, B
 * batches of equal size (spp is rounded up to a multiple of B above B; below, each sample is its
 * own batch). The spread of single samples would overstate a low-discrepancy estimator's error
 * (its samples are not independent); independent scrambles make the batch means independent and
 * unbiased, so theirs is an honest estimate (randomised quasi-Monte Carlo replicates).
 * RANDOM: independent PCG32 numbers per sample, the noise from the samples' own variance (the
 * renderer before version 6, bit for bit). The light-tracing passes (mirrors) use PCG32 with
 * either; their passes are independent and their variance is added as before. */
enum { GIB_REF_SAMPLER_DEFAULT = 0, GIB_REF_SAMPLER_SOBOL = 1, GIB_REF_SAMPLER_RANDOM = 2 };

/* The strategies of full and higher (reference/ref_connect.c, ref_pilot.c). CAMERA: camera paths
 * with next-event estimation alone, the estimator before light vertices, bit for bit (and its
 * cache key). LIGHT_VERTICES: also a light vertex per sample connected to every camera vertex,
 * weighted by multiple importance sampling. AUTO, the default: a pilot (a sixteenth of the
 * pixels, 16 independent samples each, both ways) picks the one of the two with the lower
 * variance x cost, a deterministic choice recorded in the EXR header (`strategies`). Light
 * vertices pay off where lights sit close to surfaces (a lamp under a ceiling: 8x as efficient
 * on the closed room of reference/PERFORMANCE.md) and cost up to a third elsewhere. */
enum {
    GIB_REF_STRATEGIES_AUTO = 0,
    GIB_REF_STRATEGIES_CAMERA = 1,
    GIB_REF_STRATEGIES_LIGHT_VERTICES = 2
};
/* "auto", "camera", "light-vertices" (a command line's words); parse returns -1 for others. */
const char *gib_ref_strategies_name(int strategies);
int gib_ref_strategies_parse(const char *name);
#define GIB_REF_SOBOL_BATCHES 8
const char *gib_ref_sampler_name(int sampler);
/* Returns the enum value ("sobol", "random"), or -1. */
int gib_ref_sampler_parse(const char *name);

/* A request to stop early, for a caller that catches an interrupt (`gibench reference` on Ctrl-C):
 * once `requested` is set, a render in rounds toward a target noise abandons the round in progress
 * (its threads stop at the next pixel or light chunk; the statistics go back to the last finished
 * round) and returns the rounds finished (gib_ref_stats.interrupted), each sample as it would have
 * been; a request during the first round ends the render after it. The renderer sets rounds_done
 * after each round, so a handler can tell whether anything would be kept. Lock-free atomics: a signal handler on any of the render's threads may use them (C11
 * 7.14.1.1), and the renderer's threads read them without a data race. */
typedef struct gib_ref_interrupt {
    atomic_int requested;
    atomic_int rounds_done;
} gib_ref_interrupt;

typedef struct gib_ref_params {
    int component;        /* enum gib_component */
    int width, height;
    int spp;              /* samples per pixel (and light-tracing passes of width*height particles);
                           * with target_noise, the first round's count. Random estimators need
                           * at least 2: with one sample the variance is unknown. */
    float dmax;           /* ao: hits farther than this do not occlude; <= 0 or INFINITY = unbounded */
    int obscurance;       /* ao: 1 = obscurance rho(d) = min(d / dmax, 1); needs a finite dmax */
    int max_depth;        /* full, higher: most surface vertices on a path; 0 = default 8 */
    int min_depth;        /* full, higher: Russian roulette from this depth on; 0 = default 3 */
    int max_specular;     /* caustic (and what higher leaves out): most S vertices; 0 = default 1 */
    int cone;             /* indirect: 0 = the whole hemisphere; k >= 1 = only diffuse cone k - 1
                           * of the cone techniques' set (harness/base/cone_set.h): rho_d times
                           * the mean radiance over its cap, what that cone alone should gather */
    float cone_aperture;  /* with cone: the cap's full aperture, degrees; 0 = default 60. Cap
                           * directions below the surface count as black (a tilted cone wider
                           * than 60 degrees reaches under the horizon) */
    double target_noise;  /* > 0: add rounds until noise_rmse / mean <= this, up to max_spp */
    int max_spp;          /* cap with target_noise; 0 = default 65536 */
    uint64_t seed;        /* default 1 */
    int sampler;          /* GIB_REF_SAMPLER_*; 0 = sobol */
    int threads;          /* 0 = all cores */
    int camera;           /* index into scene->cameras */
    float time;           /* seconds: the instant a moving scene is rendered at (gib_motion_pose);
                           * ignored (normalised to 0) for a static scene */
    int strategies;       /* full, higher: GIB_REF_STRATEGIES_* (0 = auto) */
    int quiet;            /* no progress output */
    gib_ref_interrupt *interrupt; /* NULL: none; never changes the image */
} gib_ref_params;

typedef struct gib_ref_stats {
    double seconds;
    double noise_rmse;    /* image standard error, as above */
    double mean;          /* mean of all RGB samples of the image */
    long long rays;       /* rays traced (primary, shadow, bounce, ao, light paths, camera links) */
    int spp;              /* samples per pixel actually taken (1 for deterministic estimators) */
    int rounds;           /* sampling rounds (1 without target_noise) */
    int target_reached;   /* with target_noise: 1 if noise_rmse / mean <= target_noise (always for
                           * a deterministic estimator: its noise is exactly 0) */
    int interrupted;      /* 1: stopped early by p->interrupt, before the target or max_spp */
    int deterministic;    /* gib_component_deterministic() */
    double embree_cpu_seconds; /* bench only: seconds inside Embree's ray calls, summed over
                                * threads (0 unless the bench asked for it, or not measurable) */
    int threads;          /* threads the render ran on (at most one per image row, 256) */
    double render_seconds; /* seconds of sampling alone (seconds less the BVH build) */
    int light_vertices;   /* full, higher: 1 when light vertices were sampled */
    double pilot_gain;    /* with GIB_REF_STRATEGIES_AUTO: the pilot's efficiency of light
                           * vertices over camera paths alone (0: no pilot ran) */
} gib_ref_stats;

/* Renders into out (3 channels, allocated here). If stderr_img is non-NULL it receives the per-pixel
 * standard error (3 channels). */
int gib_reference_render(const gib_scene *scene, const gib_ref_params *p, gib_image *out,
                         gib_image *stderr_img, gib_ref_stats *stats, gib_error *err);

/* Renders n components of one scene at one instant together: p[0..n-1] are the parameters each
 * would be rendered with alone (the same time; sizes and cameras may differ; threads and quiet
 * from p[0]; interrupt is not heard). The world is built once, each view's (camera and size)
 * primary ray per pixel is traced once a round, and each component otherwise runs as alone, with
 * its own statistics, random streams, light passes and rounds toward its own target noise, so
 * out[i], stderr_img[i] (NULL: none) and stats[i] are gib_reference_render's for p[i], bit for
 * bit, but for stats[i].seconds: the whole set's. 0, or -1 with err (nothing allocated). */
#define GIB_REF_SET_MAX 16
int gib_reference_render_set(const gib_scene *scene, const gib_ref_params *p, int n,
                             gib_image *out, gib_image *stderr_img, gib_ref_stats *stats,
                             gib_error *err);

/* The parameters as the renderer uses them: defaults filled in, and every field that cannot change
 * this component's image set to a fixed value (dmax of `direct`, spp of a deterministic
 * estimator, ...), so that two requests for the same image compare and hash equal. threads and
 * quiet are zeroed (they never change the image). */
void gib_reference_normalize(const gib_scene *scene, const gib_ref_params *p, gib_ref_params *out);

/* A hash of everything in p that changes the image (after gib_reference_normalize), of the
 * renderer version, of the camera p->camera names (eye, target, up, fov) and of the scene's sky
 * where it has one (a scene file's bytes already change the content hash when its sky changes;
 * this covers scenes built in C too), and of p->time for a scene that moves (a static scene's
 * hash is what it was before scenes could move). */
uint64_t gib_reference_params_hash(const gib_scene *scene, const gib_ref_params *p);

/* The cache key of a reference image: the params hash plus the scene's content hash (scene file,
 * meshes, textures). */
uint64_t gib_reference_cache_key(const gib_scene *scene, const gib_ref_params *p);

/* Fills the EXR header attributes describing a reference render, all strings: component, spp,
 * seconds, scene_hash (16 hex digits), renderer_version, noise_rmse, mean, width, height, dmax
 * ("inf" when unbounded), seed, camera, obscurance, max_depth, min_depth, max_specular,
 * target_noise, max_spp, rounds, estimator ("deterministic" or "random"), sampler ("sobol",
 * "random", or "none" for a deterministic estimator), footprint ("centre" or
 * "area" or "centre+area"), missing (path classes no estimator samples, or "none"), cache_key,
 * sky (the sky's radiance, three numbers, "0 0 0" without one), stop (why sampling ended: "spp"
 * the fixed count, "target" the target noise, "max_spp" the cap before the target, "interrupted").
 * A moving scene's also get `time` (seconds); full and higher's `strategies` (the paths' strategies
 * and how they were chosen: "camera paths", "camera paths and light vertices, balance heuristic",
 * each followed by "; asked" or "; pilot: light vertices N x as efficient"). Parameters are
 * written normalised.
 * Returns the count written, at most max_attrs; GIB_REF_ATTR_COUNT is the most there are (cone
 * and strategies never come together). */
#define GIB_REF_ATTR_COUNT 28
int gib_reference_attrs(const gib_scene *scene, const gib_ref_params *p, const gib_ref_stats *s,
                        gib_kv *attrs, int max_attrs);

/* The ray offset the renderer uses for the scene: secondary rays leave a surface point moved by
 * this along the geometric normal, toward the side the ray goes to, with tnear = 0. It is
 * 1e-4 x the diagonal of the vertices' bounding box, floored at 2^-17 x the largest coordinate
 * magnitude in the renderer's frame (gib_scene_frame: a scene far from the origin is rendered
 * moved next to it, so neither the offset nor the hit points' precision depends on where the scene
 * lies). Tests use it to state exact expected values. */
float gib_reference_ray_eps(const gib_scene *scene);

/* ---- throughput benchmark (gibench bench reference) ---- */

typedef struct gib_ref_bench_row {
    char measure[48];     /* "path_tracer", "path_tracer_embree", "raw_random", "raw_diffuse",
                           * "raw_replay"; for component full "lean_tracer", "lean_replay" */
    char api[32];         /* "rtcIntersect1", "rtcIntersect1M", "rtcIntersect8", ... */
    long long rays;
    double seconds;       /* the best (least) of the repeats; mrays_per_s is rays over it */
    double mrays_per_s;
    int repeats;
    double seconds_median, seconds_max;
    /* Paired: in each repeat, this row's rays/s over the fastest replay's rays/s of the same
     * repeat (both ran on the machine as it was then; lean_* rows: the fastest replay of the lean
     * tracer's own rays); median, least and greatest over repeats.
     * The world_build row (once, no rays) has 0. */
    double paired_median, paired_min, paired_max;
} gib_ref_bench_row;

/* At most this many repeats are kept for the medians (more are refused). */
#define GIB_REF_BENCH_MAX_REPEATS 100

/* Measures, on one scene with all p->threads threads: raw Embree throughput on random incoherent
 * rays and on a replay of the path tracer's own rays with each ray API, and the path tracer's
 * throughput (p->component, p->spp at p->width x p->height, sampling and shading included).
 * `repeats` rounds (1 to GIB_REF_BENCH_MAX_REPEATS), each running every measure once; each row
 * has the best, median and worst time and its paired ratios (see gib_ref_bench_row); each
 * repeat's own ratio (path tracer against the fastest replay) goes to `log` when it is not NULL.
 * Fills up to max_rows rows; returns the count, or -1 with err. */
int gib_reference_bench(const gib_scene *scene, const gib_ref_params *p, int repeats, FILE *log,
                        gib_ref_bench_row *rows, int max_rows, gib_error *err);

#endif

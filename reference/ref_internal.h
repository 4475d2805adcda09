/* gibench — internals of the reference renderer shared by its source files (not a public API).
 *
 *   ref_world.c      the Embree scene built from a gib_scene, the alpha-mask filter, ray casting,
 *                    surface points, robust ray offsets
 *   ref_texture.c    texture lookups: level-0 bilinear, mip pyramids, trilinear filtering, and the
 *                    ray differentials at primary hits that choose the level
 *   ref_mip_share.c  sRGB8 pyramids shared between the worlds of one process
 *   ref_bsdf.c       the material model: albedo, next-event estimation, lobe sampling
 *   ref_estimators.c direct, ao/obscurance, indirect, glossy and the auxiliary images
 *   ref_path.c       full and higher: camera paths with next-event estimation and Russian roulette
 *   ref_light.c      light tracing: the mirror-first paths of caustic, full and higher
 *   reference.c      the render loop: rounds, per-pixel statistics, target noise, threads
 *   ref_set.c        several components of one scene at one instant rendered together
 *   ref_progress.c   the progress bar / log lines, and the thread pool
 *   ref_params.c     component names, parameter normalisation, hashing and EXR attributes
 *   ref_bench.c      the throughput benchmark */
#ifndef GIB_REF_INTERNAL_H
#define GIB_REF_INTERNAL_H

#include <embree3/rtcore.h>
#include <stdatomic.h>

#include "reference.h"
#include "rng.h"
#include "sampler.h"

#define REF_PI 3.14159265358979323846f
#define REF_MAX_MIPS 24

/* A texture's mip pyramid (box filter, built once per render). levels == 0: not an albedo
 * texture, no pyramid. srgb8: every level in 8-bit sRGB 4x4 tiles (lv8), as GL stores it, and
 * read-only: worlds of one process share it (ref_mip_share.c); otherwise floats (lv; level 0 is
 * the scene's own texels). */
typedef struct ref_mip {
    int levels, srgb8;
    int w[REF_MAX_MIPS], h[REF_MAX_MIPS];
    const float *lv[REF_MAX_MIPS];
    const uint32_t *lv8[REF_MAX_MIPS];
    float *owned;
    uint32_t *owned8;        /* ref_alloc_huge'd, owned8_bytes long */
    size_t owned8_bytes;
} ref_mip;

/* A cut-out mask's first channel, which is all the alpha test reads (ref_texture.c): one byte a
 * texel in 8x8 tiles of one cache line, each byte indexing the texture's own distinct values, so
 * a lookup gives bit for bit what the floats would. code == NULL: more than 256 distinct values
 * (or no texels), the lookup is ref_tex_sample's on the texture itself. */
typedef struct ref_mask {
    int w, h;
    const gib_texture *tex;
    uint8_t *code;
    float value[256];
} ref_mask;

/* A triangle's shading data in one 64-byte record, one cache line (ref_world.c). */
typedef struct ref_tri {
    _Alignas(64) float n[3][3]; /* vertex normals (0 when the scene has none) */
    float uv[3][2];
    uint32_t mat;
} ref_tri;

#define REF_GEOM_OPAQUE 0
#define REF_GEOM_MASKED 1  /* triangles with a cut-out mask: the only ones with a filter */

/* Bench only: records the rays a single-threaded render casts, for replay. */
typedef struct ref_raylog {
    struct RTCRay *rays;
    unsigned char *occl;   /* 1: shadow ray (rtcOccluded1), 0: closest hit */
    size_t n, cap;
} ref_raylog;

typedef struct ref_world {
    RTCDevice device;
    RTCScene scene;          /* NULL when the scene has no triangles: every ray misses */
    const gib_scene *gs;     /* the scene in its frame: &frame->scene (gib_scene_frame) */
    gib_scene_frame *frame;  /* owned */
    float eps;               /* ray offset, gib_reference_ray_eps() */
    ref_mip *mips;           /* one per scene texture */
    ref_mask *masks;         /* one per scene texture (code set for the cut-out masks) */
    float *spot_cos;         /* per light: gib_spot_cos_outer (spots), computed once */
    float *light_pick;       /* per light: the probability that a light vertex starts there, in
                              * proportion to its power (ref_connect.c); NULL: no light emits */
    int has_specular;        /* some material has a specular lobe (Phong or mirror) */
    int has_mirror;          /* some material is a mirror */
    int8_t *diffuse_known;   /* per material: 1 when every point's rho_d has a channel > 0, 0 when
                              * none can, -1 when its texels decide (ref_world_diffuse_known) */
    RTCScene mirrors;        /* the mirror triangles alone (ref_may_hit_mirror) and those with a */
    RTCScene speculars;      /* specular lobe (ref_may_hit_specular); NULL: see ref_build_subset */
    float bcentre[3], bradius; /* bounding sphere of the vertices (directional light emission) */
    ref_raylog *log;         /* bench: non-NULL records every ray (single thread only) */
    int time_embree;         /* bench: count the clock ticks spent inside Embree's ray calls */
    ref_tri *tris;           /* one per triangle, in Embree's order (opaque, then masked) */
    uint32_t geo_base[2];    /* Embree geometry g's primitive k is record geo_base[g] + k */
    uint32_t *rec_tri;       /* record -> scene triangle */
    char embree_msg[512];    /* last message from Embree's error callback */
} ref_world;

/* A surface point, oriented for shading toward the side the ray came from. */
typedef struct ref_hit {
    float p[3];              /* position, interpolated from the triangle's vertices */
    float n[3];              /* shading normal: interpolated vertex normal, unit length */
    float ng[3];             /* geometric normal, unit length, on the same side as n */
    float uv[2];
    float duv[4];            /* du/dx, dv/dx, du/dy, dv/dy per pixel: primary hits only */
    int has_duv;             /* 1 at primary hits: albedo is filtered at the pixel's footprint */
    int has_kd;              /* kd holds ref_albedo() (primary hits: filtered once per pixel) */
    float kd[3];
    int has_nee;             /* nee_dif/nee_spec hold ref_nee() toward wo (primary hits of `full`:
                              * delta lights give the same value every sample, so once per pixel) */
    float nee_dif[3], nee_spec[3];
    float t;                 /* ray distance */
    uint32_t prim;           /* triangle record (w->rec_tri[prim] is the scene's triangle) */
    const gib_material *mat;
    int back;                /* seen from behind a one-sided material: shades to 0 */
} ref_hit;

int ref_world_build(ref_world *w, const gib_scene *gs, gib_error *err);
/* Zeroed memory mapped on 2 MiB boundaries and advised onto transparent huge pages; release with
 * ref_free_huge and the same size. */
void *ref_alloc_huge(size_t bytes);
void ref_free_huge(void *p, size_t bytes);
void ref_world_free(ref_world *w);

/* Casts the ray (o, d) from tnear = 0 and fills hit, oriented toward the viewer at -d.
 * Returns 1 on a hit, 0 on a miss. */
int ref_trace(const ref_world *w, const float o[3], const float d[3], ref_hit *hit);
/* ref_trace in two halves, so that the memory latency of a hit's shading data can overlap other
 * work: _start finds the hit and prefetches its triangle record; _finish fills the hit and
 * prefetches its albedo texel. */
typedef struct ref_pending {
    struct RTCRayHit rh;
    float o[3], d[3];
    uint32_t prim;
} ref_pending;
int ref_trace_start(const ref_world *w, const float o[3], const float d[3], ref_pending *pq);
void ref_trace_finish(const ref_world *w, const ref_pending *pq, ref_hit *hit);
/* What ref_material's kd has at every point of material m without a texture lookup: 1 some
 * channel > 0, 0 none, -1 the texel decides. */
static inline int ref_diffuse_known(const ref_world *w, uint32_t m)
{
    return w->diffuse_known ? w->diffuse_known[m] : -1;
}
/* 0 when the ray (o, d) meets no mirror triangle, so its first hit cannot be a mirror; 1 when it
 * meets one or when the world has no scene of its mirrors (ref_build_subset). The light tracer asks
 * before tracing a particle's first ray through the whole scene: only a mirror there continues. */
int ref_may_hit_mirror(const ref_world *w, const float o[3], const float d[3]);
/* The same for the triangles with a specular lobe (Phong or mirror): caustic's camera paths
 * continue only from such a vertex. */
int ref_may_hit_specular(const ref_world *w, const float o[3], const float d[3]);
/* Fills an Embree ray (o, d) over [0, tfar], time 0, every mask bit. */
void ref_ray_init(struct RTCRay *r, const float o[3], const float d[3], float tfar);
/* 1 when a surface lies on the ray (o, d) within (0, tfar]. */
int ref_occluded(const ref_world *w, const float o[3], const float d[3], float tfar);
/* The shadow rays (ref_occluded calls that reached Embree) the calling thread has cast so far:
 * the pilot (ref_pilot.c) weighs them apart from closest-hit rays. */
long long ref_shadow_rays(void);
/* Bench: a cheap clock (the time-stamp counter on x86, nanoseconds elsewhere; ticks to seconds
 * by comparing it with the wall clock over a run), and the ticks the calling thread has spent
 * inside Embree's ray calls since it last asked, with w->time_embree set. */
uint64_t ref_ticks(void);
uint64_t ref_embree_ticks_take(void);
double ref_ticks_overhead(void);
/* Bench: the lean tracer (ref_bench_lean.c), the least work a next-event-estimation path tracer
 * can do per ray on w: p's camera, size, spp and depths on `threads` threads (w->log, when set,
 * records its rays). Returns its seconds; *rays is every ray it cast. */
double ref_lean_render(const ref_world *w, const gib_ref_params *p, int threads, long long *rays);
/* 1 when the lean tracer's paths are `full`'s kind on s: component full, no sky, no mirror. */
int ref_lean_applies(const gib_scene *s, int component);
/* The distance to the first surface on (o, d) within (0, tfar], or INFINITY. */
float ref_hit_distance(const ref_world *w, const float o[3], const float d[3], float tfar);

/* Ray differentials at a primary hit (Igehy 1999): fills h->duv from the camera rays through the
 * centres of the pixels one to the right and one down, intersected with the hit triangle's
 * plane. */
void ref_hit_differentials(const ref_world *w, const gib_camera *cam, int width, int height,
                           int px, int py, ref_hit *h);

/* ---- textures (ref_texture.c) ---- */

/* Bilinear lookup of level 0 with repeat wrap; texel rows run top-down, t = 1 - v. */
void ref_tex_sample(const gib_texture *t, float u, float v, float out[4]);
/* Builds the box-filtered pyramid of t; returns -1 with err when out of memory. */
int ref_mip_build(ref_mip *m, const gib_texture *t, gib_error *err);
void ref_mip_free(ref_mip *m);
/* GL's trilinear (LINEAR_MIPMAP_LINEAR) lookup with the isotropic LOD of the derivatives
 * duv = du/dx, dv/dx, du/dy, dv/dy; level 0 bilinear (GL's LINEAR magnification) when the LOD
 * is <= 0 or duv is NULL. */
void ref_mip_sample(const ref_mip *m, float u, float v, const float *duv, float out[4]);
/* Builds w->mips and w->masks: the pyramids of the scene's albedo textures and the compact
 * first channels of its cut-out masks, one texture a task on all cores. */
int ref_world_textures(ref_world *w, const gib_scene *gs, gib_error *err);
int ref_mask_build(ref_mask *m, const gib_texture *t, gib_error *err);
void ref_mask_free(ref_mask *m);
/* The mask's first channel, bilinear as ref_tex_sample's (identical arithmetic). */
float ref_mask_sample(const ref_mask *m, float u, float v);
/* Prefetches the cache lines of level 0 that a bilinear lookup at (u, v) reads. */
void ref_mip_prefetch(const ref_mip *m, float u, float v);
/* The LOD GL would use: log2(max(|duv_x * size|, |duv_y * size|)). */
float ref_mip_lod(const ref_mip *m, const float duv[4]);
/* Whether t's level 0, packed, is exactly the sRGB8 level lv0 of its size. */
int ref_mip_same8(const gib_texture *t, const uint32_t *lv0);

/* ---- sRGB8 pyramids shared between worlds (ref_mip_share.c) ---- */

/* Into m (its shape set) a shared pyramid of t's path and size whose level 0 is t packed, held
 * for m; 0 if there is none. */
int ref_share_take(ref_mip *m, const gib_texture *t);
/* Offers m's new sRGB8 pyramid, held once for m, to later worlds; without memory for the entry m
 * keeps it alone. */
void ref_share_put(const ref_mip *m, const char *path);
/* Releases m's hold on the shared pyramid at p8; 0 if p8 is not shared (the caller frees it). */
int ref_share_drop(const uint32_t *p8);

/* ---- materials (ref_bsdf.c) ---- */

/* The material at a hit, textures applied: rho_d, rho_s and the lobe type. */
typedef struct ref_mat {
    float kd[3];
    float ks[3];
    int spec;                /* enum gib_spec_type; GIB_SPEC_NONE when rho_s is 0 */
    float phong_n;
} ref_mat;

void ref_material(const ref_world *w, const ref_hit *h, ref_mat *m);
/* ref_material's specular lobe alone (spec, phong_n, ks), without the albedo's texel: kd untouched. */
void ref_material_specular(const ref_hit *h, ref_mat *m);
/* rho_d at the hit: albedo times its texture, trilinear at primary hits, level 0 elsewhere. */
void ref_albedo(const ref_world *w, const ref_hit *h, float a[3]);

/* Next-event estimation toward every light: the reflected radiance toward wo of the light
 * arriving unoccluded, split into the diffuse lobe (to dif) and the Phong lobe (to spec; NULL:
 * not wanted). Mirrors add nothing (a delta lobe never meets a delta light). */
void ref_nee(const ref_world *w, const ref_hit *h, const ref_mat *m, const float wo[3],
             float dif[3], float spec[3], long long *rays);
/* ref_nee with each chunk of lights' visibility passed to weigh(arg, v) before shading (the
 * camera path's MIS weights, ref_path.c); weigh NULL: ref_nee itself. */
struct ref_nee_vis;
void ref_nee_weighed(const ref_world *w, const ref_hit *h, const ref_mat *m, const float wo[3],
                     float dif[3], float spec[3], long long *rays,
                     void (*weigh)(const void *arg, struct ref_nee_vis *v), const void *arg);
/* ref_nee in two halves, so that the shadow rays can be cast before the albedo texel is read:
 * _visible casts them for lights [first, first + REF_NEE_LIGHTS) and keeps the unoccluded ones'
 * irradiance, cosine and Phong lobe (wanted lobes: want_d, want_s); _shade adds their reflected
 * radiance with the material's (textured) reflectances, in light order: the same arithmetic as
 * ref_nee. spec NULL: the Phong lobe is not wanted. */
#define REF_NEE_LIGHTS 8
typedef struct ref_nee_vis {
    int n;
    float e[REF_NEE_LIGHTS][3], cosn[REF_NEE_LIGHTS], lobe[REF_NEE_LIGHTS];
    float pb[REF_NEE_LIGHTS]; /* the light strategy's density of the hit point (ref_lv_density) */
    float wd[REF_NEE_LIGHTS]; /* the diffuse part's weight: 1, or its MIS weight (ref_path.c) */
} ref_nee_vis;
void ref_nee_visible(const ref_world *w, const ref_hit *h, const float wo[3], int want_d,
                     int want_s, float phong_n, uint32_t first, ref_nee_vis *v, long long *rays);
void ref_nee_shade(const ref_nee_vis *v, const ref_mat *m, float dif[3], float spec[3]);

/* 1 when the scene has a sky (gib_scene.sky: a uniform environment of that radiance, seen by rays
 * that escape; 0 = none). */
static inline int ref_has_sky(const gib_scene *s)
{
    return s && (s->sky[0] > 0.0f || s->sky[1] > 0.0f || s->sky[2] > 0.0f);
}

/* Next-event estimation toward the sky: ADDS to dif (diffuse lobe) and spec (specular lobe; NULL:
 * not wanted) the reflected sky radiance toward wo, one importance-sampled direction per lobe,
 * each tested for escaping the scene: diffuse rho_d L V (cosine-weighted direction), Phong
 * rho_s (n + 2) / (n + 1) cos L V (a direction from the Phong lobe), mirror rho_s L V (the mirror
 * direction: the sky is not a delta light, so a mirror does show it). Directions leaving through
 * the geometric surface give 0. With a sky it draws exactly 4 random numbers (diffuse u1 u2, then
 * Phong u1 u2) whatever is wanted; without one it draws none and casts no ray, so scenes without
 * a sky render exactly as before it existed. */
void ref_nee_sky(const ref_world *w, const ref_hit *h, const ref_mat *m, const float wo[3],
                 ref_rng *rng, float dif[3], float spec[3], long long *rays);

/* Orthonormal basis around unit n. */
void ref_basis(const float n[3], float t[3], float b[3]);
/* Cosine-weighted direction about n (pdf cos / pi). */
void ref_sample_cosine(const float n[3], float u1, float u2, float d[3]);
/* Mirror direction of wo about n. */
void ref_reflect(const float wo[3], const float n[3], float r[3]);
/* A direction from the normalised Phong lobe about r (pdf (n+1)/(2 pi) cos^n alpha). The
 * returned weight f cos / pdf for rho_s = 1 is (n + 2) / (n + 1) max(0, n_s . d); 0 means the
 * sample went below the surface. */
float ref_sample_phong(const float r[3], float n_exp, const float ns[3], float u1, float u2,
                       float d[3]);
/* Luminance weight used to choose lobes. */
static inline float ref_lum(const float c[3])
{
    return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
}

/* ---- light vertices (ref_connect.c): the second strategy of full and higher ----
 *
 * A light vertex y is a surface point reached by a ray from a light (the light chosen in
 * proportion to its power, the direction uniform over the light's emission: sphere, spot cone,
 * or a disk across the scene for a directional light). Connected by a shadow ray to a camera
 * vertex x through both vertices' diffuse lobes, it samples the paths L y x ... E that camera
 * paths find by a diffuse bounce from x to y and next-event estimation at y; the two are combined
 * by multiple importance sampling (ref_path.c). */

/* 1 when full or higher (parameters q, normalised) can sample light vertices: paths of 2 or more
 * vertices (`higher` keeps them from 3 on) and a light that emits. Whether a render does is
 * q->strategies' choice, or the pilot's (ref_pilot.c). */
int ref_light_vertices(const gib_scene *s, const gib_ref_params *q);
/* 1 when the light emits anything (positive luminance; a spot's cone not empty). */
int ref_light_emits(const gib_light *l);
/* The light's power, the selection weight of light vertices: luminance times the solid angle it
 * emits into (a directional light: across the scene's bounding disk). */
float ref_light_power(const ref_world *w, const gib_light *l);
/* Builds w->light_pick (NULL when no light emits). */
int ref_light_pick_build(ref_world *w, gib_error *err);
/* The light strategy's density (area measure) of a point with geometric normal ng lit by light i
 * from direction wi (toward the light) at distance dist: 0 when the light lies below ng. */
float ref_lv_density(const ref_world *w, uint32_t i, const float wi[3], float dist,
                     const float ng[3]);

typedef struct ref_lvert {
    int ok;                  /* 0: the ray missed, or the point reflects nothing diffusely */
    float p[3], ng[3];       /* the point; its geometric normal, on the light's side */
    float rad[3];            /* rho_d / pi E cos_n / density: its diffuse radiance over density */
    float pdf;               /* its density (ref_lv_density) */
} ref_lvert;

/* A light vertex's ray from three uniform numbers (w->light_pick set): the light, chosen with u0,
 * whose index it returns, and the emitted ray (o, d) from u1, u2. */
uint32_t ref_lv_ray(const ref_world *w, float u0, float u1, float u2, float o[3], float d[3]);
/* Samples one light vertex from the sample's numbers (1D for the light when there are several,
 * 2D for the direction): one ray, counted in *rays. */
void ref_lv_sample(const ref_world *w, ref_rng *rng, ref_lvert *lv, long long *rays);
/* The connection of lv to camera vertex h through h's diffuse lobe: g = (what multiplies h's
 * throughput and rho_d) with the MIS weight against a camera bounce whose probability of taking
 * h's diffuse lobe, its Russian roulette included, is pa_lobe. Returns 0 (g untouched) when the
 * two do not see each other or nothing is carried; casts at most one shadow ray. */
int ref_lv_connect(const ref_world *w, const ref_hit *h, const ref_lvert *lv, float pa_lobe,
                   float g[3], long long *rays);
/* The camera strategy's density (area measure) of y reached from x (shading normal nx) by a
 * diffuse bounce of probability pa_lobe: pa_lobe cos_x / pi cos_y / d^2, ngy y's geometric normal
 * facing x. */
float ref_camera_density(const float x[3], const float nx[3], float pa_lobe, const float y[3],
                         const float ngy[3]);
/* The balance heuristic (Veach 1997, Sec. 9.2.2): a / (a + b) for densities a, b >= 0, as
 * 1 / (1 + b/a) so that large densities (points close together) do not overflow; 0 when a is 0
 * or b/a is not finite. (The power heuristic's noise was 1-3% higher on the closed room and the
 * Cornell box: reference/PERFORMANCE.md.) */
static inline float ref_mis_weight(float a, float b)
{
    if (!(a > 0.0f))
        return 0.0f;
    float r = b / a;
    return r <= 3e38f ? 1.0f / (1.0f + r) : 0.0f;
}

/* ---- one render's shared state ---- */

typedef struct ref_ctx {
    const ref_world *w;
    const gib_camera *cam;
    gib_ref_params p;        /* normalised */
    float right[3], up[3], fwd[3], tan_half, aspect;
    int light_part;          /* light tracing runs (caustic, full, higher: scenes with mirrors) */
    int camera_part;         /* per-pixel camera samples run */
    int lv_on;               /* full and higher sample light vertices (ref_connect.c) */
} ref_ctx;

/* A contribution of light tracing to one pixel. */
typedef struct ref_splat {
    uint32_t pix;
    float v[3];
} ref_splat;

typedef struct ref_splats {
    ref_splat *s;
    size_t n, cap;
    int oom;
} ref_splats;

/* The visible point of pixel (x, y), as every camera sample of the pixel starts from it: the
 * camera ray through the pixel centre (counted in *rays), the albedo filtered at the pixel's
 * footprint, and for `full` next-event estimation there (once per pixel). wo points to the eye.
 * Returns 0 when there is nothing to sample (a miss, or the back of a one-sided surface for a
 * shaded component): the pixel is exactly 0. */
int ref_pixel_hit(const ref_ctx *c, int x, int y, ref_hit *h, float wo[3], long long *rays);

/* The pilot of GIB_REF_STRATEGIES_AUTO (ref_pilot.c): renders a sixteenth of c's pixels with
 * and without light vertices and returns the efficiency of light vertices over camera paths
 * alone (variance x cost), 0 when there was nothing to measure. Deterministic (its own seeds,
 * sums in row order) whatever nthreads. */
double ref_pilot_gain(const ref_ctx *c, int nthreads);

/* n <= REF_PATH_BATCH camera samples of the component at the visible point h (wo toward the
 * eye), sample i on its own stream rng[i] into out[i]: the same values whether taken one at a
 * time or together (full and higher run them as one batch, ref_est_paths). */
#define REF_PATH_BATCH 16
void ref_sample_camera(const ref_ctx *c, const ref_hit *h, const float wo[3], int n,
                       ref_rng *rng, float (*out)[3], long long *rays);

/* Estimators. Each adds the rays it casts to *rays. */
void ref_est_direct(const ref_world *w, const ref_hit *h, const float wo[3], ref_rng *rng,
                    float out[3], long long *rays);
/* One cosine-weighted visibility sample: 1 when unoccluded within dmax (<= 0 or inf: unbounded);
 * with obscurance, min(d / dmax, 1). */
float ref_est_ao(const ref_world *w, const ref_hit *h, float dmax, int obscurance, ref_rng *rng,
                 long long *rays);
/* ref_est_ao in parts, for AO images of one view that differ only in dmax and obscurance: their
 * samples draw the same numbers (the same seeds), hence the same ray, so one closest-hit ray cast
 * as far as the farthest dmax serves them all (ref_set.c). ref_ao_ray: the sample's ray (its two
 * numbers); ref_ao_value: the sample's value when the first surface on it lies at t (INFINITY:
 * none as far as it was cast, which is at least dmax), what ref_est_ao returns bit for bit. */
void ref_ao_ray(const ref_world *w, const ref_hit *h, ref_rng *rng, float o[3], float d[3]);
float ref_ao_value(float t, float dmax, int obscurance);
/* caustic, camera part: L S+ D E whose light-side vertex is Phong. */
void ref_est_caustic(const ref_ctx *c, const ref_hit *h, ref_rng *rng, float out[3],
                     long long *rays);
void ref_est_aux(const ref_ctx *c, const ref_hit *h, float out[3]);
/* full (higher_only = 0) or higher (1): n <= REF_PATH_BATCH camera paths from one visible
 * point, path i on its own stream rng[i] into out[i], run together depth by depth so that their
 * memory misses overlap (ref_path.c); each out[i] is what the path alone would give. */
void ref_est_paths(const ref_ctx *c, const ref_hit *h, const float wo[3], int higher_only,
                   int n, ref_rng *rng, float (*out)[3], long long *rays);

/* Path classes (reference.h): 1 when a path of `verts` surface vertices whose visible point x1
 * leaves through lobe s1 (1 = S) and whose other vertices are all S (all_s_rest) belongs to
 * direct, indirect, glossy or caustic (with max_specular), i.e. NOT to higher. */
int ref_basic_class(int verts, int s1, int all_s_rest, int max_specular);

/* Light tracing: traces `count` particles of light pass `pass`, chunk `chunk`, and appends
 * their camera splats (already divided by the pass's particle count). */
void ref_light_chunk(const ref_ctx *c, uint64_t pass, uint32_t chunk, int count,
                     ref_splats *out, long long *rays);
/* Particles per light-tracing chunk (the unit of work; particle i of a pass is particle
 * i % REF_LIGHT_CHUNK of chunk i / REF_LIGHT_CHUNK). */
#define REF_LIGHT_CHUNK 4096
/* Particles per light pass: one per pixel. */
static inline long long ref_light_particles(const ref_ctx *c)
{
    return (long long)c->p.width * c->p.height;
}

/* gib_component_deterministic for a given max_depth (full and higher with one vertex are). */
int ref_deterministic(const gib_scene *s, int component, int max_depth);
/* With Sobol batches: spp above GIB_REF_SOBOL_BATCHES rounded up to a multiple of it. */
int ref_sobol_round_spp(int spp);

/* gib_reference_render on an already built world (the bench times rendering alone); no
 * parameter checks beyond the caller's. */
int ref_render_world(const ref_world *w, const gib_scene *scene, const gib_ref_params *p,
                     gib_image *out, gib_image *stderr_img, gib_ref_stats *stats, gib_error *err);
/* The checks gib_reference_render makes. */
int ref_check_params(const gib_scene *scene, const gib_ref_params *p, gib_error *err);

/* ---- thread pool and progress (ref_progress.c) ---- */

typedef struct ref_progress {
    int enabled, tty;
    const char *what;
    double t0, last_print;
    long long units_per_spp;    /* work units (pixel samples + particles) per sample per pixel */
    atomic_llong units;         /* done so far */
    atomic_llong rays;
    atomic_llong embree_ticks;  /* with w->time_embree: ticks inside Embree, all threads */
    int threads_used;           /* the most threads any ref_parallel of this render ran */
    long long units_target;     /* for the estimate of time left */
    int round, spp_goal;
    double noise_rel;           /* last round's noise / mean, or < 0 */
    double target;
    int printed;
} ref_progress;

typedef void (*ref_task_fn)(void *ctx, int task);
/* Runs fn(ctx, task) for task = 0 .. ntasks-1 on nthreads threads; the calling thread updates the
 * progress display meanwhile. Tasks may run in any order and on any thread. */
void ref_parallel(int nthreads, int ntasks, ref_task_fn fn, void *ctx, ref_progress *prog);
void ref_progress_tick(ref_progress *prog, int force);
void ref_progress_round(ref_progress *prog, int spp_done, double noise_rel);
void ref_progress_end(ref_progress *prog);
double ref_now(void);

/* fmaxf and fminf, inlined: without -ffinite-math-only GCC calls libm for them. The same results
 * as x86-64 glibc's for every input but signalling NaNs: a quiet NaN gives the other operand, and
 * a tie (+0 against -0) the second operand, as maxss/minss do. */
static inline float ref_fmaxf(float a, float b)
{
    return (a > b || b != b) ? a : b;
}

static inline float ref_fminf(float a, float b)
{
    return (a < b || b != b) ? a : b;
}

/* Small vector helpers. */
static inline float ref_dot(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Origin for a ray leaving h (point p, unit geometric normal ng) in direction d: offset along the
 * geometric normal, toward the side d points to, by w->eps. (Inline: it runs for every ray the
 * path tracer casts.) */
static inline void ref_offset_point(const ref_world *w, const float p[3], const float ng[3],
                                    const float d[3], float o[3])
{
    float s = ref_dot(ng, d) >= 0.0f ? w->eps : -w->eps;
    for (int k = 0; k < 3; k++)
        o[k] = p[k] + s * ng[k];
}

static inline void ref_offset_origin(const ref_world *w, const ref_hit *h, const float d[3],
                                     float o[3])
{
    ref_offset_point(w, h->p, h->ng, d, o);
}

#endif

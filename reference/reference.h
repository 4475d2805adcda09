/* gibench — the reference renderer: an Embree 3 path tracer with one estimator per
 * light-transport component (DESIGN.md, "Light-transport components").
 *
 * Deterministic: each pixel's sampler is seeded from (pixel index, sample round, seed), so the same
 * build, scene, size, component and spp give the same image bit for bit, whatever the thread count.
 * Each pixel's sample variance gives its standard error; the image's noise RMSE is
 * sqrt(mean over pixels and channels of variance / spp). */
#ifndef GIB_REFERENCE_H
#define GIB_REFERENCE_H

#include "../harness/imaging/image.h"
#include "../scenes/scene.h"

#define GIB_REFERENCE_VERSION "gibench-ref-1"

enum gib_component {
    GIB_COMP_AO = 0,      /* (1/pi) integral V(x,w) cos dw, V = 0 when a hit lies within dmax */
    GIB_COMP_DIRECT = 1,  /* L D E and L S E with shadows */
    GIB_COMP_COUNT
};

const char *gib_component_name(int component);
/* Returns the enum value, or -1 for an unknown name. */
int gib_component_parse(const char *name);

typedef struct gib_ref_params {
    int component;        /* enum gib_component */
    int width, height;
    int spp;              /* samples per pixel */
    float dmax;           /* ao: hits farther than this do not occlude; <= 0 or INFINITY = unbounded */
    uint64_t seed;        /* default 1 */
    int threads;          /* 0 = all cores */
    int camera;           /* index into scene->cameras */
    int quiet;            /* no progress output */
} gib_ref_params;

typedef struct gib_ref_stats {
    double seconds;
    double noise_rmse;    /* image standard error, as above */
    double mean;          /* mean of all RGB samples of the image */
    long long rays;       /* rays traced (primary + shadow + ao) */
} gib_ref_stats;

/* Renders into out (3 channels, allocated here). If stderr_img is non-NULL it receives the per-pixel
 * standard error (3 channels). */
int gib_reference_render(const gib_scene *scene, const gib_ref_params *p, gib_image *out,
                         gib_image *stderr_img, gib_ref_stats *stats, gib_error *err);

/* Fills the EXR header attributes describing a reference render, all strings: component, spp,
 * seconds, scene_hash (16 hex digits), renderer_version, noise_rmse, mean, width, height, dmax
 * ("inf" when unbounded, since dmax <= 0 and inf give the same image), seed, camera. Returns the
 * count written, at most max_attrs; GIB_REF_ATTR_COUNT is how many there are. */
#define GIB_REF_ATTR_COUNT 12
int gib_reference_attrs(const gib_scene *scene, const gib_ref_params *p, const gib_ref_stats *s,
                        gib_kv *attrs, int max_attrs);

/* The ray offset the renderer uses for the scene: secondary rays leave a surface point moved by
 * this along the geometric normal, toward the side the ray goes to, with tnear = 0. It is
 * 1e-4 x the diagonal of the vertices' bounding box, floored at 2^-17 x the largest coordinate
 * magnitude (float precision far from the origin). Tests use it to state exact expected values. */
float gib_reference_ray_eps(const gib_scene *scene);

#endif

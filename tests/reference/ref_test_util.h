/* gibench tests: tiny gib_scenes built by hand in C for the reference renderer's tests, so each
 * test knows its geometry exactly and can state the analytic answer. */
#ifndef GIB_REF_TEST_UTIL_H
#define GIB_REF_TEST_UTIL_H

#include <stdio.h>

#include "reference/reference.h"
#include "tests/common/check.h"

/* Test bookkeeping: checks through tests/common/check.h (CHECK and the others), counted in
 * `failures` (defined in ref_test_util.c); main returns failures != 0. */
extern int failures;

void rt_scene_init(gib_scene *s, const char *name);
void rt_scene_free(gib_scene *s);

/* Returns the material index. Diffuse, one-sided, no textures. */
int rt_material(gib_scene *s, float r, float g, float b);
/* Returns the texture index; rgba is copied (w*h*4 floats, row 0 on top). */
int rt_texture(gib_scene *s, int w, int h, const float *rgba);

/* A planar quad p0 p1 p2 p3 (counter-clockwise seen from the side `normal` points to), uv (0,0)
 * (1,0) (1,1) (0,1) at its corners, as two triangles. */
void rt_quad(gib_scene *s, const float p0[3], const float p1[3], const float p2[3],
             const float p3[3], const float normal[3], int material);
/* An axis-aligned rectangle in the plane y = h, x in [x0, x1], z in [z0, z1], normal +y. */
void rt_floor(gib_scene *s, float h, float x0, float x1, float z0, float z1, int material);

void rt_point_light(gib_scene *s, float x, float y, float z, float r, float g, float b);
void rt_spot_light(gib_scene *s, const float pos[3], const float dir[3], float intensity,
                   float exponent, float outer_deg);
void rt_camera(gib_scene *s, const float eye[3], const float target[3], const float up[3],
               float vfov_deg);

/* A uniform sky of radiance (r, g, b) (gib_scene.sky), and GIB_FEAT_SKY. */
void rt_sky(gib_scene *s, float r, float g, float b);

/* The scene of ref_determinism: a 8 x 8 m floor, an alpha-masked two-sided Phong board above it,
 * a mirror wall and a point light (every estimator runs on it, light tracing included). */
void rt_scene_mixed(gib_scene *s);

/* The form factor from a point (normal +y) at the origin to the polygon R[0..n-1] (coordinates
 * relative to the point, entirely above its horizon), by Lambert's formula
 *     F = (1 / 2 pi) | sum_i angle(R_i, R_i+1) * (n . unit(R_i x R_i+1)) |:
 * the fraction of cosine-weighted directions that hit the polygon. */
double rt_form_factor_up(double R[][3], int n);

/* Two renders' images a and b, three planar channels of w x h (img[c * w * h + y * w + x]) with
 * each pixel's variance of the mean: the image means' difference in standard errors (the two
 * variances added; signed, the channel with the largest |z|) into *zmean, and the largest |z| of
 * the nb x nb block means into *zblock. A block whose difference and variance are both 0
 * (deterministic on both sides) agrees exactly: z = 0. */
void rt_z_diff(const double *a_img, const double *a_var, const double *b_img, const double *b_var,
               int w, int h, int nb, double *zmean, double *zblock);

/* Default parameters: quiet, seed 1, all cores. */
gib_ref_params rt_params(int component, int w, int h, int spp);

/* Renders or aborts the test with the renderer's message. */
void rt_render(const gib_scene *s, const gib_ref_params *p, gib_image *img, gib_image *sd,
               gib_ref_stats *st);

/* The camera ray of pixel (x, y) intersected with the plane y = h, in double: the analytic visible
 * point. Returns 0 when the ray does not reach the plane. */
int rt_hit_plane_y(const gib_scene *s, int cam, int w, int h, int x, int y, double plane_y,
                   double P[3]);

/* Per-pixel agreement with an analytic answer whose one-sample variance is known: rt_zstats_add
 * takes a pixel (measured value and the renderer's standard error; expected value and variance
 * of one sample, over spp samples); rt_zstats_check asks that the image-wide deviation be within
 * 3 of the renderer's standard errors of the sum, no pixel beyond 5 analytic standard errors
 * (~0.5 expected false alarms per million pixels), and the renderer's variance within 5% of the
 * analytic one (it estimates the same variance from thousands of pixels) with independent samples
 * (sobol = 0); with Sobol samples (sobol = 1) at most 5% above it: the analytic variance is that
 * of independent samples, which a stratified estimator does not exceed on these smooth
 * integrands (measured ratios 0.04-0.25), while the image-wide deviation, judged by the
 * renderer's own variance, keeps that variance honest. */
typedef struct rt_zstats {
    double dsum, var_r, var_a, esum, msum, worst_z, zsum;
    int n;
    int sobol;
} rt_zstats;
void rt_zstats_add(rt_zstats *z, double got, double se, double expect, double var1, int spp);
void rt_zstats_check(rt_zstats *z, const char *what);

#endif

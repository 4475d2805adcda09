/* gibench technique `lrsm` — the pure math of layered reflective shadow maps (Sugihara, Rauwendaal,
 * Salvi 2014), on the CPU. techniques/lrsm/lrsm_common.glsl computes the same numbers line for line
 * (the GLSL is what renders; this file is what the unit tests check). */
#ifndef GIB_LRSM_MATH_H
#define GIB_LRSM_MATH_H

#include "techniques/common/light_view_shared.h"
#include "techniques/lrsm/lrsm_shared.h"

/* erf(x) by Abramowitz and Stegun 7.1.26: |error| < 1.5e-7 for every x (GLSL has no erf). */
double lrsm_erf(double x);
/* Standard normal CDF Phi(x) = (1 + erf(x / sqrt 2)) / 2 through lrsm_erf. */
double lrsm_phi(double x);

/* The smallest depth variance Eq. 12 uses, in warped depth units (z in [0,1] over a layer's range):
 * sigma^2 is 0 on flat texels and E[z^2] - mu^2 of 16-bit UNORM moments cancels to a few 2^-16
 * either side of it, so sigma^2 is floored at 2^-15 (sigma >= 0.0055 of the layer's depth range). */
#define LRSM_MIN_VARIANCE (1.0 / 32768.0)

/* Eq. 12: the share of a Gaussian N(mu, sigma2) of depths inside [zc - rc, zc + rc], in closed form
 * Phi((zc + rc - mu) / sigma) - Phi((zc - rc - mu) / sigma), sigma2 floored at LRSM_MIN_VARIANCE. */
double lrsm_visibility(double zc, double rc, double mu, double sigma2);

/* k of Eq. 15: smoothstep 3t^2 - 2t^3 of t clamped to [0,1]; k(t) + k(1 - t) = 1, so two layers'
 * decays add to 1 across their overlap. */
double lrsm_smooth(double t);

/* Static depth partitions (Sec. 4.3): the light's depth range [z0, z1] over the scene's bounds is cut
 * into `parts` equal partitions of width w; layer d covers [z0 + d w - delta/2, z0 + (d+1) w +
 * delta/2] with delta = overlap * w, so neighbouring layers share a band of width delta around
 * their boundary. The outer ends of the first and last layers are open (no decay there: nothing
 * lies beyond the scene's bounds). */
typedef struct lrsm_partition {
    double z0, z1;   /* depth range of the light's view over the scene bounds */
    int parts;       /* D */
    double overlap;  /* delta as a fraction of w */
} lrsm_partition;
/* [zmin, zmax] of layer d (the range depths are warped over). */
void lrsm_layer_range(const lrsm_partition *p, int d, double *zmin, double *zmax);
/* Eq. 15: the decay f(zc) of layer d; 0 outside its range (except beyond the open outer ends). */
double lrsm_decay(const lrsm_partition *p, int d, double zc);
/* Whether layer d's range meets [a, b] (outer ends open): the layers a cone sample of depth
 * interval [zc - rc, zc + rc] reads (lrsm_sample.glsl says why not only those holding zc). */
int lrsm_layer_overlaps(const lrsm_partition *p, int d, double a, double b);
/* Whether a texel at depth z belongs to depth layer d (inside its range, outer ends open). */
int lrsm_in_depth_layer(const lrsm_partition *p, int d, double z);
/* The normal partition of a texel with <n.l> = cosnl among `parts` equal ones over (0, 1]; -1 when
 * cosnl <= 0 (facing away from the light: no layer). */
int lrsm_normal_part(double cosnl, int parts);

/* The weight of an RSM texel in the filtered radiance: the area of surface it sees, Eq. 3's
 * Jacobian dx = (r^2 / <n.l>) dw, in units that keep it in (0, 1]: (z / zfar)^2 cos_face^3 (the
 * texel's solid angle on a perspective or cube face, times r^2; 1 for an orthographic view, kind
 * GIB_LV_KIND_ORTHO) times min(LRSM_JACOBIAN_COS / <n.l>, 1) (lrsm_shared.h: surfaces lit at
 * grazing counted up to 1 / 0.1 times a face-on one, not without bound). lrsm_common.glsl has the
 * GLSL twin. */
double lrsm_area_weight(int kind, double z, double zfar, double cos_face, double cosnl);

/* One RSM texel as the construction pass sees it, and one layer texel it writes (Table 1, each
 * value premultiplied by the layer's opacity alpha = members / 4 of the 2x2 block). */
typedef struct lrsm_texel {
    int valid;         /* a surface was seen */
    double z;          /* depth from the light */
    double n[3];       /* normal facing the light */
    double cosnl;      /* <n.l> */
    double radiance[3];/* rho L_d <n.l> / pi */
    double area;       /* its weight in the filtered radiance: lrsm_area_weight, or 1 (the paper) */
} lrsm_texel;
typedef struct lrsm_layer_texel {
    double radiance[4];   /* sum of members' radiance x area / 4, sum of their areas / 4 */
    double normal[4];     /* sum of members' normals / 4, alpha */
    double depth[3];      /* sum of warped z / 4, of warped z^2 / 4, alpha */
} lrsm_layer_texel;
/* Fills out[d * normal_parts + k] for every layer from one 2x2 block of RSM texels. */
void lrsm_build_block(const lrsm_partition *p, int normal_parts, const lrsm_texel block[4],
                      lrsm_layer_texel *out);

/* A cone sample as the share of the cone's rays that meet a plane (parameter hits 1; lrsm_cone.frag
 * says why). The cone's directions are the cap around its axis v flattened onto its tangent plane,
 * w = v + sin_half u with u uniform in the unit disk, and a ray meets a plane through the sample
 * when the plane's crossing lies within the sample's step along the axis. */

/* The mean of max(<n.w>, 0) over that cap, for a unit normal n at cos_axis to v (its component
 * across v sin_axis = sqrt(1 - cos_axis^2)): <n.w> = cos_axis + b x with b = sin_half sin_axis and
 * x distributed as a disk's projection on a line, density (2 / pi) sqrt(1 - x^2), so in closed form
 * (2 / pi) int_u^1 (a + b x) sqrt(1 - x^2) dx from the zero crossing u = -a / b. Eq. 8's <n.v> for
 * a cone of one direction (sin_half 0); a plane along the axis still faces part of a wide cone. */
double lrsm_cap_cosine(double cos_axis, double sin_axis, double sin_half);

/* The share of the rays of a sample (radius rc, step `step` x its diameter) that meet a plane at
 * distance delta from its centre, the plane's cap cosine E (lrsm_cap_cosine) standing for the
 * cosine between the rays and its normal: a ray at offset y across the axis crosses the plane at
 * (delta + y sqrt(1 - E^2)) / E along it, inside the step when |delta + y sqrt(1 - E^2)| <= step
 * rc E. y spreads as a disk's projection (variance rc^2 / 4) and delta is uncertain by
 * sigma2_delta; both are taken as one Gaussian: Phi((h - delta) / S) - Phi((-h - delta) / S),
 * h = step rc E, S^2 = rc^2 (1 - E^2) / 4 + sigma2_delta. A plane facing the axis is met whole by
 * the sample whose step holds it (touching spheres tile the axis, so the shares of successive
 * samples add to 1); a plane along the axis by few rays, the fewer the farther from the centre. */
double lrsm_plane_hits(double delta, double E, double rc, double step, double sigma2_delta);

/* The variance of a layer's plane along its normal: the footprint's depth variance var (world units)
 * times <n.l>^2, less what the plane's own tilt to the light spreads over a footprint 2 rc wide (a
 * ramp of slope tan(theta) across a square: (rc tan theta)^2 / 3 in depth, (rc sin theta)^2 / 3
 * along the normal), at least 0: only the spread of several surfaces about one plane. */
double lrsm_plane_spread(double var, double cos_nl, double rc);

/* Sec. 5: mip level = log2 of the sample's projected diameter in layer texels, at least clamp. */
double lrsm_mip(double diameter_texels, double clamp);

#endif

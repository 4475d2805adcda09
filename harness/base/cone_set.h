/* The diffuse cone set of the cone-tracing techniques (techniques/common/voxel_cone.glsl's
 * diffuse_cone_dir and diffuse_cone_weight), on the C side: the reference renders what one cone
 * of it sees (`gibench reference --cone`), so that a cone technique's error can be split into its
 * cones' own errors and the error of gathering the hemisphere from six cones at all.
 * tests/common/test_voxel_cone.c checks that both sides give the same directions and weights. */
#ifndef GIB_CONE_SET_H
#define GIB_CONE_SET_H

#define GIB_DIFFUSE_CONES 6
#define GIB_DIFFUSE_CONE_APERTURE_DEG 60.0f /* the techniques' default diffuse_aperture */

/* Cone i's axis for the unit normal n: i = 0 along n, i = 1..5 tilted 60 degrees from n at
 * azimuth (i - 1) x 72 degrees in the basis of gib_cone_basis(n). */
void gib_diffuse_cone_dir(int i, const float n[3], float dir[3]);
/* Its weight in the gather: 2/7 for the cone along n, 1/7 for each tilted one (sum 1). */
float gib_diffuse_cone_weight(int i);
/* Unit t, b completing unit d (t x b = d), as techniques/common/basis.glsl's ortho_basis. */
void gib_cone_basis(const float d[3], float t[3], float b[3]);
/* A direction distributed uniformly in solid angle over the cap of half-angle `half` (radians)
 * about unit `axis`, from u1, u2 in [0, 1). */
void gib_cone_cap_sample(const float axis[3], float half, float u1, float u2, float d[3]);

#endif

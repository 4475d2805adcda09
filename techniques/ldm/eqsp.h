/* gibench — deterministic LDM directions (Aalund, Frisvad, Bærentzen 2015, Sec. 3.2 and 3.3):
 * Leopardi's recursive zonal equal-area partition of the sphere (EQSP, ETNA 25, 2006), written from
 * the algorithm's description, and the LDM vectors for N directions: the first N centres of the
 * EQSP of S^2 into 2N regions, so that the 2N directions +-v_i each stand for 2 pi / N sr (Eq. 2
 * with weight 2/N). ldm_directions_axis() maps the toolbox pole (+z) to a scene's up axis by a
 * cyclic permutation. Deterministic (plain double arithmetic, no allocation) and O(N). The
 * partition step by step, the hemisphere sample set and its measured convergence:
 * techniques/ldm/EQSP.md. */
#ifndef GIB_LDM_EQSP_H
#define GIB_LDM_EQSP_H

/* Largest region count the functions accept (2N for the LDM directions). */
#define LDM_EQSP_MAX_REGIONS (1 << 24)

/* Zones of the EQSP of S^2 into n regions: the North cap, the collars, the South cap.
 * caps[k] is the colatitude of the bottom of zone k (caps[0] = polar cap colatitude, last = pi);
 * regions[k] is the number of regions in zone k (1 for the caps; n = 1: one zone, caps[0] = pi).
 * Returns the zone count (collars + 2, or 1 when n = 1), or -1 when n < 1 or n is too large; writes
 * at most max_zones entries (either array may be NULL), so a call with max_zones = 0 sizes them. */
int ldm_eqsp_caps(int n, double *caps, int *regions, int max_zones);

/* Region k of the EQSP of S^2 into n regions, in toolbox order, as 4 doubles per region:
 * lon_lo, lon_hi (radians; 0 <= lon_lo < 2*pi, lon_lo < lon_hi <= lon_lo + 2*pi — a sector that
 * wraps past 2*pi has lon_hi > 2*pi), colat_top, colat_bot. The caps span [0, 2*pi], a
 * single-region collar [2*pi*o, 2*pi*o + 2*pi] (the toolbox writes a zero-width interval there).
 * Returns n (or -1); writes at most max regions (4*max doubles). */
int ldm_eqsp_regions(int n, double *bounds, int max);

/* Region centres in spherical polar coordinates (2 doubles per point: longitude in [0, 2*pi),
 * colatitude), as eq_point_set_polar(2, n). Returns n (or -1); writes at most max points. */
int ldm_eqsp_points_polar(int n, double *lon_colat, int max);

/* Region centres as unit vectors (3 doubles per point), as eq_point_set(2, n). Returns n (or -1);
 * writes at most max points. */
int ldm_eqsp_points(int n, double *xyz, int max);

/* The N LDM view vectors for `directions` = n (see 2. above), unit length, 3 floats each, pole +z.
 * Returns n, or -1 when n < 1, 2n exceeds LDM_EQSP_MAX_REGIONS, or EQSP(2n) is not symmetric
 * about the equator (never observed); writes at most max vectors. */
int ldm_directions(int n, float *dirs, int max);

/* As ldm_directions, with the pole on axis pole_axis (0 = x, 1 = y, 2 = z) by a cyclic permutation
 * of the coordinates: world[(pole_axis + 1 + c) % 3] = toolbox[c]. Returns -1 for a bad axis. */
int ldm_directions_axis(int n, int pole_axis, float *dirs, int max);

#endif

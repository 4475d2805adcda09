/* gibench — deterministic LDM directions (Aalund, Frisvad, Bærentzen 2015, Sec. 3.2 and 3.3).
 *
 * 1. EQSP: Leopardi's recursive zonal equal-area partition of S^2 ("A partition of the unit sphere
 *    into regions of equal area and small diameter", ETNA 25, 2006), as the EQ sphere partitioning
 *    toolbox computes it (eq_caps, eq_regions, eq_point_set with the default options, i.e. no
 *    "extra" offset). Written from the algorithm's description, not copied:
 *      - every region has area A = 4*pi/n;
 *      - the polar caps have colatitude c = 2 asin(sqrt(A/pi)/2);
 *      - the ideal collar angle is sqrt(A); the number of collars is max(1, round((pi-2c)/sqrt(A)))
 *        (no collars for n <= 2); the collars first get equal colatitude height (pi-2c)/collars;
 *      - the ideal (real) number of regions of each collar, collar area / A, is rounded in order
 *        from the North pole, carrying the accumulated rounding error a to the next zone:
 *        m_k = round(r_k + a), a += r_k - m_k (round half away from zero);
 *      - the cap colatitudes are then recomputed so that cap k encloses exactly
 *        (1 + m_1 + ... + m_k) * A;
 *      - collar k is split into m_k equal longitude sectors; successive collars are rotated by the
 *        accumulated offset o (in turns) of eq_point_set_polar / eq_regions for S^2:
 *        o_1 = 0, o_{k+1} = frac(o_k + (1/m_{k+1} - 1/m_k)/2 + gcd(m_k, m_{k+1})/(2 m_k m_{k+1})),
 *        where m_{k+1} of the last collar is the South cap's 1;
 *      - a region's centre is (colatitude midway between its caps, longitude midway along its
 *        sector), i.e. longitude 2*pi*o_k + (2j-1)*pi/m_k for j = 1..m_k; the caps' centres are the
 *        poles; a collar of a single region (only n = 3 has one) has its centre at longitude
 *        2*pi*o_k, as in the toolbox;
 *      - Cartesian: x = sin(colat) cos(lon), y = sin(colat) sin(lon), z = cos(colat); the North
 *        pole is +z. Order: North cap, collars from North to South (each by increasing j), South cap.
 *
 * 2. LDM directions for the `directions` parameter N (the number of LDMs). One LDM along v is
 *    traced both ways, v and -v (Sec. 3.1), so the N LDMs give 2N sample directions over the sphere,
 *    and Eq. 2 (weight 2/N over the N sample directions in a hemisphere) needs each of those 2N
 *    directions to stand for solid angle 4*pi/(2N) = 2*pi/N. So:
 *
 *      the N LDM vectors v_0..v_{N-1} are the FIRST N centres of the EQSP of S^2 into 2N regions.
 *
 *    For even region counts the zone sizes of the partition read the same from either pole (checked
 *    for every even count up to 20000 by the test), so its North half ends exactly at the equator,
 *    and the first N centres are the North cap, every collar wholly in the North hemisphere and,
 *    when the number of collars is odd, the first half (toolbox order: longitudes 2*pi*o + [0, pi))
 *    of the equatorial collar, whose other half holds exactly their antipodes. That is the "half of
 *    the samples in the bottom ring culled" of Figure 5, whose 128 samples are this set for
 *    N = 128: EQSP(256) has zones 1 7 12 18 22 26 28 28 28 26 ... 1 (13 collars) and
 *    1+7+12+18+22+26+28+28/2 = 128. (ldm_directions checks that the North half ends at the
 *    equator — after N regions at a zone boundary, or in the middle of an even collar — and fails
 *    otherwise.) Every v_i has z >= 0 (z = 0 exactly for the equatorial ones), and no two are
 *    parallel or antiparallel.
 *    The 2N directions {+v_i, -v_i} are the centres of an exactly equal-area, antipodally symmetric
 *    partition of S^2 (the North half of EQSP(2N), its equatorial collar, and the point reflection
 *    of its North half); its South half differs from EQSP(2N)'s only by a rotation of each collar in
 *    longitude.
 *
 *    Hemisphere sample set of Eq. 2 for a surface with unit normal n: for each LDM i, the sample
 *    direction is w_i = sign(n.v_i) v_i, i.e. whichever of v_i, -v_i has cos > 0 (when n.v_i = 0
 *    the sample has weight 0 and either may be taken), and
 *        AO(x) ~= (2/N) * sum_{i<N} V(x, w_i) * |n . v_i|.
 *    For V = 1 this is (2/N) sum |n.v_i| -> 1, with first-order convergence (measured over 2000
 *    normals plus the axes: worst |AO - 1| between 0.74/N and 0.85/N for N = 16..8192, largest for
 *    normals along the pole; RMS about 0.18/N; e.g. worst 0.0059 at N = 128, 0.0017 at N = 512).
 *    tests/ldm/test_eqsp.c holds it to 1/N.
 *    For photon splitting (Sec. 3.4) all 2N directions +-v_i are used.
 *
 *    ldm_directions() returns the v_i in the toolbox frame (pole +z); ldm_directions_axis() maps the
 *    pole to another axis by a cyclic permutation of the coordinates (a proper rotation), e.g.
 *    pole_axis = 1 for y-up scenes: (x, y, z)_world = (y, z, x)_toolbox.
 *
 * Everything is deterministic (plain double arithmetic, no allocation) and O(N). */
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

/* gibench — unit tests of techniques/ldm/eqsp.c: Leopardi's EQ partition of S^2 and the LDM
 * direction set of Aalund et al. 2015 (Sec. 3.2, Eq. 2). Each check prints expected, measured and
 * tolerance; the exit status is the number of failed checks (capped). */
#include "tests/common/check.h"
#include "techniques/ldm/eqsp.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static int failures;

/* Why a tolerance is what it is: counts and integers exact, double arithmetic to its rounding, the
 * float directions to theirs, the EQSP toolbox's printed values to their 4 decimals, and Eq. 2's
 * worst error to 1/N (measured 0.74/N to 0.85/N for N = 16 to 8192). */
static const char *why(double tol)
{
    return tol == 0      ? "exact"
           : tol <= 1e-9 ? "double rounding"
           : tol <= 1e-6 ? "float rounding"
           : tol <= 1e-4 ? "the toolbox's values to 4 decimals"
                         : "1/N: Eq. 2's worst error, measured 0.74/N-0.85/N";
}
#define check(what, want, got, tol) CHECK_NEAR(what, want, got, tol, why(tol))



static void *xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p) {
        fprintf(stderr, "out of memory\n");
        exit(2);
    }
    return p;
}


/* ---- zones --------------------------------------------------------------------------------- */

static void test_caps(void)
{
    double caps[64];
    int reg[64];
    char name[96];

    int z = ldm_eqsp_caps(10, caps, reg, 64);
    check("N=10 zone count", 4, z, 0);
    const double c10[4] = {0.6435, 1.5708, 2.4981, 3.1416};
    const int r10[4] = {1, 4, 4, 1};
    for (int k = 0; k < 4 && k < z; k++) {
        snprintf(name, sizeof name, "N=10 cap colatitude %d", k);
        check(name, c10[k], caps[k], 1e-4);
        snprintf(name, sizeof name, "N=10 regions in zone %d", k);
        check(name, r10[k], reg[k], 0);
    }

    z = ldm_eqsp_caps(4, caps, reg, 64);
    check("N=4 polar cap colatitude", 1.0472, caps[0], 1e-4);
    check("N=4 zone count (cap, one collar, cap)", 3, z, 0);
    check("N=4 regions in the collar", 2, reg[1], 0);

    z = ldm_eqsp_caps(1024, caps, reg, 64);
    const int r1024[7] = {1, 7, 13, 19, 25, 31, 35};
    for (int k = 0; k < 7; k++) {
        snprintf(name, sizeof name, "N=1024 regions in zone %d", k);
        check(name, r1024[k], reg[k], 0);
    }
    check("N=1024 zone count (27 collars + 2 caps)", 29, z, 0);

    /* Figure 5 of the paper: N = 128 LDMs come from EQSP(256), 13 collars, 28 at the equator. */
    z = ldm_eqsp_caps(256, caps, reg, 64);
    check("N=256 zone count (13 collars + 2 caps)", 15, z, 0);
    check("N=256 equatorial collar regions", 28, reg[7], 0);
    check("N=256 equatorial collar centre colatitude", M_PI / 2, 0.5 * (caps[6] + caps[7]), 1e-12);

    /* degenerate counts */
    z = ldm_eqsp_caps(1, caps, reg, 64);
    check("N=1 zone count", 1, z, 0);
    check("N=1 cap colatitude", M_PI, caps[0], 0);
    z = ldm_eqsp_caps(2, caps, reg, 64);
    check("N=2 zone count", 2, z, 0);
    check("N=2 polar cap colatitude", M_PI / 2, caps[0], 0);
    z = ldm_eqsp_caps(3, caps, reg, 64);
    check("N=3 zone count", 3, z, 0);
    check("N=3 regions in the collar", 1, reg[1], 0);
    check("N=0 rejected", -1, ldm_eqsp_caps(0, caps, reg, 64), 0);
    check("sizing call (max_zones 0) returns the zone count", 29,
          ldm_eqsp_caps(1024, NULL, NULL, 0), 0);
}

/* ---- the toolbox's documented examples --------------------------------------------------- */

static void test_toolbox_examples(void)
{
    /* eq_point_set_polar(2,4) = [0 pi/2 3pi/2 0; 0 pi/2 pi/2 pi] (longitude; colatitude) */
    double p[8], b[16], x[12];
    const double ep[8] = {0, 0, M_PI / 2, M_PI / 2, 3 * M_PI / 2, M_PI / 2, 0, M_PI};
    check("eq_point_set_polar(2,4) count", 4, ldm_eqsp_points_polar(4, p, 4), 0);
    double err = 0;
    for (int i = 0; i < 8; i++)
        err = fmax(err, fabs(p[i] - ep[i]));
    check("eq_point_set_polar(2,4) max abs difference", 0, err, 1e-12);
    /* eq_point_set(2,4): (0,0,1), (0,1,0), (0,-1,0), (0,0,-1) */
    const double ex[12] = {0, 0, 1, 0, 1, 0, 0, -1, 0, 0, 0, -1};
    ldm_eqsp_points(4, x, 4);
    err = 0;
    for (int i = 0; i < 12; i++)
        err = fmax(err, fabs(x[i] - ex[i]));
    check("eq_point_set(2,4) max abs difference", 0, err, 1e-12);
    /* eq_regions(2,4): [0,2pi]x[0,pi/3], [0,pi]x[pi/3,2pi/3], [pi,2pi]x[pi/3,2pi/3],
     * [0,2pi]x[2pi/3,pi] */
    const double eb[16] = {0,         2 * M_PI,     0,        M_PI / 3,
                           0,         M_PI,         M_PI / 3, 2 * M_PI / 3,
                           M_PI,      2 * M_PI,     M_PI / 3, 2 * M_PI / 3,
                           0,         2 * M_PI,     2 * M_PI / 3, M_PI};
    check("eq_regions(2,4) count", 4, ldm_eqsp_regions(4, b, 4), 0);
    err = 0;
    for (int i = 0; i < 16; i++)
        err = fmax(err, fabs(b[i] - eb[i]));
    check("eq_regions(2,4) max abs difference", 0, err, 1e-12);

    /* N = 10 by hand from the algorithm: collar 1 (4 regions, offset 0) at longitudes
     * pi/4 + k pi/2; the offset to collar 2 (4 regions) is (1/4-1/4)/2 + gcd(4,4)/(2*4*4) = 1/8
     * turn, so collar 2 is at pi/2 + k pi/2; colatitudes midway between the caps. */
    double q[20];
    ldm_eqsp_points_polar(10, q, 10);
    double caps[4];
    ldm_eqsp_caps(10, caps, NULL, 4);
    err = 0;
    for (int k = 0; k < 4; k++) {
        double l1 = M_PI / 4 + k * M_PI / 2, l2 = fmod(M_PI / 2 + k * M_PI / 2, 2 * M_PI);
        double d1 = fabs(q[2 * (1 + k)] - l1), d2 = fabs(q[2 * (5 + k)] - l2);
        d2 = fmin(d2, 2 * M_PI - d2);
        err = fmax(err, fmax(d1, d2));
        err = fmax(err, fabs(q[2 * (1 + k) + 1] - 0.5 * (caps[0] + caps[1])));
        err = fmax(err, fabs(q[2 * (5 + k) + 1] - 0.5 * (caps[1] + caps[2])));
    }
    check("N=10 centres (hand-derived offsets) max abs difference", 0, err, 1e-12);
}

/* ---- partition properties over many N ------------------------------------------------------ */

static double wrap_diff(double a, double lo) /* a - lo in [0, 2pi) */
{
    double d = fmod(a - lo, 2 * M_PI);
    return d < 0 ? d + 2 * M_PI : d;
}

typedef struct part_stats {
    double area_err, sum_err, unit_err, polar_xyz_err, outside;
    int count_bad, zone_sum_bad;
} part_stats;

static void partition_stats(int n, part_stats *s)
{
    double *b = xmalloc(sizeof(double) * 4 * (size_t)n);
    double *p = xmalloc(sizeof(double) * 2 * (size_t)n);
    double *x = xmalloc(sizeof(double) * 3 * (size_t)n);
    int zc = ldm_eqsp_caps(n, NULL, NULL, 0);
    int *reg = xmalloc(sizeof(int) * (size_t)zc);
    ldm_eqsp_caps(n, NULL, reg, zc);
    long zs = 0;
    for (int k = 0; k < zc; k++)
        zs += reg[k];
    if (zs != n)
        s->zone_sum_bad++;
    if (ldm_eqsp_regions(n, b, n) != n || ldm_eqsp_points_polar(n, p, n) != n ||
        ldm_eqsp_points(n, x, n) != n)
        s->count_bad++;
    double ideal = 4 * M_PI / n, total = 0;
    for (int i = 0; i < n; i++) {
        const double *r = b + 4 * i;
        double area = (cos(r[2]) - cos(r[3])) * (r[1] - r[0]);
        total += area;
        s->area_err = fmax(s->area_err, fabs(area - ideal));
        double lon = p[2 * i], colat = p[2 * i + 1];
        double len = sqrt(x[3 * i] * x[3 * i] + x[3 * i + 1] * x[3 * i + 1] +
                          x[3 * i + 2] * x[3 * i + 2]);
        s->unit_err = fmax(s->unit_err, fabs(len - 1));
        double e = fmax(fabs(x[3 * i + 2] - cos(colat)),
                        fmax(fabs(x[3 * i] - sin(colat) * cos(lon)),
                             fabs(x[3 * i + 1] - sin(colat) * sin(lon))));
        s->polar_xyz_err = fmax(s->polar_xyz_err, e);
        /* how far outside its region the centre lies (0 when inside) */
        double out = 0;
        if (colat < r[2])
            out = fmax(out, r[2] - colat);
        if (colat > r[3])
            out = fmax(out, colat - r[3]);
        double dl = wrap_diff(lon, r[0]);
        if (dl > r[1] - r[0] && dl - (r[1] - r[0]) < 2 * M_PI - dl)
            out = fmax(out, dl - (r[1] - r[0]));
        else if (dl > r[1] - r[0])
            out = fmax(out, 2 * M_PI - dl);
        s->outside = fmax(s->outside, out);
    }
    s->sum_err = fmax(s->sum_err, fabs(total - 4 * M_PI));
    free(b);
    free(p);
    free(x);
    free(reg);
}

static void test_partition(void)
{
    part_stats s;
    memset(&s, 0, sizeof s);
    for (int n = 1; n <= 3000; n++)
        partition_stats(n, &s);
    const int big[] = {4096, 10007, 65536, 262144};
    for (unsigned k = 0; k < sizeof big / sizeof big[0]; k++)
        partition_stats(big[k], &s);
    printf("     (partitions N = 1..3000, 4096, 10007, 65536, 262144)\n");
    check("zone counts sum to N (failures)", 0, s.zone_sum_bad, 0);
    check("region/point counts == N (failures)", 0, s.count_bad, 0);
    check("max |region area - 4 pi/N|", 0, s.area_err, 1e-9);
    check("max |sum of region areas - 4 pi|", 0, s.sum_err, 1e-9);
    check("max ||centre| - 1|", 0, s.unit_err, 1e-12);
    check("max |xyz - polar2cart(lon, colat)|", 0, s.polar_xyz_err, 1e-12);
    check("max distance of a centre outside its region (rad)", 0, s.outside, 1e-12);

    /* Even region counts: zone sizes read the same from both poles (the basis of the LDM set). */
    int asym = 0, first = 0;
    int *reg = xmalloc(sizeof(int) * 4096);
    for (int n = 2; n <= 20000; n += 2) {
        int z = ldm_eqsp_caps(n, NULL, reg, 4096);
        for (int k = 0; k < z; k++)
            if (reg[k] != reg[z - 1 - k]) {
                if (!asym)
                    first = n;
                asym++;
                break;
            }
    }
    free(reg);
    if (asym)
        printf("     first asymmetric even N: %d\n", first);
    check("even N <= 20000 with asymmetric zone sizes", 0, asym, 0);
}

/* ---- LDM directions -------------------------------------------------------------------------- */

static double dot3f(const float *a, const double *n)
{
    return (double)a[0] * n[0] + (double)a[1] * n[1] + (double)a[2] * n[2];
}

/* Eq. 2 with V = 1: (2/N) sum over the hemisphere sample of each LDM (w_i = +-v_i, cos > 0). */
static double ao_constant(const float *v, int n, const double nrm[3])
{
    double s = 0;
    for (int i = 0; i < n; i++) {
        double c = dot3f(v + 3 * i, nrm);
        s += c > 0 ? c : -c; /* cos of whichever of v_i, -v_i lies in the hemisphere of nrm */
    }
    return 2.0 * s / n;
}

/* worst |AO - 1| over 2000 normals spread over the sphere (Fibonacci lattice) plus the axes */
static double ao_worst(const float *v, int n, double *rms)
{
    const int m = 2000;
    double worst = 0, ss = 0, ga = M_PI * (3 - sqrt(5.0));
    for (int k = 0; k < m + 6; k++) {
        double nrm[3] = {0, 0, 0};
        if (k < m) {
            double z = 1 - (2 * k + 1.0) / m, r = sqrt(1 - z * z);
            nrm[0] = r * cos(ga * k);
            nrm[1] = r * sin(ga * k);
            nrm[2] = z;
        } else {
            nrm[(k - m) % 3] = (k - m) < 3 ? 1 : -1;
        }
        double e = fabs(ao_constant(v, n, nrm) - 1);
        worst = fmax(worst, e);
        ss += e * e;
    }
    *rms = sqrt(ss / (m + 6));
    return worst;
}

static void test_directions(void)
{
    char name[128];
    /* Every N up to 10000 works and returns N. */
    int bad = 0;
    for (int n = 1; n <= 10000; n++)
        if (ldm_directions(n, NULL, 0) != n)
            bad++;
    check("ldm_directions(N) != N for N = 1..10000 (failures)", 0, bad, 0);
    check("ldm_directions(0) rejected", -1, ldm_directions(0, NULL, 0), 0);
    check("ldm_directions_axis bad axis rejected", -1, ldm_directions_axis(8, 3, NULL, 0), 0);

    const int ns[] = {1, 2, 3, 32, 128, 512, 2048};
    double prev_worst = 1e9;
    for (unsigned t = 0; t < sizeof ns / sizeof ns[0]; t++) {
        int n = ns[t];
        float *v = xmalloc(sizeof(float) * 3 * (size_t)n);
        float *v2 = xmalloc(sizeof(float) * 3 * (size_t)n);
        double *c = xmalloc(sizeof(double) * 3 * 2 * (size_t)n);
        snprintf(name, sizeof name, "N=%d count", n);
        check(name, n, ldm_directions(n, v, n), 0);
        ldm_directions(n, v2, n);
        snprintf(name, sizeof name, "N=%d deterministic (bytes differing)", n);
        check(name, 0, memcmp(v, v2, sizeof(float) * 3 * (size_t)n) != 0, 0);

        /* = the first N centres of EQSP(2N), z >= 0, unit length */
        ldm_eqsp_points(2 * n, c, 2 * n);
        double diff = 0, zmin = 1, unit = 0;
        int on_eq = 0;
        for (int i = 0; i < n; i++) {
            double l = 0;
            for (int k = 0; k < 3; k++) {
                diff = fmax(diff, fabs(v[3 * i + k] - c[3 * i + k]));
                l += (double)v[3 * i + k] * v[3 * i + k];
            }
            unit = fmax(unit, fabs(sqrt(l) - 1));
            zmin = fmin(zmin, v[3 * i + 2]);
            on_eq += v[3 * i + 2] == 0.0f;
        }
        snprintf(name, sizeof name, "N=%d max |v_i - EQSP(2N) centre i|", n);
        check(name, 0, diff, 1e-6);
        snprintf(name, sizeof name, "N=%d max ||v_i| - 1|", n);
        check(name, 0, unit, 1e-6);
        snprintf(name, sizeof name, "N=%d min z (closed North hemisphere)", n);
        CHECK_AT_LEAST(name, zmin, 0, "the directions lie in the closed North hemisphere");
        if (n == 128) {
            /* Figure 5: 28 equatorial centres of EQSP(256), half of them kept */
            check("N=128 directions on the equator (half of 28)", 14, on_eq, 0);
        }

        /* no two parallel or antiparallel */
        double maxdot = 0;
        for (int i = 0; i < n; i++)
            for (int j = i + 1; j < n; j++) {
                double d = fabs((double)v[3 * i] * v[3 * j] + (double)v[3 * i + 1] * v[3 * j + 1] +
                                (double)v[3 * i + 2] * v[3 * j + 2]);
                maxdot = fmax(maxdot, d);
            }
        if (n > 1) {
            snprintf(name, sizeof name, "N=%d max |v_i . v_j| (i != j)", n);
            CHECK_AT_MOST(name, maxdot, 1 - 1e-6, "no two directions parallel or antiparallel");
        }

        /* Each of the 2N directions +-v_i stands for solid angle 2 pi/N, so the hemisphere
         * estimator of Eq. 2 integrates V = 1 to ~1. */
        if (n >= 32) {
            double rms, worst = ao_worst(v, n, &rms);
            double tol = 1.0 / n; /* measured worst: 0.74/N .. 0.85/N for N = 16..8192 */
            snprintf(name, sizeof name, "N=%d Eq.2 with V=1: worst |AO-1| (2006 normals)", n);
            check(name, 0, worst, tol);
            printf("     N=%d Eq.2 with V=1: RMS |AO-1| = %.3g, N*worst = %.3f\n", n, rms,
                   n * worst);
            snprintf(name, sizeof name, "N=%d worst error below that of N/4", n);
            CHECK_AT_MOST(name, worst, prev_worst, "more directions integrate V = 1 better");
            prev_worst = worst;
        }
        free(v);
        free(v2);
        free(c);
    }

    /* pole on y: a cyclic permutation (x,y,z)_world = (y,z,x)_toolbox */
    float a[3 * 64], b[3 * 64];
    ldm_directions(64, a, 64);
    ldm_directions_axis(64, 1, b, 64);
    double e = 0;
    for (int i = 0; i < 64; i++) {
        e = fmax(e, fabs(b[3 * i + 0] - a[3 * i + 1]));
        e = fmax(e, fabs(b[3 * i + 1] - a[3 * i + 2]));
        e = fmax(e, fabs(b[3 * i + 2] - a[3 * i + 0]));
    }
    check("pole_axis=1 is (y,z,x) of the toolbox frame", 0, e, 0);
    check("pole_axis=1: first direction is +y", 1, b[1], 0);

    /* max truncates the output but not the count */
    float few[6] = {7, 7, 7, 7, 7, 7};
    check("max=1 still returns N", 16, ldm_directions(16, few, 1), 0);
    check("max=1 writes one vector only", 7, few[3], 0);
}

int main(void)
{
    test_caps();
    test_toolbox_examples();
    test_partition();
    test_directions();
    printf("%s: %d failed check(s)\n", failures ? "FAIL" : "PASS", failures);
    return failures > 100 ? 100 : failures;
}

/* gibench — Leopardi's EQ partition of S^2 and the LDM directions derived from it (see eqsp.h for
 * the algorithm and the direction-set convention). */
#include "eqsp.h"

#include <math.h>
#include <stddef.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Spherical radius (colatitude) of an S^2 cap of the given area: area = 4 pi sin^2(s/2). */
static double cap_colat(double area)
{
    double h = sqrt(area / M_PI) / 2.0;
    if (h >= 1.0)
        return M_PI;
    return 2.0 * asin(h);
}

static int gcd_int(int a, int b)
{
    while (b) {
        int t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* Rotation (in turns) from a collar of n_top sectors to the next one of n_bot sectors that aligns
 * their sector centres and then maximises the smallest angle between the two sets of centres
 * (the toolbox's circle_offset without the extra twist). */
static double circle_offset(int n_top, int n_bot)
{
    return (1.0 / n_bot - 1.0 / n_top) / 2.0 +
           (double)gcd_int(n_top, n_bot) / (2.0 * (double)n_top * (double)n_bot);
}

/* Zones (North cap, collars, South cap) generated one at a time from the North pole, so nothing
 * is allocated: the rounding to whole region counts carries its error forward, and each cap
 * colatitude depends only on the regions above it. */
typedef struct zone_iter {
    int n;         /* regions of the partition */
    int zones;     /* collars + 2, or 1 for n = 1 */
    int k;         /* index of the next zone */
    double area;   /* 4 pi / n */
    double c_polar, a_fit;
    double err;    /* accumulated rounding error */
    long cum;      /* regions in zones 0..k-1 */
    double top;    /* colatitude of the top of zone k */
} zone_iter;

static int zi_init(zone_iter *it, int n)
{
    if (n < 1 || n > LDM_EQSP_MAX_REGIONS)
        return -1;
    it->n = n;
    it->k = 0;
    it->err = 0.0;
    it->cum = 0;
    it->top = 0.0;
    it->area = 4.0 * M_PI / n;
    if (n == 1) {
        it->zones = 1;
        it->c_polar = M_PI;
        it->a_fit = 0.0;
        return 0;
    }
    int collars = 0;
    if (n == 2) {
        it->c_polar = M_PI / 2.0;
    } else {
        it->c_polar = cap_colat(it->area);
        double ideal_angle = sqrt(it->area);
        collars = (int)lround((M_PI - 2.0 * it->c_polar) / ideal_angle);
        if (collars < 1)
            collars = 1;
    }
    it->zones = collars + 2;
    it->a_fit = collars > 0 ? (M_PI - 2.0 * it->c_polar) / collars : 0.0;
    return 0;
}

/* Next zone: its region count *m and its top and bottom colatitudes; 0 when there is none. */
static int zi_next(zone_iter *it, int *m, double *top, double *bot)
{
    if (it->k >= it->zones)
        return 0;
    int k = it->k;
    double ideal;
    if (k == 0 || k == it->zones - 1) {
        ideal = 1.0;
    } else {
        double t = it->c_polar + (k - 1) * it->a_fit;
        double b = it->c_polar + k * it->a_fit;
        ideal = 2.0 * M_PI * (cos(t) - cos(b)) / it->area;
    }
    int mk = (int)lround(ideal + it->err);
    it->err += ideal - mk;
    it->cum += mk;
    *m = mk;
    *top = it->top;
    if (k == it->zones - 1)
        *bot = M_PI;
    else if (k == 0)
        *bot = it->c_polar;
    else
        *bot = cap_colat((double)it->cum * it->area);
    it->top = *bot;
    it->k++;
    return 1;
}

int ldm_eqsp_caps(int n, double *caps, int *regions, int max_zones)
{
    zone_iter it;
    if (zi_init(&it, n))
        return -1;
    int m, k = 0;
    double top, bot;
    while (zi_next(&it, &m, &top, &bot)) {
        if (k < max_zones) {
            if (caps)
                caps[k] = bot;
            if (regions)
                regions[k] = m;
        }
        k++;
    }
    return k;
}

/* Walks the regions of EQSP(n) in toolbox order, calling emit for each with its zone and sector
 * geometry. Stops early when emit returns non-zero. */
typedef struct region_info {
    int zone, zones;   /* zone index, zone count */
    int j, m;          /* sector j (0-based) of m in this zone */
    double top, bot;   /* colatitudes */
    double lon0;       /* 2 pi * offset of the zone (0 for the caps) */
} region_info;

typedef int (*region_fn)(void *ctx, const region_info *r);

static int walk_regions(int n, region_fn emit, void *ctx)
{
    zone_iter it;
    if (zi_init(&it, n))
        return -1;
    region_info r;
    int m, prev_m = 0;
    double offset = 0.0;
    r.zones = it.zones;
    for (r.zone = 0; zi_next(&it, &m, &r.top, &r.bot); r.zone++) {
        int is_collar = r.zone > 0 && r.zone < it.zones - 1;
        if (is_collar && prev_m > 0) {
            offset += circle_offset(prev_m, m);
            offset -= floor(offset);
        }
        r.lon0 = is_collar ? 2.0 * M_PI * offset : 0.0;
        r.m = m;
        for (r.j = 0; r.j < m; r.j++)
            if (emit(ctx, &r))
                return n;
        prev_m = is_collar ? m : 0;
    }
    return n;
}

/* Longitude of the centre of sector j of the zone, in [0, 2 pi). */
static double centre_lon(const region_info *r)
{
    if (r->m == 1)
        return r->lon0;
    return fmod(r->lon0 + (2.0 * r->j + 1.0) * M_PI / r->m, 2.0 * M_PI);
}

/* Colatitude of the centre: the poles for the caps, else midway between the zone's caps. */
static double centre_colat(const region_info *r)
{
    if (r->zone == 0)
        return 0.0;
    if (r->zone == r->zones - 1)
        return M_PI;
    return 0.5 * (r->top + r->bot);
}

typedef struct out_ctx {
    double *d;
    float *f;
    int i, max, count;
    int pole_axis;
} out_ctx;

static int emit_bounds(void *p, const region_info *r)
{
    out_ctx *c = p;
    if (c->i < c->max && c->d) {
        double *b = c->d + 4 * c->i;
        double lo, hi;
        int is_cap = r->zone == 0 || r->zone == r->zones - 1;
        if (is_cap) {
            lo = 0.0;
            hi = 2.0 * M_PI;
        } else if (r->m == 1) {
            lo = r->lon0;
            hi = r->lon0 + 2.0 * M_PI;
        } else {
            lo = fmod(r->lon0 + 2.0 * M_PI * r->j / r->m, 2.0 * M_PI);
            hi = fmod(r->lon0 + 2.0 * M_PI * (r->j + 1) / r->m, 2.0 * M_PI);
            if (hi <= lo)
                hi += 2.0 * M_PI;
        }
        b[0] = lo;
        b[1] = hi;
        b[2] = r->top;
        b[3] = r->bot;
    }
    c->i++;
    return 0;
}

static int emit_polar(void *p, const region_info *r)
{
    out_ctx *c = p;
    if (c->i < c->max && c->d) {
        c->d[2 * c->i] = centre_lon(r);
        c->d[2 * c->i + 1] = centre_colat(r);
    }
    c->i++;
    return 0;
}

static int emit_xyz(void *p, const region_info *r)
{
    out_ctx *c = p;
    if (c->i < c->max && c->d) {
        double lon = centre_lon(r), colat = centre_colat(r);
        double s = sin(colat);
        c->d[3 * c->i] = s * cos(lon);
        c->d[3 * c->i + 1] = s * sin(lon);
        c->d[3 * c->i + 2] = cos(colat);
    }
    c->i++;
    return 0;
}

int ldm_eqsp_regions(int n, double *bounds, int max)
{
    out_ctx c = {bounds, NULL, 0, max, 0, 2};
    return walk_regions(n, emit_bounds, &c);
}

int ldm_eqsp_points_polar(int n, double *lon_colat, int max)
{
    out_ctx c = {lon_colat, NULL, 0, max, 0, 2};
    return walk_regions(n, emit_polar, &c);
}

int ldm_eqsp_points(int n, double *xyz, int max)
{
    out_ctx c = {xyz, NULL, 0, max, 0, 2};
    return walk_regions(n, emit_xyz, &c);
}

/* The first N = count centres of EQSP(2N). The North half must end exactly at the equator: either
 * a zone boundary after N regions, or a collar straddling the equator whose first half completes
 * N (then its two halves are antipodal). Its centres are put exactly on z = 0. */
static int emit_direction(void *p, const region_info *r)
{
    out_ctx *c = p;
    if (c->i >= c->count)
        return 1;
    int before = c->i - r->j; /* regions in the zones above */
    int equatorial = before + r->m > c->count;
    if (equatorial && (r->m % 2 != 0 || before + r->m / 2 != c->count)) {
        c->i = -1; /* not symmetric about the equator */
        return 1;
    }
    if (c->i >= c->max || !c->f) {
        c->i++;
        return c->i >= c->count;
    }
    double v[3];
    double lon = centre_lon(r);
    if (equatorial) {
        v[0] = cos(lon);
        v[1] = sin(lon);
        v[2] = 0.0;
    } else {
        double colat = centre_colat(r), s = sin(colat);
        v[0] = s * cos(lon);
        v[1] = s * sin(lon);
        v[2] = cos(colat);
    }
    float *o = c->f + 3 * c->i;
    for (int k = 0; k < 3; k++)
        o[(c->pole_axis + 1 + k) % 3] = (float)v[k];
    c->i++;
    return c->i >= c->count;
}

int ldm_directions_axis(int n, int pole_axis, float *dirs, int max)
{
    if (n < 1 || n > LDM_EQSP_MAX_REGIONS / 2 || pole_axis < 0 || pole_axis > 2)
        return -1;
    out_ctx c = {NULL, dirs, 0, max, n, pole_axis};
    if (walk_regions(2 * n, emit_direction, &c) < 0 || c.i != n)
        return -1;
    return n;
}

int ldm_directions(int n, float *dirs, int max)
{
    return ldm_directions_axis(n, 2, dirs, max);
}

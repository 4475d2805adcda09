/* gibench — a procedural stand-in for the hairball of the LDM paper (2.88M triangles there): many
 * thin tubes following smoothed random walks inside a ball, so that a ray through the middle
 * crosses tens of surfaces (high depth complexity) while the triangle count stays tractable on
 * llvmpipe.
 *
 * Deterministic from `seed`: its own PCG32 generator (O'Neill, pcg-random.org, the minimal
 * 32-bit variant), and only +, -, *, / and sqrt on doubles in the walk (correctly rounded in IEEE
 * arithmetic; the project builds C11 without extensions, so GCC contracts nothing into FMAs), so
 * the paths are the same on every machine; cos/sin, from the C library, enter only the directions
 * around a ring.
 *
 * Each tube: a start point uniform in the ball of radius 0.9 R, a random unit direction, then
 * `segments` steps of length 2.4 R / segments. Before each step the direction is bent by a random
 * unit vector times 0.5 and, beyond 0.75 R from the centre, pulled toward the centre (by the unit
 * vector to the centre times 2 (|p| / R - 0.75) / 0.25), then renormalised, and the turn is
 * halved until it is at most 60 degrees (sharper turns fold a tube's rings); a point beyond
 * R - thickness is moved back onto that radius, so all geometry lies inside the ball. Around the
 * path: rings of `sides` vertices at distance `thickness`, in rotation-minimising frames (each
 * frame's reference vector projected onto the new ring plane), joined into quads of two
 * triangles. The ends are open. Normals are SMOOTH (the unit vector from the path to the vertex),
 * unlike the flat-faced generators: hair is round.
 *
 * Counts: tubes x (segments + 1) x sides vertices, tubes x segments x sides x 2 triangles. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

typedef struct pcg32 {
    uint64_t state, inc;
} pcg32;

static uint32_t pcg32_next(pcg32 *r)
{
    const uint64_t old = r->state;
    r->state = old * 6364136223846793005ull + r->inc;
    const uint32_t xorshifted = (uint32_t)(((old >> 18) ^ old) >> 27);
    const uint32_t rot = (uint32_t)(old >> 59);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

static void pcg32_seed(pcg32 *r, uint64_t seed, uint64_t stream)
{
    r->state = 0;
    r->inc = (stream << 1) | 1u;
    pcg32_next(r);
    r->state += seed;
    pcg32_next(r);
}

/* Uniform in [-1, 1). */
static double sym(pcg32 *r)
{
    return (double)pcg32_next(r) * (2.0 / 4294967296.0) - 1.0;
}

static double len3(const double v[3])
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* Uniform in the unit ball (rejection from the cube); when unit, scaled to length 1. */
static void random_in_ball(pcg32 *r, double out[3], int unit)
{
    for (;;) {
        out[0] = sym(r);
        out[1] = sym(r);
        out[2] = sym(r);
        const double l2 = out[0] * out[0] + out[1] * out[1] + out[2] * out[2];
        if (l2 <= 1.0 && l2 > 1e-6)
            break;
    }
    if (unit) {
        const double l = len3(out);
        out[0] /= l;
        out[1] /= l;
        out[2] /= l;
    }
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* u made perpendicular to unit t and unit length; falls back to the axis least along t. */
static void perpendicular(const double t[3], double u[3])
{
    for (int attempt = 0; attempt < 2; attempt++) {
        const double d = u[0] * t[0] + u[1] * t[1] + u[2] * t[2];
        double v[3] = {u[0] - d * t[0], u[1] - d * t[1], u[2] - d * t[2]};
        const double l = len3(v);
        if (l > 1e-6) {
            u[0] = v[0] / l;
            u[1] = v[1] / l;
            u[2] = v[2] / l;
            return;
        }
        const double ax = fabs(t[0]), ay = fabs(t[1]), az = fabs(t[2]);
        u[0] = ax <= ay && ax <= az;
        u[1] = !u[0] && ay <= az;
        u[2] = !u[0] && !u[1];
    }
}

/* The ball's and the tubes' measures, shared by every tube. */
typedef struct hair_shape {
    double radius, thick, step, limit; /* limit: how far from the centre a path point may be */
    uint32_t segs, sides, material;
    double ring_c[64], ring_s[64];     /* cos and sin around a ring */
} hair_shape;

/* The next direction: dir bent by the random unit vector and, far out, pulled toward the centre;
 * at most 60 degrees per step: the turn is halved until it is (a sharper turn would fold the
 * tube's rings into each other on the inside of the bend). */
static void bend_direction(const hair_shape *h, const double pos[3], const double bend[3],
                           double dir[3])
{
    const double q = len3(pos) / h->radius;
    const double pull = q > 0.75 ? 2.0 * (q - 0.75) / 0.25 / (q * h->radius) : 0.0;
    double nd[3];
    for (int k = 0; k < 3; k++)
        nd[k] = dir[k] + 0.5 * bend[k] - pull * pos[k];
    for (int halve = 0;; halve++) {
        double l = len3(nd);
        if (!(l > 1e-9)) { /* an exact reversal: turn toward the random vector */
            memcpy(nd, bend, sizeof nd);
            l = 1.0;
        }
        for (int k = 0; k < 3; k++)
            nd[k] /= l;
        if (nd[0] * dir[0] + nd[1] * dir[1] + nd[2] * dir[2] >= 0.5 || halve == 8)
            break;
        for (int k = 0; k < 3; k++)
            nd[k] += dir[k];
    }
    memcpy(dir, nd, sizeof nd);
}

/* One tube's path: segs + 1 points of a random walk inside the ball. */
static void walk_tube(pcg32 *rng, const hair_shape *h, double *path)
{
    double pos[3], dir[3], bend[3];
    random_in_ball(rng, pos, 0);
    for (int k = 0; k < 3; k++)
        pos[k] *= 0.9 * h->radius;
    random_in_ball(rng, dir, 1);
    memcpy(path, pos, sizeof pos);
    for (uint32_t s = 1; s <= h->segs; s++) {
        random_in_ball(rng, bend, 1);
        bend_direction(h, pos, bend, dir);
        for (int k = 0; k < 3; k++)
            pos[k] += h->step * dir[k];
        const double pl = len3(pos);
        if (pl > h->limit)
            for (int k = 0; k < 3; k++)
                pos[k] *= h->limit / pl;
        memcpy(path + 3 * (size_t)s, pos, sizeof pos);
    }
}

/* The tube's rings of vertices around its path, in rotation-minimising frames. */
static void tube_rings(gib_geom *g, const hair_shape *h, const double *path)
{
    const uint32_t segs = h->segs;
    double u[3] = {0, 0, 0}, t[3] = {0, 0, 0};
    for (uint32_t s = 0; s <= segs; s++) {
        const double *a = path + 3 * (size_t)(s > 0 ? s - 1 : 0);
        const double *b = path + 3 * (size_t)(s < segs ? s + 1 : segs);
        double nt[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const double l = len3(nt);
        if (l > 1e-9 * h->radius || s == 0) /* else keep the previous tangent */
            for (int k = 0; k < 3; k++)
                t[k] = l > 0 ? nt[k] / l : (k == 2);
        perpendicular(t, u);
        double v[3];
        cross3(t, u, v);
        for (uint32_t j = 0; j < h->sides; j++) {
            double n[3];
            float fp[3], fn[3];
            for (int k = 0; k < 3; k++) {
                n[k] = h->ring_c[j] * u[k] + h->ring_s[j] * v[k];
                fp[k] = (float)(path[3 * (size_t)s + (size_t)k] + h->thick * n[k]);
                fn[k] = (float)n[k];
            }
            const float uv[2] = {(float)j / (float)h->sides, (float)s / (float)segs};
            gib_geom_vertex(g, fp, fn, uv);
        }
    }
}

/* Quads between rings s and s+1 of the tube whose first vertex is base, wound so that the normal
 * points out of the tube. */
static void tube_quads(gib_geom *g, const hair_shape *h, uint32_t base)
{
    const uint32_t sides = h->sides;
    for (uint32_t s = 0; s < h->segs; s++)
        for (uint32_t j = 0; j < sides; j++) {
            const uint32_t j1 = (j + 1) % sides;
            const uint32_t a = base + s * sides + j, b = base + s * sides + j1;
            const uint32_t c = base + (s + 1) * sides + j, d = base + (s + 1) * sides + j1;
            gib_geom_triangle(g, a, b, c, h->material);
            gib_geom_triangle(g, b, d, c, h->material);
        }
}

int gib_gen_hairball(gib_geom *g, const gib_proc_params *p, gib_error *err)
{
    hair_shape h;
    h.radius = gib_proc_get(p, GIB_PK_RADIUS, 0, GIB_HAIRBALL_RADIUS);
    h.thick = gib_proc_get(p, GIB_PK_THICKNESS, 0, GIB_HAIRBALL_THICKNESS * h.radius);
    const uint32_t tubes = (uint32_t)gib_proc_get(p, GIB_PK_TUBES, 0, GIB_HAIRBALL_TUBES);
    h.segs = (uint32_t)gib_proc_get(p, GIB_PK_SEGMENTS, 0, GIB_HAIRBALL_SEGMENTS);
    h.sides = (uint32_t)gib_proc_get(p, GIB_PK_SIDES, 0, GIB_HAIRBALL_SIDES);
    const uint64_t seed = (uint64_t)gib_proc_get(p, GIB_PK_SEED, 0, GIB_HAIRBALL_SEED);

    gib_mat_desc hair = gib_mat_desc_diffuse("hair", 0.6f, 0.6f, 0.6f);
    int m = gib_geom_material(g, &hair, err);
    if (m < 0 || gib_geom_reserve(g, tubes * (h.segs + 1) * h.sides,
                                  tubes * h.segs * h.sides * 2, err))
        return -1;
    h.material = (uint32_t)m;
    double *path = gib_calloc((size_t)(h.segs + 1) * 3, sizeof(double), err);
    if (!path)
        return -1;
    for (uint32_t j = 0; j < h.sides; j++) {
        h.ring_c[j] = cos(2.0 * M_PI * j / h.sides);
        h.ring_s[j] = sin(2.0 * M_PI * j / h.sides);
    }
    h.step = 2.4 * h.radius / h.segs;
    h.limit = h.radius - h.thick;
    pcg32 rng;
    pcg32_seed(&rng, seed, 0x9e3779b97f4a7c15ull);
    for (uint32_t tube = 0; tube < tubes; tube++) {
        walk_tube(&rng, &h, path);
        const uint32_t base = g->vcount;
        tube_rings(g, &h, path);
        tube_quads(g, &h, base);
    }
    free(path);
    return 0;
}

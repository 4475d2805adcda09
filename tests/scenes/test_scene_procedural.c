/* The procedural scenes beyond the Cornell box: the hairball (documented triangle count, same
 * content hash on every load, depth complexity measured by brute force), the furnace (a closed
 * sphere seen from inside: normals toward the centre, bounds +-R, light at the centre, the
 * tessellation numbers furnace.scene states), the generator keys' errors (file:line), and every
 * hard-case scene (loads, has a light and a camera, says "hard case:", finite data, and the
 * property it exists for). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scenes/scene.h"
#include "tests/scenes/scene_test.h"

static const double *vtx(const gib_scene *s, uint32_t tri, int k, double out[3])
{
    const float *p = s->positions + 3 * (size_t)s->indices[3 * (size_t)tri + (size_t)k];
    out[0] = p[0];
    out[1] = p[1];
    out[2] = p[2];
    return out;
}

static void sub(const double a[3], const double b[3], double o[3])
{
    o[0] = a[0] - b[0];
    o[1] = a[1] - b[1];
    o[2] = a[2] - b[2];
}

static void cross(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Corners whose vertex normal points against the triangle's winding (smooth normals of a closed
 * shape must agree with it). */
static uint32_t corners_against_winding(const gib_scene *s)
{
    uint32_t against = 0;
    for (uint32_t t = 0; t < s->triangle_count; t++) {
        double a[3], b[3], c[3], e1[3], e2[3], g[3];
        vtx(s, t, 0, a);
        vtx(s, t, 1, b);
        vtx(s, t, 2, c);
        sub(b, a, e1);
        sub(c, a, e2);
        cross(e1, e2, g);
        for (int k = 0; k < 3; k++) {
            const float *nf = s->normals + 3 * (size_t)s->indices[3 * (size_t)t + (size_t)k];
            const double n[3] = {nf[0], nf[1], nf[2]};
            against += dot(n, g) <= 0;
        }
    }
    return against;
}

/* How many triangles the whole line o + t d, t > 0, crosses (Moller-Trumbore in double). */
static int crossings(const gib_scene *s, const double o[3], const double d[3])
{
    int n = 0;
    for (uint32_t t = 0; t < s->triangle_count; t++) {
        double a[3], b[3], c[3], e1[3], e2[3], pv[3], tv[3], qv[3];
        vtx(s, t, 0, a);
        vtx(s, t, 1, b);
        vtx(s, t, 2, c);
        sub(b, a, e1);
        sub(c, a, e2);
        cross(d, e2, pv);
        const double det = dot(e1, pv);
        if (fabs(det) < 1e-300)
            continue;
        sub(o, a, tv);
        const double u = dot(tv, pv) / det;
        if (u < 0 || u > 1)
            continue;
        cross(tv, e1, qv);
        const double v = dot(d, qv) / det;
        if (v < 0 || u + v > 1)
            continue;
        n += dot(e2, qv) / det > 0;
    }
    return n;
}

/* Every vertex finite with a unit normal; indices in range; at least one light and camera. */
static void check_finite(const gib_scene *s)
{
    uint32_t bad = 0;
    for (uint32_t v = 0; v < s->vertex_count; v++) {
        const float *p = s->positions + 3 * (size_t)v, *n = s->normals + 3 * (size_t)v;
        const double l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        bad += !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]) || !(fabs(l - 1) < 1e-4);
    }
    for (uint32_t i = 0; i < 3 * s->triangle_count; i++)
        bad += s->indices[i] >= s->vertex_count;
    CHECK(bad == 0, "%s: %u bad vertices or indices", s->name, bad);
    CHECK(s->light_count >= 1 && s->camera_count >= 1, "%s: %u lights, %u cameras", s->name,
          s->light_count, s->camera_count);
}

static int load(const char *name, gib_scene *s)
{
    gib_error err;
    int rc = gib_scene_load(name, s, &err);
    CHECK(rc == 0, "%s: %s", name, err.msg);
    if (rc == 0)
        check_finite(s);
    return rc;
}

/* ------------------------------------------------------------------ hairball */

static void test_hairball(void)
{
    gib_scene s, s2;
    if (load("hairball", &s))
        return;
    /* hairball.scene / FORMAT.md: tubes x segments x sides x 2, tubes x (segments+1) x sides. */
    CHECK(s.triangle_count == 1200u * 20 * 6 * 2, "hairball: %u triangles, want 288000",
          s.triangle_count);
    CHECK(s.vertex_count == 1200u * 21 * 6, "hairball: %u vertices, want 151200",
          s.vertex_count);
    for (int k = 0; k < 3; k++)
        CHECK(s.bounds_min[k] >= -1.0f && s.bounds_max[k] <= 1.0f && s.bounds_max[k] > 0.9f,
              "hairball: bounds [%g, %g] on axis %d, want inside the ball of radius 1 and "
              "filling it",
              s.bounds_min[k], s.bounds_max[k], k);
    CHECK(load("hairball", &s2) == 0, "hairball: second load");
    if (s2.vertex_count == s.vertex_count) {
        CHECK(s2.content_hash == s.content_hash, "hairball: content hash differs between loads");
        CHECK(!memcmp(s.positions, s2.positions, 12 * (size_t)s.vertex_count) &&
                  !memcmp(s.normals, s2.normals, 12 * (size_t)s.vertex_count),
              "hairball: geometry differs between loads");
        gib_scene_free(&s2);
    }
    /* Tube normals are smooth but must agree with the winding (outward). */
    uint32_t against = 0;
    against += corners_against_winding(&s);
    CHECK(against == 0, "hairball: %u corners whose normal disagrees with the winding", against);
    /* Another seed: another hairball, another hash. */
    char path[512];
    snprintf(path, sizeof path, "%s/hair2.scene", tmpdir);
    FILE *f = fopen(path, "wb");
    if (f) {
        fputs("[scene]\n[mesh.h]\nprocedural = hairball\ntubes = 10\nseed = 2\n"
              "[light.l]\ntype = point\nposition = 0 2 0\nintensity = 1 1 1\n"
              "[camera.c]\neye = 0 0 3\ntarget = 0 0 0\n",
              f);
        fclose(f);
        gib_scene s3, s4;
        if (load(path, &s3) == 0) {
            CHECK(s3.triangle_count == 10u * 20 * 6 * 2, "hairball defaults: %u triangles",
                  s3.triangle_count);
            CHECK(memcmp(s3.positions, s.positions, 12 * (size_t)s3.vertex_count) != 0,
                  "hairball: seed 2 gives the same tubes as seed 1");
            f = fopen(path, "wb");
            if (f) {
                fputs("[scene]\n[mesh.h]\nprocedural = hairball\ntubes = 10\nseed = 3\n"
                      "[light.l]\ntype = point\nposition = 0 2 0\nintensity = 1 1 1\n"
                      "[camera.c]\neye = 0 0 3\ntarget = 0 0 0\n",
                      f);
                fclose(f);
            }
            if (load(path, &s4) == 0) {
                CHECK(s4.content_hash != s3.content_hash, "hairball: seed not in the hash");
                gib_scene_free(&s4);
            }
            gib_scene_free(&s3);
        }
        unlink(path);
    }
    /* Depth complexity: surfaces crossed by the camera's centre ray (the whole line), and the
     * mean over a grid of lines aimed at points within 0.25 m of the centre, perpendicular to
     * the view. */
    const gib_camera *c = &s.cameras[0];
    float fr[3], fu[3], ff[3];
    gib_camera_basis(c, fr, fu, ff);
    const double o[3] = {c->eye[0], c->eye[1], c->eye[2]};
    double sum = 0;
    int rays = 0, centre = 0, lo = 1 << 30, hi = 0;
    for (int i = -3; i <= 3; i++)
        for (int j = -3; j <= 3; j++) {
            const double x = 0.25 * i / 3.0, y = 0.25 * j / 3.0;
            if (x * x + y * y > 0.25 * 0.25 + 1e-12)
                continue;
            double d[3];
            for (int k = 0; k < 3; k++)
                d[k] = c->target[k] + x * fr[k] + y * fu[k] - o[k];
            const int n = crossings(&s, o, d);
            if (i == 0 && j == 0)
                centre = n;
            sum += n;
            rays++;
            lo = n < lo ? n : lo;
            hi = n > hi ? n : hi;
        }
    printf("ok   hairball: %u triangles, %u vertices, bounds %.3f..%.3f; depth complexity: "
           "centre ray %d surfaces, %d rays within 0.25 m of the centre: mean %.1f (min %d, "
           "max %d)\n",
           s.triangle_count, s.vertex_count, s.bounds_min[0], s.bounds_max[0], centre, rays,
           sum / rays, lo, hi);
    CHECK(centre >= 20 && sum / rays >= 20,
          "hairball: depth complexity too low (centre %d, mean %.1f), want tens", centre,
          sum / rays);
    gib_scene_free(&s);
}

/* ------------------------------------------------------------------ furnace */

static void test_furnace(void)
{
    gib_scene s;
    if (load("furnace", &s))
        return;
    const double R = 1.0;
    CHECK(s.triangle_count == 20u << (2 * 5), "furnace: %u triangles, want 20 x 4^5 = 20480",
          s.triangle_count);
    for (int k = 0; k < 3; k++) {
        NEAR(s.bounds_min[k], -R, 1e-7, "subdivided icosahedron: (+-R, 0, 0) ... are vertices");
        NEAR(s.bounds_max[k], R, 1e-7, "subdivided icosahedron: (+-R, 0, 0) ... are vertices");
    }
    CHECK(s.light_count == 1 && s.lights[0].type == GIB_LIGHT_POINT, "furnace: one point light");
    NEAR(s.lights[0].position[0], 0, 0, "light at the centre");
    NEAR(s.lights[0].position[1], 0, 0, "light at the centre");
    NEAR(s.lights[0].position[2], 0, 0, "light at the centre");
    NEAR(s.lights[0].intensity[1], 1.0, 0, "1 W/sr");
    CHECK(s.material_count == 1 && s.materials[0].albedo[0] == 0.5f, "furnace: one material, 0.5");
    CHECK(s.features & GIB_FEAT_CLOSED, "furnace: closed");
    const float *eye = s.cameras[0].eye;
    CHECK(sqrt((double)eye[0] * eye[0] + eye[1] * eye[1] + eye[2] * eye[2]) < 0.9 * R,
          "furnace: camera inside");
    /* Normals: every vertex normal is its face's normal, pointing to the centre: the centre lies
     * on the line through the circumcentre along the normal, so n . (-p) = d (the plane's
     * distance) for each corner p, and the winding agrees. */
    uint32_t bad = 0;
    double dmin = 1e30, dmax = 0, area = 0, dsum = 0;
    for (uint32_t t = 0; t < s.triangle_count; t++) {
        double a[3], b[3], c[3], e1[3], e2[3], g[3];
        vtx(&s, t, 0, a);
        vtx(&s, t, 1, b);
        vtx(&s, t, 2, c);
        sub(b, a, e1);
        sub(c, a, e2);
        cross(e1, e2, g);
        const double ga = sqrt(dot(g, g));
        const double d = -dot(g, a) / ga; /* > 0: the normal points toward the centre */
        for (int k = 0; k < 3; k++) {
            const float *nf = s.normals + 3 * (size_t)s.indices[3 * (size_t)t + (size_t)k];
            const double n[3] = {nf[0], nf[1], nf[2]};
            double p[3];
            vtx(&s, t, k, p);
            bad += !(dot(n, g) > 0.99999 * ga) || !(-dot(n, p) > 0.99 * R);
        }
        dmin = d < dmin ? d : dmin;
        dmax = d > dmax ? d : dmax;
        dsum += d;
        area += 0.5 * ga;
    }
    CHECK(bad == 0, "furnace: %u corners whose normal does not point to the centre", bad);
    const double dmean = dsum / s.triangle_count, area_factor = 4 * M_PI * R * R / area;
    printf("ok   furnace: %u triangles; face distance / R: min %.6f mean %.6f max %.6f; "
           "4 pi R^2 / area = %.6f\n",
           s.triangle_count, dmin / R, dmean / R, dmax / R, area_factor);
    /* The numbers furnace.scene states (subdivisions = 5). */
    NEAR(dmin / R, 0.99972, 5e-6, "furnace.scene comment");
    NEAR(dmean / R, 0.99976, 5e-6, "furnace.scene comment");
    NEAR(dmax / R, 0.99977, 5e-6, "furnace.scene comment");
    NEAR(area_factor, 1.00030, 5e-6, "furnace.scene comment");
    gib_scene_free(&s);
}

/* ------------------------------------------------------------------ hard cases */

/* Distance from p to the nearest triangle whose plane it projects into (inside the triangle). */
static double nearest_face(const gib_scene *s, const float pf[3])
{
    const double p[3] = {pf[0], pf[1], pf[2]};
    double best = INFINITY;
    for (uint32_t t = 0; t < s->triangle_count; t++) {
        double a[3], b[3], c[3], e1[3], e2[3], g[3], ap[3], w[3];
        vtx(s, t, 0, a);
        vtx(s, t, 1, b);
        vtx(s, t, 2, c);
        sub(b, a, e1);
        sub(c, a, e2);
        cross(e1, e2, g);
        const double gg = dot(g, g);
        if (!(gg > 0))
            continue;
        sub(p, a, ap);
        cross(e1, ap, w);
        const double v = dot(w, g) / gg;
        cross(ap, e2, w);
        const double u = dot(w, g) / gg;
        if (u < 0 || v < 0 || u + v > 1)
            continue;
        const double dist = fabs(dot(ap, g)) / sqrt(gg);
        best = dist < best ? dist : best;
    }
    return best;
}

static void test_hard_cases(void)
{
    static const char *const names[] = {
        "hard_grazing", "hard_coplanar", "hard_thin_wall", "hard_far",   "hard_tiny",
        "hard_huge",    "hard_sliver",   "hard_light_touching", "hard_empty"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        gib_scene s;
        if (load(names[i], &s))
            continue;
        CHECK(strncmp(s.description, "hard case:", 10) == 0,
              "%s: description must start with 'hard case:': %s", names[i], s.description);
        const double ext = fmax(s.bounds_max[0] - s.bounds_min[0],
                                fmax(s.bounds_max[1] - s.bounds_min[1],
                                     s.bounds_max[2] - s.bounds_min[2]));
        const char *n = names[i];
        if (!strcmp(n, "hard_grazing")) {
            const float *d = s.lights[0].direction;
            CHECK(fabs(d[1]) < sin(1.0 * M_PI / 180), "grazing: light %.3f deg off the plane",
                  asin(fabs(d[1])) * 180 / M_PI);
        } else if (!strcmp(n, "hard_coplanar")) {
            unsigned mats = 0; /* materials of triangles lying in y = 0 */
            for (uint32_t t = 0; t < s.triangle_count; t++) {
                double a[3], b[3], c[3];
                if (vtx(&s, t, 0, a)[1] == 0 && vtx(&s, t, 1, b)[1] == 0 &&
                    vtx(&s, t, 2, c)[1] == 0)
                    mats |= 1u << (s.tri_material[t] & 31);
            }
            CHECK(__builtin_popcount(mats) >= 3,
                  "coplanar: want floor, tile and block bottom in y = 0");
        } else if (!strcmp(n, "hard_thin_wall")) {
            int thin = 0;
            for (uint32_t t = 0; t < s.triangle_count; t++) {
                double a[3];
                thin += fabs(fabs(vtx(&s, t, 0, a)[0]) - 0.0005) < 1e-7;
            }
            CHECK(thin >= 12, "thin wall: no 1 mm wall at x = 0");
            CHECK(s.features & GIB_FEAT_CLOSED, "thin wall: the room encloses everything");
        } else if (!strcmp(n, "hard_far")) {
            CHECK(s.bounds_min[0] >= 99999.0f && s.bounds_min[2] >= 99999.0f && ext < 1,
                  "far: bounds from %g", s.bounds_min[0]);
        } else if (!strcmp(n, "hard_tiny")) {
            CHECK(ext > 0.9e-3 && ext < 1.1e-3, "tiny: extent %g m, want 1e-3", ext);
        } else if (!strcmp(n, "hard_huge")) {
            CHECK(ext > 0.9e4 && ext < 1.1e4, "huge: extent %g m, want 1e4", ext);
        } else if (!strcmp(n, "hard_sliver")) {
            uint32_t degenerate = 0, wrong_way = 0;
            double worst = 0;
            for (uint32_t t = 0; t < s.triangle_count; t++) {
                double a[3], b[3], c[3], e1[3], e2[3], e3[3], g[3];
                vtx(&s, t, 0, a);
                vtx(&s, t, 1, b);
                vtx(&s, t, 2, c);
                sub(b, a, e1);
                sub(c, a, e2);
                sub(c, b, e3);
                cross(e1, e2, g);
                const double area2 = sqrt(dot(g, g));
                const double lmax = sqrt(fmax(dot(e1, e1), fmax(dot(e2, e2), dot(e3, e3))));
                /* Zero area, up to float rounding of the corners (collinear ones in float). */
                if (area2 <= 1e-5 * lmax * lmax) {
                    degenerate++;
                } else {
                    worst = fmax(worst, lmax * lmax / area2); /* longest edge / height */
                    wrong_way += g[1] <= 0 &&
                                 !strcmp(s.materials[s.tri_material[t]].name, "slivers");
                }
            }
            printf("ok   hard_sliver: %u triangles, %u degenerate, worst aspect %.0f\n",
                   s.triangle_count, degenerate, worst);
            CHECK(degenerate >= 1000 && worst > 500, "sliver: %u degenerate, aspect %.0f",
                  degenerate, worst);
            CHECK(wrong_way == 0, "sliver: %u floor triangles wound against +y", wrong_way);
        } else if (!strcmp(n, "hard_light_touching")) {
            double closest = INFINITY;
            for (uint32_t l = 0; l < s.light_count; l++)
                closest = fmin(closest, nearest_face(&s, s.lights[l].position));
            CHECK(closest <= 1e-6, "light touching: nearest light %g m from a face", closest);
        } else if (!strcmp(n, "hard_empty")) {
            float r[3], u[3], f[3];
            gib_camera_basis(&s.cameras[0], r, u, f);
            uint32_t visible = 0;
            for (uint32_t v = 0; v < s.vertex_count; v++) {
                const float *p = s.positions + 3 * (size_t)v, *e = s.cameras[0].eye;
                visible += (p[0] - e[0]) * f[0] + (p[1] - e[1]) * f[1] + (p[2] - e[2]) * f[2] > 0;
            }
            CHECK(visible == 0, "empty: %u vertices in front of the camera", visible);
        }
        printf("ok   %-20s %6u triangles, extent %g m: %s\n", n, s.triangle_count, ext,
               s.description);
        gib_scene_free(&s);
    }
}

/* ------------------------------------------------------------------ ring */

/* The ring generator (FORMAT.md): 6 x segments triangles; every vertex within [r0, r0 + t] of the
 * axis and [0, h] in height; inner-wall normals point toward the axis, outer ones away, rim +y;
 * every corner's normal on the side of its triangle's winding (the walls are smooth, the winding
 * must still agree); ring.scene (the thesis' simple ring) is the room's 12 + 192 triangles. */
static void test_ring(void)
{
    char path[512];
    write_file("ring.scene",
               "[scene]\n[mesh.r]\nprocedural = ring\nradius = 0.4\nthickness = 0.05\n"
               "height = 0.3\nsegments = 12\n"
               "[light.l]\ntype = point\nposition = 0 2 0\nintensity = 1 1 1\n"
               "[camera.c]\neye = 0 1 3\ntarget = 0 0 0\n",
               path, sizeof path);
    gib_scene s;
    if (load(path, &s))
        return;
    CHECK(s.triangle_count == 6u * 12, "ring: %u triangles, want 72", s.triangle_count);
    uint32_t bad_pos = 0, bad_n = 0, against = 0;
    /* Float positions of r = 0.4 and 0.45: 1e-6 m covers cos/sin rounded to float. */
    const double r0 = 0.4, r1 = 0.45, h = 0.3, eps = 1e-6;
    for (uint32_t v = 0; v < s.vertex_count; v++) {
        const float *p = s.positions + 3 * (size_t)v, *n = s.normals + 3 * (size_t)v;
        const double r = sqrt((double)p[0] * p[0] + (double)p[2] * p[2]);
        bad_pos += r < r0 - eps || r > r1 + eps || p[1] < -eps || p[1] > h + eps;
        const double radial = (p[0] * n[0] + p[2] * n[2]) / r;
        if (fabs(n[1] - 1.0) < 1e-6)
            bad_n += fabs(p[1] - h) > eps; /* rim: at the top */
        else if (fabs(r - r0) < eps)
            bad_n += !(radial < -0.999999); /* inner wall: toward the axis */
        else if (fabs(r - r1) < eps)
            bad_n += !(radial > 0.999999); /* outer wall: away from it */
        else
            bad_n++;
    }
    against += corners_against_winding(&s);
    CHECK(bad_pos == 0, "ring: %u vertices outside the ring's shell", bad_pos);
    CHECK(bad_n == 0, "ring: %u vertices whose normal is not the wall's or the rim's", bad_n);
    CHECK(against == 0, "ring: %u corners whose normal disagrees with the winding", against);
    printf("ok   ring: %u triangles, %u vertices, normals radial and +y\n", s.triangle_count,
           s.vertex_count);
    gib_scene_free(&s);
    unlink(path);
    gib_scene r;
    if (load("ring", &r) == 0) {
        CHECK(r.triangle_count == 12 + 6 * 32, "ring.scene: %u triangles, want 204",
              r.triangle_count);
        gib_scene_free(&r);
    }
}

/* ------------------------------------------------------------------ generator key errors */

static void expect_error(const char *what, const char *text, int line, const char *phrase)
{
    char path[512];
    snprintf(path, sizeof path, "%s/case.scene", tmpdir);
    FILE *f = fopen(path, "wb");
    if (!f) {
        CHECK(0, "cannot write %s", path);
        return;
    }
    fputs(text, f);
    fclose(f);
    gib_scene s;
    gib_error err;
    err.msg[0] = '\0';
    int rc = gib_scene_load(path, &s, &err);
    if (rc == 0)
        gib_scene_free(&s);
    char at[32];
    snprintf(at, sizeof at, ":%d:", line);
    CHECK(rc == -1 && strstr(err.msg, path) && strstr(err.msg, at) && strstr(err.msg, phrase),
          "%s: rc %d, want -1 with '%s' at line %d: %s", what, rc, phrase, line, err.msg);
    if (rc == -1)
        printf("ok   %-24s %s\n", what, strstr(err.msg, at) ? strstr(err.msg, at) : err.msg);
    unlink(path);
}

#define CAM "[camera.c]\neye = 0 0 5\ntarget = 0 0 0\n"

static void test_key_errors(void)
{
    expect_error("tubes on room", "[scene]\n[mesh.r]\nprocedural = room\ntubes = 4\n" CAM, 4,
                 "'tubes' applies only to 'procedural = hairball'");
    expect_error("sides not whole", "[scene]\n[mesh.h]\nprocedural = hairball\nsides = 4.5\n" CAM,
                 4, "'sides' must be a whole number from 3 to 64");
    expect_error("sides too few", "[scene]\n[mesh.h]\nprocedural = hairball\nsides = 2\n" CAM, 4,
                 "from 3 to 64, got '2'");
    expect_error("radius negative",
                 "[scene]\n[mesh.s]\nprocedural = sphere_interior\nradius = -1\n" CAM, 4,
                 "'radius' must be a positive number");
    expect_error("subdivisions too many",
                 "[scene]\n[mesh.s]\nprocedural = sphere_interior\nsubdivisions = 9\n" CAM, 4,
                 "from 0 to 7");
    expect_error("size count for quad", "[scene]\n[mesh.q]\nprocedural = quad\nsize = 1 2 3\n" CAM,
                 4, "'size' of a quad takes 2 numbers (width depth), got 3");
    expect_error("size count for room", "[scene]\n[mesh.q]\nprocedural = room\nsize = 1 2\n" CAM,
                 4, "takes 3 numbers (width height depth)");
    expect_error("key on a mesh file", "[scene]\n[mesh.m]\nfile = a.obj\nseed = 3\n" CAM, 4,
                 "applies only to procedural meshes");
    expect_error("hairball too big",
                 "[scene]\n[mesh.h]\nprocedural = hairball\nsegments = 1000\ntubes = 100000\n" CAM,
                 5, "more than the 16777216 allowed");
    expect_error("thickness vs radius",
                 "[scene]\n[mesh.h]\nprocedural = hairball\nradius = 1\nthickness = 0.3\n" CAM, 5,
                 "less than a quarter of 'radius'");
    expect_error("slivers segments",
                 "[scene]\n[mesh.f]\nprocedural = slivers\nsegments = 1\n" CAM, 4,
                 "'segments' must be from 2");
    expect_error("seed given twice",
                 "[scene]\n[mesh.h]\nprocedural = hairball\nseed = 1\nseed = 2\n" CAM, 5,
                 "given twice");
    expect_error("ring segments", "[scene]\n[mesh.r]\nprocedural = ring\nsegments = 2\n" CAM, 4,
                 "ring: 'segments' must be from 3");
    expect_error("height on a box", "[scene]\n[mesh.b]\nprocedural = box\nheight = 2\n" CAM, 4,
                 "'height' applies only to 'procedural = ring'");
}

int main(void)
{
    if (scene_test_begin("gib_scene_proc") < 0)
        return 1;
    test_hairball();
    test_furnace();
    test_hard_cases();
    test_ring();
    test_key_errors();
    return scene_test_end();
}

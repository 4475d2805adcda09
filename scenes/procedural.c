/* gibench — scenes built in C: the generators' keys and their checks, and three generators: the
 * Cornell box from its published measurements, a plane with a box on it, and a closed room to put
 * scanned models in. The others live in proc_shapes.c (quad, box, slivers, sphere_interior),
 * proc_hairball.c, proc_water.c and proc_ring.c.
 *
 * Every flat face gets its own vertices carrying the face's geometric normal, so the shading normal
 * equals the geometric normal and the GL side and the path tracer cannot disagree about it. All
 * materials are Lambertian and two-sided: the faces are single-sided quads (walls without
 * thickness), and a technique that culls or flips by winding must not change what they reflect. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/base/hash.h"
#include "scene_internal.h"

/* ------------------------------------------------------------------ keys and generators */

#define K(k) (1u << (k))

/* Each key's own rules, checked by the parser (scene_file.c) with the key's line. */
static const gib_proc_key_info key_info[GIB_PK_COUNT] = {
    [GIB_PK_SIZE] = {"size", 2, 3, 0, 0.0, 1e30},
    [GIB_PK_RADIUS] = {"radius", 1, 1, 0, 0.0, 1e30},
    [GIB_PK_THICKNESS] = {"thickness", 1, 1, 0, 0.0, 1e30},
    [GIB_PK_TUBES] = {"tubes", 1, 1, 1, 1.0, 1e6},
    [GIB_PK_SEGMENTS] = {"segments", 1, 1, 1, 1.0, 1e6},
    [GIB_PK_SIDES] = {"sides", 1, 1, 1, 3.0, 64.0},
    [GIB_PK_SEED] = {"seed", 1, 1, 1, 0.0, 4294967295.0},
    [GIB_PK_SUBDIVISIONS] = {"subdivisions", 1, 1, 1, 0.0, 7.0},
    [GIB_PK_HEIGHT] = {"height", 1, 1, 0, 0.0, 1e30},
};

/* The generators, the keys each takes, and how many numbers its `size` has. */
static const struct generator {
    const char *name;
    unsigned keys;
    int size_n;
} generators[] = {
    {"cornell_box", 0, 0},
    {"plane_box", 0, 0},
    {"room", K(GIB_PK_SIZE), 3},
    {"box", K(GIB_PK_SIZE), 3},
    {"quad", K(GIB_PK_SIZE), 2},
    {"slivers", K(GIB_PK_SIZE) | K(GIB_PK_SEGMENTS), 2},
    {"sphere_interior", K(GIB_PK_RADIUS) | K(GIB_PK_SUBDIVISIONS), 0},
    {"hairball", K(GIB_PK_RADIUS) | K(GIB_PK_THICKNESS) | K(GIB_PK_TUBES) | K(GIB_PK_SEGMENTS) |
                     K(GIB_PK_SIDES) | K(GIB_PK_SEED),
     0},
    {"water", K(GIB_PK_SIZE) | K(GIB_PK_SEGMENTS), 2},
    {"ring", K(GIB_PK_RADIUS) | K(GIB_PK_THICKNESS) | K(GIB_PK_HEIGHT) | K(GIB_PK_SEGMENTS), 0},
};
#define NGEN (sizeof generators / sizeof generators[0])

/* Hairball and slivers sizes are capped so that a typo cannot ask for gigabytes. */
#define MAX_GENERATED_TRIANGLES (1u << 24)

int gib_proc_key_find(const char *name)
{
    for (int k = 0; k < GIB_PK_COUNT; k++)
        if (strcmp(name, key_info[k].name) == 0)
            return k;
    return -1;
}

const gib_proc_key_info *gib_proc_key_get(int key)
{
    return key >= 0 && key < GIB_PK_COUNT ? &key_info[key] : NULL;
}

int gib_proc_key_parse(gib_proc_params *p, const char *name, const char *value, int line,
                       char *msg, size_t msg_len)
{
    const int k = gib_proc_key_find(name);
    if (k < 0) {
        snprintf(msg, msg_len, "'%s' is not a generator key", name);
        return -1;
    }
    const gib_proc_key_info *ki = &key_info[k];
    double v[3];
    int n = 0, ok = 1;
    const char *s = value;
    for (;;) {
        while (*s == ' ' || *s == '\t' || *s == ',')
            s++;
        if (!*s)
            break;
        char *end;
        double d = strtod(s, &end);
        if (end == s || !isfinite(d) || (*end && *end != ' ' && *end != '\t' && *end != ',')) {
            ok = 0;
            break;
        }
        if (n < 3)
            v[n] = d;
        n++;
        s = end;
    }
    if (!ok || n < ki->min_n || n > ki->max_n) {
        if (ki->min_n == ki->max_n)
            snprintf(msg, msg_len, "'%s' expects %d number%s, got '%s'", name, ki->min_n,
                     ki->min_n == 1 ? "" : "s", value);
        else
            snprintf(msg, msg_len, "'%s' expects %d or %d numbers, got '%s'", name, ki->min_n,
                     ki->max_n, value);
        return -1;
    }
    for (int i = 0; i < n; i++) {
        if (ki->whole ? !(v[i] == floor(v[i]) && v[i] >= ki->lo && v[i] <= ki->hi)
                      : !(v[i] > ki->lo && v[i] <= ki->hi)) {
            if (ki->whole)
                snprintf(msg, msg_len, "'%s' must be a whole number from %.0f to %.0f, got '%s'",
                         name, ki->lo, ki->hi, value);
            else
                snprintf(msg, msg_len, "'%s' must be %s, got '%s'", name,
                         n > 1 ? "positive numbers" : "a positive number", value);
            return -1;
        }
        p->v[k][i] = v[i];
    }
    p->set |= K(k);
    p->count[k] = n;
    p->line[k] = line;
    return 0;
}

double gib_proc_get(const gib_proc_params *p, int key, int i, double dflt)
{
    return p && (p->set & K(key)) && i < p->count[key] ? p->v[key][i] : dflt;
}

static const struct generator *find_generator(const char *name)
{
    for (size_t i = 0; i < NGEN; i++)
        if (strcmp(name, generators[i].name) == 0)
            return &generators[i];
    return NULL;
}

int gib_procedural_known(const char *name)
{
    return find_generator(name) != NULL;
}

const char *gib_procedural_names(void)
{
    return "cornell_box, plane_box, room, box, quad, slivers, sphere_interior, hairball, water, ring";
}

/* "room, box" : the generators that take key k. */
static void takers(int k, char *out, size_t n)
{
    size_t used = 0;
    out[0] = '\0';
    for (size_t i = 0; i < NGEN; i++)
        if (generators[i].keys & K(k)) {
            int w = snprintf(out + used, n - used, "%s%s", used ? ", " : "", generators[i].name);
            if (w < 0 || (size_t)w >= n - used)
                break;
            used += (size_t)w;
        }
}

int gib_procedural_check(const char *name, const gib_proc_params *p, int *key, char *msg,
                         size_t msg_len)
{
    const struct generator *gen = find_generator(name);
    *key = -1;
    if (!gen) {
        snprintf(msg, msg_len, "unknown procedural generator '%s' (known: %s)", name,
                 gib_procedural_names());
        return -1;
    }
    for (int k = 0; k < GIB_PK_COUNT; k++) {
        if (!(p->set & K(k)) || (gen->keys & K(k)))
            continue;
        char who[160];
        takers(k, who, sizeof who);
        *key = k;
        snprintf(msg, msg_len, "'%s' applies only to 'procedural = %s', not to '%s'",
                 key_info[k].name, who, name);
        return -1;
    }
    if ((p->set & K(GIB_PK_SIZE)) && p->count[GIB_PK_SIZE] != gen->size_n) {
        *key = GIB_PK_SIZE;
        snprintf(msg, msg_len, "'size' of a %s takes %d numbers (%s), got %d", name, gen->size_n,
                 gen->size_n == 3 ? "width height depth" : "width depth", p->count[GIB_PK_SIZE]);
        return -1;
    }
    if (strcmp(name, "hairball") == 0) {
        const double r = gib_proc_get(p, GIB_PK_RADIUS, 0, GIB_HAIRBALL_RADIUS);
        const double t = gib_proc_get(p, GIB_PK_THICKNESS, 0, GIB_HAIRBALL_THICKNESS * r);
        const double tris = gib_proc_get(p, GIB_PK_TUBES, 0, GIB_HAIRBALL_TUBES) *
                            gib_proc_get(p, GIB_PK_SEGMENTS, 0, GIB_HAIRBALL_SEGMENTS) *
                            gib_proc_get(p, GIB_PK_SIDES, 0, GIB_HAIRBALL_SIDES) * 2.0;
        if (!(t < 0.25 * r)) {
            *key = (p->set & K(GIB_PK_THICKNESS)) ? GIB_PK_THICKNESS : GIB_PK_RADIUS;
            snprintf(msg, msg_len,
                     "hairball: 'thickness' (a tube's radius, %g) must be less than a quarter "
                     "of 'radius' (the ball's, %g)",
                     t, r);
            return -1;
        }
        if (tris > MAX_GENERATED_TRIANGLES) {
            *key = (p->set & K(GIB_PK_TUBES))      ? GIB_PK_TUBES
                   : (p->set & K(GIB_PK_SEGMENTS)) ? GIB_PK_SEGMENTS
                                                   : GIB_PK_SIDES;
            snprintf(msg, msg_len,
                     "hairball: tubes x segments x sides x 2 = %.0f triangles, more than the "
                     "%u allowed",
                     tris, MAX_GENERATED_TRIANGLES);
            return -1;
        }
    }
    if (strcmp(name, "slivers") == 0 && (p->set & K(GIB_PK_SEGMENTS))) {
        const double n = p->v[GIB_PK_SEGMENTS][0];
        if (n < 2 || 2 * n > MAX_GENERATED_TRIANGLES) {
            *key = GIB_PK_SEGMENTS;
            snprintf(msg, msg_len, "slivers: 'segments' must be from 2 to %u, got %.0f",
                     MAX_GENERATED_TRIANGLES / 2, n);
            return -1;
        }
    }
    if (strcmp(name, "water") == 0 && (p->set & K(GIB_PK_SEGMENTS))) {
        const double n = p->v[GIB_PK_SEGMENTS][0];
        if (2 * n * n > MAX_GENERATED_TRIANGLES) {
            *key = GIB_PK_SEGMENTS;
            snprintf(msg, msg_len, "water: 'segments' must be from 1 to 2896 (2 x segments^2 "
                     "triangles, at most %u), got %.0f", MAX_GENERATED_TRIANGLES, n);
            return -1;
        }
    }
    if (strcmp(name, "ring") == 0 && (p->set & K(GIB_PK_SEGMENTS))) {
        const double n = p->v[GIB_PK_SEGMENTS][0];
        if (n < 3 || 6 * n > MAX_GENERATED_TRIANGLES) {
            *key = GIB_PK_SEGMENTS;
            snprintf(msg, msg_len, "ring: 'segments' must be from 3 to %u, got %.0f",
                     MAX_GENERATED_TRIANGLES / 6, n);
            return -1;
        }
    }
    return 0;
}

/* The Cornell box, from "Cornell Box data", Cornell University Program of Computer Graphics
 * (www.graphics.cornell.edu/online/box/data.html), coordinates in millimetres, converted to
 * metres. The walls enclose x in [0, 556], y in [0, 548.8], z in [0, 559.2]; the camera looks
 * along +z from z = -800, so x = 0 (the green wall) appears on the right.
 *
 * The published data is not quite a box: the red wall's bottom edge runs from x = 552.8 to 549.6
 * while its top edge is at x = 556, so that quad is twisted out of plane by about 3 mm, and the
 * floor and back wall are trapezoids. We keep the published coordinates as they are and split
 * every quad into two triangles with their own vertices and geometric normals, so each triangle is
 * exactly planar and shading normals equal geometric normals (no smoothing across the twist).
 *
 * The published scene's area light is not built: scenes/cornell.scene replaces it with a spot
 * light (the techniques under test take point-like lights). The blocks have no bottom faces, as
 * in the published data. Albedos are the RGB values used by common renderers (Mitsuba's and
 * pbrt-v3's cornell-box scenes, converted from the published spectral reflectances): white
 * 0.725 0.71 0.68, red 0.63 0.065 0.05, green 0.14 0.45 0.091. */
/* clang-format off */
static const float cornell_quads[][4][3] = {
    /* 0 floor (white) */
    {{552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}},
    /* 1 ceiling (white) */
    {{556, 548.8f, 0}, {556, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}},
    /* 2 back wall (white) */
    {{549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556, 548.8f, 559.2f}},
    /* 3 right wall (green) */
    {{0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}},
    /* 4 left wall (red) */
    {{552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556, 548.8f, 559.2f}, {556, 548.8f, 0}},
    /* 5-9 short block (white) */
    {{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}},
    {{290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}},
    {{130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}},
    {{82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}},
    {{240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}},
    /* 10-14 tall block (white) */
    {{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}},
    {{423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}},
    {{472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}},
    {{314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}},
    {{265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}},
};
/* clang-format on */

static int build_cornell(gib_geom *g, gib_error *err)
{
    const int nq = (int)(sizeof cornell_quads / sizeof cornell_quads[0]);
    gib_mat_desc white = gib_mat_desc_diffuse("white", 0.725f, 0.71f, 0.68f);
    gib_mat_desc red = gib_mat_desc_diffuse("red", 0.63f, 0.065f, 0.05f);
    gib_mat_desc green = gib_mat_desc_diffuse("green", 0.14f, 0.45f, 0.091f);
    int mw = gib_geom_material(g, &white, err);
    int mr = mw < 0 ? -1 : gib_geom_material(g, &red, err);
    int mg = mr < 0 ? -1 : gib_geom_material(g, &green, err);
    if (mg < 0 || gib_geom_reserve(g, (uint32_t)nq * 6, (uint32_t)nq * 2, err))
        return -1;
    /* Walls face the inside of the box; block faces face away from the block's centre. */
    const float room_centre[3] = {0.278f, 0.2744f, 0.2796f};
    const float short_centre[3] = {0.186f, 0.0825f, 0.169f};
    const float tall_centre[3] = {0.3685f, 0.165f, 0.35125f};
    for (int i = 0; i < nq; i++) {
        float q[4][3];
        for (int k = 0; k < 4; k++)
            for (int c = 0; c < 3; c++)
                q[k][c] = cornell_quads[i][k][c] * 0.001f; /* mm -> m */
        uint32_t m = (uint32_t)(i == 3 ? mg : i == 4 ? mr : mw);
        if (i < 5)
            gib_geom_add_quad(g, q, room_centre, +1, m);
        else
            gib_geom_add_quad(g, q, i < 10 ? short_centre : tall_centre, -1, m);
    }
    return 0;
}

/* An 8 m x 8 m ground plane at y = 0 centred on the origin, and a 1 m cube standing on it at the
 * origin (no bottom face: it would coincide with the ground). The box is orange so that its
 * indirect light on the ground is told apart from the ground's own colour. */
static int build_plane_box(gib_geom *g, gib_error *err)
{
    gib_mat_desc ground = gib_mat_desc_diffuse("ground", 0.7f, 0.7f, 0.7f);
    gib_mat_desc box = gib_mat_desc_diffuse("box", 0.7f, 0.35f, 0.15f);
    int mg = gib_geom_material(g, &ground, err);
    int mb = mg < 0 ? -1 : gib_geom_material(g, &box, err);
    if (mb < 0 || gib_geom_reserve(g, 6 + 5 * 6, 2 + 5 * 2, err))
        return -1;
    float q[4][3] = {{-4, 0, -4}, {4, 0, -4}, {4, 0, 4}, {-4, 0, 4}};
    const float above[3] = {0, 1, 0};
    gib_geom_add_quad(g, q, above, +1, (uint32_t)mg);
    const float lo[3] = {-0.5f, 0.0f, -0.5f}, hi[3] = {0.5f, 1.0f, 0.5f};
    const uint32_t mats[6] = {(uint32_t)mb, (uint32_t)mb, (uint32_t)mb,
                              (uint32_t)mb, (uint32_t)mb, (uint32_t)mb};
    gib_geom_add_box(g, lo, hi, 0, 1u << 2 /* no -y face */, mats);
    return 0;
}

/* The inside of a closed box, floor at y = 0, centred on x and z, all faces facing inward. Each
 * face has its own material (room_floor, room_ceiling, room_wall_xneg/xpos/zneg/zpos, all 0.7
 * grey) so that a scene file can colour single walls. */
static int build_room(gib_geom *g, const gib_proc_params *p, gib_error *err)
{
    float size[3];
    for (int i = 0; i < 3; i++)
        size[i] = (float)gib_proc_get(p, GIB_PK_SIZE, i, i == 1 ? 3.0 : 4.0);
    static const char *names[6] = {"room_wall_xneg", "room_wall_xpos", "room_floor",
                                   "room_ceiling",   "room_wall_zneg", "room_wall_zpos"};
    uint32_t mats[6];
    for (int f = 0; f < 6; f++) {
        gib_mat_desc d = gib_mat_desc_diffuse(names[f], 0.7f, 0.7f, 0.7f);
        int m = gib_geom_material(g, &d, err);
        if (m < 0)
            return -1;
        mats[f] = (uint32_t)m;
    }
    if (gib_geom_reserve(g, 6 * 6, 6 * 2, err))
        return -1;
    const float lo[3] = {-0.5f * size[0], 0.0f, -0.5f * size[2]};
    const float hi[3] = {0.5f * size[0], size[1], 0.5f * size[2]};
    gib_geom_add_box(g, lo, hi, 1, 0, mats);
    return 0;
}

int gib_procedural_build(const char *name, const gib_proc_params *p, gib_geom *out, uint64_t *hash,
                         gib_error *err)
{
    *hash = gib_hash_str(*hash, "procedural");
    *hash = gib_hash_str(*hash, name);
    /* `size` hashes as it always did (three floats), so the room scenes keep their hashes. */
    for (int k = 0; k < GIB_PK_COUNT && p; k++) {
        if (!(p->set & K(k)))
            continue;
        if (k != GIB_PK_SIZE)
            *hash = gib_hash_str(*hash, key_info[k].name);
        for (int i = 0; i < p->count[k]; i++)
            *hash = k == GIB_PK_SIZE ? gib_hash_f32(*hash, (float)p->v[k][i])
                                     : gib_hash_bytes(*hash, &p->v[k][i], sizeof(double));
    }
    if (strcmp(name, "cornell_box") == 0)
        return build_cornell(out, err);
    if (strcmp(name, "plane_box") == 0)
        return build_plane_box(out, err);
    if (strcmp(name, "room") == 0)
        return build_room(out, p, err);
    if (strcmp(name, "box") == 0)
        return gib_gen_box(out, p, err);
    if (strcmp(name, "quad") == 0)
        return gib_gen_quad(out, p, err);
    if (strcmp(name, "slivers") == 0)
        return gib_gen_slivers(out, p, err);
    if (strcmp(name, "sphere_interior") == 0)
        return gib_gen_sphere_interior(out, p, err);
    if (strcmp(name, "hairball") == 0)
        return gib_gen_hairball(out, p, err);
    if (strcmp(name, "water") == 0)
        return gib_gen_water(out, p, err);
    if (strcmp(name, "ring") == 0)
        return gib_gen_ring(out, p, err);
    return gib_fail(err, "unknown procedural generator '%s' (known: %s)", name,
                    gib_procedural_names());
}
